// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Node paths (seed 001 §V.A.2, algorithm 8): the tube between consecutive
/// cross-sections along a path, with twist reduction (§V.C). Frames are carried along the path
/// by rotation-minimising transport (double reflection), and the mismatch left where the path
/// meets a junction's ring, or closes on itself, is spread evenly along its length (the
/// global alignment the seed left undone); the seed's local alignment is an option.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/tubes/branch_mesh.hpp"
#include "cellforge/tubes/detail/tube_buffer.hpp"

namespace cellforge {

/// How the cross-sections along a path are turned about the path (§V.C).
enum class tube_alignment : std::uint8_t {
  none,    ///< each cross-section on its own frame (shows the twist the seed's figure 9 has)
  local,   ///< the seed's local alignment: each frame as close as possible to the previous one
  global,  ///< rotation-minimising frames, the closing mismatch spread evenly along the path
};

namespace detail::tubes {

/// One cross-section along a path: its centre, the unit direction of travel, the radius, and
/// for a bend the unit direction in the bend's plane along which it is widened by `widen`
/// (a mitre: the tube keeps its width through the bend). A station on a junction's ring is
/// `fixed`: its vertices exist from `first_vertex` on, in the ring's order (counter-clockwise
/// about the ring's direction, which points against travel when `reversed`).
struct station {
  glm::dvec3 centre{0.0}, tangent{0, 0, 1};
  double radius = 1;
  glm::dvec3 bend{0.0};
  double widen = 1;
  bool fixed = false, reversed = false;
  std::uint32_t first_vertex = 0;
  glm::dvec3 fixed_first{1, 0, 0};  ///< direction of a fixed ring's vertex 0 from its centre
};

/// The vertex of a fixed station at path position m (counter-clockwise about travel). O(1).
template <class = void>
std::uint32_t fixed_vertex(const station& s, std::uint32_t m, std::uint32_t sides) {
  return s.first_vertex + (s.reversed ? (sides - m % sides) % sides : m % sides);
}

/// Rotation-minimising transport of frame vector u from station a to station b (Wang et al.,
/// double reflection). O(1).
template <class = void>
glm::dvec3 transport(const glm::dvec3& u, const station& a, const station& b) {
  const glm::dvec3 v1 = b.centre - a.centre;
  const double c1 = glm::dot(v1, v1);
  if (!(c1 > 0)) return u;
  const glm::dvec3 rl = u - (2 / c1) * glm::dot(v1, u) * v1;
  const glm::dvec3 tl = a.tangent - (2 / c1) * glm::dot(v1, a.tangent) * v1;
  const glm::dvec3 v2 = b.tangent - tl;
  const double c2 = glm::dot(v2, v2);
  const glm::dvec3 r = c2 > 0 ? rl - (2 / c2) * glm::dot(v2, rl) * v2 : rl;
  // Re-orthogonalised against b's tangent: rounding must not accumulate over long paths.
  return glm::normalize(r - glm::dot(r, b.tangent) * b.tangent);
}

/// u projected into the plane of unit normal t (the seed's local alignment), or any
/// perpendicular when u is along t. O(1).
template <class = void>
glm::dvec3 project_frame(const glm::dvec3& u, const glm::dvec3& t) {
  const glm::dvec3 p = u - glm::dot(u, t) * t;
  const double l = glm::length(p);
  return l > 1e-12 ? p / l : any_perpendicular(t);
}

/// Buffers build_path reuses from one path to the next (none allocates once warm).
struct path_scratch {
  std::vector<glm::dvec3> frame;
  std::vector<double> arc, cosines, sines;
  std::vector<std::uint32_t> first, cap;
};

/// Appends the tube through `stations` to `out`: new rings for the stations that are not
/// fixed, quads between consecutive ones (outward), flat caps at free ends when `cap_start` /
/// `cap_end`, faces tagged with `segment_edge[i]` for the tube from station i to i + 1 (and
/// `start_node` / `end_node` for caps). `closed` joins the last station back to the first.
/// `reuse` (optional) keeps the working arrays across calls. O(stations × sides).
template <class = void>
void build_path(buffer& out, std::span<const station> stations, bool closed, std::uint32_t sides,
                tube_alignment alignment, std::span<const std::uint32_t> segment_edge, bool cap_start,
                std::uint32_t start_node, bool cap_end, std::uint32_t end_node,
                path_scratch* reuse = nullptr) {
  const std::size_t n = stations.size();
  path_scratch own;
  path_scratch& scratch = reuse != nullptr ? *reuse : own;
  // Frames: the direction of each station's vertex 0 before the spread correction.
  std::vector<glm::dvec3>& frame = scratch.frame;
  frame.resize(n);
  frame[0] = stations[0].fixed ? stations[0].fixed_first : any_perpendicular(stations[0].tangent);
  for (std::size_t i = 1; i < n; ++i)
    frame[i] = alignment == tube_alignment::global  ? transport(frame[i - 1], stations[i - 1], stations[i])
               : alignment == tube_alignment::local ? project_frame(frame[i - 1], stations[i].tangent)
                                                    : any_perpendicular(stations[i].tangent);
  // Arc length, for spreading the closing correction.
  std::vector<double>& arc = scratch.arc;
  arc.assign(n + 1, 0.0);
  for (std::size_t i = 1; i < n; ++i)
    arc[i] = arc[i - 1] + glm::length(stations[i].centre - stations[i - 1].centre);
  arc[n] = arc[n - 1] + (closed ? glm::length(stations[0].centre - stations[n - 1].centre) : 0.0);
  // Where the path ends on a ring it does not choose (a junction's, or its own start when
  // closed): the angle from the carried frame to that ring's vertex 0, and the vertex offset
  // k that leaves the smallest rotation to spread.
  const double step = 2 * std::numbers::pi / sides;
  double spread = 0;
  std::int64_t offset = 0;
  const bool ends_fixed = !closed && stations[n - 1].fixed;
  if (closed || ends_fixed) {
    glm::dvec3 carried, target, axis;
    if (closed) {
      carried = alignment == tube_alignment::global ? transport(frame[n - 1], stations[n - 1], stations[0])
                                                    : project_frame(frame[n - 1], stations[0].tangent);
      target = frame[0];
      axis = stations[0].tangent;
    } else {
      carried = frame[n - 1];
      target = stations[n - 1].fixed_first;
      axis = stations[n - 1].tangent;
    }
    const double phi = angle_about(carried, target, axis);
    offset = -static_cast<std::int64_t>(std::llround(phi / step));
    spread = alignment == tube_alignment::none ? 0.0 : phi + offset * step;
  }
  const double total = closed ? arc[n] : arc[n - 1];
  // The ring's directions at turn 0, once per side count: a ring turned by t is the frame
  // turned by t (one sincos per ring instead of one per vertex).
  std::vector<double>&cosines = scratch.cosines, &sines = scratch.sines;
  if (cosines.size() != sides) {
    cosines.resize(sides), sines.resize(sides);
    for (std::uint32_t j = 0; j < sides; ++j) cosines[j] = std::cos(j * step), sines[j] = std::sin(j * step);
  }
  // Vertex ids of each station in path order (counter-clockwise about travel).
  std::vector<std::uint32_t>& first = scratch.first;
  first.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const station& s = stations[i];
    if (s.fixed) {
      first[i] = s.first_vertex;
      continue;
    }
    const double turn = total > 0 ? spread * arc[i] / total : 0.0;
    const double ct = std::cos(turn), st = std::sin(turn);
    const glm::dvec3 u0 = frame[i], v0 = glm::cross(s.tangent, u0);
    const glm::dvec3 u = ct * u0 + st * v0, v = ct * v0 - st * u0;
    first[i] = static_cast<std::uint32_t>(out.points.size());
    glm::dvec3 area(0.0);  // twice the vector area of the ring (Newell)
    for (std::uint32_t j = 0; j < sides; ++j) {
      glm::dvec3 e = cosines[j] * u + sines[j] * v;
      e += (s.widen - 1) * glm::dot(e, s.bend) * s.bend;
      out.add_point(s.centre + s.radius * e);
      if (j > 0)
        area += glm::cross(out.points[out.points.size() - 2] - s.centre, out.points.back() - s.centre);
    }
    area += glm::cross(out.points.back() - s.centre, out.points[first[i]] - s.centre);
    // The cross-section the tube has across its axis: the ring's area seen along the tangent.
    const double ratio = 0.5 * std::abs(glm::dot(area, s.tangent)) / (std::numbers::pi * s.radius * s.radius);
    // Station i ends segment i - 1 and starts segment i (around the ring when closed).
    const auto note = [&](std::size_t segment) {
      const std::uint32_t e = segment_edge[segment];
      if (e < out.section_ratio.size()) out.section_ratio[e] = std::min(out.section_ratio[e], ratio);
    };
    if (i > 0 || closed) note(i > 0 ? i - 1 : n - 1);
    if (i + 1 < n || closed) note(i);
  }
  // Path position m of station i: fixed rings through their own order, the last one (or the
  // first, for a closed path) shifted by the chosen offset.
  // (No division per vertex: m < sides, and the shift is reduced to [0, sides) once.)
  const auto offset_mod = static_cast<std::uint32_t>((offset % sides + sides) % sides);
  const auto vertex = [&](std::size_t i, std::uint32_t m, bool wrapped) -> std::uint32_t {
    const station& s = stations[i];
    std::uint32_t mm = m + ((wrapped || (ends_fixed && i == n - 1)) ? offset_mod : 0);
    if (mm >= sides) mm -= sides;
    if (!s.fixed) return first[i] + mm;
    return s.first_vertex + (s.reversed && mm != 0 ? sides - mm : mm);  // as fixed_vertex
  };
  const std::size_t segments = closed ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i) {
    const std::size_t b = (i + 1) % n;
    const bool wrapped = closed && b == 0;
    for (std::uint32_t j = 0; j < sides; ++j) {
      const std::uint32_t jn = j + 1 == sides ? 0 : j + 1;
      const std::uint32_t quad[4] = {vertex(i, j, false), vertex(i, jn, false), vertex(b, jn, wrapped),
                                     vertex(b, j, wrapped)};
      out.add_face(quad, {tube_face_kind::extrusion, segment_edge[i]});
    }
  }
  std::vector<std::uint32_t>& cap = scratch.cap;
  cap.resize(sides);
  if (cap_start && !closed) {  // facing back along the path
    for (std::uint32_t j = 0; j < sides; ++j) cap[j] = vertex(0, sides - 1 - j, false);
    out.add_face(detail::span_of(cap), {tube_face_kind::end_cap, start_node});
  }
  if (cap_end && !closed) {
    for (std::uint32_t j = 0; j < sides; ++j) cap[j] = vertex(n - 1, j, false);
    out.add_face(detail::span_of(cap), {tube_face_kind::end_cap, end_node});
  }
}

}  // namespace detail::tubes
}  // namespace cellforge
