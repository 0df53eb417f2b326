// self_intersections: closed meshes with none, two interpenetrating cubes counted by hand,
// the shared-vertex, shared-edge, coplanar, piercing and fold cases, nearly coplanar
// configurations at scales where an epsilon would decide wrongly, float points, the budget,
// zero-area triangles, random soups against a brute-force all-pairs run of the same exact
// pair test, and jittered or lattice-snapped closed meshes (shared vertices) against the
// old all-pairs answer.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory_resource>
#include <random>
#include <span>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/ear_clipping.hpp"
#include "cellforge/algorithms/loop_subdivision.hpp"
#include "cellforge/algorithms/self_intersections.hpp"
#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh_geometry.hpp"
#include "cellforge/samples/skeletons.hpp"
#include "cellforge/samples/tube_soups.hpp"
#include "cellforge/tubes/tube_mesh.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace self_intersections_tests {

namespace {

using cellforge::polygon_soup;
using cellforge::self_intersection_options;
using cellforge::self_intersection_result;
using cellforge::self_intersections;
using cellforge::surface_mesh;
using glm::dvec3;

template <class P>
self_intersection_result check(const polygon_soup<P>& soup, const self_intersection_options& o = {}) {
  const surface_mesh<P> m = cellforge::make_mesh(soup);
  return self_intersections(m, o);
}

// A soup of the given triangles, each with its own three vertices (nothing shared).
polygon_soup<dvec3> separate(const std::vector<std::array<dvec3, 3>>& tris) {
  polygon_soup<dvec3> s;
  for (const auto& t : tris) {
    const auto base = static_cast<std::uint32_t>(s.points.size());
    for (const dvec3& p : t) s.points.push_back(p);
    s.add_face({base, base + 1, base + 2});
  }
  return s;
}

// Triangles over one shared point list (shared indices are shared vertices).
polygon_soup<dvec3> indexed(std::vector<dvec3> points,
                            const std::vector<std::array<std::uint32_t, 3>>& faces) {
  polygon_soup<dvec3> s;
  s.points = std::move(points);
  for (const auto& f : faces) s.add_face({f[0], f[1], f[2]});
  return s;
}

std::size_t pairs(const polygon_soup<dvec3>& s) { return check(s).intersecting_face_pairs; }

// Closes: the unit cube shifted by `offset`, appended to s.
void add_cube(polygon_soup<dvec3>& s, const dvec3& offset, double size = 1) {
  const polygon_soup<dvec3> c = cellforge::hexahedron();
  const auto base = static_cast<std::uint32_t>(s.points.size());
  for (const dvec3& p : c.points) s.points.push_back(offset + size * p);
  for (std::size_t f = 0; f < c.num_faces(); ++f) {
    std::vector<std::uint32_t> face;
    for (const std::uint32_t v : c.face(f)) face.push_back(base + v);
    s.add_face(face);
  }
}

}  // namespace

TEST_CASE("self_intersections: closed meshes have none") {
  using namespace cellforge;
  using namespace cellforge::samples;
  const std::vector<std::pair<const char*, polygon_soup<dvec3>>> shapes = {
      {"tetrahedron", tetrahedron()},
      {"cube", hexahedron()},
      {"octahedron", octahedron()},
      {"icosahedron", icosahedron()},
      {"dodecahedron", dodecahedron()},
      {"icosphere 3", icosphere(3)},
      {"uv sphere quads", uv_sphere(24, 12, false)},
      {"torus quads", torus(32, 12, 1.0, 0.3, false)},
      {"torus triangles", torus(40, 16, 1.0, 0.3, true)},
      {"cylinder with polygon caps", cylinder(16, 4, true, false)},
      {"lattice tubes 3x3x3", lattice_tube_mesh(3, 3, 3)},
      {"lattice tubes 4x3x2 triangles", lattice_tube_mesh(4, 3, 2, {1.0, 0.5, true})},
      {"tree tubes", tree_tube_mesh(4)},
      {"spline tube", spline_tube()},
  };
  for (const auto& shape : shapes) {
    const char* const name = shape.first;  // no structured binding: clang 14 cannot CAPTURE one
    const polygon_soup<dvec3>& soup = shape.second;
    CAPTURE(name);
    const self_intersection_result r = check(soup);
    CHECK(r.complete);
    CHECK(r.intersecting_face_pairs == 0);
    CHECK(r.intersecting_triangle_pairs == 0);
    CHECK(r.degenerate_triangles == 0);
    CHECK(r.faces == soup.num_faces());
    CHECK(r.pairs_tested > 0);
  }
  // Loop-subdivided meshes.
  for (const auto& soup : {icosahedron(), octahedron(), triangulate_fan(hexahedron())}) {
    const surface_mesh<dvec3> m = loop_subdivided(make_mesh(soup), loop_subdivision_options{.levels = 3});
    const self_intersection_result r = self_intersections(m);
    CHECK(r.triangles == m.num_faces());
    CHECK(r.intersecting_face_pairs == 0);
  }
}

TEST_CASE("self_intersections: two interpenetrating cubes") {
  // Cube A = [0,1]^3, cube B = A + (0.5, 0.3, 0.7). The face x = 1 of A crosses B's faces
  // y = 0.3 and z = 0.7 (B's faces y = 1.3, z = 1.7 are beyond A's face, and B's x faces are
  // parallel to it); likewise y = 1 of A crosses x = 0.5 and z = 0.7, and z = 1 of A crosses
  // x = 0.5 and y = 0.3; A's faces x, y, z = 0 lie outside B's range. 6 face pairs.
  polygon_soup<dvec3> s;
  add_cube(s, dvec3(0.0));
  add_cube(s, dvec3(0.5, 0.3, 0.7));
  const self_intersection_result r = check(s);
  CHECK(r.intersecting_face_pairs == 6);
  REQUIRE(r.face_pairs.size() == 6);
  for (const auto& [f, g] : r.face_pairs) {
    CHECK(f.idx() < 6);  // one face of each cube
    CHECK(g.idx() >= 6);
  }
  CHECK(r.triangles == 24);
  CHECK(r.ear_clipped_faces == 0);
  // Apart: none. Sharing a face plane without overlapping (touching along a face): B at x + 1
  // touches A along the whole face x = 1, and the faces around it touch along edges.
  polygon_soup<dvec3> apart;
  add_cube(apart, dvec3(0.0));
  add_cube(apart, dvec3(2.0, 0.0, 0.0));
  CHECK(pairs(apart) == 0);
  polygon_soup<dvec3> touching;
  add_cube(touching, dvec3(0.0));
  add_cube(touching, dvec3(1.0, 0.25, 0.25), 0.5);
  // B's face x = 1 lies on A's face x = 1 (coplanar overlap); B's four side faces touch A's
  // face x = 1 along an edge.
  CHECK(pairs(touching) == 5);
  // Only max_reported pairs are listed, the count is complete.
  self_intersection_options few;
  few.max_reported = 2;
  const self_intersection_result r2 = check(s, few);
  CHECK(r2.intersecting_face_pairs == 6);
  CHECK(r2.face_pairs.size() == 2);
}

TEST_CASE("self_intersections: a shared vertex") {
  // T1 in the plane z = 0, T2 rising from the shared vertex 0: they meet only there.
  const std::vector<dvec3> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, -1, 1}, {-1, 0, 2}};
  CHECK(pairs(indexed(pts, {{{0, 1, 2}}, {{0, 3, 4}}})) == 0);
  // The same corner as two different vertices: touching counts.
  CHECK(pairs(separate({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {-1, -1, 1}, {-1, 0, 2}}}})) == 1);
  // T2 passes through the shared vertex into T1's interior and out below.
  CHECK(pairs(indexed({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 1}, {0.3, 0.3, -1}},
                      {{{0, 1, 2}}, {{0, 3, 4}}})) == 1);
  // Through the vertex but outside T1's corner: none.
  CHECK(pairs(indexed({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-0.3, -0.3, 1}, {-0.3, -0.3, -1}},
                      {{{0, 1, 2}}, {{0, 3, 4}}})) == 0);
  // T2's far edge pierces T1 although no corner of T2 lies in T1's plane near it.
  CHECK(pairs(indexed({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 1}, {1, 1, -1}},
                      {{{0, 1, 2}}, {{0, 3, 4}}})) == 1);
  // A corner of T2 in T1's plane along T1's edge direction (T2's edge 0-3 runs inside T1's
  // edge 0-1): they share a segment.
  CHECK(pairs(indexed({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0, 0}, {0, -1, 1}},
                      {{{0, 1, 2}}, {{0, 3, 4}}})) == 1);
  // ... and pointing away from T1: only the vertex.
  CHECK(pairs(indexed({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-0.5, 0, 0}, {0, -1, 1}},
                      {{{0, 1, 2}}, {{0, 3, 4}}})) == 0);
  // Coplanar: corners apart (a fan of two triangles around the vertex) vs overlapping.
  CHECK(pairs(indexed({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}},
                      {{{0, 1, 2}}, {{0, 3, 4}}})) == 0);
  CHECK(pairs(indexed({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, 1, 0.0}},
                      {{{0, 1, 2}}, {{0, 3, 4}}})) == 1);
  CHECK(pairs(indexed({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}}, {{{0, 1, 2}}, {{0, 3, 4}}})) ==
        1);
  // Coplanar, touching along a common ray from the vertex (edges 0-2 and 0-3 overlap).
  CHECK(pairs(indexed({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 2, 0}, {-1, 1, 0}},
                      {{{0, 1, 2}}, {{0, 3, 4}}})) == 1);
  // Coplanar, T2 wholly inside T1's corner but beyond T1 (beyond its far edge): the corner
  // contains T2's edges, so they overlap near the vertex.
  CHECK(pairs(indexed({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {3, 1, 0}, {1, 3, 0}}, {{{0, 1, 2}}, {{0, 3, 4}}})) ==
        1);
}

TEST_CASE("self_intersections: a shared edge, and the fold") {
  // Edge 0-1 shared. A dihedral angle, a flat continuation, and a fold onto the first face.
  const dvec3 a(0, 0, 0), b(1, 0, 0), c(0.3, 1, 0);
  CHECK(pairs(indexed({a, b, c, {0.5, 0.5, 1}}, {{{0, 1, 2}}, {{1, 0, 3}}})) == 0);
  CHECK(pairs(indexed({a, b, c, {0.5, -1, 0}}, {{{0, 1, 2}}, {{1, 0, 3}}})) == 0);
  CHECK(pairs(indexed({a, b, c, {0.7, 0.5, 0}}, {{{0, 1, 2}}, {{1, 0, 3}}})) == 1);
  CHECK(pairs(indexed({a, b, c, {3, 9, 0}}, {{{0, 1, 2}}, {{1, 0, 3}}})) == 1);
  // Nearly folded: the other face a hair above the plane (exactly not coplanar).
  CHECK(pairs(indexed({a, b, c, {0.7, 0.5, 1e-300}}, {{{0, 1, 2}}, {{1, 0, 3}}})) == 0);
  // Two quads folded flat: faces 0 and 1 share edge 1-2 and lie on top of each other.
  polygon_soup<dvec3> fold;
  fold.points = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {1, 0.2, 0}, {1, 0.8, 0}};
  fold.add_face({0, 1, 2, 3});  // a flat rectangle
  fold.add_face({2, 1, 4, 5});  // a quad hinged on edge 1-2 and laid back onto it
  const self_intersection_result r = check(fold);
  CHECK(r.intersecting_face_pairs == 1);
  CHECK(r.intersecting_triangle_pairs == 3);  // all but (0 2 3) with (2 1 4), which meet only at vertex 2
}

TEST_CASE("self_intersections: no shared vertex") {
  // Piercing through the interior; crossing edges; coplanar overlap, touching, containment.
  const std::array<dvec3, 3> base = {dvec3(0, 0, 0), dvec3(1, 0, 0), dvec3(0, 1, 0)};
  auto with = [&](std::array<dvec3, 3> t) { return pairs(separate({base, t})); };
  CHECK(with({dvec3(0.2, 0.2, -1), dvec3(0.3, 0.2, 1), dvec3(0.2, 0.3, 1)}) == 1);   // pierces
  CHECK(with({dvec3(2, 2, -1), dvec3(3, 2, 1), dvec3(2, 3, 1)}) == 0);               // beside
  CHECK(with({dvec3(0.2, 0.2, 0.1), dvec3(0.3, 0.2, 1), dvec3(0.2, 0.3, 1)}) == 0);  // above
  CHECK(with({dvec3(0.2, 0.2, 0), dvec3(0.3, 0.2, 1), dvec3(0.2, 0.3, 1)}) == 1);    // corner on it
  CHECK(with({dvec3(0.5, 0.5, 0), dvec3(2, 2, 1), dvec3(2, 2, -1)}) == 1);           // corner on its edge
  CHECK(with({dvec3(0.6, 0.6, 0), dvec3(2, 2, 1), dvec3(2, 2, -1)}) == 0);           // just outside it
  CHECK(with({dvec3(0.5, -1, 0.5), dvec3(0.5, 1, 0.5), dvec3(0.5, 0, -0.5)}) == 1);  // through an edge
  CHECK(with({dvec3(0.2, 0.2, 0), dvec3(2, 0.2, 0), dvec3(0.2, 2, 0)}) == 1);        // coplanar overlap
  CHECK(with({dvec3(0.1, 0.1, 0), dvec3(0.2, 0.1, 0), dvec3(0.1, 0.2, 0)}) == 1);    // coplanar inside
  CHECK(with({dvec3(-1, -1, 0), dvec3(3, -1, 0), dvec3(-1, 3, 0)}) == 1);            // coplanar around
  CHECK(with({dvec3(1, 0, 0), dvec3(2, 0, 0), dvec3(2, 1, 0)}) == 1);                // coplanar, a point
  CHECK(with({dvec3(0.5, 0.5, 0), dvec3(1.5, -0.5, 0), dvec3(2, 1, 0)}) == 1);    // coplanar, along the edge
  CHECK(with({dvec3(0.51, 0.51, 0), dvec3(1.5, -0.5, 0), dvec3(2, 1, 0)}) == 0);  // coplanar, apart
  CHECK(with({dvec3(0, 1, 0), dvec3(1, 0, 0), dvec3(1, 1, 0)}) == 1);             // coplanar, an edge
  // The public pair test on the caller's point type.
  using fp = std::array<float, 3>;
  CHECK(cellforge::triangles_intersect<fp>({fp{0, 0, 0}, fp{1, 0, 0}, fp{0, 1, 0}},
                                           {fp{0.2f, 0.2f, -1}, fp{0.3f, 0.2f, 1}, fp{0.2f, 0.3f, 1}}));
  CHECK_FALSE(cellforge::triangles_intersect<fp>({fp{0, 0, 0}, fp{1, 0, 0}, fp{0, 1, 0}},
                                                 {fp{2, 2, -1}, fp{3, 2, 1}, fp{2, 3, 1}}));
}

TEST_CASE("self_intersections: nearly coplanar, where an epsilon decides wrongly") {
  for (const double s : {1e-300, 1e-150, 1.0, 1e15, 1e150}) {
    CAPTURE(s);
    // The second triangle lies above the first's plane by one unit in the last place of
    // the coordinates (or a subnormal): apart, though any tolerance would call it coplanar
    // and overlapping.
    const double h = s == 1e-300 ? 1e-310 : s * 0x1p-52;
    const std::array<dvec3, 3> t = {s * dvec3(0, 0, 0), s * dvec3(1, 0, 0), s * dvec3(0, 1, 0)};
    CHECK(pairs(separate(
              {t, {dvec3(0.2 * s, 0.2 * s, h), dvec3(0.6 * s, 0.2 * s, h), dvec3(0.2 * s, 0.6 * s, h)}})) ==
          0);
    // Tilted by a hair so that it crosses the plane inside the triangle: it intersects.
    CHECK(pairs(separate(
              {t, {dvec3(0.2 * s, 0.2 * s, h), dvec3(0.6 * s, 0.2 * s, -h), dvec3(0.2 * s, 0.6 * s, h)}})) ==
          1);
    // Crossing the plane outside the triangle (beyond the hypotenuse, by a hair of the
    // coordinates): apart.
    CHECK(pairs(separate({t,
                          {dvec3(0.5 * s, 0.5 * s, 0) + dvec3(s * 0x1p-50, s * 0x1p-50, h),
                           dvec3(0.5 * s, 0.5 * s, 0) + dvec3(s * 0x1p-50, s * 0x1p-50, -h),
                           dvec3(2 * s, 2 * s, 0)}})) == 0);
    // The same exactly on the hypotenuse: it touches.
    CHECK(pairs(separate(
              {t, {dvec3(0.5 * s, 0.5 * s, h), dvec3(0.5 * s, 0.5 * s, -h), dvec3(2 * s, 2 * s, 0)}})) == 1);
    // A shared edge with the other face a hair out of plane (a fold within an epsilon).
    CHECK(pairs(indexed({t[0], t[1], t[2], dvec3(0.7 * s, 0.5 * s, h)}, {{{0, 1, 2}}, {{1, 0, 3}}})) == 0);
    CHECK(pairs(indexed({t[0], t[1], t[2], dvec3(0.7 * s, 0.5 * s, 0)}, {{{0, 1, 2}}, {{1, 0, 3}}})) == 1);
  }
}

TEST_CASE("self_intersections: a convex quad is split as ear clipping splits it") {
  // The quad shortcut must give ear clipping's own two triangles: random quads near a
  // square (off their plane, in random orientations and scales, some concave in
  // projection), compared with clip_polygon one by one.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-0.6, 0.6), angle(-3.14159, 3.14159), scale(-6, 6);
  cellforge::ear_clip_options clip;
  clip.planarity_tolerance = std::numeric_limits<double>::infinity();
  clip.allow_non_simple = true;
  int shortcut = 0, refused = 0, mismatches = 0;
  for (int t = 0; t < 20000; ++t) {
    const double a = angle(rng), b = angle(rng), s = std::pow(10.0, scale(rng));
    const dvec3 u(std::cos(a), std::sin(a), 0),
        w(-std::sin(a) * std::cos(b), std::cos(a) * std::cos(b), std::sin(b));
    const dvec3 n = glm::cross(u, w);
    std::vector<dvec3> q;
    for (const auto& [x, y] : std::array<std::pair<double, double>, 4>{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}})
      q.push_back(s * ((x + jitter(rng)) * u + (y + jitter(rng)) * w + 0.2 * jitter(rng) * n));
    if (!cellforge::detail::self_intersect::convex_projected_quad(std::span<const dvec3>(q))) {
      ++refused;
      continue;
    }
    ++shortcut;
    cellforge::ear_clip_report report;
    const auto tris = cellforge::detail::ears::clip_polygon(q, clip, report);
    const std::vector<cellforge::index_triangle> expected{{3, 0, 1}, {1, 2, 3}};
    if (tris != expected) {
      ++mismatches;
      MESSAGE("miss: quad " << t << " is clipped otherwise");
    }
  }
  std::printf("convex quads: %d by the shortcut (%d mismatches), %d left to ear clipping\n", shortcut,
              mismatches, refused);
  CHECK(shortcut > 10000);
  CHECK(refused > 0);
  CHECK(mismatches == 0);
}

TEST_CASE("self_intersections: a convex polygon is clipped as ear clipping clips it") {
  // clip_convex_projection must give clip_polygon's own triangles: random polygons of 4 to 16
  // corners near a regular one (off their plane by up to a tenth or by rounding only, in random
  // orientations and scales, a seventh dented, some concave or crossing in projection),
  // compared one by one.
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> jitter(-1, 1), angle(-3.14159, 3.14159), scale(-6, 6);
  cellforge::ear_clip_options clip;
  clip.planarity_tolerance = std::numeric_limits<double>::infinity();
  clip.allow_non_simple = true;
  int shortcut = 0, refused = 0, mismatches = 0;
  for (int t = 0; t < 6000; ++t) {
    const double a = angle(rng), b = angle(rng), s = std::pow(10.0, scale(rng));
    const dvec3 u(std::cos(a), std::sin(a), 0),
        w(-std::sin(a) * std::cos(b), std::cos(a) * std::cos(b), std::sin(b));
    const dvec3 n = glm::cross(u, w);
    const std::size_t corners = 4 + static_cast<std::size_t>(t % 13);
    const double wobble = t % 3 == 0 ? 0.0 : 0.1 * jitter(rng), spread = t % 5 == 0 ? 0.9 : 0.2;
    std::vector<dvec3> q;
    std::vector<std::uint32_t> ids;
    for (std::size_t i = 0; i < corners; ++i) {
      const double phi = 6.283185307179586 * (static_cast<double>(i) + spread * 0.5 * jitter(rng)) /
                         static_cast<double>(corners);
      const double r = t % 7 == 0 && i == 2 ? 0.3 : 1.0;  // a dent: concave in projection
      q.push_back(s * (r * std::cos(phi) * u + r * std::sin(phi) * w + wobble * jitter(rng) * n));
      ids.push_back(static_cast<std::uint32_t>(i));
    }
    std::vector<cellforge::index_triangle> fast;
    if (!cellforge::detail::self_intersect::clip_convex_projection(
            std::span<const std::uint32_t>(ids), std::span<const dvec3>(q),
            [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
              fast.push_back({x, y, z});
            })) {
      CHECK(fast.empty());
      ++refused;
      continue;
    }
    ++shortcut;
    cellforge::ear_clip_report report;
    if (fast != cellforge::detail::ears::clip_polygon(q, clip, report)) {
      ++mismatches;
      MESSAGE("miss: polygon " << t << " (" << corners << " corners) is clipped otherwise");
    }
  }
  std::printf("convex polygons: %d by the shortcut (%d mismatches), %d left to ear clipping\n", shortcut,
              mismatches, refused);
  CHECK(shortcut > 3000);
  CHECK(refused > 500);
  CHECK(mismatches == 0);
}

TEST_CASE("self_intersections: polygons are tested as their triangulations") {
  // A non-planar quad: two triangles, ear clipped; and a flat concave L hexagon.
  polygon_soup<dvec3> q;
  q.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0}};
  q.add_face({0, 1, 2, 3});
  const self_intersection_result r = check(q);
  CHECK(r.triangles == 2);
  CHECK(r.ear_clipped_faces == 1);
  CHECK(r.intersecting_face_pairs == 0);
  // An L-shaped prism: concave top and bottom (ear clipped into 4 triangles each).
  polygon_soup<dvec3> l;
  const std::vector<glm::dvec2> outline = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (const double z : {0.0, 1.0})
    for (const auto& p : outline) l.points.push_back({p.x, p.y, z});
  l.add_face({5, 4, 3, 2, 1, 0});
  l.add_face({6, 7, 8, 9, 10, 11});
  for (std::uint32_t i = 0; i < 6; ++i) {
    const std::uint32_t j = (i + 1) % 6;
    l.add_face({i, j, j + 6, i + 6});
  }
  const self_intersection_result rl = check(l);
  CHECK(rl.triangles == 4 + 4 + 12);
  CHECK(rl.ear_clipped_faces == 2);
  CHECK(rl.intersecting_face_pairs == 0);
  // A polygon with a straight corner (a T-junction vertex) is ear clipped, not fanned into
  // a zero-area triangle.
  polygon_soup<dvec3> t;
  t.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  t.add_face({0, 1, 2, 3, 4});
  const self_intersection_result rt = check(t);
  CHECK(rt.degenerate_triangles == 0);
  CHECK(rt.triangles == 3);
}

TEST_CASE("self_intersections: zero-area triangles are reported, not tested") {
  polygon_soup<dvec3> s = separate({{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}},  // collinear
                                    {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
                                    {{{0.5, 0, -1}, {0.5, 0, 1}, {0.5, 0.5, 0}}}});
  const self_intersection_result r = check(s);
  CHECK(r.degenerate_triangles == 1);
  REQUIRE(r.degenerate_faces.size() == 1);
  CHECK(r.degenerate_faces[0].idx() == 0);
  CHECK(r.intersecting_face_pairs == 1);  // faces 1 and 2 only
  REQUIRE(r.face_pairs.size() == 1);
  CHECK(r.face_pairs[0].first.idx() == 1);
  CHECK(r.face_pairs[0].second.idx() == 2);
  // NaN corners are degenerate too.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(check(separate({{{{nan, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}}))
            .degenerate_triangles == 1);
}

TEST_CASE("self_intersections: float points") {
  using fp = std::array<float, 3>;
  const self_intersection_result r = check(cellforge::icosphere<fp>(3));
  CHECK(r.intersecting_face_pairs == 0);
  CHECK(r.triangles == 1280);
  polygon_soup<fp> s = cellforge::hexahedron<fp>();
  const std::size_t n = s.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const fp& p = s.points[i];
    s.points.push_back({p[0] + 0.5f, p[1] + 0.3f, p[2] + 0.7f});
  }
  const std::size_t faces = s.num_faces();
  for (std::size_t f = 0; f < faces; ++f) {
    std::vector<std::uint32_t> face;
    for (const std::uint32_t v : s.face(f)) face.push_back(v + static_cast<std::uint32_t>(n));
    s.add_face(face);
  }
  CHECK(check(s).intersecting_face_pairs == 6);
}

TEST_CASE("self_intersections: the work budget") {
  const polygon_soup<dvec3> soup = cellforge::icosphere(3);
  self_intersection_options o;
  o.work_budget = 10;
  const self_intersection_result r = check(soup, o);
  CHECK_FALSE(r.complete);
  CHECK(r.candidate_pairs <= 10);
  CHECK(r.work == r.candidate_pairs);
  o.work_budget = 0;  // unlimited, as in every part (it was the size-scaled default until 0.6)
  const self_intersection_result all = check(soup, o);
  CHECK(all.complete);
  CHECK(all.candidate_pairs > 10);
  // Everything in one cell (a fan of long thin triangles around one vertex) is bounded too.
  polygon_soup<dvec3> fan;
  fan.points.push_back({0, 0, 0});
  const int n = 1000;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.141592653589793 * i / n;
    fan.points.push_back({std::cos(a), std::sin(a), 0});
  }
  for (int i = 0; i < n; ++i)
    fan.add_face({0, static_cast<std::uint32_t>(1 + i), static_cast<std::uint32_t>(1 + (i + 1) % n)});
  self_intersection_options small;
  small.work_budget = 100000;
  const self_intersection_result rf = check(fan, small);
  CHECK_FALSE(rf.complete);
  CHECK(rf.candidate_pairs <= 100000);
  const self_intersection_result full = check(fan);
  CHECK(full.complete);
  CHECK(full.intersecting_face_pairs == 0);
}

namespace {

// The brute-force reference: every pair of triangles of different faces, the same exact test.
std::vector<std::uint64_t> brute_force(const polygon_soup<dvec3>& s) {
  namespace si = cellforge::detail::self_intersect;
  std::vector<std::uint64_t> out;
  for (std::uint32_t f = 0; f < s.num_faces(); ++f)
    for (std::uint32_t g = f + 1; g < s.num_faces(); ++g) {
      const auto a = s.face(f), b = s.face(g);
      const std::array<dvec3, 3> p = {s.points[a[0]], s.points[a[1]], s.points[a[2]]},
                                 q = {s.points[b[0]], s.points[b[1]], s.points[b[2]]};
      if (si::degenerate(p[0], p[1], p[2]) || si::degenerate(q[0], q[1], q[2])) continue;
      if (si::pair_intersects(p, {a[0], a[1], a[2]}, q, {b[0], b[1], b[2]}))
        out.push_back(static_cast<std::uint64_t>(f) << 32 | g);
    }
  return out;
}

}  // namespace

TEST_CASE("self_intersections: random soups against brute force") {
  std::mt19937_64 rng(12);
  for (int round = 0; round < 24; ++round) {
    CAPTURE(round);
    // Small triangles in a box: continuous coordinates, or a coarse integer lattice where
    // coplanar, collinear and touching configurations are common.
    const bool lattice = round % 2 == 1;
    std::uniform_real_distribution<double> centre(0, 10), offset(-1, 1);
    std::uniform_int_distribution<int> cell(0, 6), step(-2, 2);
    std::vector<std::array<dvec3, 3>> tris;
    const int count = 150 + 20 * round;
    for (int i = 0; i < count; ++i) {
      std::array<dvec3, 3> t{};
      if (lattice) {
        const dvec3 c(cell(rng), cell(rng), cell(rng));
        for (dvec3& p : t) p = c + dvec3(step(rng), step(rng), step(rng));
      } else {
        const dvec3 c(centre(rng), centre(rng), centre(rng));
        for (dvec3& p : t) p = c + dvec3(offset(rng), offset(rng), offset(rng));
      }
      tris.push_back(t);
    }
    const polygon_soup<dvec3> s = separate(tris);
    self_intersection_options o;
    o.max_reported = 1 << 20;
    const self_intersection_result r = check(s, o);
    const std::vector<std::uint64_t> expected = brute_force(s);
    REQUIRE(r.complete);
    CHECK(r.intersecting_face_pairs == expected.size());
    CHECK(r.intersecting_triangle_pairs == expected.size());
    REQUIRE(r.face_pairs.size() == expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
      CHECK(r.face_pairs[i].first.idx() == expected[i] >> 32);
      CHECK(r.face_pairs[i].second.idx() == static_cast<std::uint32_t>(expected[i]));
    }
    CHECK(!expected.empty());
    if (lattice) CHECK(r.degenerate_triangles > 0);
  }
}

// Configurations a broad phase could drop (boxes of very different sizes, needles whose boxes
// are flat, contact at a single point, coplanar overlap), built so that the answer is known by
// construction, and checked against it and against the brute-force pair loop. Dyadic
// coordinates: every contact below is exact.
TEST_CASE("self_intersections: big and small, slivers, point contact, coplanar overlap") {
  const double tiny = std::ldexp(1.0, -6), hair = std::ldexp(1.0, -40);
  auto same_as_brute_force = [](const polygon_soup<dvec3>& s, std::size_t expected) {
    self_intersection_options o;
    o.max_reported = 1 << 20;
    const self_intersection_result r = check(s, o);
    const std::vector<std::uint64_t> brute = brute_force(s);
    CHECK(r.complete);
    CHECK(r.degenerate_triangles == 0);
    CHECK(brute.size() == expected);
    CHECK(r.intersecting_face_pairs == expected);
    REQUIRE(r.face_pairs.size() == brute.size());
    for (std::size_t i = 0; i < brute.size(); ++i) {
      CHECK(r.face_pairs[i].first.idx() == brute[i] >> 32);
      CHECK(r.face_pairs[i].second.idx() == static_cast<std::uint32_t>(brute[i]));
    }
  };
  SUBCASE("one huge triangle under 400 tiny ones") {
    // Big: z = 0, covering [-1000, 1000]²'s middle. Tiny ones on a grid 4 apart (never each other):
    // piercing it, resting a corner on it, or a hair above it, in turn.
    std::vector<std::array<dvec3, 3>> tris = {
        {dvec3(-1024, -1024, 0), dvec3(1024, -1024, 0), dvec3(0, 1024, 0)}};
    std::size_t meeting = 0;
    for (int i = 0; i < 20; ++i)
      for (int j = 0; j < 20; ++j) {
        const dvec3 c(4.0 * i - 40, 4.0 * j - 40, 0);
        const int kind = (i + j) % 3;
        const double z0 = kind == 0 ? -tiny : kind == 1 ? 0 : hair;
        tris.push_back(
            {c + dvec3(0, 0, z0), c + dvec3(tiny, 0, z0 + tiny), c + dvec3(0, tiny, z0 + 2 * tiny)});
        meeting += kind < 2 ? 1 : 0;
      }
    same_as_brute_force(separate(tris), meeting);
  }
  SUBCASE("needles: coplanar crossings, and a hair apart") {
    // Ten needles along x (1024 long, 2^-30 wide) at y = 0..9 in z = 0; ten along y across
    // them: the even ones in the same plane cross all ten, the odd ones lie a hair above.
    const double thin = std::ldexp(1.0, -30);
    std::vector<std::array<dvec3, 3>> tris;
    for (int i = 0; i < 10; ++i) tris.push_back({dvec3(0, i, 0), dvec3(1024, i, 0), dvec3(512, i + thin, 0)});
    std::size_t crossings = 0;
    for (int j = 0; j < 10; ++j) {
      const double x = 10.0 * j + 5, z = j % 2 == 0 ? 0 : hair;
      tris.push_back({dvec3(x, -1, z), dvec3(x + thin, 10, z), dvec3(x, 20, z)});
      crossings += j % 2 == 0 ? 10 : 0;
    }
    same_as_brute_force(separate(tris), crossings);
  }
  SUBCASE("contact at one point, with no vertex shared") {
    // A base in z = 0; each other triangle (apart from one another) reaches it in one point:
    // a corner on its interior, on an edge, on a corner; one stops a hair short.
    const std::array<dvec3, 3> base = {dvec3(0, 0, 0), dvec3(64, 0, 0), dvec3(0, 64, 0)};
    const std::vector<dvec3> touch = {{8, 8, 0}, {32, 0, 0}, {64, 0, 0}, {0, 64, 0}, {16, 16, hair}};
    std::vector<std::array<dvec3, 3>> tris = {base};
    for (const dvec3& t : touch) tris.push_back({t, t + dvec3(1, -2, 4), t + dvec3(-2, 1, 4)});
    same_as_brute_force(separate(tris), 4);
  }
  SUBCASE("coplanar: overlapping, nested, edge to edge, a hair apart") {
    // In the plane x + y + z = 64 (dyadic points on it exactly): pairs (2k, 2k + 1) that overlap,
    // nest, share a piece of edge, or miss by a hair; the pairs are far apart from each other.
    auto on_plane = [](double x, double y) { return dvec3(x, y, 64 - x - y); };
    std::vector<std::array<dvec3, 3>> tris;
    for (int k = 0; k < 4; ++k) {
      const double o = 16.0 * k;
      tris.push_back({on_plane(o, 0), on_plane(o + 8, 0), on_plane(o, 8)});
      if (k == 0) tris.push_back({on_plane(o + 2, 2), on_plane(o + 10, 2), on_plane(o + 2, 10)});  // overlap
      if (k == 1) tris.push_back({on_plane(o + 1, 1), on_plane(o + 2, 1), on_plane(o + 1, 2)});    // nested
      if (k == 2) tris.push_back({on_plane(o + 2, 6), on_plane(o + 6, 2), on_plane(o + 8, 8)});  // edge piece
      if (k == 3)  // a corner a hair beyond the hypotenuse x + y = o + 8
        tris.push_back({on_plane(o + 2 + hair, 6), on_plane(o + 8, 6), on_plane(o + 2 + hair, 12)});
    }
    same_as_brute_force(separate(tris), 3);
  }
}

namespace {

// The old answer: every pair of triangles (of the triangulation the check uses) of different
// faces, decided by the exact pair test alone: no grid, no spatial order, no shared-vertex
// shortcut. Returns the sorted distinct face-pair keys; `triangle_pairs` counts the pairs.
std::vector<std::uint64_t> all_pairs_exact(const surface_mesh<dvec3>& m, std::size_t& triangle_pairs) {
  namespace si = cellforge::detail::self_intersect;
  std::vector<dvec3> pos(m.vertices_size());
  for (std::size_t i = 0; i < pos.size(); ++i) pos[i] = m.points()[i];
  std::vector<si::entry> all, tris;
  self_intersection_result unused;
  si::triangulate_for_test(m, std::span<const dvec3>(pos), all, unused);
  for (const si::entry& e : all)
    if (!si::degenerate(pos[e.v[0]], pos[e.v[1]], pos[e.v[2]])) tris.push_back(e);
  std::vector<std::uint64_t> out;
  triangle_pairs = 0;
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (std::size_t j = i + 1; j < tris.size(); ++j) {
      const si::entry &a = tris[i], &b = tris[j];
      if (a.face == b.face) continue;
      const std::array<dvec3, 3> p = {pos[a.v[0]], pos[a.v[1]], pos[a.v[2]]},
                                 q = {pos[b.v[0]], pos[b.v[1]], pos[b.v[2]]};
      if (!si::pair_intersects(p, a.v, q, b.v)) continue;
      ++triangle_pairs;
      out.push_back(static_cast<std::uint64_t>(std::min(a.face, b.face)) << 32 | std::max(a.face, b.face));
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

TEST_CASE("self_intersections: meshes with shared vertices against the old all-pairs answer") {
  // Closed meshes (shared vertices, so the shared-vertex shortcut and the spatial order are
  // used) moved by noise from none to wild, or snapped to a coarse lattice where coplanar,
  // touching and zero-area triangles are common; triangles and (non-planar) quads.
  std::mt19937_64 rng(35);
  std::size_t by_topology = 0, rounds_hit = 0, degenerate = 0;
  for (int round = 0; round < 16; ++round) {
    CAPTURE(round);
    polygon_soup<dvec3> s = round % 4 == 3   ? cellforge::uv_sphere(12, 8, false)
                            : round % 4 == 2 ? cellforge::torus(14, 6, 1, 0.3, false)
                                             : cellforge::icosphere(2);
    const double noise = std::array<double, 4>{0.0, 0.02, 0.15, 0.6}[static_cast<std::size_t>(round / 4)];
    const bool snap = round % 2 == 1;
    std::normal_distribution<double> jitter(0, noise > 0 ? noise : 1);
    for (dvec3& p : s.points) {
      if (noise > 0) p += dvec3(jitter(rng), jitter(rng), jitter(rng));
      if (snap) p = glm::round(p * 4.0) / 4.0;  // a lattice of 1/4: exact coplanar contacts
    }
    const surface_mesh<dvec3> m = cellforge::make_mesh(s);
    self_intersection_options o;
    o.max_reported = 1 << 20;
    const self_intersection_result r = self_intersections(m, o);
    std::size_t triangle_pairs = 0;
    const std::vector<std::uint64_t> expected = all_pairs_exact(m, triangle_pairs);
    REQUIRE(r.complete);
    CHECK(r.intersecting_triangle_pairs == triangle_pairs);
    CHECK(r.intersecting_face_pairs == expected.size());
    REQUIRE(r.face_pairs.size() == expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
      CHECK(r.face_pairs[i].first.idx() == expected[i] >> 32);
      CHECK(r.face_pairs[i].second.idx() == static_cast<std::uint32_t>(expected[i]));
    }
    by_topology += r.pairs_by_topology;
    rounds_hit += expected.empty() ? 0 : 1;
    degenerate += r.degenerate_triangles;
  }
  MESSAGE("16 meshes: " << rounds_hit << " with intersections, " << by_topology
                        << " pairs decided by a shared vertex's star, " << degenerate
                        << " zero-area triangles");
  CHECK(by_topology > 0);  // the shortcut was taken ...
  CHECK(rounds_hit >= 4);  // ... and the meshes do intersect, touch and degenerate
  CHECK(degenerate > 0);
}

// The check's answer on m equals the all-pairs answer (face pairs and triangle pairs).
void require_all_pairs_answer(const surface_mesh<dvec3>& m, const self_intersection_result& r) {
  std::size_t triangle_pairs = 0;
  const std::vector<std::uint64_t> expected = all_pairs_exact(m, triangle_pairs);
  REQUIRE(r.complete);
  CHECK(r.intersecting_triangle_pairs == triangle_pairs);
  REQUIRE(r.face_pairs.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    CHECK(r.face_pairs[i].first.idx() == expected[i] >> 32);
    CHECK(r.face_pairs[i].second.idx() == static_cast<std::uint32_t>(expected[i]));
  }
}

TEST_CASE("self_intersections: a tube mesh pushed through itself or folded is caught") {
  // A tube mesh (quads, one grid box per quad) with one wall vertex moved through the tube's axis
  // past the opposite wall, or one quad folded back across its neighbour: the check must find
  // exactly what testing every pair of triangles finds, and find something.
  const auto s = cellforge::samples::random_tree(7, {.nodes = 24});
  const auto tubes = cellforge::make_tubes(s);
  self_intersection_options o;
  o.max_reported = 1 << 20;
  REQUIRE(self_intersections(tubes.mesh, o).intersecting_face_pairs == 0);
  using cellforge::face_handle;
  using cellforge::vertex_handle;
  // The point of the skeleton's edges nearest p.
  const auto axis_point = [&](const dvec3& p) {
    dvec3 best = s.points[0];
    for (const auto& e : s.edges) {
      const dvec3 a = s.points[e[0]], d = s.points[e[1]] - a;
      const double t = std::clamp(glm::dot(p - a, d) / glm::dot(d, d), 0.0, 1.0);
      if (glm::distance(a + t * d, p) < glm::distance(best, p)) best = a + t * d;
    }
    return best;
  };
  std::size_t pushed = 0;
  for (std::uint32_t v = 5; v < tubes.mesh.vertices_size(); v += tubes.mesh.vertices_size() / 5) {
    CAPTURE(v);
    surface_mesh<dvec3> m = tubes.mesh;
    const dvec3 p = m.position(vertex_handle(v)), a = axis_point(p);
    m.set_position(vertex_handle(v), a - 1.6 * (p - a));  // 0.6 radii beyond the opposite wall
    const self_intersection_result r = self_intersections(m, o);
    CHECK(r.intersecting_face_pairs > 0);
    require_all_pairs_answer(m, r);
    ++pushed;
  }
  CHECK(pushed == 5);
  // Fold: quad g, across edge (f0, f1) of quad f, laid back over f, its far corners just above
  // and just below f's plane, so that it crosses f.
  std::size_t folded = 0;
  for (const face_handle f : tubes.mesh.faces()) {
    std::vector<vertex_handle> fv, gv;
    for (const vertex_handle x : tubes.mesh.vertices_around(f)) fv.push_back(x);
    if (fv.size() != 4) continue;
    face_handle g;
    bool found = false;
    for (const face_handle h : tubes.mesh.faces_around(fv[0]))
      if (h != f)
        for (const vertex_handle x : tubes.mesh.vertices_around(h))
          if (x == fv[1]) g = h, found = true;
    REQUIRE(found);
    for (const vertex_handle x : tubes.mesh.vertices_around(g)) gv.push_back(x);
    if (gv.size() != 4) continue;
    while (gv[0] != fv[1]) std::rotate(gv.begin(), gv.begin() + 1, gv.end());  // g: f1, f0, g2, g3
    REQUIRE(gv[1] == fv[0]);
    surface_mesh<dvec3> m = tubes.mesh;
    const auto at = [&](vertex_handle x) { return m.position(x); };
    const dvec3 n = glm::normalize(glm::cross(at(fv[2]) - at(fv[0]), at(fv[3]) - at(fv[1])));
    const double e =
        0.02 * std::min(glm::distance(at(fv[1]), at(fv[0])), glm::distance(at(fv[3]), at(fv[0])));
    m.set_position(gv[2], at(fv[3]) + e * n);
    m.set_position(gv[3], at(fv[2]) - e * n);
    CAPTURE(f.idx());
    CHECK(cellforge::folded_edges(m).edges.size() > 0);
    const self_intersection_result r = self_intersections(m, o);
    bool f_and_g = false;
    for (const auto& [x, y] : r.face_pairs)
      f_and_g = f_and_g || (x.idx() == std::min(f.idx(), g.idx()) && y.idx() == std::max(f.idx(), g.idx()));
    CHECK(f_and_g);
    require_all_pairs_answer(m, r);
    if (++folded == 3) break;
  }
  CHECK(folded == 3);
}

TEST_CASE("self_intersections: a sphere of 110,000 triangles") {
  const surface_mesh<dvec3> m = cellforge::make_mesh(cellforge::sphere_with_vertices(55000));
  const self_intersection_result r = self_intersections(m);
  MESSAGE("110k-triangle sphere: " << r.milliseconds << " ms, " << r.candidate_pairs << " candidate pairs, "
                                   << r.pairs_tested << " tested");
  CHECK(r.complete);
  CHECK(r.triangles == m.num_faces());
  CHECK(r.triangles > 100000);
  CHECK(r.intersecting_face_pairs == 0);
}

}  // namespace self_intersections_tests

// The check by pieces' scratch block (what its engine's arrays live in): a Release build takes
// its arrays from it, and the sanitizer and fuzz builds bypass it, so its own arithmetic is
// tested here (where it maps: Linux, no AddressSanitizer).
TEST_CASE("scratch_arena: aligned, in order, the top reused, the rest on the heap") {
  using cellforge::detail::scratch_arena;
  // The size rule: every array in the block below 256 MB of room, up to 2 MB above.
  CHECK(scratch_arena::largest_for(100u << 20) == (100u << 20));
  CHECK(scratch_arena::largest_for(std::size_t{300} << 20) == (2u << 20));
  CHECK_FALSE(scratch_arena(1u << 20).mapped());  // below 64 MB of room: nothing mapped
  scratch_arena arena(8u << 20, 3u << 20, 0);
  if (!arena.mapped()) {
    MESSAGE("scratch_arena: no block here (sanitizer build or no mmap): every array on the heap");
    return;
  }
  std::pmr::memory_resource& r = arena;
  void* a = r.allocate(100, 8);
  void* b = r.allocate(3, 64);
  CHECK(arena.owns(a));
  CHECK(arena.owns(b));
  CHECK(reinterpret_cast<std::uintptr_t>(b) % 64 == 0);
  CHECK(static_cast<char*>(b) >= static_cast<char*>(a) + 100);  // in order, not overlapping
  std::memset(a, 0x5a, 100);
  std::memset(b, 0xa5, 3);
  CHECK(static_cast<unsigned char*>(a)[99] == 0x5a);
  // The top is reused; a block below the top is not.
  r.deallocate(b, 3, 64);
  void* b2 = r.allocate(3, 64);
  CHECK(b2 == b);
  r.deallocate(a, 100, 8);
  void* c = r.allocate(100, 8);
  CHECK(c != a);
  CHECK(arena.owns(c));
  // Over `largest`: the heap.
  void* big = r.allocate(4u << 20, 16);
  CHECK_FALSE(arena.owns(big));
  r.deallocate(big, 4u << 20, 16);
  // Full: the rest goes to the heap, and what the block held stays intact.
  std::vector<void*> held;
  void* last = nullptr;
  for (int k = 0; k < 16; ++k) {
    last = r.allocate(1u << 20, 4096);
    if (!arena.owns(last)) break;
    std::memset(last, k, 1u << 20);
    held.push_back(last);
    last = nullptr;
  }
  REQUIRE(last != nullptr);  // the block (8 MB and rounding) filled before 16 MB
  CHECK(held.size() >= 7);   // 8-10 MB of block, less what came before
  std::memset(last, 0xff, 1u << 20);
  for (std::size_t k = 0; k < held.size(); ++k)
    CHECK(static_cast<unsigned char*>(held[k])[(1u << 20) - 1] == static_cast<unsigned char>(k));
  r.deallocate(last, 1u << 20, 4096);
  // A vector grown in it keeps its values.
  std::pmr::vector<std::uint32_t> v(&arena);
  for (std::uint32_t i = 0; i < 1000; ++i) v.push_back(i * 7);
  bool kept = true;
  for (std::size_t i = 0; i < v.size(); ++i) kept = kept && v[i] == 7 * i;
  CHECK(kept);
}
