// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// tidy_to_solid's parallel classes (sketch/tidy.hpp, docs/sketch.md "Tidying"): lines parallel
/// in 3D in a first reading, and the corners the faces turn (where lines may go straight on);
/// tidy_drawing's classes from the drawing's precision, and the offsets that measure it.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/sketch/inflation.hpp"

namespace cellforge::detail::tidy {

/// The corners the faces turn: (junction, its two neighbours in the loop, sorted). O(Σ L log).
template <class = void>
std::set<std::array<std::uint32_t, 3>> turned_corners(
    const std::vector<std::vector<std::vector<std::uint32_t>>>& faces) {
  std::set<std::array<std::uint32_t, 3>> out;
  for (const auto& face : faces)
    for (const auto& loop : face)
      for (std::size_t k = 0, n = loop.size(); k < n; ++k) {
        const std::uint32_t a = loop[k], v = loop[(k + 1) % n], b = loop[(k + 2) % n];
        out.insert({v, std::min(a, b), std::max(a, b)});
      }
  return out;
}

/// Classes of lines parallel in 3D in a reading: longest line first, every unassigned line of
/// the same part of the drawing (`part` per junction) within `tolerance` (radians, up to sign)
/// joins it unless it shares a junction with a member (two lines at one junction of a solid
/// are never parallel), except a line going straight on from one member where no face turns
/// (in `turned`: junction, far ends sorted): a wall meets a seam there, the lines are one line. A class whose
/// drawing directions form two tight groups far apart (gap over four times either group's spread, and over
/// the turn the drawing's own precision allows the lines beside it) is split.
/// Classes of one line are dropped. Then classes of different parts whose drawing directions are each other's
/// only match within the tolerance are merged: the depth of a part drawn inside another is read on its own,
/// so only its drawing directions compare. O(E log E + E · W + C²), W the lines within the tolerance in the
/// drawing, C the classes.
template <class = void>
std::vector<std::vector<std::uint32_t>> parallel_classes(
    const std::vector<glm::dvec3>& q, const std::vector<std::array<std::uint32_t, 2>>& edges,
    const std::vector<std::uint32_t>& part, double tolerance,
    const std::set<std::array<std::uint32_t, 3>>& turned = {}) {
  const std::size_t ne = edges.size();
  std::vector<glm::dvec3> dir(ne);
  std::vector<double> len(ne), ang(ne), flat_len(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    const glm::dvec3 d = q[edges[e][1]] - q[edges[e][0]];
    len[e] = glm::length(d);
    flat_len[e] = glm::length(glm::dvec2(d));
    dir[e] = len[e] > 0 ? d / len[e] : d;
    ang[e] = line_angle(glm::dvec2(d));
  }
  std::vector<std::uint32_t> by_angle(ne), by_length(ne);
  for (std::uint32_t e = 0; e < ne; ++e) by_angle[e] = by_length[e] = e;
  std::sort(by_angle.begin(), by_angle.end(), [&](auto a, auto b) { return ang[a] < ang[b]; });
  std::sort(by_length.begin(), by_length.end(), [&](auto a, auto b) { return len[a] > len[b]; });
  std::vector<double> sorted(ne);
  for (std::size_t k = 0; k < ne; ++k) sorted[k] = ang[by_angle[k]];
  std::vector<char> taken(ne, 0);
  std::vector<std::uint32_t> mark(q.size(), std::numeric_limits<std::uint32_t>::max());
  std::vector<std::uint32_t> via(
      q.size(),
      std::numeric_limits<std::uint32_t>::max());  // per marked junction: the far end of its one member
  // Whether line (v, w) goes straight on from the one member of class `id` at v, at no face's corner.
  const auto straight_on = [&](std::uint32_t v, std::uint32_t w, std::uint32_t id) {
    if (turned.empty() || mark[v] != id || via[v] == std::numeric_limits<std::uint32_t>::max()) return false;
    const std::uint32_t u = via[v];
    return glm::dot(q[u] - q[v], q[w] - q[v]) < 0 && !turned.count({v, std::min(u, w), std::max(u, w)});
  };
  std::vector<std::vector<std::uint32_t>> raw, out;
  std::uint32_t id = 0;
  for (const auto seed : by_length) {
    if (taken[seed] || !(len[seed] > 0)) continue;
    std::vector<std::uint32_t> cls{seed};
    taken[seed] = 1;
    ++id;
    mark[edges[seed][0]] = mark[edges[seed][1]] = id;
    via[edges[seed][0]] = edges[seed][1], via[edges[seed][1]] = edges[seed][0];
    // The 3D angle bounds the drawing's angle only when the line is not steep: the window in
    // the drawing is widened by the line's slope.
    const double flat = std::hypot(dir[seed].x, dir[seed].y);
    const double window =
        flat > 1e-6 ? std::min(std::numbers::pi / 2, 2 * tolerance / flat) : std::numbers::pi / 2;
    const auto visit = [&](std::size_t k) {
      const std::uint32_t e = by_angle[k];
      if (taken[e] || !(len[e] > 0) || part[edges[e][0]] != part[edges[seed][0]]) return;
      if (std::abs(glm::dot(dir[e], dir[seed])) < std::cos(tolerance)) return;
      const std::uint32_t a = edges[e][0], b = edges[e][1];
      if ((mark[a] == id && !straight_on(a, b, id)) || (mark[b] == id && !straight_on(b, a, id))) return;
      taken[e] = 1, cls.push_back(e);
      // A junction with two members takes no third; one with one remembers its far end.
      via[a] = mark[a] == id ? std::numeric_limits<std::uint32_t>::max() : b;
      via[b] = mark[b] == id ? std::numeric_limits<std::uint32_t>::max() : a;
      mark[a] = mark[b] = id;
    };
    // Angles within the window, wrapping at π.
    const double lo = ang[seed] - window, hi = ang[seed] + window;
    const auto scan = [&](double a, double b) {
      for (auto k =
               static_cast<std::size_t>(std::lower_bound(sorted.begin(), sorted.end(), a) - sorted.begin());
           k < ne && sorted[k] <= b; ++k)
        visit(k);
    };
    scan(std::max(lo, 0.0), std::min(hi, std::numbers::pi));
    if (lo < 0) scan(lo + std::numbers::pi, std::numbers::pi);
    if (hi > std::numbers::pi) scan(0.0, hi - std::numbers::pi);
    raw.push_back(std::move(cls));
  }
  // The drawing's precision, from the classes themselves: the median over lines of classes of
  // three or more of the line's offset across its class's drawing direction at its far end
  // (|sin| of the angle off the class's mean times the line's length in the drawing). Zero
  // for an exact drawing. O(E log E).
  std::vector<double> offsets;
  for (const auto& cls : raw) {
    if (cls.size() < 3) continue;
    double sx = 0, sy = 0;
    for (const auto e : cls)
      sx += flat_len[e] * std::cos(2 * ang[e]), sy += flat_len[e] * std::sin(2 * ang[e]);
    const double mean_angle = 0.5 * std::atan2(sy, sx);
    for (const auto e : cls) offsets.push_back(std::abs(std::sin(ang[e] - mean_angle)) * flat_len[e]);
  }
  double precision = 0;
  if (!offsets.empty()) {
    std::nth_element(offsets.begin(), offsets.begin() + static_cast<std::ptrdiff_t>(offsets.size() / 2),
                     offsets.end());
    precision = offsets[offsets.size() / 2];
  }
  for (auto& cls : raw) {
    // Lines parallel in 3D are parallel in the drawing up to the pen's slips: a class whose
    // drawing directions fall into two tight groups far apart (an affine reading can bring two
    // directions of space within the tolerance) is two classes, when the gap is also wider
    // than the slips can turn the lines beside it (6 × precision / length each: a median
    // offset is about a sixth of the largest two slipped ends make).
    if (cls.size() >= 4) {
      const std::uint32_t seed = cls.front();
      std::vector<std::pair<double, std::uint32_t>> by;
      for (const auto e : cls) {
        double t = ang[e] - ang[seed];
        t -= std::numbers::pi * std::round(t / std::numbers::pi);
        by.push_back({t, e});
      }
      std::sort(by.begin(), by.end());
      std::size_t cut = 0;
      double widest = 0;
      // The groups widened by their slips, for every cut at once: below[k] the highest reach of
      // by[0..k), above[k] the lowest of by[k..): O(n) per class, not O(n) per cut.
      const std::size_t nb = by.size();
      std::vector<double> below(nb + 1, -std::numbers::pi), above(nb + 1, std::numbers::pi);
      for (std::size_t i = 0; i < nb; ++i) {
        const double slip = flat_len[by[i].second] > 0 ? 6 * precision / flat_len[by[i].second] : 0.0;
        below[i + 1] = std::max(below[i], by[i].first + slip);
      }
      for (std::size_t i = nb; i-- > 0;) {
        const double slip = flat_len[by[i].second] > 0 ? 6 * precision / flat_len[by[i].second] : 0.0;
        above[i] = std::min(above[i + 1], by[i].first - slip);
      }
      for (std::size_t k = 2; k + 2 <= nb; ++k) {
        const double gap = by[k].first - by[k - 1].first,
                     spread = std::max(by[k - 1].first - by.front().first, by.back().first - by[k].first);
        if (gap > 4 * spread && above[k] > below[k] && gap > widest) widest = gap, cut = k;
      }
      if (cut > 0) {
        std::vector<std::uint32_t> low, high;
        for (std::size_t k = 0; k < by.size(); ++k) (k < cut ? low : high).push_back(by[k].second);
        out.push_back(std::move(low));
        cls = std::move(high);
      }
    }
    if (cls.size() >= 2) out.push_back(std::move(cls));
  }
  // Across parts: each class's drawing direction (length-weighted mean of doubled angles).
  const std::size_t nc = out.size();
  std::vector<double> mean(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    double sx = 0, sy = 0;
    for (const auto e : out[c]) sx += len[e] * std::cos(2 * ang[e]), sy += len[e] * std::sin(2 * ang[e]);
    mean[c] = 0.5 * std::atan2(sy, sx);
  }
  const auto class_part = [&](std::size_t c) { return part[edges[out[c][0]][0]]; };
  // The only class of part `other` within the tolerance of class c's direction, or nc.
  const auto only_match = [&](std::size_t c, std::uint32_t other) {
    std::size_t found = nc;
    for (std::size_t k = 0; k < nc; ++k)
      if (class_part(k) == other && angle_distance(mean[k], mean[c]) <= tolerance) {
        if (found != nc) return nc;
        found = k;
      }
    return found;
  };
  std::vector<std::size_t> into(nc);
  for (std::size_t c = 0; c < nc; ++c) into[c] = c;
  for (std::size_t c = 0; c < nc; ++c)
    for (std::size_t k = c + 1; k < nc; ++k)
      if (class_part(k) != class_part(c) && into[k] == k && only_match(c, class_part(k)) == k &&
          only_match(k, class_part(c)) == c) {
        std::size_t root = c;
        while (into[root] != root) root = into[root];
        into[k] = root;
      }
  std::vector<std::vector<std::uint32_t>> merged;
  std::vector<std::size_t> slot(nc, nc);
  for (std::size_t c = 0; c < nc; ++c) {
    std::size_t root = c;
    while (into[root] != root) root = into[root];
    if (slot[root] == nc) slot[root] = merged.size(), merged.emplace_back();
    for (const auto e : out[c]) merged[slot[root]].push_back(e);
  }
  return merged;
}

}  // namespace cellforge::detail::tidy

namespace cellforge::detail::tidy {

/// A line's direction in the drawing (angle mod π) and how far its ends slipping by `precision`
/// can turn it (2 precision / length, at most π/2). Lengths and precision in one unit. O(1).
struct line_slip {
  double angle = 0, slip = 0, length = 0;
};

/// The lines of a drawing with their slips (zero-length lines: slip π/2). O(E).
template <class = void>
std::vector<line_slip> line_slips(const std::vector<glm::dvec2>& p,
                                  const std::vector<std::array<std::uint32_t, 2>>& edges, double precision) {
  std::vector<line_slip> out(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const glm::dvec2 d = p[edges[e][1]] - p[edges[e][0]];
    out[e].length = glm::length(d);
    out[e].angle = line_angle(d);
    out[e].slip = out[e].length > 2 * precision
                      ? std::min(std::numbers::pi / 2, std::asin(2 * precision / out[e].length))
                      : std::numbers::pi / 2;
  }
  return out;
}

/// Direction classes of a drawing whose junctions are placed to `precision` (the largest slip of a
/// junction, in the points' unit): lines are parallel when one direction lies within every
/// line's slip (an arc of ± 2 precision / length about its angle), so classes never chain as a
/// fixed angle does. The fewest such arcs' common points (greedy stabbing of the arcs cut open
/// where no arc covers, or at the widest gap), then every line moved to the class whose
/// length²-weighted mean direction is nearest in units of its slip, three rounds; two lines of a
/// class at one junction only going straight on. Classes of two lines or more. O(E log E + offers).
template <class = void>
std::vector<std::vector<std::uint32_t>> drawing_classes(
    const std::vector<glm::dvec2>& p, const std::vector<std::array<std::uint32_t, 2>>& edges,
    double precision) {
  constexpr double pi = std::numbers::pi;
  const std::vector<line_slip> s = line_slips(p, edges, precision);
  std::vector<std::uint32_t> lines;
  for (std::uint32_t e = 0; e < s.size(); ++e)
    if (s[e].length > 0 && s[e].slip < pi / 2) lines.push_back(e);
  if (lines.size() < 2) return {};
  // Cut the circle of directions where no arc covers (the start of the widest uncovered stretch),
  // else at the widest gap between angles.
  std::sort(lines.begin(), lines.end(), [&](auto a, auto b) { return s[a].angle < s[b].angle; });
  double cut = 0, widest = -1;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const auto a = lines[k], b = lines[(k + 1) % lines.size()];
    double gap = s[b].angle - s[a].angle;
    if (gap <= 0) gap += pi;
    const double open = gap - s[a].slip - s[b].slip;
    const double score = open > 0 ? pi + open : gap;  // an uncovered stretch beats any gap
    if (score > widest) widest = score, cut = s[a].angle + (open > 0 ? s[a].slip + 0.5 * open : 0.5 * gap);
  }
  const auto unrolled = [&](double a) {  // angle in [cut, cut + π)
    double t = a - cut;
    t -= pi * std::floor(t / pi);
    return cut + t;
  };
  // Greedy stabbing by right end of the arcs (clipped to the unrolled range).
  std::vector<std::pair<double, std::uint32_t>> by_right;
  for (const auto e : lines) by_right.push_back({std::min(unrolled(s[e].angle) + s[e].slip, cut + pi), e});
  std::sort(by_right.begin(), by_right.end());
  std::vector<double> centre;
  for (const auto& [right, e] : by_right)
    if (centre.empty() || unrolled(s[e].angle) - s[e].slip > centre.back()) centre.push_back(right);
  // Refine: each line to the class whose direction lies in its arc, nearest in slips, best fits
  // first; two lines of a class at one junction only going straight on (the two are one line;
  // turning, they are two sides of a corner, never parallel). Directions: the length²-weighted
  // means of the members (doubled angles).
  std::vector<std::size_t> of(s.size(), centre.size());
  std::vector<std::vector<std::pair<std::size_t, std::uint32_t>>> at(p.size());  // (class, line) per junction
  for (int round = 0; round < 3; ++round) {
    std::vector<std::tuple<double, std::uint32_t, std::size_t>> offers;  // (slips off, line, class)
    for (const auto e : lines)
      for (auto it = std::lower_bound(centre.begin(), centre.end(), unrolled(s[e].angle) - s[e].slip);
           it != centre.end() && *it <= unrolled(s[e].angle) + s[e].slip; ++it)
        offers.emplace_back(std::abs(*it - unrolled(s[e].angle)) / s[e].slip, e,
                            static_cast<std::size_t>(it - centre.begin()));
    std::sort(offers.begin(), offers.end());
    std::fill(of.begin(), of.end(), centre.size());
    for (auto& v : at) v.clear();
    for (const auto& [off, e, c] : offers) {
      if (of[e] < centre.size()) continue;
      bool clash = false;
      for (const std::uint32_t end : edges[e]) {
        std::size_t members = 0;
        for (const auto& [c2, f] : at[end]) {
          if (c2 != c) continue;
          const std::uint32_t far_e = edges[e][0] == end ? edges[e][1] : edges[e][0],
                              far_f = edges[f][0] == end ? edges[f][1] : edges[f][0];
          clash = clash || ++members > 1 || glm::dot(p[far_e] - p[end], p[far_f] - p[end]) >= 0;
        }
      }
      if (clash) continue;
      of[e] = c;
      for (const std::uint32_t end : edges[e]) at[end].push_back({c, e});
    }
    std::vector<double> sx(centre.size(), 0), sy(centre.size(), 0);
    for (const auto e : lines)
      if (of[e] < centre.size()) {
        const double w = s[e].length * s[e].length;
        sx[of[e]] += w * std::cos(2 * s[e].angle), sy[of[e]] += w * std::sin(2 * s[e].angle);
      }
    std::vector<double> moved;
    for (std::size_t c = 0; c < centre.size(); ++c)
      moved.push_back(sx[c] == 0 && sy[c] == 0 ? centre[c] : unrolled(0.5 * std::atan2(sy[c], sx[c])));
    // Keep the order (classes do not pass each other at these slips; sort to be safe).
    std::vector<std::size_t> order(centre.size());
    for (std::size_t c = 0; c < order.size(); ++c) order[c] = c;
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return moved[a] < moved[b]; });
    for (std::size_t c = 0; c < order.size(); ++c) centre[c] = moved[order[c]];
  }
  std::vector<std::vector<std::uint32_t>> classes(centre.size());
  for (const auto e : lines)
    if (of[e] < centre.size()) classes[of[e]].push_back(e);
  std::vector<std::vector<std::uint32_t>> out;
  for (auto& c : classes)
    if (c.size() >= 2) out.push_back(std::move(c));
  return out;
}

/// The median over lines of classes of three or more of the line's offset across its class's
/// mean direction at its far end (|sin| of the angle off the mean times the length). O(E).
template <class = void>
double median_offset(const std::vector<glm::dvec2>& p, const std::vector<std::array<std::uint32_t, 2>>& edges,
                     const std::vector<std::vector<std::uint32_t>>& classes) {
  const std::vector<line_slip> s = line_slips(p, edges, 0.0);
  std::vector<double> offsets;
  for (const auto& c : classes) {
    if (c.size() < 3) continue;
    double sx = 0, sy = 0;
    for (const auto e : c)
      sx += s[e].length * std::cos(2 * s[e].angle), sy += s[e].length * std::sin(2 * s[e].angle);
    const double mean = 0.5 * std::atan2(sy, sx);
    for (const auto e : c) offsets.push_back(std::abs(std::sin(s[e].angle - mean)) * s[e].length);
  }
  if (offsets.empty()) return 0;
  std::nth_element(offsets.begin(), offsets.begin() + static_cast<std::ptrdiff_t>(offsets.size() / 2),
                   offsets.end());
  return offsets[offsets.size() / 2];
}

}  // namespace cellforge::detail::tidy
