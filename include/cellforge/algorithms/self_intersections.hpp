// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// An exact self-intersection check for polygon meshes: every face is triangulated, pairs of
/// triangles whose boxes meet are found with a uniform grid over the faces' triangles taken two at
/// a time (a quad is one box), and each pair is decided by the
/// signs of orient3d / orient2d alone (core/predicates.hpp), with no epsilon anywhere.
/// O(n + candidate pairs) for n triangles (radix sorts), the pairs bounded by a work budget. What
/// is tested, when two triangles intersect and the proof that the test is complete: docs/predicates.md.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/algorithms/detail/triangle_pairs.hpp"
#include "cellforge/algorithms/ear_clipping.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/morton.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/core/work_budget.hpp"
#include "cellforge/halfedge/handles.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"

namespace cellforge {

// The deprecated members below warn where a user names them, not at every copy of the structs.
/// Limits of self_intersections.
struct self_intersection_options {
  /// Work budget: the most candidate pairs (two boxes in one grid cell) examined;
  /// automatic (the default): 256 per triangle plus 2^20; 0: unlimited. A closed mesh with
  /// well-shaped triangles needs some 10–30 per triangle. Past it: complete = false.
  cellforge::work_budget work_budget = cellforge::work_budget::automatic;
  /// How many intersecting face pairs (and faces with zero-area triangles) to list.
  std::size_t max_reported = 100;
};

/// What self_intersections found; work (stage_report) counts the candidate pairs, complete is
/// false when the budget stopped the search.
struct self_intersection_result : stage_report {
  /// Distinct pairs of faces with at least one intersecting pair of triangles.
  std::size_t intersecting_face_pairs = 0;
  /// Intersecting pairs of triangles (a face pair may hold several).
  std::size_t intersecting_triangle_pairs = 0;
  /// The first max_reported intersecting face pairs, by face index (first < second).
  std::vector<std::pair<face_handle, face_handle>> face_pairs;
  std::size_t faces = 0;      ///< live faces
  std::size_t triangles = 0;  ///< triangles of their triangulations
  /// Polygons not both planar and strictly convex (a quad convex in projection counts as
  /// planar when orient3d's floating-point filter cannot tell it from planar).
  std::size_t ear_clipped_faces = 0;
  /// Box pairs examined in grid cells (the budget counts these; a box holds up to two triangles
  /// of one face): in each cell, the pairs that could have the low corner of their boxes'
  /// intersection there.
  std::size_t candidate_pairs = 0;
  std::size_t pairs_tested = 0;  ///< pairs of different faces with overlapping boxes, tested exactly
  /// Of pairs_tested, those sharing a vertex whose star projects one-to-one on a coordinate
  /// plane: decided without geometry (they meet only in what they share).
  std::size_t pairs_by_topology = 0;
  /// self_intersections_by_pieces (piece_self_intersections.hpp) only: the pieces, the groups of
  /// pieces certified embedded, and the pairs of pieces whose boxes overlap that a certified group
  /// holds or that a plane separates (neither tested).
  std::size_t pieces = 0, certified_groups = 0, certified_piece_pairs = 0, separated_piece_pairs = 0;
  std::size_t degenerate_triangles = 0;       ///< zero-area triangles (not tested)
  std::vector<face_handle> degenerate_faces;  ///< the first max_reported faces holding one
};

namespace detail::self_intersect {

/// The face-pair keys found (first face << 32 | second), sorted and deduplicated, into r: their
/// count and the first max_reported pairs. Shared by both checks. O(n log n).
template <class = void>
void report_pairs(self_intersection_result& r, std::vector<std::uint64_t>& found, std::size_t max_reported) {
  compact(found);
  r.intersecting_face_pairs = found.size();
  for (std::size_t i = 0; i < found.size() && i < max_reported; ++i)
    r.face_pairs.emplace_back(face_handle(static_cast<std::uint32_t>(found[i] >> 32)),
                              face_handle(static_cast<std::uint32_t>(found[i])));
}

/// One triangle of a face's triangulation.
struct entry {
  std::array<std::uint32_t, 3> v;  ///< vertex indices
  std::uint32_t face;
  std::array<double, 6> box;  ///< min x, y, z, max x, y, z
};

/// Triangulates every live face of m into `out` as described in the file comment, with
/// positions from `pos` (indexed by vertex). O(Σ face size) for convex faces.
template <Point3 P>
void triangulate_for_test(const surface_mesh<P>& m, std::span<const vec> pos, std::vector<entry>& out,
                          self_intersection_result& r) {
  std::vector<std::uint32_t> ids;
  std::vector<vec> corners;
  for (const face_handle f : m.faces()) {
    ++r.faces;
    ids.clear();
    corners.clear();
    for (const vertex_handle v : m.vertices_around(f)) {
      ids.push_back(v.idx());
      corners.push_back(pos[v.idx()]);
    }
    const bool clipped = triangulate_polygon(detail::span_of(ids), detail::span_of(corners),
                                             [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
                                               entry e;
                                               e.v = {a, b, c};
                                               e.face = f.idx();
                                               out.push_back(e);
                                             });
    if (clipped) ++r.ear_clipped_faces;
  }
}

/// Groups the triangles (in face order, as triangulate_for_test makes them) two at a time within
/// a face, so that a quad is one box for the grid: its boxes and pairs are about half those of
/// its triangles. Puts the groups in Morton order of their box centres (10 bits an axis), their
/// triangles after them, and renumbers the vertices (and their positions) in order of first use,
/// so that groups near in space are near in memory, and so are their corners. `first` gets each
/// group's first triangle (a last entry closes it), `boxes` each group's box (the union of its
/// triangles'). The faces keep their indices. O(n + vertices).
template <class = void>
void spatial_order(std::vector<entry>& tris, std::vector<vec>& pos, std::vector<std::uint32_t>& first,
                   std::vector<std::array<double, 6>>& boxes) {
  const std::size_t n = tris.size();
  std::vector<std::uint32_t> start;  // groups in face order
  start.reserve(n / 2 + 2);
  for (std::size_t t = 0; t < n;) {
    start.push_back(static_cast<std::uint32_t>(t));
    t += t + 1 < n && tris[t + 1].face == tris[t].face ? 2 : 1;
  }
  const std::size_t g = start.size();
  start.push_back(static_cast<std::uint32_t>(n));
  std::vector<std::array<double, 6>> group_box(g);
  vec lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < g; ++i) {
    std::array<double, 6> b = tris[start[i]].box;
    for (std::uint32_t t = start[i] + 1; t < start[i + 1]; ++t)
      for (std::size_t k = 0; k < 3; ++k)
        b[k] = std::min(b[k], tris[t].box[k]), b[k + 3] = std::max(b[k + 3], tris[t].box[k + 3]);
    group_box[i] = b;
    for (int k = 0; k < 3; ++k) {
      const double c = 0.5 * b[static_cast<std::size_t>(k)] + 0.5 * b[static_cast<std::size_t>(k) + 3];
      lo[k] = std::min(lo[k], c), hi[k] = std::max(hi[k], c);
    }
  }
  std::vector<std::uint64_t> order(g);
  for (std::size_t i = 0; i < g; ++i) {
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const double c = 0.5 * group_box[i][static_cast<std::size_t>(k)] +
                       0.5 * group_box[i][static_cast<std::size_t>(k) + 3];
      const double q = (c - lo[k]) / (hi[k] - lo[k]) * 1023.0;
      const std::uint64_t cell = q > 0 ? (q < 1023 ? static_cast<std::uint64_t>(q) : 1023) : 0;  // NaN: 0
      code |= cellforge::detail::morton_spread(cell) << k;
    }
    order[i] = code << 32 | i;
  }
  radix_sort_high(order);
  std::vector<entry> sorted;
  sorted.reserve(n);
  first.clear();
  first.reserve(g + 1);
  boxes.resize(g);
  for (std::size_t i = 0; i < g; ++i) {
    const auto at = static_cast<std::uint32_t>(order[i]);
    first.push_back(static_cast<std::uint32_t>(sorted.size()));
    boxes[i] = group_box[at];
    for (std::uint32_t t = start[at]; t < start[at + 1]; ++t) sorted.push_back(tris[t]);
  }
  first.push_back(static_cast<std::uint32_t>(n));
  std::vector<std::uint64_t>().swap(order);
  std::vector<std::array<double, 6>>().swap(group_box);
  constexpr std::uint32_t unset = 0xFFFFFFFFu;
  std::vector<std::uint32_t> renumber(pos.size(), unset);
  std::vector<vec> moved;
  moved.reserve(pos.size());
  for (entry& e : sorted)
    for (std::uint32_t& x : e.v) {
      if (renumber[x] == unset) {
        renumber[x] = static_cast<std::uint32_t>(moved.size());
        moved.push_back(pos[x]);
      }
      x = renumber[x];
    }
  tris.swap(sorted);
  pos.swap(moved);
}

}  // namespace detail::self_intersect

/// Whether the closed triangles a and b have a common point (touching counts), exactly;
/// false when either has zero area. O(1).
template <Point3 P>
bool triangles_intersect(const std::array<P, 3>& a, const std::array<P, 3>& b) {
  namespace si = detail::self_intersect;
  const std::array<glm::dvec3, 3> p = {to_dvec3(a[0]), to_dvec3(a[1]), to_dvec3(a[2])},
                                  q = {to_dvec3(b[0]), to_dvec3(b[1]), to_dvec3(b[2])};
  if (si::degenerate(p[0], p[1], p[2]) || si::degenerate(q[0], q[1], q[2])) return false;
  return si::disjoint_pair_meets(p, q);
}

/// Finds the pairs of faces of m whose triangles intersect, exactly (see the file comment
/// for what is tested and what counts as intersecting). O(n log n + candidate pairs) for n
/// triangles, candidate pairs capped by options.work_budget.
template <Point3 P>
self_intersection_result self_intersections(const surface_mesh<P>& m,
                                            const self_intersection_options& options = {}) {
  namespace si = detail::self_intersect;
  const detail::stopwatch start;
  self_intersection_result r;
  std::vector<glm::dvec3> pos(m.vertices_size());
  for (std::size_t i = 0; i < pos.size(); ++i) pos[i] = to_dvec3(m.points()[i]);

  std::vector<si::entry> all;
  all.reserve(m.num_faces() * 2);
  si::triangulate_for_test(m, pos, all, r);
  r.triangles = all.size();
  if (all.size() >= 0xFFFFFFFFu)
    throw error(error_category::invalid_input, "self_intersections: more than 2^32 - 1 triangles");

  // Drop the zero-area triangles (reported); box the others.
  std::vector<si::entry> tris;
  tris.reserve(all.size());
  for (si::entry& e : all) {
    const glm::dvec3 &a = pos[e.v[0]], &b = pos[e.v[1]], &c = pos[e.v[2]];
    if (si::degenerate(a, b, c)) {
      ++r.degenerate_triangles;
      const face_handle f(e.face);
      if (r.degenerate_faces.size() < options.max_reported &&
          (r.degenerate_faces.empty() || r.degenerate_faces.back() != f))
        r.degenerate_faces.push_back(f);
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      e.box[static_cast<std::size_t>(k)] = std::min({a[k], b[k], c[k]});
      e.box[static_cast<std::size_t>(k) + 3] = std::max({a[k], b[k], c[k]});
    }
    tris.push_back(e);
  }
  std::vector<si::entry>().swap(all);
  const std::size_t n = tris.size();
  const std::size_t budget = options.work_budget.limit(256 * n + (std::size_t{1} << 20));
  auto finish = [&] {
    r.milliseconds = start.ms();
    r.work = r.candidate_pairs;
    return r;
  };
  if (n < 2) return finish();

  std::vector<std::uint32_t> first;
  std::vector<std::array<double, 6>> group_boxes;
  si::spatial_order(tris, pos, first, group_boxes);
  const std::vector<std::uint8_t> good =
      si::injective_stars(std::span<const si::entry>(tris), pos, pos.size());
  struct corners_face {  // what a pair test reads of a triangle, compact
    std::array<std::uint32_t, 3> v;
    std::uint32_t face;
    std::array<double, 6> box;
  };
  std::vector<corners_face> ids(n);
  for (std::size_t t = 0; t < n; ++t) ids[t] = {tris[t].v, tris[t].face, tris[t].box};
  std::vector<si::entry>().swap(tris);
  std::vector<std::uint64_t> found;  // face-pair keys, compacted as they grow
  std::size_t compact_at = 1 << 16;
  std::array<glm::dvec3, 3> p{}, q{};
  const auto test = [&](const corners_face& a, const corners_face& b) {
    if (a.face == b.face) return;
    // The groups' boxes overlap; their triangles' may not (one branch: hard to predict).
    if ((static_cast<int>(a.box[0] <= b.box[3]) & static_cast<int>(b.box[0] <= a.box[3]) &
         static_cast<int>(a.box[1] <= b.box[4]) & static_cast<int>(b.box[1] <= a.box[4]) &
         static_cast<int>(a.box[2] <= b.box[5]) & static_cast<int>(b.box[2] <= a.box[5])) == 0)
      return;
    ++r.pairs_tested;
    // A shared vertex whose star projects one-to-one: they meet only in what they share.
    for (const std::uint32_t x : a.v)
      if (good[x] != 0 && (x == b.v[0] || x == b.v[1] || x == b.v[2])) {
        ++r.pairs_by_topology;
        return;
      }
    for (std::size_t k = 0; k < 3; ++k) p[k] = pos[a.v[k]], q[k] = pos[b.v[k]];
    if (!si::pair_intersects(p, a.v, q, b.v)) return;
    ++r.intersecting_triangle_pairs;
    const std::uint32_t f = std::min(a.face, b.face), g = std::max(a.face, b.face);
    found.push_back(static_cast<std::uint64_t>(f) << 32 | g);
    if (found.size() >= compact_at) {
      si::compact(found);
      compact_at = std::max(compact_at, 2 * found.size());
    }
  };
  // Each pair of overlapping group boxes once, so each pair of triangles in two groups once.
  const si::box_pair_count pairs =
      si::for_each_box_pair(detail::span_of(group_boxes), budget, [&](std::uint32_t i, std::uint32_t j) {
        for (std::uint32_t a = first[i]; a < first[i + 1]; ++a)
          for (std::uint32_t b = first[j]; b < first[j + 1]; ++b) test(ids[a], ids[b]);
        return true;
      });
  r.candidate_pairs = pairs.candidate_pairs;
  r.complete = pairs.complete;
  if (!r.complete) {
    // Appended piece by piece: `"..." + std::to_string(n)` trips g++ 12's false -Wrestrict
    // (GCC PR 105329) in a user's -O2 -Werror build.
    std::string message = "self_intersections: the work budget of ";
    message += std::to_string(budget);
    message += " candidate box pairs was spent after testing ";
    message += std::to_string(r.pairs_tested);
    message += " pairs of ";
    message += std::to_string(n);
    message += " triangles: the answer is partial (raise self_intersection_options::work_budget)";
    r.diagnostics.push_back(std::move(message));
  }
  si::report_pairs(r, found, options.max_reported);
  return finish();
}

}  // namespace cellforge
