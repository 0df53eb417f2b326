// SPDX-License-Identifier: MIT
#pragma once
// The topology half of Loop subdivision: one 1→4 split of a triangle mesh written in closed
// form, with every child's twin known from its parent's index (no search, no hash table).
//
// Numbering (E parent edges, F parent faces, V parent vertices):
//   vertices  v (kept) and V + e (the point on parent edge e);
//   edges     2e, 2e+1: the two halves of parent edge e, half-edges 4e .. 4e+3, where
//             child edge 2e touches A = tail of half-edge 2e and child edge 2e+1 touches
//             B = head of half-edge 2e; 2E + 3f + k: face f's interior edge opposite its
//             corner k (half-edge 2(2E+3f+k) in the corner face, +1 in the centre face);
//   faces     4f + k: the corner face at corner k of face f, 4f + 3: the centre face.
// A half of a parent half-edge h keeps h's side bit (h & 1), so children of the two sides
// of a parent edge are twins exactly when the parents were; across a flipped edge (both
// sides run A→B) both first halves sit on the A child edge and both second halves on the
// B child edge, which is why the side of a half is read off the heads, not assumed.

#include <cstdint>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge::detail::loop {

using record = halfedge_mesh::record;
inline constexpr std::uint32_t npos = halfedge_mesh::npos;

/// Element counts of a triangle mesh, wide enough to see 32-bit overflow coming.
struct counts {
  std::uint64_t vertices = 0, edges = 0, faces = 0;
  /// The counts after one Loop step: V + E, 2E + 3F, 4F. O(1).
  counts next() const noexcept { return {vertices + edges, 2 * edges + 3 * faces, 4 * faces}; }
  /// True when every index (half-edges included) stays below the mesh's reserved values.
  bool fits() const noexcept {
    constexpr std::uint64_t limit = halfedge_mesh::removed_mark;  // npos and removed_mark are reserved
    return vertices < limit && faces < limit && 2 * edges < limit;
  }
};

template <class = void>
std::string corrupted(std::uint32_t f, const char* what) {
  return cellforge::detail::cat("loop_subdivide: face ", std::to_string(f), " ", what,
                                "; the mesh is corrupted (validate() says where)");
}

/// Number of half-edges around face f, stopping past `limit` (for the error message only).
template <class = void>
std::size_t face_size(std::span<const record> he, std::uint32_t h0, std::size_t limit) {
  std::size_t n = 0;
  std::uint32_t h = h0;
  do {
    ++n;
    h = he[h].next;
  } while (h != h0 && h < he.size() && n <= limit);
  return n;
}

/// Throws the error for face f with n vertices (n > limit: the loop did not close). O(1).
[[noreturn]] inline void not_a_triangle(std::uint32_t f, std::size_t n, std::size_t limit) {
  throw error(
      error_category::invalid_input,
      cellforge::detail::cat("loop_subdivide: face ", std::to_string(f), " has ",
                             (n > limit ? std::string("more than 3") : std::to_string(n)),
                             " vertices; Loop subdivision needs triangles (triangulate the mesh first)"));
}

/// Splits every triangle of the parent (records `he`, face anchors `anchors`, `nv`
/// vertices, no removed elements) into four: writes the child records (boundary children
/// get only their head; finish() links their rings) and the child face anchors. With
/// `vertex_anchors` (an array of at least nv entries), also writes each parent vertex's
/// anchor as a child face half-edge ending at it (what a closed child needs; see
/// write_edge_vertex_anchors for the others). Returns the number of face half-edges whose
/// twin runs the same way, i.e. twice the parent's flipped edges, which is exactly the
/// child's flipped edge count. Throws cellforge::error naming the first face that is not
/// a triangle or whose records are inconsistent; the outputs are then partly written and
/// must be discarded. O(F).
template <class = void>
std::size_t split_faces(std::span<const record> he, std::span<const std::uint32_t> anchors, std::uint32_t nv,
                        std::vector<record>& out, std::vector<std::uint32_t>& out_anchors,
                        std::uint32_t* vertex_anchors = nullptr) {
  const std::size_t nh = he.size();
  const auto ne = static_cast<std::uint32_t>(nh / 2);
  const auto nf = static_cast<std::uint32_t>(anchors.size());
  const std::uint32_t interior_base = 2 * ne;  // first interior child edge
  // The halves of parent edges (half-edges below 4E) are written in edge order, scattered;
  // the interior half-edges come face by face, in index order, so they are appended rather
  // than written over a value-initialised array (half the child records at 1M triangles:
  // about 100 MB less to fill).
  out.clear();
  reserve_large(out, 4 * std::size_t{ne} + 6 * std::size_t{nf});
  out.resize(4 * std::size_t{ne});
  record* o = out.data();
  std::uint32_t* oa = out_anchors.data();
  std::size_t flipped_sides = 0;

  for (std::uint32_t f = 0; f < nf; ++f) {
    std::uint32_t h[3];
    h[0] = anchors[f];
    h[1] = h[0] < nh ? he[h[0]].next : npos;
    h[2] = h[1] < nh ? he[h[1]].next : npos;
    if (h[2] >= nh)
      throw error(error_category::invalid_input, corrupted(f, "links to a half-edge that does not exist"));
    const record r[3] = {he[h[0]], he[h[1]], he[h[2]]};
    if (r[0].face != f || r[1].face != f || r[2].face != f)
      throw error(error_category::invalid_input,
                  corrupted(f, "has a half-edge that belongs to another face"));
    if (r[2].next != h[0]) not_a_triangle(f, face_size(he, h[0], nh), nh);
    // Corner k is the tail of h[k]: v[k] = head(h[k-1]).
    const std::uint32_t v[3] = {r[2].head, r[0].head, r[1].head};
    if (v[0] >= nv || v[1] >= nv || v[2] >= nv)
      throw error(error_category::invalid_input, corrupted(f, "uses a vertex that does not exist"));

    std::uint32_t first[3], second[3], mid[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t hk = h[k], e = hk >> 1, s = hk & 1u;
      const record& t = he[hk ^ 1u];
      const bool boundary = t.face == npos;
      const bool flipped = !boundary && t.head == r[k].head;
      flipped_sides += flipped;
      if (!flipped && t.head != v[k])
        throw error(error_category::invalid_input, corrupted(f, "has an edge whose two half-edges disagree"));
      // q = 1 when this half-edge runs B→A: its first half then lies on the B child edge.
      const std::uint32_t q = s & static_cast<std::uint32_t>(!flipped);
      first[k] = 4 * e + 2 * q + s;
      second[k] = 4 * e + 2 * (1u - q) + s;
      mid[k] = nv + e;
      if (boundary) {  // the faceless children point back at their twins' tails
        o[first[k] ^ 1u] = record{v[k], npos, npos, npos};
        o[second[k] ^ 1u] = record{mid[k], npos, npos, npos};
      }
    }

    const std::uint32_t fc = 4 * f;
    const std::uint32_t in = 2 * (interior_base + 3 * f);  // half-edge of interior edge k: in + 2k
    record interior[6];                                    // half-edges in .. in + 5
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t kp = (k + 2) % 3;  // the corner before k
      const std::uint32_t cut = in + 2 * k;  // m[k] → m[k-1], in corner face k
      o[first[k]] = record{mid[k], cut, second[kp], fc + k};
      interior[2 * k] = record{mid[kp], second[kp], first[k], fc + k};
      o[second[kp]] = record{v[k], first[k], cut, fc + k};
      // Centre face: m[k-1] → m[k] is the twin of cut.
      interior[2 * k + 1] = record{mid[k], in + 2 * ((k + 1) % 3) + 1, in + 2 * kp + 1, fc + 3};
      oa[fc + k] = first[k];
    }
    out.insert(out.end(), std::begin(interior), std::end(interior));
    oa[fc + 3] = in + 2 * 1 + 1;    // leaves m[0], the centre face's first vertex
    if (vertex_anchors != nullptr)  // second[k-1] ends at corner k, in corner face k
      for (int k = 0; k < 3; ++k) vertex_anchors[v[k]] = second[(k + 2) % 3];
  }
  return flipped_sides;
}

/// Writes the anchors of the child vertices on the parent's `ne` edges when the parent is
/// closed: the first half of half-edge 2e is child half-edge 4e (2e has side 0 and runs
/// A→B, so q = 0), a face half-edge ending at the edge's vertex nv + e. O(E), sequential.
template <class = void>
void write_edge_vertex_anchors(std::uint32_t nv, std::uint32_t ne, std::uint32_t* vertex_anchors) {
  for (std::uint32_t e = 0; e < ne; ++e) vertex_anchors[nv + e] = 4 * e;
}

/// The boundary edges after one step, from those before: both halves of each. O(#boundary).
template <class = void>
void split_boundary(std::vector<std::uint32_t>& boundary_edges) {
  const std::size_t n = boundary_edges.size();
  boundary_edges.resize(2 * n);
  for (std::size_t i = n; i-- > 0;) {
    const std::uint32_t e = boundary_edges[i];
    boundary_edges[2 * i] = 2 * e;
    boundary_edges[2 * i + 1] = 2 * e + 1;
  }
}

}  // namespace cellforge::detail::loop
