// expect: smooth_result
// expect: (conversion|convert)
// Smoothing results come back in the mesh's point type: taking the curves of a float mesh as
// glm::dvec3 is a type error, not a silent conversion.
#include <glm/vec3.hpp>

#include "cellforge/smooth/smooth_edges.hpp"

int main() {
  const cellforge::surface_mesh<glm::vec3> mesh;  // float positions
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
  auto call = [&] {
    const cellforge::smooth_result<glm::vec3> r = cellforge::smooth_edges(mesh);
    return r.curves.size();
  };
#else
  auto call = [&] {
    const cellforge::smooth_result<glm::dvec3> r = cellforge::smooth_edges(mesh);
    return r.curves.size();
  };
#endif
  return sizeof(call) > 0 ? 0 : 1;  // never run: the test is whether it compiles
}
