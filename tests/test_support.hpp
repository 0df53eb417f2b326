// Helpers shared by the tests: checked validity with the reason in the report, and the
// Euler characteristic of a half-edge mesh.
#pragma once

#include <doctest/doctest.h>

#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
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
/// A CAD-like point: private members, getters, an (x, y, z) constructor and no default one.
class sealed_point {
 public:
  sealed_point(double x, double y, double z) : x_(x), y_(y), z_(z) {}
  double x() const { return x_; }
  double y() const { return y_; }
  double z() const { return z_; }
  bool operator==(const sealed_point&) const = default;

 private:
  double x_, y_, z_;
};
}  // namespace test_support
CELLFORGE_REGISTER_POINT3_GET_CTOR(test_support::sealed_point, double, x, y, z);

namespace test_support {
/// The same soup with its points converted (exactly) to glm::dvec3: the double-precision run
/// on the very numbers a mesh of P holds.
template <cellforge::Point3 P>
cellforge::polygon_soup<glm::dvec3> soup_as_dvec3(const cellforge::polygon_soup<P>& s) {
  cellforge::polygon_soup<glm::dvec3> out;
  for (const P& p : s.points) out.points.push_back(cellforge::to_dvec3(p));
  out.face_offsets = s.face_offsets;
  out.face_vertices = s.face_vertices;
  return out;
}
}  // namespace test_support

namespace test_support {
/// V - E + F of the live elements.
inline int euler(const cellforge::halfedge_mesh& m) {
  return static_cast<int>(m.num_vertices()) - static_cast<int>(m.num_edges()) +
         static_cast<int>(m.num_faces());
}
}  // namespace test_support
