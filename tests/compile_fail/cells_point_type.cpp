// expect: mesh_to_cell_complex
// expect: surface_mesh
// A cell-complex algorithm given a mesh of another point type than it is asked for does not
// compile.
#include <glm/vec3.hpp>

#include "cellforge/cells/conversion.hpp"

int main() {
  const cellforge::surface_mesh<glm::vec3> mesh;  // float positions
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
  auto call = [&] { return cellforge::mesh_to_cell_complex(mesh); };
#else
  auto call = [&] { return cellforge::mesh_to_cell_complex<glm::dvec3>(mesh); };
#endif
  return sizeof(call) > 0 ? 0 : 1;  // never run: the test is whether it compiles
}
