// SPDX-License-Identifier: MIT
// Arc detection (sketch/arc_detection.hpp) on generated strokes with known truth: exact
// elliptical arcs of every eccentricity, rotation and sweep 30-180 degrees, straight lines and
// L-shaped polylines, sampled like a pen and moved by noise of 0.2 % of the drawing's size.
// Every arc must be found with its centre and axes within the stated tolerances, no line or
// L leg read as an arc; totals are printed and every miss named. Release runs the full set,
// the sanitizer build (no NDEBUG) a tenth of it.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/samples/round_drawings.hpp"
#include "cellforge/sketch/arc_detection.hpp"

// The pieces this file tests, named (its page above includes them).
#include "cellforge/sketch/detail/arc_detection_impl.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace arc_detection_tests {

using cellforge::arc_rejection;
using cellforge::elliptical_arc;
using cellforge::stroke_piece_kind;
constexpr double pi = std::numbers::pi;

#ifdef NDEBUG
constexpr bool full = true;
#else
constexpr bool full = false;  // the sanitizer build: 10-50x slower, a tenth of the strokes
#endif

// The generated drawings live in the unit square; its diagonal is the drawing's size.
const double size = std::sqrt(2.0);
constexpr double noise = 0.002;    // × size: the largest displacement of a sample
constexpr double spacing = 0.005;  // × size: the pen's sampling step along a stroke

struct generator {
  cellforge::detail::splitmix rng;
  // A sample moved by a random vector of length <= noise × size (uniform in the disc).
  glm::dvec2 jitter(glm::dvec2 p) {
    const double r = noise * size * std::sqrt(rng.uniform(0, 1));
    const double t = rng.uniform(0, 2 * pi);
    return p + r * glm::dvec2(std::cos(t), std::sin(t));
  }
  // Samples a segment at the pen's spacing (both ends), into `out`, the first end skipped
  // when `skip_first` (an L's corner is sampled once).
  void segment(glm::dvec2 a, glm::dvec2 b, std::vector<glm::dvec2>& out, bool skip_first) {
    const int n = std::max(2, static_cast<int>(std::ceil(glm::length(b - a) / (spacing * size))));
    for (int i = skip_first ? 1 : 0; i <= n; ++i) out.push_back(jitter(a + (b - a) * (double(i) / n)));
  }
};

// The largest distance of an arc's points from its chord, / size.
double sagitta(const elliptical_arc<glm::dvec2>& a) {
  const glm::dvec2 p0 = cellforge::arc_point(a, 0.0), p1 = cellforge::arc_point(a, 1.0);
  const glm::dvec2 c = p1 - p0;
  double worst = 0;
  for (int i = 1; i < 200; ++i) {
    const glm::dvec2 d = cellforge::arc_point(a, i / 200.0) - p0;
    worst = std::max(worst, std::abs(c.x * d.y - c.y * d.x) / glm::length(c));
  }
  return worst / size;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5))];
}

TEST_CASE("arc detection: exact arcs, lines and L shapes with 0.2 % noise") {
  generator g{{20261203}};
  const int n_arcs = full ? 300 : 30, n_lines = full ? 100 : 10, n_ells = full ? 100 : 10;
  std::vector<std::vector<glm::dvec2>> strokes;
  std::vector<elliptical_arc<glm::dvec2>> truth;
  std::vector<std::string> names;
  int redrawn = 0;
  while (static_cast<int>(truth.size()) < n_arcs) {
    const double a = g.rng.uniform(0.1, 0.45), ratio = g.rng.uniform(0.25, 1.0);
    const double cx = g.rng.uniform(0.3, 0.7), cy = g.rng.uniform(0.3, 0.7);
    const double rot = g.rng.uniform(0, pi), start = g.rng.uniform(-pi, pi);
    const double sweep = g.rng.uniform(30, 180) * pi / 180 * (g.rng.uniform(0, 1) < 0.5 ? -1 : 1);
    const elliptical_arc<glm::dvec2> arc{{cx, cy}, a, a * ratio, rot, start, sweep};
    // An arc whose bulge is within a few noise widths of its chord is a line at this noise.
    if (sagitta(arc) < 5 * noise) {
      ++redrawn;
      continue;
    }
    // Samples at about the pen's spacing along the curve.
    const int n = std::max(8, static_cast<int>(std::abs(sweep) * a / (spacing * size)));
    std::vector<glm::dvec2> s;
    for (int i = 0; i <= n; ++i) s.push_back(g.jitter(cellforge::arc_point(arc, double(i) / n)));
    std::ostringstream name;
    name << "arc " << truth.size() << " (axes " << a << ", " << a * ratio << ", sweep "
         << std::abs(sweep) * 180 / pi << " deg)";
    strokes.push_back(s);
    truth.push_back(arc);
    names.push_back(name.str());
  }
  const std::size_t first_line = strokes.size();
  for (int k = 0; k < n_lines; ++k) {
    const glm::dvec2 a(g.rng.uniform(0, 1), g.rng.uniform(0, 1));
    const double len = g.rng.uniform(0.1, 0.9), t = g.rng.uniform(0, pi);
    std::vector<glm::dvec2> s;
    g.segment(a, a + len * glm::dvec2(std::cos(t), std::sin(t)), s, false);
    strokes.push_back(s);
    names.push_back("line " + std::to_string(k));
  }
  const std::size_t first_ell = strokes.size();
  std::vector<glm::dvec2> corners;
  for (int k = 0; k < n_ells; ++k) {
    const glm::dvec2 c(g.rng.uniform(0.2, 0.8), g.rng.uniform(0.2, 0.8));
    const double t0 = g.rng.uniform(0, 2 * pi), turn = g.rng.uniform(30, 150) * pi / 180;
    const double l0 = g.rng.uniform(0.1, 0.5), l1 = g.rng.uniform(0.1, 0.5);
    const glm::dvec2 d0(std::cos(t0), std::sin(t0)), d1(std::cos(t0 + turn), std::sin(t0 + turn));
    std::vector<glm::dvec2> s;
    g.segment(c - l0 * d0, c, s, false);
    g.segment(c, c + l1 * d1, s, true);
    strokes.push_back(s);
    corners.push_back(c);
    names.push_back("L " + std::to_string(k) + " (turn " + std::to_string(turn * 180 / pi) + " deg)");
  }

  const auto r = cellforge::detect_arcs(strokes, {.drawing_size = size});
  CHECK(r.self_crossing_strokes == 0);  // lines, arcs and Ls with a pen's jitter do not cross themselves
  REQUIRE(r.strokes.size() == strokes.size());
  CHECK(r.drawing_size == size);
  // Stated tolerances (docs/sketch.md, "Arc detection"), as fractions of the drawing's size:
  // the curve found lies within curve_tol of the true arc over the stroke, both ways, its ends
  // within end_tol of the true ends; its centre and axes within the tolerance of its sweep's
  // band (a short arc of an ellipse does not determine them at this noise).
  constexpr double curve_tol = 0.004, end_tol = 0.006;
  const auto centre_tol = [](double sweep_deg) {
    return sweep_deg >= 150 ? 0.02 : sweep_deg >= 120 ? 0.05 : 1e9;
  };
  int found = 0, accurate = 0, wrong = 0, banded = 0;
  std::vector<double> curve_err, centre_err[3], axis_err[3];
  // The distance of a point from an arc's whole ellipse.
  const auto off = [](const elliptical_arc<glm::dvec2>& a, glm::dvec2 p) {
    const double c = std::cos(a.rotation), s = std::sin(a.rotation);
    const glm::dvec2 d = p - a.centre;
    return std::abs(
        cellforge::detail::ellipse_frame_distance(a.rx, a.ry, {c * d.x + s * d.y, -s * d.x + c * d.y}).first);
  };
  for (std::size_t s = 0; s < strokes.size(); ++s) {
    const auto& sum = r.strokes[s];
    const auto piece = [&](std::size_t k) { return r.pieces[sum.first_piece + k]; };
    if (s < first_line) {
      const auto& t = truth[s];
      if (sum.num_pieces != 1 || piece(0).kind != stroke_piece_kind::arc) {
        MESSAGE("missed " << names[s] << ": " << sum.num_pieces
                          << " pieces, as one arc: " << std::string(cellforge::to_string(sum.whole)));
        continue;
      }
      ++found;
      const auto& a = piece(0).arc;
      double ce_curve = 0;
      for (int i = 0; i <= 40; ++i)
        ce_curve = std::max(
            {ce_curve, off(t, cellforge::arc_point(a, i / 40.0)), off(a, cellforge::arc_point(t, i / 40.0))});
      ce_curve /= size;
      const double end_err =
          std::max(glm::length(a.centre + (cellforge::arc_point(a, 0.0) - a.centre) -
                               cellforge::arc_point(t, 0.0)),
                   glm::length(cellforge::arc_point(a, 1.0) - cellforge::arc_point(t, 1.0))) /
          size;
      const double ce = glm::length(a.centre - t.centre) / size;
      // rx >= ry in the result; the truth's a >= b by construction.
      const double ae = std::max(std::abs(a.rx - t.rx), std::abs(a.ry - t.ry)) / size;
      const double deg = std::abs(t.sweep) * 180 / pi;
      const int band = deg >= 150 ? 0 : deg >= 120 ? 1 : 2;
      curve_err.push_back(ce_curve);
      centre_err[band].push_back(ce);
      axis_err[band].push_back(ae);
      if (band < 2) ++banded;
      const bool same_way = (a.sweep > 0) == (t.sweep > 0);
      if (ce_curve <= curve_tol && end_err <= end_tol && ce <= centre_tol(deg) && ae <= centre_tol(deg) &&
          same_way)
        ++accurate;
      else
        MESSAGE("inaccurate " << names[s] << ": curve off by " << ce_curve << ", ends by " << end_err
                              << ", centre by " << ce << ", axes by " << ae
                              << std::string(same_way ? "" : ", runs the wrong way"));
    } else if (s < first_ell) {
      if (sum.num_pieces != 1 || piece(0).kind != stroke_piece_kind::line) {
        ++wrong;
        MESSAGE("wrong " << names[s] << ": " << sum.num_pieces << " pieces, first "
                         << std::string(piece(0).kind == stroke_piece_kind::arc ? "an arc" : "a line"));
      }
    } else {
      const glm::dvec2 c = corners[s - first_ell];
      const bool two_lines = sum.num_pieces == 2 && piece(0).kind == stroke_piece_kind::line &&
                             piece(1).kind == stroke_piece_kind::line;
      // The split sample is the corner, to the noise and the sampling step.
      if (!two_lines || glm::length(piece(0).to - c) > 3 * spacing * size) {
        ++wrong;
        MESSAGE("wrong " << names[s] << ": " << sum.num_pieces << " pieces");
      }
    }
  }
  const char* band_name[3] = {"150-180 deg", "120-150 deg", "30-120 deg"};
  std::ostringstream bands;
  for (int b = 0; b < 3; ++b)
    bands << "; " << band_name[b] << " (" << centre_err[b].size() << "): centre error median "
          << percentile(centre_err[b], 0.5) << " max " << percentile(centre_err[b], 1) << ", axes median "
          << percentile(axis_err[b], 0.5) << " max " << percentile(axis_err[b], 1);
  MESSAGE("arcs found "
          << found << " of " << n_arcs << ", " << accurate << " accurate (" << redrawn
          << " drawn arcs were within 5 noise widths of their chord and redrawn); lines and Ls wrong: "
          << wrong << " of " << n_lines + n_ells << "; curve error median " << percentile(curve_err, 0.5)
          << " max " << percentile(curve_err, 1) << bands.str() << "; " << r.fits << " fits, " << r.splits
          << " splits, " << r.merges << " merges, " << r.milliseconds << " ms");
  CHECK(found == n_arcs);
  CHECK(accurate == n_arcs);
  CHECK(banded > 0);
  CHECK(wrong == 0);
  CHECK(r.num_arcs == static_cast<std::size_t>(n_arcs));
  CHECK(r.num_lines == static_cast<std::size_t>(n_lines + 2 * n_ells));
}

TEST_CASE("arc detection: a round drawn in one stroke, another point type, bad input") {
  // A line, a quarter ellipse tangent to it, and a line tangent to its other end, in one stroke
  // of float points (a rounded corner drawn without lifting the pen).
  generator g{{77}};
  using F = std::array<float, 2>;
  const elliptical_arc<glm::dvec2> q{{0.6, 0.6}, 0.3, 0.18, 0.3, -pi / 2, pi / 2};
  const glm::dvec2 p0 = cellforge::arc_point(q, 0.0), p1 = cellforge::arc_point(q, 1.0);
  std::vector<glm::dvec2> s;
  g.segment(p0 - 0.5 * cellforge::arc_tangent(q, 0.0), p0, s, false);
  for (int i = 1; i <= 60; ++i) s.push_back(g.jitter(cellforge::arc_point(q, i / 60.0)));
  g.segment(p1, p1 + 0.4 * cellforge::arc_tangent(q, 1.0), s, true);
  std::vector<std::vector<F>> strokes(1);
  for (const glm::dvec2& p : s) strokes[0].push_back({static_cast<float>(p.x), static_cast<float>(p.y)});
  strokes.push_back({{0.5f, 0.5f}, {0.5f, 0.5f}});  // one distinct sample: dropped, with a reason
  const auto r = cellforge::detect_arcs(strokes, {.drawing_size = size});
  REQUIRE(r.strokes.size() == 2);
  CHECK(r.dropped_strokes == 1);
  CHECK(r.strokes[1].num_pieces == 0);
  static_assert(std::is_base_of_v<cellforge::stage_report, std::remove_cvref_t<decltype(r)>>);
  CHECK_FALSE(r.diagnostics.empty());  // the dropped stroke is said (stage_report::diagnostics)
  CHECK(r.milliseconds > 0);
  std::string kinds;
  for (std::size_t k = 0; k < r.strokes[0].num_pieces; ++k)
    kinds += r.pieces[k].kind == stroke_piece_kind::arc ? 'A' : 'L';
  INFO("pieces: " << kinds);
  CHECK(r.strokes[0].whole == arc_rejection::off_curve);
  REQUIRE(kinds == "LAL");
  const auto& a = r.pieces[1].arc;
  // Where the arc meets its tangent lines is not sharp: the ends may slide along them by a few
  // sampling steps; the ellipse itself is the quarter's.
  CHECK(glm::length(glm::dvec2(a.centre[0], a.centre[1]) - q.centre) / size < 0.02);
  CHECK(std::abs(a.rx - q.rx) / size < 0.02);
  CHECK(std::abs(a.ry - q.ry) / size < 0.02);
  CHECK(r.diagnostics.size() == 2);
  MESSAGE("round in one stroke: " << kinds << ", arc sweep " << std::abs(a.sweep) * 180 / pi
                                  << " deg (true 90), " << r.diagnostics[0] << "; " << r.diagnostics[1]);

  CHECK_THROWS_AS(cellforge::detect_arcs(std::vector<std::vector<glm::dvec2>>{{{0, 0}, {NAN, 1}}}),
                  cellforge::error);
  CHECK_THROWS_AS(cellforge::detect_arcs(strokes, {.tolerance = 0}), cellforge::error);
  CHECK_THROWS_AS(cellforge::detect_arcs(strokes, {.drawing_size = -1}), cellforge::error);
  CHECK(cellforge::detect_arcs(std::vector<std::vector<glm::dvec2>>{}).pieces.empty());
  // An exact circle through fit_ellipse: centre and radius to rounding.
  std::vector<glm::dvec2> c;
  for (int i = 0; i < 12; ++i)
    c.push_back(glm::dvec2(1, 2) + 0.5 * glm::dvec2(std::cos(i * 0.2), std::sin(i * 0.2)));
  const auto f = cellforge::fit_ellipse(c);
  REQUIRE(f.rejection == arc_rejection::none);
  CHECK(glm::length(f.centre - glm::dvec2(1, 2)) < 1e-9);
  CHECK(std::abs(f.rx - 0.5) < 1e-9);
  CHECK(f.max_distance < 1e-9);
  CHECK(cellforge::fit_ellipse(std::vector<glm::dvec2>{{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}, {5, 5}})
            .rejection == arc_rejection::not_an_ellipse);
  CHECK(r.self_crossing_strokes == 0);

  // Self-intersecting strokes: a figure of eight (crossing at its centre) and a curl (a
  // trochoid's loop); the pieces are read, the crossings counted and the first one located.
  std::vector<std::vector<glm::dvec2>> crossed(2);
  for (int i = 0; i <= 200; ++i) {
    const double t = 2 * pi * i / 200.0 + 0.3;
    crossed[0].push_back(glm::dvec2(0.5, 0.5) + 0.4 * glm::dvec2(std::sin(t), std::sin(t) * std::cos(t)));
  }
  for (int i = 0; i <= 120; ++i) {
    const double t = 2 * pi * i / 120.0 - pi;
    crossed[1].push_back(glm::dvec2(0.5, 0.5) + 0.12 * glm::dvec2(t - 1.5 * std::sin(t), -1.5 * std::cos(t)));
  }
  const auto x = cellforge::detect_arcs(crossed, {.drawing_size = size});
  REQUIRE(x.strokes.size() == 2);
  CHECK(x.self_crossing_strokes == 2);
  CHECK(x.strokes[0].self_crossings == 1);
  CHECK(x.strokes[1].self_crossings == 1);
  CHECK(x.strokes[0].num_pieces > 1);
  std::string said;
  for (const auto& d : x.diagnostics)
    if (d.find("crosses itself") != std::string::npos) said += d + "\n";
  INFO(said);
  CHECK(said.find("stroke 0: crosses itself once, first at (0.5") == 0);
  CHECK(said.find("stroke 1: crosses itself once") != std::string::npos);
}

TEST_CASE("arc detection: circles in the faces of a quasi-normalon, fitted with the view's axes") {
  // A round's ends are circles in faces normal to a model axis; in a parallel view the other
  // two unit axes are drawn as u and v, and fit_view_circle fits only centre and radius. The
  // same strokes through the free ellipse fit show what the view's axes add.
  generator g{{31}};
  const int n = full ? 200 : 20;
  int accurate = 0, redrawn = 0;
  std::vector<double> centre_err, radius_err, free_centre_err;
  for (int k = 0; k < n; ++k) {
    // A random rotation (uniform quaternion); its first two rows project the model axes.
    const double u1 = g.rng.uniform(0, 1), u2 = g.rng.uniform(0, 2 * pi), u3 = g.rng.uniform(0, 2 * pi);
    const double qa = std::sqrt(1 - u1) * std::sin(u2), qb = std::sqrt(1 - u1) * std::cos(u2);
    const double qc = std::sqrt(u1) * std::sin(u3), qd = std::sqrt(u1) * std::cos(u3);
    const double row0[3] = {1 - 2 * (qb * qb + qc * qc), 2 * (qa * qb - qc * qd), 2 * (qa * qc + qb * qd)};
    const double row1[3] = {2 * (qa * qb + qc * qd), 1 - 2 * (qa * qa + qc * qc), 2 * (qb * qc - qa * qd)};
    const int ia = k % 3, ib = (k + 1) % 3;
    const glm::dvec2 u(row0[ia], row1[ia]), v(row0[ib], row1[ib]);
    if (std::abs(u.x * v.y - u.y * v.x) < 0.2) {  // the face nearly edge-on: another view
      --k;
      continue;
    }
    const double r = g.rng.uniform(0.05, 0.3), sweep = g.rng.uniform(30, 180) * pi / 180,
                 t0 = g.rng.uniform(0, 2 * pi);
    const glm::dvec2 c(g.rng.uniform(0.3, 0.7), g.rng.uniform(0.3, 0.7));
    // As for the free arcs: a bulge within 5 noise widths of the chord is a line at this noise.
    double bulge = 0;
    const glm::dvec2 e0 = c + r * (u * std::cos(t0) + v * std::sin(t0));
    const glm::dvec2 e1 = c + r * (u * std::cos(t0 + sweep) + v * std::sin(t0 + sweep));
    for (int i = 1; i < 100; ++i) {
      const double t = t0 + sweep * i / 100;
      const glm::dvec2 d = c + r * (u * std::cos(t) + v * std::sin(t)) - e0;
      bulge = std::max(bulge, std::abs((e1 - e0).x * d.y - (e1 - e0).y * d.x) / glm::length(e1 - e0));
    }
    if (bulge < 5 * noise * size) {
      ++redrawn;
      --k;
      continue;
    }
    std::vector<glm::dvec2> s;
    const int m = std::max(8, static_cast<int>(sweep * r / (spacing * size)));
    for (int i = 0; i <= m; ++i) {
      const double t = t0 + sweep * i / m;
      s.push_back(g.jitter(c + r * (u * std::cos(t) + v * std::sin(t))));
    }
    const auto f = cellforge::fit_view_circle(s, u, v);
    REQUIRE(f.rejection == arc_rejection::none);
    const double ce = glm::length(f.centre - c) / size, re = std::abs(f.radius - r) / r;
    centre_err.push_back(ce);
    radius_err.push_back(re);
    const auto e = cellforge::fit_ellipse(s);
    free_centre_err.push_back(glm::length(e.centre - c) / size);
    // Stated: centre and radius within 1 % of the size (the radius's own error is printed).
    if (ce <= 0.01 && std::abs(f.radius - r) <= 0.01 * size && f.max_distance <= 0.005 * size)
      ++accurate;
    else
      MESSAGE("view circle " << k << " (radius " << r << ", sweep " << sweep * 180 / pi
                             << " deg): centre off by " << ce << ", radius by " << re * 100 << " %");
  }
  MESSAGE("view circles: " << accurate << " of " << n << " with centre and radius within 1 % of the size ("
                           << redrawn << " redrawn: bulge within 5 noise widths); centre error median "
                           << percentile(centre_err, 0.5) << " max " << percentile(centre_err, 1)
                           << ", radius error median " << percentile(radius_err, 0.5) * 100 << " % max "
                           << percentile(radius_err, 1) * 100
                           << " %; the free ellipse fit on the same strokes: centre "
                           << "median " << percentile(free_centre_err, 0.5) << " max "
                           << percentile(free_centre_err, 1));
  CHECK(accurate == n);
  CHECK_THROWS_AS(cellforge::fit_view_circle(std::vector<glm::dvec2>{{0, 0}, {1, 0}, {0, 1}},
                                             glm::dvec2(1, 0), glm::dvec2(2, 0)),
                  cellforge::error);
}

// The generated round drawings (samples/round_drawings.hpp) drawn by a pen: every edge
// and every arc one stroke, samples 0.5 % of the size apart, each moved by up to 0.2 % of the
// size. No line may become an arc and every arc whose bulge (largest distance from its chord)
// is at least 5 noise widths must be found as one arc, as in the set above; smaller arcs are
// lines at this noise (a round seen nearly edge-on, or an arc split at its contour point):
// those found are counted, not required.
TEST_CASE("arc detection: the round drawings sampled like a pen, 0.2 % noise") {
  cellforge::samples::round_sweep_options o;
  o.drawings = full ? 240 : 24;
  generator g{{20261204}};
  std::size_t lines = 0, lines_right = 0, arcs = 0, bulging = 0, bulging_found = 0, shallow_found = 0,
              self_crossing = 0;
  std::vector<std::string> misses;
  for (const auto& s : cellforge::samples::round_drawing_sweep(o)) {
    const auto& p = s.drawing.lines.points;
    glm::dvec2 lo = p[0], hi = p[0];
    for (const auto& q : p) lo = glm::min(lo, q), hi = glm::max(hi, q);
    const double d = glm::length(hi - lo);
    const auto pen = [&](glm::dvec2 q) { return q + (g.jitter(glm::dvec2(0)) / size) * d; };
    std::vector<std::vector<glm::dvec2>> strokes;
    for (const auto& e : s.drawing.lines.edges) {
      const glm::dvec2 a = p[e[0]], b = p[e[1]];
      const int n = std::max(2, static_cast<int>(std::ceil(glm::length(b - a) / (spacing * d))));
      std::vector<glm::dvec2> stroke;
      for (int i = 0; i <= n; ++i) stroke.push_back(pen(a + (b - a) * (static_cast<double>(i) / n)));
      strokes.push_back(std::move(stroke));
    }
    std::vector<double> bulge;
    for (const auto& a : s.drawing.arcs) {
      const double length = std::abs(a.curve.sweep) * std::max(a.curve.rx, a.curve.ry);
      const int n = std::max(8, static_cast<int>(std::ceil(length / (spacing * d))));
      std::vector<glm::dvec2> stroke;
      for (int i = 0; i <= n; ++i)
        stroke.push_back(pen(cellforge::arc_point(a.curve, static_cast<double>(i) / n)));
      strokes.push_back(std::move(stroke));
      bulge.push_back(sagitta(a.curve) * size / d);
    }
    const auto r = cellforge::detect_arcs(strokes, {.drawing_size = d});
    REQUIRE(r.strokes.size() == strokes.size());
    self_crossing += r.self_crossing_strokes;
    const std::size_t nl = s.drawing.lines.edges.size();
    for (std::size_t k = 0; k < strokes.size(); ++k) {
      const auto& sum = r.strokes[k];
      bool any_arc = false;
      for (std::size_t i = 0; i < sum.num_pieces; ++i)
        any_arc |= r.pieces[sum.first_piece + i].kind == stroke_piece_kind::arc;
      const bool one_arc = sum.num_pieces == 1 && any_arc;
      if (k < nl) {
        ++lines;
        lines_right += !any_arc;
        if (any_arc) misses.push_back(s.name + ": line " + std::to_string(k) + " read as an arc");
        continue;
      }
      ++arcs;
      if (bulge[k - nl] >= 5 * noise) {
        ++bulging;
        bulging_found += one_arc;
        if (!one_arc)
          misses.push_back(s.name + ": arc " + std::to_string(k - nl) + " (bulge " +
                           std::to_string(bulge[k - nl]) +
                           ") not found: " + std::string(cellforge::to_string(sum.whole)));
      } else {
        shallow_found += one_arc;
      }
    }
  }
  std::printf(
      "arc detection on the round drawings: lines %zu of %zu kept straight; arcs bulging 5 noise widths "
      "or more %zu of %zu found; shallower arcs %zu of %zu found (at this noise they are lines)\n",
      lines_right, lines, bulging_found, bulging, shallow_found, arcs - bulging);
  for (const auto& m : misses) std::printf("  miss: %s\n", m.c_str());
  CHECK(lines_right == lines);
  CHECK(bulging_found == bulging);
  CHECK(self_crossing == 0);  // a pen's jitter is no self-intersection
  CHECK(bulging > 0);
}

}  // namespace arc_detection_tests
