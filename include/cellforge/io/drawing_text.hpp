// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The plain text format of line drawings: `j x y` a junction (numbered from 0 in file order),
/// `e a b` an edge between two junction indices, `#` comments and blank lines; `a` is kept for
/// arcs. See docs/formats.md ("Line drawing text").

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge::io {

/// How line drawings are written as text.
struct drawing_text_write_options {
  /// Written as '#' comment lines at the top when not empty.
  std::string comment{};
};

/// Parses line-drawing text held in memory; `name` is used in error messages. Edges may name
/// junctions defined later in the file. Throws an io error with file and line on malformed input
/// (unknown keyword, bad or missing number, trailing junk, NaN/Inf, index out of range, an edge
/// from a junction to itself or given twice, arcs). O(size of the text + E log E).
template <Point2 P2 = glm::dvec2>
line_drawing<P2> parse_drawing_text(std::string_view text, std::string_view name = "<memory>") {
  using S = scalar2_t<P2>;
  constexpr auto limit = std::numeric_limits<std::uint32_t>::max();
  detail::text_cursor c(text, name, '#');
  if (text.starts_with("\xEF\xBB\xBF")) c.pos += 3;
  line_drawing<P2> d;
  std::vector<const char*> edge_lines;
  std::vector<std::array<std::int64_t, 2>> raw;
  while (c.next_content()) {
    const char* line = c.pos;
    const char* q = c.pos;
    while (!c.at_token_end()) ++c.pos;
    const std::string_view key(q, static_cast<std::size_t>(c.pos - q));
    if (key == "j") {
      const std::size_t i = d.points.size();
      if (i >= limit - 1) c.fail_at(line, "too many junctions for 32-bit indices");
      const S x =
          c.coordinate<S>([&] { return "coordinate x of junction " + std::to_string(i) + " (j x y)"; });
      const S y =
          c.coordinate<S>([&] { return "coordinate y of junction " + std::to_string(i) + " (j x y)"; });
      c.skip_blanks();
      if (!c.at_line_end())
        c.fail("unexpected " + c.token() + " after the 2 coordinates of junction " + std::to_string(i) +
               " (j x y)");
      d.points.push_back(point2_traits<P2>::make(x, y));
    } else if (key == "e") {
      const std::size_t e = raw.size();
      if (e >= limit - 1) c.fail_at(line, "too many edges");
      std::array<std::int64_t, 2> ab{};
      for (int k = 0; k < 2; ++k) {
        c.skip_blanks();
        const char* at = c.pos;
        ab[k] = c.integer([&] {
          return std::string(k == 0 ? "the first" : "the second") + " junction index of edge " +
                 std::to_string(e) + " (e a b)";
        });
        if (ab[k] < 0)
          c.fail_at(at, "junction index " + std::to_string(ab[k]) + " of edge " + std::to_string(e) +
                            " is negative (indices are 0-based)");
      }
      c.skip_blanks();
      if (!c.at_line_end())
        c.fail("unexpected " + c.token() + " after the 2 junction indices of edge " + std::to_string(e) +
               " (e a b)");
      if (ab[0] == ab[1])
        c.fail_at(line,
                  "edge " + std::to_string(e) + " joins junction " + std::to_string(ab[0]) + " to itself");
      raw.push_back(ab);
      edge_lines.push_back(line);
    } else if (key == "a") {
      c.fail_at(line,
                "arcs are not read yet (the rounds-and-fillets stage will read them): draw straight edges");
    } else {
      c.pos = q;
      c.fail("expected 'j x y' (a junction), 'e a b' (an edge) or a '#' comment, found " + c.token());
    }
    c.next_line();
  }
  const std::size_t nv = d.points.size();
  d.edges.reserve(raw.size());
  for (std::size_t e = 0; e < raw.size(); ++e) {
    for (const std::int64_t v : raw[e])
      if (static_cast<std::uint64_t>(v) >= nv)
        c.fail_at(edge_lines[e], "junction index " + std::to_string(v) + " of edge " + std::to_string(e) +
                                     " out of range (" + std::to_string(nv) +
                                     " junctions; indices are 0-based)");
    d.edges.push_back({static_cast<std::uint32_t>(raw[e][0]), static_cast<std::uint32_t>(raw[e][1])});
  }
  std::vector<std::array<std::uint32_t, 3>> keys(d.edges.size());
  for (std::size_t e = 0; e < d.edges.size(); ++e)
    keys[e] = {std::min(d.edges[e][0], d.edges[e][1]), std::max(d.edges[e][0], d.edges[e][1]),
               static_cast<std::uint32_t>(e)};
  std::sort(keys.begin(), keys.end());
  std::uint32_t later = limit, earlier = limit;
  for (std::size_t k = 1; k < keys.size(); ++k)
    if (keys[k][0] == keys[k - 1][0] && keys[k][1] == keys[k - 1][1] && keys[k][2] < later)
      later = keys[k][2], earlier = keys[k - 1][2];
  if (later != limit)
    c.fail_at(edge_lines[later], "edge " + std::to_string(later) + " repeats edge " +
                                     std::to_string(earlier) + " (line " +
                                     std::to_string(detail::line_of(
                                         text, static_cast<std::size_t>(edge_lines[earlier] - text.data()))) +
                                     "; junctions " + std::to_string(d.edges[later][0]) + " and " +
                                     std::to_string(d.edges[later][1]) + ")");
  return d;
}

/// Reads a line-drawing text file. Throws an io error naming the path when it cannot be read, or
/// with file and line when it is malformed. O(file size + E log E).
template <Point2 P2 = glm::dvec2>
line_drawing<P2> read_drawing_text(const std::filesystem::path& path) {
  const std::string bytes = detail::read_file(path);
  return parse_drawing_text<P2>(bytes, detail::display_name(path));
}

namespace detail {

/// Throws invalid_input, prefixed by `writer`, for what the text reader would reject: NaN/Inf
/// positions, out-of-range ends, self loops, repeated edges, 2^32 junctions. O(V + E log E).
template <LineDrawing D>
void check_drawing_writable(const D& d, std::string_view writer) {
  if (line_drawing_traits<D>::num_junctions(d) >= std::numeric_limits<std::uint32_t>::max() - 1)
    throw error(error_category::invalid_input, std::string(writer) + ": more than 2^32 - 2 junctions");
  const drawing_validation v = validate_drawing(d, {.tolerance = 0});
  switch (v.defect) {
    case drawing_defect::bad_position:
    case drawing_defect::endpoint_out_of_range:
    case drawing_defect::self_loop:
    case drawing_defect::duplicate_edge:
      throw error(error_category::invalid_input, std::string(writer) + ": " + v.message);
    default:
      return;
  }
}

/// Writes the lines of a checked drawing. O(V + E).
template <LineDrawing D>
void put_drawing_text(std::ostream& os, const D& d, const drawing_text_write_options& options) {
  using T = line_drawing_traits<D>;
  using P = drawing_point_t<D>;
  output_buffer out(os);
  put_comment_lines(out, options.comment, "# ");
  const std::size_t nv = T::num_junctions(d), ne = T::num_edges(d);
  out.put("# cellforge line drawing: ");
  out.number(nv);
  out.put(" junctions (j x y, numbered from 0), ");
  out.number(ne);
  out.put(" edges (e a b)\n");
  for (std::size_t i = 0; i < nv; ++i) {
    const P p = P(T::position(d, i));
    out.put("j ");
    out.number(point2_traits<P>::get(p, 0));
    out.put(' ');
    out.number(point2_traits<P>::get(p, 1));
    out.put('\n');
  }
  for (std::size_t e = 0; e < ne; ++e) {
    const std::array<std::size_t, 2> ab = T::endpoints(d, e);
    out.put("e ");
    out.number(ab[0]);
    out.put(' ');
    out.number(ab[1]);
    out.put('\n');
  }
  out.finish("line drawing text");
}

}  // namespace detail

/// Writes any LineDrawing as text, numbers in shortest round-trip form (exact round trips).
/// Throws invalid_input, before writing anything, on what the reader would reject. O(V + E log E).
template <LineDrawing D>
void write_drawing_text(std::ostream& os, const D& d, const drawing_text_write_options& options = {}) {
  detail::check_drawing_writable(d, "write_drawing_text");
  detail::put_drawing_text(os, d, options);
}

/// Writes a line-drawing text file (see the stream overload); a drawing the format cannot hold
/// is refused before the file is opened; io errors name the path. O(V + E log E).
template <LineDrawing D>
void write_drawing_text(const std::filesystem::path& path, const D& d,
                        const drawing_text_write_options& options = {}) {
  detail::check_drawing_writable(d, "write_drawing_text");
  detail::write_file(path, [&](std::ostream& os) { detail::put_drawing_text(os, d, options); });
}

/// The text of a drawing as a string (see write_drawing_text). O(V + E log E).
template <LineDrawing D>
std::string drawing_text_string(const D& d, const drawing_text_write_options& options = {}) {
  std::ostringstream os;
  write_drawing_text(os, d, options);
  return os.str();
}

}  // namespace cellforge::io
