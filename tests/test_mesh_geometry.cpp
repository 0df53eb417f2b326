#include <doctest/doctest.h>

#include "test_support.hpp"

#include <array>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh_geometry.hpp"
#include "mesh_fixtures.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace mesh_geometry_tests {

using cellforge::face_handle;
using cellforge::vertex_handle;

// The fixture's cube moved and scaled, in point type P: [1, 1+s] x [2, 2+s] x [3, 3+s].
template <class P>
cellforge::polygon_soup<P> moved_cube(double s) {
  const auto c = fixtures::cube();
  cellforge::polygon_soup<P> out;
  for (const auto& p : c.points) out.points.push_back(cellforge::from_dvec3<P>(glm::dvec3(1, 2, 3) + s * p));
  out.face_offsets = c.face_offsets;
  out.face_vertices = c.face_vertices;
  return out;
}

TEST_CASE_TEMPLATE("mesh geometry of a cube, in the caller's point type", P, glm::dvec3, std::array<float, 3>,
                   test_support::user_point) {
  const auto m = cellforge::make_mesh(moved_cube<P>(2.0));
  // Every face: area 4, a unit axis normal pointing away from the centre (2, 3, 4).
  for (const face_handle f : m.faces()) {
    const P n = cellforge::face_normal(m, f);
    const glm::dvec3 nd = cellforge::to_dvec3(n), c = cellforge::to_dvec3(cellforge::face_centroid(m, f));
    CHECK(cellforge::face_area(m, f) == doctest::Approx(4.0));
    CHECK(glm::length(nd) == doctest::Approx(1.0));
    CHECK(glm::dot(nd, c - glm::dvec3(2, 3, 4)) == doctest::Approx(1.0));  // centroid 1 out along n
  }
  CHECK(cellforge::surface_area(m) == doctest::Approx(24.0));
  // Corners: the normal is the diagonal out of the centre.
  const std::vector<P> normals = cellforge::vertex_normals(m);
  for (const vertex_handle v : m.vertices()) {
    const glm::dvec3 n = cellforge::to_dvec3(cellforge::vertex_normal(m, v));
    const glm::dvec3 out = glm::normalize(cellforge::to_dvec3(m.position(v)) - glm::dvec3(2, 3, 4));
    CHECK(glm::length(n - out) < 1e-6);
    CHECK(glm::length(cellforge::to_dvec3(normals[v.idx()]) - n) < 1e-6);
  }
  const auto [lo, hi] = cellforge::bounds(m);
  CHECK(cellforge::to_dvec3(lo) == glm::dvec3(1, 2, 3));
  CHECK(cellforge::to_dvec3(hi) == glm::dvec3(3, 4, 5));
  CHECK(cellforge::face_normals(m).size() == m.faces_size());
}

TEST_CASE("Euler characteristic and components") {
  auto cube = cellforge::make_mesh(fixtures::cube());
  CHECK(cellforge::euler_characteristic(cube) == 2);
  CHECK(cellforge::euler_characteristic(cellforge::make_mesh(fixtures::torus())) == 0);
  CHECK(cellforge::euler_characteristic(cellforge::make_mesh(fixtures::mobius())) == 0);
  CHECK(cellforge::euler_characteristic(cellforge::make_mesh(fixtures::plane(3, 2))) == 1);
  CHECK(cellforge::connected_components(cube).count == 1);

  // Two cubes in one soup, plus an isolated vertex: three components.
  auto two = fixtures::cube();
  const auto second = moved_cube<glm::dvec3>(1.0);
  const auto n = static_cast<std::uint32_t>(two.points.size());
  two.points.insert(two.points.end(), second.points.begin(), second.points.end());
  for (std::size_t f = 0; f < second.num_faces(); ++f) {
    std::vector<std::uint32_t> face(second.face(f).begin(), second.face(f).end());
    for (auto& i : face) i += n;
    two.add_face(face);
  }
  two.points.push_back({9, 9, 9});
  const auto m = cellforge::make_mesh(two);
  const auto c = cellforge::connected_components(m);
  CHECK(c.count == 3);
  CHECK(c.vertex_component[0] != c.vertex_component[8]);
  CHECK(c.vertex_component[0] == c.vertex_component[7]);
  CHECK(c.vertex_component[16] == 2);
  CHECK(cellforge::euler_characteristic(m) == 5);  // 2 + 2 + an isolated vertex

  // Removed vertices are no component.
  auto edited = m;
  edited.remove_vertex(vertex_handle(16));
  const auto e = cellforge::connected_components(edited);
  CHECK(e.count == 2);
  CHECK(e.vertex_component[16] == cellforge::halfedge_mesh::npos);
}

TEST_CASE("mesh geometry: degenerate faces and empty meshes") {
  cellforge::surface_mesh<glm::dvec3> m;
  CHECK(cellforge::bounds(m).first == glm::dvec3(0.0));
  const auto a = m.add_vertex({0, 0, 0}), b = m.add_vertex({1, 0, 0}), c = m.add_vertex({2, 0, 0});
  const face_handle f = m.add_face({a, b, c});  // collinear: no normal, no area
  CHECK(cellforge::face_normal(m, f) == glm::dvec3(0.0));
  CHECK(cellforge::face_area(m, f) == 0.0);
  CHECK(cellforge::vertex_normal(m, a) == glm::dvec3(0.0));
  CHECK(cellforge::face_centroid(m, f) == glm::dvec3(1, 0, 0));
}

TEST_CASE("folded_edges: faces at an edge whose normals point opposite ways") {
  // Two triangles on edge ab: flat (normals agree), then the second turned back over the
  // first until it nearly lies on it (normals 179.8 degrees apart) — a fold, which touches
  // only along ab, so no self-intersection test sees it.
  for (const double far : {1.0, 1e300}) {
    cellforge::surface_mesh<glm::dvec3> m;
    const auto a = m.add_vertex(far * glm::dvec3(0, 0, 0)), b = m.add_vertex(far * glm::dvec3(1, 0, 0));
    const auto c = m.add_vertex(far * glm::dvec3(0, 1, 0)), d = m.add_vertex(far * glm::dvec3(0.5, -1, 0));
    m.add_face({a, b, c});
    m.add_face({b, a, d});
    CHECK(cellforge::folded_edges(m).edges.empty());
    m.set_position(d, far * glm::dvec3(0.5, 1, 0.004));
    const cellforge::fold_result folds = cellforge::folded_edges(m);
    REQUIRE(folds.edges.size() == 1);
    CHECK(folds.edges[0] == m.find_edge(a, b));
    CHECK(folds.within_deg == 20);
    REQUIRE(folds.diagnostics.size() == 1);  // stage_report: the folds said in a sentence
    CHECK(folds.diagnostics[0].find("1 edges fold the surface back") != std::string::npos);
    // A right-angle crease is no fold; at 175 degrees apart it is one only within 10 degrees.
    m.set_position(d, far * glm::dvec3(0.5, 0, 1));
    CHECK(cellforge::folded_edges(m).edges.empty());
    CHECK(cellforge::folded_edges(m).diagnostics.empty());  // no fold, nothing to say
    m.set_position(d, far * glm::dvec3(0.5, std::cos(5 * 3.141592653589793 / 180),
                                       std::sin(5 * 3.141592653589793 / 180)));
    CHECK(cellforge::folded_edges(m, 10).edges.size() == 1);
    CHECK(cellforge::folded_edges(m, 4).edges.empty());
  }
  // Faces that disagree in orientation are no fold when flat, and one when folded back.
  {
    cellforge::surface_mesh<glm::dvec3> m;
    const auto a = m.add_vertex({0, 0, 0}), b = m.add_vertex({1, 0, 0});
    const auto c = m.add_vertex({0, 1, 0}), d = m.add_vertex({0.5, -1, 0});
    m.add_face({a, b, c});
    m.add_face({a, b, d});  // ab runs the same way in both: a flipped edge
    REQUIRE(m.is_flipped(m.find_edge(a, b)));
    CHECK(cellforge::folded_edges(m).edges.empty());
    m.set_position(d, {0.5, 1, 0.004});
    CHECK(cellforge::folded_edges(m).edges.size() == 1);
  }
  // A closed surface has none.
  CHECK(cellforge::folded_edges(cellforge::make_mesh(fixtures::cube())).edges.empty());
}

}  // namespace mesh_geometry_tests
