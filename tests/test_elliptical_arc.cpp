// SPDX-License-Identifier: MIT
// Elliptical arcs of line drawings (sketch/elliptical_arc.hpp): the centre form, SVG's
// endpoint form and back, points and tangents, and what validate(arc_drawing) refuses.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace elliptical_arc_tests {

using cellforge::arc_defect;
using cellforge::elliptical_arc;
constexpr double pi = std::numbers::pi;

TEST_CASE("elliptical arc: points, tangents and samples of a quarter circle") {
  const elliptical_arc<glm::dvec2> a{{1, 2}, 3, 3, 0, 0, pi / 2};
  CHECK(glm::length(cellforge::arc_point(a, 0.0) - glm::dvec2(4, 2)) < 1e-15);
  CHECK(glm::length(cellforge::arc_point(a, 1.0) - glm::dvec2(1, 5)) < 1e-15);
  CHECK(glm::length(cellforge::arc_tangent(a, 0.0) - glm::dvec2(0, 1)) < 1e-15);
  CHECK(glm::length(cellforge::arc_tangent(a, 1.0) - glm::dvec2(-1, 0)) < 1e-15);
  // Clockwise: the tangent still points the way the arc runs.
  const elliptical_arc<glm::dvec2> b{{0, 0}, 2, 1, 0, 0, -pi / 2};
  CHECK(glm::length(cellforge::arc_point(b, 1.0) - glm::dvec2(0, -1)) < 1e-15);
  CHECK(glm::length(cellforge::arc_tangent(b, 0.0) - glm::dvec2(0, -1)) < 1e-15);
  const std::vector<glm::dvec2> s = cellforge::sample_arc(a, 4);
  REQUIRE(s.size() == 5);
  for (const glm::dvec2& p : s) CHECK(std::abs(glm::length(p - glm::dvec2(1, 2)) - 3) < 1e-14);
  CHECK_THROWS_AS(cellforge::sample_arc(a, 0), cellforge::error);
}

TEST_CASE("elliptical arc: the endpoint form round-trips over random arcs, every flag") {
  cellforge::detail::splitmix rng{14};
  int checked = 0, misses = 0;
  for (int k = 0; k < 400; ++k) {
    const double rx = rng.uniform(0.1, 5), ry = rng.uniform(0.1, 5), rot = rng.uniform(-pi, pi);
    const double start = rng.uniform(-pi, pi), sweep = rng.uniform(0.05, 2 * pi - 0.05) * (k % 2 ? 1 : -1);
    const double cx = rng.uniform(-10, 10), cy = rng.uniform(-10, 10);
    const elliptical_arc<glm::dvec2> a{{cx, cy}, rx, ry, rot, start, sweep};
    const auto e = cellforge::arc_endpoint_form(a);
    CHECK(e.large_arc == (std::abs(sweep) > pi));
    CHECK(e.ccw == (sweep > 0));
    const elliptical_arc<glm::dvec2> b = cellforge::arc_from_endpoints(e);
    ++checked;
    const double err = std::max({glm::length(b.centre - a.centre), std::abs(b.rx - rx), std::abs(b.ry - ry),
                                 std::abs(b.sweep - sweep),
                                 glm::length(cellforge::arc_point(b, 0.5) - cellforge::arc_point(a, 0.5))});
    if (err > 1e-9) {
      ++misses;
      MESSAGE("arc " << k << ": round-trip error " << err);
    }
  }
  MESSAGE("endpoint form round trips: " << checked - misses << " of " << checked << " within 1e-9");
  CHECK(misses == 0);
}

TEST_CASE("elliptical arc: the SVG conversion's special cases") {
  using E = cellforge::arc_endpoints<glm::dvec2>;
  // A half circle: radius exactly half the chord, centre at the midpoint.
  const auto h = cellforge::arc_from_endpoints(E{{0, 0}, {2, 0}, 1, 1, 0, false, true});
  CHECK(glm::length(h.centre - glm::dvec2(1, 0)) < 1e-15);
  CHECK(std::abs(std::abs(h.sweep) - pi) < 1e-12);
  // Radii too small are scaled up (SVG's rule) to the half circle.
  const auto s = cellforge::arc_from_endpoints(E{{0, 0}, {2, 0}, 0.25, 0.25, 0, false, false});
  CHECK(std::abs(s.rx - 1) < 1e-12);
  CHECK(std::abs(s.ry - 1) < 1e-12);
  // The four flag combinations of one pair of ends and radius give the four arcs.
  for (int f = 0; f < 4; ++f) {
    const bool large = f & 1, ccw = f & 2;
    const auto a = cellforge::arc_from_endpoints(E{{0, 0}, {1, 1}, 1, 1, 0, large, ccw});
    CHECK((std::abs(a.sweep) > pi) == large);
    CHECK((a.sweep > 0) == ccw);
    CHECK(glm::length(cellforge::arc_point(a, 1.0) - glm::dvec2(1, 1)) < 1e-12);
    // The small ccw arc from (0,0) to (1,1) bulges to the lower right round the centre (0, 1).
    if (!large && ccw) CHECK(glm::length(a.centre - glm::dvec2(0, 1)) < 1e-12);
    if (!large && !ccw) CHECK(glm::length(a.centre - glm::dvec2(1, 0)) < 1e-12);
  }
  // Half ellipses at awkward angles (rounding puts lambda a few ulps either side of 1): the
  // centre is the chord's midpoint to rounding, not 1e-8 off, the flags come back, and the
  // radii of a scaled arc read again give the same arc bit for bit.
  cellforge::detail::splitmix rng{11};
  for (int i = 0; i < 200; ++i) {
    const double t = rng.uniform(0, 2 * pi), rot = rng.uniform(-4, 4), rx = rng.uniform(0.2, 5),
                 ry = rng.uniform(0.2, 5);
    const glm::dvec2 c(rng.uniform(-9, 9), rng.uniform(-9, 9));
    const elliptical_arc<glm::dvec2> half{c, rx, ry, rot, t, pi};
    const glm::dvec2 p0 = cellforge::arc_point(half, 0.0), p1 = cellforge::arc_point(half, 1.0);
    for (int f = 0; f < 4; ++f) {
      const bool large = f & 1, ccw = f & 2;
      const auto a = cellforge::arc_from_endpoints(E{p0, p1, rx, ry, rot, large, ccw});
      CHECK(glm::length(a.centre - (p0 + p1) * 0.5) < 1e-13 * (1 + glm::length(c)));
      CHECK(glm::length(a.centre - c) < 1e-12 * (1 + glm::length(c)));
      const auto back = cellforge::arc_endpoint_form(a);
      CHECK(back.large_arc == large);
      CHECK(back.ccw == ccw);
      const auto again = cellforge::arc_from_endpoints(E{p0, p1, a.rx, a.ry, a.rotation, large, ccw});
      CHECK(again.centre == a.centre);
      CHECK(again.rx == a.rx);
      CHECK(again.start == a.start);
      CHECK(again.sweep == a.sweep);
    }
  }
  // Negative radii count by magnitude; zero radius and equal ends are errors with a reason.
  CHECK(std::abs(cellforge::arc_from_endpoints(E{{0, 0}, {2, 0}, -1, -1, 0, false, true}).rx - 1) < 1e-12);
  CHECK_THROWS_WITH_AS(cellforge::arc_from_endpoints(E{{0, 0}, {2, 0}, 0, 1, 0, false, true}),
                       doctest::Contains("zero-radius arc is a corner"), cellforge::error);
  CHECK_THROWS_WITH_AS(cellforge::arc_from_endpoints(E{{1, 1}, {1, 1}, 1, 1, 0, false, true}),
                       doctest::Contains("no sweep"), cellforge::error);
  CHECK_THROWS_AS(cellforge::arc_from_endpoints(E{{0, 0}, {NAN, 0}, 1, 1, 0, false, true}), cellforge::error);
}

TEST_CASE("elliptical arc: another point type comes back out") {
  using F = std::array<float, 2>;
  const elliptical_arc<F> a{{1.f, 1.f}, 2, 1, pi / 6, 0, pi / 3};
  const F p = cellforge::arc_point(a, 1.0);
  const auto e = cellforge::arc_endpoint_form(a);
  const elliptical_arc<F> b = cellforge::arc_from_endpoints(e);
  CHECK(std::abs(b.rx - 2) < 1e-5);
  CHECK(std::abs(cellforge::arc_point(b, 1.0)[0] - p[0]) < 1e-5f);
}

TEST_CASE("elliptical arc: validate(arc_drawing) names the first bad arc") {
  cellforge::arc_drawing<glm::dvec2> d;
  d.lines.points = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  d.lines.edges = {{1, 2}, {2, 3}, {3, 0}};
  d.arcs.push_back(
      {{0, 1}, cellforge::arc_from_endpoints<glm::dvec2>({{0, 0}, {2, 0}, 1, 1, 0, false, true})});
  CHECK(cellforge::validate(d).ok());
  CHECK(cellforge::validate_arc(d.arcs[0].curve) == arc_defect::none);
  auto bad = d;
  bad.arcs[0].ends = {0, 0};
  auto v = cellforge::validate(bad);
  CHECK(v.ends_equal);
  CHECK(v.message.find("arc 0 starts and ends at junction 0") != std::string::npos);
  bad = d;
  bad.arcs[0].ends = {0, 7};
  CHECK(cellforge::validate(bad).end_out_of_range);
  bad = d;
  bad.arcs[0].ends = {0, 2};
  v = cellforge::validate(bad);
  CHECK(v.end_off_curve);
  CHECK(v.message.find("from the curve's last point") != std::string::npos);
  bad = d;
  bad.arcs[0].curve.rx = 0;
  CHECK(cellforge::validate(bad).defect == arc_defect::zero_radius);
  bad = d;
  bad.arcs[0].curve.sweep = 0;
  CHECK(cellforge::validate(bad).defect == arc_defect::zero_sweep);
  bad = d;
  bad.arcs[0].curve.start = NAN;
  CHECK(cellforge::validate(bad).defect == arc_defect::bad_value);
  CHECK_THROWS_AS(cellforge::validate(d, {.tolerance = -1}), cellforge::error);
}

}  // namespace elliptical_arc_tests
