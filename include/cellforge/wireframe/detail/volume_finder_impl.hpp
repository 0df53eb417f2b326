// SPDX-License-Identifier: MIT
#pragma once
// The engine of the volume finder (included by wireframe/volume_finder.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/polygon_intersection.hpp"
#include "cellforge/wireframe/circuit_tracer.hpp"
#include "cellforge/wireframe/volume_finder.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

namespace detail {

/// The faces around every edge, in right-hand rotation order about the edge's direction.
/// O(Σ L + E·k log k) for k faces at an edge.
template <class = void>
std::vector<std::vector<edge_fan_entry>> edge_fans(const wire_graph& g, const std::vector<wire_face>& faces,
                                                   const std::vector<char>* kept = nullptr) {
  std::vector<std::vector<edge_fan_entry>> fan(g.num_edges());
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    if (kept && !(*kept)[i]) continue;
    for (const auto& loop : faces[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const std::uint32_t a = loop[k], b = loop[(k + 1) % loop.size()];
        const std::uint32_t e = g.find_edge(a, b);
        fan[e].push_back({i, g.edges[e][0] == a ? 1 : -1, 0.0});
      }
  }
  for (std::uint32_t e = 0; e < g.num_edges(); ++e) {
    auto& f = fan[e];
    if (f.empty()) continue;
    const glm::dvec3 d = glm::normalize(g.points[g.edges[e][1]] - g.points[g.edges[e][0]]);
    const glm::dvec3 x = any_perpendicular(d, perpendicular_rule::x_below_0_6), y = glm::cross(d, x);
    for (auto& en : f) {
      // The face lies to the left of its walk: inward = normal × walked direction.
      const glm::dvec3 w = glm::cross(faces[en.face].normal, static_cast<double>(en.walk) * d);
      en.angle = std::atan2(glm::dot(w, y), glm::dot(w, x));
    }
    std::sort(f.begin(), f.end(), [](const edge_fan_entry& a, const edge_fan_entry& b) {
      return a.angle != b.angle ? a.angle < b.angle : a.face < b.face;
    });
  }
  return fan;
}

/// Whether the region bounded by `shell` (faces of one closed surface) contains the surface
/// `inner` (faces of another, not crossing it): the exact point-in-solid test of
/// core/polygon_intersection.hpp from a vertex of `inner` that is not a vertex of `shell`, so
/// that a solid touching the other at a vertex or an edge never starts on its boundary; a
/// start that is still undecided (on a face's plane, or every ray grazing) tries the next
/// vertex. O(tries · Σ L).
template <class = void>
bool surface_inside(const wire_graph& g, const std::vector<wire_face>& faces,
                    const std::vector<std::uint32_t>& shell, const std::vector<std::uint32_t>& inner,
                    std::vector<std::uint32_t>& mark, std::uint32_t stamp) {
  for (const auto i : shell)
    for (const auto& loop : faces[i].loops)
      for (const auto v : loop) mark[v] = stamp;
  auto loops_of = [&](std::uint32_t i) -> const polygon_loops& { return faces[i].loops; };
  std::size_t tries = 0;
  for (const auto i : inner)
    for (const auto& loop : faces[i].loops)
      for (const auto v : loop) {
        if (mark[v] == stamp) continue;
        mark[v] = stamp;  // each vertex once
        const polygon_location l = point_in_polyhedron(g.points, shell, loops_of, g.points[v]);
        if (l != polygon_location::boundary) return l == polygon_location::inside;
        if (++tries == 16) return false;
      }
  return false;
}

/// True when the faces `boundary` of one volume make a 2-manifold there: each edge on at most
/// two of them, and around each vertex one fan (two parts of a volume touching along an edge or
/// at a vertex break make_cell_complex's volumes). `corners` is scratch. O(Σ L log Σ L).
template <class = void>
bool manifold_boundary(const wire_graph& g, const std::vector<wire_face>& faces,
                       std::span<const std::uint32_t> boundary,
                       std::vector<std::array<std::uint32_t, 3>>& corners) {
  corners.clear();  // (vertex, edge before it, edge after it) per corner
  for (const auto f : boundary)
    for (const auto& loop : faces[f].loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const std::uint32_t v = loop[k], prev = loop[(k + loop.size() - 1) % loop.size()],
                            next = loop[(k + 1) % loop.size()];
        corners.push_back({v, g.find_edge(prev, v), g.find_edge(v, next)});
      }
  std::sort(corners.begin(), corners.end());
  std::vector<std::uint32_t> edges, up;
  for (std::size_t b = 0, e = 0; b < corners.size(); b = e) {
    for (e = b; e < corners.size() && corners[e][0] == corners[b][0]; ++e) {
    }
    edges.clear();
    for (std::size_t k = b; k < e; ++k) edges.push_back(corners[k][1]), edges.push_back(corners[k][2]);
    std::sort(edges.begin(), edges.end());
    // Each edge at the vertex on at most two corners (at most two faces of the volume).
    for (std::size_t k = 0; k + 2 < edges.size(); ++k)
      if (edges[k] == edges[k + 2]) return false;
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    up.resize(edges.size());
    for (std::uint32_t k = 0; k < up.size(); ++k) up[k] = k;
    auto find = [&](std::uint32_t x) {
      while (up[x] != x) x = up[x] = up[up[x]];
      return x;
    };
    auto index = [&](std::uint32_t edge) {
      return static_cast<std::uint32_t>(std::lower_bound(edges.begin(), edges.end(), edge) - edges.begin());
    };
    std::size_t fans = edges.size();
    for (std::size_t k = b; k < e; ++k) {
      const auto x = find(index(corners[k][1])), y = find(index(corners[k][2]));
      if (x != y) up[x] = y, --fans;
    }
    if (fans != 1) return false;
  }
  return true;
}

template <class = void>
struct basic_region_links;
using region_links = basic_region_links<>;

/// Which faces lie between two current roots of a union-find over regions, for
/// merge_unforced: how many that must stay, and the walls that may go. Pairs are keyed by
/// current roots; absorbing a root moves its pairs to the surviving root (the root with the
/// shorter neighbour list is absorbed, so each pair moves O(log F) times). O(F log F) in all.
template <class>
struct basic_region_links {
  struct link {
    std::uint32_t needed = 0;
    std::vector<std::uint32_t> walls;
  };
  std::unordered_map<std::uint64_t, link> pairs;
  std::vector<std::vector<std::uint32_t>> neighbours;

  explicit basic_region_links(std::size_t regions) : neighbours(regions) {}
  static std::uint64_t key(std::uint32_t a, std::uint32_t b) noexcept {
    if (a > b) std::swap(a, b);
    return (std::uint64_t{a} << 32) | b;
  }
  void add(std::uint32_t a, std::uint32_t b, std::uint32_t face, bool wall) {
    auto& l = pairs[key(a, b)];
    if (wall)
      l.walls.push_back(face);
    else
      ++l.needed;
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  /// Unites roots a and b in `uf` and moves the absorbed root's pairs to the survivor.
  void unite(std::uint32_t a, std::uint32_t b, union_find& uf) {
    if (neighbours[a].size() > neighbours[b].size()) std::swap(a, b);
    uf.parent[a] = b;  // a is absorbed into b
    pairs.erase(key(a, b));
    for (const auto y0 : neighbours[a]) {
      const auto y = uf.find(y0);
      if (y == b) continue;
      const auto it = pairs.find(key(a, y));
      if (it == pairs.end()) continue;  // listed twice, moved already
      link moved = std::move(it->second);
      pairs.erase(it);
      auto& l = pairs[key(b, y)];
      l.needed += moved.needed;
      l.walls.insert(l.walls.end(), moved.walls.begin(), moved.walls.end());
      neighbours[b].push_back(y);
    }
    std::vector<std::uint32_t>().swap(neighbours[a]);
  }
};

template <class = void>
class basic_face_reader;
using face_reader = basic_face_reader<>;

/// The reading rule of docs/wireframe.md on the regions a set of faces bounds: which faces no
/// edge needs are not faces. In rounds: the faces no edge needs among those still kept are
/// grouped (two such faces are in one group when they share an edge or a bounded region), and
/// each group is decided by an exact search over its faces (drop or keep each): a reading is
/// certified when every edge keeps two non-coplanar faces or three, no kept face has one
/// volume on both sides, no volume uses an edge more than twice, and no wall the wireframe
/// cannot decide (a seam wall: no edge needs it and it continues in the plane of another face
/// at every edge, as inside a grid) is dropped or turned to the outside; among certified
/// readings the search takes the one with the fewest kept faces no edge needs, then the fewest
/// kept faces, then the largest area dropped (readings equal in all three keep the faces they
/// disagree on, reported as unforced). Branch and bound, drop first, with propagation: a face
/// an edge needs is kept, a face with one volume on both sides goes. Dropping faces makes the
/// rest only more needed, so rounds end. O(rounds · Σ L · k) plus the search, which spends
/// from the work budget (per group at most `group_nodes` nodes; past that, the best reading
/// found and a diagnostic).
template <class>
class basic_face_reader {
 public:
  std::vector<char> drop, opened, unforced;  // per face
  union_find merged;                         // regions, O = regions; joined across drops
  std::vector<std::string> notes;            // what the search could not settle, for diagnostics
  std::vector<char> undecided;               // per face: kept because equally good readings disagree
  std::size_t groups_searched = 0, readings_certified = 0;
  std::uint64_t group_nodes = 1u << 15;
  /// A certified reading of a group that keeps no more faces no edge needs than the one taken:
  /// its faces kept that the taken one drops and the reverse, its volumes minus the taken
  /// one's (in the group's regions), and the first key of the order that set it aside.
  struct group_reading {
    std::vector<std::uint32_t> add, remove;
    int volumes = 0;
    reading_key key = reading_key::none;
    /// Its solid is a 2-manifold wherever the taken one's is, at the vertices of the faces in
    /// which they differ (not twelve caps of a geodesic sphere touching at their corners).
    bool manifold = true;
  };
  std::vector<group_reading> other_readings;
  std::size_t readings_per_group = 8;
  bool complete = true;  // false once a search or the rounds ran out of the work budget

  basic_face_reader(const wire_graph& g, const std::vector<wire_face>& faces, const edge_face_lists& at,
                    const std::vector<std::array<std::uint32_t, 2>>& sides, const std::vector<char>& alive,
                    std::uint32_t regions, face_reading reading)
      : drop(faces.size(), 0),
        opened(faces.size(), 0),
        unforced(faces.size(), 0),
        merged(std::size_t{regions} + 1),
        undecided(faces.size(), 0),
        g_(g),
        faces_(faces),
        at_(at),
        sides_(sides),
        alive_(alive),
        O_(regions),
        reading_(reading),
        root_faces_(std::size_t{regions} + 1),
        seam_wall_(faces.size(), 0),
        ambiguous_(std::size_t{regions} + 1, 0),
        kept_cache_(alive),
        local_(faces.size(), no_index) {
    for (std::uint32_t i = 0; i < faces.size(); ++i)
      if (alive[i])
        for (const auto rg : sides[i]) root_faces_[rg].push_back(i);
    // Walls the wireframe cannot decide, on the faces as given: a seam wall no edge needs whose
    // regions reach, through such walls, a region with a face no edge needs to the outside (a
    // grid's inner walls behind the middles of its sides). Those walls stay and those regions
    // never open; a seam wall of a closed group (a 3D cross's inner cube) may merge, and a face
    // filling a hole of its plane (a disc in a ring face: a stepped bore) is no seam wall.
    std::vector<std::uint32_t> scratch;
    union_find through(std::size_t{regions} + 1);
    std::vector<char> mouth(std::size_t{regions} + 1, 0);
    std::vector<std::uint32_t> seams;
    for (std::uint32_t i = 0; i < faces.size(); ++i) {
      if (!alive[i] || needed_faces_one(g_, faces_, at_, alive_, i, scratch)) continue;
      if (sides[i][0] == O_ || sides[i][1] == O_) {
        mouth[sides[i][0] == O_ ? sides[i][1] : sides[i][0]] = 1;
      } else if (!faces[i].fills_hole && is_seam(i)) {  // a nested outline is no wall among walls
        seams.push_back(i);
        through.unite(sides[i][0], sides[i][1]);
      }
    }
    std::vector<char> reached(std::size_t{regions} + 1, 0);
    for (std::uint32_t rg = 0; rg < regions; ++rg)
      if (mouth[rg]) reached[through.find(rg)] = 1;
    for (const auto i : seams)
      if (reached[through.find(sides[i][0])]) {
        seam_wall_[i] = 1;
        ambiguous_[sides[i][0]] = ambiguous_[sides[i][1]] = 1;
      }
  }

  void run(work_counter& budget) {
    if (reading_ == face_reading::keep_all) return mark_unforced();
    const auto nf = static_cast<std::uint32_t>(faces_.size());
    for (;;) {
      // Out of budget: stop with the readings committed so far (each certified), flagged.
      if (budget.limit != 0 && budget.used + nf > budget.limit) {
        complete = false;
        notes.push_back(cellforge::detail::cat("the reading rule ran out of its work budget after ",
                                               std::to_string(groups_searched),
                                               " group searches; the faces still undecided are kept"));
        break;
      }
      budget.spend(nf);
      mark_unforced();
      // Groups: the free faces no edge needs, joined through shared edges and bounded regions.
      std::vector<std::uint32_t> free;
      for (std::uint32_t i = 0; i < nf; ++i)
        if (unforced[i] && !frozen(i)) free.push_back(i);
      if (free.empty()) break;
      union_find group(nf + merged.parent.size());
      const std::uint32_t outside = merged.find(O_);
      for (const auto i : free) {
        for (const auto rg : sides_[i])
          if (const auto r = merged.find(rg); r != outside) group.unite(i, nf + r);
        for (const auto& loop : faces_[i].loops)
          for (std::size_t k = 0; k < loop.size(); ++k)
            for (const auto j : at_[g_.find_edge(loop[k], loop[(k + 1) % loop.size()])])
              if (j != i && unforced[j] && !frozen(j)) group.unite(i, j);
      }
      std::vector<std::pair<std::uint32_t, std::uint32_t>> by_group;  // (root, face)
      for (const auto i : free) by_group.push_back({group.find(i), i});
      std::sort(by_group.begin(), by_group.end());
      bool changed = false;
      std::vector<std::uint32_t> members;
      for (std::size_t b = 0, e = 0; b < by_group.size(); b = e) {
        members.clear();
        for (e = b; e < by_group.size() && by_group[e].first == by_group[b].first; ++e)
          members.push_back(by_group[e].second);
        // Earlier groups of the round may have made some of these needed or merged their sides.
        std::erase_if(members, [&](std::uint32_t i) {
          return drop[i] || frozen(i) || merged.find(sides_[i][0]) == merged.find(sides_[i][1]) ||
                 needed_faces_one(g_, faces_, at_, kept_now(), i, scratch_);
        });
        if (members.empty()) continue;
        // keep_walls: a group with no face on the outside cannot open, and its walls stay
        // whatever the search would find (the vase's 12 rings: 2^12 leaves, all refused).
        if (reading_ == face_reading::keep_walls &&
            std::none_of(members.begin(), members.end(), [&](std::uint32_t i) {
              return merged.find(sides_[i][0]) == outside || merged.find(sides_[i][1]) == outside;
            }))
          continue;
        const auto picked = search(members, budget);
        if (!picked.empty()) {
          commit(picked);
          changed = true;
        }
      }
      if (!changed) break;
    }
    mark_unforced();
  }

 private:
  const wire_graph& g_;
  const std::vector<wire_face>& faces_;
  const edge_face_lists& at_;
  const std::vector<std::array<std::uint32_t, 2>>& sides_;
  const std::vector<char>& alive_;
  std::uint32_t O_;
  face_reading reading_;
  std::vector<std::vector<std::uint32_t>> root_faces_;  // per merged root, the faces bounding it
  std::vector<char> seam_wall_, ambiguous_;             // per face; per merged root
  std::vector<std::uint32_t> vertex_first_,
      vertex_faces_;  // CSR vertex → alive faces, built when first needed
  std::vector<std::uint32_t> scratch_;
  std::vector<char> kept_cache_;

  // ---- the search's state (one group at a time) ----
  std::vector<std::uint32_t> local_;      // face → index in the group, no_index otherwise
  std::vector<std::uint32_t> G_;          // the group's faces, in search order
  std::vector<char> st_;                  // per group face: 0 undecided, 1 keep, 2 drop
  std::vector<std::uint32_t> roots_;      // the merged roots the group touches (sorted)
  std::vector<std::uint32_t> up_, size_;  // rollback union-find over roots_
  std::vector<char> out_, amb_;           // per local root: holds the outside; holds an ambiguous region
  std::vector<std::vector<std::uint32_t>> bound_;      // per local root: faces (kept, any) bounding it
  std::vector<std::array<std::uint32_t, 3>> corners_;  // scratch of manifold_boundary
  struct undo {
    int kind;  // 0: face state, 1: union (child), 2: bound_ growth
    std::uint32_t a, b;
  };
  std::vector<undo> trail_;
  std::vector<std::uint32_t> queue_;
  struct score {
    std::uint32_t c1 = 0, volumes = 0, c2 = 0;
    double area = 0.0;
  };
  score best_;
  bool have_best_ = false;
  std::vector<std::vector<char>> optima_;
  // Certified readings with the fewest kept faces no edge needs met so far, best first by the
  // order (at most readings_per_group + 1 of them).
  std::vector<std::pair<score, std::vector<char>>> met_;
  std::uint64_t nodes_ = 0, limit_ = 0;
  bool stopped_ = false;
  std::size_t leaves_ = 0;

  bool kept(std::uint32_t i) const { return alive_[i] && !drop[i]; }
  /// Per face: kept (alive, not dropped); updated by commit.
  const std::vector<char>& kept_now() const { return kept_cache_; }
  /// Seam walls never go. Every other face no edge needs is searched, face by face: one between
  /// the outside and a region next to a seam wall stays only because each reading dropping it
  /// turns the wall to the outside (`amb_` in assign), not because its region is frozen whole.
  bool frozen(std::uint32_t i) const { return seam_wall_[i] != 0; }
  /// unforced[i]: kept, and needed by no edge among the kept faces.
  void mark_unforced() {
    const auto& k = kept_now();
    for (std::uint32_t i = 0; i < faces_.size(); ++i)
      unforced[i] = k[i] && !needed_faces_one(g_, faces_, at_, k, i, scratch_);
  }
  /// A seam continues, at every edge, in the plane of another alive face: a wall among walls.
  bool is_seam(std::uint32_t i) const {
    for (const auto& loop : faces_[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        bool flat = false;
        for (const auto j : at_[g_.find_edge(loop[k], loop[(k + 1) % loop.size()])])
          flat = flat || (j != i && alive_[j] && coplanar_normals(faces_[i].normal, faces_[j].normal));
        if (!flat) return false;
      }
    return true;
  }
  template <class Visit>
  void for_edges(std::uint32_t i, Visit&& visit) const {
    for (const auto& loop : faces_[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k) visit(g_.find_edge(loop[k], loop[(k + 1) % loop.size()]));
  }

  // During a search: is face j present (kept so far or still open)?
  bool present(std::uint32_t j) const {
    if (!kept(j)) return false;
    const auto l = local_[j];
    return l == no_index || st_[l] != 2;
  }
  std::uint32_t lroot(std::uint32_t rg) {
    const auto r = merged.find(rg);
    auto x = static_cast<std::uint32_t>(std::lower_bound(roots_.begin(), roots_.end(), r) - roots_.begin());
    if (x == roots_.size() || roots_[x] != r) return no_index - 1;  // a region the group does not touch
    while (up_[x] != x) x = up_[x];
    return x;
  }
  /// The present faces at edge e, other than `skip`, make a genuine edge.
  bool edge_ok(std::uint32_t e, std::uint32_t skip) {
    scratch_.clear();
    for (const auto j : at_[e])
      if (j != skip && present(j)) scratch_.push_back(j);
    auto normal = [&](std::uint32_t j) { return faces_[j].normal; };
    return !edge_needs_more(scratch_, normal);
  }
  void set(std::uint32_t l, char v) {
    trail_.push_back({0, l, static_cast<std::uint32_t>(st_[l])});
    st_[l] = v;
  }
  /// Assigns v to group face l and propagates; false on a conflict (the caller undoes the trail).
  bool assign(std::uint32_t l, char v) {
    if (st_[l] != 0) return st_[l] == v;
    set(l, v);
    queue_.clear();
    queue_.push_back(l);
    while (!queue_.empty()) {
      const auto x = queue_.back();
      queue_.pop_back();
      const auto f = G_[x];
      if (st_[x] == 1) {
        if (lroot(sides_[f][0]) == lroot(sides_[f][1])) return false;
        continue;
      }
      // Dropped: every edge must stay genuine; faces that keep it so are forced.
      bool ok = true;
      for_edges(f, [&](std::uint32_t e) {
        if (!ok) return;
        if (!edge_ok(e, no_index)) {
          ok = false;
          return;
        }
        for (const auto j : at_[e]) {
          const auto lj = local_[j];
          if (lj == no_index || st_[lj] != 0 || !present(j)) continue;
          if (!edge_ok(e, j)) {
            set(lj, 1);
            queue_.push_back(lj);
          }
        }
      });
      if (!ok) return false;
      auto a = lroot(sides_[f][0]), b = lroot(sides_[f][1]);
      if (a == b) continue;
      if ((out_[a] && amb_[b]) || (out_[b] && amb_[a])) return false;
      // Faces between a and b: an open one must go, a kept one makes the reading invalid.
      if (bound_[a].size() > bound_[b].size()) std::swap(a, b);
      for (const auto j : bound_[a]) {
        if (!present(j)) continue;
        const auto p = lroot(sides_[j][0]), q = lroot(sides_[j][1]);
        if (!((p == a && q == b) || (p == b && q == a))) continue;
        const auto lj = local_[j];
        if (lj == no_index || st_[lj] == 1) return false;
        set(lj, 2);
        queue_.push_back(lj);
      }
      up_[a] = b;  // a (the smaller list) is absorbed
      trail_.push_back({1, a, static_cast<std::uint32_t>(bound_[b].size())});
      bound_[b].insert(bound_[b].end(), bound_[a].begin(), bound_[a].end());
      trail_.push_back({2, b, static_cast<std::uint32_t>(out_[b] | (amb_[b] << 1))});
      out_[b] = out_[b] || out_[a];
      amb_[b] = amb_[b] || amb_[a];
    }
    return true;
  }
  void undo_to(std::size_t mark) {
    while (trail_.size() > mark) {
      const undo u = trail_.back();
      trail_.pop_back();
      if (u.kind == 0) {
        st_[u.a] = static_cast<char>(u.b);
      } else if (u.kind == 2) {
        out_[u.a] = static_cast<char>(u.b & 1);
        amb_[u.a] = static_cast<char>((u.b >> 1) & 1);
      } else {
        const auto b = up_[u.a];
        bound_[b].resize(u.b);
        up_[u.a] = u.a;
      }
    }
  }
  /// Needed among the present faces, counting open faces as dropped when `pessimistic`.
  bool needed_now(std::uint32_t f, bool pessimistic) {
    bool need = false;
    for_edges(f, [&](std::uint32_t e) {
      if (need) return;
      scratch_.clear();
      for (const auto j : at_[e]) {
        if (j == f || !present(j)) continue;
        if (pessimistic && local_[j] != no_index && st_[local_[j]] == 0) continue;
        scratch_.push_back(j);
      }
      auto normal = [&](std::uint32_t j) { return faces_[j].normal; };
      need = edge_needs_more(scratch_, normal);
    });
    return need;
  }
  /// A complete assignment: no volume uses an edge more than twice; keep_walls merges no two
  /// volumes. Returns false when it fails.
  bool certified() {
    std::vector<std::uint32_t> members(roots_.size(), 0), boundary;
    for (std::uint32_t x = 0; x < roots_.size(); ++x) ++members[lroot_of_local(x)];
    for (std::uint32_t r = 0; r < roots_.size(); ++r) {
      // Only volumes this group merged can break the manifold.
      if (up_[r] != r || out_[r] || members[r] < 2) continue;
      boundary.clear();
      for (const auto j : bound_[r])
        if (present(j) && (lroot(sides_[j][0]) == r) != (lroot(sides_[j][1]) == r)) boundary.push_back(j);
      std::sort(boundary.begin(), boundary.end());
      boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
      if (!manifold_boundary(g_, faces_, boundary, corners_)) return false;
    }
    if (reading_ == face_reading::keep_walls)
      for (std::uint32_t l = 0; l < G_.size(); ++l)
        if (st_[l] == 2 && !out_[lroot(sides_[G_[l]][0])]) return false;
    return true;
  }
  std::uint32_t lroot_of_local(std::uint32_t x) const {
    while (up_[x] != x) x = up_[x];
    return x;
  }
  static int compare(const score& a, const score& b) {
    if (a.c1 != b.c1) return a.c1 < b.c1 ? -1 : 1;
    if (a.volumes != b.volumes) return a.volumes < b.volumes ? -1 : 1;
    if (a.c2 != b.c2) return a.c2 < b.c2 ? -1 : 1;
    const double tol = 1e-9 * std::max({a.area, b.area, 1e-300});
    if (std::abs(a.area - b.area) <= tol) return 0;
    return a.area > b.area ? -1 : 1;
  }
  /// The first key in which a and b differ (`none`: equal in all).
  static reading_key first_difference(const score& a, const score& b) {
    if (a.c1 != b.c1) return reading_key::unneeded_faces;
    if (a.volumes != b.volumes) return reading_key::volumes;
    if (a.c2 != b.c2) return reading_key::faces;
    return compare(a, b) != 0 ? reading_key::area : reading_key::none;
  }
  void leaf() {
    ++leaves_;
    if (!certified()) return;
    ++readings_certified;
    score s;
    for (std::uint32_t x = 0; x < roots_.size(); ++x) s.volumes += up_[x] == x && !out_[x];
    for (std::uint32_t l = 0; l < G_.size(); ++l) {
      if (st_[l] == 2) {
        s.area += faces_[G_[l]].area;
      } else {
        ++s.c2;
        s.c1 += !needed_now(G_[l], false);
      }
    }
    if (readings_per_group > 0 && (!have_best_ || s.c1 <= best_.c1)) {
      // Kept best first; a reading with fewer kept faces no edge needs clears the others.
      if (have_best_ && s.c1 < best_.c1) met_.clear();
      const auto at =
          std::find_if(met_.begin(), met_.end(), [&](const auto& m) { return compare(s, m.first) < 0; });
      if (static_cast<std::size_t>(at - met_.begin()) <= readings_per_group) met_.insert(at, {s, st_});
      if (met_.size() > readings_per_group + 1) met_.pop_back();
    }
    const int c = have_best_ ? compare(s, best_) : -1;
    if (c > 0) return;
    if (c < 0) {
      best_ = s;
      have_best_ = true;
      optima_.clear();
    }
    if (optima_.size() < 8) optima_.push_back(st_);
  }
  void dfs(std::size_t pos) {
    if (stopped_) return;
    if (++nodes_ > limit_) {
      stopped_ = true;
      return;
    }
    while (pos < G_.size() && st_[pos] != 0) ++pos;
    if (pos == G_.size()) return leaf();
    if (have_best_) {
      // Bound: faces kept so far, and those of them unneeded even if every open face goes.
      score lb;
      for (std::uint32_t l = 0; l < G_.size(); ++l)
        if (st_[l] == 1) {
          ++lb.c2;
          lb.c1 += !needed_now(G_[l], true);
        }
      if (lb.c1 > best_.c1) return;
      // Every face dropped: nothing beats it; the search goes on only for other readings.
      if (best_.c2 == 0 && readings_per_group == 0) return;
    }
    for (const char v : {char{2}, char{1}}) {
      const std::size_t mark = trail_.size();
      if (assign(static_cast<std::uint32_t>(pos), v)) dfs(pos + 1);
      undo_to(mark);
      if (stopped_) return;
    }
  }
  /// Whether the solid's surface (faces between the outside and a volume, in the current
  /// assignment) is one fan about vertex v, each edge there on at most two of its faces.
  /// O(faces at v · their length).
  bool manifold_at(std::uint32_t v) {
    if (vertex_first_.empty()) {
      vertex_first_.assign(g_.num_vertices() + 1, 0);
      for (std::uint32_t i = 0; i < faces_.size(); ++i)
        if (alive_[i])
          for (const auto& loop : faces_[i].loops)
            for (const auto u : loop) ++vertex_first_[u + 1];
      for (std::size_t u = 0; u < g_.num_vertices(); ++u) vertex_first_[u + 1] += vertex_first_[u];
      vertex_faces_.resize(vertex_first_.back());
      std::vector<std::uint32_t> fill(vertex_first_.begin(), vertex_first_.end() - 1);
      for (std::uint32_t i = 0; i < faces_.size(); ++i)
        if (alive_[i])
          for (const auto& loop : faces_[i].loops)
            for (const auto u : loop) vertex_faces_[fill[u]++] = i;
    }
    const auto o = merged.find(O_);
    auto outside = [&](std::uint32_t rg) {
      const auto x = lroot(rg);
      return x == no_index - 1 ? merged.find(rg) == o : out_[x] != 0;
    };
    std::vector<std::array<std::uint32_t, 2>> corners;  // (edge before v, edge after v)
    for (std::uint32_t k = vertex_first_[v]; k < vertex_first_[v + 1]; ++k) {
      const auto f = vertex_faces_[k];
      if (!present(f) || outside(sides_[f][0]) == outside(sides_[f][1])) continue;
      for (const auto& loop : faces_[f].loops)
        for (std::size_t i = 0; i < loop.size(); ++i)
          if (loop[i] == v)
            corners.push_back({g_.find_edge(loop[(i + loop.size() - 1) % loop.size()], v),
                               g_.find_edge(v, loop[(i + 1) % loop.size()])});
    }
    if (corners.empty()) return true;
    std::vector<std::uint32_t> edges;
    for (const auto& c : corners) edges.push_back(c[0]), edges.push_back(c[1]);
    std::sort(edges.begin(), edges.end());
    for (std::size_t k = 0; k + 2 < edges.size(); ++k)
      if (edges[k] == edges[k + 2]) return false;
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    union_find fan(edges.size());
    std::size_t fans = edges.size();
    auto index = [&](std::uint32_t e) {
      return static_cast<std::uint32_t>(std::lower_bound(edges.begin(), edges.end(), e) - edges.begin());
    };
    for (const auto& c : corners) {
      const auto a = fan.find(index(c[0])), b = fan.find(index(c[1]));
      if (a != b) fan.unite(a, b), --fans;
    }
    return fans == 1;
  }
  /// How many of the vertices `at` are not manifold_at under the assignment `st` (replayed).
  std::size_t pinched(const std::vector<char>& st, const std::vector<std::uint32_t>& at) {
    st_.assign(G_.size(), 0);
    bool ok = true;
    for (std::uint32_t l = 0; l < G_.size() && ok; ++l) ok = assign(l, st[l]);
    std::size_t n = 0;
    if (ok)
      for (const auto v : at) n += !manifold_at(v);
    undo_to(0);
    return ok ? n : at.size() + 1;
  }
  /// The best certified reading of the group's faces `members`: the faces to drop.
  std::vector<std::uint32_t> search(std::vector<std::uint32_t> members, work_counter& budget) {
    ++groups_searched;
    // Larger faces first: the first readings found drop the larger mouths.
    std::sort(members.begin(), members.end(), [&](std::uint32_t a, std::uint32_t b) {
      return faces_[a].area != faces_[b].area ? faces_[a].area > faces_[b].area : a < b;
    });
    G_ = members;
    for (std::uint32_t l = 0; l < G_.size(); ++l) local_[G_[l]] = l;
    st_.assign(G_.size(), 0);
    roots_.clear();
    roots_.push_back(merged.find(O_));
    for (const auto f : G_)
      for (const auto rg : sides_[f]) roots_.push_back(merged.find(rg));
    std::sort(roots_.begin(), roots_.end());
    roots_.erase(std::unique(roots_.begin(), roots_.end()), roots_.end());
    const std::size_t nr = roots_.size();
    up_.resize(nr);
    out_.assign(nr, 0);
    amb_.assign(nr, 0);
    bound_.assign(nr, {});
    const auto o = merged.find(O_);
    for (std::uint32_t x = 0; x < nr; ++x) {
      up_[x] = x;
      out_[x] = roots_[x] == o;
      amb_[x] = ambiguous_[roots_[x]];
      if (roots_[x] == o) continue;  // the outside's faces matter only through the other side
      for (const auto j : root_faces_[roots_[x]])
        if (kept(j)) bound_[x].push_back(j);
    }
    // Faces whose other side is the outside are listed with their bounded side only; list
    // them under the outside too, so that a merge with the outside finds them.
    if (const auto xo =
            static_cast<std::uint32_t>(std::lower_bound(roots_.begin(), roots_.end(), o) - roots_.begin());
        xo < nr)
      for (std::uint32_t x = 0; x < nr; ++x)
        if (x != xo)
          for (const auto j : bound_[x])
            if (merged.find(sides_[j][0]) == o || merged.find(sides_[j][1]) == o) bound_[xo].push_back(j);
    trail_.clear();
    have_best_ = false;
    optima_.clear();
    met_.clear();
    nodes_ = 0;
    leaves_ = 0;
    stopped_ = false;
    const std::uint64_t left =
        budget.limit == 0 ? ~std::uint64_t{0} : (budget.limit > budget.used ? budget.limit - budget.used : 0);
    // Each node looks at the group's faces: the search stops before the budget would throw.
    limit_ = std::min<std::uint64_t>(group_nodes, left / (G_.size() + 1) + 1);
    dfs(0);
    budget.spend(std::min<std::uint64_t>(nodes_ * (G_.size() + 1), left));
    std::vector<std::uint32_t> picked;
    const std::size_t other_start = other_readings.size();
    if (have_best_) {
      // Readings alike in every key keep the faces they disagree on (the wireframe does not decide).
      std::vector<char> choice = optima_.front();
      if (optima_.size() > 1) {
        std::vector<char> meet(G_.size(), 2);
        for (const auto& opt : optima_)
          for (std::uint32_t l = 0; l < G_.size(); ++l)
            if (opt[l] != 2) meet[l] = 1;
        // The meet is certified when it assigns cleanly and passes the checks.
        st_.assign(G_.size(), 0);
        bool ok = true;
        for (std::uint32_t l = 0; l < G_.size() && ok; ++l) ok = assign(l, meet[l]);
        ok = ok && st_ == meet && certified();
        undo_to(0);
        if (ok) {
          for (std::uint32_t l = 0; l < G_.size(); ++l)
            if (meet[l] != choice[l]) undecided[G_[l]] = 1;
          choice = meet;
        }
        notes.push_back(std::to_string(optima_.size()) + (optima_.size() == 8 ? " or more" : "") +
                        " equally good readings of a group of " + std::to_string(G_.size()) +
                        " faces no edge needs" +
                        (ok ? "; the faces they disagree on are kept" : "; the first is taken"));
      }
      for (std::uint32_t l = 0; l < G_.size(); ++l)
        if (choice[l] == 2) picked.push_back(G_[l]);
      // The other readings as good in the first key, against the one taken.
      const auto volumes_of = [&](const score& x) { return static_cast<int>(x.volumes); };
      for (const auto& [sc, st] : met_) {
        if (st == choice || sc.c1 != best_.c1) continue;
        if (other_readings.size() >= other_start + readings_per_group) break;
        group_reading o;
        for (std::uint32_t l = 0; l < G_.size(); ++l) {
          if (st[l] != 2 && choice[l] == 2) o.add.push_back(G_[l]);
          if (st[l] == 2 && choice[l] != 2) o.remove.push_back(G_[l]);
        }
        std::sort(o.add.begin(), o.add.end());
        std::sort(o.remove.begin(), o.remove.end());
        o.volumes = volumes_of(sc) - volumes_of(best_);
        o.key = first_difference(sc, best_);
        if (o.key != reading_key::unneeded_faces) {
          std::vector<std::uint32_t> at;
          for (const auto list : {&o.add, &o.remove})
            for (const auto f : *list)
              for (const auto& loop : faces_[f].loops) at.insert(at.end(), loop.begin(), loop.end());
          std::sort(at.begin(), at.end());
          at.erase(std::unique(at.begin(), at.end()), at.end());
          o.manifold = pinched(st, at) <= pinched(choice, at);
        }
        other_readings.push_back(std::move(o));
      }
    }
    if (stopped_) {
      complete = false;
      notes.push_back(cellforge::detail::cat("the search of a group of ", std::to_string(G_.size()),
                                             " faces no edge needs stopped after ", std::to_string(nodes_),
                                             " steps (work budget); the best reading found is taken"));
    }
    for (const auto f : G_) local_[f] = no_index;
    std::sort(picked.begin(), picked.end());
    return picked;
  }
  void commit(const std::vector<std::uint32_t>& pick) {
    for (const auto i : pick) drop[i] = 1, kept_cache_[i] = 0;
    for (const auto i : pick) {
      const auto a = merged.find(sides_[i][0]), b = merged.find(sides_[i][1]);
      if (a == b) continue;
      merged.unite(a, b);
      // The survivor takes the other's faces, the shorter list moved into the longer.
      const auto keep = merged.find(a), gone = keep == a ? b : a;
      ambiguous_[keep] = ambiguous_[keep] || ambiguous_[gone];
      if (root_faces_[keep].size() < root_faces_[gone].size())
        std::swap(root_faces_[keep], root_faces_[gone]);
      root_faces_[keep].insert(root_faces_[keep].end(), root_faces_[gone].begin(), root_faces_[gone].end());
      std::vector<std::uint32_t>().swap(root_faces_[gone]);
    }
    const auto o = merged.find(O_);
    for (const auto i : pick) opened[i] = merged.find(sides_[i][0]) == o;
  }
};

}  // namespace detail

namespace detail {
/// What a group's other reading stands for, in words. O(1).
template <class = void>
std::string reading_words(std::size_t add, std::size_t remove, int volumes, reading_key key) {
  static const char* const why[] = {"more faces no edge needs", "the fewest volumes", "the fewest faces",
                                    "the largest area dropped", "nothing: as good in every key"};
  const std::string v = volumes == 0 ? "as many volumes"
                        : volumes > 0
                            ? std::to_string(volumes) + " more volume" + (volumes > 1 ? "s" : "")
                            : std::to_string(-volumes) + " fewer volume" + (volumes < -1 ? "s" : "");
  return cellforge::detail::cat("keeps ", std::to_string(add), " faces the answer drops and drops ",
                                std::to_string(remove), " it keeps (", v, "); set aside by ",
                                why[static_cast<int>(key)]);
}
}  // namespace detail

template <class>
volume_result find_volumes(const wire_graph& g, const std::vector<wire_face>& faces,
                           const volume_options& options) {
  detail::stopwatch clock;
  volume_result r;
  const auto nf = static_cast<std::uint32_t>(faces.size());
  const auto fan = detail::edge_fans(g, faces);

  // Surfaces: faces joined through shared edges; objects: through shared vertices too, so that
  // two solids touching at a vertex are one object.
  detail::union_find surface(nf), object(nf);
  for (const auto& f : fan)
    for (std::size_t k = 1; k < f.size(); ++k) {
      surface.unite(f[0].face, f[k].face);
      object.unite(f[0].face, f[k].face);
    }
  {
    std::vector<std::uint32_t> first(g.num_vertices(), no_index);
    for (std::uint32_t i = 0; i < nf; ++i)
      for (const auto& loop : faces[i].loops)
        for (const auto v : loop) {
          if (first[v] == no_index)
            first[v] = i;
          else
            object.unite(first[v], i);
        }
  }
  std::vector<std::uint32_t> object_id(nf, no_index);
  r.object_of_face.resize(nf);
  for (std::uint32_t i = 0; i < nf; ++i) {
    const auto root = object.find(i);
    if (object_id[root] == no_index) object_id[root] = static_cast<std::uint32_t>(r.objects++);
    r.object_of_face[i] = object_id[root];
  }

  // Shells: side 2i is face i's normal side, 2i+1 the other. Around an edge, the side of a
  // face facing increasing angle is its normal side exactly when it walks the edge forwards.
  detail::union_find side(2 * std::size_t{nf});
  auto side_id = [](std::uint32_t face, int s) { return 2 * face + (s > 0 ? 0u : 1u); };
  for (std::uint32_t e = 0; e < fan.size(); ++e) {
    const auto& f = fan[e];
    for (std::size_t k = 0; k < f.size(); ++k) {
      const auto& a = f[k];
      const auto& b = f[(k + 1) % f.size()];
      if (k + 1 < f.size() && a.angle == b.angle)
        r.diagnostics.push_back(cellforge::detail::cat("faces ", std::to_string(a.face), " and ",
                                                       std::to_string(b.face), " leave edge ",
                                                       std::to_string(e), " at the same angle"));
      side.unite(side_id(a.face, a.walk), side_id(b.face, -b.walk));
    }
  }
  std::vector<std::uint32_t> shell_of(2 * std::size_t{nf}), shell_root_id(2 * std::size_t{nf}, no_index);
  std::vector<double> shell_volume;
  std::vector<std::vector<std::uint32_t>> shell_faces;
  std::vector<std::uint32_t> shell_surface;
  for (std::uint32_t s = 0; s < 2 * nf; ++s) {
    const auto root = side.find(s);
    if (shell_root_id[root] == no_index) {
      shell_root_id[root] = static_cast<std::uint32_t>(shell_volume.size());
      shell_volume.push_back(0.0);
      shell_faces.emplace_back();
      shell_surface.push_back(surface.find(s / 2));
    }
    const auto sh = shell_of[s] = shell_root_id[root];
    const wire_face& f = faces[s / 2];
    // The region on side s has outward normal -s·n there: divergence theorem about the centre.
    const double contribution = glm::dot(area_vector(g, f), g.points[f.loops[0][0]] - g.center) / 3.0;
    shell_volume[sh] += (s % 2 == 0 ? -1.0 : 1.0) * contribution;
    shell_faces[sh].push_back(s / 2);
  }
  r.shells = shell_volume.size();
  r.manifold_milliseconds = clock.ms();

  // Regions: every positive shell bounds one; a negative shell (a surface's outside) belongs
  // to the smallest positive shell of another surface containing it, else to the unbounded
  // region.
  std::vector<std::uint32_t> region_of_shell(r.shells, no_index);
  std::uint32_t regions = 0;
  for (std::size_t s = 0; s < r.shells; ++s)
    if (shell_volume[s] > 0.0) region_of_shell[s] = regions++;
  std::vector<bounding_box> shell_box(r.shells);
  for (std::size_t s = 0; s < r.shells; ++s)
    for (const auto i : shell_faces[s])
      for (const auto v : faces[i].loops[0]) shell_box[s].add(g.points[v]);
  std::vector<std::size_t> positive;
  for (std::size_t s = 0; s < r.shells; ++s)
    if (shell_volume[s] > 0.0) positive.push_back(s);
  std::sort(positive.begin(), positive.end(),
            [&](std::size_t a, std::size_t b) { return shell_volume[a] < shell_volume[b]; });
  std::vector<std::uint32_t> mark(g.num_vertices(), no_index);
  std::uint32_t stamp = 0;
  for (std::size_t s = 0; s < r.shells; ++s) {
    if (shell_volume[s] > 0.0) continue;
    ++r.outside_shells;
    const auto& b = shell_box[s];
    // The smallest positive shell of another surface whose box holds this one's and which
    // contains it (positive is sorted by volume).
    for (const auto t : positive) {
      if (shell_surface[t] == shell_surface[s]) continue;
      const auto& c = shell_box[t];
      if (b.min.x < c.min.x || b.min.y < c.min.y || b.min.z < c.min.z || b.max.x > c.max.x ||
          b.max.y > c.max.y || b.max.z > c.max.z)
        continue;
      if (!detail::surface_inside(g, faces, shell_faces[t], shell_faces[s], mark, stamp++)) continue;
      region_of_shell[s] = region_of_shell[t];
      ++r.nested_shells;
      break;
    }
  }

  // The reading rule. O is the unbounded region, index `regions`.
  const std::uint32_t O = regions;
  std::vector<std::array<std::uint32_t, 2>> sides_of(nf);
  std::vector<char> alive(nf, 0);
  for (std::uint32_t i = 0; i < nf; ++i) {
    for (int k = 0; k < 2; ++k) {
      const auto rg = region_of_shell[shell_of[side_id(i, k == 0 ? 1 : -1)]];
      sides_of[i][static_cast<std::size_t>(k)] = rg == no_index ? O : rg;
    }
    alive[i] = sides_of[i][0] != sides_of[i][1];
  }
  const auto at = detail::faces_at_edges(g, faces, &alive);
  detail::face_reader reader(g, faces, at, sides_of, alive, regions, options.reading);
  reader.readings_per_group = options.alternatives_per_group;
  detail::work_counter budget{options.work_budget, 0, "find_volumes"};
  reader.run(budget);
  r.groups = reader.groups_searched;
  r.readings = reader.readings_certified;
  r.complete = reader.complete;
  r.work = budget.used;
  for (auto& note : reader.notes) r.diagnostics.push_back(std::move(note));
  std::vector<char>& drop = reader.drop;
  detail::union_find& merged = reader.merged;
  for (std::uint32_t i = 0; i < nf; ++i) {
    if (drop[i]) {
      r.dropped.push_back(i);
      volume_alternative a;
      a.add = {i};
      a.reading = reader.opened[i] ? "would close a hole or dent" : "would split a volume in two";
      r.diagnostics.push_back(
          cellforge::detail::cat("face ", std::to_string(i), " (", std::to_string(faces[i].loops[0].size()),
                                 "-gon): no edge needs it, so it is not a face (it ", a.reading, ")"));
      r.alternatives.push_back(std::move(a));
    } else if (reader.unforced[i]) {
      r.unforced.push_back(i);
    }
  }
  for (auto& o : reader.other_readings) {
    volume_alternative a;
    a.add = std::move(o.add);
    a.remove = std::move(o.remove);
    a.set_aside_by = o.key;
    a.undecided = o.key != reading_key::unneeded_faces && o.manifold;
    a.reading = detail::reading_words(a.add.size(), a.remove.size(), o.volumes, o.key);
    r.diagnostics.push_back(cellforge::detail::cat("another reading ", a.reading));
    r.alternatives.push_back(std::move(a));
  }

  // merge_unforced: one kept unforced wall at a time, with every other wall between the same
  // two volumes, when none of those is needed, every edge keeps its faces and the merged
  // volume uses no edge more than twice (two parts of it meeting along an edge).
  if (options.merge_unforced) {
    detail::region_links links(std::size_t{regions} + 1);
    std::vector<char> is_wall(nf, 0);
    for (const auto i : r.unforced) is_wall[i] = sides_of[i][0] != O && sides_of[i][1] != O;
    std::vector<std::vector<std::uint32_t>> bounding(std::size_t{regions} + 1);  // per merged root
    for (std::uint32_t i = 0; i < nf; ++i) {
      if (!alive[i] || drop[i]) continue;
      const auto a = merged.find(sides_of[i][0]), b = merged.find(sides_of[i][1]);
      if (a != b) links.add(a, b, i, is_wall[i] != 0);
      bounding[a].push_back(i);
      bounding[b].push_back(i);
    }
    std::vector<std::uint32_t> kept;
    std::vector<std::uint32_t> uses;
    std::vector<std::array<std::uint32_t, 3>> corners;
    auto normal = [&](std::uint32_t j) { return faces[j].normal; };
    for (const auto i : r.unforced) {
      const auto a = merged.find(sides_of[i][0]), b = merged.find(sides_of[i][1]);
      if (!is_wall[i] || a == b) continue;
      const auto it = links.pairs.find(detail::region_links::key(a, b));
      if (it == links.pairs.end() || it->second.needed != 0) continue;
      const std::vector<std::uint32_t> walls = it->second.walls;
      for (const auto w : walls) drop[w] = 1;  // tentatively: every wall between the two
      bool ok = true;
      for (std::size_t x = 0; x < walls.size() && ok; ++x)
        for (const auto& loop : faces[walls[x]].loops)
          for (std::size_t k = 0; k < loop.size() && ok; ++k) {
            kept.clear();
            for (const auto j : at[g.find_edge(loop[k], loop[(k + 1) % loop.size()])])
              if (!drop[j]) kept.push_back(j);
            ok = !kept.empty() && !detail::edge_needs_more(kept, normal);
          }
      // The merged volume: each of its edges on at most two of its faces, one fan at each vertex.
      uses.clear();
      for (const auto root : {a, b})
        for (const auto j : bounding[root]) {
          if (drop[j]) continue;
          const auto p = merged.find(sides_of[j][0]), q = merged.find(sides_of[j][1]);
          if ((p == a || p == b) != (q == a || q == b)) uses.push_back(j);
        }
      std::sort(uses.begin(), uses.end());
      uses.erase(std::unique(uses.begin(), uses.end()), uses.end());
      ok = ok && detail::manifold_boundary(g, faces, uses, corners);
      if (!ok) {
        for (const auto w : walls) drop[w] = 0;
        continue;
      }
      for (const auto w : walls) {
        r.merged.push_back(w);
        r.diagnostics.push_back(
            cellforge::detail::cat("wall ", std::to_string(w), " merged away (merge_unforced)"));
      }
      links.unite(a, b, merged);
      const auto keep = merged.find(a), gone = keep == a ? b : a;
      if (bounding[keep].size() < bounding[gone].size()) std::swap(bounding[keep], bounding[gone]);
      bounding[keep].insert(bounding[keep].end(), bounding[gone].begin(), bounding[gone].end());
      std::vector<std::uint32_t>().swap(bounding[gone]);
    }
    std::erase_if(r.unforced, [&](std::uint32_t i) { return drop[i] != 0; });
    std::sort(r.merged.begin(), r.merged.end());
  }
  for (const auto i : r.unforced)
    r.diagnostics.push_back(cellforge::detail::cat(
        "face ", std::to_string(i),
        ": no edge needs it; kept, since the wireframe does not decide which such walls go"));

  const std::uint32_t outside = merged.find(O);
  std::vector<std::uint32_t> volume_id(regions + 1, no_index);
  r.face_volumes.resize(nf);
  r.face_kept.assign(nf, 1);
  for (std::uint32_t i = 0; i < nf; ++i) {
    const std::uint32_t a = merged.find(sides_of[i][0]), b = merged.find(sides_of[i][1]);
    if (a == b || drop[i]) {
      r.face_kept[i] = 0;
      if (!alive[i])
        r.diagnostics.push_back(
            cellforge::detail::cat("face ", std::to_string(i), " has the same region on both sides"));
      r.face_volumes[i] = {no_index, no_index};
      continue;
    }
    std::array<std::uint32_t, 2> vol{no_index, no_index};
    const std::uint32_t sides[2] = {a, b};
    for (int k = 0; k < 2; ++k) {
      if (sides[k] == outside) continue;
      if (volume_id[sides[k]] == no_index) {
        volume_id[sides[k]] = static_cast<std::uint32_t>(r.volumes.size());
        r.volumes.emplace_back();
      }
      vol[static_cast<std::size_t>(k)] = volume_id[sides[k]];
      // The volume on the normal side sees the normal pointing in (-1); on the other side out (+1).
      r.volumes[vol[static_cast<std::size_t>(k)]].emplace_back(i, k == 0 ? -1 : 1);
    }
    r.face_volumes[i] = vol;
  }
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
