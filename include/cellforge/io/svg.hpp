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
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/core/work_budget.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/svg_visibility.hpp"
#include "cellforge/io/detail/svg_writing.hpp"
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
  /// hidden-line tests may spend; automatic (the default): 1.6 x 10^7 + 256 per edge and point;
  /// 0: unlimited. Past it, edges and points
  /// are judged from one point against a few of the nearest faces; past twice it, they are
  /// drawn visible untested (svg_result counts both). The picture then stays near-linear.
  cellforge::work_budget work_budget = cellforge::work_budget::automatic;
};

/// What a picture holds; edge counts are of the visibility computation, drawn or not.
/// stage_report: milliseconds the call, work the hidden-line tests' units, complete false (and
/// a diagnostic naming svg_options::work_budget) when the budget made some edges approximate.
struct svg_result : stage_report {
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
};

/// One edge or segment of the scene and where it is hidden.
struct svg_edge_visibility {
  std::size_t layer = 0;                        ///< as returned by the add_ call
  glm::dvec3 a{0.0}, b{0.0};                    ///< ends, with the layer's offset applied
  std::vector<std::array<double, 2>> hidden{};  ///< sorted disjoint intervals of t (point a + t (b - a))
  bool exact = true;  ///< false: past the work budget, judged as a whole from its midpoint or not at all
};

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
    const cellforge::detail::stopwatch clock;
    std::string text;
    svg_result r = write_to(text, options);
    os.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!os) throw error(error_category::io, "svg: writing the picture to the stream failed");
    r.milliseconds = clock.ms();
    return r;
  }

  /// Writes the picture to a file (nothing is created when the scene or options are invalid);
  /// throws io naming the path when it cannot be written. Costs as above.
  svg_result write(const file_path& path, const svg_options& options = {}) const {
    const cellforge::detail::stopwatch clock;
    std::string text;
    svg_result r = write_to(text, options);
    detail::write_file(path, [&](std::ostream& os) {
      os.write(text.data(), static_cast<std::streamsize>(text.size()));
      if (!os) throw error(error_category::io, "writing the picture failed (disk full?)");
    });
    r.milliseconds = clock.ms();
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
  frame render(const svg_options& o) const;

  /// Mesh edges (each undirected edge once per layer, optionally feature edges only) and
  /// line segments, in the order they were given. O(total face size x log).
  template <class FacesOf>
  void collect_edges(frame& fr, FacesOf&& faces_of) const;

  /// Boundary, non-manifold, silhouette or sharp: the edge shapes the picture. Orientation is
  /// read from how each face runs along the edge, so non-orientable meshes are judged right.
  bool is_feature(const frame& fr, std::span<const std::pair<std::uint64_t, std::uint32_t>> sides,
                  std::size_t li, std::uint32_t wa, std::uint32_t wb, double cos_feature) const;

  std::span<const std::uint32_t> face(std::size_t f) const {
    return {face_vertices_.data() + face_offsets_[f], face_offsets_[f + 1] - face_offsets_[f]};
  }

  svg_result write_to(std::string& out, const svg_options& o) const;

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

#include "cellforge/io/detail/svg_impl.hpp"
