// SPDX-License-Identifier: MIT
#pragma once
// Number and keyword writers shared by the 3DCL and the PLY cell-complex writers.

#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>

namespace cellforge::io::detail {

// Appends the decimal digits of n; appending pieces instead of `" " + std::to_string(n)`
// also keeps g++ 12's false -Wrestrict (PR 105329) out of a user's -O2 -Werror build.
template <class = void>
void put_count(std::string& out, std::uint64_t n) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, n);
  out.append(buf, r.ptr);
}

// Appends a keyword, a space and a count, e.g. "edges 12".
template <class = void>
void put_keyword(std::string& out, std::string_view keyword, std::uint64_t n) {
  out += keyword;
  out += ' ';
  put_count(out, n);
}

template <class = void>
void put_signed(std::string& out, std::uint32_t index, int sign) {
  out += sign < 0 ? " -" : " +";
  put_count(out, index);
}

template <class = void>
void put_double(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

}  // namespace cellforge::io::detail
