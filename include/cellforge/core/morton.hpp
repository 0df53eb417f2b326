// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Morton (Z-order) codes of points in a box: sorting by them lays out points that are near
/// in space near in memory, which is what the hull's insertion order and the wireframe's
/// crossing grid want.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace cellforge::detail {

/// Spreads the low 21 bits of x to every third bit of a 63-bit word. O(1).
template <class = void>
std::uint64_t morton_spread(std::uint64_t x) noexcept {
  x &= 0x1FFFFF;
  x = (x | x << 32) & 0x1F00000000FFFFull;
  x = (x | x << 16) & 0x1F0000FF0000FFull;
  x = (x | x << 8) & 0x100F00F00F00F00Full;
  x = (x | x << 4) & 0x10C30C30C30C30C3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

/// The 63-bit Morton code of p in the box [lo, lo + extent] (extent > 0 on every axis; points
/// outside are clamped to it). O(1).
template <class = void>
std::uint64_t morton_code(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& extent) noexcept {
  const glm::dvec3 t = glm::clamp((p - lo) / extent * 2097151.0, 0.0, 2097151.0);
  return morton_spread(static_cast<std::uint64_t>(t.x)) |
         morton_spread(static_cast<std::uint64_t>(t.y)) << 1 |
         morton_spread(static_cast<std::uint64_t>(t.z)) << 2;
}

/// The ids in Morton order of their points `at(id)` (a glm::dvec3) in the ids' own bounding
/// box, ties by id: ids near in space come out near in the order. O(n log n).
template <class Position>
std::vector<std::uint32_t> morton_order(std::span<const std::uint32_t> ids, Position&& at) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const std::uint32_t i : ids) lo = glm::min(lo, at(i)), hi = glm::max(hi, at(i));
  const glm::dvec3 span = hi - lo;
  const glm::dvec3 extent(span.x > 0 ? span.x : 1, span.y > 0 ? span.y : 1, span.z > 0 ? span.z : 1);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  keyed.reserve(ids.size());
  for (const std::uint32_t i : ids) keyed.emplace_back(morton_code(at(i), lo, extent), i);
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order;
  order.reserve(keyed.size());
  for (const auto& k : keyed) order.push_back(k.second);
  return order;
}

}  // namespace cellforge::detail
