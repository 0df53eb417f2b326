// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample skeletons for tests, examples and benchmarks (not included by cellforge.hpp): node
/// lattices, complete graphs on a sphere, the Petersen graph, Möbius ladders, rings, a
/// figure-eight, random trees with branch angles and clearance that a tube mesh can honour,
/// and neuron-like trees (a soma, dense thin dendrites, close branch points). Every generator
/// is deterministic for its arguments.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <numbers>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/tubes/skeleton.hpp"

namespace cellforge::samples {

namespace detail {
template <Point3 P>
void add_node(skeleton<P>& s, const glm::dvec3& p, double r) {
  s.points.push_back(from_dvec3<P>(p));
  s.radii.push_back(r);
}
template <Point3 P>
void add_edge(skeleton<P>& s, std::size_t a, std::size_t b) {
  s.edges.push_back({static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b)});
}

/// Refuses a generator's arguments before anything is allocated: each count below its smallest
/// value, or a skeleton of more than 10^8 nodes or edges (some GB of skeleton, and a tube mesh
/// of it would need some hundred GB). Counts come in as doubles so that products cannot overflow.
template <class = void>
void require_skeleton(const char* what, std::initializer_list<std::pair<const char*, double>> counts,
                      double smallest, double nodes, double edges) {
  for (const auto& [name, value] : counts)
    if (!(value >= smallest))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat(std::string(what), ": ", name, " must be at least ",
                                         std::to_string(static_cast<long long>(smallest)), ", got ",
                                         std::to_string(static_cast<long long>(value))));
  constexpr double limit = 1e8;
  if (nodes > limit || edges > limit)
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(what), ": the skeleton would have about ",
                                       std::to_string(nodes), " nodes and ", std::to_string(edges),
                                       " edges, more than the 10^8 a sample may have; make it smaller"));
}
/// The distance between segments p1q1 and p2q2: their closest points with clamped parameters
/// (as in Ericson's Real-Time Collision Detection). O(1).
template <class = void>
double segment_distance(glm::dvec3 p1, glm::dvec3 q1, glm::dvec3 p2, glm::dvec3 q2) {
  const glm::dvec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r), c = glm::dot(d1, r),
               b = glm::dot(d1, d2), den = a * e - b * b;
  double sp = den > 1e-300 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
  double tp = (b * sp + f) / e;
  if (tp < 0)
    tp = 0, sp = std::clamp(-c / a, 0.0, 1.0);
  else if (tp > 1)
    tp = 1, sp = std::clamp((b - c) / a, 0.0, 1.0);
  return glm::length(p1 + sp * d1 - (p2 + tp * d2));
}

/// A hash grid of cubic cells of side `cell` listing segment numbers, for the generators'
/// clearance tests. O(1) per cell visited.
struct segment_grid {
  double cell = 1;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  std::int64_t index(double x) const { return static_cast<std::int64_t>(std::floor(x / cell)); }
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    const auto q = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & 0x1FFFFF; };
    return q(x) | q(y) << 21 | q(z) << 42;
  }
  /// Calls visit(key) for every cell the box of a and b widened by `widen` meets, until it
  /// returns false (then returns false).
  template <class Visit>
  bool for_cells(const glm::dvec3& a, const glm::dvec3& b, double widen, Visit&& visit) const {
    const glm::dvec3 lo = glm::min(a, b) - widen, hi = glm::max(a, b) + widen;
    for (std::int64_t x = index(lo.x); x <= index(hi.x); ++x)
      for (std::int64_t y = index(lo.y); y <= index(hi.y); ++y)
        for (std::int64_t z = index(lo.z); z <= index(hi.z); ++z)
          if (!visit(key(x, y, z))) return false;
    return true;
  }
};
}  // namespace detail

/// The a × b × c node lattice with edges between axis neighbours (the seed's
/// `Lattice_10_8_3` is lattice(10, 8, 3)): every inner node a branch of valence up to 6.
/// O(abc).
template <Point3 P = glm::dvec3>
skeleton<P> lattice(int a, int b, int c, double spacing = 4, double radius = 0.5) {
  const double n = double(a) * b * c;
  detail::require_skeleton("lattice", {{"a", double(a)}, {"b", double(b)}, {"c", double(c)}}, 1, n, 3 * n);
  skeleton<P> s;
  const auto id = [&](int x, int y, int z) { return static_cast<std::size_t>(x + a * (y + b * z)); };
  for (int z = 0; z < c; ++z)
    for (int y = 0; y < b; ++y)
      for (int x = 0; x < a; ++x) detail::add_node(s, spacing * glm::dvec3(x, y, z), radius);
  for (int z = 0; z < c; ++z)
    for (int y = 0; y < b; ++y)
      for (int x = 0; x < a; ++x) {
        if (x + 1 < a) detail::add_edge(s, id(x, y, z), id(x + 1, y, z));
        if (y + 1 < b) detail::add_edge(s, id(x, y, z), id(x, y + 1, z));
        if (z + 1 < c) detail::add_edge(s, id(x, y, z), id(x, y, z + 1));
      }
  return s;
}

/// A ring of n nodes on a circle of radius `circle`. O(n).
template <Point3 P = glm::dvec3>
skeleton<P> ring(int n, double circle = 10, double radius = 0.5) {
  detail::require_skeleton("ring", {{"n", double(n)}}, 3, n, n);  // two nodes would join by two edges
  skeleton<P> s;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * i / n;
    detail::add_node(s, circle * glm::dvec3(std::cos(t), std::sin(t), 0), radius);
    detail::add_edge(s, i, (i + 1) % n);
  }
  return s;
}

/// The complete graph K_n with its nodes spread on a sphere of radius `sphere` (a Fibonacci
/// lattice). Its chords pass close to each other: for n = 8 the closest two non-adjacent ones
/// are 0.046 × `sphere` apart, so the default radius leaves them clear up to K8. O(n²).
template <Point3 P = glm::dvec3>
skeleton<P> complete_graph(int n, double sphere = 10, double radius = 0.15) {
  detail::require_skeleton("complete_graph", {{"n", double(n)}}, 2, n, 0.5 * n * (n - 1.0));
  skeleton<P> s;
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (2 * i + 1.0) / n, r = std::sqrt(1 - z * z),
                 t = i * std::numbers::pi * (3 - std::sqrt(5.0));
    detail::add_node(s, sphere * glm::dvec3(r * std::cos(t), r * std::sin(t), z), radius);
  }
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) detail::add_edge(s, i, j);
  return s;
}

/// The Petersen graph: an outer pentagon, spokes, and an inner pentagram whose nodes sit at
/// different heights so that its crossing edges pass 0.13 × `size` apart. O(1).
template <Point3 P = glm::dvec3>
skeleton<P> petersen(double size = 10, double radius = 0.4) {
  skeleton<P> s;
  for (int i = 0; i < 5; ++i) {
    const double t = 2 * std::numbers::pi * i / 5 + std::numbers::pi / 2;
    detail::add_node(s, size * glm::dvec3(std::cos(t), std::sin(t), 0), radius);
    constexpr double height[5] = {2, 1, 4, 0, 3};  // the order that keeps the star's edges furthest apart
    detail::add_node(s, size * glm::dvec3(0.5 * std::cos(t), 0.5 * std::sin(t), 0.3 + 0.15 * height[i]),
                     radius);
  }
  for (int i = 0; i < 5; ++i) {
    detail::add_edge(s, 2 * i, 2 * ((i + 1) % 5));
    detail::add_edge(s, 2 * i, 2 * i + 1);
    detail::add_edge(s, 2 * i + 1, 2 * ((i + 2) % 5) + 1);
  }
  return s;
}

/// The Möbius ladder on n nodes (n even): a ring of n with chords between opposite nodes
/// (the seed's `Mobius_16_16` stand-in is mobius_ladder(16)). O(n).
template <Point3 P = glm::dvec3>
skeleton<P> mobius_ladder(int n, double circle = 10, double radius = 0.4) {
  detail::require_skeleton("mobius_ladder", {{"n", double(n)}}, 4, 1.5 * n, 2.0 * n);
  if (n % 2 != 0)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("mobius_ladder: n must be even, got ", std::to_string(n)));
  skeleton<P> s = ring<P>(n, circle, radius);
  // Chords cross at the centre: lift alternate ones so that they clear each other.
  for (int i = 0; i < n / 2; ++i) {
    const glm::dvec3 a = to_dvec3(s.points[i]), b = to_dvec3(s.points[i + n / 2]);
    detail::add_node(s, 0.5 * (a + b) + glm::dvec3(0, 0, (i - (n / 2 - 1) / 2.0) * 4 * radius), radius);
    detail::add_edge(s, i, s.points.size() - 1);
    detail::add_edge(s, s.points.size() - 1, i + n / 2);
  }
  return s;
}

/// Two rings of n nodes sharing one node (a figure-eight: one branch of degree 4). O(n).
template <Point3 P = glm::dvec3>
skeleton<P> figure_eight(int n = 12, double circle = 5, double radius = 0.5) {
  detail::require_skeleton("figure_eight", {{"n", double(n)}}, 3, 2.0 * n, 2.0 * n);
  skeleton<P> s = ring<P>(n, circle, radius);
  const std::size_t first = s.points.size();
  for (int i = 1; i < n; ++i) {
    const double t = std::numbers::pi + 2 * std::numbers::pi * i / n;
    detail::add_node(s, glm::dvec3(2 * circle, 0, 0) + circle * glm::dvec3(std::cos(t), std::sin(t), 0),
                     radius);
  }
  detail::add_edge(s, 0, first);
  for (int i = 1; i + 1 < n; ++i) detail::add_edge(s, first + i - 1, first + i);
  detail::add_edge(s, first + n - 2, 0);
  return s;
}

/// A grid of u × v nodes on a Möbius band (the seed's `Mobius_16_16` stand-in is
/// mobius_grid(16, 16)): edges across and along the band, the last column joined to the
/// first turned over. O(uv).
template <Point3 P = glm::dvec3>
skeleton<P> mobius_grid(int u, int v, double circle = 40, double width = 18, double radius = 0.4) {
  const double n = double(u) * v;
  detail::require_skeleton("mobius_grid", {{"u", double(u)}, {"v", double(v)}}, 2, n,
                           2 * n);  // v - 1 divides
  skeleton<P> s;
  for (int i = 0; i < u; ++i)
    for (int j = 0; j < v; ++j) {
      const double t = 2 * std::numbers::pi * i / u, w = width * (2.0 * j / (v - 1) - 1);
      detail::add_node(s,
                       glm::dvec3((circle + w * std::cos(t / 2)) * std::cos(t),
                                  (circle + w * std::cos(t / 2)) * std::sin(t), w * std::sin(t / 2)),
                       radius);
    }
  const auto id = [&](int i, int j) { return static_cast<std::size_t>(i * v + j); };
  for (int i = 0; i < u; ++i)
    for (int j = 0; j < v; ++j) {
      if (j + 1 < v) detail::add_edge(s, id(i, j), id(i, j + 1));
      if (i + 1 < u)
        detail::add_edge(s, id(i, j), id(i + 1, j));
      else
        detail::add_edge(s, id(i, j), id(0, v - 1 - j));  // the half turn
    }
  return s;
}

/// The edge graph of an icosahedron of circumradius `size` (the seed's `polyhedron` stand-in):
/// 12 branches of valence 5, 30 edges, cycle rank 19. O(1).
template <Point3 P = glm::dvec3>
skeleton<P> icosahedron_edges(double size = 10, double radius = 0.5) {
  skeleton<P> s;
  const double g = (1 + std::sqrt(5.0)) / 2, scale = size / std::sqrt(1 + g * g);
  std::vector<glm::dvec3> p;
  for (int a = -1; a <= 1; a += 2)
    for (int b = -1; b <= 1; b += 2) {
      p.push_back(scale * glm::dvec3(0, a, b * g));
      p.push_back(scale * glm::dvec3(a, b * g, 0));
      p.push_back(scale * glm::dvec3(b * g, 0, a));
    }
  for (const glm::dvec3& q : p) detail::add_node(s, q, radius);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j)
      if (std::abs(glm::length(p[i] - p[j]) - 2 * scale) < 1e-9 * size) detail::add_edge(s, i, j);
  return s;
}

/// A curved chain of n nodes along a conical spiral (the seed's `eyespline` stand-in: a spline
/// through the eye). O(n).
template <Point3 P = glm::dvec3>
skeleton<P> spiral_chain(int n = 200, double size = 20, double radius = 0.4) {
  detail::require_skeleton("spiral_chain", {{"n", double(n)}}, 2, n, n);  // n - 1 divides
  skeleton<P> s;
  for (int i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / (n - 1), a = 3 * 2 * std::numbers::pi * t;
    detail::add_node(s, size * glm::dvec3((0.3 + t) * std::cos(a), (0.3 + t) * std::sin(a), t), radius);
    if (i > 0) detail::add_edge(s, i - 1, i);
  }
  return s;
}

/// How random_tree grows a tree.
struct random_tree_options {
  std::size_t nodes = 100;
  double root_radius = 1.0;
  double taper = 0.93;  ///< a child's radius over its parent's
  double min_radius = 0.15;
  double min_branch_angle = 60;    ///< degrees between any two edges at a node
  double segment_over_radius = 6;  ///< segment length in parent radii (plus one root radius)
  double chain_probability = 0.6;  ///< a node continues as a chain (degree 2) rather than branching
};

/// A random tree: chains of degree-2 nodes and branches of 2–3 children, every angle between
/// two edges at a node at least `min_branch_angle`, and every segment clear of every other
/// non-adjacent one by 1.5 times the sum of their radii (a candidate that is not is not grown).
/// Deterministic for its seed. About O(n) while the tree is sparse, more as it crowds (a
/// hash grid answers the clearance test; candidates that fail are retried up to 30 times):
/// measured at -O1 1.7 s for 100,000 nodes, 4.5 s for 1,000 trees of 10 to 10,000 (1.45 million).
template <Point3 P = glm::dvec3>
skeleton<P> random_tree(std::uint64_t seed, const random_tree_options& o = {}) {
  detail::require_skeleton("random_tree", {{"nodes", static_cast<double>(o.nodes)}}, 1,
                           static_cast<double>(o.nodes), static_cast<double>(o.nodes));
  skeleton<P> s;
  cellforge::detail::splitmix rng{seed};
  std::vector<glm::dvec3> pos{glm::dvec3(0.0)};
  std::vector<double> rad{o.root_radius};
  std::vector<std::uint32_t> parent{0xFFFFFFFFu};
  const double cos_min = std::cos(o.min_branch_angle * std::numbers::pi / 180);
  // A hash grid of cells twice the shortest segment's length: each segment is listed in every
  // cell its box, widened by the largest clearance any test can ask for, meets; a test then
  // reads only the cells of the candidate's own box. Cells stay sparse however dense the tree.
  // Any cell size finds the same segments; at the shortest segment's length a segment was
  // listed in some hundred cells, three times the generator's time (1,000 trees: 13 s → 4.5 s).
  const double cell = 2 * (o.segment_over_radius * o.min_radius + o.root_radius);
  const double widest = 1.5 * 2 * std::max(o.root_radius, o.min_radius);
  struct segment {
    std::uint32_t a, b;
  };
  std::vector<segment> segments;
  detail::segment_grid grid{cell, {}};
  const auto for_cells = [&](const glm::dvec3& a, const glm::dvec3& b, double widen, auto&& visit) {
    return grid.for_cells(a, b, widen, visit);
  };
  const auto segment_distance = detail::segment_distance<>;
  const auto clear = [&](std::uint32_t from, const glm::dvec3& to, double r) {
    return for_cells(pos[from], to, 0.0, [&](std::uint64_t k) {
      const auto it = grid.cells.find(k);
      if (it == grid.cells.end()) return true;
      for (const std::uint32_t g : it->second) {
        const segment& other = segments[g];
        if (other.a == from || other.b == from) continue;  // adjacent: the angle rule covers it
        if (segment_distance(pos[from], to, pos[other.a], pos[other.b]) <
            1.5 * (r + std::max(rad[other.a], rad[other.b])))
          return false;
      }
      return true;
    });
  };
  std::vector<std::uint32_t> open{0};
  std::vector<glm::dvec3> heading{glm::dvec3(0, 0, 1)};
  while (!open.empty() && pos.size() < o.nodes) {
    const std::size_t pick = rng.next() % open.size();
    const std::uint32_t v = open[pick];
    const glm::dvec3 h = heading[pick];
    open[pick] = open.back(), heading[pick] = heading.back();
    open.pop_back(), heading.pop_back();
    const int children = v == 0                                    ? 3
                         : rng.uniform(0, 1) < o.chain_probability ? 1
                                                                   : 2 + static_cast<int>(rng.next() % 2);
    std::vector<glm::dvec3> used;
    if (parent[v] != 0xFFFFFFFFu) used.push_back(glm::normalize(pos[parent[v]] - pos[v]));
    for (int k = 0; k < children && pos.size() < o.nodes; ++k)
      for (int attempt = 0; attempt < 30; ++attempt) {
        const glm::dvec3 d =
            glm::normalize(h + (children == 1 ? 0.5 : 1.2) *
                                   glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
        if (!std::all_of(used.begin(), used.end(),
                         [&](const glm::dvec3& u) { return glm::dot(u, d) < cos_min; }))
          continue;
        const double r = std::max(o.min_radius, rad[v] * o.taper);
        const glm::dvec3 p = pos[v] + (o.segment_over_radius * rad[v] + o.root_radius) * d;
        if (!clear(v, p, r)) continue;
        const auto c = static_cast<std::uint32_t>(pos.size());
        pos.push_back(p), rad.push_back(r), parent.push_back(v);
        segments.push_back({v, c});
        for_cells(pos[v], p, widest, [&](std::uint64_t k) {
          grid.cells[k].push_back(static_cast<std::uint32_t>(segments.size() - 1));
          return true;
        });
        used.push_back(d);
        open.push_back(c), heading.push_back(d);
        break;
      }
  }
  for (std::size_t i = 0; i < pos.size(); ++i) detail::add_node(s, pos[i], rad[i]);
  for (const segment& g : segments) detail::add_edge(s, g.a, g.b);
  return s;
}

/// What a neuron-like skeleton looks like (lengths in µm, as SWC's).
struct neuron_options {
  std::size_t samples = 1000;    ///< nodes, soma included (the growth stops there, or when crowded)
  double soma_radius = 8;        ///< of the soma's middle sample; the soma is a chain of `soma_samples`
  int soma_samples = 5;          ///< along x, radii falling off as a sphere's (at least 1)
  int primary_dendrites = 6;     ///< leaving the soma's middle sample
  double primary_radius = 1.6;   ///< largest radius of a primary dendrite (each takes 0.6–1 of it)
  double min_radius = 0.1;       ///< thinnest dendrite
  double close_branching = 0.5;  ///< share of branch points 2–6 r after the previous one (else 10–40 r)
  double tortuosity = 0.25;      ///< random turn per sample (about this many radians at most)
  /// µm added to the 8 radii along the tree within which segments count as adjacent (exempt
  /// from the separation test). 0.8.0 used 2: thin dendrites then came back within r + r'.
  double adjacent_slack = 0;
};

/// A neuron-like tree, as reconstructions (SWC) have them: a soma of several samples, dendrites
/// sampled every 1–3 radii (every 0.25 µm at least), tapering from primary_radius to min_radius
/// over their branchings, branch points often 2–6 radii apart, siblings 30°–80° apart, tortuous
/// paths. Non-adjacent dendrites keep 1.5 times the sum of their radii apart (a hash grid tests
/// it; segments within 8 radii along the tree, plus adjacent_slack, are adjacent). Deterministic
/// for its seed.
/// About O(n) (a bounded search of the tree near each new sample).
template <Point3 P = glm::dvec3>
skeleton<P> neuron(std::uint64_t seed, const neuron_options& o = {}) {
  detail::require_skeleton(
      "neuron",
      {{"samples", static_cast<double>(o.samples)}, {"soma_samples", static_cast<double>(o.soma_samples)}}, 1,
      static_cast<double>(o.samples), static_cast<double>(o.samples));
  if (!(o.soma_radius > 0 && o.primary_radius > 0 && o.min_radius > 0 && o.min_radius <= o.primary_radius &&
        o.primary_radius < o.soma_radius && std::isfinite(o.soma_radius)))
    throw error(error_category::invalid_input,
                "neuron: radii must be positive and finite, min_radius <= primary_radius < soma_radius");
  if (!(o.adjacent_slack >= 0 && std::isfinite(o.adjacent_slack)))
    throw error(error_category::invalid_input,
                cellforge::detail::cat("neuron: adjacent_slack must be finite and not negative, got ",
                                       std::to_string(o.adjacent_slack)));
  cellforge::detail::splitmix rng{seed};
  std::vector<glm::dvec3> pos;
  std::vector<double> rad;
  std::vector<std::vector<std::uint32_t>> adjacent;  // for the search of nodes near along the tree
  struct segment {
    std::uint32_t a, b;
  };
  std::vector<segment> segments;
  detail::segment_grid grid{3, {}};
  const auto for_cells = [&](const glm::dvec3& a, const glm::dvec3& b, double widen, auto&& visit) {
    return grid.for_cells(a, b, widen, visit);
  };
  const auto add = [&](const glm::dvec3& p, double r) {
    pos.push_back(p), rad.push_back(r), adjacent.emplace_back();
    return static_cast<std::uint32_t>(pos.size() - 1);
  };
  const auto join = [&](std::uint32_t a, std::uint32_t b, bool listed = true) {
    adjacent[a].push_back(b), adjacent[b].push_back(a);
    segments.push_back({a, b});
    if (!listed) return;
    // Listed with its own clearance: a query widened by the other's finds every pair closer
    // than 1.5 (r + r') (boxes are never farther apart than their segments).
    for_cells(pos[a], pos[b], 1.5 * std::max(rad[a], rad[b]), [&](std::uint64_t k) {
      grid.cells[k].push_back(static_cast<std::uint32_t>(segments.size() - 1));
      return true;
    });
  };
  const auto segment_distance = detail::segment_distance<>;
  // Nodes within `reach` of v along the tree (a bounded search): their segments are adjacent.
  std::vector<std::uint32_t> near, stack;
  std::vector<double> along;
  std::vector<std::uint32_t> seen_at;  // per node: the stamp of the last search that saw it
  std::uint32_t stamp = 0;
  const auto near_along_tree = [&](std::uint32_t v, double reach) {
    ++stamp;
    seen_at.resize(pos.size(), 0);
    near.clear(), stack.assign(1, v), along.assign(1, 0.0);
    seen_at[v] = stamp;
    while (!stack.empty()) {
      const std::uint32_t u = stack.back();
      const double d = along.back();
      stack.pop_back(), along.pop_back();
      near.push_back(u);
      for (const std::uint32_t w : adjacent[u]) {
        const double dw = d + glm::length(pos[w] - pos[u]);
        if (seen_at[w] == stamp || dw > reach) continue;
        seen_at[w] = stamp;
        stack.push_back(w), along.push_back(dw);
      }
    }
    std::sort(near.begin(), near.end());
  };
  // The soma (its samples' segments are not in the grid): a dendrite never comes nearer its
  // axis than it was, once within its radius and the clearance.
  const glm::dvec3 soma_ends[2] = {{-0.7 * o.soma_radius, 0, 0}, {0.7 * o.soma_radius, 0, 0}};
  const auto clear = [&](std::uint32_t from, const glm::dvec3& to, double r) {
    const double now = segment_distance(pos[from], pos[from], soma_ends[0], soma_ends[1]);
    if (segment_distance(pos[from], to, soma_ends[0], soma_ends[1]) < std::min(now, o.soma_radius + 1.5 * r))
      return false;
    near_along_tree(from, 8 * std::max(r, rad[from]) + o.adjacent_slack);
    return for_cells(pos[from], to, 1.5 * r, [&](std::uint64_t k) {
      const auto it = grid.cells.find(k);
      if (it == grid.cells.end()) return true;
      for (const std::uint32_t g : it->second) {
        const segment& other = segments[g];
        if (std::binary_search(near.begin(), near.end(), other.a) ||
            std::binary_search(near.begin(), near.end(), other.b))
          continue;
        if (segment_distance(pos[from], to, pos[other.a], pos[other.b]) <
            1.5 * (r + std::max(rad[other.a], rad[other.b])))
          return false;
      }
      return true;
    });
  };
  const auto random_unit = [&] {
    while (true) {
      const glm::dvec3 d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      const double l = glm::length(d);
      if (l > 0.1 && l <= 1) return d / l;
    }
  };
  // The soma: samples along x, the middle one the largest, as a sphere's cross-sections.
  const double rs = o.soma_radius;
  const int half = (o.soma_samples - 1) / 2;
  const std::uint32_t soma = add(glm::dvec3(0.0), rs);
  for (int side = -1; side <= 1; side += 2) {
    std::uint32_t prev = soma;
    for (int k = 1; k <= half && pos.size() < o.samples; ++k) {
      const double x = 0.7 * rs * k / half;
      const std::uint32_t v = add(glm::dvec3(side * x, 0, 0), 0.9 * std::sqrt(rs * rs - x * x));
      join(prev, v, false);
      prev = v;
    }
  }
  // Growing tips: the node, its heading, the direction it set out in, and the arc length
  // left before it branches.
  struct tip {
    std::uint32_t node;
    glm::dvec3 heading, base;
    double until_branch;
    glm::dvec3 sibling{0.0};  ///< the direction the sibling of the last branch point set out in
    double since_branch = 1e300;
  };
  std::vector<tip> open;
  // Close branch points come in pairs, not chains: after one, the next is far.
  const auto next_gap = [&](double r, bool close_allowed) {
    return r *
           (close_allowed && rng.uniform(0, 1) < o.close_branching ? rng.uniform(2, 6) : rng.uniform(10, 40));
  };
  std::vector<glm::dvec3> primaries;
  for (int k = 0; k < o.primary_dendrites && pos.size() < o.samples; ++k)
    for (int attempt = 0; attempt < 50; ++attempt) {
      const glm::dvec3 d = random_unit();
      // Clear of the soma's axis (its end caps) and of the other primaries.
      if (std::fabs(d.x) > 0.5) continue;
      if (!std::all_of(primaries.begin(), primaries.end(),
                       [&](const glm::dvec3& e) { return glm::dot(d, e) < std::cos(0.7); }))
        continue;
      const double r = o.primary_radius * rng.uniform(0.6, 1.0);
      const glm::dvec3 p = 1.05 * rs * d;
      primaries.push_back(d);
      const std::uint32_t v = add(p, r);
      join(soma, v, false);
      open.push_back({v, d, d, r * rng.uniform(10, 40)});  // no branch point beside the soma
      break;
    }
  while (!open.empty() && pos.size() < o.samples) {
    const std::size_t pick = rng.next() % open.size();
    tip t = open[pick];
    open[pick] = open.back();
    open.pop_back();
    const std::uint32_t v = t.node;
    const double r = rad[v];
    const bool branch = t.until_branch <= 0;
    const int children = branch ? 2 : 1;
    const double spread = rng.uniform(40, 90) * std::numbers::pi / 180;  // siblings' angle
    // A branch point soon after another branches across the first one's plane, as the
    // tubes there must (siblings of the two that ran side by side would overlap).
    const glm::dvec3 across = glm::cross(t.heading, t.sibling);
    const glm::dvec3 side = t.since_branch < 10 * r && glm::length(across) > 0.1
                                ? glm::normalize(across)
                                : glm::normalize(glm::cross(t.heading, random_unit()));
    std::vector<tip> grown;
    for (int k = 0; k < children && pos.size() < o.samples; ++k)
      for (int attempt = 0; attempt < 10; ++attempt) {
        glm::dvec3 d = t.heading;
        if (branch) {  // the siblings part by `spread` about the heading
          const double a = (k == 0 ? 0.5 : -0.5) * spread;
          d = std::cos(a) * t.heading + std::sin(a) * side;
        } else {  // a tortuous walk that keeps to its general direction
          d = glm::normalize(t.heading + o.tortuosity * random_unit() + 0.1 * (t.base - t.heading));
        }
        const double rc = std::max(o.min_radius, branch ? r * rng.uniform(0.7, 0.9) : r * 0.995);
        const double step = std::max(0.25, rc * rng.uniform(1, 3));
        const glm::dvec3 p = pos[v] + step * d;
        if (!clear(v, p, rc)) continue;
        const std::uint32_t c = add(p, rc);
        join(v, c);
        grown.push_back({c, d, branch ? d : t.base,
                         branch ? next_gap(rc, t.since_branch > 8 * r) : t.until_branch - step, t.sibling,
                         branch ? step : t.since_branch + step});
        break;
      }
    if (grown.size() == 2) grown[0].sibling = grown[1].heading, grown[1].sibling = grown[0].heading;
    for (const tip& g : grown) open.push_back(g);
  }
  skeleton<P> s;
  for (std::size_t i = 0; i < pos.size(); ++i) detail::add_node(s, pos[i], rad[i]);
  for (const segment& g : segments) detail::add_edge(s, g.a, g.b);
  return s;
}

}  // namespace cellforge::samples
