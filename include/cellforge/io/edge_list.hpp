// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The plain edge-list wireframe format: `vertices N`, N lines `x y z`, `edges M`, M lines
/// `i j` (0-based vertex indices), `#` comments. See docs/formats.md ("Edge list").

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/io/detail/face_checks.hpp"
#include "cellforge/io/detail/numbers.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"

namespace cellforge::io {

/// How edge lists are read.
struct edge_list_read_options {
  /// Accept an edge given twice (either direction); the pipeline then reports it. Off: an error.
  bool allow_duplicate_edges = false;
  /// Accept an edge from a vertex to itself. Off: an error.
  bool allow_self_loops = false;
};

/// How edge lists are written.
struct edge_list_write_options {
  /// Written as '#' comment lines at the top when not empty.
  std::string comment{};
};

namespace detail {

/// Reads the keyword `expected` followed by a count that fits a 32-bit index, alone on its line.
template <class What>
std::uint32_t read_section_header(text_cursor& c, std::string_view expected, What&& what) {
  const char* start = c.pos;
  while (!c.at_token_end()) ++c.pos;
  if (std::string_view(start, static_cast<std::size_t>(c.pos - start)) != expected) {
    c.pos = start;
    c.fail(cellforge::detail::cat("expected '", std::string(expected), " <count>', found ", c.token()));
  }
  c.skip_blanks();
  const char* at = c.pos;
  const std::int64_t n = c.integer(what);
  if (n < 0) c.fail_at(at, what() + " must not be negative, found " + std::to_string(n));
  if (n >= std::int64_t{std::numeric_limits<std::uint32_t>::max()})
    c.fail_at(at, what() + " " + std::to_string(n) + " exceeds the 32-bit limit");
  c.skip_blanks();
  if (!c.at_line_end()) c.fail(cellforge::detail::cat("unexpected ", c.token(), " after ", what()));
  c.next_line();
  return static_cast<std::uint32_t>(n);
}

/// Moves to the next content line or fails naming what was expected there.
template <class = void>
void expect_line(text_cursor& c, const std::string& expected) {
  if (!c.next_content())
    c.fail_at(c.content_end(), cellforge::detail::cat("expected ", expected, ", found end of file"));
}

}  // namespace detail

/// Parses edge-list text held in memory; `name` is used in error messages. Throws an io error
/// with file and line on malformed input. O(size of the text + E log E for the duplicate check).
template <Point3 P>
wireframe<P> parse_edge_list(std::string_view bytes, std::string_view name = "<memory>",
                             const edge_list_read_options& options = {}) {
  using S = scalar_t<P>;
  detail::text_cursor c(bytes, name, '#');
  if (bytes.starts_with("\xEF\xBB\xBF")) c.pos += 3;  // a byte-order mark some editors add
  if (!c.next_content())
    c.fail_at(
        c.content_end(),
        "empty file: expected 'vertices <count>', the vertex lines, 'edges <count>' and the edge lines");
  const std::uint32_t nv =
      detail::read_section_header(c, "vertices", [] { return std::string("the vertex count"); });
  wireframe<P> w;
  const auto left = [&] { return static_cast<std::size_t>(c.end - c.pos); };
  // Reserve no more than the rest of the file can hold ("0 0 0\n" and "0 1\n" are the shortest lines).
  w.points.reserve(detail::plausible_count(nv, left(), 6));
  for (std::uint32_t v = 0; v < nv; ++v) {
    detail::expect_line(c, cellforge::detail::cat("vertex ", std::to_string(v), " of ", std::to_string(nv)));
    // The edges section arriving early is the likeliest mistake: say so rather than "expected a number".
    const bool edges_keyword = static_cast<std::size_t>(c.end - c.pos) >= 5 &&
                               std::string_view(c.pos, 5) == "edges" &&
                               (c.end - c.pos == 5 || detail::is_blank(c.pos[5]) || detail::is_eol(c.pos[5]));
    if (edges_keyword)
      c.fail(cellforge::detail::cat("found 'edges' after ", std::to_string(v),
                                    " vertices; the 'vertices' count says ", std::to_string(nv)));
    const S x =
        c.coordinate<S>([&] { return cellforge::detail::cat("coordinate x of vertex ", std::to_string(v)); });
    const S y =
        c.coordinate<S>([&] { return cellforge::detail::cat("coordinate y of vertex ", std::to_string(v)); });
    const S z =
        c.coordinate<S>([&] { return cellforge::detail::cat("coordinate z of vertex ", std::to_string(v)); });
    c.skip_blanks();
    if (!c.at_line_end())
      c.fail(cellforge::detail::cat("vertex ", std::to_string(v), " has more than 3 coordinates: unexpected ",
                                    c.token()));
    w.points.push_back(point_traits<P>::make(x, y, z));
    c.next_line();
  }
  detail::expect_line(c,
                      cellforge::detail::cat("'edges <count>' after the ", std::to_string(nv), " vertices"));
  const std::uint32_t ne =
      detail::read_section_header(c, "edges", [] { return std::string("the edge count"); });
  w.edges.reserve(detail::plausible_count(ne, left(), 4));
  std::vector<const char*> line_of_edge;  // for naming the line of a duplicate after sorting
  if (!options.allow_duplicate_edges) line_of_edge.reserve(w.edges.capacity());
  for (std::uint32_t e = 0; e < ne; ++e) {
    detail::expect_line(c, cellforge::detail::cat("edge ", std::to_string(e), " of ", std::to_string(ne)));
    const char* line = c.pos;
    std::array<std::uint32_t, 2> ends{};
    for (int k = 0; k < 2; ++k) {
      c.skip_blanks();
      const char* at = c.pos;
      const std::int64_t i = c.integer([&] {
        return cellforge::detail::cat(std::string(k == 0 ? "the first" : "the second"),
                                      " vertex index of edge ", std::to_string(e));
      });
      if (i < 0 || i >= std::int64_t{nv})
        c.fail_at(at, cellforge::detail::cat("edge ", std::to_string(e), ": vertex index ", std::to_string(i),
                                             " out of range ",
                                             (nv == 0 ? std::string("(the file has no vertices)")
                                                      : cellforge::detail::cat("(0..", std::to_string(nv - 1),
                                                                               "; indices are 0-based)"))));
      ends[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(i);
    }
    c.skip_blanks();
    if (!c.at_line_end())
      c.fail(cellforge::detail::cat("edge ", std::to_string(e),
                                    " has more than 2 vertex indices: unexpected ", c.token()));
    if (ends[0] == ends[1] && !options.allow_self_loops)
      c.fail_at(line,
                cellforge::detail::cat("edge ", std::to_string(e), " joins vertex ", std::to_string(ends[0]),
                                       " to itself (edge_list_read_options::allow_self_loops accepts it)"));
    w.edges.push_back(ends);
    if (!options.allow_duplicate_edges) line_of_edge.push_back(line);
    c.next_line();
  }
  if (c.next_content())
    c.fail(cellforge::detail::cat("unexpected ", c.token(), " after the last of ", std::to_string(ne),
                                  " edges (the 'edges' count)"));
  if (!options.allow_duplicate_edges && ne > 1) {
    // Sort (min, max, index) and name the later of the first duplicate pair found.
    std::vector<std::array<std::uint32_t, 3>> keys(ne);
    for (std::uint32_t e = 0; e < ne; ++e)
      keys[e] = {std::min(w.edges[e][0], w.edges[e][1]), std::max(w.edges[e][0], w.edges[e][1]), e};
    std::sort(keys.begin(), keys.end());
    std::uint32_t worst = ne, first = ne;
    for (std::size_t i = 1; i < keys.size(); ++i)
      if (keys[i][0] == keys[i - 1][0] && keys[i][1] == keys[i - 1][1] && keys[i][2] < worst) {
        worst = keys[i][2];
        first = keys[i - 1][2];
      }
    if (worst != ne)
      c.fail_at(line_of_edge[worst],
                cellforge::detail::cat(
                    "edge ", std::to_string(worst), " repeats edge ", std::to_string(first), " (vertices ",
                    std::to_string(w.edges[worst][0]), " and ", std::to_string(w.edges[worst][1]),
                    "; edge_list_read_options::allow_duplicate_edges accepts it)"));
  }
  return w;
}

/// Reads an edge-list file. Throws an io error naming the path when it cannot be read, or with
/// file and line when it is malformed. O(file size + E log E).
template <Point3 P>
wireframe<P> read_edge_list(const file_path& path, const edge_list_read_options& options = {}) {
  const std::string bytes = detail::read_file(path);
  return parse_edge_list<P>(bytes, detail::display_name(path), options);
}

/// Writes any Wireframe as an edge list, numbers in shortest round-trip form so reading gives
/// the same points bit for bit. Throws invalid_input on a non-finite point or an index out of
/// range (a file the reader would reject). O(V + E).
template <Wireframe G>
void write_edge_list(std::ostream& os, const G& g, const edge_list_write_options& options = {}) {
  using T = wireframe_traits<G>;
  const std::size_t nv = T::num_vertices(g), ne = T::num_edges(g);
  if (nv >= std::numeric_limits<std::uint32_t>::max() || ne >= std::numeric_limits<std::uint32_t>::max())
    throw error(error_category::invalid_input, "write_edge_list: more than 2^32 - 2 vertices or edges");
  detail::output_buffer out(os);
  detail::put_comment_lines(out, options.comment, "# ");
  out.put("vertices ");
  out.number(nv);
  out.put('\n');
  for (std::size_t v = 0; v < nv; ++v) {
    const auto p = T::position(g, v);
    detail::check_point_finite(p, v, "edge_list");
    for (std::size_t k = 0; k < 3; ++k) {
      if (k != 0) out.put(' ');
      out.number(coord(p, k));
    }
    out.put('\n');
  }
  out.put("edges ");
  out.number(ne);
  out.put('\n');
  for (std::size_t e = 0; e < ne; ++e) {
    const auto ab = T::endpoints(g, e);
    if (ab[0] >= nv || ab[1] >= nv)
      throw error(
          error_category::invalid_input,
          cellforge::detail::cat("write_edge_list: edge ", std::to_string(e),
                                 " has a vertex index out of range (", std::to_string(nv), " vertices)"));
    out.number(ab[0]);
    out.put(' ');
    out.number(ab[1]);
    out.put('\n');
  }
  out.finish("edge list");
}

/// Writes an edge-list file; io errors name the path. O(V + E).
template <Wireframe G>
void write_edge_list(const file_path& path, const G& g, const edge_list_write_options& options = {}) {
  detail::write_file(path, [&](std::ostream& os) { write_edge_list(os, g, options); });
}

}  // namespace cellforge::io
