// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Wavefront OBJ as a skeleton graph: `v x y z [r]` nodes, the radius a fourth value or one
/// uniform radius for all, and `l a b c ...` polylines as directed edges a -> b -> c.
/// See docs/formats.md ("OBJ skeletons").

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/tubes/skeleton.hpp"

namespace cellforge::io {

/// A skeleton read from OBJ, and what of the file was not part of it.
template <Point3 P>
struct skeleton_obj_data {
  cellforge::skeleton<P> skeleton;       ///< every `v` a node, every `l` segment an edge, in file order
  std::size_t uniform_radius_nodes = 0;  ///< nodes that took skeleton_obj_read_options::uniform_radius
  std::size_t skipped_statements = 0;    ///< unknown statements ignored (not strict)
  std::uint64_t first_skipped_line = 0;  ///< line of the first of them, 0 if none
};

/// How OBJ skeletons are read.
struct skeleton_obj_read_options {
  /// The radius of every `v` without a fourth value (positive); 0: none, and such a `v` is an error.
  double uniform_radius = 0;
  /// Unknown statements are an error instead of being skipped (and counted).
  bool strict = false;
};

/// How OBJ skeletons are written.
struct skeleton_obj_write_options {
  /// Written as '#' comment lines at the top when not empty.
  std::string comment{};
};

/// Parses OBJ text held in memory as a skeleton; `name` is used in error messages. Throws an io
/// error with file and line on malformed input (a missing or bad radius, faces, bad indices,
/// zero-length or repeated segments), invalid_input for a bad uniform_radius. O(size + E log E).
template <Point3 P>
skeleton_obj_data<P> parse_skeleton_obj(std::string_view bytes, std::string_view name = "<memory>",
                                        const skeleton_obj_read_options& options = {}) {
  using S = scalar_t<P>;
  const double uniform = options.uniform_radius;
  if (!(uniform >= 0) || !std::isfinite(uniform))
    throw error(error_category::invalid_input,
                cellforge::detail::cat(
                    "skeleton_obj_read_options::uniform_radius must be positive (or 0 for none), found ",
                    cellforge::detail::skeleton_number(uniform)));
  detail::text_cursor c(bytes, name, '#', /*line_continuation=*/true);
  if (bytes.starts_with("\xEF\xBB\xBF")) c.pos += 3;
  skeleton_obj_data<P> data;
  auto& s = data.skeleton;
  std::vector<const char*> segment_at;  // where each edge was read, for naming a repeated one
  while (c.next_content()) {
    const char* line = c.pos;
    while (!c.at_token_end()) ++c.pos;
    const std::string_view keyword(line, static_cast<std::size_t>(c.pos - line));
    if (keyword == "v") {
      const std::size_t v = s.points.size() + 1;  // 1-based, as the file counts
      const S x = c.coordinate<S>(
          [&] { return cellforge::detail::cat("coordinate x of vertex ", std::to_string(v)); });
      const S y = c.coordinate<S>(
          [&] { return cellforge::detail::cat("coordinate y of vertex ", std::to_string(v)); });
      const S z = c.coordinate<S>(
          [&] { return cellforge::detail::cat("coordinate z of vertex ", std::to_string(v)); });
      c.skip_blanks();
      // x y z r, or x y z / x y z r g b [a] (colours) taking the uniform radius.
      const char* fourth = c.pos;
      double values[4] = {};
      int extra = 0;
      for (; !c.at_line_end(); c.skip_blanks(), ++extra) {
        if (extra == 4)
          c.fail(cellforge::detail::cat(
              "too many values for 'v' (x y z r, or x y z r g b [a] with the uniform radius): unexpected ",
              c.token()));
        values[extra] = c.number<double>([&] {
          return cellforge::detail::cat("value ", std::to_string(extra + 4), " of vertex ",
                                        std::to_string(v));
        });
      }
      double r = uniform;
      if (extra == 1) {
        r = values[0];
        if (!std::isfinite(r) || !(r > 0))
          c.fail_at(fourth,
                    cellforge::detail::cat("the radius of vertex ", std::to_string(v), " (the 4th value), ",
                                           detail::quote_token(fourth, c.end),
                                           (std::isfinite(r) ? ", must be positive" : ", is not finite")));
      } else if (extra == 2) {
        c.fail_at(line, "'v' takes x y z r (or x y z [r g b [a]] with a uniform radius); found 5 values");
      } else {
        if (uniform == 0)
          c.fail_at(line, cellforge::detail::cat("vertex ", std::to_string(v),
                                                 " has no radius: give it as a 4th value or set "
                                                 "skeleton_obj_read_options::uniform_radius"));
        ++data.uniform_radius_nodes;
      }
      if (s.points.size() >= std::numeric_limits<std::uint32_t>::max() - 1)
        c.fail_at(line, "too many vertices for 32-bit indices");
      s.points.push_back(point_traits<P>::make(x, y, z));
      s.radii.push_back(r);
    } else if (keyword == "l") {
      detail::read_obj_polyline(c, line, s.points.size(), false, "",
                                [&](std::uint32_t a, std::uint32_t b, const char* at) {
                                  s.edges.push_back({a, b});
                                  segment_at.push_back(at);
                                });
    } else if (keyword == "f" || keyword == "fo") {
      c.fail_at(line, "a face in a skeleton file: skeletons are 'v' and 'l' (read surfaces with read_obj)");
    } else if (keyword != "g" && keyword != "o") {
      detail::skip_obj_statement(c, line, keyword, options.strict, data.skipped_statements,
                                 data.first_skipped_line);
    }
    c.next_line();
  }
  // A segment given twice (in either direction) would be two tubes in one: name the later one.
  const auto [worst, first] = cellforge::detail::first_repeated_edge(
      s.edges.size(), [&](std::size_t j) -> std::array<std::size_t, 2> {
        return {s.edges[j][0], s.edges[j][1]};
      });
  if (worst != ~std::size_t{0})
    c.fail_at(
        segment_at[worst],
        cellforge::detail::cat("the segment from vertex ", std::to_string(s.edges[worst][0] + 1), " to ",
                               std::to_string(s.edges[worst][1] + 1), " repeats the one on line ",
                               std::to_string(detail::line_of(
                                   bytes, static_cast<std::size_t>(segment_at[first] - bytes.data())))));
  return data;
}

/// Reads an OBJ file as a skeleton. Throws an io error naming the path when it cannot be read,
/// or with file and line when it is malformed. O(file size + E log E).
template <Point3 P>
skeleton_obj_data<P> read_skeleton_obj(const file_path& path, const skeleton_obj_read_options& options = {}) {
  const std::string bytes = detail::read_file(path);
  return parse_skeleton_obj<P>(bytes, detail::display_name(path), options);
}

namespace detail {

template <Skeleton G>
void put_skeleton_obj(std::ostream& os, const G& g, const skeleton_obj_write_options& options) {
  using T = skeleton_traits<G>;
  output_buffer out(os);
  put_comment_lines(out, options.comment, "# ");
  const std::size_t nv = T::num_nodes(g), ne = T::num_edges(g);
  for (std::size_t i = 0; i < nv; ++i) {
    const auto p = skeleton_point_t<G>(T::position(g, i));
    out.put('v');
    for (std::size_t k = 0; k < 3; ++k) {
      out.put(' ');
      out.number(coord(p, k));
    }
    out.put(' ');
    out.number(static_cast<double>(T::radius(g, i)));
    out.put('\n');
  }
  for (std::size_t j = 0; j < ne; ++j) {
    const std::array<std::size_t, 2> ab = T::endpoints(g, j);
    out.put("l ");
    out.number(ab[0] + std::uint64_t{1});
    out.put(' ');
    out.number(ab[1] + std::uint64_t{1});
    out.put('\n');
  }
  out.finish("OBJ");
}

}  // namespace detail

/// Writes any Skeleton as OBJ: `v x y z r` per node, `l from to` per edge (1-based), numbers in
/// shortest round-trip form. Throws invalid_input, before writing anything, on a skeleton its
/// reader would reject (bad radius or position, bad endpoints, self loop, repeated edge).
/// O(V log V + E log E).
template <Skeleton G>
void write_skeleton_obj(std::ostream& os, const G& g, const skeleton_obj_write_options& options = {}) {
  cellforge::detail::check_skeleton_writable(g, "write_skeleton_obj");
  detail::put_skeleton_obj(os, g, options);
}

/// Writes an OBJ skeleton file; a refused skeleton leaves an existing file untouched. io errors
/// name the path. O(V log V + E log E).
template <Skeleton G>
void write_skeleton_obj(const file_path& path, const G& g, const skeleton_obj_write_options& options = {}) {
  cellforge::detail::check_skeleton_writable(g, "write_skeleton_obj");
  detail::write_file(path, [&](std::ostream& os) { detail::put_skeleton_obj(os, g, options); });
}

}  // namespace cellforge::io
