// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Seed 000 §6.1–6.2: outward unit face normals, continuous surfaces grown across edges whose
/// dihedral angle is below a user angle, and the data each surface is smoothed with (F, L1, L2,
/// interior vertices).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

/// The checked geometry of a closed mesh that smoothing works on: positions, outward unit face
/// normals (Newell), face centres (vertex averages) and the model size (bounding-box diagonal).
struct solid_geometry {
  std::vector<glm::dvec3> positions;     ///< by vertex index
  std::vector<glm::dvec3> face_normals;  ///< by face index, unit, pointing out of the solid
  std::vector<glm::dvec3> face_centres;  ///< by face index
  double model_size = 0;                 ///< bounding-box diagonal
  bool reversed = false;                 ///< the faces wind inwards (negative signed volume)
};

/// Checks m (closed, consistently oriented, no garbage, finite positions, no degenerate face,
/// non-zero volume) and computes its solid_geometry; `who` prefixes the messages. O(V + F·k).
/// Throws error(topology) or error(invalid_input) naming the problem.
template <Point3 P>
solid_geometry solid_geometry_of(const surface_mesh<P>& m, const char* who = "smooth_edges") {
  const std::string w(who);
  if (m.has_garbage())
    throw error(error_category::invalid_input,
                w + ": the mesh has removed elements; call garbage_collection() first");
  if (m.num_faces() == 0) throw error(error_category::invalid_input, w + ": the mesh has no faces");
  if (!m.is_closed())
    throw error(error_category::topology, w + ": the mesh has " + std::to_string(m.num_boundary_edges()) +
                                              " boundary edges; smoothing needs a closed solid");
  if (!m.is_consistently_oriented())
    throw error(error_category::topology, w + ": the mesh is not consistently oriented (" +
                                              std::to_string(m.num_flipped_edges()) +
                                              " flipped edges); orient it first");
  solid_geometry g;
  g.positions.resize(m.vertices_size());
  bounding_box box;
  for (vertex_handle v : m.vertices()) {
    const glm::dvec3 p = to_dvec3(m.position(v));
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw error(error_category::invalid_input,
                  w + ": vertex " + std::to_string(v.idx()) + " has a non-finite coordinate");
    g.positions[v.idx()] = p;
    box.add(p);
  }
  check_double_range(box, w);  // 1e300 would make every face "degenerate"
  g.model_size = box.diagonal();
  const double size = g.model_size;
  g.face_normals.resize(m.faces_size());
  g.face_centres.resize(m.faces_size());
  std::vector<std::uint32_t> ids;
  double six_volume = 0;
  for (face_handle f : m.faces()) {
    ids.clear();
    glm::dvec3 n(0), c(0);
    const glm::dvec3 o = g.positions[m.head(m.halfedge(f)).idx()];  // local origin: less cancellation
    for (halfedge_handle h : m.halfedges_around(f)) {
      const glm::dvec3 a = g.positions[m.tail(h).idx()] - o, b = g.positions[m.head(h).idx()] - o;
      n += glm::cross(a, b);
      c += a;
      ids.push_back(m.tail(h).idx());
      if (!(glm::length(b - a) > 1e-14 * size))
        throw error(error_category::invalid_input,
                    w + ": face " + std::to_string(f.idx()) + " is degenerate (an edge of zero length)");
      six_volume += glm::dot(g.positions[m.tail(h).idx()], glm::cross(g.positions[m.head(h).idx()], o));
    }
    std::sort(ids.begin(), ids.end());
    const double len = glm::length(n);
    if (std::adjacent_find(ids.begin(), ids.end()) != ids.end() || !(len > 1e-14 * size * size))
      throw error(error_category::invalid_input, w + ": face " + std::to_string(f.idx()) +
                                                     " is degenerate (zero area or a repeated vertex)");
    g.face_normals[f.idx()] = n / len;
    g.face_centres[f.idx()] = o + c / static_cast<double>(ids.size());
  }
  // Σ over faces of the fan triangles (o, a, b) gives six times the signed volume.
  if (!(std::abs(six_volume) > 1e-12 * size * size * size))
    throw error(error_category::invalid_input, w + ": the mesh encloses no volume");
  if (six_volume < 0) {
    g.reversed = true;
    for (auto& n : g.face_normals) n = -n;
  }
  return g;
}

/// One continuous surface (§6.1–6.2): its faces F, its border edges L1 (one face in F), its
/// inner edges L2 (both faces in F) and its interior vertices (every incident edge in L2).
struct continuous_surface {
  std::vector<std::uint32_t> faces, l1_edges, l2_edges, interior_vertices;
};

/// All continuous surfaces of a mesh; surface_of_face[f] is the index into surfaces.
struct surface_partition {
  std::vector<std::uint32_t> surface_of_face;
  std::vector<continuous_surface> surfaces;
};

/// The angle in degrees between unit normals a and b, accurate near 0 and 180 (atan2, not acos,
/// so that coplanar faces give exactly 0 rather than a rounding-dependent sliver). O(1).
template <class = void>
double normal_angle_deg(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * (180.0 / std::numbers::pi);
}

/// Throws error(invalid_input) unless 0 ≤ angle_deg ≤ 90 (§6.1's user range). O(1).
template <class = void>
void check_surface_angle(double angle_deg, const char* who) {
  if (!(angle_deg >= 0.0 && angle_deg <= 90.0))
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(who), ": angle_deg = ", std::to_string(angle_deg),
                                       ", must be within 0..90 degrees"));
}

/// §6.1–6.2: grows surfaces from the lowest unused face across edges whose outward normals differ
/// by less than angle_deg (strictly), repeating until every face has a surface. O(V + E + F).
/// Throws error(invalid_input) for an angle outside 0..90.
template <class = void>
surface_partition continuous_surfaces(const halfedge_mesh& m, std::span<const glm::dvec3> face_normals,
                                      double angle_deg) {
  check_surface_angle(angle_deg, "continuous_surfaces");
  constexpr std::uint32_t none = 0xFFFFFFFFu;
  auto joins = [&](face_handle a, face_handle b) {
    return normal_angle_deg(face_normals[a.idx()], face_normals[b.idx()]) < angle_deg;
  };
  surface_partition out;
  out.surface_of_face.assign(m.faces_size(), none);
  std::vector<face_handle> queue;
  for (face_handle seed : m.faces()) {
    if (out.surface_of_face[seed.idx()] != none) continue;
    const auto s = static_cast<std::uint32_t>(out.surfaces.size());
    out.surfaces.emplace_back();
    queue.assign(1, seed);
    out.surface_of_face[seed.idx()] = s;
    for (std::size_t i = 0; i < queue.size(); ++i) {
      // The seed walks the L1 edges of F; a queue of F's faces visits the same edges once each.
      for (halfedge_handle h : m.halfedges_around(queue[i])) {
        const face_handle g = m.face(halfedge_mesh::twin(h));
        if (out.surface_of_face[g.idx()] == none && joins(queue[i], g)) {
          out.surface_of_face[g.idx()] = s;
          queue.push_back(g);
        }
      }
    }
    for (face_handle f : queue) out.surfaces[s].faces.push_back(f.idx());
  }
  std::vector<std::uint8_t> all_l2(m.vertices_size(), 1);
  for (edge_handle e : m.edges()) {
    const std::uint32_t a = out.surface_of_face[m.face(e, 0).idx()],
                        b = out.surface_of_face[m.face(e, 1).idx()];
    if (a == b) {
      out.surfaces[a].l2_edges.push_back(e.idx());
    } else {
      out.surfaces[a].l1_edges.push_back(e.idx());
      out.surfaces[b].l1_edges.push_back(e.idx());
      all_l2[m.vertex(e, 0).idx()] = 0;
      all_l2[m.vertex(e, 1).idx()] = 0;
    }
  }
  // An interior vertex is touched by one surface only; its surface is that of any incident face.
  for (vertex_handle v : m.vertices()) {
    if (!all_l2[v.idx()] || m.is_isolated(v)) continue;
    out.surfaces[out.surface_of_face[m.face(m.anchor(v)).idx()]].interior_vertices.push_back(v.idx());
  }
  return out;
}

}  // namespace cellforge
