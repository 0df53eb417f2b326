// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// OFF (Object File Format) reading and writing for polygon soups. ASCII only; the
/// `OFF`, `COFF`, `NOFF`, `CNOFF`, `STOFF` ... headers are read with their extra vertex
/// values (normals, colours, texture coordinates) checked and skipped. See docs/formats.md.

#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/io/detail/face_checks.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"

namespace cellforge::io {

/// How OFF files are read.
struct off_read_options {
  /// Accept faces that use a vertex twice (degenerate faces); by default they are an error.
  bool allow_repeated_vertices = false;
};

/// How OFF files are written.
struct off_write_options {
  /// Written as '#' comment lines after the header when not empty (one per line of text).
  std::string comment{};
};

namespace detail {

/// The vertex layout an OFF header keyword announces.
struct off_header {
  bool colours = false;    // C: r g b [a] after the position (and normal)
  bool normals = false;    // N: nx ny nz after the position
  bool texcoords = false;  // ST: s t at the end
  std::size_t min_values() const noexcept {
    return 3 + (normals ? 3 : 0) + (colours ? 3 : 0) + (texcoords ? 2 : 0);
  }
  std::size_t max_values() const noexcept { return min_values() + (colours ? 1 : 0); }
};

/// Parses the header keyword at the cursor ([ST][C][N][4][n]OFF) or fails with what is accepted.
template <class = void>
off_header parse_off_keyword(text_cursor& c) {
  const char* start = c.pos;
  const char* q = c.pos;
  off_header h;
  const auto take = [&](std::string_view s) {
    if (static_cast<std::size_t>(c.end - q) >= s.size() && std::string_view(q, s.size()) == s) {
      q += s.size();
      return true;
    }
    return false;
  };
  h.texcoords = take("ST");
  h.colours = take("C");
  h.normals = take("N");
  const bool four = take("4");
  const bool n_dim = take("n");
  if (!take("OFF") || (q != c.end && !is_blank(*q) && !is_eol(*q) && *q != '#'))
    c.fail(cellforge::detail::cat(
        "expected an OFF header ('OFF', 'COFF', 'NOFF', 'CNOFF', 'STOFF', ...), found ", c.token()));
  if (four || n_dim)
    c.fail(cellforge::detail::cat("4D and n-dimensional OFF (", quote_token(start, c.end),
                                  ") are not supported"));
  c.pos = q;
  c.skip_blanks();
  if (!c.at_line_end() && static_cast<std::size_t>(c.end - c.pos) >= 6 &&
      std::string_view(c.pos, 6) == "BINARY")
    c.fail("binary OFF is not supported; convert the file to ASCII OFF or PLY");
  return h;
}

/// Reads a non-negative count that must fit a 32-bit index.
template <class What>
std::uint32_t read_count(text_cursor& c, What&& what) {
  c.skip_blanks();
  const char* start = c.pos;
  const std::int64_t n = c.integer(what);
  if (n < 0) c.fail_at(start, what() + " must not be negative, found " + std::to_string(n));
  if (n >= std::int64_t{std::numeric_limits<std::uint32_t>::max()})
    c.fail_at(start, what() + " " + std::to_string(n) + " exceeds the 32-bit limit");
  return static_cast<std::uint32_t>(n);
}

}  // namespace detail

/// Parses OFF text held in memory; `name` is used in error messages. Throws an io error
/// with file and line on malformed input. O(size of the text).
template <Point3 P>
polygon_soup<P> parse_off(std::string_view bytes, std::string_view name = "<memory>",
                          const off_read_options& options = {}) {
  using S = scalar_t<P>;
  detail::text_cursor c(bytes, name, '#');
  if (bytes.starts_with("\xEF\xBB\xBF")) c.pos += 3;  // a UTF-8 byte-order mark some editors add
  if (!c.next_content())
    c.fail_at(c.content_end(),
              "empty file: expected an OFF header ('OFF') followed by the vertex and face counts");

  // The keyword is optional (Geomview): a file may start right at the counts.
  detail::off_header header;
  const char* digits_end = c.pos;
  while (digits_end != c.end && *digits_end >= '0' && *digits_end <= '9') ++digits_end;
  if (digits_end == c.pos || !(digits_end == c.end || detail::is_blank(*digits_end) ||
                               detail::is_eol(*digits_end) || *digits_end == '#')) {
    header = detail::parse_off_keyword(c);
    if (c.at_line_end() && !c.next_content())
      c.fail_at(c.content_end(),
                "expected the vertex, face and edge counts after the header, found end of file");
  }
  const std::uint32_t nv = detail::read_count(c, [] { return std::string("the vertex count"); });
  const std::uint32_t nf = detail::read_count(c, [] { return std::string("the face count"); });
  c.skip_blanks();
  if (!c.at_line_end()) (void)detail::read_count(c, [] { return std::string("the edge count"); });
  c.skip_blanks();
  if (!c.at_line_end())
    c.fail(cellforge::detail::cat("unexpected ", c.token(), " after the vertex, face and edge counts"));

  polygon_soup<P> soup;
  const auto left = static_cast<std::size_t>(c.end - c.pos);
  // The shortest vertex line is "0 0 0\n" and the shortest face "3 0 1 2\n".
  soup.reserve(detail::plausible_count(nv, left, 6), detail::plausible_count(nf, left, 8),
               detail::plausible_count(std::uint64_t{nf} * 3, left, 2));

  const std::size_t min_values = header.min_values(), max_values = header.max_values();
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (!c.next_content())
      c.fail_at(c.content_end(), cellforge::detail::cat("expected ", std::to_string(nv), " vertices, found ",
                                                        std::to_string(v), " before end of file"));
    const char* line = c.pos;
    const S x =
        c.coordinate<S>([&] { return cellforge::detail::cat("coordinate x of vertex ", std::to_string(v)); });
    const S y =
        c.coordinate<S>([&] { return cellforge::detail::cat("coordinate y of vertex ", std::to_string(v)); });
    const S z =
        c.coordinate<S>([&] { return cellforge::detail::cat("coordinate z of vertex ", std::to_string(v)); });
    c.skip_blanks();
    if (!c.at_line_end() || min_values != 3) {
      std::size_t values = 3;
      for (; !c.at_line_end(); c.skip_blanks(), ++values) {
        if (values == max_values) {
          c.fail(cellforge::detail::cat(
              "vertex ", std::to_string(v), " has more than ", std::to_string(max_values),
              " values: unexpected ", c.token(),
              (max_values == 3 ? " (colours or normals need a COFF or NOFF header)" : "")));
        }
        (void)c.number<double>(
            [&] { return cellforge::detail::cat("a number after vertex ", std::to_string(v)); });
      }
      if (values < min_values)
        c.fail_at(
            line,
            cellforge::detail::cat(
                "vertex ", std::to_string(v), " has ", std::to_string(values),
                " values; this OFF variant needs ", std::to_string(min_values),
                (max_values > min_values ? cellforge::detail::cat(" or ", std::to_string(max_values)) : "")));
    }
    soup.points.push_back(point_traits<P>::make(x, y, z));
    c.next_line();
  }

  std::vector<std::uint32_t> scratch;
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (!c.next_content())
      c.fail_at(c.content_end(), cellforge::detail::cat("expected ", std::to_string(nf), " faces, found ",
                                                        std::to_string(f), " before end of file"));
    const char* line = c.pos;
    const std::int64_t k =
        c.integer([&] { return cellforge::detail::cat("the vertex count of face ", std::to_string(f)); });
    if (k < 3)
      c.fail_at(line, cellforge::detail::cat("face ", std::to_string(f), " has ", std::to_string(k),
                                             " vertices; a face needs at least 3"));
    const std::size_t first = soup.face_vertices.size();
    for (std::int64_t i = 0; i < k; ++i) {
      c.skip_blanks();
      const char* at = c.pos;
      const std::int64_t idx = c.integer([&] {
        return cellforge::detail::cat("vertex ", std::to_string(i), " of face ", std::to_string(f));
      });
      if (idx < 0 || idx >= std::int64_t{nv}) {
        c.fail_at(at,
                  cellforge::detail::cat(
                      "face ", std::to_string(f), ": vertex index ", std::to_string(idx), " out of range ",
                      (nv == 0 ? std::string("(the file has no vertices)")
                               : cellforge::detail::cat("(0..", std::to_string(nv - 1), ")"))));
      }
      soup.face_vertices.push_back(static_cast<std::uint32_t>(idx));
    }
    // An optional colour follows: a colour-map index or 3 or 4 components.
    c.skip_blanks();
    for (int values = 0; !c.at_line_end(); c.skip_blanks(), ++values) {
      if (values == 4)
        c.fail(cellforge::detail::cat("face ", std::to_string(f), " has more values after its ",
                                      std::to_string(k),
                                      " vertex indices than a colour (at most 4): unexpected ", c.token()));
      (void)c.number<double>(
          [&] { return cellforge::detail::cat("a colour value after face ", std::to_string(f)); });
    }
    if (const auto problem =
            detail::close_face(soup, first, options.allow_repeated_vertices, scratch, 0, "off_read_options"))
      c.fail_at(line, cellforge::detail::cat("face ", std::to_string(f), " ", *problem));
    c.next_line();
  }
  if (c.next_content())
    c.fail(cellforge::detail::cat("unexpected ", c.token(), " after the last of ", std::to_string(nf),
                                  " faces (the header's face count)"));
  return soup;
}

/// Reads an OFF file. Throws an io error naming the path when it cannot be read, or with
/// file and line when it is malformed. O(file size).
template <Point3 P>
polygon_soup<P> read_off(const file_path& path, const off_read_options& options = {}) {
  const std::string bytes = detail::read_file(path);
  return parse_off<P>(bytes, detail::display_name(path), options);
}

/// Writes a soup as ASCII OFF, numbers in shortest round-trip form so reading gives the
/// same points bit for bit. Throws invalid_input on NaN/Inf points or bad indices. O(size).
template <Point3 P>
void write_off(std::ostream& os, const polygon_soup<P>& soup, const off_write_options& options = {}) {
  detail::check_face_indices(soup, "off");
  detail::output_buffer out(os);
  out.put("OFF\n");
  detail::put_comment_lines(out, options.comment, "# ");
  out.number(soup.points.size());
  out.put(' ');
  out.number(soup.num_faces());
  out.put(" 0\n");
  for (std::size_t i = 0; i < soup.points.size(); ++i) {
    const P& p = soup.points[i];
    detail::check_point_finite(p, i, "off");
    out.number(coord(p, 0));
    out.put(' ');
    out.number(coord(p, 1));
    out.put(' ');
    out.number(coord(p, 2));
    out.put('\n');
  }
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto face = soup.face(f);
    out.number(face.size());
    for (const std::uint32_t v : face) {
      out.put(' ');
      out.number(v);
    }
    out.put('\n');
  }
  out.finish("OFF");
}

/// Writes a soup to an OFF file (see the stream overload). Throws an io error naming the
/// path when it cannot be written. O(size).
template <Point3 P>
void write_off(const file_path& path, const polygon_soup<P>& soup, const off_write_options& options = {}) {
  detail::write_file(path, [&](std::ostream& os) { write_off(os, soup, options); });
}

}  // namespace cellforge::io
