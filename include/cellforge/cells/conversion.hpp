// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Conversions between the 3DCL and half-edge meshes: a volume's boundary to a closed,
/// outward-oriented mesh (faces with holes triangulated), and a closed mesh to a one-volume
/// cell complex (optionally merging coplanar neighbouring faces into polygons with holes).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

/// How a volume's boundary becomes a mesh.
struct boundary_mesh_options {
  /// Triangulate every face; by default only faces with holes are (a half-edge face has one loop).
  bool triangulate_all = false;
};

/// How a closed mesh becomes a cell complex.
struct mesh_to_cells_options {
  /// Merge neighbouring coplanar faces into one polygon face (with holes where needed).
  bool merge_coplanar = false;
  /// Faces count as coplanar when their normals differ by at most this angle (degrees) from
  /// the first face of the region and their vertices lie within `coplanar_distance` (a
  /// fraction of the model's bounding-box diagonal) of its plane.
  double coplanar_angle_deg = 1e-4;
  double coplanar_distance = 1e-9;
};

namespace detail::cells {

/// Triangulates a planar polygon with holes (loops[0] counter-clockwise about n, the others
/// clockwise): holes are bridged to the outer ring, then ears are clipped with exact 2D
/// orientation tests in the projection that drops n's largest coordinate (exact, no rounding).
/// The result is checked: every triangle turns the right way and the areas add up to the
/// polygon's, otherwise it throws naming `who`. Returns indices into the loops concatenated.
/// O(k·n²) for n vertices, k holes.
template <class = void>
std::vector<std::array<std::uint32_t, 3>> triangulate_face(const std::vector<std::vector<glm::dvec3>>& loops,
                                                           const glm::dvec3& n, const std::string& who) {
  const int k = std::abs(n.x) >= std::abs(n.y) && std::abs(n.x) >= std::abs(n.z) ? 0
                : std::abs(n.y) >= std::abs(n.z)                                 ? 1
                                                                                 : 2;
  int ax = (k + 1) % 3, ay = (k + 2) % 3;
  if (n[k] < 0) std::swap(ax, ay);  // keep counter-clockwise loops counter-clockwise in 2D
  std::vector<glm::dvec2> p;
  std::vector<std::uint32_t> start;
  for (const auto& loop : loops) {
    start.push_back(static_cast<std::uint32_t>(p.size()));
    for (const auto& q : loop) p.push_back({q[ax], q[ay]});
  }
  start.push_back(static_cast<std::uint32_t>(p.size()));
  auto orient = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) { return orient2d(p[a], p[b], p[c]); };
  auto fail = [&](const std::string& why) -> void {
    throw error(error_category::topology, who + ": cannot triangulate the face: " + why);
  };

  for (std::size_t l = 0; l + 1 < start.size(); ++l) {
    double twice = 0.0;  // signed area (doubled): outer loop positive, holes negative
    for (std::uint32_t i = start[l]; i < start[l + 1]; ++i) {
      const std::uint32_t j = i + 1 < start[l + 1] ? i + 1 : start[l];
      twice += p[i].x * p[j].y - p[j].x * p[i].y;
    }
    if (l == 0 ? !(twice > 0) : !(twice < 0))
      fail(l == 0 ? std::string("the outer loop does not turn counter-clockwise about the normal")
                  : cellforge::detail::cat("hole ", std::to_string(l),
                                           " does not turn clockwise about the normal"));
  }
  std::vector<std::uint32_t> ring;
  for (std::uint32_t i = start[0]; i < start[1]; ++i) ring.push_back(i);
  // Holes in order of decreasing largest x, each bridged from its rightmost vertex M to a
  // ring vertex visible from M along the ray to +x (as in Eberly's "triangulation by ear
  // clipping").
  std::vector<std::uint32_t> holes;
  for (std::uint32_t h = 1; h + 1 < start.size(); ++h) holes.push_back(h);
  auto rightmost = [&](std::uint32_t h) {
    std::uint32_t m = start[h];
    for (std::uint32_t i = start[h]; i < start[h + 1]; ++i)
      if (p[i].x > p[m].x || (p[i].x == p[m].x && p[i].y < p[m].y)) m = i;
    return m;
  };
  std::sort(holes.begin(), holes.end(),
            [&](std::uint32_t a, std::uint32_t b) { return p[rightmost(a)].x > p[rightmost(b)].x; });
  // The ring holds every bridge made so far twice (there and back), so a position may be on
  // the ring twice: of two copies, take the one whose corner opens towards M (the inside of
  // the ring is on the left of its edges), or the second hole is spliced into the outside.
  auto opens_towards = [&](std::size_t i, const glm::dvec2& M) {
    const glm::dvec2 a = p[ring[(i + ring.size() - 1) % ring.size()]], v = p[ring[i]],
                     b = p[ring[(i + 1) % ring.size()]];
    const int in = orient2d(a, v, M), out = orient2d(v, b, M);
    return orient2d(a, v, b) >= 0 ? in >= 0 && out >= 0 : in >= 0 || out >= 0;
  };
  for (std::uint32_t h : holes) {
    const std::uint32_t m = rightmost(h);
    const glm::dvec2 M = p[m];
    double best = std::numeric_limits<double>::infinity();
    std::size_t hit = ring.size();
    bool hit_faces_m = false;  // M on the left of the hit edge: the copy of a bridge facing M
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const glm::dvec2 a = p[ring[i]], b = p[ring[(i + 1) % ring.size()]];
      if ((a.y > M.y) == (b.y > M.y) && a.y != M.y && b.y != M.y) continue;
      if (a.y == b.y) continue;  // horizontal: its ends are found through their other edges
      const double x = a.x + (M.y - a.y) * (b.x - a.x) / (b.y - a.y);
      const bool faces_m = orient2d(a, b, M) > 0;
      if (x >= M.x && (x < best || (x == best && faces_m && !hit_faces_m)))
        best = x, hit = i, hit_faces_m = faces_m;
    }
    if (hit == ring.size())
      fail(cellforge::detail::cat("hole ", std::to_string(h), " is not inside the outer loop"));
    // Candidate: the hit edge's end with the larger x; then any ring vertex inside the
    // triangle (M, hit point, candidate) that makes a smaller angle with the ray.
    const std::size_t i1 = (hit + 1) % ring.size();
    std::size_t pos = p[ring[hit]].x > p[ring[i1]].x ? hit : i1;
    const glm::dvec2 I{best, M.y}, C = p[ring[pos]];
    if (C != I) {
      const int o = orient2d(M, I, C);
      double best_slope = std::numeric_limits<double>::infinity(), best_dist = best_slope;
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const glm::dvec2 r = p[ring[i]];
        if (r == C || !(r.x > M.x)) continue;
        if (orient2d(M, I, r) * o < 0 || orient2d(I, C, r) * o < 0 || orient2d(C, M, r) * o < 0) continue;
        const double slope = std::abs(r.y - M.y) / (r.x - M.x), dist = glm::length(r - M);
        if (slope < best_slope || (slope == best_slope && dist < best_dist))
          best_slope = slope, best_dist = dist, pos = i;
      }
    }
    if (!opens_towards(pos, M))
      for (std::size_t i = 0; i < ring.size(); ++i)
        if (i != pos && p[ring[i]] == p[ring[pos]] && opens_towards(i, M)) {
          pos = i;
          break;
        }
    std::vector<std::uint32_t> bridged(ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(pos) + 1);
    const std::uint32_t len = start[h + 1] - start[h];
    for (std::uint32_t j = 0; j <= len; ++j) bridged.push_back(start[h] + (m - start[h] + j) % len);
    bridged.insert(bridged.end(), ring.begin() + static_cast<std::ptrdiff_t>(pos), ring.end());
    ring = std::move(bridged);
  }

  // Ear clipping over a linked ring; vertices at the position of the ear's corners (bridge
  // copies) do not block it.
  std::vector<std::array<std::uint32_t, 3>> tris;
  const std::size_t nr = ring.size();
  std::vector<std::uint32_t> nx(nr), pv(nr);
  for (std::size_t i = 0; i < nr; ++i)
    nx[i] = static_cast<std::uint32_t>((i + 1) % nr), pv[i] = static_cast<std::uint32_t>((i + nr - 1) % nr);
  std::size_t left = nr;
  std::uint32_t cur = 0;
  auto is_ear = [&](std::uint32_t i) {
    const std::uint32_t a = ring[pv[i]], b = ring[i], c = ring[nx[i]];
    if (orient(a, b, c) <= 0) return false;
    for (std::uint32_t j = nx[nx[i]]; j != pv[i]; j = nx[j]) {
      const std::uint32_t q = ring[j];
      if (p[q] == p[a] || p[q] == p[b] || p[q] == p[c]) continue;
      if (orient(a, b, q) >= 0 && orient(b, c, q) >= 0 && orient(c, a, q) >= 0) return false;
    }
    return true;
  };
  while (left > 3) {
    std::uint32_t i = cur;
    bool clipped = false;
    for (std::size_t tries = 0; tries < left; ++tries, i = nx[i])
      if (is_ear(i)) {
        clipped = true;
        break;
      }
    if (!clipped) {  // only collinear corners left where no ear is: clip a flat one
      i = cur;
      for (std::size_t tries = 0; tries < left && !clipped; ++tries, i = nx[i])
        if (orient(ring[pv[i]], ring[i], ring[nx[i]]) == 0) {
          clipped = true;
          break;
        }
      if (!clipped) fail("no ear found (the loops cross or touch each other)");
    }
    tris.push_back({ring[pv[i]], ring[i], ring[nx[i]]});
    nx[pv[i]] = nx[i];
    pv[nx[i]] = pv[i];
    cur = pv[i];
    --left;
  }
  tris.push_back({ring[pv[cur]], ring[cur], ring[nx[cur]]});

  // Check: no triangle turns backwards and the areas add up.
  auto area2 = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return (p[b].x - p[a].x) * (p[c].y - p[a].y) - (p[b].y - p[a].y) * (p[c].x - p[a].x);
  };
  double polygon = 0.0, sum = 0.0, scale = 0.0;
  for (std::size_t l = 0; l + 1 < start.size(); ++l)
    for (std::uint32_t i = start[l]; i < start[l + 1]; ++i) {
      const std::uint32_t j = i + 1 < start[l + 1] ? i + 1 : start[l];
      polygon += p[i].x * p[j].y - p[j].x * p[i].y;
    }
  for (const auto& t : tris) {
    if (orient(t[0], t[1], t[2]) < 0) fail("a triangle turns backwards (the loops are not nested as stated)");
    const double a = area2(t[0], t[1], t[2]);
    sum += a;
    scale += std::abs(a);
  }
  if (!(std::abs(sum - polygon) <= 1e-9 * std::max(scale, std::abs(polygon))) || !(polygon > 0))
    fail("the triangles do not cover the face exactly (the loops cross, or a hole is outside)");
  return tris;
}

}  // namespace detail::cells

/// The boundary of volume c as a closed surface mesh with normals pointing out of c:
/// positions in the complex's point type P, the complex's vertex of each mesh vertex in
/// "v:cell_vertex" and the face of each mesh face in "f:cell_face" (std::uint32_t). Faces
/// with holes (all faces, with triangulate_all) are triangulated. O(size of c), plus
/// O(k·n²) per triangulated face. Throws what make_mesh throws (e.g. a pinched boundary).
template <Point3 P>
surface_mesh<P> volume_boundary_mesh(const cell_complex<P>& cc, cell_volume c,
                                     const boundary_mesh_options& options = {}) {
  if (!(c.idx() < cc.num_volumes()))
    throw error(error_category::invalid_input,
                cellforge::detail::cat("volume_boundary_mesh: there is no volume ", std::to_string(c.idx())));
  polygon_soup<P> soup;
  std::vector<std::uint32_t> cell_vertex_of, cell_face_of;
  std::unordered_map<std::uint32_t, std::uint32_t> index;
  auto id = [&](cell_vertex v) {
    const auto [it, fresh] = index.emplace(v.idx(), static_cast<std::uint32_t>(soup.points.size()));
    if (fresh) {
      soup.points.push_back(cc.point(v));
      cell_vertex_of.push_back(v.idx());
    }
    return it->second;
  };
  std::vector<std::uint32_t> face;
  for (const auto& [f, sign] : cc.volume_faces(c)) {
    if (cc.num_loops(f) == 1 && !options.triangulate_all) {
      face.clear();
      for (cell_vertex v : cc.loop_vertices(f, 0)) face.push_back(id(v));
      if (sign < 0) std::reverse(face.begin(), face.end());
      soup.add_face(face);
      cell_face_of.push_back(f.idx());
      continue;
    }
    std::vector<std::vector<glm::dvec3>> loops(cc.num_loops(f));
    std::vector<cell_vertex> flat;
    for (std::size_t l = 0; l < loops.size(); ++l)
      for (cell_vertex v : cc.loop_vertices(f, l))
        loops[l].push_back(to_dvec3(cc.point(v))), flat.push_back(v);
    const auto tris = detail::cells::triangulate_face(
        loops, detail::cells::access::unit_normal(cc, f),
        cellforge::detail::cat("volume_boundary_mesh: face ", std::to_string(f.idx())));
    for (const auto& t : tris) {
      face = {id(flat[t[0]]), id(flat[t[1]]), id(flat[t[2]])};
      if (sign < 0) std::swap(face[1], face[2]);
      soup.add_face(face);
      cell_face_of.push_back(f.idx());
    }
  }
  surface_mesh<P> m = make_mesh(soup);
  auto cv = m.template add_vertex_property<std::uint32_t>("v:cell_vertex");
  auto cf = m.template add_face_property<std::uint32_t>("f:cell_face");
  std::copy(cell_vertex_of.begin(), cell_vertex_of.end(), cv.vector().begin());
  std::copy(cell_face_of.begin(), cell_face_of.end(), cf.vector().begin());
  return m;
}

/// A closed, consistently oriented mesh as a one-volume cell complex: one face per mesh face,
/// or, with merge_coplanar, one face per region of coplanar neighbouring faces (holes where the
/// region surrounds others; a region that touches itself at a vertex stays unmerged). The
/// face signs make the volume's signed volume positive.
/// O(size of the mesh) (plus the regions' boundary walks). Throws topology when the mesh is
/// not closed or not consistently oriented.
template <Point3 P>
cell_complex<P> mesh_to_cell_complex(const surface_mesh<P>& m, const mesh_to_cells_options& options = {}) {
  using std::uint32_t;
  constexpr uint32_t none = 0xFFFFFFFFu;
  if (!m.is_closed())
    throw error(
        error_category::topology,
        cellforge::detail::cat("mesh_to_cell_complex: the mesh has ", std::to_string(m.num_boundary_edges()),
                               " boundary edges; a volume needs a closed surface"));
  if (!m.is_consistently_oriented())
    throw error(error_category::topology,
                "mesh_to_cell_complex: the mesh is not consistently oriented (orient it first)");
  auto pos = [&](vertex_handle v) { return to_dvec3(m.position(v)); };
  bounding_box box;
  for (vertex_handle v : m.vertices()) box.add(pos(v));

  // Regions of faces: each face alone, or grown from a seed across coplanar neighbours.
  std::vector<uint32_t> region(m.faces_size(), none);
  std::vector<glm::dvec3> region_normal;
  std::vector<std::vector<face_handle>> members;
  auto normal_of = [&](face_handle f) {
    std::vector<vertex_handle> vs;
    for (vertex_handle v : m.vertices_around(f)) vs.push_back(v);
    const glm::dvec3 n = detail::cells::newell(vs, [&](vertex_handle v) { return pos(v); });
    const double len = glm::length(n);
    return len > 0 ? n / len : n;
  };
  const double cos_tol = std::cos(options.coplanar_angle_deg * std::numbers::pi / 180.0),
               dist_tol = options.coplanar_distance * box.diagonal();
  for (face_handle seed : m.faces()) {
    if (region[seed.idx()] != none) continue;
    const auto r = static_cast<uint32_t>(members.size());
    const glm::dvec3 n = normal_of(seed), o = pos(m.head(m.halfedge(seed)));
    region_normal.push_back(n);
    members.push_back({seed});
    region[seed.idx()] = r;
    for (std::size_t i = 0; options.merge_coplanar && i < members[r].size(); ++i)
      for (halfedge_handle h : m.halfedges_around(members[r][i])) {
        const face_handle g = m.face(halfedge_mesh::twin(h));
        if (region[g.idx()] != none || glm::dot(normal_of(g), n) < cos_tol) continue;
        bool flat = true;
        for (vertex_handle v : m.vertices_around(g))
          flat = flat && std::abs(glm::dot(pos(v) - o, n)) <= dist_tol;
        if (!flat) continue;
        region[g.idx()] = r;
        members[r].push_back(g);
      }
  }

  // Each region's boundary loops: half-edges whose twin lies in another region, chained at
  // their heads. A region whose boundary passes a vertex twice, or has several outer loops,
  // falls back to one face per mesh face.
  cell_complex_input<P> in;
  std::vector<uint32_t> vid(m.vertices_size(), none), eid(m.edges_size(), none);
  auto vertex_id = [&](vertex_handle v) {
    if (vid[v.idx()] == none) {
      vid[v.idx()] = static_cast<uint32_t>(in.points.size());
      in.points.push_back(m.position(v));
    }
    return vid[v.idx()];
  };
  auto add_loops = [&](const std::vector<std::vector<vertex_handle>>& loops) {
    cell_input_face face;
    for (const auto& loop : loops) {
      face.loops.emplace_back();
      for (std::size_t i = 0; i < loop.size(); ++i) {
        face.loops.back().push_back(vertex_id(loop[i]));
        const edge_handle e = m.find_edge(loop[i], loop[(i + 1) % loop.size()]);
        if (eid[e.idx()] == none) {
          eid[e.idx()] = static_cast<uint32_t>(in.edges.size());
          in.edges.push_back({0, 0});  // endpoints filled once every vertex has its index
        }
      }
    }
    in.faces.push_back(std::move(face));
  };
  std::unordered_map<uint32_t, halfedge_handle> out;
  for (std::size_t r = 0; r < members.size(); ++r) {
    std::vector<std::vector<vertex_handle>> loops;
    bool simple = true;
    if (members[r].size() > 1) {
      out.clear();
      for (face_handle f : members[r])
        for (halfedge_handle h : m.halfedges_around(f))
          if (region[m.face(halfedge_mesh::twin(h)).idx()] != r)
            simple = simple && out.emplace(m.tail(h).idx(), h).second;
      std::size_t walked = 0;
      while (simple && walked < out.size()) {
        halfedge_handle h{};
        for (const auto& [v, g] : out)
          if (g.is_valid()) h = g;
        std::vector<vertex_handle> loop;
        while (h.is_valid() && out[m.tail(h).idx()].is_valid()) {
          out[m.tail(h).idx()] = halfedge_handle();
          loop.push_back(m.tail(h));
          ++walked;
          const auto it = out.find(m.head(h).idx());
          h = it == out.end() ? halfedge_handle() : it->second;
        }
        loops.push_back(std::move(loop));
      }
      // Exactly one loop turns counter-clockwise about the region's normal: the outer one.
      std::size_t outer = loops.size(), positive = 0;
      for (std::size_t l = 0; l < loops.size(); ++l)
        if (glm::dot(detail::cells::newell(loops[l], [&](vertex_handle v) { return pos(v); }),
                     region_normal[r]) > 0)
          ++positive, outer = l;
      simple = simple && positive == 1;
      if (simple) std::swap(loops[0], loops[outer]);
    }
    if (members[r].size() == 1 || !simple) {
      for (face_handle f : members[r]) {
        std::vector<vertex_handle> loop;
        for (vertex_handle v : m.vertices_around(f)) loop.push_back(v);
        add_loops({loop});
      }
    } else {
      add_loops(loops);
    }
  }
  for (edge_handle e : m.edges())
    if (eid[e.idx()] != none) in.edges[eid[e.idx()]] = {vid[m.vertex(e, 0).idx()], vid[m.vertex(e, 1).idx()]};

  // One volume; the signs make its signed volume positive.
  double six = 0.0;
  for (const auto& face : in.faces) {
    auto at = [&](std::uint32_t i) { return to_dvec3(in.points[i]) - box.center(); };
    const glm::dvec3 apex = at(face.loops[0][0]);
    for (const auto& loop : face.loops)
      for (std::size_t i = 0; i < loop.size(); ++i)
        six += glm::dot(apex, glm::cross(at(loop[i]), at(loop[(i + 1) % loop.size()])));
  }
  cell_input_volume vol;
  for (std::size_t f = 0; f < in.faces.size(); ++f)
    vol.faces.emplace_back(static_cast<uint32_t>(f), six < 0 ? -1 : 1);
  if (!in.faces.empty()) in.volumes.push_back(std::move(vol));
  return make_cell_complex(std::move(in));
}

}  // namespace cellforge
