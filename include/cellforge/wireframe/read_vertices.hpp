// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 1 of the wireframe pipeline (seed 000 §4.1): read and label vertices and edges,
/// merge points closer than a tolerance relative to the model size, check the edges and
/// record for each vertex its incident edges with their direction.

#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/tolerance.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// Options of read_vertices.
struct read_options {
  tolerance merge{1e-9};  ///< points closer than this (relative to the bounding-box diagonal) are one vertex
  bool prune_dangling = true;  ///< remove edges that cannot lie on any circuit (trees hanging off the graph)
  bool strict =
      false;  ///< throw on zero-length, duplicate and dangling edges instead of dropping them with a note
};

/// What read_vertices found; `graph` is the labelled wireframe the other stages use.
struct read_result : stage_report {
  wire_graph graph;
  std::size_t input_vertices = 0, input_edges = 0;
  std::size_t merged_points = 0;        ///< points merged into an earlier point within tolerance
  std::size_t zero_length_edges = 0;    ///< dropped: both ends are the same vertex (after merging)
  std::size_t duplicate_edges = 0;      ///< dropped: join the same two vertices as an earlier edge
  std::size_t isolated_vertices = 0;    ///< points used by no remaining edge
  std::vector<std::uint32_t> dangling;  ///< caller's indices of edges removed because no circuit can use them
};

namespace detail {

inline std::string point_text(const glm::dvec3& p) {
  return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
}

/// Merges points within tol by hashing them to cells of side tol; returns each point's
/// representative (the smallest index of its cluster). O(n) expected.
inline std::vector<std::uint32_t> merge_close_points(const std::vector<glm::dvec3>& p,
                                                     const std::vector<char>& used, double tol) {
  const std::size_t n = p.size();
  union_find uf(n);
  // Cell → first point, then a linked list through `next`: no allocation per cell.
  std::unordered_map<std::array<std::int64_t, 3>, std::uint32_t, cell_hash> cells;
  cells.reserve(n);
  std::vector<std::uint32_t> next(n, no_index);
  auto cell_of = [&](const glm::dvec3& q) {
    return std::array<std::int64_t, 3>{static_cast<std::int64_t>(std::floor(q.x / tol)),
                                       static_cast<std::int64_t>(std::floor(q.y / tol)),
                                       static_cast<std::int64_t>(std::floor(q.z / tol))};
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    const auto [it, fresh] = cells.emplace(cell_of(p[i]), i);
    if (!fresh) {
      next[i] = it->second;
      it->second = i;
    }
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    const auto c = cell_of(p[i]);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == cells.end()) continue;
          for (std::uint32_t j = it->second; j != no_index; j = next[j])
            if (j > i && glm::length(p[i] - p[j]) <= tol) uf.unite(i, j);
        }
  }
  std::vector<std::uint32_t> rep(n);
  for (std::uint32_t i = 0; i < n; ++i) rep[i] = uf.find(i);
  return rep;
}

}  // namespace detail

/// Reads any Wireframe into the labelled graph: checks coordinates and indices, merges close
/// points, drops (or rejects) zero-length, duplicate and dangling edges. O(V + E) expected.
template <Wireframe G>
read_result read_vertices(const G& wire, const read_options& options = {}) {
  using T = wireframe_traits<G>;
  detail::stopwatch clock;
  read_result r;
  const std::size_t nv = T::num_vertices(wire), ne = T::num_edges(wire);
  r.input_vertices = nv;
  r.input_edges = ne;
  if (ne == 0) throw error(error_category::invalid_input, "read_vertices: the wireframe has no edges");
  if (nv >= no_index || ne >= no_index)
    throw error(error_category::invalid_input, "read_vertices: more than 2^32-1 vertices or edges");
  std::vector<glm::dvec3> p(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    p[v] = to_dvec3(T::position(wire, v));
    if (!std::isfinite(p[v].x) || !std::isfinite(p[v].y) || !std::isfinite(p[v].z))
      throw error(error_category::invalid_input, "read_vertices: vertex " + std::to_string(v) +
                                                     " has a NaN or infinite coordinate " +
                                                     detail::point_text(p[v]));
  }
  std::vector<std::array<std::uint32_t, 2>> ends(ne);
  std::vector<char> used(nv, 0);
  bounding_box box;
  for (std::size_t e = 0; e < ne; ++e) {
    const auto ab = T::endpoints(wire, e);
    if (ab[0] >= nv || ab[1] >= nv)
      throw error(error_category::invalid_input,
                  "read_vertices: edge " + std::to_string(e) + " refers to vertex " +
                      std::to_string(std::max(ab[0], ab[1])) + " but there are only " + std::to_string(nv) +
                      " vertices");
    ends[e] = {static_cast<std::uint32_t>(ab[0]), static_cast<std::uint32_t>(ab[1])};
    for (const auto v : ends[e]) {
      used[v] = 1;
      box.add(p[v]);
    }
  }
  const double tol = options.merge.absolute(box);
  if (box.diagonal() == 0.0)
    throw error(error_category::invalid_input, "read_vertices: all " + std::to_string(ne) +
                                                   " edges have zero length (every point is " +
                                                   detail::point_text(box.min) + ")");
  const std::vector<std::uint32_t> rep = detail::merge_close_points(p, used, tol);
  for (std::size_t v = 0; v < nv; ++v)
    if (used[v] && rep[v] != v) {
      ++r.merged_points;
      r.diagnostics.push_back("vertex " + std::to_string(v) + " lies within " + std::to_string(tol) +
                              " of vertex " + std::to_string(rep[v]) + " and was merged into it");
    }

  // Edges between representatives; zero-length and duplicate ones dropped (or rejected).
  std::unordered_map<std::uint64_t, std::uint32_t> seen;
  std::vector<std::uint32_t> kept;
  auto complain = [&](const std::string& what) {
    if (options.strict) throw error(error_category::invalid_input, "read_vertices: " + what);
    r.diagnostics.push_back(what);
  };
  for (std::uint32_t e = 0; e < ne; ++e) {
    std::uint32_t a = rep[ends[e][0]], b = rep[ends[e][1]];
    if (a == b) {
      ++r.zero_length_edges;
      complain("edge " + std::to_string(e) + " has zero length (its ends " + std::to_string(ends[e][0]) +
               " and " + std::to_string(ends[e][1]) + " are the same point) and was dropped");
      continue;
    }
    const std::uint64_t k = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
    const auto [it, fresh] = seen.emplace(k, e);
    if (!fresh) {
      ++r.duplicate_edges;
      complain("edge " + std::to_string(e) + " duplicates edge " + std::to_string(it->second) +
               " (vertices " + std::to_string(a) + "-" + std::to_string(b) + ") and was dropped");
      continue;
    }
    ends[e] = {a, b};
    kept.push_back(e);
  }

  // Dangling edges: repeatedly strip vertices of degree 1, since no circuit passes through them.
  std::vector<char> alive(ne, 0);
  for (const auto e : kept) alive[e] = 1;
  if (options.prune_dangling) {
    std::vector<std::uint32_t> deg(nv, 0);
    std::vector<std::vector<std::uint32_t>> inc(nv);
    for (const auto e : kept)
      for (const auto v : ends[e]) {
        ++deg[v];
        inc[v].push_back(e);
      }
    std::vector<std::uint32_t> stack;
    for (std::uint32_t v = 0; v < nv; ++v)
      if (deg[v] == 1) stack.push_back(v);
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      if (deg[v] != 1) continue;
      for (const auto e : inc[v]) {
        if (!alive[e]) continue;
        alive[e] = 0;
        r.dangling.push_back(e);
        const std::uint32_t w = ends[e][0] == v ? ends[e][1] : ends[e][0];
        --deg[v];
        if (--deg[w] == 1) stack.push_back(w);
      }
    }
    std::sort(r.dangling.begin(), r.dangling.end());
    for (const auto e : r.dangling)
      complain("edge " + std::to_string(e) + " is dangling (it lies on no circuit) and was removed");
  }

  // Label the remaining vertices in the caller's order so that indices survive the trip.
  wire_graph& g = r.graph;
  std::vector<std::uint32_t> label(nv, no_index);
  for (std::uint32_t e = 0; e < ne; ++e)
    if (alive[e])
      for (const auto v : ends[e]) label[v] = 0;
  bounding_box kept_box;
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (label[v] == no_index) {
      if (used[v] && rep[v] == v) ++r.isolated_vertices;
      continue;
    }
    label[v] = static_cast<std::uint32_t>(g.points.size());
    g.points.push_back(p[v]);
    g.input_vertex.push_back(v);
    kept_box.add(p[v]);
  }
  for (std::uint32_t e = 0; e < ne; ++e)
    if (alive[e]) {
      g.edges.push_back({label[ends[e][0]], label[ends[e][1]]});
      g.input_edge.push_back(e);
    }
  if (g.edges.empty())
    throw error(error_category::topology, "read_vertices: no edge lies on a circuit (the " +
                                              std::to_string(ne) +
                                              " edges form trees), so the wireframe bounds no face");
  g.size = kept_box.diagonal();
  g.center = kept_box.center();
  g.merge_tolerance = tol;
  g.link();
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
