// SPDX-License-Identifier: MIT
// Exact line/segment/point tests against planar polygons (core/polygon_intersection.hpp) and
// Morton codes (core/morton.hpp): clean passes, grazes through vertices and along edges,
// holes, either loop orientation, points on and off a closed surface, solids that touch.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/core/morton.hpp"
#include "cellforge/core/polygon_intersection.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace polygon_intersection_tests {

using cellforge::polygon_location;
using cellforge::polygon_loops;

namespace {

// A unit square in z = 0 with a square hole (0.25..0.75), and the cube [0,1]^3.
const std::vector<glm::dvec3> square_points = {{0, 0, 0},       {1, 0, 0},       {1, 1, 0},
                                               {0, 1, 0},       {0.25, 0.25, 0}, {0.75, 0.25, 0},
                                               {0.75, 0.75, 0}, {0.25, 0.75, 0}};

polygon_location through(const polygon_loops& loops, glm::dvec3 p, glm::dvec3 q) {
  return cellforge::line_through_polygon(square_points, loops, p, q);
}

}  // namespace

TEST_CASE("line through polygon: inside, outside, and grazing exactly") {
  const polygon_loops square{{0, 1, 2, 3}};
  CHECK(through(square, {0.5, 0.5, -1}, {0.5, 0.5, 1}) == polygon_location::inside);
  CHECK(through(square, {0.1, 0.9, 2}, {0.2, 0.8, -3}) == polygon_location::inside);  // slanted
  CHECK(through(square, {1.5, 0.5, -1}, {1.5, 0.5, 1}) == polygon_location::outside);
  // Through a corner, along the line of an edge, through a point of an edge: boundary.
  CHECK(through(square, {0, 0, -1}, {0, 0, 1}) == polygon_location::boundary);
  CHECK(through(square, {0.5, 0, -1}, {0.5, 0, 1}) == polygon_location::boundary);
  CHECK(through(square, {1, 0.3, -1}, {1, 0.3, 1}) == polygon_location::boundary);
  // One ulp inside and outside an edge is decided exactly.
  const double in = std::nextafter(1.0, 0.0), out = std::nextafter(1.0, 2.0);
  CHECK(through(square, {in, 0.3, -1}, {in, 0.3, 1}) == polygon_location::inside);
  CHECK(through(square, {out, 0.3, -1}, {out, 0.3, 1}) == polygon_location::outside);
  // Either orientation of the loop.
  const polygon_loops reversed{{3, 2, 1, 0}};
  CHECK(through(reversed, {0.5, 0.5, -1}, {0.5, 0.5, 1}) == polygon_location::inside);
  CHECK(through(reversed, {1.5, 0.5, -1}, {1.5, 0.5, 1}) == polygon_location::outside);
}

TEST_CASE("line through polygon: holes are outside, their boundary is boundary") {
  for (const polygon_loops& holed :
       {polygon_loops{{0, 1, 2, 3}, {7, 6, 5, 4}}, polygon_loops{{0, 1, 2, 3}, {4, 5, 6, 7}}}) {
    CHECK(through(holed, {0.5, 0.5, -1}, {0.5, 0.5, 1}) == polygon_location::outside);
    CHECK(through(holed, {0.1, 0.5, -1}, {0.1, 0.5, 1}) == polygon_location::inside);
    CHECK(through(holed, {0.25, 0.5, -1}, {0.25, 0.5, 1}) == polygon_location::boundary);
  }
}

TEST_CASE("segment pierces polygon: ends strictly on both sides and a clean pass") {
  const polygon_loops square{{0, 1, 2, 3}};
  const auto plane = cellforge::plane_vertices(square_points, square);
  auto pierces = [&](glm::dvec3 a, glm::dvec3 b) {
    return cellforge::segment_pierces_polygon(square_points, square, plane, a, b);
  };
  CHECK(pierces({0.5, 0.5, -1}, {0.5, 0.5, 1}));
  CHECK_FALSE(pierces({0.5, 0.5, 0.5}, {0.5, 0.5, 1}));  // both ends above
  CHECK_FALSE(pierces({0.5, 0.5, 0}, {0.5, 0.5, 1}));    // an end on the plane
  CHECK_FALSE(pierces({2, 0.5, -1}, {2, 0.5, 1}));       // beside it
  CHECK_FALSE(pierces({1, 1, -1}, {1, 1, 1}));           // through a corner
}

TEST_CASE("point in polyhedron: a cube, a cube with a cavity, touching solids") {
  const std::vector<glm::dvec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                     {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const std::vector<polygon_loops> cube = {{{0, 3, 2, 1}}, {{4, 5, 6, 7}}, {{0, 1, 5, 4}},
                                           {{1, 2, 6, 5}}, {{2, 3, 7, 6}}, {{3, 0, 4, 7}}};
  auto loops = [](const polygon_loops& f) -> const polygon_loops& { return f; };
  auto where = [&](glm::dvec3 q) { return cellforge::point_in_polyhedron(p, cube, loops, q); };
  CHECK(where({0.5, 0.5, 0.5}) == polygon_location::inside);
  CHECK(where({0.999, 0.001, 0.5}) == polygon_location::inside);
  CHECK(where({1.5, 0.5, 0.5}) == polygon_location::outside);
  CHECK(where({-1e-9, 0.5, 0.5}) == polygon_location::outside);
  // On a face, or at a corner: the shared vertex of two cubes touching at it is never a start.
  CHECK(where({0.5, 0.5, 1}) == polygon_location::boundary);
  CHECK(where({1, 1, 1}) == polygon_location::boundary);
  // Beside a face's plane but off the face: decided (outside).
  CHECK(where({2, 0.5, 1}) == polygon_location::outside);
  // Face orientation does not matter (parity).
  std::vector<polygon_loops> flipped = cube;
  for (auto& f : flipped) std::reverse(f[0].begin(), f[0].end());
  CHECK(cellforge::point_in_polyhedron(p, flipped, loops, {0.5, 0.5, 0.5}) == polygon_location::inside);
}

TEST_CASE("morton codes: interleaved bits, Z order, clamped to the box") {
  using cellforge::detail::morton_code;
  using cellforge::detail::morton_spread;
  CHECK(morton_spread(0) == 0);
  CHECK(morton_spread(1) == 1);
  CHECK(morton_spread(2) == 8);
  CHECK(morton_spread(3) == 9);
  CHECK(morton_spread(0x1FFFFF) == 0x1249249249249249ull);
  const glm::dvec3 lo(0.0), extent(1.0);
  // x is the lowest bit of each triple, then y, then z.
  CHECK(morton_code({1, 0, 0}, lo, extent) == morton_spread(0x1FFFFF));
  CHECK(morton_code({0, 1, 0}, lo, extent) == morton_spread(0x1FFFFF) << 1);
  CHECK(morton_code({0, 0, 1}, lo, extent) == morton_spread(0x1FFFFF) << 2);
  CHECK(morton_code({0.1, 0.1, 0.1}, lo, extent) < morton_code({0.6, 0.1, 0.1}, lo, extent));
  CHECK(morton_code({-5, 2, 0.5}, lo, extent) == morton_code({0, 1, 0.5}, lo, extent));
}

TEST_CASE("morton order: ids along the Z-curve of their own box, ties by id, flat axes allowed") {
  using cellforge::detail::morton_order;
  // The four corners of a unit square in the plane z = 3 (z is flat), given out of order, and
  // a repeated point: Z order visits (0,0), (1,0), (0,1), (1,1); equal points keep id order.
  const std::vector<glm::dvec3> p{{1, 1, 3}, {0, 1, 3}, {1, 0, 3}, {0, 0, 3}, {1, 0, 3}};
  const std::vector<std::uint32_t> ids{0, 1, 2, 3, 4};
  const auto at = [&](std::uint32_t i) { return p[i]; };
  CHECK(morton_order(std::span<const std::uint32_t>(ids), at) == std::vector<std::uint32_t>{3, 2, 4, 1, 0});
  // Only the ids given, in the box of those alone.
  const std::vector<std::uint32_t> some{0, 3};
  CHECK(morton_order(std::span<const std::uint32_t>(some), at) == std::vector<std::uint32_t>{3, 0});
  CHECK(morton_order(std::span<const std::uint32_t>(), at).empty());
}

}  // namespace polygon_intersection_tests
