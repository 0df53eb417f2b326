// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Pairing the arcs of a drawing into rounds and fillets (seed 003
/// §"Rounds and fillets", step 2 of detection): arcs of one ellipse meeting end to end are one
/// end curve; two end curves are the two ends of one blend when (rule 1) a contour line is
/// tangent to both, or else (rule 2) they are translates of each other — in parallel faces, of
/// the same size and orientation — with mutually parallel lines at their ends. Each end
/// curve's two lines, extended, meet at the skeleton's vertex. See docs/sketch.md.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/union_find.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/sketch/detail/parallel.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge {

/// Options of pair_arcs.
struct arc_pairing_options {
  /// Centres, semi-axes and ends agree within this fraction of the drawing's diagonal.
  double tolerance = 1e-4;
  /// Lines are parallel, a contour line tangent, rotations equal within this angle (radians).
  double angle_tolerance = 1e-3;
  /// Arc ends lie on their junctions within this fraction of the diagonal (validate(arc_drawing)), raised
  /// to 64 ε for float points; a drawing typed or snapped to a few decimals needs more.
  double end_tolerance = 1e-9;
  /// Largest group of mutually congruent end curves matched exactly (by the least total
  /// distance); a larger group is matched greedily, nearest first, with a diagnostic.
  std::size_t exact_group = 14;
};

/// Which of the seed's two rules paired two end curves.
enum class pairing_rule : std::uint8_t {
  contour_line,    ///< rule 1: a contour line tangent to both
  parallel_lines,  ///< rule 2: translates of each other, with mutually parallel lines at their ends
};

/// One blend found: its two end curves, each one or more arcs of one ellipse.
template <Point2 P>
struct arc_pair {
  static constexpr std::uint32_t npos = ~std::uint32_t{0};
  std::array<std::vector<std::uint32_t>, 2> arcs;  ///< each end curve's arcs, from ends[k][0] to ends[k][1]
  std::array<std::array<std::uint32_t, 2>, 2>
      ends{};  ///< end junctions; ends[1][j] is the translate of ends[0][j]
  std::array<std::array<std::uint32_t, 2>, 2> lines{};  ///< the straight line at each end junction
  std::array<P, 2> corners{};  ///< where each end curve's two lines meet, extended: the skeleton's vertices
  std::array<elliptical_arc<P>, 2> curves{};  ///< each end curve as one arc, from ends[k][0] to ends[k][1]
  pairing_rule rule = pairing_rule::parallel_lines;
  /// b for rule 1 (a round on the contour); a_or_c for rule 2: in a wireframe drawing a and c
  /// are the two Necker readings of one drawing, told apart only by a reading (docs/sketch.md).
  blend_category category = blend_category::a_or_c;
  std::uint32_t contour = npos;  ///< the contour line (rule 1)
};

/// What pair_arcs found: the pairs, the arcs left unpaired (each with a diagnostic), counts and
/// the time.
template <Point2 P>
struct arc_pairing_result : stage_report {
  std::vector<arc_pair<P>> pairs;
  std::vector<std::uint32_t> unpaired;  ///< arcs in no pair
  std::size_t arcs = 0, curves = 0;     ///< arcs read, end curves they make
  std::size_t by_contour = 0, by_parallel_lines = 0, unpaired_curves = 0;
};

namespace detail::pairing {

/// An end curve: arcs of one ellipse in a chain, its end junctions, their lines and corner.
struct chain {
  std::vector<std::uint32_t> arcs;
  std::array<std::uint32_t, 2> ends{};
  std::vector<std::uint32_t> inner;      ///< junctions between its arcs
  std::array<std::uint32_t, 2> lines{};  ///< the straight line at each end
  glm::dvec2 centre{0.0};
  double rx = 0, ry = 0, rotation = 0;  ///< rx >= ry, rotation in [0, π)
  double start = 0, sweep = 0;          ///< the whole curve in the first arc's parametrisation
  glm::dvec2 corner{0.0};
  bool usable = true;
  bool paired = false;
};

/// An arc's ellipse with rx >= ry and its rotation in [0, π). O(1).
template <Point2 P>
void normalised_shape(const elliptical_arc<P>& a, double& rx, double& ry, double& rotation) {
  rx = a.rx, ry = a.ry, rotation = a.rotation;
  if (ry > rx) std::swap(rx, ry), rotation += std::numbers::pi / 2;
  rotation = std::fmod(rotation, std::numbers::pi);
  if (rotation < 0) rotation += std::numbers::pi;
}

/// Whether two ellipses have the same shape and orientation (centres not compared). O(1).
template <class = void>
bool same_shape(const chain& a, const chain& b, double tol, double angle) {
  if (std::abs(a.rx - b.rx) > tol || std::abs(a.ry - b.ry) > tol) return false;
  if (a.rx - a.ry <= tol) return true;  // a circle: any rotation
  double d = std::abs(a.rotation - b.rotation);
  d = std::min(d, std::numbers::pi - d);
  return d <= angle * std::max(1.0, a.rx / (a.rx - a.ry));
}

/// The unit direction of line e, from its first junction to its second. O(1).
template <class = void>
glm::dvec2 line_direction(const std::vector<glm::dvec2>& q, const std::array<std::uint32_t, 2>& e) {
  return glm::normalize(q[e[1]] - q[e[0]]);
}

/// Whether directions u and v are parallel (either way) within `angle` radians. O(1).
template <class = void>
bool parallel(glm::dvec2 u, glm::dvec2 v, double angle) {
  return sketch::parallel_within(u, v, std::sin(std::min(angle, std::numbers::pi / 2)));
}

}  // namespace detail::pairing

/// Pairs the arcs of `d` into blends by the seed's two rules, in order: end curves (arcs of one
/// ellipse meeting end to end, each end on exactly one straight line) sharing a tangent contour
/// line; then, among the rest, end curves that are translates of each other (same semi-axes and
/// rotation, ends moved by the centres' difference) with parallel lines at corresponding ends and
/// the new edge along neither, matched with the most pairs, then the fewest new edges parallel to no straight
/// line of the drawing, then the least total distance between partners. Throws invalid_input when an arc is
/// not valid (validate(arc_drawing) to end_tolerance of the size, 64 ε for float points: a zero radius, ends
/// not on the curve, ...) or a line names a junction that does not exist; an arc that cannot be paired is
/// reported in `unpaired` and a diagnostic. O(V + E + A² + groups' matchings), a group of g congruent curves
/// costing up to the number of matchings of g (exact_group bounds it).
template <Point2 P>
arc_pairing_result<P> pair_arcs(const arc_drawing<P>& d, const arc_pairing_options& options = {}) {
  using detail::pairing::chain;
  const detail::stopwatch t_start;
  arc_pairing_result<P> out;
  // Arc ends on their junctions to end_tolerance of the size (or the point type's own precision).
  if (const arc_validation v = validate(d, {options.end_tolerance}); !v.ok())
    throw error(error_category::invalid_input, cellforge::detail::cat("pair_arcs: ", v.message));
  const std::size_t nv = d.lines.points.size(), na = d.arcs.size();
  for (std::size_t e = 0; e < d.lines.edges.size(); ++e)
    for (const std::uint32_t j : d.lines.edges[e])
      if (j >= nv)
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("pair_arcs: line ", std::to_string(e), " names junction ",
                                           std::to_string(j), ", of ", std::to_string(nv)));
  out.arcs = na;
  std::vector<glm::dvec2> q(nv);
  glm::dvec2 lo(0), hi(0);
  for (std::size_t i = 0; i < nv; ++i) {
    q[i] = to_dvec2(d.lines.points[i]);
    lo = i == 0 ? q[i] : glm::min(lo, q[i]);
    hi = i == 0 ? q[i] : glm::max(hi, q[i]);
  }
  const double size = glm::length(hi - lo), tol = options.tolerance * size, ang = options.angle_tolerance;
  std::vector<std::vector<std::uint32_t>> lines_at(nv), arcs_at(nv);
  for (std::uint32_t e = 0; e < d.lines.edges.size(); ++e)
    for (const std::uint32_t j : d.lines.edges[e]) lines_at[j].push_back(e);
  for (std::uint32_t a = 0; a < na; ++a)
    for (const std::uint32_t j : d.arcs[a].ends) arcs_at[j].push_back(a);
  const auto arc_names = [&](const std::vector<std::uint32_t>& arcs) {
    std::string s = arcs.size() == 1 ? "arc " : "arcs ";
    for (std::size_t k = 0; k < arcs.size(); ++k) s += (k ? ", " : "") + std::to_string(arcs[k]);
    return s;
  };

  // End curves: arcs of one ellipse meeting at a junction of two arcs.
  std::vector<chain> shapes(na);
  for (std::uint32_t a = 0; a < na; ++a) {
    chain& c = shapes[a];
    c.centre = to_dvec2(d.arcs[a].curve.centre);
    detail::pairing::normalised_shape(d.arcs[a].curve, c.rx, c.ry, c.rotation);
  }
  detail::union_find groups(na);
  for (std::uint32_t j = 0; j < nv; ++j)
    if (arcs_at[j].size() == 2 && lines_at[j].size() <= 1) {
      const std::uint32_t a = arcs_at[j][0], b = arcs_at[j][1];
      if (a != b && glm::length(shapes[a].centre - shapes[b].centre) <= tol &&
          detail::pairing::same_shape(shapes[a], shapes[b], tol, ang))
        groups.unite(a, b);
    }
  std::vector<chain> chains;
  std::vector<std::uint32_t> chain_of(na, ~std::uint32_t{0});
  for (std::uint32_t a = 0; a < na; ++a) {
    if (chain_of[a] != ~std::uint32_t{0}) continue;
    std::vector<std::uint32_t> members;
    for (std::uint32_t b = a; b < na; ++b)
      if (groups.find(b) == groups.find(a)) members.push_back(b);
    // The chain's ends: junctions met by one of its arcs only.
    std::vector<std::uint32_t> ends;
    for (const std::uint32_t m : members)
      for (const std::uint32_t j : d.arcs[m].ends) {
        std::size_t count = 0;
        for (const std::uint32_t o : arcs_at[j]) count += groups.find(o) == groups.find(a);
        if (count == 1) ends.push_back(j);
      }
    chain c;
    const auto index = static_cast<std::uint32_t>(chains.size());
    for (const std::uint32_t m : members) chain_of[m] = index;
    if (ends.size() != 2) {
      c.arcs = members;
      c.usable = false;
      out.diagnostics.push_back(arc_names(members) +
                                ": the arcs of one ellipse close up or branch; a round's end "
                                "curve is one open arc");
      chains.push_back(std::move(c));
      continue;
    }
    // Walk from one end, arc by arc.
    std::uint32_t at = ends[0];
    double total = 0, dir = 0;
    std::vector<bool> done(members.size(), false);
    for (std::size_t step = 0; step < members.size(); ++step) {
      std::size_t k = 0;
      while (k < members.size() &&
             (done[k] || (d.arcs[members[k]].ends[0] != at && d.arcs[members[k]].ends[1] != at)))
        ++k;
      if (k == members.size()) break;
      done[k] = true;
      const drawing_arc<P>& arc = d.arcs[members[k]];
      const bool forward = arc.ends[0] == at;
      if (step == 0) {
        dir = (forward ? 1.0 : -1.0) * (arc.curve.sweep > 0 ? 1.0 : -1.0);
        c.start = forward ? arc.curve.start : arc.curve.start + arc.curve.sweep;
        c.centre = to_dvec2(arc.curve.centre);
        c.rx = arc.curve.rx, c.ry = arc.curve.ry, c.rotation = arc.curve.rotation;
      } else {
        c.inner.push_back(at);
      }
      c.arcs.push_back(members[k]);
      total += std::abs(arc.curve.sweep);
      at = forward ? arc.ends[1] : arc.ends[0];
    }
    c.sweep = dir * total;
    c.ends = {ends[0], at};
    const elliptical_arc<P>& first = d.arcs[c.arcs[0]].curve;
    detail::pairing::normalised_shape(first, c.rx, c.ry, c.rotation);
    c.rotation = first.rotation;  // the parametrisation stays the first arc's
    c.rx = first.rx, c.ry = first.ry;
    for (int k = 0; k < 2 && c.usable; ++k) {
      const std::uint32_t j = c.ends[static_cast<std::size_t>(k)];
      if (lines_at[j].size() != 1 || arcs_at[j].size() != 1) {
        c.usable = false;
        out.diagnostics.push_back(arc_names(c.arcs) + ": end junction " + std::to_string(j) + " is on " +
                                  std::to_string(lines_at[j].size()) + " straight lines and " +
                                  std::to_string(arcs_at[j].size()) +
                                  " arcs; a round's end curve ends where one straight line goes on");
      } else {
        c.lines[static_cast<std::size_t>(k)] = lines_at[j][0];
      }
    }
    if (c.usable) {
      // The corner: the two end lines extended until they meet.
      const auto far = [&](int k) {
        const auto& e = d.lines.edges[c.lines[static_cast<std::size_t>(k)]];
        return q[e[0] == c.ends[static_cast<std::size_t>(k)] ? e[1] : e[0]];
      };
      const glm::dvec2 a0 = q[c.ends[0]], u = a0 - far(0), a1 = q[c.ends[1]], v = a1 - far(1);
      const double den = u.x * v.y - u.y * v.x;
      if (std::abs(den) <= ang * glm::length(u) * glm::length(v)) {
        c.usable = false;
        out.diagnostics.push_back(arc_names(c.arcs) + ": the lines at its ends are parallel and never meet");
      } else {
        const double s = ((a1 - a0).x * v.y - (a1 - a0).y * v.x) / den;
        c.corner = a0 + s * u;
      }
    }
    chains.push_back(std::move(c));
  }
  out.curves = chains.size();

  // Whether chain b is chain a moved by the difference of their centres (same shape), and how
  // their ends correspond (true: crossed), with parallel lines at corresponding ends.
  const auto congruent = [&](const chain& a, const chain& b, bool& crossed) {
    chain sa = a, sb = b;
    detail::pairing::normalised_shape(elliptical_arc<glm::dvec2>{a.centre, a.rx, a.ry, a.rotation, 0, 1},
                                      sa.rx, sa.ry, sa.rotation);
    detail::pairing::normalised_shape(elliptical_arc<glm::dvec2>{b.centre, b.rx, b.ry, b.rotation, 0, 1},
                                      sb.rx, sb.ry, sb.rotation);
    if (!detail::pairing::same_shape(sa, sb, tol, ang)) return false;
    const glm::dvec2 t = b.centre - a.centre;
    for (const bool cross : {false, true}) {
      bool ok = true;
      for (std::size_t k = 0; k < 2 && ok; ++k) {
        const std::size_t m = cross ? 1 - k : k;
        ok = glm::length(q[a.ends[k]] + t - q[b.ends[m]]) <= tol &&
             detail::pairing::parallel(detail::pairing::line_direction(q, d.lines.edges[a.lines[k]]),
                                       detail::pairing::line_direction(q, d.lines.edges[b.lines[m]]), ang);
      }
      if (ok) {
        crossed = cross;
        return true;
      }
    }
    return false;
  };
  const auto make_pair = [&](std::uint32_t i, std::uint32_t k, bool crossed, pairing_rule rule) {
    chain& a = chains[i];
    chain& b = chains[k];
    a.paired = b.paired = true;
    // Every member holding a P is given here: P need not be default-constructible.
    arc_pair<P> p{
        .arcs = {a.arcs, b.arcs},
        .ends = {a.ends, b.ends},
        .lines = {a.lines, b.lines},
        .corners = {from_dvec2<P>(a.corner), from_dvec2<P>(b.corner)},
        .curves = {elliptical_arc<P>{from_dvec2<P>(a.centre), a.rx, a.ry, a.rotation, a.start, a.sweep},
                   elliptical_arc<P>{from_dvec2<P>(b.centre), b.rx, b.ry, b.rotation, b.start, b.sweep}},
        .rule = rule,
        .category = rule == pairing_rule::contour_line ? blend_category::b : blend_category::a_or_c,
    };
    if (crossed) {
      std::reverse(p.arcs[1].begin(), p.arcs[1].end());
      std::swap(p.ends[1][0], p.ends[1][1]);
      std::swap(p.lines[1][0], p.lines[1][1]);
      p.curves[1].start += p.curves[1].sweep;
      p.curves[1].sweep = -p.curves[1].sweep;
    }
    out.pairs.push_back(std::move(p));
    return &out.pairs.back();
  };

  // Rule 1: a straight line between inner junctions of two end curves, tangent to both.
  std::vector<std::uint32_t> inner_of(nv, ~std::uint32_t{0});
  for (std::uint32_t c = 0; c < chains.size(); ++c)
    for (const std::uint32_t j : chains[c].inner) inner_of[j] = c;
  const auto tangent_at = [&](const chain& c, glm::dvec2 p) {
    const double co = std::cos(c.rotation), si = std::sin(c.rotation);
    const glm::dvec2 r = p - c.centre, l(co * r.x + si * r.y, -si * r.x + co * r.y);
    const double t = std::atan2(l.y / c.ry, l.x / c.rx);
    const glm::dvec2 dl(-c.rx * std::sin(t), c.ry * std::cos(t));
    return glm::normalize(glm::dvec2(co * dl.x - si * dl.y, si * dl.x + co * dl.y));
  };
  for (std::uint32_t e = 0; e < d.lines.edges.size(); ++e) {
    const auto& ln = d.lines.edges[e];
    const std::uint32_t ca = inner_of[ln[0]], cb = inner_of[ln[1]];
    if (ca == ~std::uint32_t{0} && cb == ~std::uint32_t{0}) continue;
    const std::string what =
        cellforge::detail::cat("line ", std::to_string(e), " (junctions ", std::to_string(ln[0]), " and ",
                               std::to_string(ln[1]), ")");
    if (ca == ~std::uint32_t{0} || cb == ~std::uint32_t{0} || ca == cb) {
      out.diagnostics.push_back(what +
                                " leaves an arc's interior but does not join two end curves: not a contour "
                                "line");
      continue;
    }
    chain& a = chains[ca];
    chain& b = chains[cb];
    const glm::dvec2 dir = detail::pairing::line_direction(q, ln);
    bool crossed = false;
    if (!a.usable || !b.usable || a.paired || b.paired) continue;
    if (!detail::pairing::parallel(dir, tangent_at(a, q[ln[0]]), ang) ||
        !detail::pairing::parallel(dir, tangent_at(b, q[ln[1]]), ang)) {
      out.diagnostics.push_back(what + " joins " + arc_names(a.arcs) + " and " + arc_names(b.arcs) +
                                " but is not tangent to both: not a contour line");
      continue;
    }
    if (!congruent(a, b, crossed)) {
      out.diagnostics.push_back(what + " is tangent to " + arc_names(a.arcs) + " and " + arc_names(b.arcs) +
                                ", which are not translates of each other (not in parallel faces, or not one "
                                "round's ends)");
      continue;
    }
    make_pair(ca, cb, crossed, pairing_rule::contour_line)->contour = e;
    ++out.by_contour;
  }

  // Rule 2: congruent end curves with parallel lines, least total distance per group.
  std::vector<std::uint32_t> open;
  for (std::uint32_t c = 0; c < chains.size(); ++c)
    if (chains[c].usable && !chains[c].paired) open.push_back(c);
  const std::size_t no = open.size();
  std::vector<std::vector<std::pair<std::uint32_t, bool>>> compatible(no);
  detail::union_find comp(no);
  for (std::uint32_t i = 0; i < no; ++i)
    for (std::uint32_t k = i + 1; k < no; ++k) {
      bool crossed = false;
      // The new edge may not run along a line at its own corner: the skeleton would have
      // collinear edges at a vertex (two corners on one line, e.g. along a shared side).
      const chain& a = chains[open[i]];
      const glm::dvec2 t = chains[open[k]].centre - a.centre;
      bool along = !(glm::length(t) > 0);
      for (std::size_t s = 0; s < 2 && !along; ++s)
        along = detail::pairing::parallel(detail::pairing::line_direction(q, d.lines.edges[a.lines[s]]),
                                          t / glm::length(t), ang);
      if (!along && congruent(a, chains[open[k]], crossed)) {
        compatible[i].push_back({k, crossed});
        comp.unite(i, k);
      }
    }
  // A pair's cost: the distance between the partners, plus a penalty that outweighs any sum of
  // distances when the new edge would be parallel to no straight line of the drawing (an
  // edge of a polyhedron mostly is: the other sides of its faces, a round's contour line).
  std::vector<glm::dvec2> directions;
  for (const auto& ln : d.lines.edges)
    if (q[ln[0]] != q[ln[1]]) directions.push_back(detail::pairing::line_direction(q, ln));
  const auto dist = [&](std::uint32_t i, std::uint32_t k) {
    const glm::dvec2 t = chains[open[k]].centre - chains[open[i]].centre;
    const double len = glm::length(t);
    bool supported = false;
    for (std::size_t e = 0; e < directions.size() && !supported && len > 0; ++e)
      supported = detail::pairing::parallel(directions[e], t / len, ang);
    return len + (supported ? 0.0 : 1000 * size);
  };
  std::vector<bool> grouped(no, false);
  for (std::uint32_t root = 0; root < no; ++root) {
    if (grouped[root]) continue;
    std::vector<std::uint32_t> g;
    for (std::uint32_t i = 0; i < no; ++i)
      if (comp.find(i) == comp.find(root)) g.push_back(i), grouped[i] = true;
    if (g.size() < 2) continue;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> best, cur;
    std::size_t best_pairs = 0;
    double best_cost = std::numeric_limits<double>::infinity();
    std::vector<bool> taken(no, false);
    if (g.size() <= options.exact_group) {
      // Most pairs first, then the fewest new edges parallel to no line, then least total
      // distance: every matching of the group.
      const auto search = [&](auto&& self, std::size_t at, double cost) -> void {
        while (at < g.size() && taken[g[at]]) ++at;
        if (at == g.size()) {
          if (cur.size() > best_pairs || (cur.size() == best_pairs && cost < best_cost))
            best = cur, best_pairs = cur.size(), best_cost = cost;
          return;
        }
        const std::uint32_t i = g[at];
        taken[i] = true;
        for (const auto& [k, crossed] : compatible[i])
          if (!taken[k]) {
            (void)crossed;
            taken[k] = true;
            cur.push_back({i, k});
            self(self, at + 1, cost + dist(i, k));
            cur.pop_back();
            taken[k] = false;
          }
        self(self, at + 1, cost);  // i unpaired
        taken[i] = false;
      };
      search(search, 0, 0.0);
    } else {
      std::vector<std::pair<double, std::pair<std::uint32_t, std::uint32_t>>> all;
      for (const std::uint32_t i : g)
        for (const auto& [k, crossed] : compatible[i]) all.push_back({dist(i, k), {i, k}}), (void)crossed;
      std::sort(all.begin(), all.end());
      for (const auto& [cost, ik] : all)
        if (!taken[ik.first] && !taken[ik.second])
          taken[ik.first] = taken[ik.second] = true, best.push_back(ik);
      out.diagnostics.push_back(std::to_string(g.size()) +
                                " congruent end curves matched nearest first (more than "
                                "exact_group = " +
                                std::to_string(options.exact_group) + ")");
    }
    for (const auto& [i, k] : best) {
      bool crossed = false;
      for (const auto& [kk, cr] : compatible[i])
        if (kk == k) crossed = cr;
      make_pair(open[i], open[k], crossed, pairing_rule::parallel_lines);
      ++out.by_parallel_lines;
    }
  }
  for (std::uint32_t c = 0; c < chains.size(); ++c) {
    if (chains[c].paired) continue;
    ++out.unpaired_curves;
    for (const std::uint32_t a : chains[c].arcs) out.unpaired.push_back(a);
    if (!chains[c].usable) continue;  // its diagnostic says why
    bool any = false;
    for (std::uint32_t o = 0; o < chains.size() && !any; ++o) {
      bool crossed = false;
      any = o != c && chains[o].usable && congruent(chains[c], chains[o], crossed);
    }
    out.diagnostics.push_back(
        arc_names(chains[c].arcs) + " (junctions " + std::to_string(chains[c].ends[0]) + " to " +
        std::to_string(chains[c].ends[1]) + ") has no partner: " +
        (any ? std::string("the arcs congruent to it were paired with nearer ones")
             : std::string(
                   "no other arc has its size and orientation at a translate of its ends with parallel "
                   "lines there (a round's two arcs lie in parallel faces)")));
  }
  std::sort(out.unpaired.begin(), out.unpaired.end());
  out.milliseconds = t_start.ms();
  return out;
}

}  // namespace cellforge
