#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <numbers>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/algorithms/soup_queries.hpp"
#include "cellforge/algorithms/soup_transforms.hpp"
#include "cellforge/samples/tube_soups.hpp"

namespace test_user {
/// A CAD-like point type, registered through the one-line macro.
struct cad_vec {
  double x = 0, y = 0, z = 0;
};
}  // namespace test_user
CELLFORGE_REGISTER_POINT3(test_user::cad_vec, double, x, y, z);

// Own namespace: the test files of a group are compiled as one translation unit.
namespace shapes_tests {

namespace {

using cellforge::polygon_soup;
using cellforge::soup_statistics;
constexpr double pi = std::numbers::pi;

/// What a fixture must look like; -1 means "do not check".
struct expected {
  std::int64_t vertices = -1, edges = -1, faces = -1, boundary = 0, inconsistent = 0;
  std::int64_t euler = -1;
  bool orientable = true;
};

/// Checks, for every vertex, that the faces around it form one fan: its link (the edges
/// opposite to it in its faces) is a single cycle (closed) or a single path (boundary).
/// Returns the number of vertices where that fails (non-manifold vertices).
template <class P>
std::size_t count_nonmanifold_vertices(const polygon_soup<P>& soup) {
  std::vector<std::vector<std::array<std::uint32_t, 2>>> link(soup.points.size());
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto face = soup.face(f);
    for (std::size_t i = 0; i < face.size(); ++i)
      link[face[i]].push_back({face[(i + face.size() - 1) % face.size()], face[(i + 1) % face.size()]});
  }
  std::size_t bad = 0;
  for (const auto& edges : link) {
    if (edges.empty()) continue;
    std::map<std::uint32_t, std::vector<std::uint32_t>> adj;
    for (const auto& [a, b] : edges) {
      adj[a].push_back(b);
      adj[b].push_back(a);
    }
    std::size_t ends = 0;
    bool ok = true;
    for (const auto& [v, n] : adj) {
      ends += n.size() == 1;
      ok = ok && n.size() <= 2;
    }
    // Connected: walk from one end (or anywhere on a cycle).
    std::uint32_t start = adj.begin()->first;
    for (const auto& [v, n] : adj)
      if (n.size() == 1) start = v;
    std::map<std::uint32_t, bool> seen;
    std::vector<std::uint32_t> stack{start};
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      if (seen[v]) continue;
      seen[v] = true;
      for (const std::uint32_t w : adj[v]) stack.push_back(w);
    }
    ok = ok && seen.size() == adj.size() && (ends == 0 || ends == 2);
    bad += !ok;
  }
  return bad;
}

/// Number of closed loops formed by the boundary edges.
template <class P>
std::size_t count_boundary_loops(const polygon_soup<P>& soup) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto face = soup.face(f);
    for (std::size_t i = 0; i < face.size(); ++i) {
      const std::uint32_t a = face[i], b = face[(i + 1) % face.size()];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<std::uint32_t> parent(soup.points.size());
  for (std::uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  const std::function<std::uint32_t(std::uint32_t)> find = [&](std::uint32_t x) {
    return parent[x] == x ? x : parent[x] = find(parent[x]);
  };
  std::map<std::uint32_t, int> degree;
  for (const auto& [e, n] : uses)
    if (n == 1) {
      ++degree[e.first];
      ++degree[e.second];
      parent[find(e.first)] = find(e.second);
    }
  std::size_t loops = 0;
  for (const auto& [v, d] : degree) {
    REQUIRE(d == 2);  // a boundary vertex of a manifold lies on exactly one loop
    loops += find(v) == v;
  }
  return loops;
}

template <class P>
soup_statistics check_fixture(const polygon_soup<P>& soup, const expected& want) {
  const soup_statistics st = cellforge::analyze_soup(soup);
  if (want.vertices >= 0) CHECK(static_cast<std::int64_t>(st.vertices) == want.vertices);
  if (want.vertices >= 0) CHECK(static_cast<std::int64_t>(soup.num_points()) == want.vertices);
  if (want.edges >= 0) CHECK(static_cast<std::int64_t>(st.edges) == want.edges);
  if (want.faces >= 0) CHECK(static_cast<std::int64_t>(st.faces) == want.faces);
  if (want.euler != -1) CHECK(st.euler_characteristic() == want.euler);
  if (want.boundary >= 0) CHECK(static_cast<std::int64_t>(st.boundary_edges) == want.boundary);
  if (want.inconsistent >= 0) CHECK(static_cast<std::int64_t>(st.inconsistent_edges) == want.inconsistent);
  CHECK(st.degenerate_faces == 0);
  CHECK(st.nonmanifold_edges == 0);
  CHECK(count_nonmanifold_vertices(soup) == 0);
  CHECK(cellforge::is_soup_orientable(soup) == want.orientable);
  CHECK(cellforge::is_soup_closed(soup) == (st.boundary_edges == 0));
  // The single-purpose queries agree with the combined one.
  CHECK(cellforge::euler_characteristic(soup) == st.euler_characteristic());
  CHECK(cellforge::count_boundary_edges(soup) == st.boundary_edges);
  CHECK(cellforge::count_inconsistent_edges(soup) == st.inconsistent_edges);
  return st;
}

template <class P>
bool same_soup(const polygon_soup<P>& a, const polygon_soup<P>& b) {
  if (a.face_offsets != b.face_offsets || a.face_vertices != b.face_vertices ||
      a.num_points() != b.num_points())
    return false;
  for (std::size_t i = 0; i < a.num_points(); ++i)
    if (cellforge::to_dvec3(a.points[i]) != cellforge::to_dvec3(b.points[i])) return false;
  return true;
}

/// Every face's normal (Newell) points away from the origin: outward for a star-shaped
/// solid centred at the origin.
template <class P>
std::size_t count_inward_faces(const polygon_soup<P>& soup, const glm::dvec3& centre = glm::dvec3(0)) {
  std::size_t inward = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto face = soup.face(f);
    glm::dvec3 normal(0), centroid(0);
    for (std::size_t i = 0; i < face.size(); ++i) {
      const glm::dvec3 a = cellforge::to_dvec3(soup.points[face[i]]);
      normal += glm::cross(a, cellforge::to_dvec3(soup.points[face[(i + 1) % face.size()]]));
      centroid += a;
    }
    centroid /= static_cast<double>(face.size());
    inward += glm::dot(normal, centroid - centre) <= 0;
  }
  return inward;
}

template <class P>
bool all_faces_have(const polygon_soup<P>& soup, std::size_t size) {
  for (std::size_t f = 0; f < soup.num_faces(); ++f)
    if (soup.face(f).size() != size) return false;
  return true;
}

template <class P>
void check_on_unit_sphere(const polygon_soup<P>& soup, double eps) {
  for (const P& p : soup.points)
    CHECK(glm::length(cellforge::to_dvec3(p)) == doctest::Approx(1.0).epsilon(eps));
}

template <class E>
void check_invalid(E&& make) {
  try {
    make();
    FAIL("expected cellforge::error(invalid_input)");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::invalid_input);
    CHECK(!e.message().empty());
  }
}

}  // namespace

#define CF_POINT_TYPES glm::dvec3, std::array<float, 3>, test_user::cad_vec

TEST_CASE_TEMPLATE("Platonic solids: counts, closed, outward, regular", P, CF_POINT_TYPES) {
  using namespace cellforge;
  const double phi = std::numbers::phi;
  struct solid_case {
    polygon_soup<P> soup;
    std::int64_t v, e, f;
    std::size_t face_size;
    double volume;
  };
  const double ico_edge = 2.0 / std::sqrt(1.0 + phi * phi);
  const double dode_edge = 2.0 / (std::sqrt(3.0) * phi);
  const std::vector<solid_case> cases{
      {tetrahedron<P>(), 4, 6, 4, 3, 8.0 / (9.0 * std::sqrt(3.0))},
      {hexahedron<P>(), 8, 12, 6, 4, 1.0},
      {octahedron<P>(), 6, 12, 8, 3, 4.0 / 3.0},
      {icosahedron<P>(), 12, 30, 20, 3, 5.0 / 12.0 * (3 + std::sqrt(5.0)) * std::pow(ico_edge, 3)},
      {dodecahedron<P>(), 20, 30, 12, 5, (15 + 7 * std::sqrt(5.0)) / 4.0 * std::pow(dode_edge, 3)},
  };
  for (const auto& c : cases) {
    CAPTURE(c.v);
    check_fixture(c.soup, {.vertices = c.v, .edges = c.e, .faces = c.f, .euler = 2});
    CHECK(is_soup_closed(c.soup));
    CHECK(all_faces_have(c.soup, c.face_size));
    CHECK(signed_volume(c.soup) == doctest::Approx(c.volume).epsilon(1e-6));
    const glm::dvec3 centre = c.v == 8 ? glm::dvec3(0.5) : glm::dvec3(0);
    CHECK(count_inward_faces(c.soup, centre) == 0);
    // Regular: every face edge has the same length (also proves the face vertex order).
    const auto f0 = c.soup.face(0);
    const double edge = glm::length(to_dvec3(c.soup.points[f0[0]]) - to_dvec3(c.soup.points[f0[1]]));
    for (std::size_t f = 0; f < c.soup.num_faces(); ++f) {
      const auto face = c.soup.face(f);
      for (std::size_t i = 0; i < face.size(); ++i)
        CHECK(glm::length(to_dvec3(c.soup.points[face[i]]) -
                          to_dvec3(c.soup.points[face[(i + 1) % face.size()]])) ==
              doctest::Approx(edge).epsilon(1e-6));
    }
    if (c.v != 8) check_on_unit_sphere(c.soup, 1e-6);
  }
  CHECK(glm::length(to_dvec3(icosahedron<P>().points[0]) - to_dvec3(icosahedron<P>().points[1])) ==
        doctest::Approx(ico_edge).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("icosphere and uv_sphere", P, CF_POINT_TYPES) {
  using namespace cellforge;
  double previous_volume = 0;
  for (int k = 0; k <= 4; ++k) {
    const auto s = icosphere<P>(k);
    const std::int64_t p = std::int64_t{1} << (2 * k);
    check_fixture(s, {.vertices = 10 * p + 2, .edges = 30 * p, .faces = 20 * p, .euler = 2});
    check_on_unit_sphere(s, 1e-6);
    CHECK(count_inward_faces(s) == 0);
    CHECK(signed_volume(s) < 4.0 / 3.0 * pi);
    CHECK(signed_volume(s) > previous_volume);  // converges from inside
    previous_volume = signed_volume(s);
  }
  CHECK(previous_volume > 0.99 * 4.0 / 3.0 * pi);
  for (const bool tri : {true, false}) {
    for (const auto& [sl, st] : {std::pair{3, 2}, {8, 5}, {17, 9}}) {
      const auto s = uv_sphere<P>(sl, st, tri);
      const std::int64_t quads = std::int64_t{sl} * (st - 2);
      check_fixture(s, {.vertices = std::int64_t{sl} * (st - 1) + 2,
                        .edges = std::int64_t{sl} * (st - 1) + std::int64_t{sl} * st + (tri ? quads : 0),
                        .faces = 2 * sl + (tri ? 2 : 1) * quads,
                        .euler = 2});
      check_on_unit_sphere(s, 1e-6);
      CHECK(count_inward_faces(s) == 0);
      CHECK(signed_volume(s) > 0);
    }
  }
  CHECK(same_soup(icosphere<P>(3), icosphere<P>(3)));
}

TEST_CASE_TEMPLATE("sphere_with_vertices hits the benchmark vertex counts exactly", P, CF_POINT_TYPES) {
  using namespace cellforge;
  std::vector<int> sizes{64, 144, 256, 400, 1024, 4096};
  for (int n = 4; n <= 130; ++n) sizes.push_back(n);
  for (const int n : sizes) {
    CAPTURE(n);
    const auto s = sphere_with_vertices<P>(n);
    check_fixture(
        s, {.vertices = n, .edges = 3 * std::int64_t{n} - 6, .faces = 2 * std::int64_t{n} - 4, .euler = 2});
    CHECK(all_faces_have(s, 3));
    check_on_unit_sphere(s, 1e-6);
    CHECK(count_inward_faces(s) == 0);
    CHECK(signed_volume(s) > 0);
  }
  // Quality at the benchmark sizes: no sliver triangles, and close to the sphere's volume.
  for (const int n : {64, 144, 256, 400, 1024, 4096}) {
    CAPTURE(n);
    const auto s = sphere_with_vertices<P>(n);
    double min_angle = 180;
    for (std::size_t f = 0; f < s.num_faces(); ++f) {
      const auto t = s.face(f);
      for (int i = 0; i < 3; ++i) {
        const glm::dvec3 a = to_dvec3(s.points[t[static_cast<std::size_t>(i)]]);
        const glm::dvec3 b = to_dvec3(s.points[t[static_cast<std::size_t>((i + 1) % 3)]]);
        const glm::dvec3 c = to_dvec3(s.points[t[static_cast<std::size_t>((i + 2) % 3)]]);
        min_angle = std::min(min_angle,
                             glm::degrees(std::acos(glm::dot(glm::normalize(b - a), glm::normalize(c - a)))));
      }
    }
    CHECK(min_angle > 25.0);
    CHECK(signed_volume(s) > 0.9 * 4.0 / 3.0 * pi);
  }
  CHECK(same_soup(sphere_with_vertices<P>(400), sphere_with_vertices<P>(400)));
}

TEST_CASE_TEMPLATE("torus, cylinder, disk and grid plane", P, CF_POINT_TYPES) {
  using namespace cellforge;
  for (const bool tri : {true, false}) {
    const std::int64_t M = 24, m = 12, k = tri ? 2 : 1;
    const auto t = torus<P>(24, 12, 1.0, 0.3, tri);
    check_fixture(t,
                  {.vertices = M * m, .edges = 2 * M * m + (k - 1) * M * m, .faces = k * M * m, .euler = 0});
    CHECK(signed_volume(t) == doctest::Approx(2 * pi * pi * 0.3 * 0.3).epsilon(0.05));
    CHECK(signed_volume(t) < 2 * pi * pi * 0.3 * 0.3);

    const std::int64_t s = 10, r = 3;
    const auto capped = cylinder<P>(10, 3, true, tri);
    check_fixture(capped, {.vertices = s * (r + 1) + (tri ? 2 : 0),
                           .edges = s * (r + 1) + s * r + (tri ? s * r + 2 * s : 0),
                           .faces = k * s * r + (tri ? 2 * s : 2),
                           .euler = 2});
    CHECK(signed_volume(capped) == doctest::Approx(2 * 0.5 * s * std::sin(2 * pi / s)).epsilon(1e-6));
    CHECK(count_inward_faces(capped) == 0);
    const auto open = cylinder<P>(10, 3, false, tri);
    check_fixture(open, {.vertices = s * (r + 1), .boundary = 2 * s, .euler = 0});
    CHECK(count_boundary_loops(open) == 2);

    const auto g = grid_plane<P>(5, 3, tri);
    check_fixture(g, {.vertices = 6 * 4, .faces = k * 15, .boundary = 2 * (5 + 3), .euler = 1});
    CHECK(count_boundary_loops(g) == 1);
    for (std::size_t f = 0; f < g.num_faces(); ++f) {
      const auto face = g.face(f);
      const glm::dvec3 a = to_dvec3(g.points[face[0]]), b = to_dvec3(g.points[face[1]]),
                       c = to_dvec3(g.points[face[2]]);
      CHECK(glm::cross(b - a, c - a).z > 0);  // faces +z
    }
  }
  const auto d = disk<P>(12, 4);
  check_fixture(d, {.vertices = 1 + 12 * 4, .faces = 12 * 7, .boundary = 12, .euler = 1});
  CHECK(count_boundary_loops(d) == 1);
  for (std::size_t f = 0; f < d.num_faces(); ++f) {
    const auto face = d.face(f);
    const glm::dvec3 a = to_dvec3(d.points[face[0]]), b = to_dvec3(d.points[face[1]]),
                     c = to_dvec3(d.points[face[2]]);
    CHECK(glm::cross(b - a, c - a).z > 0);
  }
}

TEST_CASE_TEMPLATE("Möbius strip: one boundary loop, seam edges agree in direction", P, CF_POINT_TYPES) {
  using namespace cellforge;
  for (const bool tri : {true, false})
    for (const auto& dims : {std::pair{3, 1}, {5, 2}, {16, 16}, {7, 3}}) {
      const int a = dims.first, c = dims.second;
      CAPTURE(a);
      CAPTURE(c);
      const std::int64_t A = a, C = c, k = tri ? 2 : 1;
      const auto m = mobius_strip<P>(a, c, tri);
      check_fixture(m, {.vertices = A * (C + 1),
                        .edges = A * (C + 1) + A * C + (k - 1) * A * C,
                        .faces = k * A * C,
                        .boundary = 2 * A,
                        .inconsistent = C,
                        .euler = 0,
                        .orientable = false});
      CHECK(count_boundary_loops(m) == 1);
    }
  CHECK(same_soup(mobius_band<P>(), mobius_strip<P>(16, 16, true)));
}

TEST_CASE_TEMPLATE("Klein bottle and projective plane are closed and non-orientable", P, CF_POINT_TYPES) {
  using namespace cellforge;
  for (const bool tri : {true, false})
    for (const auto& dims : {std::pair{3, 3}, {4, 6}, {32, 16}}) {
      const int u = dims.first, v = dims.second;
      CAPTURE(u);
      CAPTURE(v);
      const std::int64_t U = u, V = v, k = tri ? 2 : 1;
      const auto kb = klein_bottle<P>(u, v, tri);
      check_fixture(kb, {.vertices = U * V,
                         .edges = 2 * U * V + (k - 1) * U * V,
                         .faces = k * U * V,
                         .inconsistent = V,
                         .euler = 0,
                         .orientable = false});
      CHECK(is_soup_closed(kb));
    }
  const auto rp2 = projective_plane<P>();
  check_fixture(
      rp2, {.vertices = 6, .edges = 15, .faces = 10, .inconsistent = -1, .euler = 1, .orientable = false});
  CHECK(is_soup_closed(rp2));
  // The torus, unlike the Klein bottle with the same Euler characteristic, is orientable
  // and consistently oriented.
  const auto t = torus<P>(8, 6);
  CHECK(is_soup_orientable(t));
  CHECK(count_inconsistent_edges(t) == 0);
}

TEST_CASE_TEMPLATE("random orientation plane", P, CF_POINT_TYPES) {
  using namespace cellforge;
  const int nx = 8, ny = 6;
  const std::uint64_t seed = 20240601;
  const auto plain = grid_plane<P>(nx, ny, true);
  const auto r = random_orientation_plane<P>(nx, ny, seed);
  // Which faces were reversed, read back from the output and from the documented bit source.
  std::vector<bool> flipped(r.num_faces());
  std::mt19937_64 bits(seed);
  std::size_t flips = 0;
  for (std::size_t f = 0; f < r.num_faces(); ++f) {
    const auto a = plain.face(f), b = r.face(f);
    flipped[f] = !std::equal(a.begin(), a.end(), b.begin());
    if (flipped[f]) CHECK((a[0] == b[0] && a[1] == b[2] && a[2] == b[1]));
    CHECK(flipped[f] == ((bits() >> 63) != 0));
    flips += flipped[f];
  }
  CHECK(flips > 0);
  CHECK(flips < r.num_faces());
  // Inconsistent edges, counted independently: interior edges between a flipped and a kept face.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> faces_of;
  for (std::size_t f = 0; f < plain.num_faces(); ++f) {
    const auto face = plain.face(f);
    for (std::size_t i = 0; i < 3; ++i)
      faces_of[{std::min(face[i], face[(i + 1) % 3]), std::max(face[i], face[(i + 1) % 3])}].push_back(f);
  }
  std::int64_t disagree = 0;
  for (const auto& [e, fs] : faces_of) disagree += fs.size() == 2 && flipped[fs[0]] != flipped[fs[1]];
  CHECK(disagree > 0);
  check_fixture(r, {.vertices = (nx + 1) * (ny + 1),
                    .faces = 2 * nx * ny,
                    .boundary = 2 * (nx + ny),
                    .inconsistent = disagree,
                    .euler = 1,
                    .orientable = true});
  CHECK(same_soup(r, random_orientation_plane<P>(nx, ny, seed)));
  CHECK(!same_soup(r, random_orientation_plane<P>(nx, ny, seed + 1)));
}

TEST_CASE_TEMPLATE("lattice and tree tube meshes are closed manifolds of the right genus", P,
                   CF_POINT_TYPES) {
  using namespace cellforge;
  using namespace cellforge::samples;
  for (const bool tri : {false, true})
    for (const auto& dims : {std::array{1, 1, 1}, {3, 1, 1}, {2, 2, 1}, {2, 2, 2}, {4, 3, 2}, {10, 8, 3}}) {
      const int nx = dims[0], ny = dims[1], nz = dims[2];
      CAPTURE(nx);
      CAPTURE(ny);
      CAPTURE(nz);
      const lattice_tube_options opt{.spacing = 2.0, .width = 0.5, .triangles = tri};
      const auto mesh = lattice_tube_mesh<P>(nx, ny, nz, opt);
      const std::int64_t nodes = std::int64_t{nx} * ny * nz;
      const std::int64_t edges = std::int64_t{nx - 1} * ny * nz + std::int64_t{nx} * (ny - 1) * nz +
                                 std::int64_t{nx} * ny * (nz - 1);
      const std::int64_t genus = edges - nodes + 1;
      check_fixture(mesh, {.euler = 2 - 2 * genus});
      CHECK(is_soup_closed(mesh));
      CHECK(all_faces_have(mesh, tri ? 3 : 4));
      const double w = opt.width, s = opt.spacing;
      CHECK(signed_volume(mesh) ==
            doctest::Approx(nodes * w * w * w + edges * w * w * (s - w)).epsilon(1e-5));
    }
  for (int depth = 0; depth <= 8; ++depth) {
    CAPTURE(depth);
    const auto tree = tree_tube_mesh<P>(depth);
    check_fixture(tree, {.euler = 2});
    CHECK(is_soup_closed(tree));
    CHECK(signed_volume(tree) > 0);
  }
  // A square ring of four nodes: genus 1, and its hole is really there (volume of 4 + 4 pieces).
  const std::vector<std::array<int, 3>> ring{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<std::array<std::uint32_t, 2>> ring_edges{{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  const auto r = lattice_graph_tube_mesh<P>(ring, ring_edges);
  check_fixture(r, {.euler = 0});
  CHECK(signed_volume(r) == doctest::Approx(4 * 0.125 + 4 * 0.125).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("spline tube", P, CF_POINT_TYPES) {
  using namespace cellforge;
  using namespace cellforge::samples;
  for (const bool tri : {true, false}) {
    const spline_tube_options opt{
        .segments_around = 10, .samples_per_span = 6, .radius = 0.1, .triangles = tri};
    const auto tube = spline_tube<P>(opt);
    const std::int64_t rings = 5 * 6 + 1, around = 10;
    check_fixture(tube, {.vertices = rings * around + (tri ? 2 : 0), .euler = 2});
    CHECK(signed_volume(tube) > 0);
    auto open_opt = opt;
    open_opt.capped = false;
    const auto open = spline_tube<P>(open_opt);
    check_fixture(open, {.vertices = rings * around, .boundary = 2 * around, .euler = 0});
    CHECK(count_boundary_loops(open) == 2);
  }
  // Along a straight line the frames must not turn: vertex 0 of every ring stays on one line,
  // and the volume is that of a prism of the same length.
  const std::vector<P> line{point_traits<P>::make(0, 0, 0), point_traits<P>::make(1, 1, 1),
                            point_traits<P>::make(2, 2, 2), point_traits<P>::make(3, 3, 3)};
  const spline_tube_options opt{.segments_around = 8, .samples_per_span = 4, .radius = 0.2};
  const auto straight = spline_tube<P>(line, opt);
  const glm::dvec3 first = to_dvec3(straight.points[0]), axis = glm::normalize(glm::dvec3(1, 1, 1));
  for (std::size_t ring = 0; ring < 13; ++ring) {
    const glm::dvec3 d = to_dvec3(straight.points[ring * 8]) - first;
    CHECK(glm::length(d - glm::dot(d, axis) * axis) < 1e-5);
  }
  const double prism = 0.5 * 8 * 0.2 * 0.2 * std::sin(2 * pi / 8) * 3 * std::sqrt(3.0);
  CHECK(signed_volume(straight) == doctest::Approx(prism).epsilon(1e-5));
  // A curve with a U-turn stays closed and outward.
  const std::vector<glm::dvec3> hook{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0.5}};
  const auto bent = spline_tube<P>(hook, opt);
  check_fixture(bent, {.euler = 2});
  CHECK(signed_volume(bent) > 0);
}

TEST_CASE_TEMPLATE("soup helpers: transforms, fan triangulation, counts", P, CF_POINT_TYPES) {
  using namespace cellforge;
  const auto cube = hexahedron<P>();
  CHECK(signed_volume(scaled(cube, 2.0)) == doctest::Approx(8.0));
  CHECK(signed_volume(scaled(cube, glm::dvec3(1, 2, 3))) == doctest::Approx(6.0));
  // A mirror keeps the solid outward by reversing its faces.
  const auto mirrored = scaled(cube, glm::dvec3(-1, 1, 1));
  CHECK(signed_volume(mirrored) == doctest::Approx(1.0));
  CHECK(count_inward_faces(mirrored, glm::dvec3(-0.5, 0.5, 0.5)) == 0);
  const auto moved = transformed(cube, glm::translate(glm::dmat4(1.0), glm::dvec3(5, 0, 0)));
  CHECK(to_dvec3(moved.points[0]) == glm::dvec3(5, 0, 0));
  CHECK(signed_volume(moved) == doctest::Approx(1.0));
  glm::dmat4 projective(1.0);
  projective[0][3] = 1;
  check_invalid([&] { (void)transformed(cube, projective); });

  const auto tris = triangulate_fan(cube);
  CHECK(tris.num_faces() == 12);
  check_fixture(tris, {.vertices = 8, .edges = 18, .faces = 12, .euler = 2});
  CHECK(signed_volume(tris) == doctest::Approx(1.0));
  const auto dode = triangulate_fan(dodecahedron<P>());
  CHECK(dode.num_faces() == 36);
  CHECK(signed_volume(dode) == doctest::Approx(signed_volume(dodecahedron<P>())));

  // Unreferenced points do not count; a fin of three faces on one edge is non-manifold.
  polygon_soup<P> fin;
  for (int i = 0; i < 6; ++i) fin.points.push_back(point_traits<P>::make(i, i * i, 1));
  fin.add_face({0, 1, 2});
  fin.add_face({1, 0, 3});
  fin.add_face({0, 1, 4});
  const soup_statistics st = analyze_soup(fin);
  CHECK(st.vertices == 5);
  CHECK(st.edges == 7);
  CHECK(st.nonmanifold_edges == 1);
  CHECK(st.boundary_edges == 6);
  CHECK(st.euler_characteristic() == 5 - 7 + 3);
  fin.add_face({2, 2, 5});
  CHECK(analyze_soup(fin).degenerate_faces == 1);
  std::vector<std::uint32_t> big_face(20);
  for (std::uint32_t i = 0; i < 20; ++i) {
    fin.points.push_back(point_traits<P>::make(std::cos(i * 0.3), std::sin(i * 0.3), 0));
    big_face[i] = 6 + i;
  }
  fin.add_face(big_face);
  CHECK(analyze_soup(fin).degenerate_faces == 1);
  big_face[17] = big_face[3];
  fin.add_face(big_face);
  CHECK(analyze_soup(fin).degenerate_faces == 2);
  auto broken = fin;
  broken.face_offsets.back() += 1;  // offsets that run past the index array
  check_invalid([&] { (void)analyze_soup(broken); });
  fin.add_face({0, 99, 1});
  check_invalid([&] { (void)analyze_soup(fin); });
  check_invalid([&] { (void)signed_volume(fin); });

  // Two triangles, first consistent, then one reversed.
  polygon_soup<P> pair;
  for (int i = 0; i < 4; ++i) pair.points.push_back(point_traits<P>::make(i & 1, i >> 1, 0));
  pair.add_face({0, 1, 3});
  pair.add_face({0, 3, 2});
  CHECK(count_inconsistent_edges(pair) == 0);
  pair.face_vertices = {0, 1, 3, 0, 2, 3};
  CHECK(count_inconsistent_edges(pair) == 1);
  CHECK(is_soup_orientable(pair));
  CHECK(!is_soup_closed(pair));
  CHECK(is_soup_closed(polygon_soup<P>{}));
}

TEST_CASE("invalid parameters throw invalid_input") {
  using namespace cellforge;
  using namespace cellforge::samples;
  using P = glm::dvec3;
  check_invalid([] { (void)icosphere<P>(-1); });
  check_invalid([] { (void)icosphere<P>(40); });
  check_invalid([] { (void)uv_sphere<P>(2, 4); });
  check_invalid([] { (void)uv_sphere<P>(8, 1); });
  check_invalid([] { (void)uv_sphere<P>(1 << 30, 1 << 30); });
  check_invalid([] { (void)sphere_with_vertices<P>(3); });
  check_invalid([] { (void)sphere_with_vertices<P>(-10); });
  check_invalid([] { (void)torus<P>(2, 8); });
  check_invalid([] { (void)torus<P>(8, 2); });
  check_invalid([] { (void)torus<P>(8, 8, 1.0, 1.5); });
  check_invalid([] { (void)torus<P>(8, 8, 1.0, 0.0); });
  check_invalid([] { (void)torus<P>(8, 8, std::nan(""), 0.1); });
  check_invalid([] { (void)cylinder<P>(2, 1, true, true); });
  check_invalid([] { (void)cylinder<P>(8, 0, true, true); });
  check_invalid([] { (void)disk<P>(2, 1); });
  check_invalid([] { (void)disk<P>(5, 0); });
  check_invalid([] { (void)grid_plane<P>(0, 3); });
  check_invalid([] { (void)grid_plane<P>(3, -1); });
  check_invalid([] { (void)mobius_strip<P>(2, 4); });
  check_invalid([] { (void)mobius_strip<P>(8, 0); });
  check_invalid([] { (void)klein_bottle<P>(2, 8); });
  check_invalid([] { (void)klein_bottle<P>(8, 2); });
  check_invalid([] { (void)random_orientation_plane<P>(0, 4, 1); });
  check_invalid([] { (void)lattice_tube_mesh<P>(0, 1, 1); });
  check_invalid([] { (void)lattice_tube_mesh<P>(2, 2, 2, {.spacing = 1, .width = 1}); });
  check_invalid([] { (void)lattice_tube_mesh<P>(2, 2, 2, {.spacing = 1, .width = -0.1}); });
  check_invalid([] { (void)tree_tube_mesh<P>(-1); });
  check_invalid([] { (void)tree_tube_mesh<P>(64); });
  const std::vector<std::array<int, 3>> nodes{{0, 0, 0}, {1, 0, 0}, {1, 1, 1}, {0, 0, 0}};
  using edge_list = std::vector<std::array<std::uint32_t, 2>>;
  check_invalid([&] { (void)lattice_graph_tube_mesh<P>(std::span(nodes.data(), 2), edge_list{{0, 5}}); });
  check_invalid([&] { (void)lattice_graph_tube_mesh<P>(std::span(nodes.data(), 3), edge_list{{1, 2}}); });
  check_invalid([&] {
    (void)lattice_graph_tube_mesh<P>(std::span(nodes.data(), 2), edge_list{{0, 1}, {1, 0}});
  });
  check_invalid([&] { (void)lattice_graph_tube_mesh<P>(nodes, edge_list{}); });
  const std::vector<std::array<int, 3>> far{{1 << 20, 0, 0}};
  check_invalid([&] { (void)lattice_graph_tube_mesh<P>(far, edge_list{}); });
  check_invalid([] { (void)spline_tube<P>(std::vector<P>{{0, 0, 0}}); });
  check_invalid([] { (void)spline_tube<P>(std::vector<P>{{0, 0, 0}, {0, 0, 0}, {1, 0, 0}}); });
  check_invalid([] { (void)spline_tube<P>(std::vector<P>{{0, 0, 0}, {std::nan(""), 0, 0}}); });
  check_invalid([] { (void)spline_tube<P>({.segments_around = 2}); });
  check_invalid([] { (void)spline_tube<P>({.samples_per_span = 0}); });
  check_invalid([] { (void)spline_tube<P>({.radius = 0}); });
}

}  // namespace shapes_tests
