// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The polyhedral skeleton of a drawing with rounds and fillets (seed 003
/// §"Rounds and fillets", stage 2): for every pair of arcs, suppress both arcs, extend the lines
/// at their ends until they meet — the meeting point is a new vertex — and join the two new
/// vertices by an edge. The result is an ordinary line drawing for drawing_to_cells; each
/// blend keeps its 2D geometry (the two end ellipses, the new edge) and whether it is a convex
/// round or a concave fillet, read from the skeleton's faces. See docs/sketch.md.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/sketch/arc_pairing.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/face_finder.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge {

/// Options of round_skeleton.
struct round_skeleton_options {
  arc_pairing_options pairing;
  /// Find the skeleton's faces to tell rounds from fillets (off: every blend's kind unknown).
  bool classify = true;
  face_finder_options faces;
};

/// Convex round, concave fillet, or not known (the skeleton's faces were not found, or its two
/// ends disagree).
enum class blend_kind : std::uint8_t { round, fillet, unknown };

/// One blend of the skeleton: the new edge and its junctions, and the 2D geometry of the round.
template <Point2 P>
struct skeleton_blend {
  std::size_t pair = 0;                      ///< index into the pairing's pairs
  std::array<std::uint32_t, 2> junctions{};  ///< the new vertices (skeleton junctions)
  std::uint32_t edge = 0;                    ///< the new edge (skeleton edge) between them
  blend_kind kind = blend_kind::unknown;
  blend_category category = blend_category::a_or_c;
  /// Each end curve as one elliptical arc (centre, semi-axes, rotation: the circle's image),
  /// from the junction on its first line to the one on its second.
  std::array<elliptical_arc<P>, 2> curves{};
  /// The new edge's drawing vector (junctions[1] − junctions[0]): the blend's axis direction in 2D.
  glm::dvec2 axis{0.0};
};

/// What round_skeleton made: the skeleton drawing, its blends, the pairing, where every
/// junction of the input went (npos when it was suppressed), the faces found (when
/// classifying), the skeleton's validation, counts, time and diagnostics.
template <Point2 P>
struct round_skeleton_result : stage_report {
  static constexpr std::uint32_t npos = ~std::uint32_t{0};
  line_drawing<P> skeleton;
  std::vector<skeleton_blend<P>> blends;
  arc_pairing_result<P> pairing;
  std::vector<std::uint32_t> junction_map;
  face_finder_result faces;
  drawing_validation validation;  ///< validate(drawing) of the skeleton
  std::size_t rounds = 0, fillets = 0, unknown = 0;
  std::size_t suppressed_junctions = 0, suppressed_lines = 0, new_junctions = 0;
};

/// The polyhedral skeleton of an arc drawing: pair_arcs, then per pair suppress its arcs, the
/// junctions between and at their ends and its contour line, move each end line's arc end to
/// the corner where the end curve's two lines meet (one new junction per end curve), and add
/// the edge between the two corners. Then, unless options.classify is off, find the skeleton's
/// faces: a blend is a round when its corner is a convex corner of the face that held its end
/// curve (the face's 2D loop, a parallel view keeping convexity), a fillet when reflex. Arcs
/// left unpaired are dropped with a diagnostic (their lines dangle: `validation` says so).
/// Throws as pair_arcs. O(pairing + V + E + face finding).
template <Point2 P>
round_skeleton_result<P> round_skeleton(const arc_drawing<P>& d, const round_skeleton_options& options = {}) {
  const detail::stopwatch t_start;
  round_skeleton_result<P> out;
  out.pairing = pair_arcs(d, options.pairing);
  const auto& pairs = out.pairing.pairs;
  const std::size_t nv = d.lines.points.size();
  constexpr std::uint32_t npos = round_skeleton_result<P>::npos;
  std::vector<bool> gone(nv, false), line_gone(d.lines.edges.size(), false);
  // Arc-end junction -> the corner (index into `corners`) its line moves to.
  std::vector<std::uint32_t> moved(nv, npos);
  std::vector<P> corners;
  for (const auto& p : pairs) {
    for (std::size_t k = 0; k < 2; ++k) {
      const auto c = static_cast<std::uint32_t>(corners.size());
      corners.push_back(p.corners[k]);
      for (const std::uint32_t j : p.ends[k]) gone[j] = true, moved[j] = c;
      for (const std::uint32_t a : p.arcs[k])
        for (const std::uint32_t j : d.arcs[a].ends) gone[j] = true;
    }
    if (p.contour != arc_pair<P>::npos) line_gone[p.contour] = true;
  }
  for (const std::uint32_t a : out.pairing.unpaired)
    out.diagnostics.push_back(
        cellforge::detail::cat("arc ", std::to_string(a), " has no partner and is left out of the skeleton"));
  out.junction_map.assign(nv, npos);
  for (std::uint32_t j = 0; j < nv; ++j)
    if (!gone[j]) {
      out.junction_map[j] = static_cast<std::uint32_t>(out.skeleton.points.size());
      out.skeleton.points.push_back(d.lines.points[j]);
    } else {
      ++out.suppressed_junctions;
    }
  const auto first_corner = static_cast<std::uint32_t>(out.skeleton.points.size());
  for (const P& c : corners) out.skeleton.points.push_back(c);
  out.new_junctions = corners.size();
  const auto map = [&](std::uint32_t j) {
    return moved[j] != npos ? first_corner + moved[j] : out.junction_map[j];
  };
  for (std::uint32_t e = 0; e < d.lines.edges.size(); ++e) {
    const auto& ln = d.lines.edges[e];
    const std::uint32_t a = map(ln[0]), b = map(ln[1]);
    if (line_gone[e] || a == npos || b == npos) {
      ++out.suppressed_lines;
      continue;
    }
    out.skeleton.edges.push_back({a, b});
  }
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    // The curves are given here: P need not be default-constructible.
    skeleton_blend<P> b{.pair = i,
                        .junctions = {first_corner + static_cast<std::uint32_t>(2 * i),
                                      first_corner + static_cast<std::uint32_t>(2 * i + 1)},
                        .edge = static_cast<std::uint32_t>(out.skeleton.edges.size()),
                        .kind = blend_kind::unknown,
                        .category = pairs[i].category,
                        .curves = pairs[i].curves,
                        .axis = to_dvec2(pairs[i].corners[1]) - to_dvec2(pairs[i].corners[0])};
    out.skeleton.edges.push_back(b.junctions);
    out.blends.push_back(std::move(b));
  }
  out.validation = validate(out.skeleton);
  if (!out.validation.ok())
    out.diagnostics.push_back(
        cellforge::detail::cat("the skeleton is not a readable drawing: ", out.validation.message));

  // Round or fillet: the corner's turn in the face loop through its two end lines.
  if (options.classify && out.validation.ok() && !out.blends.empty()) {
    out.faces = find_faces(out.skeleton, options.faces);
    std::vector<glm::dvec2> q(out.skeleton.points.size());
    for (std::size_t j = 0; j < q.size(); ++j) q[j] = to_dvec2(out.skeleton.points[j]);
    const auto corner_sign = [&](std::uint32_t c, std::uint32_t f0, std::uint32_t f1) {
      for (const auto& loop : out.faces.loops) {
        const std::size_t n = loop.size();
        for (std::size_t i = 0; i < n; ++i) {
          if (loop[i] != c) continue;
          const std::uint32_t prev = loop[(i + n - 1) % n], next = loop[(i + 1) % n];
          if (!((prev == f0 && next == f1) || (prev == f1 && next == f0))) continue;
          double area = 0;
          for (std::size_t k = 0; k < n; ++k) {
            const glm::dvec2 a = q[loop[k]], b = q[loop[(k + 1) % n]];
            area += a.x * b.y - b.x * a.y;
          }
          const glm::dvec2 u = q[c] - q[prev], v = q[next] - q[c];
          const double turn = u.x * v.y - u.y * v.x;
          return (turn > 0) == (area > 0) ? 1 : -1;
        }
      }
      return 0;
    };
    for (auto& b : out.blends) {
      const arc_pair<P>& p = pairs[b.pair];
      int votes[2] = {0, 0};
      for (std::size_t k = 0; k < 2; ++k) {
        std::array<std::uint32_t, 2> far{};
        for (std::size_t s = 0; s < 2; ++s) {
          const auto& ln = d.lines.edges[p.lines[k][s]];
          far[s] = map(ln[0] == p.ends[k][s] ? ln[1] : ln[0]);
        }
        votes[k] = corner_sign(b.junctions[k], far[0], far[1]);
      }
      if (votes[0] != 0 && votes[0] == votes[1]) {
        b.kind = votes[0] > 0 ? blend_kind::round : blend_kind::fillet;
      } else {
        out.diagnostics.push_back(cellforge::detail::cat(
            "blend ", std::to_string(b.pair),
            (votes[0] == 0 || votes[1] == 0
                 ? ": no face of the skeleton holds an end curve's corner; round or fillet "
                   "unknown"
                 : ": one end reads as a round, the other as a fillet; left unknown")));
      }
    }
  }
  for (const auto& b : out.blends)
    ++(b.kind == blend_kind::round ? out.rounds : b.kind == blend_kind::fillet ? out.fillets : out.unknown);
  out.milliseconds = t_start.ms();
  return out;
}

namespace detail {

/// A coherent orientation of face loops (junction cycles): +1 or −1 per loop, so that across
/// every edge its two loops run opposite ways (each connected set of loops starts at +1). O(L log L).
template <class = void>
std::vector<int> coherent_senses(const std::vector<std::vector<std::uint32_t>>& loops) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::size_t, bool>>> sides;
  for (std::size_t l = 0; l < loops.size(); ++l)
    for (std::size_t i = 0; i < loops[l].size(); ++i) {
      const std::uint32_t a = loops[l][i], b = loops[l][(i + 1) % loops[l].size()];
      sides[{std::min(a, b), std::max(a, b)}].push_back({l, a < b});
    }
  std::vector<int> sense(loops.size(), 0);
  for (std::size_t seed = 0; seed < loops.size(); ++seed) {
    if (sense[seed] != 0) continue;
    sense[seed] = 1;
    std::vector<std::size_t> stack{seed};
    while (!stack.empty()) {
      const std::size_t l = stack.back();
      stack.pop_back();
      for (std::size_t i = 0; i < loops[l].size(); ++i) {
        const std::uint32_t a = loops[l][i], b = loops[l][(i + 1) % loops[l].size()];
        const bool forward = a < b;
        for (const auto& [m, fwd] : sides[{std::min(a, b), std::max(a, b)}]) {
          if (m == l || sense[m] != 0) continue;
          // Run opposite: same stored direction means opposite senses.
          sense[m] = fwd == forward ? -sense[l] : sense[l];
          stack.push_back(m);
        }
      }
    }
  }
  return sense;
}

}  // namespace detail

/// Decides category a or c (and b for fillets, which have no contour line) of every blend from a
/// reading of the skeleton: depth[j] the depth of skeleton junction j, larger towards the viewer
/// (inflation's z). The skeleton's face loops (found when classifying) are oriented coherently
/// and outward (the reading's signed volume positive); a face faces the viewer when its outward
/// loop runs counter-clockwise in the drawing; a blend is a, b or c as two, one or none of the
/// faces at its new edge do. A rule-1 pair the reading does not put on the contour gets a
/// diagnostic. Throws invalid_input when depth has the wrong size or no faces were found.
/// O(L + blends · L), L the loops' total length.
template <Point2 P>
void resolve_blend_categories(round_skeleton_result<P>& r, const std::vector<double>& depth) {
  const std::size_t nv = r.skeleton.points.size();
  if (depth.size() != nv)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("resolve_blend_categories: ", std::to_string(depth.size()),
                                       " depths for ", std::to_string(nv), " skeleton junctions"));
  const auto& loops = r.faces.loops;
  if (loops.empty())
    throw error(
        error_category::invalid_input,
        "resolve_blend_categories: the skeleton has no faces (round_skeleton with classify on finds them)");
  const std::vector<int> sense = detail::coherent_senses(loops);
  std::vector<glm::dvec3> p(nv);
  for (std::size_t j = 0; j < nv; ++j) p[j] = glm::dvec3(to_dvec2(r.skeleton.points[j]), depth[j]);
  double volume = 0;
  std::vector<double> area(loops.size(), 0);
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const auto& lp = loops[l];
    for (std::size_t i = 0; i < lp.size(); ++i) {
      const glm::dvec3 a = p[lp[i]], b = p[lp[(i + 1) % lp.size()]];
      area[l] += sense[l] * (a.x * b.y - b.x * a.y);
      if (i >= 1 && i + 1 < lp.size()) volume += sense[l] * glm::dot(p[lp[0]], glm::cross(a, b));
    }
  }
  const double outward = volume < 0 ? -1.0 : 1.0;
  for (auto& b : r.blends) {
    int front = 0, faces = 0;
    for (std::size_t l = 0; l < loops.size(); ++l) {
      const auto& lp = loops[l];
      bool has = false;
      for (std::size_t i = 0; i < lp.size() && !has; ++i) {
        const std::uint32_t u = lp[i], v = lp[(i + 1) % lp.size()];
        has = (u == b.junctions[0] && v == b.junctions[1]) || (u == b.junctions[1] && v == b.junctions[0]);
      }
      if (!has) continue;
      ++faces;
      front += outward * area[l] > 0;
    }
    if (faces != 2) {
      r.diagnostics.push_back(cellforge::detail::cat("blend ", std::to_string(b.pair), ": its edge is on ",
                                                     std::to_string(faces),
                                                     " faces, not two; category left as it was"));
      continue;
    }
    const blend_category c = front == 2   ? blend_category::a
                             : front == 1 ? blend_category::b
                                          : blend_category::c;
    if (b.category == blend_category::b && c != blend_category::b)
      r.diagnostics.push_back(
          cellforge::detail::cat("blend ", std::to_string(b.pair),
                                 " has a contour line but the reading does not put it on the contour"));
    else
      b.category = c;
  }
}

}  // namespace cellforge
