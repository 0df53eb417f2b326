// expect: satisf.*Skeleton
// expect: vessel_graph
// expect-count: 2 (does not satisfy|satisfaction of) [^ ]*Skeleton
// A graph type without a skeleton_traits specialisation must be rejected at the call by the
// Skeleton concept: validate(skeleton), and make_tubes, whose return type names the skeleton's
// point type (clang 14 substitutes it first; the concept must still be what the error names).
// decltype: the call is resolved, nothing is compiled.
#include <array>
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/tubes/skeleton.hpp"
#include "cellforge/tubes/tube_mesh.hpp"

struct vessel_graph {
  std::vector<glm::dvec3> nodes;
  std::vector<double> radii;
  std::vector<std::array<std::size_t, 2>> links;
};
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
template <>
struct cellforge::skeleton_traits<vessel_graph> {
  using point_type = glm::dvec3;
  static std::size_t num_nodes(const vessel_graph& g) { return g.nodes.size(); }
  static glm::dvec3 position(const vessel_graph& g, std::size_t i) { return g.nodes[i]; }
  static double radius(const vessel_graph& g, std::size_t i) { return g.radii[i]; }
  static std::size_t num_edges(const vessel_graph& g) { return g.links.size(); }
  static std::array<std::size_t, 2> endpoints(const vessel_graph& g, std::size_t j) { return g.links[j]; }
};
#endif

int main() {
  const vessel_graph g{{{0, 0, 0}, {1, 0, 0}}, {0.5, 0.5}, {{0, 1}}};
  using tubes = decltype(cellforge::make_tubes(g));
  return cellforge::validate(g).ok() && sizeof(tubes) > 0 ? 0 : 1;
}
