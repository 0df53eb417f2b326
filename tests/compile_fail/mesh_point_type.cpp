// expect: find_thin_points
// expect: surface_mesh
// A mesh algorithm asked for the wrong point type is a compile error, not the run-time
// "property 'v:point' exists with another type" it used to be: the mesh carries its type.
#include <array>

#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/thin/thin_points.hpp"

int main() {
  cellforge::polygon_soup<std::array<float, 3>> soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (auto f : {std::array<std::uint32_t, 3>{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}}) soup.add_face(f);
  const auto mesh = cellforge::make_mesh(soup);  // surface_mesh<std::array<float, 3>>
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
  const auto r = cellforge::find_thin_points(mesh);
#else
  const auto r = cellforge::find_thin_points<glm::dvec3>(mesh);
#endif
  return r.loops.size() < 100 ? 0 : 1;
}
