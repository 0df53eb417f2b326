// expect: satisf.*Point3
// expect: not_a_point
// A struct never registered through point_traits must be rejected at the call by the
// Point3 concept, naming the concept, instead of failing deep inside an algorithm.
#include "cellforge/core/point_traits.hpp"

struct not_a_point {
  double x, y, z;
};
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
CELLFORGE_REGISTER_POINT3(not_a_point, double, x, y, z);
#endif

int main() {
  const not_a_point p{1, 2, 3};
  return cellforge::to_dvec3(p).x == 1.0 ? 0 : 1;
}
