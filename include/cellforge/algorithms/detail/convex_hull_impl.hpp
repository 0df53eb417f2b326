// SPDX-License-Identifier: MIT
#pragma once
// The engine of convex hull (included by algorithms/convex_hull.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <ranges>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/convex_hull.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/morton.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/detail/mesh_access.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

namespace detail::hull {

inline constexpr std::uint32_t none = 0xFFFFFFFFu;

/// A point waiting outside the hull, with its coordinates copied so that the outside
/// sets are read sequentially (the hull's cost is memory traffic, not arithmetic).
struct outside_point {
  glm::dvec3 p;
  std::uint32_t index;
};

/// A triangle of the hull under construction. Edge i runs from v[i] to v[(i+1)%3]; nbr[i]
/// is the face across it.
struct face {
  orient3d_plane plane;  // filter data of the supporting plane
  std::array<std::uint32_t, 3> v{};
  std::array<std::uint32_t, 3> nbr{};
  std::uint64_t mark = 0;              // in round r: 4r visible, 4r+1 strictly below the eye, 4r+2 coplanar
  std::array<std::uint8_t, 3> twin{};  // edge i of nbr[i] is edge i of this face, reversed
  std::uint8_t flat = 0;               // bit i: the face across edge i lies in the same plane
  bool alive = false;
};

/// Quickhull's outside set of a face: the points assigned to it (they see it).
struct outside_set {
  std::vector<outside_point> points;
  std::uint32_t furthest = 0;  // position of the largest orient3d value
  double furthest_value = 0;
};

/// The hull as index lists: vertices (input indices) and faces over them.
struct result {
  int dimension = -1;
  std::vector<std::uint32_t> vertices;      // input index of each output vertex
  std::vector<std::uint32_t> face_offsets;  // CSR faces over `vertices`
  std::vector<std::uint32_t> face_vertices;
  // For triangle output of a solid hull: per face corner c (3 f + e), the corner 3 g + k
  // whose edge is the same edge reversed, so the mesh can be linked without searching.
  std::vector<std::uint32_t> neighbours;
  std::size_t non_corner_removed = 0;
  std::size_t exact_evaluations = 0;
};

template <class = void>
class basic_engine;
using engine = basic_engine<>;

/// The 3D hull engine over a subset of the points (quickhull, or insertion with walks),
/// every orientation decision exact.
template <class>
class basic_engine {
 public:
  explicit basic_engine(std::span<const glm::dvec3> pts) : pts_(pts) {}

  /// Builds the hull of the candidates; returns the dimension of their span. When it is
  /// 3, faces() lists the triangles. O(n log n) expected.
  int run(std::span<const std::uint32_t> candidates) {
    faces_.clear();
    sets_.clear();
    free_.clear();
    with_sets_ = true;
    std::array<std::uint32_t, 4> s{};
    const int dim = initial_simplex(candidates, s);
    simplex_ = s;
    if (dim < 3) return dim;
    start_tetrahedron(s);
    assign_initial(candidates, s);
    expand();
    return 3;
  }

  /// Builds the hull by inserting the candidates one by one in the order given (see
  /// brio_order) and locating each by a walk over the faces toward it, as seen from a point
  /// inside: no outside sets at all. Best when (nearly) every point is a vertex, e.g. points
  /// on a sphere. O(n log n) expected in BRIO order.
  int run_incremental(std::span<const std::uint32_t> candidates) {
    faces_.clear();
    sets_.clear();
    free_.clear();
    with_sets_ = false;
    faces_.reserve(2 * candidates.size() + 8);  // every point may become a vertex
    std::array<std::uint32_t, 4> s{};
    const int dim = initial_simplex(candidates, s);
    simplex_ = s;
    if (dim < 3) return dim;
    start_tetrahedron(s);
    // The walk looks from a point strictly inside the first tetrahedron (checked exactly).
    centre_ = 0.25 * (pts_[s[0]] + pts_[s[1]] + pts_[s[2]] + pts_[s[3]]);
    for (std::uint32_t f = 0; f < 4; ++f) {
      double value = 0;
      if (side(faces_[f], centre_, value) >= 0) {  // a sliver: rounding put it outside
        with_sets_ = true;
        sets_.resize(faces_.size());
        assign_initial(candidates, s);
        expand();
        return 3;
      }
    }
    reset_rounds();
    std::uint32_t last = 0;
    for (std::uint32_t q : candidates) {
      if (q == s[0] || q == s[1] || q == s[2] || q == s[3]) continue;
      const glm::dvec3& p = pts_[q];
      std::uint32_t f = locate(p, last);
      double value = 0;
      if (f == none) {  // the walk ran out of budget: look at every face
        for (std::uint32_t g = 0; g < faces_.size() && f == none; ++g)
          if (faces_[g].alive && side(faces_[g], p, value) > 0) f = g;
        if (f == none) continue;
      } else if (side(faces_[f], p, value) <= 0) {
        continue;  // the ray from the centre leaves through f beyond p: p is inside or on the hull
      }
      carve(f, p);
      cone(q);
      last = created_.front();
    }
    return 3;
  }

  const std::vector<face>& faces() const noexcept { return faces_; }
  const std::array<std::uint32_t, 4>& simplex() const noexcept { return simplex_; }
  std::size_t exact_evaluations() const noexcept { return exact_; }

  int side(const face& f, const glm::dvec3& q) {
    double value = 0;
    return side(f, q, value);
  }
  /// Sign of orient3d of face f's plane and point q; `value` gets the approximation.
  int side(const face& f, const glm::dvec3& q, double& value) {
    const int s = orient3d_filter(f.plane, q, value);
    if (s != 0) return s;
    ++exact_;
    return orient3d_exact(pts_[f.v[0]], pts_[f.v[1]], pts_[f.v[2]], q);
  }
  int orient(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    double value = 0;
    const int s = orient3d_filter(prepare_orient3d(pts_[a], pts_[b], pts_[c]), pts_[d], value);
    if (s != 0) return s;
    ++exact_;
    return orient3d_exact(pts_[a], pts_[b], pts_[c], pts_[d]);
  }

 private:
  // ---------------------------------------------------------------- start

  // Picks four affinely independent candidates, spread wide for a good start: the two
  // extremes of the longest axis, the point farthest from their line, the point farthest
  // from that plane (distances approximate, independence decided exactly).
  int initial_simplex(std::span<const std::uint32_t> cand, std::array<std::uint32_t, 4>& s) {
    if (cand.empty()) return -1;
    std::array<std::uint32_t, 3> lo{}, hi{};
    lo.fill(cand[0]);
    hi.fill(cand[0]);
    for (std::uint32_t i : cand)
      for (int k = 0; k < 3; ++k) {
        if (pts_[i][k] < pts_[lo[static_cast<std::size_t>(k)]][k]) lo[static_cast<std::size_t>(k)] = i;
        if (pts_[i][k] > pts_[hi[static_cast<std::size_t>(k)]][k]) hi[static_cast<std::size_t>(k)] = i;
      }
    std::size_t axis = 0;
    for (std::size_t k = 1; k < 3; ++k)
      if (pts_[hi[k]][static_cast<int>(k)] - pts_[lo[k]][static_cast<int>(k)] >
          pts_[hi[axis]][static_cast<int>(axis)] - pts_[lo[axis]][static_cast<int>(axis)])
        axis = k;
    s[0] = lo[axis];
    s[1] = hi[axis];
    if (pts_[s[0]] == pts_[s[1]]) return 0;  // the largest extent is 0: one distinct point

    const glm::dvec3 a = pts_[s[0]], ab = pts_[s[1]] - a;
    double best = -1;
    for (std::uint32_t i : cand) {
      const glm::dvec3 c = glm::cross(ab, pts_[i] - a);
      const double d2 = glm::dot(c, c);
      if (d2 > best) best = d2, s[2] = i;
    }
    if (collinear(pts_[s[0]], pts_[s[1]], pts_[s[2]])) {  // rounding may have fooled the search
      s[2] = none;
      for (std::uint32_t i : cand)
        if (!collinear(pts_[s[0]], pts_[s[1]], pts_[i])) {
          s[2] = i;
          break;
        }
      if (s[2] == none) return 1;
    }

    const orient3d_plane plane = prepare_orient3d(pts_[s[0]], pts_[s[1]], pts_[s[2]]);
    best = -1;
    for (std::uint32_t i : cand) {
      double value = 0;
      orient3d_filter(plane, pts_[i], value);
      if (std::fabs(value) > best) best = std::fabs(value), s[3] = i;
    }
    if (orient(s[0], s[1], s[2], s[3]) == 0) {
      s[3] = none;
      for (std::uint32_t i : cand)
        if (orient(s[0], s[1], s[2], i) != 0) {
          s[3] = i;
          break;
        }
      if (s[3] == none) return 2;
    }
    return 3;
  }

  std::uint32_t new_face(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    std::uint32_t f;
    if (!free_.empty()) {
      f = free_.back();
      free_.pop_back();
    } else {
      f = static_cast<std::uint32_t>(faces_.size());
      faces_.emplace_back();
      if (with_sets_) sets_.emplace_back();
    }
    face& F = faces_[f];
    F.plane = prepare_orient3d(pts_[a], pts_[b], pts_[c]);
    F.v = {a, b, c};
    F.nbr = {none, none, none};
    F.flat = 0;
    if (with_sets_) sets_[f].points.clear();  // keeps its capacity for the next use of the slot
    F.mark = 0;
    F.alive = true;
    return f;
  }

  void start_tetrahedron(std::array<std::uint32_t, 4>& s) {
    // Faces point away from the fourth vertex: make s[3] lie below (s[0], s[1], s[2]).
    if (orient(s[0], s[1], s[2], s[3]) > 0) std::swap(s[1], s[2]);
    const std::uint32_t a = s[0], b = s[1], c = s[2], d = s[3];
    const std::array<std::array<std::uint32_t, 3>, 4> tri{{{a, b, c}, {a, d, b}, {b, d, c}, {c, d, a}}};
    for (const auto& t : tri) new_face(t[0], t[1], t[2]);
    // Neighbours: the face holding the reversed edge (no two faces are coplanar).
    for (std::uint32_t f = 0; f < 4; ++f)
      for (std::uint32_t e = 0; e < 3; ++e) {
        const std::uint32_t x = tri[f][e], y = tri[f][(e + 1) % 3];
        for (std::uint32_t g = 0; g < 4; ++g)
          for (std::uint32_t k = 0; k < 3; ++k)
            if (tri[g][k] == y && tri[g][(k + 1) % 3] == x) {
              faces_[f].nbr[e] = g;
              faces_[f].twin[e] = static_cast<std::uint8_t>(k);
            }
      }
  }

  void add_outside(std::uint32_t f, const outside_point& q, double value) {
    outside_set& S = sets_[f];
    if (S.points.empty()) {
      stack_.push_back(f);
      S.furthest = 0;
      S.furthest_value = value;
    } else if (value > S.furthest_value) {
      S.furthest = static_cast<std::uint32_t>(S.points.size());
      S.furthest_value = value;
    }
    S.points.push_back(q);
  }

  void assign_initial(std::span<const std::uint32_t> cand, const std::array<std::uint32_t, 4>& s) {
    stack_.clear();
    for (std::uint32_t q : cand) {
      if (q == s[0] || q == s[1] || q == s[2] || q == s[3]) continue;
      for (std::uint32_t f = 0; f < 4; ++f) {
        double value = 0;
        if (side(faces_[f], pts_[q], value) > 0) {
          add_outside(f, {pts_[q], q}, value);
          break;
        }
      }
    }
  }

  // ---------------------------------------------------------------- main loop

  struct horizon_edge {
    std::uint32_t a, b, outer;  // edge a -> b of a visible face; `outer` is the face beyond
    std::uint8_t outer_edge;    // the edge b -> a in `outer`
    bool flat;                  // the eye lies in the plane of `outer`
  };

  // The faces `eye` sees strictly, found from f0 (one of them) across edges: a disk, whose
  // boundary edges go to horizon_. Returns nothing; fills visible_ and horizon_.
  void carve(std::uint32_t f0, const glm::dvec3& eye_p) {
    ++round_;
    visible_.assign(1, f0);
    horizon_.clear();
    const std::uint64_t seen = 4 * round_, below = seen + 1, on = seen + 2;
    faces_[f0].mark = seen;
    for (std::size_t i = 0; i < visible_.size(); ++i) {
      const std::uint32_t g = visible_[i];
      for (std::uint32_t e = 0; e < 3; ++e) {
        const std::uint32_t h = faces_[g].nbr[e];
        face& H = faces_[h];
        if (H.mark == seen) continue;
        if (H.mark != below && H.mark != on) {
          double value = 0;
          const int s = side(H, eye_p, value);
          H.mark = s > 0 ? seen : s < 0 ? below : on;
          if (s > 0) {
            visible_.push_back(h);
            continue;
          }
        }
        horizon_.push_back({faces_[g].v[e], faces_[g].v[(e + 1) % 3], h, faces_[g].twin[e], H.mark == on});
      }
    }
  }

  // Deletes the visible faces and joins the eye to the horizon with a cone of new faces
  // (created_), linked to each other and to the faces beyond the horizon.
  void cone(std::uint32_t eye) {
    for (std::uint32_t g : visible_) {
      faces_[g].alive = false;
      if (with_sets_) sets_[g].points.clear();
      free_.push_back(g);
    }
    created_.clear();
    for (const horizon_edge& he : horizon_) {
      const std::uint32_t F = new_face(he.a, he.b, eye);
      created_.push_back(F);
      link(F, 0, he.outer, he.outer_edge, he.flat);
      if (start_round_[he.a] == round_)
        throw error(error_category::internal, "convex_hull: the horizon passes a vertex twice");
      start_of_[he.a] = F;
      start_round_[he.a] = round_;
    }
    for (std::uint32_t F : created_) {
      const std::uint32_t b = faces_[F].v[1];
      if (start_round_[b] != round_)
        throw error(error_category::internal, "convex_hull: the horizon is not a closed loop");
      const std::uint32_t G = start_of_[b];
      // Two cone faces (a, b, eye) and (b, c, eye) are coplanar when c is on F's plane.
      link(F, 1, G, 2, side(faces_[F], pts_[faces_[G].v[1]]) == 0);
    }
  }

  // Makes edge i of F and edge k of G each other's twin, flat or not.
  void link(std::uint32_t F, std::uint32_t i, std::uint32_t G, std::uint32_t k, bool flat) {
    face& A = faces_[F];
    face& B = faces_[G];
    A.nbr[i] = G;
    B.nbr[k] = F;
    A.twin[i] = static_cast<std::uint8_t>(k);
    B.twin[k] = static_cast<std::uint8_t>(i);
    A.flat = static_cast<std::uint8_t>(flat ? A.flat | (1u << i) : A.flat & ~(1u << i));
    B.flat = static_cast<std::uint8_t>(flat ? B.flat | (1u << k) : B.flat & ~(1u << k));
  }

  void reset_rounds() {
    round_ = 0;
    start_of_.assign(pts_.size(), none);
    start_round_.assign(pts_.size(), 0);
  }

  // The face whose cone from the centre contains p: from `start`, cross any edge whose
  // plane through the centre has p on its far side. none when the step budget runs out.
  std::uint32_t locate(const glm::dvec3& p, std::uint32_t start) {
    std::uint32_t f = start;
    const std::size_t budget =
        64 + 4 * static_cast<std::size_t>(std::sqrt(static_cast<double>(faces_.size())));
    for (std::size_t step = 0; step < budget; ++step) {
      const face& F = faces_[f];
      bool moved = false;
      for (std::uint32_t t = 0; t < 3 && !moved; ++t) {
        const std::uint32_t e = (t + static_cast<std::uint32_t>(step)) % 3;  // rotate: no cycling
        double value = 0;
        int o = orient3d_filter(prepare_orient3d(centre_, pts_[F.v[e]], pts_[F.v[(e + 1) % 3]]), p, value);
        if (o == 0) {
          ++exact_;
          o = orient3d_exact(centre_, pts_[F.v[e]], pts_[F.v[(e + 1) % 3]], p);
        }
        if (o < 0) {
          f = F.nbr[e];
          moved = true;
        }
      }
      if (!moved) return f;
    }
    return none;
  }

  // Quickhull: repeatedly the furthest outside point of a face becomes a vertex.
  void expand() {
    reset_rounds();
    std::vector<outside_point> points;
    while (!stack_.empty()) {
      const std::uint32_t f0 = stack_.back();
      stack_.pop_back();
      if (!faces_[f0].alive || sets_[f0].points.empty()) continue;
      const std::uint32_t eye = sets_[f0].points[sets_[f0].furthest].index;
      carve(f0, pts_[eye]);
      // Collect the outside points of the visible faces before their slots are reused.
      points.clear();
      for (std::uint32_t g : visible_)
        for (const outside_point& q : sets_[g].points)
          if (q.index != eye) points.push_back(q);
      cone(eye);
      // Points outside a deleted face are outside a new face or inside the new hull.
      for (const outside_point& q : points) {
        for (std::uint32_t F : created_) {
          double value = 0;
          if (side(faces_[F], q.p, value) > 0) {
            add_outside(F, q, value);
            break;
          }
        }
      }
    }
  }

  std::span<const glm::dvec3> pts_;
  std::vector<face> faces_;
  std::vector<outside_set> sets_;  // quickhull only, parallel to faces_
  bool with_sets_ = true;
  std::vector<std::uint32_t> free_, stack_;
  std::vector<std::uint32_t> start_of_;
  std::vector<std::uint64_t> start_round_;
  std::uint64_t round_ = 0;
  glm::dvec3 centre_{0.0};
  std::vector<std::uint32_t> visible_, created_;
  std::vector<horizon_edge> horizon_;
  std::array<std::uint32_t, 4> simplex_{};
  std::size_t exact_ = 0;
};

/// A biased randomised insertion order: random rounds of doubling size, each sorted along
/// a Morton curve, so that insertion stays random at large scale (expected O(n log n)) and
/// local within a round. Fixed seed: the same input always gives the same mesh. O(n log n).
template <class = void>
std::vector<std::uint32_t> brio_order(std::span<const glm::dvec3> pts) {
  std::vector<std::uint32_t> order(pts.size());
  std::iota(order.begin(), order.end(), 0u);
  // Fisher-Yates on splitmix64 rather than std::shuffle: the same order with every standard
  // library (a distribution's output is implementation-defined), and no <random> to compile.
  std::uint64_t state = 0x5eed5eedu;
  for (std::size_t i = order.size(); i > 1; --i) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    std::swap(order[i - 1], order[(z ^ (z >> 31)) % i]);
  }
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (std::uint32_t q : order) lo = glm::min(lo, pts[q]), hi = glm::max(hi, pts[q]);
  const glm::dvec3 extent = glm::max(hi - lo, glm::dvec3(std::numeric_limits<double>::min()));
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(order.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    keyed[i] = {morton_code(pts[order[i]], lo, extent), order[i]};
  for (std::size_t hi_end = keyed.size(); hi_end > 0;) {
    const std::size_t lo_end = hi_end > 64 ? hi_end / 2 : 0;
    std::sort(keyed.begin() + static_cast<std::ptrdiff_t>(lo_end),
              keyed.begin() + static_cast<std::ptrdiff_t>(hi_end));
    hi_end = lo_end;
  }
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

/// The convex polygon of coplanar points, counter-clockwise in the coordinate plane
/// (axes i, j) where a, b, c are not collinear; collinear points dropped. O(n log n).
template <class = void>
std::vector<std::uint32_t> planar_hull(std::span<const glm::dvec3> pts, std::span<const std::uint32_t> cand,
                                       const std::array<std::uint32_t, 4>& s) {
  int i = 0, j = 1;
  for (const auto& [u, v] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{2, 0}}) {
    const glm::dvec3 &a = pts[s[0]], &b = pts[s[1]], &c = pts[s[2]];
    if (orient2d(a[u], a[v], b[u], b[v], c[u], c[v]) != 0) {
      i = u;
      j = v;
      break;
    }
  }
  std::vector<std::uint32_t> order(cand.begin(), cand.end());
  std::sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) {
    return pts[p][i] < pts[q][i] || (pts[p][i] == pts[q][i] && pts[p][j] < pts[q][j]);
  });
  auto turn = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return orient2d(pts[a][i], pts[a][j], pts[b][i], pts[b][j], pts[c][i], pts[c][j]);
  };
  // Andrew's monotone chain: lower hull left to right, then upper hull right to left.
  std::vector<std::uint32_t> chain;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = chain.size();
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::uint32_t p = pass == 0 ? order[k] : order[order.size() - 1 - k];
      while (chain.size() >= base + 2 && turn(chain[chain.size() - 2], chain.back(), p) <= 0)
        chain.pop_back();
      chain.push_back(p);
    }
    chain.pop_back();  // the last point starts the other chain
  }
  return chain;
}

/// Per vertex of the 3D hull, twice the number of creases (non-flat edges) around it,
/// from the faces' flat bits: one sequential pass. Empty when no edge is flat at all (then
/// every vertex is a corner). O(faces).
template <class = void>
std::vector<std::uint32_t> crease_counts(const engine& eng, std::size_t n) {
  const auto& faces = eng.faces();
  if (std::none_of(faces.begin(), faces.end(), [](const face& F) { return F.alive && F.flat != 0; }))
    return {};
  std::vector<std::uint32_t> count(n, 0);
  for (const face& F : faces) {
    if (!F.alive) continue;
    for (std::uint32_t e = 0; e < 3; ++e)
      if (!(F.flat >> e & 1u)) {
        ++count[F.v[e]];
        ++count[F.v[(e + 1) % 3]];
      }
  }
  return count;
}

/// Writes the live triangles of the engine, or one polygon per planar facet, to `out`.
template <class = void>
void emit_faces(engine& eng, bool merge, result& out) {
  const auto& faces = eng.faces();
  std::vector<std::uint32_t> local(0);
  auto vertex = [&](std::uint32_t input) {
    if (local[input] == none) {
      local[input] = static_cast<std::uint32_t>(out.vertices.size());
      out.vertices.push_back(input);
    }
    return local[input];
  };
  std::uint32_t max_index = 0;
  for (const face& F : faces)
    if (F.alive) max_index = std::max({max_index, F.v[0], F.v[1], F.v[2]});
  local.assign(static_cast<std::size_t>(max_index) + 1, none);
  out.face_offsets.assign(1, 0);
  if (!merge) {
    std::vector<std::uint32_t> number(faces.size(), none);
    std::uint32_t count = 0;
    for (std::uint32_t f = 0; f < faces.size(); ++f)
      if (faces[f].alive) number[f] = count++;
    out.face_vertices.reserve(3 * count);
    out.face_offsets.reserve(count + 1);
    out.neighbours.reserve(3 * count);
    for (const face& F : faces) {
      if (!F.alive) continue;
      for (std::uint32_t v : F.v) out.face_vertices.push_back(vertex(v));
      for (std::uint32_t e = 0; e < 3; ++e) out.neighbours.push_back(3 * number[F.nbr[e]] + F.twin[e]);
      out.face_offsets.push_back(static_cast<std::uint32_t>(out.face_vertices.size()));
    }
    return;
  }
  // Group triangles across flat edges (union-find), then walk each group's boundary.
  std::vector<std::uint32_t> parent(faces.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    const face& F = faces[f];
    if (!F.alive) continue;
    for (std::uint32_t e = 0; e < 3; ++e)
      if (F.flat >> e & 1u) parent[find(f)] = find(F.nbr[e]);
  }
  // Each facet is a convex polygon whose vertices are corners: every boundary vertex has
  // exactly one outgoing boundary edge in it, so `succ` (per vertex) chains the loop.
  std::vector<std::uint32_t> succ(local.size(), none);
  std::vector<std::uint8_t> seen(faces.size(), 0);
  std::vector<std::uint32_t> members;
  for (std::uint32_t f = 0; f < faces.size(); ++f) {
    if (!faces[f].alive || seen[f]) continue;
    const std::uint32_t root = find(f);
    // Flood the group from f through flat edges to list its members.
    members.assign(1, f);
    seen[f] = 1;
    for (std::size_t k = 0; k < members.size(); ++k)
      for (std::uint32_t g : faces[members[k]].nbr)
        if (!seen[g] && find(g) == root) {
          seen[g] = 1;
          members.push_back(g);
        }
    std::uint32_t start = none;
    for (std::uint32_t g : members)
      for (std::uint32_t e = 0; e < 3; ++e)
        if (find(faces[g].nbr[e]) != root) {
          succ[faces[g].v[e]] = faces[g].v[(e + 1) % 3];
          start = faces[g].v[e];
        }
    std::uint32_t v = start;
    std::size_t guard = 0;
    do {
      out.face_vertices.push_back(vertex(v));
      v = succ[v];
      if (++guard > 3 * members.size() + 3)
        throw error(error_category::internal, "convex_hull: a merged facet has no simple boundary");
    } while (v != start);
    out.face_offsets.push_back(static_cast<std::uint32_t>(out.face_vertices.size()));
  }
}

/// True when a hull of an evenly spread sample of the points keeps most of the sample as
/// vertices (points in convex position, e.g. on a sphere): then insertion with walks beats
/// quickhull, whose outside sets only pay off when most points fall inside. O(sample).
template <class At>
bool mostly_vertices(std::size_t n, const At& point_at) {
  // About one point in eight, 32 to 512 of them: a few percent of the hull's own cost.
  if (n < 256) return false;
  const std::size_t sample = std::clamp<std::size_t>(n / 8, 32, 512);
  std::vector<glm::dvec3> some;
  const std::size_t stride = n / sample;
  for (std::size_t i = 0; i < n; i += stride) some.push_back(point_at(i));
  std::vector<std::uint32_t> all(some.size());
  std::iota(all.begin(), all.end(), 0u);
  engine eng(detail::span_of(some));
  if (eng.run(detail::span_of(all)) != 3) return false;
  std::vector<std::uint8_t> used(some.size(), 0);
  std::size_t vertices = 0;
  for (const face& F : eng.faces())
    if (F.alive)
      for (std::uint32_t v : F.v) vertices += used[v] == 0, used[v] = 1;
  return 2 * vertices >= some.size();
}

/// Inputs smaller than this are hulled whole: the filter's two passes would not pay.
inline constexpr std::size_t interior_filter_min_points = 4096;

/// Akl-Toussaint filter: from the extreme points along the 3 axes and 4 cube diagonals
/// (both ways), the points strictly inside their polytope, which cannot be hull corners, are
/// dropped; the rest are copied to `kept` with their input indices. The test is exact: an
/// axis-aligned box shown (exactly) to lie strictly inside the polytope takes most points
/// with six comparisons, the others are kept unless the orient3d filter certifies them below
/// every face. Returns false, keeping nothing, when the extremes span less than 3D.
/// O(n) for two passes over the input.
template <class At>
bool discard_interior(std::size_t n, const At& point_at, std::vector<glm::dvec3>& kept,
                      std::vector<std::uint32_t>& kept_index, std::size_t& exact) {
  // Directions: +-x, +-y, +-z, then +-(1,1,1), +-(1,1,-1), +-(1,-1,1), +-(-1,1,1).
  std::array<double, 14> best;
  best.fill(-std::numeric_limits<double>::infinity());
  std::array<std::uint32_t, 14> arg{};
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 p = point_at(i);
    const std::array<double, 7> d{
        p.x, p.y, p.z, p.x + p.y + p.z, p.x + p.y - p.z, p.x - p.y + p.z, -p.x + p.y + p.z};
    for (std::size_t k = 0; k < 7; ++k) {
      if (d[k] > best[2 * k]) best[2 * k] = d[k], arg[2 * k] = static_cast<std::uint32_t>(i);
      if (-d[k] > best[2 * k + 1]) best[2 * k + 1] = -d[k], arg[2 * k + 1] = static_cast<std::uint32_t>(i);
    }
  }
  std::sort(arg.begin(), arg.end());
  std::vector<glm::dvec3> extremes;
  for (std::size_t k = 0; k < arg.size(); ++k)
    if (k == 0 || arg[k] != arg[k - 1]) extremes.push_back(point_at(arg[k]));
  std::vector<std::uint32_t> all(extremes.size());
  std::iota(all.begin(), all.end(), 0u);
  engine polytope(detail::span_of(extremes));
  if (polytope.run(detail::span_of(all)) != 3) return false;
  std::vector<orient3d_plane> planes;
  std::vector<const face*> faces;
  for (const face& F : polytope.faces())
    if (F.alive) planes.push_back(F.plane), faces.push_back(&F);

  // The box: the extremes' bounding box shrunk toward their centroid, as large as it can be
  // with all 8 corners strictly inside (exact tests), found by bisection.
  glm::dvec3 lo = extremes[0], hi = extremes[0], centre(0.0);
  for (const glm::dvec3& e : extremes) {
    lo = glm::min(lo, e);
    hi = glm::max(hi, e);
    centre += e;
  }
  centre /= static_cast<double>(extremes.size());
  auto box_inside = [&](double t, glm::dvec3& blo, glm::dvec3& bhi) {
    blo = centre + t * (lo - centre);
    bhi = centre + t * (hi - centre);
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 q((c & 1) ? bhi.x : blo.x, (c & 2) ? bhi.y : blo.y, (c & 4) ? bhi.z : blo.z);
      for (const face* F : faces)
        if (polytope.side(*F, q) >= 0) return false;
    }
    return true;
  };
  glm::dvec3 box_lo(1.0), box_hi(0.0);  // empty until a box is found
  double inside_t = 0, outside_t = 1;
  for (int step = 0; step < 24; ++step) {
    const double t = 0.5 * (inside_t + outside_t);
    glm::dvec3 blo, bhi;
    if (box_inside(t, blo, bhi))
      inside_t = t, box_lo = blo, box_hi = bhi;
    else
      outside_t = t;
  }
  exact += polytope.exact_evaluations();

  kept.clear();
  kept_index.clear();
  std::size_t first = 0;  // the face that last kept a point is tried first: neighbours agree
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 p = point_at(i);
    if (p.x >= box_lo.x && p.x <= box_hi.x && p.y >= box_lo.y && p.y <= box_hi.y && p.z >= box_lo.z &&
        p.z <= box_hi.z)
      continue;
    bool inside = true;
    for (std::size_t k = 0; k < planes.size() && inside; ++k) {
      const std::size_t f = (first + k) % planes.size();
      double value = 0;
      if (orient3d_filter(planes[f], p, value) >= 0) inside = false, first = f;  // 0: not certified
    }
    if (inside) continue;
    kept.push_back(p);
    kept_index.push_back(static_cast<std::uint32_t>(i));
  }
  return true;
}

/// The hull of all points as index lists; see convex_hull for the degenerate cases.
template <class = void>
result compute(std::span<const glm::dvec3> pts, const convex_hull_options& options) {
  result out;
  std::vector<std::uint32_t> all(pts.size());
  std::iota(all.begin(), all.end(), 0u);
  const bool incremental =
      options.method == convex_hull_method::incremental ||
      (options.method == convex_hull_method::automatic &&
       mostly_vertices(pts.size(), [&](std::size_t i) -> const glm::dvec3& { return pts[i]; }));
  // Insertion copies the points into insertion order first: each insertion then touches
  // points and faces created just before, in memory as in space (3x fewer cache misses).
  std::vector<std::uint32_t> order;
  std::vector<glm::dvec3> reordered;
  if (incremental) {
    order = brio_order(pts);
    reordered.resize(pts.size());
    for (std::size_t i = 0; i < order.size(); ++i) reordered[i] = pts[order[i]];
    pts = detail::span_of(reordered);
  }
  engine eng(pts);
  out.dimension = incremental ? eng.run_incremental(detail::span_of(all)) : eng.run(detail::span_of(all));
  const auto& s = eng.simplex();
  out.face_offsets.assign(1, 0);
  if (out.dimension == 0) {
    out.vertices = {s[0]};
  } else if (out.dimension == 1) {
    out.vertices = {s[0], s[1]};
  } else if (out.dimension == 2) {
    out.vertices = planar_hull(pts, detail::span_of(all), s);
    const auto k = static_cast<std::uint32_t>(out.vertices.size());
    if (options.merge_coplanar) {  // the polygon and its reverse
      for (std::uint32_t i = 0; i < k; ++i) out.face_vertices.push_back(i);
      out.face_offsets.push_back(k);
      for (std::uint32_t i = k; i-- > 0;) out.face_vertices.push_back(i);
      out.face_offsets.push_back(2 * k);
    } else {  // two fans from different vertices, so that no diagonal is used twice
      auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        out.face_vertices.insert(out.face_vertices.end(), {a, b, c});
        out.face_offsets.push_back(static_cast<std::uint32_t>(out.face_vertices.size()));
      };
      for (std::uint32_t i = 1; i + 1 < k; ++i) tri(0, i, i + 1);
      tri(1, 0, k - 1);
      for (std::uint32_t i = k - 1; i > 2; --i) tri(1, i, i - 1);
    }
  } else if (out.dimension == 3) {
    // Points on the surface that are not corners (inside a facet or an edge) can become
    // vertices when inserted before the corners around them; rebuild from corners only.
    const std::vector<std::uint32_t> creases = crease_counts(eng, pts.size());
    std::vector<std::uint32_t> corners;
    std::size_t non_corner = 0;
    if (!creases.empty()) {  // some edge is flat: look for vertices with fewer than 3 creases
      std::vector<std::uint8_t> used(pts.size(), 0);
      for (const face& F : eng.faces())
        if (F.alive)
          for (std::uint32_t v : F.v) used[v] = 1;
      for (std::uint32_t v = 0; v < pts.size(); ++v)
        if (used[v]) {
          if (creases[v] >= 6)  // each crease counted from both of its faces
            corners.push_back(v);
          else
            ++non_corner;
        }
    }
    if (non_corner > 0) {
      out.non_corner_removed = non_corner;
      if (eng.run(detail::span_of(corners)) != 3)
        throw error(error_category::internal, "convex_hull: the corners of a solid hull span less than 3D");
    }
    emit_faces(eng, options.merge_coplanar, out);
  }
  out.exact_evaluations = eng.exact_evaluations();
  if (incremental)
    for (std::uint32_t& v : out.vertices) v = order[v];
  return out;
}

/// Writes the closed triangle mesh of r straight into m's records (the hull already knows
/// every face's neighbours, so no edge needs to be looked up). O(faces).
template <class = void>
void link_triangles(halfedge_mesh& m, const result& r) {
  using access = detail::mesh_access;
  const std::size_t nf = r.face_offsets.size() - 1;
  access::resize(m, r.vertices.size(), 3 * nf / 2, nf);
  std::vector<std::uint32_t> he(3 * nf, none);  // half-edge of each face corner's edge
  std::uint32_t edges = 0;
  for (std::size_t c = 0; c < 3 * nf; ++c) {
    if (he[c] != none) continue;
    const std::size_t d = r.neighbours[c];
    if (d >= 3 * nf || he[d] != none || r.neighbours[d] != c)
      throw error(error_category::internal, "convex_hull: face neighbours do not match");
    he[c] = 2 * edges;
    he[d] = 2 * edges + 1;
    ++edges;
  }
  auto& records = access::records(m);
  auto& anchors = access::face_anchors(m);
  for (std::size_t f = 0; f < nf; ++f) {
    for (std::size_t e = 0; e < 3; ++e)
      records[he[3 * f + e]] = {r.face_vertices[3 * f + (e + 1) % 3], he[3 * f + (e + 1) % 3],
                                he[3 * f + (e + 2) % 3], static_cast<std::uint32_t>(f)};
    anchors[f] = he[3 * f];
  }
  // A convex polytope's surface has one closed fan per vertex: the fan walk can be skipped.
  access::finish(m, {}, access::fan_check::trust);
}

}  // namespace detail::hull

template <std::ranges::contiguous_range R>
requires std::ranges::sized_range<R> && Point3<std::ranges::range_value_t<R>>
    surface_mesh<std::ranges::range_value_t<R>> convex_hull(const R& input,
                                                            const convex_hull_options& options,
                                                            convex_hull_report* report) {
  using P = std::ranges::range_value_t<R>;
  const std::span<const P> points(std::ranges::data(input), std::ranges::size(input));
  if (points.size() >= detail::hull::none)
    throw error(error_category::invalid_input, "convex_hull: too many points for 32-bit indices");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3 p = to_dvec3(points[i]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("convex_hull: point ", std::to_string(i),
                                         " has a NaN or infinite coordinate"));
  }
  const auto point_at = [&](std::size_t i) { return to_dvec3(points[i]); };
  convex_hull_options run = options;
  if (run.method == convex_hull_method::automatic)
    run.method = detail::hull::mostly_vertices(points.size(), point_at) ? convex_hull_method::incremental
                                                                        : convex_hull_method::quickhull;
  std::vector<glm::dvec3> pts;
  std::vector<std::uint32_t> kept_index;  // input index of each point in pts, when some were dropped
  std::size_t filter_exact = 0;
  if (!(run.method == convex_hull_method::quickhull && options.discard_interior &&
        points.size() >= detail::hull::interior_filter_min_points &&
        detail::hull::discard_interior(points.size(), point_at, pts, kept_index, filter_exact))) {
    kept_index.clear();
    pts.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) pts[i] = point_at(i);
  }
  detail::hull::result r = detail::hull::compute(detail::span_of(pts), run);
  if (!kept_index.empty())
    for (std::uint32_t& v : r.vertices) v = kept_index[v];
  r.exact_evaluations += filter_exact;
  if (r.dimension < 3 && !options.allow_degenerate)
    throw error(error_category::invalid_input,
                r.dimension < 0 ? std::string("convex_hull: no points given")
                                : cellforge::detail::cat("convex_hull: the points span only ",
                                                         std::to_string(r.dimension), " dimension(s) (all ",
                                                         (r.dimension == 2   ? "coplanar"
                                                          : r.dimension == 1 ? "collinear"
                                                                             : "equal"),
                                                         "); set allow_degenerate to accept a flat hull"));
  surface_mesh<P> m;
  auto pos = m.positions();
  auto index = m.template add_vertex_property<std::uint32_t>(input_index_property_name, detail::hull::none);
  if (!r.neighbours.empty())
    detail::hull::link_triangles(m, r);
  else
    m.build(r.vertices.size(), r.face_offsets, r.face_vertices);
  for (std::size_t v = 0; v < r.vertices.size(); ++v) {
    pos.vector()[v] = points[r.vertices[v]];
    index.vector()[v] = r.vertices[v];
  }
  if (report) {
    report->dimension = r.dimension;
    report->input_points = points.size();
    report->vertices = m.num_vertices();
    report->edges = m.num_edges();
    report->faces = m.num_faces();
    report->non_corner_vertices_removed = r.non_corner_removed;
    report->exact_evaluations = r.exact_evaluations;
    report->interior_discarded = points.size() - pts.size();
  }
  return m;
}

}  // namespace cellforge
