// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample drawings (samples/drawings.hpp): one-volume solids for the sketch sweep, part 2:
/// normalons from voxel layouts (random blocks, skylines, notched blocks, through-slots), stairs
/// and quasi-normalons.

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
#include "cellforge/samples/drawings_polytopes.hpp"
#include "cellforge/samples/wireframe_models.hpp"

namespace cellforge::samples {

namespace detail {

/// Whether the corner shared by a 2×2×2 block of cells (bit dx + 2dy + 4dz set when full) is
/// a manifold point: the full cells and the empty ones each connected through faces. O(1).
template <class = void>
bool manifold_corner(unsigned mask) {
  const auto connected = [](unsigned set) {
    if (set == 0) return true;
    unsigned reached = set & (~set + 1u);
    for (bool grew = true; grew;) {
      grew = false;
      for (unsigned b = 0; b < 8; ++b)
        for (const unsigned d : {1u, 2u, 4u}) {
          const unsigned nb = 1u << (b ^ d);
          if ((reached >> b & 1u) != 0 && (set & nb) != 0 && (reached & nb) == 0) reached |= nb, grew = true;
        }
    }
    return reached == set;
  };
  return connected(mask) && connected(~mask & 0xFFu);
}

/// Full cells of a layout: label != 0; out of the lattice: empty. O(1).
template <class = void>
bool full_cell(const voxel_layout& l, std::ptrdiff_t i, std::ptrdiff_t j, std::ptrdiff_t k) {
  const auto nx = static_cast<std::ptrdiff_t>(l.xs.size()) - 1,
             ny = static_cast<std::ptrdiff_t>(l.ys.size()) - 1,
             nz = static_cast<std::ptrdiff_t>(l.zs.size()) - 1;
  if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return false;
  return l.labels[static_cast<std::size_t>(i + nx * (j + ny * k))] != 0;
}

/// What a layout's full cells make, when they make one 2-manifold solid: its genus (from the
/// Euler characteristic of the closed cubical set, 1 − genus for a solid with no cavity); -1
/// when some lattice point is not a manifold point (cells touching along an edge or at a
/// vertex only), the cells are not face-connected, or a cavity is enclosed. O(cells).
template <class = void>
int voxel_solid_genus(const voxel_layout& l) {
  const auto n = std::array<std::ptrdiff_t, 3>{static_cast<std::ptrdiff_t>(l.xs.size()) - 1,
                                               static_cast<std::ptrdiff_t>(l.ys.size()) - 1,
                                               static_cast<std::ptrdiff_t>(l.zs.size()) - 1};
  // Manifold corners, and χ = Σ over lattice points of the cubical cells they are the lowest
  // corner of, with sign (−1)^dim: a point is in the set when a cell around it is full, etc.
  std::ptrdiff_t chi = 0;
  for (std::ptrdiff_t k = 0; k <= n[2]; ++k)
    for (std::ptrdiff_t j = 0; j <= n[1]; ++j)
      for (std::ptrdiff_t i = 0; i <= n[0]; ++i) {
        unsigned mask = 0;
        for (unsigned b = 0; b < 8; ++b)
          if (full_cell(l, i - 1 + (b & 1), j - 1 + (b >> 1 & 1), k - 1 + (b >> 2 & 1))) mask |= 1u << b;
        if (!manifold_corner(mask)) return -1;
        // The cubical cell at (i,j,k) spanning the directions in `dirs` is in the set when one
        // of the full cells containing it is: cells (i - 1 + b) with b = 1 along every spanned
        // direction and 0/1 along the others.
        for (unsigned dirs = 0; dirs < 8; ++dirs) {
          bool in = false;
          for (unsigned b = 0; b < 8 && !in; ++b) {
            if ((b & dirs) != dirs) continue;
            in = (mask >> b & 1u) != 0;
          }
          if (in) chi += (std::popcount(dirs) % 2 == 0) ? 1 : -1;
        }
      }
  // Face connectivity of the full cells, and of the empty ones with the outside.
  const auto index = [&](std::ptrdiff_t i, std::ptrdiff_t j, std::ptrdiff_t k) {
    return static_cast<std::size_t>((i + 1) + (n[0] + 2) * ((j + 1) + (n[1] + 2) * (k + 1)));
  };
  std::vector<char> seen(static_cast<std::size_t>((n[0] + 2) * (n[1] + 2) * (n[2] + 2)), 0);
  const auto flood = [&](std::array<std::ptrdiff_t, 3> start, bool full) {
    std::size_t count = 0;
    std::vector<std::array<std::ptrdiff_t, 3>> todo{start};
    seen[index(start[0], start[1], start[2])] = 1;
    while (!todo.empty()) {
      const auto c = todo.back();
      todo.pop_back();
      ++count;
      for (std::size_t a = 0; a < 3; ++a)
        for (const std::ptrdiff_t s : {-1, 1}) {
          auto d = c;
          d[a] += s;
          if (d[a] < -1 || d[a] > n[a]) continue;
          if (seen[index(d[0], d[1], d[2])] || full_cell(l, d[0], d[1], d[2]) != full) continue;
          seen[index(d[0], d[1], d[2])] = 1;
          todo.push_back(d);
        }
    }
    return count;
  };
  const auto full =
      static_cast<std::size_t>(std::count_if(l.labels.begin(), l.labels.end(), [](int x) { return x != 0; }));
  if (full == 0) return -1;
  const std::size_t empty = seen.size() - full;
  if (flood({-1, -1, -1}, false) != empty) return -1;
  for (std::ptrdiff_t c = 0; c < n[0] * n[1] * n[2]; ++c)
    if (l.labels[static_cast<std::size_t>(c)] != 0) {
      if (flood({c % n[0], c / n[0] % n[1], c / (n[0] * n[1])}, true) != full) return -1;
      break;
    }
  return static_cast<int>(1 - chi);
}

/// Lattice coordinates from random widths in [lo, hi]. O(n).
template <class = void>
std::vector<double> random_coords(std::size_t cells, double lo, double hi, cellforge::detail::splitmix& rng) {
  std::vector<double> c{0.0};
  for (std::size_t i = 0; i < cells; ++i) c.push_back(c.back() + rng.uniform(lo, hi));
  return c;
}

/// A uniformly random index below n. O(1).
template <class = void>
std::size_t below(std::size_t n, cellforge::detail::splitmix& rng) {
  return static_cast<std::size_t>(rng.next() % n);
}

}  // namespace detail

/// A normalon solid (faces merged, one volume) with its genus, or nothing.
struct voxel_solid {
  sample_model model;
  int genus = 0;
};

/// The model of a layout's full cells as one merged solid when they make a 2-manifold solid
/// (detail::voxel_solid_genus) whose faces make_voxel_model can outline; nullopt otherwise.
/// O(cells log cells).
template <class = void>
std::optional<voxel_solid> voxel_solid_model(voxel_layout l, std::string name) {
  for (auto& x : l.labels) x = x != 0 ? 1 : 0;
  l.merge_faces = true;
  const int genus = detail::voxel_solid_genus(l);
  if (genus < 0) return std::nullopt;
  try {
    return voxel_solid{make_voxel_model(l, std::move(name)), genus};
  } catch (const error&) {
    return std::nullopt;  // a face outline touching itself at a vertex
  }
}

/// A random face-connected set of `count` cells grown in an nx × ny × nz lattice of random
/// widths, as a merged normalon solid; nullopt when the set is not a 2-manifold solid.
/// O(cells log cells).
template <class = void>
std::optional<voxel_solid> random_normalon(std::size_t nx, std::size_t ny, std::size_t nz, std::size_t count,
                                           std::uint64_t seed) {
  detail::require_lattice("random_normalon", nx, ny, nz);
  cellforge::detail::splitmix rng{seed ^ 0x6e6f726d616c6f6eu};
  // One draw per statement: argument order is the compiler's choice.
  std::vector<double> xs = detail::random_coords(nx, 0.5, 1.5, rng);
  std::vector<double> ys = detail::random_coords(ny, 0.5, 1.5, rng);
  std::vector<double> zs = detail::random_coords(nz, 0.5, 1.5, rng);
  voxel_layout l = empty_layout(std::move(xs), std::move(ys), std::move(zs));
  const std::size_t cells = nx * ny * nz;
  count = std::clamp<std::size_t>(count, 1, cells);
  std::vector<std::size_t> set{detail::below(cells, rng)};
  l.labels[set[0]] = 1;
  for (std::size_t guard = 0; set.size() < count && guard < 100 * cells; ++guard) {
    const std::size_t c = set[detail::below(set.size(), rng)];
    const std::size_t a = detail::below(3, rng);
    const std::array<std::size_t, 3> dim{nx, ny, nz};
    std::array<std::size_t, 3> q{c % nx, c / nx % ny, c / (nx * ny)};
    if (rng.next() & 1u) {
      if (q[a] + 1 >= dim[a]) continue;
      ++q[a];
    } else {
      if (q[a] == 0) continue;
      --q[a];
    }
    const std::size_t d = q[0] + nx * (q[1] + ny * q[2]);
    if (l.labels[d] != 0) continue;
    l.labels[d] = 1;
    set.push_back(d);
  }
  return voxel_solid_model(
      std::move(l), cellforge::detail::cat("random normalon ", std::to_string(nx), "x", std::to_string(ny),
                                           "x", std::to_string(nz), " #", std::to_string(seed)));
}

/// A skyline: an nx × ny grid of columns of random widths, each 1..max_height cells of random
/// heights tall, as a merged normalon solid. Where two diagonal columns both rise above the
/// other two of their 2 × 2 block (they would touch along an edge only) the lower of those
/// is raised; nullopt when the result still is no 2-manifold solid. O(cells log cells).
template <class = void>
std::optional<voxel_solid> random_skyline(std::size_t nx, std::size_t ny, std::size_t max_height,
                                          std::uint64_t seed) {
  max_height = std::max<std::size_t>(max_height, 1);
  detail::require_lattice("random_skyline", nx, ny, max_height);
  cellforge::detail::splitmix rng{seed ^ 0x736b796c696e6500u};
  std::vector<double> xs = detail::random_coords(nx, 0.5, 1.5, rng);
  std::vector<double> ys = detail::random_coords(ny, 0.5, 1.5, rng);
  std::vector<double> zs = detail::random_coords(max_height, 0.3, 1.0, rng);
  voxel_layout l = empty_layout(std::move(xs), std::move(ys), std::move(zs));
  std::vector<std::size_t> h(nx * ny);
  for (auto& x : h) x = 1 + detail::below(max_height, rng);
  for (bool again = true; again;) {  // heights only grow, to at most max_height: ends
    again = false;
    for (std::size_t j = 0; j + 1 < ny; ++j)
      for (std::size_t i = 0; i + 1 < nx; ++i) {
        std::size_t &a = h[i + nx * j], &b = h[i + 1 + nx * (j + 1)], &c = h[i + 1 + nx * j],
                    &d = h[i + nx * (j + 1)];
        if (std::min(a, b) > std::max(c, d)) {
          (c < d ? c : d) = std::min(a, b);
          again = true;
        } else if (std::min(c, d) > std::max(a, b)) {
          (a < b ? a : b) = std::min(c, d);
          again = true;
        }
      }
  }
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      for (std::size_t k = 0; k < h[i + nx * j]; ++k) l.at(i, j, k) = 1;
  return voxel_solid_model(
      std::move(l), cellforge::detail::cat("skyline ", std::to_string(nx), "x", std::to_string(ny), " #",
                                           std::to_string(seed)));
}

/// A 3 × 3 × 3 block of random widths with `notches` random edge or corner cells cut away
/// (cells with at least two coordinates on the block's outside); nullopt when the result is
/// not a 2-manifold solid. O(1).
template <class = void>
std::optional<voxel_solid> notched_block(std::size_t notches, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x6e6f746368000000u};
  std::vector<double> xs = detail::random_coords(3, 0.4, 1.6, rng);
  std::vector<double> ys = detail::random_coords(3, 0.4, 1.6, rng);
  std::vector<double> zs = detail::random_coords(3, 0.4, 1.6, rng);
  voxel_layout l = empty_layout(std::move(xs), std::move(ys), std::move(zs));
  std::fill(l.labels.begin(), l.labels.end(), 1);
  std::vector<std::size_t> candidates;
  for (std::size_t c = 0; c < 27; ++c) {
    const std::size_t i = c % 3, j = c / 3 % 3, k = c / 9;
    if ((i != 1) + (j != 1) + (k != 1) >= 2) candidates.push_back(c);
  }
  for (std::size_t t = 0; t < notches && !candidates.empty(); ++t) {
    const std::size_t pick = detail::below(candidates.size(), rng);
    l.labels[candidates[pick]] = 0;
    candidates.erase(candidates.begin() + static_cast<std::ptrdiff_t>(pick));
  }
  return voxel_solid_model(std::move(l), cellforge::detail::cat("notched block ", std::to_string(notches),
                                                                " #", std::to_string(seed)));
}

/// A staircase of `steps` steps (1..1000) of random treads and risers, extruded across:
/// 2·(2·steps + 2) vertices, 3·(2·steps + 2) edges, 2·steps + 4 faces (two staircase
/// polygons). O(steps²).
template <class = void>
sample_model sample_stairs(std::size_t steps, std::uint64_t seed) {
  if (steps < 1 || steps > 1000)
    throw error(error_category::invalid_input, "sample_stairs: steps must be in 1..1000");
  cellforge::detail::splitmix rng{seed ^ 0x7374616972730000u};
  std::vector<double> x{0.0}, h{0.0};  // step i spans [x[i], x[i+1]], its top at h[i+1]
  for (std::size_t s = 0; s < steps; ++s) {
    x.push_back(x.back() + rng.uniform(0.6, 1.4));
    h.push_back(h.back() + rng.uniform(0.4, 1.0));
  }
  std::vector<glm::dvec2> p{{0, 0}, {x[steps], 0}, {x[steps], h[steps]}};
  for (std::size_t i = steps; i-- > 0;) {
    p.push_back({x[i], h[i + 1]});
    if (i > 0) p.push_back({x[i], h[i]});
  }
  return extruded_polygon(
      p, rng.uniform(1.0, 3.0),
      cellforge::detail::cat("stairs ", std::to_string(steps), " #", std::to_string(seed)));
}

/// A block of random widths with `holes` (1..4) rectangular through-slots along y (genus
/// `holes`): its front and back faces have holes. O(1).
template <class = void>
voxel_solid through_slot(std::size_t holes, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x736c6f7400000000u};
  holes = std::clamp<std::size_t>(holes, 1, 4);
  const std::size_t nx = holes >= 2 ? 5 : 3, nz = holes >= 3 ? 5 : 3, ny = 1 + detail::below(2, rng);
  std::vector<double> xs = detail::random_coords(nx, 0.3, 1.5, rng);
  std::vector<double> ys = detail::random_coords(ny, 0.5, 2.0, rng);
  std::vector<double> zs = detail::random_coords(nz, 0.3, 1.5, rng);
  voxel_layout l = empty_layout(std::move(xs), std::move(ys), std::move(zs));
  std::fill(l.labels.begin(), l.labels.end(), 1);
  const std::array<std::array<std::size_t, 2>, 4> at{{{1, 1}, {3, 1}, {1, 3}, {3, 3}}};
  for (std::size_t h = 0; h < holes; ++h)
    for (std::size_t j = 0; j < ny; ++j) l.at(at[h][0], j, at[h][1]) = 0;
  auto s = voxel_solid_model(std::move(l), cellforge::detail::cat("through slot ", std::to_string(holes),
                                                                  " #", std::to_string(seed)));
  if (!s)
    throw error(error_category::invalid_input, "through_slot: not a manifold solid (a generator fault)");
  return *s;
}

/// The polygon with the corners in `which` cut off: each replaced by two points at `size`
/// (a fraction 0..0.5 of the shorter side at it) along its two sides. O(n).
template <class = void>
std::vector<glm::dvec2> chamfered_corners(const std::vector<glm::dvec2>& p, const std::vector<bool>& which,
                                          double size) {
  std::vector<glm::dvec2> out;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (i >= which.size() || !which[i]) {
      out.push_back(p[i]);
      continue;
    }
    const glm::dvec2 a = p[(i + n - 1) % n], b = p[i], c = p[(i + 1) % n];
    const double d = size * std::min(glm::length(a - b), glm::length(c - b));
    out.push_back(b + d * glm::normalize(a - b));
    out.push_back(b + d * glm::normalize(c - b));
  }
  return out;
}

/// A random quasi-normalon (docs/sketch.md): kind 0 a block with 1..4 chamfered edges, 1 a
/// block with 1..4 corners cut off, 2 a wedge, 3 a ramp, 4 an L or T block with oblique
/// chamfers, 5 a gable house (its ridge hangs on oblique edges only: not a quasi-normalon by
/// the flag's rule). Random sizes from `seed`. O(1).
template <class = void>
sample_model random_quasi_normalon(int kind, std::uint64_t seed) {
  cellforge::detail::splitmix rng{seed ^ 0x7175617369000000u};
  const double a = rng.uniform(1, 3), b = rng.uniform(1, 3), c = rng.uniform(1, 3);
  const std::string tag = cellforge::detail::cat(" #", std::to_string(seed));
  const auto pick_corners = [&](std::size_t n, std::size_t lo, std::size_t hi,
                                const std::vector<bool>& allowed) {
    std::vector<bool> which(n, false);
    const std::size_t k = lo + detail::below(hi - lo + 1, rng);
    for (std::size_t t = 0; t < 4 * k; ++t) {
      const std::size_t i = detail::below(n, rng);
      if (allowed[i] && std::count(which.begin(), which.end(), true) < static_cast<std::ptrdiff_t>(k))
        which[i] = true;
    }
    if (std::count(which.begin(), which.end(), true) == 0)
      for (std::size_t i = 0; i < n; ++i)
        if (allowed[i]) {
          which[i] = true;
          break;
        }
    return which;
  };
  switch (kind) {
    case 0: {
      const std::vector<glm::dvec2> rect{{0, 0}, {a, 0}, {a, b}, {0, b}};
      const std::vector<bool> which = pick_corners(4, 1, 4, std::vector<bool>(4, true));
      const double size = rng.uniform(0.15, 0.45);
      return extruded_polygon(chamfered_corners(rect, which, size), c,
                              cellforge::detail::cat("chamfered block", tag));
    }
    case 1: {
      std::vector<glm::dvec3> pts;
      for (unsigned corner = 0; corner < 8; ++corner) {
        const glm::dvec3 q((corner & 1u) ? a : 0.0, (corner & 2u) ? b : 0.0, (corner & 4u) ? c : 0.0);
        if (rng.uniform(0, 1) < 0.4 || corner == 7) {
          for (int axis = 0; axis < 3; ++axis) {
            glm::dvec3 r = q;
            r[axis] += ((corner >> axis & 1u) ? -1.0 : 1.0) * rng.uniform(0.15, 0.45) * std::min({a, b, c});
            pts.push_back(r);
          }
        } else {
          pts.push_back(q);
        }
      }
      return convex_polytope_model(pts, cellforge::detail::cat("corner-cut block", tag));
    }
    case 2:
      return extruded_polygon({{0, 0}, {a, 0}, {0, b}}, c, cellforge::detail::cat("wedge", tag));
    case 3:
      return extruded_polygon({{0, 0}, {a + 1, 0}, {a + 1, b}, {rng.uniform(0.3, 0.8) * (a + 1), b}}, c,
                              cellforge::detail::cat("ramp", tag));
    case 4: {
      const int letter = static_cast<int>(detail::below(2, rng));
      const std::vector<glm::dvec2> p = letter_footprint(letter, 0.0, rng);
      // Convex corners only (counter-clockwise footprints: a left turn).
      std::vector<bool> convex(p.size());
      for (std::size_t i = 0; i < p.size(); ++i) {
        const glm::dvec2 u = p[i] - p[(i + p.size() - 1) % p.size()], v = p[(i + 1) % p.size()] - p[i];
        convex[i] = u.x * v.y - u.y * v.x > 0;
      }
      const std::vector<bool> which = pick_corners(p.size(), 1, 3, convex);
      const double size = rng.uniform(0.2, 0.45);
      return extruded_polygon(
          chamfered_corners(p, which, size), c,
          cellforge::detail::cat(std::string(letter == 0 ? "chamfered L" : "chamfered T"), tag));
    }
    default:
      return extruded_polygon({{0, 0}, {a, 0}, {a, b}, {a / 2, b + rng.uniform(0.3, 1.2)}, {0, b}}, c,
                              cellforge::detail::cat("gable house", tag));
  }
}

}  // namespace cellforge::samples
