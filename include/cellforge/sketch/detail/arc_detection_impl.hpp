// SPDX-License-Identifier: MIT
#pragma once
// The engine of arc detection (included by sketch/arc_detection.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numbers>
#include <optional>
#include <ranges>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <unsupported/Eigen/NonLinearOptimization>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/sketch/arc_detection.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge {

namespace detail {

/// Distance from (y0, y1), y0, y1 >= 0, to the ellipse x0²/e0² + x1²/e1² = 1, e0 >= e1 > 0, and
/// the closest point, by bisection on the Lagrange parameter (the closest point is
/// (e0² y0 / (t + e0²), e1² y1 / (t + e1²)) for the root t of the constraint). O(log(1/ε)).
template <class = void>
std::pair<double, glm::dvec2> quadrant_ellipse_distance(double e0, double e1, double y0, double y1) {
  if (y1 > 0) {
    if (y0 > 0) {
      const double z0 = y0 / e0, z1 = y1 / e1;
      const double g0 = z0 * z0 + z1 * z1 - 1;
      if (g0 == 0) return {0.0, {y0, y1}};
      const double r0 = (e0 / e1) * (e0 / e1), n0 = r0 * z0;
      // f(s) = (n0 / (s + r0))² + (z1 / (s + 1))² − 1 decreases from +∞ at s = −1 to −1: bracket.
      double lo = z1 - 1, hi = g0 < 0 ? 0.0 : std::hypot(n0, z1) - 1, s = 0;
      for (int i = 0; i < 200; ++i) {
        s = 0.5 * (lo + hi);
        if (s == lo || s == hi) break;
        const double a = n0 / (s + r0), b = z1 / (s + 1), g = a * a + b * b - 1;
        if (g > 0)
          lo = s;
        else if (g < 0)
          hi = s;
        else
          break;
      }
      const glm::dvec2 x(r0 * y0 / (s + r0), y1 / (s + 1));
      return {glm::length(x - glm::dvec2(y0, y1)), x};
    }
    return {std::abs(y1 - e1), {0.0, e1}};
  }
  const double num = e0 * y0, den = e0 * e0 - e1 * e1;
  if (num < den) {
    const double u = num / den;
    const glm::dvec2 x(e0 * u, e1 * std::sqrt(std::max(0.0, 1 - u * u)));
    return {glm::length(x - glm::dvec2(y0, 0.0)), x};
  }
  return {std::abs(y0 - e0), {e0, 0.0}};
}

/// A point in an ellipse's own frame (centre at the origin, rx along x): its signed distance
/// (> 0 outside) and the parametric angle of its closest point. Newton steps on the angle first
/// (a few steps for a point near the curve, which is every point a fit keeps); their answer is
/// taken only when it is a minimum closer to the curve than half the smallest radius of
/// curvature, where the closest point is unique; otherwise the bisection. O(log(1/ε)).
template <class = void>
std::pair<double, double> ellipse_frame_distance(double rx, double ry, glm::dvec2 p) {
  const double inside = (p.x / rx) * (p.x / rx) + (p.y / ry) * (p.y / ry) - 1;
  double t = std::atan2(rx * p.y, ry * p.x);
  bool converged = false;
  double fp = 0;
  for (int i = 0; i < 8; ++i) {
    const double ct = std::cos(t), st = std::sin(t);
    const glm::dvec2 x(rx * ct, ry * st), d1(-rx * st, ry * ct);
    const double f = glm::dot(x - p, d1);
    fp = glm::dot(d1, d1) - glm::dot(x - p, x);  // x'' = −x
    if (!(fp > 0)) break;
    const double dt = f / fp;
    t -= dt;
    if (std::abs(dt) < 1e-13) {
      converged = true;
      break;
    }
  }
  if (converged) {
    const double dist = glm::length(p - glm::dvec2(rx * std::cos(t), ry * std::sin(t)));
    const double lo = std::min(rx, ry), hi = std::max(rx, ry);
    if (dist < 0.5 * lo * lo / hi)
      return {inside < 0 ? -dist : dist, std::remainder(t, 2 * std::numbers::pi)};
  }
  const bool swap = ry > rx;
  const double e0 = swap ? ry : rx, e1 = swap ? rx : ry;
  const double y0 = swap ? p.y : p.x, y1 = swap ? p.x : p.y;
  auto [dist, x] = quadrant_ellipse_distance(e0, e1, std::abs(y0), std::abs(y1));
  x.x = std::copysign(x.x, y0);
  x.y = std::copysign(x.y, y1);
  if (swap) std::swap(x.x, x.y);
  return {inside < 0 ? -dist : dist, std::atan2(x.y / ry, x.x / rx)};
}

/// An ellipse in double precision while it is being fitted.
struct ellipse_params {
  glm::dvec2 c{0};
  double rx = 0, ry = 0, rot = 0;
};

/// The point p in the ellipse's own frame. O(1).
template <class = void>
glm::dvec2 to_ellipse_frame(const ellipse_params& e, glm::dvec2 p) {
  const double c = std::cos(e.rot), s = std::sin(e.rot);
  const glm::dvec2 d = p - e.c;
  return {c * d.x + s * d.y, -s * d.x + c * d.y};
}

/// The same ellipse with rx its longer axis and the rotation in (−π/2, π/2]. O(1).
template <class = void>
ellipse_params normalised(ellipse_params e) {
  if (e.ry > e.rx) std::swap(e.rx, e.ry), e.rot += std::numbers::pi / 2;
  e.rot = std::remainder(e.rot, std::numbers::pi);
  if (e.rot <= -std::numbers::pi / 2) e.rot += std::numbers::pi;
  return e;
}

/// Fitzgibbon, Pilu and Fisher's direct least-squares ellipse fit, in Halíř and Flusser's
/// numerically stable form (the scatter matrix split into quadratic and linear blocks, the
/// linear block eliminated): the conic a x² + b xy + c y² + d x + e y + f = 0 minimising the
/// algebraic residual under 4ac − b² = 1, which is always an ellipse. Points are centred and
/// scaled to unit spread first. false when the points admit no ellipse (collinear, too few).
/// O(n).
template <class = void>
bool direct_ellipse_fit(const std::vector<glm::dvec2>& q, ellipse_params& out) {
  const std::size_t n = q.size();
  if (n < 5) return false;
  glm::dvec2 mean(0);
  for (const glm::dvec2& p : q) mean += p;
  mean /= static_cast<double>(n);
  double spread = 0;
  for (const glm::dvec2& p : q) spread += glm::dot(p - mean, p - mean);
  spread = std::sqrt(spread / static_cast<double>(n));
  if (!(spread > 0)) return false;
  Eigen::Matrix3d s1 = Eigen::Matrix3d::Zero(), s2 = Eigen::Matrix3d::Zero(), s3 = Eigen::Matrix3d::Zero();
  for (const glm::dvec2& p : q) {
    const glm::dvec2 u = (p - mean) / spread;
    const Eigen::Vector3d quad(u.x * u.x, u.x * u.y, u.y * u.y), lin(u.x, u.y, 1.0);
    s1 += quad * quad.transpose();
    s2 += quad * lin.transpose();
    s3 += lin * lin.transpose();
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu3(s3);
  if (!lu3.isInvertible()) return false;
  const Eigen::Matrix3d t = -lu3.solve(s2.transpose());
  const Eigen::Matrix3d m = s1 + s2 * t;
  // The constraint matrix's inverse applied to m: rows (m₂ / 2, −m₁, m₀ / 2).
  Eigen::Matrix3d mc;
  mc.row(0) = m.row(2) / 2;
  mc.row(1) = -m.row(1);
  mc.row(2) = m.row(0) / 2;
  const Eigen::EigenSolver<Eigen::Matrix3d> es(mc);
  if (es.info() != Eigen::Success) return false;
  int pick = -1;
  double best = 0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d v = es.eigenvectors().col(k).real();
    const double cond = 4 * v(0) * v(2) - v(1) * v(1);
    if (cond > best) best = cond, pick = k;
  }
  if (pick < 0) return false;
  const Eigen::Vector3d a1 = es.eigenvectors().col(pick).real();
  const Eigen::Vector3d a2 = t * a1;
  const double A = a1(0), B = a1(1), C = a1(2), D = a2(0), E = a2(1), F = a2(2);
  Eigen::Matrix2d qm;
  qm << 2 * A, B, B, 2 * C;
  const Eigen::Vector2d centre = qm.fullPivLu().solve(Eigen::Vector2d(-D, -E));
  const double f0 = A * centre(0) * centre(0) + B * centre(0) * centre(1) + C * centre(1) * centre(1) +
                    D * centre(0) + E * centre(1) + F;
  Eigen::Matrix2d form;
  form << A, B / 2, B / 2, C;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> se(form);
  const Eigen::Vector2d lam = se.eigenvalues();  // ascending: the smaller one is the longer axis
  const double ax0 = -f0 / lam(0), ax1 = -f0 / lam(1);
  if (!(ax0 > 0) || !(ax1 > 0) || !std::isfinite(ax0) || !std::isfinite(ax1)) return false;
  const Eigen::Vector2d major = se.eigenvectors().col(0);
  out.c = mean + spread * glm::dvec2(centre(0), centre(1));
  out.rx = spread * std::sqrt(ax0);
  out.ry = spread * std::sqrt(ax1);
  out.rot = std::atan2(major(1), major(0));
  return std::isfinite(out.c.x) && std::isfinite(out.c.y);
}

/// At the closest point, parametric angle t, of an ellipse: the outward unit normal in the
/// ellipse's frame and in the drawing, and the closest point in the frame. The distance's
/// derivative for a parameter is −(normal · the closest point's derivative for it): the
/// distance is stationary along the curve there. O(1).
struct closest_point_frame {
  glm::dvec2 normal_frame, normal, point_frame;
};

template <class = void>
closest_point_frame at_closest(const ellipse_params& e, double t) {
  const double ct = std::cos(t), st = std::sin(t), c = std::cos(e.rot), s = std::sin(e.rot);
  glm::dvec2 nf(e.ry * ct, e.rx * st);
  nf /= glm::length(nf);
  return {nf, {c * nf.x - s * nf.y, s * nf.x + c * nf.y}, {e.rx * ct, e.ry * st}};
}

/// The residual functor of Eigen's Levenberg–Marquardt for an ellipse fitted to points q: the
/// points' signed distances to the ellipse `model.ellipse(x)` of the parameters x, and the
/// analytic Jacobian, a row per point from `model.row(e, t)` at its closest point's angle t.
/// Eigen asks for the Jacobian where it last evaluated (the start, or an accepted step), so
/// the angles of the last evaluation are kept and not searched again. Parameters that give no
/// ellipse get residuals so large that Eigen refuses the step.
template <class Model>
struct ellipse_distance_functor {
  const std::vector<glm::dvec2>* q;
  Model model;
  Eigen::VectorXd at{};         // the parameters of the last evaluation (empty: none kept)
  std::vector<double> angle{};  // its closest points' parametric angles
  Eigen::Index values() const { return static_cast<Eigen::Index>(q->size()); }
  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) {
    at.resize(0);
    const std::optional<ellipse_params> e = model.ellipse(x);
    if (!e) {
      f.setConstant(1e150);
      return 0;
    }
    angle.resize(q->size());
    for (std::size_t k = 0; k < q->size(); ++k) {
      const auto [d, t] = ellipse_frame_distance(e->rx, e->ry, to_ellipse_frame(*e, (*q)[k]));
      f(static_cast<Eigen::Index>(k)) = d;
      angle[k] = t;
    }
    at = x;
    return 0;
  }
  int df(const Eigen::VectorXd& x, Eigen::MatrixXd& jac) {
    if (at.size() != x.size() || at != x) {
      Eigen::VectorXd f(values());
      (*this)(x, f);
    }
    const std::optional<ellipse_params> e = model.ellipse(x);
    if (!e) return -1;  // Eigen stops; an accepted step always has an ellipse
    for (std::size_t k = 0; k < q->size(); ++k)
      jac.row(static_cast<Eigen::Index>(k)) = model.row(*e, angle[k]);
    return 0;
  }
};

/// Eigen's Levenberg–Marquardt (MINPACK's lmder, Marquardt's scaling) on the points' distances
/// to the model's ellipse, from and into x: stops when a step gains less than a relative 1e-6
/// of the sum of squares, or after max_evaluations evaluations of the distances. Returns the
/// evaluations made (Eigen's nfev). O(evaluations × n).
template <class Model>
std::size_t fit_distances(const std::vector<glm::dvec2>& q, const Model& model, Eigen::VectorXd& x,
                          std::size_t max_evaluations) {
  ellipse_distance_functor<Model> f{&q, model};
  Eigen::LevenbergMarquardt<ellipse_distance_functor<Model>> lm(f);
  lm.parameters.maxfev = static_cast<Eigen::Index>(max_evaluations);
  lm.parameters.ftol = 1e-6;
  lm.minimize(x);
  return static_cast<std::size_t>(lm.nfev);
}

/// The largest distance of a point of q from the ellipse e. O(n).
template <class = void>
double max_distance(const std::vector<glm::dvec2>& q, const ellipse_params& e) {
  double worst = 0;
  for (const glm::dvec2& p : q)
    worst = std::max(worst, std::abs(ellipse_frame_distance(e.rx, e.ry, to_ellipse_frame(e, p)).first));
  return worst;
}

/// The free ellipse's parameters in the refinement: centre, each semi-axis as s with
/// axis = bound / (1 + e⁻ˢ) (e^s when the bound is infinite), rotation. The map keeps every
/// axis in (0, bound), so no step leaves the admissible ellipses: a nearly straight arc would
/// otherwise drift towards an ever larger, flatter ellipse (lower residual, no use).
template <class = void>
struct free_ellipse_model {
  double bound = std::numeric_limits<double>::infinity();
  double axis(double s) const { return std::isfinite(bound) ? bound / (1 + std::exp(-s)) : std::exp(s); }
  double slope(double axis) const { return std::isfinite(bound) ? axis * (1 - axis / bound) : axis; }
  double parameter(double axis) const {
    if (!std::isfinite(bound)) return std::log(axis);
    const double a = std::min(axis, bound * (1 - 1e-12));  // an axis at the bound: just inside
    return std::log(a / (bound - a));
  }
  std::optional<ellipse_params> ellipse(const Eigen::VectorXd& x) const {
    const ellipse_params e{{x(0), x(1)}, axis(x(2)), axis(x(3)), x(4)};
    const bool ok = e.rx > 0 && e.ry > 0 && std::isfinite(e.rx) && std::isfinite(e.ry) &&
                    std::isfinite(e.c.x) && std::isfinite(e.c.y) && std::isfinite(e.rot);
    return ok ? std::optional<ellipse_params>(e) : std::nullopt;
  }
  Eigen::Matrix<double, 1, 5> row(const ellipse_params& e, double t) const {
    const closest_point_frame f = at_closest(e, t);
    const double c = std::cos(e.rot), s = std::sin(e.rot);
    const glm::dvec2 xf = f.point_frame;
    const glm::dvec2 turn(-s * xf.x - c * xf.y, c * xf.x - s * xf.y);  // d(point)/d(rotation)
    Eigen::Matrix<double, 1, 5> r;
    r << -f.normal.x, -f.normal.y, -f.normal_frame.x * std::cos(t) * slope(e.rx),
        -f.normal_frame.y * std::sin(t) * slope(e.ry), -glm::dot(f.normal, turn);
    return r;
  }
};

/// Levenberg–Marquardt (Eigen's) on the points' signed distances to the ellipse over (centre,
/// semi-axes, rotation): the orthogonal-distance fit. Keeps both semi-axes in (0, max_axis]
/// (infinity: no bound) by the parametrisation of free_ellipse_model. Returns the distance
/// evaluations made. O(n × max_evaluations).
template <class = void>
std::size_t refine_ellipse(const std::vector<glm::dvec2>& q, ellipse_params& e, double max_axis,
                           std::size_t max_evaluations = 30) {
  const free_ellipse_model<> model{max_axis};
  Eigen::VectorXd x(5);
  x << e.c.x, e.c.y, model.parameter(e.rx), model.parameter(e.ry), e.rot;
  const std::size_t evaluations = fit_distances(q, model, x, max_evaluations);
  e = model.ellipse(x).value_or(e);
  return evaluations;
}

/// Where the polyline q crosses itself: proper crossings of two of its segments whose stretch of
/// polyline between them is longer than `min_loop` (shorter loops are a pen's jitter). Returns
/// the count and the first crossing point. Segments by their leftmost x, each compared with the
/// ones starting before its right end: O(n log n + pairs whose x-ranges overlap).
template <class = void>
std::pair<std::size_t, glm::dvec2> self_crossings(const std::vector<glm::dvec2>& q, double min_loop) {
  const std::size_t n = q.size() < 2 ? 0 : q.size() - 1;
  std::vector<double> along(q.size(), 0.0);
  for (std::size_t i = 1; i < q.size(); ++i) along[i] = along[i - 1] + glm::length(q[i] - q[i - 1]);
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  const auto lo = [&](std::size_t i) { return std::min(q[i].x, q[i + 1].x); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo(a) < lo(b); });
  std::size_t count = 0;
  glm::dvec2 first{};
  for (std::size_t u = 0; u < n; ++u) {
    const std::size_t i = order[u];
    const double hi = std::max(q[i].x, q[i + 1].x);
    for (std::size_t w = u + 1; w < n && lo(order[w]) <= hi; ++w) {
      const std::size_t j = order[w];
      const std::size_t a = std::min(i, j), b = std::max(i, j);
      if (b < a + 2 || along[b] - along[a + 1] <= min_loop) continue;
      if (std::max(std::min(q[a].y, q[a + 1].y), std::min(q[b].y, q[b + 1].y)) >
          std::min(std::max(q[a].y, q[a + 1].y), std::max(q[b].y, q[b + 1].y)))
        continue;
      if (orient2d(q[a], q[a + 1], q[b]) * orient2d(q[a], q[a + 1], q[b + 1]) < 0 &&
          orient2d(q[b], q[b + 1], q[a]) * orient2d(q[b], q[b + 1], q[a + 1]) < 0) {
        if (count++ == 0) {
          const glm::dvec2 r = q[a + 1] - q[a], t = q[b + 1] - q[b];
          const double den = r.x * t.y - r.y * t.x;
          const glm::dvec2 d = q[b] - q[a];
          first = q[a] + r * ((d.x * t.y - d.y * t.x) / den);
        }
      }
    }
  }
  return {count, first};
}

/// The total least-squares line through q[first..last]: (deviation, the end samples projected
/// onto it). O(last − first).
template <class = void>
std::pair<double, std::array<glm::dvec2, 2>> fit_line(const std::vector<glm::dvec2>& q, std::size_t first,
                                                      std::size_t last) {
  const double n = static_cast<double>(last - first + 1);
  glm::dvec2 mean(0);
  for (std::size_t k = first; k <= last; ++k) mean += q[k];
  mean /= n;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (std::size_t k = first; k <= last; ++k) {
    const Eigen::Vector2d d(q[k].x - mean.x, q[k].y - mean.y);
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> se(cov);
  const Eigen::Vector2d dir_e = se.eigenvectors().col(1);  // the larger eigenvalue: the line's direction
  const glm::dvec2 dir(dir_e(0), dir_e(1));
  const glm::dvec2 nrm(-dir.y, dir.x);
  double worst = 0;
  for (std::size_t k = first; k <= last; ++k) worst = std::max(worst, std::abs(glm::dot(q[k] - mean, nrm)));
  const auto project = [&](glm::dvec2 p) { return mean + dir * glm::dot(p - mean, dir); };
  return {worst, {project(q[first]), project(q[last])}};
}

/// An arc read from samples: the ellipse, the parametric angle of the first sample's closest
/// point, the signed sweep to the last sample's, and the largest distance.
struct arc_reading {
  arc_rejection why = arc_rejection::not_an_ellipse;
  ellipse_params e{};
  double start = 0, sweep = 0, max_distance = 0;
  std::size_t iterations = 0;
};

/// Fits and checks an ellipse through q (in the order the stroke runs): the conic fit, the
/// optional refinement, then every check of arc_rejection in its order. `eps` is the tolerance
/// and `size` the drawing's size, in q's units. O(n × refinement steps).
/// Checks an ellipse against the samples q (in the order the stroke runs): every check of
/// arc_rejection from too_large on, in that order. O(n).
template <class = void>
arc_reading check_arc(const std::vector<glm::dvec2>& q, ellipse_params e, const arc_detection_options& o,
                      double eps, double size) {
  arc_reading r;
  r.e = e;
  if (!(std::max(r.e.rx, r.e.ry) <= o.max_semi_axis * size)) {
    r.why = arc_rejection::too_large;
    return r;
  }
  r.e = normalised(r.e);
  std::vector<double> theta(q.size());
  for (std::size_t k = 0; k < q.size(); ++k) {
    const auto [d, t] = ellipse_frame_distance(r.e.rx, r.e.ry, to_ellipse_frame(r.e, q[k]));
    r.max_distance = std::max(r.max_distance, std::abs(d));
    theta[k] = t;
  }
  if (r.max_distance > eps) {
    r.why = arc_rejection::off_curve;
    return r;
  }
  // Unwrap the closest points' angles; they must run one way, stepping back by no more than
  // twice the tolerance along the curve (noise), and wind round less than once.
  double total = 0;
  std::vector<double> phi(q.size(), 0.0);
  for (std::size_t k = 1; k < q.size(); ++k) {
    total += std::remainder(theta[k] - theta[k - 1], 2 * std::numbers::pi);
    phi[k] = total;
  }
  const double dir = total >= 0 ? 1.0 : -1.0;
  double ahead = 0;
  for (std::size_t k = 1; k < q.size(); ++k) {
    ahead = std::max(ahead, dir * phi[k]);
    const double speed = std::hypot(r.e.rx * std::sin(theta[k]), r.e.ry * std::cos(theta[k]));
    if ((ahead - dir * phi[k]) * speed > 2 * eps) {
      r.why = arc_rejection::not_monotone;
      return r;
    }
  }
  if (std::abs(total) < o.min_sweep) {
    r.why = arc_rejection::sweep_too_small;
    return r;
  }
  if (std::abs(total) > 2 * std::numbers::pi) {
    r.why = arc_rejection::sweep_too_large;
    return r;
  }
  r.start = theta.front();
  r.sweep = total;
  r.why = arc_rejection::none;
  return r;
}

/// Fits and checks an ellipse through q: the conic fit, then (optionally) its refinement; the
/// refined ellipse when it passes check_arc, else the algebraic one when that passes, else the
/// refined one's rejection. `eps` is the tolerance and `size` the drawing's size, in q's units.
/// O(n × refinement steps).
template <class = void>
arc_reading read_arc(const std::vector<glm::dvec2>& q, const arc_detection_options& o, double eps,
                     double size) {
  arc_reading r;
  if (q.size() < std::max<std::size_t>(o.min_arc_samples, 5)) {
    r.why = arc_rejection::too_few_samples;
    return r;
  }
  ellipse_params algebraic;
  if (!direct_ellipse_fit(q, algebraic)) return r;
  if (!o.refine || !(std::max(algebraic.rx, algebraic.ry) <= o.max_semi_axis * size))
    return check_arc(q, algebraic, o, eps, size);
  ellipse_params refined = algebraic;
  const std::size_t steps = refine_ellipse(q, refined, o.max_semi_axis * size);
  r = check_arc(q, refined, o, eps, size);
  r.iterations = steps;
  if (r.why == arc_rejection::none) return r;
  arc_reading a = check_arc(q, algebraic, o, eps, size);
  a.iterations = steps;
  return a.why == arc_rejection::none ? a : r;
}

}  // namespace detail

template <std::ranges::input_range R>
requires Point2<std::ranges::range_value_t<R>>
auto fit_ellipse(const R& points, bool refine) {
  using P = std::ranges::range_value_t<R>;
  std::vector<glm::dvec2> q;
  for (const auto& p : points) q.push_back(to_dvec2(P(p)));
  // The centre is the origin until a fit sets it: P need not be default-constructible.
  ellipse_fit<P> out{.centre = from_dvec2<P>(glm::dvec2(0.0))};
  detail::ellipse_params e;
  if (!detail::direct_ellipse_fit(q, e)) return out;
  if (refine) out.iterations = detail::refine_ellipse(q, e, std::numeric_limits<double>::infinity());
  e = detail::normalised(e);
  out.rejection = arc_rejection::none;
  out.centre = from_dvec2<P>(e.c);
  out.rx = e.rx, out.ry = e.ry, out.rotation = e.rot;
  out.max_distance = detail::max_distance(q, e);
  return out;
}

namespace detail {

/// The drawn ellipse of the circle centre c, radius r, of the plane whose unit axes the view
/// maps to u and v: the semi-axes are r times the singular values of [u v]. O(1).
template <class = void>
ellipse_params view_circle_ellipse(glm::dvec2 c, double r, glm::dvec2 u, glm::dvec2 v) {
  Eigen::Matrix2d a;
  a << u.x, v.x, u.y, v.y;
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(a, Eigen::ComputeFullU);
  const Eigen::Vector2d major = svd.matrixU().col(0);
  return normalised(
      {c, r * svd.singularValues()(0), r * svd.singularValues()(1), std::atan2(major(1), major(0))});
}

/// A view circle's parameters in the fit: centre and log radius (a positive radius whatever the
/// step). The closest point's derivative is the identity for the centre and the point's offset
/// from the centre for the log radius.
template <class = void>
struct view_circle_model {
  glm::dvec2 u, v;
  std::optional<ellipse_params> ellipse(const Eigen::VectorXd& x) const {
    const double r = std::exp(x(2));
    if (!(r > 0) || !std::isfinite(r) || !std::isfinite(x(0)) || !std::isfinite(x(1))) return std::nullopt;
    return view_circle_ellipse({x(0), x(1)}, r, u, v);
  }
  Eigen::Matrix<double, 1, 3> row(const ellipse_params& e, double t) const {
    const closest_point_frame f = at_closest(e, t);
    return {-f.normal.x, -f.normal.y, -glm::dot(f.normal_frame, f.point_frame)};
  }
};

}  // namespace detail

template <std::ranges::input_range R>
requires Point2<std::ranges::range_value_t<R>>
auto fit_view_circle(const R& points, glm::dvec2 u, glm::dvec2 v) {
  using P = std::ranges::range_value_t<R>;
  view_circle_fit<P> out{.centre = from_dvec2<P>(glm::dvec2(0.0))};  // P need not be default-constructible
  const double det = u.x * v.y - u.y * v.x;
  if (!std::isfinite(det) || !(std::abs(det) > 1e-12 * std::max(glm::dot(u, u), glm::dot(v, v))))
    throw error(
        error_category::invalid_input,
        "fit_view_circle: the plane's axes u and v are parallel or not finite in the drawing: a face seen "
        "edge-on, whose circles are drawn as straight lines");
  std::vector<glm::dvec2> q;
  for (const auto& p : points) q.push_back(to_dvec2(P(p)));
  if (q.size() < 3) return out;
  // In the frame w = [u v]⁻¹ p the drawn ellipse is a circle: |w − w_c|² = r².
  const auto to_w = [&](glm::dvec2 p) {
    return glm::dvec2(v.y * p.x - v.x * p.y, -u.y * p.x + u.x * p.y) / det;
  };
  glm::dvec2 mean(0);
  for (const glm::dvec2& p : q) mean += to_w(p);
  mean /= static_cast<double>(q.size());
  Eigen::MatrixXd a(static_cast<Eigen::Index>(q.size()), 3);
  Eigen::VectorXd b(static_cast<Eigen::Index>(q.size()));
  for (std::size_t k = 0; k < q.size(); ++k) {
    const glm::dvec2 w = to_w(q[k]) - mean;
    const auto i = static_cast<Eigen::Index>(k);
    a(i, 0) = w.x, a(i, 1) = w.y, a(i, 2) = 1;
    b(i) = -glm::dot(w, w);
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < 3) return out;
  const Eigen::Vector3d kasa = qr.solve(b);
  const glm::dvec2 wc(-kasa(0) / 2, -kasa(1) / 2);
  const double r2 = glm::dot(wc, wc) - kasa(2);
  if (!(r2 > 0)) return out;
  glm::dvec2 c = mean + wc;
  c = u * c.x + v * c.y;
  // Levenberg–Marquardt over (centre, log radius): a positive radius whatever the step.
  const detail::view_circle_model<> model{u, v};
  Eigen::VectorXd x(3);
  x << c.x, c.y, 0.5 * std::log(r2);
  out.iterations = detail::fit_distances(q, model, x, 30);
  c = {x(0), x(1)};
  const double r = std::exp(x(2));
  const detail::ellipse_params e = detail::view_circle_ellipse(c, r, u, v);
  out.max_distance = detail::max_distance(q, e);
  out.rejection = arc_rejection::none;
  out.centre = from_dvec2<P>(c);
  out.radius = r;
  out.rx = e.rx, out.ry = e.ry, out.rotation = e.rot;
  return out;
}

template <std::ranges::input_range Strokes>
requires std::ranges::input_range<std::ranges::range_value_t<Strokes>> &&
    Point2<std::ranges::range_value_t<std::ranges::range_value_t<Strokes>>>
auto detect_arcs(const Strokes& strokes, const arc_detection_options& options) {
  using P = std::ranges::range_value_t<std::ranges::range_value_t<Strokes>>;
  const detail::stopwatch started;
  const arc_detection_options& o = options;
  if (!std::isfinite(o.tolerance) || !(o.tolerance > 0) || o.tolerance >= 0.5)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("detect_arcs: the tolerance ", detail::drawing_number(o.tolerance),
                                       " is not a number in (0, 0.5)"));
  if (!std::isfinite(o.drawing_size) || o.drawing_size < 0)
    throw error(
        error_category::invalid_input,
        cellforge::detail::cat("detect_arcs: drawing_size ", detail::drawing_number(o.drawing_size),
                               " is not a finite size >= 0 (0: take the strokes' bounding-box diagonal)"));
  if (!(o.min_sweep >= 0) || !(o.max_semi_axis > 0) || !std::isfinite(o.max_semi_axis))
    throw error(error_category::invalid_input, "detect_arcs: min_sweep must be >= 0 and max_semi_axis > 0");
  arc_detection_result<P> res;
  // Samples in double precision, consecutive repeats dropped.
  std::vector<std::vector<glm::dvec2>> all;
  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const auto& stroke : strokes) {
    std::vector<glm::dvec2> q;
    for (const auto& raw : stroke) {
      const glm::dvec2 p = to_dvec2(P(raw));
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("detect_arcs: sample ", std::to_string(q.size()), " of stroke ",
                                           std::to_string(all.size()), " is not finite"));
      if (q.empty() || p != q.back()) q.push_back(p);
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    all.push_back(std::move(q));
  }
  const double size =
      o.drawing_size > 0 ? o.drawing_size : (all.empty() || !(hi.x >= lo.x) ? 0.0 : glm::length(hi - lo));
  res.drawing_size = size;
  const double eps = o.tolerance * size;
  const auto reject = [&](arc_rejection why) { ++res.rejections[static_cast<std::size_t>(why)]; };
  // A piece whose points read() sets; built from values, so P need not be default-constructible.
  const P origin = from_dvec2<P>(glm::dvec2(0.0));
  const auto blank_piece = [&] {
    return stroke_piece<P>{.from = origin, .to = origin, .arc = {.centre = origin}};
  };
  for (std::size_t si = 0; si < all.size(); ++si) {
    const std::vector<glm::dvec2>& q = all[si];
    stroke_summary sum;
    sum.first_piece = res.pieces.size();
    sum.samples = q.size();
    if (q.size() < 2) {
      ++res.dropped_strokes;
      sum.whole = arc_rejection::too_few_samples;
      res.diagnostics.push_back(cellforge::detail::cat("stroke ", std::to_string(si),
                                                       ": fewer than two distinct samples; dropped"));
      res.strokes.push_back(sum);
      continue;
    }
    // Reads samples [a, b] as one line or one arc, or returns false with the arc's rejection.
    const auto read = [&](std::size_t a, std::size_t b, stroke_piece<P>& piece, arc_rejection& why) {
      piece.stroke = si, piece.first = a, piece.last = b;
      const auto [dev, ends] = detail::fit_line(q, a, b);
      if (dev <= eps) {
        piece.kind = stroke_piece_kind::line;
        piece.from = from_dvec2<P>(ends[0]), piece.to = from_dvec2<P>(ends[1]);
        piece.deviation = size > 0 ? dev / size : 0;
        piece.why_not_arc = why = arc_rejection::straight;
        return true;
      }
      ++res.fits;
      const std::vector<glm::dvec2> sub(q.begin() + static_cast<std::ptrdiff_t>(a),
                                        q.begin() + static_cast<std::ptrdiff_t>(b) + 1);
      const detail::arc_reading r = detail::read_arc(sub, o, eps, size);
      why = r.why;
      if (r.why != arc_rejection::none) {
        reject(r.why);
        return false;
      }
      piece.kind = stroke_piece_kind::arc;
      piece.arc = {from_dvec2<P>(r.e.c), r.e.rx, r.e.ry, r.e.rot, r.start, r.sweep};
      piece.from = arc_point(piece.arc, 0.0), piece.to = arc_point(piece.arc, 1.0);
      piece.deviation = size > 0 ? r.max_distance / size : 0;
      piece.why_not_arc = arc_rejection::none;
      return true;
    };
    std::vector<stroke_piece<P>> pieces;
    // Depth-first over sample ranges, left part first, with an explicit stack (no recursion
    // depth to worry about on long strokes).
    std::vector<std::array<std::size_t, 2>> todo{{0, q.size() - 1}};
    bool top = true;
    while (!todo.empty()) {
      const auto [a, b] = todo.back();
      todo.pop_back();
      stroke_piece<P> piece = blank_piece();
      arc_rejection why = arc_rejection::none;
      const bool ok = read(a, b, piece, why);
      if (top) sum.whole = why, top = false;
      if (ok) {
        pieces.push_back(piece);
        continue;
      }
      if (b - a < 2) {  // two samples always fit a line; kept for safety
        piece.kind = stroke_piece_kind::line;
        piece.from = from_dvec2<P>(q[a]), piece.to = from_dvec2<P>(q[b]);
        pieces.push_back(piece);
        continue;
      }
      // The farthest sample from the chord (from the first sample when the chord closes).
      const glm::dvec2 p0 = q[a], p1 = q[b];
      const glm::dvec2 chord = p1 - p0;
      const double len = glm::length(chord);
      std::size_t split = a + 1;
      double far = -1;
      for (std::size_t k = a + 1; k < b; ++k) {
        const glm::dvec2 d = q[k] - p0;
        const double dist = len > eps ? std::abs(chord.x * d.y - chord.y * d.x) / len : glm::length(d);
        if (dist > far) far = dist, split = k;
      }
      ++res.splits;
      todo.push_back({split, b});
      todo.push_back({a, split});
    }
    // Join neighbours that together are one line or one arc, until none joins.
    for (bool joined = true; joined;) {
      joined = false;
      for (std::size_t i = 0; i + 1 < pieces.size(); ++i) {
        // Same kinds join into one of that kind; a line shorter than the arc beside it joins it
        // when the two are one arc (a piece cut across the point where a line runs on
        // tangentially into an arc is short and nearly straight).
        const stroke_piece<P>&l = pieces[i], &r = pieces[i + 1];
        const auto samples = [](const stroke_piece<P>& p) { return p.last - p.first; };
        const bool same = l.kind == r.kind;
        const bool into_arc =
            !same && (l.kind == stroke_piece_kind::line ? samples(l) < samples(r) : samples(r) < samples(l));
        if (!same && !into_arc) continue;
        const stroke_piece_kind want = same ? l.kind : stroke_piece_kind::arc;
        stroke_piece<P> both = blank_piece();
        arc_rejection why = arc_rejection::none;
        if (read(l.first, r.last, both, why) && both.kind == want) {
          pieces[i] = both;
          pieces.erase(pieces.begin() + static_cast<std::ptrdiff_t>(i) + 1);
          ++res.merges;
          joined = true;
        }
      }
    }
    std::size_t lines = 0, arcs = 0;
    for (const stroke_piece<P>& p : pieces) (p.kind == stroke_piece_kind::arc ? arcs : lines)++;
    res.num_lines += lines, res.num_arcs += arcs;
    if (pieces.size() > 1)
      res.diagnostics.push_back(cellforge::detail::cat(
          "stroke ", std::to_string(si),
          ": not one line or one arc (as one arc: ", std::string(to_string(sum.whole)), "); read as ",
          std::to_string(lines), " lines and ", std::to_string(arcs), " arcs"));
    if (const auto [crossings, at] = detail::self_crossings(q, 4 * eps); crossings > 0) {
      sum.self_crossings = crossings;
      ++res.self_crossing_strokes;
      res.diagnostics.push_back(cellforge::detail::cat(
          "stroke ", std::to_string(si), ": crosses itself ",
          (crossings == 1 ? std::string("once") : std::to_string(crossings) + " times"), ", first at (",
          detail::drawing_number(at.x), ", ", detail::drawing_number(at.y),
          "); read as its pieces, a crossing is no junction (draw a closed curve "
          "as strokes that meet at junctions)"));
    }
    sum.num_pieces = pieces.size();
    res.pieces.insert(res.pieces.end(), pieces.begin(), pieces.end());
    res.strokes.push_back(sum);
  }
  res.milliseconds = started.ms();
  return res;
}

}  // namespace cellforge
