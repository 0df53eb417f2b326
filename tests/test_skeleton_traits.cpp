// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/core/wireframe.hpp"
#include "cellforge/tubes/skeleton.hpp"
#include "test_support.hpp"

// A CAD codebase's own vessel tree: joints with a diameter at a sealed point type (getters,
// a constructor, no default constructor), and segments between joint numbers.
namespace skeleton_cad {
struct joint {
  test_support::sealed_point at;
  float diameter;
};
struct vessel_tree {
  std::vector<joint> joints;
  std::vector<std::pair<int, int>> segments;  // (upstream, downstream)
};
}  // namespace skeleton_cad

template <>
struct cellforge::skeleton_traits<skeleton_cad::vessel_tree> {
  using point_type = test_support::sealed_point;
  static std::size_t num_nodes(const skeleton_cad::vessel_tree& g) { return g.joints.size(); }
  static point_type position(const skeleton_cad::vessel_tree& g, std::size_t i) { return g.joints[i].at; }
  static float radius(const skeleton_cad::vessel_tree& g, std::size_t i) { return g.joints[i].diameter / 2; }
  static std::size_t num_edges(const skeleton_cad::vessel_tree& g) { return g.segments.size(); }
  static std::array<std::size_t, 2> endpoints(const skeleton_cad::vessel_tree& g, std::size_t j) {
    return {static_cast<std::size_t>(g.segments[j].first), static_cast<std::size_t>(g.segments[j].second)};
  }
};

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace skeleton_traits_tests {

using cellforge::skeleton;
using cellforge::skeleton_defect;
using test_support::sealed_point;
using edge = std::array<std::uint32_t, 2>;

struct not_a_graph {};
static_assert(cellforge::Skeleton<skeleton_cad::vessel_tree>);
static_assert(cellforge::Skeleton<skeleton<glm::dvec3>>);
static_assert(cellforge::Skeleton<skeleton<sealed_point>>);
static_assert(cellforge::Skeleton<skeleton<std::array<float, 3>>>);
static_assert(!cellforge::Skeleton<not_a_graph>);
static_assert(!cellforge::Skeleton<cellforge::wireframe<glm::dvec3>>);  // no radii: not a skeleton
static_assert(!cellforge::Skeleton<std::vector<int>>);

namespace {

skeleton_cad::vessel_tree fork() {
  skeleton_cad::vessel_tree g;
  g.joints = {{{0, 0, 0}, 2.0f}, {{0, 0, 5}, 1.5f}, {{3, 0, 8}, 1.0f}, {{-3, 0, 8}, 0.5f}};
  g.segments = {{0, 1}, {1, 2}, {1, 3}};
  return g;
}

skeleton<glm::dvec3> chain() {
  skeleton<glm::dvec3> s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  s.radii = {0.25, 0.25, 0.25, 0.25};
  s.edges = {{0, 1}, {1, 2}, {2, 3}};
  return s;
}

void check_defect(const skeleton<glm::dvec3>& s, skeleton_defect defect, const std::string& message) {
  const auto v = cellforge::validate(s);
  CAPTURE(v.message);
  CHECK(v.defect == defect);
  CHECK(v.message == message);
  CHECK(!v.ok());
  try {
    cellforge::check_skeleton(s);
    FAIL("check_skeleton accepted a defect: " << message);
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::invalid_input);
    CHECK(std::string(e.what()) == "check_skeleton: " + message);
  }
}

}  // namespace

TEST_CASE("skeleton: a user's graph type adapts with one specialisation") {
  const auto g = fork();
  // In the caller's own point type by default...
  const skeleton<sealed_point> own = cellforge::to_skeleton(g);
  REQUIRE(own.points.size() == 4);
  CHECK(own.points[2] == sealed_point(3, 0, 8));
  CHECK(own.radii == std::vector<double>{1.0, 0.75, 0.5, 0.25});
  CHECK(own.edges == std::vector<edge>{{0, 1}, {1, 2}, {1, 3}});
  // ...or converted to another.
  const auto as_float = cellforge::to_skeleton<std::array<float, 3>>(g);
  CHECK(as_float.points[3] == std::array<float, 3>{-3, 0, 8});
  CHECK(as_float.radii == own.radii);
  CHECK(as_float.edges == own.edges);
  // And back through the plain struct's own traits.
  const auto again = cellforge::to_skeleton<sealed_point>(as_float);
  CHECK(again.points == own.points);
  CHECK(cellforge::validate(g).ok());
  CHECK(cellforge::validate(own));
  CHECK_NOTHROW(cellforge::check_skeleton(g));
}

TEST_CASE("skeleton: validation names the node or edge of every defect") {
  CHECK(cellforge::validate(chain()).ok());
  CHECK(cellforge::validate(skeleton<glm::dvec3>{}).ok());  // empty: nothing wrong
  {
    auto s = chain();
    s.radii[2] = 0;
    check_defect(s, skeleton_defect::bad_radius, "node 2: radius 0 is not positive");
    s.radii[2] = -0.5;
    check_defect(s, skeleton_defect::bad_radius, "node 2: radius -0.5 is not positive");
    s.radii[2] = std::numeric_limits<double>::quiet_NaN();
    check_defect(s, skeleton_defect::bad_radius, "node 2: radius nan is not finite");
    s.radii[2] = std::numeric_limits<double>::infinity();
    check_defect(s, skeleton_defect::bad_radius, "node 2: radius inf is not finite");
    s.radii.pop_back();
    check_defect(s, skeleton_defect::bad_radius, "the skeleton has 4 points but 3 radii");
  }
  {
    auto s = chain();
    s.points[1].y = std::numeric_limits<double>::quiet_NaN();
    check_defect(s, skeleton_defect::bad_position, "node 1: position (1, nan, 0) is not finite");
    s.points[1].y = -std::numeric_limits<double>::infinity();
    check_defect(s, skeleton_defect::bad_position, "node 1: position (1, -inf, 0) is not finite");
  }
  {
    auto s = chain();
    s.edges.push_back({3, 4});
    check_defect(s, skeleton_defect::endpoint_out_of_range, "edge 3: node 4 out of range (4 nodes)");
    const auto v = cellforge::validate(s);
    CHECK(v.edge == 3);
  }
  {
    auto s = chain();
    s.edges[1] = {2, 2};
    check_defect(s, skeleton_defect::self_loop, "edge 1 joins node 2 to itself");
    CHECK(cellforge::validate(s).node == 2);
  }
  {
    auto s = chain();
    s.edges.push_back({2, 1});  // the reverse of edge 1
    s.edges.push_back({0, 1});  // a copy of edge 0
    check_defect(s, skeleton_defect::duplicate_edge, "edge 3 repeats edge 1 (nodes 2 and 1)");
    const auto v = cellforge::validate(s);
    CHECK(v.edge == 3);
    CHECK(v.other == 1);
  }
  {
    auto s = chain();
    s.points.push_back({2, 0, 0});
    s.radii.push_back(1);
    s.points[3] = {0, -0.0, 0};  // -0 and +0 are one position
    check_defect(s, skeleton_defect::coincident_nodes, "nodes 0 and 3 coincide (both at (0, -0, 0))");
    const auto v = cellforge::validate(s);
    CHECK(v.node == 3);
    CHECK(v.other == 0);
  }
}

TEST_CASE("skeleton: the first defect in the documented order is the one reported") {
  auto s = chain();
  s.edges.push_back({1, 1});
  s.radii[3] = -1;
  CHECK(cellforge::validate(s).defect == skeleton_defect::bad_radius);
  s.radii[3] = 1;
  CHECK(cellforge::validate(s).defect == skeleton_defect::self_loop);
}

TEST_CASE("skeleton: integer point types have no non-finite positions to check") {
  skeleton<std::array<int, 3>> s;
  s.points = {{0, 0, 0}, {4, 0, 0}};
  s.radii = {1, 1};
  s.edges = {{0, 1}};
  CHECK(cellforge::validate(s).ok());
  s.points[1] = {0, 0, 0};
  CHECK(cellforge::validate(s).message == "nodes 0 and 1 coincide (both at (0, 0, 0))");
}

}  // namespace skeleton_traits_tests
