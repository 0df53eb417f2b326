// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The one test of drawn directions for parallelism that the sketch parts share (faces,
/// drawing_to_cells' readings, arc pairing).

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace cellforge::detail::sketch {

/// Whether drawn directions u and v are parallel (either way) within `sine`, the sine of the
/// angle between them; a zero direction is parallel to nothing. O(1).
template <class = void>
bool parallel_within(glm::dvec2 u, glm::dvec2 v, double sine) {
  const double lu = glm::length(u), lv = glm::length(v);
  return lu > 0 && lv > 0 && std::abs(u.x * v.y - u.y * v.x) <= sine * lu * lv;
}

}  // namespace cellforge::detail::sketch
