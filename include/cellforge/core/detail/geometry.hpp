// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The small geometry helpers the parts share, one copy each: Newell's vector of a closed
/// polygon (the cell complex, its validation, mesh geometry, ear clipping, SVG pictures, sketch
/// faces, sample models), the exact test whether two segments meet (ear clipping, the
/// self-intersection triangle pairs, the sketch face finder), the exact even-odd point in
/// polygon (the circuit tracer, the sketch faces, SVG visibility), a unit vector perpendicular
/// to another (the wireframe's fans, the tubes' frames, the sample tube soups) and a vertex
/// cycle's canonical order (the wireframe's faces, the sketch's loop comparisons).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/predicates.hpp"

namespace cellforge::detail {

/// The indices 0 .. n-1 as a range with begin() and end() (std::views::iota does not compile
/// with clang 14 over libstdc++ 12).
struct index_range {
  struct iterator {
    std::size_t i;
    std::size_t operator*() const noexcept { return i; }
    iterator& operator++() noexcept {
      ++i;
      return *this;
    }
    bool operator==(const iterator&) const noexcept = default;
  };
  std::size_t n;
  iterator begin() const noexcept { return {0}; }
  iterator end() const noexcept { return {n}; }
};

/// Newell's vector (twice the vector area; the least-squares normal of a non-planar loop) of
/// the loop of vertices `loop`, whose positions `at(vertex)` gives as glm::dvec3. Any range
/// with begin() and end(): a vector of indices, a face circulator, an index_range. O(loop size).
template <class Loop, class At>
glm::dvec3 newell(const Loop& loop, At&& at) {
  glm::dvec3 n(0.0);
  auto it = loop.begin();
  const auto end = loop.end();
  if (it == end) return n;
  const glm::dvec3 first = at(*it);
  glm::dvec3 a = first;
  for (++it;; ++it) {
    const bool closing = it == end;  // the last side runs back to the first vertex
    const glm::dvec3 b = closing ? first : glm::dvec3(at(*it));
    n += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    if (closing) break;
    a = b;
  }
  return n;
}

/// True when the closed segments ab and cd share a point, decided exactly (orient2d signs;
/// an endpoint on the other segment counts). O(1); disjoint bounding boxes settle most pairs.
template <class = void>
bool segments_meet(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                   const glm::dvec2& d) noexcept {
  if (std::max(a.x, b.x) < std::min(c.x, d.x) || std::max(c.x, d.x) < std::min(a.x, b.x) ||
      std::max(a.y, b.y) < std::min(c.y, d.y) || std::max(c.y, d.y) < std::min(a.y, b.y))
    return false;
  const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d), o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  // A point on the other segment: collinear with it and inside its bounding box.
  const auto on = [](const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& r) {
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
           r.y <= std::max(p.y, q.y);
  };
  return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) ||
         (o4 == 0 && on(c, d, b));
}

/// Whether the side ab of a polygon crosses the ray from q towards +x, decided exactly
/// (orient2d; a side's upper end is not on it, so a vertex on the ray counts once). O(1).
template <class = void>
bool crosses_ray(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& q) noexcept {
  if ((a.y > q.y) == (b.y > q.y)) return false;
  const int s = orient2d(b, a, q);
  return a.y > b.y ? s > 0 : s < 0;
}

/// Whether q is inside the closed polygon `poly` by the even-odd rule, decided exactly
/// (crosses_ray on every side; a point on the boundary may go either way). O(n).
template <class = void>
bool point_in_polygon(const std::vector<glm::dvec2>& poly, const glm::dvec2& q) noexcept {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    if (crosses_ray(poly[i], poly[j], q)) in = !in;
  return in;
}

/// The coordinate axis any_perpendicular crosses n with. Each part keeps the rule its frames
/// were made with: a frame's first axis shows in its output (ring starts, sample soups).
enum class perpendicular_rule : std::uint8_t {
  least_aligned,  ///< the axis of n's smallest |component| (ties: x, then y); |n × axis| >= √(2/3)
  x_below_0_6,    ///< x while |n.x| < 0.6, else y (the wireframe stages' fans about an edge)
  x_below_0_9,    ///< x while |n.x| < 0.9, else y (the sample tube soups' ring frames)
};

/// A unit vector perpendicular to the unit vector n: n × an axis chosen by `rule` from n
/// alone, normalised. O(1).
template <class = void>
glm::dvec3 any_perpendicular(const glm::dvec3& n,
                             perpendicular_rule rule = perpendicular_rule::least_aligned) {
  glm::dvec3 axis(0.0, 1.0, 0.0);
  switch (rule) {
    case perpendicular_rule::least_aligned:
      axis = std::abs(n.x) <= std::abs(n.y) && std::abs(n.x) <= std::abs(n.z) ? glm::dvec3(1, 0, 0)
             : std::abs(n.y) <= std::abs(n.z)                                 ? glm::dvec3(0, 1, 0)
                                                                              : glm::dvec3(0, 0, 1);
      break;
    case perpendicular_rule::x_below_0_6:
      if (std::abs(n.x) < 0.6) axis = glm::dvec3(1, 0, 0);
      break;
    case perpendicular_rule::x_below_0_9:
      if (std::abs(n.x) < 0.9) axis = glm::dvec3(1, 0, 0);
      break;
  }
  return glm::normalize(glm::cross(n, axis));
}

/// Rotates a vertex cycle to the seed's canonical order (§4.3): start at the smallest label and
/// go on towards its smaller neighbour. Returns true when the cycle was reversed. O(n).
template <class = void>
bool make_canonical_cycle(std::vector<std::uint32_t>& c) {
  if (c.size() < 2) return false;
  const auto it = std::min_element(c.begin(), c.end());
  std::rotate(c.begin(), it, c.end());
  if (c.size() > 2 && c.back() < c[1]) {
    std::reverse(c.begin() + 1, c.end());
    return true;
  }
  return false;
}

/// A copy of a vertex cycle in canonical order: its form up to rotation and reversal. O(n).
template <class = void>
std::vector<std::uint32_t> canonical_cycle(std::vector<std::uint32_t> loop) {
  make_canonical_cycle(loop);
  return loop;
}

}  // namespace cellforge::detail
