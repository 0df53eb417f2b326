#include <doctest/doctest.h>

#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <ranges>
#include <set>
#include <span>
#include <type_traits>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/core/detail/edge_table.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/halfedge/orientation.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "mesh_fixtures.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace halfedge_mesh_tests {

using namespace cellforge;

namespace {

// Shuffles the faces of a soup (same faces, another order).
fixtures::soup shuffled(const fixtures::soup& s, std::uint64_t seed) {
  std::vector<std::size_t> order(s.num_faces());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937_64(seed));
  fixtures::soup out;
  out.points = s.points;
  for (std::size_t f : order) out.add_face(s.face(f));
  return out;
}

// Builds a soup face by face through add_face.
halfedge_mesh build_incrementally(const fixtures::soup& s) {
  halfedge_mesh m;
  m.add_vertices(s.num_points());
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    std::vector<vertex_handle> vs;
    for (auto v : s.face(f)) vs.emplace_back(v);
    m.add_face(vs);
  }
  return m;
}

using test_support::euler;

// Checks every circulator of m against the soup it was built from.
void check_circulators(const halfedge_mesh& m, const fixtures::soup& s) {
  std::map<std::uint32_t, std::multiset<std::uint32_t>> faces_at;
  std::map<std::uint32_t, std::set<std::uint32_t>> neighbours;
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    auto fv = s.face(f);
    for (std::size_t i = 0; i < fv.size(); ++i) {
      faces_at[fv[i]].insert(static_cast<std::uint32_t>(f));
      neighbours[fv[i]].insert(fv[(i + 1) % fv.size()]);
      neighbours[fv[(i + 1) % fv.size()]].insert(fv[i]);
    }
  }
  for (vertex_handle v : m.vertices()) {
    std::multiset<std::uint32_t> fs;
    for (face_handle f : m.faces_around(v)) fs.insert(f.idx());
    CHECK(fs == faces_at[v.idx()]);
    std::set<std::uint32_t> ns;
    std::size_t count = 0;
    for (vertex_handle w : m.vertices_around(v)) {
      ns.insert(w.idx());
      ++count;
    }
    CHECK(ns == neighbours[v.idx()]);
    CHECK(count == neighbours[v.idx()].size());  // each incident edge once
    for (halfedge_handle h : m.halfedges_around(v)) {
      const bool leaves = m.tail(h) == v;
      const bool both_enter = m.head(h) == v && m.head(halfedge_mesh::twin(h)) == v;
      CHECK((leaves || both_enter));
    }
    CHECK(std::ranges::distance(m.edges_around(v)) == static_cast<long>(neighbours[v.idx()].size()));
  }
  for (face_handle f : m.faces()) {
    std::vector<std::uint32_t> got;
    for (vertex_handle v : m.vertices_around(f)) got.push_back(v.idx());
    const auto want = s.face(f.idx());
    CHECK(std::ranges::equal(got, want));
    for (halfedge_handle h : m.halfedges_around(f)) CHECK(m.face(h) == f);
  }
}

}  // namespace

TEST_CASE("closed meshes: tetrahedron, cube, torus") {
  struct named {
    const char* name;
    fixtures::soup soup;
    int chi;
  };
  for (const named& item : {named{"tetrahedron", fixtures::tetrahedron(), 2},
                            named{"cube", fixtures::cube(), 2}, named{"torus", fixtures::torus(), 0}}) {
    const auto& soup = item.soup;
    const int chi = item.chi;
    CAPTURE(item.name);
    build_report rep;
    auto m = make_mesh(soup, &rep);
    REQUIRE_VALID(m);
    CHECK(m.is_closed());
    CHECK(m.num_boundary_edges() == 0);
    CHECK(m.boundary_halfedges().empty());
    CHECK(m.is_consistently_oriented());
    CHECK(is_orientable(m));
    CHECK(euler(m) == chi);
    CHECK(rep.edges == fixtures::soup_edges(soup).size());
    check_circulators(m, soup);
    const auto order = shuffled(soup, 7);
    const auto inc = build_incrementally(order);
    REQUIRE_VALID(inc);
    CHECK(inc.num_edges() == m.num_edges());
    check_circulators(inc, order);
  }
}

TEST_CASE("open meshes: plane and cylinder boundaries") {
  const auto plane = fixtures::plane(6, 5);
  auto m = make_mesh(plane);
  REQUIRE_VALID(m);
  CHECK_FALSE(m.is_closed());
  CHECK(m.num_boundary_edges() == 2 * (6 + 5));
  CHECK(m.boundary_loops().size() == 1);
  CHECK(m.boundary_loops()[0].size() == 22);
  check_circulators(m, plane);
  const auto cyl = fixtures::cylinder(8, 3);
  auto c = make_mesh(cyl);
  REQUIRE_VALID(c);
  const auto loops = c.boundary_loops();
  REQUIRE(loops.size() == 2);
  CHECK(loops[0].size() == 8);
  CHECK(loops[1].size() == 8);
  CHECK(euler(c) == 0);
  check_circulators(c, cyl);
}

TEST_CASE("non-orientable: Möbius strip and Klein bottle build and circulate") {
  const auto mob = fixtures::mobius(12, 2);
  build_report rep;
  auto m = make_mesh(mob, &rep);
  REQUIRE_VALID(m);
  CHECK(rep.flipped_edges > 0);
  CHECK(m.num_flipped_edges() == rep.flipped_edges);
  CHECK_FALSE(is_orientable(m));
  CHECK(euler(m) == 0);
  const auto loops = m.boundary_loops();
  REQUIRE(loops.size() == 1);    // a Möbius strip has one boundary curve...
  CHECK(loops[0].size() == 24);  // ...twice as long as the strip
  {
    // The boundary circulator is a range whose consecutive half-edges share a vertex.
    const auto range = m.halfedges_around_boundary(loops[0].front());
    static_assert(std::ranges::forward_range<decltype(range)>);
    REQUIRE(std::ranges::distance(range) == 24);
    const std::vector<halfedge_handle> walk(range.begin(), std::ranges::next(range.begin(), 24));
    for (std::size_t i = 0; i < walk.size(); ++i) {
      const halfedge_handle a = walk[i], b = walk[(i + 1) % walk.size()];
      CHECK(m.is_boundary(a));
      const bool touch = m.head(a) == m.head(b) || m.head(a) == m.tail(b) || m.tail(a) == m.head(b) ||
                         m.tail(a) == m.tail(b);
      CHECK(touch);
    }
    CHECK(std::set<halfedge_handle>(walk.begin(), walk.end()).size() == 24);
  }
  check_circulators(m, mob);
  const auto mob_order = shuffled(mob, 3);
  const auto mi = build_incrementally(mob_order);
  REQUIRE_VALID(mi);
  check_circulators(mi, mob_order);

  const auto kb = fixtures::klein(8, 6);
  auto k = make_mesh(kb);
  REQUIRE_VALID(k);
  CHECK(k.is_closed());
  CHECK(euler(k) == 0);
  CHECK_FALSE(is_orientable(k));
  CHECK(k.num_flipped_edges() > 0);
  check_circulators(k, kb);
  auto k2 = k;
  const orient_result r = orient(k2);
  REQUIRE_VALID(k2);
  CHECK_FALSE(r.orientable());
  CHECK(r.flipped_edges_left > 0);
  CHECK(r.flipped_edges_left == k2.num_flipped_edges());
}

TEST_CASE("randomly oriented plane: faces keep their orientation, orient() repairs it") {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const auto s = fixtures::randomly_flipped(fixtures::plane(7, 6), seed);
    auto m = make_mesh(s);
    REQUIRE_VALID(m);
    CHECK(m.num_flipped_edges() > 0);
    check_circulators(m, s);  // faces keep the vertex order they were given
    CHECK(is_orientable(m));
    const auto order = shuffled(s, seed);
    auto inc = build_incrementally(order);
    REQUIRE_VALID(inc);
    check_circulators(inc, order);
    const orient_result r = orient(m);
    REQUIRE_VALID(m);
    CHECK(r.orientable());
    CHECK(r.faces_reversed > 0);
    CHECK(m.num_flipped_edges() == 0);
    CHECK(m.boundary_loops().size() == 1);
  }
}

TEST_CASE("non-manifold input: two open fans are representable, the rest is refused clearly") {
  const auto bow = fixtures::bowtie();
  auto m = make_mesh(bow);
  REQUIRE_VALID(m);
  CHECK(std::ranges::distance(m.faces_around(vertex_handle(0))) == 2);
  check_circulators(m, bow);
  CHECK(m.boundary_loops().size() == 2);
  auto mi = build_incrementally(bow);
  REQUIRE_VALID(mi);
  // Joining the two fans with a third triangle merges them into one.
  mi.add_face({vertex_handle(0), vertex_handle(2), vertex_handle(3)});
  REQUIRE_VALID(mi);
  CHECK(std::ranges::distance(mi.faces_around(vertex_handle(0))) == 3);

  // A third face on an edge.
  fixtures::soup three = fixtures::tetrahedron();
  three.points.push_back({1, 1, 1});
  three.add_face({0, 1, 4});
  try {
    (void)make_mesh(three);
    FAIL("expected an error");
  } catch (const error& e) {
    CHECK(e.category() == error_category::topology);
    CHECK(std::string(e.what()).find("edge (0, 1)") != std::string::npos);
  }
  auto t = build_incrementally(fixtures::tetrahedron());
  CHECK_THROWS_AS(t.add_face({vertex_handle(0), vertex_handle(1), t.add_vertex()}), error);
  REQUIRE_VALID(t);

  // Two closed fans at one vertex: refused by default, split on request.
  try {
    (void)make_mesh(fixtures::double_cone());
    FAIL("expected an error");
  } catch (const error& e) {
    CHECK(std::string(e.what()).find("vertex 0") != std::string::npos);
    CHECK(std::string(e.what()).find("split_nonmanifold_vertices") != std::string::npos);
  }
  build_report rep;
  const auto split = make_mesh(fixtures::double_cone(), &rep, {.split_nonmanifold_vertices = true});
  REQUIRE_VALID(split);
  REQUIRE(rep.split_vertices.size() == 1);
  CHECK(rep.split_vertices[0].second == 0);
  CHECK(split.num_vertices() == 8);
  CHECK(split.is_closed());
  CHECK(split.valence(vertex_handle(0)) == 3);
  CHECK(split.valence(vertex_handle(rep.split_vertices[0].first)) == 3);
  CHECK(split.positions()[vertex_handle(7)] == glm::dvec3(0, 0, 0));
  // Two tetrahedra sharing a vertex, one of them also touched by an open fan.
  const fixtures::soup tet = fixtures::tetrahedron();
  fixtures::soup two = tet;
  const std::size_t n = two.points.size();
  for (const glm::dvec3& p : tet.points) two.points.push_back(p + glm::dvec3(-1, -1, -1));
  for (std::size_t f = 0; f < 4; ++f) {
    std::vector<std::uint32_t> fv;
    for (auto v : tet.face(f)) fv.push_back(v == 0 ? 0 : static_cast<std::uint32_t>(v + n));
    two.add_face(fv);
  }
  two.points.push_back({0, 0, -2});
  two.points.push_back({0, -2, 0});
  two.add_face({0, static_cast<std::uint32_t>(2 * n), static_cast<std::uint32_t>(2 * n + 1)});
  CHECK_THROWS_AS((void)make_mesh(two), error);
  const auto ts = make_mesh(two, &rep, {.split_nonmanifold_vertices = true});
  REQUIRE_VALID(ts);
  CHECK(rep.split_vertices.size() == 2);
  CHECK(ts.num_boundary_edges() == 3);
}

TEST_CASE("bad face lists are rejected with the face named") {
  fixtures::soup s = fixtures::tetrahedron();
  s.add_face({0, 1, 9});
  CHECK_THROWS_WITH_AS((void)make_mesh(s), doctest::Contains("face 4 uses vertex 9"), error);
  fixtures::soup r = fixtures::tetrahedron();
  r.add_face({0, 1, 0});
  CHECK_THROWS_WITH_AS((void)make_mesh(r), doctest::Contains("face 4 repeats a vertex"), error);
  halfedge_mesh m;
  m.add_vertices(3);
  CHECK_THROWS_AS(m.add_face({vertex_handle(0), vertex_handle(1)}), error);
  CHECK_THROWS_AS(m.add_face({vertex_handle(0), vertex_handle(1), vertex_handle(7)}), error);
  CHECK(m.num_faces() == 0);
  REQUIRE_VALID(m);
}

TEST_CASE("randomised add/remove keeps every invariant") {
  for (const auto& base : {fixtures::torus(6, 5), fixtures::mobius(10, 3), fixtures::klein(6, 5),
                           fixtures::randomly_flipped(fixtures::plane(6, 6), 11)}) {
    std::mt19937_64 rng(42);
    halfedge_mesh m;
    m.add_vertices(base.num_points());
    std::vector<std::size_t> present(base.num_faces(), halfedge_mesh::npos);  // soup face -> mesh face
    std::size_t ops = 0, refused = 0;
    for (int step = 0; step < 1500; ++step) {
      const std::size_t f = rng() % base.num_faces();
      if (present[f] == halfedge_mesh::npos) {
        std::vector<vertex_handle> vs;
        for (auto v : base.face(f)) vs.emplace_back(v);
        try {
          present[f] = m.add_face(vs).idx();
        } catch (const error& e) {
          CHECK(e.category() == error_category::topology);  // a fan would close around a non-manifold vertex
          ++refused;
        }
      } else {
        m.remove_face(face_handle(present[f]));
        present[f] = halfedge_mesh::npos;
      }
      ++ops;
      const auto vr = validate(m);
      INFO("step " << step << ": " << vr.message);
      REQUIRE(vr.ok());
      if (step % 200 == 199) {
        // Compacting renumbers faces: refresh the map through a face property.
        auto tag = m.add_face_property<std::int64_t>("f:soup", -1);
        for (std::size_t k = 0; k < present.size(); ++k)
          if (present[k] != halfedge_mesh::npos) tag[face_handle(present[k])] = static_cast<std::int64_t>(k);
        m.garbage_collection();
        REQUIRE_VALID(m);
        std::fill(present.begin(), present.end(), halfedge_mesh::npos);
        for (face_handle g : m.faces()) present[static_cast<std::size_t>(tag[g])] = g.idx();
        m.remove_property(tag);
      }
    }
    CHECK(ops == 1500);
    CHECK(refused < ops / 2);
  }
}

TEST_CASE("remove_vertex removes its faces and keeps the rest valid") {
  auto m = make_mesh(fixtures::torus(6, 5));
  const std::size_t f0 = m.num_faces();
  const std::size_t deg = std::ranges::distance(m.faces_around(vertex_handle(7)));
  m.remove_vertex(vertex_handle(7));
  REQUIRE_VALID(m);
  CHECK(m.num_faces() == f0 - deg);
  CHECK(m.boundary_loops().size() == 1);
  CHECK_THROWS_AS(m.remove_vertex(vertex_handle(7)), error);
  m.garbage_collection();
  REQUIRE_VALID(m);
  CHECK(m.num_vertices() == 29);
}

TEST_CASE("properties: add, get by name, type checks, survive copies and compaction") {
  auto m = make_mesh(fixtures::cube());
  auto w = m.add_vertex_property<double>("v:weight", 1.5);
  auto tag = m.add_face_property<std::string>("f:name", "none");
  auto len = m.add_edge_property<float>("e:len");
  auto mark = m.add_halfedge_property<bool>("h:mark", false);
  CHECK(w[vertex_handle(3)] == 1.5);
  w[vertex_handle(3)] = 4.0;
  tag[face_handle(3)] = "front";
  len[edge_handle(5)] = 2.0f;
  mark[halfedge_handle(1)] = true;
  CHECK(m.get_vertex_property<double>("v:weight")[vertex_handle(3)] == 4.0);
  CHECK_THROWS_AS((void)m.get_vertex_property<int>("v:weight"), error);
  CHECK_THROWS_AS((void)m.add_vertex_property<double>("v:weight"), error);
  CHECK_FALSE(m.get_vertex_property<double>("v:nothing").is_valid());
  CHECK(m.has_property<face_handle>("f:name"));
  auto copy = m;
  w[vertex_handle(3)] = 9.0;
  CHECK(copy.get_vertex_property<double>("v:weight")[vertex_handle(3)] == 4.0);
  // New elements get the default value.
  const vertex_handle nv = m.add_vertex(glm::dvec3(7, 8, 9));
  CHECK(w[nv] == 1.5);
  CHECK(m.position(nv) == glm::dvec3(7, 8, 9));
  REQUIRE_VALID(m);
  m.remove_face(face_handle(0));
  m.remove_vertex(vertex_handle(0));
  m.garbage_collection();
  REQUIRE_VALID(m);
  auto tag2 = m.get_face_property<std::string>("f:name");
  CHECK(std::ranges::count(tag2.vector(), std::string("front")) == 1);
  CHECK(m.remove_property<vertex_handle>("v:weight"));
  CHECK_FALSE(m.has_property<vertex_handle>("v:weight"));
  REQUIRE_VALID(m);
}

TEST_CASE("circulators are std::ranges") {
  auto m = make_mesh(fixtures::tetrahedron());
  static_assert(std::ranges::forward_range<decltype(m.faces_around(vertex_handle(0)))>);
  static_assert(std::ranges::forward_range<decltype(m.vertices_around(face_handle(0)))>);
  static_assert(std::ranges::forward_range<decltype(m.vertices())>);
  CHECK(std::ranges::count_if(m.vertices_around(vertex_handle(0)),
                              [](vertex_handle v) { return v.idx() > 1; }) == 2);
  CHECK(std::ranges::distance(m.faces()) == 4);
  CHECK(m.valence(vertex_handle(0)) == 3);
  CHECK(m.valence(face_handle(0)) == 3);
  auto it = std::ranges::find(m.vertices_around(face_handle(1)), vertex_handle(3));
  CHECK(it != std::ranges::end(m.vertices_around(face_handle(1))));
}

TEST_CASE("validate names the broken invariant") {
  // A mesh whose property was resized behind its back, via a copy of the registry.
  auto m = make_mesh(fixtures::cube());
  auto p = m.add_vertex_property<int>("v:x");
  p.vector().push_back(1);
  const auto r = validate(m);
  CHECK_FALSE(r.ok());
  CHECK(r.broken == mesh_invariant::property_size);
  CHECK(r.message.find("v:x") != std::string::npos);
}

TEST_CASE("soup round trip keeps faces and their orientation") {
  const auto s = fixtures::randomly_flipped(fixtures::klein(5, 4), 5);
  const auto m = make_mesh(s);
  const auto back = to_soup(m);
  CHECK(back.points == s.points);
  CHECK(back.face_offsets == s.face_offsets);
  CHECK(back.face_vertices == s.face_vertices);
}

// ---------------------------------------------------------------------------- surface_mesh

// A CAD-style point: private members, getters, a constructor, no default constructor.
using test_support::sealed_point;

static_assert(!std::is_default_constructible_v<sealed_point>);
static_assert(cellforge::Point3<sealed_point>);

TEST_CASE("surface_mesh: positions of the caller's type, kept through copies, edits and compaction") {
  using cellforge::surface_mesh;
  surface_mesh<sealed_point> m;
  static_assert(std::is_same_v<decltype(m)::point_type, sealed_point>);
  const vertex_handle a = m.add_vertex({0, 0, 0}), b = m.add_vertex({1, 0, 0}), c = m.add_vertex({0, 1, 0});
  const std::vector<sealed_point> more{{0, 0, 1}, {5, 5, 5}};
  const vertex_handle d = m.add_vertices(more);
  m.add_face({a, b, c});
  m.add_face({a, d, b});
  m.add_face({b, d, c});
  m.add_face({c, d, a});
  REQUIRE_VALID(m);
  CHECK(m.num_vertices() == 5);
  CHECK(m.position(b) == sealed_point(1, 0, 0));
  CHECK(m.position(vertex_handle(4)) == sealed_point(5, 5, 5));
  m.set_position(b, {2, 0, 0});
  CHECK(m.points()[b.idx()] == sealed_point(2, 0, 0));

  // Copies own their positions.
  surface_mesh<sealed_point> copy = m;
  copy.set_position(b, {3, 0, 0});
  CHECK(m.position(b) == sealed_point(2, 0, 0));
  CHECK(copy.position(b) == sealed_point(3, 0, 0));
  surface_mesh<sealed_point> moved = std::move(copy);
  CHECK(moved.position(b) == sealed_point(3, 0, 0));
  copy = moved;  // a moved-from mesh can be assigned to
  CHECK(copy.position(d) == sealed_point(0, 0, 1));

  // Compaction moves positions with their vertices: the isolated vertex 4 goes.
  m.remove_vertex(vertex_handle(4));
  m.garbage_collection();
  REQUIRE_VALID(m);
  CHECK(m.num_vertices() == 4);
  CHECK(m.points().size() == 4);
  CHECK(m.position(d) == sealed_point(0, 0, 1));

  // The positions cannot be removed or shadowed by a property of another type.
  CHECK_THROWS_AS((void)m.remove_property<vertex_handle>(cellforge::point_property_name), error);
  CHECK_THROWS_AS((void)m.add_vertex_property<glm::dvec3>(cellforge::point_property_name), error);
  CHECK(m.position(a) == sealed_point(0, 0, 0));

  // clear() keeps the mesh usable: positions come back with new vertices.
  m.clear();
  CHECK(m.num_vertices() == 0);
  const vertex_handle e = m.add_vertex({4, 4, 4});
  CHECK(m.position(e) == sealed_point(4, 4, 4));
}

TEST_CASE("circulators are common ranges: begin and end have one type") {
  auto m = make_mesh(fixtures::cube());
  const auto around = m.faces_around(vertex_handle(0));
  static_assert(std::ranges::common_range<decltype(around)>);
  static_assert(std::ranges::common_range<decltype(m.vertices_around(face_handle(0)))>);
  static_assert(std::ranges::common_range<decltype(m.faces())>);
  const std::vector<face_handle> faces(around.begin(), around.end());  // the pre-ranges constructor
  CHECK(faces.size() == 3);
  CHECK(std::vector<face_handle>(std::ranges::begin(around), std::ranges::end(around)) == faces);
  const auto corners = m.vertices_around(face_handle(0));
  CHECK(std::vector<vertex_handle>(corners.begin(), corners.end()).size() == 4);
}

TEST_CASE("surface_mesh: make_mesh and to_soup keep the soup's point type") {
  cellforge::polygon_soup<sealed_point> s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  s.add_face({0, 2, 1});
  s.add_face({0, 1, 3});
  s.add_face({1, 2, 3});
  s.add_face({2, 0, 3});
  auto m = make_mesh(s);
  static_assert(std::is_same_v<decltype(m), cellforge::surface_mesh<sealed_point>>);
  REQUIRE_VALID(m);
  CHECK(m.is_closed());
  const auto back = to_soup(m);
  CHECK(back.points == s.points);
  CHECK(back.face_vertices == s.face_vertices);
}

TEST_CASE("edge_table: a bulk assign finds exactly what one insert per entry finds") {
  std::mt19937_64 rng(31);
  std::vector<cellforge::detail::edge_table::slot> entries;
  std::set<std::uint64_t> keys;
  while (entries.size() < 50000) {
    const auto k = cellforge::detail::edge_table::key(static_cast<std::uint32_t>(rng() % 4000),
                                                      static_cast<std::uint32_t>(rng() % 4000));
    if (keys.insert(k).second) entries.push_back({k, static_cast<std::uint32_t>(entries.size())});
  }
  cellforge::detail::edge_table bulk, one_by_one;
  bulk.assign(entries);
  for (const auto& e : entries) one_by_one.insert(e.key, e.value);
  CHECK(bulk.size() == entries.size());
  std::size_t wrong = 0, false_hits = 0;
  for (const auto& e : entries) wrong += bulk.find(e.key) != e.value || one_by_one.find(e.key) != e.value;
  for (int i = 0; i < 20000; ++i) {
    const auto k = cellforge::detail::edge_table::key(4000 + static_cast<std::uint32_t>(rng() % 100), 7);
    false_hits += bulk.find(k) != cellforge::detail::edge_table::not_found;
  }
  CHECK(wrong == 0);
  CHECK(false_hits == 0);
  bulk.assign({});
  CHECK(bulk.empty());
}

TEST_CASE("edge_table: try_insert keeps the first value, as a set's insert does, against std::map") {
  std::mt19937_64 rng(41);
  cellforge::detail::edge_table table;
  std::map<std::uint64_t, std::uint32_t> reference;
  std::size_t disagreements = 0;
  for (std::uint32_t i = 0; i < 30000; ++i) {
    const auto k = cellforge::detail::edge_table::key(static_cast<std::uint32_t>(rng() % 150),
                                                      static_cast<std::uint32_t>(rng() % 150));
    disagreements += table.try_insert(k, i) != reference.emplace(k, i).second;
  }
  CHECK(disagreements == 0);
  CHECK(table.size() == reference.size());
  std::size_t wrong = 0;
  for (const auto& [k, v] : reference) wrong += table.find(k) != v;
  CHECK(wrong == 0);
  table.insert(reference.begin()->first, 7);  // insert still overwrites
  CHECK(table.find(reference.begin()->first) == 7);
  CHECK(table.size() == reference.size());
}

TEST_CASE("span_of: the elements of a vector or an array, const or not, in place") {
  using cellforge::detail::span_of;
  std::vector<int> v{1, 2, 3};
  const std::vector<int>& cv = v;
  std::array<double, 2> a{0.5, 1.5};
  const std::array<double, 2>& ca = a;
  static_assert(std::is_same_v<decltype(span_of(v)), std::span<int>>);
  static_assert(std::is_same_v<decltype(span_of(cv)), std::span<const int>>);
  static_assert(std::is_same_v<decltype(span_of(a)), std::span<double>>);
  static_assert(std::is_same_v<decltype(span_of(ca)), std::span<const double>>);
  CHECK(span_of(cv).data() == v.data());
  CHECK(span_of(cv).size() == 3);
  CHECK(span_of(ca).data() == a.data());
  CHECK(span_of(ca).size() == 2);
  span_of(v)[1] = 20;
  span_of(a)[0] = -1;
  CHECK(v == std::vector<int>{1, 20, 3});
  CHECK(a[0] == -1);
  std::vector<int> empty;
  CHECK(span_of(empty).empty());
}

TEST_CASE("derived_key_table: bulk assign, inserts and erases find exactly the keys stored") {
  // Value i stands for keys[i]; the table stores only the value and 32 bits of the key's hash.
  using table_t = cellforge::detail::derived_key_table;
  std::mt19937_64 rng(37);
  std::vector<std::uint64_t> keys;
  std::set<std::uint64_t> seen;
  while (keys.size() < 50000) {
    const auto k =
        table_t::key(static_cast<std::uint32_t>(rng() % 4000), static_cast<std::uint32_t>(rng() % 4000));
    if (seen.insert(k).second) keys.push_back(k);
  }
  const auto key_of = [&keys](std::uint32_t v) { return keys[v]; };
  std::vector<table_t::slot> entries;
  for (std::uint32_t i = 0; i < keys.size(); ++i) entries.push_back(table_t::entry(keys[i], i));
  table_t bulk, one_by_one;
  bulk.assign(entries);
  for (std::uint32_t i = 0; i < keys.size(); ++i) one_by_one.insert(keys[i], i, key_of);
  CHECK(bulk.size() == keys.size());
  CHECK(4 * bulk.size() <= 3 * bulk.capacity());
  std::size_t wrong = 0, false_hits = 0;
  for (std::uint32_t i = 0; i < keys.size(); ++i)
    wrong += bulk.find(keys[i], key_of) != i || one_by_one.find(keys[i], key_of) != i;
  for (int i = 0; i < 20000; ++i)
    false_hits += bulk.find(table_t::key(4000 + static_cast<std::uint32_t>(rng() % 100), 7), key_of) !=
                  table_t::not_found;
  CHECK(wrong == 0);
  CHECK(false_hits == 0);
  // Erase all but every 16th entry: the rest stays findable across backward shifts and shrinks.
  for (std::uint32_t i = 0; i < keys.size(); ++i)
    if (i % 16 != 0) CHECK(bulk.erase(keys[i], key_of));
  CHECK(bulk.size() == (keys.size() + 15) / 16);
  CHECK(bulk.capacity() < 16384);
  std::size_t lost = 0, kept = 0;
  for (std::uint32_t i = 0; i < keys.size(); ++i) {
    const std::uint32_t found = bulk.find(keys[i], key_of);
    lost += i % 16 == 0 && found != i;
    kept += i % 16 != 0 && found != table_t::not_found;
  }
  CHECK(lost == 0);
  CHECK(kept == 0);
  CHECK_FALSE(bulk.erase(keys[1], key_of));
  std::size_t visited = 0;
  bulk.for_each([&](std::uint32_t v) { visited += v % 16 == 0; });
  CHECK(visited == bulk.size());
  bulk.assign({});
  CHECK(bulk.empty());
}

TEST_CASE("build: a large grid with holes and a flipped strip counts boundary and seams as the soup says") {
  // 300 x 300 quads, every 7th removed (holes), the faces of one row wound the other way.
  const std::uint32_t n = 300;
  cellforge::polygon_soup<glm::dvec3> s;
  for (std::uint32_t j = 0; j <= n; ++j)
    for (std::uint32_t i = 0; i <= n; ++i) s.points.push_back({i, j, 0});
  auto id = [&](std::uint32_t i, std::uint32_t j) { return j * (n + 1) + i; };
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;  // undirected edge -> faces
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t i = 0; i < n; ++i) {
      if ((j * n + i) % 7 == 3) continue;
      std::vector<std::uint32_t> f{id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      if (j == 150) std::reverse(f.begin(), f.end());
      for (std::size_t k = 0; k < 4; ++k) {
        const std::uint32_t a = f[k], b = f[(k + 1) % 4];
        ++uses[{std::min(a, b), std::max(a, b)}];
        ++directed[{a, b}];
      }
      s.add_face(f);
    }
  std::size_t boundary = 0, flipped = 0;
  for (const auto& [e, count] : uses) {
    boundary += count == 1;
    flipped += count == 2 && (directed[{e.first, e.second}] == 2 || directed[{e.second, e.first}] == 2);
  }
  cellforge::build_report report;
  const auto m = make_mesh(s, &report);
  REQUIRE_VALID(m);
  CHECK(report.boundary_edges == boundary);
  CHECK(m.num_boundary_edges() == boundary);
  CHECK(report.flipped_edges == flipped);
  CHECK(flipped > 400);  // both sides of the strip, less the edges at holes
  CHECK(m.num_faces() == s.num_faces());
  // Every boundary half-edge is found again by its end points (the bulk-built table).
  std::size_t missing = 0;
  for (const auto& [e, count] : uses)
    if (count == 1 && !m.find_unlinked(vertex_handle(e.first), vertex_handle(e.second)).is_valid() &&
        !m.find_unlinked(vertex_handle(e.second), vertex_handle(e.first)).is_valid())
      ++missing;
  CHECK(missing == 0);
}

}  // namespace halfedge_mesh_tests
