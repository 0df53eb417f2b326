// expect: satisf.*Point3
// A hand-written point_traits without `make` passes nothing: the Point3 concept names what is
// missing at the call, instead of a failure deep inside the mesh.
#include <cstddef>

#include "cellforge/halfedge/surface_mesh.hpp"

struct cad_point {
  double v[3];
};
template <>
struct cellforge::point_traits<cad_point> {
  using scalar = double;
  static double get(const cad_point& p, std::size_t i) { return p.v[i]; }
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
  static cad_point make(double x, double y, double z) { return {{x, y, z}}; }
#endif
};

int main() {
  cellforge::surface_mesh<cad_point> mesh;
  mesh.add_vertex(cad_point{{1, 2, 3}});
  return mesh.num_vertices() == 1 ? 0 : 1;
}
