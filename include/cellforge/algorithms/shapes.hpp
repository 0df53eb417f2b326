// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Shape primitives that double as test fixtures and benchmark inputs: Platonic solids, spheres
/// with exact vertex counts, cylinders, disks, grids, tori, Möbius strips, Klein bottles, the
/// projective plane and solids of revolution. The soup queries and transforms are in
/// algorithms/soup_queries.hpp and algorithms/soup_transforms.hpp (included here too); the tube
/// meshes of the seed-001 tables are test data, in samples/tube_soups.hpp.
///
/// Every generator is deterministic, costs O(output size), returns a polygon_soup of the
/// caller's point type and throws error(invalid_input) for parameters it cannot honour.
/// No face repeats a vertex and no undirected edge is used by more than two faces.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/detail/shape_building.hpp"
#include "cellforge/algorithms/soup_queries.hpp"
#include "cellforge/algorithms/soup_transforms.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"

namespace cellforge {

// ------------------------------------------------------------------------------------
// Platonic solids, all faces counter-clockwise seen from outside.
// ------------------------------------------------------------------------------------

/// Regular tetrahedron with unit circumradius (vertices at (±1,±1,±1)/√3, even sign count).
/// O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> tetrahedron() {
  static const std::array<glm::dvec3, 4> pts{{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}};
  static constexpr std::array<std::array<std::uint32_t, 3>, 4> faces{
      {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}}};
  return detail::shapes::solid<P>(pts, 1.0 / std::sqrt(3.0), faces);
}

/// The unit cube [0,1]^3 as 6 quads; vertex i sits at (i&1, (i>>1)&1, (i>>2)&1).
/// O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> hexahedron() {
  std::array<glm::dvec3, 8> pts;
  for (int i = 0; i < 8; ++i) pts[static_cast<std::size_t>(i)] = {i & 1, (i >> 1) & 1, (i >> 2) & 1};
  static constexpr std::array<std::array<std::uint32_t, 4>, 6> faces{
      {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};
  return detail::shapes::solid<P>(pts, 1.0, faces);
}

/// Regular octahedron with vertices ±x, ±y, ±z (unit circumradius), one triangle per octant.
/// O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> octahedron() {
  static const std::array<glm::dvec3, 6> pts{
      {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
  std::array<std::array<std::uint32_t, 3>, 8> faces;
  for (std::uint32_t o = 0; o < 8; ++o) {
    const std::uint32_t x = o & 1, y = 2 + ((o >> 1) & 1), z = 4 + ((o >> 2) & 1);
    // An odd number of negative axes mirrors the octant, which reverses the winding.
    const bool mirrored = ((o & 1) ^ ((o >> 1) & 1) ^ ((o >> 2) & 1)) != 0;
    faces[o] = mirrored ? std::array<std::uint32_t, 3>{x, z, y} : std::array<std::uint32_t, 3>{x, y, z};
  }
  return detail::shapes::solid<P>(pts, 1.0, faces);
}

/// Regular icosahedron with unit circumradius (12 vertices, 20 triangles).
/// O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> icosahedron() {
  return detail::shapes::solid<P>(detail::shapes::icosahedron_points(),
                                  1.0 / std::sqrt(1.0 + std::numbers::phi * std::numbers::phi),
                                  detail::shapes::icosahedron_faces);
}

/// Regular dodecahedron with unit circumradius (20 vertices, 12 pentagons), built as the
/// dual of the icosahedron: one vertex per icosahedron face, one pentagon per vertex. O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> dodecahedron() {
  namespace s = detail::shapes;
  const auto& ip = s::icosahedron_points();
  const auto& faces = s::icosahedron_faces;
  std::array<glm::dvec3, 20> pts;
  // Directed edge (v -> w) of the icosahedron -> the face that contains it.
  std::array<std::array<std::int8_t, 12>, 12> face_of{};
  for (auto& row : face_of) row.fill(-1);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& t = faces[f];
    pts[f] = glm::normalize(ip[t[0]] + ip[t[1]] + ip[t[2]]);
    for (std::size_t i = 0; i < 3; ++i) face_of[t[i]][t[(i + 1) % 3]] = static_cast<std::int8_t>(f);
  }
  std::array<std::array<std::uint32_t, 5>, 12> pentagons;
  for (std::uint32_t v = 0; v < 12; ++v) {
    // Start at any face around v; the next face counter-clockwise about v holds the edge
    // v -> (the vertex before v in the current face).
    std::uint32_t f = 0;
    while (faces[f][0] != v && faces[f][1] != v && faces[f][2] != v) ++f;
    for (std::size_t k = 0; k < 5; ++k) {
      pentagons[v][k] = f;
      const auto& t = faces[f];
      const std::size_t at = t[0] == v ? 0 : t[1] == v ? 1 : 2;
      f = static_cast<std::uint32_t>(face_of[v][t[(at + 2) % 3]]);
    }
  }
  return s::solid<P>(pts, 1.0, pentagons);
}

// ------------------------------------------------------------------------------------
// Spheres
// ------------------------------------------------------------------------------------

/// Unit sphere from an icosahedron split 1→4 `subdivisions` times: 10·4^s + 2 vertices,
/// 20·4^s triangles, nearly uniform. O(output) expected (edge midpoints through a hash).
template <Point3 P = glm::dvec3>
polygon_soup<P> icosphere(int subdivisions) {
  namespace s = detail::shapes;
  s::require(subdivisions >= 0 && subdivisions <= 13, "icosphere",
             cellforge::detail::cat("subdivisions must be in 0..13, got ", std::to_string(subdivisions)));
  const double faces_out = 20.0 * std::pow(4.0, subdivisions);
  s::require_size(faces_out / 2 + 2, 3 * faces_out, "icosphere");
  std::vector<glm::dvec3> pts;
  pts.reserve(static_cast<std::size_t>(faces_out / 2 + 2));
  for (const glm::dvec3& p : s::icosahedron_points()) pts.push_back(glm::normalize(p));
  std::vector<std::array<std::uint32_t, 3>> tris(s::icosahedron_faces.begin(), s::icosahedron_faces.end());
  for (int level = 0; level < subdivisions; ++level) {
    std::unordered_map<std::uint64_t, std::uint32_t> midpoint;
    midpoint.reserve(tris.size() * 3 / 2);
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      auto [it, fresh] = midpoint.try_emplace(s::edge_key(a, b), static_cast<std::uint32_t>(pts.size()));
      if (fresh) pts.push_back(glm::normalize(pts[a] + pts[b]));
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    next.reserve(tris.size() * 4);
    for (const auto& [a, b, c] : tris) {
      const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.push_back({a, ab, ca});
      next.push_back({ab, b, bc});
      next.push_back({ca, bc, c});
      next.push_back({ab, bc, ca});
    }
    tris.swap(next);
  }
  polygon_soup<P> soup;
  soup.reserve(pts.size(), tris.size(), 3 * tris.size());
  for (const glm::dvec3& p : pts) s::add_point(soup, p);
  for (const auto& t : tris) soup.add_face({t[0], t[1], t[2]});
  return soup;
}

/// Unit UV sphere: `slices` meridians, `stacks` latitude bands; the poles are single
/// vertices with triangle fans, quads elsewhere unless `triangles`. slices·(stacks−1)+2
/// vertices. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> uv_sphere(int slices, int stacks, bool triangles = true) {
  namespace s = detail::shapes;
  const double nv = static_cast<double>(slices) * (stacks - 1) + 2;
  s::require_counts("uv_sphere", {{"slices", slices, 3}, {"stacks", stacks, 2}}, nv, 6.0 * slices * stacks);
  polygon_soup<P> soup;
  soup.reserve(static_cast<std::size_t>(nv), 2u * slices * stacks, 6u * slices * stacks);
  const std::uint32_t north = s::add_point(soup, {0, 0, 1});
  for (int k = 1; k < stacks; ++k) {
    const double theta = s::pi * k / stacks;
    for (int i = 0; i < slices; ++i) {
      const double phi = 2.0 * s::pi * i / slices;
      s::add_point(soup, {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
    }
  }
  const std::uint32_t south = s::add_point(soup, {0, 0, -1});
  const auto n = static_cast<std::uint32_t>(slices);
  s::add_fan(soup, north, 1, n, false);
  // Quad (upper_i, lower_i, lower_i+1, upper_i+1) runs down, east, up: counter-clockwise outside.
  s::add_grid_faces(soup, stacks - 2, slices, triangles, [&](int k, int i) {
    return s::u32(1 + static_cast<std::int64_t>(k) * slices + i % slices);
  });
  s::add_fan(soup, south, 1 + (static_cast<std::uint32_t>(stacks) - 2) * n, n, true);
  return soup;
}

/// Unit triangulated sphere with exactly n vertices (n ≥ 4): two poles and latitude rings
/// whose sizes follow the circumference, zipped together by angle. O(n).
/// n = 4 gives the tetrahedron; every triangle is near-equilateral away from the poles.
template <Point3 P = glm::dvec3>
polygon_soup<P> sphere_with_vertices(int n) {
  namespace s = detail::shapes;
  s::require_counts("sphere_with_vertices", {{"n", n, 4}}, n, 6.0 * n);
  if (n == 4) return tetrahedron<P>();
  const std::int64_t inner = n - 2;  // vertices on the rings
  // Triangle side h for equilateral triangles covering 4π with n vertices; rings are
  // spaced one triangle height (h·√3/2) apart.
  const double h = std::sqrt(8.0 * s::pi / (std::sqrt(3.0) * n));
  std::int64_t rings = std::llround(s::pi / (h * std::sqrt(3.0) / 2.0)) - 1;
  rings = std::clamp<std::int64_t>(rings, 1, inner / 3);
  std::vector<double> ideal(static_cast<std::size_t>(rings));
  double total = 0;
  for (std::int64_t k = 0; k < rings; ++k) total += ideal[k] = std::sin(s::pi * (k + 1) / (rings + 1));
  std::vector<std::int64_t> count(ideal.size());
  std::int64_t sum = 0;
  for (std::size_t k = 0; k < ideal.size(); ++k) {
    ideal[k] *= static_cast<double>(inner) / total;
    sum += count[k] = std::max<std::int64_t>(3, static_cast<std::int64_t>(std::floor(ideal[k])));
  }
  // Largest-remainder correction; at most `rings` steps of O(rings) each, O(n) in all.
  while (sum != inner) {
    const bool grow = sum < inner;
    std::size_t best = ideal.size();
    for (std::size_t k = 0; k < ideal.size(); ++k) {
      if (!grow && count[k] <= 3) continue;
      const double gap = ideal[k] - static_cast<double>(count[k]);
      if (best == ideal.size() || (grow ? gap > ideal[best] - static_cast<double>(count[best])
                                        : gap < ideal[best] - static_cast<double>(count[best])))
        best = k;
    }
    count[best] += grow ? 1 : -1;
    sum += grow ? 1 : -1;
  }
  polygon_soup<P> soup;
  soup.reserve(static_cast<std::size_t>(n), 2 * static_cast<std::size_t>(n), 6 * static_cast<std::size_t>(n));
  // Ring k's vertex i sits at (i + offset_k) / count_k of a turn; odd rings are turned
  // half a step so that equal neighbouring rings interleave.
  const auto turn = [&](std::size_t k, std::int64_t i) {
    return (static_cast<double>(i) + 0.5 * static_cast<double>(k % 2)) / static_cast<double>(count[k]);
  };
  const std::uint32_t north = s::add_point(soup, {0, 0, 1});
  std::vector<std::uint32_t> first(count.size());
  for (std::size_t k = 0; k < count.size(); ++k) {
    const double theta = s::pi * static_cast<double>(k + 1) / static_cast<double>(rings + 1);
    first[k] = static_cast<std::uint32_t>(soup.points.size());
    for (std::int64_t i = 0; i < count[k]; ++i) {
      const double phi = 2.0 * s::pi * turn(k, i);
      s::add_point(soup, {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
    }
  }
  const std::uint32_t south = s::add_point(soup, {0, 0, -1});
  s::add_fan(soup, north, first.front(), static_cast<std::uint32_t>(count.front()), false);
  for (std::size_t k = 0; k + 1 < count.size(); ++k) {
    // Zip upper ring k (a vertices) to lower ring k+1 (b vertices): both start within half
    // a step of angle 0; always advance the side whose next vertex comes first, which
    // gives a + b triangles, each ring edge once, and ends on the starting edge.
    const std::int64_t a = count[k], b = count[k + 1];
    const auto up = [&](std::int64_t i) { return s::u32(first[k] + i % a); };
    const auto lo = [&](std::int64_t j) { return s::u32(first[k + 1] + j % b); };
    std::int64_t i = 0, j = 0;
    while (i < a || j < b) {
      if (j == b || (i < a && turn(k, i + 1) < turn(k + 1, j + 1))) {
        soup.add_face({up(i), lo(j), up(i + 1)});
        ++i;
      } else {
        soup.add_face({up(i), lo(j), lo(j + 1)});
        ++j;
      }
    }
  }
  s::add_fan(soup, south, first.back(), static_cast<std::uint32_t>(count.back()), true);
  return soup;
}

// ------------------------------------------------------------------------------------
// Tubes, planes and disks (orientable)
// ------------------------------------------------------------------------------------

/// Torus about the z axis, major radius R, tube radius r (0 < r < R), outward, closed,
/// genus 1: major·minor vertices and quads (twice as many triangles). O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> torus(int major_segments, int minor_segments, double R = 1, double r = 0.3,
                      bool triangles = true) {
  namespace s = detail::shapes;
  s::require(std::isfinite(R) && std::isfinite(r) && r > 0 && r < R, "torus",
             cellforge::detail::cat("radii must satisfy 0 < r < R (an embedded ring torus), got R = ",
                                    std::to_string(R), ", r = ", std::to_string(r)));
  s::require_counts("torus", {{"major_segments", major_segments, 3}, {"minor_segments", minor_segments, 3}},
                    static_cast<double>(major_segments) * minor_segments,
                    6.0 * major_segments * minor_segments);
  std::vector<s::ring_frame> rings;
  rings.reserve(static_cast<std::size_t>(major_segments));
  for (int k = 0; k < major_segments; ++k) {
    const double u = 2.0 * s::pi * k / major_segments;
    const glm::dvec3 radial(std::cos(u), std::sin(u), 0);
    // Sweep direction is +u, so (radial, -z) turns counter-clockwise about it.
    rings.push_back({R * radial, radial, {0, 0, -1}, r});
  }
  polygon_soup<P> soup;
  s::sweep_rings(soup, std::span<const s::ring_frame>(rings), minor_segments, true, false, triangles);
  return soup;
}

/// Cylinder of radius 1 about z from z = −1 to 1: `segments` around, `rings` bands along
/// (rings + 1 vertex circles). Caps are a fan about a centre vertex when `triangles`,
/// else one polygon each; outward. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> cylinder(int segments, int rings, bool capped = true, bool triangles = true) {
  namespace s = detail::shapes;
  s::require_counts("cylinder", {{"segments", segments, 3}, {"rings", rings, 1}},
                    static_cast<double>(segments) * (rings + 1) + 2, 6.0 * segments * (rings + 2));
  std::vector<s::ring_frame> frames;
  frames.reserve(static_cast<std::size_t>(rings) + 1);
  for (int k = 0; k <= rings; ++k)
    frames.push_back({{0, 0, -1.0 + 2.0 * k / rings}, {1, 0, 0}, {0, 1, 0}, 1.0});
  polygon_soup<P> soup;
  s::sweep_rings(soup, std::span<const s::ring_frame>(frames), segments, false, capped, triangles);
  return soup;
}

/// Unit disk in the xy plane, facing +z: a centre vertex and `rings` concentric circles
/// of `segments` vertices, all triangles; one boundary loop of `segments` edges. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> disk(int segments, int rings) {
  namespace s = detail::shapes;
  s::require_counts("disk", {{"segments", segments, 3}, {"rings", rings, 1}},
                    static_cast<double>(segments) * rings + 1, 6.0 * segments * rings);
  polygon_soup<P> soup;
  const std::uint32_t centre = s::add_point(soup, {0, 0, 0});
  for (int k = 1; k <= rings; ++k)
    for (int i = 0; i < segments; ++i) {
      const double phi = 2.0 * s::pi * i / segments, rad = static_cast<double>(k) / rings;
      s::add_point(soup, {rad * std::cos(phi), rad * std::sin(phi), 0});
    }
  s::add_fan(soup, centre, 1, static_cast<std::uint32_t>(segments), false);
  // (r, φ) is right-handed about +z, so step outward first, then around.
  s::add_grid_faces(soup, rings - 1, segments, true, [&](int k, int i) {
    return s::u32(1 + static_cast<std::int64_t>(k) * segments + i % segments);
  });
  return soup;
}

/// Open grid of nx × ny cells over the unit square [0,1]^2 at z = 0, facing +z: quads, or
/// two triangles per cell split along the (i,j)–(i+1,j+1) diagonal. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> grid_plane(int nx, int ny, bool triangles = true) {
  namespace s = detail::shapes;
  s::require_counts("grid_plane", {{"nx", nx, 1}, {"ny", ny, 1}}, (nx + 1.0) * (ny + 1.0), 6.0 * nx * ny);
  polygon_soup<P> soup;
  soup.reserve(static_cast<std::size_t>(nx + 1) * static_cast<std::size_t>(ny + 1),
               2 * static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny),
               6 * static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      s::add_point(soup, {static_cast<double>(i) / nx, static_cast<double>(j) / ny, 0});
  s::add_grid_faces(soup, nx, ny, triangles,
                    [&](int i, int j) { return s::u32(static_cast<std::int64_t>(j) * (nx + 1) + i); });
  return soup;
}

// ------------------------------------------------------------------------------------
// Non-orientable surfaces and inconsistently oriented inputs
// ------------------------------------------------------------------------------------

/// Möbius strip (centre circle radius 1, width 1) with each face wound as the (u, v)
/// parametrisation gives it, so the two faces on each of the `segments_across` seam edges
/// traverse it in the same direction. One boundary loop of 2·segments_along edges. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> mobius_strip(int segments_along, int segments_across, bool triangles = true) {
  namespace s = detail::shapes;
  const std::int64_t along = segments_along, across = segments_across;
  s::require_counts("mobius_strip",
                    {{"segments_along", segments_along, 3}, {"segments_across", segments_across, 1}},
                    static_cast<double>(along) * static_cast<double>(across + 1),
                    6.0 * static_cast<double>(along) * static_cast<double>(across));
  polygon_soup<P> soup;
  for (std::int64_t i = 0; i < along; ++i) {
    const double u = 2.0 * s::pi * static_cast<double>(i) / static_cast<double>(along);
    for (std::int64_t j = 0; j <= across; ++j) {
      const double v = -0.5 + static_cast<double>(j) / static_cast<double>(across);
      const double rad = 1.0 + v * std::cos(u / 2);
      s::add_point(soup, {rad * std::cos(u), rad * std::sin(u), v * std::sin(u / 2)});
    }
  }
  // Column `along` is column 0 read backwards: (u + 2π, v) is the point (u, −v).
  s::add_grid_faces(soup, segments_along, segments_across, triangles, [&](int i, int j) {
    return i == along ? s::u32(across - j) : s::u32(i * (across + 1) + j);
  });
  return soup;
}

/// Alias for the seed's "Mobius_16_16" benchmark input: mobius_strip(along, across, true).
/// O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> mobius_band(int segments_along = 16, int segments_across = 16) {
  return mobius_strip<P>(segments_along, segments_across, true);
}

/// Klein bottle as the figure-8 immersion (self-intersecting; only topology matters):
/// closed, χ = 0, non-orientable; the `v_segments` seam edges are traversed twice in the
/// same direction. u·v vertices and quads (twice as many triangles). O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> klein_bottle(int u_segments, int v_segments, bool triangles = true) {
  namespace s = detail::shapes;
  const std::int64_t nu = u_segments, nv = v_segments;
  s::require_counts("klein_bottle", {{"u_segments", u_segments, 3}, {"v_segments", v_segments, 3}},
                    static_cast<double>(nu) * static_cast<double>(nv),
                    6.0 * static_cast<double>(nu) * static_cast<double>(nv));
  polygon_soup<P> soup;
  constexpr double a = 2.0;  // radius of the figure-8's centre circle
  for (std::int64_t i = 0; i < nu; ++i) {
    const double u = 2.0 * s::pi * static_cast<double>(i) / static_cast<double>(nu);
    for (std::int64_t j = 0; j < nv; ++j) {
      const double v = 2.0 * s::pi * static_cast<double>(j) / static_cast<double>(nv);
      const double w = a + std::cos(u / 2) * std::sin(v) - std::sin(u / 2) * std::sin(2 * v);
      s::add_point(soup, {w * std::cos(u), w * std::sin(u),
                          std::sin(u / 2) * std::sin(v) + std::cos(u / 2) * std::sin(2 * v)});
    }
  }
  // (u + 2π, v) is the point (u, −v): column nu is column 0 with v mirrored.
  s::add_grid_faces(soup, u_segments, v_segments, triangles, [&](int i, int j) {
    const std::int64_t jj = j % nv;
    return i == nu ? s::u32((nv - jj) % nv) : s::u32(i * nv + jj);
  });
  return soup;
}

/// grid_plane(nx, ny, true) with each triangle's vertex order reversed with probability
/// 1/2, from the top bit of successive std::mt19937_64(seed) outputs (identical on every
/// standard library). Orientable, but neighbours disagree across many edges. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> random_orientation_plane(int nx, int ny, std::uint64_t seed) {
  polygon_soup<P> soup = grid_plane<P>(nx, ny, true);
  std::mt19937_64 bits(seed);
  for (std::size_t f = 0; f < soup.num_faces(); ++f)
    if ((bits() >> 63) != 0) {
      const auto first = soup.face_vertices.begin() + soup.face_offsets[f];
      std::reverse(first + 1, first + 3);  // keep the first vertex: (a, b, c) -> (a, c, b)
    }
  return soup;
}

/// Real projective plane as the hemi-icosahedron: the icosahedron with antipodal points
/// identified, 6 vertices, 15 edges (all pairs), 10 triangles, χ = 1. O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> projective_plane() {
  namespace s = detail::shapes;
  const auto& ip = s::icosahedron_points();
  // Vertex v of the icosahedron and its antipode map to the same class; keep the
  // representative with the first non-zero coordinate positive.
  std::array<std::uint32_t, 12> cls{};
  std::array<glm::dvec3, 6> pts;
  std::uint32_t classes = 0;
  for (std::uint32_t v = 0; v < 12; ++v) {
    std::uint32_t w = 0;
    while (glm::length(ip[w] + ip[v]) > 1e-9) ++w;
    if (w < v) {
      cls[v] = cls[w];
      continue;
    }
    const glm::dvec3& p = ip[v];
    const bool positive = p.x > 0 || (p.x == 0 && (p.y > 0 || (p.y == 0 && p.z > 0)));
    pts[classes] = glm::normalize(positive ? p : -p);
    cls[v] = classes++;
  }
  // Of each antipodal face pair keep the first one listed.
  std::vector<std::array<std::uint32_t, 3>> faces;
  std::unordered_set<std::uint32_t> seen;
  for (const auto& t : s::icosahedron_faces) {
    std::array<std::uint32_t, 3> c{cls[t[0]], cls[t[1]], cls[t[2]]};
    std::array<std::uint32_t, 3> sorted = c;
    std::sort(sorted.begin(), sorted.end());
    if (seen.insert(sorted[0] * 36 + sorted[1] * 6 + sorted[2]).second) faces.push_back(c);
  }
  return s::solid<P>(pts, 1.0, faces);
}

/// Closed solid of revolution about the z axis: `profile` lists (radius, z) pairs (x = radius,
/// y = z) from one end to the other, swept with `segments` vertices per ring. An end with
/// radius 0 is a pole vertex joined by a triangle fan; any other end is closed by one
/// `segments`-gon (quads) or a triangle fan to a centre vertex (`triangles`). Interior
/// radii must be positive. Quads between rings, split into two triangles when `triangles`.
/// Faces point outward whichever way the profile runs. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> solid_of_revolution(std::span<const glm::dvec2> profile, int segments,
                                    bool triangles = false) {
  namespace s = detail::shapes;
  const char* what = "solid_of_revolution";
  const auto m = static_cast<std::int64_t>(profile.size());
  s::require(m >= 2, what, "the profile needs at least 2 (radius, z) points");
  s::require_counts(what, {{"segments", segments, 3}},
                    static_cast<double>(segments) * static_cast<double>(m) + 2,
                    6.0 * segments * static_cast<double>(m + 1));
  for (std::int64_t k = 0; k < m; ++k) {
    const glm::dvec2 q = profile[static_cast<std::size_t>(k)];
    s::require(std::isfinite(q.x) && std::isfinite(q.y) && q.x >= 0, what, [&] {
      return cellforge::detail::cat("profile point ", std::to_string(k),
                                    " must have a finite radius >= 0 and a finite z");
    });
    s::require(q.x > 0 || k == 0 || k == m - 1, what, [&] {
      return cellforge::detail::cat("profile point ", std::to_string(k),
                                    " has radius 0; only the two ends may lie on the axis");
    });
    s::require(k == 0 || q != profile[static_cast<std::size_t>(k - 1)], what, [&] {
      return cellforge::detail::cat("profile points ", std::to_string(k - 1), " and ", std::to_string(k),
                                    " coincide");
    });
  }
  s::require(m > 2 || profile[0].x > 0 || profile[1].x > 0, what,
             "a profile of two axis points has no surface");
  polygon_soup<P> soup;
  // ring[k] = index of the first vertex of profile point k (one vertex when it is a pole).
  std::vector<std::uint32_t> ring(static_cast<std::size_t>(m));
  const auto n = static_cast<std::uint32_t>(segments);
  for (std::int64_t k = 0; k < m; ++k) {
    const glm::dvec2 q = profile[static_cast<std::size_t>(k)];
    ring[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(soup.points.size());
    if (q.x == 0) {
      s::add_point(soup, {0, 0, q.y});
      continue;
    }
    for (int i = 0; i < segments; ++i) {
      const double phi = 2.0 * s::pi * i / segments;
      s::add_point(soup, {q.x * std::cos(phi), q.x * std::sin(phi), q.y});
    }
  }
  const auto pole = [&](std::int64_t k) { return profile[static_cast<std::size_t>(k)].x == 0; };
  for (std::int64_t k = 0; k + 1 < m; ++k) {
    const std::uint32_t a = ring[static_cast<std::size_t>(k)], b = ring[static_cast<std::size_t>(k + 1)];
    if (pole(k))
      s::add_fan(soup, a, b, n, true);
    else if (pole(k + 1))
      s::add_fan(soup, b, a, n, false);
    else
      for (std::uint32_t i = 0; i < n; ++i)
        s::add_quad(soup, a + i, a + (i + 1) % n, b + (i + 1) % n, b + i, triangles);
  }
  // Caps: the first end seen from below (reversed winding), the last from above.
  for (const std::int64_t k : {std::int64_t{0}, m - 1}) {
    if (pole(k)) continue;
    const std::uint32_t first = ring[static_cast<std::size_t>(k)];
    const bool reverse = k == 0;
    if (triangles) {
      s::add_fan(soup, s::add_point(soup, {0, 0, profile[static_cast<std::size_t>(k)].y}), first, n, reverse);
    } else {
      std::vector<std::uint32_t> cap(n);
      for (std::uint32_t i = 0; i < n; ++i) cap[i] = reverse ? first + (n - i) % n : first + i;
      soup.add_face(cap);
    }
  }
  // A profile running downwards winds every face inward: flip them all.
  if (signed_volume(soup) < 0)
    for (std::size_t f = 0; f < soup.num_faces(); ++f)
      std::reverse(soup.face_vertices.begin() + soup.face_offsets[f],
                   soup.face_vertices.begin() + soup.face_offsets[f + 1]);
  return soup;
}

}  // namespace cellforge
