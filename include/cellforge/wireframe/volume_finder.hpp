// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 7 of the wireframe pipeline (seed 000 §4.7): objects and volumes. The seed walks
/// from the leftmost face and chooses the next face around an edge by a "turn direction",
/// which fails when two of its vectors are parallel (fig. 24, patched there by nudging
/// coordinates). Here the same choice — the next face in rotation order around the edge — is
/// made for every face side at once, so no turn direction is ever needed: sort the faces
/// around each edge by angle; the side of one face facing the next face continues the same
/// shell. Connected face sides are shells; a shell of negative signed volume is a surface's
/// outside and bounds no volume (the seed's outside-surface removal); an outside surface
/// nested in another surface's volume (a solid in a cavity) becomes part of that volume's
/// boundary, found by an exact point-in-solid test. Then the reading rule (docs/wireframe.md)
/// drops the faces no edge needs — the mouths of holes and dents, walls such as the square
/// under a roof — and joins the regions on their sides.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/polygon_intersection.hpp"
#include "cellforge/wireframe/circuit_tracer.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// How the faces no edge needs are read (docs/wireframe.md, "The reading rule").
enum class face_reading : std::uint8_t {
  /// A face only where some edge needs it: holes and dents stay open, walls no edge needs
  /// go (the square under a roof), except where the wireframe cannot decide which to drop
  /// (the inner walls of a grid): those stay and are reported as unforced. The default.
  needed,
  /// As `needed`, but every wall between two volumes stays (and is reported as unforced):
  /// the seed's reading of its sample 6, a vase cut into 13 volumes by its rings.
  keep_walls,
  /// Every selected face stays: holes and dents are plugged, every wall is kept.
  keep_all,
};

/// Options of find_volumes.
struct volume_options {
  face_reading reading = face_reading::needed;
  /// Also merge the volumes on both sides of the walls the reading kept although no edge needs
  /// them (reported in volume_result::unforced), one wall at a time and only while no needed
  /// face ends up inside a volume and no edge is left on fewer than two faces or on two
  /// coplanar ones; the walls merged are listed in volume_result::merged.
  bool merge_unforced = false;
  /// Abstract steps of the reading rule's rounds (faces looked at); 0 = none.
  std::uint64_t work_budget = 200'000'000;
};

/// One face around an edge: the face, and +1 when it walks the edge from start to end.
struct edge_fan_entry {
  std::uint32_t face = 0;
  int walk = 0;
  double angle = 0.0;  ///< right-hand angle about the edge (start → end), in (-π, π]
};

/// Objects, shells and volumes of a set of faces.
struct volume_result : stage_report {
  std::size_t objects = 0;
  std::vector<std::uint32_t> object_of_face;
  std::size_t shells = 0, outside_shells = 0, nested_shells = 0;
  /// Per face: the volume on its normal's side and on the other side (no_index: outside).
  std::vector<std::array<std::uint32_t, 2>> face_volumes;
  /// Per volume: (face, +1 when the face's normal points out of the volume, -1 when in).
  std::vector<std::vector<std::pair<std::uint32_t, int>>> volumes;
  std::vector<char>
      face_kept;  ///< false for faces the reading dropped, merged or with one region on both sides
  std::vector<std::uint32_t> unforced;  ///< kept faces no edge needs: the wireframe does not decide them
  std::vector<std::uint32_t> dropped;  ///< faces no edge needs that the reading removed (holes, roofs, rings)
  std::vector<std::uint32_t> merged;   ///< walls merge_unforced removed
  /// Per dropped face (same order): the other reading it stands for, "would close a hole or
  /// dent" or "would split a volume in two".
  std::vector<std::string> alternatives;
  double manifold_milliseconds = 0.0;  ///< the seed's "manifold analysis" row: rotation order and shells
};

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
    const glm::dvec3 x = any_perpendicular(d), y = glm::cross(d, x);
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
/// edge needs are not faces, in rounds. Each round takes the faces no edge needs among those
/// still kept and groups the bounded regions they join: a group with such a face on the
/// outside is a hole, dent or tunnel and opens (its regions join the outside), unless a wall
/// inside it is a seam (grid-like, undecidable: kept); a group without one becomes one volume
/// (face_reading::needed only). The round's drops are taken back group by group while any
/// would leave an edge on fewer than two faces or two coplanar ones, or a kept face with one
/// region on both sides; an open group that fails may still merge its inner walls. When no
/// group can go as a batch, the groups that fill a hole at odd depth in their plane are tried
/// one at a time (the mouth around a box standing in a frame's hole goes, the box's top
/// stays). Dropping faces makes the rest only more needed, so rounds end. O(rounds · Σ L · k).
template <class>
class basic_face_reader {
 public:
  std::vector<char> drop, opened, unforced;  // per face
  union_find merged;                         // regions, O = regions; joined across drops

  basic_face_reader(const wire_graph& g, const std::vector<wire_face>& faces, const edge_face_lists& at,
                    const std::vector<std::array<std::uint32_t, 2>>& sides, const std::vector<char>& alive,
                    std::uint32_t regions, face_reading reading)
      : drop(faces.size(), 0),
        opened(faces.size(), 0),
        unforced(faces.size(), 0),
        merged(std::size_t{regions} + 1),
        g_(g),
        faces_(faces),
        at_(at),
        sides_(sides),
        alive_(alive),
        O_(regions),
        reading_(reading),
        root_faces_(std::size_t{regions} + 1) {
    for (std::uint32_t i = 0; i < faces.size(); ++i)
      if (alive[i])
        for (const auto rg : sides[i]) root_faces_[rg].push_back(i);
  }

  void run(work_budget& budget) {
    if (reading_ == face_reading::keep_all) return mark_unforced();
    const std::size_t nf = faces_.size();
    for (;;) {
      budget.spend(nf);
      mark_unforced();
      // Groups of the current (merged) regions joined by unforced walls.
      union_find group(merged.parent.size());
      const std::uint32_t outside = merged.find(O_);
      auto root = [&](std::uint32_t rg) { return merged.find(rg); };
      for (std::uint32_t i = 0; i < nf; ++i)
        if (unforced[i] && root(sides_[i][0]) != outside && root(sides_[i][1]) != outside)
          group.unite(root(sides_[i][0]), root(sides_[i][1]));
      auto group_of = [&](std::uint32_t i) {
        return group.find(root(sides_[i][root(sides_[i][0]) != outside ? 0 : 1]));
      };
      std::vector<char> opens(group.parent.size(), 0), seam(group.parent.size(), 0),
          odd(group.parent.size(), 0);
      std::vector<std::uint32_t> groups;
      for (std::uint32_t i = 0; i < nf; ++i) {
        if (!unforced[i]) continue;
        const auto gr = group_of(i);
        groups.push_back(gr);
        if (root(sides_[i][0]) == outside || root(sides_[i][1]) == outside) {
          opens[gr] = 1;
          odd[gr] = odd[gr] || faces_[i].depth % 2 == 1;
        } else if (is_seam(i)) {
          seam[gr] = 1;
        }
      }
      std::sort(groups.begin(), groups.end());
      groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
      // 2: open (every unforced face of the group goes), 1: merge (only its walls go), 0: keep.
      std::vector<int> mode(group.parent.size(), 0);
      for (const auto gr : groups)
        mode[gr] = opens[gr] ? (seam[gr] ? 0 : 2) : (reading_ == face_reading::needed ? 1 : 0);
      if (reading_ == face_reading::keep_walls)
        for (const auto gr : groups)
          if (!opens[gr]) mode[gr] = 0;
      auto picks = [&](const std::vector<int>& m) {
        std::vector<std::uint32_t> faces;
        for (std::uint32_t i = 0; i < nf; ++i) {
          if (!unforced[i]) continue;
          const int md = m[group_of(i)];
          const bool wall = root(sides_[i][0]) != outside && root(sides_[i][1]) != outside;
          if (md == 2 || (md == 1 && wall)) faces.push_back(i);
        }
        return faces;
      };
      // The batch: take back failing groups (an open one may still merge) until it holds.
      const std::vector<int> first = mode;
      for (;;) {
        std::vector<std::uint32_t> failed;
        const auto pick = picks(mode);
        budget.spend(pick.size() + 1);
        check(pick, [&](std::uint32_t i) { failed.push_back(group_of(i)); });
        if (failed.empty()) break;
        std::sort(failed.begin(), failed.end());
        failed.erase(std::unique(failed.begin(), failed.end()), failed.end());
        for (const auto gr : failed) mode[gr] = mode[gr] == 2 ? 1 : 0;
      }
      const auto batch = picks(mode);
      if (!batch.empty()) {
        commit(batch);
        continue;
      }
      // Nothing goes as a batch: the hole fillers at odd depth, one group at a time.
      bool done = true;
      for (const auto gr : groups) {
        if (first[gr] != 2 || !odd[gr]) continue;
        std::vector<int> one(group.parent.size(), 0);
        one[gr] = 2;
        const auto pick = picks(one);
        bool ok = true;
        budget.spend(pick.size() + 1);
        check(pick, [&](std::uint32_t) { ok = false; });
        if (!ok) continue;
        commit(pick);
        done = false;
        break;
      }
      if (done) break;
    }
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
  std::vector<std::uint32_t> scratch_;

  bool kept(std::uint32_t i) const { return alive_[i] && !drop[i]; }
  /// unforced[i]: kept, and needed by no edge among the kept faces.
  void mark_unforced() {
    std::vector<char> k(faces_.size(), 0);
    for (std::uint32_t i = 0; i < faces_.size(); ++i) k[i] = kept(i);
    for (std::uint32_t i = 0; i < faces_.size(); ++i)
      unforced[i] = k[i] && !needed_faces_one(g_, faces_, at_, k, i, scratch_);
  }
  /// A seam continues, at every edge, in the plane of another kept face: a wall among walls.
  bool is_seam(std::uint32_t i) const {
    for (const auto& loop : faces_[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        bool flat = false;
        for (const auto j : at_[g_.find_edge(loop[k], loop[(k + 1) % loop.size()])])
          flat = flat || (j != i && kept(j) && coplanar_normals(faces_[i].normal, faces_[j].normal));
        if (!flat) return false;
      }
    return true;
  }
  /// Calls blame(face) for faces of `pick` whose drop, with the others, would leave one of
  /// its edges on fewer than two kept faces or two coplanar ones, or a kept face with one
  /// region on both sides. Local: the pick's edges and the faces of the regions it joins.
  template <class Blame>
  void check(const std::vector<std::uint32_t>& pick, Blame&& blame) {
    if (pick.empty()) return;
    for (const auto i : pick) drop[i] = 1;
    std::vector<std::uint32_t> keep;
    auto normal = [&](std::uint32_t j) { return faces_[j].normal; };
    for (const auto i : pick) {
      bool bad = false;
      for (const auto& loop : faces_[i].loops)
        for (std::size_t k = 0; k < loop.size() && !bad; ++k) {
          keep.clear();
          for (const auto j : at_[g_.find_edge(loop[k], loop[(k + 1) % loop.size()])])
            if (kept(j)) keep.push_back(j);
          bad = keep.empty() || edge_needs_more(keep, normal);
        }
      if (bad) blame(i);
    }
    // The merge the pick makes, on the roots it touches only.
    std::vector<std::uint32_t> touched;
    for (const auto i : pick)
      for (const auto rg : sides_[i]) touched.push_back(merged.find(rg));
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    auto index = [&](std::uint32_t rg) {
      const auto root = merged.find(rg);
      const auto it = std::lower_bound(touched.begin(), touched.end(), root);
      return it != touched.end() && *it == root ? static_cast<std::uint32_t>(it - touched.begin()) : no_index;
    };
    union_find local(touched.size());
    std::vector<std::vector<std::uint32_t>> picked_at(touched.size());
    for (const auto i : pick) {
      local.unite(index(sides_[i][0]), index(sides_[i][1]));
      for (const auto rg : sides_[i]) picked_at[index(rg)].push_back(i);
    }
    // A kept face joined to itself has both sides among the touched roots, one of them not
    // the outside (no kept face has the outside on both sides).
    const std::uint32_t outside = merged.find(O_);
    for (std::uint32_t t = 0; t < touched.size(); ++t) {
      if (touched[t] == outside) continue;
      for (const auto f : root_faces_[touched[t]]) {
        if (!kept(f)) continue;
        const auto a = index(sides_[f][0]), b = index(sides_[f][1]);
        if (a == no_index || b == no_index || local.find(a) != local.find(b)) continue;
        for (const auto i : picked_at[a]) blame(i);
        for (const auto i : picked_at[b]) blame(i);
      }
    }
    for (const auto i : pick) drop[i] = 0;
  }
  void commit(const std::vector<std::uint32_t>& pick) {
    const std::uint32_t outside = merged.find(O_);
    for (const auto i : pick) {
      drop[i] = 1;
      opened[i] = merged.find(sides_[i][0]) == outside || merged.find(sides_[i][1]) == outside;
    }
    for (const auto i : pick) {
      const auto a = merged.find(sides_[i][0]), b = merged.find(sides_[i][1]);
      if (a == b) continue;
      merged.unite(a, b);
      // The survivor takes the other's faces, the shorter list moved into the longer.
      const auto keep = merged.find(a), gone = keep == a ? b : a;
      if (root_faces_[keep].size() < root_faces_[gone].size())
        std::swap(root_faces_[keep], root_faces_[gone]);
      root_faces_[keep].insert(root_faces_[keep].end(), root_faces_[gone].begin(), root_faces_[gone].end());
      std::vector<std::uint32_t>().swap(root_faces_[gone]);
    }
  }
};

}  // namespace detail

/// Finds objects and volumes and applies the reading rule to the faces no edge needs (see the
/// file comment and docs/wireframe.md). O(Σ L + E·k log k) for the shells and the rule, plus
/// the exact nesting tests when several surfaces may nest (O(surfaces · shells) box tests and
/// O(Σ L) per test).
template <class = void>
volume_result find_volumes(const wire_graph& g, const std::vector<wire_face>& faces,
                           const volume_options& options = {}) {
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
        r.diagnostics.push_back("faces " + std::to_string(a.face) + " and " + std::to_string(b.face) +
                                " leave edge " + std::to_string(e) + " at the same angle");
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
  detail::work_budget budget{options.work_budget, 0, "find_volumes"};
  reader.run(budget);
  std::vector<char>& drop = reader.drop;
  detail::union_find& merged = reader.merged;
  for (std::uint32_t i = 0; i < nf; ++i) {
    if (drop[i]) {
      r.dropped.push_back(i);
      r.alternatives.push_back(reader.opened[i] ? "would close a hole or dent"
                                                : "would split a volume in two");
      r.diagnostics.push_back("face " + std::to_string(i) + " (" + std::to_string(faces[i].loops[0].size()) +
                              "-gon): no edge needs it, so it is not a face (it " + r.alternatives.back() +
                              ")");
    } else if (reader.unforced[i]) {
      r.unforced.push_back(i);
    }
  }

  // merge_unforced: one kept unforced wall at a time, with every other wall between the same
  // two volumes, when none of those is needed and every edge keeps its faces.
  if (options.merge_unforced) {
    detail::region_links links(std::size_t{regions} + 1);
    std::vector<char> is_wall(nf, 0);
    for (const auto i : r.unforced) is_wall[i] = sides_of[i][0] != O && sides_of[i][1] != O;
    for (std::uint32_t i = 0; i < nf; ++i) {
      if (!alive[i] || drop[i]) continue;
      const auto a = merged.find(sides_of[i][0]), b = merged.find(sides_of[i][1]);
      if (a != b) links.add(a, b, i, is_wall[i] != 0);
    }
    std::vector<std::uint32_t> kept;
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
      if (!ok) {
        for (const auto w : walls) drop[w] = 0;
        continue;
      }
      for (const auto w : walls) {
        r.merged.push_back(w);
        r.diagnostics.push_back("wall " + std::to_string(w) + " merged away (merge_unforced)");
      }
      links.unite(a, b, merged);
    }
    std::erase_if(r.unforced, [&](std::uint32_t i) { return drop[i] != 0; });
    std::sort(r.merged.begin(), r.merged.end());
  }
  for (const auto i : r.unforced)
    r.diagnostics.push_back(
        "face " + std::to_string(i) +
        ": no edge needs it; kept, since the wireframe does not decide which such walls go");

  const std::uint32_t outside = merged.find(O);
  std::vector<std::uint32_t> volume_id(regions + 1, no_index);
  r.face_volumes.resize(nf);
  r.face_kept.assign(nf, 1);
  for (std::uint32_t i = 0; i < nf; ++i) {
    const std::uint32_t a = merged.find(sides_of[i][0]), b = merged.find(sides_of[i][1]);
    if (a == b || drop[i]) {
      r.face_kept[i] = 0;
      if (!alive[i])
        r.diagnostics.push_back("face " + std::to_string(i) + " has the same region on both sides");
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
