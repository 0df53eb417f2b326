// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Strokes to junctions, shared by the drawing readers (SVG, DXF): straight segments and
/// elliptical arcs in the drawing's y-up frame, their ends snapped into junctions, strokes split
/// where a junction lies on them, duplicates merged, into an arc_drawing.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/union_find.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/sketch/detail/drawing_grid.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge::io::detail {

/// An elliptical arc stroke in endpoint form in the drawing's y-up frame, before snapping.
struct stroke_arc {
  glm::dvec2 from, to;
  double rx, ry, rotation;  // rotation in radians
  bool large, ccw;
};

/// A 2D affine map (x, y) -> (a x + c y + e, b x + d y + f).
struct affine2 {
  double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;
  glm::dvec2 operator()(glm::dvec2 p) const { return {a * p.x + c * p.y + e, b * p.x + d * p.y + f}; }
  /// This map after `m` (this ∘ m).
  affine2 then(const affine2& m) const {
    return {a * m.a + c * m.b, b * m.a + d * m.b,     a * m.c + c * m.d,
            b * m.c + d * m.d, a * m.e + c * m.f + e, b * m.e + d * m.f + f};
  }
  bool linear_identity() const { return a == 1 && b == 0 && c == 0 && d == 1; }
};

/// Carries the ellipse (rx, ry, rotation in radians) through m's linear part; a reflection
/// flips `sense` (the sweep's direction). False when m flattens the ellipse or overflows. O(1).
template <class = void>
bool map_ellipse(const affine2& m, double& rx, double& ry, double& rotation, bool& sense) {
  if (m.linear_identity()) return true;
  // The ellipse's axes under the linear part A of m: the singular values and left singular
  // vectors of L = A R(rotation) diag(rx, ry), from L Lᵀ.
  const double cs = std::cos(rotation), sn = std::sin(rotation);
  const double l00 = (m.a * cs + m.c * sn) * rx, l01 = (-m.a * sn + m.c * cs) * ry;
  const double l10 = (m.b * cs + m.d * sn) * rx, l11 = (-m.b * sn + m.d * cs) * ry;
  const double pp = l00 * l00 + l01 * l01, rr = l10 * l10 + l11 * l11, pq = l00 * l10 + l01 * l11;
  const double det = l00 * l11 - l01 * l10;
  const double s1 = std::sqrt((pp + rr) / 2 + std::hypot((pp - rr) / 2, pq));
  if (!std::isfinite(s1) || !(std::abs(det) / s1 > 0) || !std::isfinite(det)) return false;
  rx = s1;
  ry = std::abs(det) / s1;
  rotation = 0.5 * std::atan2(2 * pq, pp - rr);
  if (m.a * m.d - m.b * m.c < 0) sense = !sense;
  return true;
}

/// What snap_strokes did, for the readers' result counts.
struct stroke_snap_counts {
  std::size_t snapped = 0;              ///< stroke ends moved onto a junction
  std::size_t dropped_zero_length = 0;  ///< strokes whose ends snapped to one junction
  std::size_t merged_duplicates = 0;    ///< edges drawn twice (after splitting), kept once
  std::size_t split_at_junctions = 0;   ///< junctions that split a stroke's interior
};

/// Cluster mean of points by index list without rounding drift: exact for equal points. O(k).
template <class = void>
glm::dvec2 cluster_mean(const std::vector<glm::dvec2>& pts, const std::vector<std::uint32_t>& members) {
  // Offsets divided before they are summed, so that far-apart members cannot overflow.
  const glm::dvec2 base = pts[members[0]];
  const double k = static_cast<double>(members.size());
  glm::dvec2 sum{0, 0};
  for (const std::uint32_t i : members) sum += pts[i] / k - base / k;
  return base + sum;
}

/// Snaps the ends of segments and arcs (y-up) closer than snap_tolerance × the bounding-box
/// diagonal into junctions (numbered by first appearance), splits segments at junctions on their
/// interior when `split`, drops zero-length strokes and merges duplicate edges. `arc_line(k)`
/// gives the source line of arc k for messages; io errors are located in `name` there.
/// O(S log S + K), K the pairs sharing a cell of the snapping grids.
template <Point2 P2, class ArcLine>
arc_drawing<P2> snap_strokes(const std::vector<std::pair<glm::dvec2, glm::dvec2>>& segments,
                             const std::vector<stroke_arc>& arc_strokes, double snap_tolerance, bool split,
                             std::string_view name, ArcLine&& arc_line, stroke_snap_counts& counts,
                             std::vector<std::string>& diagnostics) {
  const std::size_t ns = segments.size(), na = arc_strokes.size();
  arc_drawing<P2> result;
  if (2 * (ns + na) >= std::numeric_limits<std::uint32_t>::max())
    throw error(error_category::io, "too many segments for 32-bit indices",
                source_location{std::string(name), 0});
  if (ns + na == 0) return result;
  const auto fail = [&](std::size_t k, const std::string& message) {
    throw error(error_category::io, message, source_location{std::string(name), arc_line(k)});
  };
  // Stroke ends: the segments', then the arcs'.
  std::vector<glm::dvec2> ends(2 * (ns + na));
  for (std::size_t s = 0; s < ns; ++s) {
    ends[2 * s] = segments[s].first;
    ends[2 * s + 1] = segments[s].second;
  }
  for (std::size_t k = 0; k < na; ++k) {
    ends[2 * (ns + k)] = arc_strokes[k].from;
    ends[2 * (ns + k) + 1] = arc_strokes[k].to;
  }
  const cellforge::detail::drawing_frame frame = cellforge::detail::make_drawing_frame(ends);
  const double eps = snap_tolerance * frame.diag;
  cellforge::detail::union_find uf(2 * (ns + na));
  cellforge::detail::for_close_points(frame.points, eps,
                                      [&](std::uint32_t i, std::uint32_t j) { uf.unite(i, j); });
  // Clusters numbered by first appearance (the union-find keeps the smallest index as root).
  constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> cluster(2 * (ns + na), none), junction_of(2 * (ns + na));
  std::vector<std::vector<std::uint32_t>> members;
  for (std::uint32_t i = 0; i < 2 * (ns + na); ++i) {
    const std::uint32_t root = uf.find(i);
    if (cluster[root] == none) {
      cluster[root] = static_cast<std::uint32_t>(members.size());
      members.emplace_back();
    }
    junction_of[i] = cluster[root];
    members[cluster[root]].push_back(i);
  }
  const std::size_t nj = members.size();
  std::vector<glm::dvec2> at(nj), at_frame(nj);
  for (std::size_t j = 0; j < nj; ++j) {
    at[j] = cluster_mean(ends, members[j]);
    at_frame[j] = cluster_mean(frame.points, members[j]);
    glm::dvec2 lo = at_frame[j], hi = at_frame[j];
    for (const std::uint32_t i : members[j]) {
      if (ends[i] != at[j]) ++counts.snapped;
      lo = glm::min(lo, frame.points[i]);
      hi = glm::max(hi, frame.points[i]);
    }
    if (glm::length(hi - lo) > eps && diagnostics.size() < 100)
      diagnostics.push_back(cellforge::detail::cat(
          std::string(name), ": junction at ", cellforge::detail::drawing_point_text(at[j]),
          " gathers a chain of ", std::to_string(members[j].size()),
          " close stroke ends wider than the snap distance: check the drawing there"));
  }
  // Edges between junctions; zero-length ones dropped.
  std::vector<std::array<std::uint32_t, 2>> edges;
  edges.reserve(ns);
  for (std::size_t s = 0; s < ns; ++s) {
    const std::uint32_t a = junction_of[2 * s], b = junction_of[2 * s + 1];
    if (a == b)
      ++counts.dropped_zero_length;
    else
      edges.push_back({a, b});
  }
  // Arcs whose ends snapped together are dropped (a closed curve is no round or fillet).
  std::vector<std::array<std::uint32_t, 2>> arc_ends;
  std::vector<std::size_t> arc_piece;
  for (std::size_t k = 0; k < na; ++k) {
    const std::uint32_t a = junction_of[2 * (ns + k)], b = junction_of[2 * (ns + k) + 1];
    if (a == b) {
      ++counts.dropped_zero_length;
      diagnostics.push_back(cellforge::detail::cat(
          std::string(name), ":", std::to_string(arc_line(k)),
          ": an arc whose ends snapped to one junction: left out (a closed curve is no round)"));
    } else {
      arc_ends.push_back({a, b});
      arc_piece.push_back(k);
    }
  }
  // Splits: junctions on an edge's interior (within eps, projecting strictly inside it).
  if (split && !edges.empty()) {
    std::vector<std::pair<glm::dvec2, glm::dvec2>> segs(edges.size());
    for (std::size_t e = 0; e < edges.size(); ++e) segs[e] = {at_frame[edges[e][0]], at_frame[edges[e][1]]};
    std::vector<std::tuple<std::uint32_t, double, std::uint32_t>> cuts;  // (edge, t, junction)
    cellforge::detail::for_grid_neighbours(
        segs, at_frame, eps, [](std::size_t, std::size_t) {},
        [&](std::size_t e, std::size_t j) {
          if (j == edges[e][0] || j == edges[e][1]) return;
          const glm::dvec2 a = segs[e].first, d = segs[e].second - a;
          const double t = glm::dot(at_frame[j] - a, d) / glm::dot(d, d);
          if (t > 0 && t < 1 && glm::length(at_frame[j] - (a + t * d)) <= eps)
            cuts.emplace_back(static_cast<std::uint32_t>(e), t, static_cast<std::uint32_t>(j));
        });
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    std::vector<std::array<std::uint32_t, 2>> pieces;
    pieces.reserve(edges.size() + cuts.size());
    std::size_t k = 0;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      std::uint32_t from = edges[e][0];
      for (; k < cuts.size() && std::get<0>(cuts[k]) == e; ++k) {
        const std::uint32_t j = std::get<2>(cuts[k]);
        if (j == from) continue;
        pieces.push_back({from, j});
        from = j;
        ++counts.split_at_junctions;
      }
      if (from != edges[e][1]) pieces.push_back({from, edges[e][1]});
    }
    edges = std::move(pieces);
  }
  // Duplicates merged (first kept), then unused junctions dropped, order kept.
  std::vector<std::array<std::uint32_t, 3>> keys(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
    keys[e] = {std::min(edges[e][0], edges[e][1]), std::max(edges[e][0], edges[e][1]),
               static_cast<std::uint32_t>(e)};
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint8_t> keep(edges.size(), 1);
  for (std::size_t q = 1; q < keys.size(); ++q)
    if (keys[q][0] == keys[q - 1][0] && keys[q][1] == keys[q - 1][1])
      keep[keys[q][2]] = 0, ++counts.merged_duplicates;
  std::vector<std::uint32_t> renumber(nj, none);
  auto& d = result.lines;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (!keep[e]) continue;
    for (const std::uint32_t j : edges[e])
      if (renumber[j] == none) renumber[j] = 0;
  }
  for (const auto& [a, b] : arc_ends) renumber[a] = renumber[b] = 0;
  for (std::size_t j = 0; j < nj; ++j)
    if (renumber[j] != none) {
      renumber[j] = static_cast<std::uint32_t>(d.points.size());
      d.points.push_back(from_dvec2<P2>(at[j]));
    }
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (keep[e]) d.edges.push_back({renumber[edges[e][0]], renumber[edges[e][1]]});
  // Arcs between their snapped junctions.
  for (std::size_t k = 0; k < arc_ends.size(); ++k) {
    const stroke_arc& piece = arc_strokes[arc_piece[k]];
    const std::array<std::uint32_t, 2> je{renumber[arc_ends[k][0]], renumber[arc_ends[k][1]]};
    try {
      result.arcs.push_back({je, arc_from_endpoints<P2>({d.points[je[0]], d.points[je[1]], piece.rx, piece.ry,
                                                         piece.rotation, piece.large, piece.ccw})});
    } catch (const error& e) {
      fail(arc_piece[k],
           cellforge::detail::cat("an arc between the junctions at ",
                                  cellforge::detail::drawing_point_text(d.points[je[0]]), " and ",
                                  cellforge::detail::drawing_point_text(d.points[je[1]]), ": ", e.message()));
    }
  }
  // With radii far beyond the distance of the ends, rounding can leave the curve off its
  // junctions: refused here rather than by every later stage.
  if (const arc_validation v = validate(result); !v)
    fail(arc_piece[v.arc], cellforge::detail::cat("an arc out of proportion to its ends: ", v.message));
  return result;
}

}  // namespace cellforge::io::detail
