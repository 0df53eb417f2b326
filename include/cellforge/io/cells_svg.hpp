// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The exploded, shaded SVG picture of a cell complex: one mesh layer per volume in its
/// colour, moved away from the model's centre.

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ostream>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/io/cells_obj.hpp"
#include "cellforge/io/cells_ply.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/io/svg.hpp"

namespace cellforge::io {

/// How the exploded picture of a complex is drawn.
struct cells_svg_options {
  /// Each volume moves away from the model's centre by this fraction of the distance from
  /// the centre to the volume's centre (0: assembled).
  double explode = 0.35;
  svg_options picture{};
  svg_style style{};  ///< fill is replaced by each volume's colour
};

namespace detail {
template <class = void>
svg_scene cells_svg_scene(const obj_data<glm::dvec3>& data, const cells_svg_options& options) {
  if (!(options.explode >= 0.0) || !std::isfinite(options.explode))
    throw error(error_category::invalid_input, "cells svg: explode must be finite and >= 0");
  bounding_box box;
  for (const glm::dvec3& p : data.soup.points) box.add(p);
  svg_scene scene;
  // Each layer gets only the points its volume's faces use, so the scene holds O(size of
  // the volumes' boundaries) points, not (volumes x points).
  constexpr std::uint32_t unused = 0xFFFFFFFFu;
  std::vector<std::uint32_t> local(data.soup.points.size(), unused);
  std::vector<std::uint32_t> face;
  polygon_soup<glm::dvec3> soup;
  for (std::size_t g = 0; g < data.groups.size(); ++g) {
    const std::size_t end =
        g + 1 < data.groups.size() ? data.groups[g + 1].first_face : data.soup.num_faces();
    soup.clear();
    bounding_box vb;
    for (std::size_t f = data.groups[g].first_face; f < end; ++f) {
      face.clear();
      for (std::uint32_t v : data.soup.face(f)) {
        if (local[v] == unused) {
          local[v] = static_cast<std::uint32_t>(soup.points.size());
          soup.points.push_back(data.soup.points[v]);
          vb.add(data.soup.points[v]);
        }
        face.push_back(local[v]);
      }
      soup.add_face(cellforge::detail::span_of(face));
    }
    for (std::size_t f = data.groups[g].first_face; f < end; ++f)
      for (std::uint32_t v : data.soup.face(f)) local[v] = unused;
    svg_style style = options.style;
    const std::array<double, 3> rgb = volume_colour(g);
    char hex[8];
    std::snprintf(hex, sizeof hex, "#%02x%02x%02x", static_cast<int>(std::lround(rgb[0] * 255)),
                  static_cast<int>(std::lround(rgb[1] * 255)), static_cast<int>(std::lround(rgb[2] * 255)));
    style.fill = hex;
    if (style.feature_angle_deg == 0) style.feature_angle_deg = 1;
    style.offset = options.explode * (vb.center() - box.center());
    scene.add_mesh(soup, style);
  }
  return scene;
}
}  // namespace detail

/// The exploded picture as a scene: one shaded mesh layer per volume holding only that
/// volume's points, offset away from the model's centre; edges drawn where faces meet at an
/// angle (not triangulation diagonals). O(size of cc).
template <Point3 P>
svg_scene cells_svg_scene(const cell_complex<P>& cc, const cells_svg_options& options = {}) {
  return detail::cells_svg_scene(detail::cells_obj_data_dvec3(cc), options);
}

/// Writes the exploded, shaded picture of cc (see cells_svg_scene). O(picture).
template <Point3 P>
svg_result write_cells_svg(std::ostream& os, const cell_complex<P>& cc,
                           const cells_svg_options& options = {}) {
  return cells_svg_scene(cc, options).write(os, options.picture);
}
template <Point3 P>
svg_result write_cells_svg(const file_path& path, const cell_complex<P>& cc,
                           const cells_svg_options& options = {}) {
  return cells_svg_scene(cc, options).write(path, options.picture);
}

}  // namespace cellforge::io
