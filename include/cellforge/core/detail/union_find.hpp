// SPDX-License-Identifier: MIT
#pragma once
// Disjoint sets with path halving, shared by the wireframe pipeline and the tube mesher.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace cellforge::detail {

template <class = void>
struct basic_union_find {
  std::vector<std::uint32_t> parent;
  explicit basic_union_find(std::size_t n = 0) : parent(n) {
    for (std::size_t i = 0; i < n; ++i) parent[i] = static_cast<std::uint32_t>(i);
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  /// Joins the sets of a and b; the smaller root survives (deterministic representatives).
  bool unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (a < b) std::swap(a, b);
    parent[a] = b;
    return true;
  }
};
using union_find = basic_union_find<>;

}  // namespace cellforge::detail
