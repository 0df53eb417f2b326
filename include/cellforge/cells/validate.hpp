// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// validate(cells): checks the geometric and topological invariants of a 3DCL that
/// make_cell_complex() does not already enforce, and says which one broke, at which element.
/// The Euler check and its formula are explained in docs/cells.md.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/text.hpp"

namespace cellforge {

/// The invariants validate(cell_complex) checks, one per way they can break.
enum class cells_invariant : std::uint8_t {
  none,              ///< everything holds
  degenerate_edge,   ///< an edge no longer than the length tolerance
  degenerate_face,   ///< a face whose outer loop has no area
  non_planar,        ///< a face vertex further from the face's plane than the tolerance
  hole_orientation,  ///< a hole loop that turns the same way as its outer loop
  open_boundary,     ///< an edge of a volume's faces not used exactly twice, in opposite directions
  orientation,       ///< a volume whose signed volume (faces' normals out) is not positive
  rotation_order,    ///< faces about an edge not in right-hand order, or two faces coincide
  wedge_mismatch,    ///< the volume between two faces about an edge is not the same seen from both
  euler,             ///< an object's V - E + F - C differs from what its topology implies
};

/// How validate(cell_complex) measures.
struct cells_validation_options {
  /// Faces may depart from their plane by this fraction of their own bounding-box diagonal (a
  /// small face is judged at its own scale, not the model's)...
  double planarity = 1e-6;
  /// ... or by this fraction of the model's diagonal, when more: points carry rounding error of
  /// their coordinates' size, and the wireframe pipeline makes faces flat to 1e-9 of it.
  double planarity_floor = 1e-8;
  /// Edges must be longer than this fraction of the diagonal.
  double min_edge_length = 1e-12;
  /// Two faces about an edge closer than this angle (radians) count as coinciding.
  double min_angle = 1e-9;
  bool check_euler = true;
};

/// What validate(cell_complex) found: ok, or the first broken invariant, its element and why;
/// plus measurements useful either way.
struct cells_validation {
  cells_invariant broken = cells_invariant::none;
  std::uint32_t element = 0xFFFFFFFFu;  ///< index of the edge, face, volume or object named
  std::string message;
  std::vector<double> signed_volumes;       ///< per volume (computed before the Euler check)
  std::vector<long long> expected_euler;    ///< per object; meaningful where euler_checked
  std::vector<std::uint8_t> euler_checked;  ///< per object: 1 when the object is a manifold solid
  bool ok() const noexcept { return broken == cells_invariant::none; }
  explicit operator bool() const noexcept { return ok(); }
};

namespace detail::cells {

/// Signed volume of c on double positions. O(size of c).
template <class = void>
double signed_volume_of(const cell_topology& cc, std::span<const glm::dvec3> pts, cell_volume c,
                        const glm::dvec3& origin) {
  double six = 0.0;
  for (const auto& [f, sign] : cc.volume_faces(c)) {
    const glm::dvec3 apex = pts[cc.loop_vertices(f, 0)[0].idx()] - origin;
    double sum = 0.0;
    for (std::size_t l = 0; l < cc.num_loops(f); ++l) {
      const auto vs = cc.loop_vertices(f, l);
      for (std::size_t k = 0; k < vs.size(); ++k) {
        const glm::dvec3 a = pts[vs[k].idx()] - origin, b = pts[vs[(k + 1) % vs.size()].idx()] - origin;
        sum += glm::dot(apex, glm::cross(a, b));
      }
    }
    six += sign * sum;
  }
  return six / 6.0;
}

// Takes r by reference: the message may read r, and arguments are evaluated in any order.
template <class = void>
cells_validation broke(cells_validation& r, cells_invariant what, std::uint32_t element, std::string msg) {
  r.broken = what;
  r.element = element;
  r.message = std::move(msg);
  return std::move(r);
}

/// Angle of the direction into face ef about edge e, in the plane perpendicular to e. O(1).
template <class = void>
double angle_about(const cell_topology& cc, std::span<const glm::dvec3> pts, cell_edge e,
                   const oriented<cell_face>& ef) {
  // Unit vectors throughout: products of the raw edge vector underflow or overflow for edges
  // shorter than ~1e-9 or longer than ~1e9 (the angle must not depend on the model's scale).
  const glm::dvec3 d = glm::normalize(pts[cc.target(e).idx()] - pts[cc.source(e).idx()]);
  const glm::dvec3 into = glm::cross(access::unit_normal(cc, ef.handle), double(ef.sign) * d);
  const glm::dvec3 ad = glm::abs(d);
  const glm::dvec3 axis = ad.x <= ad.y && ad.x <= ad.z ? glm::dvec3(1, 0, 0)
                          : ad.y <= ad.z               ? glm::dvec3(0, 1, 0)
                                                       : glm::dvec3(0, 0, 1);
  const glm::dvec3 u = glm::normalize(glm::cross(d, axis)), w = glm::cross(d, u);
  return std::atan2(glm::dot(into, w), glm::dot(into, u));
}

/// The volume on the side of face ef toward negative rotation about the edge. O(1).
template <class = void>
cell_volume wedge_before(const cell_topology& cc, const oriented<cell_face>& ef) {
  for (const auto& v : cc.face_volumes(ef.handle))
    if (v.sign == ef.sign) return v.handle;
  return {};
}

/// Euler characteristic V - E + Σ(1 - holes) of a set of faces seen as a surface. O(size).
template <class = void>
long long surface_euler(const cell_topology& cc, const std::vector<cell_face>& faces,
                        std::vector<std::uint32_t>& vmark, std::vector<std::uint32_t>& emark,
                        std::uint32_t stamp) {
  long long chi = 0;
  for (cell_face f : faces) {
    chi += 1 - static_cast<long long>(cc.num_loops(f) - 1);
    for (std::size_t l = 0; l < cc.num_loops(f); ++l) {
      for (cell_vertex v : cc.loop_vertices(f, l))
        if (vmark[v.idx()] != stamp) vmark[v.idx()] = stamp, ++chi;
      for (const auto& ue : cc.loop_edges(f, l))
        if (emark[ue.handle.idx()] != stamp) emark[ue.handle.idx()] = stamp, --chi;
    }
  }
  return chi;
}

}  // namespace detail::cells

namespace detail::cells {
/// validate() on double positions (one copy of the code for every point type).
template <class = void>
cells_validation validate_cells(const cell_topology& cc, std::span<const glm::dvec3> pts,
                                const cells_validation_options& options) {
  using detail::cells::broke;
  using detail::cells::S;
  using inv = cells_invariant;
  cells_validation r;
  bounding_box box;
  for (const glm::dvec3& p : pts) box.add(p);
  const double diag = box.diagonal(), flat_floor = options.planarity_floor * diag,
               min_len = options.min_edge_length * diag;
  const glm::dvec3 centre = box.center();

  for (cell_edge e : cc.edges())
    if (!(glm::length(pts[cc.target(e).idx()] - pts[cc.source(e).idx()]) > min_len))
      return broke(r, inv::degenerate_edge, e.idx(),
                   cellforge::detail::cat("edge ", S(e.idx()), " (", S(cc.source(e).idx()), "-",
                                          S(cc.target(e).idx()), ") has (nearly) zero length"));

  for (cell_face f : cc.faces()) {
    const glm::dvec3 n = access::unit_normal(cc, f);
    if (glm::length(n) == 0.0)
      return broke(r, inv::degenerate_face, f.idx(),
                   cellforge::detail::cat("face ", S(f.idx()), ": its outer loop has no area"));
    const glm::dvec3 o = pts[cc.loop_vertices(f, 0)[0].idx()];
    bounding_box fbox;
    for (cell_vertex v : cc.loop_vertices(f, 0)) fbox.add(pts[v.idx()]);
    const double flat_tol = std::max(options.planarity * fbox.diagonal(), flat_floor);
    for (std::size_t l = 0; l < cc.num_loops(f); ++l) {
      for (cell_vertex v : cc.loop_vertices(f, l)) {
        const double dist = std::abs(glm::dot(pts[v.idx()] - o, n));
        if (dist > flat_tol)
          return broke(r, inv::non_planar, f.idx(),
                       cellforge::detail::cat("face ", S(f.idx()), ": vertex ", S(v.idx()), " is ",
                                              std::to_string(dist), " from the face's plane (tolerance ",
                                              std::to_string(flat_tol), ")"));
      }
      if (l > 0) {
        const auto vs = cc.loop_vertices(f, l);
        const glm::dvec3 hn = detail::cells::newell(vs, [&](cell_vertex v) { return pts[v.idx()] - o; });
        if (!(glm::dot(hn, n) < 0.0))
          return broke(r, inv::hole_orientation, f.idx(),
                       cellforge::detail::cat("face ", S(f.idx()), ": hole loop ", S(l),
                                              " does not turn clockwise about the face's normal"));
      }
    }
  }

  // Volume boundaries: each edge of the faces used exactly twice, in opposite directions.
  std::vector<int> uses(cc.num_edges(), 0), net(cc.num_edges(), 0);
  std::vector<std::uint32_t> touched;
  std::vector<double> own_diag, own_area;
  for (cell_volume c : cc.volumes()) {
    for (const auto& [f, sign] : cc.volume_faces(c))
      for (std::size_t l = 0; l < cc.num_loops(f); ++l)
        for (const auto& [e, es] : cc.loop_edges(f, l)) {
          if (uses[e.idx()] == 0) touched.push_back(e.idx());
          ++uses[e.idx()];
          net[e.idx()] += sign * es;
        }
    std::uint32_t bad = 0xFFFFFFFFu;
    for (std::uint32_t e : touched) {
      if ((uses[e] != 2 || net[e] != 0) && bad == 0xFFFFFFFFu) bad = e;
      uses[e] = net[e] = 0;
    }
    touched.clear();
    if (bad != 0xFFFFFFFFu)
      return broke(r, inv::open_boundary, c.idx(),
                   cellforge::detail::cat(
                       "volume ", S(c.idx()), ": edge ", S(bad),
                       " is not used exactly twice, in opposite directions, by the volume's faces"));
    r.signed_volumes.push_back(detail::cells::signed_volume_of(cc, pts, c, centre));
    // Each volume against its own size (its bounding-box diagonal cubed), not the model's: a
    // small cell beside a large one is as valid as the same cell alone.
    // ... and its surface area: diagonal³ would refuse a long thin bar (100 m by 1 cm) that
    // diagonal × area, a length³ too, lets pass while still refusing a flat one.
    bounding_box vbox;
    double area = 0.0;
    for (const auto& vf : cc.volume_faces(c)) {
      const auto vs = cc.loop_vertices(vf.handle, 0);
      for (cell_vertex v : vs) vbox.add(pts[v.idx()]);
      const glm::dvec3 o = pts[vs[0].idx()];
      area += 0.5 * glm::length(detail::cells::newell(vs, [&](cell_vertex v) { return pts[v.idx()] - o; }));
    }
    own_diag.push_back(vbox.diagonal());
    own_area.push_back(area);
  }
  for (cell_volume c : cc.volumes()) {
    const double vd = own_diag[c.idx()], min_volume = 1e-12 * vd * own_area[c.idx()];
    if (!(r.signed_volumes[c.idx()] > min_volume)) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%g (its own diagonal %g)", r.signed_volumes[c.idx()], vd);
      return broke(r, inv::orientation, c.idx(),
                   cellforge::detail::cat("volume ", S(c.idx()), " has signed volume ", buf,
                                          "; its faces' normals (with their signs) must point out of it"));
    }
  }

  // Rotation order about each edge: strictly increasing angles making one full turn, and the
  // volume between consecutive faces the same from both faces.
  for (cell_edge e : cc.edges()) {
    const auto ef = cc.edge_faces(e);
    const auto wedges = cc.edge_wedges(e);
    if (ef.size() < 2) continue;
    double turn = 0.0;
    for (std::size_t k = 0; k < ef.size(); ++k) {
      const auto& next = ef[(k + 1) % ef.size()];
      double step =
          detail::cells::angle_about(cc, pts, e, next) - detail::cells::angle_about(cc, pts, e, ef[k]);
      while (step <= 0.0) step += 2 * std::numbers::pi;
      if (step < options.min_angle || 2 * std::numbers::pi - step < options.min_angle)
        return broke(r, inv::rotation_order, e.idx(),
                     cellforge::detail::cat("edge ", S(e.idx()), ": faces ", S(ef[k].handle.idx()), " and ",
                                            S(next.handle.idx()),
                                            " lie on the same side of the edge (they coincide near it)"));
      turn += step;
      if (detail::cells::wedge_before(cc, next) != wedges[k])
        return broke(
            r, inv::wedge_mismatch, e.idx(),
            cellforge::detail::cat("edge ", S(e.idx()), ": between faces ", S(ef[k].handle.idx()), " and ",
                                   S(next.handle.idx()), " the two faces' volumes disagree"));
    }
    if (std::abs(turn - 2 * std::numbers::pi) > 1e-6)
      return broke(r, inv::rotation_order, e.idx(),
                   cellforge::detail::cat("edge ", S(e.idx()),
                                          ": its faces are not in right-hand rotation order (they turn ",
                                          std::to_string(turn / std::numbers::pi), " pi in all)"));
  }

  if (!options.check_euler) return r;
  // Euler: expected V - E + F - C = χ(∂X)/2 + holes + Σ_volumes (χ(∂c)/2 - 1), valid when the
  // object X is a solid whose outer surface is a 2-manifold (see docs/cells.md).
  const std::size_t no = cc.num_objects();
  r.expected_euler.assign(no, 0);
  r.euler_checked.assign(no, 1);
  std::vector<long long> holes(no, 0), volume_terms(no, 0);
  std::vector<std::vector<cell_face>> outside(no);
  std::vector<std::uint32_t> vmark(cc.num_vertices(), 0xFFFFFFFFu), emark(cc.num_edges(), 0xFFFFFFFFu);
  for (cell_edge e : cc.edges())
    if (cc.edge_faces(e).empty()) r.euler_checked[cc.vertex_object(cc.source(e)).idx()] = 0;
  for (cell_face f : cc.faces()) {
    const std::uint32_t o = cc.vertex_object(cc.loop_vertices(f, 0)[0]).idx();
    holes[o] += static_cast<long long>(cc.num_loops(f) - 1);
    if (cc.face_volumes(f).empty()) r.euler_checked[o] = 0;
    if (cc.face_volumes(f).size() == 1) outside[o].push_back(f);
  }
  for (cell_vertex v : cc.vertices())
    if (cc.vertex_edges(v).empty()) r.euler_checked[cc.vertex_object(v).idx()] = 0;
  std::vector<cell_face> faces;
  std::uint32_t stamp = 0;
  for (cell_volume c : cc.volumes()) {
    faces.clear();
    for (const auto& fs : cc.volume_faces(c)) faces.push_back(fs.handle);
    const long long chi = detail::cells::surface_euler(cc, faces, vmark, emark, stamp++);
    const std::uint32_t o = cc.volume_object(c).idx();
    if (chi % 2 != 0) {
      r.euler_checked[o] = 0;
      return broke(r, inv::euler, o,
                   cellforge::detail::cat("object ", S(o), ": the boundary of volume ", S(c.idx()),
                                          " has odd Euler characteristic ", std::to_string(chi),
                                          " (it is pinched at a vertex, not a closed surface)"));
    }
    volume_terms[o] += chi / 2 - 1;
  }
  // The outer surface must be a 2-manifold: at each of its vertices the outer faces form one
  // fan (corners joined across outer edges).
  std::unordered_map<std::uint64_t, std::uint32_t> corner;
  std::vector<std::uint32_t> parent;
  auto corner_of = [&](cell_face f, cell_vertex v) {
    const auto [it, fresh] =
        corner.emplace((std::uint64_t{f.idx()} << 32) | v.idx(), static_cast<std::uint32_t>(parent.size()));
    if (fresh) parent.push_back(it->second);
    return it->second;
  };
  for (cell_edge e : cc.edges()) {
    std::vector<cell_face> out;
    for (const auto& ef : cc.edge_faces(e))
      if (cc.face_volumes(ef.handle).size() == 1) out.push_back(ef.handle);
    if (out.empty()) continue;
    const std::uint32_t o = cc.vertex_object(cc.source(e)).idx();
    if (out.size() != 2) {
      r.euler_checked[o] = 0;
      continue;
    }
    for (cell_vertex v : cc.edge_vertices(e)) {
      const std::uint32_t a = corner_of(out[0], v), b = corner_of(out[1], v);
      parent[detail::cells::find_root(parent, a)] = detail::cells::find_root(parent, b);
    }
  }
  std::vector<std::uint32_t> fan_of(cc.num_vertices(), 0xFFFFFFFFu);
  for (const auto& [key, id] : corner) {
    const auto v = static_cast<std::uint32_t>(key & 0xFFFFFFFFu);
    const std::uint32_t root = detail::cells::find_root(parent, id);
    if (fan_of[v] == 0xFFFFFFFFu) fan_of[v] = root;
    if (fan_of[v] != root) r.euler_checked[cc.vertex_object(cell_vertex(v)).idx()] = 0;
  }
  for (cell_object o : cc.objects()) {
    const long long chi = detail::cells::surface_euler(cc, outside[o.idx()], vmark, emark, stamp++);
    if (chi % 2 != 0) r.euler_checked[o.idx()] = 0;
    r.expected_euler[o.idx()] = chi / 2 + holes[o.idx()] + volume_terms[o.idx()];
    if (r.euler_checked[o.idx()] && r.expected_euler[o.idx()] != cc.object_euler(o))
      return broke(r, inv::euler, o.idx(),
                   cellforge::detail::cat("object ", S(o.idx()), ": V - E + F - C is ",
                                          std::to_string(cc.object_euler(o)), " but its surfaces imply ",
                                          std::to_string(r.expected_euler[o.idx()])));
  }
  return r;
}
}  // namespace detail::cells

/// Signed volume enclosed by c's faces (normals out: positive), by the divergence theorem over
/// each face's loops fanned from the face's first vertex, about `origin` (default: the
/// origin). O(size of c).
template <Point3 P>
double signed_volume(const cell_complex<P>& cc, cell_volume c) {
  const detail::cells::dvec3_points<P> pts(cc.points());
  return detail::cells::signed_volume_of(cc, pts.span(), c, glm::dvec3(0.0));
}
template <Point3 P>
double signed_volume(const cell_complex<P>& cc, cell_volume c, const P& origin) {
  const detail::cells::dvec3_points<P> pts(cc.points());
  return detail::cells::signed_volume_of(cc, pts.span(), c, to_dvec3(origin));
}

/// Checks edges and faces (length, area, planarity, hole orientation), every volume boundary
/// (closed and two-manifold along edges, positive signed volume), rotation orders about every
/// edge against the geometry and the face→volume signs, and per object V - E + F - C against
/// the value implied by its boundary surfaces (docs/cells.md). O(n log n) for n = size of cc.
template <Point3 P>
cells_validation validate(const cell_complex<P>& cc, const cells_validation_options& options = {}) {
  const detail::cells::dvec3_points<P> pts(cc.points());
  return detail::cells::validate_cells(cc, pts.span(), options);
}

}  // namespace cellforge
