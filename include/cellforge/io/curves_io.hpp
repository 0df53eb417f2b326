// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Files and pictures of smoothed edges and thin loops: the seed's curve file (seed 000
/// §6.5: axis, limits, two cubics per line), the polyline file (15 segments per curve), OBJ
/// `l` polylines, and SVG pictures of thin loops on a solid and of straight beside smoothed
/// edges. Layouts: docs/formats.md "Curve file" and "Polyline file".

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <ostream>
#include <ranges>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/if_satisfied.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/io/detail/numbers.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/io/svg.hpp"
#include "cellforge/smooth/edge_curve.hpp"
#include "cellforge/thin/thin_result.hpp"

namespace cellforge::io {

/// How curve and polyline files are written.
struct curve_write_options {
  std::string comment{};  ///< written as '#' lines at the top when not empty
  int segments = 15;      ///< polyline file and OBJ: straight pieces per curve (1 .. 10000)
};

namespace detail {

template <class T>
void put_curve_number(std::string& out, T v) {
  // Shortest text that reads back to the same value (a double: at most 17 significant digits).
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

template <class = void>
void put_comment(std::string& out, std::string_view text) {
  while (!text.empty()) {
    const std::size_t eol = std::min(text.find_first_of("\r\n"), text.size());
    if (eol != 0) out.append("# ").append(text.substr(0, eol)).append("\n");
    text.remove_prefix(std::min(eol + 1, text.size()));
  }
}

/// Writes text to a file (only called once the text is complete and checked). O(text).
template <class = void>
void write_text_file(const file_path& path, const std::string& text) {
  write_file(path,
             [&](std::ostream& os) { os.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

template <class = void>
void check_segments(int segments, const char* who) {
  if (segments < 1 || segments > 10000)
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(who), ": segments must be within 1 .. 10000, got ",
                                       std::to_string(segments)));
}

/// Throws invalid_input unless curve i can be written so that its reader accepts it. O(1).
template <Point3 P>
void check_curve(const edge_curve<P>& c, std::size_t i, const char* who) {
  const auto bad = [&](const std::string& what) {
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(who), ": curve ", std::to_string(i), " ", what));
  };
  if (c.has_axis_form) {
    if (c.axis < 0 || c.axis > 2)
      bad(cellforge::detail::cat("has axis ", std::to_string(c.axis), " (expected 0, 1 or 2)"));
    if (!std::isfinite(c.limits[0]) || !std::isfinite(c.limits[1])) bad("has a non-finite limit");
    if (c.limits[0] == c.limits[1]) bad("has equal limits (a curve must run along its axis)");
    for (const auto& row : c.coefficients)
      for (const double v : row)
        if (!std::isfinite(v)) bad("has a non-finite coefficient");
  } else {
    for (const auto& p : c.bezier) {
      const glm::dvec3 q = to_dvec3(p);
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
        bad("has a non-finite Bezier control point");
    }
    if (to_dvec3(c.bezier[0]) == to_dvec3(c.bezier[3])) bad("starts and ends at the same point");
  }
}

/// One line of the curve file (no line end); Bézier coordinates in P's own scalar. O(1).
template <Point3 P>
void put_curve_line(std::string& out, const edge_curve<P>& c) {
  const auto sep = [&] { out += ", "; };
  if (c.has_axis_form) {
    out += static_cast<char>('0' + c.axis);
    for (const double v : c.limits) sep(), put_curve_number(out, v);
    for (const auto& row : c.coefficients)
      for (const double v : row) sep(), put_curve_number(out, v);
  } else {
    out += '3';
    for (const auto& p : c.bezier)
      for (std::size_t k = 0; k < 3; ++k) sep(), put_curve_number(out, coord(p, k));
  }
  out += '\n';
}

/// Reads one line of comma-separated numbers (blanks around commas allowed) into `values`,
/// at most `max_values` of them; `what(i)` names value i for errors and `check(i, v, at)` may
/// reject a value where it stands. Leaves the cursor on the line end. O(line length).
template <class What, class Check>
void read_number_list(text_cursor& c, std::vector<double>& values, std::size_t max_values, What&& what,
                      Check&& check) {
  values.clear();
  const auto token = [&]() -> std::string {
    if (c.at_line_end()) return c.pos == c.end ? "end of file" : "end of line";
    const char* q = c.pos;
    while (q != c.end && *q != ',' && !is_blank(*q) && !is_eol(*q) && q - c.pos < 32) ++q;
    return cellforge::detail::cat("'", std::string(c.pos, q), "'");
  };
  for (;;) {
    c.skip_blanks();
    if (values.size() == max_values)
      c.fail(cellforge::detail::cat("too many values: expected at most ", std::to_string(max_values)));
    const char* start = c.pos;
    double v = 0;
    const parse_status s = c.at_line_end() ? parse_status::bad : parse_number(c.pos, c.end, v);
    if (s == parse_status::bad)
      c.fail(cellforge::detail::cat("expected ", what(values.size()), ", found ", token()));
    if (s == parse_status::out_of_range) {
      c.pos = start;
      c.fail(what(values.size()) + " " + token() + " is out of range");
    }
    if (!std::isfinite(v)) {
      c.pos = start;
      c.fail(what(values.size()) + " " + token() + " is not finite (NaN and Inf are rejected)");
    }
    check(values.size(), v, start);
    values.push_back(v);
    c.skip_blanks();
    if (c.at_line_end()) return;
    if (*c.pos != ',')
      c.fail(cellforge::detail::cat("expected ',' or the end of the line after ", what(values.size() - 1),
                                    ", found ", token()));
    ++c.pos;
  }
}

/// Names the values of a curve line for error messages.
template <class = void>
std::string curve_value_name(std::size_t i, int axis) {
  static constexpr const char* axis_names[] = {"the axis", "the limit at the start", "the limit at the end"};
  if (i < 3 && (i == 0 || axis < 3)) return axis_names[i];
  if (axis < 3)
    return cellforge::detail::cat("coefficient ", std::string(1, static_cast<char>('a' + (i - 3))));
  return cellforge::detail::cat("Bezier coordinate ", std::string(1, "xyz"[(i - 1) % 3]),
                                std::to_string((i - 1) / 3));
}

}  // namespace detail

/// The curve file's text: one line per curve of a range of edge_curve<P> (a vector, array or
/// span), the seed's layout (docs/formats.md "Curve file"), numbers in shortest round-trip form
/// (Bézier points in P's scalar). Throws invalid_input on curves the reader would refuse. O(n).
template <edge_curve_range R>
std::string curve_file_text(const R& curves, const curve_write_options& options = {}) {
  std::string out;
  detail::put_comment(out, options.comment);
  std::size_t i = 0;
  for (const auto& c : curves) {
    detail::check_curve(c, i++, "write_curve_file");
    detail::put_curve_line(out, c);
  }
  return out;
}

/// Writes the curve file to a stream. Throws like curve_file_text, io if the stream fails. O(n).
template <edge_curve_range R>
void write_curve_file(std::ostream& os, const R& curves, const curve_write_options& options = {}) {
  const std::string text = curve_file_text(curves, options);
  os.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!os) throw error(error_category::io, "writing the curve file failed (stream error)");
}

/// Writes the curve file; throws io naming the path when it cannot be written. O(n).
template <edge_curve_range R>
void write_curve_file(const file_path& path, const R& curves, const curve_write_options& options = {}) {
  const std::string text = curve_file_text(curves, options);  // checks before the file is created
  detail::write_text_file(path, text);
}

namespace detail {

/// parse_curve_file in double precision.
template <class = void>
std::vector<edge_curve<glm::dvec3>> parse_curves(std::string_view text, std::string_view name) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  text_cursor c(text, name);
  std::vector<edge_curve<glm::dvec3>> curves;
  std::vector<double> v;
  while (c.next_content()) {
    const char* line = c.pos;
    int axis = 0;  // set by the first value, so that later values are named by the layout
    read_number_list(
        c, v, 13, [&](std::size_t i) { return curve_value_name(i, axis); },
        [&](std::size_t i, double a, const char* at) {
          if (i != 0) return;
          if (!(a == 0.0 || a == 1.0 || a == 2.0 || a == 3.0)) {
            std::string found;
            put_curve_number(found, a);
            c.fail_at(at, cellforge::detail::cat(
                              "the axis must be 0, 1 or 2 (x, y, z) or 3 (Bezier points), found ", found));
          }
          axis = static_cast<int>(a);
        });
    const std::size_t expected = axis == 3 ? 13 : 11;
    if (v.size() != expected)
      c.fail_at(line,
                axis == 3
                    ? cellforge::detail::cat(
                          "a Bezier curve (axis 3) needs 13 values (3, then x y z of 4 points), found ",
                          std::to_string(v.size()))
                    : cellforge::detail::cat("a curve on axis ", std::to_string(axis),
                                             " needs 11 values (axis, two limits, 8 coefficients), found ",
                                             std::to_string(v.size())));
    edge_curve<glm::dvec3> curve;
    if (axis < 3) {
      if (v[1] == v[2]) {
        std::string lim;
        put_curve_number(lim, v[1]);
        c.fail_at(line, cellforge::detail::cat("the limits are equal (both ", lim,
                                               "): a curve must run along its axis"));
      }
      std::array<std::array<double, 4>, 2> k{};
      for (int i = 0; i < 8; ++i) k[i / 4][i % 4] = v[3 + i];
      curve = cellforge::detail::axis_curve(axis, {v[1], v[2]}, k);
    } else {
      for (int i = 0; i < 12; ++i) curve.bezier[i / 3][i % 3] = v[1 + i];
      if (curve.bezier[0] == curve.bezier[3]) c.fail_at(line, "the curve starts and ends at the same point");
      curve.kind = cellforge::detail::kind_of_bezier(curve.bezier);
    }
    curve.edge = static_cast<std::uint32_t>(curves.size());
    curves.push_back(curve);
    c.next_line();
  }
  return curves;
}

template <Point3 P>
std::vector<edge_curve<P>> curves_as(std::vector<edge_curve<glm::dvec3>>&& curves) {
  if constexpr (std::is_same_v<P, glm::dvec3>) {
    return std::move(curves);
  } else {
    std::vector<edge_curve<P>> out;
    out.reserve(curves.size());
    for (const auto& c : curves) out.push_back(curve_cast<P>(c));
    return out;
  }
}

}  // namespace detail

/// Parses curve-file text into curves with control points of type P (the template argument: a
/// file has no point type); curve i gets edge = i (the file holds no ids), v0 = v1 = 0, kind from
/// its coefficients. The numbers are read and checked in double precision, then converted. Throws
/// io at file:line on a malformed line. O(size of the text).
template <Point3 P>
std::vector<edge_curve<P>> parse_curve_file(std::string_view text, std::string_view name = "<memory>") {
  return detail::curves_as<P>(detail::parse_curves(text, name));
}

/// Reads a curve file into curves of type P. Throws io naming the path, or at file:line when
/// malformed. O(file size).
template <Point3 P>
std::vector<edge_curve<P>> read_curve_file(const file_path& path) {
  return parse_curve_file<P>(detail::read_file(path), detail::display_name(path));
}

// ---------------------------------------------------------------------------------------------
// Polylines

/// A random-access, sized range (vector, span, array) of polylines, each a sized forward range of
/// points of one registered type: `std::vector<std::vector<P>>`, a span of those, a vector of spans.
template <class R>
concept polyline_range = std::ranges::random_access_range<R> && std::ranges::sized_range<R> &&
    std::ranges::forward_range<std::ranges::range_value_t<R>> &&
    std::ranges::sized_range<std::ranges::range_value_t<R>> &&
    Point3<std::ranges::range_value_t<std::ranges::range_value_t<R>>>;

namespace detail {
/// curve_polylines' result type for curve range type R (unconstrained, for if_satisfied_t).
template <class R>
using curve_polylines_for =
    std::vector<std::vector<typename edge_curve_point<std::ranges::range_value_t<R>>::type>>;
}  // namespace detail

/// Every curve as `segments` straight pieces (segments + 1 points of the curves' type). O(n × segments).
template <edge_curve_range R>
cellforge::detail::if_satisfied_t<edge_curve_range<R>, detail::curve_polylines_for, R> curve_polylines(
    const R& curves, int segments = 15) {
  detail::check_segments(segments, "curve_polylines");
  std::vector<std::vector<edge_curve_range_point_t<R>>> out;
  out.reserve(std::ranges::size(curves));
  for (const auto& c : curves) out.push_back(c.polyline(segments));
  return out;
}

/// The polyline file's text: one polyline per line, `x0, y0, z0, x1, y1, z1, ...` (docs/formats.md
/// "Polyline file"), coordinates in the points' own scalar. Throws invalid_input on non-finite
/// points or a polyline of < 2 points. O(points).
template <polyline_range R>
std::string polyline_file_text(const R& polylines, const curve_write_options& options = {}) {
  std::string out;
  detail::put_comment(out, options.comment);
  for (std::size_t i = 0; i < std::ranges::size(polylines); ++i) {
    const auto& pl = polylines[i];
    if (std::ranges::size(pl) < 2)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_polyline_file: polyline ", std::to_string(i),
                                         " has fewer than 2 points"));
    bool first = true;
    for (const auto& p : pl) {
      detail::check_point_finite(p, i, "polyline_file");
      for (std::size_t k = 0; k < 3; ++k) {
        if (!first) out += ", ";
        first = false;
        detail::put_curve_number(out, coord(p, k));
      }
    }
    out += '\n';
  }
  return out;
}

/// Writes polylines as a polyline file. Throws like polyline_file_text, io when the file fails. O(points).
template <polyline_range R>
void write_polyline_file(const file_path& path, const R& polylines, const curve_write_options& options = {}) {
  detail::write_text_file(path, polyline_file_text(polylines, options));
}

/// Writes every curve as options.segments pieces (the seed's display file: 15). O(n × segments).
template <edge_curve_range R>
void write_polyline_file(const file_path& path, const R& curves, const curve_write_options& options = {}) {
  write_polyline_file(path, curve_polylines(curves, options.segments), options);
}

namespace detail {

/// parse_polyline_file in double precision.
template <class = void>
std::vector<std::vector<glm::dvec3>> parse_polylines(std::string_view text, std::string_view name) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  text_cursor c(text, name);
  std::vector<std::vector<glm::dvec3>> out;
  std::vector<double> v;
  while (c.next_content()) {
    const char* line = c.pos;
    read_number_list(
        c, v, std::size_t{3} << 24,
        [](std::size_t i) {
          return cellforge::detail::cat("coordinate ", std::string(1, "xyz"[i % 3]), " of point ",
                                        std::to_string(i / 3));
        },
        [](std::size_t, double, const char*) {});
    if (v.size() % 3 != 0 || v.size() < 6)
      c.fail_at(line, cellforge::detail::cat(
                          "a polyline needs x, y, z of at least 2 points (a multiple of 3 values), found ",
                          std::to_string(v.size()), " values"));
    std::vector<glm::dvec3>& pl = out.emplace_back();
    for (std::size_t i = 0; i < v.size(); i += 3) pl.emplace_back(v[i], v[i + 1], v[i + 2]);
    c.next_line();
  }
  return out;
}

}  // namespace detail

/// Parses polyline-file text into polylines of points of type P (the template argument: a file
/// has no point type): one polyline per line, 3k numbers (k >= 2), read in double precision and
/// converted. Throws io at file:line on a malformed line. O(size of the text).
template <Point3 P>
std::vector<std::vector<P>> parse_polyline_file(std::string_view text, std::string_view name = "<memory>") {
  std::vector<std::vector<glm::dvec3>> d = detail::parse_polylines(text, name);
  if constexpr (std::is_same_v<P, glm::dvec3>) {
    return d;
  } else {
    std::vector<std::vector<P>> out(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      out[i].reserve(d[i].size());
      for (const glm::dvec3& p : d[i]) out[i].push_back(from_dvec3<P>(p));
    }
    return out;
  }
}

/// Reads a polyline file into points of type P. Throws io naming the path, or at file:line when
/// malformed. O(file size).
template <Point3 P>
std::vector<std::vector<P>> read_polyline_file(const file_path& path) {
  return parse_polyline_file<P>(detail::read_file(path), detail::display_name(path));
}

// ---------------------------------------------------------------------------------------------
// OBJ

/// Polylines (and optionally a soup's faces) as OBJ: `v` lines, `f` lines, then one `l` line
/// per polyline, closed back to its first point when `closed`. O(points + faces).
/// The soup's point type P is independent of the polylines' (glm::dvec3 when there are no faces).
template <polyline_range R, Point3 P = glm::dvec3>
void write_polylines_obj(std::ostream& os, const R& polylines, bool closed = false,
                         const polygon_soup<P>* faces = nullptr, const curve_write_options& options = {}) {
  if (faces) detail::check_face_indices(*faces, "polylines_obj");
  for (std::size_t i = 0; i < std::ranges::size(polylines); ++i) {
    if (std::ranges::size(polylines[i]) < 2)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_polylines_obj: polyline ", std::to_string(i),
                                         " has fewer than 2 points"));
    for (const auto& p : polylines[i]) detail::check_point_finite(p, i, "polylines_obj");
  }
  detail::output_buffer out(os);
  detail::put_comment_lines(out, options.comment, "# ");
  std::uint64_t base = 1;  // OBJ indices are 1-based
  if (faces) {
    detail::put_obj_vertices(out, faces->points);
    detail::put_obj_faces(out, *faces, {});
    base += faces->points.size();
  }
  for (const auto& pl : polylines)
    for (const auto& p : pl) {
      out.put("v ");
      for (std::size_t k = 0; k < 3; ++k) out.number(coord(p, k)), out.put(k < 2 ? ' ' : '\n');
    }
  for (const auto& pl : polylines) {
    out.put('l');
    const std::size_t n = std::ranges::size(pl);
    for (std::size_t j = 0; j < n; ++j) out.put(' '), out.number(base + j);
    if (closed) out.put(' '), out.number(base);
    out.put('\n');
    base += n;
  }
  out.finish("OBJ");
}

/// Writes polylines (and optionally faces) to an OBJ file; see the stream overload. O(size).
template <polyline_range R, Point3 P = glm::dvec3>
void write_polylines_obj(const file_path& path, const R& polylines, bool closed = false,
                         const polygon_soup<P>* faces = nullptr, const curve_write_options& options = {}) {
  detail::write_file(path,
                     [&](std::ostream& os) { write_polylines_obj(os, polylines, closed, faces, options); });
}

/// Writes every curve as one `l` polyline of options.segments pieces (faces too when given). O(n × segments).
template <edge_curve_range R, Point3 P = glm::dvec3>
void write_polylines_obj(const file_path& path, const R& curves, const polygon_soup<P>* faces = nullptr,
                         const curve_write_options& options = {}) {
  write_polylines_obj(path, curve_polylines(curves, options.segments), false, faces, options);
}

// ---------------------------------------------------------------------------------------------
// SVG pictures

namespace detail {

/// A solid's style for the pictures below: shaded faces, edges drawn only where visible.
template <class = void>
svg_style solid_style(std::string fill, std::string stroke, double stroke_width) {
  svg_style s;
  s.fill = std::move(fill);
  s.stroke = std::move(stroke);
  s.stroke_width = stroke_width;
  s.draw_hidden = false;
  return s;
}

}  // namespace detail

/// A picture of thin loops on their solid.
struct thin_loops_svg_options {
  svg_options picture{};
  svg_style solid = detail::solid_style("#c9d6e3", "#6b7b8c", 0.4);
  /// Loop colours, strongest first; the last repeats for further loops.
  std::vector<std::string> colours{"#d62728", "#ff7f0e", "#9467bd", "#2ca02c", "#8c564b"};
  double width = 4.0;         ///< stroke of the strongest loop in pixels; each next one 0.7× (at least 1.5)
  std::size_t max_loops = 5;  ///< loops drawn (the first ones: strongest first)
  bool labels = true;         ///< number each loop ("1" = strongest)
};

/// Straight edges (left) beside the smoothed curves (right), same view.
struct smoothing_svg_options {
  svg_options picture = [] {
    svg_options o;
    o.width = 1100;
    o.height = 520;
    return o;
  }();
  svg_style solid = detail::solid_style("#d9e4ee", "#1f3b57", 1.0);
  std::string curve_colour = "#b03a2e";
  double curve_width = 1.4;  ///< pixels
  int segments = 15;         ///< straight pieces per curve (the seed's 15)
  double gap = 0.15;         ///< space between the panels, as a fraction of one panel's width
  bool labels = true;        ///< "straight edges" / "smoothed edges" above the panels
};

namespace detail {

/// The screen's right and up directions in world coordinates for a view (as svg_scene draws it). O(1).
template <class = void>
std::array<glm::dvec3, 2> screen_axes(const svg_view& v) {
  const double az = v.azimuth_deg * std::numbers::pi / 180.0, el = v.elevation_deg * std::numbers::pi / 180.0;
  const glm::dvec3 toward(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  const glm::dvec3 right(-std::sin(az), std::cos(az), 0.0);
  const glm::dvec3 up = glm::cross(toward, right);
  const int shift = v.up == svg_up_axis::z ? 0 : v.up == svg_up_axis::x ? 1 : 2;
  std::array<glm::dvec3, 2> out{glm::dvec3(0.0), glm::dvec3(0.0)};
  for (int i = 0; i < 3; ++i) out[0][(i + shift) % 3] = right[i], out[1][(i + shift) % 3] = up[i];
  return out;
}

template <class = void>
void check_curves_svg(const svg_options& o, const char* who) {
  if (!(o.width > 0 && o.height > 0))
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(who), ": picture width and height must be positive"));
}

}  // namespace detail

/// Draws a solid shaded with its thin loops (any polyline_range: point chains of any registered
/// type) as thick closed lines on it, the strongest (first) thickest; hidden parts of loops dashed.
/// O(size of the solid × local density + loop points).
template <Point3 P, polyline_range R>
svg_result write_thin_loops_svg(const file_path& path, const polygon_soup<P>& solid, const R& loops,
                                const thin_loops_svg_options& options = {}) {
  detail::check_curves_svg(options.picture, "write_thin_loops_svg");
  if (options.colours.empty() || !(options.width > 0.0))
    throw error(error_category::invalid_input, "write_thin_loops_svg: needs a colour and a positive width");
  svg_scene scene;
  scene.add_mesh(solid, options.solid);
  const std::size_t n = std::min<std::size_t>(std::ranges::size(loops), options.max_loops);
  // Labels go just right of each loop's rightmost point on the screen, clear of the line.
  const glm::dvec3 right = detail::screen_axes(options.picture.view)[0];
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& p : solid.points)
    lo = std::min(lo, glm::dot(to_dvec3(p), right)), hi = std::max(hi, glm::dot(to_dvec3(p), right));
  const glm::dvec3 nudge = right * (hi > lo ? 0.03 * (hi - lo) : 0.0);
  // Weakest first, so the strongest loop is drawn on top where loops cross.
  for (std::size_t k = n; k-- > 0;) {
    const auto& loop = loops[k];
    svg_style st;
    st.stroke = st.hidden_stroke = st.fill = options.colours[std::min(k, options.colours.size() - 1)];
    st.stroke_width = std::max(1.5, options.width * std::pow(0.7, static_cast<double>(k)));
    st.hidden_opacity = 0.45;
    scene.add_polyline(loop, st, true);
    if (options.labels && std::ranges::size(loop) != 0) {
      st.font_size = 14;
      const auto at = std::ranges::max_element(loop, [&](const auto& a, const auto& b) {
        return glm::dot(to_dvec3(a), right) < glm::dot(to_dvec3(b), right);
      });
      scene.add_label(to_dvec3(*at) + nudge, std::to_string(k + 1), st);
    }
  }
  return scene.write(path, options.picture);
}

/// write_thin_loops_svg for a surface mesh. Costs as above.
template <Point3 P, polyline_range R>
svg_result write_thin_loops_svg(const file_path& path, const surface_mesh<P>& solid, const R& loops,
                                const thin_loops_svg_options& options = {}) {
  return write_thin_loops_svg(path, to_soup(solid), loops, options);
}

namespace detail {
/// The loops' points as one span each (no copy).
template <Point3 Q>
std::vector<std::span<const Q>> loop_points(const thin_result<Q>& r) {
  std::vector<std::span<const Q>> out;
  out.reserve(r.loops.size());
  for (const thin_loop<Q>& l : r.loops) out.emplace_back(l.points);
  return out;
}
}  // namespace detail

/// write_thin_loops_svg for the loops of a find_thin_points result (in any point type Q). Costs as above.
template <Point3 P, Point3 Q>
svg_result write_thin_loops_svg(const file_path& path, const polygon_soup<P>& solid,
                                const thin_result<Q>& result, const thin_loops_svg_options& options = {}) {
  return write_thin_loops_svg(path, solid, detail::loop_points(result), options);
}

/// write_thin_loops_svg for a surface mesh and a find_thin_points result. Costs as above.
template <Point3 P, Point3 Q>
svg_result write_thin_loops_svg(const file_path& path, const surface_mesh<P>& solid,
                                const thin_result<Q>& result, const thin_loops_svg_options& options = {}) {
  return write_thin_loops_svg(path, to_soup(solid), detail::loop_points(result), options);
}

/// Two panels in one view: the solid with its straight edges (left) and the same solid with its
/// smoothed curves (any edge_curve_range) as polylines (right).
/// O((size of the solid + curves × segments) × local density).
template <Point3 P, edge_curve_range R>
svg_result write_smoothing_svg(const file_path& path, const polygon_soup<P>& solid, const R& curves,
                               const smoothing_svg_options& options = {}) {
  detail::check_curves_svg(options.picture, "write_smoothing_svg");
  if (!(options.gap >= 0.0 && options.gap <= 10.0) || !(options.curve_width > 0.0))
    throw error(error_category::invalid_input,
                "write_smoothing_svg: gap must be within 0 .. 10 and curve_width positive");
  const auto polylines = curve_polylines(curves, options.segments);
  // The panel's extent on the screen, from the solid and the curves (which may bulge out of it).
  const std::array<glm::dvec3, 2> axes = detail::screen_axes(options.picture.view);
  const glm::dvec3 right = axes[0],
                   up = axes[1];  // named copies: lambdas may capture them (C++20 bindings not)
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, top = -lo;
  glm::dvec3 top_point(0.0);
  const auto extend = [&](const glm::dvec3& p) {
    lo = std::min(lo, glm::dot(p, right));
    hi = std::max(hi, glm::dot(p, right));
    if (glm::dot(p, up) > top) top = glm::dot(p, up), top_point = p;
  };
  for (const auto& p : solid.points) extend(to_dvec3(p));
  // All curves in one wireframe layer: one path element, however many curves.
  wireframe<glm::dvec3> w;
  for (const auto& pl : polylines) {
    const auto base = static_cast<std::uint32_t>(w.points.size());
    for (const auto& p : pl) w.points.push_back(to_dvec3(p)), extend(w.points.back());
    for (std::uint32_t j = 0; j + 1 < pl.size(); ++j) w.edges.push_back({base + j, base + j + 1});
  }
  const double width = hi > lo ? hi - lo : 1.0;
  const glm::dvec3 shift = right * (width * (1.0 + options.gap));

  svg_scene scene;
  scene.add_mesh(solid, options.solid);
  svg_style faces = options.solid;
  faces.offset = shift;
  faces.draw_edges = false;
  scene.add_mesh(solid, faces);
  svg_style lines;
  lines.stroke = lines.hidden_stroke = options.curve_colour;
  lines.stroke_width = options.curve_width;
  lines.draw_hidden = options.solid.draw_hidden;
  lines.offset = shift;
  scene.add_wireframe(w, lines);
  if (options.labels && (!solid.points.empty() || !polylines.empty())) {
    svg_style text;
    text.font_size = 16;
    text.stroke = "#333333";
    const glm::dvec3 at = top_point - right * (glm::dot(top_point, right) - lo) + up * (0.08 * width);
    scene.add_label(at, "straight edges", text);
    text.offset = shift;
    scene.add_label(
        at, cellforge::detail::cat("smoothed edges (", std::to_string(std::ranges::size(curves)), " curves)"),
        text);
  }
  return scene.write(path, options.picture);
}

/// write_smoothing_svg for a surface mesh. Costs as above.
template <Point3 P, edge_curve_range R>
svg_result write_smoothing_svg(const file_path& path, const surface_mesh<P>& solid, const R& curves,
                               const smoothing_svg_options& options = {}) {
  return write_smoothing_svg(path, to_soup(solid), curves, options);
}

}  // namespace cellforge::io
