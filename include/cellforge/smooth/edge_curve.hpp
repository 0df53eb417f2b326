// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// One smoothed edge: a cubic Bézier that is always exact, plus, when the curve is a function of
/// one coordinate axis, the seed's axis form (seed 000 §6.4–6.5: axis, limits, cubic coefficients).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <ranges>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"

namespace cellforge {

/// How many vertex tangents shaped a curve: both (cubic), one (quadratic) or none (straight).
enum class curve_kind : std::uint8_t { straight, quadratic, cubic };

/// Which representation a smoother should produce (see smooth_options::form).
enum class curve_form : std::uint8_t { automatic, axis_polynomial, bezier };

namespace detail {

/// The double-precision control points the curve maths runs on.
using dbezier = std::array<glm::dvec3, 4>;

template <Point3 P>
dbezier to_dbezier(const std::array<P, 4>& b) {
  return {to_dvec3(b[0]), to_dvec3(b[1]), to_dvec3(b[2]), to_dvec3(b[3])};
}

template <Point3 P>
std::array<P, 4> from_dbezier(const dbezier& b) {
  return {from_dvec3<P>(b[0]), from_dvec3<P>(b[1]), from_dvec3<P>(b[2]), from_dvec3<P>(b[3])};
}

/// Four copies of the origin: a Bézier for point types without a default constructor.
template <Point3 P>
std::array<P, 4> zero_bezier() {
  const P o = point_traits<P>::make(0, 0, 0);
  return {o, o, o, o};
}

/// Bernstein form: t = 0 and t = 1 return the ends bitwise. O(1).
template <class = void>
glm::dvec3 bezier_point(const dbezier& b, double t) {
  const double s = 1.0 - t;
  return (s * s * s) * b[0] + (3.0 * s * s * t) * b[1] + (3.0 * s * t * t) * b[2] + (t * t * t) * b[3];
}

template <class = void>
glm::dvec3 bezier_tangent(const dbezier& b, double t) {
  const double s = 1.0 - t;
  return (3.0 * s * s) * (b[1] - b[0]) + (6.0 * s * t) * (b[2] - b[1]) + (3.0 * t * t) * (b[3] - b[2]);
}

template <class = void>
double bezier_chord_deviation(const dbezier& b) {
  const glm::dvec3 v = b[3] - b[0];
  const double len2 = v.x * v.x + v.y * v.y + v.z * v.z;
  double worst = 0.0;
  for (int i = 1; i <= 2; ++i) {
    const glm::dvec3 d = b[static_cast<std::size_t>(i)] - b[0];
    const glm::dvec3 off = len2 > 0.0 ? d - ((d.x * v.x + d.y * v.y + d.z * v.z) / len2) * v : d;
    worst = std::max(worst, std::sqrt(off.x * off.x + off.y * off.y + off.z * off.z));
  }
  return worst;
}

template <class = void>
void check_polyline_segments(int segments) {
  if (segments < 1)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("edge_curve::polyline: segments = ", std::to_string(segments),
                                       ", must be >= 1"));
}

}  // namespace detail

/// A smoothed edge from vertex v0 to vertex v1, evaluated from its cubic Bézier control points.
/// When has_axis_form is set, the same curve is also the seed's "function of one axis" form.
/// Positions and directions are of the point type P; they are evaluated in double precision
/// and converted with point_traits<P>::make.
template <Point3 P>
struct edge_curve {
  using point_type = P;
  std::uint32_t edge = 0, v0 = 0, v1 = 0;  ///< ids (mesh or cell); the curve runs v0 → v1
  curve_kind kind = curve_kind::straight;
  /// The seed's form (§6.5 file layout): coordinate `axis` runs from limits[0] (at v0) to
  /// limits[1] (at v1); the other two coordinates, in increasing axis order, are
  /// c[k][0]*x^3 + c[k][1]*x^2 + c[k][2]*x + c[k][3] with x the value on `axis`.
  bool has_axis_form = false;
  int axis = 0;
  std::array<double, 2> limits{};
  std::array<std::array<double, 4>, 2> coefficients{};
  /// Cubic Bézier control points; always set. bezier[0] and bezier[3] are the end vertices.
  std::array<P, 4> bezier = detail::zero_bezier<P>();

  /// Point at parameter t in [0,1] (Bernstein form: t = 0 and t = 1 return the ends bitwise). O(1).
  P point(double t) const { return from_dvec3<P>(detail::bezier_point(detail::to_dbezier(bezier), t)); }
  /// Derivative d point / dt at t in [0,1]. O(1).
  P tangent(double t) const { return from_dvec3<P>(detail::bezier_tangent(detail::to_dbezier(bezier), t)); }
  /// segments+1 points equally spaced in t (the seed draws 15 segments per curve, §6.5).
  /// O(segments); throws error(invalid_input) when segments < 1.
  std::vector<P> polyline(int segments = 15) const {
    detail::check_polyline_segments(segments);
    const detail::dbezier b = detail::to_dbezier(bezier);
    std::vector<P> out;
    out.reserve(static_cast<std::size_t>(segments) + 1);
    for (int i = 0; i < segments; ++i)
      out.push_back(from_dvec3<P>(detail::bezier_point(b, static_cast<double>(i) / segments)));
    out.push_back(bezier[3]);  // exact end, independent of rounding in i/segments
    return out;
  }
  /// Largest distance of the inner control points from the chord's line: a bound on how far
  /// the curve leaves its chord (convex hull), 0 exactly when it is a straight segment. O(1).
  double chord_deviation() const { return detail::bezier_chord_deviation(detail::to_dbezier(bezier)); }
  /// Evaluate the axis form at axis value x (only meaningful when has_axis_form). O(1).
  P axis_point(double x) const {
    glm::dvec3 p{};
    p[axis] = x;
    for (int k = 0; k < 2; ++k) {
      const auto& c = coefficients[static_cast<std::size_t>(k)];
      p[other_axis(axis, k)] = ((c[0] * x + c[1]) * x + c[2]) * x + c[3];
    }
    return from_dvec3<P>(p);
  }
  /// The k-th (0 or 1) coordinate other than `a`, in increasing order (x,y,z = 0,1,2). O(1).
  static constexpr int other_axis(int a, int k) noexcept { return k + (k >= a ? 1 : 0); }
};

/// The point type of an edge_curve (for the curve-range concepts of io/curves_io.hpp).
template <class C>
struct edge_curve_point {};
template <Point3 P>
struct edge_curve_point<edge_curve<P>> {
  using type = P;
};

/// A contiguous range of edge_curve<P> (a vector, array or span), for some point type P.
template <class R>
concept edge_curve_range = std::ranges::contiguous_range<R> && std::ranges::sized_range<R> && requires {
  typename edge_curve_point<std::ranges::range_value_t<R>>::type;
};

/// The point type of an edge_curve_range.
template <edge_curve_range R>
using edge_curve_range_point_t = typename edge_curve_point<std::ranges::range_value_t<R>>::type;

/// The same curve with its control points converted to Q (through double precision; a no-op
/// copy when Q is P). O(1).
template <Point3 Q, Point3 P>
edge_curve<Q> curve_cast(const edge_curve<P>& c) {
  if constexpr (std::is_same_v<P, Q>) {
    return c;
  } else {
    edge_curve<Q> out;
    out.edge = c.edge, out.v0 = c.v0, out.v1 = c.v1;
    out.kind = c.kind;
    out.has_axis_form = c.has_axis_form, out.axis = c.axis;
    out.limits = c.limits, out.coefficients = c.coefficients;
    out.bezier = detail::from_dbezier<Q>(detail::to_dbezier(c.bezier));
    return out;
  }
}

namespace detail {

/// The double-precision curve the builders and smooth_edges compute with.
using dcurve = edge_curve<glm::dvec3>;

/// Power-basis coefficients in t of the Bézier's coordinate `c`: a0 + a1 t + a2 t² + a3 t³.
template <class = void>
std::array<double, 4> bezier_power(const dbezier& b, int c) {
  const double b0 = b[0][c], b1 = b[1][c], b2 = b[2][c], b3 = b[3][c];
  return {b0, 3.0 * (b1 - b0), 3.0 * (b2 - 2.0 * b1 + b0), b3 - 3.0 * b2 + 3.0 * b1 - b0};
}

template <class = void>
curve_kind kind_of_bezier(const dbezier& b) {
  // The cubic term vanishes exactly for degree-elevated quadratics and lines.
  bool quadratic = false;
  for (int c = 0; c < 3; ++c) {
    const auto a = bezier_power(b, c);
    const double scale = std::abs(b[0][c]) + std::abs(b[1][c]) + std::abs(b[2][c]) + std::abs(b[3][c]);
    if (std::abs(a[3]) > 1e-14 * scale) return curve_kind::cubic;
    if (std::abs(a[2]) > 1e-14 * scale) quadratic = true;
  }
  return quadratic ? curve_kind::quadratic : curve_kind::straight;
}

/// set_axis_form below, in double precision: substitutes t = (x − limits[0]) / (limits[1] − limits[0]).
template <class = void>
bool set_axis_form(dcurve& c, int axis) {
  const double lo = c.bezier[0][axis], hi = c.bezier[3][axis];
  const double range = hi - lo;
  if (!(range != 0.0) || !std::isfinite(range)) {
    c.has_axis_form = false;
    return false;
  }
  const double s = 1.0 / range, r = -lo * s;  // t = s x + r
  for (int k = 0; k < 2; ++k) {
    const auto a = detail::bezier_power(c.bezier, dcurve::other_axis(axis, k));
    auto& out = c.coefficients[static_cast<std::size_t>(k)];
    out[0] = a[3] * s * s * s;
    out[1] = (a[2] + 3.0 * a[3] * r) * s * s;
    out[2] = (a[1] + 2.0 * a[2] * r + 3.0 * a[3] * r * r) * s;
    out[3] = a[0] + (a[1] + (a[2] + a[3] * r) * r) * r;
  }
  c.axis = axis;
  c.limits = {lo, hi};
  c.has_axis_form = true;
  return true;
}

/// largest_range_axis below, in double precision.
template <class = void>
int largest_range_axis(const glm::dvec3& p0, const glm::dvec3& p1) {
  const double dx = std::abs(p1.x - p0.x), dy = std::abs(p1.y - p0.y), dz = std::abs(p1.z - p0.z);
  return dx >= dy ? (dx >= dz ? 0 : 2) : (dy >= dz ? 1 : 2);
}

/// straight_curve below, in double precision.
template <class = void>
dcurve straight_curve(const glm::dvec3& p0, const glm::dvec3& p1) {
  dcurve c;
  c.kind = curve_kind::straight;
  c.bezier = {p0, p0 + (p1 - p0) / 3.0, p1 - (p1 - p0) / 3.0, p1};
  set_axis_form(c, largest_range_axis(p0, p1));
  return c;
}

/// axis_curve below, in double precision.
template <class = void>
dcurve axis_curve(int axis, std::array<double, 2> limits,
                  const std::array<std::array<double, 4>, 2>& coefficients) {
  if (axis < 0 || axis > 2)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("axis_curve: axis = ", std::to_string(axis), ", must be 0, 1 or 2"));
  for (double v : {limits[0], limits[1]})
    if (!std::isfinite(v)) throw error(error_category::invalid_input, "axis_curve: non-finite limit");
  for (const auto& row : coefficients)
    for (double v : row)
      if (!std::isfinite(v)) throw error(error_category::invalid_input, "axis_curve: non-finite coefficient");
  dcurve c;
  c.has_axis_form = true;
  c.axis = axis;
  c.limits = limits;
  c.coefficients = coefficients;
  const double lo = limits[0], range = limits[1] - limits[0];
  for (int i = 0; i < 4; ++i) c.bezier[static_cast<std::size_t>(i)][axis] = lo + range * (i / 3.0);
  c.bezier[3][axis] = limits[1];
  for (int k = 0; k < 2; ++k) {
    const auto& q = coefficients[static_cast<std::size_t>(k)];
    // Taylor expansion at lo gives the power basis in t; then power → Bernstein.
    const double a0 = ((q[0] * lo + q[1]) * lo + q[2]) * lo + q[3];
    const double a1 = ((3.0 * q[0] * lo + 2.0 * q[1]) * lo + q[2]) * range;
    const double a2 = (3.0 * q[0] * lo + q[1]) * range * range;
    const double a3 = q[0] * range * range * range;
    const int o = dcurve::other_axis(axis, k);
    c.bezier[0][o] = a0;
    c.bezier[1][o] = a0 + a1 / 3.0;
    c.bezier[2][o] = a0 + (2.0 * a1 + a2) / 3.0;
    c.bezier[3][o] = a0 + a1 + a2 + a3;
  }
  const bool cubic = coefficients[0][0] != 0.0 || coefficients[1][0] != 0.0;
  const bool quadratic = coefficients[0][1] != 0.0 || coefficients[1][1] != 0.0;
  c.kind = cubic ? curve_kind::cubic : quadratic ? curve_kind::quadratic : curve_kind::straight;
  return c;
}

/// hermite_curve below, in double precision.
template <class = void>
dcurve hermite_curve(const glm::dvec3& p0, const glm::dvec3& d0, const glm::dvec3& p1, const glm::dvec3& d1) {
  dcurve c;
  c.bezier = {p0, p0 + d0 / 3.0, p1 - d1 / 3.0, p1};
  c.kind = detail::kind_of_bezier(c.bezier);
  return c;
}

/// quadratic_bezier_curve below, in double precision.
template <class = void>
dcurve quadratic_bezier_curve(const glm::dvec3& p0, const glm::dvec3& q, const glm::dvec3& p1) {
  dcurve c;
  c.bezier = {p0, p0 + (2.0 / 3.0) * (q - p0), p1 + (2.0 / 3.0) * (q - p1), p1};
  c.kind = detail::kind_of_bezier(c.bezier);
  return c;
}

/// fit_axis_curve below, in double precision.
template <class = void>
std::optional<dcurve> fit_axis_curve(const glm::dvec3& p0, const glm::dvec3& p1, int axis,
                                     const std::optional<glm::dvec3>& t0,
                                     const std::optional<glm::dvec3>& t1) {
  const double range = p1[axis] - p0[axis];
  if (!(range != 0.0)) return std::nullopt;
  // A direction scaled so that its axis component equals the range is d point/dt of the x-param.
  auto scaled = [&](const glm::dvec3& d) -> std::optional<glm::dvec3> {
    // A direction (nearly) perpendicular to the axis has no finite slope on it.
    if (!(std::abs(d[axis]) > 1e-9 * std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z))) return std::nullopt;
    glm::dvec3 s = d * (range / d[axis]);
    s[axis] = range;  // exact, so the axis coordinate stays linear in t
    if (!std::isfinite(s.x) || !std::isfinite(s.y) || !std::isfinite(s.z)) return std::nullopt;
    return s;
  };
  dcurve c;
  if (t0 && t1) {
    const auto d0 = scaled(*t0), d1 = scaled(*t1);
    if (!d0 || !d1) return std::nullopt;
    c = hermite_curve(p0, *d0, p1, *d1);
  } else if (t0 || t1) {
    const auto d = scaled(t0 ? *t0 : *t1);
    if (!d) return std::nullopt;
    // The parabola's control point: half the range along the known end's slope.
    c = quadratic_bezier_curve(p0, t0 ? p0 + 0.5 * *d : p1 - 0.5 * *d, p1);
  } else {
    c = straight_curve(p0, p1);
  }
  c.bezier[1][axis] = p0[axis] + range / 3.0;
  c.bezier[2][axis] = p1[axis] - range / 3.0;
  set_axis_form(c, axis);
  return c;
}

/// fit_bezier_curve below, in double precision.
template <class = void>
dcurve fit_bezier_curve(const glm::dvec3& p0, const glm::dvec3& p1, const std::optional<glm::dvec3>& t0,
                        const std::optional<glm::dvec3>& t1) {
  const glm::dvec3 v = p1 - p0;
  const double chord = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  auto unit = [](const std::optional<glm::dvec3>& d) -> std::optional<glm::dvec3> {
    if (!d) return std::nullopt;
    const double l = std::sqrt(d->x * d->x + d->y * d->y + d->z * d->z);
    if (!(l > 0.0) || !std::isfinite(l)) return std::nullopt;
    return *d / l;
  };
  const auto u0 = unit(t0), u1 = unit(t1);
  if (!(chord > 0.0) || (!u0 && !u1)) return straight_curve(p0, p1);
  dcurve c;
  if (u0 && u1) {
    const double cos_turn = std::clamp(u0->x * u1->x + u0->y * u1->y + u0->z * u1->z, -1.0, 1.0);
    const double q = std::cos(std::acos(cos_turn) / 4.0);
    const double handle = chord / (3.0 * q * q);
    c.bezier = {p0, p0 + handle * *u0, p1 - handle * *u1, p1};
    c.kind = detail::kind_of_bezier(c.bezier);
  } else {
    const glm::dvec3 u = u0 ? *u0 : *u1;
    // |q − p0| = |q − p1| for q on the known end's tangent line: distance chord / (2 cos α).
    const double cos_a = std::abs(u.x * v.x + u.y * v.y + u.z * v.z) / chord;
    const double dist = chord / (2.0 * std::max(cos_a, 0.5));
    c = quadratic_bezier_curve(p0, u0 ? p0 + dist * u : p1 - dist * u, p1);
  }
  // A parametric curve keeps an axis form only when it is a line (then it is exact).
  if (c.kind == curve_kind::straight) set_axis_form(c, largest_range_axis(p0, p1));
  return c;
}

}  // namespace detail

// The builders in the caller's point type: the maths above, run in double precision and
// converted once (no conversion for glm::dvec3). Directions t0, t1 are of the same type.

/// Fill c's axis form for `axis` from its Bézier; requires bezier[k][axis] linear in t (which the
/// axis builders guarantee). Solves the seed's 6.4 system in closed form. O(1). Returns false
/// (form unset) for a zero range.
template <Point3 P>
bool set_axis_form(edge_curve<P>& c, int axis) {
  if constexpr (std::is_same_v<P, glm::dvec3>) {
    return detail::set_axis_form(c, axis);
  } else {
    detail::dcurve d = curve_cast<glm::dvec3>(c);
    detail::set_axis_form(d, axis);
    c.has_axis_form = d.has_axis_form, c.axis = d.axis, c.limits = d.limits, c.coefficients = d.coefficients;
    return c.has_axis_form;
  }
}

/// The axis (0,1,2) along which p0 → p1 has the largest range (the seed's choice, §6.4). O(1).
template <Point3 P>
int largest_range_axis(const P& p0, const P& p1) {
  return detail::largest_range_axis(to_dvec3(p0), to_dvec3(p1));
}

/// A straight edge p0 → p1 (Bézier on the chord thirds, axis form on the largest-range axis). O(1).
template <Point3 P>
edge_curve<P> straight_curve(const P& p0, const P& p1) {
  return curve_cast<P>(detail::straight_curve(to_dvec3(p0), to_dvec3(p1)));
}

/// The seed's stored form → a curve with control points of type P (a template argument: the
/// numbers have no point type): `axis` runs linearly from limits[0] to limits[1], the other two
/// coordinates are the cubics `coefficients` (increasing axis order). Exact Bézier conversion in
/// double precision. O(1). Throws error(invalid_input) for an axis outside 0..2 or a non-finite number.
template <Point3 P>
edge_curve<P> axis_curve(int axis, std::array<double, 2> limits,
                         const std::array<std::array<double, 4>, 2>& coefficients) {
  return curve_cast<P>(detail::axis_curve(axis, limits, coefficients));
}

/// Cubic Hermite p0 → p1 with end derivatives d0, d1 (d point/dt) as a Bézier; no axis form. O(1).
template <Point3 P>
edge_curve<P> hermite_curve(const P& p0, const std::type_identity_t<P>& d0, const std::type_identity_t<P>& p1,
                            const std::type_identity_t<P>& d1) {
  return curve_cast<P>(detail::hermite_curve(to_dvec3(p0), to_dvec3(d0), to_dvec3(p1), to_dvec3(d1)));
}

/// Quadratic Bézier p0, q, p1, degree-elevated to the cubic representation; no axis form. O(1).
template <Point3 P>
edge_curve<P> quadratic_bezier_curve(const P& p0, const std::type_identity_t<P>& q,
                                     const std::type_identity_t<P>& p1) {
  return curve_cast<P>(detail::quadratic_bezier_curve(to_dvec3(p0), to_dvec3(q), to_dvec3(p1)));
}

namespace detail {
template <Point3 P>
std::optional<glm::dvec3> optional_dvec3(const std::optional<P>& d) {
  if (!d) return std::nullopt;
  return cellforge::to_dvec3(*d);
}
}  // namespace detail

/// The seed's §6.4 fit: p0 → p1 as a function of `axis`, with the end directions t0 / t1 (any
/// length; absent = free end) giving the slopes d(other)/d(axis). Both → cubic, one → quadratic,
/// none → straight. Returns nothing when a given direction's axis component is below 1e-9 of its
/// length (the curve is then not a function of that axis) or the axis range is zero. O(1).
template <Point3 P>
std::optional<edge_curve<P>> fit_axis_curve(const P& p0, const std::type_identity_t<P>& p1, int axis,
                                            const std::optional<std::type_identity_t<P>>& t0,
                                            const std::optional<std::type_identity_t<P>>& t1) {
  const auto c = detail::fit_axis_curve(to_dvec3(p0), to_dvec3(p1), axis, detail::optional_dvec3(t0),
                                        detail::optional_dvec3(t1));
  if (!c) return std::nullopt;
  return curve_cast<P>(*c);
}

/// Parametric fit p0 → p1 from end directions t0 / t1 (absent or zero = free end). Both: cubic Bézier
/// with handles chord / (3 cos²(θ/4)) along them, θ the turn between the directions — exactly the
/// standard circular-arc handle (4/3) R tan(θ/4), so planar arcs (a quarter circle) are reproduced to
/// ~3e-4 R. One: the quadratic whose control point is equidistant from both ends (the circle-like
/// parabola; its distance is capped at one chord). None: straight. O(1).
template <Point3 P>
edge_curve<P> fit_bezier_curve(const P& p0, const std::type_identity_t<P>& p1,
                               const std::optional<std::type_identity_t<P>>& t0,
                               const std::optional<std::type_identity_t<P>>& t1) {
  return curve_cast<P>(detail::fit_bezier_curve(to_dvec3(p0), to_dvec3(p1), detail::optional_dvec3(t0),
                                                detail::optional_dvec3(t1)));
}

}  // namespace cellforge
