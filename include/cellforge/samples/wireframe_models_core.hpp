// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample wireframe models (samples/wireframe_models.hpp): the sample_model type, the voxel
/// layout and ring stack descriptions, and same_faces / same_volumes to compare a result with a
/// model's ground truth.

#include <algorithm>
#include <array>
#include <cmath>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge::samples {

/// A wireframe and what a correct conversion must find in it.
struct sample_model {
  std::string name;
  wireframe<glm::dvec3> wire;
  /// Each face: loops[0] its outer vertex cycle, loops[1..] its holes; orientation-free
  /// (compare as cyclic sequences up to rotation and reversal).
  std::vector<std::vector<std::vector<std::uint32_t>>> faces;
  /// Each volume: the indices of its faces, sorted.
  std::vector<std::vector<std::uint32_t>> volumes;
  /// Faces no edge needs: each of their edges keeps, without the face, at least two other faces
  /// and not just two coplanar ones. The reading rule (docs/wireframe.md) keeps such faces only
  /// where the wireframe cannot decide which to drop: the inner walls and the middle squares of
  /// the outside of a grid of at least 3 × 3 × 3 cubes. Every other model has none.
  std::size_t unforced_faces = 0;
};

/// A box-union model on a rectilinear lattice: cell (i, j, k) spans [xs[i], xs[i+1]] ×
/// [ys[j], ys[j+1]] × [zs[k], zs[k+1]] and carries a volume label (0 = empty, 1..L = volumes).
struct voxel_layout {
  std::vector<double> xs, ys, zs;
  std::vector<int> labels;  ///< size (xs-1)(ys-1)(zs-1), index i + nx * (j + ny * k)
  /// Merge coplanar facets with the same labels on either side into one face; false: every
  /// facet is its own face and every lattice line on the surface an edge (a quad-meshed box).
  bool merge_faces = true;
  int& at(std::size_t i, std::size_t j, std::size_t k) {
    return labels[i + (xs.size() - 1) * (j + (ys.size() - 1) * k)];
  }
};

/// A stack of planar rings of n points about the z axis, closed by planar caps or cone apexes,
/// optionally divided into volumes by walls (ring polygons as faces).
struct ring_stack {
  std::size_t n = 4;               ///< points per ring (3 or more)
  std::vector<double> radius;      ///< per ring
  std::vector<double> height;      ///< per ring (z), increasing
  std::vector<double> twist;       ///< per ring: angle offset in radians (empty: all 0)
  std::optional<double> bottom;    ///< z of a cone apex below ring 0; none: a planar cap
  std::optional<double> top;       ///< z of a cone apex above the last ring; none: a planar cap
  std::vector<std::size_t> walls;  ///< rings whose polygon is a face between two volumes
  bool triangles = false;          ///< bands as triangles (needed when twisted) instead of quads
};

namespace detail {

/// The loops of a face given as a vector of loops or as anything with a `.loops` member.
template <class Face>
const std::vector<std::vector<std::uint32_t>>& loops_of(const Face& f) {
  if constexpr (requires { f.loops; })
    return f.loops;
  else
    return f;
}

/// Canonical face: outer loop first, holes sorted after it. O(size log size).
template <class Face>
std::vector<std::vector<std::uint32_t>> canonical_face(const Face& face) {
  const auto& loops = loops_of(face);
  std::vector<std::vector<std::uint32_t>> out;
  for (const auto& l : loops) out.push_back(cellforge::detail::canonical_cycle(l));
  if (out.size() > 2) std::sort(out.begin() + 1, out.end());
  return out;
}

/// Face indices of a volume given as indices or as (index, sign) pairs or with a `.faces` member.
template <class Volume>
std::vector<std::uint32_t> volume_faces(const Volume& v) {
  std::vector<std::uint32_t> out;
  if constexpr (requires { v.faces; }) {
    return volume_faces(v.faces);
  } else {
    for (const auto& x : v) {
      if constexpr (requires { x.first; })
        out.push_back(static_cast<std::uint32_t>(x.first));
      else
        out.push_back(static_cast<std::uint32_t>(x));
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// Maps each face of `actual` to the index of the equal face of `expected`; nullopt when the
/// two lists are not the same multiset of distinct faces. O(F log F · face size).
template <class FacesA, class FacesB>
std::optional<std::vector<std::uint32_t>> match_faces(const FacesA& expected, const FacesB& actual) {
  if (expected.size() != actual.size()) return std::nullopt;
  std::map<std::vector<std::vector<std::uint32_t>>, std::uint32_t> index;
  for (std::size_t i = 0; i < expected.size(); ++i)
    if (!index.emplace(canonical_face(expected[i]), static_cast<std::uint32_t>(i)).second)
      return std::nullopt;
  std::vector<std::uint32_t> map(actual.size());
  std::vector<bool> used(expected.size(), false);
  for (std::size_t i = 0; i < actual.size(); ++i) {
    const auto it = index.find(canonical_face(actual[i]));
    if (it == index.end() || used[it->second]) return std::nullopt;
    used[it->second] = true;
    map[i] = it->second;
  }
  return map;
}

/// Newell normal of a closed polygon (not normalised; its length is twice the area). O(n).
template <class = void>
glm::dvec3 newell_normal(const std::vector<glm::dvec3>& pts, const std::vector<std::uint32_t>& loop) {
  return cellforge::detail::newell(loop, [&](std::uint32_t v) { return pts[v]; });
}

/// Counts the faces no edge needs (see sample_model::unforced_faces): a face is needed by an
/// edge of it when, without it, that edge would lie on fewer than two faces or on just two
/// coplanar ones. O(L log L), L the total loop length.
template <class = void>
std::size_t count_unforced(const sample_model& m) {
  // (smaller vertex, larger vertex, face) for every face side, sorted: the faces of an edge are a run.
  std::vector<std::array<std::uint32_t, 3>> sides;
  std::vector<glm::dvec3> normal;
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    glm::dvec3 n = newell_normal(m.wire.points, m.faces[f][0]);
    normal.push_back(n / std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z));
    for (const auto& loop : m.faces[f])
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
        sides.push_back({std::min(a, b), std::max(a, b), static_cast<std::uint32_t>(f)});
      }
  }
  std::sort(sides.begin(), sides.end());
  std::size_t unforced = 0;
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    bool needed = false;
    for (const auto& loop : m.faces[f])
      for (std::size_t i = 0; i < loop.size() && !needed; ++i) {
        const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
        const std::array<std::uint32_t, 3> lo{std::min(a, b), std::max(a, b), 0};
        std::array<std::uint32_t, 2> others{};
        std::size_t count = 0;
        for (auto it = std::lower_bound(sides.begin(), sides.end(), lo);
             it != sides.end() && (*it)[0] == lo[0] && (*it)[1] == lo[1]; ++it)
          if ((*it)[2] != f && count++ < 2) others[count - 1] = (*it)[2];
        if (count < 2) needed = true;
        if (count == 2) {
          const glm::dvec3 &u = normal[others[0]], &v = normal[others[1]];
          const glm::dvec3 c(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
          // Two unit normals: a cross product this small means the faces are coplanar.
          needed = std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z) < 1e-9;
        }
      }
    if (!needed) ++unforced;
  }
  return unforced;
}

/// Sorts each volume's faces and fills unforced_faces. O(model).
template <class = void>
sample_model finish(sample_model m) {
  for (auto& v : m.volumes) std::sort(v.begin(), v.end());
  m.unforced_faces = count_unforced(m);
  return m;
}

}  // namespace detail

/// True when `actual` holds the same faces as `expected`, each compared as vertex cycles up to
/// rotation and reversal (holes in any order), the lists in any order. Faces are vectors of loops
/// or have a `.loops` member (cell_complex_input::face). O(F log F · face size).
template <class FacesA, class FacesB>
bool same_faces(const FacesA& expected, const FacesB& actual) {
  return detail::match_faces(expected, actual).has_value();
}

/// True when the faces match (same_faces) and the volumes, mapped through that face matching,
/// are the same face sets in any order. Volumes are index lists, (index, sign) lists or have a
/// `.faces` member (cell_complex_input::volume). O((F + total volume size) log F).
template <class FacesA, class VolumesA, class FacesB, class VolumesB>
bool same_volumes(const FacesA& expected_faces, const VolumesA& expected_volumes, const FacesB& actual_faces,
                  const VolumesB& actual_volumes) {
  const auto map = detail::match_faces(expected_faces, actual_faces);
  if (!map || expected_volumes.size() != actual_volumes.size()) return false;
  std::vector<std::vector<std::uint32_t>> a, b;
  for (const auto& v : expected_volumes) a.push_back(detail::volume_faces(v));
  for (const auto& v : actual_volumes) {
    std::vector<std::uint32_t> mapped;
    for (const std::uint32_t f : detail::volume_faces(v)) {
      if (f >= map->size()) return false;
      mapped.push_back((*map)[f]);
    }
    std::sort(mapped.begin(), mapped.end());
    b.push_back(std::move(mapped));
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return a == b;
}

}  // namespace cellforge::samples
