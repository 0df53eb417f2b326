// SPDX-License-Identifier: MIT
#pragma once
// The tube mesher's output under construction: double positions, polygon faces (linked into
// half-edges as they come) and where each face came from; and the small vector helpers its
// stages share.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/tubes/detail/closed_build.hpp"

namespace cellforge {

/// What part of the skeleton a face of a tube mesh was made for.
enum class tube_face_kind : std::uint8_t {
  extrusion,  ///< the tube along a skeleton edge (index: the edge)
  junction,   ///< the surface around a branch or a sharp bend (index: the node)
  end_cap,    ///< the disc closing a free end (index: the node)
  sphere,     ///< the sphere of an isolated node (index: the node)
};

/// The skeleton element a face of a tube mesh came from (the face property "f:tube_source").
struct tube_face_source {
  tube_face_kind kind = tube_face_kind::extrusion;
  std::uint32_t index = 0xFFFFFFFFu;
  friend bool operator==(const tube_face_source&, const tube_face_source&) = default;
};

namespace detail::tubes {

template <class = void>
struct basic_buffer {
  std::vector<glm::dvec3> points;
  /// Faces of more than three corners go in as fans (for Loop subdivision); corner angles are
  /// still those of the faces as given.
  bool triangulate = false;
  /// Every face, linked as it comes (linker.faces() gives them back as a face list).
  closed_linker linker;
  std::vector<tube_face_source> sources;
  /// Per skeleton edge: the smallest area of a cross-section along it over π r² (its node's r).
  std::vector<double> section_ratio;

  std::uint32_t add_point(const glm::dvec3& p) {
    points.push_back(p);
    return static_cast<std::uint32_t>(points.size() - 1);
  }
  /// The largest and smallest cosine of any face's corner angle so far (the smallest and
  /// largest corner), taken as each face is added, while its points are in cache.
  double cos_lo = 1, cos_hi = -1;

  void add_face(std::span<const std::uint32_t> vs, tube_face_source s) {
    const auto k = static_cast<std::uint32_t>(vs.size());
    // The corner at c lies between u = p[c - 1] - p[c], minus the edge before it (exactly),
    // and w = p[c + 1] - p[c], the edge after it: each edge vector is formed and squared once.
    glm::dvec3 before = points[vs[0]] - points[vs[k - 1]];
    double before2 = glm::dot(before, before);
    for (std::uint32_t c = 0; c < k; ++c) {
      const glm::dvec3 after = points[vs[c + 1 == k ? 0 : c + 1]] - points[vs[c]];
      const double after2 = glm::dot(after, after);
      const double uw = -glm::dot(before, after), uu = before2, ww = after2;
      before = after, before2 = after2;
      // A cosine certainly inside (cos_lo, cos_hi) changes neither: most corners skip the
      // root and the division (the margin covers their rounding).
      const double inside = std::min(cos_hi, -cos_lo);
      if (inside > 0 && uw * uw < inside * inside * (uu * ww) * (1 - 1e-9)) continue;
      const double cosine = uw / std::sqrt(uu * ww);
      cos_lo = std::min(cos_lo, cosine), cos_hi = std::max(cos_hi, cosine);
    }
    if (!triangulate || k == 3) return emit(vs, s);
    for (std::uint32_t c = 1; c + 1 < k; ++c) {
      const std::uint32_t tri[3] = {vs[0], vs[c], vs[c + 1]};
      emit(tri, s);
    }
  }
  void emit(std::span<const std::uint32_t> vs, tube_face_source s) {
    linker.add_face(vs);  // a face it cannot link is kept, and finish reports it
    sources.push_back(s);
  }
  std::size_t num_faces() const noexcept { return sources.size(); }
};
using buffer = basic_buffer<>;

/// d's length, scaled by its largest component first so that coordinates far out (1e300)
/// do not overflow when squared. O(1).
template <class = void>
double safe_length(const glm::dvec3& d) {
  const double big = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  return big > 0 && std::isfinite(big) ? big * glm::length(d / big) : big;
}

/// d / |d|, scaled first as safe_length is (NaN components for a zero or non-finite d). O(1).
template <class = void>
glm::dvec3 safe_unit(const glm::dvec3& d) {
  const double big = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  return glm::normalize(d / big);
}

// The tubes' frames start from core/detail/geometry.hpp's default rule (the least aligned axis).
using cellforge::detail::any_perpendicular;

/// The signed angle from u to w about unit axis n (both projected into n's plane). O(1).
template <class = void>
double angle_about(const glm::dvec3& u, const glm::dvec3& w, const glm::dvec3& n) {
  return std::atan2(glm::dot(glm::cross(u, w), n), glm::dot(u, w));
}

}  // namespace detail::tubes
}  // namespace cellforge
