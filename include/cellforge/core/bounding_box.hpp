// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Axis-aligned bounding boxes of point sets, in double precision.

#include <algorithm>
#include <limits>
#include <ranges>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/point_traits.hpp"

namespace cellforge {

/// An axis-aligned box; empty until a point is added.
struct bounding_box {
  glm::dvec3 min{std::numeric_limits<double>::infinity()};
  glm::dvec3 max{-std::numeric_limits<double>::infinity()};

  bool empty() const noexcept { return min.x > max.x; }
  void add(const glm::dvec3& p) noexcept {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  /// Length of the diagonal; 0 for an empty box or a single point.
  double diagonal() const noexcept { return empty() ? 0.0 : glm::length(max - min); }
  glm::dvec3 center() const noexcept { return empty() ? glm::dvec3(0.0) : 0.5 * (min + max); }
};

/// Bounding box of a range of registered points. O(n).
template <std::ranges::input_range R>
requires Point3<std::ranges::range_value_t<R>> bounding_box bounding_box_of(R&& points) {
  bounding_box box;
  for (const auto& p : points) box.add(to_dvec3(p));
  return box;
}

}  // namespace cellforge
