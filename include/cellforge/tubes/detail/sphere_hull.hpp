// SPDX-License-Identifier: MIT
#pragma once
// The convex hull of a few dozen points on one sphere (a tube junction's projected rings):
// a flat triangle array with neighbour links, exact orient3d signs (filtered), no set-up
// beyond scratch buffers the caller keeps. Given the ring size, whole rings go in at once:
// the first ring as a two-sided disc, then each next ring merged by finding the faces it
// sees (a circle bound rejects most faces in one evaluation), walking their horizon and
// wrapping a band of triangles between the horizon and the ring, one orient test per band
// triangle, the ring's cap closed by a fan. A junction's hull thus never triangulates a cap
// point by point (the caps are nearly planar sets that cost the point insertion most of its
// work and are dropped anyway). Other points go in one at a time: each finds a face it sees
// (newest first), grows the visible region over the links and cones it.
// It gives up (returns false) rather than guess: fewer than four points, a degenerate start,
// a point or ring that sees no face, a ring that sees another's cap, or a result that is not
// locally convex at every edge outside the caps; the caller then uses the general hull
// (algorithms/convex_hull.hpp), which reports such input properly.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <new>
#include <span>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
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
    std::uint16_t cap = 0;  // ring r's cap (merged rings): r + 1; 0 otherwise
  };
  std::vector<tri> faces;
  std::vector<std::uint32_t> stack, visible, by_start, by_end;
  std::vector<std::uint32_t> cycle;  // merging a ring: its horizon, as indices into `horizon`
  std::vector<std::uint32_t> band;   // merging a ring: per ring edge j -> j + 1, its band face
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

/// The hull triangles of `pts` (outward, counter-clockwise) into `out`, as input indices;
/// true when every point is a vertex of the hull. `ring_size` > 0: the first points are
/// `ring_count` rings (at most as many as fit) of that many consecutive points each, in order
/// around their circle, each ring a convex polygon whose plane has every other point strictly
/// on one side (a junction's cross-sections: the points after the last ring, such as §V.D's
/// extra points, are inserted last, in input order). Each ring's cap then comes out as a fan
/// from its first point. With fewer than two rings of at least three points, every point goes
/// in one at a time, in input order. O(m²) worst case, about O(m) for a junction's rings;
/// m ≤ 65,535.
template <class = void>
bool sphere_hull(std::span<const glm::dvec3> pts, sphere_hull_scratch& s,
                 std::vector<std::array<std::uint32_t, 3>>& out, std::uint32_t ring_size = 0,
                 std::size_t ring_count = std::size_t(-1)) {
  using tri = sphere_hull_scratch::tri;
  constexpr std::uint32_t none = 0xFFFFFFFFu;
  out.clear();
  const std::size_t m = pts.size();
  if (m < 4 || m > 65535) return false;
  const std::size_t rings = ring_size > 1 ? std::min(ring_count, m / ring_size) : 0;
  // Two rings or more of at least three points: merged ring by ring (see the file comment).
  const bool merge = ring_size >= 3 && rings >= 2;
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
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint16_t cap = 0) {
    if (nf == faces.size()) faces.resize(2 * nf + 16);
    tri& t = faces[nf];
    // The plane is built in place: a copy through the stack stalls on store forwarding.
    ::new (static_cast<void*>(&t.plane)) orient3d_plane(prepare_orient3d(pts[a], pts[b], pts[c]));
    t.v = {a, b, c};
    t.mark = 0;
    t.visible = false;
    t.alive = true;
    t.cap = cap;
    return static_cast<std::uint32_t>(nf++);
  };
  s.by_start.assign(m, 0);
  s.by_end.assign(m, 0);
  std::uint32_t first_single = 3;  // the points from here on are inserted one at a time
  std::uint32_t d = 0;             // the start's fourth point (point insertion only)
  std::uint32_t stamp = 0;
  if (merge) {
    // Ring r's point j (0 <= j < ring_size), counter-clockwise seen from outside.
    const std::uint32_t n = ring_size;
    bool reversed = false;
    std::uint32_t base = 0;
    const auto rv = [&](std::uint32_t j) { return base + (reversed && j != 0 ? n - j : j); };
    // +1: q lies on the outer side of ring r's plane as listed (the ring runs clockwise seen
    // from outside); -1: the inner side; 0: on the plane (degenerate, given up).
    const auto side = [&](std::uint32_t r, const glm::dvec3& q) {
      const glm::dvec3 &a = pts[r * n], &b = pts[r * n + n / 3], &c = pts[r * n + (2 * n) / 3];
      return sphere_hull_orient(prepare_orient3d(a, b, c), a, b, c, q);
    };
    // The first ring: a two-sided disc, the fan from its point 0 on top (faces 0 .. n - 3,
    // u_k = (r0, r_k+1, r_k+2)) and reversed below (faces n - 2 .. 2n - 5).
    {
      const int o = side(0, pts[n]);  // ring 1's first point lies inside
      if (o == 0) return false;
      reversed = o > 0;
      const std::uint32_t fan = n - 2;
      for (std::uint32_t k = 0; k < fan; ++k) add(rv(0), rv(k + 1), rv(k + 2), 1);
      for (std::uint32_t k = 0; k < fan; ++k) add(rv(0), rv(k + 2), rv(k + 1), 0);
      for (std::uint32_t k = 0; k < fan; ++k) {
        tri &up = faces[k], &down = faces[fan + k];
        up.n = {k == 0 ? fan : k - 1, fan + k, k + 1 == fan ? 2 * fan - 1 : k + 1};
        down.n = {k + 1 == fan ? fan - 1 : fan + k + 1, k, k == 0 ? 0 : fan + k - 1};
      }
    }
    std::vector<std::uint32_t>&cycle = s.cycle, &ring_face = s.band;
    if (ring_face.size() < n) ring_face.resize(n);
    for (std::uint32_t r = 1; r < rings; ++r) {
      base = r * n;
      reversed = false;
      {
        const int o = side(r, pts[faces[0].v[0]]);  // a point of ring 0 lies inside
        if (o == 0) return false;
        reversed = o > 0;
      }
      // A circle about the ring bounds every ring point's height over a face's plane: most
      // faces that the ring cannot see are rejected in one evaluation instead of n.
      glm::dvec3 centre(0.0);
      for (std::uint32_t j = 0; j < n; ++j) centre += pts[base + j];
      centre /= static_cast<double>(n);
      const glm::dvec3 normal =
          glm::normalize(glm::cross(pts[base + n / 3] - pts[base], pts[base + (2 * n) / 3] - pts[base]));
      double spread = 0, thickness = 0;  // the largest in-plane and off-plane distances from the centre
      for (std::uint32_t j = 0; j < n; ++j) {
        const glm::dvec3 w = pts[base + j] - centre;
        const double z = glm::dot(w, normal);
        thickness = std::max(thickness, std::fabs(z));
        spread = std::max(spread, std::sqrt(std::max(0.0, glm::dot(w, w) - z * z)));
      }
      ++stamp;
      const auto ring_sees = [&](tri& t) {
        t.mark = stamp;
        t.visible = false;
        const glm::dvec3& nrm = t.plane.minor;
        const double along = glm::dot(nrm, normal), nn = glm::dot(nrm, nrm);
        const double bound = glm::dot(centre - t.plane.a, nrm) +
                             spread * std::sqrt(std::max(0.0, nn - along * along)) +
                             thickness * std::fabs(along);
        // The margin covers the rounding of the bound and of the plane's normal (a few ulps of
        // the products the permanent sums), for points a few units from the origin.
        if (bound < -1e-10 * (t.plane.perm.x + t.plane.perm.y + t.plane.perm.z)) return false;
        for (std::uint32_t j = 0; j < n; ++j)
          if (orient(t, pts[base + j]) > 0) return t.visible = true;
        return false;
      };
      // A face the ring sees: newest first (the caps of earlier rings are rejected at once).
      std::uint32_t seen = none;
      for (std::size_t f = nf; seen == none && f-- > 0;)
        if (faces[f].alive && ring_sees(faces[f])) seen = static_cast<std::uint32_t>(f);
      if (seen == none) return false;
      // The visible region and its horizon; a cap seen means two rings overlap.
      std::size_t stacked = 0, visible = 0, horizon = 0;
      push(s.stack, stacked, seen);
      while (stacked > 0) {
        const std::uint32_t f = s.stack[--stacked];
        if (faces[f].cap != 0) return false;
        push(s.visible, visible, f);
        for (std::uint32_t i = 0; i < 3; ++i) {
          const std::uint32_t g = faces[f].n[i];
          if (faces[g].mark != stamp && ring_sees(faces[g])) {
            push(s.stack, stacked, g);
            continue;
          }
          if (!faces[g].visible) push(s.horizon, horizon, std::array<std::uint32_t, 2>{f, i});
        }
      }
      // The horizon as one cycle h0 -> h1 -> ... (each edge a -> b of a visible face).
      for (std::size_t h = 0; h < horizon; ++h) s.by_start[faces[s.horizon[h][0]].v[s.horizon[h][1]]] = none;
      for (std::size_t h = 0; h < horizon; ++h) {
        std::uint32_t& at = s.by_start[faces[s.horizon[h][0]].v[s.horizon[h][1]]];
        if (at != none) return false;  // the region touches itself at a vertex
        at = static_cast<std::uint32_t>(h);
      }
      if (cycle.size() < horizon + 1) cycle.resize(horizon + 1);
      const auto head_of = [&](std::uint32_t h) {
        const auto [f, i] = s.horizon[h];
        return faces[f].v[i == 2 ? 0 : i + 1];
      };
      const auto tail_of = [&](std::uint32_t h) { return faces[s.horizon[h][0]].v[s.horizon[h][1]]; };
      {
        std::uint32_t h = 0;
        for (std::size_t k = 0; k < horizon; ++k) {
          cycle[k] = h;
          h = s.by_start[head_of(h)];
          if (h == none || (h == 0) != (k + 1 == horizon)) return false;  // not one simple cycle
        }
        cycle[horizon] = 0;
      }
      const auto hv = [&](std::size_t k) { return tail_of(cycle[k]); };  // h_k, h_H = h_0
      // The band's first triangle, on horizon edge h0 -> h1: the ring point with every other
      // ring point on its inner side (all lie inside the face beyond that edge, so the pencil
      // of planes about the edge orders them).
      std::uint32_t c = 0;
      {
        orient3d_plane plane = prepare_orient3d(pts[hv(0)], pts[hv(1)], pts[rv(0)]);
        for (std::uint32_t j = 1; j < n; ++j)
          if (sphere_hull_orient(plane, pts[hv(0)], pts[hv(1)], pts[rv(c)], pts[rv(j)]) > 0) {
            c = j;
            plane = prepare_orient3d(pts[hv(0)], pts[hv(1)], pts[rv(c)]);
          }
      }
      // The band: from the edge r_j -> h_i, either (h_i, h_i+1, r_j) along the horizon or
      // (r_j, h_i, r_j+1) along the ring, whichever has the other candidate inside. Its faces
      // are linked to the last one as they come (edges 1 / 2 of a horizon triangle and 0 / 1
      // of a ring triangle are the band's), to the outside over the horizon, to the cap below.
      const std::size_t first_new = nf;
      std::uint32_t j = c;
      std::size_t i = 0, along_ring = 0;
      std::uint32_t last = none, last_edge = 0, first_edge = 0;
      while (i < horizon || along_ring < n) {
        bool ring_side = i == horizon;
        if (!ring_side && along_ring < n && !(i == 0 && along_ring == 0)) {
          const glm::dvec3 &a = pts[hv(i)], &b = pts[hv(i + 1)], &p = pts[rv(j)];
          ring_side =
              sphere_hull_orient(prepare_orient3d(a, b, p), a, b, p, pts[rv(j + 1 == n ? 0 : j + 1)]) > 0;
        }
        std::uint32_t t, in_edge, out_edge;
        if (ring_side) {
          const std::uint32_t j1 = j + 1 == n ? 0 : j + 1;
          t = add(rv(j), hv(i), rv(j1));
          ring_face[j] = t;
          in_edge = 0, out_edge = 1;
          j = j1, ++along_ring;
        } else {
          t = add(hv(i), hv(i + 1), rv(j));
          const auto [f, e] = s.horizon[cycle[i]];
          const std::uint32_t g = faces[f].n[e], b = hv(i + 1);
          faces[t].n[0] = g;
          for (std::uint32_t k = 0; k < 3; ++k)
            if (faces[g].n[k] == f && faces[g].v[k] == b) faces[g].n[k] = t;
          in_edge = 2, out_edge = 1;
          ++i;
        }
        if (last == none) {
          first_edge = in_edge;
        } else {
          faces[last].n[last_edge] = t;
          faces[t].n[in_edge] = last;
        }
        last = t, last_edge = out_edge;
      }
      if (j != c) return false;
      faces[last].n[last_edge] = static_cast<std::uint32_t>(first_new);
      faces[first_new].n[first_edge] = last;
      // The cap: the fan u_k = (r0, r_k+1, r_k+2), its rim linked to the band's ring faces.
      const auto fan0 = static_cast<std::uint32_t>(nf), fan = n - 2;
      for (std::uint32_t k = 0; k < fan; ++k)
        add(rv(0), rv(k + 1), rv(k + 2), static_cast<std::uint16_t>(r + 1));
      for (std::uint32_t k = 0; k < fan; ++k) {
        const std::uint32_t u = fan0 + k;
        faces[u].n = {k == 0 ? ring_face[0] : u - 1, ring_face[k + 1],
                      k + 1 == fan ? ring_face[n - 1] : u + 1};
      }
      for (std::uint32_t k = 0; k < n; ++k)
        faces[ring_face[k]].n[2] = k == 0 ? fan0 : fan0 + std::min(k - 1, fan - 1);
      for (std::size_t k = 0; k < visible; ++k) faces[s.visible[k]].alive = false;
    }
    first_single = static_cast<std::uint32_t>(rings * n);
  } else {
    // Start: points 0, 1, 2 and the first point off their plane (the last point first: far
    // from them, so the first tetrahedron is not flat).
    tri probe;
    probe.plane = prepare_orient3d(pts[0], pts[1], pts[2]);
    probe.v = {0, 1, 2};
    const auto off = [&](std::size_t k) { return orient(probe, pts[k]) != 0; };
    if (off(m - 1)) {
      d = static_cast<std::uint32_t>(m - 1);
    } else {
      for (std::uint32_t k = 3; k + 1 < m && d == 0; ++k)
        if (off(k)) d = k;
    }
    if (d == 0) return false;
    std::uint32_t a = 0, b = 1, c = 2;
    if (orient(probe, pts[d]) > 0) std::swap(b, c);  // now orient(a, b, c, d) < 0
    // One call site besides the cone's: add is then inlined into both (-57 M instructions, 100k tree).
    const std::array<std::uint32_t, 3> start[4] = {{a, b, c}, {a, d, b}, {b, d, c}, {a, c, d}};
    for (const std::array<std::uint32_t, 3>& t : start) add(t[0], t[1], t[2]);
    for (std::uint32_t f = 0; f < 4; ++f)
      for (std::uint32_t i = 0; i < 3; ++i)
        for (std::uint32_t g = 0; g < 4; ++g)
          for (std::uint32_t k = 0; k < 3; ++k)
            if (faces[g].v[k] == faces[f].v[(i + 1) % 3] && faces[g].v[(k + 1) % 3] == faces[f].v[i])
              faces[f].n[i] = g;
  }
  for (std::uint32_t p = first_single; p < m; ++p) {
    if (p == d && !merge) continue;
    const glm::dvec3& q = pts[p];
    stamp = static_cast<std::uint32_t>(m) + p + 1;  // above the rings' stamps
    const auto judge = [&](tri& t) {
      t.mark = stamp;
      t.visible = orient(t, q) > 0;
      return t.visible;
    };
    // A face that p sees: newest first.
    std::uint32_t seen = none;
    for (std::size_t f = nf; seen == none && f-- > 0;)
      if (faces[f].alive && judge(faces[f])) seen = static_cast<std::uint32_t>(f);
    if (seen == none) return false;  // inside or on the hull: not for this hull
    // The visible region (connected) and its horizon.
    std::size_t stacked = 0, visible = 0, horizon = 0;
    push(s.stack, stacked, seen);
    while (stacked > 0) {
      const std::uint32_t f = s.stack[--stacked];
      if (faces[f].cap != 0 && merge) return false;  // a merged ring's cap is not to be cut
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
  // Merged rings were placed by local choices: the result is their hull only if it is locally
  // convex at every edge outside the caps (a closed, locally convex surface is convex).
  if (merge)
    for (std::uint32_t f = 0; f < nf; ++f) {
      const tri& t = faces[f];
      if (!t.alive) continue;
      for (std::uint32_t i = 0; i < 3; ++i) {
        const std::uint32_t g = t.n[i];
        if (g < f || (t.cap != 0 && t.cap == faces[g].cap)) continue;
        const tri& u = faces[g];
        const std::uint32_t across = u.v[0] != t.v[i] && u.v[0] != t.v[i == 2 ? 0 : i + 1]   ? u.v[0]
                                     : u.v[1] != t.v[i] && u.v[1] != t.v[i == 2 ? 0 : i + 1] ? u.v[1]
                                                                                             : u.v[2];
        if (!u.alive || orient(t, pts[across]) > 0) return false;
      }
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

/// The local-convexity tests of a closed triangulated surface: per edge outside the caps,
/// (a, b, c, d) for its faces (a, b, c) and (b, a, d), into `checks`. The first `ring_count`
/// runs of `ring_size` points are rings whose caps are skipped (edges inside one ring's cap),
/// as sphere_hull's own certificate skips them.
/// False when an edge is not used once each way. O(F log F) for F triangles.
template <class = void>
bool hull_edge_checks(std::span<const std::array<std::uint32_t, 3>> triangles, std::uint32_t ring_size,
                      std::size_t ring_count, std::vector<std::array<std::uint32_t, 4>>& checks) {
  // (smaller end, larger end, the third vertex, whether the face runs smaller -> larger)
  std::vector<std::array<std::uint32_t, 4>> halves;
  halves.reserve(3 * triangles.size());
  for (const std::array<std::uint32_t, 3>& t : triangles)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      halves.push_back({std::min(a, b), std::max(a, b), c, a < b ? 1u : 0u});
    }
  std::sort(halves.begin(), halves.end());
  checks.clear();
  if (halves.size() % 2 != 0) return false;  // an odd number of corners cannot pair up
  // A point in no ring is a ring of its own (numbered from the top, clear of the rings').
  const std::size_t ring_points = ring_size == 0 ? 0 : ring_size * ring_count;
  const auto ring = [&](std::uint32_t v) { return v < ring_points ? v / ring_size : 0xFFFFFFFFu - v; };
  for (std::size_t k = 0; k < halves.size(); k += 2) {
    const std::array<std::uint32_t, 4>&e = halves[k], &f = halves[k + 1];
    if (e[0] != f[0] || e[1] != f[1] || e[3] == f[3]) return false;
    if (k + 2 < halves.size() && halves[k + 2][0] == e[0] && halves[k + 2][1] == e[1]) return false;
    const std::array<std::uint32_t, 4>& forward = e[3] != 0 ? e : f;  // (a, b, c), a < b
    const std::array<std::uint32_t, 4>& back = e[3] != 0 ? f : e;     // (b, a, d)
    const std::uint32_t a = forward[0], b = forward[1], c = forward[2], d = back[2];
    if (ring(a) == ring(b) && ring(b) == ring(c) && ring(c) == ring(d)) continue;  // inside a cap
    checks.push_back({a, b, c, d});
  }
  return true;
}

/// Whether the surface whose edge tests are `checks` (hull_edge_checks) is locally convex at
/// every one of them on `pts`, exactly. O(E).
template <class = void>
bool hull_locally_convex(std::span<const glm::dvec3> pts,
                         std::span<const std::array<std::uint32_t, 4>> checks) {
  for (const std::array<std::uint32_t, 4>& e : checks) {
    const glm::dvec3 &a = pts[e[0]], &b = pts[e[1]], &c = pts[e[2]];
    if (sphere_hull_orient(prepare_orient3d(a, b, c), a, b, c, pts[e[3]]) > 0) return false;
  }
  return true;
}

}  // namespace cellforge::detail::tubes
