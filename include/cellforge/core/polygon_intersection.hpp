// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Exact incidence tests between lines, segments, points and planar polygons in 3D, decided
/// by the signs of orient3d alone (core/predicates.hpp) on the input points: whether a line
/// passes through a polygon's interior or only grazes its boundary, whether a segment pierces
/// it, and whether a point lies inside a closed surface of polygons (ray parity). Polygons
/// are index loops into a point array (loops[0] the outer boundary, the rest holes, any
/// orientation); they need only be planar to within rounding. See docs/predicates.md.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/predicates.hpp"

namespace cellforge {

/// Where a line, a segment or a point stands relative to a polygon or a closed surface.
enum class polygon_location : std::uint8_t {
  outside,   ///< misses it
  inside,    ///< meets its interior (and not its boundary, for a line: a clean pass)
  boundary,  ///< touches its boundary (a vertex or an edge): undecided by this line or point
};

/// Index loops of one polygon: loops[0] its outer boundary, loops[1..] holes.
using polygon_loops = std::vector<std::vector<std::uint32_t>>;

/// Three vertices of a polygon that span its plane well: the first vertex, the one farthest
/// from it and the one farthest from the line through both. O(size).
template <class = void>
std::array<std::uint32_t, 3> plane_vertices(std::span<const glm::dvec3> points, const polygon_loops& loops) {
  const std::vector<std::uint32_t>& outer = loops[0];
  const std::uint32_t a = outer[0];
  std::uint32_t b = outer[1 % outer.size()];
  double far = -1.0;
  for (const auto v : outer)
    if (const double d = glm::length(points[v] - points[a]); d > far) far = d, b = v;
  std::uint32_t c = outer[2 % outer.size()];
  const glm::dvec3 ab = points[b] - points[a];
  far = -1.0;
  for (const auto v : outer)
    if (const double d = glm::length(glm::cross(ab, points[v] - points[a])); d > far) far = d, c = v;
  return {a, b, c};
}

/// Whether the line through p and q, seen along its direction, passes through the polygon's
/// interior (inside), through a vertex or along an edge (boundary), or misses it. Exact:
/// every decision is the sign of orient3d on input points. O(size).
template <class = void>
polygon_location line_through_polygon(std::span<const glm::dvec3> points, const polygon_loops& loops,
                                      const glm::dvec3& p, const glm::dvec3& q) {
  for (const auto& loop : loops)
    for (const auto v : loop)
      if (collinear(p, q, points[v])) return polygon_location::boundary;
  // Seen along the line, the line is a point O; a helper point s fixes a half-line from O.
  // y(v) = orient3d(p, q, s, v) is the side of v's image of that half-line's line and
  // x(a, b) = orient3d(p, q, a, b) the side of O of edge a→b: a crossing-number test.
  // s is chosen so that no vertex has y = 0; then an edge with x = 0 crossing the line
  // passes through O itself.
  const glm::dvec3 d = q - p;
  const double scale = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z), 1e-300});
  const glm::dvec3 offsets[] = {
      {0.6180339887, 0.3090169944, -0.7236067977},  {-0.2763932023, 0.8506508084, 0.4472135955},
      {0.5257311121, -0.8506508084, 0.1055728090},  {0.9341723590, 0.1784110448, 0.3090169944},
      {-0.3568220898, -0.5773502692, 0.7341723590}, {0.1273220037, 0.9654157497, -0.2283454656}};
  for (const auto& offset : offsets) {
    const glm::dvec3 s = p + scale * offset;
    if (collinear(p, q, s)) continue;
    bool degenerate = false;
    for (const auto& loop : loops) {
      for (const auto v : loop)
        if (orient3d(p, q, s, points[v]) == 0) {
          degenerate = true;
          break;
        }
      if (degenerate) break;
    }
    if (degenerate) continue;
    bool odd = false;
    for (const auto& loop : loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const glm::dvec3& a = points[loop[k]];
        const glm::dvec3& b = points[loop[(k + 1) % loop.size()]];
        const int ya = orient3d(p, q, s, a), yb = orient3d(p, q, s, b);
        if (ya == yb) continue;
        const int x = orient3d(p, q, a, b);
        if (x == 0) return polygon_location::boundary;
        if ((ya < 0) == (x > 0)) odd = !odd;  // upward edge left of O, or downward edge right of it
      }
    return odd ? polygon_location::inside : polygon_location::outside;
  }
  return polygon_location::boundary;
}

/// True when the segment a–b crosses the polygon's plane (spanned by `plane`, see
/// plane_vertices) with its ends strictly on opposite sides and passes through the polygon's
/// interior, not its boundary. Exact. O(size).
template <class = void>
bool segment_pierces_polygon(std::span<const glm::dvec3> points, const polygon_loops& loops,
                             const std::array<std::uint32_t, 3>& plane, const glm::dvec3& a,
                             const glm::dvec3& b) {
  const glm::dvec3 &p0 = points[plane[0]], &p1 = points[plane[1]], &p2 = points[plane[2]];
  const int sa = orient3d(p0, p1, p2, a), sb = orient3d(p0, p1, p2, b);
  if (sa * sb >= 0) return false;
  return line_through_polygon(points, loops, a, b) == polygon_location::inside;
}

/// Whether q lies inside the closed surface made of `faces` (each an index-loop polygon, any
/// orientation), by the parity of exact ray crossings; `boundary` when q lies on a face's
/// plane inside its box or every tried ray grazes an edge (pick another point then).
/// `loops_of(face)` returns a face's polygon_loops. O(Σ face size) per ray, at most 6 rays.
template <class FaceRange, class LoopsOf>
polygon_location point_in_polyhedron(std::span<const glm::dvec3> points, const FaceRange& faces,
                                     LoopsOf&& loops_of, const glm::dvec3& q) {
  glm::dvec3 lo(q), hi(q);
  for (const auto& f : faces)
    for (const auto v : loops_of(f)[0]) {
      lo = glm::min(lo, points[v]);
      hi = glm::max(hi, points[v]);
    }
  // A ray long enough to leave the box from anywhere inside it.
  const double reach = 2.0 * glm::length(hi - lo) + 1.0;
  const glm::dvec3 directions[] = {{0.5773, 0.5719, 0.5831},   {-0.3129, 0.8447, 0.4341},
                                   {0.7071, -0.2137, -0.6741}, {-0.6262, -0.5491, 0.5535},
                                   {0.1213, 0.2711, -0.9549},  {-0.8117, -0.1931, -0.5513}};
  std::vector<std::array<std::uint32_t, 3>> planes;
  for (const auto& f : faces) {
    const auto& loops = loops_of(f);
    planes.push_back(plane_vertices(points, loops));
    const auto& t = planes.back();
    if (orient3d(points[t[0]], points[t[1]], points[t[2]], q) != 0) continue;
    // q on this face's plane: on the face, or beside it; either way not a clean start.
    glm::dvec3 flo(points[loops[0][0]]), fhi(flo);
    for (const auto v : loops[0]) {
      flo = glm::min(flo, points[v]);
      fhi = glm::max(fhi, points[v]);
    }
    if (q.x >= flo.x && q.y >= flo.y && q.z >= flo.z && q.x <= fhi.x && q.y <= fhi.y && q.z <= fhi.z)
      return polygon_location::boundary;
  }
  for (const auto& dir : directions) {
    const glm::dvec3 r = q + reach * dir;
    bool odd = false, grazed = false;
    std::size_t k = 0;
    for (const auto& f : faces) {
      const auto& t = planes[k++];
      const glm::dvec3 &p0 = points[t[0]], &p1 = points[t[1]], &p2 = points[t[2]];
      if (orient3d(p0, p1, p2, q) * orient3d(p0, p1, p2, r) >= 0) continue;
      const polygon_location l = line_through_polygon(points, loops_of(f), q, r);
      if (l == polygon_location::boundary) {
        grazed = true;
        break;
      }
      if (l == polygon_location::inside) odd = !odd;
    }
    if (!grazed) return odd ? polygon_location::inside : polygon_location::outside;
  }
  return polygon_location::boundary;
}

}  // namespace cellforge
