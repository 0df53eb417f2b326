// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample drawings (samples/drawings.hpp): the sample_drawing type, a model drawn in a parallel
/// view (project_model), in a generic random view (generic_drawing), and how far a drawing is
/// from an accident of the view (generic_margin).

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

#include "cellforge/core/detail/splitmix.hpp"
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

/// The diagonal of the box of `pts` (0 for none). O(n).
template <class = void>
double drawing_diagonal(const std::vector<glm::dvec2>& pts) {
  if (pts.empty()) return 0;
  glm::dvec2 lo = pts[0], hi = pts[0];
  for (const auto& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return glm::length(hi - lo);
}
}  // namespace detail

/// How far a drawing is from an accident of the view, relative to its size (the bounding-box
/// diagonal): the smallest of the distances between two junctions, from a junction to an edge
/// not at it, and the smallest |cos| between a face's normal and the view direction (a face seen
/// edge-on has 0). O(V² + V·E + F·L).
template <class = void>
double generic_margin(const sample_drawing& s) {
  const auto& pts = s.drawing.points;
  const double diag = detail::drawing_diagonal(pts);
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

}  // namespace cellforge::samples
