// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Reconstruction with rounds and fillets (seed 003 §"Rounds and fillets",
/// stages 3 and 4): the skeleton drawing of round_skeleton is read by drawing_to_cells, then
/// every skeleton edge that carried a blend gets its 3D radius from its end curves and the
/// reconstructed face planes, and becomes a circular-arc blend between its two faces (a convex
/// round or a concave fillet); rounded_mesh gives the rounded solid as a polygon mesh (faces
/// trimmed back by each blend's setback, blend strips tessellated to a chord tolerance) for the
/// io writers (OBJ, PLY). See docs/sketch.md, "Rounds and fillets".

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <Eigen/Dense>
#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/rounded_solid.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/sketch/drawing_to_cells.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/round_skeleton.hpp"

namespace cellforge {

/// Options of reconstruct_rounds.
struct rounds_options {
  round_skeleton_options skeleton{};
  drawing_options reading{};
  /// Largest relative disagreement a blend may show and still be called consistent: between the
  /// radii of its two end curves, of an end curve seen along the edge from a circle (1 − minor /
  /// major), and of an end curve's centre from the blend's axis (over the radius).
  double consistency = 1e-2;
  /// An end curve is taken as a circle square to the edge (its radius the 2D major semi-axis,
  /// whatever the reading) when its minor axis is within this angle (radians) of the edge's
  /// drawing direction: the image of such a circle has its minor axis along the image of its
  /// normal, the edge.
  double circle_angle = 1e-3;
};

/// Where a blend's radius comes from: the end curves lifted onto the reading's end faces and
/// seen along the edge; the 2D major semi-axes of end curves that are circles square to the
/// edge (when the lifted curves disagree: a reading that is not metric); none.
enum class radius_source : std::uint8_t { lifted, circle_2d, none };

/// The round attribute of one skeleton edge: the blend that carried it, its radius in the
/// reconstruction's units (x, y the drawing's), convex or concave, the blend's 3D frame, and how
/// well the two end curves agree with it.
struct edge_round {
  static constexpr std::uint32_t npos = ~std::uint32_t{0};
  std::size_t blend = 0;                     ///< index into the skeleton's blends
  std::uint32_t skeleton_edge = 0;           ///< the skeleton drawing's edge (the wireframe's edge)
  std::uint32_t cell_edge = npos;            ///< the cell complex's edge (npos: not in the complex)
  std::array<std::uint32_t, 2> junctions{};  ///< the edge's skeleton junctions
  blend_kind kind = blend_kind::unknown;
  /// The seed's visibility category in this reading (a, b or c; a and c swap with the Necker
  /// mirror), from resolve_blend_categories; a_or_c when the reading could not decide.
  blend_category category = blend_category::a_or_c;
  bool convex = true;  ///< a round (kind round) or a fillet (kind fillet)
  double radius = 0;   ///< mean of the two end radii
  std::array<double, 2> end_radius{};
  /// The faces of the edge (face_loops indices) and, per end, the end face holding its end curve.
  std::array<std::size_t, 2> faces{};
  std::array<std::size_t, 2> end_faces{};
  /// The wedge's angle between the two faces, seen along the edge, on the side that holds the
  /// blend (the solid's for a round, the outside's for a fillet), radians.
  double wedge_angle = 0;
  /// Distance from the edge to each tangent line, in both faces: radius / tan(wedge_angle / 2).
  double setback = 0;
  /// Diagnostics: |r0 − r1| / radius; per end 1 − minor/major of its curve seen along the edge;
  /// per end the distance of its curve's centre from the blend's axis over the radius.
  double radius_spread = 0;
  std::array<double, 2> roundness_defect{}, centre_offset{};
  /// Per end: the angle between its 2D minor axis and the edge's drawing direction (0 for a circle
  /// square to the edge), and minor over major semi-axis in 2D.
  std::array<double, 2> circle_angle{}, axis_ratio{};
  radius_source source = radius_source::none;
  bool consistent = false;  ///< every diagnostic of its source within options.consistency
};

/// What reconstruct_rounds made: the skeleton and its blends, the skeleton's reading as a cell
/// complex, one round attribute per blend, counts, time and diagnostics.
template <Point3 Q, Point2 P>
struct rounds_result : stage_report {
  round_skeleton_result<P> skeleton;
  drawing_result<Q, P> reading;
  std::vector<edge_round> rounds;
  /// The skeleton's junctions in 3D as the rounds use them: the reading's, or, when its blends
  /// disagree with circular ones and circles square to their edges fix the view, the reading
  /// mapped by z → k z + a x + b y (depth_map = {k, a, b}) to make it metric.
  std::vector<Q> points;
  bool depth_corrected = false;
  std::array<double, 3> depth_map{1, 0, 0};
  std::size_t consistent = 0, inconsistent = 0;
};

/// Options of rounded_mesh.
struct rounded_mesh_options {
  /// Largest distance of a blend strip's chords from its circle, relative to the skeleton
  /// drawing's diagonal.
  double chord_tolerance = 1e-3;
  int max_segments = 256;  ///< segments per blend at most (work bound)
};

/// The rounded solid as a polygon mesh: every skeleton face trimmed back by the setbacks of its
/// blends (a round's end face loses its corner to the end curve, a fillet's gains it), every
/// blend a strip of quads; face_source[f] is the skeleton face (face_loops index) of mesh face f,
/// or −1 − blend for a strip's quad. Faces are oriented outward. stage_report: milliseconds the
/// call, diagnostics the blends skipped and why.
template <Point3 Q>
struct rounded_mesh_result : stage_report {
  polygon_soup<Q> mesh;
  std::vector<std::int64_t> face_source;
  std::size_t strips = 0, strip_quads = 0, skipped = 0;  ///< skipped: blends with no radius
};

/// Options of rounded_brep.
struct rounded_brep_options {
  /// How far a vertex may lie from a surface or curve it is on and still pass the check of the
  /// answer, relative to the skeleton's bounding-box diagonal.
  double tolerance = 1e-9;
};

/// The rounded solid as an exact boundary (planar faces, one cylinder per blend, straight edges
/// and end arcs), its volume from the skeleton's and the blends' cross-sections, counts, time;
/// ok false, with the reason in diagnostics, when the shell fails its check (every edge used once
/// each way, every vertex on its surfaces and curves, positive volume).
struct rounded_brep_result : stage_report {
  rounded_solid solid;
  double volume = 0;
  std::size_t planar_faces = 0, blend_faces = 0, lines = 0, arcs = 0;
  std::size_t skipped = 0;  ///< blends with no radius: their edges stay sharp
  bool ok = false;
};

/// The round attributes of a skeleton already read: for each blend of `sk`, its two faces and
/// end faces in `reading` (face loops of the skeleton's junctions, positions reading.wire), the
/// radius of each end curve — the 2D ellipse lifted onto its end face's plane and seen along the
/// edge is a circle of the blend's radius (any end plane, square to the edge or not), or, when
/// the lifted curves disagree with a circular blend (a reading that is not metric), the 2D major
/// semi-axis of end curves that are circles square to the edge — the wedge, the setback and the
/// consistency diagnostics. Throws invalid_input when `reading` is not a reading of `sk`'s
/// skeleton. O(blends · F · L).
template <Point3 Q, Point2 P>
std::vector<edge_round> round_attributes(const round_skeleton_result<P>& sk,
                                         const drawing_result<Q, P>& reading,
                                         std::vector<std::string>& diagnostics,
                                         const rounds_options& options = {});

/// Reconstruction with rounds: round_skeleton, drawing_to_cells on the skeleton, then
/// round_attributes. The radii are in the reading's units: x, y are the drawing's, so a parallel
/// view's scale is kept, and the Necker mirror (z → −z) leaves every radius as it is.
/// Throws as round_skeleton and drawing_to_cells; invalid_input when the skeleton is not a
/// readable drawing. O(round_skeleton + drawing_to_cells + blends · F · L).
template <Point3 Q = glm::dvec3, Point2 P>
rounds_result<Q, P> reconstruct_rounds(const arc_drawing<P>& d, const rounds_options& options = {});

/// The rounded solid of a reconstruction: per blend with a radius, its axis the edge moved by
/// radius / sin(wedge / 2) along the wedge's bisector, its cross-section arc from the tangent
/// line in one face to the other in n = ⌈arc / (2 acos(1 − tolerance / radius))⌉ chords, each arc
/// point moved along the edge onto the end planes; then every face loop with its blend corners
/// replaced (tangent points in the blend's faces, the end curve in its end faces). Throws
/// invalid_input when two blends share a junction or a corner is on a face that is neither a
/// blend face nor its end face, or a face has holes. O(V + F · L + Σ segments).
template <Point3 Q, Point2 P>
rounded_mesh_result<Q> rounded_mesh(const rounds_result<Q, P>& r, const rounded_mesh_options& options = {});

/// The rounded solid of a reconstruction as a B-rep for CAD (io::write_step): the blends of
/// rounded_mesh, each a cylinder face bounded by its two tangent lines and its two end arcs,
/// the skeleton's faces trimmed by the same edges (an end face's corner replaced by the arc).
/// The volume is the skeleton's less each round's cross-section (kite less sector) times its
/// length along the edge between the end planes, plus each fillet's. Throws as rounded_mesh.
/// O(V + F · L + blends).
template <Point3 Q, Point2 P>
rounded_brep_result rounded_brep(const rounds_result<Q, P>& r, const rounded_brep_options& options = {});

}  // namespace cellforge

#include "cellforge/sketch/detail/rounds_impl.hpp"
