// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The engine of cells/certify.hpp (included at its end; including this first includes that).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/detail/triangle_pairs.hpp"
#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/certify.hpp"
#include "cellforge/cells/validate.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/predicates.hpp"

namespace cellforge::detail::certify {

using vec = glm::dvec3;
using std::uint32_t;
inline constexpr uint32_t none = 0xFFFFFFFFu;

/// "a, b, c" of the first `named` values, "and k more" past them. O(named).
template <class = void>
std::string list(std::span<const uint32_t> xs, std::size_t named, std::size_t stride = 1,
                 std::size_t pick = 0) {
  std::string s;
  const std::size_t n = xs.size() / stride;
  for (std::size_t i = 0; i < n && i < named; ++i) {
    if (i) s += ", ";
    s += std::to_string(xs[i * stride + pick]);
  }
  if (n > named) s += cellforge::detail::cat(" and ", std::to_string(n - named), " more");
  return s;
}

/// The certificate's work counter: false once the budget is spent. O(1).
struct budget {
  std::uint64_t limit = 0, used = 0;
  bool spend(std::uint64_t n) {
    used += n;
    return limit == 0 || used <= limit;
  }
  std::uint64_t left() const { return limit == 0 ? 0 : (used >= limit ? 1 : limit - used); }
};

/// A face as the crossing test sees it: box, exact plane (when planar), triangles.
struct face_info {
  std::array<double, 6> box{};
  double extent = 0.0;  ///< bounding-box diagonal
  /// 0: not exactly planar; 1: every vertex has coordinate `axis` equal to `level`; 2: every
  /// vertex exactly on the plane of `plane` (three of its vertices).
  std::uint8_t planar = 0;
  int axis = 0;
  double level = 0.0;
  std::array<uint32_t, 3> plane{};
  /// Exactly planar, one loop, strictly convex in the projection on axes (u, w), turning `turn`.
  bool convex = false;
  /// An axis-aligned rectangle: four vertices, edges parallel to the axes; the face is its box.
  bool rectangle = false;
  int u = 0, w = 1, turn = 1;
  uint32_t tri_begin = 0, tri_end = 0;  ///< into the triangle list, once triangulated
  bool triangulated = false;
};

/// One weakly simple ring of a face with holes bridged in, triangulated by ear clipping in the
/// projection that drops `drop_axis` (exact orient2d; vertices at an ear corner's position do not
/// block it). Emits vertex ids. O(n · reflex vertices) per lap, O(n² · r) at worst.
template <class Add>
void clip_ring(std::span<const vec> pts, std::vector<uint32_t> ring, int u, int w, int sense, Add&& add) {
  auto turn = [&](uint32_t a, uint32_t b, uint32_t c) {
    return sense * orient2d(pts[a][u], pts[a][w], pts[b][u], pts[b][w], pts[c][u], pts[c][w]);
  };
  auto same = [&](uint32_t a, uint32_t b) { return pts[a][u] == pts[b][u] && pts[a][w] == pts[b][w]; };
  std::size_t n = ring.size();
  std::vector<uint32_t> next(n), prev(n);
  for (std::size_t i = 0; i < n; ++i)
    next[i] = static_cast<uint32_t>((i + 1) % n), prev[i] = static_cast<uint32_t>((i + n - 1) % n);
  // An ear whose area is at rounding level for its size (three vertices collinear up to the
  // rounding of the input) waits until a lap finds no other: its diagonal would pass through
  // the middle vertex's neighbourhood, off the face where the face is not exactly planar.
  auto thin = [&](uint32_t a, uint32_t b, uint32_t c) {
    const vec &p = pts[a], &q = pts[b], &r = pts[c];
    const double ux = q[u] - p[u], uy = q[w] - p[w], vx = r[u] - p[u], vy = r[w] - p[w];
    const double wx = r[u] - q[u], wy = r[w] - q[w];
    const double longest = std::max({ux * ux + uy * uy, vx * vx + vy * vy, wx * wx + wy * wy});
    return std::fabs(ux * vy - uy * vx) <= 1e-12 * longest;
  };
  uint32_t i = 0;
  std::size_t stall = 0;
  bool thin_ok = false;
  while (n > 3) {
    const uint32_t a = prev[i], c = next[i];
    bool ear = turn(ring[a], ring[i], ring[c]) > 0 && (thin_ok || !thin(ring[a], ring[i], ring[c]));
    if (ear) {
      for (uint32_t r = next[c]; r != a && ear; r = next[r]) {
        const uint32_t x = ring[r];
        if (same(x, ring[a]) || same(x, ring[i]) || same(x, ring[c])) continue;
        if (turn(ring[prev[r]], x, ring[next[r]]) > 0) continue;  // only reflex or flat vertices block
        ear = !(turn(ring[a], ring[i], x) >= 0 && turn(ring[i], ring[c], x) >= 0 &&
                turn(ring[c], ring[a], x) >= 0);
      }
    }
    if (!ear && ++stall > n) {
      stall = 0;
      if (!thin_ok) {  // a lap without a good ear: slivers may go now
        thin_ok = true;
        continue;
      }
      // A lap without any ear (a face crossing itself): clip the first convex corner anyway.
      for (std::size_t k = 0; k < n && turn(ring[prev[i]], ring[i], ring[next[i]]) <= 0; ++k) i = next[i];
      ear = true;
    }
    if (!ear) {
      i = next[i];
      continue;
    }
    add(ring[prev[i]], ring[i], ring[next[i]]);
    next[prev[i]] = next[i];
    prev[next[i]] = prev[i];
    i = next[i];
    --n;
    stall = 0;
    thin_ok = false;
  }
  add(ring[prev[i]], ring[i], ring[next[i]]);
}

/// Triangulates face f of cc (loops[0] outer, the rest holes) into vertex-id triangles: one loop
/// as self_intersections does; holes bridged into the outer loop first, each from its extreme
/// vertex to the nearest ring vertex it sees (exact segment tests), then clip_ring. O(n) for
/// convex faces; O(n² · holes) to bridge.
template <class Add>
void triangulate_face(const cell_topology& cc, std::span<const vec> pts, cell_face f, Add&& add) {
  std::vector<uint32_t> ids;
  std::vector<vec> corners;
  const auto outer = cc.loop_vertices(f, 0);
  for (const cell_vertex v : outer) ids.push_back(v.idx()), corners.push_back(pts[v.idx()]);
  if (cc.num_loops(f) == 1) {
    self_intersect::triangulate_polygon(detail::span_of(ids), detail::span_of(corners), add);
    return;
  }
  // The projection: drop the dominant axis of the outer loop's Newell normal.
  vec centroid(0.0);
  for (const vec& p : corners) centroid += p;
  centroid /= static_cast<double>(corners.size());
  const vec nrm = ears::newell_normal(detail::span_of(std::as_const(corners)), centroid);
  const int k = ears::dominant_axis(nrm), u = (k + 1) % 3, w = (k + 2) % 3;
  const int sense = nrm[k] > 0 ? 1 : -1;
  auto area2 = [&](const std::vector<uint32_t>& loop) {
    double a = 0;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const vec &p = pts[loop[i]], &q = pts[loop[(i + 1) % loop.size()]];
      a += p[u] * q[w] - q[u] * p[w];
    }
    return a;
  };
  std::vector<uint32_t> ring = ids;
  std::vector<std::vector<uint32_t>> holes;
  for (std::size_t l = 1; l < cc.num_loops(f); ++l) {
    const auto hv = cc.loop_vertices(f, l);
    std::vector<uint32_t> h;
    for (const cell_vertex v : hv) h.push_back(v.idx());
    if (area2(h) * sense > 0) std::reverse(h.begin(), h.end());  // holes turn against the outer loop
    holes.push_back(std::move(h));
  }
  // Holes by decreasing extreme u: each bridge then lands on the ring or an earlier hole.
  auto extreme = [&](const std::vector<uint32_t>& h) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < h.size(); ++i)
      if (pts[h[i]][u] > pts[h[best]][u] ||
          (pts[h[i]][u] == pts[h[best]][u] && pts[h[i]][w] > pts[h[best]][w]))
        best = i;
    return best;
  };
  std::sort(holes.begin(), holes.end(),
            [&](const auto& a, const auto& b) { return pts[a[extreme(a)]][u] > pts[b[extreme(b)]][u]; });
  auto o2 = [&](uint32_t a, uint32_t b, uint32_t c) {
    return orient2d(pts[a][u], pts[a][w], pts[b][u], pts[b][w], pts[c][u], pts[c][w]);
  };
  auto on_seg = [&](uint32_t a, uint32_t b, uint32_t c) {  // c collinear with ab, within its box
    return std::min(pts[a][u], pts[b][u]) <= pts[c][u] && pts[c][u] <= std::max(pts[a][u], pts[b][u]) &&
           std::min(pts[a][w], pts[b][w]) <= pts[c][w] && pts[c][w] <= std::max(pts[a][w], pts[b][w]);
  };
  // True when the segment m-v is blocked by the segment a-b (touching counts, but not at a
  // point of m's or v's position).
  auto blocks = [&](uint32_t m, uint32_t v, uint32_t a, uint32_t b) {
    const bool am = pts[a] == pts[m] || pts[a] == pts[v], bm = pts[b] == pts[m] || pts[b] == pts[v];
    if (am && bm) return false;
    const int s1 = o2(m, v, a), s2 = o2(m, v, b), s3 = o2(a, b, m), s4 = o2(a, b, v);
    if (s1 * s2 < 0 && s3 * s4 < 0) return true;
    return (s1 == 0 && !am && on_seg(m, v, a)) || (s2 == 0 && !bm && on_seg(m, v, b)) ||
           (s3 == 0 && on_seg(a, b, m) && pts[m] != pts[a] && pts[m] != pts[b]) ||
           (s4 == 0 && on_seg(a, b, v) && pts[v] != pts[a] && pts[v] != pts[b]);
  };
  for (std::size_t hi = 0; hi < holes.size(); ++hi) {
    auto& h = holes[hi];
    const std::size_t mi = extreme(h);
    const uint32_t m = h[mi];
    std::vector<std::size_t> order(ring.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return glm::length(pts[ring[a]] - pts[m]) < glm::length(pts[ring[b]] - pts[m]);
    });
    std::size_t at = ring.size();
    for (const std::size_t i : order) {
      const uint32_t v = ring[i];
      if (pts[v] == pts[m]) continue;
      // The bridge must leave v into the face: inside the corner prev(v), v, next(v).
      const uint32_t pv = ring[(i + ring.size() - 1) % ring.size()], nv = ring[(i + 1) % ring.size()];
      const int convex = sense * o2(pv, v, nv);
      const bool left_next = sense * o2(v, nv, m) > 0, left_prev = sense * o2(pv, v, m) > 0;
      if (!(convex > 0 ? left_next && left_prev : left_next || left_prev)) continue;
      bool seen = true;
      for (std::size_t e = 0; e < ring.size() && seen; ++e)
        seen = !blocks(m, v, ring[e], ring[(e + 1) % ring.size()]);
      for (std::size_t g = hi; g < holes.size() && seen; ++g)
        for (std::size_t e = 0; e < holes[g].size() && seen; ++e)
          seen = !blocks(m, v, holes[g][e], holes[g][(e + 1) % holes[g].size()]);
      if (seen) {
        at = i;
        break;
      }
    }
    if (at == ring.size()) at = order.empty() ? 0 : order.front();  // nothing seen (a broken face): nearest
    std::vector<uint32_t> spliced(ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(at) + 1);
    for (std::size_t s = 0; s <= h.size(); ++s) spliced.push_back(h[(mi + s) % h.size()]);
    spliced.push_back(ring[at]);
    spliced.insert(spliced.end(), ring.begin() + static_cast<std::ptrdiff_t>(at) + 1, ring.end());
    ring = std::move(spliced);
  }
  clip_ring(pts, std::move(ring), u, w, sense, add);
}

/// The exact test of one segment (ends p, q, complex ids ip, iq or none) against one closed
/// triangle (ids t): true when they meet other than at a shared vertex. O(1).
template <class = void>
bool segment_meets_triangle(const vec& p, const vec& q, uint32_t ip, uint32_t iq, std::span<const vec> pts,
                            const std::array<uint32_t, 3>& t) {
  namespace si = self_intersect;
  const vec &a = pts[t[0]], &b = pts[t[1]], &c = pts[t[2]];
  const int sp_at = ip == t[0] ? 0 : ip == t[1] ? 1 : ip == t[2] ? 2 : -1;
  const int sq_at = iq == t[0] ? 0 : iq == t[1] ? 1 : iq == t[2] ? 2 : -1;
  if (sp_at >= 0 && sq_at >= 0) return true;  // a diagonal of the face's triangulation: inside it
  if (sp_at >= 0 || sq_at >= 0) {
    const int at = sp_at >= 0 ? sp_at : sq_at;
    const vec& x = sp_at >= 0 ? q : p;
    if (orient3d(a, b, c, x) != 0) return false;  // leaves the triangle's plane at the shared corner
    const vec& v = pts[t[static_cast<std::size_t>(at)]];
    const si::tri tr = si::make_tri(v, pts[t[static_cast<std::size_t>((at + 1) % 3)]],
                                    pts[t[static_cast<std::size_t>((at + 2) % 3)]]);
    return si::in_corner(tr, x);
  }
  const int sp = orient3d(a, b, c, p), sq = orient3d(a, b, c, q);
  return si::segment_meets(p, q, sp, sq, si::make_tri(a, b, c));
}

/// The state of one certify run over a complex (and maybe a wireframe).
template <class = void>
class basic_certifier;
using certifier = basic_certifier<>;

template <class>
class basic_certifier {
 public:
  basic_certifier(const cell_topology& cc, std::span<const vec> pts, const input_wire* wire,
                  const certify_options& options, certificate_result& r)
      : cc_(cc), pts_(pts), wire_(wire), o_(options), r_(r) {}

  void run() {
    bounding_box box;
    for (const vec& p : pts_) box.add(p);
    if (wire_)
      for (const vec& p : wire_->points) box.add(p);
    merge_ = o_.merge.absolute(box);
    flat_ = o_.planarity.absolute(box);
    const std::uint64_t size = cc_.num_faces() + cc_.num_edges() + (wire_ ? wire_->edges.size() : 0);
    budget_.limit = o_.work_budget.limit(256 * size + (std::uint64_t{1} << 22));
    count_faces();
    if (o_.check_edges) check_edges();
    if (o_.check_volumes) check_volumes();
    if (wire_ && o_.check_input_edges) check_input_edges();
    if (o_.check_crossings && r_.complete) check_crossings();
    r_.work = budget_.used;
    if (!r_.complete)
      r_.diagnostics.push_back(cellforge::detail::cat("the work budget of ", std::to_string(budget_.limit),
                                                      " steps ran out; raise certify_options::work_budget"));
  }

 private:
  using K = certificate_failure::kind;

  // The elements by const reference: the message may be built from them in the same call.
  void fail(K kind, std::string message, const std::vector<uint32_t>& elements) {
    r_.failures.push_back({kind, std::move(message), elements});
  }

  void count_faces() {
    for (const cell_face f : cc_.faces())
      if (cc_.face_volumes(f).empty()) ++r_.faces_without_volume;
    info_.resize(cc_.num_faces());
    for (const cell_face f : cc_.faces()) {
      face_info& fi = info_[f.idx()];
      bounding_box b;
      for (std::size_t l = 0; l < cc_.num_loops(f); ++l)
        for (const cell_vertex v : cc_.loop_vertices(f, l)) b.add(pts_[v.idx()]);
      fi.box = {b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z};
      fi.extent = b.diagonal();
    }
  }

  // ---- genuine edges
  void check_edges() {
    std::vector<uint32_t> seams;
    for (const cell_edge e : cc_.edges()) {
      const auto ef = cc_.edge_faces(e);
      if (ef.empty()) {
        ++r_.dangling_edges;
      } else if (ef.size() == 1) {
        if (cc_.face_volumes(ef[0].handle).empty()) ++r_.free_edges;  // else the volume is open
      } else if (ef.size() == 2 && seam(e, ef[0], ef[1])) {
        seams.push_back(e.idx());
      }
    }
    r_.seam_edges = seams.size();
    if (!seams.empty() && !o_.seams_fail)
      r_.diagnostics.push_back(std::to_string(seams.size()) +
                               " edges lie on two coplanar faces only (seams): " + list(seams, o_.max_named));
    if (!seams.empty() && o_.seams_fail)
      fail(K::seam_edge,
           (seams.size() == 1 ? "edge " : "edges ") + list(seams, o_.max_named) +
               (seams.size() == 1 ? " lies" : " lie") +
               " on two coplanar faces only: a seam inside a flat surface, not an edge of a solid",
           seams);
  }

  /// Faces a and b at e lie in one plane, on opposite sides of e. O(1).
  bool seam(cell_edge e, const oriented<cell_face>& a, const oriented<cell_face>& b) const {
    const vec &na = cells::access::unit_normal(cc_, a.handle),
              &nb = cells::access::unit_normal(cc_, b.handle);
    const double extent = std::max(info_[a.handle.idx()].extent, info_[b.handle.idx()].extent);
    if (!(glm::length(glm::cross(na, nb)) * extent <= flat_)) return false;
    const vec d = pts_[cc_.target(e).idx()] - pts_[cc_.source(e).idx()];
    const vec into_a = glm::cross(na, double(a.sign) * d), into_b = glm::cross(nb, double(b.sign) * d);
    return glm::dot(into_a, into_b) < 0.0;  // the same side is a fold: the crossing test's
  }

  // ---- volumes
  void check_volumes() {
    const std::size_t ne = cc_.num_edges(), nv = cc_.num_vertices();
    std::vector<int> uses(ne, 0), net(ne, 0);
    std::vector<uint32_t> touched;
    std::vector<uint32_t> open, four, pinched, inverted;
    // Corners (face, vertex) of one volume, joined across the edges it uses twice.
    std::vector<uint32_t> parent, vertex_root(nv, none), vertex_stamp(nv, none);
    std::vector<std::array<uint32_t, 2>> first_use(ne);  // (corner of the use's start, of its end)
    std::string first_open, first_four, first_pinch, first_inverted;
    for (const cell_volume c : cc_.volumes()) {
      if (!budget_.spend(cc_.volume_faces(c).size())) return stop();
      parent.clear();
      for (const auto& [f, sign] : cc_.volume_faces(c))
        for (std::size_t l = 0; l < cc_.num_loops(f); ++l) {
          const auto es = cc_.loop_edges(f, l);
          const auto base = static_cast<uint32_t>(parent.size());
          for (std::size_t k = 0; k < es.size(); ++k) parent.push_back(base + static_cast<uint32_t>(k));
          for (std::size_t k = 0; k < es.size(); ++k) {
            const uint32_t e = es[k].handle.idx();
            const uint32_t from = base + static_cast<uint32_t>(k),
                           to = base + static_cast<uint32_t>((k + 1) % es.size());
            // Direction of this use under the volume's sign: +1 along the edge's source → target.
            const int dir = sign * es[k].sign;
            if (uses[e] == 0) {
              touched.push_back(e);
              // Corners at the edge's source and target, whichever way this use runs.
              first_use[e] =
                  es[k].sign > 0 ? std::array<uint32_t, 2>{from, to} : std::array<uint32_t, 2>{to, from};
            } else if (uses[e] == 1) {
              const std::array<uint32_t, 2> here =
                  es[k].sign > 0 ? std::array<uint32_t, 2>{from, to} : std::array<uint32_t, 2>{to, from};
              for (int s = 0; s < 2; ++s)
                unite(parent, first_use[e][static_cast<std::size_t>(s)], here[static_cast<std::size_t>(s)]);
            }
            ++uses[e];
            net[e] += dir;
          }
        }
      uint32_t bad_open = none, bad_four = none;
      int bad_uses = 0;
      for (const uint32_t e : touched) {
        if (uses[e] == 2 && net[e] == 0) {
        } else if (uses[e] >= 4 && uses[e] % 2 == 0 && net[e] == 0) {
          if (bad_four == none) bad_four = e, bad_uses = uses[e];
        } else if (bad_open == none) {
          bad_open = e;
          bad_uses = uses[e] * 16 + (net[e] < 0 ? -net[e] : net[e]);
        }
      }
      for (const uint32_t e : touched) uses[e] = net[e] = 0;
      touched.clear();
      if (bad_open != none) {
        open.push_back(c.idx()), open.push_back(bad_open);
        if (first_open.empty()) {
          const int n = bad_uses / 16;
          first_open = cellforge::detail::cat(
              "volume ", std::to_string(c.idx()), " is not closed: its faces use edge ",
              std::to_string(bad_open),
              (n == 1   ? " once"
               : n == 2 ? " twice in the same direction"
                        : cellforge::detail::cat(" ", std::to_string(n), " times, unpaired")));
        }
        continue;
      }
      if (bad_four != none) {
        four.push_back(c.idx()), four.push_back(bad_four);
        if (first_four.empty())
          first_four = cellforge::detail::cat(
              "volume ", std::to_string(c.idx()), " uses edge ", std::to_string(bad_four), " ",
              (bad_uses == 4 ? std::string("four") : std::to_string(bad_uses)), " times");
        continue;
      }
      // Manifold at the vertices: each vertex's corners form one fan.
      uint32_t pinch = none;
      uint32_t corner = 0;
      for (const auto& [f, sign] : cc_.volume_faces(c))
        for (std::size_t l = 0; l < cc_.num_loops(f); ++l)
          for (const cell_vertex v : cc_.loop_vertices(f, l)) {
            const uint32_t root = find(parent, corner++);
            if (vertex_stamp[v.idx()] != c.idx()) {
              vertex_stamp[v.idx()] = c.idx();
              vertex_root[v.idx()] = root;
            } else if (vertex_root[v.idx()] != root && pinch == none) {
              pinch = v.idx();
            }
          }
      if (pinch != none) {
        pinched.push_back(c.idx()), pinched.push_back(pinch);
        if (first_pinch.empty())
          first_pinch =
              cellforge::detail::cat("volume ", std::to_string(c.idx()), " is pinched at vertex ",
                                     std::to_string(pinch), " (its faces there make more than one fan)");
        continue;
      }
      // Positive volume against the volume's own size (as validate judges it).
      bounding_box vb;
      for (const auto& vf : cc_.volume_faces(c))
        for (const cell_vertex v : cc_.loop_vertices(vf.handle, 0)) vb.add(pts_[v.idx()]);
      const double vd = vb.diagonal();
      const double vol = cells::signed_volume_of(cc_, pts_, c, vb.center());
      if (!(vol > 1e-12 * vd * vd * vd)) {
        inverted.push_back(c.idx());
        if (first_inverted.empty()) {
          char buf[64];
          std::snprintf(buf, sizeof buf, "%g", vol);
          first_inverted = cellforge::detail::cat(
              "volume ", std::to_string(c.idx()), " has signed volume ", buf,
              (vol < 0 ? " (its faces' normals point into it)" : " (it encloses nothing)"));
        }
      }
    }
    auto more = [&](const std::vector<uint32_t>& xs, std::size_t stride) {
      const std::size_t n = xs.size() / stride;
      return n > 1 ? cellforge::detail::cat(" (and ", std::to_string(n - 1), " more volumes)")
                   : std::string();
    };
    if (!open.empty()) fail(K::open_volume, first_open + more(open, 2), open);
    if (!four.empty()) fail(K::non_manifold_volume, first_four + more(four, 2), four);
    if (!pinched.empty()) {
      if (auto* f = find_failure(K::non_manifold_volume)) {
        f->elements.insert(f->elements.end(), pinched.begin(), pinched.end());
      } else {
        fail(K::non_manifold_volume, first_pinch + more(pinched, 2), pinched);
      }
    }
    if (!inverted.empty()) fail(K::inverted_volume, first_inverted + more(inverted, 1), inverted);
  }

  certificate_failure* find_failure(K kind) {
    for (auto& f : r_.failures)
      if (f.what == kind) return &f;
    return nullptr;
  }

  static uint32_t find(std::vector<uint32_t>& parent, uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  static void unite(std::vector<uint32_t>& parent, uint32_t a, uint32_t b) {
    parent[find(parent, a)] = find(parent, b);
  }

  void stop() { r_.complete = false; }

  // ---- input edges
  /// The complex vertex (or, past the complex's vertices, another input vertex) within the
  /// merge tolerance of each input vertex: a hash grid of cell side = the tolerance. O(V) expected.
  void match_vertices() {
    const std::size_t nv = cc_.num_vertices(), ni = wire_->points.size();
    const double side = merge_ > 0 ? merge_ : 1.0;
    const double inv = 1.0 / side;
    // Cell coordinates clamped into int64 before the cast (a far point at a tiny tolerance would
    // overflow it) and hashed in unsigned arithmetic, which wraps; clamped points share cells,
    // and every candidate's distance is measured anyway.
    auto cell = [&](double c, int d) {
      const double f = std::clamp(std::floor(c * inv), -9.0e18, 9.0e18);
      return static_cast<std::uint64_t>(static_cast<std::int64_t>(f)) +
             static_cast<std::uint64_t>(std::int64_t{d});
    };
    auto key_of = [&](const vec& p, int dx, int dy, int dz) {
      return cell(p.x, dx) * 73856093u ^ cell(p.y, dy) * 19349663u ^ cell(p.z, dz) * 83492791u;
    };
    std::unordered_map<std::uint64_t, std::vector<uint32_t>> grid;
    grid.reserve(nv + ni);
    std::vector<vec> rep(pts_.begin(), pts_.end());
    for (uint32_t v = 0; v < nv; ++v) grid[key_of(pts_[v], 0, 0, 0)].push_back(v);
    match_.assign(ni, none);
    for (uint32_t i = 0; i < ni; ++i) {
      const vec& p = wire_->points[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("certify: input vertex ", std::to_string(i),
                                           " has a NaN or infinite coordinate"));
      uint32_t best = none;
      double best_d = merge_;
      auto look = [&](std::uint64_t key) {
        const auto it = grid.find(key);
        if (it == grid.end()) return;
        for (const uint32_t v : it->second) {
          const double d = glm::length(rep[v] - p);
          if (d <= best_d && (best == none || d < best_d || v < best)) best = v, best_d = d;
        }
      };
      look(key_of(p, 0, 0, 0));
      if (best == none || best_d > 0)
        for (int dx = -1; dx <= 1; ++dx)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz)
              if (dx || dy || dz) look(key_of(p, dx, dy, dz));
      if (best == none) {  // off the complex: its own representative
        best = static_cast<uint32_t>(rep.size());
        rep.push_back(p);
        grid[key_of(p, 0, 0, 0)].push_back(best);
      }
      match_[i] = best;
    }
    reps_ = rep.size();
  }

  /// The complex edge joining u and w, or none. O(degree of u).
  uint32_t edge_between(uint32_t u, uint32_t w) const {
    for (const auto& oe : cc_.vertex_edges(cell_vertex(u))) {
      const cell_edge e = oe.handle;
      const uint32_t other = oe.sign > 0 ? cc_.target(e).idx() : cc_.source(e).idx();
      if (other == w) return e.idx();
    }
    return none;
  }

  /// True when input edge (u, w), both complex vertices, is a chain of complex edges on faces,
  /// each ending within the merge tolerance of the segment and further along it. `steps` counts
  /// the chain's edges. O(chain · degree).
  bool covered(uint32_t u, uint32_t w, std::size_t& steps) {
    const vec a = pts_[u], d = pts_[w] - a;
    const double len2 = glm::dot(d, d);
    if (!(len2 > 0)) return false;
    const uint32_t direct = edge_between(u, w);
    steps = 1;
    if (direct != none) return !cc_.edge_faces(cell_edge(direct)).empty();
    uint32_t x = u;
    double tx = 0.0;
    steps = 0;
    while (x != w) {
      if (!budget_.spend(1 + cc_.vertex_edges(cell_vertex(x)).size())) {
        stop();
        return false;
      }
      uint32_t best = none;
      double best_t = 2.0;
      for (const auto& oe : cc_.vertex_edges(cell_vertex(x))) {
        const cell_edge e = oe.handle;
        if (cc_.edge_faces(e).empty()) continue;
        const uint32_t y = oe.sign > 0 ? cc_.target(e).idx() : cc_.source(e).idx();
        const double t = y == w ? 1.0 : glm::dot(pts_[y] - a, d) / len2;
        if (!(t > tx) || t > 1.0) continue;
        if (y != w && glm::length(pts_[y] - (a + t * d)) > merge_) continue;
        if (t < best_t) best_t = t, best = y;
      }
      if (best == none) return false;
      x = best;
      tx = best_t;
      ++steps;
      if (steps > cc_.num_vertices()) return false;
    }
    return true;
  }

  void check_input_edges() {
    match_vertices();
    const auto& edges = wire_->edges;
    const std::size_t ne = edges.size(), ni = wire_->points.size();
    r_.input_edges = ne;
    // Merged edges (representatives), each once: the graph whose bridges are the acyclic edges.
    std::vector<std::array<uint32_t, 2>> ends(ne, {none, none});
    std::vector<char> first(ne, 0);
    std::unordered_map<std::uint64_t, uint32_t> seen;
    seen.reserve(ne);
    for (uint32_t e = 0; e < ne; ++e) {
      const auto [a, b] = edges[e];
      if (a >= ni || b >= ni)
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("certify: input edge ", std::to_string(e), " joins vertex ",
                                           std::to_string(std::max(a, b)), " but there are ",
                                           std::to_string(ni), " vertices"));
      const uint32_t u = match_[a], w = match_[b];
      ends[e] = {u, w};
      if (u == w) {
        ++r_.zero_length_input_edges;
        continue;
      }
      const std::uint64_t key = std::uint64_t{std::min(u, w)} << 32 | std::max(u, w);
      if (!seen.emplace(key, e).second) {
        ++r_.duplicate_input_edges;
        continue;
      }
      first[e] = 1;
    }
    const std::vector<char> bridge = bridges(ends, first);
    std::vector<uint32_t> unused;
    for (uint32_t e = 0; e < ne; ++e) {
      const auto [u, w] = ends[e];
      if (u == w) continue;
      std::size_t steps = 0;
      const bool on_faces = u < cc_.num_vertices() && w < cc_.num_vertices() && covered(u, w, steps);
      if (!r_.complete) return;
      if (on_faces) {
        ++r_.covered_input_edges;
        if (steps > 1) ++r_.split_input_edges;
        continue;
      }
      // The first of a set of duplicates stands for them all.
      const uint32_t rep = first[e] ? e : seen.at(std::uint64_t{std::min(u, w)} << 32 | std::max(u, w));
      if (bridge[rep]) {
        r_.acyclic_input_edges.push_back(e);
      } else {
        unused.push_back(e);
      }
      loose_.push_back(e);
    }
    if (!r_.acyclic_input_edges.empty())
      r_.diagnostics.push_back(std::to_string(r_.acyclic_input_edges.size()) +
                               " input edges lie on no cycle (dangling trees or bridges), so on no face: " +
                               list(r_.acyclic_input_edges, o_.max_named));
    r_.unused_input_edges = unused;
    if (!unused.empty())
      fail(K::unused_input_edge,
           (unused.size() == 1 ? "input edge " : "input edges ") + list(unused, o_.max_named) +
               (unused.size() == 1 ? " lies" : " lie") + " on a cycle of the wireframe but on no face",
           unused);
  }

  /// Edges (those with first[e]) that lie on no cycle of the graph they make: iterative
  /// Tarjan, by edge so that nothing is confused. O(V + E).
  std::vector<char> bridges(const std::vector<std::array<uint32_t, 2>>& ends,
                            const std::vector<char>& first) const {
    const std::size_t n = reps_, ne = ends.size();
    std::vector<uint32_t> start(n + 1, 0);
    for (uint32_t e = 0; e < ne; ++e)
      if (first[e]) ++start[ends[e][0] + 1], ++start[ends[e][1] + 1];
    for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    std::vector<uint32_t> adj(start[n]);
    {
      std::vector<uint32_t> fill(start.begin(), start.end() - 1);
      for (uint32_t e = 0; e < ne; ++e)
        if (first[e]) adj[fill[ends[e][0]]++] = e, adj[fill[ends[e][1]]++] = e;
    }
    std::vector<char> bridge(ne, 0);
    std::vector<uint32_t> disc(n, none), low(n, 0), via(n, none), cursor(start.begin(), start.end() - 1);
    std::vector<uint32_t> stack;
    uint32_t time = 0;
    for (uint32_t s = 0; s < n; ++s) {
      if (disc[s] != none || start[s] == start[s + 1]) continue;
      disc[s] = low[s] = time++;
      stack.push_back(s);
      while (!stack.empty()) {
        const uint32_t v = stack.back();
        if (cursor[v] < start[v + 1]) {
          const uint32_t e = adj[cursor[v]++];
          if (e == via[v]) continue;
          const uint32_t w = ends[e][0] == v ? ends[e][1] : ends[e][0];
          if (disc[w] == none) {
            disc[w] = low[w] = time++;
            via[w] = e;
            stack.push_back(w);
          } else {
            low[v] = std::min(low[v], disc[w]);
          }
        } else {
          stack.pop_back();
          if (via[v] != none) {
            const uint32_t e = via[v];
            const uint32_t p = ends[e][0] == v ? ends[e][1] : ends[e][0];
            low[p] = std::min(low[p], low[v]);
            if (low[v] > disc[p]) bridge[e] = 1;
          }
        }
      }
    }
    return bridge;
  }

  // ---- crossings
  /// Exact planarity of every face, for the cheap separations. O(size).
  void classify_planes() {
    for (const cell_face f : cc_.faces()) {
      face_info& fi = info_[f.idx()];
      const auto outer = cc_.loop_vertices(f, 0);
      const vec& p0 = pts_[outer[0].idx()];
      for (int k = 0; k < 3 && fi.planar == 0; ++k) {
        bool flat = true;
        for (std::size_t l = 0; l < cc_.num_loops(f) && flat; ++l)
          for (const cell_vertex v : cc_.loop_vertices(f, l))
            if (pts_[v.idx()][k] != p0[k]) {
              flat = false;
              break;
            }
        if (flat) fi.planar = 1, fi.axis = k, fi.level = p0[k];
      }
      if (fi.planar) continue;
      // Three vertices spanning the plane: the first, the farthest from it, the farthest from both.
      uint32_t a = outer[0].idx(), b = a, c = a;
      double far = -1;
      for (const cell_vertex v : outer)
        if (const double d = glm::length(pts_[v.idx()] - pts_[a]); d > far) far = d, b = v.idx();
      far = -1;
      for (const cell_vertex v : outer)
        if (const double d = glm::length(glm::cross(pts_[b] - pts_[a], pts_[v.idx()] - pts_[a])); d > far)
          far = d, c = v.idx();
      if (collinear(pts_[a], pts_[b], pts_[c])) continue;
      bool flat = true;
      const auto plane = prepare_orient3d(pts_[a], pts_[b], pts_[c]);
      for (std::size_t l = 0; l < cc_.num_loops(f) && flat; ++l)
        for (const cell_vertex v : cc_.loop_vertices(f, l)) {
          const uint32_t x = v.idx();
          if (x == a || x == b || x == c) continue;
          double value = 0;
          if (orient3d_filter(plane, pts_[x], value) != 0 ||
              orient3d_exact(pts_[a], pts_[b], pts_[c], pts_[x]) != 0) {
            flat = false;
            break;
          }
        }
      if (flat) fi.planar = 2, fi.plane = {a, b, c};
    }
    for (const cell_face f : cc_.faces()) classify_convex(f);
  }

  /// Sets the projection of planar face f and whether it is strictly convex (one loop of at most
  /// 32 vertices, every vertex strictly inside every other edge's line). O(n²) orient2d.
  void classify_convex(cell_face f) {
    face_info& fi = info_[f.idx()];
    if (fi.planar == 0) return;
    int k = fi.axis;
    if (fi.planar == 2)
      k = self_intersect::drop_axis(pts_[fi.plane[0]], pts_[fi.plane[1]], pts_[fi.plane[2]]);
    if (k < 0) return;
    fi.u = (k + 1) % 3, fi.w = (k + 2) % 3;
    const auto loop = cc_.loop_vertices(f, 0);
    const std::size_t n = loop.size();
    if (cc_.num_loops(f) != 1 || n > 32) return;
    if (fi.planar == 1 && n == 4) {
      // Edges alternately along u and along w, each of positive length: a rectangle.
      auto along = [&](std::size_t i, int axis) {
        const vec &p = pts_[loop[i].idx()], &q = pts_[loop[(i + 1) % 4].idx()];
        const int other = axis == fi.u ? fi.w : fi.u;
        return p[axis] != q[axis] && p[other] == q[other];
      };
      const int a0 = along(0, fi.u) ? fi.u : fi.w, a1 = a0 == fi.u ? fi.w : fi.u;
      fi.rectangle = along(0, a0) && along(1, a1) && along(2, a0) && along(3, a1);
    }
    const int s = o2(fi, loop[0].idx(), loop[1].idx(), loop[2].idx());
    if (s == 0) return;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        if (j != i && j != (i + 1) % n && o2(fi, loop[i].idx(), loop[(i + 1) % n].idx(), loop[j].idx()) != s)
          return;
    fi.convex = true;
    fi.turn = s;
  }

  /// orient2d of vertices a, b, c in face fi's projection. O(1).
  int o2(const face_info& fi, uint32_t a, uint32_t b, uint32_t c) const {
    const vec &p = pts_[a], &q = pts_[b], &r = pts_[c];
    return orient2d(p[fi.u], p[fi.w], q[fi.u], q[fi.w], r[fi.u], r[fi.w]);
  }

  /// True when vertex z (on f's plane) lies in the closed convex face f. O(|f|).
  bool in_convex(uint32_t f, uint32_t z) const {
    const face_info& fi = info_[f];
    const auto loop = cc_.loop_vertices(cell_face(f), 0);
    for (std::size_t i = 0; i < loop.size(); ++i)
      if (fi.turn * o2(fi, loop[i].idx(), loop[(i + 1) % loop.size()].idx(), z) < 0) return false;
    return true;
  }

  /// True when the closed segments ab and cd (one plane, f's projection) meet. O(1).
  bool segments_meet2(const face_info& fi, uint32_t a, uint32_t b, uint32_t c, uint32_t d) const {
    const auto at = [&](uint32_t v) { return glm::dvec2(pts_[v][fi.u], pts_[v][fi.w]); };
    return cellforge::detail::segments_meet(at(a), at(b), at(c), at(d));
  }

  /// Side of p against the plane of planar face fi (p not one of its vertices). O(1).
  int side(const face_info& fi, const vec& p) const {
    if (fi.planar == 1) return p[fi.axis] > fi.level ? 1 : p[fi.axis] < fi.level ? -1 : 0;
    const vec &a = pts_[fi.plane[0]], &b = pts_[fi.plane[1]], &c = pts_[fi.plane[2]];
    return orient3d(a, b, c, p);
  }

  /// The triangles of face f (made on first use). O(face) the first time.
  std::span<const std::array<uint32_t, 3>> triangles(uint32_t f) {
    face_info& fi = info_[f];
    if (!fi.triangulated) {
      fi.tri_begin = static_cast<uint32_t>(tris_.size());
      triangulate_face(cc_, pts_, cell_face(f), [&](uint32_t a, uint32_t b, uint32_t c) {
        if (!self_intersect::degenerate(pts_[a], pts_[b], pts_[c])) tris_.push_back({a, b, c});
      });
      fi.tri_end = static_cast<uint32_t>(tris_.size());
      fi.triangulated = true;
    }
    return {tris_.data() + fi.tri_begin, tris_.data() + fi.tri_end};
  }

  /// One face of a pair as the other sees it: the face, its vertex marks (stamp_ at its
  /// vertices) and its vertices' places in its outer loop.
  struct role {
    uint32_t face;
    const std::vector<uint32_t>& in;
    const std::vector<uint32_t>& place;
  };

  /// True when vertices a and b of face x follow each other in one of its loops. O(1) for a
  /// face of one loop, O(degree) otherwise.
  bool consecutive(const role& x, uint32_t a, uint32_t b) const {
    const cell_face f(x.face);
    if (cc_.num_loops(f) == 1) {
      const std::size_t n = cc_.loop_vertices(f, 0).size();
      const std::size_t d = (x.place[b] + n - x.place[a]) % n;
      return d == 1 || d == n - 1;
    }
    const uint32_t e = edge_between(a, b);
    if (e == none) return false;
    for (const auto& of : cc_.edge_faces(cell_edge(e)))
      if (of.handle.idx() == x.face) return true;
    return false;
  }

  /// Segment z1-z2 in the plane of convex face f: true when it meets f other than at a shared
  /// vertex or as a shared edge. O(|f|).
  bool segment_in_plane_meets(const role& f, uint32_t z1, uint32_t z2) const {
    const face_info& fi = info_[f.face];
    const auto loop = cc_.loop_vertices(cell_face(f.face), 0);
    const std::size_t n = loop.size();
    const bool s1 = f.in[z1] == stamp_, s2 = f.in[z2] == stamp_;
    if (s1 && s2) return !consecutive(f, z1, z2);  // a chord of a strictly convex face crosses it
    if (s1 || s2) {
      const uint32_t v = s1 ? z1 : z2, x = s1 ? z2 : z1;
      const uint32_t at = f.place[v];
      const uint32_t prev = loop[(at + n - 1) % n].idx(), next = loop[(at + 1) % n].idx();
      return fi.turn * o2(fi, v, next, x) >= 0 && fi.turn * o2(fi, prev, v, x) >= 0;
    }
    if (in_convex(f.face, z1) || in_convex(f.face, z2)) return true;
    for (std::size_t i = 0; i < n; ++i)
      if (segments_meet2(fi, z1, z2, loop[i].idx(), loop[(i + 1) % n].idx())) return true;
    return false;
  }

  /// What f's plane decides about the pair (f, g): 0 they meet only at shared vertices and along
  /// shared edges, 1 they meet elsewhere, -1 not decided here. g's vertices strictly on one side
  /// but for at most one shared vertex or a shared edge: 0. f convex, g planar on one closed
  /// side: g meets the plane only in its vertices and edges on it, tested in f's plane; g convex
  /// in f's plane: coplanar_meet. O(|f|·|g|) at worst.
  int decide(const role& f, const role& g) {
    const face_info& fi = info_[f.face];
    if (fi.planar == 0) return -1;
    const face_info& gi = info_[g.face];
    on_.clear();
    bool pos = false, neg = false, zero = false;
    std::size_t shared = 0;
    std::array<uint32_t, 2> two{none, none};
    const cell_face gf(g.face);
    for (std::size_t l = 0; l < cc_.num_loops(gf); ++l)
      for (const cell_vertex v : cc_.loop_vertices(gf, l)) {
        if (f.in[v.idx()] == stamp_) {
          if (shared < 2) two[shared] = v.idx();
          ++shared;
          on_.push_back(1);
          continue;
        }
        const int s = side(fi, pts_[v.idx()]);
        pos |= s > 0, neg |= s < 0, zero |= s == 0;
        if (pos && neg) return -1;  // g straddles f's plane
        on_.push_back(s == 0);
      }
    if (!zero && (pos || neg)) {
      if (shared <= 1) return 0;
      if (shared == 2 && consecutive(f, two[0], two[1]) && consecutive(g, two[0], two[1])) return 0;
    }
    if (!fi.convex || gi.planar == 0) return -1;
    if (!pos && !neg) return gi.convex ? coplanar_meet(f, g, shared, two) : -1;
    std::size_t at = 0;
    for (std::size_t l = 0; l < cc_.num_loops(gf); ++l) {
      const auto loop = cc_.loop_vertices(gf, l);
      const std::size_t base = at;
      for (std::size_t k = 0; k < loop.size(); ++k, ++at) {
        if (!on_[at]) continue;
        const uint32_t z = loop[k].idx();
        if (f.in[z] != stamp_ && in_convex(f.face, z)) return 1;
        const std::size_t k2 = (k + 1) % loop.size();
        if (on_[base + k2] && segment_in_plane_meets(f, z, loop[k2].idx())) return 1;
      }
    }
    return 0;
  }

  /// The edge line a→b of a convex face turning sx, against the vertices ys of another face in
  /// its plane: -1 when some lies strictly inside, else whether the two meet on the line other
  /// than at a shared vertex or along the shared edge (touch_on_line). O(|ys|).
  int line_test(const face_info& fi, uint32_t a, uint32_t b, int sx, std::span<const cell_vertex> ys) const {
    std::array<uint32_t, 3> line{};
    std::size_t online = 0;
    for (const cell_vertex y : ys) {
      const int s = sx * o2(fi, a, b, y.idx());
      if (s > 0) return -1;
      if (s == 0 && online < 3) line[online++] = y.idx();
    }
    return touch_on_line(fi, a, b, line, online) ? 1 : 0;
  }

  /// Convex faces f and g in one plane: they meet other than at shared vertices and edges unless
  /// an edge line of one has the other on its closed outer side, touching the line only at
  /// shared vertices or along a shared edge (two convex polygons with disjoint interiors have
  /// such a line; through their common vertex when they share one). O(|f|·|g|), O(1) for a
  /// shared edge.
  int coplanar_meet(const role& f, const role& g, std::size_t shared,
                    const std::array<uint32_t, 2>& two) const {
    const face_info& fi = info_[f.face];
    const auto F = cc_.loop_vertices(cell_face(f.face), 0), G = cc_.loop_vertices(cell_face(g.face), 0);
    const int sg = o2(fi, G[0].idx(), G[1].idx(), G[2].idx());
    if (sg == 0) return 1;
    if (shared == 2 && consecutive(f, two[0], two[1]) && consecutive(g, two[0], two[1])) {
      // A shared edge a→b (f's direction): they touch along it when g lies beyond its line.
      uint32_t a = two[0], b = two[1];
      if (F[(f.place[a] + 1) % F.size()].idx() != b) std::swap(a, b);
      for (const cell_vertex x : G)
        if (x.idx() != a && x.idx() != b) return fi.turn * o2(fi, a, b, x.idx()) < 0 ? 0 : 1;
      return 1;
    }
    if (shared == 1) {
      const uint32_t v = two[0];
      for (int pass = 0; pass < 2; ++pass) {
        const auto X = pass == 0 ? F : G, Y = pass == 0 ? G : F;
        const role& x = pass == 0 ? f : g;
        const int sx = pass == 0 ? fi.turn : sg;
        const std::size_t at = x.place[v], n = X.size();
        const uint32_t prev = X[(at + n - 1) % n].idx(), next = X[(at + 1) % n].idx();
        for (const auto& [a, b] : {std::pair{prev, v}, std::pair{v, next}})
          if (const int t = line_test(fi, a, b, sx, Y); t >= 0) return t;
      }
      return 1;
    }
    for (int pass = 0; pass < 2; ++pass) {
      const auto X = pass == 0 ? F : G, Y = pass == 0 ? G : F;
      const int sx = pass == 0 ? fi.turn : sg;
      for (std::size_t i = 0; i < X.size(); ++i)
        if (const int t = line_test(fi, X[i].idx(), X[(i + 1) % X.size()].idx(), sx, Y); t >= 0) return t;
    }
    return 1;  // no edge line separates them: their interiors overlap
  }

  /// Points of the closed segment ab (ids) and the hull of the collinear vertices `line` (one
  /// vertex or an edge) in common, other than a shared vertex or the shared edge itself. O(1).
  bool touch_on_line(const face_info& fi, uint32_t a, uint32_t b, const std::array<uint32_t, 3>& line,
                     std::size_t n) const {
    if (n == 0) return false;
    if (n > 2) return true;
    const int t = pts_[a][fi.u] != pts_[b][fi.u] ? fi.u : fi.w;
    auto coord = [&](uint32_t v) { return pts_[v][t]; };
    if (n == 1) {
      const uint32_t z = line[0];
      if (z == a || z == b) return false;
      return std::min(coord(a), coord(b)) <= coord(z) && coord(z) <= std::max(coord(a), coord(b));
    }
    const uint32_t z1 = line[0], z2 = line[1];
    if ((z1 == a && z2 == b) || (z1 == b && z2 == a)) return false;
    const double lo = std::max(std::min(coord(a), coord(b)), std::min(coord(z1), coord(z2)));
    const double hi = std::min(std::max(coord(a), coord(b)), std::max(coord(z1), coord(z2)));
    if (lo > hi) return false;
    if (lo < hi) return true;
    // One common point: fine when it is one vertex of both.
    for (const uint32_t x : {a, b})
      for (const uint32_t z : {z1, z2})
        if (x == z && coord(x) == lo) return false;
    return true;
  }

  /// Marks face f's vertices in `marks` with the current stamp, and their outer-loop places. O(face).
  void mark(uint32_t f, std::vector<uint32_t>& marks, std::vector<uint32_t>& places) {
    for (std::size_t l = 0; l < cc_.num_loops(cell_face(f)); ++l) {
      const auto loop = cc_.loop_vertices(cell_face(f), l);
      for (std::size_t k = 0; k < loop.size(); ++k) {
        marks[loop[k].idx()] = stamp_;
        if (l == 0) places[loop[k].idx()] = static_cast<uint32_t>(k);
      }
    }
  }

  /// Two axis-aligned rectangles (each equal to its box) meet exactly in their boxes'
  /// intersection: fine when that is a shared vertex or a shared edge. O(1).
  bool rectangles_meet(uint32_t f, uint32_t g) const {
    const auto &a = info_[f].box, &b = info_[g].box;
    vec lo, hi;
    int dims = 0;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::max(a[static_cast<std::size_t>(k)], b[static_cast<std::size_t>(k)]);
      hi[k] = std::min(a[static_cast<std::size_t>(k) + 3], b[static_cast<std::size_t>(k) + 3]);
      if (lo[k] > hi[k]) return false;
      dims += lo[k] < hi[k] ? 1 : 0;
    }
    if (dims == 2) return true;
    // The intersection's ends must be vertices of both: among the (at most four) shared ids.
    const auto F = cc_.loop_vertices(cell_face(f), 0), G = cc_.loop_vertices(cell_face(g), 0);
    bool at_lo = false, at_hi = false;
    for (const cell_vertex x : F)
      for (const cell_vertex y : G)
        if (x == y) {
          const vec& p = pts_[x.idx()];
          at_lo |= p == lo;
          at_hi |= p == hi;
        }
    // (A segment along one axis between two corners of a rectangle is one of its sides.)
    return !(at_lo && at_hi);
  }

  /// True when faces f and g meet other than at shared vertices and along shared edges: two
  /// rectangles by their boxes, else what either face's plane decides, else triangle by
  /// triangle. O(|f|·|g|).
  bool faces_meet(uint32_t f, uint32_t g) {
    if (info_[f].rectangle && info_[g].rectangle) return rectangles_meet(f, g);
    ++stamp_;
    mark(f, in_f_, place_f_);
    mark(g, in_g_, place_g_);
    const role rf{f, in_f_, place_f_}, rg{g, in_g_, place_g_};
    if (const int t = decide(rf, rg); t >= 0) return t == 1;
    if (const int t = decide(rg, rf); t >= 0) return t == 1;
    ++r_.triangle_pairs_tested;
    triangles(f);  // both made before either span is taken: the list may grow
    const auto tg = triangles(g);
    const auto tf = triangles(f);
    std::array<vec, 3> p{}, q{};
    for (const auto& ta : tf) {
      for (std::size_t k = 0; k < 3; ++k) p[k] = pts_[ta[k]];
      const std::array<double, 6> ba = tri_box(p);
      for (const auto& tb : tg) {
        for (std::size_t k = 0; k < 3; ++k) q[k] = pts_[tb[k]];
        const std::array<double, 6> bb = tri_box(q);
        if (ba[0] > bb[3] || bb[0] > ba[3] || ba[1] > bb[4] || bb[1] > ba[4] || ba[2] > bb[5] ||
            bb[2] > ba[5])
          continue;
        if (self_intersect::pair_intersects(p, ta, q, tb)) return true;
      }
    }
    if (!budget_.spend(tf.size() * tg.size())) stop();
    return false;
  }

  static std::array<double, 6> tri_box(const std::array<vec, 3>& p) {
    return {std::min({p[0].x, p[1].x, p[2].x}), std::min({p[0].y, p[1].y, p[2].y}),
            std::min({p[0].z, p[1].z, p[2].z}), std::max({p[0].x, p[1].x, p[2].x}),
            std::max({p[0].y, p[1].y, p[2].y}), std::max({p[0].z, p[1].z, p[2].z})};
  }

  /// True when segment (p, q) with complex ids ip, iq (or none) meets face f other than at a
  /// shared vertex. O(|f|).
  bool segment_meets(uint32_t f, const vec& p, const vec& q, uint32_t ip, uint32_t iq) {
    ++stamp_;
    mark(f, in_f_, place_f_);
    const face_info& fi = info_[f];
    const bool sp = ip != none && in_f_[ip] == stamp_, sq = iq != none && in_f_[iq] == stamp_;
    // Off the plane but for shared ends: it meets the face at most there.
    if (fi.planar != 0 && !(sp && sq)) {
      const int a = sp ? 0 : side(fi, p), b = sq ? 0 : side(fi, q);
      if (sp ? b != 0 : sq ? a != 0 : a != 0 && a == b) return false;
    }
    for (const auto& t : triangles(f))
      if (segment_meets_triangle(p, q, ip, iq, pts_, t)) return true;
    return false;
  }

  void check_crossings() {
    classify_planes();
    in_f_.assign(cc_.num_vertices(), 0);
    in_g_.assign(cc_.num_vertices(), 0);
    place_f_.assign(cc_.num_vertices(), 0);
    place_g_.assign(cc_.num_vertices(), 0);
    // Items: faces, then segments (faceless complex edges, then input edges off the faces).
    struct segment {
      vec p, q;
      uint32_t ip, iq;
      uint32_t name;  ///< complex edge, or input edge
      bool input;
    };
    std::vector<segment> segments;
    for (const cell_edge e : cc_.edges())
      if (cc_.edge_faces(e).empty()) {
        const uint32_t a = cc_.source(e).idx(), b = cc_.target(e).idx();
        segments.push_back({pts_[a], pts_[b], a, b, e.idx(), false});
      }
    if (wire_)
      for (const uint32_t e : loose_) {
        const auto [a, b] = wire_->edges[e];
        const uint32_t u = match_[a], w = match_[b];
        const bool cu = u < cc_.num_vertices(), cw = w < cc_.num_vertices();
        segments.push_back({cu ? pts_[u] : wire_->points[a], cw ? pts_[w] : wire_->points[b], cu ? u : none,
                            cw ? w : none, e, true});
      }
    const std::size_t nf = cc_.num_faces();
    std::vector<std::array<double, 6>> boxes(nf + segments.size());
    for (std::size_t f = 0; f < nf; ++f) boxes[f] = info_[f].box;
    for (std::size_t s = 0; s < segments.size(); ++s) {
      const vec &p = segments[s].p, &q = segments[s].q;
      boxes[nf + s] = {std::min(p.x, q.x), std::min(p.y, q.y), std::min(p.z, q.z),
                       std::max(p.x, q.x), std::max(p.y, q.y), std::max(p.z, q.z)};
    }
    std::vector<uint32_t> cross, pierce_input, pierce_edge;
    const auto pairs = self_intersect::for_each_box_pair(
        detail::span_of(boxes), budget_.left(), [&](uint32_t i, uint32_t j) {
          if (i > j) std::swap(i, j);
          if (j >= nf && i >= nf) return true;  // two segments
          ++r_.face_pairs_tested;
          if (!budget_.spend(1)) return false;
          if (j < nf) {
            if (faces_meet(i, j)) cross.push_back(i), cross.push_back(j);
          } else {
            const segment& s = segments[j - nf];
            if (segment_meets(i, s.p, s.q, s.ip, s.iq)) {
              auto& out = s.input ? pierce_input : pierce_edge;
              out.push_back(s.name), out.push_back(i);
            }
          }
          return r_.complete;
        });
    budget_.spend(pairs.candidate_pairs);
    if (!pairs.complete) stop();
    sort_pairs(cross);
    sort_pairs(pierce_input);
    sort_pairs(pierce_edge);
    if (!cross.empty()) {
      const std::size_t n = cross.size() / 2;
      fail(K::faces_cross,
           cellforge::detail::cat(
               "faces ", std::to_string(cross[0]), " and ", std::to_string(cross[1]), " cross",
               (n > 1 ? cellforge::detail::cat(" (and ", std::to_string(n - 1), " more pairs: faces ",
                                               pair_list(cross), ")")
                      : std::string())),
           cross);
    }
    if (!pierce_input.empty())
      fail(K::input_edge_pierces_face, pierce_message("input edge", pierce_input), pierce_input);
    if (!pierce_edge.empty()) fail(K::edge_pierces_face, pierce_message("edge", pierce_edge), pierce_edge);
  }

  static void sort_pairs(std::vector<uint32_t>& xs) {
    std::vector<std::pair<uint32_t, uint32_t>> p;
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2) p.emplace_back(xs[i], xs[i + 1]);
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    xs.clear();
    for (const auto& [a, b] : p) xs.push_back(a), xs.push_back(b);
  }

  std::string pair_list(const std::vector<uint32_t>& xs) const {
    std::string s;
    const std::size_t n = xs.size() / 2;
    for (std::size_t i = 1; i < n && i <= o_.max_named; ++i)
      s += (i > 1 ? ", " : "") + std::to_string(xs[2 * i]) + "/" + std::to_string(xs[2 * i + 1]);
    if (n - 1 > o_.max_named) s += ", ...";
    return s;
  }

  std::string pierce_message(const char* what, const std::vector<uint32_t>& xs) const {
    std::vector<uint32_t> edges, faces;
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2) edges.push_back(xs[i]), faces.push_back(xs[i + 1]);
    for (auto* v : {&edges, &faces}) {
      std::sort(v->begin(), v->end());
      v->erase(std::unique(v->begin(), v->end()), v->end());
    }
    return cellforge::detail::cat(std::string(what), (edges.size() == 1 ? " " : "s "),
                                  list(edges, o_.max_named), (edges.size() == 1 ? " pierces " : " pierce "),
                                  (faces.size() == 1 ? "face " : "faces "), list(faces, o_.max_named));
  }

  const cell_topology& cc_;
  std::span<const vec> pts_;
  const input_wire* wire_;
  const certify_options& o_;
  certificate_result& r_;
  double merge_ = 0, flat_ = 0;
  budget budget_;
  std::vector<face_info> info_;
  std::vector<std::array<uint32_t, 3>> tris_;
  std::vector<uint32_t> in_f_, in_g_, place_f_, place_g_;  ///< vertex marks of the two faces of a pair
  std::vector<char> on_;                                   ///< per vertex of g: on f's plane
  uint32_t stamp_ = 0;
  std::vector<uint32_t> match_;  ///< input vertex → complex vertex (or a representative past them)
  std::size_t reps_ = 0;
  std::vector<uint32_t> loose_;  ///< input edges (non-zero length) on no face
};

/// certify on double positions (one copy for every point type). See certify().
template <class>
certificate_result run(const cell_topology& cc, std::span<const vec> pts, const input_wire* wire,
                       const certify_options& options) {
  const stopwatch clock;
  certificate_result r;
  certifier(cc, pts, wire, options, r).run();
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge::detail::certify
