// SPDX-License-Identifier: MIT
#pragma once
// The tube mesher's half-edge build: a CSR face list that should be a closed, consistently
// oriented surface (every directed edge a -> b met by exactly one b -> a) is linked in one
// pass over the faces in emission order, then one walk around every vertex, where
// basic_halfedge_mesh::build buckets every corner by vertex first (four passes, two of them
// scattered over the whole mesh). The tube's faces come ring by ring, so a corner's twin is
// almost always among the last few dozen corners: a list of open edges per vertex finds it
// in cache. The records are the ones build writes (same edge numbering, same vertex
// anchors); anything that is not a closed oriented surface is left to build, which reports it.

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/halfedge/detail/mesh_access.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge::detail::tubes {

/// A hint to load the line at p into cache (no effect where the compiler has no builtin). O(1).
template <class T>
void prefetch([[maybe_unused]] const T* p) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#endif
}

/// Links faces (CSR over `num_vertices`) into `mesh` (no faces yet; its vertex properties,
/// if already sized, are kept) when they form a closed, consistently oriented surface and
/// returns true; otherwise returns false with no connectivity (face properties sized, their
/// values kept), for build to report what is wrong. The fans are still verified (a vertex
/// with two closed fans throws as build does). O(total face size × the longest open-edge list
/// at a vertex): O(1) per corner for tubes.
template <class = void>
bool build_closed(halfedge_mesh& mesh, std::size_t num_vertices, std::span<const std::uint32_t> offsets,
                  std::span<const std::uint32_t> fv) {
  using access = mesh_access;
  constexpr std::uint32_t npos = halfedge_mesh::npos;
  const std::size_t nh = fv.size();
  // A closed surface has two corners per edge.
  if (offsets.empty() || offsets[0] != 0 || offsets.back() != nh || nh % 2 != 0 || num_vertices >= npos / 2 ||
      nh >= npos / 2 || mesh.halfedges_size() != 0 || mesh.faces_size() != 0)
    return false;
  const std::size_t nf = offsets.size() - 1;
  // No half-edges yet: the records grow as edges open (the write frontier only advances), so
  // the largest array is never filled with placeholders first.
  access::resize(mesh, num_vertices, 0, nf);
  std::vector<halfedge_mesh::record>& he = access::records(mesh);
  reserve_large(he, nh);
  std::vector<std::uint32_t>& anchor = access::vertex_anchors(mesh);  // all npos
  std::vector<std::uint32_t>& face_anchor = access::face_anchors(mesh);
  // One pass, faces in order. Edges are numbered as build numbers them, in order of first
  // use: a corner a -> b with no twin yet opens edge e and takes half-edge 2e; until its twin
  // comes, the twin's record 2e + 1 serves as scratch, on a list of such open edges per
  // vertex (from first[a] through .next, with .head = b), so the matching needs no arrays of
  // its own; the twin b -> a finds it on a's list and takes 2e + 1. A face's records are
  // written once all its corners have their half-edges.
  uninitialized_array<std::uint32_t> first(num_vertices);
  std::fill(first.begin(), first.end(), npos);
  std::vector<std::uint32_t> corner_half(8);  // grown to the longest face, never shrunk
  std::uint32_t next_edge = 0;
  const std::size_t ne = nh / 2;
  std::size_t unmatched = 0;
  const auto give_up = [&] {  // face properties keep their values (the caller may swap them out)
    he.clear();
    access::halfedge_properties(mesh).resize(0);
    access::edge_properties(mesh).resize(0);
    face_anchor.clear();
    std::fill(anchor.begin(), anchor.end(), npos);
    return false;
  };
  constexpr std::uint32_t lookahead = 32;  // corners: a ring of quads for octagons
  // The records grow by a chunk that stays in cache until written over: push_back per record
  // was an out-of-line call (4% of make_tubes' instructions).
  constexpr std::size_t chunk = 4096;
  // One face of k corners from fv[o] on; false when it cannot be part of a closed surface.
  // K > 0 is k known at compile time (triangles and quads, nearly every face of a tube mesh):
  // the loops unroll and the wrap-arounds fold away.
  const auto link = [&]<std::uint32_t K>(std::uint32_t f, std::uint32_t o, std::uint32_t k_run) {
    const std::uint32_t k = K != 0 ? K : k_run;
    const std::uint32_t* const vs = fv.data() + o;
    for (std::uint32_t c = 0; c < k; ++c) {
      if (vs[c] >= num_vertices) return false;
      for (std::uint32_t d = 0; d < c; ++d)
        if (vs[d] == vs[c]) return false;  // a repeated vertex: build names it
    }
    std::uint32_t local[K != 0 ? K : 1];
    std::uint32_t* const half = K != 0 ? local : corner_half.data();
    for (std::uint32_t i = 0; i < k; ++i) {
      // The list a corner two rings on will search, and the first entry of one a ring on: a path's
      // first ring matches a junction's corners from long ago, out of cache.
      const std::uint32_t c = o + i;
      if (c + 2 * lookahead < nh) prefetch(&first[fv[c + 2 * lookahead]]);
      if (c + lookahead < nh && first[fv[c + lookahead]] != npos) prefetch(&he[first[fv[c + lookahead]]]);
      const std::uint32_t a = vs[i], b = vs[i + 1 == k ? 0 : i + 1];
      // The twin leaves b for a: an open edge on b's list whose other end is a.
      std::uint32_t before = npos, t = first[b];
      while (t != npos && he[t].head != a) before = t, t = he[t].next;
      if (t != npos) {
        (before == npos ? first[b] : he[before].next) = he[t].next;
        half[i] = t;
        --unmatched;
      } else {
        if (next_edge == ne) return false;  // more edges than a closed surface has
        const std::uint32_t h = 2 * next_edge++;
        if (h == he.size()) he.resize(std::min(nh, he.size() + chunk));
        he[h + 1] = {b, first[a], npos, npos};  // h: written with its face below
        first[a] = h + 1;
        half[i] = h;
        ++unmatched;
      }
    }
    face_anchor[f] = half[0];
    for (std::uint32_t i = 0; i < k; ++i) {
      const std::uint32_t h = half[i], v = vs[i + 1 == k ? 0 : i + 1];
      halfedge_mesh::record& r = he[h];
      r.head = v;
      r.next = half[i + 1 == k ? 0 : i + 1];
      r.prev = half[i == 0 ? k - 1 : i - 1];
      r.face = f;
      if (anchor[v] == npos || anchor[v] < h) anchor[v] = h;  // as build's: the last one in
    }
    return true;
  };
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t o = offsets[f], e = offsets[f + 1];
    if (e < o + 3 || e > nh) return give_up();
    const auto ff = static_cast<std::uint32_t>(f);
    bool ok;
    if (e - o == 4) {
      ok = link.template operator()<4>(ff, o, 4);
    } else if (e - o == 3) {
      ok = link.template operator()<3>(ff, o, 3);
    } else {
      if (corner_half.size() < e - o) corner_half.resize(e - o);
      ok = link.template operator()<0>(ff, o, e - o);
    }
    if (!ok) return give_up();
  }
  // A boundary, an edge of three faces or two faces disagreeing in orientation: not closed.
  if (unmatched != 0) return give_up();
  first.free();
  access::halfedge_properties(mesh).resize(nh);
  access::edge_properties(mesh).resize(ne);
  // Each vertex's corners must form one fan. Walking around every vertex from its anchor
  // reaches each half-edge at most once, and all of them exactly when no vertex has a second
  // fan; eight walks go side by side so that their cache misses overlap.
  constexpr std::size_t lanes = 8;
  std::array<std::uint32_t, lanes> start{}, at{};
  std::size_t reached = 0;
  for (std::size_t v0 = 0; v0 < num_vertices && reached <= nh; v0 += lanes) {
    std::size_t live = 0;
    for (std::size_t k = 0; k < lanes && v0 + 4 * lanes + k < num_vertices; ++k)
      if (anchor[v0 + 4 * lanes + k] != npos) prefetch(&he[anchor[v0 + 4 * lanes + k]]);
    for (std::size_t k = 0; k < lanes; ++k) {
      start[k] = at[k] = v0 + k < num_vertices ? anchor[v0 + k] : npos;
      live += start[k] != npos ? 1 : 0;
    }
    while (live > 0 && reached <= nh)
      for (std::size_t k = 0; k < lanes; ++k) {
        if (at[k] == npos) continue;
        ++reached;
        at[k] = he[at[k]].next ^ 1u;  // the next half-edge into the same vertex
        if (at[k] == start[k]) at[k] = npos, --live;
      }
  }
  if (reached != nh) {
    access::finish(mesh);  // names the vertex where fans meet (throws)
    return true;
  }
  access::finish_closed(mesh, 0);  // every twin pair runs both ways: no flipped edge
  return true;
}

}  // namespace cellforge::detail::tubes
