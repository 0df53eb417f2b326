// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 7 of the wireframe pipeline (seed 000 §4.7): objects and volumes. The seed walks
/// from the leftmost face and chooses the next face around an edge by a "turn direction",
/// which fails when two of its vectors are parallel (fig. 24, patched there by nudging
/// coordinates). Here the same choice — the next face in rotation order around the edge — is
/// made for every face side at once, so no turn direction is ever needed: sort the faces
/// around each edge by angle; the side of one face facing the next face continues the same
/// shell. Connected face sides are shells; a shell of negative signed volume is an object's
/// outside surface and bounds no volume (the seed's outside-surface removal); an outside
/// surface nested in another object's volume (a solid in a cavity) becomes part of that
/// volume's boundary, found by ray parity.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/wireframe/circuit_tracer.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// Options of find_volumes.
struct volume_options {
  /// Merge the volumes on both sides of every unforced face and drop such faces (a house with
  /// a wall between box and roof becomes one volume).
  bool merge_unforced = false;
};

/// One face around an edge: the face, and +1 when it walks the edge from start to end.
struct edge_fan_entry {
  std::uint32_t face = 0;
  int walk = 0;
  double angle = 0.0;  ///< right-hand angle about the edge (start → end), in (-π, π]
};

/// Objects, shells and volumes of a set of faces.
struct volume_result : stage_report {
  std::size_t objects = 0;
  std::vector<std::uint32_t> object_of_face;
  std::size_t shells = 0, outside_shells = 0, nested_shells = 0;
  /// Per face: the volume on its normal's side and on the other side (no_index: outside).
  std::vector<std::array<std::uint32_t, 2>> face_volumes;
  /// Per volume: (face, +1 when the face's normal points out of the volume, -1 when in).
  std::vector<std::vector<std::pair<std::uint32_t, int>>> volumes;
  std::vector<char> face_kept;  ///< false for faces dropped by merging (or with one volume on both sides)
  std::vector<std::uint32_t> unforced;  ///< walls no edge forces (see find_volumes)
  double manifold_milliseconds = 0.0;   ///< the seed's "manifold analysis" row: rotation order and shells
};

namespace detail {

/// The faces around every edge, in right-hand rotation order about the edge's direction.
/// O(Σ L + E·k log k) for k faces at an edge.
inline std::vector<std::vector<edge_fan_entry>> edge_fans(const wire_graph& g,
                                                          const std::vector<wire_face>& faces,
                                                          const std::vector<char>* kept = nullptr) {
  std::vector<std::vector<edge_fan_entry>> fan(g.num_edges());
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    if (kept && !(*kept)[i]) continue;
    for (const auto& loop : faces[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const std::uint32_t a = loop[k], b = loop[(k + 1) % loop.size()];
        const std::uint32_t e = g.find_edge(a, b);
        fan[e].push_back({i, g.edges[e][0] == a ? 1 : -1, 0.0});
      }
  }
  for (std::uint32_t e = 0; e < g.num_edges(); ++e) {
    auto& f = fan[e];
    if (f.empty()) continue;
    const glm::dvec3 d = glm::normalize(g.points[g.edges[e][1]] - g.points[g.edges[e][0]]);
    const glm::dvec3 x = any_perpendicular(d), y = glm::cross(d, x);
    for (auto& en : f) {
      // The face lies to the left of its walk: inward = normal × walked direction.
      const glm::dvec3 w = glm::cross(faces[en.face].normal, static_cast<double>(en.walk) * d);
      en.angle = std::atan2(glm::dot(w, y), glm::dot(w, x));
    }
    std::sort(f.begin(), f.end(), [](const edge_fan_entry& a, const edge_fan_entry& b) {
      return a.angle != b.angle ? a.angle < b.angle : a.face < b.face;
    });
  }
  return fan;
}

/// Ray-parity test of point q against the closed surface made of `faces` (any orientation).
/// Tries other ray directions when a ray grazes an edge. O(Σ L).
inline bool inside_surface(const wire_graph& g, const std::vector<wire_face>& all,
                           const std::vector<std::uint32_t>& faces, const glm::dvec3& q) {
  const double tol = 1e-9 * g.size;
  const glm::dvec3 dirs[] = {{0.5773, 0.5719, 0.5831},
                             {-0.3129, 0.8447, 0.4341},
                             {0.7071, -0.2137, -0.6741},
                             {-0.6262, -0.5491, 0.5535},
                             {0.1213, 0.2711, -0.9549}};
  for (const auto& d0 : dirs) {
    const glm::dvec3 r = glm::normalize(d0);
    bool parity = false, grazed = false;
    for (const auto i : faces) {
      const wire_face& f = all[i];
      const glm::dvec3 o = g.points[f.loops[0][0]];
      const double den = glm::dot(f.normal, r);
      if (std::abs(den) < 1e-9) continue;
      const double t = glm::dot(f.normal, o - q) / den;
      if (t <= 0.0) continue;
      const glm::dvec3 x = q + t * r;
      plane_component frame;
      frame.origin = o;
      frame.normal = f.normal;
      frame.u = any_perpendicular(f.normal);
      frame.w = glm::cross(f.normal, frame.u);
      const glm::dvec2 px = project(frame, x);
      bool in = false;
      for (const auto& loop : f.loops) {
        std::vector<glm::dvec2> poly;
        for (const auto v : loop) poly.push_back(project(frame, g.points[v]));
        for (std::size_t k = 0; k < poly.size(); ++k) {
          const glm::dvec2 a = poly[k], b = poly[(k + 1) % poly.size()];
          const glm::dvec2 ab = b - a;
          const double len2 = glm::dot(ab, ab);
          const double s = len2 > 0.0 ? std::clamp(glm::dot(px - a, ab) / len2, 0.0, 1.0) : 0.0;
          if (glm::length(px - (a + s * ab)) <= tol) grazed = true;
        }
        if (inside_2d(poly, px)) in = !in;
      }
      if (in) parity = !parity;
    }
    if (!grazed) return parity;
  }
  return false;
}

}  // namespace detail

/// Finds objects and volumes (see the file comment). O(Σ L + E·k log k) for the shells, plus
/// O(objects × faces) ray tests when several objects may nest.
inline volume_result find_volumes(const wire_graph& g, const std::vector<wire_face>& faces,
                                  const volume_options& options = {}) {
  detail::stopwatch clock;
  volume_result r;
  const auto nf = static_cast<std::uint32_t>(faces.size());
  const auto fan = detail::edge_fans(g, faces);

  // Objects: faces joined through shared edges.
  detail::union_find obj(nf);
  for (const auto& f : fan)
    for (std::size_t k = 1; k < f.size(); ++k) obj.unite(f[0].face, f[k].face);
  std::vector<std::uint32_t> object_id(nf, no_index);
  r.object_of_face.resize(nf);
  for (std::uint32_t i = 0; i < nf; ++i) {
    const auto root = obj.find(i);
    if (object_id[root] == no_index) object_id[root] = static_cast<std::uint32_t>(r.objects++);
    r.object_of_face[i] = object_id[root];
  }

  // Shells: side 2i is face i's normal side, 2i+1 the other. Around an edge, the side of a
  // face facing increasing angle is its normal side exactly when it walks the edge forwards.
  detail::union_find side(2 * std::size_t{nf});
  auto side_id = [](std::uint32_t face, int s) { return 2 * face + (s > 0 ? 0u : 1u); };
  for (std::uint32_t e = 0; e < fan.size(); ++e) {
    const auto& f = fan[e];
    for (std::size_t k = 0; k < f.size(); ++k) {
      const auto& a = f[k];
      const auto& b = f[(k + 1) % f.size()];
      if (k + 1 < f.size() && a.angle == b.angle)
        r.diagnostics.push_back("faces " + std::to_string(a.face) + " and " + std::to_string(b.face) +
                                " leave edge " + std::to_string(e) + " at the same angle");
      side.unite(side_id(a.face, a.walk), side_id(b.face, -b.walk));
    }
  }
  std::vector<std::uint32_t> shell_of(2 * std::size_t{nf}), shell_root_id(2 * std::size_t{nf}, no_index);
  std::vector<double> shell_volume;
  std::vector<std::vector<std::uint32_t>> shell_faces;
  std::vector<std::uint32_t> shell_object;
  for (std::uint32_t s = 0; s < 2 * nf; ++s) {
    const auto root = side.find(s);
    if (shell_root_id[root] == no_index) {
      shell_root_id[root] = static_cast<std::uint32_t>(shell_volume.size());
      shell_volume.push_back(0.0);
      shell_faces.emplace_back();
      shell_object.push_back(r.object_of_face[s / 2]);
    }
    const auto sh = shell_of[s] = shell_root_id[root];
    const wire_face& f = faces[s / 2];
    // The region on side s has outward normal -s·n there: divergence theorem about the centre.
    const double contribution = glm::dot(area_vector(g, f), g.points[f.loops[0][0]] - g.center) / 3.0;
    shell_volume[sh] += (s % 2 == 0 ? -1.0 : 1.0) * contribution;
    shell_faces[sh].push_back(s / 2);
  }
  r.shells = shell_volume.size();
  r.manifold_milliseconds = clock.ms();

  // Regions: every positive shell bounds one; a negative shell (an object's outside) belongs
  // to the smallest positive shell of another object containing it, else to the unbounded region.
  std::vector<std::uint32_t> region_of_shell(r.shells, no_index);
  std::uint32_t regions = 0;
  for (std::size_t s = 0; s < r.shells; ++s)
    if (shell_volume[s] > 0.0) region_of_shell[s] = regions++;
  std::vector<bounding_box> shell_box(r.shells);
  for (std::size_t s = 0; s < r.shells; ++s)
    for (const auto i : shell_faces[s])
      for (const auto v : faces[i].loops[0]) shell_box[s].add(g.points[v]);
  for (std::size_t s = 0; s < r.shells; ++s) {
    if (shell_volume[s] > 0.0) continue;
    ++r.outside_shells;
    if (r.objects < 2) continue;
    const glm::dvec3 q = g.points[faces[shell_faces[s][0]].loops[0][0]];
    std::size_t best = no_index;
    for (std::size_t t = 0; t < r.shells; ++t) {
      if (shell_volume[t] <= 0.0 || shell_object[t] == shell_object[s]) continue;
      const auto& b = shell_box[t];
      if (q.x < b.min.x || q.y < b.min.y || q.z < b.min.z || q.x > b.max.x || q.y > b.max.y || q.z > b.max.z)
        continue;
      if (best != no_index && shell_volume[t] >= shell_volume[best]) continue;
      if (detail::inside_surface(g, faces, shell_faces[t], q)) best = t;
    }
    if (best != no_index) {
      region_of_shell[s] = region_of_shell[best];
      ++r.nested_shells;
    }
  }

  // Merge across unforced faces when asked: the unbounded region is `regions`.
  detail::union_find merged(regions + 1);
  auto region = [&](std::uint32_t face, int s) {
    const auto rg = region_of_shell[shell_of[side_id(face, s)]];
    return rg == no_index ? regions : rg;
  };
  // Unforced faces: between two volumes, and at each edge at least two other faces remain,
  // not just two coplanar ones (a wall whose edge shows on a flat outer surface is forced).
  for (std::uint32_t i = 0; i < nf; ++i) {
    if (region(i, 1) == regions || region(i, -1) == regions || region(i, 1) == region(i, -1)) continue;
    bool forced = false;
    for (const auto& loop : faces[i].loops)
      for (std::size_t k = 0; k < loop.size() && !forced; ++k) {
        const auto& f = fan[g.find_edge(loop[k], loop[(k + 1) % loop.size()])];
        if (f.size() < 3) forced = true;
        if (f.size() == 3) {
          std::array<std::uint32_t, 2> o{};
          std::size_t n = 0;
          for (const auto& en : f)
            if (en.face != i) o[n++] = en.face;
          forced = glm::length(glm::cross(faces[o[0]].normal, faces[o[1]].normal)) < 1e-9;
        }
      }
    if (!forced) r.unforced.push_back(i);
  }
  if (options.merge_unforced)
    for (const auto i : r.unforced) merged.unite(region(i, 1), region(i, -1));
  const std::uint32_t outside = merged.find(regions);
  std::vector<std::uint32_t> volume_id(regions + 1, no_index);
  r.face_volumes.resize(nf);
  r.face_kept.assign(nf, 1);
  for (std::uint32_t i = 0; i < nf; ++i) {
    const std::uint32_t a = merged.find(region(i, 1)), b = merged.find(region(i, -1));
    if (a == b) {
      r.face_kept[i] = 0;
      if (!options.merge_unforced)
        r.diagnostics.push_back("face " + std::to_string(i) + " has the same volume on both sides");
      r.face_volumes[i] = {no_index, no_index};
      continue;
    }
    std::array<std::uint32_t, 2> vol{no_index, no_index};
    const std::uint32_t sides[2] = {a, b};
    for (int k = 0; k < 2; ++k) {
      if (sides[k] == outside) continue;
      if (volume_id[sides[k]] == no_index) {
        volume_id[sides[k]] = static_cast<std::uint32_t>(r.volumes.size());
        r.volumes.emplace_back();
      }
      vol[static_cast<std::size_t>(k)] = volume_id[sides[k]];
      // The volume on the normal side sees the normal pointing in (-1); on the other side out (+1).
      r.volumes[vol[static_cast<std::size_t>(k)]].emplace_back(i, k == 0 ? -1 : 1);
    }
    r.face_volumes[i] = vol;
  }
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
