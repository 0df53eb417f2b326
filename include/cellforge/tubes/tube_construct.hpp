// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The tube construct (seed 001 §V.A): a skeleton graph split into
/// junctions (branches: nodes of degree 3 or more, and any other node the caller marks) and
/// the paths of nodes between them. No two junctions are adjacent: a node is inserted on
/// every edge that joins two. Paths are traced by iteration, never recursion.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/union_find.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/tubes/skeleton.hpp"

namespace cellforge {

/// What a node of the tube construct is.
enum class tube_node_kind : std::uint8_t {
  path_node,  ///< degree 2 (a node of a path) — or degree 1 (the free end of a path)
  junction,   ///< a branch (degree 3 or more) or a node marked as a junction
  isolated,   ///< degree 0: a sphere of its own
};

/// One node of the construct: a skeleton node, or a node inserted between two junctions.
struct tube_node {
  static constexpr std::uint32_t none = 0xFFFFFFFFu;
  std::uint32_t skeleton_node = none;  ///< the skeleton node, or none for an inserted node
  std::uint32_t split_edge = none;     ///< for an inserted node: the skeleton edge it splits in half
  tube_node_kind kind = tube_node_kind::path_node;
  std::uint32_t degree = 0;
};

/// A path: construct nodes in order, and the skeleton edge of each step. An open path runs
/// from a junction or a free end to a junction or a free end; a closed path (a ring of
/// nodes, no junction) repeats its first node implicitly after its last.
struct tube_path {
  std::vector<std::uint32_t> nodes;
  std::vector<std::uint32_t> edges;  ///< size nodes - 1 (open) or nodes (closed)
  std::vector<std::uint8_t> along;   ///< per step: 1 when the step follows its edge's direction
  bool closed = false;
};

/// The construct of a whole skeleton.
struct tube_construct {
  std::vector<tube_node> nodes;          ///< skeleton nodes first (same indices), then inserted ones
  std::vector<std::uint32_t> junctions;  ///< construct nodes that are junctions, ascending
  std::vector<std::uint32_t> isolated;   ///< construct nodes of degree 0
  std::vector<tube_path> paths;          ///< in the seed's order (see make_tube_construct)
  std::size_t inserted_nodes = 0;        ///< nodes added between adjacent junctions
  std::size_t components = 0;            ///< connected components of the skeleton (isolated nodes count)
  std::int64_t cycle_rank = 0;           ///< E − V + C: the genus the tube surface must have
};

namespace detail::tubes {

/// Incidence lists in CSR form: for node v, the (edge, other end) pairs. O(V + E).
struct incidence {
  std::vector<std::uint32_t> start;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> items;
  std::size_t degree(std::size_t v) const noexcept { return start[v + 1] - start[v]; }
};

template <class = void>
incidence make_incidence(std::size_t nv, const std::vector<std::array<std::uint32_t, 2>>& edges) {
  incidence inc;
  inc.start.assign(nv + 1, 0);
  for (const auto& e : edges) ++inc.start[e[0] + 1], ++inc.start[e[1] + 1];
  for (std::size_t v = 0; v < nv; ++v) inc.start[v + 1] += inc.start[v];
  inc.items.resize(inc.start[nv]);
  std::vector<std::uint32_t> fill(inc.start.begin(), inc.start.end() - 1);
  // Out-edges of a node come before its in-edges, each in edge order: the seed converts the
  // paths that leave a branch first.
  for (std::uint32_t j = 0; j < edges.size(); ++j) inc.items[fill[edges[j][0]]++] = {j, edges[j][1]};
  for (std::uint32_t j = 0; j < edges.size(); ++j) inc.items[fill[edges[j][1]]++] = {j, edges[j][0]};
  return inc;
}

}  // namespace detail::tubes

/// Builds the tube construct of a skeleton given as node count and directed edges (already
/// validated: endpoints in range, no self-loops, no duplicates). `junction[v]` marks extra
/// junctions (e.g. sharp bends); empty means none. Paths come in the seed's order (algorithm
/// 7): those leaving a junction (out-edges first), then those starting at a free end, then
/// rings. O(V + E), no recursion.
template <class = void>
tube_construct make_tube_construct(std::size_t num_nodes,
                                   const std::vector<std::array<std::uint32_t, 2>>& edges,
                                   const std::vector<std::uint8_t>& junction = {}) {
  constexpr std::uint32_t none = tube_node::none;
  const detail::tubes::incidence inc = detail::tubes::make_incidence(num_nodes, edges);
  tube_construct tc;
  tc.nodes.resize(num_nodes);
  for (std::uint32_t v = 0; v < num_nodes; ++v) {
    tube_node& n = tc.nodes[v];
    n.skeleton_node = v;
    n.degree = static_cast<std::uint32_t>(inc.degree(v));
    n.kind = n.degree == 0                                         ? tube_node_kind::isolated
             : n.degree >= 3 || (!junction.empty() && junction[v]) ? tube_node_kind::junction
                                                                   : tube_node_kind::path_node;
    if (n.kind == tube_node_kind::junction) tc.junctions.push_back(v);
    if (n.kind == tube_node_kind::isolated) tc.isolated.push_back(v);
  }
  const auto is_junction = [&](std::uint32_t v) { return tc.nodes[v].kind == tube_node_kind::junction; };
  // A node between every two adjacent junctions: the construct node of edge j's midpoint.
  std::vector<std::uint32_t> midpoint(edges.size(), none);
  for (std::uint32_t j = 0; j < edges.size(); ++j)
    if (is_junction(edges[j][0]) && is_junction(edges[j][1])) {
      midpoint[j] = static_cast<std::uint32_t>(tc.nodes.size());
      tc.nodes.push_back({none, j, tube_node_kind::path_node, 2});
      ++tc.inserted_nodes;
    }

  std::vector<std::uint8_t> used(edges.size(), 0);
  // Walks from node `from` along edge j until a junction or a free end (or back to `from`
  // on a ring), appending to `path`. Iterative: a path of any length uses O(1) stack.
  const auto walk = [&](std::uint32_t from, std::uint32_t j, tube_path& path) {
    std::uint32_t at = from;
    path.nodes.push_back(from);
    while (true) {
      used[j] = 1;
      const std::uint32_t next = edges[j][0] == at ? edges[j][1] : edges[j][0];
      const std::uint8_t along = edges[j][0] == at ? 1 : 0;
      if (midpoint[j] != none) {  // junction – inserted node – junction: two steps on one edge
        path.nodes.push_back(midpoint[j]);
        path.edges.push_back(j);
        path.along.push_back(along);
      }
      path.edges.push_back(j);
      path.along.push_back(along);
      if (next == from && !is_junction(next)) {  // back at the start of a ring
        path.closed = true;
        return;
      }
      path.nodes.push_back(next);
      if (is_junction(next) || inc.degree(next) != 2) return;
      // The other edge of a degree-2 node.
      const auto* it = &inc.items[inc.start[next]];
      const std::uint32_t other = it[0].first == j ? it[1].first : it[0].first;
      if (used[other]) return;
      at = next;
      j = other;
    }
  };
  // Each path is walked into one buffer and copied out at its size: one allocation per array
  // instead of the growth steps of each (half of this function's time on a random tree).
  tube_path p;
  {  // Room for every open path (each has two ends, at junctions or free ends): the array of
     // paths then grows at most for rings, instead of copying itself into fresh pages.
    std::size_t ends = 0;
    for (std::uint32_t v = 0; v < num_nodes; ++v)
      ends += is_junction(v) ? inc.degree(v) : inc.degree(v) == 1 ? 1 : 0;
    detail::reserve_large(tc.paths, ends / 2);
  }
  const auto start = [&]() -> tube_path& {
    p.nodes.clear(), p.edges.clear(), p.along.clear();
    p.closed = false;
    return p;
  };
  for (const std::uint32_t b : tc.junctions)
    for (std::size_t k = inc.start[b]; k < inc.start[b + 1]; ++k)
      if (!used[inc.items[k].first]) {
        walk(b, inc.items[k].first, start());
        tc.paths.push_back(p);
      }
  // Free ends: a node of degree 1; the seed starts at nodes with no in-node, so sources first.
  for (int pass = 0; pass < 2; ++pass)
    for (std::uint32_t v = 0; v < num_nodes; ++v) {
      if (inc.degree(v) != 1 || is_junction(v)) continue;
      const std::uint32_t j = inc.items[inc.start[v]].first;
      if (used[j] || (pass == 0 && edges[j][0] != v)) continue;
      walk(v, j, start());
      tc.paths.push_back(p);
    }
  // What is left are rings of degree-2 nodes: start at the lowest node.
  for (std::uint32_t v = 0; v < num_nodes; ++v)
    for (std::size_t k = inc.start[v]; k < inc.start[v + 1]; ++k)
      if (!used[inc.items[k].first]) {
        walk(v, inc.items[k].first, start());
        if (!p.closed)
          throw error(error_category::internal,
                      cellforge::detail::cat("make_tube_construct: an unused edge at node ",
                                             std::to_string(v), " is not on a ring"));
        tc.paths.push_back(p);
      }

  // Components by union-find over the edges (isolated nodes are components of their own).
  detail::union_find sets(num_nodes);
  std::size_t components = num_nodes;
  for (const auto& e : edges) components -= sets.unite(e[0], e[1]) ? 1 : 0;
  tc.components = components;
  tc.cycle_rank = static_cast<std::int64_t>(edges.size()) - static_cast<std::int64_t>(num_nodes) +
                  static_cast<std::int64_t>(components);
  return tc;
}

/// The tube construct of any Skeleton: junctions are its nodes of degree 3 or more (make_tubes
/// adds the sharp bends its options ask for). Validates g first (check_skeleton). O(V + E).
template <Skeleton G>
tube_construct make_tube_construct(const G& g) {
  check_skeleton(g);
  using T = skeleton_traits<G>;
  std::vector<std::array<std::uint32_t, 2>> edges(T::num_edges(g));
  for (std::size_t j = 0; j < edges.size(); ++j) {
    const std::array<std::size_t, 2> ab = T::endpoints(g, j);
    edges[j] = {static_cast<std::uint32_t>(ab[0]), static_cast<std::uint32_t>(ab[1])};
  }
  return make_tube_construct(T::num_nodes(g), edges);
}

}  // namespace cellforge
