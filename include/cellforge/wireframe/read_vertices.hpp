// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 1 of the wireframe pipeline (seed 000 §4.1): read and label vertices and edges,
/// merge points closer than a tolerance relative to the model size, check the edges and
/// record for each vertex its incident edges with their direction.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/common.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/morton.hpp"
#include "cellforge/core/tolerance.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// Options of read_vertices.
struct wireframe_read_options {
  /// Points closer than this fraction of their local edge length (the median length of the
  /// edges at each, the smaller of the two) are one vertex: a far vertex or a long part does
  /// not swallow a small one. A vertex lies inside an edge within this fraction of both.
  tolerance merge{1e-9};
  bool prune_dangling = true;  ///< remove edges that cannot lie on any circuit (trees hanging off the graph)
  /// Throw on zero-length, duplicate and dangling edges instead of dropping them with a note.
  bool strict = false;
  bool split_at_vertices = true;  ///< split an edge where another vertex lies inside it (T-junction, overlap)
  /// Steps the merge and split searches may take (cells visited, vertices tested); 0: no limit.
  cellforge::work_budget work_budget = 200'000'000;
  /// Number the graph's vertices along a Morton curve and its edges by their ends, so that the
  /// pipeline's speed does not depend on the caller's numbering (results are mapped back to
  /// it); false keeps the caller's order in the graph.
  bool spatial_order = true;
};

/// What read_vertices found; `graph` is the labelled wireframe the other stages use.
struct wireframe_read_result : stage_report {
  wire_graph graph;
  std::size_t input_vertices = 0, input_edges = 0;
  std::size_t merged_points = 0;        ///< points merged into an earlier point within tolerance
  std::size_t zero_length_edges = 0;    ///< dropped: both ends are the same vertex (after merging)
  std::size_t duplicate_edges = 0;      ///< dropped: join the same two vertices as an earlier edge
  std::size_t isolated_vertices = 0;    ///< points used by no remaining edge
  std::size_t split_edges = 0;          ///< vertices found inside edges (each splits an edge there)
  std::vector<std::uint32_t> dangling;  ///< caller's indices of edges removed because no circuit can use them
};

namespace detail {

/// Grid coordinate floor(x) as an integer, clamped to ±2^52 so that no finite input (a model
/// 1e12 from the origin, a cell of 1e-12) overflows; clamping only merges far cells. O(1).
template <class = void>
std::int64_t grid_coordinate(double x) {
  constexpr double limit = 4503599627370496.0;  // 2^52: exact in a double, far from int64 overflow
  const double c = std::floor(x);
  return static_cast<std::int64_t>(c != c ? 0.0 : std::clamp(c, -limit, limit));
}

template <class = void>
std::string number_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

template <class = void>
std::string point_text(const glm::dvec3& p) {
  return cellforge::detail::cat("(", number_text(p.x), ", ", number_text(p.y), ", ", number_text(p.z), ")");
}

/// The edges that are no loops listed by their ends (smaller end, then larger, then index):
/// two stable counting passes over the vertex labels, where a comparison sort of edges in a
/// random order costs a mispredicted branch or a cache miss per step. O(E + V).
template <class = void>
std::vector<std::uint32_t> edges_by_ends(const std::vector<std::array<std::uint32_t, 2>>& ends,
                                         std::size_t nv) {
  std::vector<std::uint32_t> start(nv + 1, 0), by_larger, out;
  for (const auto& [a, b] : ends)
    if (a != b) ++start[std::max(a, b) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  by_larger.resize(start.back());
  for (std::uint32_t e = 0; e < ends.size(); ++e)
    if (ends[e][0] != ends[e][1]) by_larger[start[std::max(ends[e][0], ends[e][1])]++] = e;
  start.assign(nv + 1, 0);
  for (const std::uint32_t e : by_larger) ++start[std::min(ends[e][0], ends[e][1]) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  out.resize(by_larger.size());
  for (const std::uint32_t e : by_larger) out[start[std::min(ends[e][0], ends[e][1])]++] = e;
  return out;
}

/// Merges the points listed in `order`: two points are one when they are equal or closer than
/// both their tolerances `tol[i]` (a point's own scale). Points are hashed to cells of 64
/// tolerances in one grid per factor of 8 of tolerance; each point looks in the grids of its
/// own and larger tolerances, where its ball covers a cell or a few. Returns each point's
/// representative (the smallest index of its cluster, whatever the order; a spatial order keeps
/// the cell look-ups in cache). O(n · levels) expected, levels = log8 of the tolerances' spread.
template <class = void>
std::vector<std::uint32_t> merge_close_points(const std::vector<glm::dvec3>& p,
                                              const std::vector<std::uint32_t>& order,
                                              const std::vector<double>& tol, work_counter& budget) {
  const std::size_t n = p.size();
  union_find uf(n);
  glm::dvec3 low(std::numeric_limits<double>::infinity());
  for (const std::uint32_t i : order) low = glm::min(low, p[i]);
  // Equal points first (a zero tolerance merges only these).
  {
    std::unordered_map<std::array<std::int64_t, 3>, std::uint32_t, cell_hash> same;
    same.reserve(order.size());
    for (const std::uint32_t i : order) {
      std::array<std::int64_t, 3> key{};
      for (int k = 0; k < 3; ++k) {
        const double c = p[i][k] == 0.0 ? 0.0 : p[i][k];  // -0 and +0 alike
        std::memcpy(&key[static_cast<std::size_t>(k)], &c, sizeof c);
      }
      const auto [it, fresh] = same.emplace(key, i);
      if (!fresh) uf.unite(it->second, i);
    }
  }
  // Grid level of a tolerance: tolerances in [8^L, 8^(L+1)) share cells of 64 · 8^(L+1).
  auto level_of = [](double t) {
    int e = 0;
    std::frexp(t, &e);  // t < 2^e
    return static_cast<int>(std::floor((e - 1) / 3.0));
  };
  auto cell_size = [](int level) { return std::ldexp(64.0, 3 * level + 3); };
  auto cell_of = [&](const glm::dvec3& q, int level) {
    const glm::dvec3 c = (q - low) / cell_size(level);
    return std::array<std::int64_t, 4>{level, grid_coordinate(c.x), grid_coordinate(c.y),
                                       grid_coordinate(c.z)};
  };
  // Cell → first point, then a linked list through `next`: no allocation per cell.
  std::unordered_map<std::array<std::int64_t, 4>, std::uint32_t, cell_hash> cells;
  cells.reserve(order.size());
  std::vector<std::uint32_t> next(n, no_index);
  std::vector<int> levels;
  for (const std::uint32_t i : order) {
    if (!(tol[i] > 0.0) || !std::isfinite(tol[i])) continue;
    const int level = level_of(tol[i]);
    levels.push_back(level);
    const auto [it, fresh] = cells.emplace(cell_of(p[i], level), i);
    if (!fresh) {
      next[i] = it->second;
      it->second = i;
    }
  }
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  for (const std::uint32_t i : order) {
    const double t = tol[i];
    if (!(t > 0.0) || !std::isfinite(t)) continue;
    for (auto l = std::lower_bound(levels.begin(), levels.end(), level_of(t)); l != levels.end(); ++l) {
      // Only the cells the ball of radius t about p[i] reaches: almost always one.
      const auto lo = cell_of(p[i] - t, *l), hi = cell_of(p[i] + t, *l);
      for (std::int64_t x = lo[1]; x <= hi[1]; ++x)
        for (std::int64_t y = lo[2]; y <= hi[2]; ++y)
          for (std::int64_t z = lo[3]; z <= hi[3]; ++z) {
            budget.spend();
            const auto it = cells.find({*l, x, y, z});
            if (it == cells.end()) continue;
            for (std::uint32_t j = it->second; j != no_index; j = next[j]) {
              budget.spend();
              if (j != i && glm::length(p[i] - p[j]) <= std::min(t, tol[j])) uf.unite(i, j);
            }
          }
    }
  }
  std::vector<std::uint32_t> rep(n);
  for (std::uint32_t i = 0; i < n; ++i) rep[i] = uf.find(i);
  return rep;
}

/// Each point's local length: the median length of the non-zero edges at it (the longer middle
/// one of an even count), 0 for a point on no such edge. O(E log deg).
template <class = void>
std::vector<double> local_lengths(const std::vector<glm::dvec3>& p,
                                  const std::vector<std::array<std::uint32_t, 2>>& ends) {
  std::vector<std::uint32_t> start(p.size() + 1, 0);
  for (const auto& [a, b] : ends)
    if (a != b) ++start[a + 1], ++start[b + 1];
  for (std::size_t v = 0; v < p.size(); ++v) start[v + 1] += start[v];
  std::vector<double> len(start.back());
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (const auto& [a, b] : ends)
      if (a != b) {
        const double l = glm::length(p[b] - p[a]);
        len[fill[a]++] = l;
        len[fill[b]++] = l;
      }
  }
  std::vector<double> out(p.size(), 0.0);
  for (std::size_t v = 0; v < p.size(); ++v) {
    const auto begin = len.begin() + start[v], end = len.begin() + start[v + 1];
    if (begin == end) continue;
    const auto mid = begin + (end - begin) / 2;
    std::nth_element(begin, mid, end);
    out[v] = *mid;
  }
  return out;
}

/// Splits edges at vertices lying strictly inside them, within the smaller of the vertex's
/// tolerance `tol[v]` and `relative` times the edge's length: a grid of cells about the
/// median edge length holds the vertices; each edge visits the cells along it. Pieces are
/// appended in order along the edge and keep their edge's origin. Returns the number of splits.
/// Vertices are visited in `order` (a spatial order keeps the cell look-ups in cache; the
/// result does not depend on it). O(E + V + vertices in the visited cells), spent from `budget`.
template <class = void>
std::size_t split_at_vertices(const std::vector<glm::dvec3>& p, const std::vector<char>& is_vertex,
                              const std::vector<std::uint32_t>& order,
                              std::vector<std::array<std::uint32_t, 2>>& ends,
                              std::vector<std::uint32_t>& origin, const std::vector<double>& tol,
                              double relative, work_counter& budget) {
  // The search runs on the points of `order` copied in that order and on edges relabelled by
  // rank (a point's place in it): near points near in memory whatever the caller's numbering.
  const std::size_t n = ends.size(), m = order.size();
  std::vector<std::uint32_t> rank(p.size(), 0);
  for (std::uint32_t i = 0; i < m; ++i) rank[order[i]] = i;
  std::vector<glm::dvec3> q(m);
  for (std::uint32_t i = 0; i < m; ++i) q[i] = p[order[i]];
  std::vector<std::array<std::uint32_t, 2>> by_rank(n);  // ends by rank
  for (std::uint32_t e = 0; e < n; ++e) by_rank[e] = {rank[ends[e][0]], rank[ends[e][1]]};
  // Edges visited in the order of their first ends (a counting sort by rank, stable in edge
  // order); the splits are applied afterwards in edge order, so the pieces are numbered as if
  // visited in edge order.
  std::vector<std::uint32_t> rank_start(m + 1, 0), visit_order(n);
  for (std::uint32_t e = 0; e < n; ++e) ++rank_start[by_rank[e][0] + 1];
  for (std::size_t i = 0; i < m; ++i) rank_start[i + 1] += rank_start[i];
  for (std::uint32_t e = 0; e < n; ++e) visit_order[rank_start[by_rank[e][0]]++] = e;

  std::vector<double> lengths;
  double total_length = 0.0;
  glm::dvec3 low(std::numeric_limits<double>::infinity());
  for (const std::uint32_t e : visit_order)
    if (by_rank[e][0] != by_rank[e][1]) {
      lengths.push_back(glm::length(q[by_rank[e][1]] - q[by_rank[e][0]]));
      total_length += lengths.back();
      low = glm::min(low, glm::min(q[by_rank[e][0]], q[by_rank[e][1]]));
    }
  if (lengths.empty()) return 0;
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2),
                   lengths.end());
  // The median edge length, but never so small that walking all edges visits more than about
  // 4 cells per edge or vertex: a few long edges beside many tiny ones stay linear.
  const double work_cap = total_length / (4.0 * static_cast<double>(ends.size() + p.size()));
  double h = std::max({lengths[lengths.size() / 2], 4.0 * relative * lengths[lengths.size() / 2], work_cap});
  if (!(h > 0.0) || !std::isfinite(h)) h = 1.0;
  // Cells centred on low + k·h: vertices of a lattice of that pitch (grids, CAD models) lie in
  // the middle of cells, not on their walls, and a short edge's box covers 2 cells, not 12.
  auto cell_of = [&](const glm::dvec3& x) {
    const glm::dvec3 c = (x - low) / h + 0.5;
    return std::array<std::int64_t, 3>{grid_coordinate(c.x), grid_coordinate(c.y), grid_coordinate(c.z)};
  };
  std::unordered_map<std::array<std::int64_t, 3>, std::uint32_t, cell_hash> cells;
  std::vector<std::uint32_t> next(m, no_index);  // by rank
  for (std::uint32_t v = 0; v < m; ++v) {
    if (!is_vertex[order[v]]) continue;
    const auto [it, fresh] = cells.emplace(cell_of(q[v]), v);
    if (!fresh) {
      next[v] = it->second;
      it->second = v;
    }
  }
  std::size_t splits = 0;
  std::vector<std::pair<double, std::uint32_t>> inside;  // (t, the caller's label)
  std::vector<std::uint32_t> seen_stamp(m, no_index);
  std::vector<std::pair<std::uint32_t, std::vector<std::uint32_t>>> found;  // edge, vertices inside along it
  for (const std::uint32_t e : visit_order) {
    const std::uint32_t a = by_rank[e][0], b = by_rank[e][1];
    if (a == b) continue;
    const glm::dvec3 pa = q[a], d = q[b] - pa;
    const double len = glm::length(d), edge_tol = relative * len;
    inside.clear();
    auto visit = [&](const std::array<std::int64_t, 3>& c) {
      budget.spend();
      const auto it = cells.find(c);
      if (it == cells.end()) return;
      for (std::uint32_t v = it->second; v != no_index; v = next[v]) {
        budget.spend();
        if (v == a || v == b || seen_stamp[v] == e) continue;
        seen_stamp[v] = static_cast<std::uint32_t>(e);
        const double t = glm::dot(q[v] - pa, d) / (len * len);
        const double within = std::min(edge_tol, tol[order[v]]);
        if (t * len <= within || (1.0 - t) * len <= within) continue;
        if (glm::length(pa + t * d - q[v]) <= within) inside.emplace_back(t, order[v]);
      }
    };
    const auto lo = cell_of(glm::min(pa, q[b]) - edge_tol), hi = cell_of(glm::max(pa, q[b]) + edge_tol);
    // In double: clamped coordinates would overflow an integer product.
    const double box_cells = (static_cast<double>(hi[0] - lo[0]) + 1) *
                             (static_cast<double>(hi[1] - lo[1]) + 1) *
                             (static_cast<double>(hi[2] - lo[2]) + 1);
    if (box_cells <= 64) {
      // Short edges (the usual case): the few cells of the edge's box.
      for (auto x = lo[0]; x <= hi[0]; ++x)
        for (auto y = lo[1]; y <= hi[1]; ++y)
          for (auto z = lo[2]; z <= hi[2]; ++z) visit({x, y, z});
    } else {
      // Long edges: sample every half cell and look at the 27 cells around each sample.
      // (Capped so that an edge of overflowing length cannot make the cast undefined; the
      // budget ends such walks long before.)
      const auto steps = static_cast<std::size_t>(std::min(std::ceil(2.0 * len / h), 1e15));
      for (std::size_t s = 0; s <= steps; ++s) {
        const auto c = cell_of(pa + d * (static_cast<double>(s) / static_cast<double>(steps)));
        for (std::int64_t dx = -1; dx <= 1; ++dx)
          for (std::int64_t dy = -1; dy <= 1; ++dy)
            for (std::int64_t dz = -1; dz <= 1; ++dz) visit({c[0] + dx, c[1] + dy, c[2] + dz});
      }
    }
    if (inside.empty()) continue;
    std::sort(inside.begin(), inside.end());
    splits += inside.size();
    found.emplace_back(e, std::vector<std::uint32_t>(inside.size()));
    for (std::size_t k = 0; k < inside.size(); ++k) found.back().second[k] = inside[k].second;
  }
  std::sort(found.begin(), found.end());
  for (const auto& [e, at] : found) {
    const std::uint32_t a = ends[e][0], b = ends[e][1];
    ends[e] = {a, at[0]};
    std::uint32_t from = at[0];
    for (std::size_t k = 1; k < at.size(); ++k) {
      ends.push_back({from, at[k]});
      origin.push_back(origin[e]);
      from = at[k];
    }
    ends.push_back({from, b});
    origin.push_back(origin[e]);
  }
  return splits;
}

}  // namespace detail

/// Reads any Wireframe into the labelled graph: checks coordinates and indices, merges close
/// points, drops (or rejects) zero-length, duplicate and dangling edges; out of work budget, an
/// empty graph with complete false and a diagnostic naming the option. O(V + E) expected.
template <Wireframe G>
wireframe_read_result read_vertices(const G& wire, const wireframe_read_options& options = {}) {
  using T = wireframe_traits<G>;
  detail::stopwatch clock;
  wireframe_read_result r;
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
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("read_vertices: vertex ", std::to_string(v),
                                         " has a NaN or infinite coordinate ", detail::point_text(p[v])));
  }
  std::vector<std::array<std::uint32_t, 2>> ends(ne);
  std::vector<char> used(nv, 0);
  bounding_box box;
  for (std::size_t e = 0; e < ne; ++e) {
    const auto ab = T::endpoints(wire, e);
    if (ab[0] >= nv || ab[1] >= nv)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("read_vertices: edge ", std::to_string(e), " refers to vertex ",
                                         std::to_string(std::max(ab[0], ab[1])), " but there are only ",
                                         std::to_string(nv), " vertices"));
    ends[e] = {static_cast<std::uint32_t>(ab[0]), static_cast<std::uint32_t>(ab[1])};
    for (const auto v : ends[e]) {
      used[v] = 1;
      box.add(p[v]);
    }
  }
  {
    // Lengths, areas and volumes are products of coordinates, some tests use fourth powers (a
    // cube reads right from about 1e-80 to 1e75 units): past 1e±50 say so, not "zero length".
    const glm::dvec3 span = box.max - box.min;
    const double extent = std::max({span.x, span.y, span.z});
    const double reach = std::max({std::abs(box.min.x), std::abs(box.min.y), std::abs(box.min.z),
                                   std::abs(box.max.x), std::abs(box.max.y), std::abs(box.max.z)});
    if (!box.empty() && extent > 0.0 && (extent < 1e-50 || reach > 1e50))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat(
                      "read_vertices: the model spans ", detail::number_text(extent), " and reaches ",
                      detail::number_text(reach),
                      " from the origin; lengths, areas and volumes are computed in double, which holds "
                      "this only between 1e-50 and 1e50 units: scale the model into that range"));
  }
  options.merge.absolute(box);  // checks the option (finite, >= 0)
  detail::work_counter budget{options.work_budget, 0, "read_vertices",
                              "wireframe_read_options::work_budget (wireframe_options::read)"};
  if (box.diagonal() == 0.0)
    throw error(
        error_category::invalid_input,
        cellforge::detail::cat("read_vertices: all ", std::to_string(ne),
                               " edges have zero length (every point is ", detail::point_text(box.min), ")"));
  // The used points in Morton order (or the caller's): the merge and split searches visit
  // them so, and their hash-grid cells stay in cache whatever the caller's numbering.
  std::vector<std::uint32_t> visit;
  for (std::uint32_t v = 0; v < nv; ++v)
    if (used[v]) visit.push_back(v);
  if (options.spatial_order)  // keyed in the used points' box (`box` above)
    visit =
        detail::morton_order(std::span<const std::uint32_t>(visit), [&](std::uint32_t v) { return p[v]; });
  // Each point's tolerance: a fraction of its local edge length, so that the bounding box (a far
  // vertex, a long part) does not decide what is close for a small part.
  std::vector<double> tol = detail::local_lengths(p, ends);
  for (auto& t : tol) t *= options.merge.relative;
  // Out of budget the graph is left empty (a half-merged one is no wireframe), complete false.
  std::vector<std::uint32_t> rep;
  try {
    rep = detail::merge_close_points(p, visit, tol, budget);
  } catch (const error& e) {
    detail::stop_at_budget(r, budget, e);
    r.milliseconds = clock.ms();
    return r;
  }
  double merged_within = 0.0;  // the largest distance of a point from its representative
  for (std::size_t v = 0; v < nv; ++v)
    if (used[v] && rep[v] != v) {
      ++r.merged_points;
      const double d = glm::length(p[v] - p[rep[v]]);
      merged_within = std::max(merged_within, d);
      r.diagnostics.push_back(cellforge::detail::cat("vertex ", std::to_string(v), " lies within ",
                                                     detail::number_text(tol[v]), " of vertex ",
                                                     std::to_string(rep[v]), " and was merged into it"));
    }

  // Edges between representatives, split where another vertex lies inside them (a T-junction
  // or one edge overlapping another); every piece remembers the caller's edge.
  const std::vector<std::array<std::uint32_t, 2>> input_ends = ends;
  std::vector<std::uint32_t> origin(ne);
  for (std::uint32_t e = 0; e < ne; ++e) {
    origin[e] = e;
    ends[e] = {rep[ends[e][0]], rep[ends[e][1]]};
  }
  if (options.split_at_vertices) {
    std::vector<char> is_rep(nv, 0);
    for (std::uint32_t v = 0; v < nv; ++v) is_rep[v] = used[v] && rep[v] == v;
    std::size_t splits = 0;
    try {
      splits = detail::split_at_vertices(p, is_rep, visit, ends, origin, tol, options.merge.relative, budget);
    } catch (const error& e) {
      detail::stop_at_budget(r, budget, e);
      r.milliseconds = clock.ms();
      return r;
    }
    if (splits > 0)
      r.diagnostics.push_back(std::to_string(splits) +
                              " vertices lie inside edges (T-junctions or overlapping edges); the edges were "
                              "split there");
    r.split_edges = splits;
  }
  const auto np = static_cast<std::uint32_t>(ends.size());

  // Zero-length and duplicate pieces dropped (or rejected).
  // Duplicates found by sorting the pieces by their ends: same_as[e] is the first piece joining
  // the same two vertices (a hash table of 10^5 nodes costs more, freeing them most).
  const auto undirected = [](std::uint32_t a, std::uint32_t b) {
    return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
  };
  std::vector<std::uint32_t> same_as(np, no_index);
  {
    const std::vector<std::uint32_t> by_ends = detail::edges_by_ends(ends, nv);
    for (std::size_t i = 0; i < by_ends.size(); ++i) {
      const std::uint32_t e = by_ends[i], prev = i > 0 ? by_ends[i - 1] : no_index;
      same_as[e] =
          prev != no_index && undirected(ends[prev][0], ends[prev][1]) == undirected(ends[e][0], ends[e][1])
              ? same_as[prev]
              : e;
    }
  }
  std::vector<std::uint32_t> kept;
  // The first few of each kind are named; the rest are counted (10^5 duplicates are one line).
  constexpr std::size_t named_per_kind = 8;
  auto complain = [&](std::size_t count_so_far, auto&& what) {
    if (options.strict)
      throw error(error_category::invalid_input, cellforge::detail::cat("read_vertices: ", what()));
    if (count_so_far <= named_per_kind) r.diagnostics.push_back(what());
  };
  for (std::uint32_t e = 0; e < np; ++e) {
    const std::uint32_t a = ends[e][0], b = ends[e][1], o = origin[e];
    if (a == b) {
      complain(++r.zero_length_edges, [&] {
        return cellforge::detail::cat(
            "edge ", std::to_string(o), " has zero length (its ends ", std::to_string(input_ends[o][0]),
            " and ", std::to_string(input_ends[o][1]), " are the same point) and was dropped");
      });
      continue;
    }
    if (same_as[e] != e) {
      const std::uint32_t first = origin[same_as[e]];
      complain(++r.duplicate_edges, [&] {
        return cellforge::detail::cat("edge ", std::to_string(o), " duplicates edge ", std::to_string(first),
                                      " (vertices ", std::to_string(a), "-", std::to_string(b),
                                      ") and was dropped");
      });
      continue;
    }
    kept.push_back(e);
  }
  if (r.zero_length_edges > named_per_kind)
    r.diagnostics.push_back(cellforge::detail::cat(
        "... ", std::to_string(r.zero_length_edges - named_per_kind), " more zero-length edges dropped (",
        std::to_string(r.zero_length_edges), " in all)"));
  if (r.duplicate_edges > named_per_kind)
    r.diagnostics.push_back(cellforge::detail::cat("... ", std::to_string(r.duplicate_edges - named_per_kind),
                                                   " more duplicate edges dropped (",
                                                   std::to_string(r.duplicate_edges), " in all)"));

  // Dangling edges: repeatedly strip vertices of degree 1, since no circuit passes through them.
  std::vector<char> alive(np, 0);
  for (const auto e : kept) alive[e] = 1;
  if (options.prune_dangling) {
    // Vertex → kept edges, one flat array in edge order.
    std::vector<std::uint32_t> start(nv + 1, 0);
    for (const auto e : kept)
      for (const auto v : ends[e]) ++start[v + 1];
    for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
    std::vector<std::uint32_t> inc(start.back()), deg(nv);
    for (std::size_t v = 0; v < nv; ++v) deg[v] = start[v + 1] - start[v];
    {
      std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
      for (const auto e : kept)
        for (const auto v : ends[e]) inc[fill[v]++] = e;
    }
    std::vector<std::uint32_t> stack;
    for (std::uint32_t v = 0; v < nv; ++v)
      if (deg[v] == 1) stack.push_back(v);
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      if (deg[v] != 1) continue;
      for (std::uint32_t k = start[v]; k < start[v + 1]; ++k) {
        const std::uint32_t e = inc[k];
        if (!alive[e]) continue;
        alive[e] = 0;
        r.dangling.push_back(origin[e]);
        const std::uint32_t w = ends[e][0] == v ? ends[e][1] : ends[e][0];
        --deg[v];
        if (--deg[w] == 1) stack.push_back(w);
      }
    }
    std::sort(r.dangling.begin(), r.dangling.end());
    r.dangling.erase(std::unique(r.dangling.begin(), r.dangling.end()), r.dangling.end());
    std::size_t named = 0;
    for (const auto e : r.dangling)
      complain(++named, [&] {
        return cellforge::detail::cat("edge ", std::to_string(e),
                                      " is dangling (it lies on no circuit) and was removed");
      });
    if (named > named_per_kind)
      r.diagnostics.push_back(cellforge::detail::cat("... ", std::to_string(named - named_per_kind),
                                                     " more dangling edges removed (", std::to_string(named),
                                                     " in all)"));
  }

  // Label the remaining vertices: in space-filling-curve order (spatial_order), so that the
  // stages' walks over neighbouring vertices, edges and faces stay in cache whatever order the
  // caller numbered them in, or in the caller's order. Results are mapped back to the
  // caller's labels and edge order (input_vertex, input_edge, read_order).
  wire_graph& g = r.graph;
  std::vector<std::uint32_t> label(nv, no_index);
  for (std::uint32_t e = 0; e < np; ++e)
    if (alive[e])
      for (const auto v : ends[e]) label[v] = 0;
  bounding_box kept_box;
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (label[v] != no_index)
      kept_box.add(p[v]);
    else if (used[v] && rep[v] == v)
      ++r.isolated_vertices;
  }
  // `visit` is in Morton order when spatial_order, else in the caller's.
  for (const std::uint32_t v : visit)
    if (label[v] != no_index) g.input_vertex.push_back(v);
  g.points.reserve(g.input_vertex.size());
  for (const auto v : g.input_vertex) {
    label[v] = static_cast<std::uint32_t>(g.points.size());
    g.points.push_back(p[v]);
  }
  for (std::uint32_t e = 0; e < np; ++e)
    if (alive[e]) {
      g.edges.push_back({label[ends[e][0]], label[ends[e][1]]});
      g.input_edge.push_back(origin[e]);
    }
  if (options.spatial_order) {
    // Edges by their ends' labels (smaller end first): a vertex's edges are then listed by
    // neighbour, and edges near in space are near in memory.
    const auto ne_kept = static_cast<std::uint32_t>(g.edges.size());
    g.read_order = detail::edges_by_ends(g.edges, g.points.size());
    std::vector<std::array<std::uint32_t, 2>> edges(ne_kept);
    std::vector<std::uint32_t> input_edge(ne_kept);
    for (std::uint32_t i = 0; i < ne_kept; ++i) {
      edges[i] = g.edges[g.read_order[i]];
      input_edge[i] = g.input_edge[g.read_order[i]];
    }
    g.edges = std::move(edges);
    g.input_edge = std::move(input_edge);
  }
  if (g.edges.empty())
    throw error(error_category::topology,
                cellforge::detail::cat("read_vertices: no edge lies on a circuit (the ", std::to_string(ne),
                                       " edges form trees), so the wireframe bounds no face"));
  g.size = kept_box.diagonal();
  g.center = kept_box.center();
  g.merge_tolerance = merged_within;
  g.link();
  r.work = budget.used;
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
