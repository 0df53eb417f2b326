// SPDX-License-Identifier: MIT
#pragma once
// The geometry half of Loop subdivision: the vertex and edge masks, applied to any
// attribute (positions, or a user's vertex property) read from the parent mesh. It needs
// no circulation: one pass over the parent edges gathers each vertex's valence and the sum
// of its neighbours (so flipped edges and several fans at a vertex need no special walk),
// and writes every edge point; one pass over the vertices finishes the vertex points.

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "cellforge/algorithms/detail/loop_topology.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"

namespace cellforge::detail::loop {

/// Which masks to apply (the public options, reduced to what the masks need).
struct mask_params {
  bool warren = false;        ///< Warren's β instead of Loop's original one
  bool move_boundary = true;  ///< boundary vertices follow the cubic B-spline rule
  bool keep_corners = false;  ///< ... except those with a single face, which stay
};

/// β(n) of the interior vertex mask: Loop's (5/8 − (3/8 + cos(2π/n)/4)²)/n, or Warren's
/// 3/(8n) (3/16 for n = 3). O(1).
template <class = void>
double beta(std::uint32_t n, bool warren) noexcept {
  if (warren) return n == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * n);
  const double c = 0.375 + 0.25 * std::cos(2.0 * std::numbers::pi / n);
  return (0.625 - c * c) / n;
}

/// What the masks did beyond the rules' normal case.
struct mask_stats {
  std::size_t fixed_vertices = 0;  ///< kept in place: several fans, or a broken fan
};

/// Per-vertex gathering state: the neighbour sum, the valence and the number of boundary
/// edges (0 inside, 2 on a manifold boundary, 2k at a vertex with k open fans).
template <class A>
struct vertex_node {
  A sum{};
  std::uint32_t valence = 0, boundary = 0;
};

[[noreturn]] inline void bad_edge(std::uint32_t e) {
  throw error(error_category::invalid_input,
              cellforge::detail::cat("loop_subdivide: edge ", std::to_string(e),
                                     " has an end vertex or face link that does not exist; the "
                                     "mesh is corrupted (validate() says where)"));
}

/// The end vertices (a, b) of edge e, b the head of its half-edge 2e; throws when either
/// does not exist. Both sides of a flipped edge end at b: a is then the tail of side 0. O(1).
template <class = void>
std::pair<std::uint32_t, std::uint32_t> edge_ends(std::span<const record> he, std::uint32_t e,
                                                  std::uint32_t nv) {
  const record& r0 = he[2 * e];
  const std::uint32_t b = r0.head, h = he[2 * e + 1].head;
  const std::uint32_t a = h != b ? h : (r0.prev < he.size() ? he[r0.prev].head : npos);
  if (a >= nv || b >= nv) bad_edge(e);
  return {a, b};
}

/// Applies Loop's masks to the attribute `read(v)` (accumulated as A: double or a GLM
/// double vector) of a parent with records `he` and `nv` vertices, whose boundary edges are
/// listed; `store(i, value)` receives the child vertex i (v for parent vertices, nv + e for
/// the point on edge e). O(V + E).
template <class A, class Read, class Store>
mask_stats apply_masks(std::span<const record> he, std::uint32_t nv,
                       std::span<const std::uint32_t> boundary_edges, const mask_params& params, Read&& read,
                       Store&& store) {
  const std::size_t nh = he.size();
  const auto ne = static_cast<std::uint32_t>(nh / 2);
  std::vector<vertex_node<A>> node;
  reserve_large(node, nv);
  node.resize(nv);

  // Boundary edges first: a boundary vertex's mask sees only its boundary neighbours.
  for (const std::uint32_t e : boundary_edges) {
    const std::uint32_t b = he[2 * e].head, a = he[2 * e + 1].head;
    if (a >= nv || b >= nv) bad_edge(e);
    ++node[a].boundary;
    ++node[b].boundary;
    node[a].sum += read(b);
    node[b].sum += read(a);
  }

  for (std::uint32_t e = 0; e < ne; ++e) {
    const record& r0 = he[2 * e];
    const record& r1 = he[2 * e + 1];
    const auto [a, b] = edge_ends(he, e, nv);
    const A pa = read(a), pb = read(b);
    vertex_node<A>& na = node[a];
    vertex_node<A>& nb = node[b];
    ++na.valence;
    ++nb.valence;
    if (r0.face != npos && r1.face != npos) {
      const std::uint32_t c = r0.next < nh ? he[r0.next].head : npos;
      const std::uint32_t d = r1.next < nh ? he[r1.next].head : npos;
      if (c >= nv || d >= nv) bad_edge(e);
      // Weights first, so that huge coordinates do not overflow in the sums.
      store(nv + e, 0.375 * pa + 0.375 * pb + 0.125 * read(c) + 0.125 * read(d));
      if (na.boundary == 0) na.sum += pb;
      if (nb.boundary == 0) nb.sum += pa;
    } else {
      store(nv + e, 0.5 * pa + 0.5 * pb);
    }
  }

  // The vertex masks; (1 − nβ, β) tabulated for the usual valences.
  constexpr std::uint32_t table_size = 32;
  std::array<double, table_size> centre{}, ring{};
  for (std::uint32_t n = 3; n < table_size; ++n) {
    ring[n] = beta(n, params.warren);
    centre[n] = 1.0 - n * ring[n];
  }
  mask_stats stats;
  for (std::uint32_t v = 0; v < nv; ++v) {
    const vertex_node<A>& n = node[v];
    const A p = read(v);
    if (n.boundary == 0 && n.valence >= 3) {
      const double w = n.valence < table_size ? ring[n.valence] : beta(n.valence, params.warren);
      const double c = n.valence < table_size ? centre[n.valence] : 1.0 - n.valence * w;
      store(v, c * p + w * n.sum);
    } else if (n.boundary == 2 && params.move_boundary && !(params.keep_corners && n.valence == 2)) {
      store(v, 0.75 * p + 0.125 * n.sum);
    } else {
      // Isolated, a boundary kept by the options, or several fans (2k boundary edges): no
      // single curve passes through such a vertex, so it stays where it is.
      store(v, p);
      if (n.boundary > 2 || n.boundary == 1 || (n.boundary == 0 && n.valence > 0)) ++stats.fixed_vertices;
    }
  }
  return stats;
}

/// The linear rule for user attributes: parent vertices keep their value, the point on an
/// edge takes the mean of its two ends. O(V + E).
template <class A, class Read, class Store>
void apply_linear(std::span<const record> he, std::uint32_t nv, Read&& read, Store&& store) {
  const auto ne = static_cast<std::uint32_t>(he.size() / 2);
  for (std::uint32_t v = 0; v < nv; ++v) store(v, read(v));
  for (std::uint32_t e = 0; e < ne; ++e) {
    const auto [a, b] = edge_ends(he, e, nv);
    store(nv + e, 0.5 * read(a) + 0.5 * read(b));
  }
}

}  // namespace cellforge::detail::loop
