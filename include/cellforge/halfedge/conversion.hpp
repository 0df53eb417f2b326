// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Conversion between polygon soups (what files hold) and surface meshes, in the soup's
/// own point type.

#include <algorithm>
#include <span>

#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"

namespace cellforge {

/// Builds a mesh with the soup's point type from a soup in one linking pass.
/// O(total face size). Throws cellforge::error naming what cannot be represented.
template <Point3 P>
surface_mesh<P> make_mesh(const polygon_soup<P>& soup, build_report* report = nullptr,
                          const build_options& options = {}) {
  surface_mesh<P> m;
  build_report r = m.build(soup.points.size(), soup.face_offsets, soup.face_vertices, options);
  const std::span<P> pts = m.points();
  std::copy(soup.points.begin(), soup.points.end(), pts.begin());
  for (const auto& [copy, original] : r.split_vertices) pts[copy] = soup.points[original];
  if (report) *report = std::move(r);
  return m;
}

/// Writes the live vertices and faces of m into a soup (compacting removed elements),
/// each face starting at its first vertex. O(size of the mesh).
template <Point3 P>
polygon_soup<P> to_soup(const surface_mesh<P>& m) {
  const std::span<const P> pts = m.points();
  polygon_soup<P> soup;
  soup.reserve(m.num_vertices(), m.num_faces(), 3 * m.num_faces());
  std::vector<std::uint32_t> index(m.vertices_size(), halfedge_mesh::npos);
  for (vertex_handle v : m.vertices()) {
    index[v.idx()] = static_cast<std::uint32_t>(soup.points.size());
    soup.points.push_back(pts[v.idx()]);
  }
  for (face_handle f : m.faces()) {
    for (vertex_handle v : m.vertices_around(f)) soup.face_vertices.push_back(index[v.idx()]);
    soup.face_offsets.push_back(static_cast<std::uint32_t>(soup.face_vertices.size()));
  }
  return soup;
}

}  // namespace cellforge
