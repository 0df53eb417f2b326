// expect: satisf.*Wireframe
// expect: cad_graph
// expect-count: 2 (does not satisfy|satisfaction of) [^ ]*Wireframe
// A graph type without a wireframe_traits specialisation must be rejected at the call by
// the Wireframe concept: to_wireframe, and wireframe_to_cells, whose return type names the
// graph's point type (clang 14 substitutes it first). decltype: nothing is compiled.
#include <array>
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/core/wireframe.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

struct cad_graph {
  std::vector<glm::dvec3> nodes;
  std::vector<std::array<std::size_t, 2>> links;
};
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
template <>
struct cellforge::wireframe_traits<cad_graph> {
  using point_type = glm::dvec3;
  static std::size_t num_vertices(const cad_graph& g) { return g.nodes.size(); }
  static glm::dvec3 position(const cad_graph& g, std::size_t v) { return g.nodes[v]; }
  static std::size_t num_edges(const cad_graph& g) { return g.links.size(); }
  static std::array<std::size_t, 2> endpoints(const cad_graph& g, std::size_t e) { return g.links[e]; }
};
#endif

int main() {
  const cad_graph g{{{0, 0, 0}, {1, 0, 0}}, {{0, 1}}};
  using cells = decltype(cellforge::wireframe_to_cells(g));
  return cellforge::to_wireframe(g).edges.size() == 1 && sizeof(cells) > 0 ? 0 : 1;
}
