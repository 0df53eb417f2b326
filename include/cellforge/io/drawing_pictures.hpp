// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Pictures of line drawings: the edges as `<line>`s, junction dots and labels, and face loops
/// as translucent polygons in golden-angle hues, in drawing coordinates (y flipped back for
/// SVG); drawings with arcs add them as `A` path commands. The edges read back through
/// read_svg_drawing (and the arcs through parse_svg_arc_drawing); the rest is marked
/// `data-cellforge` so that the reader skips it. See docs/formats.md ("SVG line drawings").

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/io/detail/arc_io.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/xml.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge::io {

/// How a drawing is pictured.
struct drawing_svg_options {
  double width_px = 640;             ///< width of the picture; the height follows the drawing's shape
  double margin = 0.06;              ///< free space around the drawing, a fraction of its larger side
  double stroke_px = 1.5;            ///< edge width in output pixels
  std::string stroke = "#1f3b57";    ///< edge colour
  bool junction_dots = true;         ///< a dot on every junction
  double dot_px = 2.5;               ///< dot radius in output pixels
  bool labels = false;               ///< junction numbers next to the dots
  double font_px = 11;               ///< label size in output pixels
  double face_opacity = 0.35;        ///< fill opacity of the face polygons
  std::string background = "white";  ///< empty or "none": transparent
  std::string title{};               ///< written as `<title>`
};

namespace detail {

/// Appends a number in shortest round-trip form. O(1).
template <class = void>
void drawing_svg_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

/// The k-th colour of a sequence of distinct hues (golden angle apart), as `#rrggbb`. O(1).
template <class = void>
std::string golden_colour(std::size_t k) {
  const double h = std::fmod(static_cast<double>(k) * 137.50776405003785, 360.0) / 60.0;
  const double s = 0.65, l = 0.5;  // HSL
  const double c = (1 - std::abs(2 * l - 1)) * s, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)),
               m = l - c / 2;
  const int sector = static_cast<int>(h) % 6;
  const double rgb[6][3] = {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}};
  std::string out = "#";
  constexpr char hex[] = "0123456789abcdef";
  for (int i = 0; i < 3; ++i) {
    const int v = std::clamp(static_cast<int>(std::lround((rgb[sector][i] + m) * 255)), 0, 255);
    out += hex[v >> 4];
    out += hex[v & 15];
  }
  return out;
}

}  // namespace detail

namespace detail {

/// The picture of drawing_svg_string, with `extent` (SVG coordinates) inside the view box too
/// and `strokes(out, pts, num)` writing more strokes into the edges group after the lines.
/// O(V + E + loops + what strokes writes).
template <LineDrawing D, class Strokes>
std::string drawing_svg_picture(const D& d, const std::vector<std::vector<std::uint32_t>>& faces,
                                const drawing_svg_options& options, const std::vector<glm::dvec2>& extent,
                                Strokes&& strokes) {
  using T = line_drawing_traits<D>;
  using P = drawing_point_t<D>;
  const std::size_t nv = T::num_junctions(d), ne = T::num_edges(d);
  std::vector<glm::dvec2> pts(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    const glm::dvec2 p = to_dvec2(P(T::position(d, i)));
    if (!std::isfinite(p.x) || !std::isfinite(p.y))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("drawing_svg: junction ", std::to_string(i), " is not finite"));
    pts[i] = {p.x, -p.y};  // SVG's y points down
  }
  const auto check = [&](std::size_t v, const std::string& where) {
    if (v >= nv)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("drawing_svg: ", where, " names junction ", std::to_string(v),
                                         " of ", std::to_string(nv)));
  };
  glm::dvec2 lo{0, 0}, hi{1, 1};
  if (nv > 0) {
    lo = hi = pts[0];
    for (const auto& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
    for (const auto& p : extent) lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  double side = std::max(hi.x - lo.x, hi.y - lo.y);
  if (!(side > 0)) side = std::max(1.0, std::abs(lo.x) + std::abs(lo.y));
  const double pad = options.margin * side;
  const glm::dvec2 vb0 = lo - pad, vb_size = (hi - lo) + 2 * pad;
  const double w = std::max(vb_size.x, side * 1e-3), h = std::max(vb_size.y, side * 1e-3);
  const double px = w / options.width_px;  // user units per output pixel
  std::string out;
  const auto num = [&](double v) { detail::drawing_svg_number(out, v); };
  const auto attr = [&](std::string_view key, double v) {
    out += ' ';
    out += key;
    out += "=\"";
    num(v);
    out += '"';
  };
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\"";
  attr("width", options.width_px);
  attr("height", std::round(options.width_px * h / w));
  out += " viewBox=\"";
  num(vb0.x);
  out += ' ';
  num(vb0.y);
  out += ' ';
  num(w);
  out += ' ';
  num(h);
  out += "\">\n";
  if (!options.title.empty()) {
    out += "<title>";
    detail::svg_escape(out, options.title);
    out += "</title>\n";
  }
  if (!options.background.empty() && options.background != "none") {
    out += "<rect data-cellforge=\"background\"";
    attr("x", vb0.x);
    attr("y", vb0.y);
    attr("width", w);
    attr("height", h);
    out += " fill=\"";
    detail::svg_escape(out, options.background);
    out += "\"/>\n";
  }
  if (!faces.empty()) {
    out += "<g data-cellforge=\"faces\" stroke=\"none\" fill-rule=\"evenodd\"";
    attr("fill-opacity", options.face_opacity);
    out += ">\n";
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (faces[f].size() < 3) continue;
      out += cellforge::detail::cat("<path fill=\"", detail::golden_colour(f), "\" d=\"");
      for (std::size_t k = 0; k < faces[f].size(); ++k) {
        check(faces[f][k], cellforge::detail::cat("face loop ", std::to_string(f)));
        out += k == 0 ? "M" : " L";
        num(pts[faces[f][k]].x);
        out += ' ';
        num(pts[faces[f][k]].y);
      }
      out += cellforge::detail::cat(" Z\"><title>face loop ", std::to_string(f), "</title></path>\n");
    }
    out += "</g>\n";
  }
  out += "<g data-cellforge=\"edges\" fill=\"none\" stroke-linecap=\"round\" stroke=\"";
  detail::svg_escape(out, options.stroke);
  out += '"';
  attr("stroke-width", options.stroke_px * px);
  out += ">\n";
  for (std::size_t e = 0; e < ne; ++e) {
    const std::array<std::size_t, 2> ab = T::endpoints(d, e);
    check(ab[0], cellforge::detail::cat("edge ", std::to_string(e)));
    check(ab[1], cellforge::detail::cat("edge ", std::to_string(e)));
    out += "<line";
    attr("x1", pts[ab[0]].x);
    attr("y1", pts[ab[0]].y);
    attr("x2", pts[ab[1]].x);
    attr("y2", pts[ab[1]].y);
    out += "/>\n";
  }
  strokes(out, pts, num);
  out += "</g>\n";
  if (options.junction_dots && nv > 0) {
    out += "<g data-cellforge=\"junctions\" fill=\"";
    detail::svg_escape(out, options.stroke);
    out += "\">\n";
    for (std::size_t i = 0; i < nv; ++i) {
      out += "<circle";
      attr("cx", pts[i].x);
      attr("cy", pts[i].y);
      attr("r", options.dot_px * px);
      out += "/>\n";
    }
    out += "</g>\n";
  }
  if (options.labels && nv > 0) {
    out += "<g data-cellforge=\"labels\" font-family=\"sans-serif\"";
    attr("font-size", options.font_px * px);
    out += " fill=\"";
    detail::svg_escape(out, options.stroke);
    out += "\">\n";
    for (std::size_t i = 0; i < nv; ++i) {
      out += "<text";
      attr("x", pts[i].x + 1.5 * options.dot_px * px);
      attr("y", pts[i].y - 1.5 * options.dot_px * px);
      out += cellforge::detail::cat(">", std::to_string(i), "</text>\n");
    }
    out += "</g>\n";
  }
  out += "</svg>\n";
  return out;
}

}  // namespace detail

/// The SVG picture of a drawing and its face loops (junction cycles; each a polygon in its own
/// colour) as text. Edges are `<line>`s with exact coordinates (x, -y) in a `<g
/// data-cellforge="edges">`; faces, dots and labels are in groups read_svg_drawing skips. Throws
/// invalid_input on NaN/Inf positions or an index out of range. O(V + E + total loop length).
template <LineDrawing D>
std::string drawing_svg_string(const D& d, const std::vector<std::vector<std::uint32_t>>& faces = {},
                               const drawing_svg_options& options = {}) {
  return detail::drawing_svg_picture(d, faces, options, {}, [](std::string&, const auto&, const auto&) {});
}

/// The picture of a drawing with arcs: as drawing_svg_string, and each arc a `<path d="M x0 y0
/// A rx ry rotation large sweep x1 y1">` between its junctions in the edges group (y flipped:
/// the rotation negated and the sweep flag the opposite of ccw), read back by
/// parse_svg_arc_drawing. `arc_colour[k]`, when given for every arc, draws arc k in the k-th
/// golden-angle hue (e.g. the pair it belongs to). Throws invalid_input as drawing_svg_string,
/// and on an arc validate(arc_drawing) refuses. O(V + E + A + loops).
template <Point2 P>
std::string arc_drawing_svg_string(const arc_drawing<P>& d,
                                   const std::vector<std::vector<std::uint32_t>>& faces = {},
                                   const drawing_svg_options& options = {},
                                   const std::vector<std::size_t>& arc_colour = {}) {
  if (const arc_validation v = validate(d); !v)
    throw error(error_category::invalid_input, cellforge::detail::cat("arc_drawing_svg: ", v.message));
  if (!arc_colour.empty() && arc_colour.size() != d.arcs.size())
    throw error(error_category::invalid_input,
                cellforge::detail::cat("arc_drawing_svg: ", std::to_string(arc_colour.size()),
                                       " arc colours for ", std::to_string(d.arcs.size()), " arcs"));
  std::vector<glm::dvec2> extent;
  for (const drawing_arc<P>& a : d.arcs)
    for (int k = 0; k <= 16; ++k) {
      const glm::dvec2 p = to_dvec2(arc_point(a.curve, k / 16.0));
      extent.push_back({p.x, -p.y});
    }
  return detail::drawing_svg_picture(
      d.lines, faces, options, extent,
      [&](std::string& out, const std::vector<glm::dvec2>& pts, const auto& num) {
        for (std::size_t k = 0; k < d.arcs.size(); ++k) {
          const drawing_arc<P>& a = d.arcs[k];
          const elliptical_arc<P>& c = a.curve;
          out += "<path";
          if (!arc_colour.empty())
            out += cellforge::detail::cat(" stroke=\"", detail::golden_colour(arc_colour[k]), "\"");
          out += " d=\"M";
          num(pts[a.ends[0]].x);
          out += ' ';
          num(pts[a.ends[0]].y);
          out += " A";
          num(c.rx);
          out += ' ';
          num(c.ry);
          out += ' ';
          num(detail::arc_degrees(-c.rotation));
          const auto flags = arc_endpoint_form(c);
          out += flags.large_arc ? " 1" : " 0";
          out += flags.ccw ? " 0 " : " 1 ";  // SVG's sweep flag is y-down's: the opposite of ccw
          num(pts[a.ends[1]].x);
          out += ' ';
          num(pts[a.ends[1]].y);
          out += cellforge::detail::cat("\"><title>arc ", std::to_string(k), "</title></path>\n");
        }
      });
}

/// Writes the picture of arc_drawing_svg_string to a file; io errors name the path. O(V + E + A + loops).
template <Point2 P>
void write_arc_drawing_svg(const file_path& path, const arc_drawing<P>& d,
                           const std::vector<std::vector<std::uint32_t>>& faces = {},
                           const drawing_svg_options& options = {},
                           const std::vector<std::size_t>& arc_colour = {}) {
  const std::string text = arc_drawing_svg_string(d, faces, options, arc_colour);
  detail::write_file(path, [&](std::ostream& os) {
    os.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!os) throw error(error_category::io, "writing SVG failed (stream error)");
  });
}

/// Writes the picture of drawing_svg_string to a file; io errors name the path. O(V + E + loops).
template <LineDrawing D>
void write_drawing_svg(const file_path& path, const D& d,
                       const std::vector<std::vector<std::uint32_t>>& faces = {},
                       const drawing_svg_options& options = {}) {
  const std::string text = drawing_svg_string(d, faces, options);
  detail::write_file(path, [&](std::ostream& os) {
    os.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!os) throw error(error_category::io, "writing SVG failed (stream error)");
  });
}

}  // namespace cellforge::io
