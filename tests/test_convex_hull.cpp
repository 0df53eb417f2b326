// 3D convex hull: every hull is checked independently of the hull's code paths — every input
// point on the inner side of every face (with __int128 arithmetic written here on integer
// inputs), every edge convex, every vertex a corner, the mesh valid, closed, outward, of
// Euler characteristic 2 — on random, lattice, duplicate, coplanar, collinear and spherical
// inputs, over three point types.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/convex_hull.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace convex_hull_tests {

namespace {

using cellforge::convex_hull;
using cellforge::convex_hull_options;
using cellforge::convex_hull_report;
using cellforge::face_handle;
using cellforge::halfedge_mesh;
using cellforge::surface_mesh;
using cellforge::vertex_handle;

__extension__ typedef __int128 i128;

// orient3d on integer-valued doubles with __int128: the test's own exact reference.
int orient_int(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
  auto I = [](double v) {  // integer inputs only (the tests below make sure)
    return static_cast<i128>(static_cast<std::int64_t>(v));
  };
  const i128 ux = I(b.x) - I(a.x), uy = I(b.y) - I(a.y), uz = I(b.z) - I(a.z);
  const i128 vx = I(c.x) - I(a.x), vy = I(c.y) - I(a.y), vz = I(c.z) - I(a.z);
  const i128 wx = I(d.x) - I(a.x), wy = I(d.y) - I(a.y), wz = I(d.z) - I(a.z);
  const i128 det = wx * (uy * vz - uz * vy) + wy * (uz * vx - ux * vz) + wz * (ux * vy - uy * vx);
  return det > 0 ? 1 : det < 0 ? -1 : 0;
}

enum class reference { int128, predicate };

// Every check of a 3D hull; `sample_faces` limits the all-points-against-a-face test.
template <class P>
void check_hull(const std::vector<P>& input, const surface_mesh<P>& m, reference ref,
                std::size_t sample_faces = std::numeric_limits<std::size_t>::max()) {
  const auto v = cellforge::validate(m);
  INFO(v.message);
  REQUIRE(v.ok());
  REQUIRE(m.is_closed());
  REQUIRE(m.is_consistently_oriented());
  REQUIRE(static_cast<long>(m.num_vertices()) - static_cast<long>(m.num_edges()) +
              static_cast<long>(m.num_faces()) ==
          2);
  const auto pos = m.positions();
  const auto index = m.template get_vertex_property<std::uint32_t>(cellforge::input_index_property_name);
  REQUIRE(index);
  std::vector<glm::dvec3> pts;
  for (const P& p : input) pts.push_back(cellforge::to_dvec3(p));
  auto at = [&](vertex_handle h) { return cellforge::to_dvec3(pos[h]); };
  auto orient = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
    return ref == reference::int128 ? orient_int(a, b, c, d) : cellforge::orient3d(a, b, c, d);
  };
  // Inner loops count failures instead of asserting each of millions of facts.
  std::size_t bad_vertices = 0, bad_faces = 0, concave_edges = 0, non_corners = 0;
  std::set<std::uint32_t> distinct;
  for (vertex_handle h : m.vertices()) {
    if (index[h] >= input.size() || at(h) != pts[index[h]]) {  // positions are the input's own values
      ++bad_vertices;
      continue;
    }
    distinct.insert(index[h]);
  }
  CHECK(bad_vertices == 0);
  CHECK(distinct.size() == m.num_vertices());

  // Faces (all, or a sample): planar, strictly convex polygons; every input point on the
  // inner side or on the plane.
  std::size_t checked = 0, outside = 0;
  const std::size_t stride = std::max<std::size_t>(1, m.num_faces() / std::min(sample_faces, m.num_faces()));
  std::size_t fi = 0;
  for (face_handle f : m.faces()) {
    if (fi++ % stride != 0) continue;
    std::vector<glm::dvec3> c;
    for (vertex_handle h : m.vertices_around(f)) c.push_back(at(h));
    bool ok = c.size() >= 3;
    for (std::size_t i = 0; ok && i < c.size(); ++i) {  // planar and strictly convex
      const glm::dvec3 &a = c[i], &b = c[(i + 1) % c.size()], &d = c[(i + 2) % c.size()];
      ok = orient(c[0], c[1], c[2], c[i]) == 0 &&
           glm::dot(glm::cross(b - a, d - b), glm::cross(c[1] - c[0], c[2] - c[1])) > 0;
    }
    bad_faces += !ok;
    ++checked;
    for (const glm::dvec3& p : pts) outside += orient(c[0], c[1], c[2], p) > 0;
  }
  CHECK(checked > 0);
  CHECK(bad_faces == 0);
  CHECK(outside == 0);

  // Edges: the two faces meet convexly; vertices: at least three creases (corners only).
  std::vector<int> creases(m.vertices_size(), 0);
  for (auto e : m.edges()) {
    const auto h0 = halfedge_mesh::halfedge(e, 0), h1 = halfedge_mesh::halfedge(e, 1);
    const glm::dvec3 a = at(m.tail(h0)), b = at(m.head(h0));
    const glm::dvec3 c0 = at(m.head(m.next(h0))), c1 = at(m.head(m.next(h1)));
    const int s = orient(a, b, c0, c1);
    concave_edges += s > 0;
    if (s < 0) {
      ++creases[m.tail(h0).idx()];
      ++creases[m.head(h0).idx()];
    }
  }
  for (vertex_handle h : m.vertices()) non_corners += creases[h.idx()] < 3;
  CHECK(concave_edges == 0);
  CHECK(non_corners == 0);
}

std::vector<glm::dvec3> lattice(int n, double scale = 1.0) {
  std::vector<glm::dvec3> p;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) p.push_back(scale * glm::dvec3(i, j, k));
  return p;
}

std::vector<glm::dvec3> random_sphere(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::vector<glm::dvec3> p(n);
  for (auto& q : p) {
    q = {g(rng), g(rng), g(rng)};
    q /= glm::length(q);
  }
  return p;
}

}  // namespace

TEST_CASE("hull of random integer points in a ball, checked with __int128") {
  std::mt19937_64 rng(1);
  std::uniform_int_distribution<int> c(-1000, 1000);
  std::vector<glm::dvec3> pts;
  while (pts.size() < 600) {
    const glm::dvec3 p(c(rng), c(rng), c(rng));
    if (glm::dot(p, p) <= 1e6) pts.push_back(p);
  }
  convex_hull_report report;
  const auto m = convex_hull(pts, {}, &report);
  check_hull(pts, m, reference::int128);
  CHECK(report.dimension == 3);
  CHECK(report.input_points == pts.size());
  CHECK(report.vertices == m.num_vertices());
  CHECK(report.faces == m.num_faces());
  CHECK(report.faces == 2 * report.vertices - 4);  // triangles of a closed sphere
  CHECK(report.vertices > 20);
}

TEST_CASE("the 10 x 10 x 10 lattice: the cube with coplanar points on every face") {
  const auto pts = lattice(10);
  convex_hull_report report;
  const auto m = convex_hull(pts, {}, &report);
  check_hull(pts, m, reference::int128);
  CHECK(m.num_vertices() == 8);
  CHECK(m.num_faces() == 12);
  CHECK(report.exact_evaluations > 0);  // lattices are full of exact zeros

  const auto quads = convex_hull(pts, {.merge_coplanar = true});
  check_hull(pts, quads, reference::int128);
  CHECK(quads.num_vertices() == 8);
  CHECK(quads.num_faces() == 6);
  for (face_handle f : quads.faces()) CHECK(quads.valence(f) == 4);

  // The same at tiny and huge scales (exact powers of two keep the lattice exact).
  for (const double s : {0x1p-1000, 0x1p-30, 0x1p900}) {
    const auto scaled = convex_hull(lattice(6, s), {.merge_coplanar = true});
    CHECK(cellforge::validate(scaled).ok());
    CHECK(scaled.num_vertices() == 8);
    CHECK(scaled.num_faces() == 6);
  }
}

TEST_CASE("many duplicates and points inside a tetrahedron") {
  std::mt19937_64 rng(2);
  const std::vector<glm::dvec3> corners{{0, 0, 0}, {60, 0, 0}, {0, 60, 0}, {0, 0, 60}};
  std::vector<glm::dvec3> pts;
  std::uniform_int_distribution<int> pick(0, 3), c(0, 20);
  for (int i = 0; i < 3000; ++i)
    pts.push_back(i % 3 == 0 ? corners[static_cast<std::size_t>(pick(rng))]
                             : glm::dvec3(c(rng), c(rng), c(rng)));
  for (const auto& q : corners) pts.push_back(q);
  const auto m = convex_hull(pts);
  check_hull(pts, m, reference::int128);
  CHECK(m.num_vertices() == 4);
  CHECK(m.num_faces() == 4);
  // Each corner is one of its duplicates.
  const auto pos = m.positions();
  std::set<std::array<double, 3>> got;
  for (vertex_handle v : m.vertices()) got.insert({pos[v].x, pos[v].y, pos[v].z});
  CHECK(got.size() == 4);
}

TEST_CASE("points on the faces and edges of an octahedron are not corners") {
  // An octahedron with many points on its facets and edges, shuffled so that some are
  // inserted before the corners around them.
  std::vector<glm::dvec3> pts;
  const int r = 12;
  for (int x = -r; x <= r; ++x)
    for (int y = -r; y <= r; ++y)
      for (int z = -r; z <= r; ++z)
        if (const int s = std::abs(x) + std::abs(y) + std::abs(z); s == r || (s < r && s % 5 == 0))
          pts.push_back({x, y, z});
  std::shuffle(pts.begin(), pts.end(), std::mt19937_64(4));
  convex_hull_report report;
  const auto m = convex_hull(pts, {}, &report);
  check_hull(pts, m, reference::int128);
  CHECK(m.num_vertices() == 6);
  CHECK(m.num_faces() == 8);
  const auto merged = convex_hull(pts, {.merge_coplanar = true});
  CHECK(merged.num_faces() == 8);
}

TEST_CASE("coplanar input gives a flat hull: the polygon twice, back to back") {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> c(-50, 50);
  std::vector<glm::dvec3> pts;
  for (int i = 0; i < 500; ++i) {
    const double x = c(rng), y = c(rng);
    pts.push_back({x, y, 2 * x - 3 * y + 7});  // the plane z = 2x - 3y + 7
  }
  convex_hull_report report;
  const auto m = convex_hull(pts, {}, &report);
  CHECK(report.dimension == 2);
  CHECK(cellforge::validate(m).ok());
  CHECK(m.is_closed());
  CHECK(m.is_consistently_oriented());
  const std::size_t k = m.num_vertices();
  CHECK(k >= 3);
  CHECK(m.num_faces() == 2 * (k - 2));
  // The polygon is the 2D hull: every point on the inner side of every boundary edge.
  const auto poly = convex_hull(pts, {.merge_coplanar = true});
  REQUIRE(poly.num_faces() == 2);
  const auto pos = poly.positions();
  const face_handle top = *poly.faces().begin();
  std::vector<glm::dvec3> ring;
  for (vertex_handle v : poly.vertices_around(top)) ring.push_back(pos[v]);
  CHECK(ring.size() == k);
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const glm::dvec3 a = ring[i], b = ring[(i + 1) % ring.size()], nxt = ring[(i + 2) % ring.size()];
    const int turn = cellforge::orient2d(a.x, a.y, b.x, b.y, nxt.x, nxt.y);
    for (const auto& p : pts) CHECK(cellforge::orient2d(a.x, a.y, b.x, b.y, p.x, p.y) * turn >= 0);
    CHECK(turn != 0);  // no collinear vertex on the polygon
  }
  CHECK_THROWS_AS(convex_hull(pts, {.allow_degenerate = false}), cellforge::error);
}

TEST_CASE("points on a circle: flat when exactly coplanar, a thin solid when tilted") {
  std::vector<glm::dvec3> flat, tilted;
  const int n = 64;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * i / n;
    flat.push_back({std::cos(t), std::sin(t), 0.25});
    tilted.push_back({std::cos(t), std::sin(t) * 0.6, std::sin(t) * 0.8});
  }
  convex_hull_report report;
  const auto m = convex_hull(flat, {}, &report);
  CHECK(report.dimension == 2);
  CHECK(m.num_vertices() == static_cast<std::size_t>(n));
  const auto t = convex_hull(tilted, {}, &report);
  CHECK(cellforge::validate(t).ok());
  if (report.dimension == 3) check_hull(tilted, t, reference::predicate);
}

TEST_CASE("collinear, single-point, tiny and empty inputs") {
  convex_hull_report report;
  std::vector<glm::dvec3> line;
  for (int i = 0; i < 50; ++i) line.push_back({3 * i % 17, 2 * (3 * i % 17), -(3 * i % 17)});
  auto m = convex_hull(line, {}, &report);
  CHECK(report.dimension == 1);
  CHECK(m.num_vertices() == 2);
  CHECK(m.num_faces() == 0);
  const auto pos = m.positions();
  std::set<double> xs;
  for (vertex_handle v : m.vertices()) xs.insert(pos[v].x);
  CHECK(xs == std::set<double>{0.0, 16.0});  // the segment's two ends

  m = convex_hull(std::vector<glm::dvec3>(10, glm::dvec3(1, 2, 3)), {}, &report);
  CHECK(report.dimension == 0);
  CHECK(m.num_vertices() == 1);

  m = convex_hull(std::vector<glm::dvec3>{}, {}, &report);
  CHECK(report.dimension == -1);
  CHECK(m.num_vertices() == 0);

  m = convex_hull(std::vector<glm::dvec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, &report);
  CHECK(report.dimension == 2);
  CHECK(m.num_faces() == 2);
  CHECK(cellforge::validate(m).ok());

  const std::vector<glm::dvec3> tet{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m = convex_hull(tet, {}, &report);
  check_hull(tet, m, reference::int128);
  CHECK(m.num_faces() == 4);

  CHECK_THROWS_AS(convex_hull(line, {.allow_degenerate = false}), cellforge::error);
  CHECK_THROWS_AS(convex_hull(std::vector<glm::dvec3>{}, {.allow_degenerate = false}), cellforge::error);
}

TEST_CASE("NaN and infinite coordinates are rejected") {
  std::vector<glm::dvec3> pts = lattice(3);
  pts[5].y = std::numeric_limits<double>::quiet_NaN();
  try {
    convex_hull(pts);
    FAIL("no error");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::invalid_input);
    CHECK(std::string(e.what()).find("point 5") != std::string::npos);
  }
  pts[5].y = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(convex_hull(pts), cellforge::error);
}

TEST_CASE("points on a sphere: every point is a corner (the seed's special case)") {
  const auto small = random_sphere(2000, 5);
  convex_hull_report report;
  auto m = convex_hull(small, {}, &report);
  check_hull(small, m, reference::predicate);
  CHECK(m.num_vertices() == small.size());

  const auto large = random_sphere(100000, 6);
  m = convex_hull(large, {}, &report);  // automatic: the sample says insertion with walks
  check_hull(large, m, reference::predicate, 4);
  CHECK(m.num_vertices() == large.size());
  CHECK(report.faces == 2 * large.size() - 4);
}

TEST_CASE("cross-sections on a sphere: coplanar rings stay, and merge into cap polygons") {
  // Rings of 24 points at heights z = ±0.5 (exactly coplanar) plus scattered points: as in
  // seed 001's tube branches, every point lies on the sphere and must be a hull vertex.
  std::vector<glm::dvec3> pts;
  for (const double z : {-0.5, 0.5})
    for (int i = 0; i < 24; ++i) {
      const double t = 2 * std::numbers::pi * i / 24, r = std::sqrt(1 - z * z);
      pts.push_back({r * std::cos(t), r * std::sin(t), z});
    }
  for (const auto& q : random_sphere(300, 8))
    if (std::fabs(q.z) < 0.45) pts.push_back(q);
  const auto m = convex_hull(pts);
  check_hull(pts, m, reference::predicate);
  CHECK(m.num_vertices() == pts.size());
  const auto merged = convex_hull(pts, {.merge_coplanar = true});
  check_hull(pts, merged, reference::predicate);
  std::size_t caps = 0;
  for (face_handle f : merged.faces()) caps += merged.valence(f) == 24;
  CHECK(caps == 2);
}

TEST_CASE("both algorithms give the same hull on every kind of input") {
  std::vector<std::vector<glm::dvec3>> inputs{lattice(7), random_sphere(1500, 11)};
  std::mt19937_64 rng(12);
  std::uniform_int_distribution<int> c(-40, 40);
  std::vector<glm::dvec3> ball, cylinder;
  while (ball.size() < 1500) {
    const glm::dvec3 p(c(rng), c(rng), c(rng));
    if (glm::dot(p, p) <= 1600) ball.push_back(p);
  }
  for (int z = 0; z < 10; ++z)  // coplanar rings: many exact zeros in both algorithms
    for (int i = 0; i < 40; ++i)
      cylinder.push_back({std::round(30 * std::cos(i * 0.157)), std::round(30 * std::sin(i * 0.157)), z});
  inputs.push_back(ball);
  inputs.push_back(cylinder);
  for (const auto& pts : inputs) {
    std::set<std::array<double, 3>> reference_corners;
    for (const auto method :
         {cellforge::convex_hull_method::quickhull, cellforge::convex_hull_method::incremental,
          cellforge::convex_hull_method::automatic}) {
      const auto m = convex_hull(pts, {.method = method});
      check_hull(pts, m, &pts == &inputs[1] ? reference::predicate : reference::int128);
      // The corners are the same points whichever algorithm ran (duplicates aside).
      const auto pos = m.positions();
      std::set<std::array<double, 3>> corners;
      for (vertex_handle v : m.vertices()) corners.insert({pos[v].x, pos[v].y, pos[v].z});
      if (reference_corners.empty()) reference_corners = corners;
      CHECK(corners == reference_corners);
    }
  }
}

TEST_CASE("random small-grid inputs: duplicates, coplanar and collinear everywhere") {
  // Few distinct values per coordinate make almost every orientation test an exact zero.
  std::mt19937_64 rng(13);
  std::uniform_int_distribution<int> size(1, 80), kind(0, 3);
  int solids = 0, flats = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = size(rng), k = kind(rng);
    std::uniform_int_distribution<int> c(0, k == 0 ? 1 : k == 1 ? 3 : 6);
    std::vector<glm::dvec3> pts;
    for (int i = 0; i < n; ++i) {
      glm::dvec3 p(c(rng), c(rng), c(rng));
      if (k == 3) p.z = p.x + p.y;  // all on one plane
      pts.push_back(p);
    }
    for (const auto method :
         {cellforge::convex_hull_method::quickhull, cellforge::convex_hull_method::incremental}) {
      for (const bool merge : {false, true}) {
        convex_hull_report report;
        const auto m = convex_hull(pts, {.merge_coplanar = merge, .method = method}, &report);
        REQUIRE(cellforge::validate(m).ok());
        if (report.dimension == 3) {
          check_hull(pts, m, reference::int128);
          solids += !merge;
        } else {
          CHECK(m.is_closed());
          flats += report.dimension == 2 && !merge;
          if (report.dimension == 2) CHECK(m.num_faces() == (merge ? 2u : 2 * (m.num_vertices() - 2)));
          if (report.dimension < 2) CHECK(m.num_faces() == 0);
        }
      }
    }
  }
  CHECK(solids > 300);
  CHECK(flats > 100);
}

TEST_CASE("dropping the points inside the polytope of extremes first gives the same hull") {
  std::mt19937_64 rng(21);
  std::uniform_int_distribution<int> c(-1000, 1000), g(0, 4);
  // The expected count where the polytope of extremes is the whole cube: its interior points.
  auto strictly_inside = [](const std::vector<glm::dvec3>& pts, double lo, double hi) {
    return static_cast<std::size_t>(std::count_if(pts.begin(), pts.end(), [&](const glm::dvec3& p) {
      return p.x > lo && p.x < hi && p.y > lo && p.y < hi && p.z > lo && p.z < hi;
    }));
  };
  struct input {
    std::string name;
    std::vector<glm::dvec3> pts;
    std::size_t min_discarded, max_discarded;
  };
  std::vector<input> inputs;
  std::vector<glm::dvec3> cube, ball, lattice20 = lattice(20), few_values, slab;
  for (int i = 0; i < 30000; ++i) cube.push_back(glm::dvec3(c(rng), c(rng), c(rng)));
  while (ball.size() < 20000) {
    const glm::dvec3 p(c(rng), c(rng), c(rng));
    if (glm::dot(p, p) <= 1e6) ball.push_back(p);
  }
  for (int i = 0; i < 10000; ++i) few_values.push_back(glm::dvec3(g(rng), g(rng), g(rng)));  // duplicates
  for (int i = 0; i < 10000; ++i) slab.push_back(glm::dvec3(c(rng), c(rng), i % 2));         // two planes
  const std::size_t lattice_inside = strictly_inside(lattice20, 0, 19),
                    values_inside = strictly_inside(few_values, 0, 4);
  inputs = {{"cube", cube, cube.size() / 2, cube.size()},
            {"ball", ball, ball.size() / 2, ball.size()},
            {"lattice 20^3", lattice20, lattice_inside, lattice_inside},  // 18^3: the rest lie on faces
            {"5^3 values", few_values, values_inside, values_inside},
            {"slab", slab, 0, 0}};  // every point on one of the two planes: none strictly inside
  for (const input& in : inputs) {  // no structured binding: clang 14 cannot capture one in INFO
    const std::vector<glm::dvec3>& pts = in.pts;
    INFO(in.name);
    for (const bool merge : {false, true}) {
      convex_hull_report with, without;
      const auto a = convex_hull(
          pts, {.merge_coplanar = merge, .method = cellforge::convex_hull_method::quickhull}, &with);
      const auto b = convex_hull(pts,
                                 {.merge_coplanar = merge,
                                  .method = cellforge::convex_hull_method::quickhull,
                                  .discard_interior = false},
                                 &without);
      check_hull(pts, a, reference::int128, 200);
      CHECK(without.interior_discarded == 0);
      CHECK(with.interior_discarded >= in.min_discarded);
      CHECK(with.interior_discarded <= in.max_discarded);
      CHECK(with.vertices == without.vertices);
      CHECK(with.faces == without.faces);
      std::set<std::array<double, 3>> ca, cb;
      for (vertex_handle v : a.vertices())
        ca.insert({a.positions()[v].x, a.positions()[v].y, a.positions()[v].z});
      for (vertex_handle v : b.vertices())
        cb.insert({b.positions()[v].x, b.positions()[v].y, b.positions()[v].z});
      CHECK(ca == cb);
    }
  }
}

TEST_CASE("extremes on one plane with the solid beyond it: the filter steps aside") {
  // Every extreme along the 14 directions lies on the tilted plane; one point off it, near the
  // middle, makes the input solid. The filter's polytope is flat, so it must hull everything.
  const glm::dvec3 n = glm::normalize(glm::dvec3(1, 2, 3));
  const glm::dvec3 u = glm::normalize(glm::cross(n, glm::dvec3(1, 0, 0))), w = glm::cross(n, u);
  std::vector<glm::dvec3> pts;
  for (int i = 0; i < 6000; ++i) {
    const double a = 2 * std::numbers::pi * i / 6000.0;
    pts.push_back(100.0 * (std::cos(a) * u + std::sin(a) * w));
  }
  pts.push_back(0.5 * n);
  convex_hull_report report;
  const auto m = convex_hull(pts, {.method = cellforge::convex_hull_method::quickhull}, &report);
  check_hull(pts, m, reference::predicate, 200);
  CHECK(report.dimension == 3);
  CHECK(report.interior_discarded == 0);
  CHECK(m.num_vertices() >= 6001);  // the apex and the circle (rounded points off the plane may add none)
}

TEST_CASE("points on a sphere through quickhull with the filter: nothing is inside") {
  const auto pts = random_sphere(8000, 5);
  convex_hull_report report;
  const auto m = convex_hull(pts, {.method = cellforge::convex_hull_method::quickhull}, &report);
  check_hull(pts, m, reference::predicate, 200);
  CHECK(m.num_vertices() == pts.size());
  CHECK(report.interior_discarded == 0);
}

TEST_CASE_TEMPLATE("every point type gives the same hull", P, glm::dvec3, std::array<float, 3>,
                   test_support::user_point) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<float> c(-1, 1);
  std::vector<P> pts;
  for (int i = 0; i < 3000; ++i) pts.push_back(cellforge::point_traits<P>::make(c(rng), c(rng), c(rng)));
  convex_hull_report report;
  const auto m = convex_hull(std::span<const P>(pts), {}, &report);
  check_hull(pts, m, reference::predicate);
  CHECK(report.dimension == 3);
  CHECK(m.num_vertices() > 30);
}

TEST_CASE("convex_hull takes any contiguous range and returns its point type") {
  const std::array<std::array<float, 3>, 5> box{
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.1f, 0.1f, 0.1f}}};
  const auto a = convex_hull(box);
  static_assert(
      std::is_same_v<std::remove_cvref_t<decltype(a)>, cellforge::surface_mesh<std::array<float, 3>>>);
  CHECK(a.num_vertices() == 4);  // the inner point is no corner
  const glm::dvec3 c_array[4] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
  const auto b = convex_hull(c_array);
  CHECK(b.num_faces() == 4);
  CHECK(convex_hull(std::span<const glm::dvec3>(c_array)).num_faces() == 4);
  CHECK(convex_hull(std::vector<glm::dvec3>(std::begin(c_array), std::end(c_array))).num_edges() == 6);
}

}  // namespace convex_hull_tests
