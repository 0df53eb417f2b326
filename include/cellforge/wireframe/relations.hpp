// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 8 of the wireframe pipeline (seed 000 §4.8): outward pointers (each volume's faces
/// with the normal turned to point out of it) and, around each edge, the faces and volumes in
/// right-hand rotation order — derived from the same rotation order the volume finder used,
/// so the seed's case analysis of fig. 25 is not needed.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/wireframe/volume_finder.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// Options of find_relations (none yet; kept for a uniform stage interface).
struct relations_options {};

/// Around one edge: faces in right-hand order about start → end, and the volume between
/// each face and the next (no_index: none, the outside). Face indices are into the face list
/// given to find_relations (wireframe_result::extra.faces), volumes as in find_volumes.
struct edge_relation {
  std::vector<std::uint32_t> faces;
  std::vector<int> face_walks;         ///< +1 when the face walks the edge start → end
  std::vector<std::uint32_t> volumes;  ///< volumes[k] lies between faces[k] and faces[k + 1] (cyclically)
};

/// The relations of the 3DCL.
struct relations_result : stage_report {
  std::vector<edge_relation> edges;
  /// Per volume, per face in it: the outward pointer (unit normal pointing out of the volume).
  std::vector<std::vector<glm::dvec3>> outward;
};

/// Derives rotation orders and outward pointers from the kept faces and the volumes.
/// O(Σ L + E·k log k).
template <class = void>
relations_result find_relations(const wire_graph& g, const std::vector<wire_face>& faces,
                                const volume_result& volumes, const relations_options& = {}) {
  detail::stopwatch clock;
  relations_result r;
  const auto fan = detail::edge_fans(g, faces, &volumes.face_kept);
  r.edges.resize(g.num_edges());
  for (std::uint32_t e = 0; e < g.num_edges(); ++e) {
    auto& rel = r.edges[e];
    for (std::size_t k = 0; k < fan[e].size(); ++k) {
      const auto& a = fan[e][k];
      rel.faces.push_back(a.face);
      rel.face_walks.push_back(a.walk);
      // Between a and the next face lies the region on a's side facing increasing angle.
      rel.volumes.push_back(volumes.face_volumes[a.face][a.walk > 0 ? 0 : 1]);
    }
  }
  r.outward.resize(volumes.volumes.size());
  for (std::size_t v = 0; v < volumes.volumes.size(); ++v)
    for (const auto& [f, s] : volumes.volumes[v])
      r.outward[v].push_back(static_cast<double>(s) * faces[f].normal);
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
