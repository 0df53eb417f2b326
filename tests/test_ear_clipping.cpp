// Ear clipping: each triangulation is checked as a 2-chain — n - 2 triangles, every polygon
// side used once in its direction, every diagonal once each way, every triangle turning
// like the polygon — which together prove the triangles tile the polygon exactly; plus
// area sums and centroid-inside tests on the smaller shapes.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/ear_clipping.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace ear_clipping_tests {

namespace {

using cellforge::ear_clip;
using cellforge::index_triangle;
using poly2 = std::vector<glm::dvec2>;

// ------------------------------------------------------------------ shapes (counter-clockwise)

poly2 regular(int n, double r = 1) {
  poly2 p;
  for (int i = 0; i < n; ++i)
    p.push_back({r * std::cos(2 * std::numbers::pi * i / n), r * std::sin(2 * std::numbers::pi * i / n)});
  return p;
}
poly2 l_shape() { return {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}}; }
poly2 u_shape() { return {{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}}; }
poly2 star(int tips, double inner = 0.4) {
  poly2 p;
  for (int i = 0; i < 2 * tips; ++i) {
    const double t = std::numbers::pi * i / tips, r = i % 2 == 0 ? 1.0 : inner;
    p.push_back({r * std::cos(t), r * std::sin(t)});
  }
  return p;
}
// A comb: a spine along the bottom and `teeth` thin teeth pointing up.
poly2 comb(int teeth) {
  poly2 p{{0, 0}, {2.0 * teeth, 0}};
  for (int i = teeth - 1; i >= 0; --i) {
    p.push_back({2.0 * i + 1.0, 1});
    p.push_back({2.0 * i + 1.0, 10});
    p.push_back({2.0 * i + 0.0, 10});
    if (i > 0) p.push_back({2.0 * i + 0.0, 1});
  }
  return p;
}
// A thick spiral band: out along one arm, back along a parallel one.
poly2 spiral(int steps, double turns = 3) {
  poly2 outer, inner;
  for (int i = 0; i <= steps; ++i) {
    const double t = turns * 2 * std::numbers::pi * i / steps, r = 1 + t;
    outer.push_back({(r + 0.5) * std::cos(t), (r + 0.5) * std::sin(t)});
    inner.push_back({(r - 0.5) * std::cos(t), (r - 0.5) * std::sin(t)});
  }
  poly2 p(inner.begin(), inner.end());
  p.insert(p.end(), outer.rbegin(), outer.rend());
  return p;
}
// A square with `k` extra points on each side (collinear runs).
poly2 dotted_square(int k) {
  poly2 p;
  const std::array<glm::dvec2, 4> c{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  for (int s = 0; s < 4; ++s)
    for (int i = 0; i <= k; ++i) p.push_back(c[s] + (c[(s + 1) % 4] - c[s]) * (double(i) / (k + 1)));
  return p;
}
poly2 reversed(poly2 p) { return poly2(p.rbegin(), p.rend()); }

// Places a 2D polygon in the 3D plane spanned by two orthonormal vectors, offset.
std::vector<glm::dvec3> place(const poly2& p, const glm::dvec3& u = {1, 0, 0},
                              const glm::dvec3& v = {0, 1, 0}, const glm::dvec3& origin = glm::dvec3(0)) {
  std::vector<glm::dvec3> out;
  for (const auto& q : p) out.push_back(origin + q.x * u + q.y * v);
  return out;
}
std::pair<glm::dvec3, glm::dvec3> random_plane(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  const glm::dvec3 n = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
  const glm::dvec3 u = glm::normalize(glm::cross(n, glm::dvec3(g(rng), g(rng), g(rng))));
  return {u, glm::cross(n, u)};
}

double shoelace(const poly2& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    a += p[i].x * p[(i + 1) % p.size()].y - p[(i + 1) % p.size()].x * p[i].y;
  return a / 2;
}
bool inside(const poly2& p, const glm::dvec2& q) {  // crossing number
  bool in = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    if ((p[i].y > q.y) != (p[j].y > q.y) &&
        q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x)
      in = !in;
  return in;
}

// The full check in the polygon's own 2D coordinates (`p2` is the polygon before placing).
void check_tiling(const poly2& p2, const std::vector<index_triangle>& tris, std::size_t degenerate = 0,
                  bool centroids = true) {
  const std::size_t n = p2.size();
  REQUIRE(tris.size() == n - 2);
  const int sense = shoelace(p2) > 0 ? 1 : -1;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::size_t bad_index = 0, flat = 0, wrong_turn = 0, outside = 0;
  double area = 0;
  for (const auto& t : tris) {
    if (t[0] >= n || t[1] >= n || t[2] >= n || t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++bad_index;
      continue;
    }
    const glm::dvec2 a = p2[t[0]], b = p2[t[1]], c = p2[t[2]];
    const int turn = cellforge::orient2d(a, b, c) * sense;
    flat += turn == 0;
    wrong_turn += turn < 0;
    area += std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) / 2;
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    if (centroids && turn != 0) outside += !inside(p2, (a + b + c) / 3.0);
  }
  CHECK(bad_index == 0);
  CHECK(flat == degenerate);
  CHECK(wrong_turn == 0);
  CHECK(outside == 0);
  CHECK(area == doctest::Approx(std::fabs(shoelace(p2))).epsilon(1e-9));
  // Sides once in the polygon's direction, never backwards; diagonals once each way.
  std::size_t bad_edges = 0;
  for (const auto& [e, count] : directed) {
    const bool side = (e.first + 1) % n == e.second;
    const bool backwards = (e.second + 1) % n == e.first;
    if (side)
      bad_edges += count != 1;
    else if (backwards)
      ++bad_edges;
    else
      bad_edges += count != 1 || directed.count({e.second, e.first}) != 1;
  }
  for (std::uint32_t i = 0; i < n; ++i)
    bad_edges += directed.count({i, static_cast<std::uint32_t>((i + 1) % n)}) != 1;
  CHECK(bad_edges == 0);
}

void check_shape(const poly2& p2, std::mt19937_64& rng) {
  // In the xy-plane, clockwise and counter-clockwise, and in a random 3D plane.
  check_tiling(p2, ear_clip(place(p2)));
  check_tiling(reversed(p2), ear_clip(place(reversed(p2))));
  const auto [u, v] = random_plane(rng);
  cellforge::ear_clip_report report;
  const auto tris = ear_clip(place(p2, u, v, {3, -2, 7}), {}, &report);
  check_tiling(p2, tris);
  CHECK(report.area == doctest::Approx(std::fabs(shoelace(p2))).epsilon(1e-9));
  CHECK(std::fabs(glm::dot(report.normal, u)) < 1e-9);
  CHECK(glm::dot(report.normal, glm::cross(u, v)) * shoelace(p2) > 0);  // turns like the polygon
}

}  // namespace

TEST_CASE("convex, concave, comb, star and spiral polygons tile exactly") {
  std::mt19937_64 rng(1);
  SUBCASE("convex") { check_shape(regular(12), rng); }
  SUBCASE("triangle") { check_shape(regular(3), rng); }
  SUBCASE("L") { check_shape(l_shape(), rng); }
  SUBCASE("U") { check_shape(u_shape(), rng); }
  SUBCASE("comb") { check_shape(comb(12), rng); }
  SUBCASE("star") { check_shape(star(9), rng); }
  SUBCASE("spiral") { check_shape(spiral(120), rng); }
}

TEST_CASE("collinear vertices never become zero-area triangles") {
  std::mt19937_64 rng(2);
  check_shape(dotted_square(5), rng);
  // Collinear runs at reflex corners and along the inner sides of an L.
  check_shape(
      {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {2, 1}, {1, 1}, {1, 2}, {1, 3}, {0, 3}, {0, 2}, {0, 1}}, rng);
  // A triangle whose vertices are mostly on one side: only a fan from the far corner works.
  poly2 fan{{0, 0}};
  for (int i = 1; i <= 20; ++i) fan.push_back({i, 0});
  fan.push_back({10, 5});
  check_shape(fan, rng);
}

TEST_CASE("random star-shaped integer polygons with collinear midpoints") {
  // Integer points sorted by angle around a non-lattice centre form a simple polygon;
  // inserting the exact midpoint of some sides adds flat vertices.
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> coord(-20, 20), count(3, 40);
  int shapes = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const glm::dvec2 centre(0.5, 0.25);
    poly2 p;
    const int n = count(rng);
    for (int i = 0; i < n; ++i) p.push_back({coord(rng), coord(rng)});
    std::sort(p.begin(), p.end(), [&](const glm::dvec2& a, const glm::dvec2& b) {
      return std::atan2(a.y - centre.y, a.x - centre.x) < std::atan2(b.y - centre.y, b.x - centre.x);
    });
    p.erase(std::unique(p.begin(), p.end()), p.end());
    bool star_shaped = p.size() >= 3;  // the centre must see every side from inside
    for (std::size_t i = 0; star_shaped && i < p.size(); ++i)
      star_shaped = cellforge::orient2d(p[i], p[(i + 1) % p.size()], centre) > 0;
    if (!star_shaped) continue;
    poly2 q;
    for (std::size_t i = 0; i < p.size(); ++i) {
      q.push_back(p[i]);
      const glm::dvec2 m = (p[i] + p[(i + 1) % p.size()]) / 2.0;
      if (m == glm::floor(m) && i % 2 == 0) q.push_back(m);
    }
    check_tiling(q, ear_clip(place(q)));
    ++shapes;
  }
  CHECK(shapes > 50);
}

TEST_CASE("a repeated vertex keeps the tiling, with one zero-area triangle") {
  const poly2 p{{0, 0}, {2, 0}, {2, 0}, {2, 2}, {1, 3}, {0, 2}};
  cellforge::ear_clip_report report;
  const auto tris = ear_clip(place(p), {}, &report);
  check_tiling(p, tris, 1, false);
  CHECK(report.degenerate_triangles == 1);
  // The first vertex repeated at the end, as many files close their polygons, and a run of
  // three equal vertices.
  const poly2 closed{{0, 0}, {3, 0}, {3, 3}, {3, 3}, {3, 3}, {0, 3}, {0, 0}};
  check_tiling(closed, ear_clip(place(closed), {}, &report), 3, false);
  CHECK(report.degenerate_triangles == 3);
}

TEST_CASE("10,000-vertex comb, star and spiral finish and tile exactly") {
  const std::vector<poly2> big{comb(2500), star(5000), spiral(5000, 8)};
  for (const poly2& p : big) {
    REQUIRE(p.size() >= 10000);
    check_tiling(p, ear_clip(place(p)), 0, false);  // the 2-chain checks prove the tiling
  }
}

TEST_CASE_TEMPLATE("every point type", P, glm::dvec3, std::array<float, 3>, test_support::user_point) {
  std::vector<P> poly;
  for (const auto& q : u_shape()) poly.push_back(cellforge::point_traits<P>::make(q.x, 0.5f, q.y));
  const auto tris = ear_clip(std::span<const P>(poly));
  check_tiling(u_shape(), tris);
}

TEST_CASE("bad polygons give clear errors") {
  auto fails = [](const std::vector<glm::dvec3>& p, const char* words, cellforge::ear_clip_options o = {}) {
    try {
      ear_clip(p, o);
      FAIL("no error for: " << words);
    } catch (const cellforge::error& e) {
      CHECK(e.category() == cellforge::error_category::invalid_input);
      INFO(e.what());
      CHECK(std::string(e.what()).find(words) != std::string::npos);
    }
  };
  fails({{0, 0, 0}, {1, 0, 0}}, "at least 3");
  fails({{0, 0, 0}, {1, 0, 0}, {0, std::numeric_limits<double>::quiet_NaN(), 0}}, "NaN");
  fails({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}, "no area");
  fails({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2}, {0, 1, 0}}, "not planar");
  fails(place({{0, 0}, {4, 4}, {4, 0}, {0, 2}}), "not simple");                  // a figure eight
  fails(place({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}), "not simple");          // touches itself
  fails(place({{0, 0}, {2, 0}, {2, 2}, {1, 1}, {2, 2}, {0, 2}}), "not simple");  // a needle back and forth
  poly2 pentagram;
  for (int i = 0; i < 5; ++i) pentagram.push_back(regular(5)[static_cast<std::size_t>(2 * i % 5)]);
  fails(place(pentagram), "not simple");  // every vertex convex: only the crossing test sees it
  // Within a looser tolerance the bent quad is accepted.
  CHECK(ear_clip(std::vector<glm::dvec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2}, {0, 1, 0}},
                 {.planarity_tolerance = 0.1})
            .size() == 2);
  // Non-simple input on request: n - 2 triangles, no hang, forced ears reported when needed.
  cellforge::ear_clip_report report;
  const auto tris = ear_clip(place(pentagram), {.allow_non_simple = true}, &report);
  CHECK(tris.size() == 3);
  const auto touching = ear_clip(place({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}), {.allow_non_simple = true});
  CHECK(touching.size() == 3);
}

TEST_CASE("triangulate: a soup of mixed faces, with sources") {
  cellforge::polygon_soup<glm::dvec3> soup;
  for (const auto& q : l_shape()) soup.points.push_back({q.x, q.y, 0});
  soup.points.push_back({0, 0, 5});
  soup.add_face({0, 1, 2, 3, 4, 5});
  soup.add_face({0, 6, 1});
  cellforge::triangulate_report report;
  const auto out = cellforge::triangulate(soup, {}, &report);
  CHECK(out.num_faces() == 5);
  CHECK(report.polygons == 1);
  CHECK(report.triangles_added == 4);
  CHECK(report.source_face == std::vector<std::uint32_t>{0, 0, 0, 0, 1});
  soup.add_face({0, 1, 9});
  CHECK_THROWS_AS(cellforge::triangulate(soup), cellforge::error);
}

TEST_CASE("triangulate_faces: a closed polygon mesh becomes a closed triangle mesh") {
  // A hexagonal prism: two hexagons and six quads, outward.
  cellforge::polygon_soup<glm::dvec3> soup;
  for (int z = 0; z < 2; ++z)
    for (int i = 0; i < 6; ++i)
      soup.points.push_back({std::cos(i * std::numbers::pi / 3), std::sin(i * std::numbers::pi / 3), z});
  soup.add_face({5, 4, 3, 2, 1, 0});
  soup.add_face({6, 7, 8, 9, 10, 11});
  for (std::uint32_t i = 0; i < 6; ++i) soup.add_face({i, (i + 1) % 6, 6 + (i + 1) % 6, 6 + i});
  auto m = cellforge::make_mesh(soup);
  const auto report = cellforge::triangulate_faces(m, {}, "f:source");
  CHECK(report.polygons == 8);
  CHECK(report.triangles_added == 2 * 4 + 6 * 2);
  CHECK(cellforge::validate(m).ok());
  CHECK(m.is_closed());
  CHECK(m.is_consistently_oriented());
  CHECK(m.num_faces() == 20);
  const auto source = m.get_face_property<std::uint32_t>("f:source");
  REQUIRE(source);
  std::map<std::uint32_t, int> per_source;
  for (auto f : m.faces()) {
    CHECK(m.valence(f) == 3);
    ++per_source[source[f]];
  }
  CHECK(per_source.size() == 8);
  CHECK(per_source[0] == 4);
  m.garbage_collection();
  CHECK(cellforge::validate(m).ok());
  CHECK(static_cast<long>(m.num_vertices()) - static_cast<long>(m.num_edges()) +
            static_cast<long>(m.num_faces()) ==
        2);
}

TEST_CASE("triangulate_faces refuses a diagonal that is already an edge, leaving the mesh unchanged") {
  cellforge::polygon_soup<glm::dvec3> soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, -1}, {0.5, 0.5, -2}};
  soup.add_face({0, 1, 2, 3});
  soup.add_face({0, 2, 4});  // both diagonals of the quad already exist
  soup.add_face({1, 3, 5});
  auto m = cellforge::make_mesh(soup);
  REQUIRE(cellforge::validate(m).ok());
  CHECK_THROWS_AS(cellforge::triangulate_faces(m), cellforge::error);
  CHECK(m.num_faces() == 3);
  CHECK(!m.has_garbage());
  CHECK(cellforge::validate(m).ok());
}

}  // namespace ear_clipping_tests
