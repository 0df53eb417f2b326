// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Axis-aligned bounding boxes of point sets, in double precision.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ranges>
#include <string>
#include <string_view>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
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

/// Refuses (error naming `who`) a box whose lengths, areas and volumes double cannot hold: an
/// extent under 1e-50 or a coordinate beyond 1e50 (a volume is a cube, 1e300 would be inf and a
/// face "degenerate"). An empty or single-point box passes. O(1).
template <class = void>
void check_double_range(const bounding_box& box, std::string_view who) {
  if (box.empty()) return;
  const glm::dvec3 span = box.max - box.min;
  const double extent = std::max({span.x, span.y, span.z});
  const double reach = std::max({std::abs(box.min.x), std::abs(box.min.y), std::abs(box.min.z),
                                 std::abs(box.max.x), std::abs(box.max.y), std::abs(box.max.z)});
  if (extent > 0 && (extent < 1e-50 || reach > 1e50)) {
    char text[96];
    std::snprintf(text, sizeof text, "the model spans %.6g and reaches %.6g from the origin", extent, reach);
    throw error(error_category::invalid_input,
                cellforge::detail::cat(
                    std::string(who), ": ", text,
                    "; its lengths, areas and volumes are squares and cubes of that, which double holds only "
                    "between 1e-50 and 1e50 units: scale the model into that range"));
  }
}

}  // namespace cellforge
