// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// What find_thin_points returns: thin loops and the axis in the mesh's point type P, plus the
/// work counters. A header of its own so that the curve and picture writers (io/curves_io.hpp)
/// take thin results without the thin-point finder.

#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/stage_report.hpp"

namespace cellforge {

/// The part of a thin_loop that holds no points.
struct thin_loop_base {
  std::vector<std::uint32_t> vertices;  ///< closed chain, in order (mesh or cell vertex ids)
  std::vector<std::uint32_t> edges;     ///< edges[i] joins vertices[i] and vertices[i+1 mod n]
  double length = 0;                    ///< sum of the chain's edge lengths
  double total_length = 0;              ///< the cycle's least length (all its boundary chains)
  std::size_t chains = 1;               ///< boundary chains of that selection; the longest is reported
  double axis_position = 0;             ///< centroid along the axis, 0 at the start end, 1 at the other
  std::size_t cycle = 0;                ///< 1-based cycle (selection size) it occurred at
  double strength = 0;                  ///< detection strength (0..1), loops sorted strongest first
};

/// One thin loop: a closed chain of vertices and edges, with their positions in P.
template <Point3 P>
struct thin_loop : thin_loop_base {
  using point_type = P;
  std::vector<P> points;  ///< positions of vertices (the mesh's own points, converted back from double)
};

/// The part of a thin_result that holds no points. milliseconds (stage_report): the phases'
/// sum; complete false when thin_options::work_budget ran out: the growing stopped early
/// (cycle_lengths is shorter than faces − 1) and loops are only looked for in the cycles grown.
struct thin_result_base : stage_report {
  int axis_iterations = 0;
  bool axis_converged = false;
  std::uint32_t start_face = 0;       ///< mesh face (or cell face) the growing started from
  std::vector<double> cycle_lengths;  ///< least total length per cycle (index = cycle − 1)
  bool values_smoothed = false;       ///< seed detector: alternating values were smoothed
  std::uint64_t selections_examined = 0, duplicates_dropped = 0, selections_kept = 0;
  std::size_t max_kept = 0;
  double ring_cycles = 0;         ///< estimated cycles per ring of faces (edges a plane across the axis cuts)
  std::uint32_t grown_faces = 0;  ///< faces the growing ran over: mesh faces, or clusters (cluster_faces)
  std::uint32_t clustered_faces = 0;  ///< cluster_faces: mesh faces merged into fans or pairs
  double axis_ms = 0, growing_ms = 0, detection_ms = 0;  ///< the phases' wall times
};

/// Everything find_thin_points found and how much work it took; positions and the axis in P.
template <Point3 P>
struct thin_result : thin_result_base {
  using point_type = P;
  P axis_origin = point_traits<P>::make(0, 0, 0);
  P axis_direction = point_traits<P>::make(0, 0, 1);  ///< points away from the start end
  std::vector<thin_loop<P>> loops;                    ///< reported thin loops, strongest first
};

namespace detail::thin {

/// The result in the point type P: one conversion of every point at the end (none for
/// glm::dvec3). O(loop points).
template <Point3 P>
thin_result<P> result_as(thin_result<glm::dvec3>&& r) {
  if constexpr (std::is_same_v<P, glm::dvec3>) {
    return std::move(r);
  } else {
    thin_result<P> out;
    static_cast<thin_result_base&>(out) = std::move(static_cast<thin_result_base&>(r));
    out.axis_origin = from_dvec3<P>(r.axis_origin);
    out.axis_direction = from_dvec3<P>(r.axis_direction);
    out.loops.reserve(r.loops.size());
    for (thin_loop<glm::dvec3>& l : r.loops) {
      thin_loop<P>& x = out.loops.emplace_back();
      static_cast<thin_loop_base&>(x) = std::move(static_cast<thin_loop_base&>(l));
      x.points.reserve(l.points.size());
      for (const glm::dvec3& p : l.points) x.points.push_back(from_dvec3<P>(p));
    }
    return out;
  }
}

}  // namespace detail::thin

}  // namespace cellforge
