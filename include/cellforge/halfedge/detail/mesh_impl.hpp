// SPDX-License-Identifier: MIT
#pragma once
// Out-of-class definitions of halfedge_mesh's editing operations (included by mesh.hpp).

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

namespace detail {
template <class = void>
std::string vtx(std::uint32_t v) {
  return cellforge::detail::cat("vertex ", std::to_string(v));
}
template <class = void>
std::string edge_name(std::uint32_t a, std::uint32_t b) {
  return cellforge::detail::cat("edge (", std::to_string(a), ", ", std::to_string(b), ")");
}
// True when the indices are pairwise distinct; O(n^2) for small n, O(n log n) otherwise.
template <class T>
bool all_distinct(std::span<const T> xs) {
  if (xs.size() <= 16) {
    for (std::size_t i = 1; i < xs.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (xs[i] == xs[j]) return false;
    return true;
  }
  // Filled by push_back: g++ 12 -O2 misreads the range constructor here (-Wfree-nonheap-object).
  std::vector<T> c;
  c.reserve(xs.size());
  for (const T& x : xs) c.push_back(x);
  std::sort(c.begin(), c.end());
  return std::adjacent_find(c.begin(), c.end()) == c.end();
}
// The error for a third face on the edge (lo, hi): corners a and b already pair on it, c is
// a third. Out of line so that build's matching loop stays small.
template <class = void>
[[noreturn]] void throw_third_face(std::span<const std::uint32_t> offsets, std::uint32_t lo, std::uint32_t hi,
                                   std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const auto face_of = [&](std::uint32_t x) {
    return std::to_string(std::upper_bound(offsets.begin(), offsets.end(), x) - offsets.begin() - 1);
  };
  throw error(
      error_category::topology,
      cellforge::detail::cat("build: ", edge_name(lo, hi), " is used by faces ", face_of(a), ", ", face_of(b),
                             " and ", face_of(c), "; a half-edge mesh allows at most two faces per edge"));
}
// The error for face f (its vertices `face`, nv vertices in all) that uses a vertex out of
// range or repeats one. Out of line so that build's counting loop stays small.
template <class = void>
[[noreturn]] void throw_bad_face(std::size_t f, std::span<const std::uint32_t> face, std::size_t nv) {
  for (std::uint32_t v : face)
    if (v >= nv)
      throw error(
          error_category::invalid_input,
          cellforge::detail::cat("build: face ", std::to_string(f), " uses vertex ", std::to_string(v),
                                 ", but there are only ", std::to_string(nv), " vertices"));
  throw error(error_category::invalid_input,
              cellforge::detail::cat("build: face ", std::to_string(f), " repeats a vertex"));
}
}  // namespace detail

template <class Unused>
halfedge_handle basic_halfedge_mesh<Unused>::find_halfedge(vertex_handle a, vertex_handle b) const noexcept {
  for (halfedge_handle h : halfedges_around(a)) {
    if (head(h) == b && tail(h) == a) return h;
    if (head(twin(h)) == b && tail(twin(h)) == a) return twin(h);
  }
  return {};
}

template <class Unused>
edge_handle basic_halfedge_mesh<Unused>::find_edge(vertex_handle a, vertex_handle b) const noexcept {
  for (edge_handle e : edges_around(a)) {
    const halfedge_handle h = halfedge(e, 0);
    if ((head(h) == b && tail(h) == a) || (head(h) == a && tail(h) == b)) return e;
  }
  return {};
}

template <class Unused>
face_handle basic_halfedge_mesh<Unused>::add_face(std::span<const vertex_handle> vs) {
  const std::size_t n = vs.size();
  if (n < 3)
    throw error(
        error_category::invalid_input,
        cellforge::detail::cat("add_face: a face needs at least 3 vertices, got ", std::to_string(n)));
  for (vertex_handle v : vs) check_vertex(v, "add_face");
  if (!detail::all_distinct(vs))
    throw error(error_category::invalid_input, "add_face: a face must not repeat a vertex");
  if (faces_size() >= npos - 1 || halfedges_size() + 2 * n >= removed_mark)
    throw error(error_category::invalid_input, "add_face: the mesh is full (32-bit indices)");

  auto at = [&](std::size_t i) { return vs[i % n].idx(); };
  // Phase 1: find each edge's existing unlinked half-edge; check nothing becomes non-manifold.
  scratch_buffers& sb = scratch_;
  std::vector<std::uint32_t>& match = sb.assign_u32(0, n, npos);
  std::vector<std::uint8_t>& flipped = sb.assign_u8(0, n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t a = at(i), b = at(i + 1);
    std::uint32_t m = unlinked_.find(table_key(b, a), unlinked_key());
    if (m == detail::derived_key_table::not_found) {
      m = unlinked_.find(table_key(a, b), unlinked_key());
      flipped[i] = m != detail::derived_key_table::not_found;
    }
    if (m != detail::derived_key_table::not_found) {
      match[i] = m;
    } else if (is_boundary(vertex_handle(a)) && find_edge(vertex_handle(a), vertex_handle(b)).is_valid()) {
      throw error(error_category::topology,
                  cellforge::detail::cat("add_face: ", detail::edge_name(a, b),
                                         " already has two faces; a third would make it non-manifold"));
    }
  }
  std::vector<std::vector<fan>>& fans = sb.fan_lists(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t v = at(i);
    if (is_isolated(vertex_handle(v))) continue;
    if (!is_boundary(vertex_handle(v)))
      throw error(error_category::topology,
                  cellforge::detail::cat("add_face: ", detail::vtx(v),
                                         " is already surrounded by a closed fan of faces; another "
                                         "face there would make it non-manifold"));
    read_fans(v, fans[i]);
    const std::uint32_t m_in = match[(i + n - 1) % n], m_out = match[i];
    if (m_in == npos || m_out == npos) continue;
    const std::uint32_t x_in = m_in ^ 1u, x_out = m_out ^ 1u;
    if (fan_ending_at(fans[i], x_in) == fan_ending_at(fans[i], x_out) && fans[i].size() > 1)
      throw error(
          error_category::topology,
          cellforge::detail::cat("add_face: the face would close one fan of faces around ", detail::vtx(v),
                                 " while other fans remain there (non-manifold vertex)"));
  }

  // Phase 2: link. Nothing below throws except on allocation failure.
  const std::uint32_t f = n32(face_anchor_.size());
  std::vector<std::uint32_t>& hs = sb.assign_u32(1, n, npos);
  std::vector<std::uint8_t>& is_new = sb.assign_u8(1, n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t a = at(i), b = at(i + 1);
    if (match[i] != npos) {
      const std::uint32_t m = match[i];
      unlinked_.erase(flipped[i] ? table_key(a, b) : table_key(b, a), unlinked_key());
      hs[i] = m ^ 1u;
      if (flipped[i]) ++flipped_edges_;
    } else {
      const std::uint32_t e = new_edge();
      hs[i] = 2 * e;
      is_new[i] = 1;
      he_[2 * e].head = b;      // the table reads the key (a, b) off these two heads
      he_[2 * e + 1].head = a;  // the boundary side points back to the face half-edge's tail
      he_[2 * e + 1].face = npos;
      unlinked_.insert(table_key(a, b), 2 * e, unlinked_key());
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    record& r = he_[hs[i]];
    r.head = at(i + 1);
    r.face = f;
    r.next = hs[(i + 1) % n];
    r.prev = hs[(i + n - 1) % n];
  }
  face_anchor_.push_back(hs[0]);
  fprops_.push_back();

  // Phase 3: rings of boundary half-edges around each corner.
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t v = at(i);
    const std::size_t ip = (i + n - 1) % n;
    const std::uint32_t b_in = is_new[ip] ? hs[ip] ^ 1u : npos;
    const std::uint32_t b_out = is_new[i] ? hs[i] ^ 1u : npos;
    std::vector<fan>& fv = fans[i];
    if (is_new[ip] && is_new[i]) {
      fv.push_back({b_in, b_out});
    } else if (!is_new[ip] && is_new[i]) {
      move_fan_end(fv, hs[ip], b_out);
    } else if (is_new[ip] && !is_new[i]) {
      move_fan_end(fv, hs[i], b_in);
    } else {
      const std::uint32_t x_in = hs[ip], x_out = hs[i];
      const auto ia = fan_ending_at(fv, x_in), ib = fan_ending_at(fv, x_out);
      if (ia == ib) {
        fv.erase(ia);  // the fan closes
      } else {
        *ia = {other_end(*ia, x_in), other_end(*ib, x_out)};  // two fans merge into one
        fv.erase(ib);
      }
    }
    write_fans(v, fv, hs[i]);
  }
  return face_handle(f);
}

template <class Unused>
void basic_halfedge_mesh<Unused>::remove_face(face_handle fh) {
  if (!is_valid(fh))
    throw error(error_category::invalid_input,
                cellforge::detail::cat("remove_face: face ", std::to_string(fh.idx()),
                                       " does not exist or was removed"));
  const std::uint32_t f = fh.idx();
  scratch_buffers& sb = scratch_;
  std::vector<std::uint32_t>& hs = sb.assign_u32(0, 0, npos);
  std::vector<std::uint32_t>& vs = sb.assign_u32(1, 0, npos);
  for (halfedge_handle h : halfedges_around(fh)) {
    hs.push_back(h.idx());
    vs.push_back(tail(h).idx());
  }
  const std::size_t n = hs.size();
  std::vector<std::uint8_t>& interior = sb.assign_u8(0, n, 0);
  for (std::size_t i = 0; i < n; ++i) interior[i] = he_[hs[i] ^ 1u].face != npos;

  // Read every corner's fans and, where the face splits a fan, from which side the walk enters it.
  std::vector<std::vector<fan>>& fans = sb.fan_lists(n);
  std::vector<std::uint32_t>& split_fan = sb.assign_u32(2, n, npos);
  std::vector<std::uint32_t>& entry = sb.assign_u32(3, n, npos);
  for (std::size_t i = 0; i < n; ++i) {
    read_fans(vs[i], fans[i]);
    const std::size_t ip = (i + n - 1) % n;
    if (!(interior[ip] && interior[i]) || fans[i].empty()) continue;
    for (std::size_t k = 0; k < fans[i].size() && split_fan[i] == npos; ++k) {
      std::uint32_t ent = npos;
      walk_fan(fans[i][k].start, vs[i], nullptr, f, &ent);
      if (ent != npos) {
        split_fan[i] = n32(k);
        entry[i] = ent;
      }
    }
  }

  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t h = hs[i], t = h ^ 1u;
    if (interior[i]) {
      const std::uint32_t t_tail = he_[he_[t].prev].head, t_head = he_[t].head;
      if (t_head == he_[h].head) --flipped_edges_;
      he_[h].face = npos;
      he_[h].head = t_tail;
      unlinked_.insert(table_key(t_tail, t_head), t, unlinked_key());
    } else {
      unlinked_.erase(table_key(vs[i], vs[(i + 1) % n]), unlinked_key());
      he_[h] = record{};
      he_[t] = record{};
      ++removed_edges_;
    }
  }

  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t ip = (i + n - 1) % n;
    const std::uint32_t v = vs[i];
    const std::uint32_t h_in = hs[ip], h_out = hs[i];
    std::vector<fan>& fv = fans[i];
    if (interior[ip] && interior[i]) {
      if (fv.empty()) {
        fv.push_back({h_out, h_in});  // a closed fan opens up
      } else {
        const fan old = fv[split_fan[i]];
        const bool via_in = entry[i] == h_in;
        fv[split_fan[i]] = {old.start, via_in ? h_in : h_out};
        fv.insert(fv.begin() + static_cast<std::ptrdiff_t>(split_fan[i]) + 1,
                  fan{via_in ? h_out : h_in, old.end});
      }
    } else if (interior[ip]) {
      move_fan_end(fv, h_out ^ 1u, h_in);
    } else if (interior[i]) {
      move_fan_end(fv, h_in ^ 1u, h_out);
    } else {
      fv.erase(fan_ending_at(fv, h_in ^ 1u));  // the face was a fan of its own
    }
    write_fans(v, fv, npos);
  }
  face_anchor_[f] = npos;
  ++removed_faces_;
}

template <class Unused>
void basic_halfedge_mesh<Unused>::remove_vertex(vertex_handle v) {
  check_vertex(v, "remove_vertex");
  std::vector<face_handle> around;
  for (face_handle f : faces_around(v)) around.push_back(f);
  for (face_handle f : around) remove_face(f);
  vertex_anchor_[v.idx()] = removed_mark;
  ++removed_vertices_;
}

template <class Unused>
void basic_halfedge_mesh<Unused>::reverse_face(face_handle fh) {
  if (!is_valid(fh))
    throw error(error_category::invalid_input,
                cellforge::detail::cat("reverse_face: face ", std::to_string(fh.idx()),
                                       " does not exist or was removed"));
  std::vector<std::uint32_t> hs, vs;
  for (halfedge_handle h : halfedges_around(fh)) {
    hs.push_back(h.idx());
    vs.push_back(tail(h).idx());
  }
  const std::size_t n = hs.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t t = hs[i] ^ 1u;
    if (he_[t].face == npos)
      unlinked_.erase(table_key(vs[i], vs[(i + 1) % n]), unlinked_key());
    else if (he_[t].head == he_[hs[i]].head)
      --flipped_edges_;
  }
  for (std::size_t i = 0; i < n; ++i) {
    record& r = he_[hs[i]];
    r.head = vs[i];
    r.next = hs[(i + n - 1) % n];
    r.prev = hs[(i + 1) % n];
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t t = hs[i] ^ 1u;
    const std::uint32_t new_tail = vs[(i + 1) % n];
    if (he_[t].face == npos) {
      // The boundary side keeps pointing at the face half-edge's tail; its ring slots follow its ends.
      std::swap(he_[t].next, he_[t].prev);
      he_[t].head = new_tail;
      unlinked_.insert(table_key(new_tail, vs[i]), hs[i], unlinked_key());
    } else if (he_[t].head == vs[i]) {
      ++flipped_edges_;
    }
  }
  face_anchor_[fh.idx()] = hs[n - 1];  // keeps the face's first vertex first
}

template <class Unused>
build_report basic_halfedge_mesh<Unused>::build(std::size_t nv, std::span<const std::uint32_t> offsets,
                                                std::span<const std::uint32_t> fv,
                                                const build_options& options) {
  if (offsets.empty() || offsets[0] != 0 || offsets.back() != fv.size())
    throw error(error_category::invalid_input,
                "build: face offsets must start at 0 and end at the number of face indices");
  if (nv >= removed_mark || fv.size() >= removed_mark / 2)
    throw error(error_category::invalid_input, "build: too many vertices or faces for 32-bit indices");
  // A triangle mesh (the common case) runs passes that know every face has three corners at
  // 3f: they read no offsets and their corner loops unroll.
  const std::size_t nf = offsets.size() - 1;
  bool triangles = fv.size() == 3 * nf;
  // Blocks without an early exit inside, so that the compiler vectorises this extra read of
  // the offsets (an early exit per face made it ~1.5 % of a closed build at 10^6).
  for (std::size_t f0 = 1; triangles && f0 < nf; f0 += 4096) {
    std::uint32_t differ = 0;
    for (std::size_t f = f0, end = std::min(nf, f0 + 4096); f < end; ++f) differ |= offsets[f] ^ n32(3 * f);
    triangles = differ == 0;
  }
  return triangles ? build_faces<true>(nv, offsets, fv, options)
                   : build_faces<false>(nv, offsets, fv, options);
}

template <class Unused>
template <bool Triangles>
build_report basic_halfedge_mesh<Unused>::build_faces(std::size_t nv, std::span<const std::uint32_t> offsets,
                                                      std::span<const std::uint32_t> fv,
                                                      const build_options& options) {
  const std::size_t nf = offsets.size() - 1;
  const std::size_t nh = fv.size();
  // Face f's corners are [first(f), last(f)).
  const auto first = [&offsets](std::size_t f) { return Triangles ? n32(3 * f) : offsets[f]; };
  const auto last = [&offsets](std::size_t f) { return Triangles ? n32(3 * f + 3) : offsets[f + 1]; };

  // Pass 1, faces in order: check each face, then count its corners by the smaller end of
  // their edge (corner c is the edge fv[c] -> fv[c+1], cyclically within its face). The
  // counts sit two slots up so that the fill below leaves bucket lo at [start[lo], start[lo+1]).
  std::vector<std::uint32_t> start;
  detail::reserve_large(start, nv + 2);
  start.resize(nv + 2, 0);
  if constexpr (Triangles) {
    // The face's vertices are loaded once (the counts' stores may alias them) and checked
    // in one branch.
    for (std::size_t f = 0; f < nf; ++f) {
      const std::uint32_t a = fv[3 * f], b = fv[3 * f + 1], c = fv[3 * f + 2];
      if ((std::max({a, b, c}) >= nv) | (a == b) | (b == c) | (a == c)) [[unlikely]]
        detail::throw_bad_face(f, fv.subspan(3 * f, 3), nv);
      ++start[std::min(a, b) + 2];
      ++start[std::min(b, c) + 2];
      ++start[std::min(c, a) + 2];
    }
  }
  for (std::size_t f = 0; !Triangles && f < nf; ++f) {
    const std::uint32_t o = first(f), e = last(f);
    if (e < o || e > nh)
      throw error(
          error_category::invalid_input,
          cellforge::detail::cat("build: face offsets must not decrease (face ", std::to_string(f), ")"));
    if (e - o < 3)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("build: face ", std::to_string(f), " has fewer than 3 vertices"));
    const std::span<const std::uint32_t> face = fv.subspan(o, e - o);
    const bool in_range = std::all_of(face.begin(), face.end(), [nv](std::uint32_t v) { return v < nv; });
    if (!in_range || !detail::all_distinct(face)) detail::throw_bad_face(f, face, nv);
    for (std::uint32_t c = o; c < e; ++c) ++start[std::min(fv[c], fv[c + 1 == e ? o : c + 1]) + 2];
  }
  for (std::size_t i = 2; i < start.size(); ++i) start[i] += start[i - 1];

  // Pass 2: the corners bucketed by smaller end, each with its larger end beside it
  // (hi << 32 | down << 31 | corner, down when the corner runs from hi to lo), so matching
  // reads one contiguous run per vertex and sees seams without reading the faces again.
  constexpr std::uint64_t down = std::uint64_t{1} << 31, corner_bits = down - 1;  // corners < 2^31
  detail::uninitialized_array<std::uint64_t> items(nh);  // every slot is written below
  const auto put = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    items[start[std::min(a, b) + 1]++] = std::uint64_t{std::max(a, b)} << 32 | (a > b ? down : 0) | c;
  };
  if constexpr (Triangles) {  // the vertices loaded once, as in pass 1
    for (std::size_t f = 0; f < nf; ++f) {
      const std::uint32_t c0 = n32(3 * f), a = fv[c0], b = fv[c0 + 1], c = fv[c0 + 2];
      put(a, b, c0);
      put(b, c, c0 + 1);
      put(c, a, c0 + 2);
    }
  }
  for (std::size_t f = 0; !Triangles && f < nf; ++f) {
    const std::uint32_t o = first(f), e = last(f);
    for (std::uint32_t c = o; c < e; ++c) put(fv[c], fv[c + 1 == e ? o : c + 1], c);
  }

  // Pass 3: match the corners of each edge within its bucket; a third one is an error. Each
  // corner's partner is set to npos when its item is reached, so `partner` needs no fill.
  detail::uninitialized_array<std::uint32_t> partner(nh);
  std::size_t pairs = 0, flipped = 0;
  const auto pair_up = [&](std::uint64_t x, std::uint64_t y, std::uint32_t lo) {
    const auto c = static_cast<std::uint32_t>(x & corner_bits),
               d = static_cast<std::uint32_t>(y & corner_bits);
    if (partner[d] != npos) detail::throw_third_face(offsets, lo, n32(x >> 32), d, partner[d], c);
    partner[c] = d;
    partner[d] = c;
    ++pairs;
    flipped += ((x ^ y) & down) == 0;  // both corners run the same way along the edge
  };
  for (std::uint32_t lo = 0; lo < nv; ++lo) {
    const std::uint32_t b0 = start[lo], b1 = start[lo + 1];
    if (b1 - b0 <= 24) {
      for (std::uint32_t i = b0; i < b1; ++i) {
        const std::uint64_t x = items[i];
        partner[x & corner_bits] = npos;
        for (std::uint32_t j = i; j-- > b0;) {
          if (items[j] >> 32 != x >> 32) continue;
          pair_up(x, items[j], lo);
          break;
        }
      }
    } else {  // a high-degree vertex: sort its bucket (by larger end, then corner) instead
      std::sort(items.begin() + b0, items.begin() + b1,
                [](std::uint64_t x, std::uint64_t y) { return (x & ~down) < (y & ~down); });
      for (std::uint32_t i = b0; i < b1; ++i) partner[items[i] & corner_bits] = npos;
      for (std::uint32_t i = b0 + 1; i < b1; ++i)
        if (items[i] >> 32 == items[i - 1] >> 32) pair_up(items[i], items[i - 1], lo);
    }
  }
  items.free();  // before the mesh arrays: the peak stays at the mesh plus `partner`
  detail::release(start);

  const std::size_t ne = nh - pairs;
  clear_connectivity();
  detail::reserve_large(vertex_anchor_, nv);
  // Vertex properties (positions) are sized when link_fans has freed its arrays: a lower peak.
  vertex_anchor_.assign(nv, npos);
  detail::reserve_large(he_, 2 * ne);
  he_.resize(2 * ne);
  hprops_.resize(2 * ne);
  eprops_.resize(ne);
  detail::reserve_large(face_anchor_, nf);  // filled in face order below
  fprops_.resize(nf);

  // Pass 4, faces in order: number the edges in order of first use (so half-edges of nearby
  // faces sit close in memory) and write the face's records. A corner whose partner comes
  // later opens a new edge and leaves its half-edge in partner[c] for that partner; one
  // whose partner came earlier takes the twin of the partner's half-edge. The same pass
  // counts what link_fans' first pass would (corners, anchors, boundary), so the records
  // are not read again.
  known_counts known;
  detail::reserve_large(known.unlinked, nh - 2 * pairs);
  detail::reserve_large(known.corners, nv);
  known.corners.resize(nv, 0);
  flipped_edges_ = flipped;
  std::uint32_t next_edge = 0;
  // The last face half-edge into each vertex, as link_fans picks: a maximum in which npos
  // (no corner yet) counts as the smallest, without a branch.
  const auto raise_anchor = [this](std::uint32_t v, std::uint32_t h) {
    std::uint32_t& anchor = vertex_anchor_[v];
    anchor = std::max(anchor + 1, h + 1) - 1;
  };
  // The half-edge of corner c (whose edge ends at `head`) with partner p: the twin of the
  // partner's if the partner came first (npos never does), else a new edge's.
  const auto number = [&](std::uint32_t c, std::uint32_t p, std::uint32_t head) {
    if (p < c) return partner[p] ^ 1u;
    const std::uint32_t h = 2 * next_edge++;
    partner[c] = h;
    if (p == npos) [[unlikely]] {  // boundary side: head at the face half-edge's tail
      he_[h ^ 1u].head = fv[c];
      ++known.boundary;
      known.unlinked.push_back(detail::derived_key_table::entry(table_key(fv[c], head), h));
    }
    return h;
  };
  if constexpr (Triangles) {
    // The face's three half-edges stay in registers and each record is stored whole (the
    // general loop below, whose field stores may alias its partner loads, takes twice as long).
    for (std::size_t f = 0; f < nf; ++f) {
      const std::uint32_t c0 = n32(3 * f), a = fv[c0], b = fv[c0 + 1], c = fv[c0 + 2];
      const std::uint32_t h0 = number(c0, partner[c0], b), h1 = number(c0 + 1, partner[c0 + 1], c),
                          h2 = number(c0 + 2, partner[c0 + 2], a);
      face_anchor_.push_back(h0);
      he_[h0] = record{b, h1, h2, n32(f)};
      he_[h1] = record{c, h2, h0, n32(f)};
      he_[h2] = record{a, h0, h1, n32(f)};
      ++known.corners[b];
      ++known.corners[c];
      ++known.corners[a];
      raise_anchor(b, h0);
      raise_anchor(c, h1);
      raise_anchor(a, h2);
    }
  }
  for (std::size_t f = 0; !Triangles && f < nf; ++f) {
    const std::uint32_t o = first(f), e = last(f);
    for (std::uint32_t c = o; c < e; ++c) partner[c] = number(c, partner[c], fv[c + 1 == e ? o : c + 1]);
    face_anchor_.push_back(partner[o]);
    for (std::uint32_t c = o; c < e; ++c) {
      const std::uint32_t cn = c + 1 == e ? o : c + 1, cp = c == o ? e - 1 : c - 1;
      const std::uint32_t h = partner[c], head = fv[cn];
      he_[h] = record{head, partner[cn], partner[cp], n32(f)};
      ++known.corners[head];
      raise_anchor(head, h);
    }
  }
  partner.free();
  build_report report;
  link_fans(options, report, true, &known);
  return report;
}

template <class Unused>
void basic_halfedge_mesh<Unused>::link_fans(const build_options& options, build_report& report,
                                            bool verify_fans) {
  link_fans(options, report, verify_fans, nullptr);
}

template <class Unused>
void basic_halfedge_mesh<Unused>::link_fans(const build_options& options, build_report& report,
                                            bool verify_fans, known_counts* known) {
  const std::size_t nv = vertex_anchor_.size();
  unlinked_.clear();
  // Corners per vertex (to check that the fans found reach every face), anchors, seams, boundary.
  std::vector<std::uint32_t> corners;
  std::size_t boundary = 0;
  std::vector<detail::derived_key_table::slot> unlinked;  // the unlinked table's entries, by half-edge
  if (known) {
    corners = std::move(known->corners);
    boundary = known->boundary;
    unlinked = std::move(known->unlinked);
  } else {
    std::fill(vertex_anchor_.begin(), vertex_anchor_.end(), npos);
    flipped_edges_ = 0;
    corners.assign(nv, 0);
    for (std::uint32_t h = 0; h < he_.size(); ++h) {
      const record& r = he_[h];
      if (r.face == npos) {
        ++boundary;
        continue;
      }
      ++corners[r.head];
      vertex_anchor_[r.head] = h;
      if (h < (h ^ 1u) && he_[h ^ 1u].face != npos && he_[h ^ 1u].head == r.head) ++flipped_edges_;
    }
  }
  // A closed mesh (the common case) needs neither the unlinked table nor the rings below:
  // skipping them saves two passes over the half-edges and four arrays.
  if (boundary > 0) {
    if (!known) {
      detail::reserve_large(unlinked, boundary);
      for (std::uint32_t h = 0; h < he_.size(); ++h)
        if (he_[h].face != npos && he_[h ^ 1u].face == npos)
          unlinked.push_back(detail::derived_key_table::entry(unlinked_key()(h), h));
    }
    unlinked_.assign(unlinked);
  }

  std::vector<std::uint32_t> covered, ring_first, ring_last;
  std::vector<std::uint64_t> seen;  // two bits per half-edge: head end done, tail end done
  if (boundary > 0) {
    for (auto* a : {&covered, &ring_first, &ring_last}) detail::reserve_large(*a, nv);
    covered.assign(nv, 0);
    ring_first.assign(nv, npos);
    ring_last.assign(nv, npos);
    seen.assign((2 * he_.size() + 63) / 64, 0);
  }
  const auto bit = [](std::uint32_t h, unsigned side) { return std::uint64_t{1} << (2 * (h & 31u) + side); };
  const auto mark = [&](std::uint32_t h, unsigned side) { seen[h >> 5] |= bit(h, side); };
  for (const detail::derived_key_table::slot& entry : unlinked) {  // the boundary half-edges, in order
    const std::uint32_t b = entry.value ^ 1u;
    for (unsigned side = 0; side < 2; ++side) {
      const std::uint32_t v = side == 0 ? he_[b].head : he_[b ^ 1u].head;
      if (seen[b >> 5] & bit(b, side)) continue;
      std::size_t count = 0;
      const std::uint32_t e = walk_fan(b, v, &count);
      mark(b, side);
      mark(e, he_[e].head == v ? 0u : 1u);
      covered[v] += n32(count);
      if (ring_first[v] == npos)
        ring_first[v] = b;
      else
        ring_slot(ring_last[v], v) = b;
      ring_slot(b, v) = e;
      ring_last[v] = e;
    }
  }
  std::vector<std::uint32_t> nonmanifold;
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (corners[v] == 0) {
      ++report.isolated_vertices;
      continue;
    }
    const bool open = boundary > 0 && ring_first[v] != npos;
    std::size_t reached = open ? covered[v] : 0;
    if (open) {
      ring_slot(ring_last[v], v) = ring_first[v];
      vertex_anchor_[v] = ring_first[v];
    } else if (!verify_fans) {
      continue;
    } else {
      const std::uint32_t a = vertex_anchor_[v];
      std::uint32_t t = a;
      do {
        ++reached;
        t = (he_[t].head == v ? he_[t].next : he_[t].prev) ^ 1u;
      } while (t != a && reached <= corners[v]);
    }
    if (reached == corners[v]) continue;
    if (!options.split_nonmanifold_vertices) {
      const std::uint32_t total = corners[v];
      clear_connectivity();
      vprops_.resize(nv);
      throw error(error_category::topology,
                  cellforge::detail::cat(
                      "build: the ", std::to_string(total), " faces around ", detail::vtx(v),
                      (open ? " form a closed fan plus open ones" : " form several closed fans"),
                      " (a non-manifold vertex, e.g. two cones touching at their tips); set "
                      "build_options::split_nonmanifold_vertices to give each fan its own vertex"));
    }
    nonmanifold.push_back(v);
  }
  // Free the temporaries before the vertex properties (positions after a build) are allocated.
  for (auto* a : {&corners, &covered, &ring_first, &ring_last}) detail::release(*a);
  detail::release(unlinked);
  detail::release(seen);
  vprops_.resize(nv);
  if (!nonmanifold.empty()) split_fans(nonmanifold, report);
  report.vertices = vertex_anchor_.size();
  report.edges = edges_size();
  report.faces = faces_size();
  report.boundary_edges = boundary;
  report.flipped_edges = flipped_edges_;
}

template <class Unused>
void basic_halfedge_mesh<Unused>::split_fans(const std::vector<std::uint32_t>& bad, build_report& report) {
  // The face half-edges entering each listed vertex: one per face at it.
  std::vector<std::uint8_t> listed(vertex_anchor_.size(), 0), marked(he_.size(), 0);
  for (std::uint32_t v : bad) listed[v] = 1;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> incoming;  // (vertex, half-edge)
  for (std::uint32_t h = 0; h < he_.size(); ++h)
    if (he_[h].face != npos && listed[he_[h].head]) incoming.emplace_back(he_[h].head, h);
  std::sort(incoming.begin(), incoming.end());
  // Marks the faces of one fan at v by their half-edge entering v; returns those half-edges.
  std::vector<std::uint32_t> fan_in;
  auto walk = [&](std::uint32_t start, std::uint32_t v, bool closed) {
    fan_in.clear();
    std::uint32_t t = closed ? start : start ^ 1u;
    for (std::size_t guard = 0; guard <= he_.size(); ++guard) {
      const std::uint32_t in = he_[t].head == v ? t : he_[t].prev;
      marked[in] = 1;
      fan_in.push_back(in);
      const std::uint32_t u = (he_[t].head == v ? he_[t].next : he_[t].prev) ^ 1u;
      if (he_[u].face == npos || u == start) break;
      t = u;
    }
  };
  for (std::uint32_t v : bad) {
    const std::uint32_t a = vertex_anchor_[v];
    if (he_[a].face == npos) {
      std::uint32_t s = a;
      do {
        walk(s, v, false);
        s = ring_slot(ring_slot(s, v), v);
      } while (s != a);
    } else {
      walk(a, v, true);
    }
  }
  for (const auto& [v, h] : incoming) {
    if (marked[h]) continue;
    walk(h, v, true);  // an unreached fan at v is closed: every open one starts at a ring entry
    const std::uint32_t copy = n32(vertex_anchor_.size());
    vertex_anchor_.push_back(h);
    vprops_.push_back();
    for (std::uint32_t in : fan_in) he_[in].head = copy;
    report.split_vertices.emplace_back(copy, v);
  }
}

template <class Unused>
void basic_halfedge_mesh<Unused>::garbage_collection() {
  if (!has_garbage()) return;
  const std::size_t nv = vertices_size(), ne = edges_size(), nf = faces_size();
  std::vector<std::uint32_t> vmap(nv, npos), emap(ne, npos), fmap(nf, npos);
  std::uint32_t kv = 0, ke = 0, kf = 0;
  for (std::uint32_t v = 0; v < nv; ++v)
    if (vertex_anchor_[v] != removed_mark) vmap[v] = kv++;
  for (std::uint32_t e = 0; e < ne; ++e)
    if (he_[2 * e].head != npos) emap[e] = ke++;
  for (std::uint32_t f = 0; f < nf; ++f)
    if (face_anchor_[f] != npos) fmap[f] = kf++;
  auto hmap = [&](std::uint32_t h) { return h == npos ? npos : 2 * emap[h >> 1] + (h & 1u); };

  for (std::uint32_t e = 0; e < ne; ++e) {
    if (emap[e] == npos) continue;
    for (std::uint32_t i = 0; i < 2; ++i) {
      record r = he_[2 * e + i];
      r.head = vmap[r.head];
      r.next = hmap(r.next);
      r.prev = hmap(r.prev);
      r.face = r.face == npos ? npos : fmap[r.face];
      he_[2 * emap[e] + i] = r;
      hprops_.move_element(2 * emap[e] + i, 2 * e + i);
    }
    eprops_.move_element(emap[e], e);
  }
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (vmap[v] == npos) continue;
    vertex_anchor_[vmap[v]] = hmap(vertex_anchor_[v]);
    vprops_.move_element(vmap[v], v);
  }
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (fmap[f] == npos) continue;
    face_anchor_[fmap[f]] = hmap(face_anchor_[f]);
    fprops_.move_element(fmap[f], f);
  }
  he_.resize(2 * std::size_t{ke});
  vertex_anchor_.resize(kv);
  face_anchor_.resize(kf);
  vprops_.resize(kv);
  hprops_.resize(2 * std::size_t{ke});
  eprops_.resize(ke);
  fprops_.resize(kf);
  std::vector<detail::derived_key_table::slot> entries;
  for (std::uint32_t h = 0; h < he_.size(); ++h)
    if (he_[h].face != npos && he_[h ^ 1u].face == npos)
      entries.push_back(detail::derived_key_table::entry(unlinked_key()(h), h));
  unlinked_.assign(entries);
  removed_vertices_ = removed_edges_ = removed_faces_ = 0;
}

}  // namespace cellforge
