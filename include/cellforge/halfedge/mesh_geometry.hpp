// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// What a mesh user reaches for first: face normals, areas and centroids, vertex normals and
/// the bounding box of a surface_mesh (in the mesh's own point type), and the Euler
/// characteristic and connected components of any half-edge mesh. All computed in double
/// precision; non-planar polygons use Newell's normal, so they need no triangulation.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"

namespace cellforge {

namespace detail::geometry {

// Newell's vector of face f: its direction is the face normal, its length twice the area
// (exact for planar polygons, the least-squares normal for non-planar ones). O(|f|).
template <Point3 P>
glm::dvec3 newell(const surface_mesh<P>& m, face_handle f) {
  return cellforge::detail::newell(m.vertices_around(f),
                                   [&](vertex_handle v) { return to_dvec3(m.position(v)); });
}

template <Point3 P>
P unit_or_zero(const glm::dvec3& v) {
  const double len = glm::length(v);
  return from_dvec3<P>(len > 0 && std::isfinite(len) ? v / len : glm::dvec3(0.0));
}

}  // namespace detail::geometry

/// The unit normal of face f (right-handed about its vertex order); zero for a degenerate
/// face. O(|f|).
template <Point3 P>
P face_normal(const surface_mesh<P>& m, face_handle f) {
  return detail::geometry::unit_or_zero<P>(detail::geometry::newell(m, f));
}

/// The area of face f (of its projection on its Newell plane for a non-planar polygon). O(|f|).
template <Point3 P>
double face_area(const surface_mesh<P>& m, face_handle f) {
  return 0.5 * glm::length(detail::geometry::newell(m, f));
}

/// The centroid of face f's vertices. O(|f|).
template <Point3 P>
P face_centroid(const surface_mesh<P>& m, face_handle f) {
  glm::dvec3 c(0.0);
  std::size_t n = 0;
  for (const vertex_handle v : m.vertices_around(f)) c += to_dvec3(m.position(v)), ++n;
  return from_dvec3<P>(n > 0 ? c / static_cast<double>(n) : c);
}

/// The unit normal at vertex v: the area-weighted mean of its faces' normals (each fan
/// counted once per face); zero for an isolated vertex or when they cancel. O(Σ |f| around v).
template <Point3 P>
P vertex_normal(const surface_mesh<P>& m, vertex_handle v) {
  glm::dvec3 sum(0.0);
  for (const face_handle f : m.faces_around(v)) sum += detail::geometry::newell(m, f);
  return detail::geometry::unit_or_zero<P>(sum);
}

/// Every live face's unit normal, indexed by face index (removed faces: zero). O(size).
template <Point3 P>
std::vector<P> face_normals(const surface_mesh<P>& m) {
  std::vector<P> out(m.faces_size(), from_dvec3<P>(glm::dvec3(0.0)));
  for (const face_handle f : m.faces()) out[f.idx()] = face_normal(m, f);
  return out;
}

/// Every live vertex's unit normal, indexed by vertex index (removed vertices: zero).
/// O(size): each face's normal is computed once.
template <Point3 P>
std::vector<P> vertex_normals(const surface_mesh<P>& m) {
  std::vector<glm::dvec3> sum(m.vertices_size(), glm::dvec3(0.0));
  for (const face_handle f : m.faces()) {
    const glm::dvec3 n = detail::geometry::newell(m, f);
    for (const vertex_handle v : m.vertices_around(f)) sum[v.idx()] += n;
  }
  std::vector<P> out;
  out.reserve(sum.size());
  for (const glm::dvec3& s : sum) out.push_back(detail::geometry::unit_or_zero<P>(s));
  return out;
}

/// The total area of the live faces. O(size).
template <Point3 P>
double surface_area(const surface_mesh<P>& m) {
  double a = 0;
  for (const face_handle f : m.faces()) a += face_area(m, f);
  return a;
}

/// The axis-aligned box of the live vertices as its (min, max) corners in the mesh's point
/// type; (origin, origin) for a mesh without vertices. O(V).
template <Point3 P>
std::pair<P, P> bounds(const surface_mesh<P>& m) {
  bounding_box box;
  for (const vertex_handle v : m.vertices()) box.add(to_dvec3(m.position(v)));
  if (box.empty()) return {from_dvec3<P>(glm::dvec3(0.0)), from_dvec3<P>(glm::dvec3(0.0))};
  return {from_dvec3<P>(box.min), from_dvec3<P>(box.max)};
}

/// The edges where a surface folds back onto itself: the normals of the two faces at the edge
/// point opposite ways, more than 180° − `within_deg` apart (a dihedral angle below within_deg);
/// milliseconds the call, a diagnostic when there are folds.
struct fold_result : stage_report {
  std::vector<edge_handle> edges;  ///< in edge order; empty for a surface without folds
  double within_deg = 0;           ///< the angle the normals had to come within of 180°
};

/// Finds m's folds: edges with two faces whose unit normals make an angle above 180° −
/// within_deg (faces without a normal, zero area, are skipped; on an edge whose faces disagree in
/// orientation one normal is reversed first). O(V + E + F).
template <Point3 P>
fold_result folded_edges(const surface_mesh<P>& m, double within_deg = 20) {
  const detail::stopwatch clock;
  fold_result r;
  r.within_deg = within_deg;
  std::vector<glm::dvec3> normal(m.faces_size(), glm::dvec3(0.0));
  std::vector<glm::dvec3> loop;
  for (const face_handle f : m.faces()) {
    // Newell's vector of the face moved to its first corner and divided by its extent: it
    // squares coordinates, which far out (1e300) would overflow where the normal is plain.
    loop.clear();
    for (const vertex_handle v : m.vertices_around(f)) loop.push_back(to_dvec3(m.position(v)));
    double big = 0;
    const glm::dvec3 o = loop.front();
    for (glm::dvec3& p : loop) {
      p -= o;
      big = std::max({big, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    }
    if (!(big > 0 && std::isfinite(big))) continue;
    for (glm::dvec3& p : loop) p /= big;
    const glm::dvec3 v = cellforge::detail::newell(loop, [&](const glm::dvec3& p) { return p; });
    if (glm::length(v) > 0) normal[f.idx()] = glm::normalize(v);
  }
  const double limit = -std::cos(within_deg * std::numbers::pi / 180);
  for (const edge_handle e : m.edges()) {
    if (m.is_boundary(e)) continue;
    // On an edge whose faces disagree in orientation (a Möbius band's seam) one normal is
    // reversed: compare the surface's sides, not the faces' windings.
    const glm::dvec3 a = normal[m.face(e, 0).idx()];
    const glm::dvec3 b = m.is_flipped(e) ? -normal[m.face(e, 1).idx()] : normal[m.face(e, 1).idx()];
    if (glm::dot(a, a) > 0 && glm::dot(b, b) > 0 && glm::dot(a, b) < limit) r.edges.push_back(e);
  }
  if (!r.edges.empty())
    r.diagnostics.push_back(cellforge::detail::cat(std::to_string(r.edges.size()),
                                                   " edges fold the surface back onto itself (first: edge ",
                                                   std::to_string(r.edges.front().idx()), ")"));
  r.milliseconds = clock.ms();
  return r;
}

/// V − E + F of the live elements (2 − 2g − b for a connected orientable surface of genus g
/// with b boundary loops). O(1).
template <class = void>
std::int64_t euler_characteristic(const halfedge_mesh& m) noexcept {
  return static_cast<std::int64_t>(m.num_vertices()) - static_cast<std::int64_t>(m.num_edges()) +
         static_cast<std::int64_t>(m.num_faces());
}

/// Connected components through edges: the component of every vertex slot (removed vertices:
/// npos) and their number; an isolated vertex is a component of its own.
struct mesh_components {
  std::vector<std::uint32_t> vertex_component;
  std::size_t count = 0;
};

/// Labels the connected components of m. O(V + E).
template <class = void>
mesh_components connected_components(const halfedge_mesh& m) {
  mesh_components c;
  c.vertex_component.assign(m.vertices_size(), halfedge_mesh::npos);
  std::vector<vertex_handle> stack;
  for (const vertex_handle seed : m.vertices()) {
    if (c.vertex_component[seed.idx()] != halfedge_mesh::npos) continue;
    const auto label = static_cast<std::uint32_t>(c.count++);
    c.vertex_component[seed.idx()] = label;
    stack.push_back(seed);
    while (!stack.empty()) {
      const vertex_handle v = stack.back();
      stack.pop_back();
      for (const vertex_handle w : m.vertices_around(v))
        if (c.vertex_component[w.idx()] == halfedge_mesh::npos) {
          c.vertex_component[w.idx()] = label;
          stack.push_back(w);
        }
    }
  }
  return c;
}

}  // namespace cellforge
