// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 2 of the wireframe pipeline (seed 000 §4.2): find candidate faces. The default
/// tracer is polynomial: every plane spanned by two adjacent edges collects the edges lying in
/// it, and the bounded faces of that plane's planar arrangement are the candidates (nested
/// cycles in one plane become holes). The seed's breadth-first circuit search with its pruning
/// is kept, faithfully, as an option; it is exponential in the worst case, so it runs under a
/// work budget.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/core/tolerance.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// Which face-finding method circuit tracing uses.
enum class tracer_kind : std::uint8_t {
  planar,    ///< faces of each plane's planar arrangement; polynomial (default)
  seed_bfs,  ///< the seed's breadth-first circuit search with pruning; exponential worst case
};

/// Options of trace_circuits.
struct trace_options {
  tracer_kind kind = tracer_kind::planar;
  tolerance planarity{1e-9};  ///< a point lies in a plane when closer than this (relative to model size)
  cellforge::work_budget work_budget =
      200'000'000;                    ///< abstract steps (path extensions, incidences visited); 0 = none
  std::size_t max_circuit_edges = 0;  ///< seed_bfs only: longest circuit searched; 0 = number of edges
  /// planar only, for noisy coordinates: refit each plane to the vertices it holds and give its
  /// faces the fitted normal (docs/wireframe.md, "Tolerances"). Off, the corner planes and each
  /// face's own normal, as the seed: faces within the tolerance of one plane stay apart.
  bool fit_planes = false;
};

/// Candidate faces and what it took to find them.
struct trace_result : stage_report {
  std::vector<wire_face> faces;      ///< candidates; seed_bfs reports every circuit found (with repeats)
  std::size_t planes = 0;            ///< planar: distinct planes spanned by adjacent edges
  std::size_t plane_components = 0;  ///< planar: connected in-plane edge sets traced
  std::size_t holes = 0;             ///< planar: loops assigned as holes of a containing face
  std::size_t circuits = 0;          ///< circuits found (before making them unique)
};

namespace detail {

/// One connected set of edges lying in one plane, with its traced faces.
struct plane_component {
  glm::dvec3 origin{0.0}, normal{0.0}, u{0.0}, w{0.0};  // plane frame: u × w = normal
  double extent = 0.0;                                  // largest distance of a vertex from origin
  std::vector<std::vector<std::uint32_t>> bounded;      // counter-clockwise walks (candidate faces)
  std::vector<std::vector<std::uint32_t>> outer;        // clockwise walks (outer boundaries)
};

template <class = void>
glm::dvec2 project(const plane_component& c, const glm::dvec3& p) {
  const glm::dvec3 d = p - c.origin;
  return {glm::dot(d, c.u), glm::dot(d, c.w)};
}

template <class = void>
double signed_area_2d(const std::vector<glm::dvec2>& q) {
  double s = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const auto& a = q[i];
    const auto& b = q[(i + 1) % q.size()];
    s += (a.x - q[0].x) * (b.y - q[0].y) - (b.x - q[0].x) * (a.y - q[0].y);
  }
  return 0.5 * s;
}

/// Buffers trace_plane_faces reuses from one plane to the next (a model has as many planes
/// as faces), sized once for the whole graph.
struct plane_scratch {
  std::vector<std::uint32_t> local;  // graph vertex -> local index, valid where stamp matches
  std::vector<std::uint32_t> stamp;
  std::uint32_t round = 0;
  std::vector<std::uint32_t> verts, from, to, first, out, pos, walk_of, walk_start, walk, keep;
  std::vector<glm::dvec2> q;
  explicit plane_scratch(std::size_t nv) : local(nv), stamp(nv, no_index) {}
};

/// Traces the faces of one in-plane edge set: angular order around each vertex, walks with
/// the face on the left. Edges walked on both sides by one walk (trees, bridges) are removed
/// and the walk repeated. O(k log k) for k in-plane edges.
template <class = void>
void trace_plane_faces(const wire_graph& g, std::vector<std::uint32_t>& edges, plane_component& c,
                       plane_scratch& w, work_counter& budget) {
  for (;;) {
    ++w.round;
    w.verts.clear();
    for (const auto e : edges)
      for (const auto v : g.edges[e])
        if (w.stamp[v] != w.round) {
          w.stamp[v] = w.round;
          w.local[v] = static_cast<std::uint32_t>(w.verts.size());
          w.verts.push_back(v);
        }
    const std::size_t nv = w.verts.size();
    w.q.resize(nv);
    for (std::size_t i = 0; i < nv; ++i) w.q[i] = project(c, g.points[w.verts[i]]);
    // Half-edge 2k goes start→end of edges[k], 2k+1 end→start; out[first[v]..first[v+1]) are
    // the half-edges leaving local vertex v.
    const std::size_t nh = 2 * edges.size();
    w.from.resize(nh);
    w.to.resize(nh);
    w.first.assign(nv + 1, 0);
    for (std::uint32_t k = 0; k < edges.size(); ++k) {
      const std::uint32_t a = w.local[g.edges[edges[k]][0]], b = w.local[g.edges[edges[k]][1]];
      w.from[2 * k] = a, w.to[2 * k] = b, w.from[2 * k + 1] = b, w.to[2 * k + 1] = a;
      ++w.first[a + 1];
      ++w.first[b + 1];
    }
    for (std::size_t v = 0; v < nv; ++v) w.first[v + 1] += w.first[v];
    w.out.resize(nh);
    w.pos.assign(w.first.begin(), w.first.end() - 1);  // fill cursor, reused below as position
    for (std::uint32_t h = 0; h < nh; ++h) w.out[w.pos[w.from[h]]++] = h;
    w.pos.resize(nh);
    for (std::uint32_t v = 0; v < nv; ++v) {
      const auto begin = w.out.begin() + w.first[v], end = w.out.begin() + w.first[v + 1];
      budget.spend(static_cast<std::uint64_t>(end - begin));
      const glm::dvec2 origin = w.q[v];
      auto half = [&](std::uint32_t h) {
        const glm::dvec2 d = w.q[w.to[h]] - origin;
        return (d.y > 0.0 || (d.y == 0.0 && d.x > 0.0)) ? 0 : 1;
      };
      // Counter-clockwise order by angle, decided with exact orientation tests.
      std::sort(begin, end, [&](std::uint32_t x, std::uint32_t y) {
        const int hx = half(x), hy = half(y);
        if (hx != hy) return hx < hy;
        return orient2d(origin, w.q[w.to[x]], w.q[w.to[y]]) > 0;
      });
      for (std::uint32_t i = w.first[v]; i < w.first[v + 1]; ++i) w.pos[w.out[i]] = i - w.first[v];
    }
    // next(h): at to(h), the outgoing half-edge just clockwise of the twin, which keeps the face on the left.
    w.walk_of.assign(nh, no_index);
    w.walk_start.clear();
    w.walk.clear();
    for (std::uint32_t h0 = 0; h0 < nh; ++h0) {
      if (w.walk_of[h0] != no_index) continue;
      const auto id = static_cast<std::uint32_t>(w.walk_start.size());
      w.walk_start.push_back(static_cast<std::uint32_t>(w.walk.size()));
      std::uint32_t h = h0;
      do {
        w.walk_of[h] = id;
        w.walk.push_back(h);
        budget.spend();
        const std::uint32_t v = w.to[h], degree = w.first[v + 1] - w.first[v];
        const std::uint32_t twin = h ^ 1u;
        h = w.out[w.first[v] + (w.pos[twin] + degree - 1) % degree];
      } while (h != h0);
    }
    w.walk_start.push_back(static_cast<std::uint32_t>(w.walk.size()));
    w.keep.clear();
    for (std::uint32_t k = 0; k < edges.size(); ++k)
      if (w.walk_of[2 * k] != w.walk_of[2 * k + 1]) w.keep.push_back(edges[k]);
    if (w.keep.size() != edges.size()) {
      edges.swap(w.keep);
      if (edges.empty()) return;
      continue;
    }
    std::vector<glm::dvec2> poly;
    for (std::size_t k = 0; k + 1 < w.walk_start.size(); ++k) {
      std::vector<std::uint32_t> loop;
      poly.clear();
      for (std::uint32_t i = w.walk_start[k]; i < w.walk_start[k + 1]; ++i) {
        loop.push_back(w.verts[w.from[w.walk[i]]]);
        poly.push_back(w.q[w.from[w.walk[i]]]);
      }
      (signed_area_2d(poly) > 0.0 ? c.bounded : c.outer).push_back(std::move(loop));
    }
    return;
  }
}

/// A plane's coordinates in units of the hash's quanta: normal / qn, offset / qo. O(1).
template <class = void>
std::array<double, 4> plane_coords(const glm::dvec3& n, const glm::dvec3& o, double qn, double qo) {
  return {n.x / qn, n.y / qn, n.z / qn, glm::dot(n, o) / qo};
}

/// The least-squares plane of some graph vertices (three or more, not all on a line): its unit
/// normal, turned towards `hint`, and their centroid; `hint` itself when they are degenerate.
/// The normal solves the 3 × 3 covariance along the axis its plane is least steep to. O(n).
template <class = void>
std::pair<glm::dvec3, glm::dvec3> fit_plane(const wire_graph& g, std::span<const std::uint32_t> verts,
                                            const glm::dvec3& hint) {
  glm::dvec3 c(0.0);
  for (const auto v : verts) c += g.points[v];
  c /= static_cast<double>(verts.size());
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  for (const auto v : verts) {
    const glm::dvec3 d = g.points[v] - c;
    xx += d.x * d.x, xy += d.x * d.y, xz += d.x * d.z;
    yy += d.y * d.y, yz += d.y * d.z, zz += d.z * d.z;
  }
  const double dx = yy * zz - yz * yz, dy = xx * zz - xz * xz, dz = xx * yy - xy * xy;
  glm::dvec3 n;
  if (dx >= dy && dx >= dz)
    n = {dx, xz * yz - xy * zz, xy * yz - xz * yy};
  else if (dy >= dz)
    n = {xz * yz - xy * zz, dy, xy * xz - yz * xx};
  else
    n = {xy * yz - xz * yy, xy * xz - yz * xx, dz};
  const double l = glm::length(n);
  if (!(l > 0.0) || !std::isfinite(l)) return {hint, c};
  n /= l;
  return {glm::dot(n, hint) < 0.0 ? -n : n, c};
}

template <class = void>
class basic_fan_index;
using fan_index = basic_fan_index<>;

/// At a vertex of high degree (a sphere's pole), which of its edges may lie in the plane of a
/// pair (i, j): for each edge i the others sorted by their angle about i, folded to [0, π),
/// so that the edges coplanar with i and j are those near j in that order (edges nearly
/// along i lie in every plane through i and are always candidates). Candidates are then
/// tested exactly as any edge is. O(deg² log deg) to build, O(candidates) per pair, instead
/// of O(deg) per pair.
template <class>
class basic_fan_index {
 public:
  void build(std::span<const glm::dvec3> dirs, double tol) {
    n_ = dirs.size();
    angle_.assign(n_ * n_, 0.0);
    order_.assign(n_ * n_, 0);
    rank_.assign(n_ * n_, 0);
    along_.assign(n_, {});
    window_.assign(n_, 0.0);
    counts_.assign(n_, 0);
    for (std::uint32_t i = 0; i < n_; ++i) {
      const glm::dvec3 axis = glm::normalize(dirs[i]);
      const glm::dvec3 e1 = any_perpendicular(axis, perpendicular_rule::x_below_0_6),
                       e2 = glm::cross(axis, e1);
      std::uint32_t count = 0;
      for (std::uint32_t k = 0; k < n_; ++k) {
        if (k == i) continue;
        const glm::dvec3 d = dirs[k] - glm::dot(dirs[k], axis) * axis;
        const double across = glm::length(d);
        if (across <= 4.0 * tol) {  // along i (or i itself): in every plane through i
          along_[i].push_back(k);
          continue;
        }
        double t = std::atan2(glm::dot(d, e2), glm::dot(d, e1));
        if (t < 0.0) t += std::numbers::pi;
        if (t >= std::numbers::pi) t -= std::numbers::pi;
        angle_[i * n_ + k] = t;
        order_[i * n_ + count++] = k;
        // An edge within tol of a plane through i is within this angle of it, about i.
        window_[i] = std::max(window_[i], 2.0 * tol / across + 1e-12);
      }
      counts_[i] = count;
      const auto begin = order_.begin() + static_cast<std::ptrdiff_t>(i * n_);
      std::sort(begin, begin + count,
                [&](std::uint32_t a, std::uint32_t b) { return angle_[i * n_ + a] < angle_[i * n_ + b]; });
      for (std::uint32_t r = 0; r < count; ++r) rank_[i * n_ + order_[i * n_ + r]] = r;
    }
  }
  /// Calls f(k) for every edge k that may lie in the plane of edges i and j (i and j too).
  template <class F>
  void candidates(std::uint32_t i, std::uint32_t j, F&& f) const {
    f(i);
    for (const auto k : along_[i]) f(k);
    const std::uint32_t count = counts_[i];
    const double tj = angle_[i * n_ + j], w = window_[i];
    const std::uint32_t* row = order_.data() + i * n_;
    const std::uint32_t r = rank_[i * n_ + j];
    auto near = [&](std::uint32_t k) {
      const double d = std::abs(angle_[i * n_ + k] - tj);
      return std::min(d, std::numbers::pi - d) <= w;  // folded angles wrap at π
    };
    // Walk both ways from j, wrapping, until an edge is out of the window (or all are seen).
    std::uint32_t seen = 1;
    f(j);
    for (std::uint32_t s = 1; seen < count; ++s, ++seen)
      if (const std::uint32_t k = row[(r + s) % count]; near(k))
        f(k);
      else
        break;
    for (std::uint32_t s = 1; seen < count; ++s, ++seen)
      if (const std::uint32_t k = row[(r + count - s) % count]; near(k))
        f(k);
      else
        break;
  }
  std::size_t degree() const noexcept { return n_; }
  bool along(std::uint32_t i, std::uint32_t j) const {
    return std::find(along_[i].begin(), along_[i].end(), j) != along_[i].end();
  }

 private:
  std::size_t n_ = 0;
  std::vector<double> angle_, window_;
  std::vector<std::uint32_t> order_, rank_, counts_;
  std::vector<std::vector<std::uint32_t>> along_;
};

/// The polynomial planar-arrangement tracer. O(sum over vertices of degree² + sum over planes
/// of k log k) for k edges in a plane.
template <class = void>
void trace_planar(const wire_graph& g, const trace_options& opt, trace_result& r, work_counter& budget) {
  const double tol = std::max(opt.planarity.absolute(bounding_box{g.center - 0.5 * g.size / std::sqrt(3.0),
                                                                  g.center + 0.5 * g.size / std::sqrt(3.0)}),
                              g.merge_tolerance);
  const std::size_t nv = g.num_vertices(), ne = g.num_edges();
  // Per vertex a deg × deg matrix of "this pair of edges has been assigned a plane".
  std::vector<std::size_t> pair_base(nv + 1, 0);
  for (std::uint32_t v = 0; v < nv; ++v) pair_base[v + 1] = pair_base[v] + g.degree(v) * g.degree(v);
  std::vector<char> done(pair_base[nv], 0);
  std::vector<std::uint32_t> vstamp(nv, no_index), estamp(ne, no_index), vtest(nv, no_index);
  std::vector<char> vin(nv, 0);
  std::uint32_t stamp = 0;
  std::vector<std::uint32_t> cverts, cedges, local, off;  // reused by every plane search
  std::vector<glm::dvec3> dirs;
  fan_index fan;
  plane_scratch scratch(nv);
  std::vector<plane_component> comps;
  std::vector<std::array<double, 4>> plane_keys;          // per component: its plane's coordinates
  std::vector<std::vector<std::uint32_t>> plane_samples;  // per component: a few of its vertices
  std::vector<std::uint32_t> group;  // component → plane group (first component of the group)

  // Two passes: planes are first seeded from well-conditioned corners (angle over ~0.5°),
  // whose normals are accurate; nearly straight corners only seed planes no corner covered.
  for (int pass = 0; pass < 2; ++pass)
    for (std::uint32_t v = 0; v < nv; ++v) {
      const auto inc = g.around(v);
      // The directions of v's edges side by side: at a vertex of high degree (a sphere's pole)
      // every plane search starts by testing all of them against its plane.
      dirs.resize(inc.size());
      for (std::uint32_t k = 0; k < inc.size(); ++k) dirs[k] = g.points[inc[k].other] - g.points[v];
      const bool indexed = inc.size() > 24;
      if (indexed) fan.build(detail::span_of(dirs), tol);
      for (std::uint32_t i = 0; i < inc.size(); ++i)
        for (std::uint32_t j = i + 1; j < inc.size(); ++j) {
          if (done[pair_base[v] + i * inc.size() + j]) continue;
          budget.spend();
          const glm::dvec3 da = g.points[inc[i].other] - g.points[v],
                           db = g.points[inc[j].other] - g.points[v];
          glm::dvec3 n = glm::cross(da, db);
          const double ln = glm::length(n), la = glm::length(da), lb = glm::length(db);
          if (pass == 0 && ln < 1e-2 * la * lb) continue;
          done[pair_base[v] + i * inc.size() + j] = 1;
          // Collinear pair: the far end of one edge lies within tolerance of the other's line.
          if (ln <= tol * std::max(la, lb)) continue;
          n /= ln;
          // Breadth-first over edges lying in the plane (normal m through o), starting at v; each
          // vertex's in-plane incidences are noted as it is scanned, the vertices found off the
          // plane are kept in `off`. `fan_ok`: the plane is the corner's, which the fan index knows.
          auto collect = [&](const glm::dvec3& m, const glm::dvec3& o, bool fan_ok) {
            const std::uint32_t cid = stamp++;  // marks this search in the stamp arrays
            cverts.assign(1, v);
            cedges.clear();
            off.clear();
            vstamp[v] = cid;
            for (std::size_t head = 0; head < cverts.size(); ++head) {
              const std::uint32_t x = cverts[head];
              const auto ix = g.around(x);
              local.clear();
              budget.spend(ix.size());
              if (head == 0) {
                // x == v, scanned first (no edge of it is found yet): its contiguous directions,
                // at a vertex of high degree only those the fan index names.
                auto take = [&](std::uint32_t a) {
                  if (estamp[ix[a].edge] == cid) return;
                  const std::uint32_t y = ix[a].other;
                  if (std::abs(glm::dot(m, g.points[y] - o)) > tol) {
                    off.push_back(y);
                    return;
                  }
                  vtest[y] = cid;
                  vin[y] = 1;
                  estamp[ix[a].edge] = cid;
                  cedges.push_back(ix[a].edge);
                  local.push_back(a);
                  if (vstamp[y] != cid) {
                    vstamp[y] = cid;
                    cverts.push_back(y);
                  }
                };
                if (fan_ok && indexed && !fan.along(i, j))
                  fan.candidates(i, j, take);
                else
                  for (std::uint32_t a = 0; a < ix.size(); ++a) take(a);
              }
              for (std::uint32_t a = 0; a < ix.size() && head != 0; ++a) {
                const auto& in = ix[a];
                if (estamp[in.edge] == cid) {  // found from its other end
                  local.push_back(a);
                  continue;
                }
                const std::uint32_t y = in.other;
                if (vtest[y] != cid) {
                  vtest[y] = cid;
                  vin[y] = std::abs(glm::dot(m, g.points[y] - o)) <= tol;
                  if (!vin[y]) off.push_back(y);
                }
                if (!vin[y]) continue;
                estamp[in.edge] = cid;
                cedges.push_back(in.edge);
                local.push_back(a);
                if (vstamp[y] != cid) {
                  vstamp[y] = cid;
                  cverts.push_back(y);
                }
              }
              // Every pair of in-plane edges at x spans this plane: mark them. O(k²) for k
              // in-plane edges, not O(deg²), which matters at the poles of a sphere.
              for (std::size_t p = 0; p < local.size(); ++p)
                for (std::size_t q = p + 1; q < local.size(); ++q)
                  done[pair_base[x] + local[p] * ix.size() + local[q]] = 1;
            }
          };
          // The vertex's own direction test (dirs) and the plane test agree: both measure the
          // far end's distance from the plane through v.
          glm::dvec3 origin = g.points[v];
          collect(n, origin, true);
          // The plane of one corner tilts by the coordinates' noise over the corner's edges,
          // which a large face multiplies: fit the plane to the vertices found (least squares)
          // and search again while the fit takes in vertices the last plane left out. On exact
          // input the fit moves the plane by rounding only and the first search stands.
          for (int refit = 0; opt.fit_planes && refit < 4 && cverts.size() >= 4; ++refit) {
            const auto [fn, fo] = fit_plane(g, detail::span_of(cverts), n);
            bool more = false;
            for (const auto y : off) more = more || std::abs(glm::dot(fn, g.points[y] - fo)) <= tol;
            n = fn;
            origin = fo;
            if (!more) break;
            collect(n, origin, false);
          }
          // A forest has no circuit: most planes spanned by two edges hold just those two.
          if (cedges.size() < cverts.size()) continue;
          plane_component c;
          c.origin = origin;
          c.normal = n;
          c.u = glm::normalize(da - glm::dot(da, n) * n);
          c.w = glm::cross(n, c.u);
          for (const auto x : cverts) c.extent = std::max(c.extent, glm::length(g.points[x] - origin));
          trace_plane_faces(g, cedges, c, scratch, budget);
          // Filed for grouping with the other components of the same geometric plane (holes).
          auto& sample = plane_samples.emplace_back();
          for (std::size_t q = 0; q < cverts.size(); q += std::max<std::size_t>(1, cverts.size() / 8))
            sample.push_back(cverts[q]);
          comps.push_back(std::move(c));
        }
    }
  r.plane_components = comps.size();

  // Groups of components lying in one geometric plane. Planes are filed under their rounded
  // coordinates (quanta far coarser than two estimates of one plane differ by); the same plane
  // rounds the same way unless a coordinate sits near a half, and then the neighbour on that
  // side is tried too; both normal signs. Each component joins the group of the first earlier
  // component found in its plane. O(C log C).
  {
    // Two estimates of one plane differ by the tolerance over the components' size in their
    // normals and by the tolerance in their offsets: the quanta stay 20 times coarser than
    // that, so that the neighbour keys tried near a half find them (on exact input 1e-3).
    double smallest = g.size;
    for (const auto& c : comps) smallest = std::min(smallest, std::max(c.extent, 1e-300));
    const double qn = std::min(1.0, std::max(1e-3, 40.0 * tol / smallest));
    const double qo = std::max(1e-3 * g.size, 40.0 * tol);
    for (const auto& c : comps) plane_keys.push_back(plane_coords(c.normal, c.origin - g.center, qn, qo));
    using key4 = std::array<std::int64_t, 4>;
    std::vector<std::pair<key4, std::uint32_t>> filed(comps.size());
    for (std::uint32_t k = 0; k < comps.size(); ++k) {
      key4 own{};
      for (int t = 0; t < 4; ++t)
        own[static_cast<std::size_t>(t)] =
            static_cast<std::int64_t>(std::round(plane_keys[k][static_cast<std::size_t>(t)]));
      filed[k] = {own, k};
    }
    std::sort(filed.begin(), filed.end());
    group.resize(comps.size());
    for (std::uint32_t k = 0; k < comps.size(); ++k) {
      const auto& pc = plane_keys[k];
      std::uint32_t found = no_index;
      for (int sign = 1; sign >= -1 && found == no_index; sign -= 2) {
        key4 base{};
        std::array<int, 4> step{};
        for (int t = 0; t < 4; ++t) {
          const double x = sign * pc[static_cast<std::size_t>(t)];
          base[static_cast<std::size_t>(t)] = static_cast<std::int64_t>(std::round(x));
          const double f = x - std::floor(x);
          step[static_cast<std::size_t>(t)] = std::abs(f - 0.5) < 0.05 ? (f < 0.5 ? 1 : -1) : 0;
        }
        for (int combo = 0; combo < 16 && found == no_index; ++combo) {
          key4 key = base;
          bool skip = false;
          for (int t = 0; t < 4; ++t)
            if ((combo >> t) & 1) {
              skip = skip || step[static_cast<std::size_t>(t)] == 0;
              key[static_cast<std::size_t>(t)] += step[static_cast<std::size_t>(t)];
            }
          if (skip) continue;
          auto it = std::lower_bound(filed.begin(), filed.end(), std::pair<key4, std::uint32_t>{key, 0});
          for (; it != filed.end() && it->first == key && it->second < k && found == no_index; ++it) {
            const auto& oc = comps[it->second];
            // Parallel to within the tilt the tolerance allows over the smaller component (never
            // finer than 1 - |cos| < 1e-9), and the samples within the tolerance of the plane.
            const double tilt =
                std::max(4.5e-5, 4.0 * tol / std::max(std::min(oc.extent, comps[k].extent), 1e-300));
            bool same = glm::length(glm::cross(oc.normal, comps[k].normal)) < tilt;
            for (const auto v : plane_samples[k])
              same = same && std::abs(glm::dot(oc.normal, g.points[v] - oc.origin)) <= tol;
            if (same) found = group[it->second];
          }
        }
      }
      group[k] = found == no_index ? k : found;
      if (found == no_index) ++r.planes;
    }
  }

  // Holes: an outer walk of one component inside a bounded walk of another component of the
  // same plane is a hole of the smallest such walk.
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> members;
  for (std::uint32_t c = 0; c < comps.size(); ++c) members[group[c]].push_back(c);
  std::vector<std::vector<wire_face>> faces_of(comps.size());
  for (std::uint32_t c = 0; c < comps.size(); ++c)
    for (const auto& b : comps[c].bounded) {
      wire_face f;
      f.loops.push_back(b);
      faces_of[c].push_back(std::move(f));
    }
  for (const auto& [root, list] : members) {
    if (list.size() < 2) continue;
    const plane_component& frame = comps[root];
    auto poly_of = [&](const std::vector<std::uint32_t>& loop) {
      std::vector<glm::dvec2> poly;
      for (const auto v : loop) poly.push_back(project(frame, g.points[v]));
      return poly;
    };
    for (const auto c : list)
      for (const auto& o : comps[c].outer) {
        const glm::dvec2 probe = project(frame, g.points[o[0]]);
        double best = 0.0;
        std::pair<std::uint32_t, std::size_t> host{no_index, 0};
        std::uint32_t depth = 0;  // bounded walks of other components around this one
        for (const auto d : list) {
          if (d == c) continue;
          for (std::size_t k = 0; k < comps[d].bounded.size(); ++k) {
            budget.spend(comps[d].bounded[k].size());
            const auto poly = poly_of(comps[d].bounded[k]);
            if (!point_in_polygon(poly, probe)) continue;
            ++depth;
            const double a = std::abs(signed_area_2d(poly));
            if (host.first == no_index || a < best) best = a, host = {d, k};
          }
        }
        if (host.first == no_index) continue;
        for (auto& f : faces_of[c]) f.depth = std::max(f.depth, depth);
        // o turns clockwise about its own component's normal; the host's may point the other
        // way (which pair of edges first spanned the plane decides it), and a hole must turn
        // clockwise about its face's normal.
        std::vector<std::uint32_t> hole = o;
        if (glm::dot(comps[c].normal, comps[host.first].normal) < 0.0) std::reverse(hole.begin(), hole.end());
        faces_of[host.first][host.second].loops.push_back(std::move(hole));
        for (auto& filler : faces_of[c]) filler.fills_hole = true;
        ++r.holes;
      }
  }
  // A face's normal is its plane's fitted one (the first component's of its geometric plane,
  // turned as its loop turns): faces of one plane then have parallel normals however noisy
  // their corners, so a seam between two of them, or a hole's mouth beside the face around
  // it, reads as flat (coplanar_normals).
  for (std::uint32_t c = 0; c < comps.size(); ++c)
    for (auto& f : faces_of[c]) {
      update_normal(g, f);
      const glm::dvec3 n = comps[group[c]].normal;
      if (opt.fit_planes && f.area > 0.0) f.normal = glm::dot(f.normal, n) < 0.0 ? -n : n;
      r.faces.push_back(std::move(f));
    }
}

/// The seed's breadth-first circuit search (§4.2), faithful: from each edge, paths grow from
/// the end vertex of lower degree; paths with an inner circuit and paths starting with the
/// same two edges as a found circuit are removed. Exponential worst case; budgeted.
template <class = void>
void trace_bfs(const wire_graph& g, const trace_options& opt, trace_result& r, work_counter& budget) {
  const std::size_t max_len = opt.max_circuit_edges == 0 ? g.num_edges() : opt.max_circuit_edges;
  struct path {
    std::vector<std::uint32_t> verts;  // verts[0] = start; verts.back() = latest vertex
    std::vector<std::uint32_t> edges;
  };
  for (std::uint32_t e = 0; e < g.num_edges(); ++e) {
    const auto [s, t] = g.edges[e];
    // Grow from the vertex with fewer edges; on a tie the end vertex (seed §4.2).
    const std::uint32_t sel = g.degree(s) < g.degree(t) ? s : t;
    const std::uint32_t other = sel == s ? t : s;
    std::vector<path> current{{{other, sel}, {e}}}, next;
    std::vector<std::uint32_t> closed_second;  // second edges of circuits found from e
    std::vector<std::uint32_t> closed_now;     // ... at the current step
    while (!current.empty()) {
      next.clear();
      closed_now.clear();
      for (const auto& pth : current) {
        if (pth.edges.size() >= max_len) continue;
        const std::uint32_t last = pth.verts.back();
        for (const auto& in : g.around(last)) {
          budget.spend();
          if (std::find(pth.edges.begin(), pth.edges.end(), in.edge) != pth.edges.end()) continue;
          if (in.other == pth.verts[0]) {
            // A circuit: every circuit closing at this step is kept (seed fig. 11).
            wire_face f;
            f.loops.push_back(pth.verts);
            update_normal(g, f);
            r.faces.push_back(std::move(f));
            ++r.circuits;
            closed_now.push_back(pth.edges.size() >= 2 ? pth.edges[1] : in.edge);
            continue;
          }
          // An inner circuit (the path returns to a vertex other than its start) is removed.
          if (std::find(pth.verts.begin(), pth.verts.end(), in.other) != pth.verts.end()) continue;
          path grown = pth;
          grown.verts.push_back(in.other);
          grown.edges.push_back(in.edge);
          next.push_back(std::move(grown));
        }
      }
      // Paths starting with the same two edges as a found circuit are removed (seed fig. 11).
      closed_second.insert(closed_second.end(), closed_now.begin(), closed_now.end());
      std::erase_if(next, [&](const path& pth) {
        return std::find(closed_second.begin(), closed_second.end(), pth.edges[1]) != closed_second.end();
      });
      current.swap(next);
    }
  }
}

}  // namespace detail

/// Finds candidate faces of a labelled wireframe with the chosen tracer. Planar: polynomial,
/// O(Σ deg(v)² + Σ_planes k log k); seed_bfs: exponential worst case, stopped by the work budget
/// (then complete is false, the faces are those found, and a diagnostic names the option).
template <class = void>
trace_result trace_circuits(const wire_graph& g, const trace_options& options = {}) {
  detail::stopwatch clock;
  trace_result r;
  detail::work_counter budget{options.work_budget, 0, "trace_circuits",
                              "trace_options::work_budget (wireframe_options::trace)"};
  try {  // out of budget: the faces traced so far, complete false
    if (options.kind == tracer_kind::planar)
      detail::trace_planar(g, options, r, budget);
    else
      detail::trace_bfs(g, options, r, budget);
  } catch (const error& e) {
    detail::stop_at_budget(r, budget, e);
  }
  if (options.kind == tracer_kind::planar) r.circuits = r.faces.size();
  r.work = budget.used;
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
