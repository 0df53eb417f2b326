// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Solids of revolution with a known answer for the thin-point finder: dumbbells,
/// hourglasses, cylinders, spheres (quad and triangle versions), and the six solids of
/// the seed's table 5 (seed 000 §7.3) at about the seed's face counts.

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"

namespace cellforge::samples {

/// A test solid about the z axis and its ground truth.
template <Point3 P = glm::dvec3>
struct thin_sample {
  polygon_soup<P> soup;
  std::string name;
  std::vector<glm::dvec2> profile;  ///< (radius, z) per ring, bottom to top
  int segments = 0;
  bool triangles = false;
  int neck_ring = -1;         ///< profile index of the thinnest interior ring; −1: none
  std::vector<int> necks;     ///< every neck ring (local radius minima), thinnest first
  double neck_z = 0;          ///< z of neck_ring
  double neck_perimeter = 0;  ///< perimeter of the neck ring's polygon
  double ring_spacing = 0;    ///< largest z distance between neighbouring rings
};

namespace detail::thin {

/// Builds the sample from rings z_k = z0 + k·(z1−z0)/(rings−1) with radius r(z); the necks
/// are the interior rings whose radius is below both neighbours'. O(output).
template <Point3 P>
thin_sample<P> revolve(std::string name, int segments, int rings, bool triangles, double z0, double z1,
                       const std::function<double(double)>& radius) {
  if (rings < 3)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("thin sample '", name, "': rings must be at least 3, got ",
                                       std::to_string(rings)));
  // The profile is allocated before solid_of_revolution checks the mesh's size: check it here.
  cellforge::detail::shapes::require_counts("thin sample", {{"segments", segments, 3}},
                                            double(segments) * rings, 4.0 * segments * rings);
  thin_sample<P> s;
  s.name = std::move(name), s.segments = segments, s.triangles = triangles;
  for (int k = 0; k < rings; ++k) {
    const double z = z0 + (z1 - z0) * k / (rings - 1);
    s.profile.push_back({radius(z), z});
  }
  s.soup = solid_of_revolution<P>(s.profile, segments, triangles);
  s.ring_spacing = (z1 - z0) / (rings - 1);
  for (int k = 1; k + 1 < rings; ++k)
    if (s.profile[k].x < s.profile[k - 1].x && s.profile[k].x <= s.profile[k + 1].x) s.necks.push_back(k);
  std::stable_sort(s.necks.begin(), s.necks.end(),
                   [&](int a, int b) { return s.profile[a].x < s.profile[b].x; });
  if (!s.necks.empty()) {
    s.neck_ring = s.necks.front();
    s.neck_z = s.profile[s.neck_ring].y;
    s.neck_perimeter = 2.0 * segments * s.profile[s.neck_ring].x * std::sin(std::numbers::pi / segments);
  }
  return s;
}

/// Bulbs of radius 1 joined by necks of radius `neck`: `bulbs` bulbs over z ∈ [−bulbs, bulbs].
template <class = void>
double chain_radius(double z, int bulbs, double neck) {
  const double u = (z + bulbs) / 2.0;                 // 0 .. bulbs, one bulb per unit
  const double x = u - std::floor(u);                 // position inside the bulb
  const bool end = u < 0.5 ? true : u > bulbs - 0.5;  // the outer halves of the end bulbs
  if (end) {
    // A rounded end: radius 1 at the bulb centre down to 0.3 at the tip.
    const double d = std::min(u < 0.5 ? 0.5 - u : u - (bulbs - 0.5), 0.5) / 0.5;
    return 0.3 + 0.7 * std::sqrt(std::max(0.0, 1.0 - d * d));
  }
  return neck + (1.0 - neck) * std::sin(std::numbers::pi * x);
}

}  // namespace detail::thin

/// Dumbbell along z ∈ [−2, 2]: two bulbs of radius 1, a neck of radius `neck` at z = 0,
/// ends of radius 0.3 closed by caps. `rings` odd puts a ring on the neck. O(output).
template <Point3 P = glm::dvec3>
thin_sample<P> thin_dumbbell(int segments, int rings, bool triangles, double neck = 0.35) {
  return detail::thin::revolve<P>("dumbbell", segments, rings, triangles, -2, 2,
                                  [&](double z) { return detail::thin::chain_radius(z, 2, neck); });
}

/// A chain of `bulbs` bulbs (2 = the dumbbell) along z ∈ [−bulbs, bulbs]. O(output).
template <Point3 P = glm::dvec3>
thin_sample<P> thin_chain(int bulbs, int segments, int rings, bool triangles, double neck = 0.35) {
  return detail::thin::revolve<P>(std::to_string(bulbs) + "-bulb chain", segments, rings, triangles, -bulbs,
                                  bulbs,
                                  [&](double z) { return detail::thin::chain_radius(z, bulbs, neck); });
}

/// Hourglass along z ∈ [−2, 2]: radius neck + (1 − neck)·(z/2)², the waist at z = 0 (twice
/// as long as wide, so that its central axis is well defined). O(output).
template <Point3 P = glm::dvec3>
thin_sample<P> thin_hourglass(int segments, int rings, bool triangles, double neck = 0.3) {
  return detail::thin::revolve<P>("hourglass", segments, rings, triangles, -2, 2,
                                  [&](double z) { return neck + (1.0 - neck) * z * z / 4; });
}

/// Plain capped cylinder of radius 0.5 along z ∈ [−1.5, 1.5]: no neck. O(output).
template <Point3 P = glm::dvec3>
thin_sample<P> thin_cylinder(int segments, int rings, bool triangles) {
  return detail::thin::revolve<P>("cylinder", segments, rings, triangles, -1.5, 1.5,
                                  [](double) { return 0.5; });
}

/// Unit sphere with `rings` latitude rings between the poles (pole fans). No neck. O(output).
template <Point3 P = glm::dvec3>
thin_sample<P> thin_sphere(int segments, int rings, bool triangles) {
  thin_sample<P> s;
  s.name = "sphere", s.segments = segments, s.triangles = triangles;
  for (int k = 0; k <= rings + 1; ++k) {
    const double theta = std::numbers::pi * (1.0 - static_cast<double>(k) / (rings + 1));
    s.profile.push_back({k == 0 || k == rings + 1 ? 0.0 : std::sin(theta), std::cos(theta)});
  }
  s.soup = solid_of_revolution<P>(s.profile, segments, triangles);
  s.ring_spacing = std::sin(std::numbers::pi / (rings + 1));
  return s;
}

/// Bottle along z ∈ [−1, 1.2]: a body of radius 1, shoulders, a neck of radius 0.3 near
/// z = 0.85 and a lip widening to 0.42. O(output).
template <Point3 P = glm::dvec3>
thin_sample<P> thin_bottle(int segments, int rings, bool triangles) {
  return detail::thin::revolve<P>("bottle", segments, rings, triangles, -1, 1.2, [](double z) {
    if (z < 0.2) return 1.0;
    if (z < 0.85) return 0.3 + 0.7 * 0.5 * (1 + std::cos(std::numbers::pi * (z - 0.2) / 0.65));
    return 0.3 + 0.12 * (z - 0.85) / 0.35 * (z - 0.85) / 0.35;
  });
}

/// Vase along z ∈ [−1, 1]: foot 0.6, belly 1 at z = −0.3, waist 0.45 at z = 0.5, mouth 0.8.
template <Point3 P = glm::dvec3>
thin_sample<P> thin_vase(int segments, int rings, bool triangles) {
  return detail::thin::revolve<P>("vase", segments, rings, triangles, -1, 1, [](double z) {
    const double pi = std::numbers::pi;
    if (z < -0.3) return 0.6 + 0.4 * std::sin(0.5 * pi * (z + 1) / 0.7);
    if (z < 0.5) return 0.45 + 0.55 * 0.5 * (1 + std::cos(pi * (z + 0.3) / 0.8));
    return 0.45 + 0.35 * std::sin(0.5 * pi * (z - 0.5) / 0.5);
  });
}

/// The six solids of the seed's table 5 (§7.3), example 1..6: dumbbell, hourglass, two-neck
/// chain, bottle, vase, three-neck chain; quads 242/242/470/482/242/722 faces (12 around),
/// triangles 216/216/456/456/216/696. O(output).
template <Point3 P = glm::dvec3>
thin_sample<P> thin_table5_solid(int example, bool triangles) {
  const int seg = 12;
  // Quads: 12·(rings−1) + 2 caps; triangles: 2·12·rings (bands and two cap fans).
  const auto rings = [&](int quad_rings, int tri_rings) { return triangles ? tri_rings : quad_rings; };
  switch (example) {
    case 1:
      return thin_dumbbell<P>(seg, rings(21, 9), triangles);
    case 2:
      return thin_hourglass<P>(seg, rings(21, 9), triangles);
    case 3:
      return thin_chain<P>(3, seg, rings(40, 19), triangles);  // necks on rings
    case 4:
      return thin_bottle<P>(seg, rings(41, 19), triangles);
    case 5:
      return thin_vase<P>(seg, rings(21, 9), triangles);
    case 6:
      return thin_chain<P>(4, seg, rings(61, 29), triangles);
    default:
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("thin_table5_solid: example ", std::to_string(example),
                                         " does not exist; allowed 1 to 6"));
  }
}

}  // namespace cellforge::samples
