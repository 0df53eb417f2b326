// SPDX-License-Identifier: MIT
#pragma once
// make_cell_complex and renumber_cells: building and renumbering the relations (included by
// cells/cell_complex.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/core/detail/newell.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/halfedge/handles.hpp"

namespace cellforge {

template <Point3 P>
P cell_complex<P>::face_normal(cell_face f) const {
  return from_dvec3<P>(detail::cells::access::unit_normal(*this, f));
}

namespace detail::cells {

template <class = void>
std::string S(std::uint64_t x) {
  return std::to_string(x);
}

[[noreturn]] inline void fail(error_category c, const std::string& msg) {
  throw error(c, cellforge::detail::cat("make_cell_complex: ", msg));
}

using cellforge::detail::newell;  // Newell normal of a vertex loop (core/detail/newell.hpp)

/// One edge seen from one end: the other end and the edge.
struct edge_link {
  std::uint32_t other, edge;
};

/// Fills CSR `start` from per-row counts (counts become write cursors). O(rows).
template <class = void>
void counts_to_starts(std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& cursor) {
  start.assign(cursor.size() + 1, 0);
  for (std::size_t i = 0; i < cursor.size(); ++i) start[i + 1] = start[i] + cursor[i];
  for (std::size_t i = 0; i < cursor.size(); ++i) cursor[i] = start[i];
}

/// Union-find root with path halving. O(α(n)) amortised.
template <class = void>
std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace detail::cells

namespace detail::cells {
/// The body of make_cell_complex on double positions (one copy for every point type). O(n log n).
template <class>
void build_topology(cell_topology& cc, std::span<const glm::dvec3> points,
                    std::vector<std::array<std::uint32_t, 2>>&& edges,
                    const std::vector<cell_input_face>& faces,
                    const std::vector<cell_input_volume>& volumes) {
  using std::uint32_t;
  constexpr auto bad = error_category::invalid_input;
  constexpr auto topo = error_category::topology;
  const std::size_t nv = points.size(), ne = edges.size(), nf = faces.size(), nc = volumes.size();
  if (nv >= 0xFFFFFFFFu || ne >= 0xFFFFFFFFu || nf >= 0xFFFFFFFFu || nc >= 0xFFFFFFFFu)
    fail(bad, "more than 2^32 - 2 elements of one kind");
  for (std::size_t v = 0; v < nv; ++v) {
    const glm::dvec3& p = points[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail(bad, cellforge::detail::cat("vertex ", S(v), " has a non-finite coordinate (NaN or Inf)"));
  }

  // Edges: endpoints, no loops, no duplicates; vertex → edges with direction. The first bad
  // edge (out of range, a loop) and the first repeat are both found, and the earlier reported.
  std::size_t first_bad = ne;
  for (std::size_t e = 0; e < ne && first_bad == ne; ++e)
    if (edges[e][0] >= nv || edges[e][1] >= nv || edges[e][0] == edges[e][1]) first_bad = e;
  std::vector<uint32_t> cursor(nv, 0);
  for (std::size_t e = 0; e < first_bad; ++e) {
    ++cursor[edges[e][0]];
    ++cursor[edges[e][1]];
  }
  counts_to_starts(cc.vertex_edge_start_, cursor);
  // Per vertex, (neighbour, edge) sorted: the flat edge look-up of the face loops below (a
  // hash table costs a cache miss and an allocation per edge, the more when the vertices are
  // numbered at random).
  std::vector<edge_link> links(2 * first_bad);
  const auto by_other = [](const edge_link& x, const edge_link& y) {
    return x.other < y.other || (x.other == y.other && x.edge < y.edge);
  };
  cc.vertex_edges_.resize(2 * first_bad);
  for (std::size_t e = 0; e < first_bad; ++e) {
    const auto [a, b] = edges[e];
    links[cursor[a]] = {b, static_cast<uint32_t>(e)};
    cc.vertex_edges_[cursor[a]++] = {cell_edge(e), +1};
    links[cursor[b]] = {a, static_cast<uint32_t>(e)};
    cc.vertex_edges_[cursor[b]++] = {cell_edge(e), -1};
  }
  std::size_t repeat = ne, repeated = ne;  // the earliest edge joining the same vertices as an earlier one
  for (std::size_t v = 0; v < nv; ++v) {
    const auto begin = links.begin() + cc.vertex_edge_start_[v],
               end = links.begin() + cc.vertex_edge_start_[v + 1];
    std::sort(begin, end, by_other);
    for (auto it = begin; end - it > 1; ++it)  // not it + 1 < end: begin may be null
      if (it->other == (it + 1)->other && (it + 1)->edge < repeat) {
        auto group = it;  // the group's first edge is the one repeated
        while (group != begin && (group - 1)->other == it->other) --group;
        repeat = (it + 1)->edge;
        repeated = group->edge;
      }
  }
  if (repeat < first_bad) {
    const auto [a, b] = edges[repeat];
    fail(bad, cellforge::detail::cat("edge ", S(repeat), " repeats edge ", S(repeated),
                                     " (both join vertices ", S(a), " and ", S(b), ")"));
  }
  if (first_bad < ne) {
    const auto [a, b] = edges[first_bad];
    if (a >= nv || b >= nv)
      fail(bad, cellforge::detail::cat("edge ", S(first_bad), " joins vertex ", S(std::max(a, b)),
                                       " but there are ", S(nv), " vertices"));
    fail(bad, cellforge::detail::cat("edge ", S(first_bad), " joins vertex ", S(a), " to itself"));
  }
  const auto edge_of = [&](uint32_t a, uint32_t b) {
    const edge_link* lo = links.data() + cc.vertex_edge_start_[a];
    const edge_link* hi = links.data() + cc.vertex_edge_start_[a + 1];
    if (hi - lo > 16) lo = std::lower_bound(lo, hi, edge_link{b, 0}, by_other);
    for (; lo != hi && lo->other <= b; ++lo)
      if (lo->other == b) return lo->edge;
    return 0xFFFFFFFFu;
  };

  // Faces: loops of vertices and signed edge uses; normals.
  std::vector<uint32_t> edge_uses(ne, 0);
  std::vector<uint32_t> seen(nv, 0xFFFFFFFFu);  // face that last used each vertex
  std::vector<uint32_t> used_by(ne, 0xFFFFFFFFu);
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& loops = faces[f].loops;
    if (loops.empty()) fail(bad, cellforge::detail::cat("face ", S(f), " has no loop"));
    for (std::size_t l = 0; l < loops.size(); ++l) {
      const auto& loop = loops[l];
      const auto where = [&] {
        return cellforge::detail::cat("face ", S(f), " loop ", S(l));
      };  // built only on failure
      if (loop.size() < 3) fail(bad, where() + " has " + S(loop.size()) + " vertices; a loop needs 3");
      for (const uint32_t a : loop)
        if (a >= nv) fail(bad, where() + " uses vertex " + S(a) + " but there are " + S(nv) + " vertices");
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
        if (seen[a] == f) fail(topo, where() + " visits vertex " + S(a) + " a second time in the face");
        seen[a] = static_cast<uint32_t>(f);
        const uint32_t e = edge_of(a, b);
        if (e == 0xFFFFFFFFu)
          fail(topo,
               where() + ": consecutive vertices " + S(a) + " and " + S(b) + " are not joined by an edge");
        if (used_by[e] == f) fail(topo, where() + " uses edge " + S(e) + " a second time in the face");
        used_by[e] = static_cast<uint32_t>(f);
        const bool along = edges[e][0] == a;
        cc.loop_vertices_.push_back(cell_vertex(a));
        cc.loop_edges_.push_back({cell_edge(e), along ? +1 : -1});
        ++edge_uses[e];
      }
      cc.loop_start_.push_back(static_cast<uint32_t>(cc.loop_vertices_.size()));
    }
    cc.face_loop_start_.push_back(static_cast<uint32_t>(cc.loop_start_.size() - 1));
    const glm::dvec3 n = newell(loops[0], [&](uint32_t v) -> const glm::dvec3& { return points[v]; });
    const double len = glm::length(n);
    cc.normals_.push_back(len > 0.0 && std::isfinite(len) ? n / len : glm::dvec3(0.0));
  }

  // Volumes: signed faces; face → volumes.
  std::vector<std::array<oriented<cell_volume>, 2>> fv(nf);
  std::vector<std::uint8_t> nfv(nf, 0);
  std::vector<int> net(ne, 0);
  std::vector<uint32_t> touched;
  for (std::size_t c = 0; c < nc; ++c) {
    const auto& signed_faces = volumes[c].faces;
    if (signed_faces.empty()) fail(bad, cellforge::detail::cat("volume ", S(c), " has no face"));
    for (const auto& [f, sign] : signed_faces) {
      if (f >= nf)
        fail(bad, cellforge::detail::cat("volume ", S(c), " uses face ", S(f), " but there are ", S(nf),
                                         " faces"));
      if (sign != 1 && sign != -1)
        fail(bad,
             cellforge::detail::cat("volume ", S(c), " uses face ", S(f), " with sign ", std::to_string(sign),
                                    "; the sign must be +1 (normal out of the volume) or -1"));
      for (std::uint8_t k = 0; k < nfv[f]; ++k)
        if (fv[f][k].handle.idx() == c)
          fail(topo, cellforge::detail::cat("volume ", S(c), " uses face ", S(f), " twice"));
      if (nfv[f] == 2)
        fail(topo,
             cellforge::detail::cat("face ", S(f), " is in more than two volumes (", S(fv[f][0].handle.idx()),
                                    ", ", S(fv[f][1].handle.idx()), ", ", S(c), ")"));
      for (std::uint8_t k = 0; k < nfv[f]; ++k)
        if (fv[f][k].sign == sign)
          fail(topo,
               cellforge::detail::cat("face ", S(f), " has volumes ", S(fv[f][k].handle.idx()), " and ", S(c),
                                      " on the same side (both with sign ", std::to_string(sign), ")"));
      fv[f][nfv[f]++] = {cell_volume(c), sign};
      cc.volume_faces_.push_back({cell_face(f), sign});
      // Closedness: the signed face boundaries must cancel on every edge.
      for (uint32_t k = cc.loop_start_[cc.face_loop_start_[f]];
           k < cc.loop_start_[cc.face_loop_start_[f + 1]]; ++k) {
        const uint32_t e = cc.loop_edges_[k].handle.idx();
        if (net[e] == 0) touched.push_back(e);
        net[e] += sign * cc.loop_edges_[k].sign;
      }
    }
    for (uint32_t e : touched)
      if (net[e] != 0) {
        const uint32_t bad_edge = e;
        for (uint32_t t : touched) net[t] = 0;
        fail(topo,
             cellforge::detail::cat("the boundary of volume ", S(c), " is not closed: edge ", S(bad_edge),
                                    " (", S(edges[bad_edge][0]), "-", S(edges[bad_edge][1]),
                                    ") is not used equally often in both directions by its faces"));
      }
    touched.clear();
    cc.volume_face_start_.push_back(static_cast<uint32_t>(cc.volume_faces_.size()));
  }
  for (std::size_t f = 0; f < nf; ++f) {
    cc.face_volumes_.insert(cc.face_volumes_.end(), fv[f].begin(), fv[f].begin() + nfv[f]);
    cc.face_volume_start_.push_back(static_cast<uint32_t>(cc.face_volumes_.size()));
  }

  // Edge → faces in right-hand rotation order about source → target, by the angle of the
  // direction into each face (normal × direction of travel, always perpendicular to the edge,
  // so a non-convex face is measured on the right side of the edge).
  cursor.assign(edge_uses.begin(), edge_uses.end());
  counts_to_starts(cc.edge_face_start_, cursor);
  cc.edge_faces_.resize(cc.edge_face_start_.back());
  cc.edge_wedges_.resize(cc.edge_face_start_.back());
  std::vector<double> angle(cc.edge_faces_.size(), 0.0);
  for (std::size_t f = 0; f < nf; ++f)
    for (uint32_t k = cc.loop_start_[cc.face_loop_start_[f]]; k < cc.loop_start_[cc.face_loop_start_[f + 1]];
         ++k) {
      const auto [e, sign] = cc.loop_edges_[k];
      const auto [a, b] = edges[e.idx()];
      // Unit d and u: the raw edge vector's products underflow / overflow at extreme scales.
      const glm::dvec3 d = glm::normalize(points[b] - points[a]);
      const glm::dvec3 into = glm::cross(cc.normals_[f], double(sign) * d);
      // A basis (u, w) of the plane perpendicular to d, from the axis least aligned with d.
      const glm::dvec3 ad = glm::abs(d);
      const glm::dvec3 axis = ad.x <= ad.y && ad.x <= ad.z ? glm::dvec3(1, 0, 0)
                              : ad.y <= ad.z               ? glm::dvec3(0, 1, 0)
                                                           : glm::dvec3(0, 0, 1);
      const glm::dvec3 u = glm::normalize(glm::cross(d, axis)), w = glm::cross(d, u);
      const uint32_t slot = cursor[e.idx()]++;
      angle[slot] = std::atan2(glm::dot(into, w), glm::dot(into, u));
      cc.edge_faces_[slot] = {cell_face(f), sign};
    }
  std::vector<uint32_t> order;
  std::vector<oriented<cell_face>> tmp;
  for (std::size_t e = 0; e < ne; ++e) {
    const uint32_t s = cc.edge_face_start_[e], n = cc.edge_face_start_[e + 1] - s;
    if (n == 0) continue;
    order.resize(n);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t i, uint32_t j) {
      return angle[s + i] != angle[s + j]
                 ? angle[s + i] < angle[s + j]
                 : cc.edge_faces_[s + i].handle.idx() < cc.edge_faces_[s + j].handle.idx();
    });
    tmp.clear();
    for (uint32_t i : order) tmp.push_back(cc.edge_faces_[s + i]);
    // The wedge after face k (toward positive rotation) is on the normal side of a face that
    // runs along e, so it is that face's volume whose sign is -1 (normal pointing into it).
    auto wedge_after = [&](const oriented<cell_face>& ef) {
      const int want = ef.sign > 0 ? -1 : +1;
      for (const auto& v : cc.face_volumes(ef.handle))
        if (v.sign == want) return v.handle;
      return cell_volume();
    };
    // Canonical start: the first face after an outside wedge (the seed starts at a face not
    // between two volumes), else the lowest face index; same order under any rigid motion.
    uint32_t first = 0;
    bool found_outside = false;
    for (uint32_t k = 0; k < n && !found_outside; ++k)
      if (!wedge_after(tmp[k]).is_valid()) first = (k + 1) % n, found_outside = true;
    if (!found_outside)
      first = static_cast<uint32_t>(
          std::min_element(tmp.begin(), tmp.end(),
                           [](const auto& x, const auto& y) { return x.handle.idx() < y.handle.idx(); }) -
          tmp.begin());
    for (uint32_t k = 0; k < n; ++k) {
      cc.edge_faces_[s + k] = tmp[(first + k) % n];
      cc.edge_wedges_[s + k] = wedge_after(cc.edge_faces_[s + k]);
    }
  }

  // Objects: connected components through edges, and through faces and volumes too, so
  // that a face's hole and a volume's inner shell (a cavity) stay with their outer boundary.
  std::vector<uint32_t> parent(nv);
  std::iota(parent.begin(), parent.end(), 0u);
  auto join = [&](uint32_t a, uint32_t b) { parent[find_root(parent, a)] = find_root(parent, b); };
  for (const auto& [a, b] : edges) join(a, b);
  for (const auto& f : faces)
    for (const auto& loop : f.loops) join(loop[0], f.loops[0][0]);
  for (const auto& c : volumes)
    for (const auto& fs : c.faces) join(faces[fs.first].loops[0][0], faces[c.faces[0].first].loops[0][0]);
  cc.vertex_object_.assign(nv, 0xFFFFFFFFu);
  uint32_t no = 0;
  for (uint32_t v = 0; v < nv; ++v) {
    const uint32_t r = find_root(parent, v);
    if (cc.vertex_object_[r] == 0xFFFFFFFFu) cc.vertex_object_[r] = no++;
    cc.vertex_object_[v] = cc.vertex_object_[r];
  }
  cc.object_counts_.assign(no, {0, 0, 0, 0});
  for (uint32_t v = 0; v < nv; ++v) ++cc.object_counts_[cc.vertex_object_[v]][0];
  for (const auto& ab : edges) ++cc.object_counts_[cc.vertex_object_[ab[0]]][1];
  for (std::size_t f = 0; f < nf; ++f) ++cc.object_counts_[cc.vertex_object_[faces[f].loops[0][0]]][2];
  cc.volume_object_.resize(nc);
  cursor.assign(no, 0);
  for (std::size_t c = 0; c < nc; ++c) {
    const uint32_t f = volumes[c].faces.front().first;
    cc.volume_object_[c] = cc.vertex_object_[faces[f].loops[0][0]];
    ++cc.object_counts_[cc.volume_object_[c]][3];
    ++cursor[cc.volume_object_[c]];
  }
  counts_to_starts(cc.object_volume_start_, cursor);
  cc.object_volumes_.resize(nc);
  for (std::size_t c = 0; c < nc; ++c) cc.object_volumes_[cursor[cc.volume_object_[c]]++] = cell_volume(c);

  cc.ends_ = std::move(edges);
}
}  // namespace detail::cells

template <Point3 P>
cell_complex<P> make_cell_complex(cell_complex_input<P> input) {
  cell_complex<P> cc;
  {
    const detail::cells::dvec3_points<P> coords(input.points);
    detail::cells::build_topology(cc, coords.span(), std::move(input.edges), input.faces, input.volumes);
  }
  cc.points_ = std::move(input.points);
  return cc;
}

template <Point3 Q, Point3 P>
cell_complex<Q> convert_points(const cell_complex<P>& cc) {
  cell_complex<Q> out;
  static_cast<cell_topology&>(out) = cc;
  out.points_.reserve(cc.num_vertices());
  for (const P& p : cc.points()) out.points_.push_back(from_dvec3<Q>(to_dvec3(p)));
  return out;
}

namespace detail::cells {
/// The body of renumber_cells on the relations (positions apart). O(size of from).
template <class>
void renumber_topology(const cell_topology& from, cell_topology& to,
                       std::span<const std::uint32_t> vertex_label,
                       std::span<const std::uint32_t> edge_label) {
  using std::uint32_t;
  const std::size_t nv = from.num_vertices(), ne = from.num_edges();
  const auto check = [](std::span<const uint32_t> label, std::size_t n, const char* what) {
    if (label.size() != n)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat(std::string("renumber_cells: "), S(label.size()), " ", what,
                                         " labels for ", S(n), " ", what, "s"));
    std::vector<char> seen(n, 0);
    for (const uint32_t x : label) {
      if (x >= n || seen[x])
        throw error(error_category::invalid_input,
                    cellforge::detail::cat(std::string("renumber_cells: the "), what,
                                           " labels are not a permutation of 0..", S(n - 1)));
      seen[x] = 1;
    }
  };
  check(vertex_label, nv, "vertex");
  check(edge_label, ne, "edge");
  // Faces and volumes keep their numbers: everything of theirs but vertex and edge handles stays.
  to = from;
  std::vector<uint32_t> old_edge(ne);
  for (uint32_t e = 0; e < ne; ++e) {
    old_edge[edge_label[e]] = e;
    to.ends_[edge_label[e]] = {vertex_label[from.ends_[e][0]], vertex_label[from.ends_[e][1]]};
  }
  // Vertex → edges in the new edge order, as make_cell_complex fills them.
  std::vector<uint32_t> cursor(nv, 0);
  for (uint32_t v = 0; v < nv; ++v)
    cursor[vertex_label[v]] = from.vertex_edge_start_[v + 1] - from.vertex_edge_start_[v];
  counts_to_starts(to.vertex_edge_start_, cursor);
  for (uint32_t e = 0; e < ne; ++e) {
    to.vertex_edges_[cursor[to.ends_[e][0]]++] = {cell_edge(e), +1};
    to.vertex_edges_[cursor[to.ends_[e][1]]++] = {cell_edge(e), -1};
  }
  // Faces about each edge: the same rotation, moved to the edge's new place.
  for (uint32_t e = 0; e < ne; ++e) {
    const uint32_t o = old_edge[e];
    to.edge_face_start_[e + 1] =
        to.edge_face_start_[e] + (from.edge_face_start_[o + 1] - from.edge_face_start_[o]);
  }
  for (uint32_t e = 0; e < ne; ++e) {
    const uint32_t o = old_edge[e], n = from.edge_face_start_[o + 1] - from.edge_face_start_[o];
    std::copy_n(from.edge_faces_.begin() + from.edge_face_start_[o], n,
                to.edge_faces_.begin() + to.edge_face_start_[e]);
    std::copy_n(from.edge_wedges_.begin() + from.edge_face_start_[o], n,
                to.edge_wedges_.begin() + to.edge_face_start_[e]);
  }
  for (auto& v : to.loop_vertices_) v = cell_vertex(vertex_label[v.idx()]);
  for (auto& ue : to.loop_edges_) ue.handle = cell_edge(edge_label[ue.handle.idx()]);
  // Objects numbered by their first vertex, as make_cell_complex numbers them.
  const std::size_t no = from.num_objects();
  std::vector<uint32_t> old_vertex(nv), object_label(no, 0xFFFFFFFFu);
  for (uint32_t v = 0; v < nv; ++v) old_vertex[vertex_label[v]] = v;
  uint32_t next = 0;
  for (uint32_t v = 0; v < nv; ++v) {
    uint32_t& o = object_label[from.vertex_object_[old_vertex[v]]];
    if (o == 0xFFFFFFFFu) o = next++;
    to.vertex_object_[v] = o;
  }
  for (uint32_t o = 0; o < no; ++o) to.object_counts_[object_label[o]] = from.object_counts_[o];
  cursor.assign(no, 0);
  for (auto& o : to.volume_object_) ++cursor[o = object_label[o]];
  counts_to_starts(to.object_volume_start_, cursor);
  for (uint32_t c = 0; c < to.volume_object_.size(); ++c)
    to.object_volumes_[cursor[to.volume_object_[c]]++] = cell_volume(c);
}
}  // namespace detail::cells

template <Point3 P>
cell_complex<P> renumber_cells(const cell_complex<P>& cc, std::span<const std::uint32_t> vertex_label,
                               std::span<const std::uint32_t> edge_label) {
  cell_complex<P> out;
  detail::cells::renumber_topology(cc, out, vertex_label, edge_label);
  std::vector<std::uint32_t> old_vertex(cc.num_vertices());  // (P need not be default-constructible)
  for (std::uint32_t v = 0; v < old_vertex.size(); ++v) old_vertex[vertex_label[v]] = v;
  out.points_.reserve(old_vertex.size());
  for (const std::uint32_t v : old_vertex) out.points_.push_back(cc.points_[v]);
  return out;
}

template <class Unused>
template <Point3 P>
void basic_cell_topology<Unused>::topology_to_input(cell_complex_input<P>& in) const {
  in.edges = ends_;
  in.faces.resize(num_faces());
  for (cell_face f : faces()) {
    auto& loops = in.faces[f.idx()].loops;
    loops.resize(num_loops(f));
    for (std::size_t l = 0; l < loops.size(); ++l)
      for (cell_vertex v : loop_vertices(f, l)) loops[l].push_back(v.idx());
  }
  in.volumes.resize(num_volumes());
  for (cell_volume c : volumes())
    for (const auto& [f, s] : volume_faces(c)) in.volumes[c.idx()].faces.emplace_back(f.idx(), s);
}

}  // namespace cellforge
