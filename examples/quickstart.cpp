// The README's usage example, compiled so that it stays true.
#include <cstdio>

#include "cellforge/cellforge.hpp"

namespace cad {
struct Vec {
  double x, y, z;
};
}  // namespace cad
CELLFORGE_REGISTER_POINT3(cad::Vec, double, x, y, z);  // one line registers it

int main() {
  cellforge::polygon_soup<cad::Vec> soup;  // a Möbius strip of 3 quads
  soup.points = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {2, 0, 1}, {2, 1, 1}};
  soup.add_face({0, 2, 3, 1});
  soup.add_face({2, 4, 5, 3});
  soup.add_face({4, 1, 0, 5});  // glued with a half twist
  auto mesh = cellforge::make_mesh(soup);
  for (auto f : mesh.faces_around(cellforge::vertex_handle(0))) std::printf("face %u\n", f.idx());
  std::printf("valid: %d, orientable: %d, boundary loops: %zu\n", cellforge::validate(mesh).ok(),
              cellforge::is_orientable(mesh), mesh.boundary_loops().size());
}
