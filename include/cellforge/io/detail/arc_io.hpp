// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// What the arc readers and writers of text and SVG share: one conversion of rotations from
/// degrees to radians for every reader and its exact inverse for the writers (so that arcs
/// written and read again keep their rotation bit for bit).

#include <bit>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>

namespace cellforge::io::detail {

/// The radians of a rotation given in degrees, as every arc reader converts them. O(1).
template <class = void>
double arc_radians(double degrees) {
  return degrees * (std::numbers::pi / 180);
}

/// Degrees that arc_radians maps back to `radians` bit for bit when there are any (the shortest
/// in text among the doubles next to radians · 180/π), else the nearest. O(1).
template <class = void>
double arc_degrees(double radians) {
  const double guess = radians * (180 / std::numbers::pi);
  double best = guess;
  std::size_t best_len = std::numeric_limits<std::size_t>::max();
  // Bit for bit: -0 and 0 are different text.
  const auto same = [](double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
  };
  for (int side = 0; side < 2; ++side) {
    double d = guess;
    for (int k = 0; k < 5; ++k) {
      if (same(arc_radians(d), radians)) {
        char buf[32];
        const auto r = std::to_chars(buf, buf + sizeof buf, d);
        const auto len = static_cast<std::size_t>(r.ptr - buf);
        if (len < best_len) best = d, best_len = len;
      }
      d = std::nextafter(d, (side == 0 ? -1 : 1) * std::numeric_limits<double>::infinity());
    }
  }
  return best;
}

}  // namespace cellforge::io::detail
