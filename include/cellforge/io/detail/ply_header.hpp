// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The PLY header: formats, scalar types, elements and their properties, parsed and
/// checked before any data is read so that the data loop can trust the layout.

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/io/detail/text_cursor.hpp"

namespace cellforge::io {

/// PLY body encodings.
enum class ply_format : std::uint8_t { ascii, binary_little_endian, binary_big_endian };

}  // namespace cellforge::io

namespace cellforge::io::detail {

/// PLY scalar types, in the order of their size.
enum class ply_type : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

constexpr std::size_t size_of(ply_type t) noexcept {
  switch (t) {
    case ply_type::int8:
    case ply_type::uint8:
      return 1;
    case ply_type::int16:
    case ply_type::uint16:
      return 2;
    case ply_type::int32:
    case ply_type::uint32:
    case ply_type::float32:
      return 4;
    case ply_type::float64:
      return 8;
  }
  return 8;
}

constexpr bool is_integral(ply_type t) noexcept { return t != ply_type::float32 && t != ply_type::float64; }

/// Calls f(std::type_identity<T>{}) with the C++ type of a PLY scalar type.
template <class F>
decltype(auto) with_ply_type(ply_type t, F&& f) {
  switch (t) {
    case ply_type::int8:
      return f(std::type_identity<std::int8_t>{});
    case ply_type::uint8:
      return f(std::type_identity<std::uint8_t>{});
    case ply_type::int16:
      return f(std::type_identity<std::int16_t>{});
    case ply_type::uint16:
      return f(std::type_identity<std::uint16_t>{});
    case ply_type::int32:
      return f(std::type_identity<std::int32_t>{});
    case ply_type::uint32:
      return f(std::type_identity<std::uint32_t>{});
    case ply_type::float32:
      return f(std::type_identity<float>{});
    case ply_type::float64:
      break;
  }
  return f(std::type_identity<double>{});
}

/// Both spellings of the PLY type names (the original and the sized ones).
template <class = void>
std::optional<ply_type> parse_ply_type(std::string_view s) noexcept {
  struct entry {
    std::string_view a, b;
    ply_type t;
  };
  constexpr entry names[] = {
      {"char", "int8", ply_type::int8},        {"uchar", "uint8", ply_type::uint8},
      {"short", "int16", ply_type::int16},     {"ushort", "uint16", ply_type::uint16},
      {"int", "int32", ply_type::int32},       {"uint", "uint32", ply_type::uint32},
      {"float", "float32", ply_type::float32}, {"double", "float64", ply_type::float64}};
  for (const auto& e : names)
    if (s == e.a || s == e.b) return e.t;
  return std::nullopt;
}

/// The name cellforge writes for a type (the original spelling, read by every tool).
constexpr std::string_view ply_type_name(ply_type t) noexcept {
  constexpr std::string_view names[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double"};
  return names[static_cast<int>(t)];
}

/// The PLY type that holds a C++ arithmetic type exactly, if there is one.
template <class T>
constexpr std::optional<ply_type> ply_type_of() noexcept {
  if constexpr (std::is_same_v<T, float>)
    return ply_type::float32;
  else if constexpr (std::is_same_v<T, double>)
    return ply_type::float64;
  else if constexpr (std::is_integral_v<T> && std::is_signed_v<T> && sizeof(T) == 1)
    return ply_type::int8;
  else if constexpr (std::is_integral_v<T> && std::is_unsigned_v<T> && sizeof(T) == 1)
    return ply_type::uint8;
  else if constexpr (std::is_integral_v<T> && std::is_signed_v<T> && sizeof(T) == 2)
    return ply_type::int16;
  else if constexpr (std::is_integral_v<T> && std::is_unsigned_v<T> && sizeof(T) == 2)
    return ply_type::uint16;
  else if constexpr (std::is_integral_v<T> && std::is_signed_v<T> && sizeof(T) == 4)
    return ply_type::int32;
  else if constexpr (std::is_integral_v<T> && std::is_unsigned_v<T> && sizeof(T) == 4)
    return ply_type::uint32;
  else
    return std::nullopt;
}

struct ply_property {
  std::string name;
  ply_type type = ply_type::float32;  ///< the value type, or the item type of a list
  bool is_list = false;
  ply_type count_type = ply_type::uint8;  ///< lists only
};

struct ply_element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<ply_property> properties;
  const char* declared_at = nullptr;  ///< its header line, for errors about its layout

  /// Bytes one instance takes in binary when it has no lists; 0 when it has lists.
  std::size_t fixed_size() const noexcept {
    std::size_t n = 0;
    for (const auto& p : properties) {
      if (p.is_list) return 0;
      n += size_of(p.type);
    }
    return n;
  }
  /// The fewest bytes one binary instance can take (lists count as empty).
  std::size_t min_size() const noexcept {
    std::size_t n = 0;
    for (const auto& p : properties) n += p.is_list ? size_of(p.count_type) : size_of(p.type);
    return n;
  }
  const ply_property* find(std::string_view prop) const noexcept {
    for (const auto& p : properties)
      if (p.name == prop) return &p;
    return nullptr;
  }
};

struct ply_header {
  ply_format format = ply_format::ascii;
  std::vector<ply_element> elements;
  std::size_t data_offset = 0;  ///< first byte after the end_header line
};

/// Reads a header token (up to a blank or line end), failing with `expected` when there is none.
template <class = void>
std::string_view header_token(text_cursor& c, std::string_view expected) {
  c.skip_blanks();
  if (c.at_line_end())
    c.fail(cellforge::detail::cat("expected ", std::string(expected), ", found ", c.token()));
  const char* start = c.pos;
  while (!c.at_token_end()) ++c.pos;
  return {start, static_cast<std::size_t>(c.pos - start)};
}

template <class = void>
ply_type header_type(text_cursor& c, std::string_view expected) {
  const std::string_view name = header_token(c, expected);
  const auto t = parse_ply_type(name);
  if (!t) {
    c.fail_at(name.data(),
              cellforge::detail::cat("unknown property type ", quote_token(name.data(), c.end),
                                     " (expected char, uchar, short, ushort, int, uint, float, double or "
                                     "int8, uint8, int16, uint16, int32, uint32, float32, float64)"));
  }
  return *t;
}

template <class = void>
void header_line_end(text_cursor& c, std::string_view after) {
  c.skip_blanks();
  if (!c.at_line_end())
    c.fail(cellforge::detail::cat("unexpected ", c.token(), " after ", std::string(after)));
  c.next_line();
}

/// Parses and checks a PLY header. The cursor is left on the first data byte. O(header size).
template <class = void>
ply_header parse_ply_header(text_cursor& c) {
  ply_header h;
  if (c.at_end()) c.fail("empty file: expected 'ply' on the first line");
  {
    const char* start = c.pos;
    while (!c.at_token_end()) ++c.pos;
    if (std::string_view(start, static_cast<std::size_t>(c.pos - start)) != "ply") {
      c.pos = start;
      c.fail(cellforge::detail::cat("not a PLY file: expected 'ply' on the first line, found ", c.token()));
    }
    header_line_end(c, "'ply'");
  }
  bool have_format = false;
  for (;;) {
    if (c.at_end()) c.fail_at(c.content_end(), "the header has no 'end_header' line");
    c.skip_blanks();
    if (c.at_line_end()) {  // tolerate blank header lines
      c.next_line();
      continue;
    }
    const char* line = c.pos;
    const std::string_view key = header_token(c, "a header keyword");
    if (key == "end_header") {
      c.skip_blanks();
      if (!c.at_line_end()) c.fail(cellforge::detail::cat("unexpected ", c.token(), " after 'end_header'"));
      // Exactly one line end: in binary files the next byte is already data.
      if (!c.at_end() && *c.pos == '\r') ++c.pos;
      if (!c.at_end() && *c.pos == '\n') ++c.pos;
      break;
    }
    if (key == "comment" || key == "obj_info") {
      c.next_line();
    } else if (key == "format") {
      if (have_format) c.fail_at(line, "a second 'format' line");
      have_format = true;
      const char* at = c.pos;
      const std::string_view f =
          header_token(c, "a format (ascii, binary_little_endian or binary_big_endian)");
      if (f == "ascii")
        h.format = ply_format::ascii;
      else if (f == "binary_little_endian")
        h.format = ply_format::binary_little_endian;
      else if (f == "binary_big_endian")
        h.format = ply_format::binary_big_endian;
      else {
        c.pos = at;
        c.skip_blanks();
        c.fail(cellforge::detail::cat("unknown PLY format ", c.token(),
                                      " (expected ascii, binary_little_endian or binary_big_endian)"));
      }
      c.skip_blanks();
      const char* vat = c.pos;
      const double version = c.number<double>([] { return std::string("the format version (1.0)"); });
      if (version != 1.0)
        c.fail_at(vat, cellforge::detail::cat("unsupported PLY version ", quote_token(vat, c.end),
                                              " (only 1.0 is defined)"));
      header_line_end(c, "the format version");
    } else if (key == "element") {
      ply_element e;
      e.declared_at = line;
      e.name = std::string(header_token(c, "an element name"));
      c.skip_blanks();
      const char* at = c.pos;
      const std::int64_t n =
          c.integer([&] { return cellforge::detail::cat("the count of element '", e.name, "'"); });
      if (n < 0)
        c.fail_at(at, cellforge::detail::cat("the count of element '", e.name,
                                             "' must not be negative, found ", std::to_string(n)));
      e.count = static_cast<std::uint64_t>(n);
      for (const auto& other : h.elements)
        if (other.name == e.name)
          c.fail_at(line, cellforge::detail::cat("element '", e.name, "' is declared twice"));
      h.elements.push_back(std::move(e));
      header_line_end(c, "the element count");
    } else if (key == "property") {
      if (h.elements.empty()) c.fail_at(line, "'property' before any 'element' line");
      ply_property p;
      c.skip_blanks();
      if (std::string_view(c.pos, static_cast<std::size_t>(c.end - c.pos)).starts_with("list") &&
          (c.pos + 4 == c.end || is_blank(c.pos[4]))) {
        c.pos += 4;
        p.is_list = true;
        c.skip_blanks();
        const char* at = c.pos;
        p.count_type = header_type(c, "the list count type");
        if (!is_integral(p.count_type))
          c.fail_at(at, cellforge::detail::cat("a list count type must be an integer type, found ",
                                               quote_token(at, c.end)));
      }
      p.type = header_type(c, "a property type");
      p.name = std::string(header_token(c, "a property name"));
      auto& e = h.elements.back();
      if (e.find(p.name))
        c.fail_at(line, cellforge::detail::cat("property '", p.name, "' of element '", e.name,
                                               "' is declared twice"));
      e.properties.push_back(std::move(p));
      header_line_end(c, "the property name");
    } else {
      c.fail_at(line, cellforge::detail::cat(
                          "unknown header line starting with ", quote_token(line, c.end),
                          " (expected format, element, property, comment, obj_info or end_header)"));
    }
  }
  if (!have_format) c.fail_at(c.begin, "the header has no 'format' line");
  for (const auto& e : h.elements) {
    if (e.count > 0 && e.properties.empty())
      c.fail_at(e.declared_at, cellforge::detail::cat("element '", e.name, "' has ", std::to_string(e.count),
                                                      " instances but no properties"));
  }
  h.data_offset = static_cast<std::size_t>(c.pos - c.begin);
  return h;
}

}  // namespace cellforge::io::detail
