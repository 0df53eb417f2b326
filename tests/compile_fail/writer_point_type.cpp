// expect: write_mesh
// expect: surface_mesh
// An io writer asked to write positions of another type than the mesh holds does not compile.
#include <glm/vec3.hpp>

#include "cellforge/io/mesh_io.hpp"

int main() {
  const cellforge::surface_mesh<glm::vec3> mesh;
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
  auto call = [&] { cellforge::io::write_mesh("never.off", mesh); };
#else
  auto call = [&] { cellforge::io::write_mesh<glm::dvec3>("never.off", mesh); };
#endif
  return sizeof(call) > 0 ? 0 : 1;  // never run: the test is whether it compiles
}
