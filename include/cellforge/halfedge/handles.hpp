// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Strong 32-bit index handles for mesh elements: a vertex handle cannot be passed
/// where a face is expected, and every handle has an invalid sentinel.

#include <compare>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>  // declares std::hash, without <functional> (a tenth of a small TU's compile)

namespace cellforge {

/// A typed index into one of the mesh's element arrays. Default-constructed: invalid.
template <class Tag>
class handle {
 public:
  static constexpr std::uint32_t invalid_index = std::numeric_limits<std::uint32_t>::max();

  constexpr handle() noexcept = default;
  constexpr explicit handle(std::uint32_t index) noexcept : index_(index) {}
  constexpr explicit handle(std::size_t index) noexcept : index_(static_cast<std::uint32_t>(index)) {}
  constexpr explicit handle(int index) noexcept : index_(static_cast<std::uint32_t>(index)) {}

  /// The index into the element arrays (and property arrays). O(1).
  constexpr std::uint32_t idx() const noexcept { return index_; }
  constexpr bool is_valid() const noexcept { return index_ != invalid_index; }
  constexpr explicit operator bool() const noexcept { return is_valid(); }

  friend constexpr auto operator<=>(handle, handle) noexcept = default;

 private:
  std::uint32_t index_ = invalid_index;
};

struct vertex_tag {};
struct halfedge_tag {};
struct edge_tag {};
struct face_tag {};

using vertex_handle = handle<vertex_tag>;
using halfedge_handle = handle<halfedge_tag>;
using edge_handle = handle<edge_tag>;
using face_handle = handle<face_tag>;

}  // namespace cellforge

template <class Tag>
struct std::hash<cellforge::handle<Tag>> {
  std::size_t operator()(cellforge::handle<Tag> h) const noexcept {
    return static_cast<std::size_t>(h.idx());  // the identity, as std::hash<std::uint32_t> is
  }
};
