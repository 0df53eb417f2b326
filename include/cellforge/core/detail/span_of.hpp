// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// span_of(v): a std::span over a vector's or an array's elements, for passing one to a
/// std::span parameter inside the library. Written at a call that does not depend on a template
/// parameter, the implicit vector-to-span conversion makes g++ 12 check std::span's range
/// constraints (contiguous_range and the iterator concepts under it) where the call is
/// *defined*: about 70 M compiler instructions per element type in every translation unit that
/// includes the header, used or not (docs/benchmarks.md, "Compile time of the headers").
/// Through this function template the check waits until the calling code is instantiated.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace cellforge::detail {

/// The elements of v as a span. O(1).
template <class T, class A>
std::span<T> span_of(std::vector<T, A>& v) noexcept {
  return {v.data(), v.size()};
}
template <class T, class A>
std::span<const T> span_of(const std::vector<T, A>& v) noexcept {
  return {v.data(), v.size()};
}
template <class T, std::size_t N>
std::span<T> span_of(std::array<T, N>& a) noexcept {
  return {a.data(), N};
}
template <class T, std::size_t N>
std::span<const T> span_of(const std::array<T, N>& a) noexcept {
  return {a.data(), N};
}

}  // namespace cellforge::detail
