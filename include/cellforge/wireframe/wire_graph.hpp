// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The data the stages of the wireframe → cell complex pipeline hand each other: the
/// labelled graph of seed 000 §4.1 (vertices with incident edges and their direction),
/// candidate faces as vertex loops, and the timing/diagnostics every stage reports.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/union_find.hpp"
#include "cellforge/core/detail/work_counter.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/stage_report.hpp"

namespace cellforge {

/// "No such element" for 32-bit indices.
inline constexpr std::uint32_t no_index = 0xffffffffu;

/// One edge as seen from one of its vertices (seed 000 §4.1, fig. 9: "+L1, -L2").
struct wire_incidence {
  std::uint32_t edge = 0;   ///< edge index
  std::uint32_t other = 0;  ///< the vertex at the edge's other end
  bool outgoing = false;    ///< true when the edge starts at this vertex
};

template <class = void>
struct basic_wire_graph;
using wire_graph = basic_wire_graph<>;

/// The labelled wireframe after reading: merged points, checked edges, vertex→edge incidence.
template <class>
struct basic_wire_graph {
  std::vector<glm::dvec3> points;           ///< vertex positions
  std::vector<std::uint32_t> input_vertex;  ///< vertex → index of the caller's (representative) point
  std::vector<std::array<std::uint32_t, 2>> edges;  ///< (start, end)
  std::vector<std::uint32_t> input_edge;            ///< edge → index of the caller's edge
  /// edge → its place in the caller's order (pieces of split edges after the caller's edges):
  /// the order results list edges in, whatever the graph's own numbering. Empty: identity.
  std::vector<std::uint32_t> read_order;
  std::vector<std::uint32_t> first;        ///< CSR offsets into `incidences`, size V + 1
  std::vector<wire_incidence> incidences;  ///< per vertex, its incident edges
  double size = 0.0;                       ///< bounding-box diagonal: the model's length scale
  double merge_tolerance = 0.0;            ///< largest distance of a merged point from its vertex (0: none)
  glm::dvec3 center{0.0};                  ///< bounding-box centre (sums are taken about it)

  std::size_t num_vertices() const noexcept { return points.size(); }
  std::size_t num_edges() const noexcept { return edges.size(); }
  std::size_t degree(std::uint32_t v) const noexcept { return first[v + 1] - first[v]; }
  /// The incidences of vertex v. O(1).
  std::span<const wire_incidence> around(std::uint32_t v) const noexcept {
    return {incidences.data() + first[v], incidences.data() + first[v + 1]};
  }
  /// The edge joining a and b, or no_index: a scan of a's neighbours sorted by label (binary
  /// search past 16). O(log deg a); flat, so it costs one or two cache lines when the
  /// vertices are numbered spatially (wireframe_read_options::spatial_order).
  std::uint32_t find_edge(std::uint32_t a, std::uint32_t b) const noexcept {
    if (a >= points.size()) return no_index;
    const neighbour* lo = neighbours_.data() + first[a];
    const neighbour* hi = neighbours_.data() + first[a + 1];
    if (hi - lo > 16)
      lo = std::lower_bound(lo, hi, b, [](const neighbour& n, std::uint32_t x) { return n.other < x; });
    for (; lo != hi && lo->other <= b; ++lo)
      if (lo->other == b) return lo->edge;
    return no_index;
  }
  /// Rebuilds incidences and the edge look-up from `points` and `edges`. O(V + E + Σ deg log deg).
  void link() {
    const std::size_t nv = points.size();
    first.assign(nv + 1, 0);
    for (const auto& e : edges) {
      ++first[e[0] + 1];
      ++first[e[1] + 1];
    }
    for (std::size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
    incidences.assign(first.back(), {});
    neighbours_.assign(first.back(), {});
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
    for (std::uint32_t i = 0; i < edges.size(); ++i) {
      const auto [a, b] = edges[i];
      neighbours_[fill[a]] = {b, i};
      incidences[fill[a]++] = {i, b, true};
      neighbours_[fill[b]] = {a, i};
      incidences[fill[b]++] = {i, a, false};
    }
    // Already sorted when the edges are sorted by their ends (read_vertices' spatial order).
    for (std::size_t v = 0; v < nv; ++v) {
      const auto begin = neighbours_.begin() + first[v], end = neighbours_.begin() + first[v + 1];
      if (!std::is_sorted(begin, end, by_other)) std::sort(begin, end, by_other);
    }
  }

 private:
  struct neighbour {
    std::uint32_t other, edge;
  };
  static bool by_other(const neighbour& x, const neighbour& y) noexcept {
    return x.other < y.other || (x.other == y.other && x.edge < y.edge);
  }
  // Per vertex (offsets `first`), its neighbours sorted by label: the flat edge look-up the
  // stages use in their inner loops (a hash table costs a cache miss per look-up).
  std::vector<neighbour> neighbours_;
};

/// A (candidate) face: planar vertex loops. loops[0] is the outer boundary, counter-clockwise
/// about `normal`; loops[1..] are holes, clockwise about it.
struct wire_face {
  std::vector<std::vector<std::uint32_t>> loops;
  glm::dvec3 normal{0.0};  ///< unit normal, right-hand about loops[0]
  double area = 0.0;       ///< area (outer minus holes)
  /// Planar tracer: a bounded face of loops nested, as a hole, inside another face of the same
  /// plane (the top of a frame's hole); whether it is a face the reading rule decides.
  bool fills_hole = false;
  /// Planar tracer: how many faces of the same plane, not joined to this one by edges,
  /// enclose it. Even-odd, as nested outlines are read: at odd depth a face fills a hole (the
  /// mouth of a frame's hole), at even depth it is an island (a box top inside that mouth).
  std::uint32_t depth = 0;
};

/// A face a stage had and removed, and why (for the result's diagnostics: nothing is lost silently).
struct dropped_face {
  wire_face face;
  std::string reason;
  bool free_edge = false;  ///< removed only because an edge of it has no other face (it bounds no volume)
};

/// The area vector (Newell) of a face: normal × area, right-hand about loops[0]. O(size).
template <class = void>
glm::dvec3 area_vector(const wire_graph& g, const wire_face& f) {
  glm::dvec3 s(0.0);
  // Sums about one vertex of the face keep the rounding relative to the face, not the origin.
  const glm::dvec3 o = g.points[f.loops[0][0]];
  for (const auto& loop : f.loops)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const glm::dvec3 a = g.points[loop[i]] - o, b = g.points[loop[(i + 1) % loop.size()]] - o;
      s += glm::cross(a, b);
    }
  return 0.5 * s;
}

/// Sets f.normal and f.area from its loops. O(size).
template <class = void>
void update_normal(const wire_graph& g, wire_face& f) {
  const glm::dvec3 a = area_vector(g, f);
  f.area = glm::length(a);
  f.normal = f.area > 0.0 ? a / f.area : glm::dvec3(0.0);
}

/// Rotates a vertex cycle to the seed's canonical order (§4.3): start at the smallest label and
/// go on towards its smaller neighbour. Returns true when the cycle was reversed. O(n).
/// (detail::canonical_cycle, core/detail/geometry.hpp, returns a canonical copy.)
template <class = void>
bool canonical_cycle(std::vector<std::uint32_t>& c) {
  return detail::make_canonical_cycle(c);
}

/// Canonical orientation of a face: its outer loop in canonical order (the normal follows
/// it), holes rotated to their smallest label and kept clockwise about that normal. O(size).
template <class = void>
void canonicalize(wire_face& f) {
  if (canonical_cycle(f.loops[0])) {
    f.normal = -f.normal;
    for (std::size_t h = 1; h < f.loops.size(); ++h) std::reverse(f.loops[h].begin(), f.loops[h].end());
  }
  for (std::size_t h = 1; h < f.loops.size(); ++h) {
    auto& l = f.loops[h];
    std::rotate(l.begin(), std::min_element(l.begin(), l.end()), l.end());
  }
  std::sort(f.loops.begin() + 1, f.loops.end());
}

namespace detail {

/// +1 when face f walks edge e from its start to its end, -1 when the other way, 0 when f
/// does not use e. O(size of f).
template <class = void>
int walk_direction(const wire_graph& g, const wire_face& f, std::uint32_t e) {
  const auto [s, t] = g.edges[e];
  for (const auto& loop : f.loops)
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const std::uint32_t a = loop[k], b = loop[(k + 1) % loop.size()];
      if (a == s && b == t) return 1;
      if (a == t && b == s) return -1;
    }
  return 0;
}

/// For each edge, the faces using it, in face order: one flat array with offsets (a face that
/// uses an edge twice is listed twice). at[e] is a span. O(1) per look-up.
struct edge_face_lists {
  std::vector<std::uint32_t> first;  ///< size E + 1
  std::vector<std::uint32_t> faces;
  std::span<const std::uint32_t> operator[](std::size_t e) const noexcept {
    return {faces.data() + first[e], first[e + 1] - first[e]};
  }
  std::size_t size() const noexcept { return first.empty() ? 0 : first.size() - 1; }
};

/// edge_face_lists of `faces` (only faces with alive[i] != 0 when `alive` is given). O(Σ L).
template <class = void>
edge_face_lists faces_at_edges(const wire_graph& g, const std::vector<wire_face>& faces,
                               const std::vector<char>* alive = nullptr) {
  edge_face_lists at;
  std::vector<std::uint32_t> edge_of;  // per face side, in order: its edge
  at.first.assign(g.num_edges() + 1, 0);
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    if (alive && !(*alive)[i]) continue;
    for (const auto& loop : faces[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const std::uint32_t e = g.find_edge(loop[k], loop[(k + 1) % loop.size()]);
        edge_of.push_back(e);
        ++at.first[e + 1];
      }
  }
  for (std::size_t e = 0; e < g.num_edges(); ++e) at.first[e + 1] += at.first[e];
  at.faces.resize(at.first.back());
  std::vector<std::uint32_t> fill(at.first.begin(), at.first.end() - 1);
  std::size_t side = 0;
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    if (alive && !(*alive)[i]) continue;
    for (const auto& loop : faces[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k) at.faces[fill[edge_of[side++]]++] = i;
  }
  return at;
}

/// Two faces through one edge lie in one plane when their unit normals are parallel. O(1).
template <class = void>
bool coplanar_normals(const glm::dvec3& a, const glm::dvec3& b) {
  return glm::length(glm::cross(a, b)) < 1e-9;
}

/// True when an edge lying on exactly the faces `others` (a face under test left out) would
/// need another face: fewer than two faces, or just two coplanar ones (a seam inside a flat
/// surface, which a wireframe draws only where a wall meets it). O(|others|).
template <class Normal>
bool edge_needs_more(std::span<const std::uint32_t> others, Normal&& normal) {
  if (others.size() < 2) return true;
  return others.size() == 2 && coplanar_normals(normal(others[0]), normal(others[1]));
}

/// True when some edge of face i needs it among the faces with alive[j] != 0: without it that
/// edge would lie on fewer than two of them or on just two coplanar ones (the reading rule of
/// docs/wireframe.md). `at` lists the faces of every edge; `others` is scratch space.
/// O(L_i · k) for k faces at an edge.
template <class = void>
bool needed_faces_one(const wire_graph& g, const std::vector<wire_face>& faces, const edge_face_lists& at,
                      const std::vector<char>& alive, std::uint32_t i, std::vector<std::uint32_t>& others) {
  auto normal = [&](std::uint32_t j) { return faces[j].normal; };
  for (const auto& loop : faces[i].loops)
    for (std::size_t k = 0; k < loop.size(); ++k) {
      others.clear();
      for (const auto j : at[g.find_edge(loop[k], loop[(k + 1) % loop.size()])])
        if (j != i && alive[j]) others.push_back(j);
      if (edge_needs_more(others, normal)) return true;
    }
  return false;
}

/// needed_faces_one for every face with alive[i] != 0 (0 for the others). O(Σ L · k).
template <class = void>
std::vector<char> needed_faces(const wire_graph& g, const std::vector<wire_face>& faces,
                               const edge_face_lists& at, const std::vector<char>& alive) {
  std::vector<char> needed(faces.size(), 0);
  std::vector<std::uint32_t> others;
  for (std::uint32_t i = 0; i < faces.size(); ++i)
    if (alive[i]) needed[i] = needed_faces_one(g, faces, at, alive, i, others);
  return needed;
}

/// Hash of an integer grid cell (splitmix64 finaliser per coordinate). O(1).
struct cell_hash {
  template <std::size_t N>
  std::size_t operator()(const std::array<std::int64_t, N>& c) const noexcept {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (const auto x : c) {
      std::uint64_t z = h ^ (static_cast<std::uint64_t>(x) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2));
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
      h = z ^ (z >> 31);
    }
    return static_cast<std::size_t>(h);
  }
};

}  // namespace detail
}  // namespace cellforge
