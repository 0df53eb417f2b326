// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample drawings (samples/drawings.hpp): one-volume solids for the sketch sweep, part 1:
/// convex polytopes (antiprisms, frustums, bipyramids, the Platonic and Archimedean solids,
/// random and cut polytopes), extruded polygons and their random footprints.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/convex_hull.hpp"
#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/union_find.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/samples/wireframe_models.hpp"

namespace cellforge::samples {

// ---- solids for the sketch sweep -------------------------------------------------------------
// Every model in this part is a 2-manifold solid: each edge lies on exactly two face loops, and
// no two faces sharing an edge are coplanar. Models of several volumes follow further down.

namespace detail {

/// A one-volume model from its points and faces (each face a list of loops, outer first): the
/// edges are the loop sides, each once; points no loop uses are dropped. O(L log L).
template <class = void>
sample_model model_from_faces(const std::vector<glm::dvec3>& points,
                              std::vector<std::vector<std::vector<std::uint32_t>>> faces, std::string name) {
  std::vector<std::uint32_t> id(points.size(), UINT32_MAX);
  sample_model m;
  m.name = std::move(name);
  for (auto& face : faces)
    for (auto& loop : face)
      for (auto& v : loop) {
        if (id[v] == UINT32_MAX) {
          id[v] = static_cast<std::uint32_t>(m.wire.points.size());
          m.wire.points.push_back(points[v]);
        }
        v = id[v];
      }
  std::vector<std::array<std::uint32_t, 2>> edges;
  for (const auto& face : faces)
    for (const auto& loop : face)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
        edges.push_back({std::min(a, b), std::max(a, b)});
      }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  m.wire.edges = std::move(edges);
  m.faces = std::move(faces);
  m.volumes.emplace_back();
  for (std::uint32_t f = 0; f < m.faces.size(); ++f) m.volumes[0].push_back(f);
  return finish(std::move(m));
}

/// The points' bounding-box diagonal. O(n).
template <class = void>
double diagonal_of(const std::vector<glm::dvec3>& pts) {
  if (pts.empty()) return 0;
  glm::dvec3 lo = pts[0], hi = pts[0];
  for (const auto& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return glm::length(hi - lo);
}

/// Every signed permutation of `base` (all 6 orders, or only the 3 cyclic ones when `even`),
/// duplicates dropped; `keep(sign bits, odd permutation)` filters them. O(48).
template <class Keep>
void signed_permutations(std::vector<glm::dvec3>& out, glm::dvec3 base, bool even, Keep keep) {
  static constexpr std::array<std::array<int, 3>, 6> perms{
      {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {1, 0, 2}, {0, 2, 1}, {2, 1, 0}}};
  for (std::size_t k = 0; k < (even ? 3u : 6u); ++k)
    for (unsigned signs = 0; signs < 8; ++signs) {
      glm::dvec3 p;
      for (int i = 0; i < 3; ++i) {
        const double c = base[perms[k][static_cast<std::size_t>(i)]];
        p[i] = (signs >> i & 1u) != 0 ? -c : c;
      }
      unsigned minus = 0;
      for (int i = 0; i < 3; ++i)
        minus += (signs >> i & 1u) != 0 && base[perms[k][static_cast<std::size_t>(i)]] != 0;
      if (!keep(minus, k >= 3)) continue;
      bool seen = false;
      for (const auto& q : out) seen = seen || glm::length(p - q) < 1e-12;
      if (!seen) out.push_back(p);
    }
}
template <class = void>
void signed_permutations(std::vector<glm::dvec3>& out, glm::dvec3 base, bool even) {
  signed_permutations(out, base, even, [](unsigned, bool) { return true; });
}

/// Whether the closed 2D polygon is simple: no two non-adjacent sides meet, no adjacent sides
/// fold back, no repeated point. O(n²).
template <class = void>
bool simple_polygon(const std::vector<glm::dvec2>& p) {
  const std::size_t n = p.size();
  if (n < 3) return false;
  const auto cross = [](glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; };
  const auto orient = [&](glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) { return cross(b - a, c - a); };
  const auto on = [&](glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {  // c on segment ab, given collinear
    return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
           c.y <= std::max(a.y, b.y);
  };
  const auto meet = [&](glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d) {
    const double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c), d4 = orient(a, b, d);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
    return (d1 == 0 && on(c, d, a)) || (d2 == 0 && on(c, d, b)) || (d3 == 0 && on(a, b, c)) ||
           (d4 == 0 && on(a, b, d));
  };
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec2 a = p[i], b = p[(i + 1) % n], c = p[(i + 2) % n];
    if (a == b) return false;
    // Adjacent sides: they share b only (no fold back onto each other).
    if (orient(a, b, c) == 0 && glm::dot(b - a, c - b) <= 0) return false;
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      if (meet(a, b, p[j], p[(j + 1) % n])) return false;
    }
  }
  return true;
}

}  // namespace detail

/// The convex polytope of points in convex position: their hull (algorithms/convex_hull.hpp,
/// exact) with adjacent triangles merged into one polygon face where their planes agree to
/// `tolerance` relative to the size (points within it of a merged face's plane and not
/// corners of it are dropped). One volume. Throws invalid_input when the points span less
/// than 3D. O(n log n + F).
template <class = void>
sample_model convex_polytope_model(const std::vector<glm::dvec3>& points, std::string name,
                                   double tolerance = 1e-9) {
  const cellforge::detail::hull::result r =
      cellforge::detail::hull::compute(std::span<const glm::dvec3>(points), {});
  if (r.dimension < 3)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("convex_polytope_model: the points of '", name,
                                       "' span less than 3D; give a solid"));
  const double tol = tolerance * detail::diagonal_of(points);
  const std::size_t nf = r.face_offsets.size() - 1;
  const auto corner = [&](std::size_t f, std::size_t k) {
    return r.vertices[r.face_vertices[r.face_offsets[f] + k]];
  };
  // Triangles' planes and neighbours through their sides.
  std::vector<glm::dvec3> normal(nf);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> side;  // directed side -> face
  for (std::size_t f = 0; f < nf; ++f) {
    const glm::dvec3 a = points[corner(f, 0)], b = points[corner(f, 1)], c = points[corner(f, 2)];
    normal[f] = glm::normalize(glm::cross(b - a, c - a));
    for (std::size_t k = 0; k < 3; ++k)
      side[{corner(f, k), corner(f, (k + 1) % 3)}] = static_cast<std::uint32_t>(f);
  }
  cellforge::detail::union_find groups(nf);
  const auto find = [&](std::uint32_t f) { return groups.find(f); };
  for (std::size_t f = 0; f < nf; ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      const auto it = side.find({corner(f, (k + 1) % 3), corner(f, k)});
      if (it == side.end()) continue;
      const std::uint32_t g = it->second;
      // g's corner off the shared side, against f's plane.
      double off = 0;
      for (std::size_t j = 0; j < 3; ++j)
        off = std::max(off, std::abs(glm::dot(points[corner(g, j)] - points[corner(f, 0)], normal[f])));
      if (off <= tol) groups.unite(static_cast<std::uint32_t>(f), g);
    }
  // Each group's outline: the directed sides whose reverse is in another group, chained.
  std::map<std::uint32_t, std::map<std::uint32_t, std::uint32_t>> outline;  // group -> tail -> head
  for (std::size_t f = 0; f < nf; ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = corner(f, k), b = corner(f, (k + 1) % 3);
      const auto it = side.find({b, a});
      if (it == side.end() || find(it->second) != find(static_cast<std::uint32_t>(f)))
        outline[find(static_cast<std::uint32_t>(f))][a] = b;
    }
  std::vector<std::vector<std::vector<std::uint32_t>>> faces;
  for (auto& [group, next] : outline) {
    std::vector<std::uint32_t> loop;
    std::uint32_t at = next.begin()->first;
    for (std::size_t guard = 0; guard <= next.size(); ++guard) {
      loop.push_back(at);
      at = next[at];
      if (at == loop.front()) break;
    }
    if (loop.size() != next.size())
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("convex_polytope_model: a merged face of '", name,
                                         "' is not one polygon; lower the tolerance"));
    // Drop corners where the outline goes straight on (a point on a side, within tolerance).
    std::vector<std::uint32_t> corners;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const glm::dvec3 a = points[loop[(i + loop.size() - 1) % loop.size()]], b = points[loop[i]],
                       c = points[loop[(i + 1) % loop.size()]];
      if (glm::length(glm::cross(c - a, b - a)) / glm::length(c - a) > tol) corners.push_back(loop[i]);
    }
    faces.push_back({std::move(corners)});
  }
  return detail::model_from_faces(points, std::move(faces), std::move(name));
}

/// An n-gon antiprism (3 <= n <= 1024): two regular n-gons turned by half a step, joined by
/// 2n triangles; 2n vertices, 4n edges, 2n + 2 faces. O(n).
template <class = void>
sample_model sample_antiprism(std::size_t n, double height = 1.0) {
  if (n < 3 || n > 1024) throw error(error_category::invalid_input, "sample_antiprism: n must be in 3..1024");
  ring_stack s;
  s.n = n;
  s.radius = {1.0, 1.0};
  s.height = {0.0, height};
  s.twist = {0.0, std::numbers::pi / static_cast<double>(n)};
  s.triangles = true;
  return make_ring_stack(s, cellforge::detail::cat("antiprism ", std::to_string(n)));
}

/// A frustum of a regular n-gon pyramid (3 <= n <= 1024), top radius `top` (0 < top, top != 1):
/// 2n vertices, 3n edges, n + 2 faces. O(n).
template <class = void>
sample_model sample_frustum(std::size_t n, double top = 0.5, double height = 1.0) {
  if (n < 3 || n > 1024 || !(top > 0))
    throw error(error_category::invalid_input, "sample_frustum: n must be in 3..1024 and top > 0");
  ring_stack s = detail::regular_stack(n, {0.0, height});
  s.radius = {1.0, top};
  return make_ring_stack(s, cellforge::detail::cat("frustum ", std::to_string(n)));
}

/// A bipyramid over a regular n-gon (3 <= n <= 1024), apexes at heights -below and +above:
/// n + 2 vertices, 3n edges, 2n faces; its equator is a planar cycle that is not a face, and
/// at the degree-4 vertices (n = 4: all six) the opposite edges share no face. O(n).
template <class = void>
sample_model sample_bipyramid(std::size_t n, double below = 1.0, double above = 1.0) {
  if (n < 3 || n > 1024) throw error(error_category::invalid_input, "sample_bipyramid: n must be in 3..1024");
  ring_stack s = detail::regular_stack(n, {0.0});
  s.bottom = -below;
  s.top = above;
  return make_ring_stack(s, cellforge::detail::cat("bipyramid ", std::to_string(n)));
}

/// The five Platonic solids from their vertex coordinates (convex_polytope_model): tetrahedron,
/// cube, octahedron, dodecahedron, icosahedron. O(1).
template <class = void>
std::vector<sample_model> platonic_solids() {
  const double phi = (1 + std::sqrt(5.0)) / 2;
  std::vector<sample_model> out;
  std::vector<glm::dvec3> p;
  detail::signed_permutations(p, {1, 1, 1}, true, [](unsigned minus, bool) { return minus % 2 == 0; });
  out.push_back(convex_polytope_model(p, "tetrahedron"));
  p.clear();
  detail::signed_permutations(p, {1, 1, 1}, true);
  out.push_back(convex_polytope_model(p, "cube"));
  p.clear();
  detail::signed_permutations(p, {1, 0, 0}, false);
  out.push_back(convex_polytope_model(p, "octahedron"));
  p.clear();
  detail::signed_permutations(p, {1, 1, 1}, true);
  detail::signed_permutations(p, {0, 1 / phi, phi}, true);
  out.push_back(convex_polytope_model(p, "dodecahedron"));
  p.clear();
  detail::signed_permutations(p, {0, 1, phi}, true);
  out.push_back(convex_polytope_model(p, "icosahedron"));
  return out;
}

namespace detail {
/// Points at parameters t and 1 − t along every edge of a model (t = 1/2: the midpoints,
/// once): the vertices of its truncation (rectification). O(E).
template <class = void>
std::vector<glm::dvec3> edge_points(const sample_model& m, double t) {
  std::vector<glm::dvec3> out;
  for (const auto& e : m.wire.edges) {
    const glm::dvec3 a = m.wire.points[e[0]], b = m.wire.points[e[1]];
    out.push_back(a + t * (b - a));
    if (t != 0.5) out.push_back(a + (1 - t) * (b - a));
  }
  return out;
}
/// The truncation parameter that makes a truncated regular n-gon face a regular 2n-gon. O(1).
template <class = void>
double truncation(int n) {
  return 1.0 / (2.0 + 2.0 * std::sin(std::numbers::pi * (n - 2) / (2.0 * n)));
}
}  // namespace detail

/// Twelve Archimedean solids from their vertex coordinates (convex_polytope_model): the
/// truncated tetrahedron, cuboctahedron, truncated cube, truncated octahedron,
/// rhombicuboctahedron, truncated cuboctahedron, snub cube, icosidodecahedron, truncated
/// dodecahedron, truncated icosahedron, rhombicosidodecahedron and truncated
/// icosidodecahedron (120 vertices, 180 edges). The snub dodecahedron (150 edges) is left
/// out: its coordinates need a cubic root. O(1).
template <class = void>
std::vector<sample_model> archimedean_solids() {
  const double phi = (1 + std::sqrt(5.0)) / 2, r2 = std::sqrt(2.0);
  const std::vector<sample_model> plato = platonic_solids();
  std::vector<sample_model> out;
  out.push_back(convex_polytope_model(detail::edge_points(plato[0], 1.0 / 3), "truncated tetrahedron"));
  out.push_back(convex_polytope_model(detail::edge_points(plato[1], 0.5), "cuboctahedron"));
  out.push_back(
      convex_polytope_model(detail::edge_points(plato[1], detail::truncation(4)), "truncated cube"));
  out.push_back(convex_polytope_model(detail::edge_points(plato[2], 1.0 / 3), "truncated octahedron"));
  std::vector<glm::dvec3> p;
  detail::signed_permutations(p, {1, 1, 1 + r2}, false);
  out.push_back(convex_polytope_model(p, "rhombicuboctahedron"));
  p.clear();
  detail::signed_permutations(p, {1, 1 + r2, 1 + 2 * r2}, false);
  out.push_back(convex_polytope_model(p, "truncated cuboctahedron"));
  p.clear();
  // Snub cube: even permutations of (±1, ±1/t, ±t) with an even number of minus signs, odd
  // ones with an odd number; t the tribonacci constant.
  const double t = (1 + std::cbrt(19 + 3 * std::sqrt(33.0)) + std::cbrt(19 - 3 * std::sqrt(33.0))) / 3;
  detail::signed_permutations(p, {1, 1 / t, t}, false,
                              [](unsigned minus, bool odd) { return (minus % 2 == 1) == odd; });
  out.push_back(convex_polytope_model(p, "snub cube"));
  out.push_back(convex_polytope_model(detail::edge_points(plato[3], 0.5), "icosidodecahedron"));
  out.push_back(
      convex_polytope_model(detail::edge_points(plato[3], detail::truncation(5)), "truncated dodecahedron"));
  out.push_back(convex_polytope_model(detail::edge_points(plato[4], 1.0 / 3), "truncated icosahedron"));
  p.clear();
  for (const glm::dvec3 b : {glm::dvec3(1, 1, phi * phi * phi), glm::dvec3(phi * phi, phi, 2 * phi),
                             glm::dvec3(2 + phi, 0, phi * phi)})
    detail::signed_permutations(p, b, true);
  out.push_back(convex_polytope_model(p, "rhombicosidodecahedron"));
  p.clear();
  for (const glm::dvec3 b : {glm::dvec3(1 / phi, 1 / phi, 3 + phi), glm::dvec3(2 / phi, phi, 1 + 2 * phi),
                             glm::dvec3(1 / phi, phi * phi, -1 + 3 * phi),
                             glm::dvec3(2 * phi - 1, 2, 2 + phi), glm::dvec3(phi, 3, 2 * phi)})
    detail::signed_permutations(p, b, true);
  out.push_back(convex_polytope_model(p, "truncated icosidodecahedron"));
  return out;
}

/// The hull of n random points (n >= 4) kept at least 0.6/√n apart: on the unit sphere (all of
/// them corners; 3n − 6 edges) or in the unit ball (the corners are those near the surface).
/// Triangle faces in general. Deterministic in `seed`. O(n² + n log n).
template <class = void>
sample_model random_convex_polytope(std::size_t n, bool on_sphere, std::uint64_t seed) {
  if (n < 4 || n > 100000)
    throw error(error_category::invalid_input, "random_convex_polytope: n must be in 4..100000");
  cellforge::detail::splitmix rng{seed ^ 0x636f6e7665780000u};
  const double gap = 0.6 / std::sqrt(static_cast<double>(n));
  std::vector<glm::dvec3> pts;
  for (std::size_t tries = 0; pts.size() < n && tries < 1000 * n; ++tries) {
    glm::dvec3 p;  // one coordinate per statement: the same numbers with every compiler
    for (int a = 0; a < 3; ++a) p[a] = rng.uniform(-1, 1);
    const double len = glm::length(p);
    if (len > 1 || len < 1e-3) continue;
    if (on_sphere) p /= len;
    bool far = true;
    for (const auto& q : pts) far = far && glm::length(p - q) >= gap;
    if (far) pts.push_back(p);
  }
  return convex_polytope_model(pts, cellforge::detail::cat(std::string(on_sphere ? "random sphere polytope "
                                                                                 : "random ball polytope "),
                                                           std::to_string(n), " #", std::to_string(seed)));
}

/// A cube (base = 0) or a regular base-gon prism (base >= 3) cut by `cuts` random planes, each
/// keeping the side with the centre and passing at 35..90 % of the solid's reach in its
/// direction: polygon faces and, in general, degree-3 vertices. O((cuts + base)^4).
template <class = void>
sample_model cut_polytope(std::size_t base, std::size_t cuts, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x6375740000000000u};
  std::vector<std::pair<glm::dvec3, double>> planes;  // n · x <= d
  std::vector<glm::dvec3> corners;
  if (base == 0) {
    for (int a = 0; a < 3; ++a)
      for (const double s : {-1.0, 1.0}) {
        glm::dvec3 n(0.0);
        n[a] = s;
        planes.push_back({n, 1.0});
      }
    detail::signed_permutations(corners, {1, 1, 1}, true);
  } else {
    if (base < 3 || base > 64)
      throw error(error_category::invalid_input, "cut_polytope: base must be 0 or 3..64");
    const double step = 2 * std::numbers::pi / static_cast<double>(base);
    for (std::size_t i = 0; i < base; ++i) {
      const double t = step * (static_cast<double>(i) + 0.5);
      planes.push_back({{std::cos(t), std::sin(t), 0.0}, std::cos(step / 2)});
      for (const double z : {-1.0, 1.0})
        corners.push_back(
            {std::cos(step * static_cast<double>(i)), std::sin(step * static_cast<double>(i)), z});
    }
    planes.push_back({{0, 0, 1}, 1.0});
    planes.push_back({{0, 0, -1}, 1.0});
  }
  for (std::size_t c = 0; c < cuts; ++c) {
    glm::dvec3 n;
    do n = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    while (glm::length(n) > 1 || glm::length(n) < 0.1);
    n = glm::normalize(n);
    double reach = 0;
    for (const auto& q : corners) reach = std::max(reach, glm::dot(n, q));
    planes.push_back({n, rng.uniform(0.35, 0.9) * reach});
  }
  std::vector<glm::dvec3> pts;
  for (std::size_t i = 0; i < planes.size(); ++i)
    for (std::size_t j = i + 1; j < planes.size(); ++j)
      for (std::size_t k = j + 1; k < planes.size(); ++k) {
        const glm::dmat3 a = glm::transpose(glm::dmat3(planes[i].first, planes[j].first, planes[k].first));
        const double det = glm::determinant(a);
        if (std::abs(det) < 1e-9) continue;
        const glm::dvec3 x =
            glm::inverse(a) * glm::dvec3(planes[i].second, planes[j].second, planes[k].second);
        bool inside = true;
        for (const auto& [n, d] : planes) inside = inside && glm::dot(n, x) <= d + 1e-9;
        bool seen = false;
        for (const auto& q : pts) seen = seen || glm::length(q - x) < 1e-7;
        if (inside && !seen) pts.push_back(x);
      }
  return convex_polytope_model(pts,
                               (base == 0 ? std::string("cut cube ")
                                          : cellforge::detail::cat("cut prism ", std::to_string(base), " ")) +
                                   std::to_string(cuts) + " #" + std::to_string(seed));
}

/// The prism over a simple polygon (counter-clockwise or not) in the xy plane, from z = 0 to
/// z = height: 2n vertices, 3n edges, n + 2 faces. Throws invalid_input when the polygon is
/// not simple or has three consecutive collinear corners. O(n²).
template <class = void>
sample_model extruded_polygon(const std::vector<glm::dvec2>& polygon, double height, std::string name) {
  const std::size_t n = polygon.size();
  if (!detail::simple_polygon(polygon))
    throw error(error_category::invalid_input,
                cellforge::detail::cat("extruded_polygon: the footprint of '", name, "' is not simple"));
  std::vector<glm::dvec3> pts;
  for (const double z : {0.0, height})
    for (const auto& p : polygon) pts.push_back({p.x, p.y, z});
  std::vector<std::vector<std::vector<std::uint32_t>>> faces(2);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = static_cast<std::uint32_t>((i + 1) % n), k = static_cast<std::uint32_t>(n);
    const glm::dvec2 a = polygon[(i + n - 1) % n], b = polygon[i], c = polygon[j];
    if (std::abs((b - a).x * (c - b).y - (b - a).y * (c - b).x) < 1e-12 * glm::dot(c - a, c - a))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("extruded_polygon: three consecutive corners of '", name,
                                         "' are collinear; drop the middle one"));
    faces.push_back({{i, j, j + k, i + k}});
  }
  faces[0].push_back({});
  faces[1].push_back({});
  for (std::uint32_t i = 0; i < n; ++i) {
    faces[0][0].push_back(i);
    faces[1][0].push_back(static_cast<std::uint32_t>(n) + i);
  }
  return detail::model_from_faces(pts, std::move(faces), std::move(name));
}

/// A random star-shaped simple polygon of n corners (angles jittered, radii 0.35..1). O(n).
template <class = void>
std::vector<glm::dvec2> random_star_polygon(std::size_t n, cellforge::detail::splitmix& rng) {
  std::vector<glm::dvec2> p;
  for (std::size_t i = 0; i < n; ++i) {
    const double t =
        2 * std::numbers::pi * (static_cast<double>(i) + rng.uniform(-0.35, 0.35)) / static_cast<double>(n);
    const double r = rng.uniform(0.35, 1.0);
    p.push_back({r * std::cos(t), r * std::sin(t)});
  }
  return p;
}

/// An L (kind 0), T (1) or cross (2) footprint with every corner moved at random by up to
/// `jitter` (0: the rectilinear footprint; > 0: oblique sides). O(1).
template <class = void>
std::vector<glm::dvec2> letter_footprint(int kind, double jitter, cellforge::detail::splitmix& rng) {
  std::vector<glm::dvec2> p;
  if (kind == 0)
    p = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
  else if (kind == 1)
    p = {{1, 0}, {2, 0}, {2, 2}, {3, 2}, {3, 3}, {0, 3}, {0, 2}, {1, 2}};
  else
    p = {{1, 0}, {2, 0}, {2, 1}, {3, 1}, {3, 2}, {2, 2}, {2, 3}, {1, 3}, {1, 2}, {0, 2}, {0, 1}, {1, 1}};
  for (auto& q : p) {
    q.x += rng.uniform(-jitter, jitter);
    q.y += rng.uniform(-jitter, jitter);
  }
  return p;
}

}  // namespace cellforge::samples
