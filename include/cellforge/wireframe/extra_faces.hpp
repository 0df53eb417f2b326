// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 6 of the wireframe pipeline (seed 000 §4.6): faces the first trace missed (the seed's
/// cone base: its breadth-first search prunes the long base circuit) are added from the planar
/// tracer at edges with fewer than two faces; overlapping faces (two selected faces on the same
/// side of a common edge in one plane) lose the larger one; and faces with a free edge (an edge
/// no other selected face uses), which can bound no volume, are removed.

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "cellforge/wireframe/circuit_tracer.hpp"
#include "cellforge/wireframe/face_arrangement.hpp"
#include "cellforge/wireframe/unique_circuits.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// Options of extra_faces.
struct extra_face_options {
  bool add_missed = true;  ///< retrace with the planar tracer where edges lack faces
  bool remove_overlapping = true;
  bool remove_free = true;  ///< drop faces with an edge no other face shares (laminae)
  trace_options retrace{};  ///< tracer used for missed faces (kind is forced to planar)
};

/// The final face list of the face stages.
struct extra_faces_result : stage_report {
  std::vector<wire_face> faces;  ///< the selected faces, canonical order
  std::size_t added = 0, overlapping = 0, free = 0;
  std::vector<dropped_face> removed;  ///< every selected face this stage removed, and why
};

/// Adds missed faces, removes overlapping and free faces. O(V + E + F·L) plus, when faces are
/// missing, one planar trace and a crossing test of each added face against the faces.
template <class = void>
extra_faces_result extra_faces(const wire_graph& g, const std::vector<wire_face>& candidates,
                               const std::vector<std::uint32_t>& selected,
                               const extra_face_options& options = {}) {
  detail::stopwatch clock;
  extra_faces_result r;
  std::vector<wire_face> faces;
  for (const auto i : selected) faces.push_back(candidates[i]);
  std::vector<char> alive(faces.size(), 1);
  const double tol = options.retrace.planarity.relative * g.size;

  if (options.add_missed) {
    auto at = detail::faces_at_edges(g, faces, &alive);
    bool lacking = false;
    for (std::size_t e = 0; e < at.size(); ++e) lacking = lacking || at[e].size() < 2;
    if (lacking) {
      trace_options t = options.retrace;
      t.kind = tracer_kind::planar;
      auto traced = unique_circuits(g, trace_circuits(g, t).faces).faces;
      std::vector<std::vector<std::vector<std::uint32_t>>> have;  // sorted, for binary search
      for (const auto& f : faces) have.push_back(f.loops);
      std::sort(have.begin(), have.end());
      std::vector<detail::face_plane> planes;
      for (const auto& f : faces) planes.push_back({f.normal, g.points[f.loops[0][0]], {}});
      detail::crossing_test cross(g);
      for (auto& f : traced) {
        if (std::binary_search(have.begin(), have.end(), f.loops)) continue;
        bool helps = false;
        for (const auto& loop : f.loops)
          for (std::size_t k = 0; k < loop.size() && !helps; ++k)
            helps = at[g.find_edge(loop[k], loop[(k + 1) % loop.size()])].size() < 2;
        if (!helps) continue;
        const detail::face_plane pf{f.normal, g.points[f.loops[0][0]], {}};
        bool crosses = false;
        for (std::size_t i = 0; i < faces.size() && !crosses; ++i)
          crosses = cross(f, pf, faces[i], planes[i], tol);
        if (crosses) continue;
        r.diagnostics.push_back("added face " + std::to_string(f.loops[0].size()) + "-gon at vertex " +
                                std::to_string(f.loops[0][0]) + " missed by the first trace");
        planes.push_back(pf);
        faces.push_back(std::move(f));
        alive.push_back(1);
        ++r.added;
      }
    }
  }

  if (options.remove_overlapping) {
    const auto at = detail::faces_at_edges(g, faces, &alive);
    for (std::uint32_t e = 0; e < g.num_edges(); ++e) {
      const auto& list = at[e];
      for (std::size_t x = 0; x < list.size(); ++x)
        for (std::size_t y = x + 1; y < list.size(); ++y) {
          const auto &a = faces[list[x]], &b = faces[list[y]];
          if (!alive[list[x]] || !alive[list[y]]) continue;
          if (std::abs(std::abs(glm::dot(a.normal, b.normal)) - 1.0) > 1e-9) continue;
          // Same plane: they overlap when their interiors lie on the same side of the edge.
          // Faces lie to the left of their walk: inward = normal × walked direction.
          const glm::dvec3 d = g.points[g.edges[e][1]] - g.points[g.edges[e][0]];
          auto inward = [&](const wire_face& f) {
            return glm::cross(f.normal, static_cast<double>(detail::walk_direction(g, f, e)) * d);
          };
          if (glm::dot(inward(a), inward(b)) <= 0.0) continue;
          const std::uint32_t larger = a.area >= b.area ? list[x] : list[y];
          alive[larger] = 0;
          ++r.overlapping;
          r.removed.push_back(
              {faces[larger], "it overlaps a smaller face in its plane at edge " + std::to_string(e)});
          r.diagnostics.push_back("a face overlapping a smaller face in its plane at edge " +
                                  std::to_string(e) + " was removed");
        }
    }
  }

  if (options.remove_free) {
    // Iterate: removing one free face can free its neighbours.
    auto at = detail::faces_at_edges(g, faces, &alive);
    std::vector<std::uint32_t> count(g.num_edges());
    for (std::uint32_t e = 0; e < g.num_edges(); ++e) count[e] = static_cast<std::uint32_t>(at[e].size());
    std::vector<std::uint32_t> stack;
    for (std::uint32_t e = 0; e < g.num_edges(); ++e)
      if (count[e] == 1) stack.push_back(e);
    while (!stack.empty()) {
      const std::uint32_t e = stack.back();
      stack.pop_back();
      if (count[e] != 1) continue;
      for (const auto i : at[e]) {
        if (!alive[i]) continue;
        alive[i] = 0;
        ++r.free;
        r.removed.push_back(
            {faces[i], "its edge " + std::to_string(e) + " has no other face, so it bounds no volume", true});
        r.diagnostics.push_back("a face with free edge " + std::to_string(e) +
                                " (no other face uses it) bounds no volume and was removed");
        for (const auto& loop : faces[i].loops)
          for (std::size_t k = 0; k < loop.size(); ++k) {
            const auto f = g.find_edge(loop[k], loop[(k + 1) % loop.size()]);
            if (--count[f] == 1) stack.push_back(f);
          }
      }
    }
  }
  for (std::uint32_t i = 0; i < faces.size(); ++i)
    if (alive[i]) r.faces.push_back(std::move(faces[i]));
  std::sort(r.faces.begin(), r.faces.end(),
            [](const wire_face& a, const wire_face& b) { return a.loops < b.loops; });
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
