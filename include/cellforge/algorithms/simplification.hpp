// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Mesh simplification by edge collapses (seed 001 §IV.C; §II.B wants a light mesh for
/// collision detection): shortest edge first, or Garland–Heckbert quadric error metrics,
/// through the checked collapse of algorithms/edits.hpp, so topology is never changed.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/edits.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

/// Which edge is collapsed next, and where the kept vertex goes.
enum class simplify_cost : std::uint8_t {
  edge_length,  ///< shortest edge first; the kept vertex goes to the midpoint (or stays on the boundary)
  quadric,      ///< smallest quadric error first; the kept vertex goes to the error's minimum
};

/// Options of simplify(). At least one of the stopping rules usually applies; with none, the
/// mesh is simplified as far as the checks allow.
struct simplify_options {
  std::size_t target_faces = 0;  ///< stop at or below this many faces (0: no face target)
  simplify_cost cost = simplify_cost::quadric;
  double target_edge_length = 0;  ///< edge_length: collapse only edges shorter than this (0: no bound)
  double max_error = std::numeric_limits<double>::infinity();  ///< quadric: largest error allowed
  bool keep_boundary = false;   ///< boundary vertices are neither moved nor removed
  double boundary_weight = 10;  ///< quadric: weight of the planes that hold boundary edges in place
  /// Refuse a collapse that turns any surviving face's normal by more than this many degrees
  /// (in (0, 180]; 180 only refuses faces that would degenerate). Each face is compared with
  /// itself, so this also works on non-orientable meshes.
  double max_normal_angle = 60;
  int max_rounds = 4;           ///< passes over all edges; a pass retries what earlier ones refused
  bool collect_garbage = true;  ///< compact the mesh at the end (handles change)
};

// `seconds` warns where a user names it, not at every copy of the struct.
/// What simplify() did; milliseconds the call, diagnostics a missed face target and why.
struct simplify_result : stage_report {
  std::size_t faces_before = 0, faces_after = 0, vertices_before = 0, vertices_after = 0;
  std::size_t collapses = 0;
  std::array<std::size_t, num_edit_refusals> refused{};  ///< collapses refused, by reason
  double max_error = 0;  ///< quadric: largest error of a collapse done; edge_length: longest edge collapsed
  int rounds = 0;
  bool reached_target = false;  ///< faces_after <= target_faces (true when there is no face target)
  std::size_t refused_total() const noexcept {
    std::size_t n = 0;
    for (std::size_t r : refused) n += r;
    return n;
  }
  std::size_t refusals(edit_refusal why) const noexcept { return refused[static_cast<std::size_t>(why)]; }
};

namespace detail::simplification {

/// A symmetric 4x4 quadric x^T A x + 2 b.x + c, as 10 numbers.
struct quadric {
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0, b0 = 0, b1 = 0, b2 = 0, c = 0;

  // Adds w times the squared distance to the plane n.x + d = 0 (n unit).
  void add_plane(const glm::dvec3& n, double d, double w) {
    a00 += w * n.x * n.x;
    a01 += w * n.x * n.y;
    a02 += w * n.x * n.z;
    a11 += w * n.y * n.y;
    a12 += w * n.y * n.z;
    a22 += w * n.z * n.z;
    b0 += w * d * n.x;
    b1 += w * d * n.y;
    b2 += w * d * n.z;
    c += w * d * d;
  }
  quadric& operator+=(const quadric& q) {
    a00 += q.a00, a01 += q.a01, a02 += q.a02, a11 += q.a11, a12 += q.a12, a22 += q.a22;
    b0 += q.b0, b1 += q.b1, b2 += q.b2, c += q.c;
    return *this;
  }
  double operator()(const glm::dvec3& x) const {
    const double ax = a00 * x.x + a01 * x.y + a02 * x.z;
    const double ay = a01 * x.x + a11 * x.y + a12 * x.z;
    const double az = a02 * x.x + a12 * x.y + a22 * x.z;
    return std::max(0.0, x.x * ax + x.y * ay + x.z * az + 2 * (b0 * x.x + b1 * x.y + b2 * x.z) + c);
  }
  // The minimiser, when A is well conditioned (its eigenvalue product not tiny against
  // the cube of their mean); false for flat or crease-only neighbourhoods.
  bool minimum(glm::dvec3& x) const {
    const double c00 = a11 * a22 - a12 * a12, c01 = a02 * a12 - a01 * a22, c02 = a01 * a12 - a02 * a11;
    const double det = a00 * c00 + a01 * c01 + a02 * c02;
    const double trace = a00 + a11 + a22;
    if (!(trace > 0) || std::abs(det) <= 1e-9 * trace * trace * trace) return false;
    const double c11 = a00 * a22 - a02 * a02, c12 = a01 * a02 - a00 * a12, c22 = a00 * a11 - a01 * a01;
    x = -glm::dvec3(c00 * b0 + c01 * b1 + c02 * b2, c01 * b0 + c11 * b1 + c12 * b2,
                    c02 * b0 + c12 * b1 + c22 * b2) /
        det;
    return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z);
  }
};

// A collapse considered for an edge: remove one end, keep the other at `pos`.
struct candidate {
  bool ok = false;
  double cost = 0;
  glm::dvec3 pos{0.0};
  vertex_handle keep, remove;
};

template <class = void>
class basic_simplifier;
using simplifier = basic_simplifier<>;

template <class>
class basic_simplifier {
 public:
  basic_simplifier(halfedge_mesh& m, std::vector<glm::dvec3>& pos, const simplify_options& o)
      : m_(m), pos_(pos), o_(o), cos_max_(std::cos(o.max_normal_angle * 3.14159265358979323846 / 180.0)) {
    fixed_.assign(m.vertices_size(), 0);
    if (o.keep_boundary)
      for (vertex_handle v : m.vertices()) fixed_[v.idx()] = m.is_boundary(v) ? 1 : 0;
    if (o.cost == simplify_cost::quadric) init_quadrics();
  }

  candidate evaluate(edge_handle e) const {
    candidate c;
    const vertex_handle x = m_.vertex(e, 0), y = m_.vertex(e, 1);
    const bool fx = fixed_[x.idx()] != 0, fy = fixed_[y.idx()] != 0;
    if (fx && fy) return c;
    c.ok = true;
    const glm::dvec3 px = pos_[x.idx()], py = pos_[y.idx()];
    if (o_.cost == simplify_cost::edge_length) {
      c.cost = glm::dot(px - py, px - py);
      // A fixed end, or the only boundary end, stays put (the boundary must not shrink inwards).
      const bool bx = m_.is_boundary(x), by = m_.is_boundary(y);
      const bool keep_x = fx || (!fy && bx && !by), keep_y = fy || (!fx && by && !bx);
      c.keep = keep_x ? x : y;
      c.remove = keep_x ? y : x;
      c.pos = keep_x ? px : keep_y ? py : 0.5 * (px + py);
      return c;
    }
    c.keep = fx ? x : y;
    c.remove = fx ? y : x;
    quadric q = q_[x.idx()];
    q += q_[y.idx()];
    if (fx || fy) {
      c.pos = fx ? px : py;
    } else {
      glm::dvec3 best;
      const double len = glm::length(px - py);
      // The minimum is trusted only near the edge; beyond, it is an artefact of rounding.
      if (q.minimum(best) && glm::length(best - 0.5 * (px + py)) <= 2 * len) {
        c.pos = best;
      } else {
        c.pos = px;
        for (const glm::dvec3& t : {py, 0.5 * (px + py)})
          if (q(t) < q(c.pos)) c.pos = t;
      }
    }
    c.cost = q(c.pos);
    return c;
  }

  // True when no surviving face at the two ends turns by more than the allowed angle or
  // degenerates with the kept vertex at c.pos. O(d_keep + d_remove).
  bool normals_ok(const candidate& c) const {
    for (vertex_handle v : {c.remove, c.keep})
      for (face_handle f : m_.faces_around(v)) {
        std::array<glm::dvec3, 3> before, after;
        std::size_t i = 0;
        int moved = 0;
        for (vertex_handle w : m_.vertices_around(f)) {
          const bool is_end = w == c.remove || w == c.keep;
          moved += is_end ? 1 : 0;
          before[i] = pos_[w.idx()];
          after[i] = is_end ? c.pos : before[i];
          ++i;
        }
        if (moved == 2) continue;  // a face on the edge: it disappears
        const glm::dvec3 e1 = after[1] - after[0], e2 = after[2] - after[0];
        const glm::dvec3 n_new = glm::cross(e1, e2);
        const double l_new = glm::length(n_new);
        if (!(l_new > 1e-12 * glm::length(e1) * glm::length(e2))) return false;  // degenerate
        const glm::dvec3 n_old = glm::cross(before[1] - before[0], before[2] - before[0]);
        const double l_old = glm::length(n_old);
        if (l_old > 0 && glm::dot(n_old, n_new) < cos_max_ * l_old * l_new) return false;
      }
    return true;
  }

  // Merges the quadric of the removed vertex into the kept one.
  void merged(const candidate& c) {
    if (o_.cost == simplify_cost::quadric) q_[c.keep.idx()] += q_[c.remove.idx()];
    pos_[c.keep.idx()] = c.pos;
  }

 private:
  void init_quadrics() {
    q_.assign(m_.vertices_size(), {});
    for (face_handle f : m_.faces()) {
      const halfedge_handle h = m_.halfedge(f);
      const vertex_handle a = m_.tail(h), b = m_.head(h), c = m_.head(m_.next(h));
      glm::dvec3 n = glm::cross(pos_[b.idx()] - pos_[a.idx()], pos_[c.idx()] - pos_[a.idx()]);
      const double len = glm::length(n);
      if (!(len > 0)) continue;  // a degenerate face has no plane
      n /= len;
      const double d = -glm::dot(n, pos_[a.idx()]);
      for (vertex_handle v : {a, b, c}) q_[v.idx()].add_plane(n, d, 1.0);
    }
    if (!(o_.boundary_weight > 0)) return;
    // A plane through each boundary edge, perpendicular to its face, holds the edge in place.
    for (halfedge_handle b : m_.boundary_halfedges()) {
      const halfedge_handle t = halfedge_mesh::twin(b);
      const face_handle f = m_.face(t);
      const halfedge_handle h = m_.halfedge(f);
      const glm::dvec3 p0 = pos_[m_.tail(h).idx()], p1 = pos_[m_.head(h).idx()],
                       p2 = pos_[m_.head(m_.next(h)).idx()];
      const glm::dvec3 pa = pos_[m_.tail(t).idx()], pb = pos_[m_.head(t).idx()];
      glm::dvec3 n = glm::cross(glm::cross(p1 - p0, p2 - p0), pb - pa);
      const double len = glm::length(n);
      if (!(len > 0)) continue;
      n /= len;
      const double d = -glm::dot(n, pa);
      for (vertex_handle v : {m_.tail(t), m_.head(t)}) q_[v.idx()].add_plane(n, d, o_.boundary_weight);
    }
  }

  halfedge_mesh& m_;
  std::vector<glm::dvec3>& pos_;
  const simplify_options& o_;
  double cos_max_;
  std::vector<std::uint8_t> fixed_;
  std::vector<quadric> q_;
};

template <class = void>
void check_options(const simplify_options& o) {
  auto fail = [](const std::string& what) {
    throw error(error_category::invalid_input, cellforge::detail::cat("simplify: ", what));
  };
  if (o.cost != simplify_cost::edge_length && o.cost != simplify_cost::quadric) fail("unknown cost");
  if (!(o.target_edge_length >= 0) || !std::isfinite(o.target_edge_length))
    fail("target_edge_length must be a finite number >= 0");
  if (!(o.max_error >= 0)) fail("max_error must be >= 0 (infinity for no bound)");
  if (!(o.boundary_weight >= 0) || !std::isfinite(o.boundary_weight))
    fail("boundary_weight must be a finite number >= 0");
  if (!(o.max_normal_angle > 0 && o.max_normal_angle <= 180))
    fail("max_normal_angle must be in (0, 180] degrees");
  if (o.max_rounds < 1) fail("max_rounds must be at least 1");
  if (o.cost == simplify_cost::quadric && o.target_edge_length > 0)
    fail("target_edge_length applies to cost = edge_length; bound a quadric simplification with max_error");
  if (o.cost == simplify_cost::edge_length && std::isfinite(o.max_error))
    fail("max_error applies to cost = quadric; bound an edge-length simplification with target_edge_length");
}

}  // namespace detail::simplification

/// Collapses edges of a triangle mesh, cheapest first, until it has at most
/// `options.target_faces` faces or no allowed collapse is under the bound. Every collapse
/// passes the link-condition checks of collapse_halfedge, so connectivity, genus, boundary
/// loops and orientability are kept; positions move as the cost says.
/// O(n log n) per round (a heap with lazy invalidation by per-edge stamps). Throws
/// error(invalid_input) for a non-triangle face, a non-finite position or bad options.
template <Point3 P>
simplify_result simplify(surface_mesh<P>& m, const simplify_options& options = {}) {
  namespace ds = detail::simplification;
  const detail::stopwatch t0;
  ds::check_options(options);
  auto pts = m.positions();
  for (face_handle f : m.faces())
    if (!detail::edits::is_triangle(m, f))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("simplify: face ", std::to_string(f.idx()),
                                         " is not a triangle; triangulate the mesh first"));
  std::vector<glm::dvec3> pos(m.vertices_size(), glm::dvec3(0.0));
  for (vertex_handle v : m.vertices()) {
    pos[v.idx()] = to_dvec3(pts[v]);
    if (!std::isfinite(pos[v.idx()].x) || !std::isfinite(pos[v.idx()].y) || !std::isfinite(pos[v.idx()].z))
      throw error(
          error_category::invalid_input,
          cellforge::detail::cat("simplify: vertex ", std::to_string(v.idx()), " has a non-finite position"));
  }

  simplify_result result;
  result.faces_before = m.num_faces();
  result.vertices_before = m.num_vertices();
  ds::simplifier s(m, pos, options);

  struct entry {
    double cost;
    std::uint32_t edge, stamp;
    bool operator>(const entry& o) const noexcept {
      return cost > o.cost || (cost == o.cost && edge > o.edge);
    }
  };
  // A min-heap by (cost, edge) through push_heap/pop_heap: what std::priority_queue with
  // std::greater does, without <queue> and <functional> in every file that includes this.
  std::vector<entry> heap;
  const auto later = [](const entry& a, const entry& b) { return a > b; };
  std::vector<std::uint32_t> stamp;
  const double length_bound = options.target_edge_length * options.target_edge_length;
  auto push = [&](edge_handle e) {
    if (stamp.size() <= e.idx()) stamp.resize(m.edges_size() + m.edges_size() / 2 + 16, 0);
    const std::uint32_t st = ++stamp[e.idx()];  // older entries of e are stale now
    const ds::candidate c = s.evaluate(e);
    if (c.ok) {
      heap.push_back({c.cost, e.idx(), st});
      std::push_heap(heap.begin(), heap.end(), later);
    }
  };
  auto done = [&] { return options.target_faces > 0 && m.num_faces() <= options.target_faces; };

  for (int round = 0; round < options.max_rounds && !done(); ++round) {
    ++result.rounds;
    heap.clear();
    for (edge_handle e : m.edges()) push(e);
    std::size_t collapses = 0;
    while (!heap.empty() && !done()) {
      std::pop_heap(heap.begin(), heap.end(), later);
      const entry top = heap.back();
      heap.pop_back();
      const edge_handle e(top.edge);
      if (m.is_removed(e) || stamp[e.idx()] != top.stamp) continue;
      if (options.cost == simplify_cost::edge_length && length_bound > 0 && top.cost >= length_bound) break;
      if (options.cost == simplify_cost::quadric && top.cost > options.max_error) break;
      const ds::candidate c = s.evaluate(e);
      std::vector<face_handle> faces;
      const edit_refusal why = detail::edits::check_collapse(m, e, c.remove, c.keep, faces);
      if (why != edit_refusal::none) {
        ++result.refused[static_cast<std::size_t>(why)];
        continue;
      }
      if (!s.normals_ok(c)) {
        ++result.refused[static_cast<std::size_t>(edit_refusal::normal_flip)];
        continue;
      }
      detail::edits::do_collapse(m, c.remove, c.keep, faces);
      s.merged(c);
      pts[c.keep] = from_dvec3<P>(c.pos);
      result.max_error =
          std::max(result.max_error, options.cost == simplify_cost::quadric ? c.cost : std::sqrt(c.cost));
      ++result.collapses;
      ++collapses;
      for (edge_handle x : m.edges_around(c.keep)) push(x);
    }
    if (collapses == 0) break;
  }

  if (options.collect_garbage) m.garbage_collection();
  result.faces_after = m.num_faces();
  result.vertices_after = m.num_vertices();
  result.reached_target = options.target_faces == 0 || m.num_faces() <= options.target_faces;
  if (!result.reached_target) {
    // Which refusal stopped most collapses: what a caller would change (the angle, fixed vertices).
    std::size_t most = 0;
    for (std::size_t k = 1; k < result.refused.size(); ++k)
      if (result.refused[k] > result.refused[most]) most = k;
    result.diagnostics.push_back(cellforge::detail::cat(
        "simplify: ", std::to_string(result.faces_after), " faces left, above the target of ",
        std::to_string(options.target_faces), " after ", std::to_string(result.rounds), " rounds; ",
        std::to_string(result.refused_total()), " collapses refused",
        result.refused_total() == 0
            ? std::string()
            : cellforge::detail::cat(", most because ",
                                     std::string(to_string(static_cast<edit_refusal>(most))))));
  }
  result.milliseconds = t0.ms();
  return result;
}

}  // namespace cellforge
