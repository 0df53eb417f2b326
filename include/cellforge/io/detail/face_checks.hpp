// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Checks shared by the readers on each face they read.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace cellforge::io::detail {

/// A vertex index that occurs twice in `face`, if any. O(k^2) for small faces, O(k log k)
/// beyond (sorting a copy in `scratch`, reused across faces so there is no allocation per face).
inline std::optional<std::uint32_t> repeated_vertex(std::span<const std::uint32_t> face,
                                                    std::vector<std::uint32_t>& scratch) {
  if (face.size() <= 16) {
    for (std::size_t i = 1; i < face.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (face[i] == face[j]) return face[i];
    return std::nullopt;
  }
  scratch.assign(face.begin(), face.end());
  std::sort(scratch.begin(), scratch.end());
  const auto it = std::adjacent_find(scratch.begin(), scratch.end());
  if (it == scratch.end()) return std::nullopt;
  return *it;
}

/// Bytes per element the rest of a file can hold, for reserving from a header count without
/// trusting it: a claim of 10^12 faces in a 1 kB file reserves a few hundred, not terabytes. O(1).
constexpr std::size_t plausible_count(std::uint64_t claimed, std::size_t bytes_left,
                                      std::size_t min_bytes_each) noexcept {
  const std::uint64_t fits = bytes_left / min_bytes_each + 1;
  return static_cast<std::size_t>(claimed < fits ? claimed : fits);
}

}  // namespace cellforge::io::detail
