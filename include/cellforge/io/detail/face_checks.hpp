// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Checks shared by the readers on each face they read.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cellforge/core/detail/text.hpp"

namespace cellforge::io::detail {

/// A vertex index that occurs twice in `face`, if any. O(k^2) for small faces, O(k log k)
/// beyond (sorting a copy in `scratch`, reused across faces so there is no allocation per face).
template <class = void>
std::optional<std::uint32_t> repeated_vertex(std::span<const std::uint32_t> face,
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

/// Ends the face whose indices start at `first` in `soup.face_vertices`: records its end
/// offset, or returns what is wrong with it (a repeated vertex when `options_name` says
/// those are refused, or the 32-bit offset limit) for the caller to report with its place.
/// `index_base` is 1 for formats that count vertices from 1. O(face size).
template <class Soup>
std::optional<std::string> close_face(Soup& soup, std::size_t first, bool allow_repeated,
                                      std::vector<std::uint32_t>& scratch, std::uint32_t index_base,
                                      std::string_view options_name) {
  if (soup.face_vertices.size() > std::numeric_limits<std::uint32_t>::max())
    return std::string("exceeds the limit of 2^32 face vertex indices in all (32-bit offsets)");
  const std::span<const std::uint32_t> face(soup.face_vertices.data() + first,
                                            soup.face_vertices.size() - first);
  if (!allow_repeated) {
    if (const auto dup = repeated_vertex(face, scratch)) {
      return cellforge::detail::cat("uses vertex ", std::to_string(std::uint64_t{*dup} + index_base),
                                    " twice (degenerate face; ", std::string(options_name),
                                    "::allow_repeated_vertices accepts it)");
    }
  }
  soup.face_offsets.push_back(static_cast<std::uint32_t>(soup.face_vertices.size()));
  return std::nullopt;
}

/// Bytes per element the rest of a file can hold, for reserving from a header count without
/// trusting it: a claim of 10^12 faces in a 1 kB file reserves a few hundred, not terabytes. O(1).
constexpr std::size_t plausible_count(std::uint64_t claimed, std::size_t bytes_left,
                                      std::size_t min_bytes_each) noexcept {
  const std::uint64_t fits = bytes_left / min_bytes_each + 1;
  return static_cast<std::size_t>(claimed < fits ? claimed : fits);
}

}  // namespace cellforge::io::detail
