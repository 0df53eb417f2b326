// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Line drawings: the input of the sketch stages. Junctions are 2D points; edges join two
/// junctions by a straight line. Edges may cross in the drawing where hidden lines show: a
/// crossing is not a junction. `line_drawing_traits<D>` adapts a user's own drawing type;
/// `line_drawing<P>` is the plain default model; `validate(drawing)` / `check_drawing` say what in
/// a drawing no face finder can read (see docs/sketch.md, "Input: line drawings").

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/if_satisfied.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/sketch/detail/drawing_grid.hpp"

namespace cellforge {

/// The plain line drawing: junction positions, and edges as index pairs into them.
template <Point2 P>
struct line_drawing {
  using point_type = P;
  std::vector<P> points;
  std::vector<std::array<std::uint32_t, 2>> edges;
};

/// Specialise for a drawing type D with: `using point_type = ...;` (a Point2),
/// `static std::size_t num_junctions(const D&)`, `static point_type position(const D&, std::size_t i)`,
/// `static std::size_t num_edges(const D&)` and
/// `static std::array<std::size_t, 2> endpoints(const D&, std::size_t e)`.
/// The primary template is empty so that an unadapted type fails `LineDrawing` at the call.
template <class D>
struct line_drawing_traits {};

/// Anything cellforge can read as a line drawing through line_drawing_traits.
template <class D>
concept LineDrawing = requires {
  typename line_drawing_traits<D>::point_type;
}
&&Point2<typename line_drawing_traits<D>::point_type>&& requires(const D& d, std::size_t i) {
  { line_drawing_traits<D>::num_junctions(d) } -> std::convertible_to<std::size_t>;
  {
    line_drawing_traits<D>::position(d, i)
    } -> std::convertible_to<typename line_drawing_traits<D>::point_type>;
  { line_drawing_traits<D>::num_edges(d) } -> std::convertible_to<std::size_t>;
  { line_drawing_traits<D>::endpoints(d, i) } -> std::convertible_to<std::array<std::size_t, 2>>;
};

template <Point2 P>
struct line_drawing_traits<line_drawing<P>> {
  using point_type = P;
  static std::size_t num_junctions(const line_drawing<P>& d) noexcept { return d.points.size(); }
  static const P& position(const line_drawing<P>& d, std::size_t i) noexcept { return d.points[i]; }
  static std::size_t num_edges(const line_drawing<P>& d) noexcept { return d.edges.size(); }
  static std::array<std::size_t, 2> endpoints(const line_drawing<P>& d, std::size_t e) noexcept {
    return {d.edges[e][0], d.edges[e][1]};
  }
};

/// The point type of a LineDrawing.
template <LineDrawing D>
using drawing_point_t = typename line_drawing_traits<D>::point_type;

/// Copies any LineDrawing into the plain struct, in point type Q (by default D's own). Throws
/// invalid_input when it has 2^32 junctions or more (the struct's index type). O(V + E).
template <class Q = void, LineDrawing D>
requires(std::is_void_v<Q> || Point2<Q>) auto to_line_drawing(const D& d) {
  using T = line_drawing_traits<D>;
  using R = std::conditional_t<std::is_void_v<Q>, drawing_point_t<D>, Q>;
  line_drawing<R> out;
  const std::size_t nv = T::num_junctions(d), ne = T::num_edges(d);
  if (nv >= std::numeric_limits<std::uint32_t>::max())
    throw error(error_category::invalid_input, "to_line_drawing: more than 2^32 - 2 junctions");
  out.points.reserve(nv);
  out.edges.reserve(ne);
  for (std::size_t i = 0; i < nv; ++i) {
    if constexpr (std::is_same_v<R, drawing_point_t<D>>)
      out.points.push_back(T::position(d, i));
    else
      out.points.push_back(from_dvec2<R>(to_dvec2(drawing_point_t<D>(T::position(d, i)))));
  }
  for (std::size_t e = 0; e < ne; ++e) {
    const std::array<std::size_t, 2> ab = T::endpoints(d, e);
    // Out-of-range endpoints are kept (clamped to the sentinel) for validation to report.
    const auto narrow = [](std::size_t v) {
      return static_cast<std::uint32_t>(std::min<std::size_t>(v, std::numeric_limits<std::uint32_t>::max()));
    };
    out.edges.push_back({narrow(ab[0]), narrow(ab[1])});
  }
  return out;
}

/// What validate(drawing) found wrong; `none` when the drawing can be read for faces as far as
/// its input goes. Edges crossing in their interiors are not defects (hidden lines cross).
enum class drawing_defect : std::uint8_t {
  none,
  bad_position,           ///< a NaN or infinite coordinate
  endpoint_out_of_range,  ///< an edge names a junction that does not exist
  self_loop,              ///< an edge from a junction to itself
  duplicate_edge,         ///< two edges join the same two junctions (in either direction)
  empty,                  ///< no edge at all
  coincident_junctions,   ///< two junctions closer than the tolerance
  overlapping_edges,      ///< two edges collinear (within the tolerance) and overlapping
  junction_on_edge,       ///< a junction on the interior of an edge that does not end at it
  dangling_junction,      ///< a junction on fewer than two edges: no polyhedron's vertex is
};

/// The first defect of a drawing, the junctions and edges it concerns, and a sentence saying so.
struct drawing_validation {
  static constexpr std::size_t npos = ~std::size_t{0};
  drawing_defect defect = drawing_defect::none;
  std::size_t junction = npos;    ///< the junction concerned (the later of two coincident ones)
  std::size_t other = npos;       ///< the earlier of two coincident junctions
  std::size_t edge = npos;        ///< the edge concerned (the later of two)
  std::size_t other_edge = npos;  ///< the earlier edge a duplicate repeats or an overlap covers
  std::string message;
  bool ok() const noexcept { return defect == drawing_defect::none; }
  explicit operator bool() const noexcept { return ok(); }
};

/// How validate(drawing) judges geometry.
struct drawing_validation_options {
  /// Two junctions closer than this fraction of the drawing's bounding-box diagonal are one
  /// point; a junction this close to an edge is on it; edges this close to a common line are
  /// collinear. Must be finite and in [0, 0.5).
  double tolerance = 1e-9;
};

namespace detail {

/// Shortest round-trip text of a number, for messages. O(1).
template <class T>
std::string drawing_number(T v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

/// "(x, y)" of a 2D point, for messages. O(1).
template <class T>
std::string drawing_point_text(const T& p) {
  return cellforge::detail::cat("(", drawing_number(point2_traits<T>::get(p, 0)), ", ",
                                drawing_number(point2_traits<T>::get(p, 1)), ")");
}

}  // namespace detail

/// Checks a drawing in this order and returns the first defect: finite positions, edge ends in
/// range and distinct, no edge twice, at least one edge; then, to `tolerance` × the bounding-box
/// diagonal, no coincident junctions, no collinear overlapping edges, no junction on another
/// edge's interior; last, every junction on two edges or more. The geometric tests run on a
/// uniform grid: O(V log V + E log E + K), K the edge–edge and edge–junction pairs sharing a
/// grid cell (O(E) for evenly spread drawings; a junction of degree d adds d²).
template <LineDrawing D>
drawing_validation validate(const D& d, const drawing_validation_options& options = {}) {
  using T = line_drawing_traits<D>;
  using P = drawing_point_t<D>;
  using R = drawing_validation;
  const double tol = options.tolerance;
  if (!std::isfinite(tol) || tol < 0 || tol >= 0.5)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("validate(drawing): the tolerance ", detail::drawing_number(tol),
                                       " is not a finite number in [0, 0.5)"));
  const std::size_t nv = T::num_junctions(d), ne = T::num_edges(d);
  const auto jn = [](std::size_t i) { return cellforge::detail::cat("junction ", std::to_string(i)); };
  const auto en = [](std::size_t e) { return cellforge::detail::cat("edge ", std::to_string(e)); };
  std::vector<glm::dvec2> pts;
  pts.reserve(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    const P p = P(T::position(d, i));
    if constexpr (std::is_floating_point_v<scalar2_t<P>>) {
      for (std::size_t k = 0; k < 2; ++k)
        if (!std::isfinite(point2_traits<P>::get(p, k)))
          return {drawing_defect::bad_position,
                  i,
                  R::npos,
                  R::npos,
                  R::npos,
                  jn(i) + ": position " + detail::drawing_point_text(p) + " is not finite"};
    }
    pts.push_back(to_dvec2(p));
  }
  std::vector<std::array<std::size_t, 2>> ends(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    ends[e] = T::endpoints(d, e);
    for (const std::size_t v : ends[e])
      if (v >= nv)
        return {drawing_defect::endpoint_out_of_range,
                R::npos,
                R::npos,
                e,
                R::npos,
                en(e) + ": junction " + std::to_string(v) + " out of range (" + std::to_string(nv) +
                    " junctions)"};
    if (ends[e][0] == ends[e][1])
      return {drawing_defect::self_loop,
              ends[e][0],
              R::npos,
              e,
              R::npos,
              en(e) + " joins " + jn(ends[e][0]) + " to itself"};
  }
  {
    std::vector<std::array<std::size_t, 3>> keys(ne);  // (min, max, edge)
    for (std::size_t e = 0; e < ne; ++e)
      keys[e] = {std::min(ends[e][0], ends[e][1]), std::max(ends[e][0], ends[e][1]), e};
    std::sort(keys.begin(), keys.end());
    std::size_t later = R::npos, earlier = R::npos;
    for (std::size_t k = 1; k < ne; ++k)
      if (keys[k][0] == keys[k - 1][0] && keys[k][1] == keys[k - 1][1] && keys[k][2] < later)
        later = keys[k][2], earlier = keys[k - 1][2];
    if (later != R::npos)
      return {drawing_defect::duplicate_edge,
              R::npos,
              R::npos,
              later,
              earlier,
              en(later) + " repeats " + en(earlier) + " (junctions " + std::to_string(ends[later][0]) +
                  " and " + std::to_string(ends[later][1]) + ")"};
  }
  if (ne == 0)
    return {drawing_defect::empty,
            R::npos,
            R::npos,
            R::npos,
            R::npos,
            cellforge::detail::cat("the drawing has no edge (", std::to_string(nv), " junctions)")};

  const detail::drawing_frame frame = detail::make_drawing_frame(std::move(pts));
  const auto& q = frame.points;
  const double eps = tol * frame.diag;
  const std::string tol_text =
      cellforge::detail::cat(" (tolerance ", detail::drawing_number(tol), " of the drawing's diagonal)");
  {
    std::size_t later = R::npos, earlier = R::npos;
    detail::for_close_points(q, eps, [&](std::size_t i, std::size_t j) {
      if (j < later || (j == later && i < earlier)) later = j, earlier = i;
    });
    if (later != R::npos) {
      const P a = P(T::position(d, earlier)), b = P(T::position(d, later));
      return {drawing_defect::coincident_junctions,
              later,
              earlier,
              R::npos,
              R::npos,
              cellforge::detail::cat("junctions ", std::to_string(earlier), " ",
                                     detail::drawing_point_text(a), " and ", std::to_string(later), " ",
                                     detail::drawing_point_text(b), " are one point", tol_text)};
    }
  }
  std::vector<std::pair<glm::dvec2, glm::dvec2>> segs(ne);
  for (std::size_t e = 0; e < ne; ++e) segs[e] = {q[ends[e][0]], q[ends[e][1]]};
  // Overlap: f's ends within eps of e's line (and e's of f's), and their shadows on e overlap
  // by more than eps. Two edges meeting end to end in a straight line do not overlap.
  const auto overlap = [&](std::size_t e, std::size_t f) {
    const auto near_line = [&](std::size_t g, std::size_t h) {
      const glm::dvec2 a = segs[g].first, dir = segs[g].second - a;
      const double len = glm::length(dir);
      const auto off = [&](glm::dvec2 p) {
        return std::abs(dir.x * (p.y - a.y) - dir.y * (p.x - a.x)) / len;
      };
      return len > 0 && off(segs[h].first) <= eps && off(segs[h].second) <= eps;
    };
    if (!near_line(e, f) || !near_line(f, e)) return false;
    const glm::dvec2 a = segs[e].first, dir = segs[e].second - a;
    const double len = glm::length(dir);
    const double t0 = glm::dot(segs[f].first - a, dir) / len, t1 = glm::dot(segs[f].second - a, dir) / len;
    return std::min(len, std::max(t0, t1)) - std::max(0.0, std::min(t0, t1)) > eps;
  };
  std::size_t ov_later = R::npos, ov_earlier = R::npos, on_edge = R::npos, on_junction = R::npos;
  detail::for_grid_neighbours(
      segs, q, eps,
      [&](std::size_t e, std::size_t f) {
        if (e > f) std::swap(e, f);
        if ((f < ov_later || (f == ov_later && e < ov_earlier)) && overlap(e, f))
          ov_later = f, ov_earlier = e;
      },
      [&](std::size_t e, std::size_t v) {
        if (v == ends[e][0] || v == ends[e][1]) return;
        if ((e < on_edge || (e == on_edge && v < on_junction)) &&
            detail::segment_distance(q[v], segs[e].first, segs[e].second) <= eps)
          on_edge = e, on_junction = v;
      });
  if (ov_later != R::npos)
    return {drawing_defect::overlapping_edges,
            R::npos,
            R::npos,
            ov_later,
            ov_earlier,
            en(ov_later) + " (junctions " + std::to_string(ends[ov_later][0]) + " and " +
                std::to_string(ends[ov_later][1]) + ") lies along " + en(ov_earlier) + " (junctions " +
                std::to_string(ends[ov_earlier][0]) + " and " + std::to_string(ends[ov_earlier][1]) +
                "): collinear edges overlap" + tol_text};
  if (on_edge != R::npos)
    return {drawing_defect::junction_on_edge,
            on_junction,
            R::npos,
            on_edge,
            R::npos,
            jn(on_junction) + " lies on " + en(on_edge) + " (junctions " + std::to_string(ends[on_edge][0]) +
                " and " + std::to_string(ends[on_edge][1]) +
                "), which does not end there: a T-junction or an accident of the view, which no face "
                "finder can read" +
                tol_text};
  std::vector<std::uint32_t> degree(nv, 0);
  for (const auto& ab : ends) ++degree[ab[0]], ++degree[ab[1]];
  for (std::size_t i = 0; i < nv; ++i)
    if (degree[i] < 2)
      return {drawing_defect::dangling_junction,
              i,
              R::npos,
              R::npos,
              R::npos,
              jn(i) + " is on " + (degree[i] == 0 ? std::string("no edge") : std::string("one edge only")) +
                  ": not the drawing of a polyhedron, whose every vertex is on two edges or more"};
  return {};
}

/// Throws an invalid_input `cellforge::error` with validate(drawing)'s message when the drawing
/// has a defect; returns normally otherwise. Cost as validate(drawing).
template <LineDrawing D>
void check_drawing(const D& d, const drawing_validation_options& options = {}) {
  drawing_validation v = validate(d, options);
  if (!v.ok())
    throw error(error_category::invalid_input, cellforge::detail::cat("check_drawing: ", v.message));
}

}  // namespace cellforge
