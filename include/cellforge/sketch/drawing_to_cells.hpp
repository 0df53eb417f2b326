// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A line drawing becomes a cell complex in one call (seed 003 §"Finding
/// faces" and §"Inflation", on top of seed 000's wireframe pipeline): faces of the drawing
/// (sketch/face_finder.hpp) → their loops grouped into faces with holes → inflation to 3D
/// (sketch/inflation.hpp) → a 3D wireframe → wireframe_to_cells. Every stage's result comes
/// back, and the faces found in 2D are checked against the faces the 3D pipeline recovers. An
/// inexact drawing whose answer is flagged is tried again from faces found on it tidied first
/// (tidy_drawing with classes from its own precision; docs/sketch.md "Tidying").

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/work_counter.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/sketch/face_finder.hpp"
#include "cellforge/sketch/inflation.hpp"
#include "cellforge/sketch/line_drawing.hpp"
#include "cellforge/sketch/tidy.hpp"
#include "cellforge/wireframe/wire_graph.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

namespace cellforge {

/// When drawing_to_cells tidies the drawing (sketch/tidy.hpp) before inflating it.
enum class tidy_mode : std::uint8_t {
  never,
  when_needed,  ///< as drawn first; tidied when that gives no agreeing complex or no direct reading
  always,
};

/// Options of every stage of drawing_to_cells, with their own defaults.
struct drawing_options {
  face_finder_options faces{};
  /// Make nearly parallel lines exactly parallel before inflating (a drawing typed with a few
  /// decimals or snapped from strokes is not exact enough for direct inflation otherwise):
  /// by default only when the drawing as it is gives no complex whose faces agree, or reads
  /// only by optimisation (tidied, it may read directly).
  tidy_mode tidy = tidy_mode::when_needed;
  tidy_options tidying{};
  inflation_options inflation{};
  wireframe_options cells{};
  /// When the preferred reading gives no cell complex, or one whose faces disagree with the
  /// drawing's, build the other (Necker) reading instead.
  bool try_other_reading = true;
};

/// Every stage's result: the faces found, the faces with holes, the inflation, the 3D
/// wireframe and the cell complex (positions in Q), and whether 2D and 3D faces agree.
template <Point3 Q, Point2 P2 = glm::dvec2>
struct drawing_result : stage_report {
  using point_type = Q;
  face_finder_result faces;
  tidy_result<P2> tidy;  ///< the drawing inflated: `tidy.applied` when tidied, else the input as drawn
  /// The loops grouped into faces: each its outer loop, then its holes (junction cycles).
  std::vector<std::vector<std::vector<std::uint32_t>>> face_loops;
  inflation_result<Q> inflation;
  std::size_t reading = 0;  ///< the inflation reading the complex is built from (0: the preferred)
  wireframe<Q> wire;        ///< junction i at the reading's point i, the drawing's edges
  wireframe_result<Q> cells;
  /// Parts of the drawing whose depth the drawing does not decide: joined to another by one face
  /// plane (a boss or a pocket alike: read as a boss), or drawn inside another part on none of
  /// its planes (placed freely); each with a diagnostic.
  std::size_t ambiguous_parts = 0;
  /// The 3D pipeline's face loops are exactly the loops found in the drawing.
  bool faces_agree = false;
  /// Where they disagree: loops found only in the drawing, only in 3D (junction cycles).
  std::vector<std::vector<std::uint32_t>> only_in_drawing, only_in_3d;
  /// Drawn edges that bound no face of the complex (every drawn edge should bound one).
  std::vector<std::uint32_t> unused_edges;
  /// An inexact drawing's answer its precision does not confirm, each named in `diagnostics`:
  /// lines straight on through a junction where two faces barely fold (a wall the jitter hid),
  /// a face nested in another's outline nearly on its plane (a hole through, or a pocket).
  std::size_t doubts = 0;
  /// Not certified, reasons in `diagnostics`: the faces found fail their check or are ambiguous,
  /// 2D and 3D faces disagree, a drawn edge is unused, a part's depth is undecided, the 3D reading
  /// keeps walls no edge needs, or an inexact drawing leaves `doubts`. Alternatives:
  /// `faces.alternatives`, `cells.alternatives`.
  bool flagged = false;
};

namespace detail::sketch {
/// drawing_to_cells' result type (unconstrained, for if_satisfied_t).
template <class Q, class D>
using drawing_result_for = drawing_result<result_point_t<Q, typename line_drawing_traits<D>::point_type>,
                                          typename line_drawing_traits<D>::point_type>;
}  // namespace detail::sketch

/// Turns a wireframe line drawing (a parallel view of a polyhedron, hidden lines drawn) into a
/// cell complex in point type Q (void: lifted_point_t of the drawing's point type): faces,
/// inflation, the 3D pipeline; every stage's result and a 2D/3D face agreement check. Throws
/// invalid_input on a malformed drawing, topology when no solid reading exists or the 3D
/// pipeline refuses both readings; a stage out of its budget: complete false, and when no face
/// was found, cells.status budget with the stage's message. O(the stages).
/// A drawing whose scalar is double runs as a line_drawing<glm::dvec2> into glm::dvec3 (the same
/// numbers: every stage computes in double), so one instantiation serves every such caller.
template <class Q = void, LineDrawing D>
detail::if_satisfied_t<LineDrawing<D>, detail::sketch::drawing_result_for, Q, D> drawing_to_cells(
    const D& drawing, const drawing_options& options = {});

}  // namespace cellforge

#include "cellforge/sketch/detail/drawing_to_cells_impl.hpp"
