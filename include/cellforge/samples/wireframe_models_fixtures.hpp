// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample wireframe models (samples/wireframe_models.hpp): the named fixtures (tetrahedron, cube,
/// prisms, L, T, U, house, frame, the seed's close edges and sample sizes, ...) and
/// all_small_samples.

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

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/samples/wireframe_models_builders.hpp"
#include "cellforge/samples/wireframe_models_core.hpp"

namespace cellforge::samples {

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

/// A square pyramid split into two tetrahedra by a wall on its base's diagonal: 5 vertices,
/// 9 edges, 7 faces (all triangles), 2 volumes. Its base is a seam only where drawn flat: the
/// drawing says so by its parallelogram, nothing else. O(1).
template <class = void>
sample_model sample_split_pyramid() {
  sample_model m;
  m.name = "split pyramid";
  m.wire.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0.8}};
  m.wire.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}, {0, 4}, {1, 4}, {2, 4}, {3, 4}};
  m.faces = {{{0, 1, 2}}, {{0, 2, 3}}, {{0, 1, 4}}, {{1, 2, 4}}, {{2, 3, 4}}, {{3, 0, 4}}, {{0, 2, 4}}};
  m.volumes = {{0, 2, 3, 6}, {1, 4, 5, 6}};
  return detail::finish(std::move(m));
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
