// expect: no 3D point type is known for this 2D point type
// expect: lifted_point
// A user's 2D point type with no 3D type mapped to it (no lifted_point specialisation) must
// fail with a message that says what to do, not "no type named 'type'". drawing_to_cells and
// inflate take their result type through the same lifted_point_t when none is named at the call
// (tests/test_sketch_point_types.cpp names one for a type without a mapping). The control maps it.
#include <type_traits>

#include <glm/vec3.hpp>

#include "cellforge/core/point2_traits.hpp"

struct sketch_pt {
  double u, v;
};
CELLFORGE_REGISTER_POINT2(sketch_pt, double, u, v);
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
template <>
struct cellforge::lifted_point<sketch_pt> {
  using type = glm::dvec3;
};
#endif

int main() { return std::is_same_v<cellforge::lifted_point_t<sketch_pt>, glm::dvec3> ? 0 : 1; }
