// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/samples/drawings.hpp"
#include "cellforge/sketch/detail/drawing_grid.hpp"
#include "cellforge/sketch/line_drawing.hpp"

// A user's 2D point type, registered in one line.
namespace drawing_user {
struct pt {
  double x, y;
};
}  // namespace drawing_user
CELLFORGE_REGISTER_POINT2(drawing_user::pt, double, x, y);

// A sketching application's own drawing: strokes between numbered nodes, float points.
namespace drawing_cad {
struct sketch {
  std::vector<drawing_user::pt> nodes;
  std::vector<std::pair<int, int>> strokes;
};
}  // namespace drawing_cad

template <>
struct cellforge::line_drawing_traits<drawing_cad::sketch> {
  using point_type = drawing_user::pt;
  static std::size_t num_junctions(const drawing_cad::sketch& s) { return s.nodes.size(); }
  static point_type position(const drawing_cad::sketch& s, std::size_t i) { return s.nodes[i]; }
  static std::size_t num_edges(const drawing_cad::sketch& s) { return s.strokes.size(); }
  static std::array<std::size_t, 2> endpoints(const drawing_cad::sketch& s, std::size_t e) {
    return {static_cast<std::size_t>(s.strokes[e].first), static_cast<std::size_t>(s.strokes[e].second)};
  }
};

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace line_drawing_tests {

using cellforge::drawing_defect;
using cellforge::line_drawing;
using edge = std::array<std::uint32_t, 2>;

struct not_a_drawing {};
static_assert(cellforge::Point2<drawing_user::pt>);
static_assert(cellforge::LineDrawing<drawing_cad::sketch>);
static_assert(cellforge::LineDrawing<line_drawing<glm::dvec2>>);
static_assert(cellforge::LineDrawing<line_drawing<glm::vec2>>);
static_assert(cellforge::LineDrawing<line_drawing<std::array<float, 2>>>);
static_assert(cellforge::LineDrawing<line_drawing<drawing_user::pt>>);
static_assert(!cellforge::LineDrawing<not_a_drawing>);
static_assert(!cellforge::LineDrawing<std::vector<glm::dvec2>>);
static_assert(std::is_same_v<cellforge::drawing_point_t<drawing_cad::sketch>, drawing_user::pt>);

namespace {

/// A unit square with a diagonal: every junction on two edges or more.
line_drawing<glm::dvec2> square() {
  return {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}}};
}

/// An n x n lattice of unit squares: 2 n (n + 1) edges.
line_drawing<glm::dvec2> lattice(std::uint32_t n) {
  line_drawing<glm::dvec2> d;
  const auto id = [&](std::uint32_t i, std::uint32_t j) { return i * (n + 1) + j; };
  for (std::uint32_t i = 0; i <= n; ++i)
    for (std::uint32_t j = 0; j <= n; ++j) d.points.push_back({double(j), double(i)});
  for (std::uint32_t i = 0; i <= n; ++i)
    for (std::uint32_t j = 0; j < n; ++j) {
      d.edges.push_back({id(i, j), id(i, j + 1)});
      d.edges.push_back({id(j, i), id(j + 1, i)});
    }
  return d;
}

}  // namespace

TEST_CASE("line_drawing traits: the plain struct, a user's own type, conversions") {
  const auto sq = square();
  using T = cellforge::line_drawing_traits<line_drawing<glm::dvec2>>;
  CHECK(T::num_junctions(sq) == 4);
  CHECK(T::num_edges(sq) == 5);
  CHECK(T::position(sq, 2) == glm::dvec2(1, 1));
  CHECK(T::endpoints(sq, 4) == std::array<std::size_t, 2>{0, 2});

  const drawing_cad::sketch s{{{0, 0}, {2, 0}, {2, 1}, {0, 1}}, {{0, 1}, {1, 2}, {2, 3}, {3, 0}}};
  const auto plain = cellforge::to_line_drawing(s);
  static_assert(std::is_same_v<decltype(plain), const line_drawing<drawing_user::pt>>);
  REQUIRE(plain.points.size() == 4);
  CHECK(plain.points[1].x == 2);
  CHECK(plain.edges == std::vector<edge>{{0, 1}, {1, 2}, {2, 3}, {3, 0}});
  const auto as_glm = cellforge::to_line_drawing<glm::vec2>(s);
  CHECK(as_glm.points[2] == glm::vec2(2, 1));
  CHECK(cellforge::validate(s).ok());
  CHECK(cellforge::validate(as_glm).ok());
  // Out-of-range endpoints survive the copy for validation to report.
  const drawing_cad::sketch bad{{{0, 0}, {1, 0}}, {{0, 7}}};
  const auto v = cellforge::validate(cellforge::to_line_drawing(bad));
  CHECK(v.defect == drawing_defect::endpoint_out_of_range);
  CHECK(v.edge == 0);
}

TEST_CASE("validate(drawing): every defect, with the junction and edge it names") {
  CHECK(cellforge::validate(square()).ok());

  auto d = square();
  d.points[2].y = std::numeric_limits<double>::quiet_NaN();
  auto v = cellforge::validate(d);
  CHECK(v.defect == drawing_defect::bad_position);
  CHECK(v.junction == 2);
  CHECK(v.message.find("junction 2") != std::string::npos);

  d = square();
  d.points[3].x = std::numeric_limits<double>::infinity();
  CHECK(cellforge::validate(d).defect == drawing_defect::bad_position);

  d = square();
  d.edges[3] = {3, 4};
  v = cellforge::validate(d);
  CHECK(v.defect == drawing_defect::endpoint_out_of_range);
  CHECK(v.edge == 3);

  d = square();
  d.edges[1] = {2, 2};
  v = cellforge::validate(d);
  CHECK(v.defect == drawing_defect::self_loop);
  CHECK(v.edge == 1);
  CHECK(v.junction == 2);

  d = square();
  d.edges.push_back({2, 0});  // the diagonal again, reversed
  d.edges.push_back({1, 0});
  v = cellforge::validate(d);
  CHECK(v.defect == drawing_defect::duplicate_edge);
  CHECK(v.edge == 5);
  CHECK(v.other_edge == 4);

  v = cellforge::validate(line_drawing<glm::dvec2>{{{0, 0}}, {}});
  CHECK(v.defect == drawing_defect::empty);
  CHECK(cellforge::validate(line_drawing<glm::dvec2>{}).defect == drawing_defect::empty);

  // Coincident: junction 4 at 1e-12 from junction 1 (the diagonal is √2).
  d = square();
  d.points.push_back({1 + 1e-12, 0});
  d.edges.push_back({4, 2});
  d.edges.push_back({4, 3});
  v = cellforge::validate(d);
  CHECK(v.defect == drawing_defect::coincident_junctions);
  CHECK(v.junction == 4);
  CHECK(v.other == 1);
  // A coarser or finer tolerance decides.
  d.points[4] = {1 + 1e-6, 0};
  CHECK(cellforge::validate(d).ok());
  CHECK(cellforge::validate(d, {.tolerance = 1e-5}).defect == drawing_defect::coincident_junctions);

  // Overlap: edge 5 from junction 0 to (0.5, 0) lies along edge 0 (0 -> 1).
  d = square();
  d.points.push_back({0.5, 0});
  d.edges.push_back({0, 4});
  d.edges.push_back({4, 2});
  v = cellforge::validate(d);
  CHECK(v.defect == drawing_defect::overlapping_edges);
  CHECK(v.edge == 5);
  CHECK(v.other_edge == 0);

  // A T-junction: junction 4 at (0.5, 0) ends edges to 2 and 3 but is on edge 0's interior.
  d = square();
  d.points.push_back({0.5, 0});
  d.edges.push_back({4, 2});
  d.edges.push_back({4, 3});
  v = cellforge::validate(d);
  CHECK(v.defect == drawing_defect::junction_on_edge);
  CHECK(v.junction == 4);
  CHECK(v.edge == 0);
  CHECK(v.message.find("T-junction") != std::string::npos);

  // Dangling: a tail from junction 2 to a new junction 4.
  d = square();
  d.points.push_back({2, 2});
  d.edges.push_back({2, 4});
  v = cellforge::validate(d);
  CHECK(v.defect == drawing_defect::dangling_junction);
  CHECK(v.junction == 4);
  d.edges.pop_back();  // junction 4 now on no edge
  v = cellforge::validate(d);
  CHECK(v.defect == drawing_defect::dangling_junction);
  CHECK(v.message.find("no edge") != std::string::npos);

  CHECK_THROWS_AS(cellforge::validate(square(), {.tolerance = -1}), cellforge::error);
  CHECK_THROWS_AS(cellforge::validate(square(), {.tolerance = std::nan("")}), cellforge::error);
}

TEST_CASE("validate(drawing): edges crossing in their interiors are hidden lines, not defects") {
  // A square with both diagonals: they cross at (0.5, 0.5), no junction there.
  auto d = square();
  d.edges.push_back({1, 3});
  CHECK(cellforge::validate(d).ok());
  // A wireframe cube in a generic view: hidden edges cross visible ones.
  const auto s = cellforge::samples::generic_drawing(cellforge::samples::sample_cube(), 3, "prism");
  CHECK(cellforge::validate(s.drawing).ok());
  const auto l = cellforge::samples::generic_drawing(cellforge::samples::sample_L(), 5, "normalon");
  CHECK(cellforge::validate(l.drawing).ok());
}

TEST_CASE("validate(drawing): the same answer at any scale") {
  for (const double scale : {1e-6, 1.0, 1e6}) {
    auto d = square();
    d.points.push_back({0.5, 1e-10});  // a near T-junction on edge 0: 7e-11 of the diagonal
    d.edges.push_back({4, 2});
    d.edges.push_back({4, 3});
    for (auto& p : d.points) p *= scale;
    CHECK(cellforge::validate(d).defect == drawing_defect::junction_on_edge);
    CHECK(cellforge::validate(d, {.tolerance = 1e-11}).ok());
  }
}

TEST_CASE("validate(drawing): a 10,000-edge lattice validates quickly, and its defects are found") {
  auto d = lattice(70);  // 9940 edges
  CHECK(d.edges.size() == 9940);
  const auto t0 = std::chrono::steady_clock::now();
  CHECK(cellforge::validate(d).ok());
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  MESSAGE("10k-edge lattice validated in " << ms << " ms");
  // A new junction on the middle of a far edge (horizontal edge (35, 70) - (36, 70)).
  d.points.push_back({35.5, 70});
  const auto v = cellforge::validate(d);
  CHECK(v.defect == drawing_defect::junction_on_edge);
  CHECK(v.junction == d.points.size() - 1);
  CHECK(v.edge == 2 * (70 * 70 + 35));
}

TEST_CASE("check_drawing throws invalid_input with the message") {
  auto d = square();
  d.edges.push_back({1, 1});
  try {
    cellforge::check_drawing(d);
    FAIL("no throw");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::invalid_input);
    CHECK(std::string(e.what()).find("check_drawing: edge 5 joins junction 1 to itself") !=
          std::string::npos);
  }
  CHECK_NOTHROW(cellforge::check_drawing(square()));
}

}  // namespace line_drawing_tests

TEST_CASE("drawing grid: the frame is exact, close pairs and grid neighbours match a brute-force search") {
  namespace cd = cellforge::detail;
  // A power-of-two scale and centring: distances scale exactly.
  const auto f = cd::make_drawing_frame({{3, 1}, {11, 1}, {11, 5}});
  REQUIRE(f.points.size() == 3);
  CHECK(f.points[1].x - f.points[0].x == doctest::Approx(1.0));  // 8 units over a scale of 8
  CHECK(f.diag == doctest::Approx(std::sqrt(1.0 + 0.25)));
  CHECK(cd::make_drawing_frame({}).diag == 0);
  // Close pairs on a jittered lattice, against all pairs.
  std::vector<glm::dvec2> pts;
  cellforge::detail::splitmix rng{7};
  for (int i = 0; i < 300; ++i) pts.push_back({rng.uniform(-1, 1), rng.uniform(-1, 1)});
  pts.push_back(pts[10]);  // an exact duplicate
  for (const double eps : {0.0, 0.01, 0.08}) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> grid, brute;
    cd::for_close_points(pts, eps, [&](std::uint32_t i, std::uint32_t j) {
      CHECK(grid.insert({i, j}).second);
    });
    for (std::uint32_t i = 0; i < pts.size(); ++i)
      for (std::uint32_t j = i + 1; j < pts.size(); ++j)
        if (glm::length(pts[i] - pts[j]) <= eps) brute.insert({i, j});
    CHECK(grid == brute);
  }
  // Segments: every pair that comes within eps of each other shares a cell, and so does every
  // point within eps of a segment.
  std::vector<std::pair<glm::dvec2, glm::dvec2>> segs;
  for (int i = 0; i < 80; ++i) {
    const glm::dvec2 a{rng.uniform(-0.9, 0.9), rng.uniform(-0.9, 0.9)};
    segs.push_back({a, a + glm::dvec2(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1))});
  }
  const double eps = 0.01;
  std::set<std::pair<std::size_t, std::size_t>> pairs, near;
  cd::for_grid_neighbours(
      segs, pts, eps,
      [&](std::size_t s, std::size_t t) {
        pairs.insert({s, t});
      },
      [&](std::size_t s, std::size_t p) {
        near.insert({s, p});
      });
  for (std::size_t s = 0; s < segs.size(); ++s)
    for (std::size_t p = 0; p < pts.size(); ++p)
      if (cd::segment_distance(pts[p], segs[s].first, segs[s].second) <= eps) CHECK(near.count({s, p}) == 1);
  for (std::size_t s = 0; s < segs.size(); ++s)
    for (std::size_t t = s + 1; t < segs.size(); ++t) {
      const auto& [a, b] = segs[s];
      const auto& [c, d] = segs[t];
      const double gap = std::min({cd::segment_distance(a, c, d), cd::segment_distance(b, c, d),
                                   cd::segment_distance(c, a, b), cd::segment_distance(d, a, b)});
      if (gap <= eps) CHECK(pairs.count({s, t}) == 1);
    }
  CHECK(cd::segment_distance({0, 1}, {-1, 0}, {1, 0}) == doctest::Approx(1.0));
  CHECK(cd::segment_distance({3, 0}, {-1, 0}, {1, 0}) == doctest::Approx(2.0));
  CHECK(cd::segment_distance({2, 2}, {1, 1}, {1, 1}) == doctest::Approx(std::sqrt(2.0)));
}
