// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The plain text format of line drawings: `j x y` a junction (numbered from 0 in file order),
/// `e a b` an edge between two junction indices, `#` comments and blank lines; in drawings with
/// rounds and fillets also `a i j rx ry rotation large ccw`, an elliptical arc from junction i to
/// junction j in SVG's endpoint form. See docs/formats.md ("Line drawing text").

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/io/detail/arc_io.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge::io {

/// How line drawings are written as text.
struct drawing_text_write_options {
  /// Written as '#' comment lines at the top when not empty.
  std::string comment{};
};

namespace detail {

/// An arc statement as read, before its junctions are known to exist.
struct text_arc {
  std::array<std::int64_t, 2> ends{};
  double rx = 0, ry = 0, degrees = 0;
  bool large = false, ccw = false;
  const char* line = nullptr;
};

/// The reader of both drawing text formats: arcs read when `arcs`, else refused. O(size + E log E).
template <Point2 P2>
arc_drawing<P2> parse_drawing_text_statements(std::string_view text, std::string_view name, bool arcs) {
  using S = scalar2_t<P2>;
  constexpr auto limit = std::numeric_limits<std::uint32_t>::max();
  text_cursor c(text, name, '#');
  if (text.starts_with("\xEF\xBB\xBF")) c.pos += 3;
  arc_drawing<P2> result;
  line_drawing<P2>& d = result.lines;
  std::vector<const char*> edge_lines;
  std::vector<std::array<std::int64_t, 2>> raw;
  std::vector<text_arc> raw_arcs;
  while (c.next_content()) {
    const char* line = c.pos;
    const char* q = c.pos;
    while (!c.at_token_end()) ++c.pos;
    const std::string_view key(q, static_cast<std::size_t>(c.pos - q));
    if (key == "j") {
      const std::size_t i = d.points.size();
      if (i >= limit - 1) c.fail_at(line, "too many junctions for 32-bit indices");
      const S x = c.coordinate<S>(
          [&] { return cellforge::detail::cat("coordinate x of junction ", std::to_string(i), " (j x y)"); });
      const S y = c.coordinate<S>(
          [&] { return cellforge::detail::cat("coordinate y of junction ", std::to_string(i), " (j x y)"); });
      c.skip_blanks();
      if (!c.at_line_end())
        c.fail(cellforge::detail::cat("unexpected ", c.token(), " after the 2 coordinates of junction ",
                                      std::to_string(i), " (j x y)"));
      d.points.push_back(point2_traits<P2>::make(x, y));
    } else if (key == "e") {
      const std::size_t e = raw.size();
      if (e >= limit - 1) c.fail_at(line, "too many edges");
      std::array<std::int64_t, 2> ab{};
      for (int k = 0; k < 2; ++k) {
        c.skip_blanks();
        const char* at = c.pos;
        ab[k] = c.integer([&] {
          return cellforge::detail::cat(std::string(k == 0 ? "the first" : "the second"),
                                        " junction index of edge ", std::to_string(e), " (e a b)");
        });
        if (ab[k] < 0)
          c.fail_at(at, cellforge::detail::cat("junction index ", std::to_string(ab[k]), " of edge ",
                                               std::to_string(e), " is negative (indices are 0-based)"));
      }
      c.skip_blanks();
      if (!c.at_line_end())
        c.fail(cellforge::detail::cat("unexpected ", c.token(), " after the 2 junction indices of edge ",
                                      std::to_string(e), " (e a b)"));
      if (ab[0] == ab[1])
        c.fail_at(line, cellforge::detail::cat("edge ", std::to_string(e), " joins junction ",
                                               std::to_string(ab[0]), " to itself"));
      raw.push_back(ab);
      edge_lines.push_back(line);
    } else if (key == "a" && !arcs) {
      c.fail_at(line,
                "an arc ('a i j rx ry rotation large ccw'): this reader takes straight edges only; read "
                "drawings with arcs by read_arc_drawing_text / parse_arc_drawing_text (io/drawing_text.hpp)");
    } else if (key == "a") {
      const std::size_t k = raw_arcs.size();
      if (k >= limit - 1) c.fail_at(line, "too many arcs");
      const std::string form =
          cellforge::detail::cat(" of arc ", std::to_string(k), " (a i j rx ry rotation large ccw)");
      text_arc t;
      t.line = line;
      for (int m = 0; m < 2; ++m) {
        c.skip_blanks();
        const char* at = c.pos;
        t.ends[m] = c.integer([&] {
          return cellforge::detail::cat(std::string(m == 0 ? "the first" : "the second"), " junction index",
                                        form);
        });
        if (t.ends[m] < 0)
          c.fail_at(at, cellforge::detail::cat("junction index ", std::to_string(t.ends[m]), form,
                                               " is negative (indices are 0-based)"));
      }
      for (int m = 0; m < 2; ++m) {
        c.skip_blanks();
        const char* at = c.pos;
        const char* axis = m == 0 ? "rx" : "ry";
        const double r = c.coordinate<double>(
            [&] { return cellforge::detail::cat(std::string("the radius "), axis, form); });
        if (!(r > 0))
          c.fail_at(at,
                    cellforge::detail::cat(
                        std::string("the radius "), axis, form, " is ", cellforge::detail::drawing_number(r),
                        ": radii must be > 0 (a zero radius is a corner: draw the two lines meeting there)"));
        (m == 0 ? t.rx : t.ry) = r;
      }
      t.degrees =
          c.coordinate<double>([&] { return cellforge::detail::cat("the rotation in degrees", form); });
      for (int m = 0; m < 2; ++m) {
        c.skip_blanks();
        const char* at = c.pos;
        const char* flag = m == 0 ? "the large-arc flag" : "the ccw flag";
        const std::int64_t f = c.integer([&] { return flag + std::string(" (0 or 1)") + form; });
        if (f != 0 && f != 1)
          c.fail_at(at, cellforge::detail::cat(std::string(flag), form, " is ", std::to_string(f),
                                               ": expected 0 or 1"));
        (m == 0 ? t.large : t.ccw) = f == 1;
      }
      c.skip_blanks();
      if (!c.at_line_end())
        c.fail(cellforge::detail::cat("unexpected ", c.token(), " after the 7 values", form));
      if (t.ends[0] == t.ends[1])
        c.fail_at(
            line,
            cellforge::detail::cat(
                "arc ", std::to_string(k), " starts and ends at junction ", std::to_string(t.ends[0]),
                ": a closed curve is no round or fillet (draw it as two arcs with a junction between)"));
      raw_arcs.push_back(t);
    } else {
      c.pos = q;
      c.fail(cellforge::detail::cat(std::string("expected 'j x y' (a junction), 'e a b' (an edge)"),
                                    (arcs ? ", 'a i j rx ry rotation large ccw' (an arc)" : ""),
                                    " or a '#' comment, found ", c.token()));
    }
    c.next_line();
  }
  const std::size_t nv = d.points.size();
  d.edges.reserve(raw.size());
  for (std::size_t e = 0; e < raw.size(); ++e) {
    for (const std::int64_t v : raw[e])
      if (static_cast<std::uint64_t>(v) >= nv)
        c.fail_at(edge_lines[e],
                  cellforge::detail::cat("junction index ", std::to_string(v), " of edge ", std::to_string(e),
                                         " out of range (", std::to_string(nv),
                                         " junctions; indices are 0-based)"));
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
    c.fail_at(edge_lines[later],
              cellforge::detail::cat(
                  "edge ", std::to_string(later), " repeats edge ", std::to_string(earlier), " (line ",
                  std::to_string(line_of(text, static_cast<std::size_t>(edge_lines[earlier] - text.data()))),
                  "; junctions ", std::to_string(d.edges[later][0]), " and ",
                  std::to_string(d.edges[later][1]), ")"));
  result.arcs.reserve(raw_arcs.size());
  for (std::size_t k = 0; k < raw_arcs.size(); ++k) {
    const text_arc& t = raw_arcs[k];
    for (const std::int64_t v : t.ends)
      if (static_cast<std::uint64_t>(v) >= nv)
        c.fail_at(t.line, cellforge::detail::cat("junction index ", std::to_string(v), " of arc ",
                                                 std::to_string(k), " out of range (", std::to_string(nv),
                                                 " junctions; indices are 0-based)"));
    const std::array<std::uint32_t, 2> ends{static_cast<std::uint32_t>(t.ends[0]),
                                            static_cast<std::uint32_t>(t.ends[1])};
    const P2 from = d.points[ends[0]], to = d.points[ends[1]];
    if (to_dvec2(from) == to_dvec2(to))
      c.fail_at(t.line, cellforge::detail::cat("arc ", std::to_string(k), " joins junctions ",
                                               std::to_string(ends[0]), " and ", std::to_string(ends[1]),
                                               ", both at ", cellforge::detail::drawing_point_text(from),
                                               ": an arc needs distinct end points"));
    result.arcs.push_back(
        {ends, arc_from_endpoints<P2>({from, to, t.rx, t.ry, arc_radians(t.degrees), t.large, t.ccw})});
  }
  // What the writer checks: with radii far beyond the ends' distance rounding can leave the
  // computed curve off its junctions.
  if (const arc_validation v = validate(result); !v)
    c.fail_at(raw_arcs[v.arc].line, v.message + " (the arc's numbers are out of proportion to its ends)");
  return result;
}

}  // namespace detail

/// Parses line-drawing text held in memory; `name` is used in error messages. Edges may name
/// junctions defined later in the file. Throws an io error with file and line on malformed input
/// (unknown keyword, bad or missing number, trailing junk, NaN/Inf, index out of range, an edge
/// from a junction to itself or given twice, arcs: those are parse_arc_drawing_text's).
/// O(size of the text + E log E).
template <Point2 P2 = glm::dvec2>
line_drawing<P2> parse_drawing_text(std::string_view text, std::string_view name = "<memory>") {
  return detail::parse_drawing_text_statements<P2>(text, name, false).lines;
}

/// Parses line-drawing text with arcs (`a i j rx ry rotation large ccw` statements, see
/// docs/formats.md) into an arc_drawing; errors as parse_drawing_text's, and for arcs (bad or
/// missing number, radius <= 0, flag not 0/1, ends one junction or one point). O(size + E log E).
template <Point2 P2 = glm::dvec2>
arc_drawing<P2> parse_arc_drawing_text(std::string_view text, std::string_view name = "<memory>") {
  return detail::parse_drawing_text_statements<P2>(text, name, true);
}

/// Reads a line-drawing text file with arcs (see parse_arc_drawing_text); io errors name the
/// path. O(file size + E log E).
template <Point2 P2 = glm::dvec2>
arc_drawing<P2> read_arc_drawing_text(const file_path& path) {
  const std::string bytes = detail::read_file(path);
  return parse_arc_drawing_text<P2>(bytes, detail::display_name(path));
}

/// Reads a line-drawing text file. Throws an io error naming the path when it cannot be read, or
/// with file and line when it is malformed. O(file size + E log E).
template <Point2 P2 = glm::dvec2>
line_drawing<P2> read_drawing_text(const file_path& path) {
  const std::string bytes = detail::read_file(path);
  return parse_drawing_text<P2>(bytes, detail::display_name(path));
}

namespace detail {

/// Throws invalid_input, prefixed by `writer`, for what the text reader would reject: NaN/Inf
/// positions, out-of-range ends, self loops, repeated edges, 2^32 junctions. O(V + E log E).
template <LineDrawing D>
void check_drawing_writable(const D& d, std::string_view writer) {
  if (line_drawing_traits<D>::num_junctions(d) >= std::numeric_limits<std::uint32_t>::max() - 1)
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(writer), ": more than 2^32 - 2 junctions"));
  const drawing_validation v = validate(d, {.tolerance = 0});
  switch (v.defect) {
    case drawing_defect::bad_position:
    case drawing_defect::endpoint_out_of_range:
    case drawing_defect::self_loop:
    case drawing_defect::duplicate_edge:
      throw error(error_category::invalid_input,
                  cellforge::detail::cat(std::string(writer), ": ", v.message));
    default:
      return;
  }
}

/// Writes the lines of a checked drawing, and its arcs when `arcs` is given. O(V + E + A).
template <LineDrawing D, class Arc = drawing_arc<glm::dvec2>>
void put_drawing_text(std::ostream& os, const D& d, const drawing_text_write_options& options,
                      const std::vector<Arc>* arcs = nullptr) {
  using T = line_drawing_traits<D>;
  using P = drawing_point_t<D>;
  output_buffer out(os);
  put_comment_lines(out, options.comment, "# ");
  const std::size_t nv = T::num_junctions(d), ne = T::num_edges(d);
  out.put("# cellforge line drawing: ");
  out.number(nv);
  out.put(" junctions (j x y, numbered from 0), ");
  out.number(ne);
  out.put(arcs ? " edges (e a b), " : " edges (e a b)\n");
  if (arcs) {
    out.number(arcs->size());
    out.put(" arcs (a i j rx ry rotation_degrees large_arc ccw)\n");
  }
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
  if (arcs)
    for (const Arc& a : *arcs) {
      out.put("a ");
      out.number(a.ends[0]);
      out.put(' ');
      out.number(a.ends[1]);
      for (const double v : {a.curve.rx, a.curve.ry, arc_degrees(a.curve.rotation)}) {
        out.put(' ');
        out.number(v);
      }
      const auto flags = arc_endpoint_form(a.curve);
      out.put(flags.large_arc ? " 1" : " 0");
      out.put(flags.ccw ? " 1\n" : " 0\n");
    }
  out.finish("line drawing text");
}

/// Throws invalid_input, prefixed by `writer`, for what the arc text reader would reject or
/// change: the straight part's defects (check_drawing_writable) and arcs that are not valid or
/// whose curve does not start and end at its junctions (validate(arc_drawing):
/// the format keeps only the ends' junctions, radii, rotation and flags). O(V + E log E + A).
template <Point2 P>
void check_arc_drawing_writable(const arc_drawing<P>& d, std::string_view writer) {
  check_drawing_writable(d.lines, writer);
  if (d.arcs.size() >= std::numeric_limits<std::uint32_t>::max() - 1)
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(writer), ": more than 2^32 - 2 arcs"));
  const arc_validation v = validate(d);
  if (!v)
    throw error(error_category::invalid_input, cellforge::detail::cat(std::string(writer), ": ", v.message));
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
void write_drawing_text(const file_path& path, const D& d, const drawing_text_write_options& options = {}) {
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

/// Writes a drawing with arcs as text: the straight part as write_drawing_text does, then one
/// `a i j rx ry rotation large ccw` line per arc, numbers in shortest round-trip form (a drawing
/// read from text comes back bit for bit). Throws invalid_input, before writing anything, for
/// an arc not valid or not ending at its junctions. O(V + E log E + A).
template <Point2 P>
void write_arc_drawing_text(std::ostream& os, const arc_drawing<P>& d,
                            const drawing_text_write_options& options = {}) {
  detail::check_arc_drawing_writable(d, "write_arc_drawing_text");
  detail::put_drawing_text(os, d.lines, options, &d.arcs);
}

/// Writes a line-drawing text file with arcs (see the stream overload); a drawing the format
/// cannot hold is refused before the file is opened; io errors name the path. O(V + E log E + A).
template <Point2 P>
void write_arc_drawing_text(const file_path& path, const arc_drawing<P>& d,
                            const drawing_text_write_options& options = {}) {
  detail::check_arc_drawing_writable(d, "write_arc_drawing_text");
  detail::write_file(path,
                     [&](std::ostream& os) { detail::put_drawing_text(os, d.lines, options, &d.arcs); });
}

/// The text of a drawing with arcs as a string (see write_arc_drawing_text). O(V + E log E + A).
template <Point2 P>
std::string arc_drawing_text_string(const arc_drawing<P>& d, const drawing_text_write_options& options = {}) {
  std::ostringstream os;
  write_arc_drawing_text(os, d, options);
  return os.str();
}

#if defined(CELLFORGE_EXTERN_SKETCH)
// Compiled once in the file that includes cellforge/sketch/instantiate.hpp (docs/sketch.md).
extern template arc_drawing<glm::dvec2> detail::parse_drawing_text_statements<glm::dvec2>(std::string_view,
                                                                                          std::string_view,
                                                                                          bool);
extern template line_drawing<glm::dvec2> read_drawing_text<glm::dvec2>(const file_path&);
extern template line_drawing<glm::dvec2> parse_drawing_text<glm::dvec2>(std::string_view, std::string_view);
#endif

}  // namespace cellforge::io
