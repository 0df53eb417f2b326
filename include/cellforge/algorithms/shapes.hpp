// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Shape generators that double as test fixtures and benchmark inputs (Platonic solids,
/// spheres with exact vertex counts, tori, Möbius strips, Klein bottles, lattice and tree
/// tube meshes, swept spline tubes) and the soup queries the tests check them with
/// (Euler characteristic, boundary, orientability, signed volume).
///
/// Every generator is deterministic, costs O(output size), returns a polygon_soup of the
/// caller's point type and throws error(invalid_input) for parameters it cannot honour.
/// No face repeats a vertex and no undirected edge is used by more than two faces.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <random>
#include <ranges>
#include <span>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

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

/// A unit vector perpendicular to unit vector t.
template <class = void>
glm::dvec3 any_perpendicular(const glm::dvec3& t) {
  const glm::dvec3 axis = std::abs(t.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(t, axis));
}

}  // namespace detail::shapes

// ------------------------------------------------------------------------------------
// Platonic solids, all faces counter-clockwise seen from outside.
// ------------------------------------------------------------------------------------

/// Regular tetrahedron with unit circumradius (vertices at (±1,±1,±1)/√3, even sign count).
/// O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> tetrahedron() {
  static const std::array<glm::dvec3, 4> pts{{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}};
  static constexpr std::array<std::array<std::uint32_t, 3>, 4> faces{
      {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}}};
  return detail::shapes::solid<P>(pts, 1.0 / std::sqrt(3.0), faces);
}

/// The unit cube [0,1]^3 as 6 quads; vertex i sits at (i&1, (i>>1)&1, (i>>2)&1).
/// O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> hexahedron() {
  std::array<glm::dvec3, 8> pts;
  for (int i = 0; i < 8; ++i) pts[static_cast<std::size_t>(i)] = {i & 1, (i >> 1) & 1, (i >> 2) & 1};
  static constexpr std::array<std::array<std::uint32_t, 4>, 6> faces{
      {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};
  return detail::shapes::solid<P>(pts, 1.0, faces);
}

/// Regular octahedron with vertices ±x, ±y, ±z (unit circumradius), one triangle per octant.
/// O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> octahedron() {
  static const std::array<glm::dvec3, 6> pts{
      {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
  std::array<std::array<std::uint32_t, 3>, 8> faces;
  for (std::uint32_t o = 0; o < 8; ++o) {
    const std::uint32_t x = o & 1, y = 2 + ((o >> 1) & 1), z = 4 + ((o >> 2) & 1);
    // An odd number of negative axes mirrors the octant, which reverses the winding.
    const bool mirrored = ((o & 1) ^ ((o >> 1) & 1) ^ ((o >> 2) & 1)) != 0;
    faces[o] = mirrored ? std::array<std::uint32_t, 3>{x, z, y} : std::array<std::uint32_t, 3>{x, y, z};
  }
  return detail::shapes::solid<P>(pts, 1.0, faces);
}

/// Regular icosahedron with unit circumradius (12 vertices, 20 triangles).
/// O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> icosahedron() {
  return detail::shapes::solid<P>(detail::shapes::icosahedron_points(),
                                  1.0 / std::sqrt(1.0 + std::numbers::phi * std::numbers::phi),
                                  detail::shapes::icosahedron_faces);
}

/// Regular dodecahedron with unit circumradius (20 vertices, 12 pentagons), built as the
/// dual of the icosahedron: one vertex per icosahedron face, one pentagon per vertex. O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> dodecahedron() {
  namespace s = detail::shapes;
  const auto& ip = s::icosahedron_points();
  const auto& faces = s::icosahedron_faces;
  std::array<glm::dvec3, 20> pts;
  // Directed edge (v -> w) of the icosahedron -> the face that contains it.
  std::array<std::array<std::int8_t, 12>, 12> face_of{};
  for (auto& row : face_of) row.fill(-1);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& t = faces[f];
    pts[f] = glm::normalize(ip[t[0]] + ip[t[1]] + ip[t[2]]);
    for (std::size_t i = 0; i < 3; ++i) face_of[t[i]][t[(i + 1) % 3]] = static_cast<std::int8_t>(f);
  }
  std::array<std::array<std::uint32_t, 5>, 12> pentagons;
  for (std::uint32_t v = 0; v < 12; ++v) {
    // Start at any face around v; the next face counter-clockwise about v holds the edge
    // v -> (the vertex before v in the current face).
    std::uint32_t f = 0;
    while (faces[f][0] != v && faces[f][1] != v && faces[f][2] != v) ++f;
    for (std::size_t k = 0; k < 5; ++k) {
      pentagons[v][k] = f;
      const auto& t = faces[f];
      const std::size_t at = t[0] == v ? 0 : t[1] == v ? 1 : 2;
      f = static_cast<std::uint32_t>(face_of[v][t[(at + 2) % 3]]);
    }
  }
  return s::solid<P>(pts, 1.0, pentagons);
}

// ------------------------------------------------------------------------------------
// Spheres
// ------------------------------------------------------------------------------------

/// Unit sphere from an icosahedron split 1→4 `subdivisions` times: 10·4^s + 2 vertices,
/// 20·4^s triangles, nearly uniform. O(output) expected (edge midpoints through a hash).
template <Point3 P = glm::dvec3>
polygon_soup<P> icosphere(int subdivisions) {
  namespace s = detail::shapes;
  s::require(subdivisions >= 0 && subdivisions <= 13, "icosphere",
             cellforge::detail::cat("subdivisions must be in 0..13, got ", std::to_string(subdivisions)));
  const double faces_out = 20.0 * std::pow(4.0, subdivisions);
  s::require_size(faces_out / 2 + 2, 3 * faces_out, "icosphere");
  std::vector<glm::dvec3> pts;
  pts.reserve(static_cast<std::size_t>(faces_out / 2 + 2));
  for (const glm::dvec3& p : s::icosahedron_points()) pts.push_back(glm::normalize(p));
  std::vector<std::array<std::uint32_t, 3>> tris(s::icosahedron_faces.begin(), s::icosahedron_faces.end());
  for (int level = 0; level < subdivisions; ++level) {
    std::unordered_map<std::uint64_t, std::uint32_t> midpoint;
    midpoint.reserve(tris.size() * 3 / 2);
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      auto [it, fresh] = midpoint.try_emplace(s::edge_key(a, b), static_cast<std::uint32_t>(pts.size()));
      if (fresh) pts.push_back(glm::normalize(pts[a] + pts[b]));
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    next.reserve(tris.size() * 4);
    for (const auto& [a, b, c] : tris) {
      const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.push_back({a, ab, ca});
      next.push_back({ab, b, bc});
      next.push_back({ca, bc, c});
      next.push_back({ab, bc, ca});
    }
    tris.swap(next);
  }
  polygon_soup<P> soup;
  soup.reserve(pts.size(), tris.size(), 3 * tris.size());
  for (const glm::dvec3& p : pts) s::add_point(soup, p);
  for (const auto& t : tris) soup.add_face({t[0], t[1], t[2]});
  return soup;
}

/// Unit UV sphere: `slices` meridians, `stacks` latitude bands; the poles are single
/// vertices with triangle fans, quads elsewhere unless `triangles`. slices·(stacks−1)+2
/// vertices. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> uv_sphere(int slices, int stacks, bool triangles = true) {
  namespace s = detail::shapes;
  const double nv = static_cast<double>(slices) * (stacks - 1) + 2;
  s::require_counts("uv_sphere", {{"slices", slices, 3}, {"stacks", stacks, 2}}, nv, 6.0 * slices * stacks);
  polygon_soup<P> soup;
  soup.reserve(static_cast<std::size_t>(nv), 2u * slices * stacks, 6u * slices * stacks);
  const std::uint32_t north = s::add_point(soup, {0, 0, 1});
  for (int k = 1; k < stacks; ++k) {
    const double theta = s::pi * k / stacks;
    for (int i = 0; i < slices; ++i) {
      const double phi = 2.0 * s::pi * i / slices;
      s::add_point(soup, {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
    }
  }
  const std::uint32_t south = s::add_point(soup, {0, 0, -1});
  const auto n = static_cast<std::uint32_t>(slices);
  s::add_fan(soup, north, 1, n, false);
  // Quad (upper_i, lower_i, lower_i+1, upper_i+1) runs down, east, up: counter-clockwise outside.
  s::add_grid_faces(soup, stacks - 2, slices, triangles, [&](int k, int i) {
    return s::u32(1 + static_cast<std::int64_t>(k) * slices + i % slices);
  });
  s::add_fan(soup, south, 1 + (static_cast<std::uint32_t>(stacks) - 2) * n, n, true);
  return soup;
}

/// Unit triangulated sphere with exactly n vertices (n ≥ 4): two poles and latitude rings
/// whose sizes follow the circumference, zipped together by angle. O(n).
/// n = 4 gives the tetrahedron; every triangle is near-equilateral away from the poles.
template <Point3 P = glm::dvec3>
polygon_soup<P> sphere_with_vertices(int n) {
  namespace s = detail::shapes;
  s::require_counts("sphere_with_vertices", {{"n", n, 4}}, n, 6.0 * n);
  if (n == 4) return tetrahedron<P>();
  const std::int64_t inner = n - 2;  // vertices on the rings
  // Triangle side h for equilateral triangles covering 4π with n vertices; rings are
  // spaced one triangle height (h·√3/2) apart.
  const double h = std::sqrt(8.0 * s::pi / (std::sqrt(3.0) * n));
  std::int64_t rings = std::llround(s::pi / (h * std::sqrt(3.0) / 2.0)) - 1;
  rings = std::clamp<std::int64_t>(rings, 1, inner / 3);
  std::vector<double> ideal(static_cast<std::size_t>(rings));
  double total = 0;
  for (std::int64_t k = 0; k < rings; ++k) total += ideal[k] = std::sin(s::pi * (k + 1) / (rings + 1));
  std::vector<std::int64_t> count(ideal.size());
  std::int64_t sum = 0;
  for (std::size_t k = 0; k < ideal.size(); ++k) {
    ideal[k] *= static_cast<double>(inner) / total;
    sum += count[k] = std::max<std::int64_t>(3, static_cast<std::int64_t>(std::floor(ideal[k])));
  }
  // Largest-remainder correction; at most `rings` steps of O(rings) each, O(n) in all.
  while (sum != inner) {
    const bool grow = sum < inner;
    std::size_t best = ideal.size();
    for (std::size_t k = 0; k < ideal.size(); ++k) {
      if (!grow && count[k] <= 3) continue;
      const double gap = ideal[k] - static_cast<double>(count[k]);
      if (best == ideal.size() || (grow ? gap > ideal[best] - static_cast<double>(count[best])
                                        : gap < ideal[best] - static_cast<double>(count[best])))
        best = k;
    }
    count[best] += grow ? 1 : -1;
    sum += grow ? 1 : -1;
  }
  polygon_soup<P> soup;
  soup.reserve(static_cast<std::size_t>(n), 2 * static_cast<std::size_t>(n), 6 * static_cast<std::size_t>(n));
  // Ring k's vertex i sits at (i + offset_k) / count_k of a turn; odd rings are turned
  // half a step so that equal neighbouring rings interleave.
  const auto turn = [&](std::size_t k, std::int64_t i) {
    return (static_cast<double>(i) + 0.5 * static_cast<double>(k % 2)) / static_cast<double>(count[k]);
  };
  const std::uint32_t north = s::add_point(soup, {0, 0, 1});
  std::vector<std::uint32_t> first(count.size());
  for (std::size_t k = 0; k < count.size(); ++k) {
    const double theta = s::pi * static_cast<double>(k + 1) / static_cast<double>(rings + 1);
    first[k] = static_cast<std::uint32_t>(soup.points.size());
    for (std::int64_t i = 0; i < count[k]; ++i) {
      const double phi = 2.0 * s::pi * turn(k, i);
      s::add_point(soup, {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
    }
  }
  const std::uint32_t south = s::add_point(soup, {0, 0, -1});
  s::add_fan(soup, north, first.front(), static_cast<std::uint32_t>(count.front()), false);
  for (std::size_t k = 0; k + 1 < count.size(); ++k) {
    // Zip upper ring k (a vertices) to lower ring k+1 (b vertices): both start within half
    // a step of angle 0; always advance the side whose next vertex comes first, which
    // gives a + b triangles, each ring edge once, and ends on the starting edge.
    const std::int64_t a = count[k], b = count[k + 1];
    const auto up = [&](std::int64_t i) { return s::u32(first[k] + i % a); };
    const auto lo = [&](std::int64_t j) { return s::u32(first[k + 1] + j % b); };
    std::int64_t i = 0, j = 0;
    while (i < a || j < b) {
      if (j == b || (i < a && turn(k, i + 1) < turn(k + 1, j + 1))) {
        soup.add_face({up(i), lo(j), up(i + 1)});
        ++i;
      } else {
        soup.add_face({up(i), lo(j), lo(j + 1)});
        ++j;
      }
    }
  }
  s::add_fan(soup, south, first.back(), static_cast<std::uint32_t>(count.back()), true);
  return soup;
}

// ------------------------------------------------------------------------------------
// Tubes, planes and disks (orientable)
// ------------------------------------------------------------------------------------

/// Torus about the z axis, major radius R, tube radius r (0 < r < R), outward, closed,
/// genus 1: major·minor vertices and quads (twice as many triangles). O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> torus(int major_segments, int minor_segments, double R = 1, double r = 0.3,
                      bool triangles = true) {
  namespace s = detail::shapes;
  s::require(std::isfinite(R) && std::isfinite(r) && r > 0 && r < R, "torus",
             cellforge::detail::cat("radii must satisfy 0 < r < R (an embedded ring torus), got R = ",
                                    std::to_string(R), ", r = ", std::to_string(r)));
  s::require_counts("torus", {{"major_segments", major_segments, 3}, {"minor_segments", minor_segments, 3}},
                    static_cast<double>(major_segments) * minor_segments,
                    6.0 * major_segments * minor_segments);
  std::vector<s::ring_frame> rings;
  rings.reserve(static_cast<std::size_t>(major_segments));
  for (int k = 0; k < major_segments; ++k) {
    const double u = 2.0 * s::pi * k / major_segments;
    const glm::dvec3 radial(std::cos(u), std::sin(u), 0);
    // Sweep direction is +u, so (radial, -z) turns counter-clockwise about it.
    rings.push_back({R * radial, radial, {0, 0, -1}, r});
  }
  polygon_soup<P> soup;
  s::sweep_rings(soup, std::span<const s::ring_frame>(rings), minor_segments, true, false, triangles);
  return soup;
}

/// Cylinder of radius 1 about z from z = −1 to 1: `segments` around, `rings` bands along
/// (rings + 1 vertex circles). Caps are a fan about a centre vertex when `triangles`,
/// else one polygon each; outward. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> cylinder(int segments, int rings, bool capped = true, bool triangles = true) {
  namespace s = detail::shapes;
  s::require_counts("cylinder", {{"segments", segments, 3}, {"rings", rings, 1}},
                    static_cast<double>(segments) * (rings + 1) + 2, 6.0 * segments * (rings + 2));
  std::vector<s::ring_frame> frames;
  frames.reserve(static_cast<std::size_t>(rings) + 1);
  for (int k = 0; k <= rings; ++k)
    frames.push_back({{0, 0, -1.0 + 2.0 * k / rings}, {1, 0, 0}, {0, 1, 0}, 1.0});
  polygon_soup<P> soup;
  s::sweep_rings(soup, std::span<const s::ring_frame>(frames), segments, false, capped, triangles);
  return soup;
}

/// Unit disk in the xy plane, facing +z: a centre vertex and `rings` concentric circles
/// of `segments` vertices, all triangles; one boundary loop of `segments` edges. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> disk(int segments, int rings) {
  namespace s = detail::shapes;
  s::require_counts("disk", {{"segments", segments, 3}, {"rings", rings, 1}},
                    static_cast<double>(segments) * rings + 1, 6.0 * segments * rings);
  polygon_soup<P> soup;
  const std::uint32_t centre = s::add_point(soup, {0, 0, 0});
  for (int k = 1; k <= rings; ++k)
    for (int i = 0; i < segments; ++i) {
      const double phi = 2.0 * s::pi * i / segments, rad = static_cast<double>(k) / rings;
      s::add_point(soup, {rad * std::cos(phi), rad * std::sin(phi), 0});
    }
  s::add_fan(soup, centre, 1, static_cast<std::uint32_t>(segments), false);
  // (r, φ) is right-handed about +z, so step outward first, then around.
  s::add_grid_faces(soup, rings - 1, segments, true, [&](int k, int i) {
    return s::u32(1 + static_cast<std::int64_t>(k) * segments + i % segments);
  });
  return soup;
}

/// Open grid of nx × ny cells over the unit square [0,1]^2 at z = 0, facing +z: quads, or
/// two triangles per cell split along the (i,j)–(i+1,j+1) diagonal. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> grid_plane(int nx, int ny, bool triangles = true) {
  namespace s = detail::shapes;
  s::require_counts("grid_plane", {{"nx", nx, 1}, {"ny", ny, 1}}, (nx + 1.0) * (ny + 1.0), 6.0 * nx * ny);
  polygon_soup<P> soup;
  soup.reserve(static_cast<std::size_t>(nx + 1) * static_cast<std::size_t>(ny + 1),
               2 * static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny),
               6 * static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      s::add_point(soup, {static_cast<double>(i) / nx, static_cast<double>(j) / ny, 0});
  s::add_grid_faces(soup, nx, ny, triangles,
                    [&](int i, int j) { return s::u32(static_cast<std::int64_t>(j) * (nx + 1) + i); });
  return soup;
}

// ------------------------------------------------------------------------------------
// Non-orientable surfaces and inconsistently oriented inputs
// ------------------------------------------------------------------------------------

/// Möbius strip (centre circle radius 1, width 1) with each face wound as the (u, v)
/// parametrisation gives it, so the two faces on each of the `segments_across` seam edges
/// traverse it in the same direction. One boundary loop of 2·segments_along edges. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> mobius_strip(int segments_along, int segments_across, bool triangles = true) {
  namespace s = detail::shapes;
  const std::int64_t along = segments_along, across = segments_across;
  s::require_counts("mobius_strip",
                    {{"segments_along", segments_along, 3}, {"segments_across", segments_across, 1}},
                    static_cast<double>(along) * static_cast<double>(across + 1),
                    6.0 * static_cast<double>(along) * static_cast<double>(across));
  polygon_soup<P> soup;
  for (std::int64_t i = 0; i < along; ++i) {
    const double u = 2.0 * s::pi * static_cast<double>(i) / static_cast<double>(along);
    for (std::int64_t j = 0; j <= across; ++j) {
      const double v = -0.5 + static_cast<double>(j) / static_cast<double>(across);
      const double rad = 1.0 + v * std::cos(u / 2);
      s::add_point(soup, {rad * std::cos(u), rad * std::sin(u), v * std::sin(u / 2)});
    }
  }
  // Column `along` is column 0 read backwards: (u + 2π, v) is the point (u, −v).
  s::add_grid_faces(soup, segments_along, segments_across, triangles, [&](int i, int j) {
    return i == along ? s::u32(across - j) : s::u32(i * (across + 1) + j);
  });
  return soup;
}

/// Alias for the seed's "Mobius_16_16" benchmark input: mobius_strip(along, across, true).
/// O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> mobius_band(int segments_along = 16, int segments_across = 16) {
  return mobius_strip<P>(segments_along, segments_across, true);
}

/// Klein bottle as the figure-8 immersion (self-intersecting; only topology matters):
/// closed, χ = 0, non-orientable; the `v_segments` seam edges are traversed twice in the
/// same direction. u·v vertices and quads (twice as many triangles). O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> klein_bottle(int u_segments, int v_segments, bool triangles = true) {
  namespace s = detail::shapes;
  const std::int64_t nu = u_segments, nv = v_segments;
  s::require_counts("klein_bottle", {{"u_segments", u_segments, 3}, {"v_segments", v_segments, 3}},
                    static_cast<double>(nu) * static_cast<double>(nv),
                    6.0 * static_cast<double>(nu) * static_cast<double>(nv));
  polygon_soup<P> soup;
  constexpr double a = 2.0;  // radius of the figure-8's centre circle
  for (std::int64_t i = 0; i < nu; ++i) {
    const double u = 2.0 * s::pi * static_cast<double>(i) / static_cast<double>(nu);
    for (std::int64_t j = 0; j < nv; ++j) {
      const double v = 2.0 * s::pi * static_cast<double>(j) / static_cast<double>(nv);
      const double w = a + std::cos(u / 2) * std::sin(v) - std::sin(u / 2) * std::sin(2 * v);
      s::add_point(soup, {w * std::cos(u), w * std::sin(u),
                          std::sin(u / 2) * std::sin(v) + std::cos(u / 2) * std::sin(2 * v)});
    }
  }
  // (u + 2π, v) is the point (u, −v): column nu is column 0 with v mirrored.
  s::add_grid_faces(soup, u_segments, v_segments, triangles, [&](int i, int j) {
    const std::int64_t jj = j % nv;
    return i == nu ? s::u32((nv - jj) % nv) : s::u32(i * nv + jj);
  });
  return soup;
}

/// grid_plane(nx, ny, true) with each triangle's vertex order reversed with probability
/// 1/2, from the top bit of successive std::mt19937_64(seed) outputs (identical on every
/// standard library). Orientable, but neighbours disagree across many edges. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> random_orientation_plane(int nx, int ny, std::uint64_t seed) {
  polygon_soup<P> soup = grid_plane<P>(nx, ny, true);
  std::mt19937_64 bits(seed);
  for (std::size_t f = 0; f < soup.num_faces(); ++f)
    if ((bits() >> 63) != 0) {
      const auto first = soup.face_vertices.begin() + soup.face_offsets[f];
      std::reverse(first + 1, first + 3);  // keep the first vertex: (a, b, c) -> (a, c, b)
    }
  return soup;
}

/// Real projective plane as the hemi-icosahedron: the icosahedron with antipodal points
/// identified, 6 vertices, 15 edges (all pairs), 10 triangles, χ = 1. O(1).
template <Point3 P = glm::dvec3>
polygon_soup<P> projective_plane() {
  namespace s = detail::shapes;
  const auto& ip = s::icosahedron_points();
  // Vertex v of the icosahedron and its antipode map to the same class; keep the
  // representative with the first non-zero coordinate positive.
  std::array<std::uint32_t, 12> cls{};
  std::array<glm::dvec3, 6> pts;
  std::uint32_t classes = 0;
  for (std::uint32_t v = 0; v < 12; ++v) {
    std::uint32_t w = 0;
    while (glm::length(ip[w] + ip[v]) > 1e-9) ++w;
    if (w < v) {
      cls[v] = cls[w];
      continue;
    }
    const glm::dvec3& p = ip[v];
    const bool positive = p.x > 0 || (p.x == 0 && (p.y > 0 || (p.y == 0 && p.z > 0)));
    pts[classes] = glm::normalize(positive ? p : -p);
    cls[v] = classes++;
  }
  // Of each antipodal face pair keep the first one listed.
  std::vector<std::array<std::uint32_t, 3>> faces;
  std::unordered_set<std::uint32_t> seen;
  for (const auto& t : s::icosahedron_faces) {
    std::array<std::uint32_t, 3> c{cls[t[0]], cls[t[1]], cls[t[2]]};
    std::array<std::uint32_t, 3> sorted = c;
    std::sort(sorted.begin(), sorted.end());
    if (seen.insert(sorted[0] * 36 + sorted[1] * 6 + sorted[2]).second) faces.push_back(c);
  }
  return s::solid<P>(pts, 1.0, faces);
}

// ------------------------------------------------------------------------------------
// Tube meshes for the seed-001 benchmark tables (lattice, tree, spline)
// ------------------------------------------------------------------------------------

/// Shape of the square tubes around a lattice graph.
struct lattice_tube_options {
  double spacing = 1.0;    ///< distance between neighbouring lattice nodes (> 0)
  double width = 0.5;      ///< side of the square tube and of the node cube, 0 < width < spacing
  bool triangles = false;  ///< split every quad into two triangles
};

/// Closed surface around a subgraph of the integer lattice Z^3: a cube per node, a square
/// tube per unit edge, unit faces kept as quads. A 2-manifold per connected component with
/// genus = the component's cycle rank. O(output) expected.
template <Point3 P = glm::dvec3>
polygon_soup<P> lattice_graph_tube_mesh(std::span<const std::array<int, 3>> nodes,
                                        std::span<const std::array<std::uint32_t, 2>> edges,
                                        const lattice_tube_options& options = {}) {
  namespace s = detail::shapes;
  const char* what = "lattice_graph_tube_mesh";
  s::require(std::isfinite(options.spacing) && std::isfinite(options.width) && options.width > 0 &&
                 options.width < options.spacing,
             what,
             cellforge::detail::cat("need 0 < width < spacing, got width ", std::to_string(options.width),
                                    ", spacing ", std::to_string(options.spacing)));
  s::require_size(8.0 * static_cast<double>(nodes.size() + edges.size()),
                  48.0 * static_cast<double>(nodes.size() + edges.size()), what);
  // Voxels on a doubled grid: node (i,j,k) is voxel (2i,2j,2k), the edge to (i+1,j,k) is
  // voxel (2i+1,2j,2k). Occupied voxels around any voxel corner are a node plus some of
  // its arms, which are face-connected, and so are the empty ones: every edge and vertex
  // of the boundary is manifold.
  std::vector<std::array<std::int64_t, 3>> voxels;
  voxels.reserve(nodes.size() + edges.size());
  std::unordered_set<std::uint64_t> occupied;
  occupied.reserve(nodes.size() + edges.size());
  constexpr int coordinate_limit = 1 << 18;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const auto& c = nodes[n];
    s::require(std::abs(c[0]) < coordinate_limit && std::abs(c[1]) < coordinate_limit &&
                   std::abs(c[2]) < coordinate_limit,
               what, [&] {
                 return cellforge::detail::cat("node ", std::to_string(n),
                                               " lies outside the supported range |coordinate| < 2^18");
               });
    const std::array<std::int64_t, 3> v{2 * std::int64_t{c[0]}, 2 * std::int64_t{c[1]},
                                        2 * std::int64_t{c[2]}};
    s::require(occupied.insert(s::voxel_key(v[0], v[1], v[2])).second, what, [&] {
      return cellforge::detail::cat("node ", std::to_string(n), " repeats the position of an earlier node");
    });
    voxels.push_back(v);
  }
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = edges[e];
    s::require(a < nodes.size() && b < nodes.size(), what, [&] {
      return cellforge::detail::cat("edge ", std::to_string(e), " refers to a node that does not exist");
    });
    std::array<std::int64_t, 3> v{};
    int differing = 0, distance = 0;
    for (std::size_t d = 0; d < 3; ++d) {
      v[d] = std::int64_t{nodes[a][d]} + nodes[b][d];
      const int step = std::abs(nodes[a][d] - nodes[b][d]);
      differing += step != 0;
      distance += step;
    }
    s::require(differing == 1 && distance == 1, what, [&] {
      return cellforge::detail::cat("edge ", std::to_string(e),
                                    " does not join two lattice neighbours (unit, axis-aligned)");
    });
    s::require(occupied.insert(s::voxel_key(v[0], v[1], v[2])).second, what, [&] {
      return cellforge::detail::cat("edge ", std::to_string(e), " repeats an earlier edge");
    });
    voxels.push_back(v);
  }
  const double half = options.width / 2;
  const auto coordinate = [&](std::int64_t c) {
    // Corner c of the doubled grid: even corners start a node voxel, odd ones end it.
    const std::int64_t i = c >= 0 ? c / 2 : -((1 - c) / 2);
    return static_cast<double>(i) * options.spacing + ((c - 2 * i) == 0 ? -half : half);
  };
  polygon_soup<P> soup;
  std::unordered_map<std::uint64_t, std::uint32_t> corner_index;
  corner_index.reserve(4 * voxels.size());
  const auto corner = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    auto [it, fresh] =
        corner_index.try_emplace(s::voxel_key(x, y, z), static_cast<std::uint32_t>(soup.points.size()));
    if (fresh) s::add_point(soup, {coordinate(x), coordinate(y), coordinate(z)});
    return it->second;
  };
  for (const auto& v : voxels)
    for (std::size_t axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        std::array<std::int64_t, 3> n = v;
        n[axis] += side ? 1 : -1;
        if (occupied.contains(s::voxel_key(n[0], n[1], n[2]))) continue;
        // Corners in the (axis+1, axis+2) plane; that order is counter-clockwise about +axis.
        const std::size_t b = (axis + 1) % 3, c = (axis + 2) % 3;
        std::array<std::uint32_t, 4> q;
        constexpr int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
        for (int k = 0; k < 4; ++k) {
          std::array<std::int64_t, 3> p = v;
          p[axis] += side;
          p[b] += side ? du[k] : dv[k];
          p[c] += side ? dv[k] : du[k];
          q[static_cast<std::size_t>(k)] = corner(p[0], p[1], p[2]);
        }
        s::add_quad(soup, q[0], q[1], q[2], q[3], options.triangles);
      }
  return soup;
}

/// Closed tube mesh around the full nx × ny × nz node lattice (the seed's "Lattice_10_8_3"
/// is lattice_tube_mesh(10, 8, 3)); genus = E − V + 1 of the lattice graph. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> lattice_tube_mesh(int nx, int ny, int nz, const lattice_tube_options& options = {}) {
  namespace s = detail::shapes;
  s::require_counts("lattice_tube_mesh", {{"nx", nx, 1}, {"ny", ny, 1}, {"nz", nz, 1}}, 32.0 * nx * ny * nz,
                    200.0 * nx * ny * nz);
  std::vector<std::array<int, 3>> nodes;
  std::vector<std::array<std::uint32_t, 2>> edges;
  nodes.reserve(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz));
  const auto id = [&](int i, int j, int k) { return static_cast<std::uint32_t>((k * ny + j) * nx + i); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        nodes.push_back({i, j, k});
        if (i > 0) edges.push_back({id(i - 1, j, k), id(i, j, k)});
        if (j > 0) edges.push_back({id(i, j - 1, k), id(i, j, k)});
        if (k > 0) edges.push_back({id(i, j, k - 1), id(i, j, k)});
      }
  return lattice_graph_tube_mesh<P>(nodes, edges, options);
}

/// Closed genus-0 tube mesh around a 3D H-tree of `depth` binary branchings (2^depth
/// leaves; branch axes cycle x, y, z and lengths halve every three levels, so branches
/// never meet). depth 0 is a single cube. O(output) = O(2^depth).
template <Point3 P = glm::dvec3>
polygon_soup<P> tree_tube_mesh(int depth, const lattice_tube_options& options = {}) {
  namespace s = detail::shapes;
  s::require(depth >= 0 && depth <= 20, "tree_tube_mesh",
             cellforge::detail::cat("depth must be in 0..20, got ", std::to_string(depth)));
  const int top = depth > 0 ? (depth - 1) / 3 : 0;  // length exponent of the first level
  std::vector<std::array<int, 3>> nodes{{0, 0, 0}};
  std::vector<std::array<std::uint32_t, 2>> edges;
  std::vector<std::uint32_t> tips{0};
  for (int level = 0; level < depth; ++level) {
    const std::size_t axis = static_cast<std::size_t>(level % 3);
    const int length = 1 << (top - level / 3);
    std::vector<std::uint32_t> next;
    next.reserve(2 * tips.size());
    for (const std::uint32_t tip : tips)
      for (const int dir : {-1, 1}) {
        std::uint32_t prev = tip;
        for (int step = 1; step <= length; ++step) {
          std::array<int, 3> p = nodes[tip];
          p[axis] += dir * step;
          nodes.push_back(p);
          const auto cur = static_cast<std::uint32_t>(nodes.size() - 1);
          edges.push_back({prev, cur});
          prev = cur;
        }
        next.push_back(prev);
      }
    tips.swap(next);
  }
  return lattice_graph_tube_mesh<P>(nodes, edges, options);
}

/// Resolution and shape of a swept spline tube.
struct spline_tube_options {
  int segments_around = 8;   ///< vertices per cross-section (≥ 3)
  int samples_per_span = 8;  ///< cross-sections per Catmull–Rom span (≥ 1)
  double radius = 0.1;       ///< tube radius (> 0)
  bool capped = true;        ///< close both ends (fan about a centre vertex, or one polygon)
  bool triangles = true;     ///< triangles, or quads on the sides and polygon caps
};

/// Control points of the default curve (a gently winding 3D path, the stand-in for the
/// seed's "eyespline" input). O(1).
template <class = void>
std::vector<glm::dvec3> default_spline_curve() {
  return {{0, 0, 0}, {1, 0.6, 0.2}, {2, 0.1, 0.8}, {3, -0.5, 0.4}, {4, 0, -0.2}, {5, 0.7, 0.1}};
}

/// Tube of circular cross-section swept along the uniform Catmull–Rom spline through the
/// control points, with rotation-minimising frames (double reflection, so it does not
/// twist) and end caps; closed and outward when capped. O(output).
template <Point3 P = glm::dvec3, std::ranges::forward_range R>
requires Point3<std::ranges::range_value_t<R>> polygon_soup<P> spline_tube(
    const R& control_points, const spline_tube_options& options = {}) {
  namespace s = detail::shapes;
  const char* what = "spline_tube";
  s::require_counts(
      what,
      {{"segments_around", options.segments_around, 3}, {"samples_per_span", options.samples_per_span, 1}}, 0,
      0);
  s::require(std::isfinite(options.radius) && options.radius > 0, what,
             cellforge::detail::cat("radius must be finite and > 0, got ", std::to_string(options.radius)));
  std::vector<glm::dvec3> cp;
  for (const auto& p : control_points) {
    const glm::dvec3 d = to_dvec3(p);
    s::require(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z), what, [&] {
      return cellforge::detail::cat("control point ", std::to_string(cp.size()), " is not finite");
    });
    s::require(cp.empty() || glm::length(d - cp.back()) > 0, what, [&] {
      return cellforge::detail::cat("control points ", std::to_string(cp.size() - 1), " and ",
                                    std::to_string(cp.size()),
                                    " coincide; the curve direction there is undefined");
    });
    cp.push_back(d);
  }
  s::require(cp.size() >= 2, what,
             cellforge::detail::cat("need at least 2 control points, got ", std::to_string(cp.size())));
  const std::size_t spans = cp.size() - 1;
  s::require_size(static_cast<double>(spans) * options.samples_per_span * options.segments_around,
                  6.0 * static_cast<double>(spans) * options.samples_per_span * options.segments_around,
                  what);
  // Sample positions and tangents; end points are mirrored so the end tangents follow the chords.
  std::vector<glm::dvec3> pos, tan;
  const auto at = [&](std::ptrdiff_t i) {
    const auto last = static_cast<std::ptrdiff_t>(cp.size()) - 1;
    if (i < 0) return 2.0 * cp[0] - cp[1];
    if (i > last) return 2.0 * cp[static_cast<std::size_t>(last)] - cp[static_cast<std::size_t>(last - 1)];
    return cp[static_cast<std::size_t>(i)];
  };
  for (std::size_t sp = 0; sp < spans; ++sp) {
    const auto i = static_cast<std::ptrdiff_t>(sp);
    for (int k = 0; k < options.samples_per_span + (sp + 1 == spans ? 1 : 0); ++k) {
      glm::dvec3 p, t;
      s::catmull_rom(at(i - 1), at(i), at(i + 1), at(i + 2),
                     static_cast<double>(k) / options.samples_per_span, p, t);
      if (!(glm::length(t) > 1e-12)) t = at(i + 1) - at(i);  // a cusp: fall back to the chord
      pos.push_back(p);
      tan.push_back(glm::normalize(t));
    }
  }
  std::vector<s::ring_frame> rings;
  rings.reserve(pos.size());
  glm::dvec3 r = s::any_perpendicular(tan[0]);
  for (std::size_t i = 0; i < pos.size(); ++i) {
    if (i > 0) {
      // Double reflection (Wang, Jüttler, Zheng & Liu 2008): reflect the previous frame
      // across the bisector plane of the chord, then across that of the tangents.
      const glm::dvec3 v1 = pos[i] - pos[i - 1];
      const double c1 = glm::dot(v1, v1);
      if (c1 > 0) {
        const glm::dvec3 rl = r - (2.0 / c1) * glm::dot(v1, r) * v1;
        const glm::dvec3 tl = tan[i - 1] - (2.0 / c1) * glm::dot(v1, tan[i - 1]) * v1;
        const glm::dvec3 v2 = tan[i] - tl;
        const double c2 = glm::dot(v2, v2);
        r = c2 > 0 ? rl - (2.0 / c2) * glm::dot(v2, rl) * v2 : rl;
      }
      r -= glm::dot(r, tan[i]) * tan[i];  // remove rounding drift
      r = glm::length(r) > 1e-9 ? glm::normalize(r) : s::any_perpendicular(tan[i]);
    }
    rings.push_back({pos[i], r, glm::cross(tan[i], r), options.radius});
  }
  polygon_soup<P> soup;
  s::sweep_rings(soup, std::span<const s::ring_frame>(rings), options.segments_around, false, options.capped,
                 options.triangles);
  return soup;
}

/// spline_tube along default_spline_curve(). O(output).
/// The benchmark's "eyespline" stand-in.
template <Point3 P = glm::dvec3>
polygon_soup<P> spline_tube(const spline_tube_options& options = {}) {
  return spline_tube<P>(default_spline_curve(), options);
}

// ------------------------------------------------------------------------------------
// Soup queries and transforms
// ------------------------------------------------------------------------------------

/// Counts describing a soup's connectivity, from one pass over its faces.
struct soup_statistics {
  std::size_t vertices = 0;  ///< points referenced by at least one face
  std::size_t edges = 0;     ///< unique undirected edges
  std::size_t faces = 0;
  std::size_t boundary_edges = 0;      ///< edges used by exactly one face
  std::size_t nonmanifold_edges = 0;   ///< edges used by three or more faces
  std::size_t inconsistent_edges = 0;  ///< two-face edges both faces traverse in the same direction
  std::size_t degenerate_faces = 0;    ///< faces with < 3 vertices or a repeated vertex
  std::int64_t euler_characteristic() const noexcept {
    return static_cast<std::int64_t>(vertices) - static_cast<std::int64_t>(edges) +
           static_cast<std::int64_t>(faces);
  }
};

/// Vertex, edge, face, boundary, non-manifold, inconsistent and degenerate counts of a soup.
/// O(total face size) expected; throws invalid_input for an out-of-range vertex index.
template <Point3 P>
soup_statistics analyze_soup(const polygon_soup<P>& soup) {
  const auto pairing = detail::shapes::pair_half_edges(soup, "analyze_soup");
  soup_statistics st;
  st.faces = soup.num_faces();
  st.edges = pairing.edges;
  st.boundary_edges = pairing.boundary;
  st.nonmanifold_edges = pairing.nonmanifold;
  st.inconsistent_edges = pairing.inconsistent;
  std::vector<bool> used(soup.points.size(), false);
  for (const std::uint32_t v : soup.face_vertices) used[v] = true;
  st.vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
  for (std::size_t f = 0; f < st.faces; ++f)
    st.degenerate_faces += detail::shapes::degenerate_face(soup.face(f));
  return st;
}

/// V − E + F counting only referenced vertices and unique undirected edges.
/// O(total face size) expected.
template <Point3 P>
std::int64_t euler_characteristic(const polygon_soup<P>& soup) {
  return analyze_soup(soup).euler_characteristic();
}

/// Number of edges used by exactly one face.
/// O(total face size) expected.
template <Point3 P>
std::size_t count_boundary_edges(const polygon_soup<P>& soup) {
  return analyze_soup(soup).boundary_edges;
}

/// True when no edge is used by exactly one face (an empty soup is closed).
/// O(total face size) expected.
template <Point3 P>
bool is_soup_closed(const polygon_soup<P>& soup) {
  return count_boundary_edges(soup) == 0;
}

/// Edges used by exactly two faces that traverse them in the same direction, i.e. where
/// the given orientations disagree. O(total face size) expected.
template <Point3 P>
std::size_t count_inconsistent_edges(const polygon_soup<P>& soup) {
  return analyze_soup(soup).inconsistent_edges;
}

/// True when faces can be flipped so that every two-face edge is traversed once each way
/// (BFS 2-colouring of faces; edges with 1 or ≥ 3 faces impose nothing). O(total face size) expected.
template <Point3 P>
bool is_soup_orientable(const polygon_soup<P>& soup) {
  namespace s = detail::shapes;
  const auto pairing = s::pair_half_edges(soup, "is_soup_orientable");
  const std::size_t m = soup.num_faces();
  std::vector<std::int8_t> flip(m, -1);  // -1 unvisited, else whether face f must be reversed
  std::vector<std::uint32_t> queue;
  queue.reserve(m);
  for (std::size_t seed = 0; seed < m; ++seed) {
    if (flip[seed] >= 0) continue;
    flip[seed] = 0;
    queue.assign(1, static_cast<std::uint32_t>(seed));
    for (std::size_t next = 0; next < queue.size(); ++next) {
      const std::uint32_t f = queue[next];
      for (std::uint32_t h = soup.face_offsets[f]; h < soup.face_offsets[f + 1]; ++h) {
        const std::uint32_t mate = pairing.mate[h];
        if (mate == s::half_edge_pairing::none) continue;
        const std::uint32_t g = pairing.face_of[mate];
        if (g == f) continue;
        // Same tail on the shared edge means same direction: g must be flipped relative to f.
        const bool same = soup.face_vertices[h] == soup.face_vertices[mate];
        const auto want = static_cast<std::int8_t>(flip[f] ^ (same ? 1 : 0));
        if (flip[g] < 0) {
          flip[g] = want;
          queue.push_back(g);
        } else if (flip[g] != want) {
          return false;
        }
      }
    }
  }
  return true;
}

/// Signed volume enclosed by the faces (divergence theorem over fan triangles); positive
/// for a closed surface oriented outward. O(total face size).
template <Point3 P>
double signed_volume(const polygon_soup<P>& soup) {
  double six_volume = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto face = soup.face(f);
    if (face.size() < 3) continue;
    for (const std::uint32_t v : face)
      detail::shapes::require(v < soup.points.size(), "signed_volume", [&] {
        return cellforge::detail::cat("face ", std::to_string(f), " refers to missing vertex ",
                                      std::to_string(v));
      });
    const glm::dvec3 a = to_dvec3(soup.points[face[0]]);
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
      six_volume +=
          glm::dot(a, glm::cross(to_dvec3(soup.points[face[i]]), to_dvec3(soup.points[face[i + 1]])));
  }
  return six_volume / 6.0;
}

/// The soup with every point mapped by the affine transform m (last row 0 0 0 1). A
/// mirroring m (negative determinant) also reverses each face so outward stays outward. O(n).
template <Point3 P>
polygon_soup<P> transformed(const polygon_soup<P>& soup, const glm::dmat4& m) {
  detail::shapes::require(m[0][3] == 0 && m[1][3] == 0 && m[2][3] == 0 && m[3][3] == 1, "transformed",
                          "only affine transforms are supported (the last row must be 0 0 0 1)");
  polygon_soup<P> out;
  out.points.reserve(soup.points.size());
  for (const P& p : soup.points)
    out.points.push_back(from_dvec3<P>(glm::dvec3(m * glm::dvec4(to_dvec3(p), 1.0))));
  out.face_offsets = soup.face_offsets;
  out.face_vertices = soup.face_vertices;
  if (glm::determinant(glm::dmat3(m)) < 0)
    for (std::size_t f = 0; f < out.num_faces(); ++f)
      std::reverse(out.face_vertices.begin() + out.face_offsets[f] + 1,
                   out.face_vertices.begin() + out.face_offsets[f + 1]);
  return out;
}

/// The soup scaled by per-axis factors about the origin (faces reversed when an odd number
/// of factors is negative). O(n).
template <Point3 P>
polygon_soup<P> scaled(const polygon_soup<P>& soup, const glm::dvec3& factors) {
  glm::dmat4 m(1.0);
  m[0][0] = factors.x;
  m[1][1] = factors.y;
  m[2][2] = factors.z;
  return transformed(soup, m);
}

/// The soup scaled uniformly by `factor` about the origin.
/// O(n).
template <Point3 P>
polygon_soup<P> scaled(const polygon_soup<P>& soup, double factor) {
  return scaled(soup, glm::dvec3(factor));
}

/// Splits every face of k ≥ 3 vertices into the k − 2 triangles (v0, vi, vi+1), keeping
/// orientation and points; exact for convex faces. O(total face size).
template <Point3 P>
polygon_soup<P> triangulate_fan(const polygon_soup<P>& soup) {
  polygon_soup<P> out;
  std::size_t triangles = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f)
    triangles += soup.face(f).size() >= 3 ? soup.face(f).size() - 2 : 0;
  out.reserve(soup.points.size(), triangles, 3 * triangles);
  out.points = soup.points;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto face = soup.face(f);
    for (std::size_t i = 1; i + 1 < face.size(); ++i) out.add_face({face[0], face[i], face[i + 1]});
  }
  return out;
}

/// Closed solid of revolution about the z axis: `profile` lists (radius, z) pairs (x = radius,
/// y = z) from one end to the other, swept with `segments` vertices per ring. An end with
/// radius 0 is a pole vertex joined by a triangle fan; any other end is closed by one
/// `segments`-gon (quads) or a triangle fan to a centre vertex (`triangles`). Interior
/// radii must be positive. Quads between rings, split into two triangles when `triangles`.
/// Faces point outward whichever way the profile runs. O(output).
template <Point3 P = glm::dvec3>
polygon_soup<P> solid_of_revolution(std::span<const glm::dvec2> profile, int segments,
                                    bool triangles = false) {
  namespace s = detail::shapes;
  const char* what = "solid_of_revolution";
  const auto m = static_cast<std::int64_t>(profile.size());
  s::require(m >= 2, what, "the profile needs at least 2 (radius, z) points");
  s::require_counts(what, {{"segments", segments, 3}},
                    static_cast<double>(segments) * static_cast<double>(m) + 2,
                    6.0 * segments * static_cast<double>(m + 1));
  for (std::int64_t k = 0; k < m; ++k) {
    const glm::dvec2 q = profile[static_cast<std::size_t>(k)];
    s::require(std::isfinite(q.x) && std::isfinite(q.y) && q.x >= 0, what, [&] {
      return cellforge::detail::cat("profile point ", std::to_string(k),
                                    " must have a finite radius >= 0 and a finite z");
    });
    s::require(q.x > 0 || k == 0 || k == m - 1, what, [&] {
      return cellforge::detail::cat("profile point ", std::to_string(k),
                                    " has radius 0; only the two ends may lie on the axis");
    });
    s::require(k == 0 || q != profile[static_cast<std::size_t>(k - 1)], what, [&] {
      return cellforge::detail::cat("profile points ", std::to_string(k - 1), " and ", std::to_string(k),
                                    " coincide");
    });
  }
  s::require(m > 2 || profile[0].x > 0 || profile[1].x > 0, what,
             "a profile of two axis points has no surface");
  polygon_soup<P> soup;
  // ring[k] = index of the first vertex of profile point k (one vertex when it is a pole).
  std::vector<std::uint32_t> ring(static_cast<std::size_t>(m));
  const auto n = static_cast<std::uint32_t>(segments);
  for (std::int64_t k = 0; k < m; ++k) {
    const glm::dvec2 q = profile[static_cast<std::size_t>(k)];
    ring[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(soup.points.size());
    if (q.x == 0) {
      s::add_point(soup, {0, 0, q.y});
      continue;
    }
    for (int i = 0; i < segments; ++i) {
      const double phi = 2.0 * s::pi * i / segments;
      s::add_point(soup, {q.x * std::cos(phi), q.x * std::sin(phi), q.y});
    }
  }
  const auto pole = [&](std::int64_t k) { return profile[static_cast<std::size_t>(k)].x == 0; };
  for (std::int64_t k = 0; k + 1 < m; ++k) {
    const std::uint32_t a = ring[static_cast<std::size_t>(k)], b = ring[static_cast<std::size_t>(k + 1)];
    if (pole(k))
      s::add_fan(soup, a, b, n, true);
    else if (pole(k + 1))
      s::add_fan(soup, b, a, n, false);
    else
      for (std::uint32_t i = 0; i < n; ++i)
        s::add_quad(soup, a + i, a + (i + 1) % n, b + (i + 1) % n, b + i, triangles);
  }
  // Caps: the first end seen from below (reversed winding), the last from above.
  for (const std::int64_t k : {std::int64_t{0}, m - 1}) {
    if (pole(k)) continue;
    const std::uint32_t first = ring[static_cast<std::size_t>(k)];
    const bool reverse = k == 0;
    if (triangles) {
      s::add_fan(soup, s::add_point(soup, {0, 0, profile[static_cast<std::size_t>(k)].y}), first, n, reverse);
    } else {
      std::vector<std::uint32_t> cap(n);
      for (std::uint32_t i = 0; i < n; ++i) cap[i] = reverse ? first + (n - i) % n : first + i;
      soup.add_face(cap);
    }
  }
  // A profile running downwards winds every face inward: flip them all.
  if (signed_volume(soup) < 0)
    for (std::size_t f = 0; f < soup.num_faces(); ++f)
      std::reverse(soup.face_vertices.begin() + soup.face_offsets[f],
                   soup.face_vertices.begin() + soup.face_offsets[f + 1]);
  return soup;
}

}  // namespace cellforge
