// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 6 of the wireframe pipeline (seed 000 §4.6): faces the first trace missed (the seed's
/// cone base: its breadth-first search prunes the long base circuit) are added from the planar
/// tracer at edges with fewer than two faces; overlapping faces (two selected faces on the same
/// side of a common edge in one plane) lose the larger one; and faces with a free edge (an edge
/// no other selected face uses), which can bound no volume, are removed, with the faces no edge
/// needed beside them (so an open surface invents no volume).

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/union_find.hpp"
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
  /// With remove_free: a face no edge needed while the faces around it were there, next to a
  /// face removed for a free edge, goes too (it would close a volume only because an open
  /// surface was taken away: the base of a valence-3 vertex's tetrahedron in an open mesh).
  bool drop_newly_needed = true;
  /// With remove_free: a surface (faces joined through edges) with an edge on one face only is
  /// open and bounds no volume; what the free-face removal leaves of it (closed pockets) goes too.
  bool drop_open_surfaces = true;
  /// With remove_free: a flat flap on a closed part (faces removed for free edges that lie in
  /// one plane, on a surface whose only removals they are and whose rest closes: a box with a
  /// fin) leaves that part's volumes alone and is kept as faces in no volume (`fins`).
  bool keep_fins = true;
  trace_options retrace{};  ///< tracer used for missed faces (kind is forced to planar)
};

/// The final face list of the face stages.
struct extra_faces_result : stage_report {
  std::vector<wire_face> faces;  ///< the selected faces, canonical order
  std::size_t added = 0, overlapping = 0, free = 0;
  std::size_t newly_needed = 0;       ///< faces removed by drop_newly_needed
  std::size_t open_surface = 0;       ///< faces removed by drop_open_surfaces
  std::vector<dropped_face> removed;  ///< every selected face this stage removed, and why
  /// Flat flaps standing on closed parts (keep_fins): faces with a free edge that bound no
  /// volume but belong to the answer, as faces in no volume; not in `faces` (wireframe_to_cells
  /// appends them there after finding the volumes) nor in `removed`.
  std::vector<wire_face> fins;
  /// Edges on exactly one selected face before any free face was removed: the rim of an open
  /// surface, or the edge of a hole the crossing rule cut (graph labels, increasing).
  std::vector<std::uint32_t> open_edges;
};

namespace detail {
/// keep_fins of extra_faces: finds the surfaces (faces joined through edges, `at`) whose removed
/// faces (`how`: 1 for a free edge, 2 newly needed) are all flat flaps on what is left, moves
/// those flaps from r.removed to r.fins and clears `open_surface` on the rest of the surface.
/// Their removal diagnostics (`note_of`) go too. A flap: removed for a free edge, its piece (removed faces
/// joined through edges) in one plane (within `tol`), and every open edge of the surface on one. O(Σ L +
/// removed · log).
template <class = void>
void keep_flat_fins(const wire_graph& g, const std::vector<wire_face>& faces, const edge_face_lists& at,
                    const std::vector<char>& alive, const std::vector<char>& how,
                    const std::vector<std::size_t>& note_of, extra_faces_result& r, double tol,
                    std::vector<char>& open_surface) {
  const auto nf = static_cast<std::uint32_t>(faces.size());
  union_find surface(nf), piece(nf);
  for (std::uint32_t e = 0; e < g.num_edges(); ++e)
    for (const auto i : at[e]) {
      surface.unite(at[e][0], i);
      for (const auto j : at[e])
        if (how[i] != 0 && how[j] != 0) piece.unite(i, j);
    }
  // Per surface root: 1 while it may keep its rest, 0 once it cannot; has a face left.
  std::vector<char> ok(nf, 1), rest(nf, 0);
  for (std::uint32_t i = 0; i < nf; ++i) {
    const auto s = surface.find(i);
    if (alive[i]) rest[s] = 1;
    if (how[i] == 2) ok[s] = 0;
    if (how[i] != 1) continue;
    const auto p = piece.find(i);  // flat: in the plane of its piece's root face
    const glm::dvec3 n = faces[p].normal, o = g.points[faces[p].loops[0][0]];
    bool flat = coplanar_normals(n, faces[i].normal);
    for (const auto& loop : faces[i].loops)
      for (const auto v : loop) flat = flat && std::abs(glm::dot(g.points[v] - o, n)) <= tol;
    if (!flat) ok[s] = 0;
  }
  for (const auto e : r.open_edges) {
    bool on_flap = false;
    for (const auto i : at[e]) on_flap = on_flap || how[i] == 1;
    if (!on_flap) ok[surface.find(at[e][0])] = 0;
  }
  std::vector<char> fin(nf, 0);
  std::size_t kept = 0;
  for (std::uint32_t i = 0; i < nf; ++i) {
    const auto s = surface.find(i);
    if (!ok[s] || !rest[s]) continue;
    open_surface[i] = 0;
    if (how[i] == 1) fin[i] = 1, ++kept;
  }
  if (kept == 0) return;
  // r.removed holds this stage's removals in order; the fins among them are found by their loops.
  std::vector<std::vector<std::vector<std::uint32_t>>> fin_loops;
  for (std::uint32_t i = 0; i < nf; ++i)
    if (fin[i]) fin_loops.push_back(faces[i].loops), r.fins.push_back(faces[i]);
  std::sort(fin_loops.begin(), fin_loops.end());
  std::erase_if(r.removed, [&](const dropped_face& d) {
    return d.free_edge && std::binary_search(fin_loops.begin(), fin_loops.end(), d.face.loops);
  });
  r.free -= kept;
  std::vector<char> drop_note(r.diagnostics.size(), 0);
  for (std::uint32_t i = 0; i < nf; ++i)
    if (fin[i] && note_of[i] < drop_note.size()) drop_note[note_of[i]] = 1;
  std::vector<std::string> notes;
  for (std::size_t k = 0; k < r.diagnostics.size(); ++k)
    if (!drop_note[k]) notes.push_back(std::move(r.diagnostics[k]));
  r.diagnostics = std::move(notes);
  r.diagnostics.push_back(std::to_string(kept) +
                          " flat faces with a free edge stand on closed parts (fins): kept as faces in no "
                          "volume, the closed parts keep their volumes");
}
}  // namespace detail

/// Adds missed faces, removes overlapping and free faces, and with them the faces that only an
/// open surface's removal would make needed. `crossed`: the candidates the crossing rule
/// dropped (arrangement_result::crossed); those that leave an edge on fewer than two faces
/// count as there when deciding which faces were needed before the removals. O(V + E + F·L)
/// plus, when faces are missing, one planar trace and a crossing test of each added face.
template <class = void>
extra_faces_result extra_faces(const wire_graph& g, const std::vector<wire_face>& candidates,
                               const std::vector<std::uint32_t>& selected,
                               const extra_face_options& options = {},
                               std::span<const std::uint32_t> crossed = {}) {
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
      trace_result retraced = trace_circuits(g, t);
      if (!retraced.complete) {  // out of the retrace's budget: the faces it found, flagged
        r.complete = false;
        r.work += retraced.work;
        r.diagnostics.push_back(
            cellforge::detail::cat("extra_faces: the retrace stopped: ", detail::budget_note(retraced, "")));
      }
      auto traced = unique_circuits(g, std::move(retraced.faces)).faces;
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
        r.diagnostics.push_back(cellforge::detail::cat("added face ", std::to_string(f.loops[0].size()),
                                                       "-gon at vertex ", std::to_string(f.loops[0][0]),
                                                       " missed by the first trace"));
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
              {faces[larger], cellforge::detail::cat("it overlaps a smaller face in its plane at edge ",
                                                     std::to_string(e))});
          r.diagnostics.push_back(cellforge::detail::cat(
              "a face overlapping a smaller face in its plane at edge ", std::to_string(e), " was removed"));
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
    r.open_edges = stack;
    // Which faces some edge needs before anything goes: a face that becomes needed only once
    // free faces around it are gone closes a volume the wireframe does not draw.
    std::vector<char> needed;
    if (options.drop_newly_needed && !stack.empty()) {
      // The faces the crossing rule cut out of a surface (those leaving an edge on fewer than
      // two faces) were around too: a face needed only because they went is not needed either.
      std::vector<std::uint32_t> cut;
      for (const auto i : crossed) {
        bool leaves_hole = false;
        for (const auto& loop : candidates[i].loops)
          for (std::size_t k = 0; k < loop.size() && !leaves_hole; ++k)
            leaves_hole = count[g.find_edge(loop[k], loop[(k + 1) % loop.size()])] < 2;
        if (leaves_hole) cut.push_back(i);
      }
      if (cut.empty()) {
        needed = detail::needed_faces(g, faces, at, alive);
      } else {
        std::vector<wire_face> around = faces;  // copied only when the crossing rule cut holes
        std::vector<char> there = alive;
        for (const auto i : cut) around.push_back(candidates[i]);
        there.resize(around.size(), 1);
        needed = detail::needed_faces(g, around, detail::faces_at_edges(g, around, &there), there);
        needed.resize(faces.size());
      }
    }
    // The open surfaces: faces joined through edges, with an edge on one face only.
    std::vector<char> open_surface(faces.size(), 0);
    if (options.drop_open_surfaces && !stack.empty()) {
      detail::union_find surface(faces.size());
      for (std::uint32_t e = 0; e < g.num_edges(); ++e)
        for (const auto i : at[e]) surface.unite(at[e][0], i);
      for (const auto e : stack) open_surface[surface.find(at[e][0])] = 1;
      for (std::uint32_t i = 0; i < faces.size(); ++i)
        open_surface[i] = alive[i] && open_surface[surface.find(i)];
    }
    std::vector<std::uint32_t> beside;       // unneeded faces next to a removed one, to drop
    std::vector<char> how(faces.size(), 0);  // 1: removed for a free edge, 2: newly needed
    std::vector<std::size_t> note_of(faces.size(),
                                     static_cast<std::size_t>(-1));  // its diagnostic, for a free edge
    auto remove = [&](std::uint32_t i, std::string reason, bool free_edge) {
      alive[i] = 0;
      how[i] = free_edge ? 1 : 2;
      r.removed.push_back({faces[i], std::move(reason), free_edge});
      for (const auto& loop : faces[i].loops)
        for (std::size_t k = 0; k < loop.size(); ++k) {
          const auto f = g.find_edge(loop[k], loop[(k + 1) % loop.size()]);
          if (--count[f] == 1) stack.push_back(f);
          if (!needed.empty())
            for (const auto j : at[f])
              if (alive[j] && !needed[j]) beside.push_back(j);
        }
    };
    while (!stack.empty() || !beside.empty()) {
      while (!stack.empty()) {
        const std::uint32_t e = stack.back();
        stack.pop_back();
        if (count[e] != 1) continue;
        for (const auto i : at[e]) {
          if (!alive[i]) continue;
          ++r.free;
          note_of[i] = r.diagnostics.size();
          r.diagnostics.push_back(
              cellforge::detail::cat("a face with free edge ", std::to_string(e),
                                     " (no other face uses it) bounds no volume and was removed"));
          remove(i,
                 cellforge::detail::cat("its edge ", std::to_string(e),
                                        " has no other face, so it bounds no volume"),
                 true);
        }
      }
      while (!beside.empty()) {
        const std::uint32_t j = beside.back();
        beside.pop_back();
        if (!alive[j]) continue;
        ++r.newly_needed;
        r.diagnostics.push_back("a face no edge needed beside faces removed for a free edge was removed");
        remove(j,
               "no edge needed it while the faces beside it were there; they were removed for a free edge "
               "(an open surface), and it would close a volume the wireframe does not draw",
               false);
      }
    }
    // Flat flaps on closed parts: per surface whose removals were all for a free edge, each
    // piece of removed faces (joined through edges) flat, every open edge on one of them, and
    // something left: that rest is closed whatever the flaps were, so it keeps its volumes (a box
    // with a fin) and the flaps are faces in no volume. An open mesh's rim unravels into curved
    // pieces, and pockets it leaves are closed only by the spurious cycles it padded.
    if (options.keep_fins && options.drop_open_surfaces && !r.open_edges.empty())
      detail::keep_flat_fins(g, faces, at, alive, how, note_of, r, tol, open_surface);
    // What is left of an open surface is closed pockets of it (a valence-3 vertex's tetrahedron
    // whose base closes a notch of the rim): the input does not draw them as solids either.
    for (std::uint32_t i = 0; i < faces.size(); ++i) {
      if (!alive[i] || !open_surface[i]) continue;
      ++r.open_surface;
      alive[i] = 0;
      r.removed.push_back(
          {faces[i],
           "it is part of an open surface (a surface with an edge on one face only), which bounds no volume",
           true});
    }
    if (r.open_surface > 0)
      r.diagnostics.push_back(
          std::to_string(r.open_surface) +
          " faces left of open surfaces by the free-face removal were removed (no volume)");
  }
  for (std::uint32_t i = 0; i < faces.size(); ++i)
    if (alive[i]) r.faces.push_back(std::move(faces[i]));
  std::sort(r.faces.begin(), r.faces.end(),
            [](const wire_face& a, const wire_face& b) { return a.loops < b.loops; });
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
