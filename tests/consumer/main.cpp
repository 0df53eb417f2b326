// SPDX-License-Identifier: MIT
// A user's program: its own point struct and graph type, plugged into cellforge through traits.
#include <array>
#include <cstddef>
#include <cstdio>
#include <vector>

#if __has_include(<cellforge/cellforge.hpp>)
#include <cellforge/cellforge.hpp>
#endif
#include <cellforge/core/bounding_box.hpp>
#include <cellforge/core/error.hpp>
#include <cellforge/core/point_traits.hpp>
#include <cellforge/core/polygon_soup.hpp>
#include <cellforge/core/tolerance.hpp>
#include <cellforge/core/wireframe.hpp>

namespace app {
struct vec3 {
  float x, y, z;
};
// A CAD-like graph: nodes with positions, links between node ids.
struct graph {
  std::vector<vec3> nodes;
  std::vector<std::array<int, 2>> links;
};
}  // namespace app

CELLFORGE_REGISTER_POINT3(app::vec3, float, x, y, z);

template <>
struct cellforge::wireframe_traits<app::graph> {
  using point_type = app::vec3;
  static std::size_t num_vertices(const app::graph& g) { return g.nodes.size(); }
  static app::vec3 position(const app::graph& g, std::size_t v) { return g.nodes[v]; }
  static std::size_t num_edges(const app::graph& g) { return g.links.size(); }
  static std::array<std::size_t, 2> endpoints(const app::graph& g, std::size_t e) {
    return {static_cast<std::size_t>(g.links[e][0]), static_cast<std::size_t>(g.links[e][1])};
  }
};

static_assert(cellforge::Point3<app::vec3>);
static_assert(cellforge::Wireframe<app::graph>);

namespace {
int failures = 0;
void expect(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "consumer: FAILED: %s\n", what);
    ++failures;
  }
}
}  // namespace

int main() {
  // A unit square in the z = 2 plane as the user's graph.
  const app::graph g{{{0, 0, 2}, {1, 0, 2}, {1, 1, 2}, {0, 1, 2}}, {{0, 1}, {1, 2}, {2, 3}, {3, 0}}};
  const cellforge::wireframe<app::vec3> w = cellforge::to_wireframe<app::vec3>(g);
  expect(w.points.size() == 4 && w.edges.size() == 4, "to_wireframe keeps vertex and edge counts");
  expect(w.edges[3][0] == 3 && w.edges[3][1] == 0, "to_wireframe keeps edge endpoints");
  expect(cellforge::coord(w.points[2], 1) == 1.0f, "to_wireframe keeps coordinates");

  cellforge::polygon_soup<app::vec3> soup;
  soup.points = w.points;
  soup.add_face({0, 1, 2, 3});
  soup.add_face({0, 2, 1});
  expect(soup.num_faces() == 2 && soup.face(0).size() == 4 && soup.face(1)[2] == 1,
         "polygon_soup stores faces");

  const cellforge::bounding_box box = cellforge::bounding_box_of(soup.points);
  expect(box.min == glm::dvec3(0, 0, 2) && box.max == glm::dvec3(1, 1, 2), "bounding box of the square");
  const double tol = cellforge::tolerance{1e-6}.absolute(box);
  expect(tol > 1.4e-6 && tol < 1.42e-6, "relative tolerance scales with the diagonal");

  bool threw = false;
  try {
    (void)cellforge::tolerance{-1.0}.absolute(box);
  } catch (const cellforge::error& e) {
    threw = e.category() == cellforge::error_category::invalid_input;
  }
  expect(threw, "a negative tolerance throws cellforge::error(invalid_input)");

  if (failures != 0) return 1;
  std::printf("consumer ok: %zu points, %zu edges, %zu faces\n", w.points.size(), w.edges.size(),
              soup.num_faces());
  return 0;
}
