// Small face lists generated in test code: closed, open, non-orientable and non-manifold.
#pragma once
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/core/polygon_soup.hpp"

namespace fixtures {

using soup = cellforge::polygon_soup<glm::dvec3>;

// An n x m grid of quads (split into triangles) whose far sides are glued to the near
// ones: wrap_x glues column n to 0; twist_x reverses the row order when gluing (Möbius).
inline soup glued_grid(int n, int m, bool wrap_x, bool twist_x, bool wrap_y, bool twist_y,
                       bool triangles = true) {
  soup s;
  const int cols = wrap_x ? n : n + 1, rows = wrap_y ? m : m + 1;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) s.points.push_back({i, j, (i * 7 + j * 3) % 5 * 0.1});
  auto id = [&](int i, int j) -> std::uint32_t {
    if (wrap_y && j == m) {
      j = 0;
      if (twist_y) i = (n - i) % n;
    }
    if (wrap_x && i == n) {
      i = 0;
      if (twist_x) j = wrap_y ? (m - j) % m : m - j;
    }
    return static_cast<std::uint32_t>(j * cols + i);
  };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (triangles) {
        s.add_face({a, b, c});
        s.add_face({a, c, d});
      } else {
        s.add_face({a, b, c, d});
      }
    }
  return s;
}

inline soup mobius(int n = 12, int w = 2) { return glued_grid(n, w, true, true, false, false); }
inline soup torus(int n = 8, int m = 6) { return glued_grid(n, m, true, false, true, false); }
inline soup klein(int n = 8, int m = 6) { return glued_grid(n, m, true, false, true, true); }
inline soup plane(int n = 6, int m = 5) { return glued_grid(n, m, false, false, false, false); }
inline soup cylinder(int n = 8, int m = 3) { return glued_grid(n, m, true, false, false, false); }

inline soup tetrahedron() {
  soup s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  s.add_face({0, 2, 1});
  s.add_face({0, 1, 3});
  s.add_face({1, 2, 3});
  s.add_face({0, 3, 2});
  return s;
}

inline soup cube() {
  soup s;
  for (int i = 0; i < 8; ++i) s.points.push_back({i & 1, (i >> 1) & 1, (i >> 2) & 1});
  s.add_face({0, 2, 3, 1});
  s.add_face({4, 5, 7, 6});
  s.add_face({0, 1, 5, 4});
  s.add_face({2, 6, 7, 3});
  s.add_face({0, 4, 6, 2});
  s.add_face({1, 3, 7, 5});
  return s;
}

// Reverses each face with probability 1/2 (raw engine bits: the same on every platform).
inline soup randomly_flipped(soup s, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (std::size_t f = 0; f < s.num_faces(); ++f)
    if (rng() & 1u)
      std::reverse(s.face_vertices.begin() + s.face_offsets[f],
                   s.face_vertices.begin() + s.face_offsets[f + 1]);
  return s;
}

// Two triangles touching at vertex 0 only (two open fans at one vertex).
inline soup bowtie() {
  soup s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  s.add_face({0, 1, 2});
  s.add_face({0, 3, 4});
  return s;
}

// Two closed cones (double pyramids' halves) sharing their apex: two closed fans.
inline soup double_cone() {
  soup s;
  s.points = {{0, 0, 0}, {1, 0, 1}, {0, 1, 1}, {-1, 0, 1}, {1, 0, -1}, {0, 1, -1}, {-1, 0, -1}};
  for (std::uint32_t base : {1u, 4u})
    for (std::uint32_t k = 0; k < 3; ++k) s.add_face({0, base + k, base + (k + 1) % 3});
  s.add_face({1, 3, 2});
  s.add_face({4, 6, 5});
  return s;
}

// The unique undirected edges of a soup, and the faces using each vertex.
inline std::set<std::pair<std::uint32_t, std::uint32_t>> soup_edges(const soup& s) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> e;
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    auto fv = s.face(f);
    for (std::size_t i = 0; i < fv.size(); ++i) {
      auto a = fv[i], b = fv[(i + 1) % fv.size()];
      e.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return e;
}

}  // namespace fixtures
