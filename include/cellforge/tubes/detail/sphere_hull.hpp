// SPDX-License-Identifier: MIT
#pragma once
// The convex hull of a few dozen points on one sphere (a tube junction's projected rings):
// incremental insertion over a flat triangle array with neighbour links, exact orient3d signs
// (filtered), no set-up beyond scratch buffers the caller keeps. Given the ring size, the
// points go in coarse to fine (one point of every ring, then each ring's gaps halved in turn),
// so that each new point only cuts the few faces near it; each finds a face it sees among the
// faces around an inserted neighbour on its ring (else scanning the newest faces first), grows
// the visible region over the links and cones it.
// It gives up (returns false) rather than guess: fewer than four points, a degenerate start,
// or a point that sees no face or ends up not on the hull; the caller then uses the general
// hull (algorithms/convex_hull.hpp), which reports such input properly.

#include <array>
#include <cstdint>
#include <new>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/core/predicates.hpp"

namespace cellforge::detail::tubes {

/// Scratch of sphere_hull, kept by the caller across junctions so that none allocates.
struct sphere_hull_scratch {
  struct tri {
    orient3d_plane plane;
    std::array<std::uint32_t, 3> v{};  // counter-clockwise seen from outside
    std::array<std::uint32_t, 3> n{};  // n[i]: the face across edge v[i] -> v[i + 1]
    std::uint32_t mark = 0;            // insertion stamp: tested in this round
    bool visible = false, alive = false;
  };
  std::vector<tri> faces;
  std::vector<std::uint32_t> stack, visible, by_start, by_end, order, near, incident, positions, gap_start;
  std::vector<std::array<std::uint32_t, 2>> horizon;  // (visible face, edge)
  std::vector<std::uint8_t> used;
};

/// orient3d's exact sign, out of line: rarely needed, and large. O(1).
template <class = void>
[[gnu::noinline]] int sphere_hull_exact(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                                        const glm::dvec3& q) {
  return orient3d_exact(a, b, c, q);
}

/// The sign of q against the plane through a, b, c (prepared), exact. The filter is inlined
/// here: called out of line, it was 15% of the hull's instructions. O(1).
template <class = void>
[[gnu::flatten]] inline int sphere_hull_orient(const orient3d_plane& plane, const glm::dvec3& a,
                                               const glm::dvec3& b, const glm::dvec3& c,
                                               const glm::dvec3& q) {
  double value = 0;
  const int sgn = orient3d_filter(plane, q, value);
  return sgn != 0 ? sgn : sphere_hull_exact(a, b, c, q);
}

/// The positions 0 .. sides - 1 around a ring, coarse to fine: 0, then the middle of each gap
/// between positions already listed, breadth first; `gap_start[g]` is the listed position
/// that begins the gap position g splits (its neighbour on the ring). O(sides).
template <class = void>
void ring_order(std::uint32_t sides, std::vector<std::uint32_t>& positions,
                std::vector<std::uint32_t>& gap_start) {
  positions.assign(1, 0);
  gap_start.assign(1, 0);
  std::vector<std::array<std::uint32_t, 2>> gaps{{0, sides}};
  for (std::size_t g = 0; g < gaps.size(); ++g) {
    const auto [a, b] = gaps[g];
    if (b - a < 2) continue;
    const std::uint32_t j = (a + b) / 2;
    positions.push_back(j);
    gap_start.push_back(a);
    gaps.push_back({a, j});
    gaps.push_back({j, b});
  }
}

/// The hull triangles of `pts` (outward, counter-clockwise) into `out`, as input indices;
/// true when every point is a vertex of the hull. `ring_size` > 0: the first points are rings
/// of that many consecutive points each, in order around their circle (any points after the
/// last whole ring are inserted last, in input order). O(m²) worst case, about O(m) for a
/// junction's rings; m ≤ 65,535.
template <class = void>
bool sphere_hull(std::span<const glm::dvec3> pts, sphere_hull_scratch& s,
                 std::vector<std::array<std::uint32_t, 3>>& out, std::uint32_t ring_size = 0) {
  using tri = sphere_hull_scratch::tri;
  constexpr std::uint32_t none = 0xFFFFFFFFu;
  out.clear();
  const std::size_t m = pts.size();
  if (m < 4 || m > 65535) return false;
  // Insertion order, and for each point a ring neighbour inserted before it (none: scan).
  std::vector<std::uint32_t>&order = s.order, &near = s.near;
  order.resize(m);
  near.assign(m, none);
  const std::size_t rings = ring_size > 1 ? m / ring_size : 0;
  if (rings > 0 && s.positions.size() != ring_size) ring_order(ring_size, s.positions, s.gap_start);
  {
    std::size_t k = 0;
    for (std::size_t g = 0; g < (rings > 0 ? ring_size : 0); ++g)
      for (std::size_t r = 0; r < rings; ++r) {
        const auto base = static_cast<std::uint32_t>(r * ring_size);
        order[k++] = base + s.positions[g];
        if (g > 0) near[base + s.positions[g]] = base + s.gap_start[g];
      }
    for (std::size_t i = rings * ring_size; i < m; ++i) order[k++] = static_cast<std::uint32_t>(i);
  }
  const auto orient = [&](const tri& f, const glm::dvec3& q) {
    return sphere_hull_orient(f.plane, pts[f.v[0]], pts[f.v[1]], pts[f.v[2]], q);
  };
  // The scratch arrays keep their size across calls and are filled through counts: clearing
  // and pushing would value-initialise or call out of line for every element.
  const auto push = [](auto& v, std::size_t& count, const auto& x) {
    if (count == v.size()) v.resize(2 * count + 16);
    v[count++] = x;
  };
  auto& faces = s.faces;
  std::size_t nf = 0;
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (nf == faces.size()) faces.resize(2 * nf + 16);
    tri& t = faces[nf];
    // The plane is built in place: a copy through the stack stalls on store forwarding.
    ::new (static_cast<void*>(&t.plane)) orient3d_plane(prepare_orient3d(pts[a], pts[b], pts[c]));
    t.v = {a, b, c};
    t.mark = 0;
    t.visible = false;
    t.alive = true;
    return static_cast<std::uint32_t>(nf++);
  };
  // Start: the first three points in order and the first point off their plane (the last
  // point first: far from them, so the first tetrahedron is not flat).
  const std::uint32_t p0 = order[0], p1 = order[1], p2 = order[2];
  std::size_t d_at = 0;
  {
    tri probe;
    probe.plane = prepare_orient3d(pts[p0], pts[p1], pts[p2]);
    probe.v = {p0, p1, p2};
    const auto off = [&](std::size_t k) { return orient(probe, pts[order[k]]) != 0; };
    if (off(m - 1)) {
      d_at = m - 1;
    } else {
      for (std::size_t k = 3; k + 1 < m && d_at == 0; ++k)
        if (off(k)) d_at = k;
    }
    if (d_at == 0) return false;
  }
  std::vector<std::uint32_t>& incident = s.incident;  // per inserted point: a live face on it
  incident.resize(m);
  {
    const std::uint32_t d = order[d_at];
    tri probe;
    probe.plane = prepare_orient3d(pts[p0], pts[p1], pts[p2]);
    probe.v = {p0, p1, p2};
    std::uint32_t a = p0, b = p1, c = p2;
    if (orient(probe, pts[d]) > 0) std::swap(b, c);  // now orient(a, b, c, d) < 0
    // One call site besides the cone's: add is then inlined into both (-57 M instructions, 100k tree).
    const std::array<std::uint32_t, 3> start[4] = {{a, b, c}, {a, d, b}, {b, d, c}, {a, c, d}};
    for (const std::array<std::uint32_t, 3>& t : start) add(t[0], t[1], t[2]);
    for (std::uint32_t f = 0; f < 4; ++f)
      for (std::uint32_t i = 0; i < 3; ++i) {
        incident[faces[f].v[i]] = f;
        for (std::uint32_t g = 0; g < 4; ++g)
          for (std::uint32_t k = 0; k < 3; ++k)
            if (faces[g].v[k] == faces[f].v[(i + 1) % 3] && faces[g].v[(k + 1) % 3] == faces[f].v[i])
              faces[f].n[i] = g;
      }
  }
  s.by_start.assign(m, 0);
  s.by_end.assign(m, 0);
  for (std::size_t step = 3; step < m; ++step) {
    if (step == d_at) continue;
    const std::uint32_t p = order[step];
    const glm::dvec3& q = pts[p];
    const std::uint32_t stamp = p + 1;
    const auto judge = [&](tri& t) {
      t.mark = stamp;
      t.visible = orient(t, q) > 0;
      return t.visible;
    };
    const auto sees = [&](std::uint32_t f) { return judge(faces[f]); };
    // A face that p sees: around its inserted ring neighbour (a few faces), else newest first.
    std::uint32_t seen = none;
    if (near[p] != none) {
      const std::uint32_t a = near[p], f0 = incident[a];
      std::uint32_t f = f0;
      for (int turns = 0; turns < 64 && faces[f].alive; ++turns) {  // dead: a left the hull
        if (sees(f)) {
          seen = f;
          break;
        }
        const tri& t = faces[f];
        f = t.n[t.v[0] == a ? 0 : t.v[1] == a ? 1 : 2];  // the next face around a
        if (f == f0) break;
      }
    }
    for (std::size_t f = nf; seen == none && f-- > 0;)
      if (faces[f].alive && faces[f].mark != stamp && sees(static_cast<std::uint32_t>(f)))
        seen = static_cast<std::uint32_t>(f);
    if (seen == none) return false;  // inside or on the hull: not for this hull
    // The visible region (connected) and its horizon.
    std::size_t stacked = 0, visible = 0, horizon = 0;
    push(s.stack, stacked, seen);
    while (stacked > 0) {
      const std::uint32_t f = s.stack[--stacked];
      push(s.visible, visible, f);
      for (std::uint32_t i = 0; i < 3; ++i) {
        const std::uint32_t g = faces[f].n[i];
        if (faces[g].mark != stamp) {
          if (judge(faces[g])) {
            push(s.stack, stacked, g);
            continue;
          }
        }
        if (!faces[g].visible) push(s.horizon, horizon, std::array<std::uint32_t, 2>{f, i});
      }
    }
    // The cone from p over the horizon: face (a, b, p) for horizon edge a -> b.
    const std::size_t first_new = nf;
    for (std::size_t h = 0; h < horizon; ++h) {
      const auto [f, i] = s.horizon[h];
      const std::uint32_t a = faces[f].v[i], b = faces[f].v[(i + 1) % 3], g = faces[f].n[i];
      const std::uint32_t t = add(a, b, p);
      faces[t].n[0] = g;
      for (std::uint32_t k = 0; k < 3; ++k)
        if (faces[g].n[k] == f && faces[g].v[k] == b) faces[g].n[k] = t;
      s.by_start[a] = t, s.by_end[b] = t;
      incident[a] = t, incident[p] = t;
    }
    for (std::size_t t = first_new; t < nf; ++t) {
      tri& f = faces[t];
      f.n[1] = s.by_start[f.v[1]];  // edge b -> p: twin of edge p -> b of the face starting at b
      f.n[2] = s.by_end[f.v[0]];    // edge p -> a: twin of edge a -> p of the face ending at a
      // The horizon must be one simple cycle; anything else is not for this hull.
      if (f.n[1] < first_new || f.n[2] < first_new || faces[f.n[1]].v[0] != f.v[1] ||
          faces[f.n[2]].v[1] != f.v[0])
        return false;
    }
    for (std::size_t k = 0; k < visible; ++k) faces[s.visible[k]].alive = false;
  }
  s.used.assign(m, 0);
  std::size_t vertices = 0;
  for (std::size_t t = 0; t < nf; ++t) {
    const tri& f = faces[t];
    if (f.alive) {
      out.push_back(f.v);
      for (const std::uint32_t v : f.v)
        if (!s.used[v]) s.used[v] = 1, ++vertices;
    }
  }
  return vertices == m;
}

}  // namespace cellforge::detail::tubes
