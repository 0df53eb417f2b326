// SPDX-License-Identifier: MIT
#pragma once
// The engine of the face arrangement (included by wireframe/face_arrangement.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/morton.hpp"
#include "cellforge/core/polygon_intersection.hpp"
#include "cellforge/core/tolerance.hpp"
#include "cellforge/wireframe/face_arrangement.hpp"
#include "cellforge/wireframe/face_reduction.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

namespace detail {

struct face_plane {
  glm::dvec3 n{0.0}, o{0.0};
  bounding_box box;
};

/// One end of an interval where a face's interior meets another face's plane: its position
/// along the planes' common line and where it comes from (a vertex on the plane, exact, or the
/// crossing of edge (from, to) with the plane, constructed).
struct cut_end {
  double s = 0.0;
  std::uint32_t from = no_index, to = no_index;  ///< to == no_index: the vertex `from`
};

template <class = void>
class basic_interior_cuts;
using interior_cuts = basic_interior_cuts<>;

/// Open intervals [2k, 2k+1] of the line along `dir` that lie inside face f and meet plane p
/// from both sides. side[v] of f's vertices: +1 / -1 beyond tolerance, 0 on the plane (within
/// tolerance, or a vertex of the other face). Seen from just above the plane a vertex on it
/// counts as below, from just below as above; a point of the line is inside f's interior
/// only if it is inside from both views, so a boundary edge lying in the plane bounds no
/// interval (the fault that made faces meeting at such an edge "cross"). O(L log L).
template <class>
class basic_interior_cuts {
 public:
  std::vector<cut_end> intervals;

  /// `corners`: the positions of f's loops, concatenated in order (contiguous for speed).
  void compute(const wire_face& f, std::span<const glm::dvec3> corners, const face_plane& p,
               const glm::dvec3& dir, const glm::dvec3& centre, double tol) {
    above_.clear();
    below_.clear();
    std::size_t base = 0;
    for (const auto& loop : f.loops) {
      const std::size_t n = loop.size();
      sides_.resize(n);
      for (std::size_t k = 0; k < n; ++k) {
        const double d = glm::dot(p.n, corners[base + k] - p.o);
        sides_[k] = static_cast<signed char>(d > tol ? 1 : d < -tol ? -1 : 0);
      }
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t k1 = k + 1 == n ? 0 : k + 1;
        const int sx = sides_[k], sy = sides_[k1];
        if (sx == sy) continue;  // both beyond one side, or both on the plane: no end in either view
        const std::uint32_t x = loop[k], y = loop[k1];
        cut_end end;
        if (sx == 0 || sy == 0) {
          const bool at_x = sx == 0;
          end = {glm::dot(corners[base + (at_x ? k : k1)] - centre, dir), at_x ? x : y, no_index};
        } else {
          const glm::dvec3 a = corners[base + k], b = corners[base + k1];
          const double da = glm::dot(p.n, a - p.o), db = glm::dot(p.n, b - p.o);
          const glm::dvec3 c = a + (da / (da - db)) * (b - a);
          end = {glm::dot(c - centre, dir), x, y};
        }
        // Seen from just above the plane a vertex on it counts as below; from below, as above.
        if ((sx > 0) != (sy > 0)) above_.push_back(end);
        if ((sx >= 0) != (sy >= 0)) below_.push_back(end);
      }
      base += n;
    }
    auto by_position = [](const cut_end& a, const cut_end& b) { return a.s < b.s; };
    std::sort(above_.begin(), above_.end(), by_position);
    std::sort(below_.begin(), below_.end(), by_position);
    // Intersection of the two interval sets.
    intervals.clear();
    for (std::size_t i = 0, j = 0; i + 1 < above_.size() && j + 1 < below_.size();) {
      const cut_end& lo = above_[i].s >= below_[j].s ? above_[i] : below_[j];
      const cut_end& hi = above_[i + 1].s <= below_[j + 1].s ? above_[i + 1] : below_[j + 1];
      if (lo.s < hi.s) {
        intervals.push_back(lo);
        intervals.push_back(hi);
      }
      if (above_[i + 1].s < below_[j + 1].s)
        i += 2;
      else
        j += 2;
    }
  }

 private:
  std::vector<cut_end> above_, below_;
  std::vector<signed char> sides_;
};

template <class = void>
class basic_crossing_test;
using crossing_test = basic_crossing_test<>;

/// The crossing test of the selection rule, with its scratch space. Two faces in different
/// planes cross when their interiors share a segment of the planes' common line longer than
/// the tolerance: the parity along that line decides it from the vertices' sides alone (a
/// vertex within the tolerance of a plane is on it, as the tracer and the planarity check
/// decided, so the vertices the faces share are on both planes), and where a segment end is
/// constructed (an edge crossing a plane) the exact test of core/polygon_intersection.hpp
/// confirms that the edge really pierces the other face's interior. Independent of loop
/// orientation. O(L log L) per pair, O(L_a + L_b) to confirm.
template <class>
class basic_crossing_test {
 public:
  explicit basic_crossing_test(const wire_graph& g) : g_(g) {}

  /// `ca`, `cb`: the faces' corners, all loops concatenated (gathered from the graph when empty).
  bool operator()(const wire_face& a, const face_plane& pa, const wire_face& b, const face_plane& pb,
                  double tol, std::span<const glm::dvec3> ca = {}, std::span<const glm::dvec3> cb = {}) {
    glm::dvec3 dir = glm::cross(pa.n, pb.n);
    const double l = glm::length(dir);
    if (l < 1e-12) return false;  // parallel planes: coplanar faces never overlap after tracing
    if (ca.empty()) ca = gather(a, own_a_);
    if (cb.empty()) cb = gather(b, own_b_);
    if (!straddles(ca, pb, tol) || !straddles(cb, pa, tol)) return false;
    dir /= l;
    ca_.compute(a, ca, pb, dir, g_.center, tol);
    cb_.compute(b, cb, pa, dir, g_.center, tol);
    const auto& ia = ca_.intervals;
    const auto& ib = cb_.intervals;
    for (std::size_t i = 0, j = 0; i + 1 < ia.size() && j + 1 < ib.size();) {
      const bool lo_a = ia[i].s >= ib[j].s, hi_a = ia[i + 1].s <= ib[j + 1].s;
      const cut_end& lo = lo_a ? ia[i] : ib[j];
      const cut_end& hi = hi_a ? ia[i + 1] : ib[j + 1];
      if (hi.s - lo.s > tol && confirmed(lo, lo_a ? b : a, hi, hi_a ? b : a)) return true;
      if (ia[i + 1].s < ib[j + 1].s)
        i += 2;
      else
        j += 2;
    }
    return false;
  }

 private:
  const wire_graph& g_;
  interior_cuts ca_, cb_;
  std::vector<glm::dvec3> own_a_, own_b_;

  std::span<const glm::dvec3> gather(const wire_face& f, std::vector<glm::dvec3>& out) const {
    out.clear();
    for (const auto& loop : f.loops)
      for (const auto v : loop) out.push_back(g_.points[v]);
    return detail::span_of(out);
  }
  /// Some corner strictly on each side of p.
  static bool straddles(std::span<const glm::dvec3> corners, const face_plane& p, double tol) {
    bool up = false, down = false;
    for (const auto& c : corners) {
      const double d = glm::dot(p.n, c - p.o);
      up = up || d > tol;
      down = down || d < -tol;
      if (up && down) return true;
    }
    return false;
  }
  /// A shared segment whose ends are vertices is decided by the vertices' sides; an end made
  /// by an edge crossing a plane is confirmed by that edge piercing the other face exactly.
  bool confirmed(const cut_end& lo, const wire_face& lo_other, const cut_end& hi,
                 const wire_face& hi_other) const {
    if (lo.to == no_index && hi.to == no_index) return true;
    for (const auto* e : {&lo, &hi}) {
      if (e->to == no_index) continue;
      const wire_face& other = e == &lo ? lo_other : hi_other;
      if (segment_pierces_polygon(detail::span_of(g_.points), other.loops,
                                  plane_vertices(detail::span_of(g_.points), other.loops), g_.points[e->from],
                                  g_.points[e->to]))
        return true;
    }
    return false;
  }
};

template <class = void>
class basic_crossing_decision;
using crossing_decision = basic_crossing_decision<>;

/// Decides the crossing pairs the rounds of the selection rule leave open: a branch and bound
/// over the contested faces of each component (faces joined by a crossing pair or a shared
/// edge), keep or drop each. A reading is certified when no crossing pair keeps both faces and
/// every edge whose candidates made it genuine (three faces, or two not coplanar) still does;
/// the best keeps the fewest contested faces, and readings equal in that keep only the faces
/// all of them keep (the old "both go", where it is certified). Keeping a face drops its
/// partners; dropping one keeps the faces an edge then needs. Per component at most
/// `component_nodes` nodes; past that (or past the work budget) the best reading found, with a
/// diagnostic. O(nodes · L · k) per component.
template <class>
class basic_crossing_decision {
 public:
  std::uint64_t component_nodes = 1u << 15;
  std::vector<std::string> notes;

  basic_crossing_decision(const wire_graph& g, const std::vector<wire_face>& faces, const edge_face_lists& at,
                          std::vector<char>& alive)
      : g_(g), faces_(faces), at_(at), alive_(alive), local_(faces.size(), no_index) {}

  /// Drops (alive = 0) the losers of `pairs` (both alive); returns them.
  std::vector<std::uint32_t> run(const std::vector<std::array<std::uint32_t, 2>>& pairs,
                                 work_counter& budget) {
    std::vector<std::uint32_t> losers;
    if (pairs.empty()) return losers;
    const std::uint32_t nf = static_cast<std::uint32_t>(faces_.size());
    partners_.assign(nf, {});
    std::vector<std::uint32_t> contested;
    for (const auto& [a, b] : pairs) {
      partners_[a].push_back(b);
      partners_[b].push_back(a);
      contested.push_back(a);
      contested.push_back(b);
    }
    std::sort(contested.begin(), contested.end());
    contested.erase(std::unique(contested.begin(), contested.end()), contested.end());
    genuine0_.assign(g_.num_edges(), 2);  // 2: not computed yet
    union_find comp(nf);
    std::vector<char> is_contested(nf, 0);
    for (const auto f : contested) is_contested[f] = 1;
    for (const auto& [a, b] : pairs) comp.unite(a, b);
    for (const auto f : contested)
      for_edges(f, [&](std::uint32_t e) {
        for (const auto j : at_[e])
          if (j != f && is_contested[j]) comp.unite(f, j);
      });
    std::vector<std::pair<std::uint32_t, std::uint32_t>> by_comp;
    for (const auto f : contested) by_comp.push_back({comp.find(f), f});
    std::sort(by_comp.begin(), by_comp.end());
    for (std::size_t b = 0, e = 0; b < by_comp.size(); b = e) {
      G_.clear();
      for (e = b; e < by_comp.size() && by_comp[e].first == by_comp[b].first; ++e)
        G_.push_back(by_comp[e].second);
      decide(budget, losers);
    }
    for (const auto f : losers) alive_[f] = 0;
    std::sort(losers.begin(), losers.end());
    return losers;
  }

 private:
  const wire_graph& g_;
  const std::vector<wire_face>& faces_;
  const edge_face_lists& at_;
  std::vector<char>& alive_;
  std::vector<std::vector<std::uint32_t>> partners_;
  std::vector<char> genuine0_;  // per edge: its faces at the start made it genuine
  std::vector<std::uint32_t> local_, G_, scratch_, queue_;
  std::vector<char> st_;  // per component face: 0 open, 1 keep, 2 drop
  std::vector<std::pair<std::uint32_t, char>> trail_;
  std::vector<std::vector<char>> optima_;
  std::uint32_t best_ = 0;
  bool have_best_ = false, stopped_ = false;
  std::uint64_t nodes_ = 0, limit_ = 0;

  template <class Visit>
  void for_edges(std::uint32_t i, Visit&& visit) const {
    for (const auto& loop : faces_[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k) visit(g_.find_edge(loop[k], loop[(k + 1) % loop.size()]));
  }
  bool present(std::uint32_t j) const {
    if (!alive_[j]) return false;
    const auto l = local_[j];
    return l == no_index || st_[l] != 2;
  }
  bool genuine(std::uint32_t e, std::uint32_t skip) {
    scratch_.clear();
    for (const auto j : at_[e])
      if (j != skip && present(j)) scratch_.push_back(j);
    auto normal = [&](std::uint32_t j) { return faces_[j].normal; };
    return !edge_needs_more(scratch_, normal);
  }
  void set(std::uint32_t l, char v) {
    trail_.push_back({l, st_[l]});
    st_[l] = v;
    queue_.push_back(l);
  }
  bool assign(std::uint32_t l, char v) {
    if (st_[l] != 0) return st_[l] == v;
    queue_.clear();
    set(l, v);
    while (!queue_.empty()) {
      const auto x = queue_.back();
      queue_.pop_back();
      const auto f = G_[x];
      if (st_[x] == 1) {
        for (const auto p : partners_[f]) {
          const auto lp = local_[p];
          if (lp == no_index || !alive_[p]) continue;
          if (st_[lp] == 1) return false;
          if (st_[lp] == 0) set(lp, 2);
        }
        continue;
      }
      bool ok = true;
      for_edges(f, [&](std::uint32_t e) {
        if (!ok) return;
        if (genuine0_[e] == 2) {
          scratch_.clear();
          for (const auto j : at_[e])
            if (alive_[j]) scratch_.push_back(j);
          auto normal = [&](std::uint32_t j) { return faces_[j].normal; };
          genuine0_[e] = !edge_needs_more(scratch_, normal);
        }
        if (!genuine0_[e]) return;
        if (!genuine(e, no_index)) {
          ok = false;
          return;
        }
        for (const auto j : at_[e]) {
          const auto lj = local_[j];
          if (lj == no_index || st_[lj] != 0 || !alive_[j]) continue;
          if (!genuine(e, j)) set(lj, 1);
        }
      });
      if (!ok) return false;
    }
    return true;
  }
  void undo_to(std::size_t mark) {
    while (trail_.size() > mark) {
      st_[trail_.back().first] = trail_.back().second;
      trail_.pop_back();
    }
  }
  void dfs(std::size_t pos, std::uint32_t kept) {
    if (stopped_) return;
    if (++nodes_ > limit_) {
      stopped_ = true;
      return;
    }
    while (pos < G_.size() && st_[pos] != 0) kept += st_[pos++] == 1;
    if (have_best_ && kept > best_) return;
    if (pos == G_.size()) {
      if (!have_best_ || kept < best_) optima_.clear();
      best_ = kept;
      have_best_ = true;
      if (optima_.size() < 8) optima_.push_back(st_);
      return;
    }
    for (const char v : {char{2}, char{1}}) {
      const std::size_t mark = trail_.size();
      // Faces before pos are decided; count the ones this step decides from pos on.
      if (assign(static_cast<std::uint32_t>(pos), v)) dfs(pos, kept);
      undo_to(mark);
      if (stopped_ || (have_best_ && best_ == 0)) return;
    }
  }
  void decide(work_counter& budget, std::vector<std::uint32_t>& losers) {
    // Larger faces last: the smaller ones are tried (dropped) first.
    std::sort(G_.begin(), G_.end(), [&](std::uint32_t a, std::uint32_t b) {
      return faces_[a].area != faces_[b].area ? faces_[a].area < faces_[b].area : a < b;
    });
    for (std::uint32_t l = 0; l < G_.size(); ++l) local_[G_[l]] = l;
    st_.assign(G_.size(), 0);
    trail_.clear();
    optima_.clear();
    have_best_ = stopped_ = false;
    nodes_ = 0;
    const std::uint64_t left =
        budget.limit == 0 ? ~std::uint64_t{0} : (budget.limit > budget.used ? budget.limit - budget.used : 0);
    limit_ = std::min<std::uint64_t>(component_nodes, left / (G_.size() + 1) + 1);
    dfs(0, 0);
    budget.spend(std::min<std::uint64_t>(nodes_ * (G_.size() + 1), left));
    std::vector<char> choice;
    if (have_best_) {
      choice = optima_.front();
      if (optima_.size() > 1) {
        // Readings equal in the count keep only what all of them keep, when that is certified.
        std::vector<char> meet(G_.size(), 1);
        for (const auto& o : optima_)
          for (std::uint32_t l = 0; l < G_.size(); ++l)
            if (o[l] == 2) meet[l] = 2;
        st_.assign(G_.size(), 0);
        bool ok = true;
        for (std::uint32_t l = 0; l < G_.size() && ok; ++l) ok = meet[l] != 2 || assign(l, 2);
        for (std::uint32_t l = 0; l < G_.size() && ok; ++l) ok = assign(l, meet[l]);
        undo_to(0);
        if (ok) choice = meet;
      }
    }
    if (!have_best_) {
      // Nothing certified within the budget or at all: the old rule, both faces of each pair go.
      choice.assign(G_.size(), 2);
      notes.push_back(cellforge::detail::cat("no certified choice among ", std::to_string(G_.size()),
                                             " crossing candidates; all of them dropped"));
    } else if (stopped_) {
      notes.push_back(
          cellforge::detail::cat("the choice among ", std::to_string(G_.size()),
                                 " crossing candidates stopped at its work budget; the best found is taken"));
    }
    for (std::uint32_t l = 0; l < G_.size(); ++l)
      if (choice[l] == 2) losers.push_back(G_[l]);
    for (const auto f : G_) local_[f] = no_index;
  }
};

/// The pairs of faces whose boxes meet, from a uniform grid of cells about twice the median
/// face size: small faces are listed in the cells their box covers and a pair is reported in
/// the one cell holding the low corner of the intersection of their boxes; a large face (over
/// 512 cells) is paired with the small faces in the cells its plane passes through, and with
/// the other large faces. Faces are indices into `plane`. O(Σ cells per face log + pairs +
/// Σ_large cells its plane meets).
template <class Visit>
void candidate_pairs(const wire_graph& g, const std::vector<face_plane>& plane, double tol,
                     work_counter& budget, Visit&& visit) {
  if (plane.size() < 2) return;
  std::vector<double> extent;
  for (std::uint32_t i = 0; i < plane.size(); ++i) {
    const glm::dvec3 d = plane[i].box.max - plane[i].box.min;
    extent.push_back(std::max({d.x, d.y, d.z}));
  }
  std::nth_element(extent.begin(), extent.begin() + static_cast<std::ptrdiff_t>(extent.size() / 2),
                   extent.end());
  // The lattice is shifted off round numbers so that faces of axis-aligned models do not all
  // end on cell boundaries: about two cells per face.
  const double h = 2.0 * std::max(extent[extent.size() / 2], g.size * 1e-6);
  const glm::dvec3 shift(0.3719, 0.2917, 0.1343);
  auto coord = [&](double x, int k) {
    // Clamped: a cell index never overflows, whatever the coordinates.
    const double c = std::floor((x - g.center[k]) / h + shift[k]);
    return static_cast<std::int64_t>(std::clamp(c, -1e15, 1e15));
  };
  auto cell = [&](const glm::dvec3& p) {
    return std::array<std::int64_t, 3>{coord(p.x, 0), coord(p.y, 1), coord(p.z, 2)};
  };
  // The grid as (cell, face) entries sorted by cell: a cell's faces are a run.
  using cell_key = std::array<std::int64_t, 3>;
  std::vector<std::pair<cell_key, std::uint32_t>> grid;
  std::vector<std::uint32_t> big;
  for (std::uint32_t i = 0; i < plane.size(); ++i) {
    const auto lo = cell(plane[i].box.min - tol), hi = cell(plane[i].box.max + tol);
    const double count = static_cast<double>(hi[0] - lo[0] + 1) * static_cast<double>(hi[1] - lo[1] + 1) *
                         static_cast<double>(hi[2] - lo[2] + 1);
    if (count > 512) {
      big.push_back(i);
      continue;
    }
    for (auto x = lo[0]; x <= hi[0]; ++x)
      for (auto y = lo[1]; y <= hi[1]; ++y)
        for (auto z = lo[2]; z <= hi[2]; ++z) grid.push_back({{x, y, z}, i});
  }
  std::sort(grid.begin(), grid.end());
  auto boxes_meet = [&](std::uint32_t a, std::uint32_t b) {
    const auto &A = plane[a].box, &B = plane[b].box;
    for (int k = 0; k < 3; ++k)
      if (A.min[k] > B.max[k] + tol || B.min[k] > A.max[k] + tol) return false;
    return true;
  };
  for (std::size_t begin = 0, end = 0; begin < grid.size(); begin = end) {
    const cell_key c = grid[begin].first;
    while (end < grid.size() && grid[end].first == c) ++end;
    for (std::size_t x = begin; x < end; ++x)
      for (std::size_t y = x + 1; y < end; ++y) {
        const std::uint32_t a = grid[x].second, b = grid[y].second;
        if (!boxes_meet(a, b)) continue;
        if (cell(glm::max(plane[a].box.min, plane[b].box.min) - tol) != c) continue;
        visit(a, b);
      }
  }
  // Large faces: walk the cells their plane passes through, column by column along the
  // plane's steepest axis.
  std::vector<std::uint32_t> seen(plane.size(), no_index);
  std::vector<char> is_big(plane.size(), 0);
  for (const auto b : big) is_big[b] = 1;
  for (const auto b : big) {
    const glm::dvec3 n = plane[b].n, o = plane[b].o;
    const int k = std::abs(n.x) >= std::abs(n.y) && std::abs(n.x) >= std::abs(n.z) ? 0
                  : std::abs(n.y) >= std::abs(n.z)                                 ? 1
                                                                                   : 2;
    const int u = (k + 1) % 3, w = (k + 2) % 3;
    const auto lo = cell(plane[b].box.min - tol), hi = cell(plane[b].box.max + tol);
    // A face far larger than the cells (a long part beside tiny ones) crosses more columns
    // than there are faces: its boxes are then tested against every face's, which costs less.
    const double columns =
        (static_cast<double>(hi[u] - lo[u]) + 1) * (static_cast<double>(hi[w] - lo[w]) + 1);
    if (columns > 4.0 * static_cast<double>(plane.size())) {
      for (std::uint32_t i = 0; i < plane.size(); ++i) {
        budget.spend();
        if (!is_big[i] && boxes_meet(b, i)) visit(b, i);
      }
      continue;
    }
    for (auto cu = lo[u]; cu <= hi[u]; ++cu)
      for (auto cw = lo[w]; cw <= hi[w]; ++cw) {
        // The plane's k-range over this column (its four corners), widened by the tolerance.
        double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
        for (int corner = 0; corner < 4; ++corner) {
          glm::dvec3 p(0.0);
          p[u] = (static_cast<double>(cu + (corner & 1)) - shift[u]) * h + g.center[u];
          p[w] = (static_cast<double>(cw + (corner >> 1)) - shift[w]) * h + g.center[w];
          const double z = o[k] - (n[u] * (p[u] - o[u]) + n[w] * (p[w] - o[w])) / n[k];
          zmin = std::min(zmin, z);
          zmax = std::max(zmax, z);
        }
        const auto z0 = std::max(lo[k], coord(zmin - tol, k)), z1 = std::min(hi[k], coord(zmax + tol, k));
        for (auto cz = z0; cz <= z1; ++cz) {
          budget.spend();
          std::array<std::int64_t, 3> c{};
          c[static_cast<std::size_t>(k)] = cz;
          c[static_cast<std::size_t>(u)] = cu;
          c[static_cast<std::size_t>(w)] = cw;
          auto it = std::lower_bound(grid.begin(), grid.end(), std::pair<cell_key, std::uint32_t>{c, 0});
          for (; it != grid.end() && it->first == c; ++it)
            if (const auto i = it->second; std::exchange(seen[i], b) != b && boxes_meet(b, i)) visit(b, i);
        }
      }
  }
  for (std::size_t x = 0; x < big.size(); ++x)
    for (std::size_t y = x + 1; y < big.size(); ++y)
      if (boxes_meet(big[x], big[y])) visit(big[x], big[y]);
}

}  // namespace detail

template <class>
arrangement_result arrange_faces(const wire_graph& g, const std::vector<wire_face>& faces,
                                 const reduction_result& reduction, const arrangement_options& options) {
  detail::stopwatch clock;
  arrangement_result r;
  const double tol = options.planarity.relative * g.size;
  const std::size_t nv = g.num_vertices(), ne = g.num_edges();

  // Smooth entity chains: join the two edges at a degree-2 vertex when they run straight on.
  detail::union_find chain(ne);
  std::vector<char> inner(nv, 0);
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (g.degree(v) != 2) continue;
    const auto in = g.around(v);
    const glm::dvec3 a = g.points[in[0].other] - g.points[v], b = g.points[in[1].other] - g.points[v];
    if (glm::length(glm::cross(a, b)) <= tol * std::max(glm::length(a), glm::length(b)) &&
        glm::dot(a, b) < 0.0) {
      chain.unite(in[0].edge, in[1].edge);
      inner[v] = 1;
    }
  }
  r.chain_of_edge.resize(ne);
  std::vector<std::uint32_t> chain_size(ne, 0);
  for (std::uint32_t e = 0; e < ne; ++e) ++chain_size[r.chain_of_edge[e] = chain.find(e)];
  for (std::uint32_t e = 0; e < ne; ++e) r.chains += chain_size[e] > 1;
  // A chain's two ends: the endpoints of its edges that are not inner vertices.
  std::vector<std::array<std::uint32_t, 2>> ends(ne, {no_index, no_index});
  for (std::uint32_t e = 0; e < ne; ++e)
    for (const auto v : g.edges[e]) {
      if (inner[v]) continue;
      auto& en = ends[r.chain_of_edge[e]];
      (en[0] == no_index ? en[0] : en[1]) = v;
    }
  // Shpitalni–Lipson: R(e) <= min(d(v1), d(v2)) - 1, with a chain's ends standing in for
  // the inner degree-2 vertices (the seed's chain form of the bound); R(v) <= d(d - 1) / 2.
  r.edge_rank.resize(ne);
  for (std::uint32_t e = 0; e < ne; ++e) {
    const auto en = ends[r.chain_of_edge[e]];
    if (en[0] == no_index || en[1] == no_index) {
      r.edge_rank[e] = 1;  // a closed straight chain cannot happen; be safe
      continue;
    }
    const auto d = static_cast<std::uint32_t>(std::min(g.degree(en[0]), g.degree(en[1])));
    r.edge_rank[e] = d > 0 ? d - 1 : 0;
  }
  r.vertex_rank.resize(nv);
  for (std::uint32_t v = 0; v < nv; ++v) {
    const auto d = static_cast<std::uint32_t>(g.degree(v));
    r.vertex_rank[v] = inner[v] ? r.edge_rank[g.around(v)[0].edge] : d * (d - 1) / 2;
  }

  // Planes and boxes of the usable candidates, laid out in Morton order of their boxes'
  // centres so that faces near in space are near in memory: a pair test reads neighbours.
  std::vector<std::uint32_t> usable;
  std::vector<char> alive(faces.size(), 0);
  for (std::uint32_t i = 0; i < faces.size(); ++i)
    if (reduction.quality[i].usable) usable.push_back(i), alive[i] = 1;
  std::vector<detail::face_plane> plane(usable.size());
  {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
    const glm::dvec3 lo = g.center - 0.5 * g.size, extent(std::max(g.size, 1e-300));
    for (const auto i : usable) {
      bounding_box box;
      for (const auto v : faces[i].loops[0]) box.add(g.points[v]);
      keyed.push_back({detail::morton_code(box.center(), lo, extent), i});
    }
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t k = 0; k < keyed.size(); ++k) {
      const std::uint32_t i = usable[k] = keyed[k].second;
      plane[k].n = faces[i].normal;
      plane[k].o = g.points[faces[i].loops[0][0]];
      for (const auto v : faces[i].loops[0]) plane[k].box.add(g.points[v]);
    }
  }
  detail::work_counter budget{options.work_budget, 0, "arrange_faces",
                              "arrangement_options::work_budget (wireframe_options::arrangement)"};
  // Out of budget the crossing rule stops: the faces it has not dropped stay selected (crossing
  // pairs among them undecided), complete false.
  try {
    if (options.drop_crossing) {
      detail::crossing_test cross(g);
      // Each face's corners side by side: the first test of a pair (does each face have corners
      // strictly on both sides of the other's plane?) then reads two short runs, not scattered
      // points — most pairs (neighbours on a surface) end there.
      std::vector<std::uint32_t> corner_start(usable.size() + 1, 0);
      std::vector<glm::dvec3> corner;
      for (std::uint32_t k = 0; k < usable.size(); ++k) {
        for (const auto& loop : faces[usable[k]].loops)
          for (const auto v : loop) corner.push_back(g.points[v]);
        corner_start[k + 1] = static_cast<std::uint32_t>(corner.size());
      }
      auto corners = [&](std::uint32_t k) {
        return std::span<const glm::dvec3>(corner.data() + corner_start[k],
                                           corner_start[k + 1] - corner_start[k]);
      };
      auto straddles = [&](std::uint32_t f, std::uint32_t o) {
        bool up = false, down = false;
        for (std::uint32_t k = corner_start[f]; k < corner_start[f + 1] && !(up && down); ++k) {
          const double d = glm::dot(plane[o].n, corner[k] - plane[o].o);
          up = up || d > tol;
          down = down || d < -tol;
        }
        return up && down;
      };
      detail::candidate_pairs(g, plane, tol, budget, [&](std::uint32_t x, std::uint32_t y) {
        ++r.pairs_tested;
        const std::uint32_t a = usable[x], b = usable[y];
        budget.spend(corner_start[x + 1] - corner_start[x] + corner_start[y + 1] - corner_start[y]);
        // The face with fewer corners first: a ring against a neighbour's plane lies on one side.
        const bool x_first = corner_start[x + 1] - corner_start[x] <= corner_start[y + 1] - corner_start[y];
        if (x_first ? !straddles(x, y) || !straddles(y, x) : !straddles(y, x) || !straddles(x, y)) return;
        if (cross(faces[a], plane[x], faces[b], plane[y], tol, corners(x), corners(y)))
          r.crossings.push_back({std::min(a, b), std::max(a, b)});
      });
      std::sort(r.crossings.begin(), r.crossings.end());
      // The needed one of a crossing pair wins, in rounds: a face needed among all the
      // candidates beats one that is not; failing that, a face needed once the contested
      // candidates (those in a crossing pair) are left out beats one that is not needed even
      // then (spurious cycles — rings, meridians — pad the edges of the real faces they cross
      // or lie beside). A round's losers leave, which can make others needed: decide again.
      // Pairs still crossing when no round decides anything go to the search below.
      const auto at = detail::faces_at_edges(g, faces, &alive);
      std::vector<char> contested(faces.size(), 0), no_contest(faces.size(), 0);
      std::vector<std::uint32_t> scratch;
      for (bool changed = !r.crossings.empty(); changed;) {
        changed = false;
        budget.spend(r.crossings.size() + faces.size());
        std::fill(contested.begin(), contested.end(), 0);
        for (const auto& [a, b] : r.crossings)
          if (alive[a] && alive[b]) contested[a] = contested[b] = 1;
        for (std::size_t i = 0; i < faces.size(); ++i) no_contest[i] = alive[i] && !contested[i];
        const std::vector<char> needed = detail::needed_faces(g, faces, at, alive);
        // Needed among the uncontested faces: the face itself plus the faces no pair contests.
        std::vector<char> needed_alone(faces.size(), 0);
        for (std::uint32_t i = 0; i < faces.size(); ++i)
          if (contested[i] && alive[i])
            needed_alone[i] = detail::needed_faces_one(g, faces, at, no_contest, i, scratch);
        std::vector<std::uint32_t> losers;
        for (const auto& [a, b] : r.crossings) {
          if (!alive[a] || !alive[b]) continue;
          const int wins = needed[a] != needed[b]               ? (needed[a] ? 0 : 1)
                           : needed_alone[a] != needed_alone[b] ? (needed_alone[a] ? 0 : 1)
                                                                : -1;
          if (wins < 0) continue;
          const std::uint32_t winner = wins == 0 ? a : b, loser = wins == 0 ? b : a;
          losers.push_back(loser);
          r.diagnostics.push_back(cellforge::detail::cat("candidate ", std::to_string(loser),
                                                         " crosses candidate ", std::to_string(winner),
                                                         ", which an edge needs; dropped"));
        }
        for (const auto i : losers) changed = std::exchange(alive[i], 0) || changed;
      }
      // Pairs no round decides: a search for the certified choice that keeps the fewest.
      std::vector<std::array<std::uint32_t, 2>> open;
      for (const auto& [a, b] : r.crossings)
        if (alive[a] && alive[b]) open.push_back({a, b});
      detail::crossing_decision decision(g, faces, at, alive);
      for (const auto i : decision.run(open, budget))
        r.diagnostics.push_back(cellforge::detail::cat(
            "candidate ", std::to_string(i),
            " crosses a candidate no round decided against; the certified choice drops it"));
      for (auto& n : decision.notes) r.diagnostics.push_back(std::move(n));
    }
  } catch (const error& e) {
    detail::stop_at_budget(r, budget, e);
  }
  if (options.drop_crossing)
    for (std::uint32_t i = 0; i < faces.size(); ++i)
      if (reduction.quality[i].usable && alive[i] != 1) {
        alive[i] = 0;
        r.crossed.push_back(i);
      }
  for (std::uint32_t i = 0; i < faces.size(); ++i)
    if (alive[i]) r.selected.push_back(i);

  // Rank check: more selected faces at an edge than its maximum rank.
  std::vector<std::vector<std::uint32_t>> at_edge(ne);
  for (const auto i : r.selected)
    for (const auto& loop : faces[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k)
        at_edge[g.find_edge(loop[k], loop[(k + 1) % loop.size()])].push_back(i);
  std::vector<char> removed(faces.size(), 0);
  for (std::uint32_t e = 0; e < ne; ++e) {
    if (at_edge[e].size() <= r.edge_rank[e]) continue;
    ++r.rank_violations;
    r.diagnostics.push_back(
        cellforge::detail::cat("edge ", std::to_string(e), " has ", std::to_string(at_edge[e].size()),
                               " faces, more than its maximum rank ", std::to_string(r.edge_rank[e])));
    if (options.enforce_ranks) {
      std::uint32_t largest = at_edge[e][0];
      for (const auto i : at_edge[e])
        if (faces[i].area > faces[largest].area) largest = i;
      removed[largest] = 1;
    }
  }
  if (options.enforce_ranks) std::erase_if(r.selected, [&](std::uint32_t i) { return removed[i] != 0; });
  r.work = budget.used;
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
