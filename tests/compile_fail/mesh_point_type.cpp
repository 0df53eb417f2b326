// expect: simplify
// expect: surface_mesh
// A mesh algorithm asked for the wrong point type is a compile error, not the run-time
// "property 'v:point' exists with another type" it used to be (find_thin_points, smooth_edges
// and simplify all threw it): the mesh carries its type.
#include <array>

#include "cellforge/algorithms/simplification.hpp"
#include "cellforge/halfedge/conversion.hpp"

int main() {
  cellforge::polygon_soup<std::array<float, 3>> soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (auto f : {std::array<std::uint32_t, 3>{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}}) soup.add_face(f);
  auto mesh = cellforge::make_mesh(soup);  // surface_mesh<std::array<float, 3>>
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
  const auto r = cellforge::simplify(mesh, {.target_faces = 2});
#else
  const auto r = cellforge::simplify<glm::dvec3>(mesh, {.target_faces = 2});
#endif
  return r.faces_before == 4 ? 0 : 1;
}
