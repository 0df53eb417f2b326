// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The four solids of seed 000 Table 7 (§7.4), rebuilt with the edge counts the seed reports
/// (120, 468, 336, ≈944 edges); the seed does not say what they were, so these are stand-ins
/// chosen to cover creases (a prism), quads on a sphere, a torus and a triangulated sphere.

#include <string>
#include <vector>

#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge::samples {

/// One Table 7 stand-in: a name, what it is, its soup, and the seed's edge count and time.
template <Point3 P = glm::dvec3>
struct smooth_sample_solid {
  std::string name, description;
  polygon_soup<P> soup;
  std::size_t seed_edges = 0;  ///< edges of the seed's solid (Table 7)
  double seed_ms = 0;          ///< the seed's time on a 996 MHz Pentium (Table 7)
};

/// The four Table 7 stand-ins, in the table's order. O(total size) ≈ 2,000 edges.
template <Point3 P = glm::dvec3>
std::vector<smooth_sample_solid<P>> table7_solids() {
  std::vector<smooth_sample_solid<P>> out;
  out.push_back({"prism40", "40-gon prism (cylinder, one band, polygon caps): 120 edges, creases at the rims",
                 cylinder<P>(40, 1, true, false), 120, 24515});
  out.push_back({"uv_sphere_36x7", "unit quad UV sphere, 36 slices x 7 stacks: 468 edges",
                 uv_sphere<P>(36, 7, false), 468, 100234});
  out.push_back({"torus_12x14", "quad torus R = 1, r = 0.3, 12 x 14 segments: 336 edges",
                 torus<P>(12, 14, 1.0, 0.3, false), 336, 40298});
  out.push_back({"sphere_317", "triangulated unit sphere with 317 vertices: 945 edges",
                 sphere_with_vertices<P>(317), 944, 186558});
  return out;
}

/// A Table 7 stand-in ready to smooth: the figure's name, description, mesh (points of type P)
/// and the seed's edge count and ms.
template <Point3 P = glm::dvec3>
struct smooth_table7_case {
  std::string name, description;
  surface_mesh<P> mesh;
  std::size_t seed_edges = 0;
  double seed_ms = 0;
};

/// Test figure 1..4 of Table 7 as a mesh (see table7_solids()). O(size). Throws
/// error(invalid_input) for another figure number.
template <Point3 P = glm::dvec3>
smooth_table7_case<P> smooth_table7_solid(int figure) {
  if (figure < 1 || figure > 4)
    throw error(
        error_category::invalid_input,
        cellforge::detail::cat("smooth_table7_solid: figure = ", std::to_string(figure), ", must be 1..4"));
  auto s = table7_solids<P>()[static_cast<std::size_t>(figure - 1)];
  return {s.name, s.description, make_mesh(s.soup), s.seed_edges, s.seed_ms};
}

}  // namespace cellforge::samples
