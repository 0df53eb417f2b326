// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The central axis of a solid from its vertices (seed 000 §5.1): slab averages along x, y
/// and z, a line through each set of averages, the best of the three, then re-splitting
/// along the current line until its direction settles.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/stage_report.hpp"

namespace cellforge {

/// Parameters of central_axis (the thin_options fields of the same names).
struct central_axis_options {
  int slabs = 20;              ///< slabs per split (the seed's 20)
  double tolerance_deg = 0.1;  ///< converged when the direction moves less than this
  int max_iterations = 50;     ///< then the recent directions are averaged (seed's fallback)
  int fallback_average = 5;    ///< how many recent directions the fallback averages
};

/// The fitted axis: a point, a unit direction and how the iteration ended.
/// stage_report: milliseconds the call; a diagnostic when the fallback or no split was used.
struct central_axis_result : stage_report {
  glm::dvec3 centroid{0.0};  ///< mean of the vertices (the seed's "approximate center")
  glm::dvec3 origin{0.0};    ///< a point of the line: the mean of the last slab averages
  glm::dvec3 direction{0, 0, 1};
  int initial_split = 2;   ///< 0, 1, 2: the coordinate whose split gave the best first line
  int iterations = 0;      ///< re-splits along the line
  bool converged = false;  ///< false: the fallback average of recent directions was used
  double residual = 0;     ///< mean distance of the last slab averages to the line
};

namespace detail::thin {

/// A line through slab averages: mean, principal direction, mean distance, spread.
struct fitted_line {
  bool ok = false;
  glm::dvec3 origin{0.0}, direction{0.0};
  double residual = 0, spread = 0;
};

/// Unit principal eigenvector of a symmetric 3×3 matrix by power iteration from the
/// column of largest norm (deterministic; 3×3 needs few steps). O(1).
template <class = void>
glm::dvec3 principal_direction(const std::array<std::array<double, 3>, 3>& c) {
  int best = 0;
  double best_norm = -1;
  for (int j = 0; j < 3; ++j) {
    const double n = c[0][j] * c[0][j] + c[1][j] * c[1][j] + c[2][j] * c[2][j];
    if (n > best_norm) best_norm = n, best = j;
  }
  glm::dvec3 v(c[0][best], c[1][best], c[2][best]);
  if (!(glm::length(v) > 0)) return glm::dvec3(0.0);
  v = glm::normalize(v);
  for (int it = 0; it < 200; ++it) {
    glm::dvec3 w(0.0);
    for (int i = 0; i < 3; ++i) w[i] = c[i][0] * v.x + c[i][1] * v.y + c[i][2] * v.z;
    const double n = glm::length(w);
    if (!(n > 0)) break;
    w /= n;
    const bool settled = glm::length(w - v) < 1e-15;
    v = w;
    if (settled) break;
  }
  return v;
}

/// Splits the points into `slabs` groups by G = dot(axis, p) with the seed's
/// F = min(floor(slabs·(G−Gmin)/(Gmax−Gmin)), slabs−1), averages each non-empty group and
/// fits the least-squares line through the averages (their principal direction). O(n).
template <class = void>
fitted_line fit_slabs(std::span<const glm::dvec3> pts, const glm::dvec3& axis, int slabs) {
  fitted_line line;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const glm::dvec3& p : pts) {
    const double g = glm::dot(axis, p);
    lo = std::min(lo, g), hi = std::max(hi, g);
  }
  if (!(hi > lo)) return line;
  std::vector<glm::dvec3> sum(static_cast<std::size_t>(slabs), glm::dvec3(0.0));
  std::vector<std::size_t> count(static_cast<std::size_t>(slabs), 0);
  for (const glm::dvec3& p : pts) {
    const double f = std::floor(slabs * (glm::dot(axis, p) - lo) / (hi - lo));
    const auto k = static_cast<std::size_t>(std::clamp(f, 0.0, static_cast<double>(slabs - 1)));
    sum[k] += p;
    ++count[k];
  }
  std::vector<glm::dvec3> avg;
  for (std::size_t k = 0; k < sum.size(); ++k)
    if (count[k] > 0) avg.push_back(sum[k] / static_cast<double>(count[k]));  // empty slabs skipped
  if (avg.size() < 2) return line;
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& a : avg) mean += a;
  mean /= static_cast<double>(avg.size());
  std::array<std::array<double, 3>, 3> cov{};
  for (const glm::dvec3& a : avg)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) cov[i][j] += (a[i] - mean[i]) * (a[j] - mean[j]);
  glm::dvec3 d = principal_direction(cov);
  if (!(glm::length(d) > 0.5)) return line;
  if (glm::dot(d, axis) < 0) d = -d;  // keep the sense of the split direction
  line.ok = true, line.origin = mean, line.direction = d;
  double lo_t = std::numeric_limits<double>::infinity(), hi_t = -lo_t;
  for (const glm::dvec3& a : avg) {
    const double t = glm::dot(a - mean, d);
    line.residual += glm::length(a - mean - t * d);
    lo_t = std::min(lo_t, t), hi_t = std::max(hi_t, t);
  }
  line.residual /= static_cast<double>(avg.size());
  line.spread = hi_t - lo_t;
  return line;
}

template <class = void>
double angle_deg(const glm::dvec3& a, const glm::dvec3& b) {
  const double c = std::clamp(std::abs(glm::dot(a, b)), 0.0, 1.0);
  // acos loses precision near 0; the cross product does not.
  return std::atan2(glm::length(glm::cross(a, b)), c) * 180.0 / std::numbers::pi;
}

}  // namespace detail::thin

/// The central axis of a point set (seed §5.1): the best of the x-, y- and z-split lines,
/// refined by splitting along the line until it moves < tolerance_deg. O(iterations · n).
/// "Best": the smallest mean distance of the averages to the line per unit of their spread;
/// near-ties (symmetric solids fit every split) go to the line the averages spread most along.
template <class = void>
central_axis_result central_axis(std::span<const glm::dvec3> pts, const central_axis_options& options = {}) {
  namespace t = detail::thin;
  if (pts.empty()) throw error(error_category::invalid_input, "central_axis: there are no points");
  const detail::stopwatch clock;
  central_axis_result r;
  for (const glm::dvec3& p : pts) r.centroid += p;
  r.centroid /= static_cast<double>(pts.size());
  double size = 0;
  for (const glm::dvec3& p : pts) size = std::max(size, glm::length(p - r.centroid));
  // The seed's "distance between the line and the averages", made scale-free by the
  // spread of the averages along the line. Symmetric solids fit every split line almost
  // exactly, so near-ties (within 1e-3) go to the line the averages spread furthest along.
  t::fitted_line best;
  double best_ratio = 0;
  for (int d = 0; d < 3; ++d) {
    glm::dvec3 axis(0.0);
    axis[d] = 1;
    const t::fitted_line line = t::fit_slabs(pts, axis, options.slabs);
    if (!line.ok) continue;
    const double ratio = line.residual / std::max(line.spread, 1e-12 * size + 1e-300);
    const bool better =
        !best.ok || ratio < best_ratio - 1e-3 || (ratio <= best_ratio + 1e-3 && line.spread > best.spread);
    if (better) best = line, best_ratio = ratio, r.initial_split = d;
  }
  if (!best.ok) {  // every split degenerate (all points in one place): keep z
    r.origin = r.centroid;
    r.converged = true;
    r.diagnostics.emplace_back(
        "central_axis: every split is degenerate (the points in one place): the z axis");
    r.milliseconds = clock.ms();
    return r;
  }
  glm::dvec3 dir = best.direction;
  r.origin = best.origin, r.residual = best.residual;
  std::vector<glm::dvec3> recent{dir};
  for (int it = 0; it < options.max_iterations; ++it) {
    const t::fitted_line line = t::fit_slabs(pts, dir, options.slabs);
    r.iterations = it + 1;
    if (!line.ok) {
      r.converged = true;
      break;
    }
    const double moved = t::angle_deg(dir, line.direction);
    dir = line.direction, r.origin = line.origin, r.residual = line.residual;
    recent.push_back(dir);
    if (moved < options.tolerance_deg) {
      r.converged = true;
      break;
    }
  }
  if (!r.converged) {
    // The seed's fallback: the average of the most recent directions (signs aligned).
    glm::dvec3 avg(0.0);
    const std::size_t k =
        std::min<std::size_t>(recent.size(), static_cast<std::size_t>(options.fallback_average));
    for (std::size_t i = recent.size() - k; i < recent.size(); ++i)
      avg += glm::dot(recent[i], dir) < 0 ? -recent[i] : recent[i];
    if (glm::length(avg) > 0) dir = glm::normalize(avg);
    r.diagnostics.push_back(cellforge::detail::cat(
        "central_axis: not converged within ", std::to_string(options.max_iterations),
        " iterations (max_iterations); the average of the last ", std::to_string(k), " directions is taken"));
  }
  r.direction = dir;
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
