// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Tube meshes for the seed-001 benchmark tables and the tests (not in any umbrella): square
/// tubes around a lattice graph, the full node lattice ("Lattice_10_8_3"), an H-tree, and a
/// circular tube swept along a Catmull-Rom spline (the "eyespline" stand-in). Deterministic,
/// O(output size), polygon_soup in the caller's point type, error(invalid_input) for parameters
/// they cannot honour.

#include <array>
#include <cmath>
#include <cstdint>
#include <ranges>
#include <span>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/detail/shape_building.hpp"
#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"

namespace cellforge::samples {

// ------------------------------------------------------------------------------------
// Tube meshes for the seed-001 benchmark tables (lattice, tree, spline)
// ------------------------------------------------------------------------------------

/// Shape of the square tubes around a lattice graph.
struct lattice_tube_options {
  double spacing = 1.0;    ///< distance between neighbouring lattice nodes (> 0)
  double width = 0.5;      ///< side of the square tube and of the node cube, 0 < width < spacing
  bool triangles = false;  ///< split every quad into two triangles
};

/// Closed surface around a subgraph of the integer lattice Z^3: a cube per node, a square
/// tube per unit edge, unit faces kept as quads. A 2-manifold per connected component with
/// genus = the component's cycle rank. O(output) expected.
template <Point3 P = glm::dvec3>
polygon_soup<P> lattice_graph_tube_mesh(std::span<const std::array<int, 3>> nodes,
                                        std::span<const std::array<std::uint32_t, 2>> edges,
                                        const lattice_tube_options& options = {}) {
  namespace s = cellforge::detail::shapes;
  const char* what = "lattice_graph_tube_mesh";
  s::require(std::isfinite(options.spacing) && std::isfinite(options.width) && options.width > 0 &&
                 options.width < options.spacing,
             what,
             cellforge::detail::cat("need 0 < width < spacing, got width ", std::to_string(options.width),
                                    ", spacing ", std::to_string(options.spacing)));
  s::require_size(8.0 * static_cast<double>(nodes.size() + edges.size()),
                  48.0 * static_cast<double>(nodes.size() + edges.size()), what);
  // Voxels on a doubled grid: node (i,j,k) is voxel (2i,2j,2k), the edge to (i+1,j,k) is
  // voxel (2i+1,2j,2k). Occupied voxels around any voxel corner are a node plus some of
  // its arms, which are face-connected, and so are the empty ones: every edge and vertex
  // of the boundary is manifold.
  std::vector<std::array<std::int64_t, 3>> voxels;
  voxels.reserve(nodes.size() + edges.size());
  std::unordered_set<std::uint64_t> occupied;
  occupied.reserve(nodes.size() + edges.size());
  constexpr int coordinate_limit = 1 << 18;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const auto& c = nodes[n];
    s::require(std::abs(c[0]) < coordinate_limit && std::abs(c[1]) < coordinate_limit &&
                   std::abs(c[2]) < coordinate_limit,
               what, [&] {
                 return cellforge::detail::cat("node ", std::to_string(n),
                                               " lies outside the supported range |coordinate| < 2^18");
               });
    const std::array<std::int64_t, 3> v{2 * std::int64_t{c[0]}, 2 * std::int64_t{c[1]},
                                        2 * std::int64_t{c[2]}};
    s::require(occupied.insert(s::voxel_key(v[0], v[1], v[2])).second, what, [&] {
      return cellforge::detail::cat("node ", std::to_string(n), " repeats the position of an earlier node");
    });
    voxels.push_back(v);
  }
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = edges[e];
    s::require(a < nodes.size() && b < nodes.size(), what, [&] {
      return cellforge::detail::cat("edge ", std::to_string(e), " refers to a node that does not exist");
    });
    std::array<std::int64_t, 3> v{};
    int differing = 0, distance = 0;
    for (std::size_t d = 0; d < 3; ++d) {
      v[d] = std::int64_t{nodes[a][d]} + nodes[b][d];
      const int step = std::abs(nodes[a][d] - nodes[b][d]);
      differing += step != 0;
      distance += step;
    }
    s::require(differing == 1 && distance == 1, what, [&] {
      return cellforge::detail::cat("edge ", std::to_string(e),
                                    " does not join two lattice neighbours (unit, axis-aligned)");
    });
    s::require(occupied.insert(s::voxel_key(v[0], v[1], v[2])).second, what, [&] {
      return cellforge::detail::cat("edge ", std::to_string(e), " repeats an earlier edge");
    });
    voxels.push_back(v);
  }
  const double half = options.width / 2;
  const auto coordinate = [&](std::int64_t c) {
    // Corner c of the doubled grid: even corners start a node voxel, odd ones end it.
    const std::int64_t i = c >= 0 ? c / 2 : -((1 - c) / 2);
    return static_cast<double>(i) * options.spacing + ((c - 2 * i) == 0 ? -half : half);
  };
  polygon_soup<P> soup;
  std::unordered_map<std::uint64_t, std::uint32_t> corner_index;
  corner_index.reserve(4 * voxels.size());
  const auto corner = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    auto [it, fresh] =
        corner_index.try_emplace(s::voxel_key(x, y, z), static_cast<std::uint32_t>(soup.points.size()));
    if (fresh) s::add_point(soup, {coordinate(x), coordinate(y), coordinate(z)});
    return it->second;
  };
  for (const auto& v : voxels)
    for (std::size_t axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        std::array<std::int64_t, 3> n = v;
        n[axis] += side ? 1 : -1;
        if (occupied.contains(s::voxel_key(n[0], n[1], n[2]))) continue;
        // Corners in the (axis+1, axis+2) plane; that order is counter-clockwise about +axis.
        const std::size_t b = (axis + 1) % 3, c = (axis + 2) % 3;
        std::array<std::uint32_t, 4> q;
        constexpr int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
        for (int k = 0; k < 4; ++k) {
          std::array<std::int64_t, 3> p = v;
          p[axis] += side;
          p[b] += side ? du[k] : dv[k];
          p[c] += side ? dv[k] : du[k];
          q[static_cast<std::size_t>(k)] = corner(p[0], p[1], p[2]);
        }
        s::add_quad(soup, q[0], q[1], q[2], q[3], options.triangles);
      }
  return soup;
}

/// Closed tube mesh around the full nx × ny × nz node lattice (the seed's "Lattice_10_8_3"
/// is lattice_tube_mesh(10, 8, 3)); genus = E − V + 1 of the lattice graph. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> lattice_tube_mesh(int nx, int ny, int nz, const lattice_tube_options& options = {}) {
  namespace s = cellforge::detail::shapes;
  s::require_counts("lattice_tube_mesh", {{"nx", nx, 1}, {"ny", ny, 1}, {"nz", nz, 1}}, 32.0 * nx * ny * nz,
                    200.0 * nx * ny * nz);
  std::vector<std::array<int, 3>> nodes;
  std::vector<std::array<std::uint32_t, 2>> edges;
  nodes.reserve(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz));
  const auto id = [&](int i, int j, int k) { return static_cast<std::uint32_t>((k * ny + j) * nx + i); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        nodes.push_back({i, j, k});
        if (i > 0) edges.push_back({id(i - 1, j, k), id(i, j, k)});
        if (j > 0) edges.push_back({id(i, j - 1, k), id(i, j, k)});
        if (k > 0) edges.push_back({id(i, j, k - 1), id(i, j, k)});
      }
  return lattice_graph_tube_mesh<P>(nodes, edges, options);
}

/// Closed genus-0 tube mesh around a 3D H-tree of `depth` binary branchings (2^depth
/// leaves; branch axes cycle x, y, z and lengths halve every three levels, so branches
/// never meet). depth 0 is a single cube. O(output) = O(2^depth).
template <Point3 P = glm::dvec3>
polygon_soup<P> tree_tube_mesh(int depth, const lattice_tube_options& options = {}) {
  namespace s = cellforge::detail::shapes;
  s::require(depth >= 0 && depth <= 20, "tree_tube_mesh",
             cellforge::detail::cat("depth must be in 0..20, got ", std::to_string(depth)));
  const int top = depth > 0 ? (depth - 1) / 3 : 0;  // length exponent of the first level
  std::vector<std::array<int, 3>> nodes{{0, 0, 0}};
  std::vector<std::array<std::uint32_t, 2>> edges;
  std::vector<std::uint32_t> tips{0};
  for (int level = 0; level < depth; ++level) {
    const std::size_t axis = static_cast<std::size_t>(level % 3);
    const int length = 1 << (top - level / 3);
    std::vector<std::uint32_t> next;
    next.reserve(2 * tips.size());
    for (const std::uint32_t tip : tips)
      for (const int dir : {-1, 1}) {
        std::uint32_t prev = tip;
        for (int step = 1; step <= length; ++step) {
          std::array<int, 3> p = nodes[tip];
          p[axis] += dir * step;
          nodes.push_back(p);
          const auto cur = static_cast<std::uint32_t>(nodes.size() - 1);
          edges.push_back({prev, cur});
          prev = cur;
        }
        next.push_back(prev);
      }
    tips.swap(next);
  }
  return lattice_graph_tube_mesh<P>(nodes, edges, options);
}

/// Resolution and shape of a swept spline tube.
struct spline_tube_options {
  int segments_around = 8;   ///< vertices per cross-section (≥ 3)
  int samples_per_span = 8;  ///< cross-sections per Catmull–Rom span (≥ 1)
  double radius = 0.1;       ///< tube radius (> 0)
  bool capped = true;        ///< close both ends (fan about a centre vertex, or one polygon)
  bool triangles = true;     ///< triangles, or quads on the sides and polygon caps
};

/// Control points of the default curve (a gently winding 3D path, the stand-in for the
/// seed's "eyespline" input). O(1).
template <class = void>
std::vector<glm::dvec3> default_spline_curve() {
  return {{0, 0, 0}, {1, 0.6, 0.2}, {2, 0.1, 0.8}, {3, -0.5, 0.4}, {4, 0, -0.2}, {5, 0.7, 0.1}};
}

/// Tube of circular cross-section swept along the uniform Catmull–Rom spline through the
/// control points, with rotation-minimising frames (double reflection, so it does not
/// twist) and end caps; closed and outward when capped. O(output).
template <Point3 P = glm::dvec3, std::ranges::forward_range R>
requires Point3<std::ranges::range_value_t<R>> polygon_soup<P> spline_tube(
    const R& control_points, const spline_tube_options& options = {}) {
  namespace s = cellforge::detail::shapes;
  const char* what = "spline_tube";
  s::require_counts(
      what,
      {{"segments_around", options.segments_around, 3}, {"samples_per_span", options.samples_per_span, 1}}, 0,
      0);
  s::require(std::isfinite(options.radius) && options.radius > 0, what,
             cellforge::detail::cat("radius must be finite and > 0, got ", std::to_string(options.radius)));
  std::vector<glm::dvec3> cp;
  for (const auto& p : control_points) {
    const glm::dvec3 d = to_dvec3(p);
    s::require(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z), what, [&] {
      return cellforge::detail::cat("control point ", std::to_string(cp.size()), " is not finite");
    });
    s::require(cp.empty() || glm::length(d - cp.back()) > 0, what, [&] {
      return cellforge::detail::cat("control points ", std::to_string(cp.size() - 1), " and ",
                                    std::to_string(cp.size()),
                                    " coincide; the curve direction there is undefined");
    });
    cp.push_back(d);
  }
  s::require(cp.size() >= 2, what,
             cellforge::detail::cat("need at least 2 control points, got ", std::to_string(cp.size())));
  const std::size_t spans = cp.size() - 1;
  s::require_size(static_cast<double>(spans) * options.samples_per_span * options.segments_around,
                  6.0 * static_cast<double>(spans) * options.samples_per_span * options.segments_around,
                  what);
  // Sample positions and tangents; end points are mirrored so the end tangents follow the chords.
  std::vector<glm::dvec3> pos, tan;
  const auto at = [&](std::ptrdiff_t i) {
    const auto last = static_cast<std::ptrdiff_t>(cp.size()) - 1;
    if (i < 0) return 2.0 * cp[0] - cp[1];
    if (i > last) return 2.0 * cp[static_cast<std::size_t>(last)] - cp[static_cast<std::size_t>(last - 1)];
    return cp[static_cast<std::size_t>(i)];
  };
  for (std::size_t sp = 0; sp < spans; ++sp) {
    const auto i = static_cast<std::ptrdiff_t>(sp);
    for (int k = 0; k < options.samples_per_span + (sp + 1 == spans ? 1 : 0); ++k) {
      glm::dvec3 p, t;
      s::catmull_rom(at(i - 1), at(i), at(i + 1), at(i + 2),
                     static_cast<double>(k) / options.samples_per_span, p, t);
      if (!(glm::length(t) > 1e-12)) t = at(i + 1) - at(i);  // a cusp: fall back to the chord
      pos.push_back(p);
      tan.push_back(glm::normalize(t));
    }
  }
  std::vector<s::ring_frame> rings;
  rings.reserve(pos.size());
  // The soups keep the frame rule they were made with: their rings, and every figure measured on
  // them, depend on it.
  const auto perpendicular = [](const glm::dvec3& d) {
    return cellforge::detail::any_perpendicular(d, cellforge::detail::perpendicular_rule::x_below_0_9);
  };
  glm::dvec3 r = perpendicular(tan[0]);
  for (std::size_t i = 0; i < pos.size(); ++i) {
    if (i > 0) {
      // Double reflection (Wang, Jüttler, Zheng & Liu 2008): reflect the previous frame
      // across the bisector plane of the chord, then across that of the tangents.
      const glm::dvec3 v1 = pos[i] - pos[i - 1];
      const double c1 = glm::dot(v1, v1);
      if (c1 > 0) {
        const glm::dvec3 rl = r - (2.0 / c1) * glm::dot(v1, r) * v1;
        const glm::dvec3 tl = tan[i - 1] - (2.0 / c1) * glm::dot(v1, tan[i - 1]) * v1;
        const glm::dvec3 v2 = tan[i] - tl;
        const double c2 = glm::dot(v2, v2);
        r = c2 > 0 ? rl - (2.0 / c2) * glm::dot(v2, rl) * v2 : rl;
      }
      r -= glm::dot(r, tan[i]) * tan[i];  // remove rounding drift
      r = glm::length(r) > 1e-9 ? glm::normalize(r) : perpendicular(tan[i]);
    }
    rings.push_back({pos[i], r, glm::cross(tan[i], r), options.radius});
  }
  polygon_soup<P> soup;
  s::sweep_rings(soup, std::span<const s::ring_frame>(rings), options.segments_around, false, options.capped,
                 options.triangles);
  return soup;
}

/// spline_tube along default_spline_curve(). O(output).
/// The benchmark's "eyespline" stand-in.
template <Point3 P = glm::dvec3>
polygon_soup<P> spline_tube(const spline_tube_options& options = {}) {
  return spline_tube<P>(default_spline_curve(), options);
}

}  // namespace cellforge::samples
