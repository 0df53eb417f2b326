// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Morton (Z-order) codes of points in a box: sorting by them lays out points that are near
/// in space near in memory, which is what the hull's insertion order and the wireframe's
/// crossing grid want.

#include <algorithm>
#include <cstdint>

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

}  // namespace cellforge::detail
