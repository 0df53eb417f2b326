// SPDX-License-Identifier: MIT
// The sample models' ground truth checked for self-consistency with code of this file only:
// faces use existing edges and are planar, volumes are closed surfaces, per object
// V − E + F − C is 1, no face repeats; plus the expected sizes and same_faces/same_volumes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/samples/wireframe_models.hpp"

// The pieces this file tests, named (its page above includes them).
#include "cellforge/samples/wireframe_models_builders.hpp"
#include "cellforge/samples/wireframe_models_core.hpp"
#include "cellforge/samples/wireframe_models_fixtures.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace sample_models_tests {

using cellforge::samples::sample_model;

namespace {

using edge_key = std::pair<std::uint32_t, std::uint32_t>;
edge_key key(std::uint32_t a, std::uint32_t b) { return {std::min(a, b), std::max(a, b)}; }

// Objects: connected components of the wire graph joined through faces (a hole's outline
// is tied to its face's outer loop only by the face), by union-find.
std::vector<std::uint32_t> components(const sample_model& m) {
  std::vector<std::uint32_t> parent(m.wire.points.size());
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& e : m.wire.edges) parent[find(e[0])] = find(e[1]);
  for (const auto& face : m.faces)
    for (const auto& loop : face)
      for (const std::uint32_t v : loop) parent[find(v)] = find(face[0][0]);
  for (std::uint32_t v = 0; v < parent.size(); ++v) parent[v] = find(v);
  return parent;
}

// A face loop as a canonical sequence (smallest vertex first, towards the smaller neighbour).
std::vector<std::uint32_t> canon(std::vector<std::uint32_t> l) {
  std::rotate(l.begin(), std::min_element(l.begin(), l.end()), l.end());
  if (l.size() > 2 && l.back() < l[1]) std::reverse(l.begin() + 1, l.end());
  return l;
}

void check_consistent(const sample_model& m, long expected_euler = 1) {
  const std::string name = m.name;
  CAPTURE(name);
  const auto& pts = m.wire.points;
  const std::size_t nv = pts.size();
  // The wire: no zero-length, out-of-range or repeated edges, no coincident points, no isolated vertex.
  std::set<edge_key> edges;
  std::vector<int> degree(nv, 0);
  for (const auto& e : m.wire.edges) {
    REQUIRE(e[0] < nv);
    REQUIRE(e[1] < nv);
    CHECK(e[0] != e[1]);
    CHECK(edges.insert(key(e[0], e[1])).second);
    ++degree[e[0]];
    ++degree[e[1]];
  }
  for (std::size_t v = 0; v < nv; ++v) CHECK(degree[v] >= 2);
  std::set<std::array<double, 3>> distinct;
  for (const auto& p : pts) distinct.insert({p.x, p.y, p.z});
  CHECK(distinct.size() == nv);
  double size = 0;
  for (const auto& p : pts) size = std::max({size, std::abs(p.x), std::abs(p.y), std::abs(p.z)});

  // Faces: loops of 3+ distinct vertices along existing edges, planar, distinct from each other.
  std::set<std::vector<std::vector<std::uint32_t>>> seen;
  std::map<edge_key, int> face_uses;
  for (const auto& face : m.faces) {
    REQUIRE(!face.empty());
    std::set<std::uint32_t> in_face;
    for (const auto& loop : face) {
      REQUIRE(loop.size() >= 3);
      for (std::size_t i = 0; i < loop.size(); ++i) {
        REQUIRE(loop[i] < nv);
        CHECK(in_face.insert(loop[i]).second);
        const edge_key k = key(loop[i], loop[(i + 1) % loop.size()]);
        CHECK(edges.count(k) == 1);
        ++face_uses[k];
      }
    }
    // Plane through the first three non-collinear outer vertices; every vertex within 1e-9·size.
    const auto& o = face[0];
    glm::dvec3 n(0);
    for (std::size_t i = 2; i < o.size() && glm::length(n) < 1e-9 * size * size; ++i)
      n = glm::cross(pts[o[1]] - pts[o[0]], pts[o[i]] - pts[o[0]]);
    REQUIRE(glm::length(n) > 0);
    n = glm::normalize(n);
    for (const auto& loop : face)
      for (const std::uint32_t v : loop) CHECK(std::abs(glm::dot(pts[v] - pts[o[0]], n)) <= 1e-9 * size);
    std::vector<std::vector<std::uint32_t>> c;
    for (const auto& loop : face) c.push_back(canon(loop));
    std::sort(c.begin() + 1, c.end());
    CHECK(seen.insert(c).second);
  }
  // Every wire edge bounds some face.
  for (const auto& e : edges) CHECK(face_uses.count(e) == 1);

  // Volumes: closed surfaces (every edge used by exactly 0 or 2 of its faces); every face in 1 or 2 volumes.
  std::vector<int> volumes_of_face(m.faces.size(), 0);
  for (const auto& vol : m.volumes) {
    REQUIRE(vol.size() >= 4);
    std::map<edge_key, int> uses;
    std::set<std::uint32_t> distinct_faces(vol.begin(), vol.end());
    CHECK(distinct_faces.size() == vol.size());
    for (const std::uint32_t f : vol) {
      REQUIRE(f < m.faces.size());
      ++volumes_of_face[f];
      for (const auto& loop : m.faces[f])
        for (std::size_t i = 0; i < loop.size(); ++i) ++uses[key(loop[i], loop[(i + 1) % loop.size()])];
    }
    for (const auto& [k, n] : uses) CHECK(n == 2);
  }
  for (const int n : volumes_of_face) CHECK((n == 1 || n == 2));

  // Per object (connected component): V − E + F − C.
  const auto comp = components(m);
  std::map<std::uint32_t, long> euler;
  for (std::uint32_t v = 0; v < nv; ++v) euler[comp[v]] += 1;
  for (const auto& e : m.wire.edges) euler[comp[e[0]]] -= 1;
  for (const auto& face : m.faces) euler[comp[face[0][0]]] += 1;
  for (const auto& vol : m.volumes) euler[comp[m.faces[vol[0]][0][0]]] -= 1;
  for (const auto& [c, x] : euler) CHECK(x == expected_euler);
}

struct sizes {
  std::size_t v, e, f, c, objects, unforced;
};

void check_sizes(const sample_model& m, const sizes& s) {
  const std::string name = m.name;
  CAPTURE(name);
  CHECK(m.wire.points.size() == s.v);
  CHECK(m.wire.edges.size() == s.e);
  CHECK(m.faces.size() == s.f);
  CHECK(m.volumes.size() == s.c);
  const auto comp = components(m);
  CHECK(std::set<std::uint32_t>(comp.begin(), comp.end()).size() == s.objects);
  CHECK(m.unforced_faces == s.unforced);
}

std::size_t non_convex_faces(const sample_model& m) {
  std::size_t count = 0;
  for (const auto& face : m.faces) {
    const auto& o = face[0];
    const auto& p = m.wire.points;
    glm::dvec3 ref(0);
    bool reflex = face.size() > 1;
    for (std::size_t i = 0; i < o.size(); ++i) {
      const glm::dvec3 c =
          glm::cross(p[o[(i + 1) % o.size()]] - p[o[i]], p[o[(i + 2) % o.size()]] - p[o[(i + 1) % o.size()]]);
      if (glm::length(c) < 1e-12) continue;
      if (glm::length(ref) == 0) ref = c;
      if (glm::dot(ref, c) < 0) reflex = true;
    }
    count += reflex ? 1 : 0;
  }
  return count;
}

}  // namespace

TEST_CASE("sample models: every ground truth is self-consistent") {
  for (const auto& m : cellforge::samples::all_small_samples()) check_consistent(m);
  for (std::size_t n = 3; n <= 32; ++n) {
    check_consistent(cellforge::samples::sample_prism(n));
    check_consistent(cellforge::samples::sample_pyramid(n));
  }
  for (int i = 1; i <= 6; ++i) check_consistent(cellforge::samples::sample_seed(i));
  check_consistent(cellforge::samples::sample_close_edges());
  check_consistent(cellforge::samples::sample_uv_sphere(5, 4));
  check_consistent(cellforge::samples::sample_grid(4, 1, 2));
}

TEST_CASE("sample models: sizes, objects and unforced faces") {
  check_sizes(cellforge::samples::sample_tetrahedron(), {4, 6, 4, 1, 1, 0});
  check_sizes(cellforge::samples::sample_cube(), {8, 12, 6, 1, 1, 0});
  check_sizes(cellforge::samples::sample_octahedron(), {6, 12, 8, 1, 1, 0});
  check_sizes(cellforge::samples::sample_prism(7), {14, 21, 9, 1, 1, 0});
  check_sizes(cellforge::samples::sample_pyramid(32), {33, 64, 33, 1, 1, 0});
  check_sizes(cellforge::samples::sample_uv_sphere(8, 6), {42, 88, 48, 1, 1, 0});
  // Odd slices too: the rings are cycles no edge needs, so the sphere is one volume.
  check_sizes(cellforge::samples::sample_uv_sphere(7, 6), {37, 77, 42, 1, 1, 0});
  check_sizes(cellforge::samples::sample_two_cubes(), {12, 20, 11, 2, 1, 0});
  check_sizes(cellforge::samples::sample_grid(2, 2, 2), {27, 54, 36, 8, 1, 0});
  // 3×3×3: 64 vertices, 144 edges, 108 faces; no edge needs the 6 walls around the middle cube
  // nor the middle squares of the 6 sides; 4×4×4: the 36 walls inside and 24 squares.
  check_sizes(cellforge::samples::sample_grid(3, 3, 3), {64, 144, 108, 27, 1, 12});
  check_sizes(cellforge::samples::sample_grid(4, 4, 4), {125, 300, 240, 64, 1, 60});
  check_sizes(cellforge::samples::sample_L(), {12, 18, 8, 1, 1, 0});
  check_sizes(cellforge::samples::sample_T(), {16, 24, 10, 1, 1, 0});
  check_sizes(cellforge::samples::sample_U(), {16, 24, 10, 1, 1, 0});
  check_sizes(cellforge::samples::sample_house(), {9, 16, 9, 1, 1, 0});
  check_sizes(cellforge::samples::sample_disjoint_solids(), {20, 30, 14, 2, 2, 0});
  check_sizes(cellforge::samples::sample_split_edges(), {19, 23, 6, 1, 1, 0});
  check_sizes(cellforge::samples::sample_frame(), {16, 24, 10, 1, 1, 0});
  check_sizes(cellforge::samples::sample_block_with_hole(), {16, 24, 10, 1, 1, 0});
  check_sizes(cellforge::samples::sample_thin_slab(), {12, 20, 11, 2, 1, 0});
  check_sizes(cellforge::samples::sample_close_edges(), {770, 2304, 1536, 1, 1, 0});
  // The seed's samples exactly, except sample 4 (near; docs/sample_models.md).
  check_sizes(cellforge::samples::sample_seed(1), {66, 128, 66, 2, 2, 0});
  check_sizes(cellforge::samples::sample_seed(2), {16, 28, 16, 3, 1, 0});
  check_sizes(cellforge::samples::sample_seed(3), {24, 40, 19, 2, 1, 0});
  check_sizes(cellforge::samples::sample_seed(4), {539, 1080, 544, 2, 1, 0});
  check_sizes(cellforge::samples::sample_seed(5), {466, 944, 480, 1, 1, 0});
  check_sizes(cellforge::samples::sample_seed(6), {710, 2124, 1428, 13, 1, 12});
}

TEST_CASE("sample models: merged and holed faces") {
  // L, T, U: top and bottom are single non-convex faces with no edge inside them.
  CHECK(non_convex_faces(cellforge::samples::sample_L()) == 2);
  CHECK(non_convex_faces(cellforge::samples::sample_T()) == 2);
  CHECK(non_convex_faces(cellforge::samples::sample_U()) == 2);
  const auto longest = [](const sample_model& m) {
    std::size_t n = 0;
    for (const auto& f : m.faces) n = std::max(n, f[0].size());
    return n;
  };
  CHECK(longest(cellforge::samples::sample_L()) == 6);
  CHECK(longest(cellforge::samples::sample_T()) == 8);
  CHECK(longest(cellforge::samples::sample_U()) == 8);
  for (const auto& m : {cellforge::samples::sample_frame(), cellforge::samples::sample_block_with_hole()}) {
    std::size_t holed = 0;
    for (const auto& f : m.faces) holed += f.size() == 2 ? 1 : 0;
    CHECK(holed == 2);
  }
  const auto stepped = cellforge::samples::sample_stepped_block();
  CHECK(stepped.volumes.size() == 4);
  CHECK(non_convex_faces(stepped) >= 3);  // two staircase sides and the staircase wall
  // The octahedron's equator squares are cycles of edges but not faces.
  const auto octa = cellforge::samples::sample_octahedron();
  for (const auto& f : octa.faces) CHECK(f[0].size() == 3);
}

TEST_CASE("sample models: split edges are collinear chains") {
  const auto m = cellforge::samples::sample_split_edges();
  std::vector<int> degree(m.wire.points.size(), 0);
  for (const auto& e : m.wire.edges) ++degree[e[0]], ++degree[e[1]];
  std::size_t middles = 0;
  for (std::size_t v = 0; v < degree.size(); ++v) {
    if (degree[v] != 2) continue;
    ++middles;
    std::vector<glm::dvec3> dirs;
    for (const auto& e : m.wire.edges)
      if (e[0] == v || e[1] == v) dirs.push_back(m.wire.points[e[0] == v ? e[1] : e[0]] - m.wire.points[v]);
    REQUIRE(dirs.size() == 2);
    CHECK(glm::length(glm::cross(dirs[0], dirs[1])) < 1e-12);
    CHECK(glm::dot(dirs[0], dirs[1]) < 0);
  }
  CHECK(middles == 11);
}

TEST_CASE("same_faces and same_volumes: rotation, reversal and order do not matter; changes do") {
  std::mt19937 rng(7);
  for (const auto& m : {cellforge::samples::sample_stepped_block(), cellforge::samples::sample_frame(),
                        cellforge::samples::sample_grid(2, 1, 2)}) {
    const std::string name = m.name;
    CAPTURE(name);
    // Shuffle faces, rotate and reverse loops, reorder holes; renumber volumes through the permutation.
    std::vector<std::uint32_t> perm(m.faces.size());
    std::iota(perm.begin(), perm.end(), 0u);
    std::shuffle(perm.begin(), perm.end(), rng);
    std::vector<std::vector<std::vector<std::uint32_t>>> faces(m.faces.size());
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
      auto face = m.faces[f];
      for (auto& loop : face) {
        std::rotate(loop.begin(), loop.begin() + static_cast<std::ptrdiff_t>(rng() % loop.size()),
                    loop.end());
        if (rng() % 2) std::reverse(loop.begin(), loop.end());
      }
      if (face.size() > 2) std::reverse(face.begin() + 1, face.end());
      faces[perm[f]] = face;
    }
    std::vector<std::vector<std::pair<std::uint32_t, int>>> volumes;
    for (const auto& vol : m.volumes) {
      volumes.emplace_back();
      for (const auto f : vol) volumes.back().push_back({perm[f], rng() % 2 ? 1 : -1});
    }
    std::reverse(volumes.begin(), volumes.end());
    CHECK(cellforge::samples::same_faces(m.faces, faces));
    CHECK(cellforge::samples::same_volumes(m.faces, m.volumes, faces, volumes));

    // A face with two vertices swapped is a different cycle.
    auto changed = faces;
    std::swap(changed[0][0][0], changed[0][0][1]);
    CHECK_FALSE(cellforge::samples::same_faces(m.faces, changed));
    // A missing or a doubled face.
    auto fewer = faces;
    fewer.pop_back();
    CHECK_FALSE(cellforge::samples::same_faces(m.faces, fewer));
    auto doubled = faces;
    doubled.back() = doubled.front();
    CHECK_FALSE(cellforge::samples::same_faces(m.faces, doubled));
    // A volume that loses a face, or two volumes merged.
    auto vols = volumes;
    vols[0].pop_back();
    CHECK_FALSE(cellforge::samples::same_volumes(m.faces, m.volumes, faces, vols));
    if (volumes.size() > 1) {
      auto merged = volumes;
      merged[0].insert(merged[0].end(), merged[1].begin(), merged[1].end());
      merged.erase(merged.begin() + 1);
      CHECK_FALSE(cellforge::samples::same_volumes(m.faces, m.volumes, faces, merged));
    }
  }
}

TEST_CASE("sample models: transformed keeps the truth and moves the points") {
  const auto m = cellforge::samples::sample_house();
  const auto t = cellforge::samples::transformed(m, glm::dmat3(1e6), glm::dvec3(1, 2, 3));
  CHECK(t.faces == m.faces);
  CHECK(t.volumes == m.volumes);
  CHECK(t.wire.points[3] == m.wire.points[3] * 1e6 + glm::dvec3(1, 2, 3));
  check_consistent(cellforge::samples::transformed(cellforge::samples::sample_stepped_block(),
                                                   glm::dmat3(1e-6), glm::dvec3(0)));
}

TEST_CASE("sample models: bad parameters throw") {
  using cellforge::error;
  CHECK_THROWS_AS(cellforge::samples::sample_prism(2), error);
  CHECK_THROWS_AS(cellforge::samples::sample_pyramid(0), error);
  CHECK_THROWS_AS(cellforge::samples::sample_uv_sphere(8, 1), error);
  CHECK_THROWS_AS(cellforge::samples::sample_grid(0, 1, 1), error);
  CHECK_THROWS_AS(cellforge::samples::sample_seed(7), error);
  auto l = cellforge::samples::empty_layout({0, 1, 2}, {0, 1, 2}, {0, 1});
  l.at(0, 0, 0) = 2;  // label 1 unused
  CHECK_THROWS_AS(cellforge::samples::make_voxel_model(l, "gap"), error);
  l.at(0, 0, 0) = -1;
  CHECK_THROWS_AS(cellforge::samples::make_voxel_model(l, "negative"), error);
  l.labels.pop_back();
  CHECK_THROWS_AS(cellforge::samples::make_voxel_model(l, "short"), error);
  // A face outline touching itself: the top of a hook of cells whose ends (1,1) and (2,2)
  // meet only at the corner (2,2).
  auto p = cellforge::samples::empty_layout({0, 1, 2, 3, 4}, {0, 1, 2, 3}, {0, 1});
  for (const auto& c : {std::array<std::size_t, 2>{1, 1}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {3, 2}, {2, 2}})
    p.at(c[0], c[1], 0) = 1;
  CHECK_THROWS_AS(cellforge::samples::make_voxel_model(p, "pinched"), error);
}

TEST_CASE("sample models: the close-edges tube has no planar ring") {
  const auto m = cellforge::samples::sample_close_edges();
  for (std::size_t r = 0; r < 16; ++r) {
    // Best-fit plane by Newell's normal through the centroid; some point must be well off it.
    glm::dvec3 n(0), c(0);
    for (std::size_t i = 0; i < 48; ++i) {
      const glm::dvec3 a = m.wire.points[r * 48 + i], b = m.wire.points[r * 48 + (i + 1) % 48];
      n += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
      c += a / 48.0;
    }
    n = glm::normalize(n);
    double off = 0;
    for (std::size_t i = 0; i < 48; ++i)
      off = std::max(off, std::abs(glm::dot(m.wire.points[r * 48 + i] - c, n)));
    CHECK(off > 1e-3);
    CHECK(off < 1e-2);
  }
  for (const auto& f : m.faces) CHECK(f[0].size() == 3);
}

}  // namespace sample_models_tests
