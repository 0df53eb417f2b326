// Loop subdivision: positions and connectivity against an independent soup-based reference
// (std::map edge lookup), counts, boundary rules, non-orientable surfaces, point types,
// user properties, and every way the input can be refused.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/loop_subdivision.hpp"
#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/detail/mesh_access.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "mesh_fixtures.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace loop_subdivision_tests {

namespace {

using cellforge::halfedge_mesh;
using cellforge::loop_boundary;
using cellforge::loop_subdivision_options;
using cellforge::loop_weights;
using cellforge::surface_mesh;
using soup = fixtures::soup;
using u32 = std::uint32_t;
using key = std::pair<u32, u32>;

key ekey(u32 a, u32 b) { return {std::min(a, b), std::max(a, b)}; }

// ---------------------------------------------------------------- the reference

struct reference {
  soup out;
  std::map<key, u32> edge_vertex;  // parent edge -> its new vertex in `out`
};

// One Loop step written the obvious way, independently of the library: a std::map from
// each undirected edge to its opposite vertices, neighbour sets per vertex.
reference reference_loop(const soup& s, loop_weights weights = loop_weights::loop,
                         loop_boundary boundary = loop_boundary::bspline) {
  const auto nv = static_cast<u32>(s.points.size());
  std::map<key, std::vector<u32>> opposite;
  std::vector<int> faces_at(nv, 0);
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    const auto t = s.face(f);
    REQUIRE(t.size() == 3);
    for (int k = 0; k < 3; ++k) {
      opposite[ekey(t[k], t[(k + 1) % 3])].push_back(t[(k + 2) % 3]);
      ++faces_at[t[k]];
    }
  }
  reference r;
  u32 next = nv;
  for (const auto& [k, o] : opposite) r.edge_vertex[k] = next++;
  r.out.points.resize(next);

  std::vector<std::set<u32>> around(nv), boundary_around(nv);
  for (const auto& [k, o] : opposite) {
    around[k.first].insert(k.second);
    around[k.second].insert(k.first);
    if (o.size() == 1) {
      boundary_around[k.first].insert(k.second);
      boundary_around[k.second].insert(k.first);
    }
  }
  for (u32 v = 0; v < nv; ++v) {
    const glm::dvec3 p = s.points[v];
    glm::dvec3 q = p;
    if (boundary_around[v].empty() && around[v].size() >= 3) {
      const double n = static_cast<double>(around[v].size());
      double beta = 0;
      if (weights == loop_weights::warren) {
        beta = around[v].size() == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * n);
      } else {
        const double c = 3.0 / 8.0 + std::cos(2 * std::numbers::pi / n) / 4.0;
        beta = (5.0 / 8.0 - c * c) / n;
      }
      glm::dvec3 sum(0);
      for (u32 w : around[v]) sum += s.points[w];
      q = (1 - n * beta) * p + beta * sum;
    } else if (boundary_around[v].size() == 2) {
      const bool keep = boundary == loop_boundary::fixed ||
                        (boundary == loop_boundary::bspline_corners && faces_at[v] == 1);
      if (!keep) {
        glm::dvec3 sum(0);
        for (u32 w : boundary_around[v]) sum += s.points[w];
        q = 0.75 * p + 0.125 * sum;
      }
    }
    r.out.points[v] = q;
  }
  for (const auto& [k, o] : opposite) {
    const glm::dvec3 a = s.points[k.first], b = s.points[k.second];
    r.out.points[r.edge_vertex[k]] =
        o.size() == 2 ? 3.0 / 8.0 * (a + b) + (s.points[o[0]] + s.points[o[1]]) / 8.0 : (a + b) / 2.0;
  }
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    const auto t = s.face(f);
    const u32 a = t[0], b = t[1], c = t[2];
    const u32 ab = r.edge_vertex[ekey(a, b)], bc = r.edge_vertex[ekey(b, c)], ca = r.edge_vertex[ekey(c, a)];
    r.out.add_face({a, ab, ca});
    r.out.add_face({b, bc, ab});
    r.out.add_face({c, ca, bc});
    r.out.add_face({ab, bc, ca});
  }
  return r;
}

// Our vertex index -> the reference's, for one step from `before` (old vertices keep their
// index; the vertex on edge e is V + e).
std::vector<u32> index_map(const halfedge_mesh& before, const reference& ref) {
  const std::size_t nv = before.vertices_size();
  std::vector<u32> map(nv + before.edges_size());
  for (u32 v = 0; v < nv; ++v) map[v] = v;
  for (auto e : before.edges()) {
    const u32 a = before.vertex(e, 0).idx(), b = before.vertex(e, 1).idx();
    map[nv + e.idx()] = ref.edge_vertex.at(ekey(a, b));
  }
  return map;
}

// A triangle rotated to start at its smallest index (keeps its orientation).
std::array<u32, 3> canonical(u32 a, u32 b, u32 c) {
  if (b < a && b < c) return {b, c, a};
  if (c < a && c < b) return {c, a, b};
  return {a, b, c};
}

// Checks positions (to `tol`) and oriented faces of `after` against the reference.
template <class P>
void check_against(const surface_mesh<P>& after, const reference& ref, const std::vector<u32>& map,
                   double tol) {
  REQUIRE(after.num_vertices() == ref.out.points.size());
  REQUIRE(after.num_faces() == ref.out.num_faces());
  const auto pts = after.positions();
  double worst = 0;
  for (auto v : after.vertices())
    worst = std::max(worst, glm::length(cellforge::to_dvec3(pts[v]) - ref.out.points[map[v.idx()]]));
  CHECK(worst <= tol);
  std::vector<std::array<u32, 3>> ours, theirs;
  for (auto f : after.faces()) {
    std::vector<u32> vs;
    for (auto v : after.vertices_around(f)) vs.push_back(map[v.idx()]);
    REQUIRE(vs.size() == 3);
    ours.push_back(canonical(vs[0], vs[1], vs[2]));
  }
  for (std::size_t f = 0; f < ref.out.num_faces(); ++f) {
    const auto t = ref.out.face(f);
    theirs.push_back(canonical(t[0], t[1], t[2]));
  }
  std::sort(ours.begin(), ours.end());
  std::sort(theirs.begin(), theirs.end());
  CHECK(ours == theirs);  // same triangles, each with its parent's orientation
}

template <class P>
cellforge::polygon_soup<P> convert(const soup& s) {
  cellforge::polygon_soup<P> out;
  for (const auto& p : s.points) out.points.push_back(cellforge::from_dvec3<P>(p));
  out.face_offsets = s.face_offsets;
  out.face_vertices = s.face_vertices;
  return out;
}

// One level on `s`, checked against the reference; returns the subdivided mesh.
template <class P = glm::dvec3>
surface_mesh<P> one_level_checked(const soup& s, const loop_subdivision_options& o = {}, double tol = 1e-12) {
  auto m = cellforge::make_mesh(convert<P>(s));
  const auto before = m;
  loop_subdivision_options one = o;
  one.levels = 1;
  const auto r = cellforge::loop_subdivide(m, one);
  const auto v = cellforge::validate(m);
  INFO(v.message);
  REQUIRE(v.ok());
  CHECK(r.vertices_after == r.vertices_before + r.edges_before);
  CHECK(r.faces_after == 4 * r.faces_before);
  CHECK(r.edges_after == 2 * r.edges_before + 3 * r.faces_before);
  // The reference sees the same input points the mesh holds (after rounding to P).
  soup in = s;
  const auto pts = before.positions();
  for (std::size_t i = 0; i < in.points.size(); ++i)
    in.points[i] = cellforge::to_dvec3(pts[cellforge::vertex_handle(static_cast<u32>(i))]);
  const reference ref = reference_loop(in, o.weights, o.boundary);
  check_against<P>(m, ref, index_map(before, ref), tol);
  return m;
}

// ---------------------------------------------------------------- topology queries

// Whether loop_subdivide accepts a mesh of type M (false for a mesh without positions).
template <class M>
constexpr bool can_subdivide = requires(M& m) {
  cellforge::loop_subdivide(m);
};

std::int64_t euler(const halfedge_mesh& m) {
  return static_cast<std::int64_t>(m.num_vertices()) - static_cast<std::int64_t>(m.num_edges()) +
         static_cast<std::int64_t>(m.num_faces());
}

// Connected components of the faces, joined across edges.
std::size_t components(const halfedge_mesh& m) {
  std::vector<u32> parent(m.faces_size());
  for (u32 i = 0; i < parent.size(); ++i) parent[i] = i;
  auto find = [&](u32 x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (auto e : m.edges()) {
    const auto f0 = m.face(e, 0), f1 = m.face(e, 1);
    if (f0.is_valid() && f1.is_valid()) parent[find(f0.idx())] = find(f1.idx());
  }
  std::size_t n = 0;
  for (auto f : m.faces()) n += find(f.idx()) == f.idx();
  return n;
}

soup octahedron() {
  soup s;
  s.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (u32 z : {4u, 5u}) {
    const u32 ring[4] = {0, 2, 1, 3};
    for (int k = 0; k < 4; ++k) {
      if (z == 4)
        s.add_face({ring[k], ring[(k + 1) % 4], z});
      else
        s.add_face({ring[(k + 1) % 4], ring[k], z});
    }
  }
  return s;
}

std::string message_of(auto&& f) {
  try {
    f();
  } catch (const cellforge::error& e) {
    return e.what();
  }
  return "<no error>";
}

}  // namespace

// ---------------------------------------------------------------- positions and counts

TEST_CASE("one level on a tetrahedron and an octahedron matches the reference to 1e-12") {
  one_level_checked(fixtures::tetrahedron());
  one_level_checked(octahedron());
  // An irregular closed mesh with valences 3 to 7.
  one_level_checked(cellforge::sphere_with_vertices<glm::dvec3>(64));
}

TEST_CASE("Warren's weights match the reference") {
  loop_subdivision_options o;
  o.weights = loop_weights::warren;
  one_level_checked(octahedron(), o);
  one_level_checked(fixtures::torus(7, 5), o);
}

TEST_CASE("two levels on a torus match the reference, and equal two single levels") {
  const soup s = fixtures::torus(8, 6);
  auto m0 = cellforge::make_mesh(s);
  auto m1 = m0;
  cellforge::loop_subdivide(m1);
  auto m2 = m1;
  cellforge::loop_subdivide(m2);

  const reference r1 = reference_loop(s);
  const reference r2 = reference_loop(r1.out);
  const std::vector<u32> map1 = index_map(m0, r1);
  // Level 2: our vertex on an edge (a, b) of m1 is the reference's vertex on (map1[a], map1[b]).
  std::vector<u32> map2(m1.vertices_size() + m1.edges_size());
  for (u32 v = 0; v < m1.vertices_size(); ++v) map2[v] = map1[v];
  for (auto e : m1.edges())
    map2[m1.vertices_size() + e.idx()] =
        r2.edge_vertex.at(ekey(map1[m1.vertex(e, 0).idx()], map1[m1.vertex(e, 1).idx()]));
  check_against<glm::dvec3>(m2, r2, map2, 1e-12);

  auto both = m0;
  const auto r = cellforge::loop_subdivide(both, {.levels = 2});
  CHECK(cellforge::validate(both).ok());
  CHECK(r.level_ms.size() == 2);
  CHECK(r.faces_after == 16 * s.num_faces());
  const auto a = cellforge::to_soup(both), b = cellforge::to_soup(m2);
  CHECK(a.points == b.points);
  CHECK(a.face_vertices == b.face_vertices);
  CHECK(euler(both) == 0);
}

TEST_CASE("counts V' = V + E, E' = 2E + 3F, F' = 4F over three levels") {
  for (const soup& s : {fixtures::torus(5, 4), fixtures::plane(4, 3), fixtures::mobius(9, 2),
                        cellforge::icosphere<glm::dvec3>(1)}) {
    auto m = cellforge::make_mesh(s);
    std::size_t v = m.num_vertices(), e = m.num_edges(), f = m.num_faces();
    const std::int64_t chi = euler(m);
    const auto r = cellforge::loop_subdivide(m, {.levels = 3});
    for (int l = 0; l < 3; ++l) {
      v += e;
      e = 2 * e + 3 * f;
      f *= 4;
    }
    CHECK(m.num_vertices() == v);
    CHECK(m.num_edges() == e);
    CHECK(m.num_faces() == f);
    CHECK(r.vertices_after == v);
    CHECK(euler(m) == chi);
    CHECK(cellforge::validate(m).ok());
  }
}

// ---------------------------------------------------------------- boundaries

TEST_CASE("boundary rules on an open grid") {
  const soup grid = cellforge::grid_plane<glm::dvec3>(5, 4);
  for (auto rule : {loop_boundary::bspline, loop_boundary::bspline_corners, loop_boundary::fixed}) {
    loop_subdivision_options o;
    o.boundary = rule;
    auto m = one_level_checked(grid, o);
    CHECK(m.boundary_loops().size() == 1);
    CHECK(m.num_boundary_edges() == 2 * 2 * (5 + 4));
    const auto pts = m.positions();
    // A flat grid stays flat, and its straight sides stay on their lines.
    for (auto v : m.vertices()) {
      CHECK(pts[v].z == 0.0);
      CHECK(pts[v].x >= -1e-15);
      CHECK(pts[v].x <= 1 + 1e-15);
    }
    // Vertex 5 is the corner (1, 0) with a single face; vertex 0, the corner (0, 0), has two.
    const glm::dvec3 single = pts[cellforge::vertex_handle(5)], two = pts[cellforge::vertex_handle(0)];
    CHECK((single == glm::dvec3(1, 0, 0)) == (rule != loop_boundary::bspline));
    CHECK((two == glm::dvec3(0, 0, 0)) == (rule == loop_boundary::fixed));
    if (rule == loop_boundary::bspline) CHECK(glm::length(single - glm::dvec3(0.975, 0.03125, 0)) < 1e-15);
  }
}

TEST_CASE("a cylinder keeps its two boundary loops, and they are B-spline curves") {
  const soup cyl = fixtures::cylinder(8, 3);
  auto m = one_level_checked(cyl);
  CHECK(m.boundary_loops().size() == 2);
  CHECK(euler(m) == 0);
  auto m3 = cellforge::make_mesh(cyl);
  cellforge::loop_subdivide(m3, {.levels = 3});
  CHECK(cellforge::validate(m3).ok());
  CHECK(m3.boundary_loops().size() == 2);
  CHECK(m3.num_boundary_edges() == 2 * 8 * 8);
}

TEST_CASE("a vertex where two fans meet stays in place") {
  auto m = cellforge::make_mesh(fixtures::bowtie());
  const glm::dvec3 before = m.positions()[cellforge::vertex_handle(0)];
  const auto r = cellforge::loop_subdivide(m, {.levels = 2});
  CHECK(cellforge::validate(m).ok());
  CHECK(r.fixed_vertices == 2);  // the same vertex, once per level
  CHECK(m.positions()[cellforge::vertex_handle(0)] == before);
  CHECK(m.boundary_loops().size() == 2);
  CHECK(components(m) == 2);
}

// ---------------------------------------------------------------- non-orientable surfaces

TEST_CASE("Möbius strip, Klein bottle and a randomly oriented plane") {
  struct named {
    const char* name;
    soup s;
  };
  const std::vector<named> cases = {
      {"mobius (fixture)", fixtures::mobius(12, 3)},
      {"mobius (shapes)", cellforge::mobius_strip<glm::dvec3>(16, 4)},
      {"klein (fixture)", fixtures::klein(8, 6)},
      {"klein (shapes)", cellforge::klein_bottle<glm::dvec3>(10, 8)},
      {"random plane (fixture)", fixtures::randomly_flipped(fixtures::plane(7, 6), 42)},
      {"random plane (shapes)", cellforge::random_orientation_plane<glm::dvec3>(8, 8, 7)},
      {"random torus", fixtures::randomly_flipped(fixtures::torus(6, 5), 3)},
  };
  for (const named& c : cases) {
    INFO(c.name);
    // One level against the reference: positions, and every child keeps its parent's orientation.
    one_level_checked(c.s);

    auto m = cellforge::make_mesh(c.s);
    const std::int64_t chi = euler(m);
    const std::size_t loops = m.boundary_loops().size(), comps = components(m);
    std::size_t flipped = m.num_flipped_edges();
    REQUIRE(flipped > 0);
    for (int level = 0; level < 3; ++level) {
      const auto r = cellforge::loop_subdivide(m);
      const auto v = cellforge::validate(m);
      INFO(v.message);
      REQUIRE(v.ok());
      flipped *= 2;
      CHECK(m.num_flipped_edges() == flipped);
      CHECK(r.flipped_edges_after == flipped);
      CHECK(euler(m) == chi);
      CHECK(components(m) == comps);
      CHECK(m.boundary_loops().size() == loops);
      CHECK(r.fixed_vertices == 0);
    }
    // Several levels in one call give the same mesh.
    auto once = cellforge::make_mesh(c.s);
    cellforge::loop_subdivide(once, {.levels = 3});
    CHECK(cellforge::to_soup(once).face_vertices == cellforge::to_soup(m).face_vertices);
  }
}

// ---------------------------------------------------------------- point types

TEST_CASE_TEMPLATE("point types", P, glm::dvec3, std::array<float, 3>, test_support::user_point) {
  const double tol = std::is_same_v<cellforge::scalar_t<P>, float> ? 2e-6 : 1e-12;
  one_level_checked<P>(octahedron(), {}, tol);
  one_level_checked<P>(fixtures::mobius(10, 2), {}, tol);
  auto m = cellforge::make_mesh(convert<P>(fixtures::plane(3, 3)));
  const auto r = cellforge::loop_subdivide(m, {.levels = 2});
  CHECK(r.faces_after == 16 * 18);
  CHECK(cellforge::validate(m).ok());
  CHECK(m.positions().vector().size() == m.vertices_size());
}

// ---------------------------------------------------------------- properties

TEST_CASE("user vertex properties: interpolated when opted in, defaulted otherwise") {
  const soup s = fixtures::plane(4, 4);
  auto m = cellforge::make_mesh(s);
  const auto before = m;
  auto temp = m.add_vertex_property<double>("v:temperature", -1.0);
  auto shade = m.add_vertex_property<glm::vec3>("v:shade");
  auto label = m.add_vertex_property<int>("v:label", 7);
  auto fp = m.add_face_property<int>("f:region", 0);
  auto ep = m.add_edge_property<float>("e:weight", 2.5f);
  const auto pts0 = m.positions();
  for (auto v : m.vertices()) {
    temp[v] = 10.0 * pts0[v].x + pts0[v].y * pts0[v].y;
    shade[v] = glm::vec3(pts0[v]);
    label[v] = static_cast<int>(v.idx());
  }
  for (auto f : m.faces()) fp[f] = 5;
  for (auto e : m.edges()) ep[e] = 9.f;
  const std::vector<double> t0 = temp.vector();

  loop_subdivision_options o;
  o.interpolate = {{"v:temperature"}, {"v:shade", cellforge::loop_property_rule::loop}};
  cellforge::loop_subdivide(m, o);
  REQUIRE(cellforge::validate(m).ok());
  temp = m.get_vertex_property<double>("v:temperature");
  shade = m.get_vertex_property<glm::vec3>("v:shade");
  label = m.get_vertex_property<int>("v:label");
  const auto pts = m.positions();
  const std::size_t nv = before.vertices_size();
  for (auto v : before.vertices()) {
    CHECK(temp[v] == t0[v.idx()]);                 // linear: old vertices keep their value
    CHECK(label[v] == static_cast<int>(v.idx()));  // not opted in: kept on old vertices
  }
  for (auto e : before.edges()) {
    const cellforge::vertex_handle mid(static_cast<u32>(nv + e.idx()));
    CHECK(temp[mid] ==
          doctest::Approx(0.5 * (t0[before.vertex(e, 0).idx()] + t0[before.vertex(e, 1).idx()])));
    CHECK(label[mid] == 7);  // not opted in: the default on new vertices
  }
  // The loop rule applies the position masks: a copy of the positions moves with them.
  for (auto v : m.vertices()) CHECK(glm::length(glm::dvec3(shade[v]) - pts[v]) < 1e-5);
  for (auto f : m.faces()) CHECK(m.get_face_property<int>("f:region")[f] == 0);
  for (auto e : m.edges()) CHECK(m.get_edge_property<float>("e:weight")[e] == 2.5f);
}

TEST_CASE("property options that cannot be honoured are refused before anything changes") {
  auto m = cellforge::make_mesh(fixtures::tetrahedron());
  m.add_vertex_property<int>("v:label");
  m.add_vertex_property<double>("v:t");
  auto refused = [&](std::vector<cellforge::loop_property> props, const char* needle) {
    loop_subdivision_options o;
    o.interpolate = std::move(props);
    const std::string msg = message_of([&] { cellforge::loop_subdivide(m, o); });
    INFO(msg);
    CHECK(msg.find(needle) != std::string::npos);
    CHECK(m.num_faces() == 4);
  };
  refused({{"v:label"}}, "'v:label' has type");
  refused({{"v:missing"}}, "no vertex property named 'v:missing'");
  refused({{"v:t"}, {"v:t"}}, "listed twice");
  refused({{"v:point"}}, "subdivided anyway");
  CHECK(cellforge::validate(m).ok());
}

// ---------------------------------------------------------------- refusals

TEST_CASE("refuses quads, NaN, bad options and corrupted meshes with clear errors") {
  SUBCASE("a quad names the face") {
    soup mixed = fixtures::plane(2, 1);
    mixed.points.push_back({0, 2, 0});
    mixed.points.push_back({1, 2, 0});
    mixed.add_face({3, 4, 7, 6});
    auto m = cellforge::make_mesh(mixed);
    const std::string msg = message_of([&] { cellforge::loop_subdivide(m); });
    CHECK(msg.find("face 4 has 4 vertices") != std::string::npos);
    CHECK(msg.find("triangulate") != std::string::npos);
    CHECK(m.num_faces() == 5);
    CHECK(cellforge::validate(m).ok());
    // With removed elements the face keeps the handle the caller knows, and nothing is collected.
    m.remove_face(cellforge::face_handle(0));
    const std::string msg2 = message_of([&] { cellforge::loop_subdivide(m); });
    CHECK(msg2.find("face 4 has 4 vertices") != std::string::npos);
    CHECK(m.has_garbage());
    auto cube = cellforge::make_mesh(fixtures::cube());
    CHECK(message_of([&] { cellforge::loop_subdivide(cube); }).find("face 0 has 4 vertices") !=
          std::string::npos);
  }
  SUBCASE("non-finite and huge coordinates name the vertex") {
    soup s = fixtures::tetrahedron();
    s.points[2].y = std::numeric_limits<double>::quiet_NaN();
    auto m = cellforge::make_mesh(s);
    CHECK(message_of([&] { cellforge::loop_subdivide(m); }).find("vertex 2") != std::string::npos);
    s.points[2].y = std::numeric_limits<double>::infinity();
    m = cellforge::make_mesh(s);
    CHECK(message_of([&] { cellforge::loop_subdivide(m); }).find("not finite") != std::string::npos);
    s.points[2].y = 1e300;
    m = cellforge::make_mesh(s);
    CHECK(message_of([&] { cellforge::loop_subdivide(m); }).find("too large") != std::string::npos);
    CHECK(m.num_vertices() == 4);
    // A removed vertex's position is not looked at.
    s.points.push_back({std::numeric_limits<double>::quiet_NaN(), 0, 0});
    s.points[2].y = 1;
    m = cellforge::make_mesh(s);
    m.remove_vertex(cellforge::vertex_handle(4));
    CHECK(cellforge::loop_subdivide(m).faces_after == 16);
    CHECK(cellforge::validate(m).ok());
    s.points.pop_back();
    // Large but allowed coordinates stay finite through several levels.
    s.points[2].y = 1e280;
    m = cellforge::make_mesh(s);
    cellforge::loop_subdivide(m, {.levels = 3});
    for (const auto& p : m.positions().vector()) CHECK(std::isfinite(p.y));
  }
  SUBCASE("levels") {
    auto m = cellforge::make_mesh(fixtures::torus());
    const auto before = cellforge::to_soup(m);
    const auto r = cellforge::loop_subdivide(m, {.levels = 0});
    CHECK(r.faces_after == r.faces_before);
    CHECK(r.level_ms.empty());
    CHECK(cellforge::to_soup(m).points == before.points);
    CHECK(cellforge::to_soup(m).face_vertices == before.face_vertices);
    CHECK(message_of([&] { cellforge::loop_subdivide(m, {.levels = -1}); }).find("at least 0") !=
          std::string::npos);
    // 96 faces * 4^14 > 2^32: refused before any allocation (it would need terabytes).
    const std::string msg = message_of([&] { cellforge::loop_subdivide(m, {.levels = 14}); });
    CHECK(msg.find("32-bit") != std::string::npos);
    CHECK(message_of([&] { cellforge::loop_subdivide(m, {.levels = 1000000}); }).find("32-bit") !=
          std::string::npos);
    // 96 * 4^9 = 25M faces fit; 4^10 = 100M exceed the default memory limit, refused up front.
    const std::string big = message_of([&] { cellforge::loop_subdivide(m, {.levels = 10}); });
    CHECK(big.find("10 levels would make 100663296 faces") != std::string::npos);
    CHECK(big.find("loop_subdivision_options::max_faces") != std::string::npos);
    CHECK(message_of([&] {
            cellforge::loop_subdivide(m, {.levels = 3, .max_faces = 1000});
          }).find("6144 faces") != std::string::npos);
    CHECK(cellforge::to_soup(m).face_vertices == before.face_vertices);
  }
  SUBCASE("a mesh without positions is refused at compile time") {
    // What used to be a run-time "no vertex positions" error is now a type error.
    CHECK_FALSE(can_subdivide<halfedge_mesh>);
    CHECK(can_subdivide<surface_mesh<glm::dvec3>>);
    CHECK(can_subdivide<surface_mesh<glm::vec3>>);
  }
  SUBCASE("bad enum values") {
    auto m = cellforge::make_mesh(fixtures::tetrahedron());
    loop_subdivision_options o;
    o.boundary = static_cast<loop_boundary>(9);
    CHECK(message_of([&] { cellforge::loop_subdivide(m, o); }).find("boundary") != std::string::npos);
    o = {};
    o.weights = static_cast<loop_weights>(9);
    CHECK(message_of([&] { cellforge::loop_subdivide(m, o); }).find("weights") != std::string::npos);
  }
  SUBCASE("corrupted records") {
    using access = cellforge::detail::mesh_access;
    auto m = cellforge::make_mesh(fixtures::torus(4, 3));
    auto a = m, b = m, c = m, d = m;
    access::records(a)[access::face_anchors(a)[3]].head = 999;  // a vertex that does not exist
    access::face_anchors(b)[2] = access::face_anchors(b)[5];    // a half-edge of another face
    access::records(c)[access::face_anchors(c)[1]].next = 1u << 30;
    const std::uint32_t h = access::face_anchors(d)[0];
    access::records(d)[h ^ 1u].head = access::records(d)[access::records(d)[h].next].head;  // twins disagree
    CHECK(message_of([&] { cellforge::loop_subdivide(a); }).find("corrupted") != std::string::npos);
    CHECK(message_of([&] { cellforge::loop_subdivide(b); }).find("face 2") != std::string::npos);
    CHECK(message_of([&] { cellforge::loop_subdivide(c); }).find("face 1") != std::string::npos);
    CHECK(message_of([&] { cellforge::loop_subdivide(d); }).find("corrupted") != std::string::npos);
    CHECK(a.num_faces() == m.num_faces());
  }
}

// ---------------------------------------------------------------- the rest of the API

TEST_CASE("loop_subdivided returns a copy; removed elements are collected first") {
  auto m = cellforge::make_mesh(fixtures::torus(6, 4));
  cellforge::loop_subdivision_result r;
  const auto s = cellforge::loop_subdivided(m, {.levels = 2}, &r);
  CHECK(m.num_faces() == 48);
  CHECK(s.num_faces() == 48 * 16);
  CHECK(r.faces_after == s.num_faces());
  CHECK(r.milliseconds >= 0);

  m.remove_face(cellforge::face_handle(4));  // the two triangles of one quad: one hole
  m.remove_face(cellforge::face_handle(5));
  CHECK(m.has_garbage());
  const auto r2 = cellforge::loop_subdivide(m);
  CHECK(r2.faces_before == 46);
  CHECK(m.num_faces() == 46 * 4);
  CHECK(cellforge::validate(m).ok());
  CHECK(m.boundary_loops().size() == 1);
}

TEST_CASE("isolated vertices and a mesh without faces") {
  soup s = fixtures::tetrahedron();
  s.points.push_back({5, 5, 5});
  auto m = cellforge::make_mesh(s);
  cellforge::loop_subdivide(m, {.levels = 2});
  CHECK(cellforge::validate(m).ok());
  CHECK(m.positions()[cellforge::vertex_handle(4)] == glm::dvec3(5, 5, 5));
  CHECK(m.is_isolated(cellforge::vertex_handle(4)));

  soup empty;
  empty.points = {{1, 2, 3}};
  auto e = cellforge::make_mesh(empty);
  const auto r = cellforge::loop_subdivide(e, {.levels = 1000});
  CHECK(r.vertices_after == 1);
  CHECK(r.faces_after == 0);
}

// ---------------------------------------------------------------- derived state without finish()

// A closed child gets its vertex anchors, flipped count and (empty) unlinked table in closed
// form instead of from mesh_access::finish(); an open one still goes through finish(). Both
// must leave exactly the state finish() derives from the records alone.
TEST_CASE("closed-form anchors and flipped count agree with finish(), closed and open") {
  struct named {
    const char* name;
    soup s;
    bool closed;
  };
  soup with_isolated = fixtures::torus(6, 5);
  with_isolated.points.push_back({7, 7, 7});
  const std::vector<named> cases = {
      {"octahedron (closed, orientable)", octahedron(), true},
      {"torus (closed, orientable)", fixtures::torus(8, 6), true},
      {"torus + isolated vertex", with_isolated, true},
      {"klein bottle (closed, non-orientable)", fixtures::klein(8, 6), true},
      {"klein bottle (shapes)", cellforge::klein_bottle<glm::dvec3>(10, 8), true},
      {"randomly flipped torus", fixtures::randomly_flipped(fixtures::torus(6, 5), 11), true},
      {"plane (open)", fixtures::plane(5, 4), false},
      {"mobius (open, non-orientable)", fixtures::mobius(12, 3), false},
  };
  for (const named& c : cases) {
    for (int levels = 1; levels <= 2; ++levels) {
      INFO(c.name << ", " << levels << " level(s)");
      auto m = cellforge::make_mesh(c.s);
      REQUIRE(m.is_closed() == c.closed);
      const auto r = cellforge::loop_subdivide(m, {.levels = levels});
      const auto v = cellforge::validate(m);
      INFO(v.message);
      REQUIRE(v.ok());
      CHECK(m.is_closed() == c.closed);

      // The flipped count, recounted edge by edge.
      std::size_t flipped = 0;
      for (const auto e : m.edges()) flipped += m.is_flipped(e) ? 1 : 0;
      CHECK(m.num_flipped_edges() == flipped);
      CHECK(r.flipped_edges_after == flipped);
      CHECK(m.unlinked_halfedges().size() == m.num_boundary_edges());

      // Anchors: interior vertices end a face half-edge at them; isolated ones have none.
      for (const auto vh : m.vertices()) {
        if (m.is_isolated(vh)) {
          CHECK(vh.idx() == c.s.points.size() - 1);  // only the one we added
          continue;
        }
        const auto a = m.anchor(vh);
        if (!m.is_boundary(vh)) {
          CHECK(!m.is_boundary(a));
          CHECK((m.head(a) == vh || m.tail(a) == vh));
        }
      }

      // finish() from the records alone derives the same state.
      auto again = m;
      cellforge::detail::mesh_access::finish(again);
      CHECK(cellforge::validate(again).ok());
      CHECK(again.num_flipped_edges() == m.num_flipped_edges());
      CHECK(again.num_boundary_edges() == m.num_boundary_edges());
      for (const auto vh : m.vertices()) {
        CHECK(again.is_isolated(vh) == m.is_isolated(vh));
        CHECK(again.is_boundary(vh) == m.is_boundary(vh));
        CHECK(again.valence(vh) == m.valence(vh));
      }
    }
  }
}

TEST_CASE("reserve_large: a plain reserve whose huge-page hint changes nothing visible") {
  std::vector<std::uint32_t> big, small;
  cellforge::detail::reserve_large(big, std::size_t{3} << 20);  // 12 MB: hinted on Linux
  cellforge::detail::reserve_large(small, 10);
  CHECK(big.empty());
  CHECK(big.capacity() >= (std::size_t{3} << 20));
  CHECK(small.capacity() >= 10);
  big.resize(std::size_t{3} << 20, 7u);
  CHECK(big.front() == 7u);
  CHECK(big.back() == 7u);
}

}  // namespace loop_subdivision_tests
