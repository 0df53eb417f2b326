// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Queries on a polygon soup: vertex, edge, boundary and non-manifold counts, the Euler
/// characteristic, closedness, orientability and signed volume, each one pass over the faces.

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/detail/shape_building.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"

namespace cellforge {

// ------------------------------------------------------------------------------------
// Soup queries and transforms
// ------------------------------------------------------------------------------------

/// Counts describing a soup's connectivity, from one pass over its faces.
struct soup_statistics {
  std::size_t vertices = 0;  ///< points referenced by at least one face
  std::size_t edges = 0;     ///< unique undirected edges
  std::size_t faces = 0;
  std::size_t boundary_edges = 0;      ///< edges used by exactly one face
  std::size_t nonmanifold_edges = 0;   ///< edges used by three or more faces
  std::size_t inconsistent_edges = 0;  ///< two-face edges both faces traverse in the same direction
  std::size_t degenerate_faces = 0;    ///< faces with < 3 vertices or a repeated vertex
  std::int64_t euler_characteristic() const noexcept {
    return static_cast<std::int64_t>(vertices) - static_cast<std::int64_t>(edges) +
           static_cast<std::int64_t>(faces);
  }
};

/// Vertex, edge, face, boundary, non-manifold, inconsistent and degenerate counts of a soup.
/// O(total face size) expected; throws invalid_input for an out-of-range vertex index.
template <Point3 P>
soup_statistics analyze_soup(const polygon_soup<P>& soup) {
  const auto pairing = detail::shapes::pair_half_edges(soup, "analyze_soup");
  soup_statistics st;
  st.faces = soup.num_faces();
  st.edges = pairing.edges;
  st.boundary_edges = pairing.boundary;
  st.nonmanifold_edges = pairing.nonmanifold;
  st.inconsistent_edges = pairing.inconsistent;
  std::vector<bool> used(soup.points.size(), false);
  for (const std::uint32_t v : soup.face_vertices) used[v] = true;
  st.vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
  for (std::size_t f = 0; f < st.faces; ++f)
    st.degenerate_faces += detail::shapes::degenerate_face(soup.face(f));
  return st;
}

/// V − E + F counting only referenced vertices and unique undirected edges.
/// O(total face size) expected.
template <Point3 P>
std::int64_t euler_characteristic(const polygon_soup<P>& soup) {
  return analyze_soup(soup).euler_characteristic();
}

/// Number of edges used by exactly one face.
/// O(total face size) expected.
template <Point3 P>
std::size_t count_boundary_edges(const polygon_soup<P>& soup) {
  return analyze_soup(soup).boundary_edges;
}

/// True when no edge is used by exactly one face (an empty soup is closed).
/// O(total face size) expected.
template <Point3 P>
bool is_soup_closed(const polygon_soup<P>& soup) {
  return count_boundary_edges(soup) == 0;
}

/// Edges used by exactly two faces that traverse them in the same direction, i.e. where
/// the given orientations disagree. O(total face size) expected.
template <Point3 P>
std::size_t count_inconsistent_edges(const polygon_soup<P>& soup) {
  return analyze_soup(soup).inconsistent_edges;
}

/// True when faces can be flipped so that every two-face edge is traversed once each way
/// (BFS 2-colouring of faces; edges with 1 or ≥ 3 faces impose nothing). O(total face size) expected.
template <Point3 P>
bool is_soup_orientable(const polygon_soup<P>& soup) {
  namespace s = detail::shapes;
  const auto pairing = s::pair_half_edges(soup, "is_soup_orientable");
  const std::size_t m = soup.num_faces();
  std::vector<std::int8_t> flip(m, -1);  // -1 unvisited, else whether face f must be reversed
  std::vector<std::uint32_t> queue;
  queue.reserve(m);
  for (std::size_t seed = 0; seed < m; ++seed) {
    if (flip[seed] >= 0) continue;
    flip[seed] = 0;
    queue.assign(1, static_cast<std::uint32_t>(seed));
    for (std::size_t next = 0; next < queue.size(); ++next) {
      const std::uint32_t f = queue[next];
      for (std::uint32_t h = soup.face_offsets[f]; h < soup.face_offsets[f + 1]; ++h) {
        const std::uint32_t mate = pairing.mate[h];
        if (mate == s::half_edge_pairing::none) continue;
        const std::uint32_t g = pairing.face_of[mate];
        if (g == f) continue;
        // Same tail on the shared edge means same direction: g must be flipped relative to f.
        const bool same = soup.face_vertices[h] == soup.face_vertices[mate];
        const auto want = static_cast<std::int8_t>(flip[f] ^ (same ? 1 : 0));
        if (flip[g] < 0) {
          flip[g] = want;
          queue.push_back(g);
        } else if (flip[g] != want) {
          return false;
        }
      }
    }
  }
  return true;
}

/// Signed volume enclosed by the faces (divergence theorem over fan triangles); positive
/// for a closed surface oriented outward. O(total face size).
template <Point3 P>
double signed_volume(const polygon_soup<P>& soup) {
  double six_volume = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto face = soup.face(f);
    if (face.size() < 3) continue;
    for (const std::uint32_t v : face)
      detail::shapes::require(v < soup.points.size(), "signed_volume", [&] {
        return cellforge::detail::cat("face ", std::to_string(f), " refers to missing vertex ",
                                      std::to_string(v));
      });
    const glm::dvec3 a = to_dvec3(soup.points[face[0]]);
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
      six_volume +=
          glm::dot(a, glm::cross(to_dvec3(soup.points[face[i]]), to_dvec3(soup.points[face[i + 1]])));
  }
  return six_volume / 6.0;
}

}  // namespace cellforge
