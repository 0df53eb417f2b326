// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Tidying a line drawing (seed 003 §"Main stages", "2D beautification or tidying
/// up"). tidy_drawing makes nearly parallel lines exactly parallel by the smallest movement of
/// the junctions. tidy_to_solid, given the faces, moves the junctions as little as it can so
/// that the drawing becomes the exact view of a solid with those faces: planar faces, and
/// lines parallel in 3D exactly parallel, so that inflation reads it exactly. Both use Eigen's
/// sparse solvers: no dense matrix over all lines. See docs/sketch.md, "Tidying".

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/work_counter.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/sketch/detail/tidy_classes.hpp"
#include "cellforge/sketch/inflation.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge {

/// Options of tidy_drawing and tidy_to_solid.
struct tidy_options {
  /// tidy_drawing: lines whose directions differ by less than this (degrees) are one direction
  /// class and are made exactly parallel to the class's length-weighted mean direction.
  double parallel_tolerance_degrees = 0.25;
  /// tidy_drawing: when positive, how precisely the junctions are placed (the largest slip,
  /// relative to the drawing's size) and the classes are taken from it instead: lines are one class
  /// when one direction lies within every line's slip (± 2 precision / its length), which never
  /// chains as a fixed angle does. drawing_to_cells estimates it for an inexact drawing.
  double precision = 0.0;
  /// tidy_drawing: leave the drawing as it is when a junction would move by more than this,
  /// relative to the drawing's size (the classes are then not slips of the pen), with a diagnostic.
  double max_move = 0.02;
  /// tidy_to_solid: lines whose 3D directions in the first (least-squares) reading differ by
  /// less than this (degrees), and that share no junction, are one class, made exactly parallel
  /// in 3D (and so in the drawing). Also the direct method's direction tolerance in that reading.
  double direction_tolerance_degrees = 4.0;
  /// tidy_to_solid: the direct method's misclosure accepted in the first reading (relative to
  /// the drawing's size): the drawing's own inexactness.
  double closure_tolerance = 0.05;
  /// tidy_to_solid: weight of a change of depth against a move in the drawing (both relative to
  /// the size): the first reading's depths are a guess, the junctions are what was drawn.
  double depth_weight = 0.1;
  /// tidy_to_solid: leave the drawing as it is when a junction would move by more than this.
  double solid_max_move = 0.06;
  /// tidy_to_solid: Gauss–Newton steps at most (work budget; each one sparse LDLᵀ).
  int max_steps = 60;
  /// tidy_to_solid: two lines at a junction that go straight on within the direction tolerance,
  /// where no face turns from one to the other, are one class (one line: a wall meets a seam
  /// there). Off by default: an affine first reading can straighten a solid's corner;
  /// drawing_to_cells sets it to retry an answer whose walls the jitter may have hidden.
  bool straight_lines = false;
};

/// The tidied drawing, what was made parallel, and how far junctions moved.
template <Point2 P>
struct tidy_result : stage_report {
  line_drawing<P> drawing;
  std::size_t classes = 0;         ///< direction classes of two or more lines
  std::size_t parallel_lines = 0;  ///< lines in those classes
  std::size_t changed_lines = 0;   ///< lines that were not parallel to their class to rounding
  double largest_move = 0.0;       ///< the largest junction movement, relative to the drawing's size
  double rms_move = 0.0;           ///< root mean square junction movement, relative to the drawing's size
  bool applied = false;            ///< false: the drawing came back unchanged (nothing to do, or too far)
  /// tidy_to_solid: the tidied drawing is the view of a solid with the faces given: `depth` is a
  /// reading of it (drawing units, junction i) whose faces are planar to `planarity`, and
  /// which is no tilted plane.
  bool solid = false;
  double planarity = 0.0;  ///< largest planarity residual of `depth`, relative to the drawing's size
  std::vector<double> depth;
  std::size_t steps = 0;  ///< tidy_to_solid: Gauss–Newton steps taken
};

namespace detail {
/// tidy_drawing's result type for drawing type D (unconstrained, for if_satisfied_t).
template <class D>
using tidy_result_for = tidy_result<typename line_drawing_traits<D>::point_type>;
}  // namespace detail

namespace detail::tidy {

/// Minimum-norm δ with A δ = rhs (A sparse, consistent), by δ = Aᵀ y with (A Aᵀ + εI) y = rhs
/// (Eigen's SimplicialLDLT; ε relative 1e-13 makes dependent rows harmless), refined twice.
/// O(fill of the factor).
template <class = void>
Eigen::VectorXd min_norm(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& rhs, bool& ok) {
  Eigen::SparseMatrix<double> n = a * a.transpose();
  double diag = 0;
  for (Eigen::Index i = 0; i < n.rows(); ++i) diag = std::max(diag, n.coeff(i, i));
  Eigen::SparseMatrix<double> eye(n.rows(), n.rows());
  eye.setIdentity();
  n += (1e-13 * std::max(diag, 1e-300)) * eye;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(n);
  ok = ldlt.info() == Eigen::Success;
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(a.cols());
  if (!ok) return delta;
  for (int round = 0; round < 3; ++round) {
    const Eigen::VectorXd y = ldlt.solve(rhs - a * delta);
    delta += a.transpose() * y;
  }
  ok = delta.allFinite();
  return delta;
}

/// Moves of a drawing (normalised units): largest and root mean square. O(V).
template <class = void>
std::pair<double, double> moves(const std::vector<glm::dvec2>& from, const std::vector<glm::dvec2>& to) {
  double largest = 0, sum = 0;
  for (std::size_t i = 0; i < from.size(); ++i) {
    const double m = glm::length(to[i] - from[i]);
    largest = std::max(largest, m), sum += m * m;
  }
  return {largest, from.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(from.size()))};
}

}  // namespace detail::tidy

/// Makes nearly parallel lines of a drawing exactly parallel by the least movement of its
/// junctions (minimum-norm correction of the linear parallelism constraints, Eigen's sparse
/// LDLᵀ of A Aᵀ). Throws invalid_input on a NaN junction. O(E log E + fill of the factor).
template <LineDrawing D>
detail::if_satisfied_t<LineDrawing<D>, detail::tidy_result_for, D> tidy_drawing(
    const D& d, const tidy_options& options = {}) {
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
                  cellforge::detail::cat("tidy_drawing: junction ", std::to_string(i),
                                         " has a NaN or infinite coordinate"));
  }
  if (nv < 2 || ne < 2) return r;
  glm::dvec2 lo = p[0], hi = p[0];
  for (const auto& q : p) lo = glm::min(lo, q), hi = glm::max(hi, q);
  const double size = glm::length(hi - lo);
  if (!(size > 0)) return r;
  // Direction classes: by the precision when given; else angles mod π sorted, a new class where
  // the gap exceeds the tolerance.
  std::vector<std::vector<std::uint32_t>> classes;
  if (options.precision > 0) {
    std::vector<glm::dvec2> unit(nv);
    std::vector<std::array<std::uint32_t, 2>> lines;
    for (std::size_t i = 0; i < nv; ++i) unit[i] = p[i] / size;
    for (const auto& [a, b] : r.drawing.edges)  // a malformed line: zero length, no class
      lines.push_back(a < nv && b < nv ? std::array<std::uint32_t, 2>{a, b}
                                       : std::array<std::uint32_t, 2>{0, 0});
    classes = detail::tidy::drawing_classes(unit, lines, options.precision);
  } else {
    const double tol = options.parallel_tolerance_degrees * std::numbers::pi / 180.0;
    std::vector<std::pair<double, std::uint32_t>> angle;
    for (std::uint32_t e = 0; e < ne; ++e) {
      const auto [a, b] = r.drawing.edges[e];
      if (a >= nv || b >= nv || a == b) continue;
      const glm::dvec2 v = p[b] - p[a];
      if (glm::length(v) == 0) continue;
      angle.push_back({detail::line_angle(v), e});
    }
    std::sort(angle.begin(), angle.end());
    for (std::size_t k = 0; k < angle.size(); ++k) {
      if (k == 0 || angle[k].first - angle[k - 1].first > tol) classes.emplace_back();
      classes.back().push_back(angle[k].second);
    }
    // Wrap around π: the last class joins the first.
    if (classes.size() > 1 && angle.front().first + std::numbers::pi - angle.back().first <= tol) {
      for (const auto e : classes.back()) classes.front().push_back(e);
      classes.pop_back();
    }
  }
  // One constraint per line of a class of two or more: its normal component along the class's
  // normal is zero. The class direction: the length-weighted mean of the doubled angles. Classes
  // from a precision may be inconsistent (lines of two near directions taken as one, which only a
  // collapse can meet): the line at the junction that moves most that is farthest off its class
  // leaves it, and the correction is solved again, at most 16 times.
  Eigen::VectorXd delta;
  for (int attempt = 0;; ++attempt) {
    std::vector<std::pair<std::uint32_t, glm::dvec2>> rows;  // (edge, class normal)
    std::vector<std::size_t> row_class;
    r.classes = r.changed_lines = 0;
    for (std::size_t ci = 0; ci < classes.size(); ++ci) {
      const auto& c = classes[ci];
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
        row_class.push_back(ci);
        const glm::dvec2 v = p[r.drawing.edges[e][1]] - p[r.drawing.edges[e][0]];
        if (std::abs(glm::dot(normal, v)) > 1e-14 * size) ++r.changed_lines;
      }
    }
    r.parallel_lines = rows.size();
    if (r.changed_lines == 0) {
      r.largest_move = r.rms_move = 0;
      r.milliseconds = clock.ms();
      return r;
    }
    // Minimum-norm δ with A (p + δ) = 0, in units of the drawing's size: sparse, four entries a row.
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(4 * rows.size());
    Eigen::VectorXd rhs(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const auto [e, n] = rows[k];
      const auto [a, b] = r.drawing.edges[e];
      const auto row = static_cast<Eigen::Index>(k);
      entries.emplace_back(row, 2 * b, n.x), entries.emplace_back(row, 2 * b + 1, n.y);
      entries.emplace_back(row, 2 * a, -n.x), entries.emplace_back(row, 2 * a + 1, -n.y);
      rhs(row) = -glm::dot(n, p[b] - p[a]) / size;
    }
    Eigen::SparseMatrix<double> A(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(2 * nv));
    A.setFromTriplets(entries.begin(), entries.end());
    bool ok = false;
    delta = detail::tidy::min_norm(A, rhs, ok);
    double sum = 0;
    std::size_t worst = 0;
    r.largest_move = 0;
    for (std::size_t i = 0; i < nv; ++i) {
      const double m =
          std::hypot(delta(static_cast<Eigen::Index>(2 * i)), delta(static_cast<Eigen::Index>(2 * i + 1)));
      if (m > r.largest_move) r.largest_move = m, worst = i;
      sum += m * m;
    }
    r.rms_move = std::sqrt(sum / static_cast<double>(nv));
    if (ok && r.largest_move <= options.max_move) break;
    std::size_t drop = rows.size();
    double farthest = -1;
    for (std::size_t k = 0; k < rows.size() && options.precision > 0 && ok && attempt < 16; ++k) {
      const auto [a, b] = r.drawing.edges[rows[k].first];
      const double off = std::abs(glm::dot(rows[k].second, p[b] - p[a]));
      if ((a == worst || b == worst) && off > farthest) farthest = off, drop = k;
    }
    if (drop == rows.size()) {
      r.diagnostics.push_back(
          cellforge::detail::cat("tidy_drawing: making the lines parallel would move a junction by ",
                                 std::to_string(r.largest_move), " of the drawing's size: left as drawn"));
      r.milliseconds = clock.ms();
      return r;
    }
    auto& c = classes[row_class[drop]];
    c.erase(std::find(c.begin(), c.end(), rows[drop].first));
  }
  for (std::size_t i = 0; i < nv; ++i)
    r.drawing.points[i] =
        from_dvec2<P>(p[i] + size * glm::dvec2(delta(static_cast<Eigen::Index>(2 * i)),
                                               delta(static_cast<Eigen::Index>(2 * i + 1))));
  r.applied = true;
  r.milliseconds = clock.ms();
  return r;
}

/// The nearest drawing that is the view of a solid with these faces (each: outer loop, then
/// holes): a first reading by least squares (inflate with least_squares), then Gauss–Newton on
/// junctions (x, y, z), face planes and class directions — moves in the drawing, depth changes
/// (weighted less) — with face planarity and 3D parallelism as penalty rows raised to 1e6,
/// each step a sparse LDLᵀ of the normal equations (Eigen's SimplicialLDLT); then, planes and
/// directions fixed, the junctions put on them exactly (sparse minimum norm). Left as drawn,
/// with a diagnostic, when no reading is found, a junction would move more than
/// solid_max_move, or the result is not planar to 1e-9. Throws invalid_input on malformed
/// input. O(inflation + steps · sparse LDLᵀ).
template <LineDrawing D>
detail::if_satisfied_t<LineDrawing<D>, detail::tidy_result_for, D> tidy_to_solid(
    const D& d, const std::vector<std::vector<std::vector<std::uint32_t>>>& faces,
    const tidy_options& options = {}) {
  using P = drawing_point_t<D>;
  detail::stopwatch clock;
  tidy_result<P> r;
  r.drawing = to_line_drawing(d);
  const detail::inflation_problem<> pr = detail::make_inflation_problem(d, faces);
  const std::size_t nv = pr.p.size(), ne = pr.edges.size();
  const auto finish = [&](std::string why) {
    if (!why.empty())
      r.diagnostics.push_back(cellforge::detail::cat("tidy_to_solid: ", why, ": left as drawn"));
    r.milliseconds = clock.ms();
    return r;
  };
  // 1. A first reading by least squares.
  inflation_options io;
  io.least_squares = true;
  io.direction_tolerance = options.direction_tolerance_degrees * std::numbers::pi / 180.0;
  io.closure_tolerance = options.closure_tolerance;
  std::vector<double> z0(nv);
  try {
    const auto first = inflate<glm::dvec3>(r.drawing, faces, io);
    for (std::size_t i = 0; i < nv; ++i) z0[i] = first.points[i].z / pr.size;
  } catch (const error& e) {
    if (e.category() != error_category::topology && e.category() != error_category::invalid_input) throw;
    return finish(cellforge::detail::cat(std::string("no least-squares reading ("), e.what(), ")"));
  }
  // 2. Lines parallel in 3D in that reading.
  std::vector<glm::dvec3> q0(nv);
  for (std::size_t i = 0; i < nv; ++i) q0[i] = glm::dvec3(pr.p[i], z0[i]);
  std::vector<std::uint32_t> part(nv, std::numeric_limits<std::uint32_t>::max());
  for (std::uint32_t s = 0, parts = 0; s < nv; ++s) {
    if (part[s] != std::numeric_limits<std::uint32_t>::max()) continue;
    std::vector<std::uint32_t> queue{s};
    part[s] = parts;
    for (std::size_t k = 0; k < queue.size(); ++k)
      for (const auto e : pr.incident[queue[k]])
        for (const auto w : pr.edges[e])
          if (part[w] == std::numeric_limits<std::uint32_t>::max()) part[w] = parts, queue.push_back(w);
    ++parts;
  }
  const auto found = detail::tidy::parallel_classes(
      q0, pr.edges, part, options.direction_tolerance_degrees * std::numbers::pi / 180.0,
      options.straight_lines ? detail::tidy::turned_corners(faces)
                             : std::set<std::array<std::uint32_t, 3>>{});
  // With those classes first; without them when that fails (a class the first reading got wrong).
  std::string why;
  for (const bool with_classes : {true, false}) {
    if (!with_classes && found.empty()) break;
    const std::vector<std::vector<std::uint32_t>> classes =
        with_classes ? found : std::vector<std::vector<std::uint32_t>>{};
    r.classes = classes.size();
    r.parallel_lines = 0;
    for (const auto& c : classes) r.parallel_lines += c.size();
    why = [&]() -> std::string {
      // 3. Unknowns: x, y, z per junction; a, b, c per face of four junctions or more (z = a x + b y
      // + c); θ, k per class (3D direction (cos θ, sin θ, k)).
      std::vector<std::vector<std::uint32_t>> face_junctions;
      for (const auto& f : faces) {
        std::vector<std::uint32_t> js;
        for (const auto& loop : f) js.insert(js.end(), loop.begin(), loop.end());
        std::sort(js.begin(), js.end());
        js.erase(std::unique(js.begin(), js.end()), js.end());
        if (js.size() >= 4) face_junctions.push_back(std::move(js));
      }
      const auto nf = face_junctions.size(), nc = classes.size();
      const auto face_at = [&](std::size_t f) { return static_cast<Eigen::Index>(3 * nv + 3 * f); };
      const auto class_at = [&](std::size_t c) { return static_cast<Eigen::Index>(3 * nv + 3 * nf + 2 * c); };
      const auto nu = static_cast<Eigen::Index>(3 * nv + 3 * nf + 2 * nc);
      Eigen::VectorXd u(nu);
      for (std::size_t i = 0; i < nv; ++i) {
        const auto k = static_cast<Eigen::Index>(3 * i);
        u[k] = pr.p[i].x, u[k + 1] = pr.p[i].y, u[k + 2] = z0[i];
      }
      for (std::size_t f = 0; f < nf; ++f) {
        Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
        Eigen::Vector3d b = Eigen::Vector3d::Zero();
        for (const auto v : face_junctions[f]) {
          const Eigen::Vector3d row(pr.p[v].x, pr.p[v].y, 1.0);
          m += row * row.transpose(), b += row * z0[v];
        }
        u.segment<3>(face_at(f)) = m.colPivHouseholderQr().solve(b);
      }
      for (std::size_t c = 0; c < nc; ++c) {
        double sx = 0, sy = 0;
        for (const auto e : classes[c]) {
          const glm::dvec2 v = pr.p[pr.edges[e][1]] - pr.p[pr.edges[e][0]];
          const double t = 2 * std::atan2(v.y, v.x), len = glm::length(v);
          sx += len * std::cos(t), sy += len * std::sin(t);
        }
        const double t = 0.5 * std::atan2(sy, sx);
        const glm::dvec2 dir{std::cos(t), std::sin(t)};
        double rise = 0, run = 0;
        for (const auto e : classes[c]) {
          const auto [a, b] = pr.edges[e];
          const double along = glm::dot(pr.p[b] - pr.p[a], dir);
          rise += along * (z0[b] - z0[a]), run += along * along;
        }
        u[class_at(c)] = t, u[class_at(c) + 1] = run > 0 ? rise / run : 0.0;
      }
      const Eigen::VectorXd u0 = u;
      std::size_t rows_planar = 0;
      for (const auto& js : face_junctions) rows_planar += js.size();
      std::size_t rows_parallel = 0;
      for (const auto& c : classes) rows_parallel += 2 * c.size();
      const auto nr = static_cast<Eigen::Index>(3 * nv + rows_planar + rows_parallel);
      // Residuals and their Jacobian at u, constraint rows weighted by w.
      const auto evaluate = [&](const Eigen::VectorXd& x, double w, Eigen::VectorXd& res,
                                Eigen::SparseMatrix<double>* jac, double& worst) {
        std::vector<Eigen::Triplet<double>> t;
        if (jac) t.reserve(static_cast<std::size_t>(3 * nv + 5 * rows_planar + 7 * rows_parallel));
        res.resize(nr);
        Eigen::Index row = 0;
        for (std::size_t i = 0; i < nv; ++i) {
          const auto k = static_cast<Eigen::Index>(3 * i);
          res[row] = x[k] - u0[k];
          if (jac) t.emplace_back(row, k, 1.0);
          ++row;
          res[row] = x[k + 1] - u0[k + 1];
          if (jac) t.emplace_back(row, k + 1, 1.0);
          ++row;
          res[row] = options.depth_weight * (x[k + 2] - u0[k + 2]);
          if (jac) t.emplace_back(row, k + 2, options.depth_weight);
          ++row;
        }
        worst = 0;
        for (std::size_t f = 0; f < nf; ++f) {
          const Eigen::Index pf = face_at(f);
          const double a = x[pf], b = x[pf + 1], c = x[pf + 2];
          for (const auto v : face_junctions[f]) {
            const auto k = static_cast<Eigen::Index>(3 * v);
            const double g = x[k + 2] - a * x[k] - b * x[k + 1] - c;
            worst = std::max(worst, std::abs(g));
            res[row] = w * g;
            if (jac) {
              t.emplace_back(row, k + 2, w), t.emplace_back(row, k, -w * a),
                  t.emplace_back(row, k + 1, -w * b);
              t.emplace_back(row, pf, -w * x[k]), t.emplace_back(row, pf + 1, -w * x[k + 1]);
              t.emplace_back(row, pf + 2, -w);
            }
            ++row;
          }
        }
        for (std::size_t c = 0; c < nc; ++c) {
          const Eigen::Index pc = class_at(c);
          const double th = x[pc], slope = x[pc + 1], co = std::cos(th), si = std::sin(th);
          for (const auto e : classes[c]) {
            const auto ka = static_cast<Eigen::Index>(3 * pr.edges[e][0]),
                       kb = static_cast<Eigen::Index>(3 * pr.edges[e][1]);
            const double dx = x[kb] - x[ka], dy = x[kb + 1] - x[ka + 1], dz = x[kb + 2] - x[ka + 2];
            const double g1 = -si * dx + co * dy, along = co * dx + si * dy, g2 = dz - slope * along;
            worst = std::max({worst, std::abs(g1), std::abs(g2)});
            res[row] = w * g1;
            if (jac) {
              t.emplace_back(row, kb, -w * si), t.emplace_back(row, ka, w * si);
              t.emplace_back(row, kb + 1, w * co), t.emplace_back(row, ka + 1, -w * co);
              t.emplace_back(row, pc, -w * along);
            }
            ++row;
            res[row] = w * g2;
            if (jac) {
              t.emplace_back(row, kb + 2, w), t.emplace_back(row, ka + 2, -w);
              t.emplace_back(row, kb, -w * slope * co), t.emplace_back(row, ka, w * slope * co);
              t.emplace_back(row, kb + 1, -w * slope * si), t.emplace_back(row, ka + 1, w * slope * si);
              t.emplace_back(row, pc, -w * slope * (-si * dx + co * dy)),
                  t.emplace_back(row, pc + 1, -w * along);
            }
            ++row;
          }
        }
        if (jac) {
          jac->resize(nr, nu);
          jac->setFromTriplets(t.begin(), t.end());
          jac->makeCompressed();
        }
      };
      // 4. Gauss–Newton, the constraint weight raised in steps (continuation: a weak start lets
      // the junctions move before the faces are held planar).
      Eigen::VectorXd res;
      Eigen::SparseMatrix<double> jac;
      double worst = 0;
      // Each step solves the normal equations JᵀJ δ = −Jᵀr by a sparse LDLᵀ (Eigen's
      // SimplicialLDLT, the pattern analysed once): far cheaper than a sparse QR of J, and the
      // rounding that the penalty's conditioning adds to a step is corrected by the next one
      // (the fixed point is JᵀJ's stationary point whatever the step's accuracy).
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
      bool pattern = false;
      int steps = 0;
      for (const double w : {1e1, 1e2, 1e3, 1e4, 1e5, 1e6}) {
        for (int step = 0; step < 8 && steps < options.max_steps; ++step) {
          evaluate(u, w, res, &jac, worst);
          Eigen::SparseMatrix<double> normal = jac.transpose() * jac;
          const Eigen::VectorXd gradient = jac.transpose() * res;
          if (!pattern) ldlt.analyzePattern(normal), pattern = true;
          ldlt.factorize(normal);
          if (ldlt.info() != Eigen::Success) return "the sparse factorisation failed";
          const Eigen::VectorXd delta = ldlt.solve(-gradient);
          ++r.steps, ++steps;
          if (!delta.allFinite()) return "the Gauss-Newton step is not finite";
          u += delta;
          if (delta.lpNorm<Eigen::Infinity>() < 1e-11) break;
        }
      }
      evaluate(u, 1.0, res, nullptr, worst);
      // 5. Planes and directions fixed, the junctions put on them exactly: the constraints are then
      // linear in (x, y, z); the least weighted change (depth scaled by its weight) by minimum norm.
      {
        std::vector<Eigen::Triplet<double>> t;
        Eigen::VectorXd g(static_cast<Eigen::Index>(rows_planar + rows_parallel));
        Eigen::Index row = 0;
        const double dz = 1.0 / options.depth_weight;  // δz = dz · δz' (scaled unknown)
        for (std::size_t f = 0; f < nf; ++f) {
          const Eigen::Index pf = face_at(f);
          const double a = u[pf], b = u[pf + 1], c = u[pf + 2];
          for (const auto v : face_junctions[f]) {
            const auto k = static_cast<Eigen::Index>(3 * v);
            g[row] = -(u[k + 2] - a * u[k] - b * u[k + 1] - c);
            t.emplace_back(row, k + 2, dz), t.emplace_back(row, k, -a), t.emplace_back(row, k + 1, -b);
            ++row;
          }
        }
        for (std::size_t c = 0; c < nc; ++c) {
          const Eigen::Index pc = class_at(c);
          const double slope = u[pc + 1], co = std::cos(u[pc]), si = std::sin(u[pc]);
          for (const auto e : classes[c]) {
            const auto ka = static_cast<Eigen::Index>(3 * pr.edges[e][0]),
                       kb = static_cast<Eigen::Index>(3 * pr.edges[e][1]);
            const double dx = u[kb] - u[ka], dy = u[kb + 1] - u[ka + 1], dzv = u[kb + 2] - u[ka + 2];
            g[row] = -(-si * dx + co * dy);
            t.emplace_back(row, kb, -si), t.emplace_back(row, ka, si), t.emplace_back(row, kb + 1, co),
                t.emplace_back(row, ka + 1, -co);
            ++row;
            g[row] = -(dzv - slope * (co * dx + si * dy));
            t.emplace_back(row, kb + 2, dz), t.emplace_back(row, ka + 2, -dz);
            t.emplace_back(row, kb, -slope * co), t.emplace_back(row, ka, slope * co);
            t.emplace_back(row, kb + 1, -slope * si), t.emplace_back(row, ka + 1, slope * si);
            ++row;
          }
        }
        if (row > 0) {
          Eigen::SparseMatrix<double> a(row, static_cast<Eigen::Index>(3 * nv));
          a.setFromTriplets(t.begin(), t.end());
          bool ok = false;
          const Eigen::VectorXd delta = detail::tidy::min_norm(a, g, ok);
          if (ok)
            for (std::size_t i = 0; i < nv; ++i) {
              const auto k = static_cast<Eigen::Index>(3 * i);
              u[k] += delta[k], u[k + 1] += delta[k + 1], u[k + 2] += dz * delta[k + 2];
            }
        }
      }
      // 6. The result, checked against the drawing it came from: every face's planarity row of the
      // tidied drawing holds for the reading, and the reading is no tilted plane.
      std::vector<glm::dvec2> moved(nv);
      std::vector<double> depth(nv);
      for (std::size_t i = 0; i < nv; ++i) {
        const auto k = static_cast<Eigen::Index>(3 * i);
        moved[i] = {u[k], u[k + 1]};
        depth[i] = u[k + 2];
      }
      std::tie(r.largest_move, r.rms_move) = detail::tidy::moves(pr.p, moved);
      line_drawing<P> tidied = r.drawing;
      for (std::size_t i = 0; i < nv; ++i) tidied.points[i] = from_dvec2<P>(pr.centre + pr.size * moved[i]);
      double planar = std::numeric_limits<double>::infinity();
      try {
        const detail::inflation_problem<> check = detail::make_inflation_problem(tidied, faces);
        std::vector<double> zc(nv);
        for (std::size_t i = 0; i < nv; ++i) zc[i] = depth[i] * pr.size / check.size;
        planar = 0;
        for (const auto& row : check.rows)
          planar = std::max(planar, std::abs(detail::plane_residual(row, zc)));
      } catch (const error& e) {
        if (e.category() != error_category::invalid_input) throw;
        return cellforge::detail::cat(std::string("the tidied drawing is malformed ("), e.what(), ")");
      }
      r.planarity = planar;
      // No tilt: the depths' residual from their best plane z = a x + b y + c.
      Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
      Eigen::Vector3d b = Eigen::Vector3d::Zero();
      for (std::size_t i = 0; i < nv; ++i) {
        const Eigen::Vector3d row(moved[i].x, moved[i].y, 1.0);
        m += row * row.transpose(), b += row * depth[i];
      }
      const Eigen::Vector3d plane = m.colPivHouseholderQr().solve(b);
      double relief = 0;
      for (std::size_t i = 0; i < nv; ++i)
        relief =
            std::max(relief, std::abs(depth[i] - plane.dot(Eigen::Vector3d(moved[i].x, moved[i].y, 1.0))));
      if (!(r.largest_move <= options.solid_max_move))
        return cellforge::detail::cat("the nearest view of a solid moves a junction by ",
                                      std::to_string(r.largest_move),
                                      " of the drawing's size (more than solid_max_move)");
      // A line shrunk to under half its drawn length: the junctions collapsed onto the constraints.
      for (const auto& [a, b] : pr.edges)
        if (glm::length(moved[b] - moved[a]) < 0.5 * glm::length(pr.p[b] - pr.p[a]))
          return cellforge::detail::cat("the nearest view of a solid shrinks line ", std::to_string(a), "-",
                                        std::to_string(b), " to under half its length");
      if (!(planar <= 1e-9))
        return cellforge::detail::cat("the faces of the tidied drawing are planar only to ",
                                      std::to_string(planar), " of its size after ", std::to_string(r.steps),
                                      " steps (worst constraint ", std::to_string(worst), ")");
      if (!(relief > 1e-6)) return "the reading found is flat";
      r.drawing = std::move(tidied);
      r.depth.resize(nv);
      for (std::size_t i = 0; i < nv; ++i) r.depth[i] = depth[i] * pr.size;
      r.changed_lines = ne;
      r.applied = r.solid = true;
      return "";
    }();
    if (why.empty()) return finish("");
    r.diagnostics.push_back(cellforge::detail::cat(
        "tidy_to_solid: ", std::string(with_classes ? "with" : "without"), " the parallel classes: ", why));
  }
  r.largest_move = r.rms_move = 0;
  return finish("no view of a solid found near the drawing");
}

#if defined(CELLFORGE_EXTERN_SKETCH)
// Compiled once in the file that includes cellforge/sketch/instantiate.hpp (docs/sketch.md).
extern template tidy_result<glm::dvec2> tidy_drawing<line_drawing<glm::dvec2>>(
    const line_drawing<glm::dvec2>&, const tidy_options&);
extern template tidy_result<glm::dvec2> tidy_to_solid<line_drawing<glm::dvec2>>(
    const line_drawing<glm::dvec2>&, const std::vector<std::vector<std::vector<std::uint32_t>>>&,
    const tidy_options&);
#endif

}  // namespace cellforge
