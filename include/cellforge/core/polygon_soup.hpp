// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A polygon soup: points and faces as vertex-index lists, stored flat (one index
/// array plus offsets) so a million faces cost two allocations. Readers produce soups;
/// the half-edge mesh is built from one in bulk.

#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

#include "cellforge/core/point_traits.hpp"

namespace cellforge {

/// Points and polygonal faces (indices into points). Faces are stored in CSR form:
/// face f is `face_vertices[face_offsets[f] .. face_offsets[f+1])`.
template <Point3 P>
struct polygon_soup {
  std::vector<P> points;
  std::vector<std::uint32_t> face_offsets{0};
  std::vector<std::uint32_t> face_vertices;

  std::size_t num_points() const noexcept { return points.size(); }
  std::size_t num_faces() const noexcept { return face_offsets.empty() ? 0 : face_offsets.size() - 1; }

  /// The vertex indices of face f. O(1).
  std::span<const std::uint32_t> face(std::size_t f) const noexcept {
    return {face_vertices.data() + face_offsets[f], face_offsets[f + 1] - face_offsets[f]};
  }
  /// Appends a face given by vertex indices. O(size of the face), amortised.
  void add_face(std::span<const std::uint32_t> vertices) {
    face_vertices.insert(face_vertices.end(), vertices.begin(), vertices.end());
    face_offsets.push_back(static_cast<std::uint32_t>(face_vertices.size()));
  }
  void add_face(std::initializer_list<std::uint32_t> vertices) {
    add_face(std::span<const std::uint32_t>(vertices.begin(), vertices.size()));
  }
  /// Reserves room for n points and m faces with k indices in all. O(1) amortised.
  void reserve(std::size_t n, std::size_t m, std::size_t k) {
    points.reserve(n);
    face_offsets.reserve(m + 1);
    face_vertices.reserve(k);
  }
  void clear() {
    points.clear();
    face_offsets.assign(1, 0);
    face_vertices.clear();
  }
};

}  // namespace cellforge
