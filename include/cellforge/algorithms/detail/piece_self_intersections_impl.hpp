// SPDX-License-Identifier: MIT
#pragma once
// The check by pieces (included by algorithms/piece_self_intersections.hpp): the groups, their
// certificates, the separating planes and the pair tests left (docs/tubes.md, "The check by pieces").

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <memory_resource>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>
#include "cellforge/algorithms/detail/triangle_pairs.hpp"
#include "cellforge/algorithms/piece_self_intersections.hpp"
#include "cellforge/algorithms/self_intersections.hpp"
#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/halfedge/handles.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"

namespace cellforge {

namespace detail::piece_check {

using vec = glm::dvec3;
inline constexpr std::uint32_t none = 0xFFFFFFFFu;
/// The engine's arrays, all in its one scratch arena.
template <class T>
using buffer = std::pmr::vector<T>;

/// One triangle of a face's triangulation (vertex ids as the mesh numbers them).
struct triangle {
  std::array<std::uint32_t, 3> v;
  std::uint32_t face;
};

/// True when `tris` triangulate the polygon `ids` as a disc: n - 2 triangles, distinct corners,
/// every polygon edge in one triangle in its own direction, every other edge in exactly two, once
/// each way. Then the face's triangles glue into an oriented disc. O(n²).
template <class = void>
bool disc_triangulation(std::span<const std::uint32_t> ids, std::span<const triangle> tris) {
  const std::size_t n = ids.size();
  if (n < 3 || tris.size() != n - 2) return false;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (ids[i] == ids[j]) return false;
  const auto index = [&](std::uint32_t x) {
    return static_cast<std::size_t>(std::find(ids.begin(), ids.end(), x) - ids.begin());
  };
  // uses[i * n + j]: triangle sides from corner i to corner j.
  std::array<std::uint8_t, 256> small{};  // the mesher's faces; larger ones on the heap
  std::vector<std::uint8_t> large(n > 16 ? n * n : 0, 0);
  std::uint8_t* const uses = n > 16 ? large.data() : small.data();
  for (const triangle& t : tris)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t ia = index(t.v[k]), ib = index(t.v[(k + 1) % 3]);
      if (ia == n || ib == n) return false;
      if (++uses[ia * n + ib] > 1) return false;
    }
  std::size_t on_boundary = 0;
  for (std::size_t ia = 0; ia < n; ++ia)
    for (std::size_t ib = 0; ib < n; ++ib) {
      if (uses[ia * n + ib] == 0) continue;
      if (ib == (ia + 1) % n) {
        if (uses[ib * n + ia] != 0) return false;
        ++on_boundary;
      } else if (uses[ib * n + ia] != 1) {
        return false;
      }
    }
  return on_boundary == n;
}

/// Points of segments s and t nearest each other (rounded; a heuristic's input). O(1).
template <class = void>
std::array<vec, 2> closest_points(const std::array<vec, 2>& s, const std::array<vec, 2>& t) {
  const vec d1 = s[1] - s[0], d2 = t[1] - t[0], r = s[0] - t[0];
  const double a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
  double u = 0, v = 0;
  if (!(a > 0) && !(e > 0)) return {s[0], t[0]};
  if (!(a > 0)) {
    v = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = glm::dot(d1, r);
    if (!(e > 0)) {
      u = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = glm::dot(d1, d2), denom = a * e - b * b;
      u = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      v = (b * u + f) / e;
      if (v < 0) {
        v = 0, u = std::clamp(-c / a, 0.0, 1.0);
      } else if (v > 1) {
        v = 1, u = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return {s[0] + u * d1, t[0] + v * d2};
}

/// The engine: the mesh's triangles grouped by piece, the pieces' neighbours and boundary
/// half-edges, and the certificates.
template <Point3 P>
struct engine {
  // First: the arrays below live in it, and it goes last.
  cellforge::detail::scratch_arena arena;
  const surface_mesh<P>& m;
  std::span<const std::uint32_t> face_piece;
  buffer<vec> own_pos{&arena};  // positions converted to double, unless they are already
  std::span<const vec> pos;
  std::size_t pieces = 0;
  buffer<triangle> tris{&arena};              // by piece
  buffer<std::uint32_t> piece_first{&arena};  // tris of piece p: [piece_first[p], piece_first[p + 1])
  buffer<std::uint8_t> piece_ok{&arena};      // every face a disc triangulation, at least one triangle
  // Faces of piece p: faces_in[face_first[p] ...].
  buffer<std::uint32_t> face_first{&arena}, faces_in{&arena};
  // Per piece: its border (half-edges whose twin lies in another piece, or none) in classes,
  // one per piece beyond (none: the mesh's boundary): each class's range of `edges` (tail, head),
  // that piece, and its tails' mean (the apex of the cone that closes it in a group).
  struct border_class {
    std::uint32_t first, end, other;
    vec apex;
  };
  buffer<std::uint32_t> class_first{&arena};  // classes of piece p: [class_first[p], class_first[p + 1])
  buffer<border_class> classes{&arena};
  buffer<std::array<std::uint32_t, 2>> edges{&arena};
  // Per piece: every class is closed (each vertex the tail of at most one of its edges, the head
  // of as many, the same vertices both ways: its edges run in cycles); else traced per group.
  buffer<std::uint8_t> classes_closed{&arena};
  buffer<std::uint32_t> nbr_first{&arena}, nbr{&arena};  // distinct neighbouring pieces
  buffer<vec> nbr_mean{&arena};                          // per neighbour: the mean of the border to it
  buffer<std::uint8_t> nbr_held{&arena};                 // per neighbour: a certified pair group
  buffer<std::array<vec, 2>> centres{&arena};            // candidate centres per piece
  buffer<vec> mean{&arena};                              // per piece, the mean of its corners
  buffer<std::uint8_t> centre_count{&arena};
  buffer<std::uint32_t> stamp_piece{&arena};
  std::uint32_t attempt = 0;
  buffer<std::uint32_t> members{&arena};
  buffer<std::uint32_t> bd{&arena}, loop{&arena};
  buffer<std::uint8_t> bd_seen{&arena};

  engine(const surface_mesh<P>& mesh, std::span<const std::uint32_t> labels)
      : arena(scratch_bytes(mesh)), m(mesh), face_piece(labels) {}
  /// Room for the arrays of a mesh of tubes and more (a bound, not the need: pages untouched
  /// cost nothing). O(1).
  static std::size_t scratch_bytes(const surface_mesh<P>& mesh) {
    return 64 * mesh.halfedges_size() + 256 * mesh.faces_size() + 64 * mesh.vertices_size();
  }

  /// True when the edges (tail, head) run in cycles: no two share a tail, no two a head, and the
  /// heads are the tails (each vertex then the head of one edge and the tail of one). O(n²) for
  /// up to 32 edges (a count each way, no branches), O(n log n) above.
  bool closed(std::span<const std::array<std::uint32_t, 2>> e) {
    const std::size_t n = e.size();
    tails.resize(n), heads.resize(n);
    for (std::size_t i = 0; i < n; ++i) tails[i] = e[i][0], heads[i] = e[i][1];
    if (n > 32) {
      std::sort(tails.begin(), tails.end()), std::sort(heads.begin(), heads.end());
      return tails == heads && std::adjacent_find(tails.begin(), tails.end()) == tails.end();
    }
    bool ok = true;  // each head equals exactly one tail, each tail exactly one head
    for (std::size_t i = 0; i < n; ++i) {
      std::uint32_t as_tail = 0, as_head = 0;
      for (std::size_t j = 0; j < n; ++j)
        as_tail += static_cast<std::uint32_t>(tails[j] == heads[i]),
            as_head += static_cast<std::uint32_t>(heads[j] == tails[i]);
      ok = ok && as_tail == 1 && as_head == 1;
    }
    return ok;
  }
  buffer<std::uint32_t> tails{&arena}, heads{&arena};

  /// The next boundary half-edge of the group after h (stamp_piece marks the group), turning
  /// about h's head through the group's faces; none after 256 steps.
  std::uint32_t successor(std::uint32_t h) const {
    halfedge_handle c = m.next(halfedge_handle(h));
    for (int step = 0; step < 256; ++step) {
      const halfedge_handle t = halfedge_mesh::twin(c);
      const face_handle f = m.face(t);
      if (!f.is_valid() || stamp_piece[face_piece[f.idx()]] != attempt) return c.idx();
      c = m.next(t);
    }
    return none;
  }

  /// True when a plane has every corner of piece a strictly on one side and every corner of
  /// piece b strictly on the other (exact orient3d against three points of it): the plane through
  /// the middle of their means, across the line between them. O(size of a and b).
  /// A piece's axis: the segment between the means of its two borders (a tube's band), else its
  /// mean (a point).
  std::array<vec, 2> axis(std::uint32_t p) const {
    if (nbr_first[p + 1] - nbr_first[p] == 2) return {nbr_mean[nbr_first[p]], nbr_mean[nbr_first[p] + 1]};
    return {mean[p], mean[p]};
  }

  /// Piece p's distinct corners (vertex ids), gathered on first use. O(p's triangles).
  std::span<const std::uint32_t> corners_of(std::uint32_t p) {
    if (corner_first.empty()) {
      corner_first.assign(pieces, none), corner_count.assign(pieces, 0);
      detail::reserve_large(corner_stamp, m.vertices_size());
      corner_stamp.assign(m.vertices_size(), none);
    }
    if (corner_first[p] == none) {
      corner_first[p] = static_cast<std::uint32_t>(corner_ids.size());
      for (std::uint32_t t = piece_first[p]; t < piece_first[p + 1]; ++t)
        for (const std::uint32_t v : tris[t].v)
          if (corner_stamp[v] != p) corner_stamp[v] = p, corner_ids.push_back(v);
      corner_count[p] = static_cast<std::uint32_t>(corner_ids.size()) - corner_first[p];
    }
    return {corner_ids.data() + corner_first[p], corner_count[p]};
  }
  buffer<std::uint32_t> corner_first{&arena}, corner_count{&arena}, corner_ids{&arena}, corner_stamp{&arena};

  bool separated(std::uint32_t a, std::uint32_t b) {
    // Across the closest points of their axes (two tubes that pass each other), then between
    // their means.
    const card &ca = capsule(a), &cb = capsule(b);
    const auto [pa, pb] = closest_points({ca.a, ca.b}, {cb.a, cb.b});
    if (separated_by(a, b, 0.5 * (pa + pb), pb - pa)) return true;
    if (separated_by(a, b, 0.5 * (mean[a] + mean[b]), mean[b] - mean[a])) return true;
    // Two pieces on either side of a third (a tube's bands two apart): across that one's axis.
    for (std::uint32_t k = nbr_first[a]; k < nbr_first[a + 1]; ++k) {
      const std::uint32_t c = nbr[k];
      for (std::uint32_t j = nbr_first[c]; j < nbr_first[c + 1]; ++j)
        if (nbr[j] == b) {
          std::uint32_t i = nbr_first[c];
          while (nbr[i] != a) ++i;
          return separated_by(a, b, mean[c], nbr_mean[j] - nbr_mean[i]);
        }
    }
    return false;
  }

  /// What the grid over pieces reads of a piece, in 64 bytes: its capsule (the segment axis(p)
  /// and an upper bound on its corners' distance from it; reach < 0: no triangles) and the
  /// certified groups it is in (group_of[group_first, group_end), increasing). Not alignas(64):
  /// glibc's aligned allocations disturbed the heap (3 times the page faults of make_tubes after).
  struct card {
    vec a, b;
    double reach;
    std::uint32_t group_first, group_end;
  };
  buffer<card> cards{&arena};
  buffer<std::uint32_t> group_of{&arena};
  static constexpr double no_triangles = -1, unknown = -2;  // cards' reach before it is known
  buffer<std::uint8_t> tails_only{&arena};  // per piece: its border classes' tails are all its corners

  /// Piece p's capsule, its reach computed on first use: over its border classes' tails when
  /// they are all its corners, else over its triangles' corners. O(1), once O(p's triangles).
  const card& capsule(std::uint32_t p) {
    card& c = cards[p];
    if (c.reach != unknown) return c;
    if (tails_only[p] != 0) {
      const std::uint32_t first = classes[class_first[p]].first, end = classes[class_first[p + 1] - 1].end;
      c.reach = reach(c.a, c.b, end - first, [&](std::size_t i) { return pos[edges[first + i][0]]; });
    } else {
      const std::uint32_t first = piece_first[p];
      c.reach = reach(c.a, c.b, 3 * std::size_t{piece_first[p + 1] - first},
                      [&](std::size_t i) { return pos[tris[first + i / 3].v[i % 3]]; });
    }
    return c;
  }

  /// An upper bound on the distance from the segment ab of the points `at(i)`, i < n: the rounded
  /// distance to a rounded point of the segment, widened by far more than their rounding errors
  /// (the point is off by ~9 eps of the ends' coordinates, the distance by ~4 eps); NaN when a
  /// coordinate is not finite. O(n).
  template <class At>
  static double reach(const vec& a, const vec& b, std::size_t n, At&& at) {
    const vec u = b - a;
    const double l = glm::dot(u, u), inv = l > 0 ? 1 / l : 0;  // any t in [0, 1] names a point of it
    double r2 = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const vec x = at(i);
      const vec y = x - (a + std::clamp(glm::dot(x - a, u) * inv, 0.0, 1.0) * u);
      const double d2 = glm::dot(y, y);
      if (!(d2 <= r2)) r2 = d2;  // a NaN stays
    }
    const double scale = std::max(
        {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z), std::fabs(b.x), std::fabs(b.y), std::fabs(b.z)});
    return std::sqrt(r2) * (1 + 0x1p-40) + scale * 0x1p-40 + 0x1p-500;
  }

  /// True when one certified group holds pieces a and b (their group lists meet). O(the lists).
  bool held(std::uint32_t a, std::uint32_t b) const {
    std::uint32_t i = cards[a].group_first, j = cards[b].group_first;
    const std::uint32_t i1 = cards[a].group_end, j1 = cards[b].group_end;
    while (i < i1 && j < j1) {
      if (group_of[i] == group_of[j]) return true;
      if (group_of[i] < group_of[j])
        ++i;
      else
        ++j;
    }
    return false;
  }

  /// The side of the plane {x : d·(x - o) = 0} that piece p lies strictly on (±1; 0: cannot
  /// tell), decided from its capsule (cards): d·(x - o) is affine, so on the capsule it lies within
  /// |d| times the reach of its values at the axis' ends, each of those rounded by less than
  /// 8 eps of the sum of its products' magnitudes. `length` ≥ |d|. O(1).
  int capsule_side(std::uint32_t p, const vec& o, const vec& d, double length) const {
    const card& c = cards[p];
    const double margin = length * c.reach * (1 + 0x1p-40);
    const vec &a = c.a, &b = c.b;
    int side = 0;
    for (const vec& x : {a, b}) {
      const vec t = x - o;
      const double value = d.x * t.x + d.y * t.y + d.z * t.z;
      const double error = 8 * cellforge::detail::predicate_eps *
                               (std::fabs(d.x * t.x) + std::fabs(d.y * t.y) + std::fabs(d.z * t.z)) +
                           cellforge::detail::underflow_guard;
      const double need = (error + margin) * (1 + 0x1p-40);
      const int here = value > need ? 1 : value < -need ? -1 : 0;
      if (here == 0 || (side != 0 && here != side)) return 0;
      side = here;
    }
    return side;
  }

  /// True when the plane through o across d has every corner of piece a strictly on one side and
  /// every corner of piece b strictly on the other: from the pieces' capsules, else exact orient3d
  /// of each corner against three points of it.
  bool separated_by(std::uint32_t a, std::uint32_t b, const vec& o, const vec& d) {
    if (!(d.x * d.x + d.y * d.y + d.z * d.z > 0)) return false;
    const double length = std::sqrt(glm::dot(d, d)) * (1 + 0x1p-40) + 0x1p-500;  // ≥ |d|
    const int ca = capsule_side(a, o, d, length);
    if (ca != 0 && capsule_side(b, o, d, length) == -ca) return true;
    const vec u = cellforge::detail::any_perpendicular(d);
    const vec w(d.y * u.z - d.z * u.y, d.z * u.x - d.x * u.z, d.x * u.y - d.y * u.x);
    const auto plane = cellforge::detail::prepare_orient3d(o, o + u, o + w);
    const vec q = o + w;
    const auto side_of = [&](std::uint32_t p, int want) {
      for (const std::uint32_t v : corners_of(p)) {
        double value = 0;
        int o3 = cellforge::detail::orient3d_filter(plane, pos[v], value);
        if (o3 == 0) o3 = cellforge::detail::orient3d_exact(o, o + u, q, pos[v]);
        if (o3 == 0 || (want != 0 && o3 != want)) return 0;
        want = o3;
      }
      return want;
    };
    const int sa = side_of(a, 0);
    return sa != 0 && side_of(b, -sa) == -sa;
  }

  /// (p - c) × (q - c), rounded, with the sums of its products' magnitudes: the part of the
  /// orient3d filter with pivot c that a query reuses (core/predicates.hpp, orient3d_plane).
  struct minor {
    vec m, perm;
  };
  static minor minor_of(const vec& pc, const vec& qc) noexcept {
    const double yz = pc.y * qc.z, zy = pc.z * qc.y, zx = pc.z * qc.x, xz = pc.x * qc.z, xy = pc.x * qc.y,
                 yx = pc.y * qc.x;
    return {vec(yz - zy, zx - xz, xy - yx),
            vec(std::fabs(yz) + std::fabs(zy), std::fabs(zx) + std::fabs(xz), std::fabs(xy) + std::fabs(yx))};
  }
  /// orient3d(c, p, q, d) from minor_of(p - c, q - c) and d - c: the filter, and the exact
  /// evaluation when it cannot decide. O(1).
  static int sign_of(const minor& k, const vec& dc, const vec& c, const vec& p, const vec& q,
                     const vec& d) noexcept {
    const double det = dc.x * k.m.x + dc.y * k.m.y + dc.z * k.m.z;
    const double ax = std::fabs(dc.x), ay = std::fabs(dc.y), az = std::fabs(dc.z);
    const double bound = cellforge::detail::orient3d_bound * (ax * k.perm.x + ay * k.perm.y + az * k.perm.z) +
                         cellforge::detail::underflow_guard * (1.0 + ax + ay + az);
    if (det > bound) return 1;
    if (det < -bound) return -1;
    return cellforge::detail::orient3d_exact(c, p, q, d);
  }

  /// Certifies the group of pieces `members` about centre c: true when every triangle of the
  /// group, and of the cones closing its boundary (apex: a border class's mean, or a traced
  /// loop's), has c strictly on one same side, and the direction from c through the middle of
  /// the first member's first triangle lies in no other triangle's closed cone. Then the group
  /// is embedded (docs/tubes.md).
  bool certify(const vec& c) {
    ++attempt;
    if (attempt == 0) return false;
    const std::uint32_t r = members[0];
    for (const std::uint32_t x : members) {
      if (piece_ok[x] == 0) return false;
      stamp_piece[x] = attempt;
    }
    // The witness: g, the middle of r's first triangle, inside its cone (all three sides' orient3d
    // equal its facing sign f, which every triangle must share).
    const triangle& t0 = tris[piece_first[r]];
    const vec &x0 = pos[t0.v[0]], &y0 = pos[t0.v[1]], &z0 = pos[t0.v[2]];
    const vec g = (x0 + y0 + z0) / 3.0, gc = g - c;
    const int f = orient3d(c, x0, y0, z0);
    if (f == 0 || orient3d(c, x0, y0, g) != f || orient3d(c, y0, z0, g) != f || orient3d(c, z0, x0, g) != f)
      return false;
    // Faces away with sign f, and leaves g outside its closed cone (one side's sign is -f).
    // The sides in the order that most often ends soonest (any order gives the same answer):
    // 1.57 tests a triangle on trees and lattices, against 1.69 in turn.
    const auto fits = [&](const vec& x, const vec& y, const vec& z) {
      const vec xc = x - c, yc = y - c, zc = z - c;
      const minor k1 = minor_of(xc, yc);
      if (sign_of(k1, zc, c, x, y, z) != f) return false;
      if (sign_of(k1, gc, c, x, y, g) == -f) return true;
      const minor k3 = minor_of(zc, xc);
      if (sign_of(k3, gc, c, z, x, g) == -f) return true;
      const minor k2 = minor_of(yc, zc);
      return sign_of(k2, gc, c, y, z, g) == -f;
    };
    for (const std::uint32_t x : members)
      for (std::uint32_t t = piece_first[x] + (x == r ? 1 : 0); t < piece_first[x + 1]; ++t) {
        const triangle& q = tris[t];
        if (!fits(pos[q.v[0]], pos[q.v[1]], pos[q.v[2]])) return false;
      }
    // The boundary: half-edges of the group whose twin is outside it, closed by cones. When
    // every member's classes are closed, it is the union of the members' classes beyond the
    // group, each coned from its apex: every edge of the group and cones then has two triangles,
    // once each way (the spokes: each vertex of a class is one edge's head and one's tail).
    bool whole = true;
    for (const std::uint32_t x : members) whole = whole && classes_closed[x] != 0;
    if (whole) {
      for (const std::uint32_t x : members)
        for (std::uint32_t l = class_first[x]; l < class_first[x + 1]; ++l) {
          const border_class& b = classes[l];
          if (b.other != none && stamp_piece[b.other] == attempt) continue;  // inside the group
          for (std::uint32_t k = b.first; k < b.end; ++k)                    // (apex, head, tail)
            if (!fits(b.apex, pos[edges[k][1]], pos[edges[k][0]])) return false;
        }
      return true;
    }
    bd.clear();
    for (const std::uint32_t x : members)  // the members' half-edges whose twin is outside the group
      for (std::uint32_t i = face_first[x]; i < face_first[x + 1]; ++i) {
        const halfedge_handle h0 = m.halfedge(face_handle(faces_in[i]));
        halfedge_handle h = h0;
        do {
          const face_handle beyond = m.face(halfedge_mesh::twin(h));
          if (!beyond.is_valid() || stamp_piece[face_piece[beyond.idx()]] != attempt) bd.push_back(h.idx());
          h = m.next(h);
        } while (h != h0);
      }
    std::sort(bd.begin(), bd.end());
    bd_seen.assign(bd.size(), 0);
    for (std::size_t i0 = 0; i0 < bd.size(); ++i0) {
      if (bd_seen[i0] != 0) continue;
      loop.clear();
      vec sum(0.0);
      std::uint32_t h = bd[i0];
      do {
        const auto at = std::lower_bound(bd.begin(), bd.end(), h);
        if (h == none || at == bd.end() || *at != h) return false;
        std::uint8_t& seen = bd_seen[static_cast<std::size_t>(at - bd.begin())];
        if (seen != 0) return false;  // not one loop through each
        seen = 1;
        loop.push_back(h);
        sum += pos[m.head(m.prev(halfedge_handle(h))).idx()];
        h = successor(h);
      } while (h != bd[i0]);
      const vec apex = sum / static_cast<double>(loop.size());
      for (const std::uint32_t e : loop) {  // (apex, head, tail): the group's edge reversed
        const halfedge_handle he(e);
        if (!fits(apex, pos[m.head(he).idx()], pos[m.head(m.prev(he)).idx()])) return false;
      }
    }
    return true;
  }
};

/// The point nearest (least squares) to the axes of piece p's boundary loops with more than two
/// loops or two loops at an angle (a junction: its rings' axes meet at its centre); false when
/// they do not fix one. `loops`: per loop its mean point and its Newell normal. O(loops).
template <class = void>
bool axes_meet(std::span<const std::array<vec, 2>> loops, vec& out) {
  if (loops.size() < 2) return false;
  double a[3][3] = {}, b[3] = {};
  for (const auto& [q, normal] : loops) {
    const double l = std::sqrt(normal.x * normal.x + normal.y * normal.y + normal.z * normal.z);
    if (!(l > 0)) return false;
    const vec n = normal / l;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double mij = (i == j ? 1.0 : 0.0) - n[i] * n[j];
        a[i][j] += mij;
        b[i] += mij * q[j];
      }
  }
  const auto det3 = [](const double(&x)[3][3]) {
    return x[0][0] * (x[1][1] * x[2][2] - x[1][2] * x[2][1]) -
           x[0][1] * (x[1][0] * x[2][2] - x[1][2] * x[2][0]) +
           x[0][2] * (x[1][0] * x[2][1] - x[1][1] * x[2][0]);
  };
  const double d = det3(a);
  // Two loops at 30 degrees: the smallest eigenvalue of a is sin²(30)/... well away from 0.
  if (!(std::fabs(d) > 0.05 * static_cast<double>(loops.size()))) return false;
  for (int k = 0; k < 3; ++k) {
    double c[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c[i][j] = j == k ? b[i] : a[i][j];
    out[k] = det3(c) / d;
  }
  return std::isfinite(out.x) && std::isfinite(out.y) && std::isfinite(out.z);
}

}  // namespace detail::piece_check

template <Point3 P>
self_intersection_result self_intersections_by_pieces(const surface_mesh<P>& m,
                                                      std::span<const std::uint32_t> face_piece,
                                                      const self_intersection_options& options) {
  namespace si = detail::self_intersect;
  namespace pc = detail::piece_check;
  using pc::none;
  using vec = glm::dvec3;
  const detail::stopwatch start;
  self_intersection_result r;
  if (face_piece.size() != m.faces_size())
    throw error(error_category::invalid_input,
                cellforge::detail::cat("self_intersections_by_pieces: face_piece has ",
                                       std::to_string(face_piece.size()), " labels for ",
                                       std::to_string(m.faces_size()), " faces"));
  pc::engine<P> e(m, face_piece);
  if constexpr (std::is_same_v<P, glm::dvec3>) {
    e.pos = m.points();
  } else {
    e.own_pos.resize(m.vertices_size());
    for (std::size_t i = 0; i < e.own_pos.size(); ++i) e.own_pos[i] = to_dvec3(m.points()[i]);
    e.pos = e.own_pos;
  }
  const std::span<const glm::dvec3> pos = e.pos;

  // Faces by piece (a counting sort), then their triangles in that order.
  std::size_t pieces = 0;
  for (const face_handle f : m.faces()) {
    const std::uint32_t p = face_piece[f.idx()];
    if (p >= m.faces_size())
      throw error(error_category::invalid_input,
                  "self_intersections_by_pieces: a piece id is not below the number of faces");
    pieces = std::max<std::size_t>(pieces, p + 1);
  }
  e.pieces = pieces;
  pc::buffer<std::uint32_t>&face_first = e.face_first, &faces_in = e.faces_in;
  face_first.assign(pieces + 1, 0);
  detail::reserve_large(faces_in, m.num_faces());
  faces_in.resize(m.num_faces());
  for (const face_handle f : m.faces()) ++face_first[face_piece[f.idx()] + 1];
  for (std::size_t p = 0; p < pieces; ++p) face_first[p + 1] += face_first[p];
  {
    pc::buffer<std::uint32_t> fill(face_first.begin(), face_first.end() - 1, &e.arena);
    for (const face_handle f : m.faces()) faces_in[fill[face_piece[f.idx()]]++] = f.idx();
  }
  e.piece_first.assign(pieces + 1, 0);
  e.piece_ok.assign(pieces, 1);
  // Arrays of a few MB and more on huge pages where the kernel offers them: fresh memory's
  // page faults were a tenth of the check.
  detail::reserve_large(e.tris, m.num_faces() * 2);
  detail::reserve_large(e.edges, m.halfedges_size() / 2);
  detail::reserve_large(e.classes, 3 * pieces);
  detail::reserve_large(e.nbr, 3 * pieces);
  detail::reserve_large(e.nbr_mean, 3 * pieces);
  detail::reserve_large(e.centres, pieces);
  detail::reserve_large(e.mean, pieces);
  e.class_first.assign(pieces + 1, 0);
  e.classes_closed.assign(pieces, 0);
  e.nbr_first.assign(pieces + 1, 0);
  e.centres.resize(pieces);
  e.mean.resize(pieces);
  e.centre_count.assign(pieces, 0);
  std::vector<std::uint32_t> ids;
  std::vector<glm::dvec3> corners;
  std::vector<std::array<vec, 2>>
      loops;  // per neighbour slot of the piece (its border classes): tails' sum, Newell normal
  std::vector<std::uint32_t> loop_count;
  std::vector<std::array<std::uint32_t, 3>> out;  // the piece's border: tail, head, neighbour slot
  std::vector<std::uint8_t> on_border;            // per corner of the face: its edge to the next is
  detail::reserve_large(e.cards, pieces);
  e.cards.resize(pieces);
  e.tails_only.resize(pieces);
  // Per piece, the box of its faces' corners (its triangles' corners and no others but the
  // corners of faces with no triangles, which only widen it), made in the walk.
  pc::buffer<std::array<double, 6>> piece_box(&e.arena);
  detail::reserve_large(piece_box, pieces);
  piece_box.resize(pieces);
  for (std::uint32_t p = 0; p < pieces; ++p) {
    e.piece_first[p] = static_cast<std::uint32_t>(e.tris.size());
    out.clear();
    bool inner = false;  // a corner on no border edge of its face
    e.nbr_first[p] = static_cast<std::uint32_t>(e.nbr.size());
    loops.clear();
    loop_count.clear();
    vec sum(0.0);
    std::size_t corners_seen = 0;
    constexpr double inf = std::numeric_limits<double>::infinity();
    std::array<double, 6> box = {inf, inf, inf, -inf, -inf, -inf};
    for (std::uint32_t k = face_first[p]; k < face_first[p + 1]; ++k) {
      const face_handle f(faces_in[k]);
      ++r.faces;
      ids.clear();
      corners.clear();
      on_border.clear();
      const halfedge_handle h0 = m.halfedge(f);
      halfedge_handle h = h0;
      std::uint32_t tail = m.head(m.prev(h0)).idx();
      do {  // the face's corners from its first, and its half-edges to other pieces
        const std::uint32_t v = tail;
        tail = m.head(h).idx();
        ids.push_back(v);
        corners.push_back(pos[v]);
        for (std::size_t k = 0; k < 3; ++k)
          box[k] = std::min(box[k], pos[v][static_cast<int>(k)]),
          box[k + 3] = std::max(box[k + 3], pos[v][static_cast<int>(k)]);
        sum += pos[v];
        ++corners_seen;
        const face_handle g = m.face(halfedge_mesh::twin(h));
        const std::uint32_t other = g.is_valid() ? face_piece[g.idx()] : none;
        on_border.push_back(other != p ? 1 : 0);
        if (other != p) {
          std::size_t at = e.nbr_first[p];
          while (at < e.nbr.size() && e.nbr[at] != other) ++at;
          if (at == e.nbr.size()) {
            e.nbr.push_back(other);
            loops.push_back({vec(0.0), vec(0.0)});
            loop_count.push_back(0);
          }
          const std::size_t l = at - e.nbr_first[p];
          out.push_back({v, tail, static_cast<std::uint32_t>(l)});
          loops[l][0] += pos[v];
          ++loop_count[l];
        }
        h = m.next(h);
      } while (h != h0);
      for (std::size_t i = 0, j = ids.size() - 1; i < ids.size(); j = i++)
        inner = inner || (on_border[i] == 0 && on_border[j] == 0);
      // As triangulate_polygon does; a triangle, or a convex projected quad split along a
      // diagonal, is a disc; other faces' triangles are verified to be one.
      if (ids.size() == 3) {
        e.tris.push_back({{ids[0], ids[1], ids[2]}, f.idx()});
        continue;
      }
      if (ids.size() == 4 && si::convex_projected_quad(detail::span_of(corners))) {
        e.tris.push_back({{ids[3], ids[0], ids[1]}, f.idx()});
        e.tris.push_back({{ids[1], ids[2], ids[3]}, f.idx()});
        if (si::orient3d_filtered(corners[0], corners[1], corners[2], corners[3]) != 0) ++r.ear_clipped_faces;
        continue;
      }
      const std::size_t before = e.tris.size();
      const bool clipped = si::triangulate_polygon(detail::span_of(ids), detail::span_of(corners),
                                                   [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
                                                     e.tris.push_back({{a, b, c}, f.idx()});
                                                   });
      if (clipped) ++r.ear_clipped_faces;
      if (!pc::disc_triangulation(detail::span_of(ids), std::span<const pc::triangle>(
                                                            e.tris.data() + before, e.tris.size() - before)))
        e.piece_ok[p] = 0;
    }
    for (std::size_t l = 0; l < loops.size(); ++l) loops[l][0] /= static_cast<double>(loop_count[l]);
    // The border's classes, by neighbour slot (a counting sort, keeping the walk's order).
    e.class_first[p] = static_cast<std::uint32_t>(e.classes.size());
    const std::size_t edges0 = e.edges.size();
    auto at = static_cast<std::uint32_t>(edges0);
    for (std::size_t l = 0; l < loops.size(); ++l) {
      e.classes.push_back({at, at, e.nbr[e.nbr_first[p] + l], loops[l][0]});
      at += loop_count[l];
    }
    e.class_first[p + 1] = static_cast<std::uint32_t>(e.classes.size());
    e.edges.resize(at);
    for (const auto& [a, b, l] : out) e.edges[e.classes[e.class_first[p] + l].end++] = {a, b};
    bool closed = true;
    for (std::size_t l = e.class_first[p]; l < e.classes.size() && closed; ++l)
      closed = e.closed(std::span<const std::array<std::uint32_t, 2>>(e.edges.data() + e.classes[l].first,
                                                                      e.classes[l].end - e.classes[l].first));
    e.classes_closed[p] = closed ? 1 : 0;
    // Neighbours: the piece "none" (the mesh's own boundary) is no piece.
    std::size_t kept = e.nbr_first[p];
    for (std::size_t k = e.nbr_first[p]; k < e.nbr.size(); ++k)
      if (e.nbr[k] != none) {
        e.nbr_mean.push_back(loops[k - e.nbr_first[p]][0]);
        e.nbr[kept++] = e.nbr[k];
      }
    e.nbr.resize(kept);
    e.nbr_first[p + 1] = static_cast<std::uint32_t>(kept);
    if (e.tris.size() == e.piece_first[p]) e.piece_ok[p] = 0;
    // Centres to try (a star's; a piece between two others goes in pairs): the axes' meeting
    // point for a junction-like piece (each border class's Newell normal), the corners' mean.
    std::uint8_t count = 0;
    vec meet(0.0);
    bool axes = false;
    if (kept - e.nbr_first[p] != 2) {
      for (std::size_t l = 0; l < loops.size(); ++l) {
        loops[l][1] = vec(0.0);
        const auto& b = e.classes[e.class_first[p] + l];
        for (std::uint32_t k = b.first; k < b.end; ++k) {
          const vec &x = pos[e.edges[k][0]], &y = pos[e.edges[k][1]];
          loops[l][1] += vec(x.y * y.z - x.z * y.y, x.z * y.x - x.x * y.z, x.x * y.y - x.y * y.x);
        }
      }
      axes = pc::axes_meet(std::span<const std::array<vec, 2>>(loops), meet);
    }
    const vec mean = corners_seen > 0 ? sum / static_cast<double>(corners_seen) : vec(0.0);
    e.mean[p] = mean;
    if (axes && loops.size() >= 3) e.centres[p][count++] = meet;
    e.centres[p][count++] = mean;
    if (axes && loops.size() < 3) e.centres[p][count++] = meet;
    e.centre_count[p] = count;
    // The capsule; its reach from the border's tails when they are all the corners (every corner
    // on a border edge of its face, the classes closed), else on first use (separated pairs).
    typename pc::engine<P>::card& c = e.cards[p];
    const std::array<vec, 2> ab = e.axis(p);
    c.a = ab[0], c.b = ab[1];
    c.reach = e.piece_first[p] == e.tris.size() ? pc::engine<P>::no_triangles : pc::engine<P>::unknown;
    e.tails_only[p] = closed && !inner ? 1 : 0;
    piece_box[p] = box;
    if (e.tails_only[p] != 0) e.capsule(p);  // cheap while the border is in cache (a band's)
  }
  e.piece_first[pieces] = static_cast<std::uint32_t>(e.tris.size());
  e.class_first[pieces] = static_cast<std::uint32_t>(e.classes.size());
  e.nbr_first[pieces] = static_cast<std::uint32_t>(e.nbr.size());
  r.triangles = e.tris.size();
  r.pieces = pieces;
  if (e.tris.size() >= 0xFFFFFFFFu)
    throw error(error_category::invalid_input, "self_intersections_by_pieces: more than 2^32 - 1 triangles");
  const std::size_t n = e.tris.size();

  // Certificates: one group per piece (itself and its neighbours), tried about its centres.
  // An inconsistently oriented mesh has no oriented groups: nothing is certified.
  pc::buffer<std::uint8_t> certified(pieces, 0, &e.arena), covered(pieces, 0, &e.arena);
  // A cap (a piece with one neighbour) certified in the star of its neighbour's other neighbour
  // (a junction's star reaching the end of a tube): that star's piece.
  pc::buffer<std::uint32_t> holder(pieces, none, &e.arena);
  // A cap certified with a pair of neighbouring pieces (a tube's last two bands): that pair.
  pc::buffer<std::array<std::uint32_t, 2>> cap_pair(pieces, {none, none}, &e.arena);
  e.nbr_held.assign(e.nbr.size(), 0);
  // (piece, group) of each certified group's members.
  pc::buffer<std::array<std::uint32_t, 2>> joined(&e.arena);
  const auto degree = [&](std::uint32_t p) { return e.nbr_first[p + 1] - e.nbr_first[p]; };
  const auto neighbours = [&](std::uint32_t a, std::uint32_t b) {
    for (std::uint32_t k = e.nbr_first[a]; k < e.nbr_first[a + 1]; ++k)
      if (e.nbr[k] == b) return true;
    return false;
  };
  // Pieces a and b (a ≠ b) lie in one certified group: a's star, b's, a common neighbour's, a
  // cap's holder's, or the pair's own.
  const auto held = [&](std::uint32_t a, std::uint32_t b) {
    for (std::uint32_t k = e.nbr_first[a]; k < e.nbr_first[a + 1]; ++k)
      if (e.nbr[k] == b && (certified[a] != 0 || certified[b] != 0 || e.nbr_held[k] != 0)) return true;
    for (std::uint32_t k = e.nbr_first[a]; k < e.nbr_first[a + 1]; ++k) {
      const std::uint32_t c = e.nbr[k];
      if (certified[c] != 0 && neighbours(c, b)) return true;
    }
    const auto in_star = [&](std::uint32_t h, std::uint32_t x) {
      return x == h || holder[x] == h || neighbours(h, x);
    };
    if ((holder[a] != none && in_star(holder[a], b)) || (holder[b] != none && in_star(holder[b], a)))
      return true;
    const auto in_pair = [&](const std::array<std::uint32_t, 2>& pq, std::uint32_t x) {
      return pq[0] != none && (x == pq[0] || x == pq[1] || cap_pair[x] == pq);
    };
    return in_pair(cap_pair[a], b) || in_pair(cap_pair[b], a);
  };
  if (m.is_consistently_oriented()) {
    e.stamp_piece.assign(pieces, 0);
    // Stars: a piece with its neighbours, for pieces with other than two (a junction, a cap, a
    // sphere), and with the caps at its neighbours' far ends (one group where a tube ends in a
    // cap); a tube's band, between two, is certified with each neighbour in turn below.
    const auto star = [&](std::uint32_t p, bool with_caps) {
      e.members.assign(1, p);
      for (std::uint32_t k = e.nbr_first[p]; k < e.nbr_first[p + 1]; ++k) e.members.push_back(e.nbr[k]);
      const std::size_t plain = e.members.size();
      for (std::uint32_t k = e.nbr_first[p]; k < e.nbr_first[p + 1] && with_caps; ++k) {
        const std::uint32_t n = e.nbr[k];
        if (degree(n) != 2) continue;
        const std::uint32_t q =
            e.nbr[e.nbr_first[n]] == p ? e.nbr[e.nbr_first[n] + 1] : e.nbr[e.nbr_first[n]];
        if (q != p && degree(q) == 1 && holder[q] == none && certified[q] == 0) e.members.push_back(q);
      }
      if (with_caps && e.members.size() == plain) return false;  // nothing to add
      bool ok = false;
      for (std::uint8_t k = 0; k < e.centre_count[p] && !ok; ++k) ok = e.certify(e.centres[p][k]);
      // A cap (flat about its own mean) is seen from the middle of the tube it closes.
      if (!ok && degree(p) == 1) ok = e.certify(e.mean[e.nbr[e.nbr_first[p]]]);
      if (!ok) return false;
      certified[p] = 1;
      for (const std::uint32_t x : e.members)
        joined.push_back({x, static_cast<std::uint32_t>(r.certified_groups)});
      ++r.certified_groups;
      for (std::size_t i = 0; i < e.members.size(); ++i) {
        covered[e.members[i]] = 1;
        if (i >= plain) holder[e.members[i]] = p;
      }
      return true;
    };
    // Junctions and spheres first, then pairs of neighbours no star holds (a tube's bands, about
    // the middle of the border between them, with the caps beyond them), then the caps left.
    const auto stars = [&](bool caps) {
      for (std::uint32_t p = 0; p < pieces; ++p) {
        if (e.piece_ok[p] == 0 || degree(p) == 2 || (degree(p) == 1) != caps || holder[p] != none ||
            cap_pair[p][0] != none)
          continue;
        if (!star(p, true)) star(p, false);
      }
    };
    stars(false);
    const auto pairs = [&](bool caps) {  // caps: the pairs with a cap no group took, alone
      for (std::uint32_t p = 0; p < pieces; ++p)
        for (std::uint32_t k = e.nbr_first[p]; k < e.nbr_first[p + 1]; ++k) {
          const std::uint32_t q = e.nbr[k];
          if (q < p || (degree(p) == 1 || degree(q) == 1) != caps || held(p, q)) continue;
          e.members.assign({p, q});
          for (const std::uint32_t x : {p, q})
            for (std::uint32_t j = e.nbr_first[x]; j < e.nbr_first[x + 1] && !caps; ++j) {
              const std::uint32_t c = e.nbr[j];
              if (degree(c) == 1 && holder[c] == none && cap_pair[c][0] == none && certified[c] == 0)
                e.members.push_back(c);
            }
          const std::size_t with_caps = e.members.size();
          bool ok = e.certify(e.nbr_mean[k]);
          if (!ok && with_caps > 2) {
            e.members.resize(2);
            ok = e.certify(e.nbr_mean[k]);
          }
          if (!ok) continue;
          e.nbr_held[k] = 1;
          for (std::uint32_t j = e.nbr_first[q]; j < e.nbr_first[q + 1]; ++j)
            if (e.nbr[j] == p) e.nbr_held[j] = 1;
          for (std::size_t i = 2; i < e.members.size(); ++i)
            cap_pair[e.members[i]] = {p, q}, covered[e.members[i]] = 1;
          covered[p] = covered[q] = 1;
          for (const std::uint32_t x : e.members)
            joined.push_back({x, static_cast<std::uint32_t>(r.certified_groups)});
          ++r.certified_groups;
        }
    };
    pairs(false);
    stars(true);
    pairs(true);
  }

  // Each piece's certified groups, in increasing order, for the grid below (a counting sort).
  for (std::uint32_t p = 0; p < pieces; ++p) e.cards[p].group_first = e.cards[p].group_end = 0;
  for (const auto& [x, g] : joined) ++e.cards[x].group_end;
  for (std::uint32_t p = 0, sum = 0; p < pieces; ++p) {
    e.cards[p].group_first = sum;
    sum += e.cards[p].group_end;
    e.cards[p].group_end = e.cards[p].group_first;
  }
  e.group_of.resize(joined.size());
  for (const auto& [x, g] : joined) e.group_of[e.cards[x].group_end++] = g;
  joined.clear(), joined.shrink_to_fit();

  // Boxes and zero-area triangles: per piece, for the pieces the pair tests reach and for every
  // piece no certified group holds (a certified triangle has area).
  struct boxed {
    std::array<double, 6> box;
    bool degenerate;
  };
  pc::buffer<boxed> tri_box(&e.arena);                          // of the prepared pieces, in turn
  pc::buffer<std::uint32_t> box_first(pieces, none, &e.arena);  // where a prepared piece's boxes start
  std::vector<std::uint32_t> degenerate_faces;
  const auto prepare = [&](std::uint32_t p) {
    if (box_first[p] != none) return;
    box_first[p] = static_cast<std::uint32_t>(tri_box.size());
    for (std::uint32_t t = e.piece_first[p]; t < e.piece_first[p + 1]; ++t) {
      const pc::triangle& q = e.tris[t];
      const vec &a = pos[q.v[0]], &b = pos[q.v[1]], &c = pos[q.v[2]];
      boxed& x = tri_box.emplace_back();
      x.degenerate = covered[p] == 0 && si::degenerate(a, b, c);
      if (x.degenerate) {
        ++r.degenerate_triangles;
        if (degenerate_faces.empty() || degenerate_faces.back() != q.face) degenerate_faces.push_back(q.face);
      }
      for (int k = 0; k < 3; ++k) {
        x.box[static_cast<std::size_t>(k)] = std::min({a[k], b[k], c[k]});
        x.box[static_cast<std::size_t>(k) + 3] = std::max({a[k], b[k], c[k]});
      }
    }
  };
  for (std::uint32_t p = 0; p < pieces; ++p)
    if (covered[p] == 0) prepare(p);

  const std::size_t budget = options.work_budget.limit(256 * n + (std::size_t{1} << 20));
  const std::size_t limit = budget != 0 ? budget : std::numeric_limits<std::size_t>::max();

  std::vector<std::uint64_t> found;
  std::size_t compact_at = 1 << 16;
  std::array<glm::dvec3, 3> p3{}, q3{};
  // Triangles a of piece pa and b of piece pb (both prepared).
  const auto test = [&](std::uint32_t pa, std::uint32_t a, std::uint32_t pb, std::uint32_t b) {
    const pc::triangle &x = e.tris[a], &y = e.tris[b];
    if (x.face == y.face) return;
    const boxed &bx = tri_box[box_first[pa] + (a - e.piece_first[pa])],
                &by = tri_box[box_first[pb] + (b - e.piece_first[pb])];
    if (bx.degenerate || by.degenerate) return;
    if ((static_cast<int>(bx.box[0] <= by.box[3]) & static_cast<int>(by.box[0] <= bx.box[3]) &
         static_cast<int>(bx.box[1] <= by.box[4]) & static_cast<int>(by.box[1] <= bx.box[4]) &
         static_cast<int>(bx.box[2] <= by.box[5]) & static_cast<int>(by.box[2] <= bx.box[5])) == 0)
      return;
    ++r.pairs_tested;
    for (std::size_t k = 0; k < 3; ++k) p3[k] = pos[x.v[k]], q3[k] = pos[y.v[k]];
    if (!si::pair_intersects(p3, x.v, q3, y.v)) return;
    ++r.intersecting_triangle_pairs;
    const std::uint32_t f = std::min(x.face, y.face), g = std::max(x.face, y.face);
    found.push_back(static_cast<std::uint64_t>(f) << 32 | g);
    if (found.size() >= compact_at) {
      si::compact(found);
      compact_at = std::max(compact_at, 2 * found.size());
    }
  };
  std::size_t work = 0;
  bool complete = true;
  // Pieces no certified group holds: every pair of their own triangles.
  for (std::uint32_t p = 0; p < pieces && complete; ++p) {
    if (covered[p] != 0) continue;
    const std::size_t k = e.piece_first[p + 1] - e.piece_first[p];
    if (k > 64) {  // a large piece: its boxes' grid
      pc::buffer<std::array<double, 6>> boxes(k, &e.arena);
      for (std::size_t i = 0; i < k; ++i) boxes[i] = tri_box[box_first[p] + i].box;
      const std::uint32_t first = e.piece_first[p];
      const si::box_pair_count own = si::for_each_box_pair(
          detail::span_of(boxes), limit - work,
          [&](std::uint32_t a, std::uint32_t b) {
            test(p, first + a, p, first + b);
            return true;
          },
          1, &e.arena);
      work += own.candidate_pairs;
      complete = own.complete;
      continue;
    }
    if (k * (k - 1) / 2 > limit - work) {
      complete = false;
      break;
    }
    work += k * (k - 1) / 2;
    for (std::uint32_t a = e.piece_first[p]; a < e.piece_first[p + 1]; ++a)
      for (std::uint32_t b = a + 1; b < e.piece_first[p + 1]; ++b) test(p, a, p, b);
  }
  // Pairs of pieces whose boxes overlap and that no certified group holds: every pair of triangles.
  std::size_t held_pairs = 0, separated_pairs = 0;
  if (complete) {
    const si::box_pair_count pairs = si::for_each_box_pair(
        detail::span_of(piece_box), limit - work,
        [&](std::uint32_t a, std::uint32_t b) {
          if (e.cards[a].reach == e.no_triangles || e.cards[b].reach == e.no_triangles) return true;
          if (e.held(a, b)) {
            ++held_pairs;
            return true;
          }
          if (e.separated(a, b)) {
            ++separated_pairs;
            return true;
          }
          const std::size_t k = std::size_t{e.piece_first[a + 1] - e.piece_first[a]} *
                                (e.piece_first[b + 1] - e.piece_first[b]);
          if (k > limit - work) return false;
          work += k;
          prepare(a), prepare(b);
          for (std::uint32_t x = e.piece_first[a]; x < e.piece_first[a + 1]; ++x)
            for (std::uint32_t y = e.piece_first[b]; y < e.piece_first[b + 1]; ++y) test(a, x, b, y);
          return true;
        },
        3, &e.arena);  // cells three median pieces wide: a third of the grid's cost, few more candidates
    work += pairs.candidate_pairs;
    complete = pairs.complete && work <= limit;
  }
  r.candidate_pairs = work;
  r.certified_piece_pairs = held_pairs;
  r.separated_piece_pairs = separated_pairs;
  r.complete = complete;
  auto finish = [&] {
    r.milliseconds = start.ms();
    r.work = r.candidate_pairs;
    return r;
  };
  if (!r.complete) {
    std::string message = "self_intersections_by_pieces: the work budget of ";
    message += std::to_string(budget);
    message +=
        " candidate box pairs was spent: the answer is partial (raise "
        "self_intersection_options::work_budget)";
    r.diagnostics.push_back(std::move(message));
  }
  std::sort(degenerate_faces.begin(), degenerate_faces.end());
  degenerate_faces.erase(std::unique(degenerate_faces.begin(), degenerate_faces.end()),
                         degenerate_faces.end());
  for (std::size_t i = 0; i < degenerate_faces.size() && i < options.max_reported; ++i)
    r.degenerate_faces.emplace_back(degenerate_faces[i]);
  si::report_pairs(r, found, options.max_reported);
  return finish();
}

}  // namespace cellforge
