// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample wireframe models with their ground truth (faces as vertex cycles with holes,
/// volumes as face-index sets): the fixtures and benchmark inputs of the wireframe → cell
/// complex pipeline, and same_faces / same_volumes to compare a result with them.
/// See docs/sample_models.md.

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

/// Builds the model of a box union: facets between cells of different labels, merged into one
/// face per edge-connected coplanar region with the same pair of labels; straight runs of the
/// outlines become single edges. Throws invalid_input on a malformed layout or on a region whose
/// outline touches itself at a vertex. O(cells + facets · log(facets per face)).
template <class = void>
sample_model make_voxel_model(const voxel_layout& layout, std::string name) {
  const std::array<std::size_t, 3> cells{layout.xs.size() - 1, layout.ys.size() - 1, layout.zs.size() - 1};
  if (layout.xs.size() < 2 || layout.ys.size() < 2 || layout.zs.size() < 2 ||
      layout.labels.size() != cells[0] * cells[1] * cells[2])
    throw error(error_category::invalid_input, "make_voxel_model: labels do not match the lattice");
  const std::array<const std::vector<double>*, 3> coords{&layout.xs, &layout.ys, &layout.zs};
  const std::array<std::size_t, 3> pts{cells[0] + 1, cells[1] + 1, cells[2] + 1};
  using ivec = std::array<std::size_t, 3>;
  const auto label = [&](const std::array<std::ptrdiff_t, 3>& c) {
    for (int a = 0; a < 3; ++a)
      if (c[a] < 0 || c[a] >= static_cast<std::ptrdiff_t>(cells[a])) return 0;
    return layout
        .labels[static_cast<std::size_t>(c[0]) +
                cells[0] * (static_cast<std::size_t>(c[1]) + cells[1] * static_cast<std::size_t>(c[2]))];
  };
  const auto point_id = [&](const ivec& p) { return p[0] + pts[0] * (p[1] + pts[1] * p[2]); };
  int max_label = 0;
  for (const int l : layout.labels) {
    if (l < 0) throw error(error_category::invalid_input, "make_voxel_model: negative label");
    max_label = std::max(max_label, l);
  }

  // Facets of plane (axis a, position p), cell (u, v) in the plane's axes (a+1, a+2) mod 3.
  // Dense slots, ordered by (a, p, u, v); a slot holds a facet when its two labels differ.
  struct facet_key {
    int a;
    std::size_t p, u, v;
  };
  std::array<std::size_t, 4> base{};
  for (std::size_t a = 0; a < 3; ++a)
    base[a + 1] = base[a] + (cells[a] + 1) * cells[(a + 1) % 3] * cells[(a + 2) % 3];
  const auto slot = [&](const facet_key& k) {
    const auto a = static_cast<std::size_t>(k.a);
    return base[a] + (k.p * cells[(a + 1) % 3] + k.u) * cells[(a + 2) % 3] + k.v;
  };
  std::vector<std::pair<int, int>> facets(base[3], {0, 0});  // (label on the minus side, on the plus side)
  for (int a = 0; a < 3; ++a) {
    const int ua = (a + 1) % 3, va = (a + 2) % 3;
    for (std::size_t p = 0; p <= cells[a]; ++p)
      for (std::size_t u = 0; u < cells[ua]; ++u)
        for (std::size_t v = 0; v < cells[va]; ++v) {
          std::array<std::ptrdiff_t, 3> c{};
          c[a] = static_cast<std::ptrdiff_t>(p) - 1;
          c[ua] = static_cast<std::ptrdiff_t>(u);
          c[va] = static_cast<std::ptrdiff_t>(v);
          const int minus = label(c);
          c[a] += 1;
          const int plus = label(c);
          facets[slot({a, p, u, v})] = {minus, plus};
        }
  }

  // Regions: flood fill over facets sharing a side with the same label pair.
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> region(base[3], none);
  std::vector<std::vector<facet_key>> regions;
  for (int a = 0; a < 3; ++a)
    for (std::size_t p = 0; p <= cells[static_cast<std::size_t>(a)]; ++p)
      for (std::size_t u = 0; u < cells[static_cast<std::size_t>((a + 1) % 3)]; ++u)
        for (std::size_t v = 0; v < cells[static_cast<std::size_t>((a + 2) % 3)]; ++v) {
          const facet_key key{a, p, u, v};
          const std::pair<int, int> pair = facets[slot(key)];
          if (pair.first == pair.second || region[slot(key)] != none) continue;
          const std::size_t r = regions.size();
          regions.emplace_back();
          std::vector<facet_key> todo{key};
          region[slot(key)] = r;
          while (!todo.empty()) {
            const facet_key k = todo.back();
            todo.pop_back();
            regions[r].push_back(k);
            const std::array<std::array<std::ptrdiff_t, 2>, 4> steps{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
            for (const auto& s : steps) {
              if ((s[0] < 0 && k.u == 0) || (s[1] < 0 && k.v == 0)) continue;
              const facet_key n{k.a, k.p, static_cast<std::size_t>(static_cast<std::ptrdiff_t>(k.u) + s[0]),
                                static_cast<std::size_t>(static_cast<std::ptrdiff_t>(k.v) + s[1])};
              if (n.u >= cells[static_cast<std::size_t>((k.a + 1) % 3)] ||
                  n.v >= cells[static_cast<std::size_t>((k.a + 2) % 3)])
                continue;
              if (!layout.merge_faces || facets[slot(n)] != pair || region[slot(n)] != none) continue;
              region[slot(n)] = r;
              todo.push_back(n);
            }
          }
        }

  // Outline of each region as directed unit segments, counter-clockwise in (u, v); traced into loops.
  const auto lattice = [](int a, std::size_t p, std::size_t u, std::size_t v) {
    ivec q{};
    q[static_cast<std::size_t>(a)] = p;
    q[static_cast<std::size_t>((a + 1) % 3)] = u;
    q[static_cast<std::size_t>((a + 2) % 3)] = v;
    return q;
  };
  std::vector<std::vector<std::vector<std::size_t>>> region_loops(regions.size());  // lattice point ids
  std::vector<std::uint8_t> segment(pts[0] * pts[1] * pts[2], 0);  // bit a: segment from the point along +a
  for (std::size_t r = 0; r < regions.size(); ++r) {
    const int a = regions[r][0].a;
    const std::size_t p = regions[r][0].p;
    std::map<std::pair<std::size_t, std::size_t>, std::pair<std::size_t, std::size_t>>
        next;  // (u,v) -> (u,v)
    const auto in_region = [&](std::ptrdiff_t u, std::ptrdiff_t v) {
      if (u < 0 || v < 0 || static_cast<std::size_t>(u) >= cells[static_cast<std::size_t>((a + 1) % 3)] ||
          static_cast<std::size_t>(v) >= cells[static_cast<std::size_t>((a + 2) % 3)])
        return false;
      return region[slot({a, p, static_cast<std::size_t>(u), static_cast<std::size_t>(v)})] == r;
    };
    const auto add = [&](std::size_t u0, std::size_t v0, std::size_t u1, std::size_t v1) {
      if (!next.emplace(std::pair{u0, v0}, std::pair{u1, v1}).second)
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("make_voxel_model: a face outline touches itself at a vertex in '",
                                           name, "'"));
      const ivec q0 = lattice(a, p, u0, v0), q1 = lattice(a, p, u1, v1);
      const ivec& lo = point_id(q0) < point_id(q1) ? q0 : q1;
      const ivec& hi = point_id(q0) < point_id(q1) ? q1 : q0;
      for (std::size_t d = 0; d < 3; ++d)
        if (hi[d] != lo[d]) segment[point_id(lo)] |= static_cast<std::uint8_t>(1u << d);
    };
    for (const facet_key& k : regions[r]) {
      const auto u = static_cast<std::ptrdiff_t>(k.u), v = static_cast<std::ptrdiff_t>(k.v);
      if (!in_region(u, v - 1)) add(k.u, k.v, k.u + 1, k.v);
      if (!in_region(u + 1, v)) add(k.u + 1, k.v, k.u + 1, k.v + 1);
      if (!in_region(u, v + 1)) add(k.u + 1, k.v + 1, k.u, k.v + 1);
      if (!in_region(u - 1, v)) add(k.u, k.v + 1, k.u, k.v);
    }
    // Trace; the loop with positive signed area in (u, v) is the outer one.
    std::vector<std::vector<std::size_t>> loops;
    std::vector<double> areas;
    while (!next.empty()) {
      const auto start = next.begin()->first;
      auto at = start;
      std::vector<std::size_t> loop;
      double area = 0;
      do {
        const auto it = next.find(at);
        const auto to = it->second;
        next.erase(it);
        loop.push_back(point_id(lattice(a, p, at.first, at.second)));
        area += static_cast<double>(at.first) * static_cast<double>(to.second) -
                static_cast<double>(to.first) * static_cast<double>(at.second);
        at = to;
      } while (at != start);
      loops.push_back(std::move(loop));
      areas.push_back(area);
    }
    const std::size_t outer =
        static_cast<std::size_t>(std::max_element(areas.begin(), areas.end()) - areas.begin());
    std::swap(loops[0], loops[outer]);
    region_loops[r] = std::move(loops);
  }

  // Wireframe vertices: lattice points on outlines, except the middles of straight runs.
  const auto has_segment = [&](const ivec& q, std::size_t d, bool positive) {
    if (positive) return q[d] + 1 < pts[d] && (segment[point_id(q)] >> d & 1u) != 0;
    if (q[d] == 0) return false;
    ivec b = q;
    --b[d];
    return (segment[point_id(b)] >> d & 1u) != 0;
  };
  sample_model m;
  m.name = std::move(name);
  std::vector<std::uint32_t> vertex(segment.size(), UINT32_MAX);
  std::vector<bool> on_outline(segment.size(), false);
  for (std::size_t k = 0; k < pts[2]; ++k)
    for (std::size_t j = 0; j < pts[1]; ++j)
      for (std::size_t i = 0; i < pts[0]; ++i) {
        const ivec q{i, j, k};
        int degree = 0, straight = 0;
        for (std::size_t d = 0; d < 3; ++d) {
          const bool plus = has_segment(q, d, true), minus = has_segment(q, d, false);
          degree += int(plus) + int(minus);
          straight += int(plus && minus);
        }
        on_outline[point_id(q)] = degree > 0;
        if (degree > 0 && !(degree == 2 && straight == 1)) {
          vertex[point_id(q)] = static_cast<std::uint32_t>(m.wire.points.size());
          m.wire.points.emplace_back((*coords[0])[i], (*coords[1])[j], (*coords[2])[k]);
        }
      }
  // Edges: from each vertex along each positive direction to the next vertex.
  for (std::size_t k = 0; k < pts[2]; ++k)
    for (std::size_t j = 0; j < pts[1]; ++j)
      for (std::size_t i = 0; i < pts[0]; ++i) {
        const ivec q{i, j, k};
        if (vertex[point_id(q)] == UINT32_MAX) continue;
        for (std::size_t d = 0; d < 3; ++d) {
          if (!has_segment(q, d, true)) continue;
          ivec w = q;
          do ++w[d];
          while (vertex[point_id(w)] == UINT32_MAX);
          m.wire.edges.push_back({vertex[point_id(q)], vertex[point_id(w)]});
        }
      }
  // Faces, and volumes from the labels on either side.
  m.volumes.resize(static_cast<std::size_t>(max_label));
  for (std::size_t r = 0; r < regions.size(); ++r) {
    std::vector<std::vector<std::uint32_t>> face;
    for (const auto& loop : region_loops[r]) {
      std::vector<std::uint32_t> cycle;
      for (const std::size_t q : loop)
        if (vertex[q] != UINT32_MAX) cycle.push_back(vertex[q]);
      face.push_back(std::move(cycle));
    }
    const auto [minus, plus] = facets[slot(regions[r][0])];
    for (const int l : {minus, plus})
      if (l > 0)
        m.volumes[static_cast<std::size_t>(l - 1)].push_back(static_cast<std::uint32_t>(m.faces.size()));
    m.faces.push_back(std::move(face));
  }
  for (const auto& v : m.volumes)
    if (v.empty())
      throw error(error_category::invalid_input, "make_voxel_model: a label in 1..max is unused");
  return detail::finish(std::move(m));
}

/// Builds a ring stack (see ring_stack): rings joined by quad or triangle bands, closed by
/// planar caps or cone apexes, split into volumes at the wall rings. O(rings · n).
template <class = void>
sample_model make_ring_stack(const ring_stack& s, std::string name) {
  const std::size_t rings = s.radius.size(), n = s.n;
  if (n < 3 || rings == 0 || s.height.size() != rings || (!s.twist.empty() && s.twist.size() != rings))
    throw error(error_category::invalid_input, "make_ring_stack: ring data of different lengths");
  for (const std::size_t w : s.walls)
    if (w >= rings || (w == 0 && !s.bottom) || (w + 1 == rings && !s.top))
      throw error(error_category::invalid_input,
                  "make_ring_stack: a wall must not coincide with a planar cap");
  sample_model m;
  m.name = std::move(name);
  const auto id = [&](std::size_t r, std::size_t i) { return static_cast<std::uint32_t>(r * n + i % n); };
  for (std::size_t r = 0; r < rings; ++r)
    for (std::size_t i = 0; i < n; ++i) {
      const double t = 2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n) +
                       (s.twist.empty() ? 0.0 : s.twist[r]);
      m.wire.points.emplace_back(s.radius[r] * std::cos(t), s.radius[r] * std::sin(t), s.height[r]);
    }
  auto& e = m.wire.edges;
  for (std::size_t r = 0; r < rings; ++r)
    for (std::size_t i = 0; i < n; ++i) e.push_back({id(r, i), id(r, i + 1)});
  const auto volume_below = [&](std::size_t r) {  // volume of the band from ring r upwards
    return static_cast<std::size_t>(
        std::count_if(s.walls.begin(), s.walls.end(), [&](std::size_t w) { return w <= r; }));
  };
  m.volumes.resize(s.walls.size() + 1);
  const auto add_face = [&](std::vector<std::uint32_t> loop, std::size_t volume) {
    m.volumes[volume].push_back(static_cast<std::uint32_t>(m.faces.size()));
    m.faces.push_back({std::move(loop)});
  };
  const auto ring_loop = [&](std::size_t r) {
    std::vector<std::uint32_t> loop;
    for (std::size_t i = 0; i < n; ++i) loop.push_back(id(r, i));
    return loop;
  };
  for (std::size_t r = 0; r + 1 < rings; ++r) {
    const std::size_t vol = volume_below(r);
    for (std::size_t i = 0; i < n; ++i) {
      e.push_back({id(r, i), id(r + 1, i)});
      if (s.triangles) {
        // Ring r+1 point i sits between ring r points i and i+1 (twisted by half a step).
        e.push_back({id(r, i + 1), id(r + 1, i)});
        add_face({id(r, i), id(r, i + 1), id(r + 1, i)}, vol);
        add_face({id(r + 1, i), id(r, i + 1), id(r + 1, i + 1)}, vol);
      } else {
        add_face({id(r, i), id(r, i + 1), id(r + 1, i + 1), id(r + 1, i)}, vol);
      }
    }
  }
  const auto cap = [&](std::optional<double> apex, std::size_t r, std::size_t vol) {
    if (!apex) return add_face(ring_loop(r), vol);
    const auto c = static_cast<std::uint32_t>(m.wire.points.size());
    m.wire.points.emplace_back(0.0, 0.0, *apex);
    for (std::size_t i = 0; i < n; ++i) {
      e.push_back({id(r, i), c});
      add_face({id(r, i), id(r, i + 1), c}, vol);
    }
  };
  cap(s.bottom, 0, 0);
  cap(s.top, rings - 1, s.walls.size());
  for (const std::size_t w : s.walls) {
    m.volumes[volume_below(w) - 1].push_back(static_cast<std::uint32_t>(m.faces.size()));
    add_face(ring_loop(w), volume_below(w));
  }
  return detail::finish(std::move(m));
}

/// Splits edge `e` of a model at the points `at` (parameters in (0, 1), increasing): a chain of
/// collinear edges through new degree-2 vertices; face cycles gain the new vertices. O(model).
template <class = void>
sample_model split_edge(sample_model m, std::size_t e, const std::vector<double>& at) {
  if (e >= m.wire.edges.size()) throw error(error_category::invalid_input, "split_edge: no such edge");
  const auto [a, b] = m.wire.edges[e];
  std::vector<std::uint32_t> chain{a};
  for (const double t : at) {
    chain.push_back(static_cast<std::uint32_t>(m.wire.points.size()));
    m.wire.points.push_back(m.wire.points[a] + t * (m.wire.points[b] - m.wire.points[a]));
  }
  chain.push_back(b);
  m.wire.edges.erase(m.wire.edges.begin() + static_cast<std::ptrdiff_t>(e));
  for (std::size_t i = 0; i + 1 < chain.size(); ++i) m.wire.edges.push_back({chain[i], chain[i + 1]});
  for (auto& face : m.faces)
    for (auto& loop : face)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const std::size_t j = (i + 1) % loop.size();
        if (loop[i] == a && loop[j] == b) {
          loop.insert(loop.begin() + static_cast<std::ptrdiff_t>(i) + 1, chain.begin() + 1, chain.end() - 1);
          break;
        }
        if (loop[i] == b && loop[j] == a) {
          loop.insert(loop.begin() + static_cast<std::ptrdiff_t>(i) + 1, chain.rbegin() + 1,
                      chain.rend() - 1);
          break;
        }
      }
  return detail::finish(std::move(m));
}

/// The disjoint union of two models, `b` moved by `offset`. O(size of both).
template <class = void>
sample_model disjoint_union(sample_model a, const sample_model& b, glm::dvec3 offset, std::string name) {
  const auto nv = static_cast<std::uint32_t>(a.wire.points.size());
  const auto nf = static_cast<std::uint32_t>(a.faces.size());
  for (const auto& p : b.wire.points) a.wire.points.push_back(p + offset);
  for (const auto& e : b.wire.edges) a.wire.edges.push_back({e[0] + nv, e[1] + nv});
  for (auto face : b.faces) {
    for (auto& loop : face)
      for (auto& v : loop) v += nv;
    a.faces.push_back(std::move(face));
  }
  for (auto vol : b.volumes) {
    for (auto& f : vol) f += nf;
    a.volumes.push_back(std::move(vol));
  }
  a.name = std::move(name);
  return detail::finish(std::move(a));
}

/// The model with every point mapped to `linear * p + offset` (a scaling or rigid motion for
/// tolerance tests); the ground truth is unchanged. O(V).
template <class = void>
sample_model transformed(sample_model m, const glm::dmat3& linear, glm::dvec3 offset) {
  for (auto& p : m.wire.points) p = linear * p + offset;
  return m;
}

namespace detail {
/// Refuses a lattice of nx × ny × nz cells with a side of no cells or more than 10^8 cells in
/// all (GB of labels, and its model would need far more), before anything is allocated. O(1).
template <class = void>
void require_lattice(const char* what, std::size_t nx, std::size_t ny, std::size_t nz) {
  const double cells = static_cast<double>(nx) * static_cast<double>(ny) * static_cast<double>(nz);
  if (nx == 0 || ny == 0 || nz == 0 || cells > 1e8)
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(what), ": a lattice of ", std::to_string(nx), " x ",
                                       std::to_string(ny), " x ", std::to_string(nz),
                                       " cells; each side needs 1 or more and all of them at most 10^8"));
}
}  // namespace detail

/// A voxel layout of nx × ny × nz cells with the given coordinates (nx + 1, ny + 1, nz + 1 of
/// them), all empty; throws invalid_input for a side of no cells or more than 10^8 cells. O(cells).
template <class = void>
voxel_layout empty_layout(std::vector<double> xs, std::vector<double> ys, std::vector<double> zs) {
  if (xs.empty() || ys.empty() || zs.empty())
    throw error(error_category::invalid_input, "empty_layout: each axis needs at least two coordinates");
  detail::require_lattice("empty_layout", xs.size() - 1, ys.size() - 1, zs.size() - 1);
  voxel_layout l{std::move(xs), std::move(ys), std::move(zs), {}};
  l.labels.assign((l.xs.size() - 1) * (l.ys.size() - 1) * (l.zs.size() - 1), 0);
  return l;
}

namespace detail {
template <class = void>
std::vector<double> iota_coords(std::size_t n) {
  std::vector<double> c(n + 1);
  for (std::size_t i = 0; i <= n; ++i) c[i] = static_cast<double>(i);
  return c;
}
/// A regular n-gon prism or pyramid family member as a ring stack (the ring turned so that
/// a square's sides are axis-aligned).
template <class = void>
ring_stack regular_stack(std::size_t n, std::vector<double> heights, double radius = 1.0) {
  ring_stack s;
  s.n = n;
  s.height = std::move(heights);
  s.radius.assign(s.height.size(), radius);
  s.twist.assign(s.height.size(), std::numbers::pi / static_cast<double>(n));
  return s;
}
}  // namespace detail

/// A tetrahedron: 4 vertices, 6 edges, 4 faces, 1 volume. O(1).
template <class = void>
sample_model sample_tetrahedron() {
  sample_model m;
  m.name = "tetrahedron";
  m.wire.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.wire.edges = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  m.faces = {{{0, 1, 2}}, {{0, 1, 3}}, {{0, 2, 3}}, {{1, 2, 3}}};
  m.volumes = {{0, 1, 2, 3}};
  return detail::finish(std::move(m));
}

/// A box with corners (0,0,0) and `size`: 8 vertices, 12 edges, 6 faces, 1 volume. O(1).
template <class = void>
sample_model sample_cube(glm::dvec3 size = {1, 1, 1}) {
  voxel_layout l = empty_layout({0, size.x}, {0, size.y}, {0, size.z});
  l.labels = {1};
  return make_voxel_model(l, "cube");
}

/// An octahedron: 6 vertices, 12 edges, 8 faces, 1 volume; its three equatorial squares are
/// cycles of existing edges but not faces. O(1).
template <class = void>
sample_model sample_octahedron() {
  ring_stack s = detail::regular_stack(4, {0.0});
  s.twist = {0.0};
  s.bottom = -1.0;
  s.top = 1.0;
  return make_ring_stack(s, "octahedron");
}

/// A prism over a regular n-gon (3 <= n <= 1024): 2n vertices, 3n edges, n + 2 faces. O(n).
template <class = void>
sample_model sample_prism(std::size_t n) {
  if (n < 3 || n > 1024) throw error(error_category::invalid_input, "sample_prism: n must be in 3..1024");
  return make_ring_stack(detail::regular_stack(n, {0.0, 1.0}),
                         cellforge::detail::cat("prism ", std::to_string(n)));
}

/// A pyramid over a regular n-gon (3 <= n <= 1024): n + 1 vertices, 2n edges, n + 1 faces. O(n).
template <class = void>
sample_model sample_pyramid(std::size_t n) {
  if (n < 3 || n > 1024) throw error(error_category::invalid_input, "sample_pyramid: n must be in 3..1024");
  ring_stack s = detail::regular_stack(n, {0.0});
  s.top = 1.0;
  return make_ring_stack(s, cellforge::detail::cat("pyramid ", std::to_string(n)));
}

/// A UV sphere of radius 1: `slices` meridians, `stacks` bands (quads, triangle fans at the
/// poles); slices·(stacks − 1) + 2 vertices, slices·(2·stacks − 1) edges; one volume of
/// slices·stacks faces. Its rings (and with even slices its meridian circles) are planar
/// cycles of edges that no edge needs, so none is a face. O(slices · stacks).
template <class = void>
sample_model sample_uv_sphere(std::size_t slices, std::size_t stacks) {
  if (slices < 3 || stacks < 2 || slices > 4096 || stacks > 4096)
    throw error(error_category::invalid_input, "sample_uv_sphere: need 3..4096 slices and 2..4096 stacks");
  ring_stack s;
  s.n = slices;
  for (std::size_t k = 1; k < stacks; ++k) {
    const double phi = std::numbers::pi * static_cast<double>(k) / static_cast<double>(stacks);
    s.radius.push_back(std::sin(phi));
    s.height.push_back(-std::cos(phi));
  }
  s.bottom = -1.0;
  s.top = 1.0;
  return make_ring_stack(
      s, cellforge::detail::cat("uv sphere ", std::to_string(slices), "x", std::to_string(stacks)));
}

/// Two unit cubes sharing a face: 12 vertices, 20 edges, 11 faces, 2 volumes. O(1).
template <class = void>
sample_model sample_two_cubes() {
  voxel_layout l = empty_layout({0, 1, 2}, {0, 1}, {0, 1});
  l.labels = {1, 2};
  return make_voxel_model(l, "two cubes");
}

/// A k × m × n grid of unit cubes, every cube its own volume and every interior wall a face.
/// O(k·m·n · log).
template <class = void>
sample_model sample_grid(std::size_t k, std::size_t m, std::size_t n) {
  if (k == 0 || m == 0 || n == 0 || k * m * n > 1'000'000)
    throw error(error_category::invalid_input, "sample_grid: need 1 to 10^6 cubes");
  voxel_layout l = empty_layout(detail::iota_coords(k), detail::iota_coords(m), detail::iota_coords(n));
  for (std::size_t c = 0; c < l.labels.size(); ++c) l.labels[c] = static_cast<int>(c + 1);
  return make_voxel_model(
      l, cellforge::detail::cat("grid ", std::to_string(k), "x", std::to_string(m), "x", std::to_string(n)));
}

namespace detail {
/// One volume: the listed (x, y) cells of a footprint, extruded one cell high.
template <class = void>
sample_model extruded_footprint(std::vector<double> xs, std::vector<double> ys,
                                const std::vector<std::array<std::size_t, 2>>& cells, std::string name) {
  voxel_layout l = empty_layout(std::move(xs), std::move(ys), {0, 1});
  for (const auto& c : cells) l.at(c[0], c[1], 0) = 1;
  return make_voxel_model(l, std::move(name));
}
}  // namespace detail

/// An L of two boxes with coplanar faces merged: 12 vertices, 18 edges, 8 faces (two
/// non-convex hexagons), 1 volume. O(1).
template <class = void>
sample_model sample_L() {
  return detail::extruded_footprint({0, 1, 3}, {0, 1, 2.5}, {{0, 0}, {1, 0}, {0, 1}}, "L");
}

/// A T of two boxes, coplanar faces merged: 16 vertices, 24 edges, 10 faces, 1 volume. O(1).
template <class = void>
sample_model sample_T() {
  return detail::extruded_footprint({0, 1, 2, 3}, {0, 1.5, 2.5}, {{1, 0}, {0, 1}, {1, 1}, {2, 1}}, "T");
}

/// A U of three boxes, coplanar faces merged: 16 vertices, 24 edges, 10 faces, 1 volume. O(1).
template <class = void>
sample_model sample_U() {
  return detail::extruded_footprint({0, 1, 2, 3}, {0, 1, 3}, {{0, 0}, {1, 0}, {2, 0}, {0, 1}, {2, 1}}, "U");
}

/// A unit cube with a pyramid roof: 9 vertices, 16 edges, 9 faces, 1 volume. The square under
/// the roof is a cycle of edges but no edge needs it, so it is not a face (with
/// face_reading::keep_walls it is a wall between box and roof: 10 faces, 2 volumes). O(1).
template <class = void>
sample_model sample_house() {
  ring_stack s = detail::regular_stack(4, {0.0, 1.0}, std::numbers::sqrt2 / 2);
  s.top = 1.6;
  return make_ring_stack(s, "house");
}

/// Two objects: a cube and a hexagonal prism apart from it. O(1).
template <class = void>
sample_model sample_disjoint_solids() {
  return disjoint_union(sample_cube(), sample_prism(6), {3, 0.5, 0}, "disjoint solids");
}

/// A 2 × 1.5 × 1 box whose edges are split by collinear degree-2 vertices: four edges in two,
/// two in three, one in four (19 vertices, 23 edges, 6 faces, 1 volume). O(1).
template <class = void>
sample_model sample_split_edges() {
  sample_model m = sample_cube({2, 1.5, 1});
  // split_edge moves the pieces to the back, so edge 0 is always the next original edge.
  for (std::size_t i = 0; i < 7; ++i) {
    const std::vector<double> at = i < 4   ? std::vector<double>{0.5}
                                   : i < 6 ? std::vector<double>{0.25, 0.7}
                                           : std::vector<double>{0.1, 0.2, 0.9};
    m = split_edge(std::move(m), 0, at);
  }
  m.name = "split edges";
  return m;
}

/// A square frame (genus 1): a 3 × 3 ring of cells around a square hole; top and bottom are
/// faces with a hole; 16 vertices, 24 edges, 10 faces, 1 volume. O(1).
template <class = void>
sample_model sample_frame() {
  voxel_layout l = empty_layout({0, 1, 2, 3}, {0, 1, 2, 3}, {0, 0.5});
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) l.at(i, j, 0) = (i == 1 && j == 1) ? 0 : 1;
  return make_voxel_model(l, "frame");
}

/// A block with an off-centre rectangular through-hole along y: 16 vertices, 24 edges,
/// 10 faces, 1 volume. O(1).
template <class = void>
sample_model sample_block_with_hole() {
  voxel_layout l = empty_layout({0, 1, 2, 5}, {0, 3}, {0, 0.5, 1.5, 2});
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t k = 0; k < 3; ++k) l.at(i, 0, k) = (i == 1 && k == 1) ? 0 : 1;
  return make_voxel_model(l, "block with hole");
}

/// The bundled CAD-like input: a stepped L-shaped block split by internal walls into four
/// volumes (two staircase volumes with a staircase wall between them, a foot and a top box).
/// O(1).
template <class = void>
sample_model sample_stepped_block() {
  voxel_layout l = empty_layout({0, 30, 60, 90}, {0, 25, 50}, {0, 10, 20, 30, 40});
  for (std::size_t k = 0; k < 3; ++k) l.at(0, 0, k) = 1, l.at(0, 1, k) = 2;
  for (std::size_t k = 0; k < 2; ++k) l.at(1, 0, k) = 1, l.at(1, 1, k) = 2;
  l.at(2, 0, 0) = 3;
  l.at(0, 0, 3) = l.at(0, 1, 3) = 4;
  return make_voxel_model(l, "stepped block");
}

/// The seed's failure case (§8.1): many close, adjacent, nearly coplanar triangles. A
/// triangulated tube (48 points per ring, 16 rings twisted by half a step, cone caps) whose
/// ring points are lifted by up to 1e-3 of the radius so that no ring is planar: the only
/// faces are the 1 536 triangles, and a 4-cycle over two neighbours (bent by less than a
/// degree) must not become a face. 770 vertices, 2 304 edges, 1 volume. O(1).
template <class = void>
sample_model sample_close_edges() {
  ring_stack s;
  s.n = 48;
  s.triangles = true;
  for (std::size_t r = 0; r < 16; ++r) {
    s.height.push_back(0.5 * static_cast<double>(r));
    s.radius.push_back(3.0 + 0.5 * std::sin(0.3 * static_cast<double>(r)));
    s.twist.push_back(std::numbers::pi / 48.0 * static_cast<double>(r));
  }
  s.bottom = -0.8;
  s.top = 8.3;
  sample_model m = make_ring_stack(s, "close edges");
  for (std::size_t v = 0; v < 16 * 48; ++v)
    m.wire.points[v].z += 3e-3 * std::sin(1.7 * static_cast<double>(v) + 0.3 * static_cast<double>(v / 48));
  return detail::finish(std::move(m));
}

/// A slab 1000 times thinner than it is wide, split into two volumes by a wall across it:
/// close parallel faces and short edges next to long ones. 12 vertices, 20 edges, 11 faces. O(1).
template <class = void>
sample_model sample_thin_slab() {
  voxel_layout l = empty_layout({0, 0.6, 1.0}, {0, 1.0}, {0, 1e-3});
  l.labels = {1, 2};
  return make_voxel_model(l, "thin slab");
}

/// A model of about the size of sample `i` (1..6) of seed 000 §7.2, tables 1 and 3 (see
/// docs/sample_models.md for the mapping). O(size).
template <class = void>
sample_model sample_seed(int i) {
  switch (i) {
    case 1:  // exactly 66 V, 128 E, 66 faces (64 triangles + 2 long ones), 2 objects: two 32-gon pyramids
      return disjoint_union(sample_pyramid(32), sample_pyramid(32), {3, 0, 0}, "seed sample 1");
    case 2: {  // 16 V, 28 E, 16 faces, 3 volumes: exactly a row of three cubes
      sample_model m = sample_grid(3, 1, 1);
      m.name = "seed sample 2";
      return m;
    }
    case 3: {  // 24 V, 40 E, 19 faces, 2 volumes: exactly an octagonal prism halved by a wall
      ring_stack s = detail::regular_stack(8, {0.0, 1.0, 2.0});
      s.walls = {1};
      return make_ring_stack(s, "seed sample 3");
    }
    case 4: {  // 483 V, 1024 E, 544 faces, 2 volumes: a quad-meshed 31×4×4 box halved by a wall
      voxel_layout l = empty_layout(detail::iota_coords(31), detail::iota_coords(4), detail::iota_coords(4));
      l.merge_faces = false;
      for (std::size_t k = 0; k < 4; ++k)
        for (std::size_t j = 0; j < 4; ++j)
          for (std::size_t i = 0; i < 31; ++i) l.at(i, j, k) = i < 15 ? 1 : 2;
      return make_voxel_model(l, "seed sample 4");
    }
    case 5: {  // exactly 466 V, 944 E, 480 faces, 1 volume: a UV sphere of 16 slices × 30 stacks
      sample_model m = sample_uv_sphere(16, 30);
      m.name = "seed sample 5";
      return m;
    }
    case 6: {  // exactly 710 V, 2124 E, 1428 faces, 13 volumes: a vase of 11 antiprism bands
               // between 12 wall rings of 59 points, with two cone caps. The seed's reading:
               // no edge needs the rings, so by default they are not faces (1 volume, 1416
               // faces); face_reading::keep_walls reproduces the seed.
      ring_stack s;
      s.n = 59;
      s.triangles = true;
      for (std::size_t r = 0; r < 12; ++r) {
        s.height.push_back(static_cast<double>(r));
        s.radius.push_back(4.0 + std::sin(0.5 * static_cast<double>(r)));
        s.twist.push_back(std::numbers::pi / 59.0 * static_cast<double>(r));
        s.walls.push_back(r);
      }
      s.bottom = -1.5;
      s.top = 12.5;
      return make_ring_stack(s, "seed sample 6");
    }
    default:
      throw error(error_category::invalid_input, "sample_seed: the seed has samples 1..6");
  }
}

/// Every small model above (the fixtures the pipeline tests run): O(total size).
template <class = void>
std::vector<sample_model> all_small_samples() {
  std::vector<sample_model> all{sample_tetrahedron(),
                                sample_cube(),
                                sample_octahedron(),
                                sample_prism(3),
                                sample_prism(5),
                                sample_prism(32),
                                sample_pyramid(3),
                                sample_pyramid(4),
                                sample_pyramid(32),
                                sample_uv_sphere(8, 6),
                                sample_two_cubes(),
                                sample_grid(2, 2, 2),
                                sample_grid(3, 3, 3),
                                sample_L(),
                                sample_T(),
                                sample_U(),
                                sample_house(),
                                sample_disjoint_solids(),
                                sample_split_edges(),
                                sample_frame(),
                                sample_block_with_hole(),
                                sample_stepped_block(),
                                sample_thin_slab()};
  return all;
}

}  // namespace cellforge::samples
