// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Tube networks (seed 001 §V): a skeleton graph with radii becomes one
/// closed, oriented 2-manifold per connected component, whose genus is the graph's cycle rank.
/// `make_tubes(g, options)` runs the stages: the tube construct (tube_construct.hpp), the
/// branch meshes (branch_mesh.hpp), the node paths (node_path.hpp), and the mesh.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/loop_subdivision.hpp"
#include "cellforge/algorithms/piece_self_intersections.hpp"
#include "cellforge/algorithms/self_intersections.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/if_satisfied.hpp"
#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/morton.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/halfedge/mesh_geometry.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"
#include "cellforge/tubes/branch_mesh.hpp"
#include "cellforge/tubes/detail/closed_build.hpp"
#include "cellforge/tubes/detail/tube_buffer.hpp"
#include "cellforge/tubes/node_path.hpp"
#include "cellforge/tubes/skeleton.hpp"
#include "cellforge/tubes/tube_construct.hpp"

namespace cellforge {

/// Name of the face property of a tube mesh that says what each face was made for.
inline constexpr std::string_view tube_source_property_name = "f:tube_source";

/// How make_tubes shapes the tubes. The defaults are the seed's where it has one.
struct tubes_options {
  /// Vertices of each cross-section (8: an octagon; 4 gives the seed's square sections).
  std::uint32_t sides = 8;
  /// Fraction of half the angle between two edges at a junction that a cross-section's cap
  /// may fill on the junction's sphere (below 1, so that caps never touch).
  double cap_separation = 0.9;
  /// A node of degree 2 whose path turns by more than this (degrees) is meshed as a junction
  /// of two cross-sections, as a branch is (§V.D), instead of a mitred bend.
  double bend_limit_degrees = 45;
  /// §V.D method 1: a sharp bend's junction gets a virtual cross-section on the outside of
  /// the bend (kept as surface, no tube), which keeps the bend round instead of pinched. A
  /// junction of three or more edges that all leave to one side always gets one.
  bool bend_virtual_section = true;
  /// How cross-sections are turned along a path (§V.C); global by default.
  tube_alignment alignment = tube_alignment::global;
  /// §V.D method 3: this many points spread evenly over each junction's sphere are added to
  /// its hull, at the junction's radius, except those that would cut a cross-section's cap (0:
  /// none, the default by measurement — docs/tubes.md).
  std::uint32_t junction_extra_points = 0;
  /// Run the exact self-intersection check on the result (tube_self_intersections: the answer
  /// of algorithms/self_intersections.hpp at about the meshing's time on trees and lattices) and
  /// report it in tubes_result. make_tubes does not check the skeleton's clearance: tubes whose
  /// edges pass closer than their radii intersect.
  bool check_self_intersections = false;
  /// When the mesh folds or (with check_self_intersections) meets itself, the junctions beside
  /// each defect are meshed again the careful way (rings kept off winding paths, no merging),
  /// the best mesh kept: at most this many more meshings (0: none; docs/tubes.md, "Repair").
  int repair_rounds = 4;
  /// Levels of Loop subdivision applied at the end (the seed smooths its tubes so); with
  /// any, the faces are triangulated first (fans) and the result is all triangles.
  int subdivision_levels = 0;
  /// Names of the nodes for messages and diagnostics, one per node (an SWC file's sample ids,
  /// io::swc_result::ids): "sample 17" instead of "node 3". Empty: node indices. Not copied.
  std::span<const std::int64_t> node_ids = {};
};

/// What make_tubes built, and how long each stage took. stage_report: milliseconds the whole
/// call; complete false when the self-intersection check stopped at its budget; diagnostics what
/// the mesher decided on its own, one sentence each (sharp bends, virtual sections, inserted
/// nodes, spheres, a genus that differs from the cycle rank).
template <Point3 P>
struct tubes_result : stage_report {
  surface_mesh<P> mesh;  ///< with face property "f:tube_source" (tube_face_source)
  tube_construct construct;
  std::size_t junctions = 0;       ///< branches and sharp bends meshed as junctions
  std::size_t bend_junctions = 0;  ///< of which sharp bends of degree-2 nodes
  std::size_t paths = 0, closed_paths = 0, end_caps = 0, spheres = 0;
  std::size_t virtual_sections = 0;  ///< junctions given a virtual cross-section (see tubes_options)
  /// Path nodes merged with a neighbour: closer to it than their turns' mitres reach
  /// (r tan(β/2) each side), where the tube between them would fold back (docs/tubes.md).
  std::size_t merged_nodes = 0;
  /// Path nodes taken into a junction's surface: nearer the junction than its cross-section
  /// must sit to clear the junction's other edges, so the cross-section moves past them.
  std::size_t absorbed_nodes = 0;
  /// Junction cross-sections shrunk to fit: no node left to move past (the path's other end),
  /// so the cross-section keeps its cap on the junction's sphere and moves in, narrower
  /// (docs/tubes.md, "Junctions that lack room").
  std::size_t shrunk_sections = 0;
  /// Junctions merged into a neighbouring one: the path between them too short for their
  /// cross-sections. `construct` is then that of the merged skeleton; sources, section ratios
  /// and messages keep the caller's numbering.
  std::size_t merged_junctions = 0;
  /// Junctions whose hull was that of an earlier junction of the same shape: the same points
  /// on its sphere, bit for bit or but for rounding and certified (docs/tubes.md, "Junction
  /// shapes seen before"); a regular lattice's junctions nearly all are.
  std::size_t reused_junction_hulls = 0;
  std::int64_t cycle_rank = 0;  ///< E − V + C of the skeleton
  std::int64_t genus = 0;       ///< of the mesh: Σ over shells (2 − χ) / 2
  std::size_t shells = 0;       ///< connected components of the mesh
  /// Stage times. Faces are linked into half-edges as they are made, so the junction and path
  /// stages include their faces' linking; mesh_ms is the check of every vertex's fan, the shells
  /// and the move into the caller's point type.
  double construct_ms = 0, junctions_ms = 0, paths_ms = 0, mesh_ms = 0, subdivision_ms = 0;
  /// Quality: per skeleton edge, the smallest cross-section along it (the area of a ring of
  /// its path seen along the tube, over π r² of its node; a regular octagon is 0.90; NaN for
  /// an edge with no ring of its own, e.g. between two junctions' rings), the smallest over
  /// all edges, and the smallest and largest corner angle of any face as built, before any
  /// subdivision (degrees).
  std::vector<double> section_ratio;
  double min_section_ratio = 0;
  double min_corner_deg = 0, max_corner_deg = 0;
  /// With options.check_self_intersections: face pairs that intersect (0 for an embedded
  /// mesh), and whether the check finished within its budget.
  std::size_t self_intersecting_face_pairs = 0;
  /// Edges where the surface folds back onto itself (folded_edges, halfedge/mesh_geometry.hpp:
  /// the two faces' normals more than 160° apart), always checked: 0 for a good mesh.
  std::size_t folded_edges = 0;
  bool self_intersections_checked = false;
  double check_ms = 0;
  /// Meshings spent on repair (tubes_options::repair_rounds), and how many skeleton nodes the
  /// mesh returned marked for the careful way: the junctions beside each defect and the nodes
  /// merged into a defective merged junction (0 when the first mesh was kept).
  int repair_rounds = 0;
  std::size_t careful_nodes = 0;
};

namespace detail::tubes {
/// make_tubes' result type for skeleton type G (unconstrained, for detail::if_satisfied_t).
template <class G>
using tubes_result_for = tubes_result<typename skeleton_traits<G>::point_type>;
}  // namespace detail::tubes

/// Meshes the skeleton g as tubes: a closed, oriented 2-manifold per connected component
/// (genus = cycle rank), quads along edges and triangles at junctions, positions in g's point
/// type. Throws cellforge::error naming the node or edge for input it cannot mesh (see
/// validate(skeleton); edges too close in angle at a junction). O(V + E) for bounded degree,
/// O(k log k) per junction of degree k.
template <Skeleton G>
detail::if_satisfied_t<Skeleton<G>, detail::tubes::tubes_result_for, G> make_tubes(
    const G& g, const tubes_options& options = {});

/// The pieces of a tube mesh for self_intersections_by_pieces: the faces of one source
/// ("f:tube_source": the tube along one skeleton edge, one junction, one end cap, one sphere)
/// form one piece; every face piece 0 when the mesh has no such property. O(F).
template <Point3 P>
std::vector<std::uint32_t> tube_pieces(const surface_mesh<P>& mesh);

/// The exact self-intersection check of a tube mesh: self_intersections_by_pieces(mesh,
/// tube_pieces(mesh), options), the same answer as self_intersections(mesh, options) on any mesh,
/// at about the meshing's cost instead of 6–10 times it (docs/tubes.md, "The check by pieces");
/// a mesh without "f:tube_source" goes to self_intersections.
/// O(F + the triangle pairs of pieces no certificate holds), bounded by the work budget.
template <Point3 P>
self_intersection_result tube_self_intersections(const surface_mesh<P>& mesh,
                                                 const self_intersection_options& options = {});

}  // namespace cellforge

#include "cellforge/tubes/detail/tube_mesh_impl.hpp"
