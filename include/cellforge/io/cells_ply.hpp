// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A cell complex as an ASCII PLY whose faces carry the colour of their volume, and the
/// colours themselves (volume_colour, shared with the exploded SVG picture).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/io/cells_obj.hpp"
#include "cellforge/io/detail/cells_writing.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/file_path.hpp"

namespace cellforge::io {

/// A distinct, saturated colour for volume i (hues spaced by the golden angle). O(1).
template <class = void>
std::array<double, 3> volume_colour(std::size_t i) {
  const double h = std::fmod(0.13 + 0.618033988749895 * static_cast<double>(i), 1.0) * 6.0, s = 0.55,
               v = 0.92;
  const double c = v * s, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = v - c;
  const int k = static_cast<int>(h) % 6;
  const glm::dvec3 rgb = k == 0   ? glm::dvec3(c, x, 0)
                         : k == 1 ? glm::dvec3(x, c, 0)
                         : k == 2 ? glm::dvec3(0, c, x)
                         : k == 3 ? glm::dvec3(0, x, c)
                         : k == 4 ? glm::dvec3(x, 0, c)
                                  : glm::dvec3(c, 0, x);
  return {rgb.x + m, rgb.y + m, rgb.z + m};
}

namespace detail {
template <class = void>
void write_cells_ply(std::ostream& os, const obj_data<glm::dvec3>& data) {
  std::size_t largest = 0;
  for (std::size_t f = 0; f < data.soup.num_faces(); ++f)
    largest = std::max(largest, data.soup.face(f).size());
  const char* count_type = largest <= 0xFF ? "uchar" : largest <= 0xFFFF ? "ushort" : "uint";
  std::string out = cellforge::detail::cat(
      "ply\nformat ascii 1.0\ncomment 3DCL faces coloured by volume (cellforge)\nelement vertex ",
      std::to_string(data.soup.points.size()),
      "\nproperty double x\nproperty double y\nproperty double z\nelement face ",
      std::to_string(data.soup.num_faces()), "\nproperty list ", count_type,
      " int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n");
  for (const glm::dvec3& p : data.soup.points) {
    for (int k = 0; k < 3; ++k) detail::put_double(out, p[k]), out += k < 2 ? ' ' : '\n';
  }
  for (std::size_t g = 0; g < data.groups.size(); ++g) {
    const std::size_t end =
        g + 1 < data.groups.size() ? data.groups[g + 1].first_face : data.soup.num_faces();
    const std::array<double, 3> rgb = volume_colour(g);
    for (std::size_t f = data.groups[g].first_face; f < end; ++f) {
      const auto face = data.soup.face(f);
      out += std::to_string(face.size());
      for (std::uint32_t v : face) out += ' ' + std::to_string(v);
      for (int k = 0; k < 3; ++k) out += ' ' + std::to_string(static_cast<int>(std::lround(rgb[k] * 255.0)));
      out += '\n';
    }
  }
  os.write(out.data(), static_cast<std::streamsize>(out.size()));
  if (!os) throw error(error_category::io, "cells ply: writing to the stream failed");
}
}  // namespace detail

/// Writes an ASCII PLY of every volume's outward faces (then the faces of no volume), each face with the
/// colour of its volume (uchar red, green, blue face properties), faces with holes triangulated; the count
/// type of the vertex lists is the narrowest that holds the largest face. O(size).
template <Point3 P>
void write_cells_ply(std::ostream& os, const cell_complex<P>& cc) {
  detail::write_cells_ply(os, detail::cells_obj_data_dvec3(cc));
}
template <Point3 P>
void write_cells_ply(const file_path& path, const cell_complex<P>& cc) {
  detail::write_file(path, [&](std::ostream& os) { write_cells_ply(os, cc); });
}

}  // namespace cellforge::io
