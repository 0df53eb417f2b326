// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Branch meshes (seed 001 §V.A.1, algorithm 9): the surface around a junction.
/// One cross-section per incident edge is projected onto a sphere about the junction, the
/// convex hull of all projected points is taken, each cross-section's cap is removed, and
/// every vertex is moved back along its ray to its cross-section's true place. Because each
/// vertex only moves along its own ray from the centre, the surface stays star-shaped about
/// the centre and so embedded (docs/tubes.md, "pulling the sphere in").

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/convex_hull.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/tubes/detail/sphere_hull.hpp"
#include "cellforge/tubes/detail/tube_buffer.hpp"

namespace cellforge::detail::tubes {

/// One cross-section about a junction: the unit direction from the centre along its edge,
/// the ring's radius and distance from the centre, the unit direction of its first vertex
/// (perpendicular to `direction`), and whether it is virtual (kept as surface, no tube).
struct junction_ring {
  glm::dvec3 direction{0, 0, 1};
  double radius = 1, distance = 1;
  glm::dvec3 first{1, 0, 0};
  bool is_virtual = false;
};

/// Distances from the centre for the rings about one junction so that no two cross-sections'
/// caps overlap on the sphere: ring i's cap half-angle is at most `separation` times half the
/// smallest angle between its direction and another's, and never wider than the cap of a ring
/// at distance `centre_radius`. O(k²) for k rings.
template <class = void>
void place_rings(std::span<junction_ring> rings, double centre_radius, double separation) {
  for (std::size_t i = 0; i < rings.size(); ++i) {
    // acos falls as its argument grows: the smallest angle is that of the largest cosine.
    double largest = -1;
    for (std::size_t j = 0; j < rings.size(); ++j)
      if (j != i)
        largest = std::max(largest, std::clamp(glm::dot(rings[i].direction, rings[j].direction), -1.0, 1.0));
    const double closest = std::min(std::numbers::pi, std::acos(largest));
    const double widest = std::atan2(rings[i].radius, centre_radius);
    const double half_angle = std::min(widest, separation * closest / 2);
    rings[i].distance = rings[i].radius / std::tan(half_angle);
  }
}

/// A junction's hull kept with the points it was taken of (see junction_scratch).
struct remembered_hull {
  std::uint64_t key = 0, near_key = 0;  ///< shape_key of the points, exact and rounded; 0: empty
  std::uint32_t sides = 0;
  std::size_t rings = 0;
  std::vector<glm::dvec3> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::array<std::uint32_t, 4>> edge_checks;  ///< hull_edge_checks, once a near shape asks
  bool has_edge_checks = false;
};

/// Buffers build_junction reuses from one junction to the next (none allocates once warm),
/// and the hulls of the last junction shapes. A regular skeleton (a lattice, a scaffold)
/// repeats a few shapes thousands of times. The hull is a function of its points, so a shape
/// whose points are bit for bit a remembered one's takes its triangles; one whose points differ
/// by rounding alone (a turned lattice) takes them when they pass sphere_hull's own
/// certificate on its points: locally convex at every edge outside the caps.
struct junction_scratch {
  std::vector<glm::dvec3> on_sphere;
  std::vector<double> cosines, sines;
  sphere_hull_scratch hull;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> cap_triangles;
  std::vector<std::uint32_t> ring_of_point;    ///< per ring point of the hull, its ring
  std::array<remembered_hull, 32> remembered;  // an axis lattice has 27 junction shapes
  std::uint32_t next_remembered = 0;           ///< the slot the next new shape replaces (round robin)
  std::size_t reused = 0;                      ///< junctions whose hull was a remembered one
};

/// A hash of `points` and `sides`, never 0: of their bits (`exact`), or of the points rounded
/// to 2^-20 (shapes that differ by rounding alone share it, but for a point on a rounding
/// boundary). O(m).
template <class = void>
std::uint64_t shape_key(std::span<const glm::dvec3> points, std::uint32_t sides, bool exact) {
  // Rounded: the points are unit vectors, so the cast is defined (the guard keeps it so).
  const auto bits = [exact](double x) -> std::uint64_t {
    if (exact) return std::bit_cast<std::uint64_t>(x);
    return std::fabs(x) < 0x1p40 ? static_cast<std::uint64_t>(static_cast<std::int64_t>(x * 0x1p20)) : 0;
  };
  std::uint64_t h = 0xcbf29ce484222325ull ^ sides;
  for (const glm::dvec3& p : points)
    for (int k = 0; k < 3; ++k) h = (h ^ bits(p[k])) * 0x100000001b3ull;
  return h == 0 ? 1 : h;
}

/// Appends the junction surface of `rings` about `centre` to `out`: each ring's `sides`
/// vertices (ring i's first vertex is `first_vertex[i]`, counter-clockwise about its
/// direction), and the hull triangles that are not in a real ring's cap, tagged with
/// `source`. Throws cellforge::error naming the node (as `name()` says, when given) and
/// `ring_edges[i]` (the skeleton edge of ring i) when a cap is not intact in the
/// hull (two cross-sections overlap on the sphere). The hull is sphere_hull
/// (tubes/detail/sphere_hull.hpp), or the general one when that gives up. O(m) typical,
/// O(m²) worst, m = sides × rings.
template <class = void>
void build_junction(buffer& out, const glm::dvec3& centre, std::span<const junction_ring> rings,
                    std::uint32_t sides, tube_face_source source, std::span<const std::uint32_t> ring_edges,
                    std::vector<std::uint32_t>& first_vertex, junction_scratch& scratch,
                    std::span<const glm::dvec3> extra = {}, double extra_distance = 0,
                    const std::function<std::string()>* name = nullptr) {
  const std::size_t m = rings.size() * sides;
  std::vector<glm::dvec3>& on_sphere = scratch.on_sphere;
  on_sphere.resize(m + extra.size());
  std::vector<double>&cosines = scratch.cosines, &sines = scratch.sines;
  if (cosines.size() != sides) {
    cosines.resize(sides), sines.resize(sides);
    for (std::uint32_t j = 0; j < sides; ++j) {
      const double a = 2.0 * std::numbers::pi * j / sides;
      cosines[j] = std::cos(a), sines[j] = std::sin(a);
    }
  }
  first_vertex.clear();
  scratch.ring_of_point.resize(m);
  for (std::size_t i = 0; i < rings.size(); ++i) {
    first_vertex.push_back(static_cast<std::uint32_t>(out.points.size()));
    const junction_ring& r = rings[i];
    const glm::dvec3 axis = r.distance * r.direction, v = glm::cross(r.direction, r.first);
    for (std::uint32_t j = 0; j < sides; ++j) {
      const glm::dvec3 spoke = cosines[j] * r.first + sines[j] * v;
      // The hull sees each direction off its ring's circle by a few parts in 10^9: symmetric
      // junctions (lattices) have cocircular sets of points from different rings, which would
      // each cost the hull an exact evaluation. The offsets only choose among triangulations of
      // such sets, every one of which is valid for the true directions; the (i, j) term and the
      // per-ring step keep symmetric rings' sets apart.
      const double jitter = 1 + 1e-9 * (static_cast<double>((7 * i + 3 * j) % 11) / (11.0 * sides) +
                                        0.5 * static_cast<double>((5 * i) % 13) - 7);
      on_sphere[i * sides + j] = glm::normalize(axis + (r.radius * jitter) * spoke);
      // Back along its ray to the ring's own place ("pulling the sphere in").
      out.add_point(centre + axis + r.radius * spoke);
      scratch.ring_of_point[i * sides + j] = static_cast<std::uint32_t>(i);
    }
  }
  // §V.D method 3: extra points on the sphere (the caller keeps them clear of every cap), at
  // `extra_distance` along their rays: a rounder junction.
  const auto extra_first = static_cast<std::uint32_t>(out.points.size());
  for (std::size_t k = 0; k < extra.size(); ++k) {
    on_sphere[m + k] = extra[k];
    out.add_point(centre + extra_distance * extra[k]);
  }
  const auto where = [&] {
    return name != nullptr ? (*name)() : cellforge::detail::cat("node ", std::to_string(source.index));
  };
  // A remembered shape: the same points, or the same but for rounding (then certified).
  const auto same_kind = [&](const remembered_hull& h) {
    return h.sides == sides && h.rings == rings.size() && h.points.size() == on_sphere.size();
  };
  const std::uint64_t key = shape_key(detail::span_of(on_sphere), sides, true);
  remembered_hull *known = nullptr, *near = nullptr;
  for (remembered_hull& h : scratch.remembered)
    if (same_kind(h) && h.key == key && h.points == on_sphere) {
      known = &h;
      break;
    }
  // The rounded key only when no shape matched exactly (a lattice's junctions nearly all do).
  std::uint64_t near_key = 0;
  if (known == nullptr) {
    near_key = shape_key(detail::span_of(on_sphere), sides, false);
    for (remembered_hull& h : scratch.remembered)
      if (same_kind(h) && h.near_key == near_key) {
        near = &h;
        break;
      }
  }
  if (known == nullptr && near != nullptr) {
    if (!near->has_edge_checks)
      near->has_edge_checks =
          hull_edge_checks(detail::span_of(near->triangles), sides, rings.size(), near->edge_checks);
    if (near->has_edge_checks &&
        hull_locally_convex(detail::span_of(on_sphere), detail::span_of(near->edge_checks)))
      known = near;
  }
  std::vector<std::array<std::uint32_t, 3>>& triangles = scratch.triangles;
  if (known != nullptr) {
    ++scratch.reused;
  } else if (!sphere_hull(detail::span_of(on_sphere), scratch.hull, triangles, sides, rings.size())) {
    convex_hull_options o;
    o.merge_coplanar = false;
    o.method = convex_hull_method::incremental;
    const hull::result h = hull::compute(detail::span_of(on_sphere), o);
    if (h.dimension != 3 || h.vertices.size() != on_sphere.size())
      throw error(error_category::invalid_input,
                  where() + ": the cross-sections of its " + std::to_string(rings.size()) +
                      " edges do not all lie on their junction's hull (edges too close in angle)");
    triangles.clear();
    for (std::size_t f = 0; f + 1 < h.face_offsets.size(); ++f) {
      std::array<std::uint32_t, 3> t{};
      for (std::size_t k = 0; k < 3; ++k) t[k] = h.vertices[h.face_vertices[h.face_offsets[f] + k]];
      triangles.push_back(t);
    }
  }
  if (known == nullptr) {
    remembered_hull& slot = scratch.remembered[scratch.next_remembered];
    scratch.next_remembered = (scratch.next_remembered + 1) % scratch.remembered.size();
    slot.key = key, slot.near_key = near_key, slot.sides = sides, slot.rings = rings.size();
    slot.points.assign(on_sphere.begin(), on_sphere.end());
    slot.triangles.assign(triangles.begin(), triangles.end());
    slot.has_edge_checks = false;
    known = &slot;
  }
  std::vector<std::uint32_t>& cap_triangles = scratch.cap_triangles;
  cap_triangles.assign(rings.size(), 0);
  for (const std::array<std::uint32_t, 3>& t : known->triangles) {
    std::uint32_t tri[3];
    std::size_t ring_of[3];
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t input = t[k];
      if (input >= m) {  // an extra point: in no ring
        ring_of[k] = rings.size() + k;
        tri[k] = extra_first + (input - static_cast<std::uint32_t>(m));
        continue;
      }
      // From a table, not input / sides: a division per corner costs more than the rest.
      ring_of[k] = scratch.ring_of_point[input];
      tri[k] = first_vertex[0] + input;  // the rings' vertices are consecutive from the first
    }
    if (ring_of[0] == ring_of[1] && ring_of[1] == ring_of[2] && ring_of[0] < rings.size() &&
        !rings[ring_of[0]].is_virtual) {
      ++cap_triangles[ring_of[0]];
      continue;
    }
    out.add_face(tri, source);
  }
  // A ring's cap is intact exactly when sides - 2 hull triangles span its vertices alone.
  for (std::size_t i = 0; i < rings.size(); ++i)
    if (!rings[i].is_virtual && cap_triangles[i] != sides - 2)
      throw error(error_category::invalid_input,
                  where() + ": the cross-section of its edge " + std::to_string(ring_edges[i]) +
                      " is cut by another's on the junction's hull (edges too close in angle)");
}

}  // namespace cellforge::detail::tubes
