// SPDX-License-Identifier: MIT
#pragma once
// The tube mesher's half-edge build: faces that should form a closed, consistently oriented
// surface (every directed edge a -> b met by exactly one b -> a) are linked one by one as the
// mesher emits them, then one walk around every vertex checks the fans, where
// basic_halfedge_mesh::build buckets every corner of a finished face list by vertex first
// (four passes, two of them scattered over the whole mesh). The tube's faces come ring by
// ring, so a corner's twin is almost always among the last few dozen corners: a list of open
// edges per vertex finds it in cache, and no face list is kept (at 10^7 faces it was 200 MB
// written and read back once). The records are the ones build writes (same edge numbering,
// same vertex anchors); anything that is not a closed oriented surface is given back as a
// face list for build, which reports it.

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <span>
#include <utility>
#include <vector>

#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/core/detail/union_find.hpp"
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

/// Links the faces of a closed, consistently oriented surface into half-edge records as they
/// come (add_face), and hands them to a mesh (finish). A face that cannot belong to such a
/// surface stops the linking; faces() then gives every face back for build to report. Each
/// face costs O(its size × the open edges at its vertices): O(1) per corner for tubes.
template <class = void>
class basic_closed_linker {
 public:
  static constexpr std::uint32_t npos = halfedge_mesh::npos;

  /// Room for this many vertices, corners and faces (a hint: more may come). O(1).
  void reserve(std::size_t vertices, std::size_t corners, std::size_t faces) {
    reserve_large(first_, vertices);
    reserve_large(anchor_, vertices);
    reserve_large(he_, corners);
    reserve_large(face_anchor_, faces);
  }

  /// Links face vs (its vertices counter-clockwise seen from outside); false once the faces
  /// cannot be a closed surface of single vertices (a vertex repeated in a face, too many
  /// vertices or corners for 32-bit indices); the face is then kept with the others for
  /// faces(). O(face size) when the twins are near.
  bool add_face(std::span<const std::uint32_t> vs) {
    if (failed_) return keep(vs);
    // Triangles and quads, nearly every face of a tube mesh, have their size at compile time:
    // the loops unroll and the wrap-arounds fold away.
    if (vs.size() == 4) return add<4>(vs.data(), 4);
    if (vs.size() == 3) return add<3>(vs.data(), 3);
    return add<0>(vs.data(), vs.size());
  }

  /// Faces given so far (linked or kept). O(1).
  std::size_t num_faces() const noexcept { return failed_ ? offsets_.size() - 1 : num_faces_; }

  /// When the faces over `num_vertices` vertices form a closed, consistently oriented surface:
  /// moves the records into `mesh` (no faces yet; its property registries are resized, their
  /// values kept) and returns the number of connected components. Otherwise returns npos and
  /// leaves the mesh alone (faces() gives the faces back). A vertex with two closed fans throws
  /// as build does. O(corners).
  std::size_t finish(halfedge_mesh& mesh, std::size_t num_vertices) {
    using access = mesh_access;
    const std::size_t nh = 2 * std::size_t{next_edge_};
    if (failed_ || unmatched_ != 0 || num_vertices < vertices_ || num_vertices >= npos / 2 ||
        mesh.halfedges_size() != 0 || mesh.faces_size() != 0) {
      fail();
      return npos;
    }
    he_.resize(nh);
    anchor_.resize(num_vertices, npos);
    const std::size_t nf = num_faces_;
    face_anchor_.resize(nf);
    access::records(mesh).swap(he_);
    access::vertex_anchors(mesh).swap(anchor_);
    access::face_anchors(mesh).swap(face_anchor_);
    access::vertex_properties(mesh).resize(num_vertices);
    access::halfedge_properties(mesh).resize(nh);
    access::edge_properties(mesh).resize(nh / 2);
    access::face_properties(mesh).resize(nf);
    const std::vector<halfedge_mesh::record>& he = access::records(mesh);
    const std::vector<std::uint32_t>& anchor = access::vertex_anchors(mesh);
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
    if (reached != nh)
      access::finish(mesh);  // names the vertex where fans meet (throws)
    else
      access::finish_closed(mesh, 0);  // every twin pair runs both ways: no flipped edge
    // Components: the open-edge lists are all empty now; their array becomes the union-find.
    union_find sets;
    sets.parent.swap(first_);
    sets.parent.resize(num_vertices);
    std::iota(sets.parent.begin(), sets.parent.end(), std::uint32_t{0});
    std::size_t components = num_vertices;
    for (std::size_t h = 0; h < nh; h += 2) components -= sets.unite(he[h].head, he[h + 1].head) ? 1 : 0;
    return components;
  }

  /// Every face given, in order, as a face list (CSR) for build; frees the records, and the
  /// linker holds no face afterwards. O(corners).
  void faces(std::vector<std::uint32_t>& offsets, std::vector<std::uint32_t>& vertices) {
    fail();
    offsets = std::move(offsets_);
    vertices = std::move(fv_);
    offsets_.assign(1, 0);
    fv_.clear();
  }

 private:
  // A face of k corners (K > 0: k known at compile time) checked, then linked.
  template <std::uint32_t K>
  bool add(const std::uint32_t* vs, std::size_t k_run) {
    const std::size_t k = K != 0 ? K : k_run;
    bool ok = k >= 3 && k < npos / 4 && he_.size() < npos / 2 - 2 * k && num_faces_ < npos - 1;
    std::uint32_t top = 0;
    for (std::size_t c = 0; c < k; ++c) {
      ok = ok && vs[c] < npos / 2;
      top = std::max(top, vs[c]);
      for (std::size_t d = 0; d < c; ++d) ok = ok && vs[d] != vs[c];  // a repeated vertex: build names it
    }
    if (!ok) {
      fail();
      return keep({vs, k});
    }
    if (top >= vertices_) {
      vertices_ = top + 1;
      if (vertices_ > first_.size()) grow(vertices_);
    }
    if (K == 0 && corner_half_.size() < k) corner_half_.resize(k);
    link<K>(vs, static_cast<std::uint32_t>(k));
    return true;
  }

  // Edges are numbered as build numbers them, in order of first use: a corner a -> b with no
  // twin yet opens edge e and takes half-edge 2e; until its twin comes, the twin's record 2e + 1
  // serves as scratch, on a list of such open edges per vertex (from first_[a] through .next,
  // with .head = b), so the matching needs no arrays of its own; the twin b -> a finds it on
  // a's list and takes 2e + 1. A face's records are written once all its corners have their
  // half-edges.
  template <std::uint32_t K>
  void link(const std::uint32_t* vs, std::uint32_t k_run) {
    const std::uint32_t k = K != 0 ? K : k_run;
    std::uint32_t local[K != 0 ? K : 1];
    std::uint32_t* const half = K != 0 ? local : corner_half_.data();
    for (std::uint32_t i = 0; i < k; ++i) {
      const std::uint32_t a = vs[i], b = vs[i + 1 == k ? 0 : i + 1];
      // The twin leaves b for a: an open edge on b's list whose other end is a.
      std::uint32_t before = npos, t = first_[b];
      while (t != npos && he_[t].head != a) before = t, t = he_[t].next;
      if (t != npos) {
        (before == npos ? first_[b] : he_[before].next) = he_[t].next;
        half[i] = t;
        --unmatched_;
      } else {
        const std::uint32_t h = 2 * next_edge_++;
        if (h == he_.size()) he_.resize(he_.size() + chunk);
        he_[h + 1] = {b, first_[a], npos, npos};  // h: written with its face below
        first_[a] = h + 1;
        half[i] = h;
        ++unmatched_;
      }
    }
    const auto f = static_cast<std::uint32_t>(num_faces_++);
    if (f == face_anchor_.size()) face_anchor_.resize(face_anchor_.size() + chunk);
    face_anchor_[f] = half[0];
    for (std::uint32_t i = 0; i < k; ++i) {
      const std::uint32_t h = half[i], v = vs[i + 1 == k ? 0 : i + 1];
      halfedge_mesh::record& r = he_[h];
      r.head = v;
      r.next = half[i + 1 == k ? 0 : i + 1];
      r.prev = half[i == 0 ? k - 1 : i - 1];
      r.face = f;
      if (anchor_[v] == npos || anchor_[v] < h) anchor_[v] = h;  // as build's: the last one in
    }
  }

  // Room for vertex ids below n in the per-vertex arrays (rings add vertices a few at a time:
  // the arrays double).
  void grow(std::size_t n) {
    const std::size_t size = std::max(n, 2 * first_.size());
    first_.resize(size, npos);
    anchor_.resize(size, npos);
  }

  // From here on the faces are kept as a list: those linked so far are read back from their
  // records (face f starts at the tail of its anchor half-edge) and the records freed.
  void fail() {
    if (failed_) return;
    failed_ = true;
    offsets_.assign(1, 0);
    face_anchor_.resize(num_faces_);
    for (const std::uint32_t a : face_anchor_) {
      const std::uint32_t last = he_[a].prev;
      std::uint32_t h = last;
      do {
        fv_.push_back(he_[h].head);
        h = he_[h].next;
      } while (h != last);
      offsets_.push_back(static_cast<std::uint32_t>(fv_.size()));
    }
    release(he_);
    release(first_);
    release(anchor_);
    release(face_anchor_);
  }
  bool keep(std::span<const std::uint32_t> vs) {
    fv_.insert(fv_.end(), vs.begin(), vs.end());
    offsets_.push_back(static_cast<std::uint32_t>(fv_.size()));
    return false;
  }

  // The records and face anchors grow by a chunk that stays in cache until written over
  // (push_back per element is an out-of-line call: 4% of make_tubes' instructions).
  static constexpr std::size_t chunk = 4096;
  std::vector<halfedge_mesh::record> he_;
  std::vector<std::uint32_t> first_;        // per vertex: its list of open edges
  std::vector<std::uint32_t> anchor_;       // per vertex: the last half-edge into it
  std::vector<std::uint32_t> face_anchor_;  // per face: the half-edge leaving its first vertex
  std::vector<std::uint32_t> corner_half_ = std::vector<std::uint32_t>(8);  // faces of 5+ corners
  std::uint32_t next_edge_ = 0;
  std::size_t num_faces_ = 0;
  std::size_t vertices_ = 0;  // one more than the largest vertex id in a face
  std::size_t unmatched_ = 0;
  bool failed_ = false;
  std::vector<std::uint32_t> offsets_, fv_;  // once failed: every face as a list
};
using closed_linker = basic_closed_linker<>;

}  // namespace cellforge::detail::tubes
