// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Arc detection: sampled strokes (polylines) become straight pieces and elliptical arcs. A
/// stroke that fits a straight line within the tolerance stays straight; otherwise a conic is
/// fitted (Fitzgibbon's direct least-squares ellipse fit, then a geometric refinement) and
/// kept when every sample lies within the tolerance of it; otherwise the stroke is split at its
/// farthest sample from the chord and each part is read again. Needs Eigen 3.3+. See
/// docs/sketch.md, "Rounds and fillets".

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numbers>
#include <optional>
#include <ranges>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <unsupported/Eigen/NonLinearOptimization>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge {

/// Options of detect_arcs, with documented defaults (docs/sketch.md, "Arc detection").
struct arc_detection_options {
  /// A sample may lie this far from its piece's line or ellipse, as a fraction of the drawing's
  /// size. The default suits strokes with noise up to 0.2 % of the size.
  double tolerance = 0.005;
  /// The drawing's size (the diagonal of its bounding box) in the strokes' units; 0: the
  /// diagonal of the strokes' own bounding box. Give it when the strokes are part of a larger
  /// drawing, so that the tolerance means the same for all of them.
  double drawing_size = 0;
  /// A piece with fewer samples is never an arc (a conic has five degrees of freedom).
  std::size_t min_arc_samples = 8;
  /// An arc sweeps at least this parametric angle (radians); shallower is read as straight.
  double min_sweep = 10 * std::numbers::pi / 180;
  /// An arc's semi-axes are at most this × the drawing's size: a larger ellipse through the
  /// samples is a nearly straight stroke, not an arc.
  double max_semi_axis = 2.0;
  /// Refine the algebraic fit by Levenberg–Marquardt (Eigen's) on the samples' distances to the
  /// ellipse (the algebraic fit is biased on short, noisy arcs; see docs/sketch.md).
  bool refine = true;
};

/// What a piece of a stroke is.
enum class stroke_piece_kind : std::uint8_t { line, arc };

/// Why a stroke (or a piece of one) is not an elliptical arc; `none` when it is one.
enum class arc_rejection : std::uint8_t {
  none,             ///< it is an arc
  straight,         ///< it fits a straight line within the tolerance: kept straight
  too_few_samples,  ///< fewer than min_arc_samples samples
  not_an_ellipse,   ///< the conic fit is degenerate (samples on a line) or is no ellipse
  too_large,        ///< the fitted ellipse is larger than max_semi_axis × the size: nearly straight
  off_curve,        ///< a sample lies farther than the tolerance from the fitted ellipse
  not_monotone,     ///< the samples run back and forth along the ellipse
  sweep_too_small,  ///< the samples cover less than min_sweep of the ellipse
  sweep_too_large,  ///< the samples wind round the ellipse more than once
};

/// The number of arc_rejection values (for per-reason counts).
inline constexpr std::size_t arc_rejection_count = 9;

/// A short name of a rejection ("straight", "off curve", ...). O(1).
constexpr std::string_view to_string(arc_rejection r) noexcept {
  switch (r) {
    case arc_rejection::none:
      return "arc";
    case arc_rejection::straight:
      return "straight";
    case arc_rejection::too_few_samples:
      return "too few samples";
    case arc_rejection::not_an_ellipse:
      return "not an ellipse";
    case arc_rejection::too_large:
      return "too large";
    case arc_rejection::off_curve:
      return "off curve";
    case arc_rejection::not_monotone:
      return "not monotone";
    case arc_rejection::sweep_too_small:
      return "sweep too small";
    case arc_rejection::sweep_too_large:
      return "sweep too large";
  }
  return "unknown";
}

/// An ellipse fitted to points: valid when `rejection` is none, straight (never set by the fit)
/// or a later check; centre, semi-axes (rx >= ry) and rotation of the rx axis in (−π/2, π/2].
template <Point2 P>
struct ellipse_fit {
  arc_rejection rejection = arc_rejection::not_an_ellipse;  ///< none when the fit is an ellipse
  P centre{};
  double rx = 0, ry = 0, rotation = 0;
  double max_distance = 0;     ///< the largest distance of a point from the ellipse, in the points' units
  std::size_t iterations = 0;  ///< the refinement's distance evaluations (Eigen's nfev, at most 30)
};

/// A maximal straight or elliptical piece of a stroke: samples `first` to `last` (inclusive)
/// of stroke `stroke`. Consecutive pieces of a stroke share their end sample.
template <Point2 P>
struct stroke_piece {
  stroke_piece_kind kind = stroke_piece_kind::line;
  std::size_t stroke = 0, first = 0, last = 0;
  P from{}, to{};           ///< the ends: the end samples projected onto the line, or the arc's ends
  elliptical_arc<P> arc{};  ///< the arc, when kind is arc (its first point is `from`)
  double deviation = 0;     ///< the largest distance of a sample from the line or arc, / the size
  arc_rejection why_not_arc = arc_rejection::none;  ///< for a line: why it is not an arc
};

/// One stroke's summary: its pieces are pieces[first_piece .. first_piece + num_pieces).
struct stroke_summary {
  std::size_t first_piece = 0, num_pieces = 0;
  std::size_t samples = 0;  ///< distinct consecutive samples read
  /// Why the whole stroke is not one arc (none when it is one; straight when it is one line).
  arc_rejection whole = arc_rejection::none;
  /// Places where the stroke crosses itself (its sampled polyline, loops shorter than four
  /// tolerances — a pen's jitter at a corner — not counted). Its pieces are read as usual; a
  /// crossing is no junction, and a diagnostic names the first.
  std::size_t self_crossings = 0;
};

// `seconds` warns where a user names it, not at every copy of the struct.
/// What detect_arcs found: the pieces of every stroke in order, per-stroke summaries, counts,
/// and (diagnostics) a sentence for each stroke that is neither one line nor one arc, or that
/// was dropped; milliseconds the call.
template <Point2 P>
struct arc_detection_result : stage_report {
  std::vector<stroke_piece<P>> pieces;
  std::vector<stroke_summary> strokes;
  std::size_t num_lines = 0, num_arcs = 0;
  std::size_t splits = 0;                 ///< pieces split at their farthest sample
  std::size_t merges = 0;                 ///< neighbouring pieces joined again into one line or arc
  std::size_t fits = 0;                   ///< ellipse fits tried
  std::size_t dropped_strokes = 0;        ///< strokes of fewer than two distinct samples
  std::size_t self_crossing_strokes = 0;  ///< strokes that cross themselves (stroke_summary::self_crossings)
  /// Over every ellipse fit tried, how often each reason rejected it (index: arc_rejection).
  std::array<std::size_t, arc_rejection_count> rejections{};
  double drawing_size = 0;  ///< the size the tolerance was taken of
};

/// A circle of a known plane seen in a parallel view, fitted to points: the 3D circle of radius
/// `radius` whose plane's two unit axes the view maps to `u` and `v`, drawn as the ellipse
/// centre + radius (u cos t + v sin t), whose semi-axes and rotation are also given.
template <Point2 P>
struct view_circle_fit {
  arc_rejection rejection = arc_rejection::not_an_ellipse;  ///< none when the fit succeeded
  P centre{};
  double radius = 0;                    ///< in 3D, in the drawing's units
  double rx = 0, ry = 0, rotation = 0;  ///< the drawn ellipse (rx >= ry)
  double max_distance = 0;              ///< the largest distance of a point from it
  std::size_t iterations = 0;           ///< the fit's distance evaluations (Eigen's nfev, at most 30)
};

/// Fits an ellipse to points (Fitzgibbon's direct least-squares fit; with `refine`, then
/// Levenberg–Marquardt on the geometric distances) and reports the largest distance of a point
/// from it. Only the fit's own failures are reported (not_an_ellipse): no tolerance is applied.
/// O(n × evaluations), at most 30 evaluations of the distances.
template <std::ranges::input_range R>
requires Point2<std::ranges::range_value_t<R>>
auto fit_ellipse(const R& points, bool refine = true);

/// Fits the drawing of a circle lying in a known plane (a round's end in a face of a
/// quasi-normalon: u and v are the drawn images of two unit model axes, s_i d_i from
/// inflate's axis_directions and foreshortening): three unknowns (centre, radius) instead of an
/// ellipse's five, so a short arc fixes them. Kåsa's algebraic circle fit in the frame where
/// the ellipse is a circle (linear least squares, Eigen), then Levenberg–Marquardt on the
/// points' distances in the drawing. Throws invalid_input when u and v are parallel or not
/// finite. O(n × evaluations), at most 30 evaluations of the distances.
template <std::ranges::input_range R>
requires Point2<std::ranges::range_value_t<R>>
auto fit_view_circle(const R& points, glm::dvec2 u, glm::dvec2 v);

/// Reads each stroke (a range of sampled points, in drawing order) as straight pieces and
/// elliptical arcs: a stroke within the tolerance of a line is one line; else, if an ellipse
/// fits it (every sample within the tolerance, running one way, sweeping min_sweep to 2π), one
/// arc; else it is split at the sample farthest from its chord and each part read the same way;
/// last, neighbouring pieces that together fit one line or one ellipse are joined. Throws
/// invalid_input for a non-finite sample or bad options. O(Σ n_s × d_s × fit), d_s the depth
/// of the splitting (1 for a line or an arc, log n_s for an even polygon-like stroke).
template <std::ranges::input_range Strokes>
requires std::ranges::input_range<std::ranges::range_value_t<Strokes>> &&
    Point2<std::ranges::range_value_t<std::ranges::range_value_t<Strokes>>>
auto detect_arcs(const Strokes& strokes, const arc_detection_options& options = {});

}  // namespace cellforge

#include "cellforge/sketch/detail/arc_detection_impl.hpp"
