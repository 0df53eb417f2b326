// SPDX-License-Identifier: MIT
#pragma once
// The engines of grow_selections and cycle_loop (included by thin/selection_growing.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/thin/selection_growing.hpp"

namespace cellforge {

namespace detail::thin {

/// The survivors of one cycle, in order (§5.2 cut, §5.4 schedule, final stable sort).
template <class = void>
std::vector<std::uint32_t> keep_selections(const std::vector<double>& length, double keep_ratio,
                                           std::size_t cap) {
  std::vector<std::uint32_t> kept;
  if (length.empty()) return kept;
  const double least = *std::min_element(length.begin(), length.end());
  const auto cut = [&](double limit) {
    std::erase_if(kept, [&](std::uint32_t i) { return length[i] > limit; });
  };
  kept.resize(length.size());
  std::iota(kept.begin(), kept.end(), 0u);
  cut(keep_ratio * least);
  double t = 0;
  for (int adjust = 0; adjust < 20 && kept.size() > cap; ++adjust) {
    const double ratio = std::min(static_cast<double>(cap) / static_cast<double>(kept.size()), 0.95);
    t = adjust == 0 ? 0.1 * ratio : t * ratio;
    cut((1 + t) * least);
  }
  if (kept.size() > cap) {
    std::stable_sort(kept.begin(), kept.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return length[a] < length[b]; });
    kept.resize(cap);
  }
  return kept;
}

/// Length of parent ∪ {f}: the seed's quick update, in one fixed order shared by both
/// modes (subtract the edges leaving L1, then add those entering, in f's slot order) so
/// that the two modes produce bit-identical sums. `selected(g)` tests the parent.
template <class Selected>
double child_length(const thin_face_graph& g, double parent_length, std::uint32_t f, Selected&& selected) {
  double total = parent_length;
  const std::uint32_t b = g.face_start[f], e = g.face_start[f + 1];
  // An edge used twice by f (a face glued to itself) enters L1 first and then leaves it.
  const auto repeated_before = [&](std::uint32_t s) {
    for (std::uint32_t r = b; r < s; ++r)
      if (g.slot_edge[r] == g.slot_edge[s]) return true;
    return false;
  };
  const auto leaves = [&](std::uint32_t s) {
    const std::uint32_t o = g.slot_other[s];
    return o == f ? repeated_before(s) : selected(o);
  };
  for (std::uint32_t s = b; s < e; ++s)
    if (leaves(s)) total -= g.edge_length[g.slot_edge[s]];
  for (std::uint32_t s = b; s < e; ++s)
    if (!leaves(s)) total += g.edge_length[g.slot_edge[s]];
  return total;
}

/// The first selection of least length in survivor order: the survivors keep generation
/// order (or a stable sort by length), so this is the first least child in generation order.
template <class Selection, class Length>
std::size_t first_least(const std::vector<Selection>& kept, Length&& length) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < kept.size(); ++i)
    if (length(kept[i]) < length(kept[best])) best = i;
  return best;
}

template <class = void>
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// Fast mode's face sets: copy-on-write bitsets in chunks of 64 words (4096 faces) shared
/// between selections through reference counts, so that a child costs one chunk copy and
/// its chunk table, not faces/64 words.
class chunked_sets {
 public:
  static constexpr std::uint32_t words = 64, faces_per_chunk = words * 64;
  explicit chunked_sets(std::uint32_t num_faces)
      : chunks_((num_faces + faces_per_chunk - 1) / faces_per_chunk) {}
  std::uint32_t chunks() const { return chunks_; }
  /// A new set (chunk table written to `table`) holding only face f.
  void make_single(std::uint32_t* table, std::uint32_t f) {
    const std::uint32_t zero = allocate();
    refs_[zero] += chunks_ - 1;  // every chunk but f's shares one zero chunk
    for (std::uint32_t c = 0; c < chunks_; ++c) table[c] = zero;
    const std::uint32_t own = allocate();
    table[f / faces_per_chunk] = own;
    --refs_[zero];
    if (refs_[zero] == 0) free_.push_back(zero);
    word(own, f) |= bit(f);
  }
  /// An empty set (chunk table written to `table`).
  void make_empty(std::uint32_t* table) {
    const std::uint32_t zero = allocate();
    refs_[zero] = chunks_;
    for (std::uint32_t c = 0; c < chunks_; ++c) table[c] = zero;
  }
  /// `table` := parent ∪ {f}. O(chunks + words).
  void make_child(std::uint32_t* table, const std::uint32_t* parent, std::uint32_t f) {
    for (std::uint32_t c = 0; c < chunks_; ++c) ++refs_[table[c] = parent[c]];
    const std::uint32_t c = f / faces_per_chunk, own = allocate();
    std::memcpy(&data_[std::size_t{own} * words], &data_[std::size_t{parent[c]} * words], words * 8);
    release_chunk(parent[c]);
    table[c] = own;
    word(own, f) |= bit(f);
  }
  /// `table` := a copy of `source` (chunks shared). O(chunks).
  void share(std::uint32_t* table, const std::uint32_t* source) {
    for (std::uint32_t c = 0; c < chunks_; ++c) ++refs_[table[c] = source[c]];
  }
  /// Adds f to the set `table`, copying f's chunk first when another set shares it.
  void insert(std::uint32_t* table, std::uint32_t f) {
    std::uint32_t& c = table[f / faces_per_chunk];
    if (refs_[c] > 1) {
      const std::uint32_t own = allocate();
      std::memcpy(&data_[std::size_t{own} * words], &data_[std::size_t{c} * words], words * 8);
      release_chunk(c);
      c = own;
    }
    word(c, f) |= bit(f);
  }
  void release(const std::uint32_t* table) {
    for (std::uint32_t c = 0; c < chunks_; ++c) release_chunk(table[c]);
  }
  bool has(const std::uint32_t* table, std::uint32_t f) const {
    return (data_[std::size_t{table[f / faces_per_chunk]} * words + (f % faces_per_chunk) / 64] >> (f & 63)) &
           1u;
  }
  /// Whether a ∪ {fa} equals b ∪ {fb}; shared chunks are equal without a look.
  bool same(const std::uint32_t* a, std::uint32_t fa, const std::uint32_t* b, std::uint32_t fb) const {
    for (std::uint32_t c = 0; c < chunks_; ++c) {
      const bool ca = fa / faces_per_chunk == c, cb = fb / faces_per_chunk == c;
      if (a[c] == b[c] && !ca && !cb) continue;
      for (std::uint32_t w = 0; w < words; ++w) {
        std::uint64_t x = data_[std::size_t{a[c]} * words + w], y = data_[std::size_t{b[c]} * words + w];
        if (ca && (fa % faces_per_chunk) / 64 == w) x |= bit(fa);
        if (cb && (fb % faces_per_chunk) / 64 == w) y |= bit(fb);
        if (x != y) return false;
      }
    }
    return true;
  }

 private:
  static std::uint64_t bit(std::uint32_t f) { return std::uint64_t{1} << (f & 63); }
  std::uint64_t& word(std::uint32_t chunk, std::uint32_t f) {
    return data_[std::size_t{chunk} * words + (f % faces_per_chunk) / 64];
  }
  std::uint32_t allocate() {
    if (free_.empty()) {
      free_.push_back(static_cast<std::uint32_t>(refs_.size()));
      refs_.push_back(0);
      data_.resize(data_.size() + words, 0);
    }
    const std::uint32_t c = free_.back();
    free_.pop_back();
    refs_[c] = 1;
    std::fill_n(&data_[std::size_t{c} * words], words, std::uint64_t{0});
    return c;
  }
  void release_chunk(std::uint32_t c) {
    if (--refs_[c] == 0) free_.push_back(c);
  }
  std::uint32_t chunks_;
  std::vector<std::uint64_t> data_;
  std::vector<std::uint32_t> refs_, free_;
};

/// Fast mode: a survivor owns a chunk table (its face set), its inner boundary slots, a
/// Zobrist hash and its node in the lineage (growing_result::node_parent/node_face).
struct fast_selection {
  std::uint32_t table = 0;              // offset of its chunk table in the cycle's table array
  std::vector<std::uint32_t> boundary;  // inner slots: face selected, twin face not
  double length = 0;
  std::uint64_t hash = 0;
  std::uint32_t node = 0;
};

struct fast_child {
  std::uint32_t parent, face;
  std::uint64_t hash;
  double length;
};

/// Records a selection in the lineage: its parent node and the face it added.
template <class = void>
std::uint32_t add_node(growing_result& r, std::uint32_t parent, std::uint32_t face) {
  r.node_parent.push_back(parent);
  r.node_face.push_back(face);
  return static_cast<std::uint32_t>(r.node_face.size() - 1);
}

/// Stops the growing at the work budget: flagged incomplete with a diagnostic, not thrown.
template <class = void>
void out_of_budget(growing_result& r, std::uint64_t budget, std::size_t faces) {
  r.complete = false;
  r.diagnostics.push_back(cellforge::detail::cat(
      "the selection growing examined more than ", std::to_string(budget),
      " candidate selections (work_budget) and stopped after cycle ", std::to_string(r.cycle_lengths.size()),
      " of ", std::to_string(faces - 1), "; loops are looked for in the cycles grown"));
}

template <class = void>
growing_result grow_fast(const thin_face_graph& g, std::uint32_t start, const growing_options& o) {
  const std::uint32_t nf = g.num_faces;
  std::vector<std::uint64_t> key(nf);
  for (std::uint32_t f = 0; f < nf; ++f) key[f] = splitmix64(0x7468696E ^ (std::uint64_t{f} << 20) ^ f);
  growing_result r;
  chunked_sets sets(nf);
  const std::uint32_t nc = sets.chunks();
  std::vector<std::uint32_t> tables(nc), next_tables;  // chunk tables of the survivors, nc each
  std::vector<fast_selection> current(1);
  {
    fast_selection& s = current[0];
    sets.make_single(tables.data(), start);
    for (std::uint32_t k = g.face_start[start]; k < g.face_start[start + 1]; ++k)
      if (g.slot_other[k] != start) s.boundary.push_back(k);
    s.length = child_length(g, 0.0, start, [](std::uint32_t) { return false; });
    s.hash = key[start];
    s.node = add_node(r, growing_result::no_node, start);
  }
  const auto record = [&](const fast_selection& s) {
    r.cycle_lengths.push_back(s.length);
    r.cycle_node.push_back(s.node);
  };
  record(current[0]);
  std::vector<std::uint32_t> count(nf, 0), touched, candidates, unique;
  std::vector<fast_child> children;
  std::vector<std::uint32_t> table_of;  // open-addressing hash table of child indices (+1; 0 empty)
  std::vector<double> lengths;
  std::vector<fast_selection> next;
  for (std::uint32_t size = 2; size < nf; ++size) {
    children.clear();
    for (std::uint32_t p = 0; p < current.size(); ++p) {
      const fast_selection& s = current[p];
      const std::uint32_t* t = &tables[s.table];
      // An edge is in L1 exactly when one of its two faces is selected (closed mesh), so
      // counting the outer faces of the boundary slots counts shared edges.
      std::uint32_t most = 0;
      for (const std::uint32_t k : s.boundary) {
        const std::uint32_t out = g.slot_other[k];
        if (count[out]++ == 0) touched.push_back(out);
        most = std::max(most, count[out]);
      }
      candidates.clear();
      for (const std::uint32_t f : touched) {
        if (count[f] == most) candidates.push_back(f);
        count[f] = 0;
      }
      touched.clear();
      std::sort(candidates.begin(), candidates.end());
      for (const std::uint32_t f : candidates)
        children.push_back({p, f, s.hash ^ key[f],
                            child_length(g, s.length, f, [&](std::uint32_t x) { return sets.has(t, x); })});
      r.selections_examined += candidates.size();
    }
    if (r.selections_examined > o.work_budget.limit(~std::uint64_t{0})) {
      out_of_budget(r, o.work_budget, nf);
      break;
    }
    // Duplicates: equal hashes, confirmed by comparing the face sets; the first one stays
    // (children enter the table in generation order, duplicates never enter it).
    std::size_t cap = 16;
    while (cap < 2 * children.size()) cap *= 2;
    table_of.assign(cap, 0);
    unique.clear();
    lengths.clear();
    for (std::uint32_t i = 0; i < children.size(); ++i) {
      const fast_child& c = children[i];
      bool dup = false;
      std::size_t h = static_cast<std::size_t>(c.hash) & (cap - 1);
      for (; table_of[h] != 0; h = (h + 1) & (cap - 1)) {
        const fast_child& d = children[table_of[h] - 1];
        if (d.hash == c.hash &&
            sets.same(&tables[current[c.parent].table], c.face, &tables[current[d.parent].table], d.face)) {
          dup = true;
          break;
        }
      }
      if (dup) continue;
      table_of[h] = i + 1;
      unique.push_back(i);
      lengths.push_back(c.length);
    }
    r.duplicates_dropped += children.size() - unique.size();
    if (unique.empty())
      throw error(error_category::internal,
                  "find_thin_points: the selection stopped growing (disconnected faces)");
    const std::vector<std::uint32_t> kept =
        keep_selections(lengths, o.keep_ratio, static_cast<std::size_t>(o.selection_cap));
    next.clear();
    next_tables.resize(std::size_t{nc} * kept.size());
    for (const std::uint32_t k : kept) {
      const fast_child& c = children[unique[k]];
      const fast_selection& parent = current[c.parent];
      const std::uint32_t* pt = &tables[parent.table];
      fast_selection s;
      s.table = static_cast<std::uint32_t>(next.size() * nc);
      sets.make_child(&next_tables[s.table], pt, c.face);
      s.boundary.reserve(parent.boundary.size() + 4);
      for (const std::uint32_t k2 : parent.boundary)
        if (g.slot_other[k2] != c.face) s.boundary.push_back(k2);
      for (std::uint32_t k2 = g.face_start[c.face]; k2 < g.face_start[c.face + 1]; ++k2) {
        const std::uint32_t o2 = g.slot_other[k2];
        if (o2 != c.face && !sets.has(pt, o2)) s.boundary.push_back(k2);
      }
      s.length = c.length, s.hash = c.hash;
      s.node = add_node(r, parent.node, c.face);
      next.push_back(std::move(s));
    }
    for (const fast_selection& s : current) sets.release(&tables[s.table]);
    std::swap(current, next);
    std::swap(tables, next_tables);
    r.selections_kept += current.size();
    r.max_kept = std::max(r.max_kept, current.size());
    record(current[first_least(current, [](const fast_selection& x) { return x.length; })]);
  }
  return r;
}

/// Scalable mode: a survivor keeps its frontier (the unselected faces next to it) in one
/// min-heap per count of selected neighbours, keyed by (length change, face), with lazy
/// deletion: an entry is live while its face is unselected and still has that count (counts
/// only grow, so a dead entry never revives). A parent's children come out of its top heap in
/// ascending order; the parents' streams are merged, so a cycle looks only at the children it
/// keeps, the duplicates among them and one more.
struct frontier_entry {
  double delta;
  std::uint32_t face;
  friend bool operator>(const frontier_entry& a, const frontier_entry& b) {
    return a.delta > b.delta || (a.delta == b.delta && a.face > b.face);
  }
  friend bool operator<(const frontier_entry& a, const frontier_entry& b) { return b > a; }
};

struct frontier_selection {
  std::vector<std::uint32_t> table;                // chunk table of its face set
  std::vector<std::vector<frontier_entry>> heaps;  // [count] → min-heap of (delta, face)
  std::vector<std::uint32_t> live;                 // [count] → frontier faces with that count
  double length = 0;
  std::uint64_t hash = 0;
  std::uint32_t node = 0;
};

struct frontier_cursor {
  std::uint32_t level = 0;
  std::vector<std::uint32_t> open;
};

struct frontier_child {
  double length;
  std::uint64_t order;  // parent << 32 | face: ties broken by parent, then face
  std::uint32_t parent() const { return static_cast<std::uint32_t>(order >> 32); }
  std::uint32_t face() const { return static_cast<std::uint32_t>(order); }
  friend bool operator>(const frontier_child& a, const frontier_child& b) {
    return a.length != b.length ? a.length > b.length : a.order > b.order;
  }
};

template <class = void>
growing_result grow_scalable(const thin_face_graph& g, std::uint32_t start, const growing_options& o) {
  const std::uint32_t nf = g.num_faces;
  std::vector<std::uint64_t> key(nf);
  for (std::uint32_t f = 0; f < nf; ++f) key[f] = splitmix64(0x7468696E ^ (std::uint64_t{f} << 20) ^ f);
  std::uint32_t levels = 1;
  for (std::uint32_t f = 0; f < nf; ++f) levels = std::max(levels, g.face_start[f + 1] - g.face_start[f] + 1);
  growing_result r;
  chunked_sets sets(nf);
  const auto has = [&](const frontier_selection& s, std::uint32_t f) { return sets.has(s.table.data(), f); };
  // Selected neighbours of an unselected face, counted by shared edges (as the L1 edges count them).
  const auto count = [&](const frontier_selection& s, std::uint32_t f) {
    std::uint32_t n = 0;
    for (std::uint32_t k = g.face_start[f]; k < g.face_start[f + 1]; ++k)
      n += g.slot_other[k] != f && has(s, g.slot_other[k]);
    return n;
  };
  const auto alive = [&](const frontier_selection& s, std::uint32_t c, std::uint32_t f) {
    return !has(s, f) && count(s, f) == c;
  };
  // A heap is rebuilt from its live entries when a fifth of it is dead: enumerating skips
  // dead entries every cycle, rebuilding costs O(size) once per size/5 deaths.
  const auto mostly_dead = [](std::uint32_t live) { return std::size_t{live} + live / 4 + 4; };
  // Adds f: f leaves the frontier, its unselected neighbours move up a count (or enter it)
  // with their new length change (edges they share with the selection leave L1, the others
  // enter). O(degree² + degree · log frontier).
  const auto add = [&](frontier_selection& s, std::uint32_t f) {
    if (const std::uint32_t c = count(s, f); c > 0) {
      --s.live[c];
      std::vector<frontier_entry>& top = s.heaps[c];
      if (!top.empty() && top.front().face == f) {  // the usual case: f was its parent's first child
        std::pop_heap(top.begin(), top.end(), std::greater<>{});
        top.pop_back();
      }
    }
    sets.insert(s.table.data(), f);
    for (std::uint32_t k = g.face_start[f]; k < g.face_start[f + 1]; ++k) {
      const std::uint32_t x = g.slot_other[k];
      bool seen = x == f || has(s, x);
      for (std::uint32_t j = g.face_start[f]; j < k && !seen; ++j) seen = g.slot_other[j] == x;
      if (seen) continue;
      std::uint32_t shared = 0, now = 0;
      double leaving = 0, entering = 0;
      for (std::uint32_t j = g.face_start[x]; j < g.face_start[x + 1]; ++j) {
        const std::uint32_t y = g.slot_other[j];
        shared += y == f;
        bool leaves = y != x && has(s, y);
        now += leaves;
        for (std::uint32_t i = g.face_start[x]; y == x && i < j && !leaves; ++i)
          leaves = g.slot_edge[i] == g.slot_edge[j];  // an edge x uses twice enters, then leaves
        (leaves ? leaving : entering) += g.edge_length[g.slot_edge[j]];
      }
      const std::uint32_t before = now - shared;
      if (before > 0) --s.live[before];
      ++s.live[now];
      std::vector<frontier_entry>& h = s.heaps[now];
      if (h.size() > mostly_dead(s.live[now])) {
        std::erase_if(h, [&](const frontier_entry& e) { return !alive(s, now, e.face); });
        std::make_heap(h.begin(), h.end(), std::greater<>{});
      }
      h.push_back({entering - leaving, x});
      std::push_heap(h.begin(), h.end(), std::greater<>{});
    }
  };
  // Survivors live in a pool; a parent's last kept child takes over its slot (no move), other
  // children take free slots (their vectors' capacity reused).
  std::vector<frontier_selection> pool(1);
  std::vector<std::uint32_t> cur{0}, nxt, free_slots, slot_of;
  {
    frontier_selection& s = pool[0];
    s.table.resize(sets.chunks());
    sets.make_empty(s.table.data());
    s.heaps.resize(levels);
    s.live.assign(levels, 0);
    add(s, start);
    s.length = child_length(g, 0.0, start, [](std::uint32_t) { return false; });
    s.hash = key[start];
    s.node = add_node(r, growing_result::no_node, start);
  }
  r.cycle_lengths.push_back(pool[cur[0]].length);
  r.cycle_node.push_back(pool[cur[0]].node);

  // Per parent: its top count and a heap of indices into that count's heap (enumerates the
  // heap in order without changing it).
  using cursor = frontier_cursor;
  using child = frontier_child;
  std::vector<cursor> cursors;
  std::vector<child> merge, accepted;
  std::vector<std::uint64_t> accepted_hash;
  std::vector<std::uint32_t> last_child, seen_table;
  std::size_t seen_size = 16;
  while (seen_size < 4 * static_cast<std::size_t>(o.selection_cap)) seen_size *= 2;
  const auto next_child = [&](std::uint32_t p) -> bool {
    const frontier_selection& s = pool[cur[p]];
    cursor& cu = cursors[p];
    const std::vector<frontier_entry>& h = s.heaps[cu.level];
    const auto later = [&](std::uint32_t a, std::uint32_t b) { return h[a] > h[b]; };
    while (!cu.open.empty()) {
      std::pop_heap(cu.open.begin(), cu.open.end(), later);
      const std::uint32_t i = cu.open.back();
      cu.open.pop_back();
      for (const std::uint32_t j : {2 * i + 1, 2 * i + 2})
        if (j < h.size()) cu.open.push_back(j), std::push_heap(cu.open.begin(), cu.open.end(), later);
      if (!alive(s, cu.level, h[i].face)) continue;
      const std::uint32_t f = h[i].face;
      merge.push_back({s.length + h[i].delta, std::uint64_t{p} << 32 | f});
      std::push_heap(merge.begin(), merge.end(), std::greater<>{});
      return true;
    }
    return false;
  };
  for (std::uint32_t size = 2; size < nf; ++size) {
    cursors.resize(cur.size());
    merge.clear();
    for (std::uint32_t p = 0; p < cur.size(); ++p) {
      cursor& cu = cursors[p];
      cu.open.clear();
      cu.level = 0;
      for (std::uint32_t c = levels - 1; c > 0 && cu.level == 0; --c)
        if (pool[cur[p]].live[c] > 0) cu.level = c;
      if (cu.level == 0) continue;
      std::vector<frontier_entry>& h = pool[cur[p]].heaps[cu.level];
      if (h.size() > mostly_dead(pool[cur[p]].live[cu.level])) {
        std::erase_if(h, [&](const frontier_entry& e) { return !alive(pool[cur[p]], cu.level, e.face); });
        std::make_heap(h.begin(), h.end(), std::greater<>{});
      }
      // Dead entries below the first live one go for good (the chosen faces sit there).
      while (!h.empty() && !alive(pool[cur[p]], cu.level, h.front().face)) {
        std::pop_heap(h.begin(), h.end(), std::greater<>{});
        h.pop_back();
      }
      if (h.empty()) continue;
      // The top entry is live: the parent's first child, without the cursor's heap.
      for (const std::uint32_t j : {1u, 2u})
        if (j < h.size()) cu.open.push_back(j);
      if (cu.open.size() == 2 && h[2] < h[1]) std::swap(cu.open[0], cu.open[1]);  // a 2-element heap
      merge.push_back({pool[cur[p]].length + h[0].delta, std::uint64_t{p} << 32 | h[0].face});
    }
    std::make_heap(merge.begin(), merge.end(), std::greater<>{});
    // Children in ascending length (ties: parent, face); the first is the least; stop past
    // keep_ratio × least or with selection_cap distinct selections.
    accepted.clear();
    accepted_hash.clear();
    seen_table.assign(seen_size, 0);
    double least = 0;
    while (!merge.empty() && accepted.size() < static_cast<std::size_t>(o.selection_cap)) {
      std::pop_heap(merge.begin(), merge.end(), std::greater<>{});
      const child c = merge.back();
      merge.pop_back();
      ++r.selections_examined;
      if (accepted.empty()) least = c.length;
      if (c.length > o.keep_ratio * least) break;
      // Duplicates: equal hashes confirmed by comparing face sets (open addressing).
      const std::uint32_t p = c.parent(), f = c.face();
      const std::uint64_t h = pool[cur[p]].hash ^ key[f];
      std::size_t at = static_cast<std::size_t>(h) & (seen_size - 1);
      bool dup = false;
      for (; seen_table[at] != 0 && !dup; at = (at + 1) & (seen_size - 1)) {
        const child& d = accepted[seen_table[at] - 1];
        dup = accepted_hash[seen_table[at] - 1] == h &&
              sets.same(pool[cur[p]].table.data(), f, pool[cur[d.parent()]].table.data(), d.face());
      }
      if (dup) {
        ++r.duplicates_dropped;
      } else {
        accepted.push_back(c), accepted_hash.push_back(h);
        seen_table[at] = static_cast<std::uint32_t>(accepted.size());
      }
      next_child(p);
    }
    if (r.selections_examined > o.work_budget.limit(~std::uint64_t{0})) {
      out_of_budget(r, o.work_budget, nf);
      break;
    }
    if (accepted.empty())
      throw error(error_category::internal,
                  "find_thin_points: the selection stopped growing (disconnected faces)");
    // Survivors in accepted order; a parent's last child takes over its slot, others copy it.
    last_child.assign(cur.size(), 0xFFFFFFFF);
    for (std::uint32_t i = 0; i < accepted.size(); ++i) last_child[accepted[i].parent()] = i;
    slot_of.resize(accepted.size());
    for (std::uint32_t i = 0; i < accepted.size(); ++i) {
      const std::uint32_t p = accepted[i].parent();
      if (last_child[p] == i) {
        slot_of[i] = cur[p];
      } else if (!free_slots.empty()) {
        slot_of[i] = free_slots.back();
        free_slots.pop_back();
      } else {
        slot_of[i] = static_cast<std::uint32_t>(pool.size());
        pool.emplace_back();
      }
    }
    nxt.clear();
    for (std::uint32_t i = 0; i < accepted.size(); ++i) {
      const child& c = accepted[i];
      const frontier_selection& parent = pool[cur[c.parent()]];
      frontier_selection& s = pool[slot_of[i]];
      const std::uint32_t parent_node = parent.node;
      const std::uint64_t parent_hash = parent.hash;
      if (last_child[c.parent()] != i) {
        s.table.resize(sets.chunks());
        sets.share(s.table.data(), parent.table.data());
        s.heaps.resize(levels);
        for (std::uint32_t l = 0; l < levels; ++l) s.heaps[l] = parent.heaps[l];
        s.live = parent.live;
      }
      add(s, c.face());
      s.length = c.length, s.hash = parent_hash ^ key[c.face()];
      s.node = add_node(r, parent_node, c.face());
      nxt.push_back(slot_of[i]);
    }
    for (std::uint32_t p = 0; p < cur.size(); ++p)
      if (last_child[p] == 0xFFFFFFFF) sets.release(pool[cur[p]].table.data()), free_slots.push_back(cur[p]);
    std::swap(cur, nxt);
    r.selections_kept += cur.size();
    r.max_kept = std::max(r.max_kept, cur.size());
    std::size_t best = 0;
    for (std::size_t i = 1; i < cur.size(); ++i)
      if (pool[cur[i]].length < pool[cur[best]].length) best = i;  // the first least
    r.cycle_lengths.push_back(pool[cur[best]].length);
    r.cycle_node.push_back(pool[cur[best]].node);
  }
  for (const std::uint32_t k : cur) sets.release(pool[k].table.data());
  return r;
}

/// Faithful mode: the seed's selection record.
struct faithful_selection {
  std::vector<char> selected;     // Boolean array over the faces
  std::vector<std::uint32_t> l1;  // edges adjacent to one selected face
  std::vector<std::uint32_t> l2;  // edges adjacent to two selected faces
  double total = 0;
};

/// Inserts face f's edges: not in a list → L1 (added); in L1 → moved to L2 (removed).
template <class = void>
void insert_face(const thin_face_graph& g, faithful_selection& s, std::uint32_t f,
                 std::vector<std::uint32_t>& added, std::vector<std::uint32_t>& removed) {
  added.clear(), removed.clear();
  for (std::uint32_t k = g.face_start[f]; k < g.face_start[f + 1]; ++k) {
    const std::uint32_t e = g.slot_edge[k];
    if (const auto it = std::find(s.l1.begin(), s.l1.end(), e); it != s.l1.end()) {
      s.l1.erase(it);
      s.l2.push_back(e);
      removed.push_back(e);
    } else if (std::find(s.l2.begin(), s.l2.end(), e) == s.l2.end()) {
      s.l1.push_back(e);
      added.push_back(e);
    }
  }
  s.selected[f] = 1;
  // The seed's quick total: subtract what left L1, add what entered.
  for (const std::uint32_t e : removed) s.total -= g.edge_length[e];
  for (const std::uint32_t e : added) s.total += g.edge_length[e];
}

template <class = void>
growing_result grow_faithful(const thin_face_graph& g, std::uint32_t start, const growing_options& o) {
  const std::uint32_t nf = g.num_faces;
  growing_result r;
  std::vector<std::uint32_t> added, removed;
  std::vector<faithful_selection> current(1);
  current[0].selected.assign(nf, 0);
  insert_face(g, current[0], start, added, removed);
  const auto record = [&](const faithful_selection& s) {
    r.cycle_lengths.push_back(s.total);
    std::vector<std::uint32_t> loop;
    for (const std::uint32_t e : s.l1)
      for (const std::uint32_t k : g.edge_slots[e])
        if (s.selected[g.slot_face[k]]) loop.push_back(k);
    std::sort(loop.begin(), loop.end());
    r.cycle_loops.push_back(std::move(loop));
  };
  record(current[0]);
  std::vector<faithful_selection> stored;
  std::vector<double> lengths;
  for (std::uint32_t size = 2; size < nf; ++size) {
    stored.clear();
    for (const faithful_selection& s : current) {
      // Unselected faces adjacent to the most selected faces, by scanning every face.
      std::vector<std::uint32_t> adjacent(nf, 0);
      std::uint32_t most = 0;
      for (std::uint32_t f = 0; f < nf; ++f) {
        if (s.selected[f]) continue;
        for (std::uint32_t k = g.face_start[f]; k < g.face_start[f + 1]; ++k)
          if (g.slot_other[k] != f && s.selected[g.slot_other[k]]) ++adjacent[f];
        most = std::max(most, adjacent[f]);
      }
      for (std::uint32_t f = 0; f < nf && most > 0; ++f) {
        if (s.selected[f] || adjacent[f] != most) continue;
        ++r.selections_examined;
        std::vector<char> candidate = s.selected;
        candidate[f] = 1;
        const bool seen = std::any_of(stored.begin(), stored.end(),
                                      [&](const faithful_selection& t) { return t.selected == candidate; });
        if (seen) {
          ++r.duplicates_dropped;
          continue;
        }
        faithful_selection child = s;
        insert_face(g, child, f, added, removed);
        stored.push_back(std::move(child));
      }
    }
    if (r.selections_examined > o.work_budget.limit(~std::uint64_t{0})) {
      out_of_budget(r, o.work_budget, nf);
      break;
    }
    if (stored.empty())
      throw error(error_category::internal,
                  "find_thin_points: the selection stopped growing (disconnected faces)");
    lengths.clear();
    for (const faithful_selection& s : stored) lengths.push_back(s.total);
    const std::vector<std::uint32_t> kept =
        keep_selections(lengths, o.keep_ratio, static_cast<std::size_t>(o.selection_cap));
    current.clear();
    for (const std::uint32_t k : kept) current.push_back(std::move(stored[k]));
    r.selections_kept += current.size();
    r.max_kept = std::max(r.max_kept, current.size());
    record(current[first_least(current, [](const faithful_selection& x) { return x.total; })]);
  }
  return r;
}

}  // namespace detail::thin

template <class>
growing_result grow_selections(const thin_face_graph& g, std::uint32_t start, const growing_options& o) {
  const auto bad = [](const std::string& what) {
    throw error(error_category::invalid_input, cellforge::detail::cat("grow_selections: ", what));
  };
  if (start >= g.num_faces)
    bad(cellforge::detail::cat("start face ", std::to_string(start), " is not below the face count ",
                               std::to_string(g.num_faces)));
  // The graph must describe a closed surface: slots paired by edge, each seeing the other's face.
  const std::size_t slots = g.slot_edge.size();
  if (g.face_start.size() != std::size_t{g.num_faces} + 1 || g.face_start.front() != 0 ||
      g.face_start.back() != slots || g.slot_other.size() != slots || g.slot_face.size() != slots ||
      g.edge_slots.size() != g.edge_length.size() ||
      !std::is_sorted(g.face_start.begin(), g.face_start.end()))
    bad("the face graph's arrays have inconsistent sizes");
  if (g.num_faces < 2) bad("a closed surface needs at least two faces");
  for (std::uint32_t f = 0; f < g.num_faces; ++f)
    for (std::uint32_t k = g.face_start[f]; k < g.face_start[f + 1]; ++k)
      if (g.slot_face[k] != f)
        bad(cellforge::detail::cat("slot ", std::to_string(k), " does not belong to face ",
                                   std::to_string(f)));
  for (std::uint32_t k = 0; k < slots; ++k) {
    const std::uint32_t e = g.slot_edge[k];
    if (e >= g.edge_slots.size() || !(g.edge_length[e] >= 0) || !std::isfinite(g.edge_length[e]))
      bad(cellforge::detail::cat("slot ", std::to_string(k), " has an invalid edge or edge length"));
    const auto& two = g.edge_slots[e];
    const std::uint32_t twin = two[0] == k ? two[1] : two[0];
    if ((two[0] != k && two[1] != k) || twin == k || twin >= slots || g.slot_edge[twin] != e ||
        g.slot_other[k] != g.slot_face[twin])
      bad(cellforge::detail::cat("slot ", std::to_string(k),
                                 " is not paired with the other face of its edge (an open or broken graph)"));
  }
  const thin_mode mode = o.mode != thin_mode::automatic   ? o.mode
                         : g.num_faces > o.scalable_above ? thin_mode::scalable
                                                          : thin_mode::fast;
  switch (mode) {
    case thin_mode::fast:
      return detail::thin::grow_fast(g, start, o);
    case thin_mode::scalable: {
      growing_result r = detail::thin::grow_scalable(g, start, o);
      // Said, since its loops may differ from the seed's rule on some solids (docs/thin.md).
      if (o.mode == thin_mode::automatic)
        r.diagnostics.push_back(cellforge::detail::cat(
            "the selection growing used the scalable rule (", std::to_string(g.num_faces),
            " faces, above scalable_above = ", std::to_string(o.scalable_above),
            "); mode = fast keeps the seed's rule at any size"));
      return r;
    }
    default:
      return detail::thin::grow_faithful(g, start, o);
  }
}

template <class>
std::vector<std::uint32_t> cycle_loop(const thin_face_graph& g, const growing_result& r, std::size_t cycle) {
  if (cycle < 1 || cycle > r.cycle_lengths.size())
    throw error(error_category::invalid_input,
                cellforge::detail::cat("cycle_loop: cycle ", std::to_string(cycle), " is not in 1..",
                                       std::to_string(r.cycle_lengths.size())));
  if (!r.cycle_loops.empty()) return r.cycle_loops[cycle - 1];
  std::vector<char> selected(g.num_faces, 0);
  for (std::uint32_t n = r.cycle_node[cycle - 1]; n != growing_result::no_node; n = r.node_parent[n])
    selected[r.node_face[n]] = 1;
  std::vector<std::uint32_t> loop;
  for (std::uint32_t k = 0; k < g.slot_face.size(); ++k)
    if (selected[g.slot_face[k]] && !selected[g.slot_other[k]]) loop.push_back(k);
  return loop;
}

}  // namespace cellforge
