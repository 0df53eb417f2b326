// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Elliptical arcs: the curved strokes of a line drawing (a circle in 3D seen in a parallel
/// view is an ellipse, a rounded edge a quarter of one). `elliptical_arc<P>` holds the centre
/// form (centre, semi-axes, rotation, start angle, signed sweep); `arc_from_endpoints` and
/// `arc_endpoint_form` convert from and to SVG's endpoint form (two ends, radii, rotation, the
/// large-arc and sweep flags). `arc_drawing<P>` is a line drawing with arcs beside its straight
/// edges: the straight part is an ordinary `line_drawing`, untouched. See docs/sketch.md,
/// "Rounds and fillets".

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge {

/// An arc of the ellipse c + R(rotation) (rx cos θ, ry sin θ), θ from `start` to
/// `start + sweep`. Angles are in radians; θ is the ellipse's parametric (eccentric) angle, as in
/// SVG, not the polar angle of the point. The drawing's y axis points up, so sweep > 0 runs
/// counter-clockwise. A valid arc has finite values, rx, ry > 0 and 0 < |sweep| <= 2π.
template <Point2 P>
struct elliptical_arc {
  using point_type = P;
  P centre{};
  double rx = 1;        ///< semi-axis along the rotated x direction
  double ry = 1;        ///< semi-axis along the rotated y direction
  double rotation = 0;  ///< angle of the rx axis from the drawing's x axis
  double start = 0;     ///< parametric angle of the arc's first point
  double sweep = 0;     ///< signed parametric angle swept from the first point to the last
};

namespace detail {

/// The point at parametric angle t of the arc's ellipse, in double precision. O(1).
template <class P>
glm::dvec2 ellipse_point(const elliptical_arc<P>& a, double t) {
  const double c = std::cos(a.rotation), s = std::sin(a.rotation);
  const double x = a.rx * std::cos(t), y = a.ry * std::sin(t);
  return to_dvec2(a.centre) + glm::dvec2(c * x - s * y, s * x + c * y);
}

}  // namespace detail

/// The point a fraction u of the way along the arc's sweep (u = 0 its first point, 1 its last),
/// in the caller's point type. O(1).
template <Point2 P>
P arc_point(const elliptical_arc<P>& a, double u) {
  return from_dvec2<P>(detail::ellipse_point(a, a.start + u * a.sweep));
}

/// The unit tangent at a fraction u of the sweep, pointing the way the arc runs (from its first
/// point to its last), as a double vector. O(1).
template <Point2 P>
glm::dvec2 arc_tangent(const elliptical_arc<P>& a, double u) {
  const double t = a.start + u * a.sweep;
  const double c = std::cos(a.rotation), s = std::sin(a.rotation);
  const double dx = -a.rx * std::sin(t), dy = a.ry * std::cos(t);
  glm::dvec2 v(c * dx - s * dy, s * dx + c * dy);
  if (a.sweep < 0) v = -v;
  const double len = glm::length(v);
  return len > 0 ? v / len : v;
}

/// n + 1 points along the arc at equal steps of the parametric angle, both ends included
/// (n >= 1). O(n).
template <Point2 P>
std::vector<P> sample_arc(const elliptical_arc<P>& a, std::size_t n) {
  if (n == 0) throw error(error_category::invalid_input, "sample_arc: n must be at least 1");
  std::vector<P> out;
  out.reserve(n + 1);
  for (std::size_t i = 0; i <= n; ++i)
    out.push_back(arc_point(a, static_cast<double>(i) / static_cast<double>(n)));
  return out;
}

/// Why an arc is not a valid arc; `none` when it is.
enum class arc_defect : std::uint8_t {
  none,
  bad_value,    ///< a NaN or infinite centre, radius or angle
  zero_radius,  ///< rx or ry <= 0 (or below the tolerance given): a corner, not a round
  zero_sweep,   ///< the arc sweeps no angle (or more than a full turn)
};

/// The first defect of an arc: finite values, both semi-axes above `min_radius` (>= 0) and
/// 0 < |sweep| <= 2π. O(1).
template <Point2 P>
arc_defect validate_arc(const elliptical_arc<P>& a, double min_radius = 0) {
  const glm::dvec2 c = to_dvec2(a.centre);
  for (const double v : {c.x, c.y, a.rx, a.ry, a.rotation, a.start, a.sweep})
    if (!std::isfinite(v)) return arc_defect::bad_value;
  if (!(a.rx > min_radius) || !(a.ry > min_radius)) return arc_defect::zero_radius;
  if (a.sweep == 0 || std::abs(a.sweep) > 2 * std::numbers::pi) return arc_defect::zero_sweep;
  return arc_defect::none;
}

/// The arc in SVG's endpoint form (path command `A rx ry rotation large-arc sweep x y` from
/// `from`), in the drawing's y-up frame: `ccw` is SVG's sweep flag read in that frame (a
/// reader of SVG's y-down files flips it along with y).
template <Point2 P>
struct arc_endpoints {
  P from{}, to{};
  double rx = 0, ry = 0, rotation = 0;
  bool large_arc = false;  ///< |sweep| > π
  bool ccw = false;        ///< sweep > 0
};

/// The arc that SVG's endpoint form describes (the SVG specification's conversion, appendix
/// "Elliptical arc implementation notes"): radii too small to span the ends are scaled up until
/// they do (radii spanning them to rounding are taken as spanning exactly), negative radii taken
/// by magnitude; the sweep agrees with the flags (arc_endpoint_form gives them back). Throws invalid_input
/// for a zero radius, equal ends or non-finite values (SVG draws a straight line or nothing there; for a
/// sketch either is a drawing error). O(1).
template <Point2 P>
elliptical_arc<P> arc_from_endpoints(const arc_endpoints<P>& e) {
  const glm::dvec2 p0 = to_dvec2(e.from), p1 = to_dvec2(e.to);
  for (const double v : {p0.x, p0.y, p1.x, p1.y, e.rx, e.ry, e.rotation})
    if (!std::isfinite(v))
      throw error(error_category::invalid_input, "arc_from_endpoints: a non-finite end, radius or rotation");
  double rx = std::abs(e.rx), ry = std::abs(e.ry);
  if (rx == 0 || ry == 0)
    throw error(error_category::invalid_input,
                cellforge::detail::cat(
                    "arc_from_endpoints: radius ", detail::drawing_number(rx == 0 ? e.rx : e.ry),
                    " is zero: a zero-radius arc is a corner; draw the two lines meeting there instead"));
  if (p0 == p1)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("arc_from_endpoints: the arc starts and ends at ",
                                       detail::drawing_point_text(e.from),
                                       ", so it has no sweep; give distinct ends"));
  const double c = std::cos(e.rotation), s = std::sin(e.rotation);
  const glm::dvec2 h = (p0 - p1) * 0.5;
  const glm::dvec2 q(c * h.x + s * h.y, -s * h.x + c * h.y);  // the half chord in the ellipse's frame
  const double lambda = (q.x * q.x) / (rx * rx) + (q.y * q.y) / (ry * ry);
  // Radii that span the ends to rounding are taken as spanning them exactly (the centre at the
  // chord's midpoint): the square root below would turn a rounding error of 1e-16 in lambda into
  // a centre 1e-8 off, and an arc written in endpoint form would not read back the same.
  constexpr double spanning = 64 * std::numeric_limits<double>::epsilon();
  double k = 0;
  if (lambda > 1 + spanning) {
    rx *= std::sqrt(lambda), ry *= std::sqrt(lambda);
  } else if (lambda < 1 - spanning) {
    const double num = rx * rx * ry * ry - rx * rx * q.y * q.y - ry * ry * q.x * q.x;
    const double den = rx * rx * q.y * q.y + ry * ry * q.x * q.x;
    k = std::sqrt(std::max(0.0, num / den));
  }
  if (e.large_arc == e.ccw) k = -k;
  const glm::dvec2 cq(k * rx * q.y / ry, -k * ry * q.x / rx);
  const glm::dvec2 mid = (p0 + p1) * 0.5;
  const glm::dvec2 centre(c * cq.x - s * cq.y + mid.x, s * cq.x + c * cq.y + mid.y);
  const double t0 = std::atan2((q.y - cq.y) / ry, (q.x - cq.x) / rx);
  const double t1 = std::atan2((-q.y - cq.y) / ry, (-q.x - cq.x) / rx);
  double sweep = t1 - t0;
  constexpr double two_pi = 2 * std::numbers::pi;
  if (e.ccw && sweep <= 0) sweep += two_pi;
  if (!e.ccw && sweep >= 0) sweep -= two_pi;
  // A half ellipse sweeps π up to rounding: keep |sweep| on the side of π the large-arc flag
  // says, so that arc_endpoint_form gives the flags back.
  constexpr double pi = std::numbers::pi;
  if (e.large_arc && !(std::abs(sweep) > pi)) sweep = std::copysign(std::nextafter(pi, 4.0), sweep);
  if (!e.large_arc && std::abs(sweep) > pi) sweep = std::copysign(pi, sweep);
  return {from_dvec2<P>(centre), rx, ry, e.rotation, t0, sweep};
}

/// The endpoint form of an arc (the inverse of arc_from_endpoints up to rounding). O(1).
template <Point2 P>
arc_endpoints<P> arc_endpoint_form(const elliptical_arc<P>& a) {
  return {arc_point(a, 0.0), arc_point(a, 1.0), a.rx, a.ry, a.rotation, std::abs(a.sweep) > std::numbers::pi,
          a.sweep > 0};
}

/// An arc of a drawing: the junctions at its first and last points, and its curve.
template <Point2 P>
struct drawing_arc {
  std::array<std::uint32_t, 2> ends{};  ///< junctions at the curve's first and last point
  elliptical_arc<P> curve{};
};

/// The seed's visibility categories of a round or fillet (seed 003 §"Rounds and
/// fillets"), by how its two faces face the viewer: `a` both (both arcs seen whole, no line
/// between them), `b` one (a round's contour line is tangent to both arcs), `c` neither (one arc
/// seen, the other hidden). In a wireframe drawing a and c are the two Necker readings of one
/// drawing: `a_or_c` says the drawing alone cannot tell which (docs/sketch.md).
enum class blend_category : std::uint8_t { a, b, c, a_or_c };

/// A line drawing with elliptical arcs beside its straight edges. The straight part is an
/// ordinary line drawing and reads as one by every sketch stage; the arcs share its junctions.
template <Point2 P>
struct arc_drawing {
  using point_type = P;
  line_drawing<P> lines;
  std::vector<drawing_arc<P>> arcs;
};

/// What validate(arc_drawing) found wrong with an arc of a drawing.
struct arc_validation {
  static constexpr std::size_t npos = ~std::size_t{0};
  arc_defect defect = arc_defect::none;
  bool end_out_of_range = false;  ///< an end names a junction that does not exist
  bool ends_equal = false;        ///< both ends are one junction (a closed ellipse is no round)
  bool end_off_curve = false;     ///< a junction is not where the curve starts or ends
  std::size_t arc = npos;         ///< the arc concerned
  std::string message;
  bool ok() const noexcept {
    return defect == arc_defect::none && !end_out_of_range && !ends_equal && !end_off_curve;
  }
  explicit operator bool() const noexcept { return ok(); }
};

/// Checks each arc in order and returns the first that is wrong: a valid curve (validate_arc,
/// radii above `tolerance` × the junctions' bounding-box diagonal), its ends existing, distinct
/// junctions, each within that distance of the curve's first and last point. The tolerance is
/// at least the point type's own precision (64 ε of a floating-point scalar: float points hold
/// a curve's ends only to that). The straight part
/// is not checked here: with its arcs taken away it has loose ends by design (validate(drawing)
/// applies to it once the arcs are replaced, as the skeleton stage does). O(V + A).
template <Point2 P>
arc_validation validate(const arc_drawing<P>& d, const drawing_validation_options& options = {}) {
  double tol = options.tolerance;
  if (!std::isfinite(tol) || tol < 0 || tol >= 0.5)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("validate(arc_drawing): the tolerance ", detail::drawing_number(tol),
                                       " is not a finite number in [0, 0.5)"));
  if constexpr (std::is_floating_point_v<scalar2_t<P>>)
    tol = std::max(tol, 64 * static_cast<double>(std::numeric_limits<scalar2_t<P>>::epsilon()));
  const std::size_t nv = d.lines.points.size();
  glm::dvec2 lo(0), hi(0);
  for (std::size_t i = 0; i < nv; ++i) {
    const glm::dvec2 p = to_dvec2(d.lines.points[i]);
    lo = i == 0 ? p : glm::min(lo, p);
    hi = i == 0 ? p : glm::max(hi, p);
  }
  const double eps = tol * glm::length(hi - lo);
  for (std::size_t k = 0; k < d.arcs.size(); ++k) {
    const drawing_arc<P>& a = d.arcs[k];
    arc_validation v;
    v.arc = k;
    const std::string name = cellforge::detail::cat("arc ", std::to_string(k));
    v.defect = validate_arc(a.curve, eps);
    if (v.defect != arc_defect::none) {
      v.message =
          name + (v.defect == arc_defect::bad_value     ? ": a non-finite centre, radius or angle"
                  : v.defect == arc_defect::zero_radius ? ": a radius of zero (or below the tolerance): a "
                                                          "corner, not a round; draw the lines meeting"
                                                        : ": no sweep, or more than a full turn");
      return v;
    }
    for (const std::uint32_t j : a.ends)
      if (j >= nv) {
        v.end_out_of_range = true;
        v.message =
            name + ": junction " + std::to_string(j) + " out of range (" + std::to_string(nv) + " junctions)";
        return v;
      }
    if (a.ends[0] == a.ends[1]) {
      v.ends_equal = true;
      v.message = name + " starts and ends at junction " + std::to_string(a.ends[0]) +
                  ": a closed curve is no round or fillet";
      return v;
    }
    for (int side = 0; side < 2; ++side) {
      const glm::dvec2 at = detail::ellipse_point(a.curve, a.curve.start + side * a.curve.sweep);
      const glm::dvec2 j = to_dvec2(d.lines.points[a.ends[side]]);
      if (glm::length(at - j) > eps) {
        v.end_off_curve = true;
        v.message = name + ": junction " + std::to_string(a.ends[side]) + " " +
                    detail::drawing_point_text(d.lines.points[a.ends[side]]) + " is " +
                    detail::drawing_number(glm::length(at - j)) + " from the curve's " +
                    (side == 0 ? "first" : "last") + " point (tolerance " + detail::drawing_number(eps) + ")";
        return v;
      }
    }
  }
  return {};
}

}  // namespace cellforge
