// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The cubic edge fitter of seed 000 §6: every edge of a closed solid becomes a cubic,
/// quadratic or straight curve from the normals of its continuous surface (§6.1–6.4), with the
/// midpoints readjusted until they settle (§6.5). Beyond the seed: creases between surfaces are
/// smoothed too, and curves that are not a function of one axis get a parametric (Bézier) form.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/smooth/continuous_surfaces.hpp"
#include "cellforge/smooth/edge_curve.hpp"
#include "cellforge/smooth/normals.hpp"

namespace cellforge {

/// Options of smooth_edges(). The defaults go beyond the seed; seed_smooth_options() is the seed.
struct smooth_options {
  double angle_deg = 45;  ///< continuous-surface threshold (§6.1), 0..90 degrees
  /// Beyond the seed: edges between two surfaces (creases) are curved too, their end tangents
  /// along the crossing of the two sides' normals (the seed leaves them straight, §8.2).
  bool smooth_creases = true;
  /// Beyond the seed: vertices on a surface's border get that surface's normal for the surface's
  /// edges (the seed gives normals to interior vertices only, §6.2).
  bool boundary_vertex_normals = true;
  /// Beyond the seed: an edge inside a surface whose own dihedral angle is at least angle_deg is a
  /// crease too (a surface can wrap round to meet itself at a sharp edge).
  bool crease_inside_surfaces = true;
  curve_form form = curve_form::automatic;  ///< see curve_form and docs/smooth.md
  /// automatic: the axis form is used only when, at each end with a tangent, the tangent runs the
  /// chord's way along the axis and the handle the axis form implies (range / tangent's axis share)
  /// is within this factor of the chord's (|chord|); 1 ≤ value ≤ 1e6. See docs/smooth.md.
  double axis_handle_ratio = 1.25;
  double convergence = 0.001;  ///< midpoint move limit × model size (§6.5), 0 < value ≤ 1
  int max_iterations = 100;    ///< readjustment cycles (the work budget), 1..1'000'000
  int stall_cycles = 5;        ///< equal moving counts that trigger the seed's averaging, 1..1000
};

/// The seed's exact rules (seed 000 §6): creases straight, normals at interior vertices only,
/// no crease inside a surface, the axis form everywhere it exists. O(1).
template <class = void>
smooth_options seed_smooth_options() {
  smooth_options o;
  o.smooth_creases = false;
  o.boundary_vertex_normals = false;
  o.crease_inside_surfaces = false;
  o.form = curve_form::axis_polynomial;
  return o;
}

/// How one end of a curve was shaped: its tangent, when it has one, is perpendicular to both
/// normals (equal except at a crease end, where they are the two sides' normals). Directions are
/// of the mesh's point type P (zero when absent).
template <Point3 P>
struct curve_end {
  bool has_tangent = false;
  bool crease = false;
  P normal_a = point_traits<P>::make(0, 0, 0), normal_b = point_traits<P>::make(0, 0, 0);
  P direction = point_traits<P>::make(0, 0, 0);  ///< unit tangent direction along the curve (v0 → v1)
};

/// The part of smooth_result that holds no points. stage_report: milliseconds the call;
/// complete false (with a diagnostic) when max_iterations ran out before the midpoints settled.
struct smooth_result_base : stage_report {
  std::vector<std::uint32_t> surface_of_face;  ///< by face id (cell face id for a complex)
  std::size_t num_surfaces = 0;
  std::size_t num_cubic = 0, num_quadratic = 0, num_straight = 0;
  std::size_t num_axis_form = 0, num_bezier_form = 0;
  std::size_t num_axis_fallbacks = 0;  ///< axis_polynomial asked for but impossible
  std::size_t num_creases = 0;         ///< edges between two sectors of faces
  int iterations = 0;                  ///< readjustment cycles run
  bool converged = false;              ///< no midpoint moved more than the limit in the last cycle
  bool averaged = false;               ///< ended by the seed's averaging of the recent cycles
  std::vector<std::size_t> moving;     ///< per cycle: midpoints that moved more than the limit
  double model_size = 0;
};

/// What smooth_edges() returns, in the mesh's point type P; curves[i].edge == i for a mesh
/// (sorted cell-edge ids for a complex).
template <Point3 P>
struct smooth_result : smooth_result_base {
  using point_type = P;
  std::vector<edge_curve<P>> curves;
  std::vector<std::array<curve_end<P>, 2>> ends;  ///< parallel to curves: at v0 and at v1
  std::vector<P> midpoints;                       ///< parallel to curves: readjusted midpoints (§6.5)
  std::vector<P> vertex_normals;                  ///< by vertex id: interior vertices (§6.2), else zero
};

namespace detail::smooth {

using dend = curve_end<glm::dvec3>;
using dresult = smooth_result<glm::dvec3>;

template <class = void>
void check_options(const smooth_options& o) {
  check_surface_angle(o.angle_deg, "smooth_edges");
  auto bad = [](const char* name, const std::string& value, const char* range) {
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string("smooth_edges: "), name, " = ", value, ", must be within ",
                                       range));
  };
  if (!(o.convergence > 0 && o.convergence <= 1)) bad("convergence", std::to_string(o.convergence), "(0, 1]");
  if (!(o.axis_handle_ratio >= 1 && o.axis_handle_ratio <= 1e6))
    bad("axis_handle_ratio", std::to_string(o.axis_handle_ratio), "[1, 1e6]");
  if (o.max_iterations < 1 || o.max_iterations > 1'000'000)
    bad("max_iterations", std::to_string(o.max_iterations), "1..1000000");
  if (o.stall_cycles < 1 || o.stall_cycles > 1000)
    bad("stall_cycles", std::to_string(o.stall_cycles), "1..1000");
  if (o.form != curve_form::automatic && o.form != curve_form::axis_polynomial &&
      o.form != curve_form::bezier)
    bad("form", std::to_string(static_cast<int>(o.form)), "automatic, axis_polynomial, bezier");
}

/// §6.5's recursive 7-point search: the curve parameter whose point is nearest the line through
/// m along unit n. Each round keeps the two neighbours of the best of 7 points (a third of the
/// interval); stops below 1e-12 in t. O(1) (at most 26 rounds).
template <class = void>
double nearest_to_line(const dcurve& c, const glm::dvec3& m, const glm::dvec3& n) {
  double lo = 0, hi = 1;
  while (hi - lo > 1e-12) {
    std::array<double, 7> t{};
    int best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 7; ++i) {
      t[i] = i == 6 ? hi : lo + (hi - lo) * (i / 6.0);
      // |(P − M) × N| is the distance to the line; the seed's Heron formula gives the same value
      // with more cancellation.
      const double d = glm::length(glm::cross(c.point(t[i]) - m, n));
      if (d < best_d) best_d = d, best = i;
    }
    lo = t[static_cast<std::size_t>(std::max(best - 1, 0))];
    hi = t[static_cast<std::size_t>(std::min(best + 1, 6))];
  }
  return 0.5 * (lo + hi);
}

template <class = void>
struct basic_smoother;
using smoother = basic_smoother<>;

/// The smoothing state of one mesh: fixed data (normals, sectors) and the per-cycle curves.
template <class>
struct basic_smoother {
  const halfedge_mesh& m;
  const solid_geometry& g;
  const smooth_options& o;
  std::vector<std::uint8_t> smooth;       // edge is not a crease
  std::vector<std::uint8_t> form_choice;  // 0 undecided, 1 axis form, 2 Bézier
  std::vector<glm::dvec3> edge_normal, sector_normal, midpoints;
  vertex_sectors sectors;
  dresult r;

  basic_smoother(const halfedge_mesh& mesh, const solid_geometry& geometry, const smooth_options& options)
      : m(mesh), g(geometry), o(options) {}

  glm::dvec3 pos(vertex_handle v) const { return g.positions[v.idx()]; }

  // The end of edge e at its vertex i (0: tail of half-edge 0, 1: its head).
  dend end_of(edge_handle e, unsigned i, const glm::dvec3& chord) const {
    const halfedge_handle h0 = halfedge_mesh::halfedge(e, 0), h1 = halfedge_mesh::halfedge(e, 1);
    const halfedge_handle ca = i == 1 ? h0 : m.prev(h0), cb = i == 1 ? m.prev(h1) : h1;
    const std::uint32_t sa = sectors.sector_of_corner[ca.idx()], sb = sectors.sector_of_corner[cb.idx()];
    const std::uint32_t v = m.vertex(e, i).idx();
    dend end;
    end.crease = !smooth[e.idx()];
    end.normal_a = sector_normal[sa];
    end.normal_b = sector_normal[sb];
    const double chord_len = glm::length(chord);
    auto accept = [&](glm::dvec3 t) {
      const double len = glm::length(t);
      if (!(len > 1e-9 * chord_len)) return end;  // degenerate: no tangent
      if (glm::dot(t, chord) < 0) t = -t;
      if (!(glm::dot(t, chord) > 1e-9 * len * chord_len)) return end;
      dend out = end;
      out.has_tangent = true;
      out.direction = t / len;
      return out;
    };
    // §6.4: the derivative at a vertex with normal n is (n × v) × n, v the chord.
    auto along_normal = [&](const glm::dvec3& n) { return accept(glm::cross(glm::cross(n, chord), n)); };
    if (smooth[e.idx()]) {
      if (sectors.creases_at_vertex[v] == 0 || o.boundary_vertex_normals) return along_normal(end.normal_a);
      return end;
    }
    if (!o.smooth_creases) return end;
    if (sa == sb) return along_normal(end.normal_a);  // a crease that ends inside one smooth fan
    const glm::dvec3 t = glm::cross(end.normal_a, end.normal_b);
    // Unit normals: |n_a × n_b| is the sine of the angle between the sides.
    if (!(glm::length(t) > 1e-9)) return end;
    return accept(t * chord_len);
  }

  // The axis form's handle at an end is |range| / |t̂_axis|, the chord's is |chord|: their ratio
  // is |v̂_axis| / |t̂_axis|. Near 1 the x-parametrised cubic is as round as the parametric one.
  bool axis_ok(const dend& end, int axis, const glm::dvec3& chord) const {
    if (!end.has_tangent) return true;
    const double along = end.direction[axis] * (chord[axis] < 0 ? -1.0 : 1.0);
    if (!(along > 0)) return false;
    const double ratio = std::abs(chord[axis]) / glm::length(chord) / along;
    return ratio <= o.axis_handle_ratio && ratio * o.axis_handle_ratio >= 1;
  }

  void build_curves() {
    sector_normals(m, g, sectors, detail::span_of(smooth), detail::span_of(edge_normal),
                   detail::span_of(midpoints), sector_normal);
    r.num_cubic = r.num_quadratic = r.num_straight = 0;
    r.num_axis_form = r.num_bezier_form = r.num_axis_fallbacks = 0;
    for (edge_handle e : m.edges()) {
      const vertex_handle a = m.vertex(e, 0), b = m.vertex(e, 1);
      const glm::dvec3 p0 = pos(a), p1 = pos(b), chord = p1 - p0;
      const dend e0 = end_of(e, 0, chord), e1 = end_of(e, 1, chord);
      std::optional<glm::dvec3> t0, t1;
      if (e0.has_tangent) t0 = e0.direction;
      if (e1.has_tangent) t1 = e1.direction;
      const int axis = detail::largest_range_axis(p0, p1);
      std::optional<dcurve> c;
      // automatic decides each edge's form once, in the first cycle, so that tangents moving a
      // hair across the threshold cannot make the readjustment flip between forms for ever.
      std::uint8_t& choice = form_choice[e.idx()];
      if (choice == 0)
        choice =
            o.form == curve_form::bezier ? 2
            : o.form == curve_form::axis_polynomial || (axis_ok(e0, axis, chord) && axis_ok(e1, axis, chord))
                ? 1
                : 2;
      const bool want_axis = choice == 1;
      if (want_axis) c = detail::fit_axis_curve(p0, p1, axis, t0, t1);
      if (!c) {
        if (want_axis) ++r.num_axis_fallbacks;
        c = detail::fit_bezier_curve(p0, p1, t0, t1);
      }
      const int tangents = (t0 ? 1 : 0) + (t1 ? 1 : 0);
      c->kind = tangents == 2   ? curve_kind::cubic
                : tangents == 1 ? curve_kind::quadratic
                                : curve_kind::straight;
      c->edge = e.idx();
      c->v0 = a.idx();
      c->v1 = b.idx();
      ++(tangents == 2 ? r.num_cubic : tangents == 1 ? r.num_quadratic : r.num_straight);
      ++(c->has_axis_form ? r.num_axis_form : r.num_bezier_form);
      r.curves[e.idx()] = *c;
      r.ends[e.idx()] = {e0, e1};
    }
  }

  dresult run() {
    surface_partition part = continuous_surfaces(m, detail::span_of(g.face_normals), o.angle_deg);
    r.model_size = g.model_size;
    r.num_surfaces = part.surfaces.size();
    r.surface_of_face = std::move(part.surface_of_face);
    smooth.assign(m.edges_size(), 0);
    form_choice.assign(m.edges_size(), 0);
    for (edge_handle e : m.edges()) {
      const std::uint32_t fa = m.face(e, 0).idx(), fb = m.face(e, 1).idx();
      const bool same = r.surface_of_face[fa] == r.surface_of_face[fb];
      const bool sharp = o.crease_inside_surfaces &&
                         !(normal_angle_deg(g.face_normals[fa], g.face_normals[fb]) < o.angle_deg);
      smooth[e.idx()] = same && !sharp ? 1 : 0;
      r.num_creases += smooth[e.idx()] ? 0 : 1;
    }
    edge_normal = edge_normals(m, g);
    sectors = make_vertex_sectors(m, g, detail::span_of(smooth));
    midpoints.assign(m.edges_size(), glm::dvec3(0));
    for (edge_handle e : m.edges()) midpoints[e.idx()] = 0.5 * (pos(m.vertex(e, 0)) + pos(m.vertex(e, 1)));
    r.curves.assign(m.edges_size(), dcurve{});
    r.ends.assign(m.edges_size(), {});
    std::vector<std::uint8_t> frozen(m.edges_size(), 0);
    std::vector<std::vector<glm::dvec3>> history;  // the last stall_cycles + 1 midpoint sets, oldest first
    const double limit = o.convergence * g.model_size;
    std::size_t same_count = 0;
    for (bool done = false;;) {
      build_curves();
      if (done) break;
      if (r.iterations == o.max_iterations) break;  // the budget: converged stays false
      std::size_t moving = 0;
      for (edge_handle e : m.edges()) {
        const auto& ends = r.ends[e.idx()];
        if (frozen[e.idx()] || (!ends[0].has_tangent && !ends[1].has_tangent)) continue;
        const glm::dvec3 n = edge_normal[e.idx()];
        if (glm::dot(n, n) == 0) continue;
        const dcurve& c = r.curves[e.idx()];
        const glm::dvec3 next = c.point(nearest_to_line(c, midpoints[e.idx()], n));
        const double move = glm::length(next - midpoints[e.idx()]);
        midpoints[e.idx()] = next;
        // §6.5: a midpoint that moved less than the limit is no longer adjusted.
        if (move > limit)
          ++moving;
        else
          frozen[e.idx()] = 1;
      }
      ++r.iterations;
      r.moving.push_back(moving);
      history.push_back(midpoints);
      if (history.size() > static_cast<std::size_t>(o.stall_cycles) + 1) history.erase(history.begin());
      if (moving == 0) {
        r.converged = done = true;
        continue;
      }
      same_count = r.moving.size() >= 2 && r.moving[r.moving.size() - 2] == moving ? same_count + 1 : 0;
      if (same_count >= static_cast<std::size_t>(o.stall_cycles)) {
        // The seed's fallback: the same number keeps moving, so average the recent results.
        for (std::size_t i = 0; i < midpoints.size(); ++i) {
          glm::dvec3 sum(0);
          for (const auto& h : history) sum += h[i];
          midpoints[i] = sum / static_cast<double>(history.size());
        }
        r.averaged = done = true;
      }
    }
    r.midpoints = midpoints;
    r.vertex_normals.assign(m.vertices_size(), glm::dvec3(0));
    for (halfedge_handle h : m.halfedges())
      if (sectors.creases_at_vertex[m.head(h).idx()] == 0)
        r.vertex_normals[m.head(h).idx()] = sector_normal[sectors.sector_of_corner[h.idx()]];
    return std::move(r);
  }
};

/// The result in the mesh's point type: one conversion of every point at the end (none for
/// glm::dvec3). O(E + V).
template <Point3 P>
smooth_result<P> result_as(dresult&& r) {
  if constexpr (std::is_same_v<P, glm::dvec3>) {
    return std::move(r);
  } else {
    smooth_result<P> out;
    static_cast<smooth_result_base&>(out) = std::move(static_cast<smooth_result_base&>(r));
    const auto end_as = [](const dend& e) {
      curve_end<P> x;
      x.has_tangent = e.has_tangent, x.crease = e.crease;
      x.normal_a = from_dvec3<P>(e.normal_a), x.normal_b = from_dvec3<P>(e.normal_b);
      x.direction = from_dvec3<P>(e.direction);
      return x;
    };
    out.curves.reserve(r.curves.size());
    for (const dcurve& c : r.curves) out.curves.push_back(curve_cast<P>(c));
    out.ends.reserve(r.ends.size());
    for (const auto& e : r.ends) out.ends.push_back({end_as(e[0]), end_as(e[1])});
    out.midpoints.reserve(r.midpoints.size());
    for (const glm::dvec3& p : r.midpoints) out.midpoints.push_back(from_dvec3<P>(p));
    out.vertex_normals.reserve(r.vertex_normals.size());
    for (const glm::dvec3& p : r.vertex_normals) out.vertex_normals.push_back(from_dvec3<P>(p));
    return out;
  }
}

/// A volume's boundary-mesh result with cell ids (see smooth_edges on a cell complex): curves
/// renumbered and sorted by cell edge, diagonals dropped, faces and vertex normals by cell id.
template <Point3 P>
smooth_result<P> with_cell_ids(const cell_topology& cc, const halfedge_mesh& m, smooth_result<P>&& r) {
  const auto cv = m.get_vertex_property<std::uint32_t>("v:cell_vertex");
  const auto cf = m.get_face_property<std::uint32_t>("f:cell_face");
  std::vector<std::size_t> keep;
  for (std::size_t i = 0; i < r.curves.size(); ++i) {
    edge_curve<P>& c = r.curves[i];
    const cell_vertex a(cv[vertex_handle(c.v0)]), b(cv[vertex_handle(c.v1)]);
    for (const auto& oe : cc.vertex_edges(a)) {
      const auto ends = cc.edge_vertices(oe.handle);
      if ((ends[0] == a && ends[1] == b) || (ends[0] == b && ends[1] == a)) {
        c.edge = oe.handle.idx();
        c.v0 = a.idx();
        c.v1 = b.idx();
        keep.push_back(i);
        break;
      }
    }
  }
  std::sort(keep.begin(), keep.end(),
            [&](std::size_t x, std::size_t y) { return r.curves[x].edge < r.curves[y].edge; });
  smooth_result<P> out;
  static_cast<smooth_result_base&>(out) = r;
  for (std::size_t i : keep) {
    out.curves.push_back(r.curves[i]);
    out.ends.push_back(r.ends[i]);
    out.midpoints.push_back(r.midpoints[i]);
  }
  out.surface_of_face.assign(cc.num_faces(), 0xFFFFFFFFu);
  for (face_handle f : m.faces()) out.surface_of_face[cf[f]] = r.surface_of_face[f.idx()];
  out.vertex_normals.assign(cc.num_vertices(), point_traits<P>::make(0, 0, 0));
  for (vertex_handle x : m.vertices()) out.vertex_normals[cv[x]] = r.vertex_normals[x.idx()];
  return out;
}

}  // namespace detail::smooth

/// Smooths every edge of the closed solid m into a curve (seed 000
/// §6 with the beyond-seed options above); the curves, ends, midpoints and normals come back
/// in m's point type P (computed in double precision, converted once). O(E · iterations) time,
/// O(E) memory (plus stall_cycles copies of the midpoints). Throws error(topology) for an open or
/// inconsistently oriented mesh, error(invalid_input) for degenerate faces, non-finite points or bad options.
template <Point3 P>
smooth_result<P> smooth_edges(const surface_mesh<P>& m, const smooth_options& options = {}) {
  const detail::stopwatch clock;
  detail::smooth::check_options(options);
  const solid_geometry g = solid_geometry_of(m, "smooth_edges");
  smooth_result<P> r = detail::smooth::result_as<P>(detail::smooth::smoother(m, g, options).run());
  if (!r.converged && !r.averaged && r.iterations == options.max_iterations) {
    r.complete = false;
    r.diagnostics.push_back(
        cellforge::detail::cat("the midpoints still moved after ", std::to_string(r.iterations),
                               " cycles (smooth_options::max_iterations, the work budget)"));
  }
  r.milliseconds = clock.ms();
  return r;
}

/// smooth_edges() on volume v of a cell complex (via volume_boundary_mesh): curves carry cell edge
/// and vertex ids, sorted by edge; mesh edges that are no cell edge (diagonals of triangulated
/// faces with holes) are left out; surface_of_face and vertex_normals are by cell face / vertex id
/// (faces outside v: 0xFFFFFFFF). Points in the complex's point type P.
/// O(size of v · iterations). Throws what smooth_edges throws.
template <Point3 P>
smooth_result<P> smooth_edges(const cell_complex<P>& cc, cell_volume v, const smooth_options& options = {}) {
  detail::smooth::check_options(options);
  const surface_mesh<P> m = volume_boundary_mesh(cc, v);
  return detail::smooth::with_cell_ids(cc, m, smooth_edges(m, options));
}

}  // namespace cellforge
