// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// validate(mesh): checks every invariant of the half-edge mesh and says which one
/// broke, at which element. Tests call it after every edit.

#include <cstdint>
#include <string>
#include <vector>

#include "cellforge/core/detail/edge_table.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

/// The invariants of halfedge_mesh, one per way it can break.
enum class mesh_invariant : std::uint8_t {
  none,            ///< everything holds
  property_size,   ///< a property array is not as long as its element array
  face_anchor,     ///< a face's half-edge is removed or belongs to another face
  face_loop,       ///< next/prev do not form a closed loop of the face's half-edges
  face_size,       ///< a face has fewer than 3 vertices or repeats one
  edge_endpoints,  ///< an edge's half-edges do not agree on its two end vertices
  edge_faces,      ///< an edge has no face, or a removed face
  flipped_count,   ///< the stored number of flipped edges is wrong
  unlinked_table,  ///< the unlinked table is not exactly the set of boundary face half-edges
  duplicate_edge,  ///< two edges join the same pair of vertices
  vertex_anchor,   ///< a vertex's anchor is removed, not incident, or of the wrong kind
  vertex_fans,     ///< the fans around a vertex do not reach every face at it
  boundary_ring,   ///< the ring of boundary half-edges around a vertex is broken
};

/// What validate() found: ok, or the first broken invariant, its element index and why.
struct mesh_validation {
  mesh_invariant broken = mesh_invariant::none;
  std::uint32_t element = 0xFFFFFFFFu;
  std::string message;
  bool ok() const noexcept { return broken == mesh_invariant::none; }
  explicit operator bool() const noexcept { return ok(); }
};

namespace detail {
template <class = void>
mesh_validation fail(mesh_invariant what, std::uint32_t element, std::string msg) {
  return {what, element, std::move(msg)};
}
}  // namespace detail

/// Checks every invariant of m: records, face loops, edges, the unlinked table, vertex
/// anchors, fans and boundary rings, property sizes. O(size of the mesh), expected.
template <class = void>
mesh_validation validate(const halfedge_mesh& m) {
  using detail::fail;
  const std::size_t nh = m.halfedges_size(), nv = m.vertices_size(), nf = m.faces_size();
  auto S = [](std::uint64_t x) { return std::to_string(x); };

  auto check_props = [&](const detail::property_registry& r, std::size_t n,
                         const char* kind) -> mesh_validation {
    for (std::size_t i = 0; i < r.num_properties(); ++i)
      if (r.array(i).size() != n)
        return fail(mesh_invariant::property_size, static_cast<std::uint32_t>(i),
                    cellforge::detail::cat(std::string(kind), " property '", r.array(i).name(), "' has ",
                                           S(r.array(i).size()), " entries for ", S(n), " elements"));
    if (r.size() != n)
      return fail(mesh_invariant::property_size, 0,
                  cellforge::detail::cat(std::string(kind), " property registry has the wrong size"));
    return {};
  };
  if (auto r = check_props(m.registry<vertex_handle>(), nv, "vertex"); !r) return r;
  if (auto r = check_props(m.registry<halfedge_handle>(), nh, "halfedge"); !r) return r;
  if (auto r = check_props(m.registry<edge_handle>(), nh / 2, "edge"); !r) return r;
  if (auto r = check_props(m.registry<face_handle>(), nf, "face"); !r) return r;

  // Faces: anchor, closed next/prev loop, size >= 3, no repeated vertex.
  std::vector<std::uint32_t> corners(nv, 0);
  for (std::uint32_t f = 0; f < nf; ++f) {
    const face_handle fh(f);
    if (m.is_removed(fh)) continue;
    const halfedge_handle a = m.halfedge(fh);
    if (!(a.idx() < nh) || m.is_removed(a) || m.face(a) != fh)
      return fail(mesh_invariant::face_anchor, f,
                  cellforge::detail::cat("face ", S(f), ": its half-edge is removed or in another face"));
    std::vector<std::uint32_t> vs;
    halfedge_handle h = a;
    do {
      if (!(h.idx() < nh) || m.face(h) != fh)
        return fail(mesh_invariant::face_loop, f,
                    cellforge::detail::cat("face ", S(f), ": half-edge ", S(h.idx()), " is not in it"));
      const halfedge_handle n = m.next(h);
      if (!(n.idx() < nh) || m.prev(n) != h)
        return fail(mesh_invariant::face_loop, f,
                    cellforge::detail::cat("face ", S(f), ": prev(next(", S(h.idx()), ")) is not itself"));
      if (m.head(m.prev(h)).idx() >= nv)
        return fail(mesh_invariant::face_loop, f,
                    cellforge::detail::cat("face ", S(f), ": a half-edge has no head vertex"));
      vs.push_back(m.head(h).idx());
      if (vs.size() > nh)
        return fail(mesh_invariant::face_loop, f,
                    cellforge::detail::cat("face ", S(f), ": next links do not close the loop"));
      h = n;
    } while (h != a);
    if (vs.size() < 3)
      return fail(mesh_invariant::face_size, f,
                  cellforge::detail::cat("face ", S(f), " has fewer than 3 vertices"));
    if (!detail::all_distinct(std::span<const std::uint32_t>(vs)))
      return fail(mesh_invariant::face_size, f, cellforge::detail::cat("face ", S(f), " repeats a vertex"));
    for (std::uint32_t v : vs) {
      if (m.is_removed(vertex_handle(v)))
        return fail(mesh_invariant::face_loop, f,
                    cellforge::detail::cat("face ", S(f), " uses removed vertex ", S(v)));
      ++corners[v];
    }
  }

  // Edges: endpoints agree, at least one face, flipped count, unlinked table, no duplicates.
  std::size_t flipped = 0, unlinked = 0;
  detail::edge_table pairs;  // undirected vertex pairs seen so far
  pairs.reserve(nh / 2);
  const auto& table = m.unlinked_table();
  for (std::uint32_t e = 0; e < nh / 2; ++e) {
    const edge_handle eh(e);
    if (m.is_removed(eh)) {
      if (!m.is_removed(halfedge_mesh::halfedge(eh, 1)))
        return fail(mesh_invariant::edge_endpoints, e,
                    cellforge::detail::cat("edge ", S(e), ": only one of its half-edges was removed"));
      continue;
    }
    const halfedge_handle h0 = halfedge_mesh::halfedge(eh, 0), h1 = halfedge_mesh::halfedge(eh, 1);
    const bool f0 = !m.is_boundary(h0), f1 = !m.is_boundary(h1);
    if (!f0 && !f1)
      return fail(mesh_invariant::edge_faces, e, cellforge::detail::cat("edge ", S(e), " has no face"));
    if ((f0 && m.is_removed(m.face(h0))) || (f1 && m.is_removed(m.face(h1))))
      return fail(mesh_invariant::edge_faces, e,
                  cellforge::detail::cat("edge ", S(e), " refers to a removed face"));
    const vertex_handle a0 = m.tail(h0), b0 = m.head(h0), a1 = m.tail(h1), b1 = m.head(h1);
    if (a0.idx() >= nv || b0.idx() >= nv || a1.idx() >= nv || b1.idx() >= nv || a0 == b0)
      return fail(mesh_invariant::edge_endpoints, e,
                  cellforge::detail::cat("edge ", S(e), " has invalid end vertices"));
    const bool same_dir = a0 == a1 && b0 == b1, opposite = a0 == b1 && b0 == a1;
    if (!(opposite || (same_dir && f0 && f1)))
      return fail(
          mesh_invariant::edge_endpoints, e,
          cellforge::detail::cat("edge ", S(e), ": its half-edges join different vertices (", S(a0.idx()),
                                 "->", S(b0.idx()), " vs ", S(a1.idx()), "->", S(b1.idx()), ")"));
    for (const halfedge_handle b : {h0, h1}) {
      if (!m.is_boundary(b)) continue;
      for (const halfedge_handle l : {m.next(b), m.prev(b)})
        if (l.idx() >= nh || m.is_removed(l) || !m.is_boundary(l))
          return fail(mesh_invariant::boundary_ring, e,
                      cellforge::detail::cat("boundary half-edge ", S(b.idx()),
                                             ": a ring link is not a live boundary half-edge"));
    }
    if (same_dir) ++flipped;
    if (same_dir != m.is_flipped(eh))
      return fail(mesh_invariant::flipped_count, e,
                  cellforge::detail::cat("edge ", S(e), ": is_flipped() disagrees with its heads"));
    if (!pairs.try_insert(detail::edge_table::key(std::min(a0.idx(), b0.idx()), std::max(a0.idx(), b0.idx())),
                          e))
      return fail(mesh_invariant::duplicate_edge, e,
                  cellforge::detail::cat("edge ", S(e), " joins vertices ", S(a0.idx()), " and ", S(b0.idx()),
                                         ", as another edge does"));
    if (f0 != f1) {
      ++unlinked;
      const halfedge_handle fh = f0 ? h0 : h1;
      const std::uint32_t found = m.find_unlinked(m.tail(fh), m.head(fh)).idx();
      if (found != fh.idx())
        return fail(mesh_invariant::unlinked_table, e,
                    cellforge::detail::cat("boundary edge ", S(e), ": its face half-edge ", S(fh.idx()),
                                           " is not in the unlinked table"));
    }
  }
  if (flipped != m.num_flipped_edges())
    return fail(mesh_invariant::flipped_count, 0,
                cellforge::detail::cat("the mesh counts ", S(m.num_flipped_edges()),
                                       " flipped edges, there are ", S(flipped)));
  if (unlinked != table.size())
    return fail(mesh_invariant::unlinked_table, 0,
                cellforge::detail::cat("the unlinked table holds ", S(table.size()),
                                       " half-edges, the mesh has ", S(unlinked), " boundary edges"));

  // Vertices: anchor, fans reaching every face, boundary rings.
  for (std::uint32_t v = 0; v < nv; ++v) {
    const vertex_handle vh(v);
    if (m.is_removed(vh)) {
      if (corners[v] != 0)
        return fail(mesh_invariant::vertex_anchor, v,
                    cellforge::detail::cat("removed vertex ", S(v), " is still used"));
      continue;
    }
    const halfedge_handle a = m.anchor(vh);
    if (!a.is_valid()) {
      if (corners[v] != 0)
        return fail(mesh_invariant::vertex_anchor, v,
                    cellforge::detail::cat("vertex ", S(v), " has faces but no anchor half-edge"));
      continue;
    }
    if (a.idx() >= nh || m.is_removed(a) || (m.head(a) != vh && m.tail(a) != vh))
      return fail(mesh_invariant::vertex_anchor, v,
                  cellforge::detail::cat("vertex ", S(v), ": its anchor half-edge is not incident to it"));
    std::size_t faces = 0, boundary_ends = 0, steps = 0;
    for (auto w = detail::vertex_walker<halfedge_mesh>(&m, vh); !w.at_end(); w.advance()) {
      if (++steps > 4 * nh + 4)
        return fail(mesh_invariant::boundary_ring, v,
                    cellforge::detail::cat("vertex ", S(v), ": the walk around it does not end"));
      const halfedge_handle h = w.current();
      if (m.head(h) != vh && m.tail(h) != vh)
        return fail(mesh_invariant::vertex_fans, v,
                    cellforge::detail::cat("vertex ", S(v), ": the walk left its fan"));
      if (w.event() == vertex_event::face) ++faces;
      if (w.event() == vertex_event::edge && m.is_boundary(h)) ++boundary_ends;
    }
    if (faces != corners[v])
      return fail(mesh_invariant::vertex_fans, v,
                  cellforge::detail::cat("vertex ", S(v), ": the walk around it meets ", S(faces),
                                         " faces, it is in ", S(corners[v])));
    if (m.is_boundary(a) && boundary_ends % 2 != 0)
      return fail(mesh_invariant::boundary_ring, v,
                  cellforge::detail::cat("vertex ", S(v), ": an open fan has only one boundary end"));
    if (!m.is_boundary(a) && boundary_ends != 0)
      return fail(mesh_invariant::vertex_anchor, v,
                  cellforge::detail::cat("vertex ", S(v),
                                         " is on a boundary but its anchor is an interior half-edge"));
  }
  return {};
}

}  // namespace cellforge
