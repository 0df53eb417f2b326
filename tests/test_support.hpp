// Helpers shared by the tests: checked validity with the reason in the report, and the
// Euler characteristic of a half-edge mesh.
#pragma once

#include <doctest/doctest.h>

#include "cellforge/core/point_traits.hpp"
#include "cellforge/halfedge/mesh.hpp"

// Fails the test with validate()'s explanation; works for meshes and cell complexes alike.
#define REQUIRE_VALID(x)          \
  do {                            \
    const auto vr_ = validate(x); \
    INFO(vr_.message);            \
    REQUIRE(vr_.ok());            \
  } while (0)

namespace test_support {
/// A user point type of the tests' own, registered with the one-line macro.
struct user_point {
  double x, y, z;
};
}  // namespace test_support
CELLFORGE_REGISTER_POINT3(test_support::user_point, double, x, y, z);

namespace test_support {
/// V - E + F of the live elements.
inline int euler(const cellforge::halfedge_mesh& m) {
  return static_cast<int>(m.num_vertices()) - static_cast<int>(m.num_edges()) +
         static_cast<int>(m.num_faces());
}
}  // namespace test_support
