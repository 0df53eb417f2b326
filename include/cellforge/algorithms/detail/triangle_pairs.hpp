// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The exact engine of algorithms/self_intersections.hpp, shared with cells/certify.hpp: the
/// triangle-pair predicates (closed triangles, sharing decided by vertex id, every decision the
/// sign of orient3d / orient2d), the triangulation of one polygon for those tests, and the
/// uniform grid that lists each pair of overlapping boxes once under a work budget. The rules
/// (what is tested, when two triangles intersect, the grid's cost) are in self_intersections.hpp.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory_resource>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/ear_clipping.hpp"
#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/predicates.hpp"

namespace cellforge::detail::self_intersect {

using vec = glm::dvec3;

/// orient2d of a, b, c projected on the coordinate axes (u, w). O(1).
template <class = void>
int orient_uw(const vec& a, const vec& b, const vec& c, int u, int w) noexcept {
  return orient2d(a[u], a[w], b[u], b[w], c[u], c[w]);
}

/// The coordinate axes ordered by the size of triangle abc's rounded normal component,
/// largest first: the projection that drops the first keeps the most of its area. O(1).
template <class = void>
std::array<int, 3> axes_by_normal(const vec& a, const vec& b, const vec& c) noexcept {
  const vec e = b - a, f = c - a;
  std::array<double, 3> n = {std::fabs(e.y * f.z - e.z * f.y), std::fabs(e.z * f.x - e.x * f.z),
                             std::fabs(e.x * f.y - e.y * f.x)};
  for (double& x : n)
    if (std::isnan(x)) x = 0;            // overflow: any order, the exact checks decide
  std::array<int, 3> order = {0, 1, 2};  // a stable three-element sort, largest first
  auto at = [&](int i) { return n[static_cast<std::size_t>(i)]; };
  if (at(order[1]) > at(order[0])) std::swap(order[0], order[1]);
  if (at(order[2]) > at(order[1])) std::swap(order[1], order[2]);
  if (at(order[1]) > at(order[0])) std::swap(order[0], order[1]);
  return order;
}

/// The coordinate axis to drop so that triangle abc keeps a non-zero area in the other two
/// (the dominant normal component first, then exactly checked); -1 when abc is degenerate.
template <class = void>
int drop_axis(const vec& a, const vec& b, const vec& c) noexcept {
  for (const int k : axes_by_normal(a, b, c))
    if (orient_uw(a, b, c, (k + 1) % 3, (k + 2) % 3) != 0) return k;
  return -1;
}

/// orient3d's floating-point filter alone: ±1 when it decides, 0 when only the exact
/// evaluation could (an exactly coplanar configuration always gets there). O(1).
template <class = void>
int orient3d_filtered(const vec& a, const vec& b, const vec& c, const vec& d) noexcept {
  double value = 0;
  return cellforge::detail::orient3d_filter(cellforge::detail::prepare_orient3d(a, b, c), d, value);
}

/// The same against a plane prepared once for several queries. O(1).
template <class = void>
int orient3d_filtered(const cellforge::detail::orient3d_plane& plane, const vec& d) noexcept {
  double value = 0;
  return cellforge::detail::orient3d_filter(plane, d, value);
}

/// orient3d(a, b, c, d) given its filtered sign: the exact evaluation only where the
/// filter could not decide, so it equals orient3d. O(1).
template <class = void>
int orient3d_given(int filtered, const vec& a, const vec& b, const vec& c, const vec& d) noexcept {
  return filtered != 0 ? filtered : cellforge::detail::orient3d_exact(a, b, c, d);
}

// Cheap exact rejections for the configurations whose orient3d is exactly zero (flat
// regions of axis-aligned meshes), where the exact evaluation is dear. Each rests on
// π(T1 ∩ T2) ⊆ π(T1) ∩ π(T2) for a coordinate projection π, decided by exact orient2d.

/// True when the projections on (u, w) of the closed triangles a and b are disjoint: an
/// edge line of one has the other strictly outside. Then a and b are disjoint. O(1).
template <class = void>
bool projections_apart(const std::array<vec, 3>& a, const std::array<vec, 3>& b, int u, int w) noexcept {
  for (const auto* t : {&a, &b}) {
    const auto& x = *t;
    const auto& y = t == &a ? b : a;
    const int s = orient_uw(x[0], x[1], x[2], u, w);
    if (s == 0) continue;
    for (std::size_t i = 0; i < 3; ++i) {
      const vec &p = x[i], &q = x[(i + 1) % 3];
      if (orient_uw(p, q, y[0], u, w) == -s && orient_uw(p, q, y[1], u, w) == -s &&
          orient_uw(p, q, y[2], u, w) == -s)
        return true;
    }
  }
  return false;
}

/// True when x, collinear with v and a in the projection on (u, w), lies on the ray from v
/// away from a (exact coordinate comparisons). O(1).
template <class = void>
bool opposite_ray(const vec& v, const vec& a, const vec& x, int u, int w) noexcept {
  const int k = a[u] != v[u] ? u : w;
  return a[k] > v[k] ? x[k] < v[k] : x[k] > v[k];
}

/// T1 = (v, a, b), T2 = (v, c, d) projected on (u, w), T1 not collapsing: true when the
/// line through v and a (or v and b) has T1 on one closed side and T2 on the other, T2
/// touching it only on the ray away from a (b). Then π(T1) ∩ π(T2) = {π(v)}, and as π is
/// one-to-one on T1's plane, T1 ∩ T2 = {v}. O(1).
template <class = void>
bool apart_at_vertex(const vec& v, const vec& a, const vec& b, const vec& c, const vec& d, int u,
                     int w) noexcept {
  const int s = orient_uw(v, a, b, u, w);
  if (s == 0) return false;
  auto beyond = [&](const vec& e, int side) {
    for (const vec* x : {&c, &d}) {
      const int o = orient_uw(v, e, *x, u, w);
      if (o == side || (o == 0 && !opposite_ray(v, e, *x, u, w))) return false;
    }
    return true;
  };
  return beyond(a, s) || beyond(b, -s);
}

/// A triangle's corners and the projection in which it is not degenerate.
struct tri {
  std::array<vec, 3> p;
  int u = 0, w = 1;  ///< kept axes of the projection
};

/// True when x (in the triangle's plane) lies in the closed triangle. O(1).
template <class = void>
bool point_in(const tri& t, const vec& x) noexcept {
  const int s0 = orient_uw(t.p[0], t.p[1], x, t.u, t.w), s1 = orient_uw(t.p[1], t.p[2], x, t.u, t.w),
            s2 = orient_uw(t.p[2], t.p[0], x, t.u, t.w);
  return !((s0 > 0 || s1 > 0 || s2 > 0) && (s0 < 0 || s1 < 0 || s2 < 0));
}

/// True when the closed segments pq and rs (in one plane, projected on (u, w)) meet. O(1).
template <class = void>
bool segments_meet(const vec& p, const vec& q, const vec& r, const vec& s, int u, int w) noexcept {
  return cellforge::detail::segments_meet(glm::dvec2(p[u], p[w]), glm::dvec2(q[u], q[w]),
                                          glm::dvec2(r[u], r[w]), glm::dvec2(s[u], s[w]));
}

/// True when segment pq meets the closed triangle t; sp, sq are orient3d(t, p) and
/// orient3d(t, q). O(1).
template <class = void>
bool segment_meets(const vec& p, const vec& q, int sp, int sq, const tri& t) noexcept {
  if (sp * sq > 0) return false;
  if (sp == 0 && sq == 0)  // in the plane: inside, or across an edge
    return point_in(t, p) || point_in(t, q) || segments_meet(p, q, t.p[0], t.p[1], t.u, t.w) ||
           segments_meet(p, q, t.p[1], t.p[2], t.u, t.w) || segments_meet(p, q, t.p[2], t.p[0], t.u, t.w);
  // pq meets the plane in one point x; orient3d(p, q, a, b) has the sign of x against the
  // line ab within the plane times a constant, so x is inside when no two signs differ.
  const int s0 = orient3d(p, q, t.p[0], t.p[1]), s1 = orient3d(p, q, t.p[1], t.p[2]),
            s2 = orient3d(p, q, t.p[2], t.p[0]);
  return !((s0 > 0 || s1 > 0 || s2 > 0) && (s0 < 0 || s1 < 0 || s2 < 0));
}

/// True when x ≠ v, in the plane of t = (v, c, d), lies in t's closed corner at v: the ray
/// from v through x enters t. O(1).
template <class = void>
bool in_corner(const tri& t, const vec& x) noexcept {
  const int s = orient_uw(t.p[0], t.p[1], t.p[2], t.u, t.w);
  return orient_uw(t.p[0], t.p[1], x, t.u, t.w) * s >= 0 && orient_uw(t.p[0], x, t.p[2], t.u, t.w) * s >= 0;
}

/// Builds the tri of corners a, b, c (not degenerate). O(1).
template <class = void>
tri make_tri(const vec& a, const vec& b, const vec& c) noexcept {
  const int k = drop_axis(a, b, c);
  tri t;
  t.p = {a, b, c};
  t.u = (k + 1) % 3;
  t.w = (k + 2) % 3;
  return t;
}

/// Closed triangles a and b (both non-degenerate) with no shared vertex: do they meet? O(1).
template <class = void>
bool disjoint_pair_meets(const std::array<vec, 3>& a, const std::array<vec, 3>& b) noexcept {
  std::array<int, 3> sa{}, sb{};  // sides of a's corners against b's plane, and of b's against a's
  const auto plane_b = cellforge::detail::prepare_orient3d(b[0], b[1], b[2]);
  for (std::size_t i = 0; i < 3; ++i) sa[i] = orient3d_filtered(plane_b, a[i]);
  if (sa[0] == sa[1] && sa[1] == sa[2] && sa[0] != 0) return false;
  if (sa[0] == 0 || sa[1] == 0 || sa[2] == 0) {  // the exact evaluation is needed: try cheaper first
    const int k = axes_by_normal(b[0], b[1], b[2])[0];
    if (projections_apart(a, b, (k + 1) % 3, (k + 2) % 3)) return false;
  }
  for (std::size_t i = 0; i < 3; ++i) sa[i] = orient3d_given(sa[i], b[0], b[1], b[2], a[i]);
  if (sa[0] == sa[1] && sa[1] == sa[2] && sa[0] != 0) return false;
  const auto plane_a = cellforge::detail::prepare_orient3d(a[0], a[1], a[2]);
  for (std::size_t i = 0; i < 3; ++i)
    sb[i] = orient3d_given(orient3d_filtered(plane_a, b[i]), a[0], a[1], a[2], b[i]);
  if (sb[0] == sb[1] && sb[1] == sb[2] && sb[0] != 0) return false;
  const tri ta = make_tri(a[0], a[1], a[2]), tb = make_tri(b[0], b[1], b[2]);
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t j = (i + 1) % 3;
    if (segment_meets(a[i], a[j], sa[i], sa[j], tb)) return true;
    if (segment_meets(b[i], b[j], sb[i], sb[j], ta)) return true;
  }
  return false;
}

/// T1 = (v, a, b) and T2 = (v, c, d) share exactly the vertex v: do they meet elsewhere? O(1).
template <class = void>
bool vertex_pair_meets(const vec& v, const vec& a, const vec& b, const vec& c, const vec& d) noexcept {
  const auto plane2 = cellforge::detail::prepare_orient3d(v, c, d);
  const int fa = orient3d_filtered(plane2, a), fb = orient3d_filtered(plane2, b);
  if (fa * fb > 0) return false;
  const auto plane1 = cellforge::detail::prepare_orient3d(v, a, b);
  const int fc = orient3d_filtered(plane1, c), fd = orient3d_filtered(plane1, d);
  if (fc * fd > 0) return false;  // T2 meets T1's plane only at v
  const int k = axes_by_normal(v, a, b)[0];
  if (apart_at_vertex(v, a, b, c, d, (k + 1) % 3, (k + 2) % 3)) return false;
  const int sa = orient3d_given(fa, v, c, d, a), sb = orient3d_given(fb, v, c, d, b);
  if (sa * sb > 0) return false;  // T1 meets T2's plane only at v
  const int sc = orient3d_given(fc, v, a, b, c), sd = orient3d_given(fd, v, a, b, d);
  if (sc * sd > 0) return false;
  const tri t1 = make_tri(v, a, b), t2 = make_tri(v, c, d);
  if (segment_meets(a, b, sa, sb, t2) || segment_meets(c, d, sc, sd, t1)) return true;
  return (sa == 0 && in_corner(t2, a)) || (sb == 0 && in_corner(t2, b)) || (sc == 0 && in_corner(t1, c)) ||
         (sd == 0 && in_corner(t1, d));
}

/// T1 = (u, v, a) and T2 = (u, v, b) share the edge uv: do they overlap beyond it? O(1).
template <class = void>
bool edge_pair_meets(const vec& u, const vec& v, const vec& a, const vec& b) noexcept {
  if (orient3d_filtered(u, v, a, b) != 0) return false;
  // Strictly opposite sides of uv in some projection: no overlap whether coplanar or not.
  const int k = axes_by_normal(u, v, a)[0], ku = (k + 1) % 3, kw = (k + 2) % 3;
  if (orient_uw(u, v, a, ku, kw) * orient_uw(u, v, b, ku, kw) < 0) return false;
  if (orient3d(u, v, a, b) != 0) return false;
  const tri t = make_tri(u, v, a);
  return orient_uw(u, v, a, t.u, t.w) == orient_uw(u, v, b, t.u, t.w);
}

/// The exact pair test of self_intersections on two non-degenerate triangles: corners p, q
/// and their vertex ids (equal ids are one shared vertex). O(1).
template <class = void>
bool pair_intersects(const std::array<vec, 3>& p, const std::array<std::uint32_t, 3>& ip,
                     const std::array<vec, 3>& q, const std::array<std::uint32_t, 3>& iq) noexcept {
  int shared = 0;
  std::array<int, 3> match = {-1, -1, -1};  // match[i]: corner of q with p's id i
  for (std::size_t i = 0; i < 3; ++i) {
    const std::uint32_t id = ip[i];
    const int j = id == iq[0] ? 0 : id == iq[1] ? 1 : id == iq[2] ? 2 : -1;
    match[i] = j;
    shared += j >= 0 ? 1 : 0;
  }
  if (shared == 0) return disjoint_pair_meets(p, q);
  if (shared >= 3) return true;
  if (shared == 1) {
    std::size_t i = 0;
    while (match[i] < 0) ++i;
    const auto j = static_cast<std::size_t>(match[i]);
    return vertex_pair_meets(p[i], p[(i + 1) % 3], p[(i + 2) % 3], q[(j + 1) % 3], q[(j + 2) % 3]);
  }
  std::size_t free_p = 0;  // the corner of p not shared, and of q
  while (match[free_p] >= 0) ++free_p;
  std::size_t free_q = 0;
  while (free_q == static_cast<std::size_t>(match[(free_p + 1) % 3]) ||
         free_q == static_cast<std::size_t>(match[(free_p + 2) % 3]))
    ++free_q;
  return edge_pair_meets(p[(free_p + 1) % 3], p[(free_p + 2) % 3], p[free_p], q[free_q]);
}

/// True when the triangle has zero area or a non-finite coordinate (exact). O(1).
template <class = void>
bool degenerate(const vec& a, const vec& b, const vec& c) noexcept {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(a[k]) || !std::isfinite(b[k]) || !std::isfinite(c[k])) return true;
  return collinear(a, b, c);
}

/// True when polygon p is exactly planar and strictly convex (every corner strictly on one
/// side of every edge, in a projection where its first three corners do not collapse).
/// O(|p|²); polygons of more than 16 corners are left to ear clipping.
template <class = void>
bool convex_planar(std::span<const vec> p) noexcept {
  const std::size_t n = p.size();
  if (n > 16) return false;
  const int k = drop_axis(p[0], p[1], p[2]);
  if (k < 0) return false;
  for (std::size_t j = 3; j < n; ++j)  // first: most polygons off their plane fail at one test
    if (orient3d(p[0], p[1], p[2], p[j]) != 0) return false;
  const int u = (k + 1) % 3, w = (k + 2) % 3;
  const int s = orient_uw(p[0], p[1], p[2], u, w);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      if (j != i && j != (i + 1) % n && orient_uw(p[i], p[(i + 1) % n], p[j], u, w) != s) return false;
  return true;
}

/// Ear clipping's triangles (ears::clip_polygon, no planarity limit, non-simple allowed) for a
/// polygon of 4 to 16 distinct consecutive corners whose projection in clipping's plane is
/// strictly convex, without the clipper's set-up: it then finds an ear at every vertex and
/// clips them in a fixed order, which this follows (from corner 0, on past each ear's next
/// corner). False, adding nothing, for any other polygon, or near a sliver (the clipper defers
/// those). Ear clipping's own answer in every case it takes (tests/test_self_intersections.cpp).
/// O(n).
template <class Add>
bool clip_convex_projection(std::span<const std::uint32_t> ids, std::span<const vec> p, Add&& add) {
  const std::size_t n = p.size();
  if (n < 4 || n > 16) return false;
  vec lo = p[0], hi = p[0], centroid(0.0);  // as clip_polygon computes them
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z)) return false;
    lo = glm::min(lo, p[i]);
    hi = glm::max(hi, p[i]);
    centroid += p[i];
  }
  centroid /= static_cast<double>(n);
  const vec newell = ears::newell_normal(p, centroid);
  const double diagonal = glm::length(hi - lo), length = glm::length(newell);
  if (!(length > 1e-14 * diagonal * diagonal)) return false;
  const int k = ears::dominant_axis(newell);
  const int u = (k + 1) % 3, w = (k + 2) % 3, sense = newell[k] > 0 ? 1 : -1;
  std::array<std::uint8_t, 16> prev{}, next{};
  for (std::size_t i = 0; i < n; ++i) {
    if (p[i] == p[(i + n - 1) % n]) return false;  // a repeat: the clipper sets it aside
    prev[i] = static_cast<std::uint8_t>((i + n - 1) % n), next[i] = static_cast<std::uint8_t>((i + 1) % n);
  }
  const auto convex = [&](std::size_t i) {
    return sense * orient_uw(p[prev[i]], p[i], p[next[i]], u, w) > 0;
  };
  for (std::size_t i = 0; i < n; ++i)
    if (!convex(i)) return false;
  std::array<std::array<std::uint8_t, 3>, 14> out{};
  std::size_t i = 0, count = 0;
  for (std::size_t remaining = n; remaining > 3; --remaining) {
    const std::size_t a = prev[i], c = next[i];
    const double ux = p[i][u] - p[a][u], uy = p[i][w] - p[a][w], vx = p[c][u] - p[a][u],
                 vy = p[c][w] - p[a][w];
    const double wx = p[c][u] - p[i][u], wy = p[c][w] - p[i][w];
    const double longest = std::max({ux * ux + uy * uy, vx * vx + vy * vy, wx * wx + wy * wy});
    if (!(std::fabs(ux * vy - uy * vx) > 2e-12 * longest)) return false;  // thin or close: the clipper's call
    out[count++] = {prev[i], static_cast<std::uint8_t>(i), next[i]};
    next[a] = static_cast<std::uint8_t>(c), prev[c] = static_cast<std::uint8_t>(a);
    if (!convex(a) || !convex(c)) return false;  // only a non-simple polygon gets here
    i = next[c];
  }
  out[count++] = {prev[i], static_cast<std::uint8_t>(i), next[i]};
  for (std::size_t t = 0; t < count; ++t) add(ids[out[t][0]], ids[out[t][1]], ids[out[t][2]]);
  return true;
}

/// For a quad that ear clipping would triangulate: true when its projection in ear
/// clipping's plane (ears::newell_normal and ears::dominant_axis, as clip_polygon projects)
/// is strictly convex. Ear clipping then cuts the ear at corner 0 first,
/// giving (3, 0, 1) and (1, 2, 3); this answers that without its set-up. O(1).
template <class = void>
bool convex_projected_quad(std::span<const vec> p) noexcept {
  vec centroid(0.0);
  for (std::size_t i = 0; i < 4; ++i) {
    if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z)) return false;
    centroid += p[i];
  }
  centroid /= 4.0;
  // The fixed-size Newell sums (the general one's loop was a tenth of the check by pieces' set-up).
  const vec newell = ears::newell_normal(p.first<4>(), centroid);
  const int k = ears::dominant_axis(newell);
  if (!(std::fabs(newell[k]) > 0)) return false;
  const int u = (k + 1) % 3, w = (k + 2) % 3, sense = newell[k] > 0 ? 1 : -1;
  // The four turns' orient2d filters without branches (their signs vary from quad to quad);
  // the exact orient2d only when a filter cannot decide.
  std::array<double, 4> x{}, y{};
  for (std::size_t i = 0; i < 4; ++i) x[i] = p[i][u], y[i] = p[i][w];
  bool all = true, decided = true;
  for (std::size_t i = 0; i < 4; ++i) {
    const std::size_t j = (i + 1) & 3, l = (i + 2) & 3;
    const double left = (x[i] - x[l]) * (y[j] - y[l]), right = (y[i] - y[l]) * (x[j] - x[l]);
    const double det = sense > 0 ? left - right : right - left;
    const double bound = cellforge::detail::orient2d_bound * (std::fabs(left) + std::fabs(right)) +
                         cellforge::detail::underflow_guard;
    all &= det > bound;
    decided &= det > bound || det < -bound;
  }
  if (all || decided) return all;
  for (std::size_t i = 0; i < 4; ++i)
    if (orient_uw(p[i], p[(i + 1) % 4], p[(i + 2) % 4], u, w) != sense) return false;
  return true;
}

/// The grid cell coordinate of x along one axis. O(1).
template <class = void>
std::uint32_t cell_of(double x, double origin, double inv_side, std::uint32_t cells) noexcept {
  const double c = std::floor((x - origin) * inv_side);
  if (!(c > 0)) return 0;
  if (c >= static_cast<double>(cells - 1)) return cells - 1;
  return static_cast<std::uint32_t>(c);
}

/// Sorts 64-bit keys by their high 32 bits, stably (keys equal there keep their order):
/// least-significant-digit radix sort, 11 bits a pass, skipping digits that never vary.
/// O(n · passes).
template <class A>
void radix_sort_high(std::vector<std::uint64_t, A>& keys) {
  if (keys.size() < 1024) {  // the passes' set-up costs more than a comparison sort
    std::stable_sort(keys.begin(), keys.end(),
                     [](std::uint64_t a, std::uint64_t b) { return a >> 32 < b >> 32; });
    return;
  }
  std::vector<std::uint64_t, A> tmp(keys.size(), keys.get_allocator());
  std::array<std::size_t, 2048> count{};
  std::uint64_t all_or = 0, all_and = ~std::uint64_t{0};
  for (const std::uint64_t k : keys) all_or |= k, all_and &= k;
  for (unsigned shift = 32; shift < 64; shift += 11) {
    if ((((all_or ^ all_and) >> shift) & 0x7FFu) == 0) continue;  // the digit never varies
    count.fill(0);
    for (const std::uint64_t k : keys) ++count[(k >> shift) & 0x7FFu];
    std::size_t sum = 0;
    for (std::size_t& c : count) {
      const std::size_t here = c;
      c = sum;
      sum += here;
    }
    for (const std::uint64_t k : keys) tmp[count[(k >> shift) & 0x7FFu]++] = k;
    keys.swap(tmp);
  }
}

/// Sorts and deduplicates the face-pair keys. O(n log n).
template <class = void>
void compact(std::vector<std::uint64_t>& keys) {
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
}

/// Triangulates one polygon (vertex ids, corners) for the exact tests, as the file comment of
/// self_intersections.hpp says: a strictly convex projected quad as (3, 0, 1) and (1, 2, 3); an
/// exactly planar strictly convex polygon as the fan from its first corner; anything else as ear
/// clipping (no planarity limit, non-simple allowed) makes it, the fan when ear clipping refuses.
/// add(a, b, c) receives vertex ids; returns true when the polygon counts as ear clipped (not both
/// planar and strictly convex). O(n) for convex polygons, ear clipping's cost otherwise.
template <class Add>
bool triangulate_polygon(std::span<const std::uint32_t> ids, std::span<const vec> corners, Add&& add) {
  const std::size_t n = ids.size();
  if (n < 3) return false;
  // A quad whose projection is strictly convex: off its plane (a rounding error is
  // enough) ear clipping would cut it into these two triangles; in its plane they cover
  // what the fan covers, which gives the same answers. No exact planarity test needed.
  if (n == 4 && convex_projected_quad(corners)) {
    add(ids[3], ids[0], ids[1]);
    add(ids[1], ids[2], ids[3]);
    return orient3d_filtered(corners[0], corners[1], corners[2], corners[3]) != 0;
  }
  bool fan = n == 3 || convex_planar(corners);
  const bool clipped = !fan;
  if (!fan && clip_convex_projection(ids, corners, add)) return true;
  if (!fan) {
    ear_clip_options clip;
    clip.planarity_tolerance = std::numeric_limits<double>::infinity();
    clip.allow_non_simple = true;
    ear_clip_report report;
    try {
      for (const index_triangle& t : ears::clip_polygon(corners, clip, report))
        add(ids[t[0]], ids[t[1]], ids[t[2]]);
    } catch (const error&) {
      fan = true;  // no area, or a non-finite corner: its fan triangles are degenerate
    }
  }
  if (fan)
    for (std::size_t i = 1; i + 1 < n; ++i) add(ids[0], ids[i], ids[i + 1]);
  return clipped;
}

/// True when the fan of triangles (v, ring[i], ring[i + 1]) (indices mod k) projects one-to-one
/// on some coordinate plane: every projected triangle turns the same strict way (exact orient2d)
/// and the ring winds exactly once around v (it crosses the ray from v along +u once, counted
/// exactly by coordinate comparisons). Then two triangles of the fan meet only in v or, when
/// neighbours, in their shared edge. O(k).
template <class = void>
bool fan_projects_injectively(const vec& v, std::span<const vec> ring) noexcept {
  const std::size_t k = ring.size();
  if (k < 3) return false;
  vec normal(0.0);  // which axis to drop first: the largest component of the fan's normal
  for (std::size_t i = 0; i < k; ++i) {
    const vec e = ring[i] - v, f = ring[(i + 1) % k] - v;
    normal += vec(e.y * f.z - e.z * f.y, e.z * f.x - e.x * f.z, e.x * f.y - e.y * f.x);
  }
  std::array<int, 3> order = {0, 1, 2};
  std::array<double, 3> size = {std::fabs(normal.x), std::fabs(normal.y), std::fabs(normal.z)};
  for (double& x : size)
    if (std::isnan(x)) x = 0;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return size[static_cast<std::size_t>(a)] > size[static_cast<std::size_t>(b)];
  });
  for (const int drop : order) {
    const int u = (drop + 1) % 3, w = (drop + 2) % 3;
    const int s = orient_uw(v, ring[0], ring[1], u, w);
    if (s == 0) continue;
    bool same = true;
    for (std::size_t i = 1; i < k && same; ++i) same = orient_uw(v, ring[i], ring[(i + 1) % k], u, w) == s;
    if (!same) continue;
    // Upper half: angle in [0, π) from +u; each step turns by less than π the way s says, so the
    // ring passes angle 0 exactly at the steps from the lower half to the upper (s > 0), or back.
    auto upper = [&](const vec& x) { return x[w] > v[w] || (x[w] == v[w] && x[u] > v[u]); };
    std::size_t crossings = 0;
    for (std::size_t i = 0; i < k; ++i) {
      const bool from = upper(ring[i]), to = upper(ring[(i + 1) % k]);
      if (s > 0 ? (!from && to) : (from && !to)) ++crossings;
    }
    if (crossings == 1) return true;
  }
  return false;
}

/// For each vertex (ids below `vertices`), whether its star in the triangle list `tris`
/// (vertex ids of non-degenerate triangles) is one closed, consistently oriented fan that
/// projects one-to-one on a coordinate plane (fan_projects_injectively). Two triangles that
/// share such a vertex meet only in what they share, so their pair needs no geometric test.
/// Stars of more than 64 triangles are not examined. O(Σ star size²) ≤ O(64 · triangles).
template <class Tri>
std::vector<std::uint8_t> injective_stars(std::span<const Tri> tris, std::span<const vec> pos,
                                          std::size_t vertices) {
  std::vector<std::uint32_t> offset(vertices + 1, 0);
  for (const Tri& t : tris)
    for (const std::uint32_t x : t.v) ++offset[x + 1];
  for (std::size_t i = 0; i < vertices; ++i) offset[i + 1] += offset[i];
  // For each vertex: (next, previous) corners of each triangle around it, in the triangle's order.
  std::vector<std::array<std::uint32_t, 2>> around(offset[vertices]);
  {
    std::vector<std::uint32_t> fill(offset.begin(), offset.end() - 1);
    for (const Tri& t : tris)
      for (std::size_t i = 0; i < 3; ++i) around[fill[t.v[i]]++] = {t.v[(i + 1) % 3], t.v[(i + 2) % 3]};
  }
  std::vector<std::uint8_t> good(vertices, 0);
  std::vector<vec> ring;
  for (std::size_t x = 0; x < vertices; ++x) {
    const std::span<const std::array<std::uint32_t, 2>> star(around.data() + offset[x],
                                                             offset[x + 1] - offset[x]);
    const std::size_t k = star.size();
    if (k < 3 || k > 64) continue;
    // One cycle: from triangle 0, the triangle whose first corner is this one's second, k times.
    ring.clear();
    std::size_t at = 0;
    bool cycle = true;
    for (std::size_t step = 0; step < k && cycle; ++step) {
      ring.push_back(pos[star[at][0]]);
      std::size_t next = k, matches = 0;
      for (std::size_t j = 0; j < k; ++j)
        if (star[j][0] == star[at][1]) next = j, ++matches;
      cycle = matches == 1 && (next == 0) == (step + 1 == k);
      at = next;
    }
    if (!cycle) continue;
    good[x] = fan_projects_injectively(pos[x], std::span<const vec>(ring)) ? 1 : 0;
  }
  return good;
}

/// What for_each_box_pair did.
struct box_pair_count {
  std::size_t candidate_pairs = 0;  ///< pairs of boxes a grid cell examines (the budget counts these)
  std::size_t visited = 0;          ///< overlapping pairs handed to the visitor
  bool complete = true;             ///< false when the budget stopped the search
};

/// Calls visit(i, j) exactly once for every pair of closed boxes (min x, y, z, max x, y, z) that
/// overlap, i and j in one uniform grid cell: the cell side is the median of the boxes' largest
/// extents times `side_scale`, grown until no more than 8n + 2^16 cell entries are needed, and each pair is
/// visited in the cell holding the low corner of the boxes' intersection (the only pairs a cell counts as
/// candidates; the order of i and j is not fixed). Stops, complete = false, before
/// a cell that would take the candidate pairs past `budget` (0: no limit). visit may return
/// false to stop too. Its arrays come from `scratch`. O(n log n + candidate pairs).
template <class Visit>
box_pair_count for_each_box_pair(std::span<const std::array<double, 6>> boxes, std::size_t budget,
                                 Visit&& visit, double side_scale = 1,
                                 std::pmr::memory_resource* scratch = std::pmr::new_delete_resource()) {
  box_pair_count r;
  const std::size_t n = boxes.size();
  if (n < 2) return r;
  if (n >= 0xFFFFFFFFu)
    throw error(error_category::invalid_input, "for_each_box_pair: more than 2^32 - 1 boxes");
  std::array<double, 3> lo{}, hi{};
  for (std::size_t k = 0; k < 3; ++k) {
    lo[k] = std::numeric_limits<double>::infinity();
    hi[k] = -std::numeric_limits<double>::infinity();
  }
  std::pmr::vector<double> extent(n, scratch);
  for (std::size_t t = 0; t < n; ++t) {
    const auto& b = boxes[t];
    for (std::size_t k = 0; k < 3; ++k) lo[k] = std::min(lo[k], b[k]), hi[k] = std::max(hi[k], b[k + 3]);
    extent[t] = std::max({b[3] - b[0], b[4] - b[1], b[5] - b[2]});
  }
  std::nth_element(extent.begin(), extent.begin() + static_cast<std::ptrdiff_t>(n / 2), extent.end());
  const double span = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  double side = extent[n / 2] * side_scale;
  std::pmr::vector<double>(scratch).swap(extent);
  if (!(side > 0) || !std::isfinite(side)) side = span / std::cbrt(static_cast<double>(n));
  if (!(side > 0) || !std::isfinite(side)) side = 1;
  const double max_entries = 8.0 * static_cast<double>(n) + 65536.0;
  std::array<std::uint32_t, 3> cells{};
  // Grid cells of each box's corners.
  std::pmr::vector<std::array<std::uint32_t, 3>> low(scratch), top(scratch);
  reserve_large(low, n), reserve_large(top, n);
  low.resize(n), top.resize(n);
  double inv = 0, entries = 0;
  auto place = [&] {  // low and top for this grid; the number of cell entries they need
    double total = 0;
    for (std::size_t t = 0; t < n; ++t) {
      double count = 1;
      for (std::size_t k = 0; k < 3; ++k) {
        low[t][k] = cell_of(boxes[t][k], lo[k], inv, cells[k]);
        top[t][k] = cell_of(boxes[t][k + 3], lo[k], inv, cells[k]);
        count *= static_cast<double>(top[t][k] - low[t][k] + 1);
      }
      total += count;
    }
    return total;
  };
  for (int attempt = 0;; ++attempt, side *= 1.5) {
    inv = 1 / side;
    double product = 1;
    for (std::size_t k = 0; k < 3; ++k) {
      const double c = std::floor((hi[k] - lo[k]) * inv) + 1;
      cells[k] = static_cast<std::uint32_t>(std::min(c, 4294967295.0));
      product *= static_cast<double>(cells[k]);
    }
    if (!(inv > 0) || attempt > 200) {  // the box is a point or beyond range: one cell
      cells = {1, 1, 1};
      entries = place();
      break;
    }
    if (product >= 4294967295.0) continue;
    if ((entries = place()) <= max_entries) break;
  }

  // Cell entries as (cell key << 32 | box), made in box order and sorted stably by cell: the
  // boxes of a cell in a run, in increasing order.
  std::pmr::vector<std::uint64_t> keys(scratch);
  reserve_large(keys, static_cast<std::size_t>(std::min(entries, max_entries)));
  for (std::size_t t = 0; t < n; ++t) {
    for (std::uint32_t x = low[t][0]; x <= top[t][0]; ++x)
      for (std::uint32_t y = low[t][1]; y <= top[t][1]; ++y)
        for (std::uint32_t z = low[t][2]; z <= top[t][2]; ++z) {
          const std::uint64_t cell = (static_cast<std::uint64_t>(x) * cells[1] + y) * cells[2] + z;
          keys.push_back(cell << 32 | t);
        }
  }
  std::pmr::vector<std::array<std::uint32_t, 3>>(scratch).swap(top);
  radix_sort_high(keys);
  const std::size_t limit = budget != 0 ? budget : std::numeric_limits<std::size_t>::max();
  // A pair is visited in cell c only when max(low[a], low[b]) = c, i.e. for each axis one of
  // the two boxes starts in c's slab. With mask bit k set when a box starts in c along axis k,
  // that is mask[a] | mask[b] = 7: the boxes of a cell are bucketed by mask, and only buckets
  // that complete each other are paired (the candidate pairs), from contiguous copies.
  struct local {
    std::array<double, 6> box;
    std::uint32_t id;
  };
  std::pmr::vector<local> bucket(scratch);
  for (std::size_t begin = 0; begin < keys.size();) {
    const std::uint64_t cell = keys[begin] >> 32;
    std::size_t end = begin + 1;
    while (end < keys.size() && keys[end] >> 32 == cell) ++end;
    if (end - begin < 2) {
      begin = end;
      continue;
    }
    const std::array<std::uint32_t, 3> here = {
        static_cast<std::uint32_t>(cell / (static_cast<std::uint64_t>(cells[1]) * cells[2])),
        static_cast<std::uint32_t>(cell / cells[2] % cells[1]), static_cast<std::uint32_t>(cell % cells[2])};
    std::array<std::size_t, 9> start{};  // bucket m holds [start[m], start[m + 1])
    auto mask_of = [&](std::uint32_t t) {
      return static_cast<std::size_t>((low[t][0] == here[0] ? 1 : 0) | (low[t][1] == here[1] ? 2 : 0) |
                                      (low[t][2] == here[2] ? 4 : 0));
    };
    for (std::size_t i = begin; i < end; ++i) ++start[mask_of(static_cast<std::uint32_t>(keys[i])) + 1];
    std::size_t pairs = start[8] * (start[8] - 1) / 2;  // within bucket 7 (its size, before the sums)
    for (std::size_t a = 0; a < 7; ++a)
      for (std::size_t b = a + 1; b < 8; ++b)
        if ((a | b) == 7) pairs += start[a + 1] * start[b + 1];
    for (std::size_t m = 1; m < 9; ++m) start[m] += start[m - 1];
    if (pairs == 0) {
      begin = end;
      continue;
    }
    if (pairs > limit - r.candidate_pairs) {
      r.complete = false;
      return r;
    }
    r.candidate_pairs += pairs;
    bucket.resize(end - begin);
    std::array<std::size_t, 8> fill{};
    for (std::size_t m = 0; m < 8; ++m) fill[m] = start[m];
    for (std::size_t i = begin; i < end; ++i) {
      const auto t = static_cast<std::uint32_t>(keys[i]);
      bucket[fill[mask_of(t)]++] = {boxes[t], t};
    }
    auto overlap = [](const std::array<double, 6>& p, const std::array<double, 6>& q) {
      // One branch instead of six: the outcome is hard to predict.
      return (static_cast<int>(p[0] <= q[3]) & static_cast<int>(q[0] <= p[3]) &
              static_cast<int>(p[1] <= q[4]) & static_cast<int>(q[1] <= p[4]) &
              static_cast<int>(p[2] <= q[5]) & static_cast<int>(q[2] <= p[5])) != 0;
    };
    for (std::size_t a = 0; a < 8; ++a)
      for (std::size_t b = a; b < 8; ++b) {
        if ((a | b) != 7) continue;
        for (std::size_t i = start[a]; i < start[a + 1]; ++i) {
          const local& x = bucket[i];
          for (std::size_t j = a == b ? i + 1 : start[b]; j < start[b + 1]; ++j) {
            if (!overlap(x.box, bucket[j].box)) continue;
            ++r.visited;
            if (!visit(x.id, bucket[j].id)) {
              r.complete = false;
              return r;
            }
          }
        }
      }
    begin = end;
  }
  return r;
}

}  // namespace cellforge::detail::self_intersect
