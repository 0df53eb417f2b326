// expect: loop_subdivide
// expect: surface_mesh
// A mesh without positions (the connectivity-only halfedge_mesh) cannot be subdivided: the
// call does not compile, where it used to throw "the mesh has no vertex positions".
#include <glm/vec3.hpp>

#include "cellforge/algorithms/loop_subdivision.hpp"

int main() {
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
  cellforge::surface_mesh<glm::dvec3> mesh;
#else
  cellforge::halfedge_mesh mesh;
#endif
  const auto r = cellforge::loop_subdivide(mesh);
  return r.faces_after == 0 ? 0 : 1;
}
