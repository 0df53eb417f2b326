// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Inflation: a line drawing with its face loops becomes 3D. Every junction keeps its drawing
/// (x, y); its depth z is found. Direct for drawings of normalons and quasi-normalons (the view
/// is recovered from the three axis directions and depth propagated along axis edges), by
/// optimisation of weighted compliance functions over the planar-face readings otherwise.
/// Needs Eigen 3.3+. See docs/sketch.md, "Inflation".

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <unsupported/Eigen/NonLinearOptimization>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/certify.hpp"
#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/sketch/line_drawing.hpp"
#include "cellforge/wireframe/wire_graph.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

namespace cellforge {

/// How a reading was found.
enum class inflation_method : std::uint8_t {
  direct,        ///< view recovered from the three axis directions, depth propagated (exact)
  optimisation,  ///< compliance functions minimised over the planar-face readings
};

/// Weights αⱼ of the compliance functions of the optimisation (face planarity is not weighted:
/// it holds exactly by construction). Each term is normalised by its number of residuals, so a
/// weight is the term's share whatever the drawing's size. Defaults: docs/sketch.md.
struct inflation_weights {
  double msda = 1.0;           ///< minimum standard deviation of the face-corner angles
  double orthogonality = 0.1;  ///< cos² of corner angles at junctions that can be right corners
  double parallelism = 1.0;    ///< lines parallel in the drawing are parallel in 3D
  double isometry = 0.01;      ///< every line foreshortened alike (log length ratios equal)
  /// Every line a convex fold (hinge on the far corners of the next face behind this face's
  /// plane); used only on drawings whose faces admit a strictly convex reading, see docs/sketch.md.
  double convexity = 1.0;
  /// Least-squares readings only (inflation_options::least_squares): face planarity, the mean
  /// squared residual of the planarity rows (exact readings keep it 0 by construction).
  double planarity = 100.0;
};

/// Options of inflate, with documented defaults.
struct inflation_options {
  inflation_weights weights{};
  bool allow_direct = true;        ///< try the direct method first
  bool allow_optimisation = true;  ///< fall back to optimisation when direct does not apply
  /// Lines within this angle (radians) of each other are taken as parallel: clustering of the
  /// axis directions (direct) and the parallelism term. Tidied drawings: raise it to a degree.
  double direction_tolerance = 1e-6;
  /// Largest misclosure of a cycle of axis edges, relative to the drawing size, for a drawing to
  /// be read directly; and the largest planarity residual the direct solution may keep.
  double closure_tolerance = 1e-8;
  /// Rank threshold (relative) of the planarity constraints' matrix: its null space holds the
  /// planar-face readings.
  double rank_tolerance = 1e-9;
  int max_iterations = 400;  ///< Levenberg–Marquardt iterations per start (work budget)
  int starts = 8;            ///< optimisation starts (deterministic from `seed`); the best is kept
  /// Convexity prior (weights.convexity): margin of the hinge in the objective, a slope (depth
  /// over 2D distance from the line); and the margin the convex start is solved for (0: no
  /// convexity prior at all).
  double convexity_margin = 0.01;
  double convexity_start_margin = 0.1;
  /// Starts when the faces admit a convex reading: the convex start, then random ones (capped
  /// by `starts`); the convex start alone gave the true complex on every such sweep drawing.
  int convex_starts = 1;
  std::uint64_t seed = 1;  ///< seed of the random starts
  /// The drawing is inexact (sketched, jittered): read it by least squares. The optimisation
  /// then runs over the exact planar readings and the near ones (singular vectors of the
  /// planarity rows below the widest gap of the spectrum), with face planarity a weighted term,
  /// and after.planarity reports how far the reading is from planar faces. Raise
  /// direction_tolerance and closure_tolerance with it for the direct method.
  bool least_squares = false;
  /// Choose among the planar readings by the regularities a person sees (right corners, equal
  /// corners and sides of a face, parallel lines): the optimised reading, and a direct one with
  /// lines off its axes, are moved to the most regular reading near them (docs/sketch.md,
  /// "The regular reading"). Off: the compliance optimum as it is.
  bool regularity = true;
  /// Work budget of the regular reading: sought only when the planar freedom is at most this
  /// (a convex polytope of random points has one depth per junction and no regularity to find).
  std::size_t regularity_max_freedom = 24;
  /// More starts of the regular reading, from random planar readings, while the best reading
  /// found holds under a quarter of the relations (a local minimum: antiprisms, pyramids), when
  /// the planar freedom is at most regularity_starts_max_freedom (a random polytope has no
  /// regularity to find, and one search costs O(K) per relation).
  int regularity_starts = 6;
  std::size_t regularity_starts_max_freedom = 8;
  /// Hypotheses of the regular reading solved linearly before the random starts: polygons
  /// drawn as affine images of regular ones made regular (prism and antiprism caps, pyramid
  /// bases, a bipyramid's equator), three classes of parallel lines made orthogonal axes (cut
  /// cubes). Up to this many are searched, each only in the planar readings that meet it, and
  /// only when those are at most regularity_max_freedom (so also at higher planar freedom).
  std::size_t regularity_hypotheses = 4;
};

/// Value of each compliance function (unweighted, each normalised by its count) at a reading.
/// planarity: the largest distance in z of a junction from its face's plane, relative to the
/// drawing size (0 to rounding by construction).
struct inflation_residuals {
  double planarity = 0.0;
  double parallelism = 0.0;
  double orthogonality = 0.0;
  double msda = 0.0;
  double isometry = 0.0;
  double convexity = 0.0;  ///< mean squared hinge of the convexity term (0 when not used)
};

/// One reading of the drawing: the 3D points (x, y from the drawing), a score (larger is
/// preferred) and why it ranks where it does.
template <class Q>
struct inflation_reading {
  std::vector<Q> points;
  double score = 0.0;
  std::string reason;
};

/// What inflate found. points == readings[0].points.
template <class Q>
struct inflation_result : stage_report {
  using point_type = Q;
  std::vector<Q> points;  ///< the preferred reading: junction i at (x_i, y_i, z_i), mean z 0
  inflation_method method = inflation_method::direct;
  /// Both readings, best first: a drawing and its Necker reversal (z → −z) fit every regularity
  /// alike in a parallel view, so both come back, ranked by the view-from-above prior.
  std::vector<inflation_reading<Q>> readings;
  inflation_residuals before;  ///< at the start (optimisation) or of the direct solution
  inflation_residuals after;   ///< of points
  std::size_t freedom = 0;     ///< dimension of the planar-face readings, depth offset removed
  std::size_t iterations = 0;  ///< Levenberg–Marquardt iterations over all starts
  std::size_t starts = 0;      ///< optimisation starts run
  // The recovered view (direct only; view_found false otherwise).
  bool view_found = false;
  std::array<std::array<double, 2>, 3> axis_directions{};  ///< unit 2D images of the model axes
  std::array<double, 3> foreshortening{};                  ///< s_i: drawing length of a unit axis segment
  /// Model → view rotation of the preferred reading, row-major: column i is axis i in the view.
  std::array<double, 9> view_rotation{};
  double misclosure = 0.0;  ///< worst depth misclosure of an axis edge, relative to the drawing size
  /// A least-squares reading (inflation_options::least_squares): its faces are planar only to
  /// after.planarity; near_readings of the freedom were near the planar ones, not exactly.
  bool least_squares = false;
  std::size_t near_readings = 0;
  /// Regularities (right face corners, equal consecutive corners, equal consecutive sides) the
  /// reading holds to 1e-7, of `relations` (0 when the reading was not judged: direct normalons).
  std::size_t regular_relations = 0;
  std::size_t relations = 0;
  /// Judged readings passed over because their faces cross or an edge pierces a face (exact:
  /// cells/certify.hpp); self_intersecting when the reading returned does too (none better).
  std::size_t crossing_readings = 0;
  bool self_intersecting = false;
  /// Judged regular readings passed over because the main job (wireframe_to_cells) finds other
  /// faces in them than the drawing's (snapping made faces coplanar, or a new planar cycle).
  std::size_t face_changing_readings = 0;
};

namespace detail {
/// inflate's result type for result point type Q and drawing type D (unconstrained, for
/// if_satisfied_t).
template <class Q, class D>
using inflation_result_for = inflation_result<result_point_t<Q, typename line_drawing_traits<D>::point_type>>;
}  // namespace detail

/// Inflates a line drawing with its faces (each: its outer loop, then its holes; junction
/// cycles in any orientation) to 3D in point type Q (void: lifted_point_t of the drawing's point type):
/// x, y kept, z found, both Necker readings returned best first. Direct when the drawing is a
/// normalon or quasi-normalon view, else Levenberg–Marquardt over the planar-face readings.
/// Throws invalid_input on a malformed drawing or loops, topology when no solid reading with
/// planar faces exists. O(E² + V³ + starts · iterations · K · (L + E)), K the planar freedom.
template <class Q = void, LineDrawing D>
detail::if_satisfied_t<LineDrawing<D>, detail::inflation_result_for, Q, D> inflate(
    const D& drawing, const std::vector<std::vector<std::vector<std::uint32_t>>>& faces,
    const inflation_options& user_options = {});

/// inflate with every loop its own face (the hole loops of a face are then not tied to its
/// outer loop: a hole ringed by edges of its own may float in depth, with a diagnostic). O(as above).
template <class Q = void, LineDrawing D>
detail::if_satisfied_t<LineDrawing<D>, detail::inflation_result_for, Q, D> inflate(
    const D& drawing, const std::vector<std::vector<std::uint32_t>>& loops,
    const inflation_options& options = {});

}  // namespace cellforge

#include "cellforge/sketch/detail/inflation_impl.hpp"
