// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 9 of the wireframe pipeline (seed 000 §4.9): the cell list's input from the kept faces
/// and the volumes, in the caller's vertex order and labels: the vertices and edges the faces
/// use (dangling edges when asked), faces in canonical order, volumes as signed faces, and the
/// volume finder's other readings and unforced faces in the output's face numbering.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/wireframe/volume_finder.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// A planar cycle of the wireframe that is not a face of the result, in the caller's vertex
/// labels (loops[0] outer, then holes), and why.
struct face_note {
  std::vector<std::vector<std::uint32_t>> loops;
  std::string reason;
};

/// Another reading of the wireframe (volume_alternative in the caller's labels): the cycles it
/// would make faces, the faces of the answer it would not have, what it stands for.
struct reading_note {
  std::vector<face_note> add;         ///< cycles it keeps as faces (each with `reason` below)
  std::vector<std::uint32_t> remove;  ///< indices into wireframe_result::input.faces it drops
  std::string reason;                 ///< what the reading stands for and what set it aside
  reading_key set_aside_by = reading_key::unneeded_faces;
  bool undecided = false;  ///< the wireframe does not decide between it and the answer (ambiguous)
};

/// Options of assemble_cell_list.
struct cell_list_options {
  bool keep_dangling = false;  ///< put edges that bound no face into the cell list too
};

/// The cell list's input and the numbering that maps the graph to it.
template <Point3 P>
struct cell_list_result : stage_report {
  cell_complex_input<P> input;  ///< points, edges, faces (loops), volumes (signed faces)
  /// input.points[i] is the caller's point input_vertex[i]; input.edges[k] the caller's edge input_edge[k].
  std::vector<std::uint32_t> input_vertex, input_edge;
  std::vector<std::uint32_t> unforced;       ///< indices into input.faces of volume_result::unforced
  std::vector<reading_note> alternatives;    ///< volume_result::alternatives in the output's numbering
  std::vector<std::uint32_t> output_vertex;  ///< caller's vertex → index in input.points, or no_index
  std::vector<std::uint32_t> output_edge;    ///< graph edge → index in input.edges, or no_index
  std::size_t faceless_edges = 0;            ///< graph edges on no kept face
};

namespace detail {

/// The first edge of g in `order` that edge e crosses at a point inside both (not at a
/// vertex), within g's merge tolerance; no_index if none. O(E).
template <class = void>
std::uint32_t crossing_edge(const wire_graph& g, std::span<const std::uint32_t> order, std::uint32_t e) {
  const glm::dvec3 p = g.points[g.edges[e][0]], d1 = g.points[g.edges[e][1]] - p;
  for (const std::uint32_t f : order) {
    const auto [a, b] = g.edges[f];
    if (f == e || a == g.edges[e][0] || a == g.edges[e][1] || b == g.edges[e][0] || b == g.edges[e][1])
      continue;
    const glm::dvec3 q = g.points[a], d2 = g.points[b] - q, w = p - q;
    const double aa = glm::dot(d1, d1), bb = glm::dot(d1, d2), cc = glm::dot(d2, d2);
    const double dd = glm::dot(d1, w), ee = glm::dot(d2, w), den = aa * cc - bb * bb;
    if (!(den > 1e-12 * aa * cc)) continue;  // parallel
    const double s = (bb * ee - cc * dd) / den, t = (aa * ee - bb * dd) / den;
    if (!(s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0)) continue;
    const double tol = std::max(g.merge_tolerance, 1e-9 * std::sqrt(std::max(aa, cc)));
    if (glm::length((p + s * d1) - (q + t * d2)) <= tol) return f;
  }
  return no_index;
}

/// f as a face_note in the caller's vertex labels. O(size of f).
template <class = void>
face_note caller_face_note(const wire_graph& g, const wire_face& f, std::string reason) {
  face_note n{f.loops, std::move(reason)};
  for (auto& loop : n.loops)
    for (auto& v : loop) v = g.input_vertex[v];
  return n;
}

}  // namespace detail

/// Assembles the cell list's input (seed 000 §4.9) from the faces of extra_faces and the volumes
/// of find_volumes (face_kept, volumes, unforced, alternatives) on the graph read from `wire`;
/// `dangling` are the caller's edges read_vertices pruned. Edges bounding no face are left out
/// (kept with keep_dangling) with a diagnostic each, saying which edge they cross if any.
/// O(V + E + Σ L log L), plus O(left-out edges · E) for the crossing test while that is ≤ 2·10^7.
template <Wireframe G>
cell_list_result<typename wireframe_traits<G>::point_type> assemble_cell_list(
    const G& wire, const wire_graph& g, const std::vector<wire_face>& faces, const volume_result& volume,
    std::span<const std::uint32_t> dangling, const cell_list_options& options = {}) {
  using P = typename wireframe_traits<G>::point_type;
  detail::stopwatch clock;
  cell_list_result<P> list;
  std::vector<char> edge_used(g.num_edges(), 0);
  std::vector<std::uint32_t> face_id(faces.size(), no_index);
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    if (!volume.face_kept[i]) continue;
    face_id[i] = static_cast<std::uint32_t>(list.input.faces.size());
    list.input.faces.push_back({faces[i].loops});
    for (const auto& loop : faces[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k)
        edge_used[g.find_edge(loop[k], loop[(k + 1) % loop.size()])] = 1;
  }
  // Vertices and edges: those the faces use (and dangling edges when asked), caller's order.
  std::vector<std::array<std::uint32_t, 2>> edges;  // in the caller's vertex labels
  std::vector<std::uint32_t> edge_origin;
  std::vector<std::uint32_t> graph_edge_out(g.num_edges(), no_index);  // graph edge → output edge
  // An edge left out because it crosses another edge (a diagonal through a face): say so, or
  // "bounds no face" hides why. Tested against every edge while that stays cheap.
  const auto left_out = static_cast<std::size_t>(std::count(edge_used.begin(), edge_used.end(), char{0}));
  const bool test_crossings = left_out * g.num_edges() <= 20'000'000;
  // The graph's edges in the caller's order (read_vertices may number them spatially).
  std::vector<std::uint32_t> caller_order(g.num_edges());
  for (std::uint32_t e = 0; e < g.num_edges(); ++e)
    caller_order[g.read_order.empty() ? e : g.read_order[e]] = e;
  for (const std::uint32_t e : caller_order) {
    if (!edge_used[e]) {
      const std::uint32_t other =
          test_crossings ? detail::crossing_edge(g, detail::span_of(caller_order), e) : no_index;
      list.diagnostics.push_back(cellforge::detail::cat(
          "edge ", std::to_string(g.input_edge[e]), " bounds no face",
          (other != no_index
               ? cellforge::detail::cat(" (it crosses edge ", std::to_string(g.input_edge[other]),
                                        " between their ends)")
               : std::string()),
          (options.keep_dangling ? "; kept as a dangling edge" : " and is left out")));
    }
    if (edge_used[e] || options.keep_dangling) {
      graph_edge_out[e] = static_cast<std::uint32_t>(edges.size());
      edges.push_back({g.input_vertex[g.edges[e][0]], g.input_vertex[g.edges[e][1]]});
      edge_origin.push_back(g.input_edge[e]);
    }
  }
  if (options.keep_dangling) {
    for (const auto e : dangling) {
      const auto ab = wireframe_traits<G>::endpoints(wire, e);
      edges.push_back({static_cast<std::uint32_t>(ab[0]), static_cast<std::uint32_t>(ab[1])});
      edge_origin.push_back(e);
    }
  }
  std::vector<std::uint32_t> label(wireframe_traits<G>::num_vertices(wire), no_index);
  for (const auto& e : edges)
    for (const auto v : e) label[v] = 0;
  for (std::uint32_t v = 0; v < label.size(); ++v) {
    if (label[v] == no_index) continue;
    label[v] = static_cast<std::uint32_t>(list.input.points.size());
    list.input.points.push_back(static_cast<P>(wireframe_traits<G>::position(wire, v)));
    list.input_vertex.push_back(v);
  }
  // Graph vertex → output label (graph vertices are the caller's representatives).
  for (const auto& e : edges) list.input.edges.push_back({label[e[0]], label[e[1]]});
  list.input_edge = std::move(edge_origin);
  // Faces in the canonical order of the output labels (smallest first, towards its smaller
  // neighbour; holes from their smallest): the same loops whatever the graph's numbering.
  std::vector<char> reversed(list.input.faces.size(), 0);
  for (std::size_t i = 0; i < list.input.faces.size(); ++i) {
    auto& loops = list.input.faces[i].loops;
    for (auto& loop : loops)
      for (auto& v : loop) v = label[g.input_vertex[v]];
    reversed[i] = cellforge::canonical_cycle(loops[0]);
    for (std::size_t h = 1; h < loops.size(); ++h) {
      if (reversed[i]) std::reverse(loops[h].begin(), loops[h].end());
      std::rotate(loops[h].begin(), std::min_element(loops[h].begin(), loops[h].end()), loops[h].end());
    }
    std::sort(loops.begin() + 1, loops.end());
  }
  for (const auto& vol : volume.volumes) {
    cell_input_volume out;
    for (const auto& [f, s] : vol) out.faces.emplace_back(face_id[f], reversed[face_id[f]] ? -s : s);
    list.input.volumes.push_back(std::move(out));
  }
  for (const auto i : volume.unforced)
    if (face_id[i] != no_index) list.unforced.push_back(face_id[i]);
  for (const auto& a : volume.alternatives) {
    reading_note n{{}, {}, a.reading, a.set_aside_by, a.undecided};
    for (const auto i : a.add) n.add.push_back(detail::caller_face_note(g, faces[i], a.reading));
    for (const auto i : a.remove)
      if (face_id[i] != no_index) n.remove.push_back(face_id[i]);
    list.alternatives.push_back(std::move(n));
  }
  list.faceless_edges = left_out;
  list.output_vertex = std::move(label);
  list.output_edge = std::move(graph_edge_out);
  list.milliseconds = clock.ms();
  return list;
}

}  // namespace cellforge
