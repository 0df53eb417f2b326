#include <doctest/doctest.h>

#include <array>
#include <map>
#include <string>
#include <vector>

#include "cellforge/core/wireframe.hpp"

// A CAD codebase's own graph: named nodes and edges that refer to node names.
namespace traits_cad {
struct node {
  std::string name;
  float x, y, z;
};
struct graph {
  std::vector<node> nodes;
  std::vector<std::pair<std::string, std::string>> links;
  std::map<std::string, std::size_t> index;  // name -> position in nodes
};
}  // namespace traits_cad

template <>
struct cellforge::wireframe_traits<traits_cad::graph> {
  using point_type = std::array<float, 3>;
  static std::size_t num_vertices(const traits_cad::graph& g) { return g.nodes.size(); }
  static point_type position(const traits_cad::graph& g, std::size_t v) {
    return {g.nodes[v].x, g.nodes[v].y, g.nodes[v].z};
  }
  static std::size_t num_edges(const traits_cad::graph& g) { return g.links.size(); }
  static std::array<std::size_t, 2> endpoints(const traits_cad::graph& g, std::size_t e) {
    return {g.index.at(g.links[e].first), g.index.at(g.links[e].second)};
  }
};

// Own namespace: the test files of a group are compiled as one translation unit.
namespace wireframe_traits_tests {

struct not_a_graph {};
static_assert(cellforge::Wireframe<traits_cad::graph>);
static_assert(cellforge::Wireframe<cellforge::wireframe<glm::dvec3>>);
static_assert(!cellforge::Wireframe<not_a_graph>);
static_assert(!cellforge::Wireframe<std::vector<int>>);

TEST_CASE("a user's graph type adapts with one specialisation") {
  traits_cad::graph g;
  const char* names[] = {"a", "b", "c", "d"};
  const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int i = 0; i < 4; ++i) {
    g.nodes.push_back({names[i], xyz[i][0], xyz[i][1], xyz[i][2]});
    g.index[names[i]] = static_cast<std::size_t>(i);
  }
  g.links = {{"a", "b"}, {"b", "c"}, {"c", "a"}, {"a", "d"}, {"b", "d"}, {"c", "d"}};
  const auto w = cellforge::to_wireframe<glm::dvec3>(g);
  REQUIRE(w.points.size() == 4);
  REQUIRE(w.edges.size() == 6);
  CHECK(w.points[3] == glm::dvec3(0, 0, 1));
  CHECK(w.edges[4] == std::array<std::uint32_t, 2>{1, 3});
  // And back through the plain struct's own traits.
  const auto w2 = cellforge::to_wireframe<std::array<float, 3>>(w);
  CHECK(w2.points[1] == std::array<float, 3>{1, 0, 0});
  CHECK(w2.edges == w.edges);
}

}  // namespace wireframe_traits_tests
