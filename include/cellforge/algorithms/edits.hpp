// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Local edits of a triangle mesh that keep every invariant of halfedge_mesh: half-edge
/// collapse and face collapse (seed 001 §IV.C), edge split and edge flip.
///
/// Convention, the same for every edit: a *refusal* (the edit would break the structure)
/// is returned, never thrown — `edit_result::refusal` says why and the mesh is left
/// exactly as it was; `can_*` queries return the same reason without editing. Misuse
/// (a removed or out-of-range handle, a non-finite position, a missing position
/// property) throws cellforge::error(invalid_input) before anything changes.
/// Every edit removes the faces it rewrites and adds their replacements through the
/// mesh's own remove_face/add_face, so the faces it touches get new handles; face,
/// half-edge and edge properties follow them (see docs/edits.md).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/detail/mesh_access.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"

namespace cellforge {

/// Why an edit was refused (`none`: it is allowed, or it was done).
enum class edit_refusal : std::uint8_t {
  none,                ///< allowed / done
  not_triangle,        ///< a face the edit rewrites is not a triangle
  nonmanifold_vertex,  ///< a vertex that would be merged has several fans of faces (a bow-tie)
  boundary_vertices,   ///< both ends are on the boundary but the edge is interior: the surface would pinch
  link_condition,      ///< the ends share a neighbour not opposite the edge: an edge would get a third face
  tetrahedron,  ///< a vertex would keep two edges and two faces would coincide (any edge of a tetrahedron)
  isolated_triangle,  ///< a triangle whose other edges are on the boundary would shrink to a dangling edge
  degenerate,         ///< two faces at the edit share all their vertices (a two-triangle pillow)
  boundary_edge,      ///< flip: the edge has only one face
  edge_exists,        ///< flip: the other diagonal is already an edge
  fixed_vertex,       ///< simplify: the collapse would move or remove a vertex kept fixed
  normal_flip,        ///< simplify: a face's normal would turn more than allowed, or the face degenerate
};
/// Number of edit_refusal values (for per-reason counters).
inline constexpr std::size_t num_edit_refusals = 12;

/// A sentence saying why an edit was refused. O(1).
constexpr std::string_view to_string(edit_refusal r) noexcept {
  switch (r) {
    case edit_refusal::none:
      return "allowed";
    case edit_refusal::not_triangle:
      return "a face the edit rewrites is not a triangle";
    case edit_refusal::nonmanifold_vertex:
      return "a vertex to merge has several fans of faces (non-manifold vertex)";
    case edit_refusal::boundary_vertices:
      return "both ends are on the boundary but the edge is interior (the surface would pinch)";
    case edit_refusal::link_condition:
      return "the two ends share a neighbour that is not opposite the edge (link condition)";
    case edit_refusal::tetrahedron:
      return "a vertex would be left with two edges and two faces would coincide (tetrahedron)";
    case edit_refusal::isolated_triangle:
      return "a triangle with its other edges on the boundary would shrink to a dangling edge";
    case edit_refusal::degenerate:
      return "two faces at the edit have the same vertices";
    case edit_refusal::boundary_edge:
      return "the edge has only one face";
    case edit_refusal::edge_exists:
      return "the other diagonal is already an edge";
    case edit_refusal::fixed_vertex:
      return "the collapse would move or remove a fixed vertex";
    case edit_refusal::normal_flip:
      return "a face would turn over or degenerate";
  }
  return "unknown";
}

/// What an edit did. Converts to true when it was done. stage_report: milliseconds the call, the
/// refusal's sentence as the diagnostic when refused.
struct edit_result : stage_report {
  edit_refusal refusal = edit_refusal::none;
  vertex_handle vertex;  ///< collapses: the vertex kept; split: the new vertex
  edge_handle edge;      ///< flip: the new edge
  std::size_t vertices_removed = 0, faces_removed = 0, faces_added = 0;  ///< net counts
  bool ok() const noexcept { return refusal == edit_refusal::none; }
  explicit operator bool() const noexcept { return ok(); }
};

/// Where a collapse puts the vertex it keeps (templated overloads only).
enum class collapse_position : std::uint8_t {
  keep_head,  ///< where the kept vertex already is
  midpoint,   ///< halfway along the collapsed edge
  custom,     ///< at collapse_options::point
};
/// Options of the position-aware collapse overloads.
struct collapse_options {
  collapse_position position = collapse_position::keep_head;
  glm::dvec3 point{0.0};  ///< used with collapse_position::custom
};

// ==================================================================== half-edge collapse

/// Whether collapse_halfedge(m, h) would be done, or why not (mesh unchanged).
/// O((d_u + d_v) log d) for the degrees d of the two ends. Throws on an invalid handle.
template <class = void>
edit_refusal can_collapse(const halfedge_mesh& m, halfedge_handle h);
/// Whether edge e can be collapsed into its end `keep` (either direction, also on a
/// flipped edge whose two half-edges run the same way). O((d_u + d_v) log d).
template <class = void>
edit_refusal can_collapse(const halfedge_mesh& m, edge_handle e, vertex_handle keep);

/// Merges tail(h) into head(h), removing the edge's one or two triangles; positions are
/// untouched. Refuses (see edit_refusal) when the result would not be a valid surface of the
/// same topology. O((d_u + d_v) log d) plus add_face's O(degree) check per new boundary edge.
template <class = void>
edit_result collapse_halfedge(halfedge_mesh& m, halfedge_handle h);

/// Collapses edge e into its end `keep` (the other end is removed); the way to collapse a
/// flipped edge "backwards". Same checks and cost as collapse_halfedge.
template <class = void>
edit_result collapse_edge(halfedge_mesh& m, edge_handle e, vertex_handle keep);

/// collapse_halfedge, then moves the kept vertex as `options` says. Same checks and cost.
template <Point3 P>
edit_result collapse_halfedge(surface_mesh<P>& m, halfedge_handle h, const collapse_options& options);

// ==================================================================== face collapse

/// Whether collapse_face(m, f) would be done, or why not (mesh unchanged).
/// O(sum of the degrees of f's corners, times log). Throws on an invalid handle.
template <class = void>
edit_refusal can_collapse_face(const halfedge_mesh& m, face_handle f);

/// Collapses triangle f into its first vertex (seed 001 §IV.C): f and its up to three
/// neighbours disappear, two vertices are removed. On a mesh without positions the kept vertex
/// stays where it is; a surface_mesh takes the overload below. Refuses unless some
/// order of merging the corners is two valid edge collapses. O(sum of corner degrees, × log).
template <class = void>
edit_result collapse_face(halfedge_mesh& m, face_handle f);

/// collapse_face, then moves the kept vertex to the triangle's centroid (every collapse_face
/// on a surface_mesh does this). Same checks and cost.
template <Point3 P>
edit_result collapse_face(surface_mesh<P>& m, face_handle f);

// ==================================================================== edge split

/// Adds a vertex on edge e: each triangle on e becomes two (a larger face just gains the
/// vertex), every face keeping its orientation; on a flipped edge both halves stay flipped.
/// Never refused. Position untouched. O(size of the faces of e).
template <class = void>
edit_result split_edge(halfedge_mesh& m, edge_handle e);

/// split_edge, placing the new vertex at `position`.
/// Throws before editing if the position is not finite. Same cost.
template <Point3 P>
edit_result split_edge(surface_mesh<P>& m, edge_handle e, const std::type_identity_t<P>& position);

// ==================================================================== edge flip

/// Whether flip_edge(m, e) would be done, or why not. O(degree of one end).
/// Throws on an invalid handle.
template <class = void>
edit_refusal can_flip(const halfedge_mesh& m, edge_handle e);

/// Replaces interior edge e of triangles (x, y, c) and (.., d) by the edge c-d. Both new
/// triangles take the orientation of e's first face (the face of halfedge(e, 0)): on an
/// oriented mesh that is everyone's; on a flipped edge the seam moves to the two sides at
/// d. Refuses at the boundary, on non-triangles and when c-d exists. O(degree of c).
template <class = void>
edit_result flip_edge(halfedge_mesh& m, edge_handle e);

}  // namespace cellforge

#include "cellforge/algorithms/detail/edits_impl.hpp"
