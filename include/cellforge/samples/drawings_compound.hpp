// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample drawings (samples/drawings.hpp): models of several volumes (glued convex cells,
/// sliced polytopes, roofs on boxes, bar frames, cell blocks), solids touching along an edge or
/// at a vertex, and faceted solids of revolution.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/samples/drawings_normalons.hpp"
#include "cellforge/samples/drawings_polytopes.hpp"
#include "cellforge/samples/wireframe_models.hpp"

namespace cellforge::samples {

// ---- models of several volumes, touching solids and faceted curved solids ------------------------
// The families below break the one-solid model on purpose: internal walls (an edge on three or
// four faces, two of them coplanar where a wall meets a flat side), solids touching along an edge
// or at a vertex (an edge on four faces), and solids of revolution whose rings are planar cycles
// of edges that are no faces. Every volume is a ball, so V − E + F − R − C = 1 − genus for a
// connected model (C its volumes); the truth is what wireframe_to_cells reads from the 3D model
// (the test checks it).

/// Several convex cells glued into one model: each cell's points in convex position
/// (convex_polytope_model), equal points (bit for bit) one vertex, a face two cells share (the
/// same cycle) one face between two volumes. The cells must meet face to face (a corner of one
/// on a side of another is not checked here: wireframe_to_cells reads such a model otherwise).
/// O(Σ n log n).
template <class = void>
sample_model convex_cells_model(const std::vector<std::vector<glm::dvec3>>& cells, std::string name) {
  sample_model m;
  m.name = std::move(name);
  std::map<std::array<double, 3>, std::uint32_t> id;
  std::map<std::vector<std::uint32_t>, std::uint32_t> face_id;
  std::set<std::array<std::uint32_t, 2>> edges;
  for (const auto& cell : cells) {
    const sample_model c = convex_polytope_model(cell, m.name);
    std::vector<std::uint32_t> global;
    for (const auto& p : c.wire.points) {
      const auto [it, fresh] = id.insert({{p.x, p.y, p.z}, static_cast<std::uint32_t>(m.wire.points.size())});
      if (fresh) m.wire.points.push_back(p);
      global.push_back(it->second);
    }
    std::vector<std::uint32_t> volume;
    for (const auto& face : c.faces) {
      std::vector<std::uint32_t> loop;
      for (const auto v : face[0]) loop.push_back(global[v]);
      for (std::size_t k = 0; k < loop.size(); ++k)
        edges.insert(
            {std::min(loop[k], loop[(k + 1) % loop.size()]), std::max(loop[k], loop[(k + 1) % loop.size()])});
      const auto [it, fresh] = face_id.insert(
          {cellforge::detail::canonical_cycle(loop), static_cast<std::uint32_t>(m.faces.size())});
      if (fresh) m.faces.push_back({std::move(loop)});
      volume.push_back(it->second);
    }
    m.volumes.push_back(std::move(volume));
  }
  m.wire.edges.assign(edges.begin(), edges.end());
  return detail::finish(std::move(m));
}

/// A box (base = 0, sides of random lengths) or a regular base-gon prism (3..12) split by
/// `cuts` (1..3) random planes through its middle into convex cells, each its own volume (walls
/// crossing walls: an edge on four faces where two cuts cross); nullopt when a cut passes within
/// 4 % of the size of a corner (sliver cells). `diagonal`: one more wall, the box's plane through
/// two opposite vertical edges, first. O(cells · n log n).
template <class = void>
std::optional<sample_model> sliced_polytope(std::size_t base, std::size_t cuts, bool diagonal,
                                            std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x736c696365000000u};
  std::vector<glm::dvec3> start;
  const double a = rng.uniform(0.8, 2.0), b = rng.uniform(0.8, 2.0), c = rng.uniform(0.8, 2.0);
  if (base == 0) {
    for (unsigned k = 0; k < 8; ++k)
      start.push_back({(k & 1u) ? a : 0.0, (k & 2u) ? b : 0.0, (k & 4u) ? c : 0.0});
  } else {
    if (base < 3 || base > 12)
      throw error(error_category::invalid_input, "sliced_polytope: base must be 0 or 3..12");
    for (std::size_t i = 0; i < base; ++i) {
      const double t = 2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(base);
      for (const double z : {0.0, c}) start.push_back({std::cos(t), std::sin(t), z});
    }
  }
  const double size = detail::diagonal_of(start);
  std::vector<std::pair<glm::dvec3, double>> planes;                           // n · x = d
  if (diagonal && base == 0) planes.push_back({glm::dvec3(b, -a, 0.0), 0.0});  // through (0,0,z), (a,b,z)
  glm::dvec3 centre(0.0);
  for (const auto& p : start) centre += p;
  centre /= static_cast<double>(start.size());
  for (std::size_t k = 0; k < cuts; ++k) {
    glm::dvec3 n;
    do n = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    while (glm::length(n) > 1 || glm::length(n) < 0.2);
    n = glm::normalize(n);
    const glm::dvec3 at =
        centre + 0.25 * size * glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    planes.push_back({n, glm::dot(n, at)});
  }
  std::vector<std::vector<glm::dvec3>> cells{start};
  for (const auto& [n, d] : planes) {
    const double len = glm::length(n);
    std::vector<std::vector<glm::dvec3>> next;
    for (const auto& cell : cells) {
      const sample_model m = convex_polytope_model(cell, "cell");
      const auto& p = m.wire.points;
      std::vector<double> side(p.size());
      bool below = false, above = false;
      for (std::size_t i = 0; i < p.size(); ++i) {
        side[i] = (glm::dot(n, p[i]) - d) / len;
        if (side[i] != 0 && std::abs(side[i]) < 0.04 * size) return std::nullopt;
        below = below || side[i] < 0, above = above || side[i] > 0;
      }
      if (!below || !above) {
        next.push_back(cell);
        continue;
      }
      std::vector<glm::dvec3> lo, hi;
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (side[i] <= 0) lo.push_back(p[i]);
        if (side[i] >= 0) hi.push_back(p[i]);
      }
      for (const auto& e : m.wire.edges) {
        if (!((side[e[0]] < 0 && side[e[1]] > 0) || (side[e[0]] > 0 && side[e[1]] < 0))) continue;
        // The same segment gives the same point in every cell: ends in lexicographic order.
        std::uint32_t u = e[0], w = e[1];
        if (std::array<double, 3>{p[w].x, p[w].y, p[w].z} < std::array<double, 3>{p[u].x, p[u].y, p[u].z})
          std::swap(u, w);
        const double t = side[u] / (side[u] - side[w]);
        const glm::dvec3 x = p[u] + t * (p[w] - p[u]);
        lo.push_back(x), hi.push_back(x);
      }
      next.push_back(std::move(lo));
      next.push_back(std::move(hi));
    }
    cells = std::move(next);
  }
  std::string name = (base == 0 ? std::string("sliced box")
                                : cellforge::detail::cat("sliced prism ", std::to_string(base))) +
                     (diagonal ? " (diagonal wall)" : "") + ", " + std::to_string(cuts) + " cuts #" +
                     std::to_string(seed);
  sample_model m = convex_cells_model(cells, std::move(name));
  // Well shaped: no edge shorter than 3 % of the size.
  for (const auto& e : m.wire.edges)
    if (glm::length(m.wire.points[e[0]] - m.wire.points[e[1]]) < 0.03 * size) return std::nullopt;
  return m;
}

/// A roof on a box, two volumes: kind 0 a triangular prism (ridge anywhere over the box), 1 a
/// trapezoid prism, 2 a wedge (one roof side flush with a wall). The roof's ends lie in the
/// box's end walls, so the square between them is a face no reading can drop (its edges at the
/// ends would otherwise join two coplanar faces). Random sizes from `seed`. O(1).
template <class = void>
sample_model roof_on_box(int kind, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x726f6f6600000000u};
  const double a = rng.uniform(0.8, 2.0), b = rng.uniform(0.8, 2.5), c = rng.uniform(0.5, 1.5),
               h = rng.uniform(0.4, 1.2);
  std::vector<glm::dvec3> box, roof;
  for (unsigned k = 0; k < 8; ++k)
    box.push_back({(k & 1u) ? a : 0.0, (k & 2u) ? b : 0.0, (k & 4u) ? c : 0.0});
  std::vector<glm::dvec2> section{{0, c}, {a, c}};  // (x, z) along y
  std::string what;
  if (kind == 0) {
    section.push_back({rng.uniform(0.2, 0.8) * a, c + h});
    what = "gable roof";
  } else if (kind == 1) {
    const double l = rng.uniform(0.15, 0.4) * a, r = rng.uniform(0.6, 0.85) * a;
    section.push_back({r, c + h});
    section.push_back({l, c + h});
    what = "hipped-section roof";
  } else {
    section.push_back({a, c + h});
    what = "wedge roof";
  }
  for (const auto& q : section)
    for (const double y : {0.0, b}) roof.push_back({q.x, y, q.y});
  return convex_cells_model({box, roof},
                            cellforge::detail::cat("box with a ", what, " #", std::to_string(seed)));
}

/// A rectangular frame of bars (genus `holes`, 1 or 2): an nx × ny ring of lattice cells (a
/// middle bar across when holes = 2), one or two cells thick, each bar its own volume; a corner
/// cell is a block of its own or belongs to one of its two bars at random, so bars meet at
/// walls across the frame. Two holes: wireframe_to_cells reads the holes as cells (their
/// mouths continue the bars' faces; docs/sketch.md), so the sweep draws one. O(cells).
/// O(cells).
template <class = void>
sample_model bar_frame(std::size_t holes, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x6672616d65000000u};
  holes = std::clamp<std::size_t>(holes, 1, 2);
  const std::size_t nx = holes == 2 ? 5 : 3 + detail::below(3, rng), ny = 3 + detail::below(3, rng),
                    nz = 1 + detail::below(2, rng);
  voxel_layout l =
      empty_layout(detail::random_coords(nx, 0.3, 1.2, rng), detail::random_coords(ny, 0.3, 1.2, rng),
                   detail::random_coords(nz, 0.3, 0.8, rng));
  const std::size_t mid = nx / 2;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        const bool row = j == 0 || j + 1 == ny, column = i == 0 || i + 1 == nx || (holes == 2 && i == mid);
        if (!row && !column) continue;
        // Bars: rows 1 (bottom) and 2 (top), split at the middle bar (+10 right of it), 20 + the
        // column index for columns. A cell where bars cross goes to one of them at random.
        const int row_bar = (j == 0 ? 1 : 2) + (holes == 2 && i > mid ? 10 : 0),
                  column_bar = 20 + static_cast<int>(i);
        if (k > 0) {
          l.at(i, j, k) = l.at(i, j, 0);
        } else if (row && column) {
          const double u = rng.uniform(0, 1);  // a third of the corners are blocks of their own
          l.at(i, j, k) = u < 0.33                               ? 100 + static_cast<int>(i + nx * j)
                          : u < 0.66                             ? column_bar
                          : (holes == 2 && i == mid && u < 0.83) ? row_bar + 10
                                                                 : row_bar;
        } else {
          l.at(i, j, k) = row ? row_bar : column_bar;
        }
      }
  std::map<int, int> compact;  // labels 1..bars, as make_voxel_model wants them
  for (auto& x : l.labels)
    if (x != 0) x = compact.insert({x, static_cast<int>(compact.size()) + 1}).first->second;
  return make_voxel_model(l, cellforge::detail::cat("frame of bars, ", std::to_string(holes), " hole",
                                                    (holes == 2 ? "s" : ""), " #", std::to_string(seed)));
}

/// A block split into boxes by random guillotine cuts along lattice planes (each box its own
/// volume: walls ending on walls), or, with `every_cell`, a random face-connected set of
/// lattice cells whose union is a 2-manifold solid, every cell its own volume; nullopt when the
/// set is not. Random widths from `seed`. O(cells).
template <class = void>
std::optional<sample_model> cell_block(std::size_t nx, std::size_t ny, std::size_t nz, bool every_cell,
                                       std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x63656c6c00000000u};
  voxel_layout l =
      empty_layout(detail::random_coords(nx, 0.4, 1.4, rng), detail::random_coords(ny, 0.4, 1.4, rng),
                   detail::random_coords(nz, 0.4, 1.4, rng));
  int next = 1;
  if (every_cell) {
    const std::size_t count = 2 + detail::below(nx * ny * nz - 1, rng);
    std::vector<std::array<std::size_t, 3>> grown{
        {detail::below(nx, rng), detail::below(ny, rng), detail::below(nz, rng)}};
    l.at(grown[0][0], grown[0][1], grown[0][2]) = next++;
    for (std::size_t tries = 0; grown.size() < count && tries < 50 * count; ++tries) {
      auto c = grown[detail::below(grown.size(), rng)];
      const std::size_t axis = detail::below(3, rng);
      const std::array<std::size_t, 3> n{nx, ny, nz};
      if (rng.uniform(0, 1) < 0.5) {
        if (c[axis] == 0) continue;
        --c[axis];
      } else {
        if (c[axis] + 1 >= n[axis]) continue;
        ++c[axis];
      }
      if (l.at(c[0], c[1], c[2]) != 0) continue;
      l.at(c[0], c[1], c[2]) = next++;
      grown.push_back(c);
    }
    voxel_layout solid = l;
    for (auto& x : solid.labels) x = x != 0 ? 1 : 0;
    if (detail::voxel_solid_genus(solid) != 0) return std::nullopt;
  } else {
    // Guillotine: split a box of cells at a random lattice plane until it is one cell or stops.
    std::vector<std::array<std::size_t, 6>> stack{{0, nx, 0, ny, 0, nz}};
    while (!stack.empty()) {
      const auto box = stack.back();
      stack.pop_back();
      std::vector<std::size_t> axes;
      for (std::size_t a = 0; a < 3; ++a)
        if (box[2 * a + 1] - box[2 * a] > 1) axes.push_back(a);
      if (!axes.empty() &&
          (box == std::array<std::size_t, 6>{0, nx, 0, ny, 0, nz} || rng.uniform(0, 1) < 0.7)) {
        const std::size_t a = axes[detail::below(axes.size(), rng)];
        const std::size_t at = box[2 * a] + 1 + detail::below(box[2 * a + 1] - box[2 * a] - 1, rng);
        auto first = box, second = box;
        first[2 * a + 1] = at, second[2 * a] = at;
        stack.push_back(first), stack.push_back(second);
        continue;
      }
      for (std::size_t k = box[4]; k < box[5]; ++k)
        for (std::size_t j = box[2]; j < box[3]; ++j)
          for (std::size_t i = box[0]; i < box[1]; ++i) l.at(i, j, k) = next;
      ++next;
    }
  }
  return make_voxel_model(l, cellforge::detail::cat(std::string(every_cell ? "cells" : "guillotine block"),
                                                    " ", std::to_string(nx), "x", std::to_string(ny), "x",
                                                    std::to_string(nz), " #", std::to_string(seed)));
}

/// Boxes that touch along edges or at vertices only (kind 0: two along an edge; 1: a box on
/// another along an edge; 2: a chain of three along edges; 3: two at a vertex; 4: four in a 3D
/// checkerboard, each pair along an edge; 5: a face-joined pair and a third box along an edge;
/// 6: a box and a triangular prism along an edge), each its own volume; random widths. O(1).
template <class = void>
sample_model touching_solids(int kind, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x746f756368000000u};
  const auto coords = [&](std::size_t n) { return detail::random_coords(n, 0.5, 1.5, rng); };
  const std::string tag = cellforge::detail::cat(" #", std::to_string(seed));
  if (kind == 6) {
    const double a = rng.uniform(0.6, 1.5), b = rng.uniform(0.6, 1.5), c = rng.uniform(0.6, 1.5);
    std::vector<glm::dvec3> box, prism;
    for (unsigned k = 0; k < 8; ++k)
      box.push_back({(k & 1u) ? a : 0.0, (k & 2u) ? b : 0.0, (k & 4u) ? c : 0.0});
    // The prism's triangle has a corner at (a, b) and lies in the quadrant beyond it.
    const std::vector<glm::dvec2> tri{{a, b},
                                      {a + rng.uniform(0.6, 1.4), b + rng.uniform(0.1, 0.5)},
                                      {a + rng.uniform(0.1, 0.5), b + rng.uniform(0.6, 1.4)}};
    for (const auto& q : tri)
      for (const double z : {0.0, c}) prism.push_back({q.x, q.y, z});
    return convex_cells_model({box, prism}, cellforge::detail::cat("box and prism along an edge", tag));
  }
  const std::array<std::array<std::size_t, 3>, 7> lattice{
      {{2, 2, 1}, {2, 1, 2}, {3, 3, 1}, {2, 2, 2}, {2, 2, 2}, {3, 2, 1}, {1, 1, 1}}};
  const auto n = lattice[static_cast<std::size_t>(kind)];
  voxel_layout l = empty_layout(coords(n[0]), coords(n[1]), coords(n[2]));
  std::string what;
  switch (kind) {
    case 0:
      l.at(0, 0, 0) = 1, l.at(1, 1, 0) = 2, what = "two boxes along an edge";
      break;
    case 1:
      l.at(0, 0, 0) = 1, l.at(1, 0, 1) = 2, what = "a box on a box along an edge";
      break;
    case 2:
      l.at(0, 0, 0) = 1, l.at(1, 1, 0) = 2, l.at(2, 2, 0) = 3, what = "three boxes in a chain of edges";
      break;
    case 3:
      l.at(0, 0, 0) = 1, l.at(1, 1, 1) = 2, what = "two boxes at a vertex";
      break;
    case 4:
      l.at(0, 0, 0) = 1, l.at(1, 1, 0) = 2, l.at(1, 0, 1) = 3, l.at(0, 1, 1) = 4,
                 what = "3D checkerboard of four boxes";
      break;
    default:
      l.at(0, 0, 0) = 1, l.at(1, 0, 0) = 2, l.at(2, 1, 0) = 3,
                 what = "two joined boxes and one along an edge";
      break;
  }
  return make_voxel_model(l, what + tag);
}

/// A faceted solid of revolution (a ring stack, samples/wireframe_models.hpp) of n-gon rings:
/// kind 0 a barrel or vase (random radii, planar caps), 1 a spindle (cone apexes), 2 a cylinder
/// cut into 2..4 volumes by walls, 3 a twisted stack of triangle bands, 4 a UV sphere. Its rings
/// are planar cycles that are no faces (but the walls of kind 2); every ring bends the profile,
/// so no two side faces are coplanar. O(rings · n).
template <class = void>
sample_model revolved_solid(int kind, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x7265766f6c000000u};
  const std::string tag = cellforge::detail::cat(" #", std::to_string(seed));
  if (kind == 4) {
    const std::size_t slices = 5 + detail::below(8, rng), stacks = 3 + detail::below(5, rng);
    sample_model m = sample_uv_sphere(slices, stacks);
    m.name = cellforge::detail::cat("uv sphere ", std::to_string(slices), "x", std::to_string(stacks), tag);
    return m;
  }
  ring_stack s;
  s.n = 5 + detail::below(kind == 3 ? 10 : 16, rng);
  const std::size_t rings = kind == 2 ? 3 + detail::below(3, rng) : 2 + detail::below(4, rng);
  double z = 0;
  for (std::size_t r = 0; r < rings; ++r) {
    s.height.push_back(z);
    z += rng.uniform(0.3, 1.0);
    s.radius.push_back(kind == 2 ? 1.0 : rng.uniform(0.5, 1.5));
  }
  if (kind != 2)  // every ring bends the profile: radii alternate around their neighbours' mean
    for (std::size_t r = 1; r + 1 < rings; ++r) {
      const double mid = 0.5 * (s.radius[r - 1] + s.radius[r + 1]);
      if (std::abs(s.radius[r] - mid) < 0.15) s.radius[r] = mid + (s.radius[r] >= mid ? 0.15 : -0.15);
    }
  if (kind == 1) s.bottom = -rng.uniform(0.3, 1.0), s.top = z + rng.uniform(0.0, 0.7);
  if (kind == 2) {
    for (std::size_t r = 1; r + 1 < rings; ++r) s.walls.push_back(r);
    if (rng.uniform(0, 1) < 0.5) s.top = z - 1.0 + rng.uniform(0.3, 1.0);  // a cone roof on the last ring
    if (s.top && *s.top <= s.height.back()) s.top = s.height.back() + 0.5;
  }
  if (kind == 3) {
    s.triangles = true;
    for (std::size_t r = 0; r < rings; ++r)
      s.twist.push_back(std::numbers::pi / static_cast<double>(s.n) * static_cast<double>(r));
  }
  static const char* what[] = {"barrel", "spindle", "walled cylinder", "twisted stack"};
  return make_ring_stack(s, cellforge::detail::cat(std::string(what[kind]), " ", std::to_string(s.n),
                                                   "-gon, ", std::to_string(rings), " rings", tag));
}

}  // namespace cellforge::samples
