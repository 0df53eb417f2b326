// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The small geometry helpers the parts share, one copy each: Newell's vector of a closed
/// polygon (the cell complex, its validation, mesh geometry, ear clipping, SVG pictures, sketch
/// faces, sample models) and the exact test whether two segments meet (ear clipping, the
/// self-intersection triangle pairs, the sketch face finder).

#include <algorithm>
#include <cstddef>

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

}  // namespace cellforge::detail
