// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Tidying a line drawing (seed 003_be08eec927fcc329.txt, stage "2D beautification or tidying
/// up"): lines that are nearly parallel are made exactly parallel by the smallest movement of
/// the junctions (a least-squares projection with Eigen). A drawing typed in with a few
/// decimals, or snapped from hand-placed strokes, is then exact enough for direct inflation,
/// whose depth propagation needs parallel lines to be parallel to rounding.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/work_budget.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge {

/// Options of tidy_drawing.
struct tidy_options {
  /// Lines whose directions differ by less than this (degrees) are one direction class and are
  /// made exactly parallel to the class's length-weighted mean direction.
  double parallel_tolerance_degrees = 0.25;
  /// Leave the drawing as it is when a junction would move by more than this, relative to the
  /// drawing's size (the classes are then not slips of the pen), with a diagnostic.
  double max_move = 0.02;
};

/// The tidied drawing, what was made parallel, and how far junctions moved.
template <Point2 P>
struct tidy_result {
  line_drawing<P> drawing;
  std::size_t classes = 0;         ///< direction classes of two or more lines
  std::size_t parallel_lines = 0;  ///< lines in those classes
  std::size_t changed_lines = 0;   ///< lines that were not parallel to their class to rounding
  double largest_move = 0.0;       ///< the largest junction movement, relative to the drawing's size
  bool applied = false;            ///< false: the drawing came back unchanged (nothing to do, or too far)
  double milliseconds = 0.0;
  std::vector<std::string> diagnostics;
};

/// Makes nearly parallel lines of a drawing exactly parallel by the least movement of its
/// junctions (minimum-norm correction of the linear parallelism constraints, Eigen's complete
/// orthogonal decomposition). Throws invalid_input on a NaN junction. O(E log E + E·V²).
template <LineDrawing D>
tidy_result<drawing_point_t<D>> tidy_drawing(const D& d, const tidy_options& options = {}) {
  using P = drawing_point_t<D>;
  detail::stopwatch clock;
  tidy_result<P> r;
  r.drawing = to_line_drawing(d);
  const std::size_t nv = r.drawing.points.size(), ne = r.drawing.edges.size();
  std::vector<glm::dvec2> p(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    p[i] = to_dvec2(r.drawing.points[i]);
    if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y))
      throw error(error_category::invalid_input,
                  "tidy_drawing: junction " + std::to_string(i) + " has a NaN or infinite coordinate");
  }
  if (nv < 2 || ne < 2) return r;
  glm::dvec2 lo = p[0], hi = p[0];
  for (const auto& q : p) lo = glm::min(lo, q), hi = glm::max(hi, q);
  const double size = glm::length(hi - lo);
  if (!(size > 0)) return r;
  // Direction classes: angles mod π sorted, a new class where the gap exceeds the tolerance.
  const double tol = options.parallel_tolerance_degrees * std::numbers::pi / 180.0;
  std::vector<std::pair<double, std::uint32_t>> angle;
  for (std::uint32_t e = 0; e < ne; ++e) {
    const auto [a, b] = r.drawing.edges[e];
    if (a >= nv || b >= nv || a == b) continue;
    const glm::dvec2 v = p[b] - p[a];
    if (glm::length(v) == 0) continue;
    double t = std::atan2(v.y, v.x);
    if (t < 0) t += std::numbers::pi;
    if (t >= std::numbers::pi) t -= std::numbers::pi;
    angle.push_back({t, e});
  }
  std::sort(angle.begin(), angle.end());
  std::vector<std::vector<std::uint32_t>> classes;
  for (std::size_t k = 0; k < angle.size(); ++k) {
    if (k == 0 || angle[k].first - angle[k - 1].first > tol) classes.emplace_back();
    classes.back().push_back(angle[k].second);
  }
  // Wrap around π: the last class joins the first.
  if (classes.size() > 1 && angle.front().first + std::numbers::pi - angle.back().first <= tol) {
    for (const auto e : classes.back()) classes.front().push_back(e);
    classes.pop_back();
  }
  // One constraint per line of a class of two or more: its normal component along the class's
  // normal is zero. The class direction: the length-weighted mean of the doubled angles.
  std::vector<std::pair<std::uint32_t, glm::dvec2>> rows;  // (edge, class normal)
  for (const auto& c : classes) {
    if (c.size() < 2) continue;
    ++r.classes;
    double sx = 0, sy = 0;
    for (const auto e : c) {
      const glm::dvec2 v = p[r.drawing.edges[e][1]] - p[r.drawing.edges[e][0]];
      const double t = 2 * std::atan2(v.y, v.x), len = glm::length(v);
      sx += len * std::cos(t), sy += len * std::sin(t);
    }
    const double t = 0.5 * std::atan2(sy, sx);
    const glm::dvec2 normal{-std::sin(t), std::cos(t)};
    for (const auto e : c) {
      rows.push_back({e, normal});
      const glm::dvec2 v = p[r.drawing.edges[e][1]] - p[r.drawing.edges[e][0]];
      if (std::abs(glm::dot(normal, v)) > 1e-14 * size) ++r.changed_lines;
    }
  }
  r.parallel_lines = rows.size();
  if (r.changed_lines == 0) {
    r.milliseconds = clock.ms();
    return r;
  }
  // Minimum-norm δ with A (p + δ) = 0, in units of the drawing's size.
  Eigen::MatrixXd A =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(2 * nv));
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto [e, n] = rows[k];
    const auto [a, b] = r.drawing.edges[e];
    const auto row = static_cast<Eigen::Index>(k);
    A(row, 2 * b) += n.x, A(row, 2 * b + 1) += n.y;
    A(row, 2 * a) -= n.x, A(row, 2 * a + 1) -= n.y;
    rhs(row) = -glm::dot(n, p[b] - p[a]) / size;
  }
  const Eigen::VectorXd delta = A.completeOrthogonalDecomposition().solve(rhs);
  for (std::size_t i = 0; i < nv; ++i)
    r.largest_move = std::max(r.largest_move, std::hypot(delta(static_cast<Eigen::Index>(2 * i)),
                                                         delta(static_cast<Eigen::Index>(2 * i + 1))));
  if (!(r.largest_move <= options.max_move)) {
    r.diagnostics.push_back("tidy_drawing: making the lines parallel would move a junction by " +
                            std::to_string(r.largest_move) + " of the drawing's size: left as drawn");
    r.milliseconds = clock.ms();
    return r;
  }
  for (std::size_t i = 0; i < nv; ++i)
    r.drawing.points[i] =
        from_dvec2<P>(p[i] + size * glm::dvec2(delta(static_cast<Eigen::Index>(2 * i)),
                                               delta(static_cast<Eigen::Index>(2 * i + 1))));
  r.applied = true;
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
