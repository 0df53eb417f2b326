// SPDX-License-Identifier: MIT
#pragma once
// The engine of the rounds reconstruction (included by sketch/rounds.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <Eigen/Dense>
#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/rounded_solid.hpp"
#include "cellforge/sketch/drawing_to_cells.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/round_skeleton.hpp"
#include "cellforge/sketch/rounds.hpp"

namespace cellforge {

namespace detail::blends {

/// Newell normal (unit) and centroid of a face's outer loop, positions p. O(L).
template <class = void>
std::pair<glm::dvec3, glm::dvec3> plane_of(const std::vector<glm::dvec3>& p,
                                           const std::vector<std::uint32_t>& loop) {
  auto [n, c] = detail::sketch::loop_plane(p, loop);
  const double len = glm::length(n);
  return {len > 0 ? n / len : n, c};
}

/// Position of the edge a→b in a loop: k with loop[k] = a, loop[k+1] = b (+1) or the reverse
/// (−1), or 0 when the loop does not hold it. O(L).
template <class = void>
int edge_sense(const std::vector<std::uint32_t>& loop, std::uint32_t a, std::uint32_t b) {
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const std::uint32_t u = loop[k], v = loop[(k + 1) % loop.size()];
    if (u == a && v == b) return 1;
    if (u == b && v == a) return -1;
  }
  return 0;
}

/// Smooth residuals per blend (zero where undefined), for fitting a depth map: per end, the
/// lifted curve's conjugate semi-axes U, V seen along the edge give (U·U − V·V) / s and
/// 2 U·V / s (a circle has both 0); the ends' radius difference over their sum; per end, the
/// centre's offset from the axis over the radius (3 components).
inline constexpr std::size_t residuals_per_blend = 11;

/// round_attributes on the skeleton's junctions at X (face loops `faces`, the complex's
/// input_edge map); when `residuals` is given, it is filled with residuals_per_blend values per
/// blend. O(blends · F · L).
template <Point2 P>
std::vector<edge_round> attributes(const round_skeleton_result<P>& sk,
                                   const std::vector<std::vector<std::vector<std::uint32_t>>>& faces,
                                   const std::vector<glm::dvec3>& X,
                                   const std::vector<std::uint32_t>& input_edge,
                                   std::vector<std::string>& diagnostics, const rounds_options& options,
                                   std::vector<double>* residuals = nullptr) {
  if (residuals) residuals->assign(residuals_per_blend * sk.blends.size(), 0.0);
  std::vector<std::pair<glm::dvec3, glm::dvec3>> planes;
  for (const auto& f : faces) planes.push_back(plane_of(X, f[0]));
  std::vector<edge_round> out;
  for (std::size_t i = 0; i < sk.blends.size(); ++i) {
    const skeleton_blend<P>& b = sk.blends[i];
    edge_round r;
    r.blend = i;
    r.skeleton_edge = b.edge;
    r.junctions = b.junctions;
    r.kind = b.kind;
    r.convex = b.kind != blend_kind::fillet;
    const std::string who = cellforge::detail::cat("blend ", std::to_string(b.pair));
    for (std::size_t k = 0; k < input_edge.size(); ++k)
      if (input_edge[k] == b.edge) r.cell_edge = static_cast<std::uint32_t>(k);
    // Its two faces: the loops through the edge; its end faces: through a corner, not the edge.
    std::vector<std::size_t> on_edge;
    std::array<std::vector<std::size_t>, 2> at_end;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      if (edge_sense(faces[f][0], b.junctions[0], b.junctions[1]) != 0) {
        on_edge.push_back(f);
        continue;
      }
      for (std::size_t k = 0; k < 2; ++k)
        if (std::find(faces[f][0].begin(), faces[f][0].end(), b.junctions[k]) != faces[f][0].end())
          at_end[k].push_back(f);
    }
    if (on_edge.size() != 2 || at_end[0].size() != 1 || at_end[1].size() != 1) {
      diagnostics.push_back(who + ": its edge is on " + std::to_string(on_edge.size()) +
                            " faces and its corners on " + std::to_string(at_end[0].size()) + " and " +
                            std::to_string(at_end[1].size()) +
                            " end faces (two and one each wanted); no radius");
      out.push_back(r);
      continue;
    }
    r.faces = {on_edge[0], on_edge[1]};
    r.end_faces = {at_end[0][0], at_end[1][0]};
    const glm::dvec3 d = glm::normalize(X[b.junctions[1]] - X[b.junctions[0]]);
    // Into each face, square to the edge: a face's interior lies left of its loop about its normal.
    std::array<glm::dvec3, 2> t{};
    for (std::size_t s = 0; s < 2; ++s) {
      const int sense = edge_sense(faces[r.faces[s]][0], b.junctions[0], b.junctions[1]);
      t[s] = glm::normalize(glm::cross(planes[r.faces[s]].first, d * static_cast<double>(sense)));
    }
    r.wedge_angle = std::acos(std::clamp(glm::dot(t[0], t[1]), -1.0, 1.0));
    const glm::dvec3 bisector = glm::normalize(t[0] + t[1]);
    const double reach = 1.0 / std::sin(0.5 * r.wedge_angle);  // edge → axis, per unit radius
    // The 2D reading of each end curve: a circle square to the edge has its minor axis along it.
    const glm::dvec2 axis2 = b.axis / std::max(glm::length(b.axis), 1e-300);
    std::array<double, 2> major{};
    for (std::size_t k = 0; k < 2; ++k) {
      const elliptical_arc<P>& e = b.curves[k];
      const bool x_major = std::abs(e.rx) >= std::abs(e.ry);
      major[k] = std::max(std::abs(e.rx), std::abs(e.ry));
      r.axis_ratio[k] = major[k] > 0 ? std::min(std::abs(e.rx), std::abs(e.ry)) / major[k] : 0;
      const double m = e.rotation + (x_major ? 0.5 * std::numbers::pi : 0.0);
      r.circle_angle[k] = std::asin(std::min(1.0, std::abs(std::cos(m) * axis2.y - std::sin(m) * axis2.x)));
    }
    bool lifted = true;
    std::array<glm::dvec3, 2> centre{};
    for (std::size_t k = 0; k < 2; ++k) {
      const glm::dvec3 n = planes[r.end_faces[k]].first, c = planes[r.end_faces[k]].second;
      if (!(std::abs(n.z) > 1e-6)) {
        diagnostics.push_back(who + ": end face " + std::to_string(r.end_faces[k]) +
                              " is seen edge-on; its curve cannot be lifted");
        lifted = false;
        break;
      }
      // The ellipse's principal semi-axes, lifted onto the end plane, then seen along the edge.
      const elliptical_arc<P>& e = b.curves[k];
      const glm::dvec2 A = e.rx * glm::dvec2(std::cos(e.rotation), std::sin(e.rotation));
      const glm::dvec2 B = e.ry * glm::dvec2(-std::sin(e.rotation), std::cos(e.rotation));
      const auto lift = [&](glm::dvec2 w) { return glm::dvec3(w, -(n.x * w.x + n.y * w.y) / n.z); };
      const glm::dvec2 q = to_dvec2(e.centre);
      centre[k] = glm::dvec3(q, c.z + lift(q - glm::dvec2(c.x, c.y)).z);
      glm::dvec3 U = lift(A), V = lift(B);
      U -= glm::dot(U, d) * d, V -= glm::dot(V, d) * d;
      // Semi-axes a ≥ b of the seen curve: a² and b² are the eigenvalues of the Gram matrix.
      const double s = glm::dot(U, U) + glm::dot(V, V), det = glm::length(glm::cross(U, V));
      const double root = std::sqrt(std::max(0.0, 0.25 * s * s - det * det));
      const double a = std::sqrt(0.5 * s + root), bb = std::sqrt(std::max(0.0, 0.5 * s - root));
      r.end_radius[k] = std::sqrt(det);
      r.roundness_defect[k] = a > 0 ? 1 - bb / a : 1;
      if (residuals && s > 0) {
        (*residuals)[residuals_per_blend * i + 2 * k] = (glm::dot(U, U) - glm::dot(V, V)) / s;
        (*residuals)[residuals_per_blend * i + 2 * k + 1] = 2 * glm::dot(U, V) / s;
      }
    }
    const auto by_circles = [&](const std::string& why) {
      if (r.circle_angle[0] > options.circle_angle || r.circle_angle[1] > options.circle_angle) {
        diagnostics.push_back(who + ": " + why +
                              ", and its end curves are not circles square to the edge; no radius");
        return;
      }
      r.source = radius_source::circle_2d;
      r.end_radius = major;
      r.radius = 0.5 * (major[0] + major[1]);
      r.radius_spread = std::abs(major[0] - major[1]) / r.radius;
      r.setback = r.radius / std::tan(0.5 * r.wedge_angle);
      // Parallel end faces: one foreshortening.
      r.consistent =
          std::max(r.radius_spread, std::abs(r.axis_ratio[0] - r.axis_ratio[1])) <= options.consistency;
      diagnostics.push_back(who + ": " + why + "; its radius is its circles' major semi-axis in the drawing");
    };
    if (!lifted) {
      by_circles("its end curves cannot be lifted");
      out.push_back(r);
      continue;
    }
    r.source = radius_source::lifted;
    r.radius = 0.5 * (r.end_radius[0] + r.end_radius[1]);
    r.radius_spread = r.radius > 0 ? std::abs(r.end_radius[0] - r.end_radius[1]) / r.radius : 1;
    r.setback = r.radius / std::tan(0.5 * r.wedge_angle);
    for (std::size_t k = 0; k < 2; ++k) {
      // The axis: the edge moved by radius / sin(angle / 2) along the wedge's bisector.
      glm::dvec3 off = centre[k] - (X[b.junctions[0]] + r.radius * reach * bisector);
      off -= glm::dot(off, d) * d;
      r.centre_offset[k] = r.radius > 0 ? glm::length(off) / r.radius : 1;
      if (residuals && r.radius > 0)
        for (int c = 0; c < 3; ++c)
          (*residuals)[residuals_per_blend * i + 5 + 3 * k + static_cast<std::size_t>(c)] = off[c] / r.radius;
    }
    if (residuals && r.radius > 0)
      (*residuals)[residuals_per_blend * i + 4] = 0.5 * (r.end_radius[0] - r.end_radius[1]) / r.radius;
    const double worst = std::max({r.radius_spread, r.roundness_defect[0], r.roundness_defect[1],
                                   r.centre_offset[0], r.centre_offset[1]});
    r.consistent = r.radius > 0 && worst <= options.consistency;
    if (!r.consistent)
      by_circles(
          cellforge::detail::cat("its end curves lifted onto the reading disagree with a circular blend by ",
                                 std::to_string(worst), " (the reading is not metric?)"));
    out.push_back(r);
  }
  return out;
}

/// The depth map z → k z + a x + b y that makes a reading metric, from the blends whose end
/// curves are circles square to their edges: a parallel view's planar readings of a polyhedron
/// differ from the true one by such a map (x, y are the drawing's), and each circle fixes its
/// edge's true depth extent (|drawing length| · ratio / √(1 − ratio²), ratio its minor over major
/// semi-axis) and its end planes' true slopes (square to the edge): three equations per blend,
/// solved by least squares (Eigen). The first circle's sign picks the reading (the Necker mirror
/// is free); each other's sign is the one the first predicts. false when no circle is found or
/// the system is singular. O(blends).
template <class = void>
bool metric_map(const std::vector<edge_round>& rounds,
                const std::vector<std::vector<std::vector<std::uint32_t>>>& faces,
                const std::vector<glm::dvec3>& X, const rounds_options& options, std::array<double, 3>& kab) {
  std::vector<std::array<double, 4>> rows;  // k, a, b coefficients and the right-hand side
  std::array<double, 3> first{};
  bool have_first = false;
  for (const auto& r : rounds) {
    if (r.circle_angle[0] > options.circle_angle || r.circle_angle[1] > options.circle_angle) continue;
    if (r.end_faces[0] == r.end_faces[1] && r.faces[0] == r.faces[1]) continue;  // no faces found
    const double ratio = 0.5 * (r.axis_ratio[0] + r.axis_ratio[1]);
    if (!(ratio < 1 - 1e-9)) continue;
    const glm::dvec3 e = X[r.junctions[1]] - X[r.junctions[0]];
    const double len2 = std::hypot(e.x, e.y);
    double ez = len2 * ratio / std::sqrt(1 - ratio * ratio);  // the true depth extent, up to sign
    if (have_first && first[0] * e.z + first[1] * e.x + first[2] * e.y < 0) ez = -ez;
    rows.push_back({e.z, e.x, e.y, ez});
    for (const std::size_t f : r.end_faces) {
      const glm::dvec3 n = plane_of(X, faces[f][0]).first;
      if (!(std::abs(n.z) > 1e-6)) continue;
      // Slopes: the reading's plane z = p x + q y; the true one square to (e.x, e.y, ez).
      rows.push_back({-n.x / n.z, 1, 0, -e.x / ez});
      rows.push_back({-n.y / n.z, 0, 1, -e.y / ez});
    }
    if (!have_first && rows.size() >= 3) {
      Eigen::Matrix3d A;
      Eigen::Vector3d y;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) A(i, j) = rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
        y(i) = rows[static_cast<std::size_t>(i)][3];
      }
      const Eigen::ColPivHouseholderQR<Eigen::Matrix3d> qr(A);
      if (qr.rank() < 3) return false;
      const Eigen::Vector3d x = qr.solve(y);
      first = {x(0), x(1), x(2)};
      have_first = true;
    }
  }
  if (!have_first) return false;
  Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), 3);
  Eigen::VectorXd y(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = 0; j < 3; ++j)
      A(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rows[i][j];
    y(static_cast<Eigen::Index>(i)) = rows[i][3];
  }
  const Eigen::VectorXd x = A.colPivHouseholderQr().solve(y);
  kab = {x(0), x(1), x(2)};
  return std::isfinite(kab[0]) && std::abs(kab[0]) > 1e-9;
}

/// The readings X mapped by z → k z + a x + b y.
template <class = void>
std::vector<glm::dvec3> depth_mapped(const std::vector<glm::dvec3>& X, const std::array<double, 3>& kab) {
  std::vector<glm::dvec3> Y = X;
  for (auto& y : Y) y.z = kab[0] * y.z + kab[1] * y.x + kab[2] * y.y;
  return Y;
}

/// The residual functor of Eigen's Levenberg–Marquardt over (k, a, b): every blend's end curves
/// lifted onto the mapped reading should be circles of one radius about the blend's axis.
template <Point2 P>
struct depth_map_functor {
  using Scalar = double;
  using InputType = Eigen::VectorXd;
  using ValueType = Eigen::VectorXd;
  using JacobianType = Eigen::MatrixXd;
  enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };
  const round_skeleton_result<P>* sk;
  const std::vector<std::vector<std::vector<std::uint32_t>>>* faces;
  const std::vector<glm::dvec3>* X;
  const std::vector<std::uint32_t>* input_edge;
  const rounds_options* options;
  Eigen::Index inputs() const { return 3; }
  Eigen::Index values() const { return static_cast<Eigen::Index>(residuals_per_blend * sk->blends.size()); }
  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) const {
    std::vector<std::string> notes;
    std::vector<double> res;
    attributes(*sk, *faces, depth_mapped(*X, {x(0), x(1), x(2)}), *input_edge, notes, *options, &res);
    for (std::size_t i = 0; i < res.size(); ++i)
      f(static_cast<Eigen::Index>(i)) = std::isfinite(res[i]) ? res[i] : 1.0;
    return 0;
  }
};

/// The depth map that makes every blend circular, by Levenberg–Marquardt from `start` (numeric
/// Jacobian; three unknowns, residuals_per_blend per blend). Returns the squared residual norm
/// and sets kab. O(iterations · blends · F · L).
template <Point2 P>
double fit_depth_map(const round_skeleton_result<P>& sk,
                     const std::vector<std::vector<std::vector<std::uint32_t>>>& faces,
                     const std::vector<glm::dvec3>& X, const std::vector<std::uint32_t>& input_edge,
                     const rounds_options& options, std::array<double, 3>& kab) {
  const depth_map_functor<P> f{&sk, &faces, &X, &input_edge, &options};
  Eigen::NumericalDiff<depth_map_functor<P>> nd(f);
  Eigen::LevenbergMarquardt<Eigen::NumericalDiff<depth_map_functor<P>>> lm(nd);
  lm.parameters.maxfev = 400;
  lm.parameters.xtol = 1e-12;
  lm.parameters.ftol = 1e-14;
  Eigen::VectorXd x(3);
  x << kab[0], kab[1], kab[2];
  lm.minimize(x);
  Eigen::VectorXd fv(f.values());
  f(x, fv);
  kab = {x(0), x(1), x(2)};
  return fv.squaredNorm();
}

}  // namespace detail::blends

template <Point3 Q, Point2 P>
std::vector<edge_round> round_attributes(const round_skeleton_result<P>& sk,
                                         const drawing_result<Q, P>& reading,
                                         std::vector<std::string>& diagnostics,
                                         const rounds_options& options) {
  const std::size_t nv = sk.skeleton.points.size();
  if (reading.wire.points.size() != nv)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("round_attributes: the reading has ",
                                       std::to_string(reading.wire.points.size()),
                                       " junctions, the skeleton ", std::to_string(nv)));
  std::vector<glm::dvec3> X(nv);
  for (std::size_t j = 0; j < nv; ++j) X[j] = to_dvec3(reading.wire.points[j]);
  return detail::blends::attributes(sk, reading.face_loops, X, reading.cells.input_edge, diagnostics,
                                    options);
}

template <Point3 Q, Point2 P>
rounds_result<Q, P> reconstruct_rounds(const arc_drawing<P>& d, const rounds_options& options) {
  const detail::stopwatch t_start;
  rounds_result<Q, P> out;
  out.skeleton = round_skeleton(d, options.skeleton);
  out.diagnostics = out.skeleton.diagnostics;
  if (!out.skeleton.validation.ok()) {
    // Loose ends in the skeleton usually come from arcs that found no partner: that is the
    // cause, in the input's numbering, so it comes first; the skeleton's defect follows, its
    // junction named in the input's numbering too (the skeleton renumbers them).
    const auto& sk = out.skeleton;
    std::string why = "reconstruct_rounds: ";
    for (const std::string& d : sk.pairing.diagnostics)
      if (d.find("has no partner") != std::string::npos) why += d + "; ";
    if (!sk.pairing.unpaired.empty()) why += "without a partner an arc cannot be a blend, so ";
    why += cellforge::detail::cat("the skeleton is not a readable drawing: ", sk.validation.message);
    if (const std::size_t j = sk.validation.junction; j != drawing_validation::npos) {
      const std::size_t first_corner = sk.skeleton.points.size() - sk.new_junctions;
      if (j < first_corner) {
        const auto at =
            std::find(sk.junction_map.begin(), sk.junction_map.end(), static_cast<std::uint32_t>(j));
        if (at != sk.junction_map.end())
          why += cellforge::detail::cat(" (skeleton junction ", std::to_string(j), " is junction ",
                                        std::to_string(at - sk.junction_map.begin()), " of the drawing)");
      } else if (j - first_corner < 2 * sk.pairing.pairs.size()) {
        const std::size_t pair = (j - first_corner) / 2, end = (j - first_corner) % 2;
        why += cellforge::detail::cat(" (skeleton junction ", std::to_string(j), " is the corner of end ",
                                      std::to_string(end), " of arc pair ", std::to_string(pair), ", arcs");
        for (const std::uint32_t a : sk.pairing.pairs[pair].arcs[end])
          why += cellforge::detail::cat(" ", std::to_string(a));
        why += ")";
      }
    }
    throw error(error_category::invalid_input, why);
  }
  out.reading = drawing_to_cells<Q>(out.skeleton.skeleton, options.reading);
  const std::size_t nv = out.skeleton.skeleton.points.size();
  std::vector<glm::dvec3> X(nv);
  for (std::size_t j = 0; j < nv; ++j) X[j] = to_dvec3(out.reading.wire.points[j]);
  const auto& faces = out.reading.face_loops;
  const auto& input_edge = out.reading.cells.input_edge;
  std::vector<std::string> notes;
  out.rounds = detail::blends::attributes(out.skeleton, faces, X, input_edge, notes, options);
  const bool metric = std::all_of(out.rounds.begin(), out.rounds.end(), [](const edge_round& r) {
    return r.source == radius_source::lifted && r.consistent;
  });
  std::array<double, 3> kab{1, 0, 0};
  if (!metric) {
    // Starts: the circles' linear map when there is one, and the reading itself; the fit uses
    // every blend, square to its edge or not.
    std::vector<std::array<double, 3>> starts{{1, 0, 0}};
    if (std::array<double, 3> linear{}; detail::blends::metric_map(out.rounds, faces, X, options, linear))
      starts.insert(starts.begin(), linear);
    double best = std::numeric_limits<double>::infinity();
    for (auto start : starts) {
      const double value = detail::blends::fit_depth_map(out.skeleton, faces, X, input_edge, options, start);
      if (value < best && std::isfinite(start[0]) && std::abs(start[0]) > 1e-9) best = value, kab = start;
    }
  }
  if (!metric && kab != std::array<double, 3>{1, 0, 0}) {
    std::vector<glm::dvec3> Y = detail::blends::depth_mapped(X, kab);
    std::vector<std::string> again;
    auto rounds = detail::blends::attributes(out.skeleton, faces, Y, input_edge, again, options);
    const auto count = [](const std::vector<edge_round>& v) {
      return std::count_if(v.begin(), v.end(), [](const edge_round& r) {
        return r.source == radius_source::lifted && r.consistent;
      });
    };
    if (count(rounds) > count(out.rounds)) {
      out.rounds = std::move(rounds), notes = std::move(again), X = std::move(Y);
      out.depth_corrected = true;
      out.depth_map = kab;
      out.diagnostics.push_back(
          cellforge::detail::cat("the reading's blends are not circular; its depths are mapped by z -> ",
                                 std::to_string(kab[0]), " z + ", std::to_string(kab[1]), " x + ",
                                 std::to_string(kab[2]), " y, fitted so that its blends are circular"));
    }
  }
  out.diagnostics.insert(out.diagnostics.end(), notes.begin(), notes.end());
  // Categories a and c are the reading's (its faces towards the viewer or away), so they are
  // decided on the depths the radii were taken from.
  std::vector<double> depth;
  for (const auto& x : X) depth.push_back(x.z);
  try {
    const std::size_t said = out.skeleton.diagnostics.size();
    resolve_blend_categories(out.skeleton, depth);
    out.diagnostics.insert(out.diagnostics.end(),
                           out.skeleton.diagnostics.begin() + static_cast<std::ptrdiff_t>(said),
                           out.skeleton.diagnostics.end());
  } catch (const error& e) {
    out.diagnostics.push_back(
        cellforge::detail::cat(std::string("categories a and c left undecided: "), e.what()));
  }
  for (auto& r : out.rounds) r.category = out.skeleton.blends[r.blend].category;
  for (const auto& x : X) out.points.push_back(from_dvec3<Q>(x));
  for (const auto& r : out.rounds) ++(r.consistent ? out.consistent : out.inconsistent);
  out.milliseconds = t_start.ms();
  return out;
}

namespace detail::blends {

/// The skeleton's face loops (outer loops only) turned outward: coherent senses, all flipped
/// when the volume they bound is negative. Throws invalid_input naming `who` on a face with
/// holes. O(F · L).
template <class = void>
std::vector<std::vector<std::uint32_t>> outward_loops(
    const std::vector<std::vector<std::vector<std::uint32_t>>>& faces, const std::vector<glm::dvec3>& X,
    const std::string& who) {
  std::vector<std::vector<std::uint32_t>> outer;
  for (const auto& f : faces) {
    if (f.size() > 1)
      throw error(error_category::invalid_input, who + ": faces with holes are not rounded yet");
    outer.push_back(f[0]);
  }
  std::vector<int> sense = detail::coherent_senses(outer);
  double volume = 0;
  for (std::size_t l = 0; l < outer.size(); ++l)
    for (std::size_t k = 1; k + 1 < outer[l].size(); ++k)
      volume += sense[l] * glm::dot(X[outer[l][0]], glm::cross(X[outer[l][k]], X[outer[l][k + 1]]));
  for (std::size_t l = 0; l < outer.size(); ++l)
    if (sense[l] * volume < 0) std::reverse(outer[l].begin(), outer[l].end());
  return outer;
}

/// A blend's frame in 3D: its axis through `axis` along the edge d, its cross-section arc from
/// the axis towards the tangent line in faces[0] (u), turning towards faces[1] (v) through
/// sweep = π − wedge, and each end's plane (normal g, through corner c).
struct blend_frame {
  glm::dvec3 axis{0.0}, d{0.0}, u{0.0}, v{0.0};
  double radius = 0, sweep = 0;
  std::array<glm::dvec3, 2> g{}, c{};
  /// The arc's point at angle phi moved along the edge onto end plane k. O(1).
  glm::dvec3 at(double phi, std::size_t k) const {
    const glm::dvec3 q = axis + radius * (std::cos(phi) * u + std::sin(phi) * v);
    return q + d * (glm::dot(g[k], c[k] - q) / glm::dot(g[k], d));
  }
};

/// The frame of blend e on the outward loops `outer`, positions X: the axis is the edge moved
/// by radius / sin(wedge / 2) along the wedge's bisector. O(L).
template <class = void>
blend_frame frame_of(const edge_round& e, const std::vector<std::vector<std::uint32_t>>& outer,
                     const std::vector<glm::dvec3>& X) {
  blend_frame b;
  const glm::dvec3 A = X[e.junctions[0]];
  b.d = glm::normalize(X[e.junctions[1]] - A);
  std::array<glm::dvec3, 2> t{};
  for (std::size_t s = 0; s < 2; ++s) {
    const auto& loop = outer[e.faces[s]];
    const int sn = edge_sense(loop, e.junctions[0], e.junctions[1]);
    const glm::dvec3 n = plane_of(X, loop).first;
    t[s] = glm::normalize(glm::cross(n, b.d * static_cast<double>(sn)));
  }
  const double wedge = std::acos(std::clamp(glm::dot(t[0], t[1]), -1.0, 1.0));
  b.radius = e.radius;
  b.axis = A + e.radius / std::sin(0.5 * wedge) * glm::normalize(t[0] + t[1]);
  b.u = glm::normalize(A + e.setback * t[0] - b.axis);
  b.v = A + e.setback * t[1] - b.axis;
  b.v = glm::normalize(b.v - glm::dot(b.v, b.u) * b.u);
  b.sweep = std::numbers::pi - wedge;
  for (std::size_t k = 0; k < 2; ++k) {
    b.g[k] = plane_of(X, outer[e.end_faces[k]]).first;
    b.c[k] = X[e.junctions[k]];
  }
  return b;
}

/// Marks blend i's two junctions in `at` as its ends (invalid_input naming `who` when one is
/// already another blend's); false, counted in `skipped` with a note, when it has no radius. O(1).
template <class = void>
bool claim_ends(const edge_round& e, std::size_t i, std::vector<std::pair<std::uint32_t, std::uint32_t>>& at,
                std::size_t& skipped, std::vector<std::string>& diagnostics, const std::string& who) {
  if (!(e.radius > 0) || e.source == radius_source::none) {
    ++skipped;
    diagnostics.push_back(
        cellforge::detail::cat("blend ", std::to_string(e.blend), " has no radius; its edge stays sharp"));
    return false;
  }
  for (std::size_t k = 0; k < 2; ++k) {
    if (at[e.junctions[k]].first != ~std::uint32_t{0})
      throw error(error_category::invalid_input,
                  who + ": two blends meet at junction " + std::to_string(e.junctions[k]));
    at[e.junctions[k]] = {static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(k)};
  }
  return true;
}

}  // namespace detail::blends

template <Point3 Q, Point2 P>
rounded_mesh_result<Q> rounded_mesh(const rounds_result<Q, P>& r, const rounded_mesh_options& options) {
  const detail::stopwatch clock;
  rounded_mesh_result<Q> out;
  const auto& faces = r.reading.face_loops;
  const std::size_t nv = r.points.size();
  std::vector<glm::dvec3> X(nv);
  for (std::size_t j = 0; j < nv; ++j) X[j] = to_dvec3(r.points[j]);
  if (nv == 0) {
    out.milliseconds = clock.ms();
    return out;
  }
  glm::dvec3 lo = X[0], hi = X[0];
  for (const auto& x : X) lo = glm::min(lo, x), hi = glm::max(hi, x);
  const double tol = options.chord_tolerance * glm::length(glm::dvec2(hi - lo));
  const std::vector<std::vector<std::uint32_t>> outer =
      detail::blends::outward_loops(faces, X, "rounded_mesh");
  // Per junction: the blend end at it (blend, end), if any.
  constexpr std::uint32_t none = ~std::uint32_t{0};
  std::vector<std::pair<std::uint32_t, std::uint32_t>> at(nv, {none, none});
  std::vector<std::uint32_t> index(nv, none);
  const auto point = [&](const glm::dvec3& x) {
    out.mesh.points.push_back(from_dvec3<Q>(x));
    return static_cast<std::uint32_t>(out.mesh.points.size() - 1);
  };
  // Per blend and end: its arc's mesh points, from the tangent line in faces[0] to faces[1].
  std::vector<std::array<std::vector<std::uint32_t>, 2>> arc(r.rounds.size());
  std::vector<std::array<std::uint32_t, 2>> first_face(r.rounds.size());
  for (std::size_t i = 0; i < r.rounds.size(); ++i) {
    const edge_round& e = r.rounds[i];
    if (!detail::blends::claim_ends(e, i, at, out.skipped, out.diagnostics, "rounded_mesh")) continue;
    const detail::blends::blend_frame b = detail::blends::frame_of(e, outer, X);
    const double step = tol < e.radius ? 2 * std::acos(1 - tol / e.radius) : b.sweep;
    const int n = std::clamp(static_cast<int>(std::ceil(b.sweep / step)), 1, options.max_segments);
    for (std::size_t k = 0; k < 2; ++k)
      for (int m = 0; m <= n; ++m) arc[i][k].push_back(point(b.at(b.sweep * m / n, k)));
    // The strip, oriented against faces[0]'s loop along its trimmed edge.
    const bool along = detail::blends::edge_sense(outer[e.faces[0]], e.junctions[0], e.junctions[1]) > 0;
    const auto& a0 = arc[i][along ? 1 : 0];
    const auto& a1 = arc[i][along ? 0 : 1];
    for (int m = 0; m < n; ++m) {
      const auto mm = static_cast<std::size_t>(m);
      const std::array<std::uint32_t, 4> quad{a0[mm], a1[mm], a1[mm + 1], a0[mm + 1]};
      out.mesh.add_face(quad);
      out.face_source.push_back(-1 - static_cast<std::int64_t>(e.blend));
    }
    ++out.strips, out.strip_quads += static_cast<std::size_t>(n);
  }
  for (std::size_t f = 0; f < outer.size(); ++f) {
    const auto& loop = outer[f];
    std::vector<std::uint32_t> face;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const std::uint32_t j = loop[k], prev = loop[(k + loop.size() - 1) % loop.size()],
                          next = loop[(k + 1) % loop.size()];
      const auto [bi, end] = at[j];
      if (bi == none) {
        if (index[j] == none) index[j] = point(X[j]);
        face.push_back(index[j]);
        continue;
      }
      const edge_round& e = r.rounds[bi];
      const auto& curve = arc[bi][end];
      const std::uint32_t other = e.junctions[1 - end];
      if (f == e.faces[0] || f == e.faces[1]) {  // the tangent point in this face
        if (prev != other && next != other)
          throw error(error_category::invalid_input,
                      cellforge::detail::cat("rounded_mesh: face ", std::to_string(f),
                                             " holds a blend's corner but not its edge"));
        face.push_back(f == e.faces[0] ? curve.front() : curve.back());
      } else if (f == e.end_faces[end]) {  // the end curve, from prev's side to next's
        const bool prev_in_first = detail::blends::edge_sense(outer[e.faces[0]], prev, j) != 0;
        if (prev_in_first)
          face.insert(face.end(), curve.begin(), curve.end());
        else
          face.insert(face.end(), curve.rbegin(), curve.rend());
      } else {
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("rounded_mesh: junction ", std::to_string(j),
                                           " of a blend is on a fourth face"));
      }
    }
    out.mesh.add_face(face);
    out.face_source.push_back(static_cast<std::int64_t>(f));
  }
  out.milliseconds = clock.ms();
  return out;
}

template <Point3 Q, Point2 P>
rounded_brep_result rounded_brep(const rounds_result<Q, P>& r, const rounded_brep_options& options) {
  const detail::stopwatch clock;
  rounded_brep_result out;
  rounded_solid& S = out.solid;
  constexpr std::uint32_t none = rounded_solid::npos;
  const auto& faces = r.reading.face_loops;
  const std::size_t nv = r.points.size();
  std::vector<glm::dvec3> X(nv);
  for (std::size_t j = 0; j < nv; ++j) X[j] = to_dvec3(r.points[j]);
  if (nv == 0 || faces.empty()) {
    out.diagnostics.push_back("rounded_brep: the reading has no faces");
    return out;
  }
  glm::dvec3 lo = X[0], hi = X[0];
  for (const auto& x : X) lo = glm::min(lo, x), hi = glm::max(hi, x);
  const double tol = options.tolerance * glm::length(hi - lo);
  const std::vector<std::vector<std::uint32_t>> outer =
      detail::blends::outward_loops(faces, X, "rounded_brep");
  double six = 0;
  for (const auto& l : outer)
    for (std::size_t k = 1; k + 1 < l.size(); ++k) six += glm::dot(X[l[0]], glm::cross(X[l[k]], X[l[k + 1]]));
  out.volume = six / 6;
  const auto point = [&](const glm::dvec3& x) {
    S.points.push_back(x);
    return static_cast<std::uint32_t>(S.points.size() - 1);
  };
  // Per junction the blend end at it; per blend and end its tangent points in faces[0], faces[1].
  std::vector<std::pair<std::uint32_t, std::uint32_t>> at(nv, {none, none});
  std::vector<std::array<std::array<std::uint32_t, 2>, 2>> tangent(r.rounds.size());
  std::vector<std::array<std::uint32_t, 2>> arc(r.rounds.size(), {none, none});
  std::vector<std::uint32_t> cylinder(r.rounds.size(), none);
  for (std::size_t i = 0; i < r.rounds.size(); ++i) {
    const edge_round& e = r.rounds[i];
    if (!detail::blends::claim_ends(e, i, at, out.skipped, out.diagnostics, "rounded_brep")) continue;
    const detail::blends::blend_frame b = detail::blends::frame_of(e, outer, X);
    const double half = 0.5 * b.sweep;
    const glm::dvec3 middle = std::cos(half) * b.u + std::sin(half) * b.v;
    cylinder[i] = static_cast<std::uint32_t>(S.blends.size());
    S.blends.push_back({b.axis, b.d, e.radius, e.convex, middle});
    for (std::size_t k = 0; k < 2; ++k) {
      tangent[i][k] = {point(b.at(0, k)), point(b.at(b.sweep, k))};
      arc[i][k] = static_cast<std::uint32_t>(S.edges.size());
      S.edges.push_back({tangent[i][k][0], tangent[i][k][1], cylinder[i], b.g[k]});
      ++out.arcs;
    }
    // The blend's cross-section (in the plane through the edge's first corner, square to it):
    // the kite edge, tangent point, axis, tangent point less the sector; its prism between
    // the end planes has the area times the length along d through the section's centroid.
    const glm::dvec3 A = X[e.junctions[0]];
    const glm::dvec3 p0 = b.axis + e.radius * b.u,
                     p1 = b.axis + e.radius * (std::cos(b.sweep) * b.u + std::sin(b.sweep) * b.v);
    const double k0 = 0.5 * glm::length(glm::cross(p0 - b.axis, A - b.axis)),
                 k1 = 0.5 * glm::length(glm::cross(A - b.axis, p1 - b.axis));
    const double sector = 0.5 * e.radius * e.radius * b.sweep;
    const glm::dvec3 kite_centroid = (k0 * (b.axis + p0 + A) + k1 * (b.axis + A + p1)) / (3 * (k0 + k1));
    const glm::dvec3 sector_centroid =
        b.axis + (half > 0 ? 2 * e.radius * std::sin(half) / (3 * half) : e.radius) * middle;
    const double area = k0 + k1 - sector;
    const glm::dvec3 c = ((k0 + k1) * kite_centroid - sector * sector_centroid) / area;
    const auto along = [&](std::size_t k) { return glm::dot(b.g[k], b.c[k] - c) / glm::dot(b.g[k], b.d); };
    out.volume += (e.convex ? -1 : 1) * area * std::abs(along(1) - along(0));
  }
  // Straight edges, one per pair of end points.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> lines;
  const auto line = [&](std::uint32_t a, std::uint32_t b) -> std::pair<std::uint32_t, bool> {
    if (a == b) throw error(error_category::invalid_input, "rounded_brep: a trimmed edge has length zero");
    const auto key = std::minmax(a, b);
    auto [it, fresh] = lines.try_emplace({key.first, key.second}, static_cast<std::uint32_t>(S.edges.size()));
    if (fresh) S.edges.push_back({a, b, none, glm::dvec3(0.0)}), ++out.lines;
    return {it->second, S.edges[it->second].a == a};
  };
  std::vector<std::uint32_t> corner(nv, none);
  for (std::size_t f = 0; f < outer.size(); ++f) {
    const auto& loop = outer[f];
    // The face's boundary points, each with the arc to the next one (none: a straight edge).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> items;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const std::uint32_t j = loop[k], prev = loop[(k + loop.size() - 1) % loop.size()],
                          next = loop[(k + 1) % loop.size()];
      const auto [bi, end] = at[j];
      if (bi == none) {
        if (corner[j] == none) corner[j] = point(X[j]);
        items.push_back({corner[j], none});
        continue;
      }
      const edge_round& e = r.rounds[bi];
      if (f == e.faces[0] || f == e.faces[1]) {
        const std::uint32_t other = e.junctions[1 - end];
        if (prev != other && next != other)
          throw error(error_category::invalid_input,
                      cellforge::detail::cat("rounded_brep: face ", std::to_string(f),
                                             " holds a blend's corner but not its edge"));
        items.push_back({tangent[bi][end][f == e.faces[0] ? 0 : 1], none});
      } else if (f == e.end_faces[end]) {
        const std::size_t first = detail::blends::edge_sense(outer[e.faces[0]], prev, j) != 0 ? 0 : 1;
        items.push_back({tangent[bi][end][first], arc[bi][end]});
        items.push_back({tangent[bi][end][1 - first], none});
      } else {
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("rounded_brep: junction ", std::to_string(j),
                                           " of a blend is on a fourth face"));
      }
    }
    rounded_solid::face face;
    face.normal = detail::blends::plane_of(X, loop).first;
    for (std::size_t m = 0; m < items.size(); ++m) {
      const std::uint32_t a = items[m].first, b = items[(m + 1) % items.size()].first;
      if (items[m].second != none)
        face.loop.push_back({items[m].second, S.edges[items[m].second].a == a});
      else
        face.loop.push_back(line(a, b));
    }
    S.faces.push_back(std::move(face));
    ++out.planar_faces;
  }
  // Per blend its cylinder face, run against faces[0]'s use of the first tangent line.
  for (std::size_t i = 0; i < r.rounds.size(); ++i) {
    if (cylinder[i] == none) continue;
    const auto& T = tangent[i];
    rounded_solid::face face;
    face.blend = cylinder[i];
    face.loop = {line(T[0][0], T[1][0]), {arc[i][1], true}, line(T[1][1], T[0][1]), {arc[i][0], false}};
    const auto& beside = S.faces[r.rounds[i].faces[0]].loop;
    if (std::find(beside.begin(), beside.end(), face.loop[0]) != beside.end()) {
      std::reverse(face.loop.begin(), face.loop.end());
      for (auto& use : face.loop) use.second = !use.second;
    }
    S.faces.push_back(std::move(face));
    ++out.blend_faces;
  }
  // The check of the answer: a closed, coherently oriented shell on its surfaces, of positive volume.
  std::vector<std::array<int, 2>> uses(S.edges.size(), {0, 0});
  for (const auto& f : S.faces)
    for (const auto& [e, forward] : f.loop) ++uses[e][forward ? 0 : 1];
  std::size_t open = 0;
  for (std::size_t e = 0; e < uses.size(); ++e)
    if (uses[e][0] != 1 || uses[e][1] != 1)
      if (++open <= 5)
        out.diagnostics.push_back(cellforge::detail::cat(
            "rounded_brep: edge ", std::to_string(e), " is used ", std::to_string(uses[e][0]),
            " times forward and ", std::to_string(uses[e][1]), " backward (once each wanted)"));
  double off = 0;
  for (const auto& f : S.faces)
    for (const auto& [e, forward] : f.loop)
      for (const std::uint32_t p : {S.edges[e].a, S.edges[e].b}) {
        const glm::dvec3 x = S.points[p];
        if (f.blend == none) {
          const glm::dvec3 x0 = S.points[S.edges[f.loop[0].first].a];
          off = std::max(off, std::abs(glm::dot(x - x0, f.normal)));
        } else {
          const rounded_solid::cylinder& c = S.blends[f.blend];
          const glm::dvec3 q = x - c.point;
          off = std::max(off, std::abs(glm::length(q - glm::dot(q, c.axis) * c.axis) - c.radius));
        }
      }
  if (off > tol)
    out.diagnostics.push_back(cellforge::detail::cat("rounded_brep: a vertex is ", std::to_string(off),
                                                     " from a surface of its face, more than ",
                                                     std::to_string(tol)));
  if (!(out.volume > 0)) out.diagnostics.push_back("rounded_brep: the solid's volume is not positive");
  out.ok = open == 0 && off <= tol && out.volume > 0;
  out.milliseconds = clock.ms();
  return out;
}

#if defined(CELLFORGE_EXTERN_SKETCH)
// Compiled once in the file that includes cellforge/sketch/instantiate.hpp (docs/sketch.md).
extern template rounds_result<glm::dvec3, glm::dvec2> reconstruct_rounds<glm::dvec3, glm::dvec2>(
    const arc_drawing<glm::dvec2>&, const rounds_options&);
extern template rounded_mesh_result<glm::dvec3> rounded_mesh<glm::dvec3, glm::dvec2>(
    const rounds_result<glm::dvec3, glm::dvec2>&, const rounded_mesh_options&);
extern template rounded_brep_result rounded_brep<glm::dvec3, glm::dvec2>(
    const rounds_result<glm::dvec3, glm::dvec2>&, const rounded_brep_options&);
#endif

}  // namespace cellforge
