#include <doctest/doctest.h>

#include <array>
#include <glm/vec3.hpp>
#include <type_traits>

#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/tolerance.hpp"

namespace user {
struct vec {
  double x, y, z;
};
class cad_point {
 public:
  double X() const { return c_[0]; }
  double Y() const { return c_[1]; }
  double Z() const { return c_[2]; }
  void SetX(double v) { c_[0] = v; }
  void SetY(double v) { c_[1] = v; }
  void SetZ(double v) { c_[2] = v; }

 private:
  double c_[3] = {0, 0, 0};
};
// Without default constructors: public members with a constructor, and getters/setters with one.
struct fixed_vec {
  fixed_vec(float a, float b, float c) : x(a), y(b), z(c) {}
  float x, y, z;
};
class sealed_cad_point : public cad_point {  // the same getters and setters, no default constructor
 public:
  sealed_cad_point(double x, double y, double z) {
    SetX(x);
    SetY(y);
    SetZ(z);
  }
};
}  // namespace user
CELLFORGE_REGISTER_POINT3(user::vec, double, x, y, z);
CELLFORGE_REGISTER_POINT3_GET_SET(user::cad_point, double, X, Y, Z, SetX, SetY, SetZ);
CELLFORGE_REGISTER_POINT3(user::fixed_vec, float, x, y, z);
CELLFORGE_REGISTER_POINT3_GET_SET(user::sealed_cad_point, double, X, Y, Z, SetX, SetY, SetZ);

// Own namespace: the test files of a group are compiled as one translation unit.
namespace point_traits_tests {

static_assert(cellforge::Point3<glm::dvec3>);
static_assert(cellforge::Point3<glm::vec3>);
static_assert(cellforge::Point3<std::array<float, 3>>);
static_assert(cellforge::Point3<user::vec>);
static_assert(cellforge::Point3<user::cad_point>);
static_assert(!std::is_default_constructible_v<user::fixed_vec>);
static_assert(!std::is_default_constructible_v<user::sealed_cad_point>);
static_assert(cellforge::Point3<user::fixed_vec>);
static_assert(cellforge::Point3<user::sealed_cad_point>);
static_assert(!cellforge::Point3<int>);
static_assert(!cellforge::Point3<std::array<float, 2>>);

TEST_CASE_TEMPLATE("points round-trip through double precision", P, glm::dvec3, glm::vec3,
                   std::array<float, 3>, user::vec, user::cad_point, user::fixed_vec,
                   user::sealed_cad_point) {
  const P p = cellforge::point_traits<P>::make(1, -2, 3.5);
  CHECK(cellforge::coord(p, 0) == 1);
  CHECK(cellforge::coord(p, 1) == -2);
  CHECK(cellforge::coord(p, 2) == 3.5);
  const glm::dvec3 d = cellforge::to_dvec3(p);
  CHECK(d == glm::dvec3(1, -2, 3.5));
  const P q = cellforge::from_dvec3<P>(d * 2.0);
  CHECK(cellforge::coord(q, 2) == 7);
}

TEST_CASE("error carries category and location") {
  const cellforge::error e(cellforge::error_category::io, "expected a vertex count", {"cube.off", 3});
  CHECK(std::string(e.what()) == "cube.off:3: expected a vertex count");
  CHECK(e.category() == cellforge::error_category::io);
  CHECK(e.line() == 3);
  CHECK(e.message() == "expected a vertex count");
  const cellforge::error b(cellforge::error_category::io, "truncated", {"a.ply", 0, 128});
  CHECK(std::string(b.what()) == "a.ply (byte 128): truncated");
  const cellforge::error plain(cellforge::error_category::topology, "edge 3 has three faces");
  CHECK(std::string(plain.what()) == "edge 3 has three faces");
}

TEST_CASE("tolerance scales with the model") {
  cellforge::bounding_box small, large;
  small.add({0, 0, 0});
  small.add({3e-6, 4e-6, 0});
  large.add({0, 0, 0});
  large.add({3e6, 4e6, 0});
  const cellforge::tolerance tol{1e-9};
  CHECK(tol.absolute(small) == doctest::Approx(5e-15));
  CHECK(tol.absolute(large) == doctest::Approx(5e-3));
  cellforge::bounding_box bad;
  bad.add({0, 0, 0});
  bad.add({std::numeric_limits<double>::quiet_NaN(), 0, 0});
  bad.add({1, 1, std::numeric_limits<double>::infinity()});
  CHECK_THROWS_AS(tol.absolute(bad), cellforge::error);
  CHECK_THROWS_AS(cellforge::tolerance{-1}.absolute(large), cellforge::error);
}

}  // namespace point_traits_tests
