// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Wavefront OBJ reading and writing: vertices (`v`), polygonal faces (`f`, every index
/// form, relative indices included), polylines (`l`) and named groups (`g`/`o`). Texture
/// coordinates, normals, materials and smoothing groups are skipped. See docs/formats.md.

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/io/detail/face_checks.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"

namespace cellforge::io {

/// A named run of faces: faces [first_face, next group's first_face) belong to `name`.
struct obj_group {
  std::string name;
  std::uint32_t first_face = 0;
  friend bool operator==(const obj_group&, const obj_group&) = default;
};

/// Everything cellforge reads from an OBJ file.
template <Point3 P>
struct obj_data {
  polygon_soup<P> soup;                             ///< all `v` points and `f` faces
  std::vector<std::array<std::uint32_t, 2>> lines;  ///< `l` polylines split into edges
  std::vector<obj_group> groups;                    ///< `g`/`o` names, by first face; sorted
  std::size_t skipped_statements = 0;               ///< unknown statements ignored (not strict)
  std::uint64_t first_skipped_line = 0;             ///< line of the first of them, 0 if none
};

/// How OBJ files are read.
struct obj_read_options {
  /// Accept faces that use a vertex twice and `l` segments from a vertex to itself.
  bool allow_repeated_vertices = false;
  /// Unknown statements are an error instead of being skipped (and counted in obj_data).
  bool strict = false;
};

/// How OBJ files are written.
struct obj_write_options {
  /// Written as '#' comment lines at the top when not empty.
  std::string comment{};
};

namespace detail {

/// Statements of the OBJ specification that carry nothing cellforge keeps.
template <class = void>
bool is_known_obj_statement(std::string_view k) noexcept {
  constexpr std::string_view known[] = {
      "vt",     "vn",         "vp",        "p",     "s",        "usemtl",   "mtllib", "lod",   "maplib",
      "usemap", "shadow_obj", "trace_obj", "bevel", "c_interp", "d_interp", "ctech",  "stech", "cstype",
      "deg",    "bmat",       "step",      "curv",  "curv2",    "surf",     "parm",   "trim",  "hole",
      "scrv",   "sp",         "end",       "con",   "mg",       "call",     "csh",    "res"};
  return std::find(std::begin(known), std::end(known), k) != std::end(known);
}

/// Reads one face or line vertex reference (`v`, `v/vt`, `v//vn`, `v/vt/vn`) and returns the
/// 0-based vertex index, resolving negative (relative) indices against the `nv` vertices so far.
template <class = void>
std::uint32_t read_obj_index(text_cursor& c, std::uint64_t nv, bool allow_normals) {
  const char* start = c.pos;
  const auto bad = [&] {
    c.pos = start;
    c.fail(
        cellforge::detail::cat("expected a vertex reference (v, v/vt, v//vn or v/vt/vn), found ", c.token()));
  };
  std::int64_t v = 0;
  if (parse_number(c.pos, c.end, v) != parse_status::ok) bad();
  for (int slot = 1; slot <= 2 && c.pos != c.end && *c.pos == '/'; ++slot) {
    ++c.pos;
    if (slot == 2 && !allow_normals) bad();
    // The texture slot may be empty ("v//vn"); what is there must be an integer.
    if (c.pos != c.end && *c.pos != '/' && !c.at_token_end()) {
      std::int64_t ignored = 0;
      if (parse_number(c.pos, c.end, ignored) != parse_status::ok) bad();
    }
  }
  if (!c.at_token_end()) bad();
  if (v == 0) c.fail_at(start, "vertex index 0 is invalid (OBJ indices start at 1)");
  const std::int64_t n = static_cast<std::int64_t>(nv);
  const std::int64_t resolved = v > 0 ? v - 1 : n + v;
  if (resolved < 0 || resolved >= n) {
    const std::string range = n == 0  ? std::string("no vertices are defined yet")
                              : v > 0 ? cellforge::detail::cat("1..", std::to_string(n))
                                      : cellforge::detail::cat("-1..-", std::to_string(n));
    // allow_normals is false exactly for `l` statements.
    const std::string what = allow_normals ? "face" : "line";
    c.fail_at(start, (v > 0 ? what : cellforge::detail::cat("relative ", what)) + " index " +
                         std::to_string(v) + " out of range (" + range + ")" +
                         (v > 0 ? cellforge::detail::cat("; vertices must be defined before the ", what,
                                                         "s that use them")
                                : ""));
  }
  return static_cast<std::uint32_t>(resolved);
}

/// Reads the vertex references of the `l` statement at `line` and calls `segment(from, to, at)` for
/// each of its segments (`at`: where `to` was read). A segment from a vertex to itself is an error
/// unless `allow_repeated`; `option` names the option that accepts it (empty: none). O(line).
template <class Segment>
void read_obj_polyline(text_cursor& c, const char* line, std::uint64_t nv, bool allow_repeated,
                       std::string_view option, Segment&& segment) {
  std::size_t k = 0;
  std::uint32_t prev = 0;
  for (c.skip_blanks(); !c.at_line_end(); c.skip_blanks(), ++k) {
    const char* at = c.pos;
    const std::uint32_t v = read_obj_index(c, nv, false);
    if (k > 0) {
      if (v == prev && !allow_repeated)
        c.fail_at(at,
                  cellforge::detail::cat(
                      "line segment from vertex ", std::to_string(v + 1), " to itself (zero length",
                      (option.empty() ? std::string(")")
                                      : cellforge::detail::cat("; ", std::string(option), " accepts it)"))));
      segment(prev, v, at);
    }
    prev = v;
  }
  if (k < 2)
    c.fail_at(line, cellforge::detail::cat("'l' needs at least 2 vertices, found ", std::to_string(k)));
}

/// A statement the reader does not keep, at `line`: skipped when the OBJ specification knows it;
/// otherwise counted (`skipped`, `first_line`), or an error when `strict`. Text that is no statement
/// at all (binary data, another format) is an error, so it does not pass as an empty model. O(keyword).
template <class = void>
void skip_obj_statement(text_cursor& c, const char* line, std::string_view keyword, bool strict,
                        std::size_t& skipped, std::uint64_t& first_line) {
  if (is_known_obj_statement(keyword)) return;
  const auto letter = [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || ch == '_';
  };
  const bool word = !keyword.empty() && letter(keyword.front()) &&
                    std::all_of(keyword.begin(), keyword.end(),
                                [&](char ch) { return letter(ch) || (ch >= '0' && ch <= '9'); });
  if (!word) c.fail_at(line, cellforge::detail::cat("not an OBJ statement: ", quote_token(line, c.end)));
  if (strict) c.fail_at(line, cellforge::detail::cat("unknown statement ", quote_token(line, c.end)));
  if (skipped++ == 0)
    first_line = line_of({c.begin, static_cast<std::size_t>(c.end - c.begin)},
                         static_cast<std::size_t>(line - c.begin));
}

/// Rest of the line as a group name, blanks trimmed; "default" when empty. A '\' before the line
/// end joins the next line, as in every other statement, and stands for one blank. O(name).
template <class = void>
std::string read_obj_name(text_cursor& c) {
  c.skip_blanks();
  std::string name;
  std::size_t kept = 0;  // the name up to its last non-blank
  while (!c.at_line_end()) {
    if (*c.pos == '\\') {
      const char* before = c.pos;
      c.skip_blanks();  // moves only over a continuation
      if (c.pos != before) {
        name += ' ';
        continue;
      }
    }
    name += *c.pos;
    if (!is_blank(*c.pos)) kept = name.size();
    ++c.pos;
  }
  name.resize(kept);
  return name.empty() ? std::string("default") : name;
}

}  // namespace detail

/// Parses OBJ text held in memory; `name` is used in error messages. Throws an io error
/// with file and line on malformed input. O(size of the text).
template <Point3 P>
obj_data<P> parse_obj(std::string_view bytes, std::string_view name = "<memory>",
                      const obj_read_options& options = {}) {
  using S = scalar_t<P>;
  detail::text_cursor c(bytes, name, '#', /*line_continuation=*/true);
  if (bytes.starts_with("\xEF\xBB\xBF")) c.pos += 3;
  obj_data<P> data;
  auto& soup = data.soup;
  std::vector<std::uint32_t> scratch;
  while (c.next_content()) {
    const char* line = c.pos;
    while (!c.at_token_end()) ++c.pos;
    const std::string_view keyword(line, static_cast<std::size_t>(c.pos - line));
    if (keyword == "v") {
      const S x = c.coordinate<S>([] { return std::string("coordinate x"); });
      const S y = c.coordinate<S>([] { return std::string("coordinate y"); });
      const S z = c.coordinate<S>([] { return std::string("coordinate z"); });
      c.skip_blanks();
      // Accepted: x y z, x y z w (rational weight), x y z r g b [a] (a common colour extension).
      int values = 3;
      for (; !c.at_line_end(); c.skip_blanks(), ++values) {
        if (values == 7)
          c.fail(cellforge::detail::cat("too many values for 'v' (at most x y z r g b a): unexpected ",
                                        c.token()));
        (void)c.number<double>([] { return std::string("a number"); });
      }
      if (values == 5) c.fail_at(line, "'v' takes x y z [w] or x y z r g b [a]; found 5 values");
      if (soup.points.size() >= std::numeric_limits<std::uint32_t>::max())
        c.fail_at(line, "too many vertices for 32-bit indices");
      soup.points.push_back(point_traits<P>::make(x, y, z));
    } else if (keyword == "f" || keyword == "fo") {
      const std::size_t first = soup.face_vertices.size();
      for (c.skip_blanks(); !c.at_line_end(); c.skip_blanks())
        soup.face_vertices.push_back(detail::read_obj_index(c, soup.points.size(), true));
      const std::size_t k = soup.face_vertices.size() - first;
      if (k < 3)
        c.fail_at(line,
                  cellforge::detail::cat("face has ", std::to_string(k), (k == 1 ? " vertex" : " vertices"),
                                         "; a face needs at least 3"));
      if (const auto problem = detail::close_face(soup, first, options.allow_repeated_vertices, scratch, 1,
                                                  "obj_read_options"))
        c.fail_at(line, cellforge::detail::cat("face ", *problem));
    } else if (keyword == "l") {
      detail::read_obj_polyline(c, line, soup.points.size(), options.allow_repeated_vertices,
                                "obj_read_options::allow_repeated_vertices",
                                [&](std::uint32_t a, std::uint32_t b, const char*) {
                                  data.lines.push_back({a, b});
                                });
    } else if (keyword == "g" || keyword == "o") {
      std::string group = detail::read_obj_name(c);
      const auto nf = static_cast<std::uint32_t>(soup.num_faces());
      // A group that received no face yet is renamed, so "o x" then "g y" makes one group.
      if (!data.groups.empty() && data.groups.back().first_face == nf)
        data.groups.back().name = std::move(group);
      else
        data.groups.push_back({std::move(group), nf});
    } else {
      detail::skip_obj_statement(c, line, keyword, options.strict, data.skipped_statements,
                                 data.first_skipped_line);
    }
    c.next_line();
  }
  return data;
}

/// Reads an OBJ file. Throws an io error naming the path when it cannot be read, or with
/// file and line when it is malformed. O(file size).
template <Point3 P>
obj_data<P> read_obj(const file_path& path, const obj_read_options& options = {}) {
  const std::string bytes = detail::read_file(path);
  return parse_obj<P>(bytes, detail::display_name(path), options);
}

/// The wireframe of an OBJ file: all its points and its `l` edges, plus, when asked, the
/// edges of its faces (each undirected edge once). O(V + E log E).
template <Point3 P>
wireframe<P> to_wireframe(const obj_data<P>& data, bool include_face_edges = false) {
  wireframe<P> w;
  w.points = data.soup.points;
  w.edges = data.lines;
  if (include_face_edges) {
    std::vector<std::array<std::uint32_t, 2>> extra;
    extra.reserve(data.soup.face_vertices.size());
    for (std::size_t f = 0; f < data.soup.num_faces(); ++f) {
      const auto face = data.soup.face(f);
      for (std::size_t i = 0; i < face.size(); ++i) {
        const std::uint32_t a = face[i], b = face[(i + 1) % face.size()];
        extra.push_back({std::min(a, b), std::max(a, b)});
      }
    }
    for (const auto& e : w.edges) extra.push_back({std::min(e[0], e[1]), std::max(e[0], e[1])});
    std::sort(extra.begin(), extra.end());
    extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
    // Keep the file's own lines first and in order; face edges they do not cover follow.
    std::vector<std::array<std::uint32_t, 2>> lines_sorted;
    for (const auto& e : w.edges) lines_sorted.push_back({std::min(e[0], e[1]), std::max(e[0], e[1])});
    std::sort(lines_sorted.begin(), lines_sorted.end());
    for (const auto& e : extra)
      if (!std::binary_search(lines_sorted.begin(), lines_sorted.end(), e)) w.edges.push_back(e);
  }
  return w;
}

/// Reads an OBJ file's points and `l` edges as a wireframe (faces' edges too when asked). O(file size).
template <Point3 P>
wireframe<P> read_obj_wireframe(const file_path& path, const obj_read_options& options = {},
                                bool include_face_edges = false) {
  return to_wireframe(read_obj<P>(path, options), include_face_edges);
}

namespace detail {

template <Point3 P>
void put_obj_vertices(output_buffer& out, const std::vector<P>& points) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const P& p = points[i];
    check_point_finite(p, i, "obj");
    out.put("v ");
    out.number(coord(p, 0));
    out.put(' ');
    out.number(coord(p, 1));
    out.put(' ');
    out.number(coord(p, 2));
    out.put('\n');
  }
}

template <class = void>
void put_obj_lines(output_buffer& out, const std::vector<std::array<std::uint32_t, 2>>& lines,
                   std::size_t n_points) {
  for (const auto& e : lines) {
    if (e[0] >= n_points || e[1] >= n_points)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_obj: line vertex index out of range (",
                                         std::to_string(n_points), " points)"));
    out.put("l ");
    out.number(e[0] + std::uint64_t{1});
    out.put(' ');
    out.number(e[1] + std::uint64_t{1});
    out.put('\n');
  }
}

/// A `g name` line; the name as write_obj checked it.
template <class = void>
void put_obj_group(output_buffer& out, const obj_group& group) {
  out.put("g ");
  out.put(group.name.empty() ? std::string_view("default") : std::string_view(group.name));
  // A '\' at the line end would join the next line: an empty comment after it keeps it a '\'.
  if (group.name.ends_with('\\')) out.put(" #");
  out.put('\n');
}

/// Faces as `f` lines, 1-based, with a `g` line before the first face of each group; a last
/// group with no faces (a file's trailing `g`) is written after them, so it reads back.
template <Point3 P>
void put_obj_faces(output_buffer& out, const polygon_soup<P>& soup, std::span<const obj_group> groups) {
  std::size_t g = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    for (; g < groups.size() && groups[g].first_face == f; ++g) put_obj_group(out, groups[g]);
    out.put('f');
    for (const std::uint32_t v : soup.face(f)) {
      out.put(' ');
      out.number(v + std::uint64_t{1});
    }
    out.put('\n');
  }
  for (; g < groups.size(); ++g) put_obj_group(out, groups[g]);
}

}  // namespace detail

/// Writes points, faces (with `g` lines where groups start) and `l` edges as OBJ, numbers
/// in shortest round-trip form. Throws invalid_input on NaN/Inf, bad indices or unsorted groups. O(size).
template <Point3 P>
void write_obj(std::ostream& os, const obj_data<P>& data, const obj_write_options& options = {}) {
  const auto& soup = data.soup;
  detail::check_face_indices(soup, "obj");
  for (std::size_t g = 0; g < data.groups.size(); ++g) {
    if (data.groups[g].first_face > soup.num_faces() ||
        (g > 0 && data.groups[g].first_face < data.groups[g - 1].first_face))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_obj: group ", std::to_string(g),
                                         " starts at a face out of order or past the last face"));
    // A line break or '#' would end the name early and turn the rest into statements or a comment;
    // blanks at either end are not kept by a reader.
    const std::string& name = data.groups[g].name;
    if (name.find_first_of("\r\n#") != std::string::npos)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_obj: group name ", std::to_string(g),
                                         " contains a line break or '#'"));
    if (!name.empty() && (detail::is_blank(name.front()) || detail::is_blank(name.back())))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_obj: group name ", std::to_string(g), " ('", name,
                                         "') starts or ends with a blank, which OBJ does not keep"));
  }
  detail::output_buffer out(os);
  detail::put_comment_lines(out, options.comment, "# ");
  detail::put_obj_vertices(out, soup.points);
  detail::put_obj_faces(out, soup, data.groups);
  detail::put_obj_lines(out, data.lines, soup.points.size());
  out.finish("OBJ");
}

/// Writes a soup as OBJ (`v` and `f`). O(size).
template <Point3 P>
void write_obj(std::ostream& os, const polygon_soup<P>& soup, const obj_write_options& options = {}) {
  detail::check_face_indices(soup, "obj");
  detail::output_buffer out(os);
  detail::put_comment_lines(out, options.comment, "# ");
  detail::put_obj_vertices(out, soup.points);
  detail::put_obj_faces(out, soup, {});
  out.finish("OBJ");
}

/// Writes a wireframe as OBJ (`v` and one `l` per edge). O(size).
template <Point3 P>
void write_obj(std::ostream& os, const wireframe<P>& w, const obj_write_options& options = {}) {
  detail::output_buffer out(os);
  detail::put_comment_lines(out, options.comment, "# ");
  detail::put_obj_vertices(out, w.points);
  detail::put_obj_lines(out, w.edges, w.points.size());
  out.finish("OBJ");
}

/// Writes OBJ data to a file (see the stream overload). Throws an io error naming the path
/// when it cannot be written. O(size).
template <Point3 P>
void write_obj(const file_path& path, const obj_data<P>& data, const obj_write_options& options = {}) {
  detail::write_file(path, [&](std::ostream& os) { write_obj(os, data, options); });
}

/// Writes a soup to an OBJ file. O(size).
template <Point3 P>
void write_obj(const file_path& path, const polygon_soup<P>& soup, const obj_write_options& options = {}) {
  detail::write_file(path, [&](std::ostream& os) { write_obj(os, soup, options); });
}

/// Writes a wireframe to an OBJ file. O(size).
template <Point3 P>
void write_obj(const file_path& path, const wireframe<P>& w, const obj_write_options& options = {}) {
  detail::write_file(path, [&](std::ostream& os) { write_obj(os, w, options); });
}

}  // namespace cellforge::io
