// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The building blocks of the shape generators (algorithms/shapes.hpp, samples/tube_soups.hpp) and
/// the soup queries (algorithms/soup_queries.hpp): argument checks, quads, fans, swept rings, the
/// half-edge pairing of a soup.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"

namespace cellforge {

namespace detail::shapes {

inline constexpr double pi = std::numbers::pi;

/// Throws invalid_input with "<what>: <message>" unless ok. In loops pass the message as
/// a callable so that the text is only built on failure.
template <class Message>
void require(bool ok, const char* what, Message&& message) {
  if (ok) [[likely]]
    return;
  if constexpr (std::is_invocable_v<Message>)
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(what), ": ", std::string(message())));
  else
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(what), ": ", std::string(message)));
}

/// Refuses outputs whose indices would not fit the soup's 32-bit indices (or would not fit
/// in memory anyway), before anything is allocated.
template <class = void>
void require_size(double vertices, double indices, const char* what) {
  constexpr double limit = static_cast<double>(std::numeric_limits<std::uint32_t>::max() / 2);
  require(vertices <= limit && indices <= limit, what,
          cellforge::detail::cat("the requested shape is too large (about ", std::to_string(vertices),
                                 " vertices, ", std::to_string(indices),
                                 " face indices); reduce its resolution"));
}

template <class = void>
void require_at_least(int value, int minimum, const char* what, const char* name) {
  require(value >= minimum, what, [&] {
    return cellforge::detail::cat(std::string(name), " must be at least ", std::to_string(minimum), ", got ",
                                  std::to_string(value));
  });
}

/// A resolution parameter and its smallest allowed value.
struct count_parameter {
  const char* name;
  int value;
  int minimum;
};

/// require_at_least for each parameter, then require_size for the output they imply.
template <class = void>
void require_counts(const char* what, std::initializer_list<count_parameter> params, double vertices,
                    double indices) {
  for (const count_parameter& p : params) require_at_least(p.value, p.minimum, what, p.name);
  require_size(vertices, indices, what);
}

template <class = void>
std::uint32_t u32(std::int64_t i) {
  return static_cast<std::uint32_t>(i);
}

template <Point3 P>
std::uint32_t add_point(polygon_soup<P>& soup, const glm::dvec3& p) {
  soup.points.push_back(from_dvec3<P>(p));
  return static_cast<std::uint32_t>(soup.points.size() - 1);
}

/// Adds quad a-b-c-d, or its two triangles a-b-c and a-c-d (same orientation).
template <Point3 P>
void add_quad(polygon_soup<P>& soup, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
              bool triangles) {
  if (triangles) {
    soup.add_face({a, b, c});
    soup.add_face({a, c, d});
  } else {
    soup.add_face({a, b, c, d});
  }
}

/// Adds the quads (i,j) (i+1,j) (i+1,j+1) (i,j+1) for i < nu, j < nv, where `id(i, j)`
/// resolves the grid's identifications (wrap-around, seams, poles).
template <Point3 P, class Id>
void add_grid_faces(polygon_soup<P>& soup, int nu, int nv, bool triangles, Id&& id) {
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      add_quad(soup, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), triangles);
}

/// Adds a fan of triangles from `centre` over ring[first .. first+n) (cyclic); `reverse`
/// flips the winding.
template <Point3 P>
void add_fan(polygon_soup<P>& soup, std::uint32_t centre, std::uint32_t first, std::uint32_t n,
             bool reverse) {
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t a = first + i, b = first + (i + 1) % n;
    if (reverse)
      soup.add_face({centre, b, a});
    else
      soup.add_face({centre, a, b});
  }
}

/// A circle of a swept tube: centre, two unit axes spanning its plane, radius. Going
/// from `normal` towards `binormal` must turn counter-clockwise about the sweep direction.
struct ring_frame {
  glm::dvec3 centre;
  glm::dvec3 normal;
  glm::dvec3 binormal;
  double radius;
};

/// Sweeps `around`-gons along rings; the surface normal points away from the sweep axis.
/// Closed sweeps join the last ring to the first; open ones get caps when asked (a
/// triangle fan about a centre vertex, or one polygon when !triangles). O(output).
template <Point3 P>
void sweep_rings(polygon_soup<P>& soup, std::span<const ring_frame> rings, int around, bool closed,
                 bool capped, bool triangles) {
  const auto m = static_cast<std::int64_t>(rings.size());
  const auto base = static_cast<std::int64_t>(soup.points.size());
  for (const ring_frame& r : rings)
    for (int i = 0; i < around; ++i) {
      const double phi = 2.0 * pi * i / around;
      add_point(soup, r.centre + r.radius * (std::cos(phi) * r.normal + std::sin(phi) * r.binormal));
    }
  const std::int64_t bands = closed ? m : m - 1;
  add_grid_faces(soup, around, static_cast<int>(bands), triangles,
                 [&](int i, int k) { return u32(base + (k % m) * around + i % around); });
  if (closed || !capped) return;
  const std::uint32_t first = u32(base), last = u32(base + (m - 1) * around), n = u32(around);
  if (triangles) {
    add_fan(soup, add_point(soup, rings.front().centre), first, n, true);
    add_fan(soup, add_point(soup, rings.back().centre), last, n, false);
  } else {
    std::vector<std::uint32_t> cap(n);
    for (std::uint32_t i = 0; i < n; ++i) cap[i] = first + (n - i) % n;
    soup.add_face(cap);
    for (std::uint32_t i = 0; i < n; ++i) cap[i] = last + i;
    soup.add_face(cap);
  }
}

/// The icosahedron with vertices (0, ±1, ±φ) and cyclic permutations, faces outward.
template <class = void>
const std::array<glm::dvec3, 12>& icosahedron_points() {
  static constexpr double g = std::numbers::phi;
  static const std::array<glm::dvec3, 12> p{{{-1, g, 0},
                                             {1, g, 0},
                                             {-1, -g, 0},
                                             {1, -g, 0},
                                             {0, -1, g},
                                             {0, 1, g},
                                             {0, -1, -g},
                                             {0, 1, -g},
                                             {g, 0, -1},
                                             {g, 0, 1},
                                             {-g, 0, -1},
                                             {-g, 0, 1}}};
  return p;
}
inline constexpr std::array<std::array<std::uint32_t, 3>, 20> icosahedron_faces{{
    {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
    {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1},
}};

/// A fixed-size solid: points scaled by `scale`, faces as given.
template <Point3 P, std::size_t N, class Faces>
polygon_soup<P> solid(const std::array<glm::dvec3, N>& points, double scale, const Faces& faces) {
  polygon_soup<P> soup;
  for (const glm::dvec3& p : points) add_point(soup, p * scale);
  for (const auto& f : faces) soup.add_face(std::span<const std::uint32_t>(f.data(), f.size()));
  return soup;
}

/// Undirected edge key of (a, b): the smaller index in the high half.
template <class = void>
std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) noexcept {
  const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

/// The face-edges of a soup paired up: half-edge h is face-vertex slot h, running from
/// face_vertices[h] to the next vertex of its face. Built by bucketing every half-edge
/// under its smaller endpoint (a counting sort) and sorting each small bucket, so it is
/// deterministic and O(H log d) for H face-vertex slots and maximum vertex degree d.
struct half_edge_pairing {
  static constexpr std::uint32_t none = ~std::uint32_t{0};
  std::vector<std::uint32_t> face_of;  ///< face of each half-edge
  std::vector<std::uint32_t> mate;     ///< the other half-edge of a two-face edge, else none
  std::size_t edges = 0, boundary = 0, nonmanifold = 0, inconsistent = 0;
};

template <Point3 P>
half_edge_pairing pair_half_edges(const polygon_soup<P>& soup, const char* what) {
  const auto& fv = soup.face_vertices;
  const std::size_t n = soup.points.size(), hcount = fv.size(), faces = soup.num_faces();
  require(!soup.face_offsets.empty() && soup.face_offsets.front() == 0 && soup.face_offsets.back() == hcount,
          what, "face_offsets must start at 0 and end at face_vertices.size()");
  half_edge_pairing out;
  out.face_of.assign(hcount, 0);
  out.mate.assign(hcount, half_edge_pairing::none);
  std::vector<std::uint32_t> head(hcount);  // vertex each half-edge runs to
  for (std::size_t f = 0; f < faces; ++f) {
    const std::uint32_t begin = soup.face_offsets[f], end = soup.face_offsets[f + 1];
    require(begin <= end && end <= hcount, what, [&] {
      return cellforge::detail::cat("face_offsets must not decrease (face ", std::to_string(f), ")");
    });
    for (std::uint32_t h = begin; h < end; ++h) {
      require(fv[h] < n, what, [&] {
        return cellforge::detail::cat("face ", std::to_string(f), " refers to vertex ", std::to_string(fv[h]),
                                      " but the soup has only ", std::to_string(n), " points");
      });
      out.face_of[h] = static_cast<std::uint32_t>(f);
      head[h] = fv[h + 1 < end ? h + 1 : begin];
    }
  }
  // Bucket half-edges by their smaller endpoint; a repeated consecutive vertex is no edge
  // (the face is counted as degenerate instead).
  std::vector<std::uint32_t> start(n + 1, 0);
  for (std::size_t h = 0; h < hcount; ++h)
    if (fv[h] != head[h]) ++start[std::min(fv[h], head[h]) + 1];
  for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> slot(start[n]);
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t h = 0; h < hcount; ++h)
      if (fv[h] != head[h]) slot[fill[std::min(fv[h], head[h])]++] = static_cast<std::uint32_t>(h);
  }
  const auto other_end = [&](std::uint32_t h) { return std::max(fv[h], head[h]); };
  for (std::size_t v = 0; v < n; ++v) {
    const auto first = slot.begin() + start[v], last = slot.begin() + start[v + 1];
    std::sort(first, last, [&](std::uint32_t x, std::uint32_t y) {
      return other_end(x) != other_end(y) ? other_end(x) < other_end(y) : x < y;
    });
    for (auto run = first; run != last;) {
      auto stop = run;
      while (stop != last && other_end(*stop) == other_end(*run)) ++stop;
      ++out.edges;
      const auto uses = stop - run;
      if (uses == 1) ++out.boundary;
      if (uses > 2) ++out.nonmanifold;
      if (uses == 2) {
        out.mate[run[0]] = run[1];
        out.mate[run[1]] = run[0];
        out.inconsistent += fv[run[0]] == fv[run[1]];  // same tail: same direction
      }
      run = stop;
    }
  }
  return out;
}

/// True when a face has fewer than three vertices or repeats one. O(k^2) for the usual
/// small faces (no allocation), O(k log k) beyond 16 vertices.
template <class = void>
bool degenerate_face(std::span<const std::uint32_t> face) {
  if (face.size() < 3) return true;
  if (face.size() <= 16) {
    for (std::size_t i = 1; i < face.size(); ++i)
      if (std::find(face.begin(), face.begin() + static_cast<std::ptrdiff_t>(i), face[i]) !=
          face.begin() + static_cast<std::ptrdiff_t>(i))
        return true;
    return false;
  }
  std::vector<std::uint32_t> sorted(face.begin(), face.end());
  std::sort(sorted.begin(), sorted.end());
  return std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
}

/// Hash key of a voxel (or voxel corner) on the doubled lattice grid: three biased
/// 21-bit coordinates in one word.
template <class = void>
std::uint64_t voxel_key(std::int64_t x, std::int64_t y, std::int64_t z) noexcept {
  constexpr std::int64_t bias = 1 << 20;
  return (static_cast<std::uint64_t>(x + bias) << 42) | (static_cast<std::uint64_t>(y + bias) << 21) |
         static_cast<std::uint64_t>(z + bias);
}

/// Uniform Catmull–Rom point and derivative on span [p1, p2] at t in [0, 1].
template <class = void>
void catmull_rom(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& p3,
                 double t, glm::dvec3& point, glm::dvec3& tangent) {
  const double t2 = t * t, t3 = t2 * t;
  point = 0.5 * ((2.0 * p1) + (-p0 + p2) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2 +
                 (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * t3);
  tangent = 0.5 * ((-p0 + p2) + 2.0 * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t +
                   3.0 * (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * t2);
}

}  // namespace detail::shapes

}  // namespace cellforge
