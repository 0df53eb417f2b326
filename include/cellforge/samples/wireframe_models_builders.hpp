// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample wireframe models (samples/wireframe_models.hpp): the builders: box unions on a lattice
/// (make_voxel_model), ring stacks (make_ring_stack), split edges, disjoint unions and transformed
/// copies.

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
#include "cellforge/samples/wireframe_models_core.hpp"

namespace cellforge::samples {

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

}  // namespace cellforge::samples
