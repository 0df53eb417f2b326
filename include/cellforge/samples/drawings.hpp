// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample line drawings with their ground truth: sample wireframes (samples/wireframe_models.hpp)
/// seen in generic parallel views (no two junctions on one point, no junction on another
/// edge's line, no face seen edge-on), with the true face loops, the true 3D positions in view
/// coordinates and the model (faces, volumes) the drawing shows. The fixtures and benchmark
/// inputs of the sketch stages; see docs/sketch.md.

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
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/union_find.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge::samples {

/// A drawing of a sample model in a parallel view, and what a correct reading must find.
struct sample_drawing {
  std::string name;    ///< the model's name and the view, e.g. "L block, view 3"
  std::string family;  ///< "prism", "pyramid", "platonic", "normalon", ...
  line_drawing<glm::dvec2> drawing;
  /// True positions in view coordinates: drawing[i] = (points[i].x, points[i].y), depth points[i].z.
  std::vector<glm::dvec3> points;
  /// True face loops: every loop (outer boundary and holes) of every face of the model, as
  /// junction cycles (orientation-free).
  std::vector<std::vector<std::uint32_t>> loops;
  sample_model model;           ///< the model drawn (its vertex i is junction i)
  glm::dmat3 view{1.0};         ///< model → view rotation (columns: images of the model's axes)
  bool normalon = false;        ///< every edge parallel to one of the model's three axes
  bool quasi_normalon = false;  ///< not a normalon, but its axis-parallel edges connect every vertex
  /// Genus of the solid drawn (0: a ball; k: k through-holes), known from its construction
  /// (project_model leaves 0; the sweep sets it). Euler–Poincaré: V − E + F − R = 2 − 2·genus,
  /// R the holes of the faces (inner loops).
  int genus = 0;
};

namespace detail {

/// A uniformly random rotation (unit quaternion from four normals, Shoemake). O(1).
template <class = void>
glm::dmat3 random_rotation(cellforge::detail::splitmix& rng) {
  const double u1 = rng.uniform(0, 1), u2 = rng.uniform(0, 6.283185307179586),
               u3 = rng.uniform(0, 6.283185307179586);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  const double w = a * std::sin(u2), x = a * std::cos(u2), y = b * std::sin(u3), z = b * std::cos(u3);
  // glm is column-major: m[c][r].
  glm::dmat3 m;
  m[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
  m[1] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
  m[2] = {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
  return m;
}

/// Whether an edge is parallel to one of the coordinate axes, to a relative tolerance. O(1).
template <class = void>
bool axis_parallel(glm::dvec3 d) {
  const double len = glm::length(d);
  const int big = (std::abs(d.x) > 1e-9 * len) + (std::abs(d.y) > 1e-9 * len) + (std::abs(d.z) > 1e-9 * len);
  return big == 1;
}

/// The smallest distance between two junctions and from a junction to an edge not at it,
/// over `diag` (the drawing's size). O(V² + V·E).
template <class Edges>
double junction_spacing(const std::vector<glm::dvec2>& pts, const Edges& edges, double diag) {
  double spacing = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (std::size_t j = i + 1; j < pts.size(); ++j)
      spacing = std::min(spacing, glm::length(pts[i] - pts[j]) / diag);
  for (const auto& e : edges)
    for (std::uint32_t v = 0; v < pts.size(); ++v)
      if (v != e[0] && v != e[1])
        spacing = std::min(spacing, cellforge::detail::segment_distance(pts[v], pts[e[0]], pts[e[1]]) / diag);
  return spacing;
}

}  // namespace detail

/// How far a drawing is from an accident of the view, relative to its size (the bounding-box
/// diagonal): the smallest of the distances between two junctions, from a junction to an edge
/// not at it, and the smallest |cos| between a face's normal and the view direction (a face seen
/// edge-on has 0). O(V² + V·E + F·L).
template <class = void>
double generic_margin(const sample_drawing& s) {
  const auto& pts = s.drawing.points;
  if (pts.empty()) return 0;
  glm::dvec2 lo = pts[0], hi = pts[0];
  for (const auto& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double diag = glm::length(hi - lo);
  if (!(diag > 0)) return 0;
  double margin = detail::junction_spacing(pts, s.drawing.edges, diag);
  for (const auto& face : s.model.faces) {
    std::vector<glm::dvec3> loop;
    for (const auto v : face[0]) loop.push_back(s.points[v]);
    glm::dvec3 n{0.0};
    for (std::size_t k = 0; k < loop.size(); ++k) n += glm::cross(loop[k], loop[(k + 1) % loop.size()]);
    const double len = glm::length(n);
    if (len > 0) margin = std::min(margin, std::abs(n.z) / len);
  }
  return margin;
}

/// The drawing of `model` in the parallel view `view` (model → view rotation): junction i is
/// model vertex i at (x, y) of view · p. Marks normalons and quasi-normalons by the model's
/// axes. O(V + E + F·L).
template <class = void>
sample_drawing project_model(const sample_model& model, const glm::dmat3& view, std::string name,
                             std::string family) {
  sample_drawing s;
  s.name = std::move(name);
  s.family = std::move(family);
  s.model = model;
  s.view = view;
  for (const auto& p : model.wire.points) {
    const glm::dvec3 q = view * p;
    s.points.push_back(q);
    s.drawing.points.push_back({q.x, q.y});
  }
  s.drawing.edges = model.wire.edges;
  for (const auto& face : model.faces)
    for (const auto& loop : face) s.loops.push_back(loop);
  // Normalon: every edge along an axis. Quasi-normalon: the axis edges alone connect every vertex.
  const std::size_t nv = model.wire.points.size();
  cellforge::detail::union_find sets(nv);
  std::size_t axis_edges = 0, components = nv;
  for (const auto& e : model.wire.edges) {
    if (!detail::axis_parallel(model.wire.points[e[1]] - model.wire.points[e[0]])) continue;
    ++axis_edges;
    components -= sets.unite(e[0], e[1]) ? 1 : 0;
  }
  s.normalon = axis_edges == model.wire.edges.size();
  s.quasi_normalon = !s.normalon && components == 1;
  return s;
}

/// The drawing of `model` in the first of up to `attempts` random views (from `seed`) whose
/// generic_margin is at least `min_margin`. Throws invalid_input when none is. O(attempts · (V² + V·E)).
template <class = void>
sample_drawing generic_drawing(const sample_model& model, std::uint64_t seed, std::string family,
                               double min_margin = 2e-3, int attempts = 64) {
  cellforge::detail::splitmix rng{seed * 0x9e3779b97f4a7c15u + 0x736b657463680000u};
  for (int k = 0; k < attempts; ++k) {
    sample_drawing s = project_model(model, detail::random_rotation(rng),
                                     model.name + ", view " + std::to_string(seed), family);
    if (generic_margin(s) >= min_margin) return s;
  }
  throw error(error_category::invalid_input,
              cellforge::detail::cat("generic_drawing: no generic view of '", model.name, "' in ",
                                     std::to_string(attempts), " tries"));
}

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

namespace detail {

/// Whether the corner shared by a 2×2×2 block of cells (bit dx + 2dy + 4dz set when full) is
/// a manifold point: the full cells and the empty ones each connected through faces. O(1).
template <class = void>
bool manifold_corner(unsigned mask) {
  const auto connected = [](unsigned set) {
    if (set == 0) return true;
    unsigned reached = set & (~set + 1u);
    for (bool grew = true; grew;) {
      grew = false;
      for (unsigned b = 0; b < 8; ++b)
        for (const unsigned d : {1u, 2u, 4u}) {
          const unsigned nb = 1u << (b ^ d);
          if ((reached >> b & 1u) != 0 && (set & nb) != 0 && (reached & nb) == 0) reached |= nb, grew = true;
        }
    }
    return reached == set;
  };
  return connected(mask) && connected(~mask & 0xFFu);
}

/// Full cells of a layout: label != 0; out of the lattice: empty. O(1).
template <class = void>
bool full_cell(const voxel_layout& l, std::ptrdiff_t i, std::ptrdiff_t j, std::ptrdiff_t k) {
  const auto nx = static_cast<std::ptrdiff_t>(l.xs.size()) - 1,
             ny = static_cast<std::ptrdiff_t>(l.ys.size()) - 1,
             nz = static_cast<std::ptrdiff_t>(l.zs.size()) - 1;
  if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return false;
  return l.labels[static_cast<std::size_t>(i + nx * (j + ny * k))] != 0;
}

/// What a layout's full cells make, when they make one 2-manifold solid: its genus (from the
/// Euler characteristic of the closed cubical set, 1 − genus for a solid with no cavity); -1
/// when some lattice point is not a manifold point (cells touching along an edge or at a
/// vertex only), the cells are not face-connected, or a cavity is enclosed. O(cells).
template <class = void>
int voxel_solid_genus(const voxel_layout& l) {
  const auto n = std::array<std::ptrdiff_t, 3>{static_cast<std::ptrdiff_t>(l.xs.size()) - 1,
                                               static_cast<std::ptrdiff_t>(l.ys.size()) - 1,
                                               static_cast<std::ptrdiff_t>(l.zs.size()) - 1};
  // Manifold corners, and χ = Σ over lattice points of the cubical cells they are the lowest
  // corner of, with sign (−1)^dim: a point is in the set when a cell around it is full, etc.
  std::ptrdiff_t chi = 0;
  for (std::ptrdiff_t k = 0; k <= n[2]; ++k)
    for (std::ptrdiff_t j = 0; j <= n[1]; ++j)
      for (std::ptrdiff_t i = 0; i <= n[0]; ++i) {
        unsigned mask = 0;
        for (unsigned b = 0; b < 8; ++b)
          if (full_cell(l, i - 1 + (b & 1), j - 1 + (b >> 1 & 1), k - 1 + (b >> 2 & 1))) mask |= 1u << b;
        if (!manifold_corner(mask)) return -1;
        // The cubical cell at (i,j,k) spanning the directions in `dirs` is in the set when one
        // of the full cells containing it is: cells (i - 1 + b) with b = 1 along every spanned
        // direction and 0/1 along the others.
        for (unsigned dirs = 0; dirs < 8; ++dirs) {
          bool in = false;
          for (unsigned b = 0; b < 8 && !in; ++b) {
            if ((b & dirs) != dirs) continue;
            in = (mask >> b & 1u) != 0;
          }
          if (in) chi += (std::popcount(dirs) % 2 == 0) ? 1 : -1;
        }
      }
  // Face connectivity of the full cells, and of the empty ones with the outside.
  const auto index = [&](std::ptrdiff_t i, std::ptrdiff_t j, std::ptrdiff_t k) {
    return static_cast<std::size_t>((i + 1) + (n[0] + 2) * ((j + 1) + (n[1] + 2) * (k + 1)));
  };
  std::vector<char> seen(static_cast<std::size_t>((n[0] + 2) * (n[1] + 2) * (n[2] + 2)), 0);
  const auto flood = [&](std::array<std::ptrdiff_t, 3> start, bool full) {
    std::size_t count = 0;
    std::vector<std::array<std::ptrdiff_t, 3>> todo{start};
    seen[index(start[0], start[1], start[2])] = 1;
    while (!todo.empty()) {
      const auto c = todo.back();
      todo.pop_back();
      ++count;
      for (std::size_t a = 0; a < 3; ++a)
        for (const std::ptrdiff_t s : {-1, 1}) {
          auto d = c;
          d[a] += s;
          if (d[a] < -1 || d[a] > n[a]) continue;
          if (seen[index(d[0], d[1], d[2])] || full_cell(l, d[0], d[1], d[2]) != full) continue;
          seen[index(d[0], d[1], d[2])] = 1;
          todo.push_back(d);
        }
    }
    return count;
  };
  const auto full =
      static_cast<std::size_t>(std::count_if(l.labels.begin(), l.labels.end(), [](int x) { return x != 0; }));
  if (full == 0) return -1;
  const std::size_t empty = seen.size() - full;
  if (flood({-1, -1, -1}, false) != empty) return -1;
  for (std::ptrdiff_t c = 0; c < n[0] * n[1] * n[2]; ++c)
    if (l.labels[static_cast<std::size_t>(c)] != 0) {
      if (flood({c % n[0], c / n[0] % n[1], c / (n[0] * n[1])}, true) != full) return -1;
      break;
    }
  return static_cast<int>(1 - chi);
}

/// Lattice coordinates from random widths in [lo, hi]. O(n).
template <class = void>
std::vector<double> random_coords(std::size_t cells, double lo, double hi, cellforge::detail::splitmix& rng) {
  std::vector<double> c{0.0};
  for (std::size_t i = 0; i < cells; ++i) c.push_back(c.back() + rng.uniform(lo, hi));
  return c;
}

/// A uniformly random index below n. O(1).
template <class = void>
std::size_t below(std::size_t n, cellforge::detail::splitmix& rng) {
  return static_cast<std::size_t>(rng.next() % n);
}

}  // namespace detail

/// A normalon solid (faces merged, one volume) with its genus, or nothing.
struct voxel_solid {
  sample_model model;
  int genus = 0;
};

/// The model of a layout's full cells as one merged solid when they make a 2-manifold solid
/// (detail::voxel_solid_genus) whose faces make_voxel_model can outline; nullopt otherwise.
/// O(cells log cells).
template <class = void>
std::optional<voxel_solid> voxel_solid_model(voxel_layout l, std::string name) {
  for (auto& x : l.labels) x = x != 0 ? 1 : 0;
  l.merge_faces = true;
  const int genus = detail::voxel_solid_genus(l);
  if (genus < 0) return std::nullopt;
  try {
    return voxel_solid{make_voxel_model(l, std::move(name)), genus};
  } catch (const error&) {
    return std::nullopt;  // a face outline touching itself at a vertex
  }
}

/// A random face-connected set of `count` cells grown in an nx × ny × nz lattice of random
/// widths, as a merged normalon solid; nullopt when the set is not a 2-manifold solid.
/// O(cells log cells).
template <class = void>
std::optional<voxel_solid> random_normalon(std::size_t nx, std::size_t ny, std::size_t nz, std::size_t count,
                                           std::uint64_t seed) {
  detail::require_lattice("random_normalon", nx, ny, nz);
  cellforge::detail::splitmix rng{seed ^ 0x6e6f726d616c6f6eu};
  // One draw per statement: argument order is the compiler's choice.
  std::vector<double> xs = detail::random_coords(nx, 0.5, 1.5, rng);
  std::vector<double> ys = detail::random_coords(ny, 0.5, 1.5, rng);
  std::vector<double> zs = detail::random_coords(nz, 0.5, 1.5, rng);
  voxel_layout l = empty_layout(std::move(xs), std::move(ys), std::move(zs));
  const std::size_t cells = nx * ny * nz;
  count = std::clamp<std::size_t>(count, 1, cells);
  std::vector<std::size_t> set{detail::below(cells, rng)};
  l.labels[set[0]] = 1;
  for (std::size_t guard = 0; set.size() < count && guard < 100 * cells; ++guard) {
    const std::size_t c = set[detail::below(set.size(), rng)];
    const std::size_t a = detail::below(3, rng);
    const std::array<std::size_t, 3> dim{nx, ny, nz};
    std::array<std::size_t, 3> q{c % nx, c / nx % ny, c / (nx * ny)};
    if (rng.next() & 1u) {
      if (q[a] + 1 >= dim[a]) continue;
      ++q[a];
    } else {
      if (q[a] == 0) continue;
      --q[a];
    }
    const std::size_t d = q[0] + nx * (q[1] + ny * q[2]);
    if (l.labels[d] != 0) continue;
    l.labels[d] = 1;
    set.push_back(d);
  }
  return voxel_solid_model(
      std::move(l), cellforge::detail::cat("random normalon ", std::to_string(nx), "x", std::to_string(ny),
                                           "x", std::to_string(nz), " #", std::to_string(seed)));
}

/// A skyline: an nx × ny grid of columns of random widths, each 1..max_height cells of random
/// heights tall, as a merged normalon solid. Where two diagonal columns both rise above the
/// other two of their 2 × 2 block (they would touch along an edge only) the lower of those
/// is raised; nullopt when the result still is no 2-manifold solid. O(cells log cells).
template <class = void>
std::optional<voxel_solid> random_skyline(std::size_t nx, std::size_t ny, std::size_t max_height,
                                          std::uint64_t seed) {
  max_height = std::max<std::size_t>(max_height, 1);
  detail::require_lattice("random_skyline", nx, ny, max_height);
  cellforge::detail::splitmix rng{seed ^ 0x736b796c696e6500u};
  std::vector<double> xs = detail::random_coords(nx, 0.5, 1.5, rng);
  std::vector<double> ys = detail::random_coords(ny, 0.5, 1.5, rng);
  std::vector<double> zs = detail::random_coords(max_height, 0.3, 1.0, rng);
  voxel_layout l = empty_layout(std::move(xs), std::move(ys), std::move(zs));
  std::vector<std::size_t> h(nx * ny);
  for (auto& x : h) x = 1 + detail::below(max_height, rng);
  for (bool again = true; again;) {  // heights only grow, to at most max_height: ends
    again = false;
    for (std::size_t j = 0; j + 1 < ny; ++j)
      for (std::size_t i = 0; i + 1 < nx; ++i) {
        std::size_t &a = h[i + nx * j], &b = h[i + 1 + nx * (j + 1)], &c = h[i + 1 + nx * j],
                    &d = h[i + nx * (j + 1)];
        if (std::min(a, b) > std::max(c, d)) {
          (c < d ? c : d) = std::min(a, b);
          again = true;
        } else if (std::min(c, d) > std::max(a, b)) {
          (a < b ? a : b) = std::min(c, d);
          again = true;
        }
      }
  }
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      for (std::size_t k = 0; k < h[i + nx * j]; ++k) l.at(i, j, k) = 1;
  return voxel_solid_model(
      std::move(l), cellforge::detail::cat("skyline ", std::to_string(nx), "x", std::to_string(ny), " #",
                                           std::to_string(seed)));
}

/// A 3 × 3 × 3 block of random widths with `notches` random edge or corner cells cut away
/// (cells with at least two coordinates on the block's outside); nullopt when the result is
/// not a 2-manifold solid. O(1).
template <class = void>
std::optional<voxel_solid> notched_block(std::size_t notches, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x6e6f746368000000u};
  std::vector<double> xs = detail::random_coords(3, 0.4, 1.6, rng);
  std::vector<double> ys = detail::random_coords(3, 0.4, 1.6, rng);
  std::vector<double> zs = detail::random_coords(3, 0.4, 1.6, rng);
  voxel_layout l = empty_layout(std::move(xs), std::move(ys), std::move(zs));
  std::fill(l.labels.begin(), l.labels.end(), 1);
  std::vector<std::size_t> candidates;
  for (std::size_t c = 0; c < 27; ++c) {
    const std::size_t i = c % 3, j = c / 3 % 3, k = c / 9;
    if ((i != 1) + (j != 1) + (k != 1) >= 2) candidates.push_back(c);
  }
  for (std::size_t t = 0; t < notches && !candidates.empty(); ++t) {
    const std::size_t pick = detail::below(candidates.size(), rng);
    l.labels[candidates[pick]] = 0;
    candidates.erase(candidates.begin() + static_cast<std::ptrdiff_t>(pick));
  }
  return voxel_solid_model(std::move(l), cellforge::detail::cat("notched block ", std::to_string(notches),
                                                                " #", std::to_string(seed)));
}

/// A staircase of `steps` steps (1..1000) of random treads and risers, extruded across:
/// 2·(2·steps + 2) vertices, 3·(2·steps + 2) edges, 2·steps + 4 faces (two staircase
/// polygons). O(steps²).
template <class = void>
sample_model sample_stairs(std::size_t steps, std::uint64_t seed) {
  if (steps < 1 || steps > 1000)
    throw error(error_category::invalid_input, "sample_stairs: steps must be in 1..1000");
  cellforge::detail::splitmix rng{seed ^ 0x7374616972730000u};
  std::vector<double> x{0.0}, h{0.0};  // step i spans [x[i], x[i+1]], its top at h[i+1]
  for (std::size_t s = 0; s < steps; ++s) {
    x.push_back(x.back() + rng.uniform(0.6, 1.4));
    h.push_back(h.back() + rng.uniform(0.4, 1.0));
  }
  std::vector<glm::dvec2> p{{0, 0}, {x[steps], 0}, {x[steps], h[steps]}};
  for (std::size_t i = steps; i-- > 0;) {
    p.push_back({x[i], h[i + 1]});
    if (i > 0) p.push_back({x[i], h[i]});
  }
  return extruded_polygon(
      p, rng.uniform(1.0, 3.0),
      cellforge::detail::cat("stairs ", std::to_string(steps), " #", std::to_string(seed)));
}

/// A block of random widths with `holes` (1..4) rectangular through-slots along y (genus
/// `holes`): its front and back faces have holes. O(1).
template <class = void>
voxel_solid through_slot(std::size_t holes, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x736c6f7400000000u};
  holes = std::clamp<std::size_t>(holes, 1, 4);
  const std::size_t nx = holes >= 2 ? 5 : 3, nz = holes >= 3 ? 5 : 3, ny = 1 + detail::below(2, rng);
  std::vector<double> xs = detail::random_coords(nx, 0.3, 1.5, rng);
  std::vector<double> ys = detail::random_coords(ny, 0.5, 2.0, rng);
  std::vector<double> zs = detail::random_coords(nz, 0.3, 1.5, rng);
  voxel_layout l = empty_layout(std::move(xs), std::move(ys), std::move(zs));
  std::fill(l.labels.begin(), l.labels.end(), 1);
  const std::array<std::array<std::size_t, 2>, 4> at{{{1, 1}, {3, 1}, {1, 3}, {3, 3}}};
  for (std::size_t h = 0; h < holes; ++h)
    for (std::size_t j = 0; j < ny; ++j) l.at(at[h][0], j, at[h][1]) = 0;
  auto s = voxel_solid_model(std::move(l), cellforge::detail::cat("through slot ", std::to_string(holes),
                                                                  " #", std::to_string(seed)));
  if (!s)
    throw error(error_category::invalid_input, "through_slot: not a manifold solid (a generator fault)");
  return *s;
}

/// The polygon with the corners in `which` cut off: each replaced by two points at `size`
/// (a fraction 0..0.5 of the shorter side at it) along its two sides. O(n).
template <class = void>
std::vector<glm::dvec2> chamfered_corners(const std::vector<glm::dvec2>& p, const std::vector<bool>& which,
                                          double size) {
  std::vector<glm::dvec2> out;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (i >= which.size() || !which[i]) {
      out.push_back(p[i]);
      continue;
    }
    const glm::dvec2 a = p[(i + n - 1) % n], b = p[i], c = p[(i + 1) % n];
    const double d = size * std::min(glm::length(a - b), glm::length(c - b));
    out.push_back(b + d * glm::normalize(a - b));
    out.push_back(b + d * glm::normalize(c - b));
  }
  return out;
}

/// A random quasi-normalon (docs/sketch.md): kind 0 a block with 1..4 chamfered edges, 1 a
/// block with 1..4 corners cut off, 2 a wedge, 3 a ramp, 4 an L or T block with oblique
/// chamfers, 5 a gable house (its ridge hangs on oblique edges only: not a quasi-normalon by
/// the flag's rule). Random sizes from `seed`. O(1).
template <class = void>
sample_model random_quasi_normalon(int kind, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x7175617369000000u};
  const double a = rng.uniform(1, 3), b = rng.uniform(1, 3), c = rng.uniform(1, 3);
  const std::string tag = cellforge::detail::cat(" #", std::to_string(seed));
  const auto pick_corners = [&](std::size_t n, std::size_t lo, std::size_t hi,
                                const std::vector<bool>& allowed) {
    std::vector<bool> which(n, false);
    const std::size_t k = lo + detail::below(hi - lo + 1, rng);
    for (std::size_t t = 0; t < 4 * k; ++t) {
      const std::size_t i = detail::below(n, rng);
      if (allowed[i] && std::count(which.begin(), which.end(), true) < static_cast<std::ptrdiff_t>(k))
        which[i] = true;
    }
    if (std::count(which.begin(), which.end(), true) == 0)
      for (std::size_t i = 0; i < n; ++i)
        if (allowed[i]) {
          which[i] = true;
          break;
        }
    return which;
  };
  switch (kind) {
    case 0: {
      const std::vector<glm::dvec2> rect{{0, 0}, {a, 0}, {a, b}, {0, b}};
      const std::vector<bool> which = pick_corners(4, 1, 4, std::vector<bool>(4, true));
      const double size = rng.uniform(0.15, 0.45);
      return extruded_polygon(chamfered_corners(rect, which, size), c,
                              cellforge::detail::cat("chamfered block", tag));
    }
    case 1: {
      std::vector<glm::dvec3> pts;
      for (unsigned corner = 0; corner < 8; ++corner) {
        const glm::dvec3 q((corner & 1u) ? a : 0.0, (corner & 2u) ? b : 0.0, (corner & 4u) ? c : 0.0);
        if (rng.uniform(0, 1) < 0.4 || corner == 7) {
          for (int axis = 0; axis < 3; ++axis) {
            glm::dvec3 r = q;
            r[axis] += ((corner >> axis & 1u) ? -1.0 : 1.0) * rng.uniform(0.15, 0.45) * std::min({a, b, c});
            pts.push_back(r);
          }
        } else {
          pts.push_back(q);
        }
      }
      return convex_polytope_model(pts, cellforge::detail::cat("corner-cut block", tag));
    }
    case 2:
      return extruded_polygon({{0, 0}, {a, 0}, {0, b}}, c, cellforge::detail::cat("wedge", tag));
    case 3:
      return extruded_polygon({{0, 0}, {a + 1, 0}, {a + 1, b}, {rng.uniform(0.3, 0.8) * (a + 1), b}}, c,
                              cellforge::detail::cat("ramp", tag));
    case 4: {
      const int letter = static_cast<int>(detail::below(2, rng));
      const std::vector<glm::dvec2> p = letter_footprint(letter, 0.0, rng);
      // Convex corners only (counter-clockwise footprints: a left turn).
      std::vector<bool> convex(p.size());
      for (std::size_t i = 0; i < p.size(); ++i) {
        const glm::dvec2 u = p[i] - p[(i + p.size() - 1) % p.size()], v = p[(i + 1) % p.size()] - p[i];
        convex[i] = u.x * v.y - u.y * v.x > 0;
      }
      const std::vector<bool> which = pick_corners(p.size(), 1, 3, convex);
      const double size = rng.uniform(0.2, 0.45);
      return extruded_polygon(
          chamfered_corners(p, which, size), c,
          cellforge::detail::cat(std::string(letter == 0 ? "chamfered L" : "chamfered T"), tag));
    }
    default:
      return extruded_polygon({{0, 0}, {a, 0}, {a, b}, {a / 2, b + rng.uniform(0.3, 1.2)}, {0, b}}, c,
                              cellforge::detail::cat("gable house", tag));
  }
}

// ---- models of several volumes, touching solids and faceted curved solids ------------------------
// The families below break the one-solid model on purpose: internal walls (an edge on three or
// four faces, two of them coplanar where a wall meets a flat side), solids touching along an edge
// or at a vertex (an edge on four faces), and solids of revolution whose rings are planar cycles
// of edges that are no faces. Every volume is a ball, so V − E + F − R − C = 1 − genus for a
// connected model (C its volumes); the truth is what wireframe_to_cells reads from the 3D model
// (the test checks it).

/// Several convex cells glued into one model: each cell's points in convex position
/// (convex_polytope_model), equal points (bit for bit) one vertex, a face two cells share (the
/// same cycle) one face between two volumes. The cells must meet face to face (a corner of one
/// on a side of another is not checked here: wireframe_to_cells reads such a model otherwise).
/// O(Σ n log n).
template <class = void>
sample_model convex_cells_model(const std::vector<std::vector<glm::dvec3>>& cells, std::string name) {
  sample_model m;
  m.name = std::move(name);
  std::map<std::array<double, 3>, std::uint32_t> id;
  std::map<std::vector<std::uint32_t>, std::uint32_t> face_id;
  std::set<std::array<std::uint32_t, 2>> edges;
  for (const auto& cell : cells) {
    const sample_model c = convex_polytope_model(cell, m.name);
    std::vector<std::uint32_t> global;
    for (const auto& p : c.wire.points) {
      const auto [it, fresh] = id.insert({{p.x, p.y, p.z}, static_cast<std::uint32_t>(m.wire.points.size())});
      if (fresh) m.wire.points.push_back(p);
      global.push_back(it->second);
    }
    std::vector<std::uint32_t> volume;
    for (const auto& face : c.faces) {
      std::vector<std::uint32_t> loop;
      for (const auto v : face[0]) loop.push_back(global[v]);
      for (std::size_t k = 0; k < loop.size(); ++k)
        edges.insert(
            {std::min(loop[k], loop[(k + 1) % loop.size()]), std::max(loop[k], loop[(k + 1) % loop.size()])});
      const auto [it, fresh] = face_id.insert(
          {cellforge::detail::canonical_cycle(loop), static_cast<std::uint32_t>(m.faces.size())});
      if (fresh) m.faces.push_back({std::move(loop)});
      volume.push_back(it->second);
    }
    m.volumes.push_back(std::move(volume));
  }
  m.wire.edges.assign(edges.begin(), edges.end());
  return detail::finish(std::move(m));
}

/// A box (base = 0, sides of random lengths) or a regular base-gon prism (3..12) split by
/// `cuts` (1..3) random planes through its middle into convex cells, each its own volume (walls
/// crossing walls: an edge on four faces where two cuts cross); nullopt when a cut passes within
/// 4 % of the size of a corner (sliver cells). `diagonal`: one more wall, the box's plane through
/// two opposite vertical edges, first. O(cells · n log n).
template <class = void>
std::optional<sample_model> sliced_polytope(std::size_t base, std::size_t cuts, bool diagonal,
                                            std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x736c696365000000u};
  std::vector<glm::dvec3> start;
  const double a = rng.uniform(0.8, 2.0), b = rng.uniform(0.8, 2.0), c = rng.uniform(0.8, 2.0);
  if (base == 0) {
    for (unsigned k = 0; k < 8; ++k)
      start.push_back({(k & 1u) ? a : 0.0, (k & 2u) ? b : 0.0, (k & 4u) ? c : 0.0});
  } else {
    if (base < 3 || base > 12)
      throw error(error_category::invalid_input, "sliced_polytope: base must be 0 or 3..12");
    for (std::size_t i = 0; i < base; ++i) {
      const double t = 2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(base);
      for (const double z : {0.0, c}) start.push_back({std::cos(t), std::sin(t), z});
    }
  }
  const double size = detail::diagonal_of(start);
  std::vector<std::pair<glm::dvec3, double>> planes;                           // n · x = d
  if (diagonal && base == 0) planes.push_back({glm::dvec3(b, -a, 0.0), 0.0});  // through (0,0,z), (a,b,z)
  glm::dvec3 centre(0.0);
  for (const auto& p : start) centre += p;
  centre /= static_cast<double>(start.size());
  for (std::size_t k = 0; k < cuts; ++k) {
    glm::dvec3 n;
    do n = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    while (glm::length(n) > 1 || glm::length(n) < 0.2);
    n = glm::normalize(n);
    const glm::dvec3 at =
        centre + 0.25 * size * glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    planes.push_back({n, glm::dot(n, at)});
  }
  std::vector<std::vector<glm::dvec3>> cells{start};
  for (const auto& [n, d] : planes) {
    const double len = glm::length(n);
    std::vector<std::vector<glm::dvec3>> next;
    for (const auto& cell : cells) {
      const sample_model m = convex_polytope_model(cell, "cell");
      const auto& p = m.wire.points;
      std::vector<double> side(p.size());
      bool below = false, above = false;
      for (std::size_t i = 0; i < p.size(); ++i) {
        side[i] = (glm::dot(n, p[i]) - d) / len;
        if (side[i] != 0 && std::abs(side[i]) < 0.04 * size) return std::nullopt;
        below = below || side[i] < 0, above = above || side[i] > 0;
      }
      if (!below || !above) {
        next.push_back(cell);
        continue;
      }
      std::vector<glm::dvec3> lo, hi;
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (side[i] <= 0) lo.push_back(p[i]);
        if (side[i] >= 0) hi.push_back(p[i]);
      }
      for (const auto& e : m.wire.edges) {
        if (!((side[e[0]] < 0 && side[e[1]] > 0) || (side[e[0]] > 0 && side[e[1]] < 0))) continue;
        // The same segment gives the same point in every cell: ends in lexicographic order.
        std::uint32_t u = e[0], w = e[1];
        if (std::array<double, 3>{p[w].x, p[w].y, p[w].z} < std::array<double, 3>{p[u].x, p[u].y, p[u].z})
          std::swap(u, w);
        const double t = side[u] / (side[u] - side[w]);
        const glm::dvec3 x = p[u] + t * (p[w] - p[u]);
        lo.push_back(x), hi.push_back(x);
      }
      next.push_back(std::move(lo));
      next.push_back(std::move(hi));
    }
    cells = std::move(next);
  }
  std::string name = (base == 0 ? std::string("sliced box")
                                : cellforge::detail::cat("sliced prism ", std::to_string(base))) +
                     (diagonal ? " (diagonal wall)" : "") + ", " + std::to_string(cuts) + " cuts #" +
                     std::to_string(seed);
  sample_model m = convex_cells_model(cells, std::move(name));
  // Well shaped: no edge shorter than 3 % of the size.
  for (const auto& e : m.wire.edges)
    if (glm::length(m.wire.points[e[0]] - m.wire.points[e[1]]) < 0.03 * size) return std::nullopt;
  return m;
}

/// A roof on a box, two volumes: kind 0 a triangular prism (ridge anywhere over the box), 1 a
/// trapezoid prism, 2 a wedge (one roof side flush with a wall). The roof's ends lie in the
/// box's end walls, so the square between them is a face no reading can drop (its edges at the
/// ends would otherwise join two coplanar faces). Random sizes from `seed`. O(1).
template <class = void>
sample_model roof_on_box(int kind, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x726f6f6600000000u};
  const double a = rng.uniform(0.8, 2.0), b = rng.uniform(0.8, 2.5), c = rng.uniform(0.5, 1.5),
               h = rng.uniform(0.4, 1.2);
  std::vector<glm::dvec3> box, roof;
  for (unsigned k = 0; k < 8; ++k)
    box.push_back({(k & 1u) ? a : 0.0, (k & 2u) ? b : 0.0, (k & 4u) ? c : 0.0});
  std::vector<glm::dvec2> section{{0, c}, {a, c}};  // (x, z) along y
  std::string what;
  if (kind == 0) {
    section.push_back({rng.uniform(0.2, 0.8) * a, c + h});
    what = "gable roof";
  } else if (kind == 1) {
    const double l = rng.uniform(0.15, 0.4) * a, r = rng.uniform(0.6, 0.85) * a;
    section.push_back({r, c + h});
    section.push_back({l, c + h});
    what = "hipped-section roof";
  } else {
    section.push_back({a, c + h});
    what = "wedge roof";
  }
  for (const auto& q : section)
    for (const double y : {0.0, b}) roof.push_back({q.x, y, q.y});
  return convex_cells_model({box, roof},
                            cellforge::detail::cat("box with a ", what, " #", std::to_string(seed)));
}

/// A rectangular frame of bars (genus `holes`, 1 or 2): an nx × ny ring of lattice cells (a
/// middle bar across when holes = 2), one or two cells thick, each bar its own volume; a corner
/// cell is a block of its own or belongs to one of its two bars at random, so bars meet at
/// walls across the frame. Two holes: wireframe_to_cells reads the holes as cells (their
/// mouths continue the bars' faces; docs/sketch.md), so the sweep draws one. O(cells).
/// O(cells).
template <class = void>
sample_model bar_frame(std::size_t holes, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x6672616d65000000u};
  holes = std::clamp<std::size_t>(holes, 1, 2);
  const std::size_t nx = holes == 2 ? 5 : 3 + detail::below(3, rng), ny = 3 + detail::below(3, rng),
                    nz = 1 + detail::below(2, rng);
  voxel_layout l =
      empty_layout(detail::random_coords(nx, 0.3, 1.2, rng), detail::random_coords(ny, 0.3, 1.2, rng),
                   detail::random_coords(nz, 0.3, 0.8, rng));
  const std::size_t mid = nx / 2;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        const bool row = j == 0 || j + 1 == ny, column = i == 0 || i + 1 == nx || (holes == 2 && i == mid);
        if (!row && !column) continue;
        // Bars: rows 1 (bottom) and 2 (top), split at the middle bar (+10 right of it), 20 + the
        // column index for columns. A cell where bars cross goes to one of them at random.
        const int row_bar = (j == 0 ? 1 : 2) + (holes == 2 && i > mid ? 10 : 0),
                  column_bar = 20 + static_cast<int>(i);
        if (k > 0) {
          l.at(i, j, k) = l.at(i, j, 0);
        } else if (row && column) {
          const double u = rng.uniform(0, 1);  // a third of the corners are blocks of their own
          l.at(i, j, k) = u < 0.33                               ? 100 + static_cast<int>(i + nx * j)
                          : u < 0.66                             ? column_bar
                          : (holes == 2 && i == mid && u < 0.83) ? row_bar + 10
                                                                 : row_bar;
        } else {
          l.at(i, j, k) = row ? row_bar : column_bar;
        }
      }
  std::map<int, int> compact;  // labels 1..bars, as make_voxel_model wants them
  for (auto& x : l.labels)
    if (x != 0) x = compact.insert({x, static_cast<int>(compact.size()) + 1}).first->second;
  return make_voxel_model(l, cellforge::detail::cat("frame of bars, ", std::to_string(holes), " hole",
                                                    (holes == 2 ? "s" : ""), " #", std::to_string(seed)));
}

/// A block split into boxes by random guillotine cuts along lattice planes (each box its own
/// volume: walls ending on walls), or, with `every_cell`, a random face-connected set of
/// lattice cells whose union is a 2-manifold solid, every cell its own volume; nullopt when the
/// set is not. Random widths from `seed`. O(cells).
template <class = void>
std::optional<sample_model> cell_block(std::size_t nx, std::size_t ny, std::size_t nz, bool every_cell,
                                       std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x63656c6c00000000u};
  voxel_layout l =
      empty_layout(detail::random_coords(nx, 0.4, 1.4, rng), detail::random_coords(ny, 0.4, 1.4, rng),
                   detail::random_coords(nz, 0.4, 1.4, rng));
  int next = 1;
  if (every_cell) {
    const std::size_t count = 2 + detail::below(nx * ny * nz - 1, rng);
    std::vector<std::array<std::size_t, 3>> grown{
        {detail::below(nx, rng), detail::below(ny, rng), detail::below(nz, rng)}};
    l.at(grown[0][0], grown[0][1], grown[0][2]) = next++;
    for (std::size_t tries = 0; grown.size() < count && tries < 50 * count; ++tries) {
      auto c = grown[detail::below(grown.size(), rng)];
      const std::size_t axis = detail::below(3, rng);
      const std::array<std::size_t, 3> n{nx, ny, nz};
      if (rng.uniform(0, 1) < 0.5) {
        if (c[axis] == 0) continue;
        --c[axis];
      } else {
        if (c[axis] + 1 >= n[axis]) continue;
        ++c[axis];
      }
      if (l.at(c[0], c[1], c[2]) != 0) continue;
      l.at(c[0], c[1], c[2]) = next++;
      grown.push_back(c);
    }
    voxel_layout solid = l;
    for (auto& x : solid.labels) x = x != 0 ? 1 : 0;
    if (detail::voxel_solid_genus(solid) != 0) return std::nullopt;
  } else {
    // Guillotine: split a box of cells at a random lattice plane until it is one cell or stops.
    std::vector<std::array<std::size_t, 6>> stack{{0, nx, 0, ny, 0, nz}};
    while (!stack.empty()) {
      const auto box = stack.back();
      stack.pop_back();
      std::vector<std::size_t> axes;
      for (std::size_t a = 0; a < 3; ++a)
        if (box[2 * a + 1] - box[2 * a] > 1) axes.push_back(a);
      if (!axes.empty() &&
          (box == std::array<std::size_t, 6>{0, nx, 0, ny, 0, nz} || rng.uniform(0, 1) < 0.7)) {
        const std::size_t a = axes[detail::below(axes.size(), rng)];
        const std::size_t at = box[2 * a] + 1 + detail::below(box[2 * a + 1] - box[2 * a] - 1, rng);
        auto first = box, second = box;
        first[2 * a + 1] = at, second[2 * a] = at;
        stack.push_back(first), stack.push_back(second);
        continue;
      }
      for (std::size_t k = box[4]; k < box[5]; ++k)
        for (std::size_t j = box[2]; j < box[3]; ++j)
          for (std::size_t i = box[0]; i < box[1]; ++i) l.at(i, j, k) = next;
      ++next;
    }
  }
  return make_voxel_model(l, cellforge::detail::cat(std::string(every_cell ? "cells" : "guillotine block"),
                                                    " ", std::to_string(nx), "x", std::to_string(ny), "x",
                                                    std::to_string(nz), " #", std::to_string(seed)));
}

/// Boxes that touch along edges or at vertices only (kind 0: two along an edge; 1: a box on
/// another along an edge; 2: a chain of three along edges; 3: two at a vertex; 4: four in a 3D
/// checkerboard, each pair along an edge; 5: a face-joined pair and a third box along an edge;
/// 6: a box and a triangular prism along an edge), each its own volume; random widths. O(1).
template <class = void>
sample_model touching_solids(int kind, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x746f756368000000u};
  const auto coords = [&](std::size_t n) { return detail::random_coords(n, 0.5, 1.5, rng); };
  const std::string tag = cellforge::detail::cat(" #", std::to_string(seed));
  if (kind == 6) {
    const double a = rng.uniform(0.6, 1.5), b = rng.uniform(0.6, 1.5), c = rng.uniform(0.6, 1.5);
    std::vector<glm::dvec3> box, prism;
    for (unsigned k = 0; k < 8; ++k)
      box.push_back({(k & 1u) ? a : 0.0, (k & 2u) ? b : 0.0, (k & 4u) ? c : 0.0});
    // The prism's triangle has a corner at (a, b) and lies in the quadrant beyond it.
    const std::vector<glm::dvec2> tri{{a, b},
                                      {a + rng.uniform(0.6, 1.4), b + rng.uniform(0.1, 0.5)},
                                      {a + rng.uniform(0.1, 0.5), b + rng.uniform(0.6, 1.4)}};
    for (const auto& q : tri)
      for (const double z : {0.0, c}) prism.push_back({q.x, q.y, z});
    return convex_cells_model({box, prism}, cellforge::detail::cat("box and prism along an edge", tag));
  }
  const std::array<std::array<std::size_t, 3>, 7> lattice{
      {{2, 2, 1}, {2, 1, 2}, {3, 3, 1}, {2, 2, 2}, {2, 2, 2}, {3, 2, 1}, {1, 1, 1}}};
  const auto n = lattice[static_cast<std::size_t>(kind)];
  voxel_layout l = empty_layout(coords(n[0]), coords(n[1]), coords(n[2]));
  std::string what;
  switch (kind) {
    case 0:
      l.at(0, 0, 0) = 1, l.at(1, 1, 0) = 2, what = "two boxes along an edge";
      break;
    case 1:
      l.at(0, 0, 0) = 1, l.at(1, 0, 1) = 2, what = "a box on a box along an edge";
      break;
    case 2:
      l.at(0, 0, 0) = 1, l.at(1, 1, 0) = 2, l.at(2, 2, 0) = 3, what = "three boxes in a chain of edges";
      break;
    case 3:
      l.at(0, 0, 0) = 1, l.at(1, 1, 1) = 2, what = "two boxes at a vertex";
      break;
    case 4:
      l.at(0, 0, 0) = 1, l.at(1, 1, 0) = 2, l.at(1, 0, 1) = 3, l.at(0, 1, 1) = 4,
                 what = "3D checkerboard of four boxes";
      break;
    default:
      l.at(0, 0, 0) = 1, l.at(1, 0, 0) = 2, l.at(2, 1, 0) = 3,
                 what = "two joined boxes and one along an edge";
      break;
  }
  return make_voxel_model(l, what + tag);
}

/// A faceted solid of revolution (a ring stack, samples/wireframe_models.hpp) of n-gon rings:
/// kind 0 a barrel or vase (random radii, planar caps), 1 a spindle (cone apexes), 2 a cylinder
/// cut into 2..4 volumes by walls, 3 a twisted stack of triangle bands, 4 a UV sphere. Its rings
/// are planar cycles that are no faces (but the walls of kind 2); every ring bends the profile,
/// so no two side faces are coplanar. O(rings · n).
template <class = void>
sample_model revolved_solid(int kind, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x7265766f6c000000u};
  const std::string tag = cellforge::detail::cat(" #", std::to_string(seed));
  if (kind == 4) {
    const std::size_t slices = 5 + detail::below(8, rng), stacks = 3 + detail::below(5, rng);
    sample_model m = sample_uv_sphere(slices, stacks);
    m.name = cellforge::detail::cat("uv sphere ", std::to_string(slices), "x", std::to_string(stacks), tag);
    return m;
  }
  ring_stack s;
  s.n = 5 + detail::below(kind == 3 ? 10 : 16, rng);
  const std::size_t rings = kind == 2 ? 3 + detail::below(3, rng) : 2 + detail::below(4, rng);
  double z = 0;
  for (std::size_t r = 0; r < rings; ++r) {
    s.height.push_back(z);
    z += rng.uniform(0.3, 1.0);
    s.radius.push_back(kind == 2 ? 1.0 : rng.uniform(0.5, 1.5));
  }
  if (kind != 2)  // every ring bends the profile: radii alternate around their neighbours' mean
    for (std::size_t r = 1; r + 1 < rings; ++r) {
      const double mid = 0.5 * (s.radius[r - 1] + s.radius[r + 1]);
      if (std::abs(s.radius[r] - mid) < 0.15) s.radius[r] = mid + (s.radius[r] >= mid ? 0.15 : -0.15);
    }
  if (kind == 1) s.bottom = -rng.uniform(0.3, 1.0), s.top = z + rng.uniform(0.0, 0.7);
  if (kind == 2) {
    for (std::size_t r = 1; r + 1 < rings; ++r) s.walls.push_back(r);
    if (rng.uniform(0, 1) < 0.5) s.top = z - 1.0 + rng.uniform(0.3, 1.0);  // a cone roof on the last ring
    if (s.top && *s.top <= s.height.back()) s.top = s.height.back() + 0.5;
  }
  if (kind == 3) {
    s.triangles = true;
    for (std::size_t r = 0; r < rings; ++r)
      s.twist.push_back(std::numbers::pi / static_cast<double>(s.n) * static_cast<double>(r));
  }
  static const char* what[] = {"barrel", "spindle", "walled cylinder", "twisted stack"};
  return make_ring_stack(s, cellforge::detail::cat(std::string(what[kind]), " ", std::to_string(s.n),
                                                   "-gon, ", std::to_string(rings), " rings", tag));
}

/// Hand-made drawings of the kinds seed 003 shows as hard for face
/// finders, each with its genus: internal faces, several circuits in one plane, edge pairs in
/// no face, through-slots, loops shorter than faces that are no faces. O(1).
template <class = void>
std::vector<voxel_solid> sketch_classics() {
  std::vector<voxel_solid> out;
  const auto voxels = [&](std::vector<double> xs, std::vector<double> ys, std::vector<double> zs,
                          const std::vector<std::array<std::size_t, 3>>& cells, std::string name) {
    voxel_layout l = empty_layout(std::move(xs), std::move(ys), std::move(zs));
    for (const auto& c : cells) l.at(c[0], c[1], c[2]) = 1;
    auto s = voxel_solid_model(std::move(l), std::move(name));
    if (!s) throw error(error_category::invalid_input, "sketch_classics: a classic is not a manifold solid");
    out.push_back(std::move(*s));
  };
  std::vector<std::array<std::size_t, 3>> pocket, tower;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      pocket.push_back({i, j, 0});
      tower.push_back({i, j, 0});
      if (i != 1 || j != 1) pocket.push_back({i, j, 1});
    }
  tower.push_back({1, 1, 1});
  voxels({0, 1.2, 2.0, 3.1}, {0, 0.9, 1.8, 2.6}, {0, 0.8, 1.3}, pocket,
         "classic: pocket block (internal faces, a ring face)");
  voxels({0, 1.2, 2.0, 3.1}, {0, 0.9, 1.8, 2.6}, {0, 0.8, 1.5}, tower,
         "classic: cube on a block (two circuits in the top plane)");
  voxels({0, 0.7, 2.0, 2.6}, {0, 2.2}, {0, 0.6, 1.7}, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 1}, {2, 0, 1}},
         "classic: U channel (two faces in one plane)");
  voxels({0, 1.0, 1.8}, {0, 0.9, 2.0}, {0, 0.7, 1.6}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}},
         "classic: corner step (a cube on a slab's corner: three L faces)");
  voxels({0, 1.0, 1.6, 2.7}, {0, 0.8, 1.7, 2.4}, {0, 0.9},
         {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0}, {0, 2, 0}, {1, 2, 0}, {2, 2, 0}},
         "classic: frame (faces with holes, genus 1)");
  out.push_back({sample_block_with_hole(), 1});
  out.back().model.name = "classic: block with a through-slot";
  out.push_back(through_slot(2, 7));
  out.back().model.name = "classic: block with two through-slots (genus 2)";
  sample_model oct = sample_bipyramid(4, 1.2, 0.9);
  oct.name = "classic: skew octahedron (edge pairs in no face, equator no face)";
  out.push_back({oct, 0});
  sample_model house = sample_house();
  house.name = "classic: house with a pyramid roof (the square under the roof is no face)";
  out.push_back({house, 0});
  sample_model tiny = sample_frustum(3, 0.04, 1.5);
  tiny.name = "classic: triangular frustum with a tiny top";
  out.push_back({tiny, 0});
  ring_stack s = detail::regular_stack(6, {0.0, 9.0}, 0.5);
  sample_model thin = make_ring_stack(s, "classic: long thin hexagonal prism");
  out.push_back({thin, 0});
  sample_model wedge =
      extruded_polygon({{0, 0}, {3, 0}, {0, 0.25}}, 2.0, "classic: thin wedge (a sliver face)");
  out.push_back({wedge, 0});
  cellforge::detail::splitmix rng{0x636c617373696373u};
  out.push_back({extruded_polygon(random_star_polygon(12, rng), 0.7, "classic: star prism 12"), 0});
  sample_model anti = sample_antiprism(8, 0.6);
  anti.name = "classic: flat octagonal antiprism (triangle strips)";
  out.push_back({anti, 0});
  return out;
}

/// What sketch_sweep builds.
struct sketch_sweep_options {
  std::size_t max_edges = 300;  ///< models with more edges are left out
  int views_per_model = 3;  ///< random generic views per model (×4 for the Platonic and Archimedean solids)
  std::uint64_t seed = 1;   ///< seed of the random families and of the views
  std::size_t random_models = 40;  ///< models per random family
  /// 0: every drawing; else a deterministic sample of about `limit` drawings (every k-th of
  /// each family, so every family stays), the same drawings the full sweep has.
  std::size_t limit = 0;
  /// Families to build (names of sketch_sweep_families()); empty: all of them.
  std::vector<std::string> families;
  /// generic_margin a view of a drawing of up to 100 edges must reach; a drawing of E > 100
  /// edges must reach min_margin · 100 / E (sketch_margin_threshold: the junctions of a dense
  /// drawing are closer, the margin per edge spacing is kept).
  double min_margin = 1e-3;
  int view_attempts = 500;  ///< random views tried per drawing before it is dropped
};

/// The generic_margin a sweep drawing of `edges` edges must reach: options.min_margin up to
/// 100 edges, min_margin · 100 / edges beyond. O(1).
template <class = void>
double sketch_margin_threshold(const sketch_sweep_options& options, std::size_t edges) {
  return edges <= 100 ? options.min_margin : options.min_margin * 100.0 / static_cast<double>(edges);
}

/// Per family: models built, drawings planned (models × views: what the sweep without a limit
/// tries), drawings made, random draws rejected (not a manifold solid or over max_edges),
/// drawings dropped for want of a generic view, edge range.
struct sketch_sweep_family {
  std::string family;
  std::size_t models = 0, planned = 0, drawings = 0, rejected = 0, no_view = 0;
  std::size_t min_edges = 0, max_edges = 0;
};

/// What sketch_sweep did: per family counts (in the order of sketch_sweep_families()), total
/// drawings and the time taken.
struct sketch_sweep_report {
  std::vector<sketch_sweep_family> families;
  std::size_t drawings = 0;
  double ms = 0;
};

/// The family names of the sweep, in its order. O(1).
template <class = void>
std::vector<std::string> sketch_sweep_families() {
  return {"prism",          "pyramid",          "antiprism", "platonic",   "archimedean",
          "random convex",  "cut cube",         "normalon",  "stairs",     "through slot",
          "quasi-normalon", "non-convex prism", "classic",   "cell block", "sliced",
          "roof on box",    "bar frame",        "touching",  "revolved"};
}

namespace detail {

/// Whether generic_margin reaches `stop`, with early exits: a value below `stop` when it does
/// not, else one at least `stop` (not the margin: far pairs are skipped).
/// O(V² + V·E + F·L).
template <class = void>
double margin_until(const sample_drawing& s, double stop) {
  const auto& pts = s.drawing.points;
  if (pts.empty()) return 0;
  glm::dvec2 lo = pts[0], hi = pts[0];
  for (const auto& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double diag = glm::length(hi - lo);
  if (!(diag > 0)) return 0;
  const double limit = stop * diag;
  double margin = std::numeric_limits<double>::infinity();
  for (const auto& face : s.model.faces) {
    glm::dvec3 n{0.0};
    const auto& loop = face[0];
    for (std::size_t k = 0; k < loop.size(); ++k)
      n += glm::cross(s.points[loop[k]], s.points[loop[(k + 1) % loop.size()]]);
    const double len = glm::length(n);
    if (len > 0) margin = std::min(margin, std::abs(n.z) / len);
    if (margin < stop) return margin;
  }
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (std::size_t j = i + 1; j < pts.size(); ++j) {
      const glm::dvec2 d = pts[i] - pts[j];
      if (std::abs(d.x) < limit && std::abs(d.y) < limit) margin = std::min(margin, glm::length(d) / diag);
      if (margin < stop) return margin;
    }
  for (const auto& e : s.drawing.edges) {
    const glm::dvec2 a = pts[e[0]], b = pts[e[1]];
    const glm::dvec2 elo = glm::min(a, b) - limit, ehi = glm::max(a, b) + limit;
    for (std::uint32_t v = 0; v < pts.size(); ++v) {
      const glm::dvec2 q = pts[v];
      if (v == e[0] || v == e[1] || q.x < elo.x || q.y < elo.y || q.x > ehi.x || q.y > ehi.y) continue;
      margin = std::min(margin, cellforge::detail::segment_distance(q, a, b) / diag);
      if (margin < stop) return margin;
    }
  }
  return margin;  // at least `stop`; the bounding-box filters skipped the pairs farther apart
}

/// FNV-1a of a string, mixed with a number. O(length).
template <class = void>
std::uint64_t name_hash(const std::string& s, std::uint64_t mix) {
  std::uint64_t h = 0xcbf29ce484222325u ^ mix;
  for (const char c : s) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3u;
  return h;
}

/// A model of the sweep before it is drawn.
struct sweep_item {
  sample_model model;
  std::string family;
  int genus = 0;
  int views = 1;
};

}  // namespace detail

/// The test drawings of the face finder: every family of sketch_sweep_families() (prisms,
/// pyramids with frusta and bipyramids, antiprisms, Platonic and Archimedean solids, random
/// convex polytopes, cut cubes and prisms, normalons, stairs, through-slots, quasi-normalons,
/// non-convex prisms, the classics), each model in several random generic views, with the
/// true faces and the genus; deterministic in the options. `report`, when given, receives the
/// per-family counts. O(Σ views · attempts · (V² + V·E)).
template <class = void>
std::vector<sample_drawing> sketch_sweep(const sketch_sweep_options& options = {},
                                         sketch_sweep_report* report = nullptr) {
  const cellforge::detail::stopwatch start;
  if (options.views_per_model < 1 || options.view_attempts < 1 || !(options.min_margin >= 0))
    throw error(error_category::invalid_input,
                "sketch_sweep: views_per_model and view_attempts must be at least 1, min_margin >= 0");
  const std::vector<std::string> names = sketch_sweep_families();
  for (const auto& f : options.families)
    if (std::find(names.begin(), names.end(), f) == names.end())
      throw error(
          error_category::invalid_input,
          cellforge::detail::cat("sketch_sweep: no family '", f, "'; sketch_sweep_families() lists them"));
  sketch_sweep_report rep;
  for (const auto& f : names) rep.families.push_back({f});
  const auto fam = [&](const std::string& f) -> sketch_sweep_family& {
    return rep.families[static_cast<std::size_t>(std::find(names.begin(), names.end(), f) - names.begin())];
  };
  std::vector<detail::sweep_item> items;
  const int v = options.views_per_model;
  // Adds a model when it is small enough; returns whether it did.
  // Families to build: options.families, or all of them.
  const auto wanted = [&](const char* family) {
    return options.families.empty() ||
           std::find(options.families.begin(), options.families.end(), family) != options.families.end();
  };
  const auto add = [&](sample_model m, const std::string& family, int genus, int views) {
    if (m.wire.edges.size() > options.max_edges) {
      ++fam(family).rejected;
      return false;
    }
    items.push_back({std::move(m), family, genus, views});
    return true;
  };
  const auto seed_of = [&](std::uint64_t family, std::uint64_t k) {
    return options.seed * 0x9e3779b97f4a7c15u + family * 0x100000u + k;
  };
  const std::size_t emax = options.max_edges;
  // Regular families: n from 3 to 20, then every 4th up to what max_edges allows.
  const auto sizes = [](std::size_t most) {
    std::vector<std::size_t> out;
    for (std::size_t n = 3; n <= most; n += n < 20 ? 1 : 4) out.push_back(n);
    return out;
  };
  if (wanted("prism"))
    for (const std::size_t n : sizes(std::min<std::size_t>(emax / 3, 100)))
      add(sample_prism(n), "prism", 0, v);
  if (wanted("pyramid"))
    for (const std::size_t n : sizes(std::min<std::size_t>(emax / 2, 100)))
      add(sample_pyramid(n), "pyramid", 0, v);
  if (wanted("pyramid"))
    for (const std::size_t n : sizes(std::min<std::size_t>(emax / 3, 12)))
      add(sample_frustum(n, 0.25 + 0.05 * static_cast<double>(n)), "pyramid", 0, v);
  if (wanted("pyramid"))
    for (const std::size_t n : sizes(std::min<std::size_t>(emax / 3, 100)))
      if (n < 12 || n % 8 == 0) add(sample_bipyramid(n, 0.8, 1.3), "pyramid", 0, v);
  if (wanted("antiprism"))
    for (const std::size_t n : sizes(std::min<std::size_t>(emax / 4, 75)))
      add(sample_antiprism(n), "antiprism", 0, v);
  if (wanted("platonic"))
    for (auto& m : platonic_solids()) add(std::move(m), "platonic", 0, 4 * v);
  if (wanted("archimedean"))
    for (auto& m : archimedean_solids()) add(std::move(m), "archimedean", 0, 4 * v);
  // Random families: draws until random_models are kept (or 20 times as many draws).
  const std::size_t want = options.random_models, budget = 20 * options.random_models + 20;
  if (wanted("random convex")) {
    std::size_t kept = 0;
    for (std::size_t k = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(1, k)};
      const bool sphere = k % 2 == 0;
      const std::size_t n = sphere ? 4 + detail::below(97, rng) : 8 + detail::below(143, rng);
      kept += add(random_convex_polytope(n, sphere, rng.next()), "random convex", 0, v);
    }
  }
  if (wanted("cut cube")) {
    std::size_t kept = 0;
    for (std::size_t k = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(2, k)};
      const std::size_t base = k % 5 < 3 ? 0 : 3 + detail::below(6, rng);
      const std::size_t cuts = 1 + detail::below(6, rng);
      sample_model m = cut_polytope(base, cuts, rng.next());
      // Well shaped: no edge shorter than 2 % of the size (a cut grazing a corner).
      double shortest = std::numeric_limits<double>::infinity();
      for (const auto& e : m.wire.edges)
        shortest = std::min(shortest, glm::length(m.wire.points[e[0]] - m.wire.points[e[1]]));
      if (shortest < 0.02 * detail::diagonal_of(m.wire.points)) {
        ++fam("cut cube").rejected;
        continue;
      }
      kept += add(std::move(m), "cut cube", 0, v);
    }
  }
  if (wanted("normalon")) add(sample_L(), "normalon", 0, v);
  if (wanted("normalon")) add(sample_T(), "normalon", 0, v);
  if (wanted("normalon")) add(sample_U(), "normalon", 0, v);
  if (wanted("normalon")) {
    std::size_t kept = 0;
    for (std::size_t k = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(3, k)};
      std::optional<voxel_solid> s;
      if (k % 3 == 2) {
        const std::size_t notches = 1 + detail::below(6, rng);
        s = notched_block(notches, rng.next());
      } else if (k % 3 == 1) {
        const std::size_t nx = 3 + detail::below(6, rng), ny = 3 + detail::below(6, rng);
        const std::size_t height = 2 + detail::below(3, rng);
        s = random_skyline(nx, ny, height, rng.next());
      } else {
        const std::size_t nx = 2 + detail::below(4, rng), ny = 2 + detail::below(4, rng),
                          nz = 1 + detail::below(4, rng);
        const std::size_t cells = nx * ny * nz;
        const std::size_t count = 2 + detail::below(cells - 2, rng);
        s = random_normalon(nx, ny, nz, count, rng.next());
      }
      if (!s) {
        ++fam("normalon").rejected;
        continue;
      }
      kept += add(std::move(s->model), "normalon", s->genus, v);
    }
  }
  if (wanted("stairs"))
    for (std::size_t steps = 1; steps <= 20; ++steps)
      add(sample_stairs(steps, seed_of(4, steps)), "stairs", 0, v);
  if (wanted("stairs"))
    for (std::size_t steps = 25; 6 * steps + 6 <= emax; steps += 6)
      add(sample_stairs(steps, seed_of(4, steps)), "stairs", 0, v);
  if (wanted("through slot")) add(sample_block_with_hole(), "through slot", 1, v);
  if (wanted("through slot")) add(sample_frame(), "through slot", 1, v);
  if (wanted("through slot"))
    for (std::size_t k = 0, kept = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(5, k)};
      const std::size_t holes = 1 + detail::below(4, rng);
      voxel_solid s = through_slot(holes, rng.next());
      kept += add(std::move(s.model), "through slot", s.genus, v);
    }
  if (wanted("quasi-normalon"))
    for (std::size_t k = 0, kept = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(6, k)};
      kept += add(random_quasi_normalon(static_cast<int>(k % 6), rng.next()), "quasi-normalon", 0, v);
    }
  if (wanted("non-convex prism"))
    for (std::size_t k = 0, kept = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(7, k)};
      try {
        if (k % 3 == 2) {
          const int kind = static_cast<int>(detail::below(3, rng));
          const double jitter = rng.uniform(0.05, 0.3);
          const std::vector<glm::dvec2> footprint = letter_footprint(kind, jitter, rng);
          kept += add(extruded_polygon(footprint, rng.uniform(0.5, 2),
                                       cellforge::detail::cat(std::string(kind == 0   ? "oblique L"
                                                                          : kind == 1 ? "oblique T"
                                                                                      : "oblique cross"),
                                                              " prism #", std::to_string(k))),
                      "non-convex prism", 0, v);
        } else {
          const std::size_t n = 5 + detail::below(std::min<std::size_t>(emax / 3, 100) - 4, rng);
          const std::vector<glm::dvec2> footprint = random_star_polygon(n, rng);
          kept += add(extruded_polygon(
                          footprint, rng.uniform(0.3, 1.5),
                          cellforge::detail::cat("star prism ", std::to_string(n), " #", std::to_string(k))),
                      "non-convex prism", 0, v);
        }
      } catch (const error&) {
        ++fam("non-convex prism").rejected;  // a footprint that is not simple
      }
    }
  if (wanted("classic"))
    for (auto& c : sketch_classics()) add(std::move(c.model), "classic", c.genus, v);
  // Several volumes, touching solids, solids of revolution.
  if (wanted("cell block")) {
    for (std::size_t k = 2; k <= 6; ++k) {  // rows of k boxes, every box a volume
      voxel_layout l = empty_layout(detail::iota_coords(k), {0, 1}, {0, 1});
      for (std::size_t i = 0; i < k; ++i) l.labels[i] = static_cast<int>(i + 1);
      add(make_voxel_model(l, cellforge::detail::cat("row of ", std::to_string(k), " boxes")), "cell block",
          0, v);
    }
    for (const auto& n :
         std::vector<std::array<std::size_t, 3>>{{2, 2, 1}, {3, 2, 1}, {2, 2, 2}, {4, 2, 1}, {3, 2, 2}})
      add(sample_grid(n[0], n[1], n[2]), "cell block", 0, v);
    std::size_t kept = 0;
    for (std::size_t k = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(8, k)};
      const std::size_t nx = 1 + detail::below(4, rng), ny = 1 + detail::below(3, rng),
                        nz = 1 + detail::below(3, rng);
      std::optional<sample_model> m;
      if (nx * ny * nz >= 2) {
        try {
          m = cell_block(nx, ny, nz, k % 2 == 1, rng.next());
        } catch (const error&) {
          m.reset();
        }
      }
      // A cell whose walls no edge needs (the middle of 3 x 3 x 1) reads as a hole: ambiguous.
      if (!m || m->unforced_faces > 0) {
        ++fam("cell block").rejected;
        continue;
      }
      kept += add(std::move(*m), "cell block", 0, v);
    }
  }
  if (wanted("sliced")) {
    std::size_t kept = 0;
    for (std::size_t k = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(9, k)};
      const std::size_t base = k % 3 == 2 ? 3 + detail::below(8, rng) : 0;
      const bool diagonal = base == 0 && k % 3 == 1;
      const std::size_t cuts = diagonal ? detail::below(3, rng) : 1 + detail::below(3, rng);
      auto m = sliced_polytope(base, cuts, diagonal, rng.next());
      if (!m) {
        ++fam("sliced").rejected;
        continue;
      }
      kept += add(std::move(*m), "sliced", 0, v);
    }
  }
  if (wanted("roof on box"))
    for (std::size_t k = 0; k < want; ++k)
      add(roof_on_box(static_cast<int>(k % 3), seed_of(10, k)), "roof on box", 0, v);
  if (wanted("bar frame"))
    for (std::size_t k = 0; k < want; ++k)  // one hole: wireframe_to_cells fills two (docs/sketch.md)
      add(bar_frame(1, seed_of(11, k)), "bar frame", 1, v);
  if (wanted("touching"))
    for (std::size_t k = 0; k < want; ++k)
      add(touching_solids(static_cast<int>(k % 7), seed_of(12, k)), "touching", 0, v);
  if (wanted("revolved"))
    for (std::size_t k = 0; k < want; ++k)
      add(revolved_solid(static_cast<int>(k % 5), seed_of(13, k)), "revolved", 0, v);

  // The drawings: the sample keeps every stride-th drawing of each family.
  std::size_t total = 0;
  for (const auto& it : items) total += static_cast<std::size_t>(it.views);
  const std::size_t stride =
      options.limit == 0 || options.limit >= total ? 1 : (total + options.limit - 1) / options.limit;
  std::vector<std::size_t> index(names.size(), 0);
  std::vector<sample_drawing> out;
  for (const auto& it : items) {
    auto& f = fam(it.family);
    const auto fi = static_cast<std::size_t>(&f - rep.families.data());
    bool counted = false;
    f.planned += static_cast<std::size_t>(it.views);
    for (int view = 0; view < it.views; ++view) {
      if (index[fi]++ % stride != 0) continue;
      // Classics: fixed views; the others follow options.seed.
      cellforge::detail::splitmix rng{
          detail::name_hash(it.model.name, it.family == "classic" ? 0 : options.seed) +
          0x9e3779b97f4a7c15u * static_cast<std::uint64_t>(view + 1)};
      bool found = false;
      const double threshold = sketch_margin_threshold(options, it.model.wire.edges.size());
      for (int attempt = 0; attempt < options.view_attempts && !found; ++attempt) {
        sample_drawing s = project_model(it.model, detail::random_rotation(rng),
                                         it.model.name + ", view " + std::to_string(view + 1), it.family);
        if (detail::margin_until(s, threshold) < threshold) continue;
        s.genus = it.genus;
        const std::size_t e = s.drawing.edges.size();
        f.min_edges = f.drawings == 0 ? e : std::min(f.min_edges, e);
        f.max_edges = std::max(f.max_edges, e);
        ++f.drawings;
        out.push_back(std::move(s));
        found = true;
      }
      if (!found) ++f.no_view;
      if (!counted) ++f.models, counted = true;
    }
  }
  rep.drawings = out.size();
  rep.ms = start.ms();
  if (report) *report = std::move(rep);
  return out;
}

}  // namespace cellforge::samples
