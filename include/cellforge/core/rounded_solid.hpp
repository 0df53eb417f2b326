// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A rounded solid as an exact boundary: planar faces and circular-cylinder blends (rounds and
/// fillets), bounded by straight edges and by the curves where a blend's cylinder meets its end
/// planes. Made by rounded_brep (sketch/rounds.hpp), written by io::write_step as a real round.

#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

namespace cellforge {

/// One closed shell of planar and cylindrical faces, every loop counter-clockwise about the
/// outward normal, every edge used by two faces in opposite senses; one outer loop per face.
struct rounded_solid {
  static constexpr std::uint32_t npos = ~std::uint32_t{0};
  /// A blend's circular cylinder: a point on its axis, the axis (unit), the radius, convex (a
  /// round: the solid inside the cylinder) or not (a fillet: outside), and the unit direction
  /// from the axis to the middle of the blend's arc (a writer puts a periodic seam opposite).
  struct cylinder {
    glm::dvec3 point{0.0}, axis{0.0, 0.0, 1.0};
    double radius = 0;
    bool convex = true;
    glm::dvec3 middle{1.0, 0.0, 0.0};
  };
  /// An edge from points[a] to points[b]: a straight segment (blend npos), or the shorter arc of
  /// the curve where cylinder `blend` meets the plane through a and b with normal plane_normal
  /// (a circle when the plane is square to the axis, else an ellipse).
  struct edge {
    std::uint32_t a = 0, b = 0;
    std::uint32_t blend = npos;
    glm::dvec3 plane_normal{0.0};
  };
  /// A face: its loop of (edge, forward: run from a to b) and its surface: a plane through the
  /// loop with the outward unit normal `normal` (blend npos), or the cylinder `blend`.
  struct face {
    std::vector<std::pair<std::uint32_t, bool>> loop;
    std::uint32_t blend = npos;
    glm::dvec3 normal{0.0};
  };
  std::vector<glm::dvec3> points;
  std::vector<cylinder> blends;
  std::vector<edge> edges;
  std::vector<face> faces;
};

}  // namespace cellforge
