// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A cursor over a text buffer for the line-oriented formats (OFF, OBJ, ASCII PLY).
/// The hot path never counts lines: an error finds its line number by counting line
/// breaks up to the failure point once, so a clean parse pays nothing for diagnostics.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/io/detail/numbers.hpp"

namespace cellforge::io::detail {

constexpr bool is_blank(char c) noexcept { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
constexpr bool is_eol(char c) noexcept { return c == '\n' || c == '\r'; }

/// 1-based line of position `at` in `text`; "\r\n", "\n" and a lone "\r" each end a line. O(at).
template <class = void>
std::uint64_t line_of(std::string_view text, std::size_t at) noexcept {
  at = std::min(at, text.size());
  std::uint64_t line = 1;
  for (std::size_t i = 0; i < at; ++i) {
    if (text[i] == '\n' || (text[i] == '\r' && (i + 1 >= text.size() || text[i + 1] != '\n'))) ++line;
  }
  return line;
}

/// Quotes the token starting at p for an error message, cut to a readable length.
template <class = void>
std::string quote_token(const char* p, const char* end) {
  const char* q = p;
  while (q != end && !is_blank(*q) && !is_eol(*q) && q - p < 32) ++q;
  std::string s = "'";
  for (const char* c = p; c != q; ++c) {
    const auto u = static_cast<unsigned char>(*c);
    if (u >= 0x20 && u < 0x7f) {
      s += *c;
    } else {
      constexpr char hex[] = "0123456789abcdef";
      s += "\\x";
      s += hex[u >> 4];
      s += hex[u & 15];
    }
  }
  if (q != end && !is_blank(*q) && !is_eol(*q)) s += "...";
  return s + "'";
}

template <class = void>
struct basic_text_cursor;
using text_cursor = basic_text_cursor<>;

/// Reads a line-oriented text buffer: blanks, line ends, comments, numbers, tokens.
template <class>
struct basic_text_cursor {
  const char* begin;
  const char* pos;
  const char* end;
  std::string_view name;      ///< file name for error messages
  char comment = '#';         ///< starts a comment running to the end of the line; '\0' for none
  bool continuation = false;  ///< a '\' right before a line end joins the next line (OBJ)

  basic_text_cursor(std::string_view text, std::string_view file_name, char comment_char = '#',
                    bool line_continuation = false) noexcept
      : begin(text.data()),
        pos(text.data()),
        end(text.data() + text.size()),
        name(file_name),
        comment(comment_char),
        continuation(line_continuation) {}

  bool at_end() const noexcept { return pos == end; }

  /// Skips spaces and tabs on the current line (and '\'-newline pairs when enabled). O(skipped).
  void skip_blanks() noexcept {
    for (;;) {
      while (pos != end && is_blank(*pos)) ++pos;
      if (!continuation || pos == end || *pos != '\\') return;
      const char* q = pos + 1;
      while (q != end && is_blank(*q)) ++q;
      if (q == end || !is_eol(*q)) return;
      pos = skip_eol(q);
    }
  }

  /// True at the end of the current line's content: a line end, a comment or the end.
  bool at_line_end() const noexcept {
    return pos == end || is_eol(*pos) || (*pos == comment && comment != '\0');
  }

  /// True when the token just read is complete (followed by a blank, a line end or a comment).
  bool at_token_end() const noexcept {
    return at_line_end() || is_blank(*pos) || (continuation && *pos == '\\');
  }

  /// Moves past the end of the current line (whatever remains on it). O(rest of line).
  void next_line() noexcept {
    while (pos != end && !is_eol(*pos)) ++pos;
    if (pos != end) pos = skip_eol(pos);
  }

  /// Skips blank and comment-only lines; true when positioned on content, false at the end.
  bool next_content() noexcept {
    for (;;) {
      skip_blanks();
      if (pos == end) return false;
      if (!at_line_end()) return true;
      next_line();
    }
  }

  /// The token at the cursor, quoted, for error messages.
  std::string token() const {
    return pos == end     ? std::string("end of file")
           : is_eol(*pos) ? std::string("end of line")
                          : quote_token(pos, end);
  }

  /// Where the content of the buffer ends: errors "before end of file" point at the last line with content.
  const char* content_end() const noexcept {
    const char* q = end;
    while (q != begin && (is_blank(q[-1]) || is_eol(q[-1]))) --q;
    return q;
  }

  [[noreturn]] void fail_at(const char* at, const std::string& message) const {
    throw error(error_category::io, message,
                source_location{std::string(name), line_of({begin, static_cast<std::size_t>(end - begin)},
                                                           static_cast<std::size_t>(at - begin))});
  }
  [[noreturn]] void fail(const std::string& message) const { fail_at(pos, message); }

  /// Reads one number of type T from the current line. `what` (a callable returning a
  /// string, called only on failure) names the value for the error, e.g. "the vertex count".
  template <class T, class What>
  T number(What&& what) {
    skip_blanks();
    if (at_line_end()) fail(cellforge::detail::cat("expected ", what(), ", found ", token()));
    const char* start = pos;
    T value{};
    const parse_status s = parse_number(pos, end, value);
    if (s == parse_status::bad || !at_token_end()) {
      pos = start;
      fail(cellforge::detail::cat("expected ", what(), ", found ", token()));
    }
    if (s == parse_status::out_of_range) {
      pos = start;
      fail(what() + " " + token() + " is out of range");
    }
    return value;
  }

  /// Reads a coordinate for a point with scalar S: parsed, then checked finite and representable.
  template <class S, class What>
  S coordinate(What&& what) {
    const char* start = pos;
    const auto value = number<text_coordinate_t<S>>(what);
    S out{};
    if (!convert_coordinate(value, out)) {
      pos = start;
      skip_blanks();
      fail(what() + " " + token() +
           (std::isfinite(static_cast<double>(value))
                ? " does not fit the point's scalar type"
                : " is not finite (NaN and Inf coordinates are rejected)"));
    }
    return out;
  }

  /// Reads a count or an index as a signed 64-bit value, so "-3" gives a clear message
  /// instead of "not a number". The caller checks the range.
  template <class What>
  std::int64_t integer(What&& what) {
    return number<std::int64_t>(what);
  }

 private:
  const char* skip_eol(const char* q) const noexcept {
    if (*q == '\r' && q + 1 != end && q[1] == '\n') return q + 2;
    return q + 1;
  }
};

}  // namespace cellforge::io::detail
