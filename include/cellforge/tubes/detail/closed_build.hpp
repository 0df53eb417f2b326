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

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "cellforge/halfedge/detail/mesh_access.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge::detail::tubes {

/// Links faces (CSR over `num_vertices`) into `mesh` (empty) when they form a closed,
/// consistently oriented surface and returns true; returns false, the mesh untouched,
/// otherwise. The fans are still verified (a non-manifold vertex throws as build does).
/// O(total face size × the longest unmatched list at a vertex), O(1) per corner for tubes.
template <class = void>
bool build_closed(halfedge_mesh& mesh, std::size_t num_vertices, std::span<const std::uint32_t> offsets,
                  std::span<const std::uint32_t> fv) {
  using access = mesh_access;
  constexpr std::uint32_t npos = halfedge_mesh::npos;
  const std::size_t nh = fv.size();
  if (offsets.empty() || offsets[0] != 0 || offsets.back() != nh || num_vertices >= npos / 2 ||
      nh >= npos / 2 || mesh.vertices_size() != 0 || mesh.halfedges_size() != 0)
    return false;
  const std::size_t nf = offsets.size() - 1;
  // Unmatched corners leaving each vertex, as a list: pending[c] = {c's head vertex, the
  // next corner in its tail's list}. partner[c] is c's twin corner once matched.
  std::vector<std::uint32_t> first(num_vertices, npos), partner(nh);
  std::vector<std::array<std::uint32_t, 2>> pending(nh);
  std::size_t unmatched = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t o = offsets[f], e = offsets[f + 1];
    if (e < o + 3 || e > nh) return false;
    for (std::uint32_t c = o; c < e; ++c) {
      if (fv[c] >= num_vertices) return false;
      for (std::uint32_t d = o; d < c; ++d)
        if (fv[d] == fv[c]) return false;  // a repeated vertex: build names it
    }
    for (std::uint32_t c = o; c < e; ++c) {
      const std::uint32_t a = fv[c], b = fv[c + 1 == e ? o : c + 1];
      // The twin leaves b for a: search b's list.
      std::uint32_t before = npos, d = first[b];
      while (d != npos && pending[d][0] != a) before = d, d = pending[d][1];
      if (d != npos) {
        (before == npos ? first[b] : pending[before][1]) = pending[d][1];
        partner[c] = d, partner[d] = c;
        --unmatched;
      } else {
        pending[c] = {b, first[a]};
        first[a] = c;
        ++unmatched;
      }
    }
  }
  // A boundary, an edge of three faces or two faces disagreeing in orientation: not closed.
  if (unmatched != 0) return false;
  pending = {};
  first = {};
  const std::size_t ne = nh / 2;
  access::resize(mesh, num_vertices, ne, nf);
  std::vector<halfedge_mesh::record>& he = access::records(mesh);
  std::vector<std::uint32_t>& face_anchor = access::face_anchors(mesh);
  // As build's last pass: edges numbered in order of first use, a corner whose twin came
  // earlier taking the twin of the twin's half-edge.
  std::uint32_t next_edge = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const std::uint32_t o = offsets[f], e = offsets[f + 1];
    for (std::uint32_t c = o; c < e; ++c) {
      const std::uint32_t p = partner[c];
      partner[c] = p < c ? partner[p] ^ 1u : 2 * next_edge++;
    }
    face_anchor[f] = partner[o];
    for (std::uint32_t c = o; c < e; ++c) {
      const std::uint32_t cn = c + 1 == e ? o : c + 1, cp = c == o ? e - 1 : c - 1;
      halfedge_mesh::record& r = he[partner[c]];
      r.head = fv[cn];
      r.next = partner[cn];
      r.prev = partner[cp];
      r.face = static_cast<std::uint32_t>(f);
    }
  }
  partner = {};
  access::finish(mesh);  // anchors, and the walk around every vertex that finds a pinch
  return true;
}

}  // namespace cellforge::detail::tubes
