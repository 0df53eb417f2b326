// SPDX-License-Identifier: MIT
#pragma once
// The tube mesher's half-edge build: a CSR face list that should be a closed, consistently
// oriented surface (every directed edge a -> b met by exactly one b -> a) is linked in two
// passes over the faces in emission order, where basic_halfedge_mesh::build buckets every
// corner by vertex first (four passes, two of them scattered over the whole mesh). The
// tube's faces come ring by ring, so a corner's twin is almost always among the last few
// dozen corners: an unmatched-corner list per vertex finds it in cache. The records are the
// ones build writes (same edge numbering, same vertex anchors); anything that is not a
// closed oriented surface is left to build, which reports it.

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "cellforge/halfedge/detail/mesh_access.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge::detail::tubes {

/// Links faces (CSR over `num_vertices`) into `mesh` (no faces yet; its vertex properties,
/// if already sized, are kept) when they form a closed, consistently oriented surface and
/// returns true; otherwise returns false with no connectivity (face properties sized, their
/// values kept), for build to report what is wrong. The fans are still verified (a non-manifold vertex throws
/// as build does). O(total face size × the longest unmatched list at a vertex), O(1) per corner for tubes.
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
  access::resize(mesh, num_vertices, nh / 2, nf);
  std::vector<halfedge_mesh::record>& he = access::records(mesh);
  std::vector<std::uint32_t>& first = access::vertex_anchors(mesh);
  // The records serve as the matching's scratch first (one record per corner, as many as
  // there will be half-edges), so that it allocates little: the unmatched corners leaving
  // each vertex v form a list from first[v] through he[c].next, he[c].head being corner c's
  // head vertex. Edges are numbered as build numbers them, in order of first use: a corner
  // with no twin yet opens one (half[c] = 2e), the twin that comes later takes 2e + 1.
  std::vector<std::uint32_t> half(nh);
  std::uint32_t next_edge = 0;
  std::size_t unmatched = 0;
  const auto give_up = [&] {  // face properties keep their values (the caller may swap them out)
    he.clear();
    access::halfedge_properties(mesh).resize(0);
    access::edge_properties(mesh).resize(0);
    access::face_anchors(mesh).clear();
    std::fill(first.begin(), first.end(), npos);
    return false;
  };
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t o = offsets[f], e = offsets[f + 1];
    if (e < o + 3 || e > nh) return give_up();
    for (std::uint32_t c = o; c < e; ++c) {
      if (fv[c] >= num_vertices) return give_up();
      for (std::uint32_t d = o; d < c; ++d)
        if (fv[d] == fv[c]) return give_up();  // a repeated vertex: build names it
    }
    for (std::uint32_t c = o; c < e; ++c) {
      const std::uint32_t a = fv[c], b = fv[c + 1 == e ? o : c + 1];
      // The twin leaves b for a: search b's list.
      std::uint32_t before = npos, d = first[b];
      while (d != npos && he[d].head != a) before = d, d = he[d].next;
      if (d != npos) {
        (before == npos ? first[b] : he[before].next) = he[d].next;
        half[c] = half[d] ^ 1u;
        --unmatched;
      } else {
        he[c].head = b, he[c].next = first[a];
        first[a] = c;
        half[c] = 2 * next_edge++;
        ++unmatched;
      }
    }
  }
  // A boundary, an edge of three faces or two faces disagreeing in orientation: not closed.
  if (unmatched != 0) return give_up();
  // The records, and each vertex's anchor: as build's, the last half-edge that ends there.
  std::vector<std::uint32_t>& face_anchor = access::face_anchors(mesh);
  std::vector<std::uint32_t>& anchor = first;  // every list is empty: all npos
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t o = offsets[f], e = offsets[f + 1];
    face_anchor[f] = half[o];
    for (std::uint32_t c = o; c < e; ++c) {
      const std::uint32_t cn = c + 1 == e ? o : c + 1, cp = c == o ? e - 1 : c - 1;
      const std::uint32_t h = half[c], v = fv[cn];
      halfedge_mesh::record& r = he[h];
      r.head = v;
      r.next = half[cn];
      r.prev = half[cp];
      r.face = static_cast<std::uint32_t>(f);
      if (anchor[v] == npos || anchor[v] < h) anchor[v] = h;
    }
  }
  half = {};
  // Each vertex's corners must form one fan. Walking around every vertex from its anchor
  // reaches each half-edge at most once, and all of them exactly when no vertex has a second
  // fan; eight walks go side by side so that their cache misses overlap.
  constexpr std::size_t lanes = 8;
  std::array<std::uint32_t, lanes> start{}, at{};
  std::size_t reached = 0;
  for (std::size_t v0 = 0; v0 < num_vertices && reached <= nh; v0 += lanes) {
    std::size_t live = 0;
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
