// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Newell's vector of a closed polygon: the one normal computation the cell complex, its
/// validation, the mesh geometry queries and the sample models share.

#include <iterator>
#include <ranges>

#include <glm/vec3.hpp>

namespace cellforge::detail {

/// Newell's vector (twice the vector area; the least-squares normal of a non-planar loop) of
/// the loop of vertices `loop`, whose positions `at(vertex)` gives as glm::dvec3. Any forward
/// range: a vector of indices, or a face circulator. O(loop size).
template <std::ranges::forward_range Loop, class At>
glm::dvec3 newell(const Loop& loop, At&& at) {
  glm::dvec3 n(0.0);
  auto it = std::ranges::begin(loop);
  const auto end = std::ranges::end(loop);
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

}  // namespace cellforge::detail
