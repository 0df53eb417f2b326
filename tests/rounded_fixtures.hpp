// SPDX-License-Identifier: MIT
#pragma once
// A hand-made rounded solid (core/rounded_solid.hpp) with a volume known in closed form, for the
// STEP writer's tests (tests/test_io_step.cpp, and OpenCASCADE's reading in tests/occt).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/rounded_solid.hpp"

namespace rounded_fixtures {

/// A 2 × 1 × 1 box whose edge along x at y = z = 1 is rounded with radius r (a fillet's flag
/// when not convex; the solid is then not a valid one): six planes and a cylinder, 13 lines and
/// two end arcs, loops counter-clockwise about the outward normals. With `tilt` (radians) its
/// end at x = 2 turns about the line x = 2, z = 1/2 (x = 2 + (z − 1/2) tan tilt), so that end's
/// arc is an ellipse. O(1).
inline cellforge::rounded_solid rounded_box(double r, bool convex = true, double tilt = 0) {
  cellforge::rounded_solid s;
  s.points = {{0, 0, 0}, {2, 0, 0},     {2, 1, 0},     {0, 1, 0},     {0, 0, 1},
              {2, 0, 1}, {2, 1 - r, 1}, {0, 1 - r, 1}, {2, 1, 1 - r}, {0, 1, 1 - r}};
  s.blends.push_back({{0, 1 - r, 1 - r}, {1, 0, 0}, r, convex, glm::normalize(glm::dvec3(0, 1, 1))});
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> known;
  const auto use = [&](std::uint32_t a, std::uint32_t b, bool arc) -> std::pair<std::uint32_t, bool> {
    const auto key = std::minmax(a, b);
    auto [it, fresh] = known.try_emplace({key.first, key.second}, static_cast<std::uint32_t>(s.edges.size()));
    if (fresh)
      s.edges.push_back(
          {a, b, arc ? 0u : cellforge::rounded_solid::npos, arc ? glm::dvec3(1, 0, 0) : glm::dvec3(0.0)});
    return {it->second, s.edges[it->second].a == a};
  };
  // Each face: its corners, the arcs (from corner k to k + 1), its normal or its blend.
  const auto face = [&](std::vector<std::uint32_t> loop, std::vector<std::size_t> arcs, glm::dvec3 n,
                        std::uint32_t blend = cellforge::rounded_solid::npos) {
    cellforge::rounded_solid::face f;
    for (std::size_t k = 0; k < loop.size(); ++k)
      f.loop.push_back(
          use(loop[k], loop[(k + 1) % loop.size()], std::find(arcs.begin(), arcs.end(), k) != arcs.end()));
    f.normal = n;
    f.blend = blend;
    s.faces.push_back(std::move(f));
  };
  face({0, 3, 2, 1}, {}, {0, 0, -1});
  face({0, 1, 5, 4}, {}, {0, -1, 0});
  face({4, 5, 6, 7}, {}, {0, 0, 1});
  face({3, 9, 8, 2}, {}, {0, 1, 0});
  face({7, 6, 8, 9}, {1, 3}, {}, 0);
  face({1, 2, 8, 6, 5}, {2}, {1, 0, 0});
  face({0, 4, 7, 9, 3}, {2}, {-1, 0, 0});
  if (tilt != 0) {
    for (const std::uint32_t p : {1u, 2u, 5u, 6u, 8u})
      s.points[p].x = 2 + (s.points[p].z - 0.5) * std::tan(tilt);
    const glm::dvec3 n(std::cos(tilt), 0, -std::sin(tilt));
    s.faces[5].normal = n;
    for (auto& e : s.edges)
      if (e.blend == 0 && s.points[e.a].x > 1) e.plane_normal = n;
  }
  return s;
}

/// Its volume: the box's less the round's cross-section r²(1 − π/4), whose centroid is
/// 2r / (3(4 − π)) from the axis along y and z, times its length (2 + (z − 1/2) tan tilt at the
/// centroid). O(1).
inline double rounded_box_volume(double r, double tilt = 0) {
  const double a = r * r * (1 - std::numbers::pi / 4), zc = 1 - r + 2 * r / (3 * (4 - std::numbers::pi));
  return 2 * (1 - a) - std::tan(tilt) * a * (zc - 0.5);
}

}  // namespace rounded_fixtures
