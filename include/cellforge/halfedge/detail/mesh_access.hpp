// SPDX-License-Identifier: MIT
#pragma once
// Internal access to halfedge_mesh's arrays for algorithms that construct meshes in closed
// form (e.g. Loop subdivision links children directly instead of searching for twins).
// Not part of the public API: a caller must leave the mesh valid (validate() passes).

#include <vector>

#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge::detail {

template <class = void>
struct basic_mesh_access;
using mesh_access = basic_mesh_access<>;

template <class>
struct basic_mesh_access {
  using record = halfedge_mesh::record;
  static std::vector<record>& records(halfedge_mesh& m) noexcept { return m.he_; }
  static std::vector<std::uint32_t>& vertex_anchors(halfedge_mesh& m) noexcept { return m.vertex_anchor_; }
  static std::vector<std::uint32_t>& face_anchors(halfedge_mesh& m) noexcept { return m.face_anchor_; }
  static property_registry& vertex_properties(halfedge_mesh& m) noexcept { return m.vprops_; }
  static property_registry& halfedge_properties(halfedge_mesh& m) noexcept { return m.hprops_; }
  static property_registry& edge_properties(halfedge_mesh& m) noexcept { return m.eprops_; }
  static property_registry& face_properties(halfedge_mesh& m) noexcept { return m.fprops_; }

  /// Resizes the element arrays and every property registry (new entries default). O(n).
  static void resize(halfedge_mesh& m, std::size_t nv, std::size_t ne, std::size_t nf) {
    detail::reserve_large(m.vertex_anchor_, nv);  // huge-page hints: fresh large arrays fault far less
    m.vertex_anchor_.resize(nv, halfedge_mesh::npos);
    detail::reserve_large(m.he_, 2 * ne);
    m.he_.resize(2 * ne);
    detail::reserve_large(m.face_anchor_, nf);
    m.face_anchor_.resize(nf, halfedge_mesh::npos);
    m.vprops_.resize(nv);
    m.hprops_.resize(2 * ne);
    m.eprops_.resize(ne);
    m.fprops_.resize(nf);
  }

  /// After the caller has written every face half-edge {head, next, prev, face}, every
  /// boundary half-edge's head (the tail of its twin) and every face anchor, derives
  /// vertex anchors, boundary rings, the unlinked table and the flipped count. O(n).
  /// The mesh must have no removed elements. With fan_check::trust (for constructions
  /// that cannot create a vertex with two closed fans, e.g. subdividing a valid mesh) the
  /// walk around every interior vertex that would detect one is skipped.
  enum class fan_check { verify, trust };
  static build_report finish(halfedge_mesh& m, const build_options& options = {},
                             fan_check check = fan_check::verify) {
    build_report r;
    m.removed_vertices_ = m.removed_edges_ = m.removed_faces_ = 0;
    m.link_fans(options, r, check == fan_check::verify);
    return r;
  }

  /// finish() for a CLOSED mesh (no boundary half-edge) built in closed form, when the
  /// caller has also written every vertex anchor (a face half-edge ending at the vertex,
  /// npos when isolated) and knows the number of flipped edges: the unlinked table is then
  /// empty and there are no rings, so nothing needs a pass over the half-edges. O(1).
  static void finish_closed(halfedge_mesh& m, std::size_t flipped_edges) noexcept {
    m.removed_vertices_ = m.removed_edges_ = m.removed_faces_ = 0;
    m.unlinked_.clear();
    m.flipped_edges_ = flipped_edges;
  }
};

}  // namespace cellforge::detail
