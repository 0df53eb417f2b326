// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Conversion between polygon soups (what files hold) and half-edge meshes, with the
/// user's point type kept as the vertex property "v:point".

#include <string_view>

#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

/// Name of the vertex property that holds positions.
inline constexpr std::string_view point_property_name = "v:point";

/// The positions of m as a vertex property of type P (throws if absent or of another type). O(1).
template <Point3 P>
property<vertex_handle, P> points(const halfedge_mesh& m) {
  auto p = m.get_vertex_property<P>(point_property_name);
  if (!p)
    throw error(error_category::invalid_input,
                "the mesh has no vertex positions (property \"v:point\"); build it with make_mesh()");
  return p;
}

/// Builds a half-edge mesh from a soup in one linking pass; positions go to "v:point".
/// O(total face size). Throws cellforge::error naming what cannot be represented.
template <Point3 P>
halfedge_mesh make_mesh(const polygon_soup<P>& soup, build_report* report = nullptr,
                        const build_options& options = {}) {
  halfedge_mesh m;
  auto pts = m.add_vertex_property<P>(point_property_name);
  build_report r = m.build(soup.points.size(), soup.face_offsets, soup.face_vertices, options);
  std::copy(soup.points.begin(), soup.points.end(), pts.vector().begin());
  for (const auto& [copy, original] : r.split_vertices) pts[vertex_handle(copy)] = soup.points[original];
  if (report) *report = std::move(r);
  return m;
}

/// Writes the live vertices and faces of m into a soup (compacting removed elements),
/// each face starting at its first vertex. O(size of the mesh).
template <Point3 P>
polygon_soup<P> to_soup(const halfedge_mesh& m) {
  const auto pts = points<P>(m);
  polygon_soup<P> soup;
  soup.reserve(m.num_vertices(), m.num_faces(), 3 * m.num_faces());
  std::vector<std::uint32_t> index(m.vertices_size(), halfedge_mesh::npos);
  for (vertex_handle v : m.vertices()) {
    index[v.idx()] = static_cast<std::uint32_t>(soup.points.size());
    soup.points.push_back(pts[v]);
  }
  for (face_handle f : m.faces()) {
    for (vertex_handle v : m.vertices_around(f)) soup.face_vertices.push_back(index[v.idx()]);
    soup.face_offsets.push_back(static_cast<std::uint32_t>(soup.face_vertices.size()));
  }
  return soup;
}

}  // namespace cellforge
