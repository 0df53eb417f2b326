// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Seed 000 §6.3: distance-weighted edge normals, and inverse-distance-weighted vertex normals,
/// generalised to "sector" normals: the faces around a vertex split by crease edges into fans, each
/// fan with its own normal (one fan with no crease = the seed's interior vertex).

#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/smooth/continuous_surfaces.hpp"

namespace cellforge {

/// §6.3 edge normals: N(x) = (N(a)·B + N(b)·A) / (A + B), normalised, with A, B the distances from
/// the centres of faces a, b to the edge midpoint (the nearer face weighs more). Zero where the two
/// face normals cancel. O(E).
template <class = void>
std::vector<glm::dvec3> edge_normals(const halfedge_mesh& m, const solid_geometry& g) {
  std::vector<glm::dvec3> out(m.edges_size(), glm::dvec3(0));
  for (edge_handle e : m.edges()) {
    const std::uint32_t fa = m.face(e, 0).idx(), fb = m.face(e, 1).idx();
    const glm::dvec3 mid = 0.5 * (g.positions[m.vertex(e, 0).idx()] + g.positions[m.vertex(e, 1).idx()]);
    const double a = glm::length(g.face_centres[fa] - mid), b = glm::length(g.face_centres[fb] - mid);
    const glm::dvec3 n = a + b > 0 ? (g.face_normals[fa] * b + g.face_normals[fb] * a) / (a + b)
                                   : g.face_normals[fa] + g.face_normals[fb];
    const double len = glm::length(n);
    if (len > 1e-12) out[e.idx()] = n / len;
  }
  return out;
}

/// The fans ("sectors") of faces around each vertex, separated by crease edges. A corner is a face
/// half-edge, standing for (its face, its head vertex).
struct vertex_sectors {
  std::vector<std::uint32_t> sector_of_corner;  ///< by half-edge index
  std::vector<std::uint32_t> vertex_of_sector;
  std::vector<std::uint32_t> creases_at_vertex;  ///< number of incident crease edges; 0 = interior
  std::vector<glm::dvec3> face_average;          ///< normalised mean face normal of each sector
  std::size_t size() const noexcept { return vertex_of_sector.size(); }
};

/// The corner of face(h) at head(h) is h; the corner of the twin's face at head(h) is prev(twin).
/// Valid on consistently oriented meshes (the smoother checks that first). O(1).
template <class = void>
halfedge_handle corner_across(const halfedge_mesh& m, halfedge_handle h) {
  return m.prev(halfedge_mesh::twin(h));
}

/// Splits the corners at every vertex into sectors joined across non-crease edges (smooth[e] != 0),
/// by union–find. O((E + F·k) α).
template <class = void>
vertex_sectors make_vertex_sectors(const halfedge_mesh& m, const solid_geometry& g,
                                   std::span<const std::uint8_t> smooth) {
  std::vector<std::uint32_t> parent(m.halfedges_size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  vertex_sectors s;
  s.creases_at_vertex.assign(m.vertices_size(), 0);
  for (edge_handle e : m.edges()) {
    for (unsigned i = 0; i < 2; ++i) {
      const halfedge_handle h = halfedge_mesh::halfedge(e, i);
      if (smooth[e.idx()]) {
        const std::uint32_t a = find(h.idx()), b = find(corner_across(m, h).idx());
        if (a != b) parent[a] = b;
      } else {
        ++s.creases_at_vertex[m.head(h).idx()];
      }
    }
  }
  constexpr std::uint32_t none = 0xFFFFFFFFu;
  std::vector<std::uint32_t> id(m.halfedges_size(), none);
  s.sector_of_corner.assign(m.halfedges_size(), none);
  for (halfedge_handle h : m.halfedges()) {
    const std::uint32_t r = find(h.idx());
    if (id[r] == none) {
      id[r] = static_cast<std::uint32_t>(s.vertex_of_sector.size());
      s.vertex_of_sector.push_back(m.head(h).idx());
      s.face_average.emplace_back(0.0);
    }
    s.sector_of_corner[h.idx()] = id[r];
    s.face_average[id[r]] += g.face_normals[m.face(h).idx()];
  }
  for (auto& n : s.face_average) {
    const double len = glm::length(n);
    n = len > 1e-12 ? n / len : glm::dvec3(0);
  }
  return s;
}

/// §6.3 vertex normals, per sector: the inverse-distance-weighted mean of the normals of the
/// sector's smooth edges, d = distance from the vertex to the edge's current midpoint; a sector with
/// no smooth edge (or whose mean cancels) takes its faces' mean normal. O(E + sectors).
template <class = void>
void sector_normals(const halfedge_mesh& m, const solid_geometry& g, const vertex_sectors& s,
                    std::span<const std::uint8_t> smooth, std::span<const glm::dvec3> edge_normal,
                    std::span<const glm::dvec3> midpoints, std::vector<glm::dvec3>& out) {
  out.assign(s.size(), glm::dvec3(0));
  std::vector<double> weight(s.size(), 0.0);
  for (edge_handle e : m.edges()) {
    if (!smooth[e.idx()]) continue;
    for (unsigned i = 0; i < 2; ++i) {
      const halfedge_handle h = halfedge_mesh::halfedge(e, i);
      const double d = glm::length(g.positions[m.head(h).idx()] - midpoints[e.idx()]);
      if (!(d > 0)) continue;
      out[s.sector_of_corner[h.idx()]] += edge_normal[e.idx()] / d;
      weight[s.sector_of_corner[h.idx()]] += 1.0 / d;
    }
  }
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double len = glm::length(out[k]);
    // Relative test: the weights scale with 1/model size.
    out[k] = len > 1e-9 * weight[k] ? out[k] / len : s.face_average[k];
  }
}

}  // namespace cellforge
