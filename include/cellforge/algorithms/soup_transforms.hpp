// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Transforms of a polygon soup: an affine map (faces reversed by a mirroring one), scaling and
/// fan triangulation, each O(output size).

#include <algorithm>
#include <cstddef>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "cellforge/algorithms/detail/shape_building.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"

namespace cellforge {

/// The soup with every point mapped by the affine transform m (last row 0 0 0 1). A
/// mirroring m (negative determinant) also reverses each face so outward stays outward. O(n).
template <Point3 P>
polygon_soup<P> transformed(const polygon_soup<P>& soup, const glm::dmat4& m) {
  detail::shapes::require(m[0][3] == 0 && m[1][3] == 0 && m[2][3] == 0 && m[3][3] == 1, "transformed",
                          "only affine transforms are supported (the last row must be 0 0 0 1)");
  polygon_soup<P> out;
  out.points.reserve(soup.points.size());
  for (const P& p : soup.points)
    out.points.push_back(from_dvec3<P>(glm::dvec3(m * glm::dvec4(to_dvec3(p), 1.0))));
  out.face_offsets = soup.face_offsets;
  out.face_vertices = soup.face_vertices;
  if (glm::determinant(glm::dmat3(m)) < 0)
    for (std::size_t f = 0; f < out.num_faces(); ++f)
      std::reverse(out.face_vertices.begin() + out.face_offsets[f] + 1,
                   out.face_vertices.begin() + out.face_offsets[f + 1]);
  return out;
}

/// The soup scaled by per-axis factors about the origin (faces reversed when an odd number
/// of factors is negative). O(n).
template <Point3 P>
polygon_soup<P> scaled(const polygon_soup<P>& soup, const glm::dvec3& factors) {
  glm::dmat4 m(1.0);
  m[0][0] = factors.x;
  m[1][1] = factors.y;
  m[2][2] = factors.z;
  return transformed(soup, m);
}

/// The soup scaled uniformly by `factor` about the origin.
/// O(n).
template <Point3 P>
polygon_soup<P> scaled(const polygon_soup<P>& soup, double factor) {
  return scaled(soup, glm::dvec3(factor));
}

/// Splits every face of k ≥ 3 vertices into the k − 2 triangles (v0, vi, vi+1), keeping
/// orientation and points; exact for convex faces. O(total face size).
template <Point3 P>
polygon_soup<P> triangulate_fan(const polygon_soup<P>& soup) {
  polygon_soup<P> out;
  std::size_t triangles = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f)
    triangles += soup.face(f).size() >= 3 ? soup.face(f).size() - 2 : 0;
  out.reserve(soup.points.size(), triangles, 3 * triangles);
  out.points = soup.points;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto face = soup.face(f);
    for (std::size_t i = 1; i + 1 < face.size(); ++i) out.add_face({face[0], face[i], face[i + 1]});
  }
  return out;
}

}  // namespace cellforge
