// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// find_thin_points: the thin-point finder of seed 000 §5 on a closed half-edge mesh
/// or a cell-complex volume: central axis (§5.1), selection growing (§5.2, §5.4) and loop
/// detection (§5.3), returning the thin loops as ordered closed vertex chains.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/work_budget.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/thin/central_axis.hpp"
#include "cellforge/thin/loop_detection.hpp"
#include "cellforge/thin/selection_growing.hpp"
#include "cellforge/thin/thin_result.hpp"

namespace cellforge {

/// Options of find_thin_points; every field is range-checked.
struct thin_options {
  int selection_cap = 40;           ///< n_s of §5.4: selections kept per cycle, 1..1000
  double keep_ratio = 1.1;          ///< selections longer than keep_ratio × least are cut (§5.2), ≥ 1
  int slabs = 20;                   ///< slabs per axis split (§5.1), 2..100000
  double axis_tolerance_deg = 0.1;  ///< axis converged when it moves less than this, 0..90
  int max_axis_iterations = 50;     ///< then the recent directions are averaged, 1..100000
  /// automatic: the seed's rule (fast) up to scalable_above faces, the scalable rule above.
  thin_mode mode = thin_mode::automatic;
  std::uint32_t scalable_above = 4000;
  thin_detection detection = thin_detection::prominence;
  double min_strength = 1.0 / 50;     ///< 0..1
  double suppression_fraction = 0.1;  ///< (0, 1]
  int averaging_window = 5;           ///< seed detector's ±window, 1..10000
  double envelope_rings =
      1.0;  ///< prominence: rim window in estimated rings of faces, 0..1000 (docs/thin.md)
  cellforge::work_budget work_budget =
      2'000'000'000;  ///< candidate selections examined; then complete = false
  /// Merge flat triangle fans and pairs of triangles into clusters before growing (seed §8.2;
  /// docs/thin.md "Clusters"). Off by default; on, cycles count clusters, not mesh faces.
  bool cluster_faces = false;
  /// Significance (docs/thin.md "Significance"): a loop is reported only when the solid's
  /// cross-section across the axis at its level is narrower, by min_strength, than the widest
  /// cross-section on each side of it (a strict thickness minimum).
  bool girth_check = true;
};

namespace detail::thin {

template <class = void>
void check_options(const thin_options& o) {
  const auto bad = [](const std::string& what) {
    throw error(error_category::invalid_input, cellforge::detail::cat("find_thin_points: ", what));
  };
  if (o.selection_cap < 1 || o.selection_cap > 1000)
    bad(cellforge::detail::cat("selection_cap is ", std::to_string(o.selection_cap), "; allowed 1 to 1000"));
  if (!(o.keep_ratio >= 1) || !std::isfinite(o.keep_ratio))
    bad(cellforge::detail::cat("keep_ratio is ", std::to_string(o.keep_ratio),
                               "; allowed a finite value >= 1"));
  if (o.slabs < 2 || o.slabs > 100000)
    bad(cellforge::detail::cat("slabs is ", std::to_string(o.slabs), "; allowed 2 to 100000"));
  if (!(o.axis_tolerance_deg >= 0 && o.axis_tolerance_deg <= 90))
    bad(cellforge::detail::cat("axis_tolerance_deg is ", std::to_string(o.axis_tolerance_deg),
                               "; allowed 0 to 90"));
  if (o.max_axis_iterations < 1 || o.max_axis_iterations > 100000)
    bad(cellforge::detail::cat("max_axis_iterations is ", std::to_string(o.max_axis_iterations),
                               "; allowed 1 to 100000"));
  if (!(o.min_strength >= 0 && o.min_strength <= 1))
    bad(cellforge::detail::cat("min_strength is ", std::to_string(o.min_strength), "; allowed 0 to 1"));
  if (!(o.suppression_fraction > 0 && o.suppression_fraction <= 1))
    bad(cellforge::detail::cat("suppression_fraction is ", std::to_string(o.suppression_fraction),
                               "; allowed above 0 up to 1"));
  if (!(o.envelope_rings >= 0 && o.envelope_rings <= 1000))
    bad(cellforge::detail::cat("envelope_rings is ", std::to_string(o.envelope_rings),
                               "; allowed 0 to 1000"));
  if (o.averaging_window < 1 || o.averaging_window > 10000)
    bad(cellforge::detail::cat("averaging_window is ", std::to_string(o.averaging_window),
                               "; allowed 1 to 10000"));
  if (o.mode != thin_mode::fast && o.mode != thin_mode::faithful && o.mode != thin_mode::scalable &&
      o.mode != thin_mode::automatic)
    bad("mode is not fast, faithful, scalable or automatic");
  if (o.detection != thin_detection::prominence && o.detection != thin_detection::seed)
    bad("detection is not prominence or seed");
}

/// The mesh as the growing sees it, plus what is needed to turn slots back into chains.
struct thin_input {
  thin_face_graph graph;
  std::vector<std::uint32_t> face_id;      ///< mesh face of each compact face
  std::vector<std::uint32_t> edge_id;      ///< mesh edge of each compact edge
  std::vector<std::uint32_t> slot_vertex;  ///< mesh vertex the slot's half-edge leaves
  std::vector<glm::dvec3> position;        ///< by mesh vertex index
  std::vector<glm::dvec3> used_points;     ///< positions of the vertices with faces
};

template <Point3 P>
thin_input prepare(const surface_mesh<P>& m) {
  const auto fail = [](error_category c, const std::string& what) {
    throw error(c, cellforge::detail::cat("find_thin_points: ", what));
  };
  if (m.num_faces() == 0) fail(error_category::invalid_input, "the mesh has no faces");
  if (!m.is_closed())
    fail(error_category::topology,
         cellforge::detail::cat("the mesh is open (", std::to_string(m.num_boundary_edges()),
                                " boundary edges); thin points need a closed solid: fill the holes first"));
  if (!m.is_consistently_oriented())
    fail(error_category::topology,
         cellforge::detail::cat("the faces are not consistently oriented (",
                                std::to_string(m.num_flipped_edges()),
                                " edges are traversed the same way "
                                "by both faces); orient the mesh first (halfedge/orientation.hpp)"));
  const std::span<const P> pts = m.points();
  thin_input in;
  in.position.assign(m.vertices_size(), glm::dvec3(0.0));
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const vertex_handle v : m.vertices()) {
    const glm::dvec3 p = to_dvec3(pts[v.idx()]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail(error_category::invalid_input,
           cellforge::detail::cat("vertex ", std::to_string(v.idx()), " has a NaN or infinite coordinate"));
    in.position[v.idx()] = p;
    if (!m.is_isolated(v)) {
      in.used_points.push_back(p);
      lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
  }
  if (!in.used_points.empty()) {  // 1e300 would make every face "degenerate"
    bounding_box box;
    box.add(lo), box.add(hi);
    check_double_range(box, "find_thin_points");
  }
  const double diag = glm::length(hi - lo);
  std::vector<std::uint32_t> compact_face(m.faces_size(), std::numeric_limits<std::uint32_t>::max());
  for (const face_handle f : m.faces()) {
    compact_face[f.idx()] = static_cast<std::uint32_t>(in.face_id.size());
    in.face_id.push_back(f.idx());
  }
  std::vector<std::uint32_t> compact_edge(m.edges_size(), std::numeric_limits<std::uint32_t>::max());
  thin_face_graph& g = in.graph;
  g.num_faces = static_cast<std::uint32_t>(in.face_id.size());
  g.face_start.assign(1, 0);
  std::vector<std::uint32_t> face_vertices;
  double volume6 = 0.0;  // six times the enclosed volume, cones from the box corner
  for (std::uint32_t cf = 0; cf < g.num_faces; ++cf) {
    const face_handle f(in.face_id[cf]);
    face_vertices.clear();
    glm::dvec3 area(0.0);
    for (const halfedge_handle h : m.halfedges_around(f)) {
      const vertex_handle a = m.tail(h), b = m.head(h);
      face_vertices.push_back(a.idx());
      area += glm::cross(in.position[a.idx()], in.position[b.idx()]);
      const edge_handle e = halfedge_mesh::edge(h);
      if (compact_edge[e.idx()] == std::numeric_limits<std::uint32_t>::max()) {
        compact_edge[e.idx()] = static_cast<std::uint32_t>(in.edge_id.size());
        in.edge_id.push_back(e.idx());
        g.edge_length.push_back(glm::length(in.position[a.idx()] - in.position[b.idx()]));
        g.edge_slots.push_back({0, 0});
      }
      const std::uint32_t ce = compact_edge[e.idx()];
      const auto slot = static_cast<std::uint32_t>(g.slot_edge.size());
      g.edge_slots[ce][h.idx() & 1u] = slot;  // half-edge 2e+i is the edge's slot i
      g.slot_edge.push_back(ce);
      g.slot_other.push_back(compact_face[m.face(halfedge_mesh::twin(h)).idx()]);
      g.slot_face.push_back(cf);
      in.slot_vertex.push_back(a.idx());
    }
    g.face_start.push_back(static_cast<std::uint32_t>(g.slot_edge.size()));
    std::vector<std::uint32_t> sorted = face_vertices;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      fail(error_category::invalid_input,
           cellforge::detail::cat("face ", std::to_string(f.idx()), " repeats a vertex"));
    if (!(0.5 * glm::length(area) > 1e-14 * diag * diag))
      fail(error_category::invalid_input,
           cellforge::detail::cat("face ", std::to_string(f.idx()), " is degenerate (zero area)"));
    volume6 += glm::dot(in.position[face_vertices[0]] - lo, area);  // (area is twice the vector area)
  }
  // A closed surface can enclose nothing (a sheet folded onto itself): no solid, no thin points.
  if (!(std::abs(volume6) / 6.0 > 1e-12 * diag * diag * diag))
    fail(error_category::invalid_input,
         "the mesh is closed but encloses no volume (under 1e-12 of its bounding box's diagonal cubed): "
         "thin points need a solid, not a flat or folded sheet");
  // One solid: every face reachable from face 0.
  std::vector<char> seen(g.num_faces, 0);
  std::vector<std::uint32_t> stack{0};
  seen[0] = 1;
  std::size_t reached = 1;
  while (!stack.empty()) {
    const std::uint32_t f = stack.back();
    stack.pop_back();
    for (std::uint32_t k = g.face_start[f]; k < g.face_start[f + 1]; ++k)
      if (!seen[g.slot_other[k]]) seen[g.slot_other[k]] = 1, ++reached, stack.push_back(g.slot_other[k]);
  }
  if (reached != g.num_faces)
    fail(
        error_category::topology,
        cellforge::detail::cat("the mesh has more than one connected part (", std::to_string(reached), " of ",
                               std::to_string(g.num_faces), " faces reachable); run it on each part"));
  return in;
}

/// Seed §8.2's clusters. First flat fans: in slot order, each vertex whose star is 3 or more
/// unclustered triangles with normals within 1° of their mean, a simple rim and no rim edge
/// between two of them becomes one cluster (a triangulated n-gon cap is one face again).
/// Then pairs: two unclustered triangles sharing one edge are merged when each is the
/// other's clear best partner, "best" being the quad with the largest smallest corner angle
/// among those that bend by at most 20° and are strictly convex. A cluster is one face whose slots are its
/// outer boundary in order; its inner edges leave the graph, so they can never be on a selection's boundary.
/// O(slots · vertex degree).
template <class = void>
thin_input cluster_triangles(thin_input in, std::uint32_t& clustered) {
  const thin_face_graph& g = in.graph;
  constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  const std::uint32_t nf = g.num_faces;
  const auto slots = static_cast<std::uint32_t>(g.slot_edge.size());
  const auto degree = [&](std::uint32_t f) { return g.face_start[f + 1] - g.face_start[f]; };
  const auto next = [&](std::uint32_t s) {
    const std::uint32_t f = g.slot_face[s];
    return s + 1 < g.face_start[f + 1] ? s + 1 : g.face_start[f];
  };
  const auto prev = [&](std::uint32_t s) {
    const std::uint32_t f = g.slot_face[s];
    return s > g.face_start[f] ? s - 1 : g.face_start[f + 1] - 1;
  };
  const auto twin = [&](std::uint32_t s) {
    const auto& two = g.edge_slots[g.slot_edge[s]];
    return two[0] == s ? two[1] : two[0];
  };
  const auto at = [&](std::uint32_t s) { return in.position[in.slot_vertex[s]]; };
  const auto unit_normal = [&](std::uint32_t f) {
    const std::uint32_t k = g.face_start[f];
    return glm::normalize(glm::cross(at(k + 1) - at(k), at(k + 2) - at(k)));
  };
  constexpr double degree_rad = 3.14159265358979323846 / 180;
  std::vector<std::uint32_t> rep(nf, none);  // each clustered face's smallest member face
  clustered = 0;

  // Flat fans, rotating round the slots' tail vertices (twin of the previous slot).
  std::vector<char> vertex_done(in.position.size(), 0);
  std::vector<std::uint32_t> star, rim;
  for (std::uint32_t k = 0; k < slots; ++k) {
    const std::uint32_t v = in.slot_vertex[k];
    if (vertex_done[v]) continue;
    vertex_done[v] = 1;
    star.clear();
    bool ok = true;
    std::uint32_t t = k;
    do {
      const std::uint32_t f = g.slot_face[t];
      ok = degree(f) == 3 && rep[f] == none && star.size() < slots;
      star.push_back(t);
      t = twin(prev(t));
    } while (ok && t != k);
    if (!ok || star.size() < 3) continue;
    glm::dvec3 mean(0.0);
    for (const std::uint32_t x : star) mean += unit_normal(g.slot_face[x]);
    rim.clear();
    for (const std::uint32_t x : star) {
      ok = ok && glm::dot(unit_normal(g.slot_face[x]), mean) >= std::cos(degree_rad) * glm::length(mean);
      rim.push_back(in.slot_vertex[next(x)]);
      for (const std::uint32_t y : star) ok = ok && g.slot_other[next(x)] != g.slot_face[y];
    }
    std::sort(rim.begin(), rim.end());
    if (!ok || std::adjacent_find(rim.begin(), rim.end()) != rim.end()) continue;
    std::uint32_t first = nf;
    for (const std::uint32_t x : star) first = std::min(first, g.slot_face[x]);
    for (const std::uint32_t x : star) rep[g.slot_face[x]] = first;
    clustered += static_cast<std::uint32_t>(star.size());
  }

  // Pairs: quality of the quad made with the triangle across slot s, the smallest corner
  // angle; −1 when the triangles share more than that edge, bend by more than 20° or the
  // quad is not strictly convex.
  const auto quality = [&](std::uint32_t s) {
    const std::uint32_t f = g.slot_face[s], o = g.slot_other[s], t = twin(s);
    if (o == f || rep[o] != none || degree(o) != 3) return -1.0;
    std::uint32_t shared = 0;
    for (std::uint32_t k = g.face_start[f]; k < g.face_start[f + 1]; ++k) shared += g.slot_other[k] == o;
    if (shared != 1) return -1.0;  // two triangles glued along two edges are not a quad
    // s runs a→c in f = (a, c, b); t runs c→a in o = (c, a, d); the quad is c, b, a, d.
    const std::array<glm::dvec3, 4> q{at(next(s)), at(prev(s)), at(s), at(prev(t))};
    const glm::dvec3 n1 = glm::cross(q[1] - q[0], q[2] - q[0]), n2 = glm::cross(q[2] - q[0], q[3] - q[0]);
    if (!(glm::dot(n1, n2) >= std::cos(20 * degree_rad) * glm::length(n1) * glm::length(n2))) return -1.0;
    double least = 4;
    for (std::size_t i = 0; i < 4; ++i) {
      const glm::dvec3 u = q[(i + 3) % 4] - q[i], w = q[(i + 1) % 4] - q[i];
      if (!(glm::dot(glm::cross(w, u), n1 + n2) > 0)) return -1.0;  // a reflex or straight corner
      least = std::min(least,
                       std::acos(std::clamp(glm::dot(u, w) / (glm::length(u) * glm::length(w)), -1.0, 1.0)));
    }
    return least;
  };
  // Each triangle's clear best partner slot (better than the runner-up by a margin, so that
  // round-off under a rigid motion cannot flip a tie); pairs are the mutual choices.
  std::vector<std::uint32_t> best(nf, none);
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (rep[f] != none || degree(f) != 3) continue;
    double top = 0, second = -1;
    for (std::uint32_t k = g.face_start[f]; k < g.face_start[f + 1]; ++k) {
      const double qk = quality(k);
      if (qk > top)
        second = top, top = qk, best[f] = k;
      else
        second = std::max(second, qk);
    }
    if (best[f] != none && !(top > (1 + 1e-6) * second)) best[f] = none;
  }
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (best[f] == none) continue;
    const std::uint32_t o = g.slot_other[best[f]];
    if (f < o && best[o] != none && g.slot_other[best[o]] == f) rep[f] = rep[o] = f, clustered += 2;
  }
  if (clustered == 0) return in;  // nothing to merge (e.g. all quads): the graph is unchanged

  // Clusters numbered by their smallest face; members listed in face order.
  std::vector<std::uint32_t> id(nf, none), member_start(1, 0), members;
  std::uint32_t clusters = 0;
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (rep[f] == none) rep[f] = f;
    if (rep[f] == f) id[f] = clusters++;
  }
  for (std::uint32_t f = 0; f < nf; ++f) id[f] = id[rep[f]];
  member_start.assign(clusters + 1, 0);
  for (std::uint32_t f = 0; f < nf; ++f) ++member_start[id[f] + 1];
  for (std::uint32_t c = 0; c < clusters; ++c) member_start[c + 1] += member_start[c];
  members.resize(nf);
  std::vector<std::uint32_t> fill(member_start.begin(), member_start.end() - 1);
  for (std::uint32_t f = 0; f < nf; ++f) members[fill[id[f]]++] = f;

  thin_input out;
  out.position = std::move(in.position), out.used_points = std::move(in.used_points);
  thin_face_graph& c = out.graph;
  c.num_faces = clusters;
  c.face_start.assign(1, 0);
  std::vector<std::uint32_t> new_slot(slots, none), new_edge(g.edge_slots.size(), none), old_edge;
  const auto add_slot = [&](std::uint32_t k) {
    const std::uint32_t e = g.slot_edge[k];
    if (new_edge[e] == none) {
      new_edge[e] = static_cast<std::uint32_t>(old_edge.size());
      old_edge.push_back(e);
      c.edge_length.push_back(g.edge_length[e]);
      out.edge_id.push_back(in.edge_id[e]);
    }
    new_slot[k] = static_cast<std::uint32_t>(c.slot_edge.size());
    c.slot_edge.push_back(new_edge[e]);
    c.slot_other.push_back(id[g.slot_other[k]]);
    c.slot_face.push_back(static_cast<std::uint32_t>(c.face_start.size() - 1));
    out.slot_vertex.push_back(in.slot_vertex[k]);
  };
  for (std::uint32_t cl = 0; cl < clusters; ++cl) {
    const std::uint32_t first = members[member_start[cl]];
    out.face_id.push_back(in.face_id[first]);  // a cluster is named by its first mesh face
    if (member_start[cl + 1] - member_start[cl] == 1) {
      for (std::uint32_t k = g.face_start[first]; k < g.face_start[first + 1]; ++k) add_slot(k);
    } else {
      // Walk the outer boundary from its smallest slot, turning round each vertex through
      // the cluster's own faces (as boundary_chains does); a disk has one such loop.
      std::uint32_t outer = 0, start = none;
      for (std::uint32_t i = member_start[cl]; i < member_start[cl + 1]; ++i)
        for (std::uint32_t k = g.face_start[members[i]]; k < g.face_start[members[i] + 1]; ++k)
          if (id[g.slot_other[k]] != cl) ++outer, start = std::min(start, k);
      std::uint32_t walked = 0, s = start;
      do {
        add_slot(s);
        std::uint32_t t = next(s);
        for (std::uint32_t turn = 0; id[g.slot_other[t]] == cl && turn <= slots; ++turn) t = next(twin(t));
        s = t;
      } while (++walked <= outer && s != start);
      if (walked != outer)
        throw error(error_category::internal,
                    cellforge::detail::cat("find_thin_points: face cluster ", std::to_string(cl),
                                           " is not a disk; rerun without cluster_faces"));
    }
    c.face_start.push_back(static_cast<std::uint32_t>(c.slot_edge.size()));
  }
  for (const std::uint32_t e : old_edge)
    c.edge_slots.push_back({new_slot[g.edge_slots[e][0]], new_slot[g.edge_slots[e][1]]});
  return out;
}

/// Splits the boundary of a selection (its inner slots) into closed chains by walking
/// round the selected region (consistent orientation makes next/twin a boundary walk).
template <class = void>
std::vector<std::vector<std::uint32_t>> boundary_chains(const thin_face_graph& g,
                                                        const std::vector<std::uint32_t>& inner) {
  std::vector<std::vector<std::uint32_t>> chains;
  std::vector<char> used(inner.size(), 0);
  const auto index_of = [&](std::uint32_t s) {
    const auto it = std::lower_bound(inner.begin(), inner.end(), s);
    return it != inner.end() && *it == s ? static_cast<std::ptrdiff_t>(it - inner.begin())
                                         : std::ptrdiff_t{-1};
  };
  const auto next_in_face = [&](std::uint32_t s) {
    const std::uint32_t f = g.slot_face[s];
    return s + 1 < g.face_start[f + 1] ? s + 1 : g.face_start[f];
  };
  const auto twin = [&](std::uint32_t s) {
    const auto& two = g.edge_slots[g.slot_edge[s]];
    return two[0] == s ? two[1] : two[0];
  };
  for (std::size_t i = 0; i < inner.size(); ++i) {
    if (used[i]) continue;
    std::vector<std::uint32_t> chain;
    std::uint32_t s = inner[i];
    for (std::size_t guard = 0; guard <= g.slot_edge.size(); ++guard) {
      const std::ptrdiff_t k = index_of(s);
      if (k < 0 || used[static_cast<std::size_t>(k)]) break;
      used[static_cast<std::size_t>(k)] = 1;
      chain.push_back(s);
      // Turn round the head vertex through selected faces to the next boundary slot.
      std::uint32_t t = next_in_face(s);
      for (std::size_t turn = 0; index_of(t) < 0 && turn <= g.slot_edge.size(); ++turn)
        t = next_in_face(twin(t));
      s = t;
    }
    chains.push_back(std::move(chain));
  }
  return chains;
}

/// Cross-sections the significance rule samples along the axis.
inline constexpr int girth_samples = 64;

/// The perimeter of the solid's section by each plane dot(dir, p) = levels[j] (levels
/// ascending): each face adds the length of its intersection with the plane (crossings of its
/// boundary, paired along the line). O(faces · log levels + crossings).
template <class = void>
std::vector<double> cross_section_girths(const thin_input& in, const glm::dvec3& dir,
                                         const std::vector<double>& levels) {
  const thin_face_graph& g = in.graph;
  std::vector<double> girth(levels.size(), 0.0), height;
  std::vector<glm::dvec3> cross;
  for (std::uint32_t f = 0; f < g.num_faces; ++f) {
    const std::uint32_t b = g.face_start[f], n = g.face_start[f + 1] - b;
    height.resize(n);
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (std::uint32_t k = 0; k < n; ++k) {
      height[k] = glm::dot(dir, in.position[in.slot_vertex[b + k]]);
      low = std::min(low, height[k]), high = std::max(high, height[k]);
    }
    for (auto it = std::upper_bound(levels.begin(), levels.end(), low); it != levels.end() && *it < high;
         ++it) {
      cross.clear();
      for (std::uint32_t k = 0; k < n; ++k) {
        const std::uint32_t k2 = (k + 1) % n;
        if ((height[k] < *it) == (height[k2] < *it)) continue;
        const glm::dvec3 &p = in.position[in.slot_vertex[b + k]], &q = in.position[in.slot_vertex[b + k2]];
        cross.push_back(p + (q - p) * ((*it - height[k]) / (height[k2] - height[k])));
      }
      if (cross.size() < 2) continue;
      const glm::dvec3 along = cross[1] - cross[0];
      std::sort(cross.begin(), cross.end(), [&](const glm::dvec3& x, const glm::dvec3& y) {
        return glm::dot(along, x) < glm::dot(along, y);
      });
      for (std::size_t i = 0; i + 1 < cross.size(); i += 2)
        girth[static_cast<std::size_t>(it - levels.begin())] += glm::length(cross[i + 1] - cross[i]);
    }
  }
  return girth;
}

template <class = void>
thin_loop<glm::dvec3> make_loop(const thin_input& in, const std::vector<std::uint32_t>& inner,
                                const glm::dvec3& dir, double lo, double hi) {
  const thin_face_graph& g = in.graph;
  const auto chains = boundary_chains(g, inner);
  thin_loop<glm::dvec3> loop;
  loop.chains = chains.size();
  const auto chain_length = [&](const std::vector<std::uint32_t>& c) {
    double s = 0;
    for (const std::uint32_t k : c) s += g.edge_length[g.slot_edge[k]];
    return s;
  };
  std::size_t best = 0;
  for (std::size_t i = 0; i < chains.size(); ++i) {
    loop.total_length += chain_length(chains[i]);
    if (chain_length(chains[i]) > chain_length(chains[best])) best = i;
  }
  if (chains.empty()) return loop;
  std::vector<std::uint32_t> c = chains[best];
  std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());  // canonical start
  glm::dvec3 centre(0.0);
  for (const std::uint32_t k : c) {
    loop.vertices.push_back(in.slot_vertex[k]);
    loop.edges.push_back(in.edge_id[g.slot_edge[k]]);
    loop.points.push_back(in.position[in.slot_vertex[k]]);
    centre += in.position[in.slot_vertex[k]];
  }
  loop.length = chain_length(c);
  centre /= static_cast<double>(c.size());
  loop.axis_position = hi > lo ? std::clamp((glm::dot(dir, centre) - lo) / (hi - lo), 0.0, 1.0) : 0.0;
  return loop;
}

/// find_thin_points on a prepared mesh, in double precision. O(as find_thin_points).
template <class = void>
thin_result<glm::dvec3> find(thin_input prepared, const thin_options& options) {
  thin_result<glm::dvec3> r;
  const thin_input in =
      options.cluster_faces ? cluster_triangles(std::move(prepared), r.clustered_faces) : std::move(prepared);
  const thin_face_graph& g = in.graph;
  r.grown_faces = g.num_faces;

  detail::stopwatch clock;
  const central_axis_result axis =
      central_axis(detail::span_of(in.used_points),
                   {options.slabs, options.axis_tolerance_deg, options.max_axis_iterations, 5});
  glm::dvec3 dir = axis.direction;
  // Start face: the face centre farthest along the axis from the centroid (largest |G|).
  std::uint32_t start = 0;
  double far = -1, side = 0;
  for (std::uint32_t f = 0; f < g.num_faces; ++f) {
    glm::dvec3 c(0.0);
    for (std::uint32_t k = g.face_start[f]; k < g.face_start[f + 1]; ++k) c += in.position[in.slot_vertex[k]];
    c /= static_cast<double>(g.face_start[f + 1] - g.face_start[f]);
    const double gv = glm::dot(dir, c - axis.centroid);
    if (std::abs(gv) > far) far = std::abs(gv), start = f, side = gv;
  }
  if (side > 0) dir = -dir;  // the axis runs from the start end to the other end
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const glm::dvec3& p : in.used_points)
    lo = std::min(lo, glm::dot(dir, p)), hi = std::max(hi, glm::dot(dir, p));
  r.axis_origin = axis.origin, r.axis_direction = dir;
  r.axis_iterations = axis.iterations, r.axis_converged = axis.converged;
  r.start_face = in.face_id[start];
  r.axis_ms = clock.ms();

  clock.restart();
  const growing_result grown = grow_selections(
      g, start,
      {options.selection_cap, options.keep_ratio, options.mode, options.work_budget, options.scalable_above});
  r.growing_ms = clock.ms();
  r.cycle_lengths = grown.cycle_lengths;
  r.selections_examined = grown.selections_examined, r.duplicates_dropped = grown.duplicates_dropped;
  r.selections_kept = grown.selections_kept, r.max_kept = grown.max_kept;
  r.complete = grown.complete, r.diagnostics = grown.diagnostics;

  // Cycles per ring of faces: the summed axial extent of the edges over the axis extent is
  // the mean number of edges a plane across the axis cuts, which is about the number of faces
  // in one ring (exactly `segments` for quad rings, 2·segments for triangle rings).
  double axial = 0;
  for (std::size_t e = 0; e < g.edge_slots.size(); ++e) {
    const std::uint32_t s0 = g.edge_slots[e][0];
    axial += std::abs(
        glm::dot(dir, in.position[in.slot_vertex[s0]] - in.position[in.slot_vertex[g.edge_slots[e][1]]]));
  }
  const double ring_cycles = hi > lo ? std::min(axial / (hi - lo), static_cast<double>(g.num_faces)) : 0.0;
  r.ring_cycles = ring_cycles;

  clock.restart();
  const thin_detection_result found = detect_thin_cycles(
      detail::span_of(r.cycle_lengths), g.num_faces,
      {options.detection, options.min_strength, options.suppression_fraction, options.averaging_window,
       static_cast<std::size_t>(std::lround(options.envelope_rings * ring_cycles))});
  r.values_smoothed = found.smoothed;
  std::vector<thin_loop<glm::dvec3>> loops;
  for (const detected_cycle& d : found.cycles) {
    loops.push_back(make_loop(in, cycle_loop(g, grown, d.cycle), dir, lo, hi));
    loops.back().cycle = d.cycle, loops.back().strength = d.strength;
  }
  // Significance: the solid's cross-section across the axis at the loop's level must be
  // narrower, by min_strength, than its widest cross-section on each side (a strict thickness
  // minimum); sampled at girth_samples levels plus the loops' own.
  std::vector<double> levels, girth;
  if (options.girth_check && !loops.empty() && hi > lo) {
    for (int j = 0; j < girth_samples; ++j) levels.push_back(lo + (hi - lo) * (j + 0.5) / girth_samples);
    for (const auto& loop : loops) levels.push_back(lo + loop.axis_position * (hi - lo));
    std::sort(levels.begin(), levels.end());
    girth = cross_section_girths(in, dir, levels);
  }
  for (thin_loop<glm::dvec3>& loop : loops) {
    if (!girth.empty()) {
      const double at = lo + loop.axis_position * (hi - lo);
      double wide[2] = {0, 0}, here = 0;
      for (std::size_t j = 0; j < levels.size(); ++j)
        if (levels[j] == at)
          here = girth[j];
        else
          wide[levels[j] > at] = std::max(wide[levels[j] > at], girth[j]);
      const double rim = std::min(wide[0], wide[1]);
      if (!(here < (1 - options.min_strength) * rim)) {
        r.diagnostics.push_back(cellforge::detail::cat(
            "loop at cycle ", std::to_string(loop.cycle), " (length ", std::to_string(loop.length),
            ") is not reported: the cross-section at its ", "level (", std::to_string(here),
            " around) is no narrower than the widest on its ", (wide[0] <= wide[1] ? "start" : "far"),
            " side (", std::to_string(rim), "; girth_check)"));
        continue;
      }
    }
    r.loops.push_back(std::move(loop));
  }
  r.detection_ms = clock.ms();
  r.milliseconds = r.axis_ms + r.growing_ms + r.detection_ms;
  r.work = r.selections_examined;
  return r;
}

/// A volume's boundary-mesh result with cell ids: loop vertices, edges (0xFFFFFFFF where the
/// mesh edge is no cell edge) and the start face. O(loop size · vertex degree).
template <class = void>
void to_cell_ids(const cell_topology& cc, const halfedge_mesh& m, thin_result_base& r,
                 std::span<thin_loop_base* const> loops) {
  const auto cell_vertex_of = m.get_vertex_property<std::uint32_t>("v:cell_vertex");
  const auto cell_face_of = m.get_face_property<std::uint32_t>("f:cell_face");
  r.start_face = cell_face_of[face_handle(r.start_face)];
  for (thin_loop_base* loop : loops) {
    for (std::uint32_t& x : loop->vertices) x = cell_vertex_of[vertex_handle(x)];
    for (std::size_t i = 0; i < loop->edges.size(); ++i) {
      const cell_vertex a(loop->vertices[i]), b(loop->vertices[(i + 1) % loop->vertices.size()]);
      loop->edges[i] = std::numeric_limits<std::uint32_t>::max();
      for (const auto& oe : cc.vertex_edges(a)) {
        const auto ends = cc.edge_vertices(oe.handle);
        if ((ends[0] == a && ends[1] == b) || (ends[0] == b && ends[1] == a)) {
          loop->edges[i] = oe.handle.idx();
          break;
        }
      }
    }
  }
}

template <Point3 P>
thin_result<P> with_cell_ids(const cell_topology& cc, const halfedge_mesh& m, thin_result<P>&& r) {
  std::vector<thin_loop_base*> loops;
  for (thin_loop<P>& l : r.loops) loops.push_back(&l);
  to_cell_ids(cc, m, r, loops);
  return std::move(r);
}

}  // namespace detail::thin

/// The thin loops of a closed, consistently oriented, connected mesh (seed 000 §5), with loop
/// points and the axis in m's point type P (computed in double precision, converted once).
/// O(faces · cap · (boundary + candidates · degree)) in fast mode; see docs/thin.md.
template <Point3 P>
thin_result<P> find_thin_points(const surface_mesh<P>& m, const thin_options& options = {}) {
  detail::thin::check_options(options);
  return detail::thin::result_as<P>(detail::thin::find(detail::thin::prepare<P>(m), options));
}

/// find_thin_points on volume v of a cell complex (its boundary via volume_boundary_mesh);
/// loop vertices, edges and the start face are cell ids. Edges that are triangulation
/// diagonals of a holed face have no cell edge: their id is 0xFFFFFFFF. Points in the
/// complex's point type P. O(as above).
template <Point3 P>
thin_result<P> find_thin_points(const cell_complex<P>& cc, cell_volume v, const thin_options& options = {}) {
  const surface_mesh<P> m = volume_boundary_mesh(cc, v);
  return detail::thin::with_cell_ids(cc, m, find_thin_points(m, options));
}

}  // namespace cellforge
