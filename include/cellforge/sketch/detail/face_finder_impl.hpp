// SPDX-License-Identifier: MIT
#pragma once
// The engine of the face finder (included by sketch/face_finder.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iterator>
#include <limits>
#include <numbers>
#include <queue>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/work_counter.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/sketch/face_finder.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge {

namespace detail::faces {

inline constexpr std::uint32_t none = ~std::uint32_t{0};

/// The drawing as half-edges: half-edge 2e runs along edge e from its first junction, 2e + 1
/// back; outgoing half-edges of each junction in a CSR table, and a parallel class per edge.
template <class = void>
struct basic_drawing_graph {
  std::vector<glm::dvec2> p;
  std::vector<std::uint32_t> head;  ///< junction a half-edge points to
  std::vector<std::uint32_t> out_begin,
      outs;  ///< outgoing half-edges of junction v: outs[out_begin[v]..out_begin[v+1])
  std::vector<std::uint32_t> edge_class;  ///< parallel class of each edge
  std::uint32_t classes = 0;
  std::vector<std::uint32_t> main_class;  ///< up to three most used classes, if they cover most edges
  double scale = 1.0;                     ///< bounding-box diagonal

  std::uint32_t tail(std::uint32_t h) const { return head[h ^ 1u]; }
  std::uint32_t degree(std::uint32_t v) const { return out_begin[v + 1] - out_begin[v]; }
  std::size_t num_junctions() const { return p.size(); }
  std::size_t num_half_edges() const { return head.size(); }
};
using drawing_graph = basic_drawing_graph<>;

/// The direction class of each of g's first `ne` edges into `cls`: angles mod π sorted, a new
/// class where the gap to the previous exceeds `tol` radians, the last class joined to the
/// first across π; each class's first angle (before that join) into `first_angle` when given.
/// Returns the number of classes (0 without edges). O(E log E).
template <class = void>
std::uint32_t direction_classes(const drawing_graph& g, std::size_t ne, double tol,
                                std::vector<std::uint32_t>& cls, std::vector<double>* first_angle = nullptr) {
  std::vector<std::pair<double, std::uint32_t>> angle(ne);
  for (std::uint32_t e = 0; e < ne; ++e) {
    const glm::dvec2 v = g.p[g.head[2 * e]] - g.p[g.head[2 * e + 1]];
    double a = std::atan2(v.y, v.x);
    if (a < 0) a += std::numbers::pi;
    if (a >= std::numbers::pi) a -= std::numbers::pi;
    angle[e] = {a, e};
  }
  std::sort(angle.begin(), angle.end());
  cls.assign(ne, 0);
  std::uint32_t c = 0;
  for (std::size_t k = 0; k < ne; ++k) {
    if (k > 0 && angle[k].first - angle[k - 1].first > tol) ++c;
    cls[angle[k].second] = c;
    if (first_angle && first_angle->size() <= c) first_angle->push_back(angle[k].first);
  }
  // Wrap around π: the last class joins the first when they are within tolerance.
  if (ne > 1 && angle.front().first + std::numbers::pi - angle.back().first <= tol && c > 0)
    for (auto& k : cls)
      if (k == c) k = 0;
  return ne == 0 ? 0 : c + 1;
}

/// Builds the half-edge view of a drawing and its direction classes. O(V + E log E).
template <LineDrawing D>
drawing_graph make_graph(const D& d, const face_finder_options& o) {
  using T = line_drawing_traits<D>;
  drawing_graph g;
  const std::size_t nv = T::num_junctions(d), ne = T::num_edges(d);
  g.p.reserve(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    const glm::dvec2 q = to_dvec2(drawing_point_t<D>(T::position(d, i)));
    if (!std::isfinite(q.x) || !std::isfinite(q.y))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("find_faces: junction ", std::to_string(i),
                                         " has a NaN or infinite coordinate"));
    g.p.push_back(q);
  }
  if (nv > 0) {
    glm::dvec2 lo = g.p[0], hi = g.p[0];
    for (const auto& q : g.p) lo = glm::min(lo, q), hi = glm::max(hi, q);
    g.scale = std::max(glm::length(hi - lo), 1e-300);
  }
  g.head.resize(2 * ne);
  std::vector<std::uint32_t> deg(nv + 1, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    const auto ab = T::endpoints(d, e);
    if (ab[0] >= nv || ab[1] >= nv)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("find_faces: edge ", std::to_string(e),
                                         " names a junction that does not exist"));
    if (ab[0] == ab[1])
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("find_faces: edge ", std::to_string(e), " joins junction ",
                                         std::to_string(ab[0]), " to itself"));
    g.head[2 * e] = static_cast<std::uint32_t>(ab[1]);
    g.head[2 * e + 1] = static_cast<std::uint32_t>(ab[0]);
    ++deg[ab[0]], ++deg[ab[1]];
  }
  g.out_begin.assign(nv + 1, 0);
  for (std::size_t v = 0; v < nv; ++v) g.out_begin[v + 1] = g.out_begin[v] + deg[v];
  g.outs.resize(2 * ne);
  std::vector<std::uint32_t> fill(g.out_begin.begin(), g.out_begin.end() - 1);
  for (std::uint32_t h = 0; h < 2 * ne; ++h) g.outs[fill[g.tail(h)]++] = h;
  // Direction classes: angles mod π sorted, a new class where the gap exceeds the tolerance.
  g.classes = direction_classes(g, ne, o.parallel_tolerance_degrees * std::numbers::pi / 180.0, g.edge_class);
  // Main directions: the three largest classes, when they hold at least 60 % of the edges.
  std::vector<std::pair<std::size_t, std::uint32_t>> count(g.classes);
  for (std::uint32_t k = 0; k < g.classes; ++k) count[k] = {0, k};
  for (const auto k : g.edge_class) ++count[k].first;
  std::sort(count.begin(), count.end(),
            [](auto a, auto b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
  std::size_t top = 0;
  for (std::size_t k = 0; k < std::min<std::size_t>(3, count.size()); ++k) top += count[k].first;
  if (count.size() >= 3 && 10 * top >= 6 * ne && count[2].first >= 2)
    for (std::size_t k = 0; k < 3; ++k) g.main_class.push_back(count[k].second);
  return g;
}

/// Orientation of c about the line ab (> 0 left). O(1).
template <class = void>
double orient(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// The string state: successor and predecessor of every half-edge (none: an open end or start).
/// A string is a maximal chain; a closed chain is a face loop.
struct string_state {
  std::vector<std::uint32_t> next, prev;
};

/// The finder: a drawing graph, the master state, scratch marks, and the budget.
template <class = void>
struct basic_finder {
  const drawing_graph& g;
  const face_finder_options& o;
  work_counter& budget;
  std::vector<std::uint32_t> mark;  // per junction: stamp of the string being tested
  std::uint32_t stamp = 0;
  std::vector<std::uint32_t> component, component_size;  // connected components of junctions
  std::size_t forced = 0, voluntary = 0, hypotheses = 0, rejected = 0;

  basic_finder(const drawing_graph& graph, const face_finder_options& options, work_counter& b)
      : g(graph),
        o(options),
        budget(b),
        mark(graph.num_junctions(), 0),
        component(graph.num_junctions(), none) {
    for (std::uint32_t v = 0; v < g.num_junctions(); ++v) {
      if (component[v] != none) continue;
      const auto c = static_cast<std::uint32_t>(component_size.size());
      std::vector<std::uint32_t> stack{v};
      component[v] = c;
      std::uint32_t n = 0;
      while (!stack.empty()) {
        const std::uint32_t u = stack.back();
        stack.pop_back();
        ++n;
        for (std::uint32_t i = g.out_begin[u]; i < g.out_begin[u + 1]; ++i) {
          const std::uint32_t w = g.head[g.outs[i]];
          if (component[w] == none) component[w] = c, stack.push_back(w);
        }
      }
      component_size.push_back(n);
    }
  }

  /// Whether taking the loop's junctions out splits their component. O(V + E) of the component.
  bool separating(const std::vector<std::uint32_t>& loop_vertices) {
    const std::uint32_t st = next_stamp(), c = component[loop_vertices[0]];
    for (const auto v : loop_vertices) mark[v] = st;
    const std::uint32_t rest = component_size[c] - static_cast<std::uint32_t>(loop_vertices.size());
    if (rest == 0) return false;
    std::uint32_t seed = none;
    for (const auto v : loop_vertices)
      for (std::uint32_t i = g.out_begin[v]; i < g.out_begin[v + 1] && seed == none; ++i)
        if (mark[g.head[g.outs[i]]] != st) seed = g.head[g.outs[i]];
    if (seed == none) return true;  // every neighbour on the loop: the rest hangs elsewhere
    std::vector<std::uint32_t> stack{seed};
    mark[seed] = st;
    std::uint32_t reached = 0;
    while (!stack.empty()) {
      const std::uint32_t u = stack.back();
      stack.pop_back();
      ++reached;
      for (std::uint32_t i = g.out_begin[u]; i < g.out_begin[u + 1]; ++i) {
        budget.spend();
        const std::uint32_t w = g.head[g.outs[i]];
        if (mark[w] != st) mark[w] = st, stack.push_back(w);
      }
    }
    return reached < rest;
  }

  std::uint32_t first_of(const string_state& s, std::uint32_t h) const {
    std::uint32_t f = h;
    while (s.prev[f] != none && s.prev[f] != h) f = s.prev[f];
    return f;
  }
  std::uint32_t last_of(const string_state& s, std::uint32_t h) const {
    std::uint32_t l = h;
    while (s.next[l] != none && s.next[l] != h) l = s.next[l];
    return l;
  }
  std::uint32_t next_stamp() {
    if (++stamp == 0) std::fill(mark.begin(), mark.end(), 0), stamp = 1;
    return stamp;
  }

  /// Whether a turn a→b→c may join: the seed's second rule, where b has a choice.
  bool turn_allowed(const string_state& s, std::uint32_t h1, std::uint32_t h2) const {
    if (h2 == (h1 ^ 1u)) return false;
    // The reversed triple c→b→a already concatenated: two loops would share a corner path.
    return !(g.degree(g.head[h1]) >= 3 && s.next[h2 ^ 1u] == (h1 ^ 1u));
  }

  /// Whether the closed chain through h (in s, or about to be) is a face loop: a simple polygon
  /// (guaranteed by the joins) with no edge of the drawing across its inside. O(L·deg + L·chords).
  bool closed_loop_ok(const std::vector<std::uint32_t>& loop_vertices) {
    const std::size_t n = loop_vertices.size();
    if (n < 3) return false;
    const std::uint32_t st = next_stamp();
    for (const auto v : loop_vertices) mark[v] = st;
    std::vector<glm::dvec2> poly;
    poly.reserve(n);
    for (const auto v : loop_vertices) poly.push_back(g.p[v]);
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t v = loop_vertices[k];
      const std::uint32_t before = loop_vertices[(k + n - 1) % n], after = loop_vertices[(k + 1) % n];
      for (std::uint32_t i = g.out_begin[v]; i < g.out_begin[v + 1]; ++i) {
        const std::uint32_t w = g.head[g.outs[i]];
        if (w < v || mark[w] != st || w == before || w == after) continue;
        budget.spend();
        // A chord: an edge between two loop junctions. Inside the polygon it splits the face.
        const glm::dvec2 mid = 0.5 * (g.p[v] + g.p[w]);
        if (cellforge::detail::point_in_polygon(poly, mid)) return false;
      }
    }
    return true;
  }

  /// Vertices of the chain from first half-edge f to last l (its tail then every head).
  void chain_vertices(const string_state& s, std::uint32_t f, std::uint32_t l,
                      std::vector<std::uint32_t>& out) const {
    out.push_back(g.tail(f));
    for (std::uint32_t h = f;; h = s.next[h]) {
      out.push_back(g.head[h]);
      if (h == l) break;
    }
  }

  /// Whether the chain f..l of s (as segments) crosses the chain f2..l2. O(|a|·|b|).
  bool chains_cross(const string_state& s, std::uint32_t f, std::uint32_t l, std::uint32_t f2,
                    std::uint32_t l2) {
    for (std::uint32_t a = f;; a = s.next[a]) {
      const glm::dvec2 pa = g.p[g.tail(a)], pb = g.p[g.head[a]];
      for (std::uint32_t b = f2;; b = s.next[b]) {
        budget.spend();
        const std::uint32_t ta = g.tail(a), ha = g.head[a], tb = g.tail(b), hb = g.head[b];
        const glm::dvec2 pc = g.p[tb], pd = g.p[hb];
        // Segments sharing a junction meet there; they must not overlap otherwise.
        const bool share = ta == tb || ta == hb || ha == tb || ha == hb;
        if (!share && cellforge::detail::segments_meet(pa, pb, pc, pd)) return true;  // exact
        if (share) {
          // Shared end: collinear overlap is a crossing too.
          const std::uint32_t shared = (ta == tb || ta == hb) ? ta : ha;
          const std::uint32_t oa = shared == ta ? ha : ta, ob = shared == tb ? hb : tb;
          if (oa != ob && orient(g.p[shared], g.p[oa], g.p[ob]) == 0 &&
              glm::dot(g.p[oa] - g.p[shared], g.p[ob] - g.p[shared]) > 0)
            return true;
        }
        if (b == l2) break;
      }
      if (a == l) break;
    }
    return false;
  }

  /// Can the string ending with h1 continue with the string starting with h2? 0: no, 1: yes
  /// (a longer open string), 2: yes and it closes a face loop that passes closed_loop_ok.
  int can_join(const string_state& s, std::uint32_t h1, std::uint32_t h2) {
    budget.spend();
    if (s.next[h1] != none || s.prev[h2] != none || !turn_allowed(s, h1, h2)) return 0;
    const std::uint32_t f1 = first_of(s, h1);
    if (f1 == h2) {  // closing the string on itself: a cyclisation
      std::vector<std::uint32_t> loop;
      chain_vertices(s, f1, h1, loop);
      loop.pop_back();
      return closed_loop_ok(loop) ? 2 : 0;
    }
    const std::uint32_t l2 = last_of(s, h2);
    const std::uint32_t start = g.tail(f1), end = g.head[l2];
    const bool closes = end == start;
    if (closes && !turn_allowed(s, l2, f1)) return 0;
    // First rule: no junction but the joining one (and the start, when closing) in both strings.
    const std::uint32_t st = next_stamp();
    for (std::uint32_t h = f1;; h = s.next[h]) {
      mark[g.tail(h)] = st;
      if (h == h1) break;
    }
    for (std::uint32_t h = h2;; h = s.next[h]) {
      const std::uint32_t v = g.head[h];
      if (mark[v] == st && !(closes && h == l2)) return 0;
      if (h == l2) break;
    }
    if (chains_cross(s, f1, h1, h2, l2)) return 0;
    if (!closes) return 1;
    std::vector<std::uint32_t> loop;
    chain_vertices(s, f1, h1, loop);
    loop.pop_back();
    chain_vertices(s, h2, l2, loop);
    loop.pop_back();
    return closed_loop_ok(loop) ? 2 : 0;
  }

  static void join(string_state& s, std::uint32_t h1, std::uint32_t h2, const basic_finder& f) {
    s.next[h1] = h2;
    s.prev[h2] = h1;
    const std::uint32_t l2 = f.last_of(s, h2), f1 = f.first_of(s, h1);
    if (l2 != h1 && f1 != h2 && f.g.head[l2] == f.g.tail(f1) && s.next[l2] == none) {  // double concatenation
      s.next[l2] = f1;
      s.prev[f1] = l2;
    }
  }

  /// Performs every forced concatenation reachable from the junctions in `work`. Returns false
  /// on a dead end (an open end or start with no candidate left). O(joins tried).
  bool propagate(string_state& s, std::vector<std::uint32_t> work, std::size_t* count) {
    std::vector<char> queued(g.num_junctions(), 0);
    for (const auto v : work) queued[v] = 1;
    while (!work.empty()) {
      const std::uint32_t v = work.back();
      work.pop_back();
      queued[v] = 0;
      bool changed = true;
      while (changed) {
        changed = false;
        for (std::uint32_t i = g.out_begin[v]; i < g.out_begin[v + 1] && !changed; ++i) {
          const std::uint32_t in = g.outs[i] ^ 1u;  // a half-edge into v
          if (s.next[in] != none) continue;
          std::uint32_t only = none, n = 0;
          for (std::uint32_t j = g.out_begin[v]; j < g.out_begin[v + 1] && n < 2; ++j)
            if (can_join(s, in, g.outs[j]) != 0) only = g.outs[j], ++n;
          if (n == 0) return false;
          if (n == 1) {
            join(s, in, only, *this), changed = true;
            if (count) ++*count;
            wake(s, in, work, queued);
          }
        }
        for (std::uint32_t i = g.out_begin[v]; i < g.out_begin[v + 1] && !changed; ++i) {
          const std::uint32_t out = g.outs[i];
          if (s.prev[out] != none) continue;
          std::uint32_t only = none, n = 0;
          for (std::uint32_t j = g.out_begin[v]; j < g.out_begin[v + 1] && n < 2; ++j)
            if (can_join(s, g.outs[j] ^ 1u, out) != 0) only = g.outs[j] ^ 1u, ++n;
          if (n == 0) return false;
          if (n == 1) {
            join(s, only, out, *this), changed = true;
            if (count) ++*count;
            wake(s, only, work, queued);
          }
        }
      }
    }
    return true;
  }

  /// After a join at h's head: the string's two ends have new contents, so their junctions'
  /// candidates may have changed.
  void wake(const string_state& s, std::uint32_t h, std::vector<std::uint32_t>& work,
            std::vector<char>& queued) const {
    const std::uint32_t f = first_of(s, h), l = last_of(s, h);
    for (const std::uint32_t v : {g.tail(f), g.head[l], g.head[h]})
      if (!queued[v]) queued[v] = 1, work.push_back(v);
  }

  /// Commits a loop given as half-edges in order (h0 → h1 → …) to s. O(L).
  static void close_loop(string_state& s, const std::vector<std::uint32_t>& hs) {
    for (std::size_t k = 0; k < hs.size(); ++k) {
      const std::uint32_t a = hs[k], b = hs[(k + 1) % hs.size()];
      s.next[a] = b;
      s.prev[b] = a;
    }
  }

  /// Look-ahead: the consequences of closing loop hs on a copy of s reach no dead end. O(E + joins).
  bool consistent(const string_state& s, const std::vector<std::uint32_t>& hs) {
    if (!o.look_ahead) return true;
    string_state copy = s;
    close_loop(copy, hs);
    std::vector<std::uint32_t> work;
    for (const auto h : hs) work.push_back(g.head[h]);
    return propagate(copy, std::move(work), nullptr);
  }

  /// Half-edges of the loop closed by joining open string end h1 to string start h2.
  std::vector<std::uint32_t> loop_half_edges(const string_state& s, std::uint32_t h1,
                                             std::uint32_t h2) const {
    std::vector<std::uint32_t> hs;
    for (std::uint32_t h = first_of(s, h1);; h = s.next[h]) {
      hs.push_back(h);
      if (h == h1) break;
    }
    if (first_of(s, h1) != h2)
      for (std::uint32_t h = h2;; h = s.next[h]) {
        hs.push_back(h);
        if (s.next[h] == none) break;
      }
    return hs;
  }

  /// Mating value of the loop so far: edges, plus a cost per reflex turn and per edge in a
  /// third main direction. The turn sense is the first non-straight turn's.
  struct mating {
    double cost = 0;
    int sense = 0;                 // +1 left, -1 right, 0 not yet known
    std::uint32_t main_used = 0;   // bit k: main direction k used
    std::uint32_t main_count = 0;  // distinct main directions used
  };
  void extend_mating(mating& m, std::uint32_t h_prev, std::uint32_t h) const {
    m.cost += 1.0;
    if (h_prev != none) {
      const glm::dvec2 a = g.p[g.tail(h_prev)], b = g.p[g.head[h_prev]], c = g.p[g.head[h]];
      const double t = orient(a, b, c);
      const double len = glm::length(b - a) * glm::length(c - b);
      if (std::abs(t) > 1e-12 * len) {
        const int sg = t > 0 ? 1 : -1;
        if (m.sense == 0)
          m.sense = sg;
        else if (sg != m.sense)
          m.cost += o.reflex_turn_cost;
      }
    }
    const std::uint32_t c = g.edge_class[h >> 1];
    for (std::size_t k = 0; k < g.main_class.size(); ++k)
      if (g.main_class[k] == c && !(m.main_used & (1u << k))) {
        m.main_used |= 1u << k;
        if (++m.main_count == 3) m.cost += o.third_direction_cost;
      }
  }

  /// The working list: several seeds grown at once (the open strings ending with the given
  /// half-edges, each with a starting cost: its priority), by whole strings, cheapest mating
  /// value first, so that the smallest face closes first. Every loop found is checked by
  /// look-ahead; returns the first that passes (empty: none). O(expansions · L).
  std::vector<std::uint32_t> hypothesis(const string_state& s,
                                        const std::vector<std::pair<std::uint32_t, double>>& seeds,
                                        std::size_t max_expansions) {
    struct node {
      double cost;
      std::uint32_t parent;  // index into nodes; none: a seed
      std::uint32_t first;   // first half-edge of the string this node appended (a seed: its index)
      std::uint32_t last;    // last half-edge of the loop so far
      mating m;
      bool closed;
      bool judged = false;  // the separation cost is added when a closed loop is first popped
    };
    std::vector<node> nodes;
    using item = std::pair<double, std::uint32_t>;
    std::priority_queue<item, std::vector<item>, std::greater<>> open;
    for (std::uint32_t k = 0; k < seeds.size(); ++k) {
      const std::uint32_t h1 = seeds[k].first;
      mating m0;
      m0.cost = seeds[k].second;
      for (std::uint32_t h = first_of(s, h1), p = none;; p = h, h = s.next[h]) {
        extend_mating(m0, p, h);
        if (h == h1) break;
      }
      nodes.push_back({m0.cost, none, k, h1, m0, false});
      open.push({m0.cost, static_cast<std::uint32_t>(nodes.size() - 1)});
    }
    // A scratch state holding the partial loop's joins, so that can_join sees the context.
    string_state scratch = s;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> applied;
    const auto undo = [&] {
      for (auto it = applied.rbegin(); it != applied.rend(); ++it)
        scratch.next[it->first] = none, scratch.prev[it->second] = none;
      applied.clear();
    };
    std::size_t expansions = 0;
    std::vector<std::uint32_t> chain;
    while (!open.empty() && expansions < max_expansions) {
      const auto [cost, id] = open.top();
      open.pop();
      ++expansions;
      // Re-create the partial in scratch: undo the previous, apply this node's joins.
      undo();
      chain.clear();
      std::uint32_t root = id;
      for (; nodes[root].parent != none; root = nodes[root].parent) chain.push_back(root);
      const std::uint32_t h1 = seeds[nodes[root].first].first, f1 = first_of(s, h1);
      std::uint32_t end = h1;
      for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        scratch.next[end] = nodes[*it].first;
        scratch.prev[nodes[*it].first] = end;
        applied.push_back({end, nodes[*it].first});
        end = nodes[*it].last;
      }
      if (nodes[id].closed) {
        // The loop: seed chain then every appended string.
        std::vector<std::uint32_t> hs;
        for (std::uint32_t h = f1;; h = scratch.next[h]) {
          hs.push_back(h);
          if (scratch.next[h] == none || scratch.next[h] == f1) break;
        }
        undo();
        if (!nodes[id].judged) {
          nodes[id].judged = true;
          std::vector<std::uint32_t> vs;
          for (const auto h : hs) vs.push_back(g.tail(h));
          if (o.separating_loop_cost > 0 && separating(vs)) {
            nodes[id].cost += o.separating_loop_cost;
            open.push({nodes[id].cost, id});
            continue;
          }
        }
        if (consistent(s, hs)) return hs;
        ++rejected;
        continue;
      }
      const std::uint32_t v = g.head[end];
      for (std::uint32_t j = g.out_begin[v]; j < g.out_begin[v + 1]; ++j) {
        const std::uint32_t h2 = g.outs[j];
        const int r = can_join(scratch, end, h2);
        if (r == 0) continue;
        mating m = nodes[id].m;
        std::uint32_t last = end;
        if (h2 != f1) {  // a whole string appended (h2 == f1: the loop closes on the seed itself)
          std::uint32_t prev = end;
          for (std::uint32_t h = h2;; h = scratch.next[h]) {
            extend_mating(m, prev, h);
            prev = h, last = h;
            if (scratch.next[h] == none) break;
          }
        }
        if (r == 2) extend_mating(m, last, f1), m.cost -= 1.0;  // the closing turn, no new edge
        nodes.push_back({m.cost, id, h2, last, m, r == 2});
        open.push({m.cost, static_cast<std::uint32_t>(nodes.size() - 1)});
      }
    }
    undo();
    return {};
  }
};
using finder = basic_finder<>;

/// Faces beyond two per edge (walls, solids touching along an edge): what any set of face loops
/// of a generic parallel view obeys, however many faces an edge has, and the state the search
/// for the loops still needed keeps. Two faces sharing an edge are *coplanar* when each has an
/// edge along one more drawing direction (lines parallel in the drawing are parallel in space:
/// both planes hold the edge and that direction); coplanar faces at an edge lie on its two
/// sides (else they overlap), and an edge on just two coplanar faces is a seam that a wall must
/// meet. No two faces turn the same corner (the same two lines at a junction); an edge between
/// junctions of degrees p and q lies on at most min(p, q) − 1 faces.
template <class = void>
struct basic_face_rules {
  const drawing_graph& g;
  std::vector<std::uint32_t> strict_class;  ///< per edge: exact direction class
  std::vector<double> class_angle;          ///< per class: its direction's angle in [0, π)
  std::vector<std::uint32_t> capacity;      ///< per edge: most faces it can carry
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<std::vector<std::uint32_t>> classes;  ///< per loop: its exact direction classes, sorted
  std::vector<double> area;                         ///< per loop: signed area in the drawing
  std::vector<std::vector<std::uint32_t>> on_edge;  ///< per edge: loops on it
  std::vector<std::vector<std::array<std::uint32_t, 2>>> corners;  ///< per junction: edge pairs turned
  std::vector<std::vector<std::uint32_t>> at_junction;  ///< per junction: exact classes of its lines, sorted

  basic_face_rules(const drawing_graph& graph, double tolerance_degrees)
      : g(graph), on_edge(graph.num_half_edges() / 2), corners(graph.num_junctions()) {
    const std::size_t ne = g.num_half_edges() / 2;
    (void)direction_classes(g, ne, tolerance_degrees * std::numbers::pi / 180.0, strict_class, &class_angle);
    // Capacity from the junctions where the chain of e through degree-2 junctions (a split edge:
    // every face of one piece is a face of the others) ends.
    capacity.resize(ne);
    for (std::uint32_t e = 0; e < ne; ++e) {
      std::uint32_t most = std::numeric_limits<std::uint32_t>::max();
      for (std::uint32_t h : {2 * e, 2 * e + 1}) {
        for (std::size_t steps = 0; g.degree(g.head[h]) == 2 && steps < ne; ++steps) {
          const std::uint32_t v = g.head[h], a = g.outs[g.out_begin[v]], b = g.outs[g.out_begin[v] + 1];
          h = (a >> 1) == (h >> 1) ? b : a;
        }
        if (g.degree(g.head[h]) != 2) most = std::min(most, g.degree(g.head[h]) - 1);
      }
      capacity[e] = std::max<std::uint32_t>(most == std::numeric_limits<std::uint32_t>::max() ? 2 : most, 2);
    }
    at_junction.resize(g.num_junctions());
    for (std::uint32_t v = 0; v < g.num_junctions(); ++v) {
      auto& cs = at_junction[v];
      for (std::uint32_t i = g.out_begin[v]; i < g.out_begin[v + 1]; ++i)
        cs.push_back(strict_class[g.outs[i] >> 1]);
      std::sort(cs.begin(), cs.end());
      cs.erase(std::unique(cs.begin(), cs.end()), cs.end());
    }
  }

  std::uint32_t edge_between(std::uint32_t a, std::uint32_t b) const {
    for (std::uint32_t i = g.out_begin[a]; i < g.out_begin[a + 1]; ++i)
      if (g.head[g.outs[i]] == b) return g.outs[i] >> 1;
    return none;
  }
  static std::array<std::uint32_t, 2> pair(std::uint32_t a, std::uint32_t b) {
    return {std::min(a, b), std::max(a, b)};
  }
  bool corner_used(std::uint32_t v, std::uint32_t e1, std::uint32_t e2) const {
    if (g.degree(v) == 2) return false;  // a split edge: its faces all go straight on here
    const auto c = pair(e1, e2);
    return std::find(corners[v].begin(), corners[v].end(), c) != corners[v].end();
  }
  std::vector<std::uint32_t> classes_of(const std::vector<std::uint32_t>& loop) const {
    std::vector<std::uint32_t> cs;
    for (std::size_t k = 0; k < loop.size(); ++k)
      cs.push_back(strict_class[edge_between(loop[k], loop[(k + 1) % loop.size()])]);
    std::sort(cs.begin(), cs.end());
    cs.erase(std::unique(cs.begin(), cs.end()), cs.end());
    return cs;
  }
  /// Whether class c's direction is plainly not e's (half a degree: a direction along e, split
  /// from e's class by rounding, adds nothing to a plane through e).
  bool across(std::uint32_t c, std::uint32_t e) const {
    const double d = std::abs(class_angle[c] - class_angle[strict_class[e]]);
    return std::min(d, std::numbers::pi - d) > std::numbers::pi / 360.0;
  }
  /// Whether loops with classes a and b, sharing edge e, are coplanar (a direction besides e's in both).
  bool coplanar(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b,
                std::uint32_t e) const {
    for (const auto c : a)
      if (across(c, e) && std::binary_search(b.begin(), b.end(), c)) return true;
    return false;
  }
  /// The side of edge e (+1 left of its half-edge 2e, −1 right) a loop of signed area `area`
  /// covers, the loop running from junction `from` to `to` along e.
  int side(double loop_area, std::uint32_t e, std::uint32_t from) const {
    const bool forward = g.head[2 * e + 1] == from;
    return (loop_area > 0) == forward ? 1 : -1;
  }
  static double signed_area(const std::vector<glm::dvec2>& p, const std::vector<std::uint32_t>& loop) {
    double a = 0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const glm::dvec2 u = p[loop[k]], v = p[loop[(k + 1) % loop.size()]];
      a += u.x * v.y - u.y * v.x;
    }
    return 0.5 * a;
  }
  /// Whether a line from a loop junction into the loop's inside runs along one of the loop's
  /// directions: it then lies in the face's plane and enters the face, so the loop is no face
  /// (the chord rule for lines that end off the loop). O(L · degree).
  bool entered(const std::vector<std::uint32_t>& loop, const std::vector<std::uint32_t>& cs,
               double ar) const {
    const std::size_t n = loop.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t v = loop[k], before = loop[(k + n - 1) % n], after = loop[(k + 1) % n];
      // The inside at v: counter-clockwise from the line to `after` to the line to `before` when
      // the loop runs counter-clockwise, the other way round otherwise.
      const glm::dvec2 to_after = g.p[after] - g.p[v], to_before = g.p[before] - g.p[v];
      const glm::dvec2 from = ar > 0 ? to_after : to_before, to = ar > 0 ? to_before : to_after;
      const auto sweep = [&](glm::dvec2 d) {  // angle counter-clockwise from `from` to d, in [0, 2π)
        double t = std::atan2(from.x * d.y - from.y * d.x, glm::dot(from, d));
        return t < 0 ? t + 2 * std::numbers::pi : t;
      };
      const double wedge = sweep(to);
      for (std::uint32_t i = g.out_begin[v]; i < g.out_begin[v + 1]; ++i) {
        const std::uint32_t w = g.head[g.outs[i]];
        if (w == before || w == after ||
            !std::binary_search(cs.begin(), cs.end(), strict_class[g.outs[i] >> 1]))
          continue;
        const double t = sweep(g.p[w] - g.p[v]);
        if (t > 1e-9 && t < wedge - 1e-9) return true;
      }
    }
    return false;
  }
  /// Why a new loop breaks the rules against the loops kept (empty: it does not). O(L · faces per edge).
  const char* conflict(const std::vector<std::uint32_t>& loop) const {
    const auto cs = classes_of(loop);
    const double ar = signed_area(g.p, loop);
    const std::size_t n = loop.size();
    if (entered(loop, cs, ar)) return "a line in its plane enters it";
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t a = loop[k], b = loop[(k + 1) % n], c = loop[(k + 2) % n];
      const std::uint32_t e = edge_between(a, b), f = edge_between(b, c);
      if (corner_used(b, e, f)) return "turns a corner another face turns";
      if (on_edge[e].size() + 1 > capacity[e]) return "more faces at an edge than its junctions hold";
      for (const auto l : on_edge[e])
        if (coplanar(cs, classes[l], e) && side(ar, e, a) == side(area[l], e, from_of(l, e)))
          return "overlaps a coplanar face";
    }
    return nullptr;
  }
  /// The junction loop l leaves along edge e from (its traversal's tail of e).
  std::uint32_t from_of(std::uint32_t l, std::uint32_t e) const {
    const auto& loop = loops[l];
    for (std::size_t k = 0; k < loop.size(); ++k)
      if (edge_between(loop[k], loop[(k + 1) % loop.size()]) == e) return loop[k];
    return none;
  }
  void add(std::vector<std::uint32_t> loop) {
    const auto l = static_cast<std::uint32_t>(loops.size());
    const std::size_t n = loop.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t a = loop[k], b = loop[(k + 1) % n], c = loop[(k + 2) % n];
      const std::uint32_t e = edge_between(a, b), f = edge_between(b, c);
      on_edge[e].push_back(l);
      corners[b].push_back(pair(e, f));
    }
    classes.push_back(classes_of(loop));
    area.push_back(signed_area(g.p, loop));
    loops.push_back(std::move(loop));
  }
  /// Whether loops l1 and l2 at edge e are the ends of prisms along one direction s (a line of
  /// class s at each of their junctions, s in neither loop nor e's): read as right prisms, both
  /// are perpendicular to s and so coplanar. A reading prior, not a fact of the drawing (a roof's
  /// gable and the wall under it); docs/sketch.md, "Walls and contacts". O(L · degree).
  bool prism_ends(std::uint32_t l1, std::uint32_t l2, std::uint32_t e) const {
    std::vector<std::uint32_t> common = at_junction[loops[l1][0]], next;
    for (const std::uint32_t l : {l1, l2})
      for (const auto v : loops[l]) {
        next.clear();
        std::set_intersection(common.begin(), common.end(), at_junction[v].begin(), at_junction[v].end(),
                              std::back_inserter(next));
        common.swap(next);
        if (common.empty()) return false;
      }
    for (const auto c : common)
      if (across(c, e) && !std::binary_search(classes[l1].begin(), classes[l1].end(), c) &&
          !std::binary_search(classes[l2].begin(), classes[l2].end(), c))
        return true;
    return false;
  }
  /// Whether edge e, on just two loops, is a seam: they are coplanar (or prism ends along one line).
  bool seam(std::uint32_t e) const {
    if (on_edge[e].size() != 2) return false;
    const auto l1 = on_edge[e][0], l2 = on_edge[e][1];
    return coplanar(classes[l1], classes[l2], e) || prism_ends(l1, l2, e);
  }
  /// Whether edge e needs another face: fewer than two, or just two coplanar ones (a seam).
  bool needy(std::uint32_t e) const { return on_edge[e].size() < 2 || seam(e); }
  /// Whether loop l is needed: without it, one of its edges would need another face.
  bool needed(std::uint32_t l) const {
    const auto& loop = loops[l];
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const std::uint32_t e = edge_between(loop[k], loop[(k + 1) % loop.size()]);
      if (on_edge[e].size() <= 2) return true;
      if (on_edge[e].size() == 3) {
        std::array<std::uint32_t, 2> rest{};
        std::size_t n = 0;
        for (const auto x : on_edge[e])
          if (x != l) rest[n++] = x;
        if (coplanar(classes[rest[0]], classes[rest[1]], e) || prism_ends(rest[0], rest[1], e)) return true;
      }
    }
    return false;
  }
  /// Whether loop l, taken out, would leave one of its edges on three faces or more.
  bool grid_wall(std::uint32_t l) const {
    const auto& loop = loops[l];
    for (std::size_t k = 0; k < loop.size(); ++k)
      if (on_edge[edge_between(loop[k], loop[(k + 1) % loop.size()])].size() > 3) return true;
    return false;
  }
  /// Takes loop l out (the last index moves into its place). O(L · faces per edge).
  void remove(std::uint32_t l) {
    const auto drop = [&](std::uint32_t x) {
      const auto& loop = loops[x];
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const std::uint32_t a = loop[k], b = loop[(k + 1) % loop.size()], c = loop[(k + 2) % loop.size()];
        const std::uint32_t e = edge_between(a, b), f = edge_between(b, c);
        on_edge[e].erase(std::find(on_edge[e].begin(), on_edge[e].end(), x));
        corners[b].erase(std::find(corners[b].begin(), corners[b].end(), pair(e, f)));
      }
    };
    drop(l);
    const auto last = static_cast<std::uint32_t>(loops.size() - 1);
    if (l != last) {
      for (auto& on : on_edge)
        for (auto& x : on)
          if (x == last) x = l;
      loops[l] = std::move(loops[last]);
      classes[l] = std::move(classes[last]);
      area[l] = area[last];
    }
    loops.pop_back(), classes.pop_back(), area.pop_back();
  }
};
using face_rules = basic_face_rules<>;

/// The cheapest loop through edge e that the rules allow beside the loops kept: best-first over
/// simple paths from e's head back to its tail, by the mating value (edges, reflex turns, a third
/// main direction), each step turning an unused corner and crossing no line of the path, the
/// closed loop without a chord inside. Empty when none within `max_expansions`. O(expansions · L).
template <class = void>
std::vector<std::uint32_t> wall_through(finder& f, const face_rules& rules, std::uint32_t e,
                                        std::size_t max_expansions) {
  const drawing_graph& g = f.g;
  struct node {
    double cost;
    std::uint32_t parent, h, depth;
    finder::mating m;
  };
  std::vector<node> nodes;
  using item = std::pair<double, std::uint32_t>;
  std::priority_queue<item, std::vector<item>, std::greater<>> open;
  const std::uint32_t h0 = 2 * e, a = g.tail(h0);
  finder::mating m0;
  f.extend_mating(m0, none, h0);
  nodes.push_back({m0.cost, none, h0, 1, m0});
  open.push({m0.cost, 0});
  std::vector<std::uint32_t> path;
  for (std::size_t expansions = 0; !open.empty() && expansions < max_expansions; ++expansions) {
    const std::uint32_t id = open.top().second;
    open.pop();
    path.clear();
    for (std::uint32_t k = id; k != none; k = nodes[k].parent) path.push_back(nodes[k].h);
    std::reverse(path.begin(), path.end());
    const std::uint32_t last = path.back(), v = g.head[last];
    for (std::uint32_t j = g.out_begin[v]; j < g.out_begin[v + 1]; ++j) {
      const std::uint32_t h = g.outs[j], w = g.head[h], eh = h >> 1;
      f.budget.spend();
      if (eh == (last >> 1) || eh == e || rules.corner_used(v, last >> 1, eh)) continue;
      if (rules.on_edge[eh].size() + 1 > rules.capacity[eh]) continue;
      bool repeat = false;
      for (const auto p : path) repeat = repeat || (g.tail(p) == w && w != a);
      if (repeat) continue;
      // The new line crosses no line of the path (shared junctions aside), nor folds back on one.
      bool crosses = false;
      for (std::size_t k = 0; k + 1 < path.size() && !crosses; ++k) {
        const std::uint32_t p = path[k];
        const std::uint32_t pa = g.tail(p), pb = g.head[p];
        if (pa == w || pb == w) {
          const std::uint32_t shared = w, other = pa == w ? pb : pa;
          crosses = orient(g.p[shared], g.p[other], g.p[v]) == 0 &&
                    glm::dot(g.p[other] - g.p[shared], g.p[v] - g.p[shared]) > 0;
          continue;
        }
        crosses = segments_meet(g.p[pa], g.p[pb], g.p[v], g.p[w]);
      }
      if (crosses) continue;
      finder::mating m = nodes[id].m;
      f.extend_mating(m, last, h);
      if (w == a) {
        if (rules.corner_used(a, eh, e) || path.size() < 2) continue;
        std::vector<std::uint32_t> loop;
        for (const auto p : path) loop.push_back(g.tail(p));
        loop.push_back(v);
        if (!f.closed_loop_ok(loop) || rules.conflict(loop) != nullptr) continue;
        return loop;  // the cheapest closing step of the cheapest path: good enough, first found
      }
      nodes.push_back({m.cost, id, h, nodes[id].depth + 1, m});
      open.push({m.cost, static_cast<std::uint32_t>(nodes.size() - 1)});
    }
  }
  return {};
}

/// Completes an answer with the loops its edges still need (walls, contacts): rounds in which
/// every needy edge offers its cheapest allowed loop and the offers are taken cheapest first
/// while they still fit; then the loops no edge needs go. Returns the loops added and dropped.
/// O(rounds · needy edges · search).
template <class = void>
std::array<std::size_t, 2> complete_walls(finder& f, face_rules& rules, std::size_t max_expansions) {
  const std::size_t ne = f.g.num_half_edges() / 2;
  std::size_t added = 0, unneeded = 0;
  for (bool progress = true; progress;) {
    progress = false;
    std::vector<std::pair<std::pair<std::size_t, double>, std::vector<std::uint32_t>>> offers;
    for (std::uint32_t e = 0; e < ne; ++e) {
      if (!rules.needy(e)) continue;
      auto loop = wall_through(f, rules, e, max_expansions);
      if (loop.empty()) continue;
      offers.push_back({{loop.size(), 0.0}, std::move(loop)});
    }
    std::stable_sort(offers.begin(), offers.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    for (auto& [cost, loop] : offers) {
      (void)cost;
      bool needed = false;
      for (std::size_t k = 0; k < loop.size(); ++k)
        needed = needed || rules.needy(rules.edge_between(loop[k], loop[(k + 1) % loop.size()]));
      if (!needed || rules.conflict(loop) != nullptr) continue;
      rules.add(std::move(loop));
      ++added;
      progress = true;
    }
  }
  // A face exists only where an edge needs it (the reading rule's first clause, in the drawing):
  // loops no edge needs go, the longest first, where every edge keeps just two faces (a hole's
  // mouth taken for a wall). A loop no edge needs whose edge keeps three faces or more is a wall
  // inside a grid, which the drawing cannot decide: it stays, counted in `unforced`.
  for (bool dropped = true; dropped;) {
    dropped = false;
    std::uint32_t worst = none;
    for (std::uint32_t l = 0; l < rules.loops.size(); ++l) {
      if (rules.needed(l) || rules.grid_wall(l)) continue;
      if (worst == none || rules.loops[l].size() > rules.loops[worst].size()) worst = l;
    }
    if (worst != none) rules.remove(worst), dropped = true, ++unneeded;
  }
  return {added, unneeded};
}

/// Loops as a sorted list of canonical cycles, for comparing answers. O(Σ L log L).
template <class = void>
std::vector<std::vector<std::uint32_t>> canonical_set(const std::vector<std::vector<std::uint32_t>>& loops) {
  std::vector<std::vector<std::uint32_t>> out;
  for (const auto& l : loops) out.push_back(cellforge::detail::canonical_cycle(l));
  std::sort(out.begin(), out.end());
  return out;
}

/// The loops of a complete state, as junction cycles, each once. O(E).
template <class = void>
std::vector<std::vector<std::uint32_t>> loops_of(const drawing_graph& g, const string_state& s) {
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<char> seen(g.num_half_edges(), 0);
  for (std::uint32_t h0 = 0; h0 < g.num_half_edges(); ++h0) {
    if (seen[h0]) continue;
    // Only closed chains are loops.
    std::uint32_t h = h0;
    std::size_t steps = 0;
    while (s.next[h] != none && s.next[h] != h0 && steps <= g.num_half_edges()) h = s.next[h], ++steps;
    if (s.next[h] != h0) continue;
    std::vector<std::uint32_t> loop;
    for (h = h0;;) {
      seen[h] = 1;
      loop.push_back(g.tail(h));
      h = s.next[h];
      if (h == h0) break;
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

/// Checks an answer: edges on two loops, loops simple without inner chords, the Euler count.
/// O(Σ L² + E).
template <class = void>
face_validation check_loops(const drawing_graph& g, const std::vector<std::vector<std::uint32_t>>& loops,
                            double coplanar_tolerance_degrees = 1e-6) {
  face_validation c;
  const std::size_t ne = g.num_half_edges() / 2, nv = g.num_junctions();
  std::vector<std::uint32_t> uses(ne, 0);
  // Edge lookup by junction pair through the CSR table.
  const auto find_edge = [&](std::uint32_t a, std::uint32_t b) {
    for (std::uint32_t i = g.out_begin[a]; i < g.out_begin[a + 1]; ++i)
      if (g.head[g.outs[i]] == b) return g.outs[i] >> 1;
    return none;
  };
  for (std::uint32_t li = 0; li < loops.size(); ++li) {
    const auto& loop = loops[li];
    bool bad = loop.size() < 3;
    for (std::size_t k = 0; k < loop.size() && !bad; ++k) {
      const std::uint32_t e = find_edge(loop[k], loop[(k + 1) % loop.size()]);
      if (e == none)
        bad = true;
      else
        ++uses[e];
    }
    // Simple polygon: no two non-adjacent sides meet.
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n && !bad; ++i)
      for (std::size_t j = i + 1; j < n && !bad; ++j) {
        if (j == i + 1 || (i == 0 && j == n - 1)) continue;
        bad = segments_meet(g.p[loop[i]], g.p[loop[(i + 1) % n]], g.p[loop[j]], g.p[loop[(j + 1) % n]]);
      }
    if (bad) c.bad_loops.push_back(li);
  }
  // The rules of faces at an edge and at a corner, loop by loop against those before it.
  face_rules rules(g, coplanar_tolerance_degrees);
  for (std::uint32_t li = 0; li < loops.size(); ++li) {
    if (std::find(c.bad_loops.begin(), c.bad_loops.end(), li) != c.bad_loops.end()) continue;
    if (rules.conflict(loops[li]) != nullptr) c.rule_breaking_loops.push_back(li);
    rules.add(loops[li]);
  }
  for (std::uint32_t e = 0; e < ne; ++e)
    if (rules.seam(e)) c.seam_edges.push_back(e);
  for (std::uint32_t e = 0; e < ne; ++e) {
    if (uses[e] == 2)
      ++c.edges_on_two_loops;
    else if (uses[e] < 2)
      c.edges_with_fewer_loops.push_back(e);
    else
      c.edges_with_more_loops.push_back(e);
  }
  // Components (of junctions with edges) for the Euler count.
  std::vector<std::uint32_t> comp(nv, none);
  std::size_t components = 0, used_vertices = 0;
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (comp[v] != none || g.degree(v) == 0) continue;
    ++components;
    std::vector<std::uint32_t> stack{v};
    comp[v] = v;
    while (!stack.empty()) {
      const std::uint32_t u = stack.back();
      stack.pop_back();
      ++used_vertices;
      for (std::uint32_t i = g.out_begin[u]; i < g.out_begin[u + 1]; ++i) {
        const std::uint32_t w = g.head[g.outs[i]];
        if (comp[w] == none) comp[w] = v, stack.push_back(w);
      }
    }
  }
  c.euler = static_cast<long long>(used_vertices) - static_cast<long long>(ne) +
            static_cast<long long>(loops.size());
  c.euler_sphere = 2 * static_cast<long long>(components);
  return c;
}

/// Varley–Company on a graph: start, forced concatenations, voluntary mergers, hypotheses.
/// `start_rank` picks which trihedral junction starts (0: the first). O(joins · L).
template <class = void>
std::vector<std::vector<std::uint32_t>> varley_company(const drawing_graph& g, const face_finder_options& o,
                                                       work_counter& budget, std::size_t start_rank,
                                                       face_finder_result& r) {
  finder f(g, o, budget);
  const std::uint32_t nh = static_cast<std::uint32_t>(g.num_half_edges());
  string_state s{std::vector<std::uint32_t>(nh, none), std::vector<std::uint32_t>(nh, none)};
  std::vector<std::uint32_t> all(g.num_junctions());
  for (std::uint32_t v = 0; v < all.size(); ++v) all[v] = v;
  // Start: at a trihedral junction concatenate two strings (this fixes the loops' sense).
  std::size_t rank = 0;
  for (std::uint32_t v = 0; v < g.num_junctions(); ++v) {
    if (g.degree(v) != 3) continue;
    if (rank++ != start_rank) continue;
    const std::uint32_t in = g.outs[g.out_begin[v]] ^ 1u, out = g.outs[g.out_begin[v] + 1];
    if (f.can_join(s, in, out) != 0) finder::join(s, in, out, f);
    break;
  }
  bool dead = !f.propagate(s, all, &f.forced);
  std::vector<std::uint32_t> open_ends;
  while (!dead) {
    open_ends.clear();
    for (std::uint32_t h = 0; h < nh; ++h)
      if (s.next[h] == none) open_ends.push_back(h);
    if (open_ends.empty()) break;
    // Voluntary mergers: a string that closes into a face with one join, shortest loop first.
    std::uint32_t best_h1 = none, best_h2 = none;
    std::size_t best_len = std::numeric_limits<std::size_t>::max();
    for (const auto h1 : open_ends) {
      const std::uint32_t v = g.head[h1];
      for (std::uint32_t j = g.out_begin[v]; j < g.out_begin[v + 1]; ++j) {
        const std::uint32_t h2 = g.outs[j];
        if (s.prev[h2] != none) continue;
        // Only a join that closes a loop is a merger: the joined string must end at our start.
        if (h2 != f.first_of(s, h1) && g.head[f.last_of(s, h2)] != g.tail(f.first_of(s, h1))) continue;
        if (f.can_join(s, h1, h2) != 2) continue;
        const std::size_t len = f.loop_half_edges(s, h1, h2).size();
        if (len < best_len) best_len = len, best_h1 = h1, best_h2 = h2;
      }
    }
    std::vector<std::uint32_t> loop;
    if (best_h1 != none) {
      loop = f.loop_half_edges(s, best_h1, best_h2);
      std::vector<std::uint32_t> vs;
      for (const auto h : loop) vs.push_back(g.tail(h));
      // A separating loop is left to the hypotheses, which weigh it against the others.
      if (!(o.separating_loop_cost > 0 && f.separating(vs)) && f.consistent(s, loop)) {
        ++f.voluntary;
      } else {
        loop.clear();
      }
    }
    if (loop.empty()) {
      // Hypotheses: the highest-priority strings first — those beside a face already found
      // (their loop's sense is then the surface's: a loop grown elsewhere may take the wrong
      // sense and meet the others in a dead end much later), then those whose end has the
      // fewest candidates, then the longest (the most context).
      std::vector<char> closed(nh, 0), visited(nh, 0);
      for (std::uint32_t h0 = 0; h0 < nh; ++h0) {
        if (visited[h0] || s.next[h0] == none) continue;
        std::uint32_t h = h0;
        while (!visited[h] && s.next[h] != none) visited[h] = 1, h = s.next[h];
        if (h == h0)
          for (std::uint32_t x = h0;;) {
            closed[x] = 1;
            x = s.next[x];
            if (x == h0) break;
          }
      }
      std::vector<std::pair<std::array<std::size_t, 3>, std::uint32_t>> ranked;
      for (const auto h1 : open_ends) {
        const std::uint32_t v = g.head[h1];
        std::uint32_t n = 0;
        for (std::uint32_t j = g.out_begin[v]; j < g.out_begin[v + 1]; ++j)
          n += f.can_join(s, h1, g.outs[j]) != 0;
        std::size_t len = 0;
        bool beside = false;
        for (std::uint32_t h = h1; h != none && len <= nh; h = s.prev[h])
          ++len, beside = beside || closed[h ^ 1u];
        ranked.push_back({{beside ? 0u : 1u, n, nh - len}, h1});
      }
      std::sort(ranked.begin(), ranked.end());
      // Seeds by class, the best class grown together (the smallest face closes first): beside
      // the faces found, then strings of two or more half-edges (a corner already chosen), then
      // the rest. A loop's sense is the surface's only when it touches what is already decided.
      std::array<std::vector<std::pair<std::uint32_t, double>>, 3> classes;
      for (const auto& [key, h1] : ranked) {
        const std::size_t cls = key[0] == 0 ? 0 : (nh - key[2] >= 2 ? 1 : 2);
        classes[cls].push_back({h1, o.candidate_cost * (static_cast<double>(key[1]) - 1.0)});
      }
      for (auto& seeds : classes) {
        if (seeds.empty() || !loop.empty()) continue;
        if (seeds.size() > 64) seeds.resize(64);
        loop = f.hypothesis(s, seeds, 20000 + 5000 * seeds.size());
      }
      if (!loop.empty()) ++f.hypotheses;
    }
    if (loop.empty()) {
      r.diagnostics.push_back(
          cellforge::detail::cat("varley_company: ", std::to_string(open_ends.size()),
                                 " half-edges left that no face loop can take (no hypothesis passes)"));
      break;
    }
    finder::close_loop(s, loop);
    std::vector<std::uint32_t> work;
    for (const auto h : loop) work.push_back(g.head[h]);
    dead = !f.propagate(s, std::move(work), &f.forced);
  }
  if (dead)
    r.diagnostics.push_back(
        "varley_company: a forced concatenation reached a dead end (a half-edge no face can continue)");
  r.forced += f.forced;
  r.voluntary += f.voluntary;
  r.hypotheses += f.hypotheses;
  r.rejected += f.rejected;
  return loops_of(g, s);
}

/// The baseline: shortest loops at fixed edge costs (fewest edges, then shortest in the
/// drawing), picked one by one while every edge of the loop is on fewer than two loops.
/// Candidates per round: for each edge still open, its shortest cycle and the best cycle
/// avoiding one more edge of that one (so that a loop taken once is not the only candidate).
/// O(rounds · E · L · E log E).
template <class = void>
std::vector<std::vector<std::uint32_t>> shortest_loops(const drawing_graph& g, work_counter& budget) {
  const std::size_t ne = g.num_half_edges() / 2, nv = g.num_junctions();
  std::vector<std::uint32_t> left(ne, 2);
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<std::vector<std::uint32_t>> taken;  // sorted edge sets of the loops taken
  std::vector<char> banned(ne, 0);
  using cost = std::pair<std::uint32_t, double>;
  // Shortest cycle through e (as edges) over open, unbanned edges. Dijkstra on (edges, length).
  std::vector<cost> dist(nv);
  std::vector<std::uint32_t> via(nv);
  const auto cycle_through = [&](std::uint32_t e, std::vector<std::uint32_t>& edges) {
    const std::uint32_t a = g.head[2 * e + 1], b = g.head[2 * e];
    using item = std::pair<cost, std::uint32_t>;
    std::fill(dist.begin(), dist.end(), cost{none, 0});
    std::priority_queue<item, std::vector<item>, std::greater<>> q;
    dist[a] = {0, 0};
    q.push({dist[a], a});
    while (!q.empty()) {
      const auto [d, u] = q.top();
      q.pop();
      if (d != dist[u]) continue;
      if (u == b) break;
      for (std::uint32_t i = g.out_begin[u]; i < g.out_begin[u + 1]; ++i) {
        budget.spend();
        const std::uint32_t h = g.outs[i], w = g.head[h];
        if ((h >> 1) == e || left[h >> 1] == 0 || banned[h >> 1]) continue;
        const cost nd{d.first + 1, d.second + glm::length(g.p[w] - g.p[u])};
        if (dist[w].first == none || nd < dist[w]) dist[w] = nd, via[w] = h, q.push({nd, w});
      }
    }
    edges.clear();
    if (dist[b].first == none) return cost{none, 0};
    edges.push_back(e);
    for (std::uint32_t v = b; v != a; v = g.tail(via[v])) edges.push_back(via[v] >> 1);
    return cost{dist[b].first + 1, dist[b].second + glm::length(g.p[b] - g.p[a])};
  };
  // Junction cycle of a loop given as its edges, first edge first.
  const auto cycle_of = [&](const std::vector<std::uint32_t>& edges) {
    std::vector<std::uint32_t> loop;
    std::uint32_t v = g.head[2 * edges[0] + 1];
    for (const auto e : edges) {
      loop.push_back(v);
      v = g.head[2 * e] == v ? g.head[2 * e + 1] : g.head[2 * e];
    }
    return loop;
  };
  for (;;) {
    std::vector<std::pair<cost, std::vector<std::uint32_t>>> candidates;
    std::vector<std::uint32_t> first, second;
    for (std::uint32_t e = 0; e < ne; ++e) {
      if (left[e] == 0) continue;
      const cost c = cycle_through(e, first);
      if (c.first == none) continue;
      candidates.push_back({c, first});
      for (std::size_t k = 1; k < first.size(); ++k) {
        banned[first[k]] = 1;
        const cost c2 = cycle_through(e, second);
        banned[first[k]] = 0;
        if (c2.first != none) candidates.push_back({c2, second});
      }
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    bool progress = false;
    for (const auto& [c, edges] : candidates) {
      (void)c;
      bool open = true;
      for (const auto e : edges) open = open && left[e] > 0;
      if (!open) continue;
      std::vector<std::uint32_t> key = edges;
      std::sort(key.begin(), key.end());
      if (std::find(taken.begin(), taken.end(), key) != taken.end()) continue;
      for (const auto e : edges) --left[e];
      taken.push_back(std::move(key));
      loops.push_back(cycle_of(edges));
      progress = true;
    }
    if (!progress) break;
  }
  return loops;
}

/// find_faces on the drawing's graph (defined below).
template <class = void>
face_finder_result find_faces_in(const drawing_graph& g, const face_finder_options& options, double epsilon,
                                 const detail::stopwatch& clock);
}  // namespace detail::faces

template <LineDrawing D>
face_finder_result find_faces(const D& drawing, const face_finder_options& options) {
  const detail::stopwatch clock;
  return detail::faces::find_faces_in(
      detail::faces::make_graph(drawing, options), options,
      static_cast<double>(std::numeric_limits<detail::point2_scalar_t<drawing_point_t<D>>>::epsilon()),
      clock);
}

namespace detail::faces {

/// find_faces on the drawing's graph (in double whatever the drawing's point type, so that one
/// instantiation serves every caller: see CELLFORGE_EXTERN_SKETCH); `epsilon` is the machine
/// epsilon of the drawing's scalar type, `clock` started with the call. O(as find_faces).
template <class>
face_finder_result find_faces_in(const drawing_graph& g, const face_finder_options& options, double epsilon,
                                 const detail::stopwatch& clock) {
  namespace df = detail::faces;
  face_finder_result r;
  r.kind = options.kind;
  r.junctions = g.num_junctions();
  r.edges = g.num_half_edges() / 2;
  r.direction_classes = g.classes;
  detail::work_counter budget{options.work_budget, 0, "find_faces", "face_finder_options::work_budget"};
  // Parallel in space shows as parallel to the point type's rounding: float drawings need more.
  const double coplanar_tolerance =
      std::max(options.coplanar_tolerance_degrees, 100.0 * epsilon * 180.0 / std::numbers::pi);
  if (r.edges == 0) throw error(error_category::invalid_input, "find_faces: the drawing has no edge");
  try {
    if (options.kind == face_finder_kind::varley_company)
      r.loops = df::varley_company(g, options, budget, 0, r);
    else
      r.loops = df::shortest_loops(g, budget);
  } catch (const error& e) {
    if (e.category() != error_category::budget) throw;
    r.budget_fallback = true;
    if (options.kind == face_finder_kind::varley_company) {
      // Out of budget: the baseline's answer (fast at any size), flagged whatever its check says.
      r.diagnostics.push_back(
          cellforge::detail::cat(std::string(e.what()), "; the shortest-loops baseline answers instead"));
      budget.used = 0;
      try {
        r.loops = df::shortest_loops(g, budget);
      } catch (const error& again) {
        detail::stop_at_budget(r, budget, again);  // the last fallback spent: no loops, flagged
      }
    } else {
      detail::stop_at_budget(r, budget, e);  // the baseline is the last fallback: no loops, flagged
    }
  }
  if (options.walls && r.complete) {  // no walls to complete when no loops were found
    // Faces beyond two per edge: the loops that edges still need, each allowed by the rules.
    df::face_rules rules(g, coplanar_tolerance);
    for (const auto& loop : r.loops)
      if (loop.size() >= 3 && rules.conflict(loop) == nullptr) rules.add(loop);
    df::finder f(g, options, budget);
    try {
      const auto [added, dropped] = df::complete_walls(f, rules, options.wall_expansions);
      r.walls = added, r.unneeded = dropped;
    } catch (const error& e) {
      if (e.category() != error_category::budget) throw;
      r.diagnostics.push_back(cellforge::detail::cat(std::string(e.what()), " while searching walls"));
      r.budget_fallback = true;
    }
    // Where the string algorithm alone did not answer (loops added, taken out or dropped), the
    // same search from nothing must find the same loops: two searches that disagree on what the
    // rules allow leave the drawing ambiguous, and the answer is flagged with the other.
    for (std::uint32_t l = 0; l < rules.loops.size(); ++l) r.unforced += !rules.needed(l);
    if (r.unforced > 0) {
      r.ambiguous = true;
      r.diagnostics.push_back(std::to_string(r.unforced) +
                              " loops are walls no edge needs (inside a grid): kept, but the drawing "
                              "reads as well without them");
    }
    const bool completed = r.walls > 0 || r.unneeded > 0 || rules.loops.size() != r.loops.size();
    r.loops = std::move(rules.loops);
    if (completed && !r.budget_fallback) {
      df::face_rules fresh(g, coplanar_tolerance);
      try {
        (void)df::complete_walls(f, fresh, options.wall_expansions);
        if (df::canonical_set(fresh.loops) != df::canonical_set(r.loops)) {
          r.ambiguous = true;
          r.diagnostics.push_back(cellforge::detail::cat("the wall search from no loops finds other faces (",
                                                         std::to_string(fresh.loops.size()),
                                                         " loops): ambiguous"));
          r.alternatives.push_back({fresh.loops, df::check_loops(g, fresh.loops, coplanar_tolerance),
                                    "the wall search from no loops"});
        }
      } catch (const error& e) {
        if (e.category() != error_category::budget) throw;
        r.ambiguous = true;
        r.diagnostics.push_back(
            cellforge::detail::cat(std::string(e.what()), " while cross-checking the walls"));
      }
    }
  }
  r.check = df::check_loops(g, r.loops, coplanar_tolerance);
  r.flagged = !r.check.ok() || r.budget_fallback || r.ambiguous;
  if (r.loops.empty() && r.complete) r.diagnostics.push_back("find_faces: no closed loop in the drawing");
  if (!r.check.edges_with_fewer_loops.empty())
    r.diagnostics.push_back(std::to_string(r.check.edges_with_fewer_loops.size()) +
                            " edges lie on fewer than two loops (first: edge " +
                            std::to_string(r.check.edges_with_fewer_loops.front()) + ")");
  if (!r.check.seam_edges.empty())
    r.diagnostics.push_back(std::to_string(r.check.seam_edges.size()) +
                            " edges lie on just two coplanar loops and no wall meets them (first: edge " +
                            std::to_string(r.check.seam_edges.front()) + ")");
  if (!r.check.rule_breaking_loops.empty())
    r.diagnostics.push_back(
        std::to_string(r.check.rule_breaking_loops.size()) +
        " loops turn a corner another loop turns, overlap a coplanar loop, or overload an edge");
  if (!r.check.bad_loops.empty())
    r.diagnostics.push_back(std::to_string(r.check.bad_loops.size()) +
                            " loops are not simple polygons of the drawing");
  if (r.check.ok() && r.check.euler != r.check.euler_sphere)
    r.diagnostics.push_back(cellforge::detail::cat(
        "V - E + L = ", std::to_string(r.check.euler), " (a sphere per component: ",
        std::to_string(r.check.euler_sphere), "): a solid of higher genus, or a loop too few"));
  if (r.flagged && options.alternatives_when_flagged) {
    // Alternatives: the other finder, and Varley–Company from other starts; best check first.
    std::vector<face_alternative> alt = std::move(r.alternatives);  // the wall search's, if any
    // Each alternative its own budget (the answer may have spent it all); one that runs out is
    // left out, with a diagnostic.
    const auto add = [&](auto&& find, std::string reason) {
      budget.used = 0;
      try {
        alt.push_back({find(), {}, std::move(reason)});
      } catch (const error& e) {
        if (e.category() != error_category::budget) throw;
        r.diagnostics.push_back(cellforge::detail::cat("no alternative from ", reason, ": ", e.what()));
      }
    };
    if (options.kind == face_finder_kind::varley_company) {
      if (!r.budget_fallback)
        add([&] { return df::shortest_loops(g, budget); }, "the shortest-loops baseline");
      for (std::size_t k = 1; k <= 2 && !r.budget_fallback; ++k) {
        face_finder_result scratch;
        add([&] { return df::varley_company(g, options, budget, k, scratch); },
            cellforge::detail::cat("Varley-Company from trihedral junction ", std::to_string(k)));
      }
    } else {
      face_finder_result scratch;
      add([&] { return df::varley_company(g, options, budget, 0, scratch); }, "Varley-Company");
    }
    for (auto& a : alt) a.check = df::check_loops(g, a.loops, coplanar_tolerance);
    const auto score = [](const face_alternative& a) {
      return std::make_tuple(!a.check.ok(),
                             a.check.edges_with_fewer_loops.size() + a.check.seam_edges.size() +
                                 a.check.rule_breaking_loops.size() + a.check.bad_loops.size(),
                             a.check.euler_sphere - a.check.euler);
    };
    std::stable_sort(alt.begin(), alt.end(),
                     [&](const auto& a, const auto& b) { return score(a) < score(b); });
    for (auto& a : alt) a.reason += a.check.ok() ? " (passes the check)" : " (fails the check too)";
    r.alternatives = std::move(alt);
  }
  if (r.complete) r.work = budget.used;  // stop_at_budget kept the work of the spent search
  r.complete = r.complete && !r.budget_fallback;
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace detail::faces

#if defined(CELLFORGE_EXTERN_SKETCH)
// Compiled once in the file that includes cellforge/sketch/instantiate.hpp (docs/sketch.md).
extern template face_finder_result detail::faces::find_faces_in<void>(const detail::faces::drawing_graph&,
                                                                      const face_finder_options&, double,
                                                                      const detail::stopwatch&);
#endif

}  // namespace cellforge
