// SPDX-License-Identifier: MIT
#pragma once
// The engine of inflation (included by sketch/inflation.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <unsupported/Eigen/NonLinearOptimization>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/certify.hpp"
#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/sketch/inflation.hpp"
#include "cellforge/sketch/line_drawing.hpp"
#include "cellforge/wireframe/wire_graph.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

namespace cellforge {

namespace detail {
/// A drawing copied into normalised coordinates (centred on its bounding box, unit diagonal),
/// its loops checked, and the relations the stages share.
template <class = void>
struct inflation_problem {
  std::vector<glm::dvec2> p;    // normalised positions
  std::vector<glm::dvec2> raw;  // the drawing's positions, kept exactly
  std::vector<std::array<std::uint32_t, 2>> edges;
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<std::uint32_t> loop_face;              // the face of each loop
  std::vector<std::vector<std::uint32_t>> incident;  // edges at each junction
  glm::dvec2 centre{0.0};
  double size = 1.0;  // bounding-box diagonal of the drawing
  // Planarity constraints: z_d − α z_a − β z_b − γ z_c = 0.
  struct plane_row {
    std::uint32_t d, a, b, c;
    double alpha, beta, gamma;
  };
  std::vector<plane_row> rows;
};

/// Angle of a 2D direction modulo π, in [0, π). O(1).
template <class = void>
double line_angle(glm::dvec2 d) {
  double a = std::atan2(d.y, d.x);
  if (a < 0) a += std::numbers::pi;
  if (a >= std::numbers::pi) a -= std::numbers::pi;
  return a;
}

/// Distance between two line angles modulo π. O(1).
template <class = void>
double angle_distance(double a, double b) {
  const double d = std::fmod(std::abs(a - b), std::numbers::pi);
  return std::min(d, std::numbers::pi - d);
}

/// Reads and checks a drawing and its faces (each: outer loop, then holes); builds the
/// planarity rows. Throws invalid_input naming the junction, edge or loop at fault. O(V + E log E + L).
template <LineDrawing D>
inflation_problem<> make_inflation_problem(
    const D& drawing, const std::vector<std::vector<std::vector<std::uint32_t>>>& faces) {
  using T = line_drawing_traits<D>;
  inflation_problem<> pr;
  const std::size_t nv = T::num_junctions(drawing), ne = T::num_edges(drawing);
  if (nv < 4 || ne < 6)
    throw error(
        error_category::invalid_input,
        cellforge::detail::cat("inflate: a drawing of a solid has at least 4 junctions and 6 edges (got ",
                               std::to_string(nv), " and ", std::to_string(ne), ")"));
  if (nv >= std::numeric_limits<std::uint32_t>::max())
    throw error(error_category::invalid_input, "inflate: more than 2^32 - 2 junctions");
  pr.p.reserve(nv);
  glm::dvec2 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < nv; ++i) {
    const glm::dvec2 q = to_dvec2(drawing_point_t<D>(T::position(drawing, i)));
    if (!std::isfinite(q.x) || !std::isfinite(q.y))
      throw error(
          error_category::invalid_input,
          cellforge::detail::cat("inflate: junction ", std::to_string(i), " has a non-finite coordinate"));
    pr.p.push_back(q);
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  {  // scaled before it is squared: a drawing 4e300 across has an extent (8e300 overflowed)
    const glm::dvec2 span = hi - lo;
    const double big = std::max(span.x, span.y);
    pr.size = big > 0 && std::isfinite(big) ? big * glm::length(span / big) : big;
  }
  if (!(pr.size > 0) || !std::isfinite(pr.size))
    throw error(error_category::invalid_input, "inflate: the drawing has no extent");
  pr.centre = 0.5 * (lo + hi);
  pr.raw = pr.p;
  for (auto& q : pr.p) q = (q - pr.centre) / pr.size;
  std::vector<std::array<std::uint32_t, 2>> sorted;
  pr.incident.resize(nv);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::array<std::size_t, 2> ab = T::endpoints(drawing, e);
    if (ab[0] >= nv || ab[1] >= nv || ab[0] == ab[1])
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("inflate: edge ", std::to_string(e),
                                         " joins no two distinct junctions of the drawing"));
    const std::array<std::uint32_t, 2> ed{static_cast<std::uint32_t>(ab[0]),
                                          static_cast<std::uint32_t>(ab[1])};
    if (glm::length(pr.p[ed[1]] - pr.p[ed[0]]) < 1e-12)
      throw error(error_category::invalid_input, cellforge::detail::cat("inflate: edge ", std::to_string(e),
                                                                        " has zero length in the drawing"));
    pr.edges.push_back(ed);
    pr.incident[ed[0]].push_back(static_cast<std::uint32_t>(e));
    pr.incident[ed[1]].push_back(static_cast<std::uint32_t>(e));
    sorted.push_back({std::min(ed[0], ed[1]), std::max(ed[0], ed[1])});
  }
  std::sort(sorted.begin(), sorted.end());
  if (faces.size() < 4)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("inflate: a solid needs at least 4 faces (got ",
                                       std::to_string(faces.size()), "); find the faces first"));
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (faces[f].empty())
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("inflate: face ", std::to_string(f), " has no loop"));
    for (std::size_t l = 0; l < faces[f].size(); ++l) {
      const auto& loop = faces[f][l];
      const std::string where = cellforge::detail::cat(
          "inflate: face ", std::to_string(f),
          (faces[f].size() > 1 ? cellforge::detail::cat(", loop ", std::to_string(l)) : std::string()));
      if (loop.size() < 3) throw error(error_category::invalid_input, where + " has fewer than 3 junctions");
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const std::uint32_t a = loop[k], b = loop[(k + 1) % loop.size()];
        if (a >= nv || b >= nv)
          throw error(error_category::invalid_input, where + " names junction " +
                                                         std::to_string(std::max(a, b)) +
                                                         " of a drawing with " + std::to_string(nv));
        if (!std::binary_search(sorted.begin(), sorted.end(), std::array{std::min(a, b), std::max(a, b)}))
          throw error(error_category::invalid_input,
                      where + " steps from junction " + std::to_string(a) + " to " + std::to_string(b) +
                          ", which no edge joins: the loops do not belong to this drawing");
      }
      pr.loops.push_back(loop);
      pr.loop_face.push_back(static_cast<std::uint32_t>(f));
    }
  }
  // Planarity rows: per face (all its loops), the reference triangle of largest area in the drawing.
  for (std::size_t f = 0; f < faces.size(); ++f) {
    std::vector<std::uint32_t> js;
    for (const auto& loop : faces[f]) js.insert(js.end(), loop.begin(), loop.end());
    std::sort(js.begin(), js.end());
    js.erase(std::unique(js.begin(), js.end()), js.end());
    if (js.size() < 4) continue;
    const std::uint32_t a = faces[f][0][0];
    std::uint32_t b = js[0], c = js[0];
    double far = -1;
    for (const auto v : js)
      if (glm::length(pr.p[v] - pr.p[a]) > far) far = glm::length(pr.p[v] - pr.p[a]), b = v;
    const glm::dvec2 u = pr.p[b] - pr.p[a];
    double best = -1;
    for (const auto v : js) {
      const glm::dvec2 w = pr.p[v] - pr.p[a];
      const double area = std::abs(u.x * w.y - u.y * w.x);
      if (area > best) best = area, c = v;
    }
    if (!(best > 1e-12))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("inflate: face ", std::to_string(f),
                                         " is a straight line in the drawing (a face seen edge-on)"));
    const glm::dvec2 v = pr.p[c] - pr.p[a];
    const double det = u.x * v.y - u.y * v.x;
    for (const auto d : js) {
      if (d == a || d == b || d == c) continue;
      const glm::dvec2 w = pr.p[d] - pr.p[a];
      const double beta = (w.x * v.y - w.y * v.x) / det, gamma = (u.x * w.y - u.y * w.x) / det;
      pr.rows.push_back({d, a, b, c, 1 - beta - gamma, beta, gamma});
    }
  }
  return pr;
}

/// z_d − (α z_a + β z_b + γ z_c) for a planarity (or convexity) row. O(1).
template <class Row, class Z>
double plane_residual(const Row& r, const Z& z) {
  return z[r.d] - (r.alpha * z[r.a] + r.beta * z[r.b] + r.gamma * z[r.c]);
}

/// The regularities the compliance functions measure, gathered once from the drawing.
template <class = void>
struct compliance_terms {
  std::vector<std::array<std::uint32_t, 3>> corners;  // (prev, junction, next) of face loops
  std::vector<std::array<std::uint32_t, 3>> right;    // corners that can be right angles
  std::vector<std::vector<std::uint32_t>> parallel;   // classes of 2D-parallel edges (≥ 2)
  std::vector<glm::dvec2> parallel_direction;         // per class
  // Convexity: h = scale · (z_d − α z_a − β z_b − γ z_c) ≤ 0 for a convex fold (empty: unused).
  // One row per (line, face F): at planar faces every corner of the next face off the line
  // gives the same h (its depth gap to F's plane is linear, 0 on the line, and scale is 1 over
  // the distance), so one stands for all `weight` of them.
  struct convex_row {
    std::uint32_t d, a, b, c;
    double alpha, beta, gamma, scale, weight;
  };
  std::vector<convex_row> convex;
  double convex_margin = 0.0;   // the hinge is max(0, h + margin)
  std::size_t planar_rows = 0;  // least-squares readings: the planarity rows as a term
  double convex_weight() const {
    double w = 0;
    for (const auto& r : convex) w += r.weight;
    return w;
  }
  std::size_t count() const {
    std::size_t n = 0;
    for (const auto& c : parallel) n += c.size();
    return corners.size() + right.size() + n + convex.size() + planar_rows + 1;
  }
};

/// Convexity rows, when every face is one loop and every line lies on exactly two loops (the
/// loops are oriented coherently here, whatever their given senses): for each line and each of
/// its two faces F, the junction d of the other face G off F farthest from the line, against
/// F's plane through F's reference triangle, signed by F's facing (its signed area in the
/// drawing), scaled by 1 / (d's distance from the line) and weighted by the number of G's
/// junctions off F (at planar faces each gives the same h). All h ≤ 0 is a convex fold at every
/// line for one of the two Necker readings. O(E log E + Σ |F| |G|).
template <class = void>
std::vector<compliance_terms<>::convex_row> make_convexity_rows(const inflation_problem<>& pr) {
  std::vector<compliance_terms<>::convex_row> out;
  for (std::size_t l = 0; l < pr.loops.size(); ++l)
    if (pr.loop_face[l] != l) return out;  // a face with holes: not a convex solid's
  // Orient the loops coherently (each line run once each way), breadth-first over shared lines.
  std::vector<std::array<std::uint32_t, 4>> sides;  // (lo, hi, loop, runs lo → hi)
  for (std::uint32_t l = 0; l < pr.loops.size(); ++l)
    for (std::size_t k = 0; k < pr.loops[l].size(); ++k) {
      const std::uint32_t a = pr.loops[l][k], b = pr.loops[l][(k + 1) % pr.loops[l].size()];
      sides.push_back({std::min(a, b), std::max(a, b), l, a < b ? 1u : 0u});
    }
  std::sort(sides.begin(), sides.end());
  if (sides.size() != 2 * pr.edges.size()) return out;
  for (std::size_t i = 0; i < sides.size(); i += 2)
    if (sides[i][0] != sides[i + 1][0] || sides[i][1] != sides[i + 1][1] || sides[i][2] == sides[i + 1][2])
      return out;  // a line not on exactly two loops
  std::vector<std::vector<std::array<std::uint32_t, 3>>> across(pr.loops.size());  // (other, same sense)
  for (std::size_t i = 0; i < sides.size(); i += 2) {
    const std::uint32_t same = sides[i][3] == sides[i + 1][3];
    across[sides[i][2]].push_back({sides[i + 1][2], same, 0});
    across[sides[i + 1][2]].push_back({sides[i][2], same, 0});
  }
  std::vector<int> flip(pr.loops.size(), 0);  // +1 kept, −1 reversed, 0 not reached
  for (std::size_t root = 0; root < pr.loops.size(); ++root) {
    if (flip[root] != 0) continue;
    flip[root] = 1;
    std::vector<std::size_t> queue{root};
    while (!queue.empty()) {
      const std::size_t l = queue.back();
      queue.pop_back();
      for (const auto& [g, same, unused] : across[l]) {
        const int want = same ? -flip[l] : flip[l];
        if (flip[g] == 0)
          flip[g] = want, queue.push_back(g);
        else if (flip[g] != want)
          return out;  // not orientable: no solid's boundary
      }
    }
  }
  std::vector<std::vector<std::uint32_t>> loops = pr.loops;
  for (std::size_t l = 0; l < loops.size(); ++l)
    if (flip[l] < 0) std::reverse(loops[l].begin(), loops[l].end());
  std::vector<std::array<std::uint32_t, 3>> half;  // (from, to, loop)
  for (std::uint32_t l = 0; l < loops.size(); ++l)
    for (std::size_t k = 0; k < loops[l].size(); ++k)
      half.push_back({loops[l][k], loops[l][(k + 1) % loops[l].size()], l});
  std::sort(half.begin(), half.end());
  // Per loop: the sign of its area and its reference triangle (as the planarity rows pick it).
  std::vector<double> facing(loops.size());
  std::vector<std::array<std::uint32_t, 3>> ref(loops.size());
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const auto& loop = loops[l];
    double area = 0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const glm::dvec2 a = pr.p[loop[k]], b = pr.p[loop[(k + 1) % loop.size()]];
      area += a.x * b.y - a.y * b.x;
    }
    if (!(std::abs(area) > 1e-12)) return {};
    facing[l] = area > 0 ? 1.0 : -1.0;
    const std::uint32_t a = loop[0];
    std::uint32_t b = a, c = a;
    double far = -1, best = -1;
    for (const auto v : loop)
      if (glm::length(pr.p[v] - pr.p[a]) > far) far = glm::length(pr.p[v] - pr.p[a]), b = v;
    const glm::dvec2 u = pr.p[b] - pr.p[a];
    for (const auto v : loop) {
      const glm::dvec2 w = pr.p[v] - pr.p[a];
      if (std::abs(u.x * w.y - u.y * w.x) > best) best = std::abs(u.x * w.y - u.y * w.x), c = v;
    }
    ref[l] = {a, b, c};
  }
  for (const auto& h : half) {
    const auto twin = std::lower_bound(half.begin(), half.end(), std::array<std::uint32_t, 3>{h[1], h[0], 0});
    if (twin == half.end() || (*twin)[0] != h[1] || (*twin)[1] != h[0]) return {};
    const std::uint32_t f = h[2], g = (*twin)[2];
    const auto [a, b, c] = ref[f];
    const glm::dvec2 u = pr.p[b] - pr.p[a], v = pr.p[c] - pr.p[a];
    const double det = u.x * v.y - u.y * v.x;
    const glm::dvec2 line = pr.p[h[1]] - pr.p[h[0]];
    std::uint32_t far = 0;
    double far_dist = 0, count = 0;
    int sides = 0;  // bit 0: a junction left of the line, bit 1: right
    for (const auto d : loops[g]) {
      if (std::find(loops[f].begin(), loops[f].end(), d) != loops[f].end()) continue;
      const glm::dvec2 x = pr.p[d] - pr.p[h[0]];
      const double cross = line.x * x.y - line.y * x.x, dist = std::abs(cross) / glm::length(line);
      if (!(dist > 1e-12)) continue;
      ++count;
      sides |= cross > 0 ? 1 : 2;
      if (dist > far_dist) far_dist = dist, far = d;
    }
    // G on both sides of the line: its hinges have opposite signs at every planar reading.
    if (sides == 3) return {};
    if (count == 0) continue;
    const glm::dvec2 w = pr.p[far] - pr.p[a];
    const double beta = (w.x * v.y - w.y * v.x) / det, gamma = (u.x * w.y - u.y * w.x) / det;
    out.push_back({far, a, b, c, 1 - beta - gamma, beta, gamma, facing[f] / far_dist, count});
  }
  return out;
}

/// The residuals of the convex reading for Eigen's Levenberg–Marquardt: max(0, a_i t + margin)
/// per convexity row, then √λ t (a small pull to the origin, so the least t is unique and
/// m ≥ n). Its Jacobian is a_i on the active rows, 0 on the others, √λ I below: Gauss–Newton
/// on it is the semismooth Newton step of the piecewise quadratic. O(R K) per call.
template <class = void>
struct convex_hinge_functor {
  const Eigen::MatrixXd* a;
  const Eigen::VectorXd* margin;  // per row (rows and margins weighted)
  double root_lambda;
  Eigen::Index values() const { return a->rows() + a->cols(); }
  int operator()(const Eigen::VectorXd& t, Eigen::VectorXd& f) const {
    f.head(a->rows()) = (*a * t + *margin).cwiseMax(0.0);
    f.tail(a->cols()) = root_lambda * t;
    return 0;
  }
  int df(const Eigen::VectorXd& t, Eigen::MatrixXd& jac) const {
    const Eigen::VectorXd v = *a * t + *margin;
    for (Eigen::Index i = 0; i < a->rows(); ++i)
      if (v[i] > 0)
        jac.row(i) = a->row(i);
      else
        jac.row(i).setZero();
    jac.bottomRows(a->cols()) = root_lambda * Eigen::MatrixXd::Identity(a->cols(), a->cols());
    return 0;
  }
};

/// A convex reading over the planar-face readings z = N t: the least t with every convexity row
/// at most −margin, by Eigen's Levenberg–Marquardt on Σ max(0, A t + margin)² + λ‖t‖² (a convex
/// piecewise quadratic; its trust region keeps the active-set steps from cycling), stopped as
/// soon as every row is at most −margin/2. Empty when no reading reaches h < 0 on every row (the
/// drawing admits no strictly convex reading with these faces). O(iterations · (R + K) K²).
template <class = void>
Eigen::VectorXd convex_reading(const std::vector<compliance_terms<>::convex_row>& rows,
                               const Eigen::MatrixXd& basis, double margin) {
  const auto k = basis.cols();
  // Each row weighted as the hinges it stands for: √w (a t + margin).
  Eigen::MatrixXd a(static_cast<Eigen::Index>(rows.size()), k);
  Eigen::VectorXd root(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    root[static_cast<Eigen::Index>(i)] = std::sqrt(r.weight);
    a.row(static_cast<Eigen::Index>(i)) =
        r.scale * std::sqrt(r.weight) *
        (basis.row(r.d) - r.alpha * basis.row(r.a) - r.beta * basis.row(r.b) - r.gamma * basis.row(r.c));
  }
  Eigen::VectorXd t = Eigen::VectorXd::Zero(k);
  if (a.rows() == 0 || k == 0) return {};
  const Eigen::VectorXd margins = margin * root;
  convex_hinge_functor<> f{&a, &margins, std::sqrt(1e-6)};
  Eigen::LevenbergMarquardt<convex_hinge_functor<>> lm(f);
  // Eigen's own loop, one step at a time, so that it stops once the reading is convex with
  // room (enough for a start); 100 iterations at most.
  auto status = lm.minimizeInit(t);
  while ((status == Eigen::LevenbergMarquardtSpace::NotStarted ||
          status == Eigen::LevenbergMarquardtSpace::Running) &&
         lm.iter <= 100 && !((a * t + 0.5 * margins).maxCoeff() <= 0))
    status = lm.minimizeOneStep(t);
  const Eigen::VectorXd v = a * t;
  if (!t.allFinite() || !(v.maxCoeff() < 0)) return {};
  return t;
}

/// Face-loop corners, Perkins right-corner candidates and 2D-parallel classes. O(E log E + L).
template <class = void>
compliance_terms<> make_compliance_terms(const inflation_problem<>& pr, double tolerance) {
  compliance_terms<> t;
  for (const auto& loop : pr.loops)
    for (std::size_t k = 0; k < loop.size(); ++k)
      t.corners.push_back({loop[(k + loop.size() - 1) % loop.size()], loop[k], loop[(k + 1) % loop.size()]});
  // Perkins: a trihedral junction can be a right corner when it is a fork whose three angles
  // all exceed 90°, or an arrow whose two inner angles are both below 90°.
  for (std::uint32_t j = 0; j < pr.p.size(); ++j) {
    if (pr.incident[j].size() != 3) continue;
    std::array<std::pair<double, std::uint32_t>, 3> dir{};
    for (std::size_t k = 0; k < 3; ++k) {
      const auto& e = pr.edges[pr.incident[j][k]];
      const std::uint32_t o = e[0] == j ? e[1] : e[0];
      const glm::dvec2 d = pr.p[o] - pr.p[j];
      dir[k] = {std::atan2(d.y, d.x), o};
    }
    std::sort(dir.begin(), dir.end());
    std::array<double, 3> gap{};
    for (std::size_t k = 0; k < 3; ++k) {
      gap[k] = dir[(k + 1) % 3].first - dir[k].first;
      if (gap[k] < 0) gap[k] += 2 * std::numbers::pi;
    }
    const double half = std::numbers::pi / 2;
    const bool fork = gap[0] > half && gap[1] > half && gap[2] > half && gap[0] < 2 * half &&
                      gap[1] < 2 * half && gap[2] < 2 * half;
    int wide = 0, narrow = 0;
    for (const double g : gap) wide += g > 2 * half, narrow += g < half;
    if (fork || (wide == 1 && narrow == 2))
      for (std::size_t k = 0; k < 3; ++k) t.right.push_back({dir[k].second, j, dir[(k + 1) % 3].second});
  }
  // Parallel classes: edges sorted by angle, runs within the tolerance (wrapping at π).
  std::vector<std::pair<double, std::uint32_t>> by_angle;
  for (std::uint32_t e = 0; e < pr.edges.size(); ++e)
    by_angle.push_back({line_angle(pr.p[pr.edges[e][1]] - pr.p[pr.edges[e][0]]), e});
  std::sort(by_angle.begin(), by_angle.end());
  std::vector<std::vector<std::uint32_t>> runs;
  std::vector<double> run_angle;
  for (std::size_t i = 0; i < by_angle.size(); ++i) {
    if (i == 0 || by_angle[i].first - by_angle[i - 1].first > tolerance)
      runs.emplace_back(), run_angle.push_back(by_angle[i].first);
    runs.back().push_back(by_angle[i].second);
  }
  if (runs.size() > 1 && angle_distance(by_angle.back().first, by_angle.front().first) <= tolerance) {
    runs.front().insert(runs.front().end(), runs.back().begin(), runs.back().end());
    runs.pop_back();
    run_angle.pop_back();
  }
  for (std::size_t r = 0; r < runs.size(); ++r)
    if (runs[r].size() >= 2) {
      t.parallel.push_back(runs[r]);
      t.parallel_direction.push_back({std::cos(run_angle[r]), std::sin(run_angle[r])});
    }
  return t;
}

/// Cosine of the angle at q between the 3D segments to a and to b. O(1).
template <class = void>
double corner_cos(glm::dvec3 a, glm::dvec3 q, glm::dvec3 b) {
  const glm::dvec3 u = a - q, v = b - q;
  const double l = glm::length(u) * glm::length(v);
  return l > 0 ? std::clamp(glm::dot(u, v) / l, -1.0, 1.0) : 1.0;
}

/// corner_cos, and in g its derivatives with respect to the depths of a, q and b (0 where the
/// cosine is clamped or a segment has no length). O(1).
template <class = void>
double corner_cos_dz(glm::dvec3 a, glm::dvec3 q, glm::dvec3 b, std::array<double, 3>& g) {
  const glm::dvec3 u = a - q, v = b - q;
  const double lu = glm::length(u), lv = glm::length(v);
  g = {0.0, 0.0, 0.0};
  if (!(lu * lv > 0)) return 1.0;
  const double c = glm::dot(u, v) / (lu * lv);
  if (!(std::abs(c) < 1)) return std::clamp(c, -1.0, 1.0);
  const double du = v.z / (lu * lv) - c * u.z / (lu * lu), dv = u.z / (lu * lv) - c * v.z / (lv * lv);
  g = {du, -(du + dv), dv};
  return c;
}

/// d acos(c) / dc, 0 where acos is not differentiable (c = ±1: a degenerate corner). O(1).
template <class = void>
double acos_slope(double c) {
  const double s = 1 - c * c;
  return s > 0 ? -1 / std::sqrt(s) : 0.0;
}

/// The planar readings' basis N copied row-major: a residual's Jacobian row over t is
/// Σ_v ∂r/∂z_v · N_v, a few rows of N each (z = N t).
using basis_rows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The depth slope of each line of a 2D-parallel class against its class mean, times `scale`,
/// into out from row k on (k advanced); with jac, their Jacobian rows over t (N row-major in n).
/// Returns the sum of the unscaled squares. O(E), O(E K) with the Jacobian.
template <class Z>
double parallel_slopes(const inflation_problem<>& pr, const compliance_terms<>& t, const Z& z, double scale,
                       Eigen::VectorXd& out, Eigen::Index& k, Eigen::MatrixXd* jac = nullptr,
                       const basis_rows* n = nullptr) {
  double sum = 0;
  for (std::size_t c = 0; c < t.parallel.size(); ++c) {
    const Eigen::Index start = k;
    double mean = 0;
    for (const auto e : t.parallel[c]) {
      const auto& ed = pr.edges[e];
      const glm::dvec2 d = pr.p[ed[1]] - pr.p[ed[0]];
      const double s = (glm::dot(d, t.parallel_direction[c]) >= 0 ? 1.0 : -1.0) / glm::length(d);
      out[k] = s * (z[ed[1]] - z[ed[0]]);
      mean += out[k];
      if (jac) jac->row(k) = scale * s * (n->row(ed[1]) - n->row(ed[0]));
      ++k;
    }
    mean /= static_cast<double>(k - start);
    for (Eigen::Index i = start; i < k; ++i) {
      sum += (out[i] - mean) * (out[i] - mean);
      out[i] = scale * (out[i] - mean);
    }
    if (jac) {
      const Eigen::RowVectorXd m = jac->middleRows(start, k - start).colwise().mean();
      for (Eigen::Index i = start; i < k; ++i) jac->row(i) -= m;
    }
  }
  return sum;
}

/// Row i of jac += c · (N_d − α N_a − β N_b − γ N_c): a planarity or convexity row. O(K).
template <class Row>
void add_plane_row(Eigen::MatrixXd& jac, Eigen::Index i, const basis_rows& n, const Row& r, double c) {
  jac.row(i) += c * (n.row(r.d) - r.alpha * n.row(r.a) - r.beta * n.row(r.b) - r.gamma * n.row(r.c));
}

/// The convexity hinge √w max(0, h + margin) of each row, times `scale`, into out from row k
/// on (k advanced); with jac, the Jacobian rows over t. Returns Σ w max(0, h + margin)². O(R),
/// O(R K) with the Jacobian.
template <class Z>
double convexity_hinges(const compliance_terms<>& t, const Z& z, double margin, double scale,
                        Eigen::VectorXd& out, Eigen::Index& k, Eigen::MatrixXd* jac = nullptr,
                        const basis_rows* n = nullptr) {
  double total = 0;
  for (const auto& r : t.convex) {
    const double h = r.scale * plane_residual(r, z) + margin, root = std::sqrt(r.weight);
    out[k] = scale * root * std::max(0.0, h);
    total += r.weight * std::max(0.0, h) * std::max(0.0, h);
    if (jac && h > 0) add_plane_row(*jac, k, *n, r, scale * root * r.scale);
    ++k;
  }
  return total;
}

/// The compliance residual vector at depths z (normalised coordinates), with weights applied
/// (w = 1 for the unweighted values). Its squared norm is Σ αⱼ Rⱼ(z). Fills per-term sums when
/// asked. O(L + E).
template <class Z>
void compliance_residuals(const inflation_problem<>& pr, const compliance_terms<>& t,
                          const inflation_weights& w, const Z& z, Eigen::VectorXd& out,
                          inflation_residuals* terms = nullptr) {
  const auto at = [&](std::uint32_t v) { return glm::dvec3(pr.p[v], z[v]); };
  Eigen::Index k = 0;
  double sum = 0;
  // MSDA over face-corner angles.
  std::vector<double> angle(t.corners.size());
  double mean = 0;
  for (std::size_t c = 0; c < t.corners.size(); ++c) {
    const auto& q = t.corners[c];
    angle[c] = std::acos(corner_cos(at(q[0]), at(q[1]), at(q[2])));
    mean += angle[c];
  }
  mean /= static_cast<double>(std::max<std::size_t>(1, angle.size()));
  const double msda_scale = std::sqrt(w.msda / static_cast<double>(std::max<std::size_t>(1, angle.size())));
  sum = 0;
  for (const double a : angle) out[k++] = msda_scale * (a - mean), sum += (a - mean) * (a - mean);
  if (terms) terms->msda = sum / static_cast<double>(std::max<std::size_t>(1, angle.size()));
  // Orthogonality at right-corner candidates.
  const double ortho_scale =
      std::sqrt(w.orthogonality / static_cast<double>(std::max<std::size_t>(1, t.right.size())));
  sum = 0;
  for (const auto& q : t.right) {
    const double c = corner_cos(at(q[0]), at(q[1]), at(q[2]));
    out[k++] = ortho_scale * c, sum += c * c;
  }
  if (terms) terms->orthogonality = sum / static_cast<double>(std::max<std::size_t>(1, t.right.size()));
  // Parallelism: the depth slope of each line of a 2D-parallel class against the class mean.
  std::size_t np = 0;
  for (const auto& cls : t.parallel) np += cls.size();
  const double par_scale = std::sqrt(w.parallelism / static_cast<double>(std::max<std::size_t>(1, np)));
  sum = parallel_slopes(pr, t, z, par_scale, out, k);
  if (terms) terms->parallelism = sum / static_cast<double>(std::max<std::size_t>(1, np));
  // Isometry: log of each line's 3D/2D length ratio against their mean.
  std::vector<double> ratio;
  double m = 0;
  for (const auto& ed : pr.edges) {
    const glm::dvec2 d = pr.p[ed[1]] - pr.p[ed[0]];
    const double dz = z[ed[1]] - z[ed[0]];
    ratio.push_back(0.5 * std::log1p(dz * dz / glm::dot(d, d)));
    m += ratio.back();
  }
  m /= static_cast<double>(ratio.size());
  const double iso_scale = std::sqrt(w.isometry / static_cast<double>(ratio.size()));
  sum = 0;
  for (const double r : ratio) out[k++] = iso_scale * (r - m), sum += (r - m) * (r - m);
  if (terms) terms->isometry = sum / static_cast<double>(ratio.size());
  // Convexity: hinge on each row.
  if (!t.convex.empty()) {
    const double convex_scale = std::sqrt(w.convexity / t.convex_weight());
    sum = convexity_hinges(t, z, t.convex_margin, convex_scale, out, k);
    if (terms) terms->convexity = sum / t.convex_weight();
  }
  // Planarity, when it is not exact by construction (least-squares readings).
  if (t.planar_rows > 0) {
    const double planar_scale = std::sqrt(w.planarity / static_cast<double>(t.planar_rows));
    for (const auto& r : pr.rows) out[k++] = planar_scale * plane_residual(r, z);
  }
  while (k < out.size()) out[k++] = 0;
  if (terms) {
    double worst = 0;
    for (const auto& r : pr.rows) worst = std::max(worst, std::abs(plane_residual(r, z)));
    terms->planarity = worst;
  }
}

/// Rows from..k of jac minus their mean row (a term measured against its own mean). O((k − from) K).
template <class = void>
void centre_rows(Eigen::MatrixXd& jac, Eigen::Index from, Eigen::Index k) {
  if (k <= from) return;
  const Eigen::RowVectorXd m = jac.middleRows(from, k - from).colwise().mean();
  for (Eigen::Index i = from; i < k; ++i) jac.row(i) -= m;
}

/// The exact Jacobian over t of compliance_residuals (z = N t, n = N row-major), term by term
/// in the same order. O((L + E) K).
template <class Z>
void compliance_jacobian(const inflation_problem<>& pr, const compliance_terms<>& t,
                         const inflation_weights& w, const Z& z, const basis_rows& n, Eigen::MatrixXd& jac) {
  const auto at = [&](std::uint32_t v) { return glm::dvec3(pr.p[v], z[v]); };
  const auto share = [](double weight, std::size_t count) {
    return std::sqrt(weight / static_cast<double>(std::max<std::size_t>(1, count)));
  };
  jac.setZero();
  Eigen::Index k = 0;
  std::array<double, 3> g{};
  // MSDA: d acos(cos θ) per corner, against the mean.
  const double msda_scale = share(w.msda, t.corners.size());
  for (const auto& q : t.corners) {
    const double s = msda_scale * acos_slope(corner_cos_dz(at(q[0]), at(q[1]), at(q[2]), g));
    for (std::size_t j = 0; j < 3; ++j) jac.row(k) += s * g[j] * n.row(q[j]);
    ++k;
  }
  centre_rows(jac, 0, k);
  const double ortho_scale = share(w.orthogonality, t.right.size());
  for (const auto& q : t.right) {
    corner_cos_dz(at(q[0]), at(q[1]), at(q[2]), g);
    for (std::size_t j = 0; j < 3; ++j) jac.row(k) += ortho_scale * g[j] * n.row(q[j]);
    ++k;
  }
  std::size_t np = 0;
  for (const auto& cls : t.parallel) np += cls.size();
  Eigen::VectorXd scratch(jac.rows());
  parallel_slopes(pr, t, z, share(w.parallelism, np), scratch, k, &jac, &n);
  // Isometry: d/dΔz of ½ log(1 + Δz²/d²) is Δz / (d² + Δz²), against the mean.
  const Eigen::Index iso = k;
  const double iso_scale = share(w.isometry, pr.edges.size());
  for (const auto& ed : pr.edges) {
    const glm::dvec2 d = pr.p[ed[1]] - pr.p[ed[0]];
    const double dz = z[ed[1]] - z[ed[0]];
    jac.row(k++) = iso_scale * dz / (glm::dot(d, d) + dz * dz) * (n.row(ed[1]) - n.row(ed[0]));
  }
  centre_rows(jac, iso, k);
  if (!t.convex.empty())
    convexity_hinges(t, z, t.convex_margin, std::sqrt(w.convexity / t.convex_weight()), scratch, k, &jac, &n);
  if (t.planar_rows > 0) {
    const double planar_scale = share(w.planarity, t.planar_rows);
    for (const auto& r : pr.rows) add_plane_row(jac, k++, n, r, planar_scale);
  }
}

/// Eigen's Levenberg–Marquardt on a functor with an exact Jacobian (df), from t: at most
/// `budget` evaluations (about one per iteration), stopped early once the residual norm is
/// below `stop` (a system met exactly); adds its iterations. O(budget · (m K² + f)).
template <class F>
void solve_lm(F& f, Eigen::VectorXd& t, int budget, double xtol, double ftol, std::size_t& iterations,
              double stop = 0) {
  Eigen::LevenbergMarquardt<F> lm(f);
  lm.parameters.maxfev = std::max(1, budget);
  lm.parameters.xtol = xtol;
  lm.parameters.ftol = ftol;
  auto status = lm.minimizeInit(t);
  while ((status == Eigen::LevenbergMarquardtSpace::NotStarted ||
          status == Eigen::LevenbergMarquardtSpace::Running) &&
         !(lm.fnorm < stop))
    status = lm.minimizeOneStep(t);
  iterations += static_cast<std::size_t>(lm.iter);
}

/// The residual functor of Eigen's Levenberg–Marquardt over t, with z = N t, and its exact
/// Jacobian. O((L + E) K) per call.
template <class = void>
struct inflation_functor {
  const inflation_problem<>* pr;
  const compliance_terms<>* terms;
  const Eigen::MatrixXd* basis;
  const basis_rows* rows;
  inflation_weights weights;
  Eigen::Index m;
  Eigen::Index inputs() const { return basis->cols(); }
  Eigen::Index values() const { return m; }
  int operator()(const Eigen::VectorXd& t, Eigen::VectorXd& f) const {
    const Eigen::VectorXd z = *basis * t;
    compliance_residuals(*pr, *terms, weights, z, f);
    return 0;
  }
  int df(const Eigen::VectorXd& t, Eigen::MatrixXd& jac) const {
    const Eigen::VectorXd z = *basis * t;
    compliance_jacobian(*pr, *terms, weights, z, *rows, jac);
    return 0;
  }
};

/// The regularities a person sees in a solid (Lipson and Shpitalni), as relations on the face
/// loops that are exact at a regular solid's true reading: a right face corner (cos θ = 0),
/// two consecutive corners of a face equal (θ_k = θ_{k+1}), two consecutive sides of a face
/// equal in length, two classes of 2D-parallel lines square to each other (a cut cube's axes,
/// a prism's sides to its caps). Parallelism (lines parallel in the drawing are parallel in
/// 3D) and the convexity hinge are kept as plain terms. Built from the drawing alone. O(L + C²).
template <class = void>
struct regularity_terms {
  std::vector<std::array<std::uint32_t, 3>> corners;      // (prev, j, next) of every face loop
  std::vector<std::array<std::uint32_t, 2>> angle_pairs;  // consecutive corners of one loop
  std::vector<std::array<std::uint32_t, 4>> side_pairs;   // (a, b) and (c, d): consecutive sides
  std::vector<std::array<std::uint32_t, 4>> class_pairs;  // longest lines (a, b), (c, d) of two classes
  std::size_t relations() const {
    return corners.size() + angle_pairs.size() + side_pairs.size() + class_pairs.size();
  }
};

/// `direction_tolerance` groups lines into 2D-parallel classes (as the compliance terms do).
template <class = void>
regularity_terms<> make_regularity_terms(const inflation_problem<>& pr, double direction_tolerance = 1e-6) {
  regularity_terms<> t;
  for (const auto& loop : pr.loops) {
    const auto n = static_cast<std::uint32_t>(loop.size());
    const auto first = static_cast<std::uint32_t>(t.corners.size());
    for (std::uint32_t k = 0; k < n; ++k) {
      t.corners.push_back({loop[(k + n - 1) % n], loop[k], loop[(k + 1) % n]});
      t.angle_pairs.push_back({first + k, first + (k + 1) % n});
      t.side_pairs.push_back({loop[k], loop[(k + 1) % n], loop[(k + 1) % n], loop[(k + 2) % n]});
    }
  }
  // One line stands for its class (the longest: parallel in 3D is a plain term); the six
  // classes of most total length (a cut cube's axes), so that the pairs stay few.
  const auto len = [&](std::uint32_t e) { return glm::length(pr.p[pr.edges[e][1]] - pr.p[pr.edges[e][0]]); };
  std::vector<std::pair<double, std::uint32_t>> classes;
  for (const auto& c : make_compliance_terms(pr, direction_tolerance).parallel) {
    double total = 0;
    for (const auto e : c) total += len(e);
    classes.push_back(
        {-total, *std::max_element(c.begin(), c.end(), [&](auto x, auto y) { return len(x) < len(y); })});
  }
  std::sort(classes.begin(), classes.end());
  std::vector<std::uint32_t> rep;
  for (std::size_t i = 0; i < classes.size() && i < 6; ++i) rep.push_back(classes[i].second);
  for (std::size_t i = 0; i < rep.size(); ++i)
    for (std::size_t j = i + 1; j < rep.size(); ++j)
      t.class_pairs.push_back(
          {pr.edges[rep[i]][0], pr.edges[rep[i]][1], pr.edges[rep[j]][0], pr.edges[rep[j]][1]});
  return t;
}

/// The relation residuals at depths z (normalised coordinates), in the order corners (cos θ),
/// angle pairs (θ_k − θ_{k+1}, radians), side pairs ((L₁ − L₂) / (L₁ + L₂)), class pairs (the
/// cosine between their lines); with jr (relations
/// × K), their exact Jacobian rows over t (N row-major in n). O(L), O(L K) with the Jacobian.
/// With `need` (needed_relations), only the relations it marks are computed (a snap solves a
/// few of them); the others are left as they were.
template <class Z>
void regularity_residuals(const inflation_problem<>& pr, const regularity_terms<>& t, const Z& z,
                          Eigen::VectorXd& r, Eigen::MatrixXd* jr = nullptr, const basis_rows* n = nullptr,
                          const std::vector<char>* need = nullptr) {
  const auto at = [&](std::uint32_t v) { return glm::dvec3(pr.p[v], z[v]); };
  if (jr) jr->setZero();
  Eigen::Index k = 0;
  std::array<double, 3> g{};
  const auto skip = [&](Eigen::Index i) { return need && !(*need)[static_cast<std::size_t>(i)]; };
  for (const auto& q : t.corners) {
    if (skip(k)) {
      ++k;
      continue;
    }
    if (!jr) {
      r[k++] = corner_cos(at(q[0]), at(q[1]), at(q[2]));
      continue;
    }
    r[k] = corner_cos_dz(at(q[0]), at(q[1]), at(q[2]), g);
    for (std::size_t j = 0; j < 3; ++j) jr->row(k) += g[j] * n->row(q[j]);
    ++k;
  }
  // Each corner is in two angle pairs: its angle (and slope) taken once.
  std::vector<double> angle(t.corners.size()), slope(jr ? t.corners.size() : 0);
  for (std::size_t c = 0; c < angle.size(); ++c) {
    if (skip(static_cast<Eigen::Index>(c))) continue;
    angle[c] = std::acos(r[static_cast<Eigen::Index>(c)]);
    if (jr) slope[c] = acos_slope(r[static_cast<Eigen::Index>(c)]);
  }
  for (const auto& p : t.angle_pairs) {
    if (skip(k)) {
      ++k;
      continue;
    }
    r[k] = angle[p[0]] - angle[p[1]];
    if (jr) jr->row(k) = slope[p[0]] * jr->row(p[0]) - slope[p[1]] * jr->row(p[1]);
    ++k;
  }
  for (const auto& s : t.side_pairs) {
    if (skip(k)) {
      ++k;
      continue;
    }
    const glm::dvec3 u = at(s[1]) - at(s[0]), v = at(s[3]) - at(s[2]);
    const double a = glm::length(u), b = glm::length(v);
    r[k] = (a - b) / (a + b);
    // d/da = 2b / (a + b)², d/db = −2a / (a + b)²; da/dz = Δz / a along each side.
    if (jr) {
      const double q = 2 / ((a + b) * (a + b));
      jr->row(k) =
          q * b * u.z / a * (n->row(s[1]) - n->row(s[0])) - q * a * v.z / b * (n->row(s[3]) - n->row(s[2]));
    }
    ++k;
  }
  for (const auto& s : t.class_pairs) {
    if (skip(k)) {
      ++k;
      continue;
    }
    const glm::dvec3 u = at(s[1]) - at(s[0]), v = at(s[3]) - at(s[2]);
    const double a = glm::length(u), b = glm::length(v), c = glm::dot(u, v) / (a * b);
    r[k] = c;
    // dc/du_z = v_z / (a b) − c u_z / a², and alike for v.
    if (jr)
      jr->row(k) = (v.z / (a * b) - c * u.z / (a * a)) * (n->row(s[1]) - n->row(s[0])) +
                   (u.z / (a * b) - c * v.z / (b * b)) * (n->row(s[3]) - n->row(s[2]));
    ++k;
  }
}

/// The relations regularity_residuals must compute for `held`: those, and the corners their
/// angle pairs compare. O(relations).
template <class = void>
std::vector<char> needed_relations(const regularity_terms<>& t, const std::vector<std::uint32_t>& held) {
  std::vector<char> need(t.relations(), 0);
  const std::size_t pairs = t.corners.size();
  for (const auto i : held) {
    need[i] = 1;
    if (i >= pairs && i < pairs + t.angle_pairs.size())
      for (const auto c : t.angle_pairs[i - pairs]) need[c] = 1;
  }
  return need;
}

/// Residuals of the regularity reading over t (z = N t): every relation under a saturating
/// loss r / √(1 + (r/σ)²) (a relation that does not hold costs about σ², whatever how far off),
/// or only the relations in `held`, plainly; then the parallel classes' depth slopes, the
/// convexity hinge and a bound on |z| (4 drawing diagonals), plainly; and the exact Jacobian.
/// O(L + E) per call, O((L + E) K) per Jacobian.
template <class = void>
struct regularity_functor {
  const inflation_problem<>* pr;
  const compliance_terms<>* terms;
  const regularity_terms<>* reg;
  const Eigen::MatrixXd* basis;
  const basis_rows* rows;
  const std::vector<std::uint32_t>* held;  // null: every relation, robustly
  double sigma = 0.1;
  double convex_margin = 0.0;
  Eigen::Index m = 0;
  const std::vector<char>* need = nullptr;  // needed_relations(held): the relations computed
  Eigen::Index inputs() const { return basis->cols(); }
  Eigen::Index values() const { return m; }
  int operator()(const Eigen::VectorXd& t, Eigen::VectorXd& f) const { return evaluate(t, f, nullptr); }
  int df(const Eigen::VectorXd& t, Eigen::MatrixXd& jac) const {
    Eigen::VectorXd f(m);
    return evaluate(t, f, &jac);
  }
  int evaluate(const Eigen::VectorXd& t, Eigen::VectorXd& f, Eigen::MatrixXd* jac) const {
    const Eigen::VectorXd z = *basis * t;
    Eigen::VectorXd r(static_cast<Eigen::Index>(reg->relations()));
    Eigen::MatrixXd jr;
    if (jac) jr.resize(r.size(), basis->cols()), jac->setZero();
    regularity_residuals(*pr, *reg, z, r, jac ? &jr : nullptr, rows, held ? need : nullptr);
    Eigen::Index k = 0;
    if (held) {
      for (const auto i : *held) {
        if (jac) jac->row(k) = jr.row(i);
        f[k++] = r[i];
      }
    } else {
      for (Eigen::Index i = 0; i < r.size(); ++i) {
        const double q = 1 + (r[i] / sigma) * (r[i] / sigma);
        if (jac) jac->row(k) = jr.row(i) / (q * std::sqrt(q));
        f[k++] = r[i] / std::sqrt(q);
      }
    }
    parallel_slopes(*pr, *terms, z, 1.0, f, k, jac, rows);
    convexity_hinges(*terms, z, convex_margin, 1.0, f, k, jac, rows);
    for (Eigen::Index v = 0; v < z.size(); ++v) {
      f[k] = std::max(0.0, std::abs(z[v]) - 4.0);
      if (jac && f[k] > 0) jac->row(k) = (z[v] > 0 ? 1.0 : -1.0) * rows->row(v);
      ++k;
    }
    while (k < f.size()) f[k++] = 0;
    return 0;
  }
};

/// Relations of `reg` within `tolerance` at depths z. O(L).
template <class Z>
std::size_t held_relations(const inflation_problem<>& pr, const regularity_terms<>& reg, const Z& z,
                           double tolerance) {
  Eigen::VectorXd r(static_cast<Eigen::Index>(reg.relations()));
  regularity_residuals(pr, reg, z, r);
  return static_cast<std::size_t>((r.array().abs() < tolerance).count());
}

template <class = void>
Eigen::VectorXd snap_regular(const inflation_problem<>& pr, const compliance_terms<>& terms,
                             const regularity_terms<>& reg, const Eigen::MatrixXd& basis,
                             const basis_rows& rows, Eigen::VectorXd t, int max_iterations,
                             std::size_t& iterations, double exact, bool drop_worst = false);

/// A regular reading near t0: Levenberg–Marquardt on every relation under the saturating loss,
/// σ lowered 0.1 → 0.03 → 0.01 (a relation that does not hold stops pulling), then the relations
/// within `snap` of holding solved exactly (plain residuals); relations the exact solve cannot
/// meet to 1e-9 are dropped and the solve repeated (3 rounds at most). Returns t; `held` the
/// relations within 1e-7 there. O(iterations · (L + E) K + iterations · m K²).
template <class = void>
Eigen::VectorXd regular_reading(const inflation_problem<>& pr, const compliance_terms<>& terms,
                                const regularity_terms<>& reg, const Eigen::MatrixXd& basis,
                                const Eigen::VectorXd& t0, int max_iterations, std::size_t& iterations,
                                double exact, bool robust = true, bool drop_worst = false) {
  std::size_t np = 0;
  for (const auto& c : terms.parallel) np += c.size();
  const auto k = basis.cols();
  const basis_rows rows = basis;
  Eigen::VectorXd t = t0;
  if (!robust)
    return snap_regular(pr, terms, reg, basis, rows, t, max_iterations, iterations, exact, drop_worst);
  regularity_functor<> f{&pr, &terms, &reg, &basis, &rows, nullptr, 0.1, terms.convex_margin, 0};
  f.m = std::max<Eigen::Index>(
      k, static_cast<Eigen::Index>(reg.relations() + np + terms.convex.size()) + basis.rows());
  for (const double sigma : {0.1, 0.03, 0.01}) {
    f.sigma = sigma;
    solve_lm(f, t, std::min(max_iterations, 50), 1e-14, 1e-16, iterations);
  }
  const Eigen::VectorXd a =
      snap_regular(pr, terms, reg, basis, rows, t0, max_iterations, iterations, exact, true);
  const Eigen::VectorXd b =
      snap_regular(pr, terms, reg, basis, rows, t, max_iterations, iterations, exact, true);
  return held_relations(pr, reg, Eigen::VectorXd(basis * b), 100 * exact) >
                 held_relations(pr, reg, Eigen::VectorXd(basis * a), 100 * exact)
             ? b
             : a;
}

/// The relations within 1e-3 of holding at t solved exactly (plain residuals, with the parallel
/// classes and the convexity hinge); relations the solve cannot meet to 1e-9 are dropped and the
/// solve repeated (3 rounds at most); t itself when no round meets its relations.
/// O(rounds · iterations · ((L + E) K + m K²)).
/// Relations of `reg` within `tolerance` at depths z, weighted: a right corner and two classes
/// square to each other count 2, equal corners and equal sides 1 (a skewed relative of a
/// right-angled solid makes two corners or sides equal as easily as one corner right). O(L).
template <class Z>
std::size_t weighted_relations(const inflation_problem<>& pr, const regularity_terms<>& reg, const Z& z,
                               double tolerance) {
  Eigen::VectorXd r(static_cast<Eigen::Index>(reg.relations()));
  regularity_residuals(pr, reg, z, r);
  const auto corners = static_cast<Eigen::Index>(reg.corners.size());
  const auto pairs = corners + static_cast<Eigen::Index>(reg.angle_pairs.size() + reg.side_pairs.size());
  std::size_t w = 0;
  for (Eigen::Index i = 0; i < r.size(); ++i)
    if (std::abs(r[i]) < tolerance) w += i < corners || i >= pairs ? 2 : 1;
  return w;
}

template <class>
Eigen::VectorXd snap_regular(const inflation_problem<>& pr, const compliance_terms<>& terms,
                             const regularity_terms<>& reg, const Eigen::MatrixXd& basis,
                             const basis_rows& rows, Eigen::VectorXd t, int max_iterations,
                             std::size_t& iterations, double exact, bool drop_worst) {
  std::size_t np = 0;
  for (const auto& c : terms.parallel) np += c.size();
  const auto k = basis.cols();
  Eigen::VectorXd r(static_cast<Eigen::Index>(reg.relations()));
  const Eigen::VectorXd z0 = basis * t;
  regularity_residuals(pr, reg, z0, r);
  const Eigen::VectorXd r0 = r;
  Eigen::VectorXd best = t;
  std::size_t best_held = held_relations(pr, reg, z0, 100 * exact);
  // Snapped from the relations within 1e-4, 1e-3, 1e-2 and 3e-2 of holding: the most held wins.
  std::size_t tried = 0;
  for (const double near : {1e-4, 1e-3, 1e-2, 3e-2}) {
    std::vector<std::uint32_t> held;
    for (Eigen::Index i = 0; i < r0.size(); ++i)
      if (std::abs(r0[i]) < near) held.push_back(static_cast<std::uint32_t>(i));
    if (held.size() == tried) continue;  // the same relations as the last threshold
    tried = held.size();
    for (int round = 0; round < 3 && !held.empty(); ++round) {
      const std::vector<char> need = needed_relations(reg, held);
      regularity_functor<> g{&pr, &terms, &reg, &basis, &rows, &held, 0.0, 0.0, 0, &need};
      g.m = std::max<Eigen::Index>(
          k, static_cast<Eigen::Index>(held.size() + np + terms.convex.size()) + basis.rows());
      Eigen::VectorXd u = t;
      // Consistent relations converge in a few Gauss–Newton steps (stopped once every residual
      // is a thousandth of `exact`); inconsistent ones stall: 50 iterations at most.
      solve_lm(g, u, std::min(max_iterations, 50), 1e-14, 1e-10, iterations, 1e-3 * exact);
      const Eigen::VectorXd z = basis * u;
      regularity_residuals(pr, reg, z, r);
      std::vector<std::uint32_t> kept;
      for (const auto i : held)
        if (std::abs(r[i]) < exact) kept.push_back(i);
      if (kept.size() == held.size()) {
        const std::size_t h = held_relations(pr, reg, z, 100 * exact);
        if (u.allFinite() && z.cwiseAbs().maxCoeff() <= 8 && h > best_held) best_held = h, best = u;
        break;
      }
      // Most relations missed (a false one pulled the rest off): with drop_worst, drop those at
      // least half as far off as the worst and solve again, rather than all that missed.
      if (drop_worst && kept.size() * 2 < held.size()) {
        double worst = 0;
        for (const auto i : held) worst = std::max(worst, std::abs(r[i]));
        kept.clear();
        for (const auto i : held)
          if (std::abs(r[i]) < 0.5 * worst) kept.push_back(i);
      }
      held = std::move(kept);
    }
  }
  return best;
}

/// A hypothesis of the regular reading: depth differences z_i − z_j = value (normalised units)
/// that the reading meets, up to the mirror (every value negated).
struct depth_hypothesis {
  std::vector<std::array<std::uint32_t, 2>> pairs;
  std::vector<double> value;
};

/// When a polygon's drawing is the affine image c + A (cos 2πk/n, sin 2πk/n) of a regular
/// n-gon (to `tolerance`), the depth gradient g (z = g · xy + c) of the plane in which it is
/// regular, one of the mirror pair ±g; false otherwise or seen edge-on. O(n).
template <class = void>
bool regular_polygon_gradient(const inflation_problem<>& pr, const std::vector<std::uint32_t>& loop,
                              double tolerance, glm::dvec2& g) {
  const auto n = static_cast<Eigen::Index>(loop.size());
  if (n < 3) return false;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(2 * n, 6);
  Eigen::VectorXd b(2 * n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);
    const glm::dvec2 p = pr.p[loop[static_cast<std::size_t>(k)]];
    m(2 * k, 0) = 1, m(2 * k, 2) = std::cos(a), m(2 * k, 3) = std::sin(a), b[2 * k] = p.x;
    m(2 * k + 1, 1) = 1, m(2 * k + 1, 4) = std::cos(a), m(2 * k + 1, 5) = std::sin(a), b[2 * k + 1] = p.y;
  }
  const Eigen::VectorXd x = m.colPivHouseholderQr().solve(b);
  if (!x.allFinite() || (m * x - b).cwiseAbs().maxCoeff() > tolerance) return false;
  const glm::dvec2 a1(x[2], x[4]), a2(x[3], x[5]);
  const double det = a1.x * a2.y - a1.y * a2.x;
  if (!(std::abs(det) > 1e-6 * glm::length(a1) * glm::length(a2))) return false;
  // The circle's axes in 3D, (a₁, w₁) and (a₂, w₂), are square and equally long:
  // w₁ w₂ = −a₁·a₂ and w₁² − w₂² = |a₂|² − |a₁|², i.e. (w₁ + i w₂)² = q − 2ip.
  const std::complex<double> w =
      std::sqrt(std::complex<double>(glm::dot(a2, a2) - glm::dot(a1, a1), -2 * glm::dot(a1, a2)));
  // The plane's gradient meets g · a₁ = w₁, g · a₂ = w₂.
  g = {(w.real() * a2.y - w.imag() * a1.y) / det, (w.imag() * a1.x - w.real() * a2.x) / det};
  return true;
}

/// Hypotheses of the regular reading, most telling first: (1) polygons drawn as affine images
/// of regular ones — face loops, and the links of junctions whose faces are all triangles (a
/// bipyramid's equator) — grouped by their plane's gradient (parallel caps share one), a group
/// kept when it has two polygons or one of five corners or more, at most `most` groups, most
/// polygons first; (2) every three of the five longest classes of 2D-parallel lines read as
/// orthogonal axes (a cut cube's), the depth slope of each class from Σ s_i² d_i d_iᵀ = I₂ as
/// in the direct method. O(L + polygons · groups).
template <class = void>
std::vector<depth_hypothesis> regular_hypotheses(const inflation_problem<>& pr,
                                                 const compliance_terms<>& terms, double tolerance,
                                                 std::size_t most) {
  std::vector<std::vector<std::uint32_t>> polygons = pr.loops;
  std::vector<std::uint32_t> apex(polygons.size(), std::numeric_limits<std::uint32_t>::max());
  std::vector<std::vector<std::uint32_t>> at(pr.p.size());
  for (std::uint32_t l = 0; l < pr.loops.size(); ++l)
    for (const auto v : pr.loops[l]) at[v].push_back(l);
  for (std::uint32_t v = 0; v < pr.p.size(); ++v) {
    const std::size_t deg = pr.incident[v].size();
    if (deg < 3 || at[v].size() != deg) continue;
    std::vector<std::array<std::uint32_t, 2>> link;
    for (const auto l : at[v]) {
      if (pr.loops[l].size() != 3) break;
      std::array<std::uint32_t, 2> o{};
      std::size_t c = 0;
      for (const auto u : pr.loops[l])
        if (u != v && c < 2) o[c++] = u;
      link.push_back(o);
    }
    if (link.size() != deg) continue;
    std::vector<bool> used(deg, false);
    used[0] = true;
    std::vector<std::uint32_t> cycle{link[0][0]};
    std::uint32_t cur = link[0][1];
    while (cycle.size() < deg) {
      cycle.push_back(cur);
      std::size_t i = 0;
      while (i < deg && (used[i] || (link[i][0] != cur && link[i][1] != cur))) ++i;
      if (i == deg) break;
      used[i] = true;
      cur = link[i][0] == cur ? link[i][1] : link[i][0];
    }
    if (cycle.size() == deg && cur == cycle[0]) polygons.push_back(std::move(cycle)), apex.push_back(v);
  }
  struct group {
    glm::dvec2 g;
    std::vector<std::pair<std::size_t, double>> members;  // polygon, sign of g
    std::size_t corners;
  };
  std::vector<group> groups;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    glm::dvec2 g;
    if (!regular_polygon_gradient(pr, polygons[i], tolerance, g)) continue;
    const double tol = 1e-6 * (1 + glm::length(g));
    bool placed = false;
    for (auto& gr : groups) {
      const double sign = glm::length(gr.g - g) <= tol ? 1.0 : glm::length(gr.g + g) <= tol ? -1.0 : 0.0;
      if (sign == 0) continue;
      gr.members.push_back({i, sign}), gr.corners += polygons[i].size(), placed = true;
      break;
    }
    if (!placed) groups.push_back({g, {{i, 1.0}}, polygons[i].size()});
  }
  std::stable_sort(groups.begin(), groups.end(), [](const group& x, const group& y) {
    return x.members.size() > y.members.size() ||
           (x.members.size() == y.members.size() && x.corners > y.corners);
  });
  std::vector<depth_hypothesis> out;
  for (const auto& gr : groups) {
    if (out.size() >= most) break;
    if (gr.members.size() < 2 && gr.corners < 5) continue;
    depth_hypothesis h;
    for (const auto& member : gr.members) {  // parallel planes: one gradient (±g are one pair of roots)
      const auto& poly = polygons[member.first];
      for (std::size_t k = 0; k < poly.size(); ++k) {
        const std::uint32_t a = poly[k], b = poly[(k + 1) % poly.size()];
        h.pairs.push_back({a, b});
        h.value.push_back(glm::dot(gr.g, pr.p[a] - pr.p[b]));
      }
      // A junction whose triangles ring a regular polygon stands over its centre c (a right
      // pyramid's apex): v − c along the plane's normal (g, −1), so z_v − z_c = −g · (v − c) / |g|²,
      // when its drawing lies on the normal's image (else the pyramid is oblique: no row).
      const std::uint32_t v = apex[member.first];
      const double gg = glm::dot(gr.g, gr.g);
      if (v == std::numeric_limits<std::uint32_t>::max() || !(gg > 1e-12)) continue;
      glm::dvec2 c{0.0};
      for (const auto u : poly) c += pr.p[u];
      c /= static_cast<double>(poly.size());
      const glm::dvec2 d = pr.p[v] - c;
      if (std::abs(d.x * gr.g.y - d.y * gr.g.x) > tolerance * std::sqrt(gg)) continue;
      h.pairs.push_back({v, poly[0]});
      h.value.push_back(glm::dot(gr.g, c - pr.p[poly[0]]) - glm::dot(gr.g, d) / gg);
    }
    out.push_back(std::move(h));
  }
  // Orthogonal axes: the five longest classes.
  std::vector<std::pair<double, std::size_t>> classes;
  for (std::size_t c = 0; c < terms.parallel.size(); ++c) {
    double len = 0;
    for (const auto e : terms.parallel[c]) len += glm::length(pr.p[pr.edges[e][1]] - pr.p[pr.edges[e][0]]);
    classes.push_back({-len, c});
  }
  std::sort(classes.begin(), classes.end());
  if (classes.size() > 5) classes.resize(5);
  for (std::size_t i = 0; i < classes.size(); ++i)
    for (std::size_t j = i + 1; j < classes.size(); ++j)
      for (std::size_t k = j + 1; k < classes.size(); ++k) {
        const std::array<std::size_t, 3> cs{classes[i].second, classes[j].second, classes[k].second};
        Eigen::Matrix3d m;
        for (int a = 0; a < 3; ++a) {
          const glm::dvec2 d = terms.parallel_direction[cs[static_cast<std::size_t>(a)]];
          m(0, a) = d.x * d.x, m(1, a) = d.x * d.y, m(2, a) = d.y * d.y;
        }
        const Eigen::ColPivHouseholderQR<Eigen::Matrix3d> qr(m);
        if (qr.rank() < 3) continue;
        const Eigen::Vector3d u = qr.solve(Eigen::Vector3d(1, 0, 1));
        if (!(u.minCoeff() > 1e-12 && u.maxCoeff() < 1 - 1e-12)) continue;
        std::array<double, 3> s{};
        glm::dvec3 r1, r2;
        for (std::size_t a = 0; a < 3; ++a) {
          s[a] = std::sqrt(u[static_cast<Eigen::Index>(a)]);
          const glm::dvec2 d = terms.parallel_direction[cs[a]];
          r1[static_cast<glm::length_t>(a)] = s[a] * d.x, r2[static_cast<glm::length_t>(a)] = s[a] * d.y;
        }
        const glm::dvec3 r3 = glm::cross(r1, r2);
        depth_hypothesis h;
        for (std::size_t a = 0; a < 3; ++a)
          for (const auto e : terms.parallel[cs[a]]) {
            const glm::dvec2 d = pr.p[pr.edges[e][1]] - pr.p[pr.edges[e][0]];
            h.pairs.push_back({pr.edges[e][1], pr.edges[e][0]});
            h.value.push_back(glm::dot(d, terms.parallel_direction[cs[a]]) / s[a] *
                              r3[static_cast<glm::length_t>(a)]);
          }
        out.push_back(std::move(h));
      }
  return out;
}

/// The regular reading under a hypothesis: the planar readings that meet its rows (its mirror
/// chosen as t_ref's) are p + Z w, p the least-norm one; the regular reading (search and snap)
/// is sought over the span of p and Z, from p plus t_ref's part in Z. Empty when no planar
/// reading meets the rows to `tolerance` or more than `max_free` readings stay free.
/// O(R K² + the regular reading over 1 + dim Z unknowns).
template <class = void>
Eigen::VectorXd hypothesis_reading(const inflation_problem<>& pr, const compliance_terms<>& terms,
                                   const regularity_terms<>& reg, const Eigen::MatrixXd& basis,
                                   const depth_hypothesis& h, const Eigen::VectorXd& t_ref, double tolerance,
                                   std::size_t max_free, int max_iterations, std::size_t& iterations,
                                   double exact) {
  const auto k = basis.cols();
  const auto rn = static_cast<Eigen::Index>(h.pairs.size());
  Eigen::MatrixXd m(rn, k);
  Eigen::VectorXd b(rn);
  for (Eigen::Index r = 0; r < rn; ++r) {
    const auto& q = h.pairs[static_cast<std::size_t>(r)];
    m.row(r) = basis.row(q[0]) - basis.row(q[1]);
    b[r] = h.value[static_cast<std::size_t>(r)];
  }
  // The threshold must be set before the decomposition: it fixes the rank the solve uses.
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(m.rows(), m.cols());
  cod.setThreshold(1e-9);
  cod.compute(m);
  const Eigen::VectorXd p = cod.solve(b);
  if (!p.allFinite() || p.norm() < 1e-9 || (m * p - b).cwiseAbs().maxCoeff() > tolerance) return {};
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m.cols(), m.rows());
  qr.setThreshold(1e-9);
  qr.compute(m.transpose());
  const Eigen::Index free = k - qr.rank();
  if (static_cast<std::size_t>(free) > max_free) return {};
  Eigen::MatrixXd span(k, 1 + free);
  span.col(0) = p;
  Eigen::VectorXd s = Eigen::VectorXd::Zero(1 + free);
  if (free > 0) {
    span.rightCols(free) = Eigen::MatrixXd(qr.householderQ()).rightCols(free);
    s.tail(free) = span.rightCols(free).transpose() * t_ref;
  }
  const Eigen::MatrixXd reduced = basis * span;
  // Starts: each mirror (the convexity hinge is one-sided) and, with one reading left free (a
  // prism's or an antiprism's height, a pyramid's apex), the steps of a scan over ±2 drawing
  // sizes of depth where most relations change sign (come to hold): a symmetric solid has
  // other steps where many corners turn right at once, and the search alone stops at the
  // nearest local minimum. The two starts with fewest convex folds lost, then most crossings,
  // are searched. O(128 relations) per scan.
  struct start {
    std::size_t lost, crossing;
    Eigen::VectorXd s;
  };
  std::vector<start> starts;
  const auto folds_lost = [&](const Eigen::VectorXd& z) {
    std::size_t lost = 0;
    for (const auto& c : terms.convex) lost += c.scale * plane_residual(c, z) > -1e-9;
    return lost;
  };
  const Eigen::VectorXd mt = m * t_ref;
  const double nearer = (mt - b).squaredNorm() <= (mt + b).squaredNorm() ? 1.0 : -1.0;
  for (const double sign : {nearer, -nearer}) {
    if (sign != nearer && terms.convex.empty()) break;
    s[0] = sign;
    const Eigen::VectorXd s_ref = s;
    std::vector<std::pair<std::size_t, Eigen::VectorXd>> found;
    const auto rel = static_cast<Eigen::Index>(reg.relations());
    if (free == 1) {
      const Eigen::VectorXd dz = reduced.col(1);
      const double reach = 2.0 / std::max(dz.cwiseAbs().maxCoeff(), 1e-12);
      const int steps = 128;
      const double step = 2 * reach / steps;
      Eigen::VectorXd r(rel), before;
      std::vector<double> roots;
      for (int i = 0; i <= steps; ++i) {
        const double c = reach * (2.0 * i / steps - 1);
        regularity_residuals(pr, reg, Eigen::VectorXd(reduced.col(0) * sign + dz * c), r);
        if (i > 0) {
          // Relations that hold all along (a regular cap's) are rounding noise, not crossings.
          // Each crossing relation's root, linearly interpolated; their median is the start (the
          // true reading is where many roots coincide, and the step is too coarse to snap from).
          roots.clear();
          for (Eigen::Index q = 0; q < rel; ++q)
            if (r[q] * before[q] < 0 && std::abs(r[q]) > 1e-9 && std::abs(before[q]) > 1e-9)
              roots.push_back(c - step * r[q] / (r[q] - before[q]));
          if (!roots.empty()) {
            std::nth_element(roots.begin(), roots.begin() + static_cast<std::ptrdiff_t>(roots.size() / 2),
                             roots.end());
            s[1] = roots[roots.size() / 2];
            found.push_back({roots.size(), s});
          }
        }
        before = r;
      }
    }
    if (found.empty()) found.push_back({0, s_ref});
    for (const auto& [crossing, at] : found) starts.push_back({folds_lost(reduced * at), crossing, at});
  }
  std::stable_sort(starts.begin(), starts.end(), [](const start& x, const start& y) {
    return x.lost < y.lost || (x.lost == y.lost && x.crossing > y.crossing);
  });
  Eigen::VectorXd best;
  std::size_t best_held = 0;
  for (std::size_t i = 0; i < starts.size() && i < 2; ++i) {
    // One reading free: the start refined by finer scans around it (two levels of 32 steps,
    // each to the median root of the relations crossing in its busiest step), so that the
    // snap starts where the true relations hold to ~1e-6 and the false ones do not.
    if (free == 1 && starts[i].crossing > 0) {
      const Eigen::VectorXd dz = reduced.col(1);
      double width = 4.0 / std::max(dz.cwiseAbs().maxCoeff(), 1e-12) / 128;
      Eigen::VectorXd r(static_cast<Eigen::Index>(reg.relations())), before;
      std::vector<double> roots, best_roots;
      for (int level = 0; level < 2; ++level) {
        const double from = starts[i].s[1] - width, step = 2 * width / 32;
        best_roots.clear();
        for (int j = 0; j <= 32; ++j) {
          Eigen::VectorXd sj = starts[i].s;
          sj[1] = from + step * j;
          regularity_residuals(pr, reg, Eigen::VectorXd(reduced * sj), r);
          if (j > 0) {
            roots.clear();
            for (Eigen::Index q = 0; q < r.size(); ++q)
              if (r[q] * before[q] < 0 && std::abs(r[q]) > 1e-9 && std::abs(before[q]) > 1e-9)
                roots.push_back(sj[1] - step * r[q] / (r[q] - before[q]));
            if (roots.size() > best_roots.size()) best_roots = roots;
          }
          before = r;
        }
        if (best_roots.empty()) break;
        std::nth_element(best_roots.begin(),
                         best_roots.begin() + static_cast<std::ptrdiff_t>(best_roots.size() / 2),
                         best_roots.end());
        starts[i].s[1] = best_roots[best_roots.size() / 2];
        width = step;
      }
    }
    const Eigen::VectorXd t = span * regular_reading(pr, terms, reg, reduced, starts[i].s, max_iterations,
                                                     iterations, exact, true, true);
    const Eigen::VectorXd z = basis * t;
    // A reading losing convex folds counts as holding nothing (inflate ranks it as a fault).
    const std::size_t held = folds_lost(z) > 0 ? 0 : held_relations(pr, reg, z, 100 * exact);
    if (best.size() == 0 || held > best_held) best = t, best_held = held;
  }
  return best;
}

/// Whether the faces at depths z cross each other or an edge pierces a face, by the main job's
/// exact certificate (cells/certify.hpp, crossings only) on the faces as given (holes turned
/// against their outer loop). 1 crossing, 0 not, −1 not decided (the faces build no complex, or
/// the budget ran out). O(n log n + pairs of faces with overlapping boxes · their sizes).
template <class Z>
int reading_crosses(const inflation_problem<>& pr, const Z& z) {
  cell_complex_input<glm::dvec3> in;
  for (std::size_t v = 0; v < pr.p.size(); ++v) in.points.push_back(glm::dvec3(pr.p[v], z[v]));
  in.edges = pr.edges;
  const auto area = [&](const std::vector<std::uint32_t>& loop) {
    double a = 0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const glm::dvec2 p = pr.p[loop[k]], q = pr.p[loop[(k + 1) % loop.size()]];
      a += p.x * q.y - p.y * q.x;
    }
    return a;
  };
  for (std::size_t l = 0; l < pr.loops.size(); ++l) {
    if (l == 0 || pr.loop_face[l] != pr.loop_face[l - 1]) {
      in.faces.push_back({{pr.loops[l]}});
      continue;
    }
    auto hole = pr.loops[l];
    if ((area(hole) > 0) == (area(in.faces.back().loops[0]) > 0)) std::reverse(hole.begin(), hole.end());
    in.faces.back().loops.push_back(std::move(hole));
  }
  try {
    const cell_complex<glm::dvec3> c = make_cell_complex(std::move(in));
    certify_options o;
    o.check_input_edges = o.check_edges = o.check_volumes = false;
    const certificate_result r = cellforge::certify(c, o);
    if (r.find(certificate_failure::kind::faces_cross) ||
        r.find(certificate_failure::kind::edge_pierces_face))
      return 1;
    return r.complete ? 0 : -1;
  } catch (const error&) {
    return -1;
  }
}

/// Whether the main job's face stages (wireframe_to_cells, no complex built) find exactly the
/// drawing's face loops at depths z: a reading that makes two faces coplanar, loses a face or
/// gains a planar cycle that becomes a face does not. O(the pipeline's face stages).
template <class Z>
bool reading_keeps_faces(const inflation_problem<>& pr, const Z& z) {
  wireframe<glm::dvec3> w;
  for (std::size_t v = 0; v < pr.p.size(); ++v) w.points.push_back(glm::dvec3(pr.p[v], z[v]));
  w.edges = pr.edges;
  wireframe_options o;
  o.build_complex = false;
  try {
    const wireframe_result<glm::dvec3> r = wireframe_to_cells(w, o);
    std::vector<std::vector<std::uint32_t>> got, want;
    for (const auto& f : r.input.faces)
      for (const auto& loop : f.loops) {
        std::vector<std::uint32_t> l;
        for (const auto v : loop) l.push_back(r.input_vertex[v]);
        got.push_back(cellforge::detail::canonical_cycle(l));
      }
    for (const auto& loop : pr.loops) want.push_back(cellforge::detail::canonical_cycle(loop));
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    return got == want;
  } catch (const error&) {
    return false;
  }
}

/// Result of the direct method in normalised coordinates.
template <class = void>
struct direct_solution {
  bool ok = false;
  std::vector<double> z;  // one Necker reading; the other is −z
  std::array<glm::dvec2, 3> d{};
  std::array<double, 3> s{};
  std::array<double, 9> rotation{};
  double misclosure = 0;
  std::size_t reached = 0;                // junctions whose depth the hypothesis fixes
  std::size_t coverage = 0;               // lines along the three axes
  std::size_t corners = 0;                // junctions where lines along all three axes meet
  std::vector<std::vector<double>> tied;  // the readings of hypotheses tied at the top
  std::string why;
};

/// Direct inflation: axis directions from clustered line directions, foreshortenings from
/// Σ s_i² d_i d_iᵀ = I₂, depth along axis edges, the rest from face planarity. O(E² + K³ + U³),
/// U the junctions no axis edge reaches.
template <class = void>
direct_solution<> direct_inflation(const inflation_problem<>& pr, const inflation_options& o) {
  direct_solution<> best;
  best.why = "fewer than three line directions";
  const std::size_t ne = pr.edges.size(), nv = pr.p.size();
  std::vector<double> ang(ne), len(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    const glm::dvec2 d = pr.p[pr.edges[e][1]] - pr.p[pr.edges[e][0]];
    ang[e] = line_angle(d), len[e] = glm::length(d);
  }
  // Greedy clustering by total line length within the tolerance; up to 5 clusters.
  std::vector<bool> used(ne, false);
  std::vector<std::vector<std::uint32_t>> clusters;
  std::vector<direct_solution<>> consistent;  // hypotheses that close and fit planar faces
  while (clusters.size() < 6) {
    double best_w = 0;
    std::size_t pick = ne;
    for (std::size_t i = 0; i < ne; ++i) {
      if (used[i]) continue;
      double w = 0;
      for (std::size_t j = 0; j < ne; ++j)
        if (!used[j] && angle_distance(ang[i], ang[j]) <= o.direction_tolerance) w += len[j];
      if (w > best_w) best_w = w, pick = i;
    }
    if (pick == ne) break;
    std::vector<std::uint32_t> members;
    for (std::size_t j = 0; j < ne; ++j)
      if (!used[j] && angle_distance(ang[pick], ang[j]) <= o.direction_tolerance)
        members.push_back(static_cast<std::uint32_t>(j)), used[j] = true;
    clusters.push_back(std::move(members));
  }
  // Every triple of clusters is a candidate set of axes; the one reaching most junctions with
  // a closing, consistent depth wins.
  for (std::size_t c0 = 0; c0 < clusters.size(); ++c0)
    for (std::size_t c1 = c0 + 1; c1 < clusters.size(); ++c1)
      for (std::size_t c2 = c1 + 1; c2 < clusters.size(); ++c2) {
        const std::array<std::size_t, 3> cs{c0, c1, c2};
        direct_solution<> cand;
        for (std::size_t i = 0; i < 3; ++i) {
          double sx = 0, sy = 0;  // mean of doubled angles, weighted by length
          for (const auto e : clusters[cs[i]])
            sx += len[e] * std::cos(2 * ang[e]), sy += len[e] * std::sin(2 * ang[e]);
          const double a = 0.5 * std::atan2(sy, sx);
          cand.d[i] = {std::cos(a), std::sin(a)};
        }
        Eigen::Matrix3d m;
        for (int i = 0; i < 3; ++i) {
          const glm::dvec2 d = cand.d[static_cast<std::size_t>(i)];
          m(0, i) = d.x * d.x, m(1, i) = d.x * d.y, m(2, i) = d.y * d.y;
        }
        Eigen::ColPivHouseholderQR<Eigen::Matrix3d> qr(m);
        if (qr.rank() < 3) {
          cand.why = "two axis directions coincide in the drawing";
          continue;
        }
        const Eigen::Vector3d u = qr.solve(Eigen::Vector3d(1, 0, 1));
        if (!(u.minCoeff() > 1e-12 && u.maxCoeff() < 1 - 1e-12)) {
          if (best.reached == 0)
            best.why =
                "no three line directions are the image of three orthogonal axes (s_i² outside (0, 1))";
          continue;
        }
        for (std::size_t i = 0; i < 3; ++i) cand.s[i] = std::sqrt(u[static_cast<Eigen::Index>(i)]);
        const glm::dvec3 r1(cand.s[0] * cand.d[0].x, cand.s[1] * cand.d[1].x, cand.s[2] * cand.d[2].x);
        const glm::dvec3 r2(cand.s[0] * cand.d[0].y, cand.s[1] * cand.d[1].y, cand.s[2] * cand.d[2].y);
        const glm::dvec3 r3 = glm::cross(r1, r2);
        cand.rotation = {r1.x, r1.y, r1.z, r2.x, r2.y, r2.z, r3.x, r3.y, r3.z};
        // Axis edges: those within the tolerance of a cluster direction.
        std::vector<int> axis(ne, -1);
        for (std::size_t i = 0; i < 3; ++i)
          for (const auto e : clusters[cs[i]]) axis[e] = static_cast<int>(i), ++cand.coverage;
        // An axis hypothesis must be supported: two lines or more along each axis, and a
        // junction where lines along all three meet (a corner). Else any three single lines
        // would do (a pyramid's base square and one lateral line "read" as a skew corner).
        bool supported = clusters[c0].size() >= 2 && clusters[c1].size() >= 2 && clusters[c2].size() >= 2;
        for (std::uint32_t v = 0; v < nv && supported; ++v) {
          unsigned seen = 0;
          for (const auto e : pr.incident[v])
            if (axis[e] >= 0) seen |= 1u << axis[e];
          cand.corners += seen == 7u;
        }
        if (!supported || cand.corners == 0) {
          if (best.reached == 0)
            best.why = "no three line directions with two lines each meet at a corner (not a normalon view)";
          continue;
        }
        const auto dz = [&](std::size_t e) {
          const auto i = static_cast<std::size_t>(axis[e]);
          const glm::dvec2 d = pr.p[pr.edges[e][1]] - pr.p[pr.edges[e][0]];
          return glm::dot(d, cand.d[i]) / cand.s[i] * r3[static_cast<glm::length_t>(i)];
        };
        // Breadth-first depth from the largest component of the axis edges.
        std::vector<double> z(nv, 0.0);
        std::vector<int> comp(nv, -1);
        std::vector<std::size_t> comp_size;
        for (std::uint32_t s = 0; s < nv; ++s) {
          if (comp[s] >= 0) continue;
          const int id = static_cast<int>(comp_size.size());
          std::vector<std::uint32_t> queue{s};
          comp[s] = id;
          for (std::size_t q = 0; q < queue.size(); ++q) {
            const std::uint32_t v = queue[q];
            for (const auto e : pr.incident[v]) {
              if (axis[e] < 0) continue;
              const std::uint32_t w = pr.edges[e][0] == v ? pr.edges[e][1] : pr.edges[e][0];
              if (comp[w] >= 0) continue;
              comp[w] = id;
              z[w] = z[v] + (pr.edges[e][0] == v ? dz(e) : -dz(e));
              queue.push_back(w);
            }
          }
          comp_size.push_back(queue.size());
        }
        const int main =
            static_cast<int>(std::max_element(comp_size.begin(), comp_size.end()) - comp_size.begin());
        for (std::size_t e = 0; e < ne; ++e)
          if (axis[e] >= 0 && comp[pr.edges[e][0]] == main)
            cand.misclosure =
                std::max(cand.misclosure, std::abs(z[pr.edges[e][1]] - z[pr.edges[e][0]] - dz(e)));
        if (cand.misclosure > o.closure_tolerance) {
          cand.why = cellforge::detail::cat("a cycle of axis edges does not close in depth (misclosure ",
                                            std::to_string(cand.misclosure),
                                            " of the drawing size): not a normalon drawing");
          if (best.reached == 0) best.why = cand.why;
          continue;
        }
        // The junctions off the main component: least squares of face planarity and axis
        // edges, the main component's depths fixed.
        std::vector<Eigen::Index> unknown(nv, -1);
        Eigen::Index nu = 0;
        for (std::uint32_t v = 0; v < nv; ++v)
          if (comp[v] != main) unknown[v] = nu++;
        if (nu > 0) {
          std::vector<std::pair<std::vector<std::pair<Eigen::Index, double>>, double>> eqs;
          for (const auto& r : pr.rows) {
            std::vector<std::pair<Eigen::Index, double>> row;
            double rhs = 0;
            const std::array<std::pair<std::uint32_t, double>, 4> terms{
                {{r.d, 1.0}, {r.a, -r.alpha}, {r.b, -r.beta}, {r.c, -r.gamma}}};
            for (const auto& [v, c] : terms)
              if (unknown[v] >= 0)
                row.push_back({unknown[v], c});
              else
                rhs -= c * z[v];
            if (!row.empty()) eqs.push_back({std::move(row), rhs});
          }
          for (std::size_t e = 0; e < ne; ++e) {
            if (axis[e] < 0) continue;
            const auto a = pr.edges[e][0], b = pr.edges[e][1];
            if (unknown[a] < 0 && unknown[b] < 0) continue;
            std::vector<std::pair<Eigen::Index, double>> row;
            double rhs = dz(e);
            if (unknown[b] >= 0)
              row.push_back({unknown[b], 1.0});
            else
              rhs -= z[b];
            if (unknown[a] >= 0)
              row.push_back({unknown[a], -1.0});
            else
              rhs += z[a];
            eqs.push_back({std::move(row), rhs});
          }
          Eigen::MatrixXd a = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(eqs.size()), nu);
          Eigen::VectorXd rhs(static_cast<Eigen::Index>(eqs.size()));
          for (std::size_t i = 0; i < eqs.size(); ++i) {
            for (const auto& [col, c] : eqs[i].first) a(static_cast<Eigen::Index>(i), col) += c;
            rhs[static_cast<Eigen::Index>(i)] = eqs[i].second;
          }
          Eigen::ColPivHouseholderQR<Eigen::MatrixXd> ls(a);
          ls.setThreshold(o.rank_tolerance);
          cand.reached = comp_size[static_cast<std::size_t>(main)];
          if (ls.rank() < nu) {
            cand.why = std::to_string(nu - ls.rank()) +
                       " junction depth(s) fixed neither by axis edges nor by face planes";
            cand.z = z;  // the unfixed junctions at 0 (the drawing's mid-depth): a start for optimisation
            consistent.push_back(std::move(cand));
            continue;
          }
          const Eigen::VectorXd x = ls.solve(rhs);
          for (std::uint32_t v = 0; v < nv; ++v)
            if (unknown[v] >= 0) z[v] = x[unknown[v]];
          double worst = 0;
          for (const auto& r : pr.rows) worst = std::max(worst, std::abs(plane_residual(r, z)));
          for (std::size_t e = 0; e < ne; ++e)
            if (axis[e] >= 0)
              worst = std::max(worst, std::abs(z[pr.edges[e][1]] - z[pr.edges[e][0]] - dz(e)));
          if (worst > o.closure_tolerance) {
            cand.why = cellforge::detail::cat("the oblique junctions fit no planar faces (residual ",
                                              std::to_string(worst), ")");
            continue;
          }
        }
        cand.reached = nv;
        cand.ok = true;
        cand.z = std::move(z);
        consistent.push_back(std::move(cand));
      }
  // The hypothesis with most axis lines, then most three-axis corners; a tie means the drawing
  // does not say which three directions are the axes (a hexagonal prism): not read directly.
  std::pair<std::size_t, std::size_t> top{0, 0};
  std::size_t ties = 0;
  for (const auto& c : consistent) top = std::max(top, std::pair{c.coverage, c.corners});
  std::vector<std::vector<double>> tied;
  for (auto& c : consistent)
    if (std::pair{c.coverage, c.corners} == top) {
      if (c.ok) tied.push_back(c.z);
      if (ties++ == 0) best = c;
    }
  if (ties > 1) best.tied = std::move(tied);
  if (ties > 1) {
    best.ok = false;
    best.why = std::to_string(ties) + " choices of three line directions read alike as the axes (" +
               std::to_string(top.first) + " lines, " + std::to_string(top.second) +
               " corners each): the drawing does not say which are the axes";
  }
  return best;
}

/// An orthonormal basis of the depths that keep every face planar, with mean depth 0 (the
/// depth offset removed): the null space of [C; 1ᵀ] from a column-pivoting QR of its
/// transpose. O(V² (R + 1)).
template <class = void>
Eigen::MatrixXd planar_readings(const inflation_problem<>& pr, double rank_tolerance) {
  const auto nv = static_cast<Eigen::Index>(pr.p.size());
  const auto nr = static_cast<Eigen::Index>(pr.rows.size());
  Eigen::MatrixXd ct = Eigen::MatrixXd::Zero(nv, nr + 1);
  for (Eigen::Index i = 0; i < nr; ++i) {
    const auto& r = pr.rows[static_cast<std::size_t>(i)];
    ct(r.d, i) += 1, ct(r.a, i) -= r.alpha, ct(r.b, i) -= r.beta, ct(r.c, i) -= r.gamma;
  }
  ct.col(nr).setConstant(1.0 / std::sqrt(static_cast<double>(nv)));
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(ct);
  qr.setThreshold(rank_tolerance);
  const Eigen::Index rank = qr.rank();
  const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(nv, nv);
  return q.rightCols(nv - rank);
}

/// The planarity rows C (one per row of pr.rows) and a last row of ones / √V (the depth offset),
/// sparse. O(R).
template <class = void>
Eigen::SparseMatrix<double> planarity_matrix(const inflation_problem<>& pr) {
  const auto nv = static_cast<Eigen::Index>(pr.p.size());
  const auto nr = static_cast<Eigen::Index>(pr.rows.size());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(pr.rows.size() * 4 + pr.p.size());
  for (Eigen::Index i = 0; i < nr; ++i) {
    const auto& r = pr.rows[static_cast<std::size_t>(i)];
    t.emplace_back(i, r.d, 1.0), t.emplace_back(i, r.a, -r.alpha), t.emplace_back(i, r.b, -r.beta),
        t.emplace_back(i, r.c, -r.gamma);
  }
  for (Eigen::Index v = 0; v < nv; ++v) t.emplace_back(nr, v, 1.0 / std::sqrt(static_cast<double>(nv)));
  Eigen::SparseMatrix<double> c(nr + 1, nv);
  c.setFromTriplets(t.begin(), t.end());
  return c;
}

/// Dimension of the planar-face readings (the null space of [C; 1ᵀ]) from a sparse QR, for
/// drawings read directly (which need no basis). O(fill of the sparse QR): each face's rows share
/// its reference triangle, so long faces fill it (about V^2.3 on combs, docs/benchmarks.md).
template <class = void>
std::size_t planar_freedom(const inflation_problem<>& pr, double rank_tolerance) {
  // C alone: constant depths meet every row (α + β + γ = 1) and not the gauge row 1ᵀ, so
  // rank [C; 1ᵀ] = rank C + 1, and the dense gauge row would fill the factor (1.6× the time).
  Eigen::SparseMatrix<double> full = planarity_matrix(pr);
  Eigen::SparseMatrix<double> c = full.topRows(full.rows() - 1);
  // SparseQR factors a tall matrix: C when it has at least V rows, its transpose otherwise.
  if (c.rows() < c.cols()) c = Eigen::SparseMatrix<double>(c.transpose());
  c.makeCompressed();
  Eigen::Index rank = 0;
  if (c.nonZeros() > 0) {
    Eigen::SparseQR<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> qr;
    qr.setPivotThreshold(rank_tolerance);
    qr.compute(c);
    rank = qr.info() == Eigen::Success ? qr.rank() : std::min(c.rows(), c.cols());
  }
  return static_cast<std::size_t>(static_cast<Eigen::Index>(pr.p.size()) - rank - 1);
}

/// Least-squares readings of an inexact drawing: the exact planar readings and the near ones, an
/// orthonormal basis from the SVD of [C; 1ᵀ] with each planarity row scaled to unit length. The
/// near ones are the singular vectors below the widest gap (a ratio of 2 or more) among the six
/// smallest singular values above the exact ones; without such a gap, the smallest one when
/// only the tilts are exact (a solid has more), else none. Sets `near`. O(V² R).
template <class = void>
Eigen::MatrixXd near_planar_readings(const inflation_problem<>& pr, double rank_tolerance,
                                     std::size_t& near) {
  const auto nv = static_cast<Eigen::Index>(pr.p.size());
  Eigen::MatrixXd c = Eigen::MatrixXd(planarity_matrix(pr));
  for (Eigen::Index i = 0; i + 1 < c.rows(); ++i) c.row(i).normalize();
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(c, Eigen::ComputeFullV);
  std::vector<double> sigma(static_cast<std::size_t>(nv), 0.0);  // ascending, missing ones 0
  const Eigen::VectorXd& s = svd.singularValues();
  for (Eigen::Index i = 0; i < s.size(); ++i) sigma[static_cast<std::size_t>(nv - 1 - i)] = s[i];
  const double top = s.size() > 0 ? s[0] : 0.0;
  std::size_t exact = 0;
  while (exact < sigma.size() && sigma[exact] <= rank_tolerance * top) ++exact;
  near = 0;
  double widest = 2.0;
  for (std::size_t q = 1; q <= 6 && exact + q < sigma.size(); ++q) {
    const double ratio = sigma[exact + q] / std::max(sigma[exact + q - 1], 1e-300);
    if (ratio >= widest) widest = ratio, near = q;
  }
  if (near == 0 && exact <= 2 && exact < sigma.size()) near = 1;
  const auto k = static_cast<Eigen::Index>(exact + near);
  return svd.matrixV().rightCols(k);
}

/// Lines whose two face loops are coplanar at depths z (the sine of the angle between their
/// normals below 1e-3): a reading in which faces merge. O(L log L).
template <class Z>
std::size_t coplanar_neighbours(const inflation_problem<>& pr, const Z& z) {
  std::vector<glm::dvec3> normal;
  std::vector<std::array<std::uint32_t, 3>> sides;  // (lo, hi, loop)
  for (std::uint32_t l = 0; l < pr.loops.size(); ++l) {
    const auto& loop = pr.loops[l];
    glm::dvec3 n{0.0};
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const glm::dvec3 a(pr.p[loop[k]], z[loop[k]]);
      const std::uint32_t nb = loop[(k + 1) % loop.size()];
      const glm::dvec3 b(pr.p[nb], z[nb]);
      n += glm::cross(a, b);
      sides.push_back({std::min(loop[k], nb), std::max(loop[k], nb), l});
    }
    const double len = glm::length(n);
    normal.push_back(len > 0 ? n / len : n);
  }
  std::sort(sides.begin(), sides.end());
  std::size_t flat = 0;
  for (std::size_t i = 0; i + 1 < sides.size(); ++i)
    if (sides[i][0] == sides[i + 1][0] && sides[i][1] == sides[i + 1][1] &&
        glm::length(glm::cross(normal[sides[i][2]], normal[sides[i + 1][2]])) < 1e-3)
      ++flat;
  return flat;
}

/// The view-from-above score of depths z: the lines most upright in the drawing (the most
/// vertical class of 2D-parallel lines, else the most vertical line), each taken going up the
/// picture, come towards the viewer by this much (Σ Δz / Σ 3D length, in (−1, 1)): positive
/// when the object's "up" tilts towards the viewer, the top seen. Sets `lines`. O(E).
template <class = void>
double from_above_score(const inflation_problem<>& pr, const compliance_terms<>& t,
                        const std::vector<double>& z, std::size_t& lines) {
  std::vector<std::uint32_t> pick;
  double upright = -1;
  for (std::size_t c = 0; c < t.parallel.size(); ++c)
    if (std::abs(t.parallel_direction[c].y) > upright)
      upright = std::abs(t.parallel_direction[c].y), pick = t.parallel[c];
  if (pick.empty())
    for (std::uint32_t e = 0; e < pr.edges.size(); ++e) {
      const glm::dvec2 d = pr.p[pr.edges[e][1]] - pr.p[pr.edges[e][0]];
      if (std::abs(d.y) / glm::length(d) > upright) upright = std::abs(d.y) / glm::length(d), pick = {e};
    }
  double climb = 0, length = 0;
  for (const auto e : pick) {
    const auto& ed = pr.edges[e];
    const glm::dvec2 d = pr.p[ed[1]] - pr.p[ed[0]];
    const double dz = (d.y >= 0 ? 1.0 : -1.0) * (z[ed[1]] - z[ed[0]]);
    climb += dz, length += std::sqrt(glm::dot(d, d) + dz * dz);
  }
  lines = pick.size();
  return length > 0 ? climb / length : 0.0;
}

/// inflate's engine, one per result point type R: inflate<void> and inflate<R> share it (the
/// body is the sketch part's largest template). O(as inflate).
template <class R, LineDrawing D>
inflation_result<R> inflate_faces(const D& drawing,
                                  const std::vector<std::vector<std::vector<std::uint32_t>>>& faces,
                                  const inflation_options& user_options) {
  static_assert(Point3<R>, "inflate: the result point type must be a registered Point3");
  const detail::stopwatch t0;
  inflation_result<R> res;
  // Tolerances no finer than the drawing's own precision (float drawings are realizable only
  // to rounding).
  inflation_options options = user_options;
  if constexpr (std::is_floating_point_v<scalar2_t<drawing_point_t<D>>>) {
    const double eps = 64.0 * std::numeric_limits<scalar2_t<drawing_point_t<D>>>::epsilon();
    options.rank_tolerance = std::max(options.rank_tolerance, eps);
    options.closure_tolerance = std::max(options.closure_tolerance, eps);
    options.direction_tolerance = std::max(options.direction_tolerance, eps);
  }
  const detail::inflation_problem<> pr = detail::make_inflation_problem(drawing, faces);
  const std::size_t nv = pr.p.size();
  detail::compliance_terms<> terms = detail::make_compliance_terms(pr, options.direction_tolerance);
  auto m = static_cast<Eigen::Index>(terms.count() + pr.edges.size() + nv);
  Eigen::VectorXd scratch(m);
  const auto measure = [&](const std::vector<double>& z) {
    inflation_residuals r;
    detail::compliance_residuals(pr, terms, inflation_weights{1, 1, 1, 1, 1}, z, scratch, &r);
    return r;
  };
  // The basis of the planar readings is dense (O(V² R)): built only when the optimisation needs it.
  Eigen::MatrixXd basis;

  std::vector<double> z;
  detail::direct_solution<> direct;
  if (options.allow_direct) {
    direct = detail::direct_inflation(pr, options);
    if (direct.ok) {
      z = direct.z;
      res.method = inflation_method::direct;
      res.view_found = true;
      for (std::size_t i = 0; i < 3; ++i) {
        res.axis_directions[i] = {direct.d[i].x, direct.d[i].y};
        res.foreshortening[i] = direct.s[i];
      }
      res.view_rotation = direct.rotation;
      res.misclosure = direct.misclosure;
    } else {
      res.diagnostics.push_back(
          cellforge::detail::cat("inflate: direct method not applicable: ", direct.why));
    }
  }
  // A direct reading with lines off the three axes assumes those axes; it stands only if no
  // reading of the planar family is more regular (a regular prism's caps are not two axes).
  const bool oblique = direct.ok && direct.coverage < pr.edges.size() && !options.least_squares &&
                       options.allow_optimisation && options.regularity &&
                       options.regularity_max_freedom >= 3;
  if (z.empty() || oblique) {
    if (!options.allow_optimisation)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("inflate: the direct method does not apply (", direct.why,
                                         ") and optimisation is off"));
    if (options.least_squares) {
      basis = detail::near_planar_readings(pr, options.rank_tolerance, res.near_readings);
      res.least_squares = true;
      terms.planar_rows = pr.rows.size();
      m = static_cast<Eigen::Index>(terms.count() + pr.edges.size() + nv);
      scratch.resize(m);
    } else {
      basis = detail::planar_readings(pr, options.rank_tolerance);
    }
    res.freedom = static_cast<std::size_t>(basis.cols());
    // Only the flat and tilted readings z = a x + b y (2 after the offset): no solid.
    if (basis.cols() <= 2)
      throw error(
          error_category::topology,
          cellforge::detail::cat(
              "inflate: the face loops admit only flat readings (planar-face freedom ",
              std::to_string(basis.cols() + 1),
              " = the tilts and the offset): the drawing is not the view of a solid with these faces, "
              "or it is too inexact; tidy it or raise rank_tolerance"));
    std::vector<Eigen::VectorXd> starts;
    // Convexity prior: when the faces admit a strictly convex reading, it is a start and the
    // hinge term joins the objective (every start is then ranked with it).
    if (options.weights.convexity > 0 && options.convexity_start_margin > 0) {
      auto rows = detail::make_convexity_rows(pr);
      if (!rows.empty()) {
        Eigen::VectorXd tc = detail::convex_reading(rows, basis, options.convexity_start_margin);
        if (tc.size() > 0) {
          const Eigen::VectorXd zt = basis * tc;
          const double range = zt.maxCoeff() - zt.minCoeff();
          if (range > 0) tc *= 0.5 / range;
          starts.push_back(tc);
          terms.convex = std::move(rows);
          terms.convex_margin = options.convexity_margin;
          m = static_cast<Eigen::Index>(terms.count() + pr.edges.size() + nv);
          scratch.resize(m);
          res.diagnostics.push_back(
              cellforge::detail::cat("inflate: the faces admit a convex reading: convexity term on (",
                                     std::to_string(terms.convex.size()), " folds) and a convex start"));
        }
      }
    }
    const detail::basis_rows rows = basis;
    detail::inflation_functor<> f{&pr, &terms, &basis, &rows, options.weights, m};
    detail::splitmix rng{options.seed};
    if (!direct.ok && direct.reached > 0 && !direct.z.empty()) {
      Eigen::VectorXd zd(static_cast<Eigen::Index>(nv));
      for (std::size_t i = 0; i < nv; ++i) zd[static_cast<Eigen::Index>(i)] = direct.z[i];
      starts.push_back(basis.transpose() * zd);
    }
    const int wanted = terms.convex.empty() ? std::max(1, options.starts)
                                            : std::max(1, std::min(options.starts, options.convex_starts));
    // A random planar reading, its depth range half the drawing's (unit) diagonal.
    const auto random_start = [&] {
      Eigen::VectorXd t(basis.cols());
      for (Eigen::Index i = 0; i < t.size(); ++i) t[i] = rng.uniform(-1, 1);
      const Eigen::VectorXd zt = basis * t;
      const double range = zt.maxCoeff() - zt.minCoeff();
      return range > 0 ? Eigen::VectorXd(t * (0.5 / range)) : t;
    };
    while (static_cast<int>(starts.size()) < wanted) starts.push_back(random_start());
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_flat = std::numeric_limits<std::size_t>::max();
    Eigen::VectorXd best_t;
    Eigen::VectorXd fv(m);
    for (const auto& s : starts) {
      Eigen::VectorXd t = s;
      detail::solve_lm(f, t, options.max_iterations, 1e-12, 1e-14, res.iterations);
      ++res.starts;
      f(t, fv);
      const double value = fv.squaredNorm();
      const Eigen::VectorXd zt = basis * t;
      const std::size_t flat = detail::coplanar_neighbours(pr, zt);
      // Fewest merged neighbours first (a reading in which two faces of an edge are coplanar
      // has lost a face), then the lowest objective.
      if (std::isfinite(value) && (flat < best_flat || (flat == best_flat && value < best)))
        best = value, best_t = t, best_flat = flat;
      if (res.starts == 1 && !direct.ok) {
        const Eigen::VectorXd z0 = basis * s;
        res.before = measure(std::vector<double>(z0.data(), z0.data() + z0.size()));
      }
    }
    if (best_t.size() == 0)
      throw error(error_category::internal, "inflate: the optimisation produced no finite reading");
    res.diagnostics.push_back(cellforge::detail::cat(
        "inflate: optimisation objective ", std::to_string(best), " after ", std::to_string(res.iterations),
        " iterations over ", std::to_string(res.starts), " starts"));
    // The regular reading: the planar reading a person sees holds more exact regularities
    // (right corners, equal corners, equal sides) than its affine relatives z → kz + ax + by.
    struct candidate {
      Eigen::VectorXd t;
      std::size_t flat, held, weighted;
      bool from_direct;
      const char* what;
      bool regular;  // moved to a regular reading (else the direct reading or the compliance optimum)
    };
    std::vector<candidate> cands;
    const detail::regularity_terms<> reg = detail::make_regularity_terms(pr, options.direction_tolerance);
    // A relation holds to `exact` (1e-9, or the drawing's own precision); it is counted held
    // to a hundred times that.
    const double exact = std::max(1e-9, options.closure_tolerance);
    const bool regular =
        options.regularity && !res.least_squares && res.freedom <= options.regularity_max_freedom;
    if (options.regularity && !res.least_squares && !regular)
      res.diagnostics.push_back(cellforge::detail::cat(
          "inflate: regularities not sought: planar freedom ", std::to_string(res.freedom),
          " above regularity_max_freedom (", std::to_string(options.regularity_max_freedom), ")"));
    const auto judge = [&](Eigen::VectorXd t, bool from_direct, const char* what, bool moved = true) {
      const Eigen::VectorXd zt = basis * t;
      if (!zt.allFinite()) return;
      std::size_t flat = detail::coplanar_neighbours(pr, zt);
      // A reading deeper than 8 drawing diagonals is a limit, not a solid: there every corner
      // between a line along the depth and one across it tends to a right angle.
      if (zt.cwiseAbs().maxCoeff() > 8) flat += nv;
      if (!terms.convex.empty()) {  // folds not convex, in whichever Necker reading has fewer
        double up = 0, down = 0;    // hinges, each row standing for `weight` of them
        for (const auto& c : terms.convex) {
          const double h = c.scale * detail::plane_residual(c, zt);
          up += h > -1e-9 ? c.weight : 0.0, down += h < 1e-9 ? c.weight : 0.0;
        }
        flat += static_cast<std::size_t>(std::min(up, down));
      }
      cands.push_back({std::move(t), flat, detail::held_relations(pr, reg, zt, 100 * exact),
                       detail::weighted_relations(pr, reg, zt, 100 * exact), from_direct, what, moved});
    };
    if (direct.ok) {
      Eigen::VectorXd zd(static_cast<Eigen::Index>(nv));
      for (std::size_t i = 0; i < nv; ++i) zd[static_cast<Eigen::Index>(i)] = direct.z[i];
      const Eigen::VectorXd td = basis.transpose() * zd;
      judge(td, true, "the direct reading", false);
      if (regular)
        judge(detail::regular_reading(pr, terms, reg, basis, td, options.max_iterations, res.iterations,
                                      exact, false),
              false, "the direct reading, its regularities made exact");
      if (regular)
        judge(
            detail::regular_reading(pr, terms, reg, basis, td, options.max_iterations, res.iterations, exact),
            false, "the regular reading near the direct one");
    }
    // Right-angled readings of axis hypotheses the drawing does not choose between.
    for (const auto& zt : regular ? direct.tied : std::vector<std::vector<double>>{}) {
      Eigen::VectorXd zd(static_cast<Eigen::Index>(nv));
      for (std::size_t i = 0; i < nv; ++i) zd[static_cast<Eigen::Index>(i)] = zt[i];
      const Eigen::VectorXd td = basis.transpose() * zd;
      judge(detail::regular_reading(pr, terms, reg, basis, td, options.max_iterations, res.iterations, exact,
                                    false),
            false, "a tied direct reading, its regularities made exact");
    }
    judge(best_t, false, "the optimised reading", false);
    if (regular)
      judge(detail::regular_reading(pr, terms, reg, basis, best_t, options.max_iterations, res.iterations,
                                    exact),
            false, "the regular reading near the optimised one");
    // Hypotheses solved linearly (regular polygons' planes, orthogonal axes), each searched over
    // the planar readings that meet it: the symmetric starts random ones seldom find.
    if (options.regularity && !res.least_squares) {
      std::size_t tried = 0;
      for (const auto& h :
           detail::regular_hypotheses(pr, terms, 100 * exact, options.regularity_hypotheses)) {
        if (tried >= options.regularity_hypotheses) break;
        Eigen::VectorXd t = detail::hypothesis_reading(pr, terms, reg, basis, h, best_t, 100 * exact,
                                                       options.regularity_max_freedom, options.max_iterations,
                                                       res.iterations, exact);
        if (t.size() == 0) continue;
        ++tried;
        judge(std::move(t), false, "the regular reading of a hypothesis (regular polygons, orthogonal axes)");
      }
    }
    // The search can end in a local minimum holding few relations (antiprisms, pyramids): then
    // more starts, random planar readings as for the optimisation, while the best holds under
    // a quarter of the relations (a true antiprism holds two thirds, a pyramid a third).
    if (regular) {
      std::size_t most = 0;
      for (const auto& c : cands) most = std::max(most, c.held);
      const int more = res.freedom <= options.regularity_starts_max_freedom ? options.regularity_starts : 0;
      for (int k = 0; k < more && 4 * most < reg.relations(); ++k) {
        judge(detail::regular_reading(pr, terms, reg, basis, random_start(), options.max_iterations,
                                      res.iterations, exact),
              false, "the regular reading from a random start");
        if (!cands.empty()) most = std::max(most, cands.back().held);
      }
    }
    // Fewest merged neighbours (and convex folds lost), then most relations held, weighted
    // (weighted_relations); ties keep the earlier candidate (the direct reading first).
    if (cands.empty())
      throw error(error_category::internal, "inflate: the optimisation produced no finite reading");
    std::vector<std::size_t> order(cands.size());
    for (std::size_t c = 0; c < cands.size(); ++c) order[c] = c;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
      return cands[x].flat < cands[y].flat ||
             (cands[x].flat == cands[y].flat && cands[x].weighted > cands[y].weighted);
    });
    // No self-intersecting reading: the best candidate whose faces neither cross nor are
    // pierced by an edge (exactly, by certify). A regular candidate must also keep the drawing's
    // faces, as the main job finds them (snapping can make faces coplanar or a cycle planar);
    // else the direct reading or the compliance optimum. If every candidate fails, the best
    // unmoved one, flagged.
    std::vector<int> crossing(cands.size(), 2);  // 1 crosses, 0 not, −1 undecided, 2 not yet checked
    const auto crosses = [&](std::size_t c) {
      if (crossing[c] == 2) {
        crossing[c] = detail::reading_crosses(pr, Eigen::VectorXd(basis * cands[c].t));
        res.crossing_readings += crossing[c] == 1;
      }
      return crossing[c] == 1;
    };
    std::size_t pick = cands.size();
    for (const std::size_t c : order) {
      if (crosses(c)) continue;
      if (cands[c].regular && !detail::reading_keeps_faces(pr, Eigen::VectorXd(basis * cands[c].t))) {
        ++res.face_changing_readings;
        continue;
      }
      pick = c;
      break;
    }
    if (pick == cands.size()) {
      for (const std::size_t c : order)
        if (!cands[c].regular) {
          pick = c;
          break;
        }
      if (pick == cands.size()) pick = order[0];
      res.self_intersecting = crosses(pick);
    }
    if (res.self_intersecting) {
      res.diagnostics.push_back(
          "inflate: every reading found has faces that cross or an edge through a face "
          "(exact check): the reading returned self-intersects");
    } else if (res.crossing_readings > 0) {
      res.diagnostics.push_back(
          cellforge::detail::cat("inflate: ", std::to_string(res.crossing_readings),
                                 " more regular reading(s) self-intersect and were passed over"));
    }
    if (res.face_changing_readings > 0)
      res.diagnostics.push_back(cellforge::detail::cat(
          "inflate: ", std::to_string(res.face_changing_readings),
          " more regular reading(s) change the faces (the main job finds others in them) "
          "and were passed over"));
    for (const auto& c : cands)
      res.diagnostics.push_back(cellforge::detail::cat("inflate: candidate ", std::string(c.what), ": ",
                                                       std::to_string(c.held), " regularities held, ",
                                                       std::to_string(c.flat), " faults"));
    res.regular_relations = cands[pick].held;
    res.relations = reg.relations();
    res.diagnostics.push_back(cellforge::detail::cat(
        "inflate: ", std::string(cands[pick].what), " holds ", std::to_string(cands[pick].held), " of ",
        std::to_string(reg.relations()), " regularities (right, equal corners, equal sides)"));
    if (direct.ok && !cands[pick].from_direct) {
      res.diagnostics.push_back(
          "inflate: the direct reading's axes are not the drawing's: a reading of the planar family holds "
          "more regularities, and is taken");
      res.method = inflation_method::optimisation;
      res.view_found = false;
      res.view_rotation = {};
      res.axis_directions = {};
      res.foreshortening = {};
    } else if (!direct.ok) {
      res.method = inflation_method::optimisation;
    }
    if (direct.ok) res.before = measure(z);
    const Eigen::VectorXd zb = basis * cands[pick].t;
    z.assign(zb.data(), zb.data() + zb.size());
    const std::size_t flat = detail::coplanar_neighbours(pr, zb);
    if (flat > 0)
      res.diagnostics.push_back(
          cellforge::detail::cat("inflate: in the best reading found, ", std::to_string(flat),
                                 " line(s) join two coplanar faces (those faces would merge)"));
  } else {
    res.before = measure(z);
    res.freedom = detail::planar_freedom(pr, options.rank_tolerance);
    res.least_squares = options.least_squares;
  }
  // Mean depth 0, then the Necker pair ranked by the view-from-above prior.
  double mean = 0;
  for (const double v : z) mean += v;
  mean /= static_cast<double>(nv);
  for (double& v : z) v -= mean;
  std::vector<double> mirror(z);
  for (double& v : mirror) v = -v;
  res.after = measure(z);
  double range = 0;
  for (const double v : z) range = std::max(range, std::abs(v));
  if (range < 1e-6)
    res.diagnostics.push_back(
        "inflate: the reading found is flat (depth range below 1e-6 of the drawing size)");
  if (res.least_squares)
    res.diagnostics.push_back(cellforge::detail::cat(
        "inflate: least-squares reading: faces planar to ", std::to_string(res.after.planarity),
        " of the drawing size (", std::to_string(res.near_readings), " near-planar reading(s) added)"));
  std::size_t upright = 0;
  const double score = detail::from_above_score(pr, terms, z, upright);
  const auto lift = [&](const std::vector<double>& depth) {
    std::vector<R> out;
    out.reserve(nv);
    for (std::size_t i = 0; i < nv; ++i) {
      out.push_back(from_dvec3<R>(glm::dvec3(pr.raw[i], depth[i] * pr.size)));
    }
    return out;
  };
  const std::string rule =
      cellforge::detail::cat("view from above: the ", std::to_string(upright),
                             " most upright line(s) of the drawing, going up, come towards the viewer by ");
  inflation_reading<R> a{lift(z), score, rule + std::to_string(score)};
  inflation_reading<R> b{lift(mirror), -score, rule + std::to_string(-score) + " (the Necker reversal)"};
  if (score < 0) std::swap(a, b);
  if (std::abs(score) < 1e-9) a.reason += "; the prior cannot choose: both readings fit alike";
  res.points = a.points;
  if (res.view_found && score < 0) {
    // The preferred reading is the mirrored one: each axis's depth flips (third row), and
    // axis 3 is reversed (third column) so that the matrix stays a rotation.
    for (std::size_t k = 6; k < 9; ++k) res.view_rotation[k] = -res.view_rotation[k];
    for (std::size_t k = 2; k < 9; k += 3) res.view_rotation[k] = -res.view_rotation[k];
    res.axis_directions[2] = {-res.axis_directions[2][0], -res.axis_directions[2][1]};
  }
  res.readings.push_back(std::move(a));
  res.readings.push_back(std::move(b));
  res.milliseconds = t0.ms();
  return res;
}

}  // namespace detail

template <class Q, LineDrawing D>
detail::if_satisfied_t<LineDrawing<D>, detail::inflation_result_for, Q, D> inflate(
    const D& drawing, const std::vector<std::vector<std::vector<std::uint32_t>>>& faces,
    const inflation_options& user_options) {
  return detail::inflate_faces<detail::result_point_t<Q, drawing_point_t<D>>>(drawing, faces, user_options);
}

template <class Q, LineDrawing D>
detail::if_satisfied_t<LineDrawing<D>, detail::inflation_result_for, Q, D> inflate(
    const D& drawing, const std::vector<std::vector<std::uint32_t>>& loops,
    const inflation_options& options) {
  std::vector<std::vector<std::vector<std::uint32_t>>> faces;
  faces.reserve(loops.size());
  for (const auto& l : loops) faces.push_back({l});
  return inflate<Q>(drawing, faces, options);
}

#if defined(CELLFORGE_EXTERN_SKETCH)
// Compiled once in the file that includes cellforge/sketch/instantiate.hpp (docs/sketch.md).
extern template inflation_result<glm::dvec3> detail::inflate_faces<glm::dvec3, line_drawing<glm::dvec2>>(
    const line_drawing<glm::dvec2>&, const std::vector<std::vector<std::vector<std::uint32_t>>>&,
    const inflation_options&);
#endif

}  // namespace cellforge
