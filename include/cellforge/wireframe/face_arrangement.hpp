// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 5 of the wireframe pipeline (seed 000 §4.5): smooth entity chains (straight runs of
/// edges through degree-2 vertices), the Shpitalni–Lipson maximum ranks of edges and vertices,
/// and the face selection. Selection rule (documented in docs/wireframe.md): keep every usable
/// candidate whose interior crosses the interior of no other usable candidate. Candidate pairs
/// come from a uniform grid over face bounding boxes, so the cost is not all-pairs.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/tolerance.hpp"
#include "cellforge/wireframe/face_reduction.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// Options of arrange_faces.
struct arrangement_options {
  tolerance planarity{1e-9};   ///< distances under this (relative to model size) count as zero
  bool drop_crossing = true;   ///< the selection rule; false keeps every usable candidate
  bool enforce_ranks = false;  ///< seed: drop the largest face at an edge exceeding its maximum rank
  std::uint64_t work_budget = 500'000'000;
};

/// The selection and the rank analysis.
struct arrangement_result : stage_report {
  std::vector<std::uint32_t> selected;                  ///< indices of kept candidates, increasing
  std::vector<std::array<std::uint32_t, 2>> crossings;  ///< pairs of candidates whose interiors cross
  std::vector<std::uint32_t> chain_of_edge;             ///< smooth entity chain id of each edge
  std::size_t chains = 0;                               ///< chains with more than one edge
  std::vector<std::uint32_t> edge_rank;                 ///< maximum rank R(e) of each edge
  std::vector<std::uint32_t> vertex_rank;               ///< maximum rank R(v) of each vertex
  std::size_t rank_violations = 0;                      ///< edges with more selected faces than R(e)
  std::uint64_t pairs_tested = 0;
  std::size_t hole_fillers_dropped = 0;  ///< candidates filling a hole loop that no edge needs
};

namespace detail {

struct face_plane {
  glm::dvec3 n{0.0}, o{0.0};
  bounding_box box;
};

/// Positions along `dir` where the interior of face f meets the plane p (pairs of
/// entry/exit). Vertices within tol of the plane count as on its positive side.
inline std::vector<double> cut_intervals(const wire_graph& g, const wire_face& f, const face_plane& p,
                                         const glm::dvec3& dir, double tol) {
  std::vector<double> s;
  for (const auto& loop : f.loops)
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const glm::dvec3 x = g.points[loop[k]], y = g.points[loop[(k + 1) % loop.size()]];
      const double dx = glm::dot(p.n, x - p.o), dy = glm::dot(p.n, y - p.o);
      if ((dx < -tol) == (dy < -tol)) continue;
      const double t = std::clamp(dx / (dx - dy), 0.0, 1.0);
      s.push_back(glm::dot(x + t * (y - x) - p.o, dir));
    }
  std::sort(s.begin(), s.end());
  return s;
}

/// -1, 0, +1 for the vertices of f relative to plane p: whether some lie beyond tol each side.
inline std::array<bool, 2> straddles(const wire_graph& g, const wire_face& f, const face_plane& p,
                                     double tol) {
  std::array<bool, 2> side{false, false};
  for (const auto& loop : f.loops)
    for (const auto v : loop) {
      const double d = glm::dot(p.n, g.points[v] - p.o);
      if (d > tol) side[0] = true;
      if (d < -tol) side[1] = true;
    }
  return side;
}

/// True when the interiors of faces a and b (in different planes) share a segment longer than tol.
inline bool faces_cross(const wire_graph& g, const wire_face& a, const face_plane& pa, const wire_face& b,
                        const face_plane& pb, double tol) {
  glm::dvec3 dir = glm::cross(pa.n, pb.n);
  const double l = glm::length(dir);
  if (l < 1e-12) return false;  // parallel planes: coplanar faces never overlap after tracing
  const auto sa = straddles(g, a, pb, tol);
  if (!sa[0] || !sa[1]) return false;
  const auto sb = straddles(g, b, pa, tol);
  if (!sb[0] || !sb[1]) return false;
  dir /= l;
  const auto ia = cut_intervals(g, a, pb, dir, tol);
  auto ib = cut_intervals(g, b, pa, dir, tol);
  // ia is measured from pb.o, ib from pa.o: move ib to pb.o.
  const double shift = glm::dot(pa.o - pb.o, dir);
  for (auto& x : ib) x += shift;
  for (std::size_t i = 0; i + 1 < ia.size(); i += 2)
    for (std::size_t j = 0; j + 1 < ib.size(); j += 2) {
      const double lo = std::max(ia[i], ib[j]), hi = std::min(ia[i + 1], ib[j + 1]);
      if (hi - lo > tol) return true;
    }
  return false;
}

}  // namespace detail

/// Finds chains and ranks and selects the faces (see the file comment for the rule).
/// O(V + E + F·L + P·L) where P is the number of face pairs sharing a grid cell.
inline arrangement_result arrange_faces(const wire_graph& g, const std::vector<wire_face>& faces,
                                        const reduction_result& reduction,
                                        const arrangement_options& options = {}) {
  detail::stopwatch clock;
  arrangement_result r;
  const double tol = options.planarity.relative * g.size;
  const std::size_t nv = g.num_vertices(), ne = g.num_edges();

  // Smooth entity chains: join the two edges at a degree-2 vertex when they run straight on.
  detail::union_find chain(ne);
  std::vector<char> inner(nv, 0);
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (g.degree(v) != 2) continue;
    const auto in = g.around(v);
    const glm::dvec3 a = g.points[in[0].other] - g.points[v], b = g.points[in[1].other] - g.points[v];
    if (glm::length(glm::cross(a, b)) <= tol * std::max(glm::length(a), glm::length(b)) &&
        glm::dot(a, b) < 0.0) {
      chain.unite(in[0].edge, in[1].edge);
      inner[v] = 1;
    }
  }
  r.chain_of_edge.resize(ne);
  std::vector<std::uint32_t> chain_size(ne, 0);
  for (std::uint32_t e = 0; e < ne; ++e) ++chain_size[r.chain_of_edge[e] = chain.find(e)];
  for (std::uint32_t e = 0; e < ne; ++e) r.chains += chain_size[e] > 1;
  // A chain's two ends: the endpoints of its edges that are not inner vertices.
  std::vector<std::array<std::uint32_t, 2>> ends(ne, {no_index, no_index});
  for (std::uint32_t e = 0; e < ne; ++e)
    for (const auto v : g.edges[e]) {
      if (inner[v]) continue;
      auto& en = ends[r.chain_of_edge[e]];
      (en[0] == no_index ? en[0] : en[1]) = v;
    }
  // Shpitalni–Lipson: R(e) <= min(d(v1), d(v2)) - 1, with a chain's ends standing in for
  // the inner degree-2 vertices (the seed's chain form of the bound); R(v) <= d(d - 1) / 2.
  r.edge_rank.resize(ne);
  for (std::uint32_t e = 0; e < ne; ++e) {
    const auto en = ends[r.chain_of_edge[e]];
    if (en[0] == no_index || en[1] == no_index) {
      r.edge_rank[e] = 1;  // a closed straight chain cannot happen; be safe
      continue;
    }
    const auto d = static_cast<std::uint32_t>(std::min(g.degree(en[0]), g.degree(en[1])));
    r.edge_rank[e] = d > 0 ? d - 1 : 0;
  }
  r.vertex_rank.resize(nv);
  for (std::uint32_t v = 0; v < nv; ++v) {
    const auto d = static_cast<std::uint32_t>(g.degree(v));
    r.vertex_rank[v] = inner[v] ? r.edge_rank[g.around(v)[0].edge] : d * (d - 1) / 2;
  }

  // Planes and boxes of the usable candidates.
  std::vector<std::uint32_t> usable;
  std::vector<detail::face_plane> plane(faces.size());
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    if (!reduction.quality[i].usable) continue;
    usable.push_back(i);
    plane[i].n = faces[i].normal;
    plane[i].o = g.points[faces[i].loops[0][0]];
    for (const auto v : faces[i].loops[0]) plane[i].box.add(g.points[v]);
  }
  std::vector<char> crossed(faces.size(), 0);
  detail::work_budget budget{options.work_budget, 0, "arrange_faces"};
  if (options.drop_crossing && usable.size() > 1) {
    // Uniform grid with cells about the median face size; a pair is tested in the one cell
    // holding the low corner of the intersection of their boxes.
    std::vector<double> extent;
    for (const auto i : usable) {
      const glm::dvec3 d = plane[i].box.max - plane[i].box.min;
      extent.push_back(std::max({d.x, d.y, d.z}));
    }
    std::nth_element(extent.begin(), extent.begin() + static_cast<std::ptrdiff_t>(extent.size() / 2),
                     extent.end());
    // Cells twice the median face size, the lattice shifted off round numbers so that faces of
    // axis-aligned models do not all end on cell boundaries: about two cells per face.
    const double h = 2.0 * std::max(extent[extent.size() / 2], g.size * 1e-6);
    auto cell = [&](const glm::dvec3& p) {
      return std::array<std::int64_t, 3>{
          static_cast<std::int64_t>(std::floor((p.x - g.center.x) / h + 0.3719)),
          static_cast<std::int64_t>(std::floor((p.y - g.center.y) / h + 0.2917)),
          static_cast<std::int64_t>(std::floor((p.z - g.center.z) / h + 0.1343))};
    };
    std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::uint32_t>, detail::cell_hash> grid;
    std::vector<std::uint32_t> big;
    for (const auto i : usable) {
      const auto lo = cell(plane[i].box.min - tol), hi = cell(plane[i].box.max + tol);
      const std::int64_t count = (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
      if (count > 512) {
        big.push_back(i);
        continue;
      }
      for (auto x = lo[0]; x <= hi[0]; ++x)
        for (auto y = lo[1]; y <= hi[1]; ++y)
          for (auto z = lo[2]; z <= hi[2]; ++z) grid[{x, y, z}].push_back(i);
    }
    auto boxes_meet = [&](std::uint32_t a, std::uint32_t b) {
      const auto &A = plane[a].box, &B = plane[b].box;
      for (int k = 0; k < 3; ++k)
        if (A.min[k] > B.max[k] + tol || B.min[k] > A.max[k] + tol) return false;
      return true;
    };
    auto test = [&](std::uint32_t a, std::uint32_t b) {
      ++r.pairs_tested;
      budget.spend(faces[a].loops[0].size() + faces[b].loops[0].size());
      if (!detail::faces_cross(g, faces[a], plane[a], faces[b], plane[b], tol)) return;
      crossed[a] = crossed[b] = 1;
      r.crossings.push_back({std::min(a, b), std::max(a, b)});
    };
    for (const auto& [c, list] : grid)
      for (std::size_t x = 0; x < list.size(); ++x)
        for (std::size_t y = x + 1; y < list.size(); ++y) {
          const std::uint32_t a = list[x], b = list[y];
          if (!boxes_meet(a, b)) continue;
          if (cell(glm::max(plane[a].box.min, plane[b].box.min) - tol) != c) continue;
          test(a, b);
        }
    std::vector<char> is_big(faces.size(), 0);
    for (const auto b : big) is_big[b] = 1;
    for (const auto b : big)
      for (const auto i : usable)
        if (i != b && (!is_big[i] || i > b) && boxes_meet(b, i)) test(b, i);
    std::sort(r.crossings.begin(), r.crossings.end());
    for (const auto& [a, b] : r.crossings)
      r.diagnostics.push_back("candidates " + std::to_string(a) + " and " + std::to_string(b) +
                              " cross each other; neither is a face");
  }
  for (const auto i : usable)
    if (!crossed[i]) r.selected.push_back(i);

  // Hole rule: faces filling a hole loop are kept only when some edge needs them, i.e. when,
  // without the hole fillers, an edge of theirs has fewer than two other faces or just two
  // coplanar ones (then the filler is an imprint on a flat face, not the mouth of a hole).
  {
    std::vector<std::vector<std::uint32_t>> others(ne);
    for (const auto i : r.selected)
      if (!faces[i].fills_hole)
        for (const auto& loop : faces[i].loops)
          for (std::size_t k = 0; k < loop.size(); ++k)
            others[g.find_edge(loop[k], loop[(k + 1) % loop.size()])].push_back(i);
    std::erase_if(r.selected, [&](std::uint32_t i) {
      if (!faces[i].fills_hole) return false;
      for (const auto& loop : faces[i].loops)
        for (std::size_t k = 0; k < loop.size(); ++k) {
          const auto& o = others[g.find_edge(loop[k], loop[(k + 1) % loop.size()])];
          if (o.size() < 2) return false;
          if (o.size() == 2 && glm::length(glm::cross(faces[o[0]].normal, faces[o[1]].normal)) < 1e-9)
            return false;
        }
      ++r.hole_fillers_dropped;
      r.diagnostics.push_back("candidate " + std::to_string(i) +
                              " fills a hole that no edge needs closed; dropped");
      return true;
    });
  }

  // Rank check: more selected faces at an edge than its maximum rank.
  std::vector<std::vector<std::uint32_t>> at_edge(ne);
  for (const auto i : r.selected)
    for (const auto& loop : faces[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k)
        at_edge[g.find_edge(loop[k], loop[(k + 1) % loop.size()])].push_back(i);
  std::vector<char> removed(faces.size(), 0);
  for (std::uint32_t e = 0; e < ne; ++e) {
    if (at_edge[e].size() <= r.edge_rank[e]) continue;
    ++r.rank_violations;
    r.diagnostics.push_back("edge " + std::to_string(e) + " has " + std::to_string(at_edge[e].size()) +
                            " faces, more than its maximum rank " + std::to_string(r.edge_rank[e]));
    if (options.enforce_ranks) {
      std::uint32_t largest = at_edge[e][0];
      for (const auto i : at_edge[e])
        if (faces[i].area > faces[largest].area) largest = i;
      removed[largest] = 1;
    }
  }
  if (options.enforce_ranks) std::erase_if(r.selected, [&](std::uint32_t i) { return removed[i] != 0; });
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
