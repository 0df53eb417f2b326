// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 1½ of the wireframe pipeline (§4.1½, beyond seed 000): the distance tolerance the
/// input needs. Coordinates carry noise (6-decimal OBJ files, float exports, scans); a plane
/// spanned by two adjacent edges then holds the neighbours that lie in it only to within that
/// noise, while the neighbours that do not lie in it stand off by the model's geometry. Each
/// corner a–v–b gives residuals: the distances of the neighbours of a and b to the corner's
/// plane, each relative to the edge it hangs on (the sine of the edge's angle to the plane, so
/// a small part judges itself at its own scale). The near-zero cluster is noise, the large one
/// geometry; a clear gap between them (in decades) gives the tolerance, placed inside it. Where
/// that measure finds no clear gap, the same distances over their noise gain (which bounds the
/// noise of every in-plane residual by one figure however the corner is shaped) are tried; no
/// clear gap in either is reported, never hidden.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// Options of estimate_tolerance (and of the automatic choice in wireframe_to_cells).
struct tolerance_options {
  /// Choose the planarity tolerance of every stage from the data; false keeps the stages' own
  /// options (trace.planarity, reduction.planarity, arrangement.planarity, extra.retrace.planarity).
  bool automatic = true;
  /// Noise and geometry must lie this many decades apart (in either measure) for a clear gap.
  double min_gap_decades = 1.25;
  /// The tolerance stays this factor above the largest noise distance and below the smallest
  /// geometric one; closer than that in absolute terms, the gap is not clear either.
  double safety = 3.0;
  /// The planarity (relative to the bounding-box diagonal) used whenever it lies inside the
  /// gap: exact input keeps exactly the answer it had with the fixed default.
  double preferred = 1e-9;
  /// Corners sampled per vertex: all pairs of edges up to this many, then each edge with the next
  /// few in the order of their far ends' positions (a sphere's pole has thousands of pairs).
  std::size_t max_pairs_per_vertex = 36;
  /// Neighbours of a corner vertex measured per corner (strided past this).
  std::size_t max_neighbours = 16;
};

/// What estimate_tolerance found: the two clusters, the gap, and the tolerance chosen.
struct tolerance_result : stage_report {
  bool automatic = false;  ///< the tolerance below was chosen from the data (else: the options')
  /// The noise and the geometry are clearly apart: the tolerance separates them. False: the
  /// input's noise reaches its geometry somewhere (the answer may be wrong; see `reason`).
  bool clear_gap = true;
  std::string reason;  ///< why the gap is not clear; empty when it is
  /// Set by wireframe_to_cells: the gap is not clear and the reading leaves part of the
  /// wireframe unexplained (edges on no face, faces lost, no volume): the noise may have hidden
  /// faces; the answer is doubtful (status ambiguous at best, with this reason).
  bool ambiguous = false;
  /// The residuals below are each distance over its noise gain, relative to the diagonal (the
  /// distances over their edges' lengths found no clear gap); false: over their edges' lengths.
  bool noise_gain = false;
  double noise = 0.0;        ///< largest residual of the near-zero cluster (0: none seen)
  double geometry = 0.0;     ///< smallest residual of the geometric cluster (0: none seen)
  double gap_decades = 0.0;  ///< log10(geometry / the noise's bulk, its lower 99.5 %); infinite without noise
  double noise_distance = 0.0;      ///< largest distance of the noise cluster (absolute)
  double geometry_distance = 0.0;   ///< smallest distance of the geometric cluster (absolute)
  double planarity = 1e-9;          ///< the planarity tolerance chosen, relative to the diagonal
  double planarity_distance = 0.0;  ///< the same in model units
  /// Set by wireframe_to_cells: the answer is that of the stages' fixed planarity options
  /// (`planarity` is theirs), certified solid with them (the data's own precision was enough)
  /// or better than the estimated tolerance's answer; the figures above are the estimate's.
  bool fixed_pass = false;
  double estimated_planarity = 0.0;  ///< the estimate's planarity (relative), used or not (0: none made)
  std::size_t corners = 0;           ///< corners a–v–b sampled
  std::size_t samples = 0, noise_samples = 0, geometry_samples = 0;
};

namespace detail {

/// A residual for a reason: three significant digits (std::to_string prints 1e-7 as 0.000000). O(1).
template <class = void>
std::string residual_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

/// Residuals binned by their size: quarter-octave bins, each with its count, the extremes of its
/// residuals and of their distances, and its smallest slope (distance over its edge's length),
/// so that any split gives both clusters' bounds.
struct residual_bins {
  static constexpr int min_exponent = -64;  // residuals below 2^-64 (rounding) share the first bin
  static constexpr int max_exponent = 4;
  static constexpr int per_octave = 4;
  static constexpr std::size_t count = (max_exponent - min_exponent) * per_octave + 1;
  std::array<std::uint32_t, count> n{};
  std::array<std::uint32_t, count> quads{};  ///< of n: the fourth corners of chordless 4-cycles
  std::array<double, count> lo, hi, dlo, dhi, slope;
  residual_bins() {
    lo.fill(std::numeric_limits<double>::infinity());
    dlo.fill(std::numeric_limits<double>::infinity());
    slope.fill(std::numeric_limits<double>::infinity());
    hi.fill(0.0);
    dhi.fill(0.0);
  }
  /// Files a residual rel with its distance d (model units) and slope `rise` (d over its
  /// edge's length); `quad`: it closes a 4-cycle. O(1).
  void add(double rel, double d, double rise, bool quad) {
    std::size_t b = 0;
    if (rel > 0.0) {
      int e = 0;
      const double m = std::frexp(rel, &e);  // rel = m · 2^e, m in [0.5, 1)
      if (e > min_exponent) {
        const int sub = std::min(per_octave - 1, static_cast<int>((m - 0.5) * 2 * per_octave));
        b = std::min<std::size_t>(count - 1,
                                  static_cast<std::size_t>((e - min_exponent - 1) * per_octave + sub + 1));
      }
    }
    ++n[b];
    quads[b] += quad;
    lo[b] = std::min(lo[b], rel);
    hi[b] = std::max(hi[b], rel);
    dlo[b] = std::min(dlo[b], d);
    dhi[b] = std::max(dhi[b], d);
    slope[b] = std::min(slope[b], rise);
  }
};

/// Splits one measure's binned residuals (of r.samples) into noise and geometry and chooses the
/// tolerance in the gap (see estimate_tolerance); fills r's clusters, gap and planarity. O(bins).
template <class = void>
void split_residuals(const residual_bins& b, const tolerance_options& options, double diag, double reach,
                     tolerance_result& r) {
  constexpr double rounding = 8 * std::numeric_limits<double>::epsilon();
  // Candidate splits lie between consecutive non-empty bins, with at least 1 % of the
  // residuals below: the lowest order statistics of a noise cluster are spread out in log
  // space (the k lowest open a gap of G decades about 10^(-G·k) of the time, and one residual
  // is often measured from two or three corners), while a face of four corners or more gives
  // each of its corners two residuals or more in its plane. A split's gap is measured from the
  // bulk of what lies below it: its top 0.5 % come from the worst-conditioned corners (the
  // tolerance still clears all of it, in absolute terms below). The noise is the bulk of the
  // small residuals: from the lowest clear gap up, a clear gap with fewer residuals below it
  // than between it and the next clear gap lies inside the noise (residuals exact to rounding
  // under a decimal file's noise), and the split moves up to that next gap; a shape's shallow
  // angles (fewer than the residuals exactly in plane) stay geometry.
  const std::size_t min_noise = std::max<std::size_t>(3, r.samples / 100);
  constexpr std::size_t none = detail::residual_bins::count;
  auto bulk_below = [&](std::size_t split, std::size_t below) {
    double top = 0.0;
    for (std::size_t k = 0, seen = 0; k < split && 200 * seen < 199 * below; ++k)
      if (b.n[k] != 0) seen += b.n[k], top = b.hi[k];
    return top;
  };
  // A split whose upper side starts within 100 roundings of the coordinates splits rounding
  // from rounding (a short edge's rounding is a large fraction of it): never a gap.
  std::array<double, none + 1> above_min{};  // the smallest distance in bins k.. (suffix minimum)
  above_min[none] = std::numeric_limits<double>::infinity();
  for (std::size_t k = none; k-- > 0;)
    above_min[k] = std::min(above_min[k + 1], b.n[k] ? b.dlo[k] : above_min[k + 1]);
  std::size_t quads = 0;
  for (std::size_t k = 0; k < none; ++k) quads += b.quads[k];
  std::size_t below = 0, quads_below = 0, best = none, widest = none;  // the first bin of the geometry
  std::size_t best_below = 0, by_quads = none;
  double widest_gap = -1.0;
  std::size_t prev = none;  // last non-empty bin so far
  for (std::size_t k = 0; k < none; ++k) {
    if (b.n[k] == 0) continue;
    // Nor is a slope under `preferred` shape: the fixed default read it as flat even over an
    // edge as long as the diagonal (a 10-digit file far from the origin is that noisy).
    if (prev != none && below >= min_noise && above_min[k] > 100 * rounding * reach &&
        b.slope[k] >= options.preferred) {
      const double bulk = bulk_below(k, below);
      const double gap = bulk > 0.0 ? std::log10(b.lo[k] / bulk) : std::numeric_limits<double>::infinity();
      if (gap > widest_gap) widest_gap = gap, widest = k;
      if (gap >= options.min_gap_decades && (best == none || below - best_below > best_below))
        best = k, best_below = below;
      if (gap >= options.min_gap_decades && by_quads == none && 10 * (quads - quads_below) <= quads)
        by_quads = k;
    }
    below += b.n[k];
    quads_below += b.quads[k];
    prev = k;
  }
  // The quadrilaterals know best: the lowest clear gap with nine tenths of their flatness
  // residuals below it (a file where two faces of six carry decimal noise); no such gap, and
  // the noise of the quadrilaterals runs into the shape (no clear gap at all, even where the
  // widest gap below would be wide: it would call some quadrilaterals' flatness shape).
  const bool quads_unsplit = quads >= min_noise && by_quads == none;
  if (quads >= min_noise) best = by_quads;
  double best_gap = best != none ? options.min_gap_decades : widest_gap;
  if (best == none) best = widest;
  std::size_t first = none;
  for (std::size_t k = 0; k < none && first == none; ++k)
    if (b.n[k] != 0) first = k;
  // No clear split: "all geometry" when the smallest residual is within the gap width of the
  // typical one (a model of triangles: every neighbour stands off every corner's plane, and
  // the flattest angle is not far below the median one); a noise cluster instead trails off
  // towards zero, decades below its median.
  if (first != none && best_gap < options.min_gap_decades) {
    std::size_t seen = 0, median = first;
    for (std::size_t k = first; k < none && 2 * seen < r.samples; ++k)
      if (b.n[k] != 0) seen += b.n[k], median = k;
    if (b.lo[first] >= b.lo[median] * std::pow(10.0, -options.min_gap_decades)) {
      best = first;
      best_gap = std::numeric_limits<double>::infinity();
    }
  }
  const double preferred = options.preferred * diag;
  if (best == none) {
    // Everything is noise (a single flat polygon) or nothing was sampled: nothing to separate.
    r.planarity = options.preferred;
    r.planarity_distance = preferred;
    for (std::size_t k = 0; k < none; ++k)
      if (b.n[k]) {
        r.noise = std::max(r.noise, b.hi[k]);
        r.noise_distance = std::max(r.noise_distance, b.dhi[k]);
        r.noise_samples += b.n[k];
      }
    r.gap_decades = std::numeric_limits<double>::infinity();
    return;
  }
  r.geometry = b.lo[best];
  r.geometry_distance = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < none; ++k) {
    if (b.n[k] == 0) continue;
    if (k < best) {
      r.noise = std::max(r.noise, b.hi[k]);
      r.noise_distance = std::max(r.noise_distance, b.dhi[k]);
      r.noise_samples += b.n[k];
    } else {
      r.geometry_distance = std::min(r.geometry_distance, b.dlo[k]);
      r.geometry_samples += b.n[k];
    }
  }
  const double bulk = bulk_below(best, r.noise_samples);
  r.gap_decades = bulk > 0.0 ? std::log10(r.geometry / bulk) : std::numeric_limits<double>::infinity();
  // Absolute bounds: above the noise by the safety factor, below the geometry by it.
  const double low = options.safety * r.noise_distance, high = r.geometry_distance / options.safety;
  double chosen = preferred;
  if (r.gap_decades < options.min_gap_decades || quads_unsplit) {
    r.clear_gap = false;
    r.reason =
        quads_unsplit && r.gap_decades >= options.min_gap_decades
            ? cellforge::detail::cat(
                  "the quadrilaterals' flatness runs from noise to shape without a clear gap (the "
                  "widest gap, ",
                  residual_text(r.noise), " to ", residual_text(r.geometry), ", ",
                  residual_text(r.gap_decades),
                  " decades, has a tenth of them above it): the coordinates' noise may hide faces")
            : cellforge::detail::cat(
                  "the residuals of the corners' planes run from noise to shape without a clear gap "
                  "(edges ",
                  residual_text(r.noise), " and ", residual_text(r.geometry), " off their corners' planes, ",
                  residual_text(r.gap_decades), " decades apart): the coordinates' noise may hide faces");
    // Never call shape noise: below the whole cluster, as if it were all geometry.
    const double lowest = std::min(r.geometry_distance, r.noise_samples > 0 ? [&] {
      double d = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < best; ++k)
        if (b.n[k] != 0) d = std::min(d, b.dlo[k]);
      return d;
    }() : r.geometry_distance);
    chosen = std::min(preferred, lowest / options.safety);
  } else if (!(low < high)) {
    r.clear_gap = false;
    r.reason = cellforge::detail::cat("the noise reaches ", residual_text(r.noise_distance),
                                      " (model units) where the smallest feature stands ",
                                      residual_text(r.geometry_distance),
                                      " off its neighbours' plane: no single distance separates them");
    chosen = std::sqrt(r.noise_distance * r.geometry_distance);
  } else if (!(preferred >= low && preferred <= high)) {
    // Inside the gap, in the middle of it in log space (the noise at 0: well below the geometry).
    chosen = r.noise_distance > 0.0 ? std::sqrt(r.noise_distance * r.geometry_distance)
                                    : std::min(preferred, high / 1e3);
  }
  r.planarity_distance = chosen;
  r.planarity = diag > 0.0 ? chosen / diag : options.preferred;
}

}  // namespace detail

/// Estimates the planarity tolerance a labelled wireframe needs from the residuals of its
/// corners' planes (see the file comment); `preferred` is kept whenever it lies in the gap.
/// O(Σ_v min(deg², max_pairs) · max_neighbours), plus a sort of the neighbours at vertices
/// past those caps.
template <class = void>
tolerance_result estimate_tolerance(const wire_graph& g, const tolerance_options& options = {}) {
  detail::stopwatch clock;
  tolerance_result r;
  r.automatic = options.automatic;
  detail::residual_bins bins, gain_bins;  // over the edges' lengths; over the noise gains
  const double diag = g.size, scale = diag > 0.0 ? diag : 1.0;
  const std::size_t cap = std::max<std::size_t>(1, options.max_neighbours);
  // Well-conditioned corners only: a nearly straight corner's plane is mostly noise.
  constexpr double min_sine = 0.1;  // a regular polygon of up to 62 sides still counts
  constexpr double rounding = 8 * std::numeric_limits<double>::epsilon();
  // A neighbour w of a that is a neighbour of b too closes the 4-cycle v-a-w-b; without a chord
  // (a-b, v-w) such a cycle is, in the models people draw, a quadrilateral face: its residual
  // is that face's flatness, noise by construction. Neighbours of b and of v are stamped per
  // corner, so that this costs no edge look-up per residual.
  const std::size_t nv = g.num_vertices();
  std::vector<std::uint32_t> near_a(nv, no_index), near_b(nv, no_index), near_v(nv, no_index);
  std::vector<double> norm(nv);  // |p|: the coordinates' rounding is relative to it
  for (std::uint32_t v = 0; v < nv; ++v) norm[v] = glm::length(g.points[v]);
  // Where only some neighbours are sampled, they are taken in the order of their positions, so
  // that the sample (and the tolerance) does not depend on the vertices' numbering.
  auto neighbours = [&](std::uint32_t x, std::size_t limit, std::vector<std::uint32_t>& out) {
    out.clear();
    for (const auto& in : g.around(x)) out.push_back(in.other);
    if (out.size() > limit)
      std::sort(out.begin(), out.end(), [&](std::uint32_t p, std::uint32_t q) {
        const glm::dvec3 &a = g.points[p], &b = g.points[q];
        return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
      });
  };
  std::vector<std::uint32_t> around, inc;
  std::uint32_t corner = 0;  // the stamp of the current corner
  // Residuals of the neighbours of a and b (v's other neighbours are the far ends of edges
  // that the corners at v measure anyway).
  auto measure = [&](std::uint32_t v, std::uint32_t a, std::uint32_t b, const glm::dvec3& n) {
    const glm::dvec3 o = g.points[v];
    ++corner;
    for (const auto& in : g.around(v)) near_v[in.other] = corner;
    for (const auto& in : g.around(a)) near_a[in.other] = corner;
    for (const auto& in : g.around(b)) near_b[in.other] = corner;
    const bool chord = near_b[a] == corner;
    // The corner's triangle, for the barycentric feet of the neighbours (below).
    const glm::dvec3 ea = g.points[a] - o, eb = g.points[b] - o;
    const double aa = glm::dot(ea, ea), ab = glm::dot(ea, eb), bb = glm::dot(eb, eb);
    const double det = aa * bb - ab * ab;  // > 0: the corner's sine is at least min_sine
    for (const std::uint32_t x : {a, b}) {
      const std::vector<std::uint32_t>& other = x == a ? near_b : near_a;
      const auto direct = g.around(x);
      const bool sampled = direct.size() > cap;
      if (sampled) neighbours(x, cap, around);
      const std::size_t count = sampled ? around.size() : direct.size();
      const std::size_t step = (count + cap - 1) / cap;
      for (std::size_t k = 0; k < count; k += step) {
        const std::uint32_t w = sampled ? around[k] : direct[k].other;
        if (w == v || w == a || w == b) continue;
        const glm::dvec3 e = g.points[w] - g.points[x];
        const double len = glm::length(e);
        if (!(len > 0.0)) continue;
        // Never below the rounding of the coordinates: below it residuals are rounding whatever
        // their size, and a split among them would be no gap at all.
        const glm::dvec3 p = g.points[w] - o;
        const double floor = rounding * (norm[w] + norm[v]);
        const double d = std::max(std::abs(glm::dot(n, p)), floor);
        const bool quad = !chord && other[w] == corner && near_v[w] != corner;
        bins.add(d / len, d, d / len, quad);
        // The noise gain: with w's foot on the plane at barycentric (α, β, γ) of v, a, b, moving
        // the four points by δ moves the distance by at most (1 + |α| + |β| + |γ|) δ, 2 δ when
        // the foot lies in the triangle; over gain / 2, every in-plane distance stays under 2 δ.
        const double r1 = glm::dot(p, ea), r2 = glm::dot(p, eb);
        const double beta = (r1 * bb - r2 * ab) / det, gamma = (aa * r2 - ab * r1) / det;
        const double gain = 1.0 + std::abs(1.0 - beta - gamma) + std::abs(beta) + std::abs(gamma);
        const double dg = std::max(2.0 * std::abs(glm::dot(n, p)) / gain, floor);
        gain_bins.add(dg / scale, dg, dg / len, quad);
        ++r.samples;
      }
    }
  };
  for (std::uint32_t v = 0; v < nv; ++v) {
    const std::size_t deg = g.degree(v);
    if (deg < 2) continue;
    const bool all_pairs = deg * (deg - 1) / 2 <= options.max_pairs_per_vertex;
    neighbours(v, all_pairs ? deg : 0, inc);
    // Past the cap: each edge with the next few in the order of their far ends' positions.
    const std::size_t ahead = all_pairs ? deg : std::max<std::size_t>(1, options.max_pairs_per_vertex / deg);
    for (std::size_t i = 0; i < deg; ++i)
      for (std::size_t s = 1; s <= ahead && (all_pairs ? i + s < deg : s < deg); ++s) {
        const std::size_t j = all_pairs ? i + s : (i + s) % deg;
        const glm::dvec3 da = g.points[inc[i]] - g.points[v], db = g.points[inc[j]] - g.points[v];
        const glm::dvec3 c = glm::cross(da, db);
        const double lc = glm::length(c), la = glm::length(da), lb = glm::length(db);
        if (!(lc > min_sine * la * lb)) continue;
        ++r.corners;
        measure(v, inc[i], inc[j], c / lc);
      }
  }

  // The edge-length measure first: it judges a small part at its own scale, and where it finds a
  // clear gap (exact input, or noise well under the shallowest angle) its split is kept. Where it
  // finds none, noise may have been spread over decades by short edges measured far away (a
  // plane through a short side of an extrusion): the noise gain bounds every in-plane residual
  // by one figure. Not first: on exact input it can gather a shape's many shallow angles (the
  // bands of an antiprism of 36-62 sides) into a cluster larger than the one exactly in plane,
  // which the split then calls noise.
  const double reach = glm::length(g.center) + g.size;
  const tolerance_result measured = r;
  detail::split_residuals(bins, options, diag, reach, r);
  if (!r.clear_gap) {
    tolerance_result by_gain = measured;
    by_gain.noise_gain = true;
    detail::split_residuals(gain_bins, options, diag, reach, by_gain);
    if (by_gain.clear_gap) {
      r = std::move(by_gain);
    } else {
      r.reason +=
          cellforge::detail::cat("; nor over their noise gain (", detail::residual_text(by_gain.noise),
                                 " and ", detail::residual_text(by_gain.geometry), " of the diagonal, ",
                                 detail::residual_text(by_gain.gap_decades), " decades apart)");
    }
  }
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
