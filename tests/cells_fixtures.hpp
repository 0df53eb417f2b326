// SPDX-License-Identifier: MIT
#pragma once
// Hand-built cell complex inputs for the cells tests: unions of unit lattice cubes (a cube,
// two cubes sharing a face, grids, frames, disjoint cubes) and a block with a square hole.

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include "cellforge/cells/cell_complex.hpp"

namespace cells_fixtures {

using cube_cell = std::array<int, 3>;

/// The complex of a set of unit cubes at integer positions: every lattice square that bounds
/// a chosen cube is one face (normal along +axis), shared faces once, each cube one volume.
inline cellforge::cell_complex_input<glm::dvec3> lattice(const std::vector<cube_cell>& cubes) {
  cellforge::cell_complex_input<glm::dvec3> in;
  std::map<std::array<int, 3>, std::uint32_t> vid;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> eid;
  std::map<std::array<int, 4>, std::uint32_t> fid;  // (axis, x, y, z) of the face's min corner
  auto vertex = [&](std::array<int, 3> p) {
    const auto [it, fresh] = vid.emplace(p, static_cast<std::uint32_t>(in.points.size()));
    if (fresh) in.points.push_back({double(p[0]), double(p[1]), double(p[2])});
    return it->second;
  };
  auto edge = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::minmax(a, b);
    if (!eid.count(key)) {
      eid[key] = static_cast<std::uint32_t>(in.edges.size());
      in.edges.push_back({a, b});
    }
  };
  for (const auto& c : cubes) {
    cellforge::cell_input_volume vol;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        std::array<int, 3> o = c;
        o[axis] += side;
        const std::array<int, 4> key{axis, o[0], o[1], o[2]};
        auto it = fid.find(key);
        if (it == fid.end()) {
          // Loop counter-clockwise about +axis: the two other axes in cyclic order.
          const int u = (axis + 1) % 3, w = (axis + 2) % 3;
          std::array<int, 3> p0 = o, p1 = o, p2 = o, p3 = o;
          p1[u] += 1;
          p2[u] += 1;
          p2[w] += 1;
          p3[w] += 1;
          std::vector<std::uint32_t> loop{vertex(p0), vertex(p1), vertex(p2), vertex(p3)};
          for (int i = 0; i < 4; ++i) edge(loop[i], loop[(i + 1) % 4]);
          it = fid.emplace(key, static_cast<std::uint32_t>(in.faces.size())).first;
          in.faces.push_back({{loop}});
        }
        vol.faces.emplace_back(it->second, side == 1 ? +1 : -1);
      }
    in.volumes.push_back(vol);
  }
  return in;
}

inline cellforge::cell_complex_input<glm::dvec3> cube() { return lattice({{0, 0, 0}}); }
inline cellforge::cell_complex_input<glm::dvec3> two_cubes() { return lattice({{0, 0, 0}, {1, 0, 0}}); }
inline cellforge::cell_complex_input<glm::dvec3> grid(int k, int m, int n) {
  std::vector<cube_cell> cs;
  for (int x = 0; x < k; ++x)
    for (int y = 0; y < m; ++y)
      for (int z = 0; z < n; ++z) cs.push_back({x, y, z});
  return lattice(cs);
}
/// A 3x3x1 grid without its middle cube: a genus-1 solid made of eight cube volumes.
inline cellforge::cell_complex_input<glm::dvec3> frame() {
  std::vector<cube_cell> cs;
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y)
      if (x != 1 || y != 1) cs.push_back({x, y, 0});
  return lattice(cs);
}
inline cellforge::cell_complex_input<glm::dvec3> disjoint_cubes() { return lattice({{0, 0, 0}, {2, 0, 0}}); }

/// A 3x3x1 block with a 1x1 square hole through it, as ONE volume: top and bottom faces with a
/// hole loop each, four outer and four inner side faces (genus 1).
inline cellforge::cell_complex_input<glm::dvec3> block_with_hole() {
  cellforge::cell_complex_input<glm::dvec3> in;
  const double out[4][2] = {{0, 0}, {3, 0}, {3, 3}, {0, 3}}, hole[4][2] = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  for (int z = 0; z < 2; ++z)
    for (int i = 0; i < 4; ++i) in.points.push_back({out[i][0], out[i][1], double(z)});
  for (int z = 0; z < 2; ++z)
    for (int i = 0; i < 4; ++i) in.points.push_back({hole[i][0], hole[i][1], double(z)});
  // Vertices: outer bottom 0-3, outer top 4-7, hole bottom 8-11, hole top 12-15.
  for (std::uint32_t base : {0u, 8u})
    for (std::uint32_t i = 0; i < 4; ++i) {
      const std::uint32_t j = (i + 1) % 4;
      in.edges.push_back({base + i, base + j});
      in.edges.push_back({base + 4 + i, base + 4 + j});
      in.edges.push_back({base + i, base + 4 + i});
    }
  in.faces.push_back({{{4, 5, 6, 7}, {12, 15, 14, 13}}});  // top, normal +z
  in.faces.push_back({{{0, 3, 2, 1}, {8, 9, 10, 11}}});    // bottom, normal -z
  for (std::uint32_t i = 0; i < 4; ++i) {
    const std::uint32_t j = (i + 1) % 4;
    in.faces.push_back({{{i, j, 4 + j, 4 + i}}});            // outer side, normal outward
    in.faces.push_back({{{8 + i, 12 + i, 12 + j, 8 + j}}});  // inner side, normal into the hole
  }
  cellforge::cell_input_volume v;
  for (std::uint32_t f = 0; f < in.faces.size(); ++f) v.faces.emplace_back(f, +1);
  in.volumes.push_back(v);
  return in;
}

/// True when two inputs are identical: points, edges, face loops and signed volume faces.
inline bool same_input(const cellforge::cell_complex_input<glm::dvec3>& x,
                       const cellforge::cell_complex_input<glm::dvec3>& y) {
  if (x.points != y.points || x.edges != y.edges || x.faces.size() != y.faces.size() ||
      x.volumes.size() != y.volumes.size())
    return false;
  for (std::size_t f = 0; f < x.faces.size(); ++f)
    if (x.faces[f].loops != y.faces[f].loops) return false;
  for (std::size_t c = 0; c < x.volumes.size(); ++c)
    if (x.volumes[c].faces != y.volumes[c].faces) return false;
  return true;
}

/// Whether two complexes are the same in every relation, position and normal (a complex and
/// one built another way that must equal it).
template <class P>
bool same_complex(const cellforge::cell_complex<P>& x, const cellforge::cell_complex<P>& y) {
  using namespace cellforge;
  const auto eq = [](auto a, auto b) { return std::equal(a.begin(), a.end(), b.begin(), b.end()); };
  if (x.num_vertices() != y.num_vertices() || x.num_edges() != y.num_edges() ||
      x.num_faces() != y.num_faces() || x.num_volumes() != y.num_volumes() ||
      x.num_objects() != y.num_objects() || !eq(x.points(), y.points()))
    return false;
  for (cell_vertex v : x.vertices())
    if (!eq(x.vertex_edges(v), y.vertex_edges(v)) || x.vertex_object(v) != y.vertex_object(v)) return false;
  for (cell_edge e : x.edges())
    if (x.edge_vertices(e) != y.edge_vertices(e) || !eq(x.edge_faces(e), y.edge_faces(e)) ||
        !eq(x.edge_wedges(e), y.edge_wedges(e)))
      return false;
  for (cell_face f : x.faces()) {
    if (x.num_loops(f) != y.num_loops(f) || !eq(x.face_volumes(f), y.face_volumes(f)) ||
        !(x.face_normal(f) == y.face_normal(f)))
      return false;
    for (std::size_t l = 0; l < x.num_loops(f); ++l)
      if (!eq(x.loop_vertices(f, l), y.loop_vertices(f, l)) || !eq(x.loop_edges(f, l), y.loop_edges(f, l)))
        return false;
  }
  for (cell_volume c : x.volumes())
    if (!eq(x.volume_faces(c), y.volume_faces(c)) || x.volume_object(c) != y.volume_object(c)) return false;
  for (cell_object o : x.objects())
    if (!eq(x.object_volumes(o), y.object_volumes(o)) || x.object_counts(o) != y.object_counts(o))
      return false;
  return true;
}

}  // namespace cells_fixtures
