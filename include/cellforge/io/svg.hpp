// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// SVG pictures: an orthographic view of meshes, wireframes, polylines, points and labels,
/// with Lambert-shaded faces (painter's algorithm) and every edge split exactly into its
/// visible part (solid) and hidden part (dashed). Build an `svg_scene` layer by layer, write once.

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <ostream>
#include <ranges>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/edge_table.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/svg_visibility.hpp"
#include "cellforge/io/detail/xml.hpp"
#include "cellforge/io/file_path.hpp"

namespace cellforge::io {

/// The world axis drawn pointing up on the screen.
enum class svg_up_axis : std::uint8_t { x, y, z };

/// An orthographic camera looking at the centre of the scene's bounding box.
struct svg_view {
  /// Turn of the camera about the up axis, in degrees, from the first horizontal axis toward
  /// the second (z up: from +x toward +y; y up: from +z toward +x; x up: from +y toward +z).
  double azimuth_deg = 35;
  /// Height of the camera above the horizontal plane, in degrees (-90 .. 90).
  double elevation_deg = 25;
  svg_up_axis up = svg_up_axis::z;
};

/// How one layer looks. Colours are SVG colours; a fill given as `#rgb` or `#rrggbb` is shaded
/// per face, any other fill (e.g. "red") is used flat.
struct svg_style {
  std::string fill = "#9fc5e8";    ///< faces; point markers
  std::string stroke = "#1f3b57";  ///< edges, lines, marker outlines, label text
  double stroke_width = 1.0;       ///< in output pixels
  double opacity = 1.0;            ///< of the faces' fill (0 .. 1)
  bool draw_edges = true;          ///< meshes: draw the edges over the faces
  /// Meshes: 0 draws every edge; a positive angle draws only boundary, non-manifold and
  /// silhouette edges and those whose faces meet at more than this angle (degrees).
  double feature_angle_deg = 0;
  bool draw_hidden = true;                ///< draw the hidden parts of edges and points
  std::string hidden_stroke = "#1f3b57";  ///< colour of hidden parts (dashed, see-through)
  double hidden_opacity = 0.7;            ///< hidden parts are drawn over the faces
  std::string hidden_dash{};     ///< SVG dash array of hidden parts; empty: 4 on, 3 off per stroke width
  bool cull_back_faces = false;  ///< meshes: skip faces turned away (closed, oriented meshes)
  bool occludes = true;          ///< meshes: faces hide edges and points behind them
  double font_size = 12;         ///< labels, in output pixels
  glm::dvec3 offset{0.0};        ///< added to every point of the layer: exploded views, side by side
};

/// The picture as a whole.
struct svg_options {
  int width = 800, height = 600;  ///< pixels
  double margin = 20;             ///< pixels kept free around the drawing
  svg_view view{};
  /// Direction toward the light in camera coordinates (right, up, toward the viewer).
  glm::dvec3 light{-0.3, 0.8, 1.0};
  double ambient = 0.45;             ///< share of a face's colour it keeps when lit edge-on (0 .. 1)
  std::string background = "white";  ///< empty or "none": transparent
  std::string title{};               ///< written as `<title>`
  int precision = 2;                 ///< decimals of coordinates (0 .. 9)
  /// A face hides a point only when nearer by more than this fraction of the scene's diagonal.
  double depth_epsilon = 1e-6;
  /// Visible or hidden pieces shorter than this (projected, in pixels) join their neighbours.
  double min_piece_px = 0.05;
  /// Work units (grid cells visited, faces considered, polygon sides examined) the exact
  /// hidden-line tests may spend; 0: 1.6 x 10^7 + 256 per edge and point. Past it, edges and points
  /// are judged from one point against a few of the nearest faces; past twice it, they are
  /// drawn visible untested (svg_result counts both). The picture then stays near-linear.
  std::uint64_t work_budget = 0;
};

/// What a picture holds; edge counts are of the visibility computation, drawn or not.
struct svg_result {
  std::size_t faces_drawn = 0;
  std::size_t faces_facing_viewer = 0;  ///< of those drawn: right-hand normal toward the camera
  std::size_t edges = 0;                ///< mesh edges (each undirected edge once) + line segments
  std::size_t visible_edges = 0;        ///< entirely visible
  std::size_t hidden_edges = 0;         ///< entirely hidden
  std::size_t partly_hidden_edges = 0;
  std::size_t visible_pieces = 0, hidden_pieces = 0;  ///< pieces after splitting edges
  std::size_t points_visible = 0, points_hidden = 0;
  std::size_t labels = 0;
  /// Past the work budget (svg_options::work_budget): edges and points judged hidden or not as
  /// a whole from one point, and those not tested at all (drawn visible).
  std::size_t approximate_edges = 0, untested_edges = 0;
  std::size_t approximate_points = 0, untested_points = 0;
  std::uint64_t work = 0;  ///< work units the hidden-line tests spent
};

/// One edge or segment of the scene and where it is hidden.
struct svg_edge_visibility {
  std::size_t layer = 0;                        ///< as returned by the add_ call
  glm::dvec3 a{0.0}, b{0.0};                    ///< ends, with the layer's offset applied
  std::vector<std::array<double, 2>> hidden{};  ///< sorted disjoint intervals of t (point a + t (b - a))
  bool exact = true;  ///< false: past the work budget, judged as a whole from its midpoint or not at all
};

namespace detail {

/// Appends v with `precision` decimals, trailing zeros dropped; locale-independent. O(1).
template <class = void>
void svg_number(std::string& out, double v, int precision) {
  static constexpr double powers[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
  const double scaled = v * powers[precision];
  if (std::abs(scaled) < 1e15) {
    // Fast path for every coordinate inside a picture: an integer count of the last digit.
    long long n = std::llround(scaled);
    char text[32];
    char* w = text;
    if (n < 0) {
      *w++ = '-';
      n = -n;
    }
    char digits[24];
    int k = 0;
    for (; n > 0 || k <= precision; n /= 10) digits[k++] = static_cast<char>('0' + n % 10);
    int lowest = 0;  // trailing zeros of the fraction are dropped
    while (lowest < precision && digits[lowest] == '0') ++lowest;
    for (int i = k - 1; i >= precision; --i) *w++ = digits[i];
    if (lowest < precision) {
      *w++ = '.';
      for (int i = precision - 1; i >= lowest; --i) *w++ = digits[i];
    }
    out.append(text, w);
    return;
  }
  char buf[512];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, precision);
  if (r.ec != std::errc{}) {
    out += '0';  // unreachable for coordinates inside the viewport
    return;
  }
  char* e = r.ptr;
  if (precision > 0) {
    while (e[-1] == '0') --e;
    if (e[-1] == '.') --e;
  }
  const std::string_view s(buf, static_cast<std::size_t>(e - buf));
  out += s == "-0" ? std::string_view("0") : s;
}

/// `#rgb` or `#rrggbb` as 0..1 components; nothing for any other colour syntax.
template <class = void>
std::optional<glm::dvec3> svg_parse_hex(std::string_view s) {
  const auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  if (s.empty() || s[0] != '#' || (s.size() != 4 && s.size() != 7)) return std::nullopt;
  glm::dvec3 rgb(0.0);
  for (int i = 0; i < 3; ++i) {
    int v = 0;
    if (s.size() == 4) {
      const int h = hex(s[1 + i]);
      if (h < 0) return std::nullopt;
      v = h * 17;
    } else {
      const int h = hex(s[1 + 2 * i]), l = hex(s[2 + 2 * i]);
      if (h < 0 || l < 0) return std::nullopt;
      v = h * 16 + l;
    }
    rgb[i] = v / 255.0;
  }
  return rgb;
}

template <class = void>
void svg_hex_colour(std::string& out, const glm::dvec3& rgb) {
  static constexpr char digits[] = "0123456789abcdef";
  out += '#';
  for (int i = 0; i < 3; ++i) {
    const int v = static_cast<int>(std::lround(std::clamp(rgb[i], 0.0, 1.0) * 255.0));
    out += digits[v / 16];
    out += digits[v % 16];
  }
}

/// Newell's normal of a polygon (not normalised; zero for degenerate polygons). O(n).
template <class Get>
glm::dvec3 svg_newell(std::size_t n, Get&& at) {
  glm::dvec3 nrm(0.0);
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const glm::dvec3 p = at(j), q = at(i);
    nrm += glm::dvec3((p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x), (p.x - q.x) * (p.y + q.y));
  }
  return nrm;
}

/// A forward range of registered points (what add_polyline and add_points accept).
template <class R>
concept svg_point_range = std::ranges::forward_range<R> && Point3<std::ranges::range_value_t<R>>;

template <class = void>
std::uint64_t svg_edge_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

}  // namespace detail

template <class = void>
class basic_svg_scene;
using svg_scene = basic_svg_scene<>;

/// A picture under construction: layers of meshes, lines, points and labels, each with its
/// style, written as one SVG. Every add_ call returns the new layer's index.
template <class>
class basic_svg_scene {
 public:
  /// Adds a polygon soup drawn as shaded faces plus its edges (each undirected edge once).
  /// O(size of the soup). Throws invalid_input on non-finite points or bad indices.
  template <Point3 P>
  std::size_t add_mesh(const polygon_soup<P>& soup, const svg_style& style = {}) {
    check_style(style, "add_mesh");
    const std::size_t nf = soup.num_faces();
    for (std::size_t f = 0; f < nf; ++f) {
      if (soup.face_offsets[f] > soup.face_offsets[f + 1] ||
          soup.face_offsets[f + 1] > soup.face_vertices.size())
        fail(cellforge::detail::cat("add_mesh: face ", std::to_string(f),
                                    " has inconsistent offsets in the soup"));
      for (const auto v : soup.face(f))
        if (v >= soup.points.size())
          fail(cellforge::detail::cat("add_mesh: face ", std::to_string(f), " refers to point ",
                                      std::to_string(v), " but the soup has ",
                                      std::to_string(soup.points.size()), " points"));
    }
    if (soup.face_vertices.size() >= 0xffffffffu - face_vertices_.size())
      fail("add_mesh: more than 2^32 - 2 face corners in one scene");
    const auto pts = convert_points(soup.points, style, "add_mesh");
    layer l = begin_layer(layer_kind::mesh, style);
    const auto base = static_cast<std::uint32_t>(points_.size());
    append_points(pts, "add_mesh");
    for (std::size_t f = 0; f < nf; ++f) {
      for (const auto v : soup.face(f)) face_vertices_.push_back(base + v);
      face_offsets_.push_back(static_cast<std::uint32_t>(face_vertices_.size()));
      face_layer_.push_back(static_cast<std::uint32_t>(layers_.size()));
    }
    return end_layer(l);
  }

  /// Adds the edges of any wireframe as lines. O(V + E). Throws invalid_input on non-finite
  /// points or edges naming a missing vertex.
  template <Wireframe G>
  std::size_t add_wireframe(const G& g, const svg_style& style = {}) {
    using T = wireframe_traits<G>;
    check_style(style, "add_wireframe");
    const std::size_t nv = T::num_vertices(g), ne = T::num_edges(g);
    for (std::size_t e = 0; e < ne; ++e) {
      const std::array<std::size_t, 2> ab = T::endpoints(g, e);
      if (ab[0] >= nv || ab[1] >= nv)
        fail(cellforge::detail::cat("add_wireframe: edge ", std::to_string(e), " refers to vertex ",
                                    std::to_string(std::max(ab[0], ab[1])), " but the wireframe has ",
                                    std::to_string(nv), " vertices"));
    }
    std::vector<glm::dvec3> pts;
    pts.reserve(nv);
    for (std::size_t v = 0; v < nv; ++v)
      pts.push_back(checked_point(to_dvec3(T::position(g, v)), style, v, "add_wireframe"));
    layer l = begin_layer(layer_kind::lines, style);
    const auto base = static_cast<std::uint32_t>(points_.size());
    append_points(pts, "add_wireframe");
    for (std::size_t e = 0; e < ne; ++e) {
      const std::array<std::size_t, 2> ab = T::endpoints(g, e);
      segments_.push_back(
          {base + static_cast<std::uint32_t>(ab[0]), base + static_cast<std::uint32_t>(ab[1])});
    }
    return end_layer(l);
  }

  /// Adds a polyline through the points, closed back to the first when asked. O(n).
  template <detail::svg_point_range R>
  std::size_t add_polyline(R&& points, const svg_style& style = {}, bool closed = false) {
    check_style(style, "add_polyline");
    const auto pts = convert_points(points, style, "add_polyline");
    layer l = begin_layer(layer_kind::lines, style);
    const auto base = static_cast<std::uint32_t>(points_.size());
    append_points(pts, "add_polyline");
    const auto n = static_cast<std::uint32_t>(points_.size() - base);
    for (std::uint32_t i = 0; i + 1 < n; ++i) segments_.push_back({base + i, base + i + 1});
    if (closed && n >= 3) segments_.push_back({base + n - 1, base});
    return end_layer(l);
  }

  /// Adds points drawn as circles of `radius` pixels (fill and stroke from the style). O(n).
  template <detail::svg_point_range R>
  std::size_t add_points(R&& points, const svg_style& style = {}, double radius = 3) {
    check_style(style, "add_points");
    if (!(radius >= 0.0) || !std::isfinite(radius))
      fail(cellforge::detail::cat("add_points: the radius must be finite and >= 0, got ",
                                  std::to_string(radius)));
    const auto pts = convert_points(points, style, "add_points");
    layer l = begin_layer(layer_kind::points, style);
    l.radius = radius;
    append_points(pts, "add_points");
    return end_layer(l);
  }

  /// Adds text next to a 3D point, always drawn on top (colour: the style's stroke). O(text).
  template <Point3 P>
  std::size_t add_label(const P& at, std::string_view text, const svg_style& style = {}) {
    check_style(style, "add_label");
    const auto pts = convert_points(std::span<const P>(&at, 1), style, "add_label");
    layer l = begin_layer(layer_kind::label, style);
    l.text = std::string(text);
    append_points(pts, "add_label");
    return end_layer(l);
  }

  std::size_t num_layers() const noexcept { return layers_.size(); }
  bool empty() const noexcept { return layers_.empty(); }
  void clear() { *this = basic_svg_scene(); }

  /// Every edge and segment with the parameter intervals where faces hide it, as `write`
  /// would draw them. O(P + (E + F) x local density + F log F), the density term capped by
  /// options.work_budget.
  std::vector<svg_edge_visibility> edge_visibility(const svg_options& options = {}) const {
    const frame fr = render(options);
    std::vector<svg_edge_visibility> out;
    out.reserve(fr.edges.size());
    for (const auto& e : fr.edges)
      out.push_back({e.layer, points_[e.a], points_[e.b], e.hidden, e.quality == 0});
    return out;
  }

  /// Writes the picture to a stream; throws invalid_input on bad options, io if the stream
  /// fails. O(P + (E + F) x local density + F log F + output size), the density term capped
  /// by options.work_budget.
  svg_result write(std::ostream& os, const svg_options& options = {}) const {
    std::string text;
    const svg_result r = write_to(text, options);
    os.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!os) throw error(error_category::io, "svg: writing the picture to the stream failed");
    return r;
  }

  /// Writes the picture to a file (nothing is created when the scene or options are invalid);
  /// throws io naming the path when it cannot be written. Costs as above.
  svg_result write(const file_path& path, const svg_options& options = {}) const {
    std::string text;
    const svg_result r = write_to(text, options);
    detail::write_file(path, [&](std::ostream& os) {
      os.write(text.data(), static_cast<std::streamsize>(text.size()));
      if (!os) throw error(error_category::io, "writing the picture failed (disk full?)");
    });
    return r;
  }

 private:
  enum class layer_kind : std::uint8_t { mesh, lines, points, label };

  struct layer {
    layer_kind kind = layer_kind::mesh;
    svg_style style;
    std::uint32_t point_begin = 0, point_end = 0, face_begin = 0, face_end = 0, segment_begin = 0,
                  segment_end = 0;
    double radius = 0;
    std::string text;
  };

  struct edge {
    std::size_t layer = 0;
    std::uint32_t a = 0, b = 0;  // scene point indices
    std::vector<std::array<double, 2>> hidden;
    std::uint8_t quality = 0;  // 0 exact, 1 judged from its midpoint, 2 untested (past the work budget)
  };

  // Everything the writer needs, computed once per picture.
  struct frame {
    std::vector<glm::dvec3> screen;   // per point: x, y in pixels (y down), depth toward the viewer
    std::vector<std::uint32_t> weld;  // per point: the first point at exactly the same place
    std::vector<glm::dvec3> face_normal;
    std::vector<std::uint8_t> face_drawn, face_facing;
    std::vector<std::uint32_t> order;  // drawn faces, far to near
    std::vector<edge> edges;
    std::vector<std::uint8_t> point_hidden;  // per point of points layers
    glm::dvec3 toward{0.0};                  // unit vector from the scene toward the camera
    std::size_t approximate_points = 0, untested_points = 0;
    std::uint64_t work = 0;
  };

  [[noreturn]] static void fail(const std::string& what) {
    throw error(error_category::invalid_input, cellforge::detail::cat("basic_svg_scene::", what));
  }

  static void check_style(const svg_style& s, const char* who) {
    const auto bad = [&](const char* field, double v) {
      fail(cellforge::detail::cat(std::string(who), ": style.", field, " is out of range (",
                                  std::to_string(v), ")"));
    };
    if (!(s.stroke_width >= 0.0) || !std::isfinite(s.stroke_width)) bad("stroke_width", s.stroke_width);
    if (!(s.opacity >= 0.0 && s.opacity <= 1.0)) bad("opacity", s.opacity);
    if (!(s.hidden_opacity >= 0.0 && s.hidden_opacity <= 1.0)) bad("hidden_opacity", s.hidden_opacity);
    if (!(s.feature_angle_deg >= 0.0 && s.feature_angle_deg <= 180.0))
      bad("feature_angle_deg", s.feature_angle_deg);
    if (!(s.font_size > 0.0) || !std::isfinite(s.font_size)) bad("font_size", s.font_size);
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(s.offset[i])) bad("offset", s.offset[i]);
  }

  layer begin_layer(layer_kind kind, const svg_style& style) const {
    layer l;
    l.kind = kind;
    l.style = style;
    l.point_begin = static_cast<std::uint32_t>(points_.size());
    l.face_begin = static_cast<std::uint32_t>(face_layer_.size());
    l.segment_begin = static_cast<std::uint32_t>(segments_.size());
    return l;
  }

  std::size_t end_layer(layer& l) {
    l.point_end = static_cast<std::uint32_t>(points_.size());
    l.face_end = static_cast<std::uint32_t>(face_layer_.size());
    l.segment_end = static_cast<std::uint32_t>(segments_.size());
    layers_.push_back(std::move(l));
    return layers_.size() - 1;
  }

  /// The points of a range in double precision with the layer's offset, checked to be finite
  /// before the scene changes (a failed add_ call leaves the scene as it was). O(n).
  template <class R>
  static std::vector<glm::dvec3> convert_points(R&& points, const svg_style& style, const char* who) {
    std::vector<glm::dvec3> out;
    for (const auto& p : points) out.push_back(checked_point(to_dvec3(p), style, out.size(), who));
    return out;
  }

  static glm::dvec3 checked_point(const glm::dvec3& q, const svg_style& style, std::size_t index,
                                  const char* who) {
    const glm::dvec3 r = q + style.offset;
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
      fail(cellforge::detail::cat(std::string(who), ": point ", std::to_string(index),
                                  " has a non-finite coordinate (NaN or Inf)"));
    if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z))
      fail(cellforge::detail::cat(std::string(who), ": point ", std::to_string(index),
                                  " overflows when offset"));
    return r;
  }

  void append_points(const std::vector<glm::dvec3>& pts, const char* who) {
    if (pts.size() >= 0xffffffffu - points_.size())
      fail(cellforge::detail::cat(std::string(who), ": more than 2^32 - 2 points in one scene"));
    points_.insert(points_.end(), pts.begin(), pts.end());
  }

  /// Camera basis: right, up, toward the viewer, in world coordinates.
  static std::array<glm::dvec3, 3> camera(const svg_view& v) {
    const double az = v.azimuth_deg * std::numbers::pi / 180.0,
                 el = v.elevation_deg * std::numbers::pi / 180.0;
    // In a frame (h1, h2, up) that is x, y, z cyclically permuted so that `up` comes last.
    const glm::dvec3 toward(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    const glm::dvec3 right(-std::sin(az), std::cos(az), 0.0);
    const glm::dvec3 up = glm::cross(toward, right);
    const int shift = v.up == svg_up_axis::z ? 0 : v.up == svg_up_axis::x ? 1 : 2;
    const auto to_world = [shift](const glm::dvec3& f) {
      glm::dvec3 w(0.0);
      for (int i = 0; i < 3; ++i) w[(i + shift) % 3] = f[i];
      return w;
    };
    return {to_world(right), to_world(up), to_world(toward)};
  }

  static void check_options(const svg_options& o) {
    const auto bad = [](const std::string& what) { fail(cellforge::detail::cat("write: options.", what)); };
    if (o.width <= 0 || o.height <= 0)
      bad(cellforge::detail::cat("width and height must be positive, got ", std::to_string(o.width), " x ",
                                 std::to_string(o.height)));
    if (!(o.margin >= 0.0) || 2.0 * o.margin >= std::min(o.width, o.height))
      bad(cellforge::detail::cat("margin must be >= 0 and leave room to draw, got ",
                                 std::to_string(o.margin)));
    if (!std::isfinite(o.view.azimuth_deg) ||
        !(o.view.elevation_deg >= -90.0 && o.view.elevation_deg <= 90.0))
      bad("view: azimuth must be finite and elevation within -90 .. 90 degrees");
    if (!std::isfinite(o.light.x) || !std::isfinite(o.light.y) || !std::isfinite(o.light.z) ||
        glm::length(o.light) == 0.0)
      bad("light must be a finite non-zero direction");
    if (!(o.ambient >= 0.0 && o.ambient <= 1.0)) bad("ambient must be within 0 .. 1");
    if (o.precision < 0 || o.precision > 9) bad("precision must be within 0 .. 9");
    if (!(o.depth_epsilon >= 0.0) || !std::isfinite(o.depth_epsilon))
      bad("depth_epsilon must be finite and >= 0");
    if (!(o.min_piece_px >= 0.0) || !std::isfinite(o.min_piece_px))
      bad("min_piece_px must be finite and >= 0");
  }

  /// Sorts and merges hidden intervals, fills visible gaps and drops hidden pieces shorter
  /// than `tmin`, and snaps to the ends. O(k log k).
  static void normalise(std::vector<std::array<double, 2>>& iv, double tmin) {
    if (iv.empty()) return;
    std::sort(iv.begin(), iv.end());
    std::vector<std::array<double, 2>> merged;
    for (auto x : iv) {
      x[0] = std::clamp(x[0], 0.0, 1.0);
      x[1] = std::clamp(x[1], 0.0, 1.0);
      if (!merged.empty() && x[0] <= merged.back()[1] + tmin)
        merged.back()[1] = std::max(merged.back()[1], x[1]);
      else
        merged.push_back(x);
    }
    iv.clear();
    for (auto x : merged) {
      if (x[0] <= tmin) x[0] = 0.0;
      if (x[1] >= 1.0 - tmin) x[1] = 1.0;
      if (x[1] - x[0] > tmin || (x[0] == 0.0 && x[1] == 1.0)) iv.push_back(x);
    }
  }

  /// Projection, welding, face order and the visible/hidden split of every edge.
  frame render(const svg_options& o) const {
    check_options(o);
    frame fr;
    const std::size_t np = points_.size(), nf = face_layer_.size();
    const auto [right, up, toward] = camera(o.view);
    fr.toward = toward;
    bounding_box box;
    for (const auto& p : points_) box.add(p);
    const glm::dvec3 centre = box.center();
    const double diag = box.diagonal();
    if (!std::isfinite(diag)) fail("write: the scene is too large to draw (its extent overflows)");

    // Orthographic projection, then fit to the viewport keeping the aspect ratio, y down.
    fr.screen.resize(np);
    glm::dvec2 lo(0.0), hi(0.0);
    for (std::size_t i = 0; i < np; ++i) {
      const glm::dvec3 d = points_[i] - centre;
      fr.screen[i] = {glm::dot(d, right), glm::dot(d, up), glm::dot(d, toward)};
      const glm::dvec2 s(fr.screen[i]);
      lo = i == 0 ? s : glm::min(lo, s);
      hi = i == 0 ? s : glm::max(hi, s);
    }
    const double aw = o.width - 2.0 * o.margin, ah = o.height - 2.0 * o.margin;
    const double ex = hi.x - lo.x, ey = hi.y - lo.y;
    double scale = 1.0;
    if (ex > 0.0 && ey > 0.0)
      scale = std::min(aw / ex, ah / ey);
    else if (ex > 0.0)
      scale = aw / ex;
    else if (ey > 0.0)
      scale = ah / ey;
    if (!std::isfinite(scale)) scale = 1.0;  // a subnormal extent: the scene is one point
    const glm::dvec2 mid = 0.5 * (lo + hi);
    for (auto& s : fr.screen) {
      s.x = 0.5 * o.width + (s.x - mid.x) * scale;
      s.y = 0.5 * o.height - (s.y - mid.y) * scale;
    }

    // Points at exactly the same place are one vertex, across layers: a soup with split
    // vertices still has shared edges, and a line drawn along a mesh edge is not hidden by it.
    fr.weld.resize(np);
    {
      struct key_hash {
        std::size_t operator()(const std::array<std::uint64_t, 3>& k) const noexcept {
          std::uint64_t h = k[0] * 0x9E3779B97F4A7C15ull;
          h = (h ^ (h >> 29) ^ k[1]) * 0xBF58476D1CE4E5B9ull;
          h = (h ^ (h >> 31) ^ k[2]) * 0x94D049BB133111EBull;
          return static_cast<std::size_t>(h ^ (h >> 32));
        }
      };
      std::unordered_map<std::array<std::uint64_t, 3>, std::uint32_t, key_hash> ids;
      ids.reserve(np);
      for (std::size_t i = 0; i < np; ++i) {
        const glm::dvec3 p = points_[i] + glm::dvec3(0.0);  // -0 and +0 are one place
        const std::array<std::uint64_t, 3> k{std::bit_cast<std::uint64_t>(p.x),
                                             std::bit_cast<std::uint64_t>(p.y),
                                             std::bit_cast<std::uint64_t>(p.z)};
        fr.weld[i] = ids.try_emplace(k, static_cast<std::uint32_t>(i)).first->second;
      }
    }

    // Faces: normal, facing, drawn; painter's order by mean depth, far to near.
    fr.face_normal.resize(nf);
    fr.face_drawn.assign(nf, 0);
    fr.face_facing.assign(nf, 0);
    std::vector<double> depth(nf, 0.0);
    for (std::size_t f = 0; f < nf; ++f) {
      const auto vs = face(f);
      if (vs.size() < 3) continue;
      const glm::dvec3 n = detail::svg_newell(vs.size(), [&](std::size_t i) { return points_[vs[i]]; });
      fr.face_normal[f] = n;
      const double len = glm::length(n);
      if (!(len > 0.0)) continue;
      const bool facing = glm::dot(n, toward) > 0.0;
      if (layers_[face_layer_[f]].style.cull_back_faces && !facing) continue;
      fr.face_drawn[f] = 1;
      fr.face_facing[f] = facing ? 1 : 0;
      for (const auto v : vs) depth[f] += fr.screen[v].z;
      depth[f] /= static_cast<double>(vs.size());
      fr.order.push_back(static_cast<std::uint32_t>(f));
    }
    std::stable_sort(fr.order.begin(), fr.order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return depth[a] < depth[b]; });

    // Occluders: the drawn faces of layers that occlude. A face hides what is behind it by
    // more than eps; one sharing an end with an edge, by more than eps_shared (they meet
    // there exactly, so only rounding needs covering).
    const double eps = o.depth_epsilon * diag;
    const double eps_shared = 1e-3 * eps;
    detail::occlusion_grid grid;
    {
      std::vector<glm::dvec3> poly;
      for (const auto f : fr.order) {
        if (!layers_[face_layer_[f]].style.occludes) continue;
        poly.clear();
        for (const auto v : face(f)) poly.push_back(fr.screen[v]);
        grid.add_face(f, poly);
      }
      grid.build(eps_shared);  // the least margin the tests below ask for
    }

    // Every face side by welded vertex pair, sorted: the faces an edge belongs to.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> sides;
    sides.reserve(face_vertices_.size());
    for (std::size_t f = 0; f < nf; ++f) {
      const auto vs = face(f);
      for (std::size_t i = 0; i < vs.size(); ++i) {
        const std::uint32_t a = fr.weld[vs[i]], b = fr.weld[vs[(i + 1) % vs.size()]];
        if (a != b) sides.emplace_back(detail::svg_edge_key(a, b), static_cast<std::uint32_t>(f));
      }
    }
    std::sort(sides.begin(), sides.end());
    sides.erase(std::unique(sides.begin(), sides.end()), sides.end());
    const auto faces_of = [&](std::uint64_t key) {
      const auto lo_it =
          std::lower_bound(sides.begin(), sides.end(), std::pair<std::uint64_t, std::uint32_t>(key, 0));
      auto hi_it = lo_it;
      while (hi_it != sides.end() && hi_it->first == key) ++hi_it;
      return std::span<const std::pair<std::uint64_t, std::uint32_t>>(lo_it, hi_it);
    };

    collect_edges(fr, faces_of);

    // Whether face f has welded vertex w: a scan of a small face, a binary search for a large
    // one (so a 20 000-gon costs O(log) per test, not 20 000).
    constexpr std::size_t large_face = detail::occlusion_grid::banded_face_size;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> large_corners;  // (face, welded vertex)
    for (std::size_t f = 0; f < nf; ++f)
      if (face(f).size() > large_face)
        for (const auto v : face(f)) large_corners.emplace_back(static_cast<std::uint32_t>(f), fr.weld[v]);
    std::sort(large_corners.begin(), large_corners.end());
    const auto has_vertex = [&](std::uint32_t f, std::uint32_t w) {
      const auto vs = face(f);
      if (vs.size() > large_face)
        return std::binary_search(large_corners.begin(), large_corners.end(), std::make_pair(f, w));
      return std::any_of(vs.begin(), vs.end(), [&](std::uint32_t v) { return fr.weld[v] == w; });
    };

    // Split every edge into hidden and visible parts: exactly while the work budget lasts,
    // then from the midpoint against a few of the nearest faces, then not at all.
    std::size_t num_points = 0;
    for (const auto& l : layers_)
      if (l.kind == layer_kind::points) num_points += l.point_end - l.point_begin;
    const std::uint64_t budget =
        o.work_budget > 0 ? o.work_budget : 16'000'000 + 256 * std::uint64_t{fr.edges.size() + num_points};
    const std::uint64_t hard_limit = budget > detail::occlusion_grid::no_limit / 2 ? budget : 2 * budget;
    constexpr std::size_t approximate_faces = 16;  // nearest faces looked at past the budget
    for (auto& e : fr.edges) {
      const std::uint32_t wa = fr.weld[e.a], wb = fr.weld[e.b];
      const auto adjacent = faces_of(detail::svg_edge_key(wa, wb));  // sorted by face
      const auto margin = [&](std::uint32_t f) -> double {
        if (!adjacent.empty() &&
            std::binary_search(adjacent.begin(), adjacent.end(),
                               std::pair<std::uint64_t, std::uint32_t>(adjacent[0].first, f)))
          return -1.0;  // a face the edge belongs to
        return has_vertex(f, wa) || has_vertex(f, wb) ? eps_shared : eps;
      };
      const glm::dvec3 &a = fr.screen[e.a], &b = fr.screen[e.b];
      if (grid.work() <= budget && grid.hidden_intervals(a, b, margin, e.hidden, budget)) {
        const double len = glm::length(glm::dvec2(b) - glm::dvec2(a));
        normalise(e.hidden, len > 0.0 ? o.min_piece_px / len : 0.0);
        continue;
      }
      e.hidden.clear();
      e.quality = 2;
      if (grid.work() > hard_limit) continue;
      const int h = grid.point_test(0.5 * (a + b), margin, hard_limit, approximate_faces);
      if (h < 0) continue;
      e.quality = 1;
      if (h > 0) e.hidden.push_back({0.0, 1.0});
    }

    fr.point_hidden.assign(np, 0);
    for (const auto& l : layers_) {
      if (l.kind != layer_kind::points) continue;
      for (std::uint32_t i = l.point_begin; i < l.point_end; ++i) {
        const std::uint32_t w = fr.weld[i];
        const auto margin = [&](std::uint32_t f) -> double {
          return has_vertex(f, w) ? -1.0 : eps;  // a vertex of the face is on it, not behind it
        };
        const bool exact = grid.work() <= budget;
        const int h = grid.point_test(fr.screen[i], margin, exact ? budget : hard_limit,
                                      exact ? std::numeric_limits<std::size_t>::max() : approximate_faces);
        if (h < 0 || !exact) ++(h < 0 ? fr.untested_points : fr.approximate_points);
        fr.point_hidden[i] = h > 0 ? 1 : 0;
      }
    }
    fr.work = grid.work();
    return fr;
  }

  /// Mesh edges (each undirected edge once per layer, optionally feature edges only) and
  /// line segments, in the order they were given. O(total face size x log).
  template <class FacesOf>
  void collect_edges(frame& fr, FacesOf&& faces_of) const {
    for (std::size_t li = 0; li < layers_.size(); ++li) {
      const layer& l = layers_[li];
      if (l.kind == layer_kind::lines) {
        for (std::uint32_t s = l.segment_begin; s < l.segment_end; ++s) {
          const auto [a, b] = segments_[s];
          if (fr.weld[a] != fr.weld[b]) fr.edges.push_back({li, a, b, {}});
        }
      }
      if (l.kind != layer_kind::mesh || !l.style.draw_edges) continue;
      cellforge::detail::edge_table seen;  // welded edges drawn so far
      const double cos_feature = std::cos(l.style.feature_angle_deg * std::numbers::pi / 180.0);
      for (std::uint32_t f = l.face_begin; f < l.face_end; ++f) {
        const auto vs = face(f);
        for (std::size_t i = 0; i < vs.size(); ++i) {
          const std::uint32_t a = vs[i], b = vs[(i + 1) % vs.size()];
          const std::uint32_t wa = fr.weld[a], wb = fr.weld[b];
          if (wa == wb) continue;
          const std::uint64_t key = detail::svg_edge_key(wa, wb);
          if (!seen.try_insert(key, 0)) continue;
          if (l.style.feature_angle_deg > 0.0 && !is_feature(fr, faces_of(key), li, wa, wb, cos_feature))
            continue;
          fr.edges.push_back({li, a, b, {}});
        }
      }
    }
  }

  /// Boundary, non-manifold, silhouette or sharp: the edge shapes the picture. Orientation is
  /// read from how each face runs along the edge, so non-orientable meshes are judged right.
  bool is_feature(const frame& fr, std::span<const std::pair<std::uint64_t, std::uint32_t>> sides,
                  std::size_t li, std::uint32_t wa, std::uint32_t wb, double cos_feature) const {
    std::array<std::uint32_t, 2> two{};
    std::size_t count = 0;
    for (const auto& s : sides)
      if (face_layer_[s.second] == li) {
        if (count < 2) two[count] = s.second;
        ++count;
      }
    if (count != 2) return true;
    const auto runs_forward = [&](std::uint32_t f) {
      const auto vs = face(f);
      for (std::size_t i = 0; i < vs.size(); ++i)
        if (fr.weld[vs[i]] == wa && fr.weld[vs[(i + 1) % vs.size()]] == wb) return true;
      return false;
    };
    glm::dvec3 n0 = fr.face_normal[two[0]], n1 = fr.face_normal[two[1]];
    const double l0 = glm::length(n0), l1 = glm::length(n1);
    if (!(l0 > 0.0) || !(l1 > 0.0)) return true;
    n0 /= l0;
    n1 /= l1;
    // Consistently oriented neighbours run along their shared edge in opposite directions.
    if (runs_forward(two[0]) == runs_forward(two[1])) n1 = -n1;
    if (glm::dot(n0, fr.toward) * glm::dot(n1, fr.toward) < 0.0) return true;  // silhouette
    return glm::dot(n0, n1) < cos_feature;
  }

  std::span<const std::uint32_t> face(std::size_t f) const {
    return {face_vertices_.data() + face_offsets_[f], face_offsets_[f + 1] - face_offsets_[f]};
  }

  svg_result write_to(std::string& out, const svg_options& o) const {
    const frame fr = render(o);
    svg_result r;
    for (const auto& e : fr.edges) {
      r.approximate_edges += e.quality == 1 ? 1 : 0;
      r.untested_edges += e.quality == 2 ? 1 : 0;
    }
    r.approximate_points = fr.approximate_points;
    r.untested_points = fr.untested_points;
    r.work = fr.work;
    const int prec = o.precision;
    const auto num = [&](double v) { detail::svg_number(out, v, prec); };
    const auto attr = [&](std::string_view name, std::string_view value) {
      out += ' ';
      out += name;
      out += "=\"";
      detail::svg_escape(out, value);
      out += '"';
    };
    const auto num_attr = [&](std::string_view name, double v) {
      out += ' ';
      out += name;
      out += "=\"";
      num(v);
      out += '"';
    };

    out += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n";
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\"";
    out += cellforge::detail::cat(" width=\"", std::to_string(o.width), "\" height=\"",
                                  std::to_string(o.height), "\"");
    out += cellforge::detail::cat(" viewBox=\"0 0 ", std::to_string(o.width), " ", std::to_string(o.height),
                                  "\">\n");
    if (!o.title.empty()) {
      out += "<title>";
      detail::svg_escape(out, o.title);
      out += "</title>\n";
    }
    if (r.approximate_edges + r.untested_edges + r.approximate_points + r.untested_points > 0)
      out += cellforge::detail::cat(
          "<!-- cellforge: the hidden-line work budget ran out: ",
          std::to_string(r.approximate_edges + r.approximate_points),
          " edges and points judged from one point, ", std::to_string(r.untested_edges + r.untested_points),
          " not tested (drawn visible); raise svg_options::work_budget for exact hidden lines -->\n");
    if (!o.background.empty() && o.background != "none") {
      out += "<rect width=\"100%\" height=\"100%\"";
      attr("fill", o.background);
      out += "/>\n";
    }

    // Faces, far to near, each filled with its Lambert shade; a hairline of the same colour
    // closes the anti-aliasing cracks between neighbours.
    const glm::dvec3 light = glm::normalize(o.light);
    const auto [right, up, toward] = camera(o.view);
    if (!fr.order.empty()) {
      out += "<g stroke-width=\"0.5\" stroke-linejoin=\"round\">\n";
      std::string colour;
      for (const auto f : fr.order) {
        const svg_style& st = layers_[face_layer_[f]].style;
        const glm::dvec3 n = glm::normalize(fr.face_normal[f]);
        glm::dvec3 nc(glm::dot(n, right), glm::dot(n, up), glm::dot(n, toward));
        if (nc.z < 0.0) nc = -nc;  // two-sided: shade the side the viewer sees
        const double shade = o.ambient + (1.0 - o.ambient) * std::max(0.0, glm::dot(nc, light));
        colour.clear();
        if (const auto rgb = detail::svg_parse_hex(st.fill))
          detail::svg_hex_colour(colour, *rgb * shade);
        else
          colour = st.fill;
        out += "<polygon points=\"";
        bool first = true;
        for (const auto v : face(f)) {
          if (!first) out += ' ';
          first = false;
          num(fr.screen[v].x);
          out += ',';
          num(fr.screen[v].y);
        }
        out += '"';
        attr("fill", colour);
        if (st.opacity < 1.0) {
          num_attr("fill-opacity", st.opacity);
          out += " stroke=\"none\"";  // a hairline would double the opacity at shared sides
        } else {
          attr("stroke", colour);
        }
        out += "/>\n";
        ++r.faces_drawn;
        if (fr.face_facing[f]) ++r.faces_facing_viewer;
      }
      out += "</g>\n";
    }

    // Edge counts, then hidden parts (dashed, see-through, over the faces), then visible parts.
    for (const auto& e : fr.edges) {
      ++r.edges;
      if (e.hidden.empty())
        ++r.visible_edges;
      else if (e.hidden.size() == 1 && e.hidden[0][0] == 0.0 && e.hidden[0][1] == 1.0)
        ++r.hidden_edges;
      else
        ++r.partly_hidden_edges;
      r.hidden_pieces += e.hidden.size();
      double t = 0.0;
      for (const auto& h : e.hidden) {
        if (h[0] > t) ++r.visible_pieces;
        t = h[1];
      }
      if (t < 1.0) ++r.visible_pieces;
    }
    for (const bool hidden_pass : {true, false}) {
      std::size_t next = 0;
      for (std::size_t li = 0; li < layers_.size(); ++li) {
        const svg_style& st = layers_[li].style;
        std::string d;
        std::string last;  // the pen's position as written: chains pieces that meet
        const auto piece = [&](const glm::dvec3& a, const glm::dvec3& b, double t0, double t1) {
          const glm::dvec2 p = glm::dvec2(a) + t0 * (glm::dvec2(b) - glm::dvec2(a));
          const glm::dvec2 q = glm::dvec2(a) + t1 * (glm::dvec2(b) - glm::dvec2(a));
          std::string start;
          detail::svg_number(start, p.x, prec);
          start += ' ';
          detail::svg_number(start, p.y, prec);
          if (start != last) {
            d += 'M';
            d += start;
          }
          d += 'L';
          last.clear();
          detail::svg_number(last, q.x, prec);
          last += ' ';
          detail::svg_number(last, q.y, prec);
          d += last;
        };
        for (; next < fr.edges.size() && fr.edges[next].layer == li; ++next) {
          const edge& e = fr.edges[next];
          const glm::dvec3 &a = fr.screen[e.a], &b = fr.screen[e.b];
          if (hidden_pass) {
            for (const auto& h : e.hidden) piece(a, b, h[0], h[1]);
          } else {
            double t = 0.0;
            for (const auto& h : e.hidden) {
              if (h[0] > t) piece(a, b, t, h[0]);
              t = h[1];
            }
            if (t < 1.0) piece(a, b, t, 1.0);
          }
        }
        if (d.empty() || (hidden_pass && !st.draw_hidden)) continue;
        out += "<path";
        attr("d", d);
        out += " fill=\"none\"";
        attr("stroke", hidden_pass ? st.hidden_stroke : st.stroke);
        num_attr("stroke-width", st.stroke_width);
        if (hidden_pass) {
          if (st.hidden_dash.empty()) {
            // Dashes grow with the line so that thick hidden lines still read as dashed.
            const double w = std::max(1.0, st.stroke_width);
            std::string dash;
            detail::svg_number(dash, 4.0 * w, prec);
            dash += ' ';
            detail::svg_number(dash, 3.0 * w, prec);
            attr("stroke-dasharray", dash);
          } else {
            attr("stroke-dasharray", st.hidden_dash);
          }
          num_attr("stroke-opacity", st.hidden_opacity);
          out += " stroke-linejoin=\"round\"/>\n";  // butt caps: round ones would fill the gaps
        } else {
          out += " stroke-linecap=\"round\" stroke-linejoin=\"round\"/>\n";
        }
      }
    }

    // Points: hidden ones faint beneath the visible ones; then labels on top of everything.
    for (const auto& l : layers_) {
      if (l.kind != layer_kind::points) continue;
      for (const bool hidden_pass : {true, false}) {
        std::string body;
        for (std::uint32_t i = l.point_begin; i < l.point_end; ++i) {
          if (static_cast<bool>(fr.point_hidden[i]) != hidden_pass) continue;
          ++(hidden_pass ? r.points_hidden : r.points_visible);
          if (hidden_pass && !l.style.draw_hidden) continue;
          body += "<circle cx=\"";
          detail::svg_number(body, fr.screen[i].x, prec);
          body += "\" cy=\"";
          detail::svg_number(body, fr.screen[i].y, prec);
          body += "\" r=\"";
          detail::svg_number(body, l.radius, prec);
          body += "\"/>\n";
        }
        if (body.empty()) continue;
        // Hidden points are hollow rings in the hidden colour: they must not read as visible.
        out += "<g";
        attr("fill", hidden_pass ? std::string_view("none") : std::string_view(l.style.fill));
        attr("stroke", hidden_pass ? l.style.hidden_stroke : l.style.stroke);
        num_attr("stroke-width", l.style.stroke_width);
        if (hidden_pass) num_attr("opacity", l.style.hidden_opacity);
        out += ">\n";
        out += body;
        out += "</g>\n";
      }
    }
    for (const auto& l : layers_) {
      if (l.kind != layer_kind::label) continue;
      const glm::dvec3& p = fr.screen[l.point_begin];
      out += "<text";
      num_attr("x", p.x + 0.3 * l.style.font_size);
      num_attr("y", p.y - 0.3 * l.style.font_size);
      num_attr("font-size", l.style.font_size);
      out += " font-family=\"sans-serif\"";
      attr("fill", l.style.stroke);
      out += '>';
      detail::svg_escape(out, l.text);
      out += "</text>\n";
      ++r.labels;
    }
    out += "</svg>\n";
    return r;
  }

  std::vector<glm::dvec3> points_;  // every layer's points, offsets applied
  std::vector<std::uint32_t> face_offsets_{0};
  std::vector<std::uint32_t> face_vertices_;  // scene point indices
  std::vector<std::uint32_t> face_layer_;
  std::vector<std::array<std::uint32_t, 2>> segments_;
  std::vector<layer> layers_;
};

/// Writes a picture of one polygon soup (shaded faces, visible and hidden edges) to a file.
/// O(size + (E + F) x local density + F log F); throws like svg_scene::write.
template <Point3 P>
svg_result write_svg(const file_path& path, const polygon_soup<P>& soup, const svg_options& options = {},
                     const svg_style& style = {}) {
  svg_scene scene;
  scene.add_mesh(soup, style);
  return scene.write(path, options);
}

/// Writes a picture of one surface mesh (its live faces and edges) to a file, in one call.
/// O(size + (E + F) x local density + F log F); throws like svg_scene::write.
template <Point3 P>
svg_result write_svg(const file_path& path, const surface_mesh<P>& mesh, const svg_options& options = {},
                     const svg_style& style = {}) {
  return write_svg(path, to_soup(mesh), options, style);
}

/// Writes a picture of one wireframe (its edges as lines) to a file.
/// O(V + E); throws like svg_scene::write.
template <Wireframe G>
svg_result write_svg(const file_path& path, const G& g, const svg_options& options = {},
                     const svg_style& style = {}) {
  svg_scene scene;
  scene.add_wireframe(g, style);
  return scene.write(path, options);
}

}  // namespace cellforge::io
