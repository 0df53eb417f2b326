// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// splitmix64, the pseudo-random numbers of the sample generators: the same numbers with
/// every standard library (std::uniform_real_distribution is not specified bit for bit).

#include <cstdint>

namespace cellforge::detail {

/// splitmix64: the same numbers on every platform. O(1) per number.
template <class = void>
struct basic_splitmix {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
  }
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1p-53;
  }
};
using splitmix = basic_splitmix<>;

}  // namespace cellforge::detail
