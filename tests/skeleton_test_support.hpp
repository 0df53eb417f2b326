// SPDX-License-Identifier: MIT
#pragma once
// Shared by the skeleton reader tests (test_io_swc.cpp, test_io_skeleton_obj.cpp): awkward
// skeletons for exact round trips, bitwise comparison, and the exact-message checker.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "cellforge/tubes/skeleton.hpp"
#include "io_test_support.hpp"

namespace skeleton_test {

/// A skeleton with coordinates and radii that stress number formatting (negative zero,
/// subnormals, the largest finite values, every magnitude). Edges: a random forest whose
/// parents come before their children (as SWC writes them), plus `extra` further edges
/// (cycles) that are neither self loops nor repeats.
template <cellforge::Point3 P>
cellforge::skeleton<P> awkward_skeleton(unsigned seed, std::size_t n, std::size_t extra = 0) {
  std::mt19937_64 rng(seed);
  cellforge::skeleton<P> s;
  s.points = io_test::awkward_soup<P>(seed, n, 0).points;
  std::uniform_real_distribution<double> mantissa(0.5, 1.0);
  std::uniform_int_distribution<int> exponent(-60, 60);
  using L = std::numeric_limits<double>;
  for (std::size_t i = 0; i < n; ++i) {
    switch (i % 7) {
      case 0:
        s.radii.push_back(L::denorm_min());
        break;
      case 1:
        s.radii.push_back(L::max());
        break;
      case 2:
        s.radii.push_back(0.1);
        break;
      default:
        s.radii.push_back(std::ldexp(mantissa(rng), exponent(rng)));
    }
  }
  for (std::size_t i = 1; i < n; ++i)
    if (rng() % 10 != 0)
      s.edges.push_back({static_cast<std::uint32_t>(rng() % i), static_cast<std::uint32_t>(i)});
  for (std::size_t tries = 0; extra > 0 && n > 2 && tries < 100 * extra; ++tries) {
    const auto a = static_cast<std::uint32_t>(rng() % n), b = static_cast<std::uint32_t>(rng() % n);
    const bool repeat = std::any_of(s.edges.begin(), s.edges.end(), [&](const auto& e) {
      return (e[0] == a && e[1] == b) || (e[0] == b && e[1] == a);
    });
    if (a == b || repeat) continue;
    s.edges.push_back({a, b});
    --extra;
  }
  return s;
}

/// Positions equal bit for bit, radii too, and the same edges in the same order.
template <cellforge::Point3 P>
bool same_skeleton(const cellforge::skeleton<P>& a, const cellforge::skeleton<P>& b) {
  if (a.points.size() != b.points.size() || a.radii.size() != b.radii.size() || a.edges != b.edges)
    return false;
  for (std::size_t i = 0; i < a.points.size(); ++i)
    if (!io_test::same_bits(a.points[i], b.points[i])) return false;
  return std::memcmp(a.radii.data(), b.radii.data(), a.radii.size() * sizeof(double)) == 0;
}

/// A malformed input, the line its error must name and the whole message after "file:line: ".
struct bad_input {
  const char* what;
  std::string text;
  std::uint64_t line;
  std::string message;
};

/// `parse(text)` must throw an io error at the line (io_test::check_rejected) whose what() is
/// exactly "name:line: message".
template <class Parse>
void check_rejected(const bad_input& c, const std::string& name, Parse&& parse) {
  io_test::check_rejected({c.what, c.text, c.line, c.message.c_str()}, name.c_str(), parse);
  try {
    parse(c.text);
  } catch (const cellforge::error& e) {
    CHECK(std::string(e.what()) == name + ":" + std::to_string(c.line) + ": " + c.message);
  }
}

}  // namespace skeleton_test
