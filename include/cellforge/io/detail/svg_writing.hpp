// SPDX-License-Identifier: MIT
#pragma once
// Number, colour and geometry helpers of the SVG writer (io/svg.hpp).

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <ostream>
#include <ranges>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/point_traits.hpp"

namespace cellforge::io::detail {

/// Appends v with `precision` decimals, trailing zeros dropped; locale-independent. O(1).
template <class = void>
void svg_number(std::string& out, double v, int precision) {
  static constexpr double powers[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
  const double scaled = v * powers[precision];
  if (std::abs(scaled) < 1e15) {
    // Fast path for every coordinate inside a picture: an integer count of the last digit.
    long long n = std::llround(scaled);
    char text[32];
    char* w = text;
    if (n < 0) {
      *w++ = '-';
      n = -n;
    }
    char digits[24];
    int k = 0;
    for (; n > 0 || k <= precision; n /= 10) digits[k++] = static_cast<char>('0' + n % 10);
    int lowest = 0;  // trailing zeros of the fraction are dropped
    while (lowest < precision && digits[lowest] == '0') ++lowest;
    for (int i = k - 1; i >= precision; --i) *w++ = digits[i];
    if (lowest < precision) {
      *w++ = '.';
      for (int i = precision - 1; i >= lowest; --i) *w++ = digits[i];
    }
    out.append(text, w);
    return;
  }
  char buf[512];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, precision);
  if (r.ec != std::errc{}) {
    out += '0';  // unreachable for coordinates inside the viewport
    return;
  }
  char* e = r.ptr;
  if (precision > 0) {
    while (e[-1] == '0') --e;
    if (e[-1] == '.') --e;
  }
  const std::string_view s(buf, static_cast<std::size_t>(e - buf));
  out += s == "-0" ? std::string_view("0") : s;
}

/// `#rgb` or `#rrggbb` as 0..1 components; nothing for any other colour syntax.
template <class = void>
std::optional<glm::dvec3> svg_parse_hex(std::string_view s) {
  const auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  if (s.empty() || s[0] != '#' || (s.size() != 4 && s.size() != 7)) return std::nullopt;
  glm::dvec3 rgb(0.0);
  for (int i = 0; i < 3; ++i) {
    int v = 0;
    if (s.size() == 4) {
      const int h = hex(s[1 + i]);
      if (h < 0) return std::nullopt;
      v = h * 17;
    } else {
      const int h = hex(s[1 + 2 * i]), l = hex(s[2 + 2 * i]);
      if (h < 0 || l < 0) return std::nullopt;
      v = h * 16 + l;
    }
    rgb[i] = v / 255.0;
  }
  return rgb;
}

template <class = void>
void svg_hex_colour(std::string& out, const glm::dvec3& rgb) {
  static constexpr char digits[] = "0123456789abcdef";
  out += '#';
  for (int i = 0; i < 3; ++i) {
    const int v = static_cast<int>(std::lround(std::clamp(rgb[i], 0.0, 1.0) * 255.0));
    out += digits[v / 16];
    out += digits[v % 16];
  }
}

/// Newell's normal of a polygon (not normalised; zero for degenerate polygons). O(n).
template <class Get>
glm::dvec3 svg_newell(std::size_t n, Get&& at) {
  // From the closing side n-1 -> 0 on, the order of summation the pictures always had.
  return cellforge::detail::newell(cellforge::detail::index_range{n},
                                   [&](std::size_t k) { return glm::dvec3(at((k + n - 1) % n)); });
}

/// A forward range of registered points (what add_polyline and add_points accept).
template <class R>
concept svg_point_range = std::ranges::forward_range<R> && Point3<std::ranges::range_value_t<R>>;

template <class = void>
std::uint64_t svg_edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

}  // namespace cellforge::io::detail
