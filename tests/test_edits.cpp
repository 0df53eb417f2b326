#include <doctest/doctest.h>

#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "cellforge/algorithms/edits.hpp"
#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/orientation.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "mesh_fixtures.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace edits_tests {

using namespace cellforge;

namespace {

using soup = polygon_soup<glm::dvec3>;

using test_support::euler;

bool same_soup(const soup& a, const soup& b) {
  return a.points == b.points && a.face_offsets == b.face_offsets && a.face_vertices == b.face_vertices;
}

surface_mesh<glm::dvec3> mesh_of(const soup& s) { return make_mesh(s); }

// The two faces of an interior edge and their third corners.
struct edge_star {
  vertex_handle a, b, c, d;
};
edge_star star(const halfedge_mesh& m, edge_handle e) {
  const halfedge_handle h0 = halfedge_mesh::halfedge(e, 0), h1 = halfedge_mesh::halfedge(e, 1);
  edge_star s{m.tail(h0), m.head(h0), {}, {}};
  auto third = [&](halfedge_handle h) {
    for (vertex_handle v : m.vertices_around(m.face(h)))
      if (v != s.a && v != s.b) return v;
    return vertex_handle();
  };
  if (!m.is_boundary(h0)) s.c = third(h0);
  if (!m.is_boundary(h1)) s.d = third(h1);
  return s;
}

// Two triangles on the same three vertices, glued along all three edges.
soup pillow() {
  soup s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.add_face({0, 1, 2});
  s.add_face({1, 0, 2});
  return s;
}

// Triangular bipyramid: equator 0,1,2, apexes 3 (top) and 4 (bottom), outward.
soup bipyramid() {
  soup s;
  s.points = {{1, 0, 0}, {-0.5, 0.8, 0}, {-0.5, -0.8, 0}, {0, 0, 1}, {0, 0, -1}};
  for (std::uint32_t i = 0; i < 3; ++i) {
    s.add_face({i, (i + 1) % 3, 3});
    s.add_face({(i + 1) % 3, i, 4});
  }
  return s;
}

// A strip of n quads split into triangles: every vertex is on the boundary.
soup strip(int n) { return grid_plane(n, 1, true); }

halfedge_handle halfedge_between(const surface_mesh<glm::dvec3>& m, std::uint32_t a, std::uint32_t b) {
  const halfedge_handle h = m.find_halfedge(vertex_handle(a), vertex_handle(b));
  REQUIRE(h.is_valid());
  return h;
}

// Checks that a refused edit says `why` and leaves the mesh exactly as it was.
template <class Edit>
void expect_refused(surface_mesh<glm::dvec3>& m, edit_refusal why, Edit&& edit) {
  const soup before = to_soup(m);
  const std::size_t faces = m.faces_size(), edges = m.edges_size(), vertices = m.vertices_size();
  const edit_result r = edit(m);
  CHECK_FALSE(r.ok());
  CHECK(r.refusal == why);
  CHECK(same_soup(before, to_soup(m)));
  CHECK(m.faces_size() == faces);
  CHECK(m.edges_size() == edges);
  CHECK(m.vertices_size() == vertices);
  REQUIRE_VALID(m);
}

}  // namespace

// ---------------------------------------------------------------------------- collapse

TEST_CASE("collapse_halfedge on an icosahedron removes 1 vertex, 3 edges, 2 faces") {
  auto m = make_mesh(icosahedron());
  for (edge_handle e : m.edges()) {
    auto c = m;
    const edge_star s = star(c, e);
    const halfedge_handle h = halfedge_mesh::halfedge(e, 0);
    REQUIRE(can_collapse(c, h) == edit_refusal::none);
    const edit_result r = collapse_halfedge(c, h);
    REQUIRE(r.ok());
    CHECK(r.vertex == s.b);
    CHECK(r.vertices_removed == 1);
    CHECK(r.faces_removed == 2);
    CHECK(c.is_removed(s.a));
    CHECK(c.num_vertices() == 11);
    CHECK(c.num_edges() == 27);
    CHECK(c.num_faces() == 18);
    CHECK(euler(c) == 2);
    CHECK(c.valence(s.b) == 6);  // 5 + 5 - 4
    CHECK(c.valence(s.c) == 4);
    CHECK(c.valence(s.d) == 4);
    CHECK(c.is_closed());
    CHECK(c.is_consistently_oriented());
    REQUIRE_VALID(c);
  }
}

TEST_CASE("collapse on an open grid: boundary edges, interior into boundary vertex") {
  const auto m0 = make_mesh(grid_plane(3, 3, true));  // 16 vertices, 18 faces, 12 boundary edges
  SUBCASE("a boundary edge removes one face and one boundary edge") {
    auto m = m0;
    const halfedge_handle b = m.boundary_halfedges().front();
    const halfedge_handle h = halfedge_mesh::twin(b);  // the face side
    const edit_result r = collapse_halfedge(m, h);
    REQUIRE(r.ok());
    CHECK(r.faces_removed == 1);
    CHECK(m.num_vertices() == 15);
    CHECK(m.num_faces() == 17);
    CHECK(m.num_edges() == m0.num_edges() - 2);
    CHECK(m.num_boundary_edges() == 11);
    CHECK(euler(m) == 1);
    CHECK(m.boundary_loops().size() == 1);
    REQUIRE_VALID(m);
  }
  SUBCASE("an interior vertex into a boundary vertex keeps the boundary") {
    auto m = m0;
    // Vertex 5 = (1,1) is interior, vertex 1 = (1,0) on the boundary.
    const halfedge_handle h = halfedge_between(m, 5, 1);
    REQUIRE_FALSE(m.is_boundary(vertex_handle(5)));
    REQUIRE(m.is_boundary(vertex_handle(1)));
    const edit_result r = collapse_halfedge(m, h);
    REQUIRE(r.ok());
    CHECK(m.num_vertices() == 15);
    CHECK(m.num_faces() == 16);
    CHECK(m.num_boundary_edges() == 12);
    CHECK(euler(m) == 1);
    REQUIRE_VALID(m);
  }
  SUBCASE("a boundary vertex into an interior one is refused when it would pinch, done otherwise") {
    auto m = m0;
    const halfedge_handle h = halfedge_between(m, 1, 5);
    CHECK(can_collapse(m, h) == edit_refusal::none);  // 1 is the only boundary end: fine
    REQUIRE(collapse_halfedge(m, h).ok());
    CHECK(m.num_boundary_edges() == 12);
    CHECK(m.is_boundary(vertex_handle(5)));
    REQUIRE_VALID(m);
  }
}

TEST_CASE_TEMPLATE("collapse position policies, three point types", P, glm::dvec3, std::array<float, 3>,
                   test_support::user_point) {
  for (collapse_position policy :
       {collapse_position::keep_head, collapse_position::midpoint, collapse_position::custom}) {
    auto m = make_mesh(icosahedron<P>());
    const auto pts = m.positions();
    const halfedge_handle h = halfedge_mesh::halfedge(edge_handle(3), 1);
    const glm::dvec3 a = to_dvec3(pts[m.tail(h)]), b = to_dvec3(pts[m.head(h)]);
    const glm::dvec3 custom(0.25, -0.5, 2.0);
    const edit_result r = collapse_halfedge(m, h, {policy, custom});
    REQUIRE(r.ok());
    const glm::dvec3 got = to_dvec3(m.positions()[r.vertex]);
    const glm::dvec3 want = policy == collapse_position::keep_head  ? b
                            : policy == collapse_position::midpoint ? 0.5 * (a + b)
                                                                    : custom;
    CHECK(glm::length(got - want) < 1e-6);
    REQUIRE_VALID(m);
  }
  auto m = make_mesh(icosahedron<P>());
  const auto nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(
      collapse_halfedge(m, halfedge_handle(0), {collapse_position::custom, glm::dvec3(nan, 0, 0)}), error);
  CHECK(m.num_faces() == 20);
}

TEST_CASE("collapse refusals say why and leave the mesh untouched") {
  SUBCASE("every edge of a tetrahedron") {
    auto m = make_mesh(tetrahedron());
    for (halfedge_handle h : m.halfedges()) {
      CHECK(can_collapse(m, h) == edit_refusal::tetrahedron);
      expect_refused(m, edit_refusal::tetrahedron,
                     [&](surface_mesh<glm::dvec3>& x) { return collapse_halfedge(x, h); });
    }
  }
  SUBCASE("link condition: an equator edge of a bipyramid shares the third equator vertex") {
    auto m = mesh_of(bipyramid());
    expect_refused(m, edit_refusal::link_condition, [&](surface_mesh<glm::dvec3>& x) {
      return collapse_halfedge(x, halfedge_between(x, 0, 1));
    });
    // An apex edge is fine and leaves a tetrahedron.
    REQUIRE(collapse_halfedge(m, halfedge_between(m, 3, 0)).ok());
    CHECK(m.num_vertices() == 4);
    CHECK(m.num_faces() == 4);
    CHECK(m.num_edges() == 6);
    REQUIRE_VALID(m);
  }
  SUBCASE("an interior edge between two boundary vertices") {
    auto m = make_mesh(strip(3));  // 8 vertices all on the boundary
    int interior = 0;
    for (edge_handle e : m.edges()) {
      if (m.is_boundary(e)) continue;
      ++interior;
      const halfedge_handle h = halfedge_mesh::halfedge(e, 0);
      expect_refused(m, edit_refusal::boundary_vertices,
                     [&](surface_mesh<glm::dvec3>& x) { return collapse_halfedge(x, h); });
    }
    CHECK(interior == 5);
  }
  SUBCASE("a lone triangle") {
    soup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    s.add_face({0, 1, 2});
    auto m = mesh_of(s);
    for (halfedge_handle h : m.halfedges())
      expect_refused(m, edit_refusal::isolated_triangle,
                     [&](surface_mesh<glm::dvec3>& x) { return collapse_halfedge(x, h); });
  }
  SUBCASE("quads") {
    auto m = mesh_of(fixtures::cube());
    expect_refused(m, edit_refusal::not_triangle,
                   [&](surface_mesh<glm::dvec3>& x) { return collapse_halfedge(x, halfedge_handle(0)); });
  }
  SUBCASE("a bow-tie vertex") {
    auto m = mesh_of(fixtures::bowtie());
    expect_refused(m, edit_refusal::nonmanifold_vertex, [&](surface_mesh<glm::dvec3>& x) {
      return collapse_halfedge(x, halfedge_between(x, 1, 0));
    });
    expect_refused(m, edit_refusal::nonmanifold_vertex, [&](surface_mesh<glm::dvec3>& x) {
      return collapse_halfedge(x, halfedge_between(x, 0, 1));
    });
  }
  SUBCASE("a pillow of two triangles") {
    auto m = mesh_of(pillow());
    REQUIRE_VALID(m);
    expect_refused(m, edit_refusal::degenerate,
                   [&](surface_mesh<glm::dvec3>& x) { return collapse_halfedge(x, halfedge_handle(0)); });
  }
  SUBCASE("a triangle with two boundary sides at the end of a strip") {
    // Collapsing the corner's boundary edge is fine; its rung (interior, both ends on the
    // boundary) is not.
    auto m = make_mesh(strip(1));  // a square of two triangles
    const halfedge_handle b = m.boundary_halfedges().front();
    CHECK(can_collapse(m, halfedge_mesh::twin(b)) == edit_refusal::none);
    REQUIRE(collapse_halfedge(m, halfedge_mesh::twin(b)).ok());
    CHECK(m.num_faces() == 1);
    REQUIRE_VALID(m);
    for (halfedge_handle h : m.halfedges())
      expect_refused(m, edit_refusal::isolated_triangle,
                     [&](surface_mesh<glm::dvec3>& x) { return collapse_halfedge(x, h); });
  }
  SUBCASE("removed or out-of-range handles throw") {
    auto m = make_mesh(icosahedron());
    CHECK_THROWS_AS(collapse_halfedge(m, halfedge_handle(1000)), error);
    CHECK_THROWS_AS(can_collapse(m, halfedge_handle()), error);
    vertex_handle stranger;
    for (vertex_handle v : m.vertices())
      if (v != m.vertex(edge_handle(0), 0) && v != m.vertex(edge_handle(0), 1)) stranger = v;
    CHECK_THROWS_AS(collapse_edge(m, edge_handle(0), stranger), error);  // not an end
  }
}

TEST_CASE("collapse_edge goes either way, also across a flipped edge") {
  auto m = make_mesh(mobius_strip(12, 3));
  edge_handle seam;
  for (edge_handle e : m.edges())
    if (m.is_flipped(e)) seam = e;
  REQUIRE(seam.is_valid());
  const vertex_handle a = m.vertex(seam, 0), b = m.vertex(seam, 1);
  // Both half-edges of a flipped edge run the same way.
  CHECK(m.tail(halfedge_mesh::halfedge(seam, 1)) == a);
  for (vertex_handle keep : {a, b}) {
    auto c = m;
    const edit_refusal why = can_collapse(c, seam, keep);
    const edit_result r = collapse_edge(c, seam, keep);
    CHECK(r.refusal == why);
    if (!r) continue;
    CHECK(r.vertex == keep);
    CHECK(c.is_removed(keep == a ? b : a));
    CHECK(euler(c) == 0);
    CHECK_FALSE(is_orientable(c));
    REQUIRE_VALID(c);
  }
}

// ---------------------------------------------------------------------------- face collapse

TEST_CASE_TEMPLATE("collapse_face on an icosahedron: 4 faces, 2 vertices, 6 edges, to the centroid", P,
                   glm::dvec3, std::array<float, 3>, test_support::user_point) {
  auto m = make_mesh(icosahedron<P>());
  const face_handle f(7);
  std::vector<vertex_handle> corners;
  glm::dvec3 centroid(0.0);
  for (vertex_handle v : m.vertices_around(f)) {
    corners.push_back(v);
    centroid += to_dvec3(m.positions()[v]) / 3.0;
  }
  REQUIRE(can_collapse_face(m, f) == edit_refusal::none);
  const edit_result r = collapse_face(m, f);
  REQUIRE(r.ok());
  CHECK(r.vertex == corners[0]);
  CHECK(r.vertices_removed == 2);
  CHECK(r.faces_removed == 4);
  CHECK(m.is_removed(corners[1]));
  CHECK(m.is_removed(corners[2]));
  CHECK(m.num_vertices() == 10);
  CHECK(m.num_faces() == 16);
  CHECK(m.num_edges() == 24);
  CHECK(euler(m) == 2);
  CHECK(m.valence(r.vertex) == 6);
  CHECK(glm::length(to_dvec3(m.positions()[r.vertex]) - centroid) < 1e-6);
  CHECK(m.is_consistently_oriented());
  REQUIRE_VALID(m);
}

TEST_CASE("collapse_face: octahedron to tetrahedron, boundary faces, refusals") {
  SUBCASE("octahedron") {
    auto m = make_mesh(octahedron());
    REQUIRE(collapse_face(m, face_handle(0)).ok());
    CHECK(m.num_vertices() == 4);
    CHECK(m.num_faces() == 4);
    CHECK(m.num_edges() == 6);
    REQUIRE_VALID(m);
    for (face_handle f : m.faces())
      expect_refused(m, edit_refusal::tetrahedron,
                     [&](surface_mesh<glm::dvec3>& x) { return collapse_face(x, f); });
  }
  SUBCASE("every face of an open grid, one at a time") {
    const auto m0 = make_mesh(grid_plane(4, 4, true));
    int done = 0;
    for (face_handle f : m0.faces()) {
      auto m = m0;
      const edit_refusal why = can_collapse_face(m, f);
      const edit_result r = collapse_face(m, f);
      CHECK(r.refusal == why);
      REQUIRE_VALID(m);
      CHECK(euler(m) == 1);
      CHECK(m.boundary_loops().size() == 1);
      if (!r) continue;
      ++done;
      CHECK(m.num_vertices() == m0.num_vertices() - 2);
      CHECK(m.num_faces() == m0.num_faces() - r.faces_removed);
    }
    CHECK(done > 10);
  }
  SUBCASE("refusals") {
    auto t = make_mesh(tetrahedron());
    expect_refused(t, edit_refusal::tetrahedron,
                   [](surface_mesh<glm::dvec3>& x) { return collapse_face(x, face_handle(0)); });
    auto q = mesh_of(fixtures::cube());
    expect_refused(q, edit_refusal::not_triangle,
                   [](surface_mesh<glm::dvec3>& x) { return collapse_face(x, face_handle(0)); });
    auto p = mesh_of(pillow());
    expect_refused(p, edit_refusal::degenerate,
                   [](surface_mesh<glm::dvec3>& x) { return collapse_face(x, face_handle(0)); });
    CHECK_THROWS_AS(collapse_face(p, face_handle(9)), error);
  }
}

// ---------------------------------------------------------------------------- split

TEST_CASE_TEMPLATE("split_edge: interior, boundary, flipped and polygon edges", P, glm::dvec3,
                   std::array<float, 3>, test_support::user_point) {
  SUBCASE("interior edge of an icosahedron") {
    auto m = make_mesh(icosahedron<P>());
    const edge_handle e(5);
    const edge_star s = star(m, e);
    const glm::dvec3 mid = 0.5 * (to_dvec3(m.positions()[s.a]) + to_dvec3(m.positions()[s.b]));
    const edit_result r = split_edge(m, e, from_dvec3<P>(mid));
    REQUIRE(r.ok());
    CHECK(r.faces_added == 2);
    CHECK(m.num_vertices() == 13);
    CHECK(m.num_edges() == 33);
    CHECK(m.num_faces() == 22);
    CHECK(m.valence(r.vertex) == 4);
    CHECK(m.valence(s.a) == 5);
    CHECK(m.valence(s.c) == 6);
    CHECK(m.find_edge(s.a, s.b) == edge_handle());
    CHECK(glm::length(to_dvec3(m.positions()[r.vertex]) - mid) < 1e-6);
    CHECK(m.is_consistently_oriented());
    REQUIRE_VALID(m);
  }
  SUBCASE("boundary edge") {
    auto m = make_mesh(grid_plane<P>(2, 2, true));
    const edge_handle e = halfedge_mesh::edge(m.boundary_halfedges().front());
    const edit_result r = split_edge(m, e);
    REQUIRE(r.ok());
    CHECK(r.faces_added == 1);
    CHECK(m.num_vertices() == 10);
    CHECK(m.num_faces() == 9);
    CHECK(m.num_boundary_edges() == 9);
    CHECK(m.valence(r.vertex) == 3);
    CHECK(m.is_boundary(r.vertex));
    REQUIRE_VALID(m);
  }
  SUBCASE("flipped edge of a Möbius strip: both halves are seams") {
    auto m = make_mesh(mobius_strip<P>(10, 2));
    edge_handle seam;
    for (edge_handle e : m.edges())
      if (m.is_flipped(e)) seam = e;
    REQUIRE(seam.is_valid());
    const std::size_t flipped = m.num_flipped_edges();
    const vertex_handle a = m.vertex(seam, 0), b = m.vertex(seam, 1);
    const edit_result r = split_edge(m, seam);
    REQUIRE(r.ok());
    CHECK(m.num_flipped_edges() == flipped + 1);
    CHECK(m.is_flipped(m.find_edge(a, r.vertex)));
    CHECK(m.is_flipped(m.find_edge(r.vertex, b)));
    CHECK(euler(m) == 0);
    CHECK_FALSE(is_orientable(m));
    REQUIRE_VALID(m);
  }
  SUBCASE("quads gain the vertex") {
    auto m = make_mesh(hexahedron<P>());
    const edit_result r = split_edge(m, edge_handle(0));
    REQUIRE(r.ok());
    CHECK(r.faces_added == 0);
    CHECK(m.num_faces() == 6);
    CHECK(m.num_edges() == 13);
    for (face_handle f : m.faces_around(r.vertex)) CHECK(m.valence(f) == 5);
    REQUIRE_VALID(m);
  }
  auto m = make_mesh(icosahedron<P>());
  const auto inf = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(split_edge(m, edge_handle(0), from_dvec3<P>(glm::dvec3(inf, 0, 0))), error);
  CHECK_THROWS_AS(split_edge(m, edge_handle(30)), error);
  CHECK(m.num_vertices() == 12);
}

// ---------------------------------------------------------------------------- flip

TEST_CASE("flip_edge on an icosahedron moves the edge to the other diagonal") {
  auto m = make_mesh(icosahedron());
  const edge_handle e(9);
  const edge_star s = star(m, e);
  REQUIRE(can_flip(m, e) == edit_refusal::none);
  const edit_result r = flip_edge(m, e);
  REQUIRE(r.ok());
  CHECK(r.diagnostics.empty());
  CHECK(r.milliseconds >= 0);
  CHECK(m.num_edges() == 30);
  CHECK(m.num_faces() == 20);
  CHECK(m.valence(s.a) == 4);
  CHECK(m.valence(s.b) == 4);
  CHECK(m.valence(s.c) == 6);
  CHECK(m.valence(s.d) == 6);
  CHECK(r.edge == m.find_edge(s.c, s.d));
  CHECK_FALSE(m.find_edge(s.a, s.b).is_valid());
  CHECK(m.is_consistently_oriented());
  REQUIRE_VALID(m);
  // Flipping back restores the original edge set.
  REQUIRE(flip_edge(m, r.edge).ok());
  CHECK(m.find_edge(s.a, s.b).is_valid());
  // A refused edit says why in its diagnostic (stage_report), the refusal's own sentence.
  cellforge::surface_mesh<glm::dvec3> tri;
  const auto ta = tri.add_vertex({0, 0, 0}), tb = tri.add_vertex({1, 0, 0}), tc = tri.add_vertex({0, 1, 0});
  tri.add_face({ta, tb, tc});
  const edit_result refused = flip_edge(tri, tri.find_edge(ta, tb));
  CHECK(refused.refusal == edit_refusal::boundary_edge);
  REQUIRE(refused.diagnostics.size() == 1);
  CHECK(refused.diagnostics[0] == to_string(edit_refusal::boundary_edge));
  CHECK(m.valence(s.c) == 5);
  REQUIRE_VALID(m);
}

TEST_CASE("flip_edge refusals and flipped edges") {
  auto g = make_mesh(grid_plane(2, 2, true));
  const edge_handle be = halfedge_mesh::edge(g.boundary_halfedges().front());
  expect_refused(g, edit_refusal::boundary_edge,
                 [&](surface_mesh<glm::dvec3>& x) { return flip_edge(x, be); });
  auto t = make_mesh(tetrahedron());
  expect_refused(t, edit_refusal::edge_exists,
                 [](surface_mesh<glm::dvec3>& x) { return flip_edge(x, edge_handle(0)); });
  auto q = mesh_of(fixtures::cube());
  expect_refused(q, edit_refusal::not_triangle,
                 [](surface_mesh<glm::dvec3>& x) { return flip_edge(x, edge_handle(0)); });
  auto p = mesh_of(pillow());
  expect_refused(p, edit_refusal::degenerate,
                 [](surface_mesh<glm::dvec3>& x) { return flip_edge(x, edge_handle(0)); });

  // On a Möbius strip seam, the new triangles take the first face's orientation: the seam
  // moves off the flipped edge onto the two sides at the far corner.
  auto m = make_mesh(mobius_strip(12, 3));
  for (edge_handle e : m.edges()) {
    if (!m.is_flipped(e) || can_flip(m, e) != edit_refusal::none) continue;
    const std::size_t before = m.num_flipped_edges();
    const edit_result r = flip_edge(m, e);
    REQUIRE(r.ok());
    CHECK_FALSE(m.is_flipped(r.edge));
    CHECK(m.num_flipped_edges() == before + 1);
    CHECK_FALSE(is_orientable(m));
    CHECK(euler(m) == 0);
    REQUIRE_VALID(m);
    break;
  }
}

// ---------------------------------------------------------------------------- properties

TEST_CASE("face, edge and half-edge properties follow the rewritten faces") {
  auto m = make_mesh(icosphere(1));  // 80 faces
  auto fid = m.add_face_property<int>("f:id", -1);
  auto fname = m.add_face_property<std::string>("f:name");
  auto eid = m.add_edge_property<int>("e:id", -1);
  for (face_handle f : m.faces()) {
    fid[f] = static_cast<int>(f.idx());
    fname[f] = "face " + std::to_string(f.idx());
  }
  for (edge_handle e : m.edges()) eid[e] = static_cast<int>(e.idx());
  // Remember each face by its vertex set, and each edge by its ends.
  std::map<std::set<std::uint32_t>, int> face_of;
  for (face_handle f : m.faces()) {
    std::set<std::uint32_t> vs;
    for (vertex_handle v : m.vertices_around(f)) vs.insert(v.idx());
    face_of[vs] = fid[f];
  }

  SUBCASE("collapse: each re-added face keeps its value, removed ones are gone") {
    const halfedge_handle h = halfedge_mesh::halfedge(edge_handle(10), 0);
    const vertex_handle u = m.tail(h), v = m.head(h);
    std::set<int> before;
    for (face_handle f : m.faces()) before.insert(fid[f]);
    REQUIRE(collapse_halfedge(m, h).ok());
    std::set<int> after;
    for (face_handle f : m.faces()) {
      CHECK(fid[f] >= 0);
      CHECK(fname[f] == "face " + std::to_string(fid[f]));
      after.insert(fid[f]);
      // A face that did not touch u is itself; one that did had u where v is now.
      std::set<std::uint32_t> vs;
      for (vertex_handle x : m.vertices_around(f)) vs.insert(x.idx());
      std::set<std::uint32_t> old = vs;
      if (!face_of.count(vs)) {
        old.erase(v.idx());
        old.insert(u.idx());
      }
      REQUIRE(face_of.count(old) == 1);
      CHECK(face_of[old] == fid[f]);
    }
    CHECK(after.size() == m.num_faces());
    CHECK(before.size() - after.size() == 2);
    for (edge_handle e : m.edges()) CHECK(eid[e] >= 0);
  }
  SUBCASE("split: both halves come from the parent") {
    const edge_handle e(4);
    std::set<int> parents;
    for (unsigned i = 0; i < 2; ++i) parents.insert(fid[m.face(halfedge_mesh::halfedge(e, i))]);
    const edit_result r = split_edge(m, e);
    REQUIRE(r.ok());
    std::multiset<int> children;
    for (face_handle f : m.faces_around(r.vertex)) children.insert(fid[f]);
    REQUIRE(children.size() == 4);
    int inherited = 0;
    for (int p : parents) inherited += static_cast<int>(children.count(p));
    CHECK(inherited == 4);  // every child face carries its parent's values
    int halves = 0;
    for (edge_handle x : m.edges_around(r.vertex))
      if (eid[x] == static_cast<int>(e.idx())) ++halves;
    CHECK(halves == 2);  // both halves of the split edge carry its values
  }
  SUBCASE("flip: faces keep theirs, the new edge gets the default") {
    const edit_result r = flip_edge(m, edge_handle(12));
    REQUIRE(r.ok());
    std::set<int> ids;
    for (face_handle f : m.faces()) ids.insert(fid[f]);
    CHECK(ids.size() == 80);
    CHECK(eid[r.edge] == -1);
  }
  REQUIRE_VALID(m);
}

// ---------------------------------------------------------------------------- random edits

namespace {

// Forces merging the vertices `from` into v on a soup (drop the faces through two of them,
// rename the rest) and says whether the result is broken: not representable, a pinched or
// vanished vertex, duplicate faces, or another Euler characteristic or number of boundary loops.
bool forced_merge_breaks(const surface_mesh<glm::dvec3>& m, std::vector<vertex_handle> from,
                         vertex_handle v) {
  const soup s = to_soup(m);  // m has no garbage: soup indices are handles
  auto merged = [&](std::uint32_t x) {
    return x == v.idx() ||
           std::any_of(from.begin(), from.end(), [&](vertex_handle y) { return y.idx() == x; });
  };
  soup t;
  t.points = s.points;
  std::set<std::set<std::uint32_t>> seen;
  bool duplicate = false;
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    std::vector<std::uint32_t> vs(s.face(f).begin(), s.face(f).end());
    if (std::count_if(vs.begin(), vs.end(), merged) >= 2) continue;
    for (auto& x : vs)
      if (merged(x)) x = v.idx();
    duplicate |= !seen.insert(std::set<std::uint32_t>(vs.begin(), vs.end())).second;
    t.add_face(vs);
  }
  if (duplicate) return true;
  surface_mesh<glm::dvec3> r;
  try {
    r = make_mesh(t);
  } catch (const error&) {
    return true;  // an edge with three faces, or a closed fan plus another
  }
  std::size_t used = 0;
  for (vertex_handle x : r.vertices()) {
    if (r.is_isolated(x)) {
      if (!merged(x.idx()) || x == v) return true;  // a vertex lost all its faces
      continue;
    }
    ++used;
    if (detail::edits::count_fans(r, x) != 1) return true;  // pinched
  }
  const int chi = static_cast<int>(used) - static_cast<int>(r.num_edges()) + static_cast<int>(r.num_faces());
  return chi != euler(m) || r.boundary_loops().size() != m.boundary_loops().size();
}

template <class Handle>
Handle pick_live(const surface_mesh<glm::dvec3>& m, std::size_t size, std::mt19937_64& rng) {
  for (;;) {
    const Handle h(static_cast<std::uint32_t>(rng() % size));
    if (!m.is_removed(h)) return h;
  }
}

struct random_stats {
  std::array<int, 4> done{}, refused{};
};

// Applies `steps` random edits (half-edge collapse, face collapse, split, flip), validating
// after every one and tracking the Euler characteristic, the number of boundary loops and
// orientability. The mesh size is kept near its start by biasing towards splits or collapses.
random_stats random_edits(surface_mesh<glm::dvec3> m, int steps, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const int chi = euler(m);
  const bool orientable = is_orientable(m);
  const std::size_t loops = m.boundary_loops().size();
  const std::size_t start_faces = m.num_faces();
  random_stats st;
  for (int step = 0; step < steps; ++step) {
    int op = static_cast<int>(rng() % 4);
    if (m.num_faces() < start_faces / 2 && (op == 0 || op == 1)) op = 2;
    if (m.num_faces() > 2 * start_faces && op == 2) op = 0;
    const std::size_t nv = m.num_vertices(), nf = m.num_faces(), flipped = m.num_flipped_edges();
    edit_result r;
    edit_refusal why = edit_refusal::none;
    bool seam = false;
    if (op == 0) {
      const auto h = pick_live<halfedge_handle>(m, m.halfedges_size(), rng);
      why = can_collapse(m, h);
      r = collapse_halfedge(m, h);
    } else if (op == 1) {
      const auto f = pick_live<face_handle>(m, m.faces_size(), rng);
      why = can_collapse_face(m, f);
      r = collapse_face(m, f);
    } else if (op == 2) {
      const auto e = pick_live<edge_handle>(m, m.edges_size(), rng);
      seam = m.is_flipped(e);
      r = split_edge(m, e);
      CHECK(m.num_flipped_edges() == flipped + (seam ? 1 : 0));
    } else {
      const auto e = pick_live<edge_handle>(m, m.edges_size(), rng);
      why = can_flip(m, e);
      r = flip_edge(m, e);
    }
    REQUIRE(r.refusal == why);
    (r ? st.done : st.refused)[static_cast<std::size_t>(op)]++;
    const auto vr = validate(m);
    INFO("step " << step << " op " << op << ": " << vr.message);
    REQUIRE(vr.ok());
    REQUIRE(euler(m) == chi);
    if (!r) {
      REQUIRE(m.num_vertices() == nv);
      REQUIRE(m.num_faces() == nf);
    } else {
      REQUIRE(m.num_vertices() + r.vertices_removed == nv + (op == 2 ? 1 : 0));
      REQUIRE(m.num_faces() + r.faces_removed == nf + r.faces_added);
    }
    if (step % 97 == 0) {
      REQUIRE(is_orientable(m) == orientable);
      REQUIRE(m.boundary_loops().size() == loops);
    }
    if (step % 100 == 50) {  // refusals are exact here too
      auto c = m;
      c.garbage_collection();
      for (int t = 0; t < 10; ++t) {
        const halfedge_handle h(static_cast<std::uint32_t>(rng() % c.halfedges_size()));
        REQUIRE(forced_merge_breaks(c, {c.tail(h)}, c.head(h)) == (can_collapse(c, h) != edit_refusal::none));
        const face_handle f(static_cast<std::uint32_t>(rng() % c.faces_size()));
        std::vector<vertex_handle> vs;
        for (vertex_handle x : c.vertices_around(f)) vs.push_back(x);
        REQUIRE(forced_merge_breaks(c, {vs[1], vs[2]}, vs[0]) ==
                (can_collapse_face(c, f) != edit_refusal::none));
      }
    }
    if (step % 500 == 499) {
      m.garbage_collection();
      REQUIRE_VALID(m);
    }
  }
  REQUIRE(is_orientable(m) == orientable);
  REQUIRE(m.boundary_loops().size() == loops);
  return st;
}

}  // namespace

TEST_CASE("thousands of random edits keep every invariant and the topology") {
  struct named {
    std::string name;
    soup s;
  };
  const std::vector<named> inputs = {
      {"icosphere", icosphere(2)},
      {"torus", torus(12, 8)},
      {"mobius", mobius_strip(16, 3)},
      {"klein", klein_bottle(12, 8)},
      {"random orientation plane", random_orientation_plane(8, 8, 7)},
  };
#ifdef NDEBUG
  constexpr int steps = 3000;
#else
  constexpr int steps = 1500;  // the sanitizer build: half the edits, the same checks after each
#endif
  std::uint64_t seed = 1;
  for (const named& in : inputs) {
    CAPTURE(in.name);
    const random_stats st = random_edits(make_mesh(in.s), steps, seed++);
    for (int op = 0; op < 4; ++op) {
      CAPTURE(op);
      CHECK(st.done[static_cast<std::size_t>(op)] > steps / 30);
    }
    CHECK(st.refused[0] + st.refused[1] + st.refused[3] > 0);
  }
}

// ---------------------------------------------------------------------------- exactness

namespace {}  // namespace

TEST_CASE("collapse refusals are exact: refused collapses would break the surface, allowed ones would not" *
          doctest::timeout(600)) {
  std::mt19937_64 rng(11);
  std::vector<soup> inputs = {icosphere(1),       torus(6, 4),        klein_bottle(5, 4),
                              mobius_strip(6, 1), mobius_strip(7, 2), grid_plane(3, 2, true),
                              strip(4),           bipyramid(),        random_orientation_plane(4, 3, 5),
                              tetrahedron(),      strip(1),           octahedron()};
  {
    soup lone;  // a lone triangle
    lone.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    lone.add_face({0, 1, 2});
    inputs.push_back(lone);
  }
  std::array<int, num_edit_refusals> seen{}, face_seen{};
  for (const soup& s : inputs) {
    auto m = make_mesh(s);
    // Random flips first, so that low and high valences and odd links occur.
    for (int i = 0; i < 40 && m.num_faces() > 8; ++i) {
      const edge_handle e(static_cast<std::uint32_t>(rng() % m.edges_size()));
      if (!m.is_removed(e)) flip_edge(m, e);
    }
    m.garbage_collection();
    REQUIRE_VALID(m);
    for (halfedge_handle h : m.halfedges()) {
      const edit_refusal why = can_collapse(m, h);
      seen[static_cast<std::size_t>(why)]++;
      CAPTURE(to_string(why));
      CHECK(forced_merge_breaks(m, {m.tail(h)}, m.head(h)) == (why != edit_refusal::none));
    }
    for (face_handle f : m.faces()) {
      const edit_refusal why = can_collapse_face(m, f);
      face_seen[static_cast<std::size_t>(why)]++;
      CAPTURE(to_string(why));
      std::vector<vertex_handle> vs;
      for (vertex_handle x : m.vertices_around(f)) vs.push_back(x);
      const bool br = forced_merge_breaks(m, {vs[1], vs[2]}, vs[0]);
      CHECK(br == (why != edit_refusal::none));
    }
  }
  for (edit_refusal why : {edit_refusal::none, edit_refusal::link_condition, edit_refusal::boundary_vertices,
                           edit_refusal::isolated_triangle, edit_refusal::tetrahedron}) {
    CAPTURE(to_string(why));
    CHECK(seen[static_cast<std::size_t>(why)] > 0);
    CHECK(face_seen[static_cast<std::size_t>(why)] > 0);
  }
}

}  // namespace edits_tests
