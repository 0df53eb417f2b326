// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Locale-independent number parsing with std::from_chars, plus the checked conversion of
/// a parsed value into a point's scalar type (finite, representable, integral if need be).

#include <charconv>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <system_error>
#include <type_traits>
#include <utility>

namespace cellforge::io::detail {

enum class parse_status { ok, bad, out_of_range };

/// Parses a number of type T at p (no leading blanks; an optional '+' is accepted, unlike
/// plain from_chars), advancing p past it. Does not check what follows. O(length).
template <class T>
requires std::is_arithmetic_v<T> parse_status parse_number(const char*& p, const char* end, T& out)
noexcept {
  const char* q = p;
  // '+' is legal in every text format we read but from_chars refuses it; "+-1" stays invalid.
  if (q != end && *q == '+' && q + 1 != end && q[1] != '-' && q[1] != '+') ++q;
  std::from_chars_result r;
  if constexpr (std::is_floating_point_v<T>) {
    r = std::from_chars(q, end, out, std::chars_format::general);
    if (r.ec == std::errc::result_out_of_range) {
      // Tell underflow (round to zero, a valid value) from overflow (an error) by
      // re-reading in the widest type: only a genuinely huge value fails there too.
      long double wide = 0;
      const auto w = std::from_chars(q, end, wide, std::chars_format::general);
      if (w.ec != std::errc{} || std::fabs(wide) > static_cast<long double>(std::numeric_limits<T>::max())) {
        p = r.ptr;
        return parse_status::out_of_range;
      }
      out = static_cast<T>(wide);
      r.ec = std::errc{};
    }
  } else {
    // Fast path for the indices and counts that fill mesh files: up to 18 plain digits
    // cannot overflow the accumulator; anything else goes through from_chars.
    std::uint64_t acc = 0;
    const char* d = q;
    while (d != end && d - q < 18 && static_cast<unsigned char>(*d - '0') < 10)
      acc = acc * 10 + static_cast<unsigned>(*d++ - '0');
    if (d != q && (d == end || static_cast<unsigned char>(*d - '0') >= 10) &&
        acc <= std::uint64_t{std::numeric_limits<T>::max()}) {
      out = static_cast<T>(acc);
      p = d;
      return parse_status::ok;
    }
    r = std::from_chars(q, end, out);
  }
  if (r.ec == std::errc::invalid_argument) return parse_status::bad;
  p = r.ptr;
  return r.ec == std::errc{} ? parse_status::ok : parse_status::out_of_range;
}

/// Converts a parsed value to the point scalar S. False when the value is NaN or infinite,
/// outside S's range, or not a whole number while S is integral. O(1).
template <class S, class T>
requires std::is_arithmetic_v<S> && std::is_arithmetic_v<T>
bool convert_coordinate(T in, S& out) noexcept {
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(in)) return false;
    if constexpr (std::is_floating_point_v<S>) {
      if (std::fabs(static_cast<long double>(in)) > static_cast<long double>(std::numeric_limits<S>::max()))
        return false;
      out = static_cast<S>(in);
      return true;
    } else {
      if (std::trunc(in) != in) return false;
      const auto wide = static_cast<long double>(in);
      if (wide < static_cast<long double>(std::numeric_limits<S>::lowest()) ||
          wide > static_cast<long double>(std::numeric_limits<S>::max()))
        return false;
      out = static_cast<S>(in);
      return true;
    }
  } else {
    if constexpr (std::is_floating_point_v<S>) {
      out = static_cast<S>(in);
      return true;
    } else {
      if (!std::in_range<S>(in)) return false;
      out = static_cast<S>(in);
      return true;
    }
  }
}

/// The type to parse coordinate text in for scalar S: S itself when floating (exact for
/// shortest round-trip text), double when S is integral (so "2.0" is accepted).
template <class S>
using text_coordinate_t = std::conditional_t<std::is_floating_point_v<S>, S, double>;

}  // namespace cellforge::io::detail
