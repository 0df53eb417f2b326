#include <doctest/doctest.h>

#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <vector>

#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/algorithms/simplification.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh_geometry.hpp"
#include "cellforge/halfedge/orientation.hpp"
#include "cellforge/halfedge/validate.hpp"

using namespace cellforge;

namespace simplify_test {
struct pt {
  float x, y, z;
};
}  // namespace simplify_test
CELLFORGE_REGISTER_POINT3(simplify_test::pt, float, x, y, z);

// Own namespace: the test files of a group are compiled as one translation unit.
namespace simplification_tests {

namespace {

using test_support::euler;

// Whether simplify<P> accepts a mesh of type M.
template <class M, class P>
constexpr bool can_simplify = requires(M& m) {
  simplify<P>(m);
};

}  // namespace

TEST_CASE_TEMPLATE("icosphere(4) to 500 faces stays a closed, valid, outward sphere", P, glm::dvec3,
                   std::array<float, 3>, simplify_test::pt) {
  for (simplify_cost cost : {simplify_cost::quadric, simplify_cost::edge_length}) {
    CAPTURE(static_cast<int>(cost));
    auto m = make_mesh(icosphere<P>(4));
    REQUIRE(m.num_faces() == 5120);
    simplify_options o;
    o.target_faces = 500;
    o.cost = cost;
    const simplify_result r = simplify(m, o);
    CHECK(r.faces_before == 5120);
    CHECK(r.vertices_before == 2562);
    CHECK(r.faces_after == 500);
    CHECK(r.vertices_after == 252);
    CHECK(r.collapses == (5120 - 500) / 2);
    CHECK(r.reached_target);
    CHECK(r.max_error > 0);
    CHECK(r.milliseconds > 0);
    CHECK(r.diagnostics.empty());  // the target was reached: nothing to say
    CHECK(m.num_faces() == 500);
    CHECK(m.faces_size() == 500);  // garbage collected
    CHECK_FALSE(m.has_garbage());
    REQUIRE_VALID(m);
    CHECK(m.is_closed());
    CHECK(euler(m) == 2);
    CHECK(m.is_consistently_oriented());
    // Every vertex stays near the unit sphere; every face still faces outwards.
    double worst = 0;
    for (vertex_handle v : m.vertices())
      worst = std::max(worst, std::abs(glm::length(to_dvec3(m.positions()[v])) - 1.0));
    CHECK(worst < (cost == simplify_cost::quadric ? 0.01 : 0.04));
    for (face_handle f : m.faces())
      CHECK(glm::dot(to_dvec3(face_normal(m, f)), to_dvec3(face_centroid(m, f))) > 0);
    // The enclosed volume is that of a 500-face polyhedron close to the ball.
    const double volume = signed_volume(to_soup(m));
    CHECK(volume > 0.95 * 4.0 / 3.0 * std::numbers::pi);
    CHECK(volume < 1.01 * 4.0 / 3.0 * std::numbers::pi);
  }
}

TEST_CASE("genus, boundaries and orientability are kept") {
  SUBCASE("torus") {
    auto m = make_mesh(torus(32, 16));
    const simplify_result r = simplify(m, {.target_faces = 200});
    CHECK(r.reached_target);
    CHECK(m.num_faces() <= 200);
    CHECK(euler(m) == 0);
    CHECK(m.is_closed());
    CHECK(is_orientable(m));
    REQUIRE_VALID(m);
  }
  SUBCASE("Möbius strip") {
    auto m = make_mesh(mobius_strip(40, 6));
    const std::size_t flipped = m.num_flipped_edges();
    REQUIRE(flipped > 0);
    const simplify_result r = simplify(m, {.target_faces = 100});
    CHECK(r.reached_target);
    CHECK(euler(m) == 0);
    CHECK(m.boundary_loops().size() == 1);
    CHECK_FALSE(is_orientable(m));
    REQUIRE_VALID(m);
  }
  SUBCASE("Klein bottle, both costs") {
    for (simplify_cost cost : {simplify_cost::quadric, simplify_cost::edge_length}) {
      auto m = make_mesh(klein_bottle(30, 20));
      const simplify_result r = simplify(m, {.target_faces = 150, .cost = cost});
      CHECK(r.reached_target);
      CHECK(euler(m) == 0);
      CHECK(m.is_closed());
      CHECK_FALSE(is_orientable(m));
      REQUIRE_VALID(m);
    }
  }
  SUBCASE("randomly oriented plane: the faces' own orientations are kept") {
    auto m = make_mesh(random_orientation_plane(12, 12, 3));
    const simplify_result r = simplify(m, {.target_faces = 60});
    CHECK(r.reached_target);
    CHECK(euler(m) == 1);
    CHECK(is_orientable(m));
    REQUIRE_VALID(m);
  }
}

TEST_CASE("boundaries: held by quadric planes, or kept fixed") {
  const polygon_soup<glm::dvec3> grid = grid_plane(16, 16, true);
  SUBCASE("quadric: a flat square stays the same square") {
    auto m = make_mesh(grid);
    const simplify_result r = simplify(m, {.target_faces = 40});
    CHECK(r.reached_target);
    CHECK(r.max_error < 1e-12);  // every collapse stays in the plane and on the boundary lines
    glm::dvec3 lo(1e9), hi(-1e9);
    for (vertex_handle v : m.vertices()) {
      lo = glm::min(lo, m.positions()[v]);
      hi = glm::max(hi, m.positions()[v]);
    }
    CHECK(glm::length(lo - glm::dvec3(0, 0, 0)) < 1e-9);
    CHECK(glm::length(hi - glm::dvec3(1, 1, 0)) < 1e-9);
    // The area is still exactly the square's.
    double area = 0;
    for (face_handle f : m.faces()) area += face_area(m, f);
    CHECK(area == doctest::Approx(1.0).epsilon(1e-9));
    REQUIRE_VALID(m);
  }
  SUBCASE("keep_boundary: boundary vertices neither move nor go") {
    auto m = make_mesh(grid);
    std::set<std::array<double, 3>> boundary_before;
    for (vertex_handle v : m.vertices())
      if (m.is_boundary(v)) {
        const glm::dvec3 p = m.positions()[v];
        boundary_before.insert({p.x, p.y, p.z});
      }
    for (simplify_cost cost : {simplify_cost::quadric, simplify_cost::edge_length}) {
      const simplify_result r = simplify(m, {.target_faces = 70, .cost = cost, .keep_boundary = true});
      CHECK(r.reached_target);
      std::set<std::array<double, 3>> boundary_after;
      for (vertex_handle v : m.vertices())
        if (m.is_boundary(v)) {
          const glm::dvec3 p = m.positions()[v];
          boundary_after.insert({p.x, p.y, p.z});
        }
      CHECK(boundary_after == boundary_before);
      CHECK(m.num_boundary_edges() == 64);
      REQUIRE_VALID(m);
    }
  }
}

TEST_CASE("stopping rules: edge length, error bound, normal constraint") {
  SUBCASE("edge length: only edges shorter than the bound are collapsed") {
    auto m = make_mesh(icosphere(3));  // edges about 0.1 long
    const simplify_result r = simplify(m, {.cost = simplify_cost::edge_length, .target_edge_length = 0.15});
    CHECK(r.collapses > 0);
    CHECK(r.max_error < 0.15);
    CHECK(r.reached_target);
    REQUIRE_VALID(m);
  }
  SUBCASE("quadric: error bound") {
    auto m = make_mesh(icosphere(3));
    const simplify_result r = simplify(m, {.max_error = 3e-4});
    CHECK(r.collapses > 0);
    CHECK(r.max_error <= 3e-4);
    CHECK(m.num_faces() > 100);
    REQUIRE_VALID(m);
  }
  SUBCASE("a tiny normal angle refuses most collapses on a sphere") {
    auto m = make_mesh(icosphere(3));
    const simplify_result r = simplify(m, {.target_faces = 100, .max_normal_angle = 0.5});
    CHECK(r.refusals(edit_refusal::normal_flip) > 0);
    CHECK_FALSE(r.reached_target);
    REQUIRE(r.diagnostics.size() == 1);
    CHECK(r.diagnostics[0].find("above the target of 100") != std::string::npos);
    CHECK(r.diagnostics[0].find("most because a face would turn over") != std::string::npos);
    CHECK(r.faces_before - r.faces_after == 2 * r.collapses);
    REQUIRE_VALID(m);
  }
  SUBCASE("no target: as far as the checks allow, down to a tetrahedron-like minimum") {
    auto m = make_mesh(icosphere(2));
    const simplify_result r = simplify(m, {.max_normal_angle = 180});
    CHECK(m.num_faces() < 20);
    CHECK(euler(m) == 2);
    CHECK(r.refused_total() > 0);
    REQUIRE_VALID(m);
  }
}

TEST_CASE("face properties survive simplification and garbage collection") {
  auto m = make_mesh(icosphere(3));
  auto id = m.add_face_property<int>("f:id", -1);
  for (face_handle f : m.faces()) id[f] = static_cast<int>(f.idx());
  simplify(m, {.target_faces = 200});
  id = m.get_face_property<int>("f:id");
  std::set<int> ids;
  for (face_handle f : m.faces()) {
    CHECK(id[f] >= 0);
    ids.insert(id[f]);
  }
  CHECK(ids.size() == m.num_faces());
}

TEST_CASE("bad input is refused before anything changes") {
  SUBCASE("quads") {
    auto m = make_mesh(hexahedron());
    CHECK_THROWS_AS(simplify(m, {.target_faces = 2}), error);
    CHECK(m.num_faces() == 6);
  }
  SUBCASE("a non-finite position") {
    auto m = make_mesh(icosphere(1));
    m.positions()[vertex_handle(3)].y = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(simplify(m, {.target_faces = 10}), error);
    CHECK(m.num_faces() == 80);
  }
  SUBCASE("positions of another type, or none: refused at compile time") {
    CHECK(can_simplify<surface_mesh<glm::dvec3>, glm::dvec3>);
    CHECK_FALSE(can_simplify<surface_mesh<glm::dvec3>, std::array<float, 3>>);
    CHECK_FALSE(can_simplify<cellforge::halfedge_mesh, glm::dvec3>);
  }
  SUBCASE("bad options") {
    auto m = make_mesh(icosphere(1));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const simplify_options& o :
         {simplify_options{.max_normal_angle = 0}, simplify_options{.max_normal_angle = 181},
          simplify_options{.target_edge_length = 0.1},  // with the quadric cost
          simplify_options{.cost = simplify_cost::edge_length, .max_error = 1},
          simplify_options{.max_error = -1}, simplify_options{.max_error = nan},
          simplify_options{.boundary_weight = -1}, simplify_options{.max_rounds = 0},
          simplify_options{.cost = simplify_cost::edge_length, .target_edge_length = nan}}) {
      CHECK_THROWS_AS(simplify(m, o), error);
      CHECK(m.num_faces() == 80);
    }
  }
}

}  // namespace simplification_tests
