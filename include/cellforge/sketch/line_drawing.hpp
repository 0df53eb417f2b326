// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Line drawings: the input of the sketch stages. Junctions are 2D points; edges join two
/// junctions by a straight line. Edges may cross in the drawing where hidden lines show: a
/// crossing is not a junction. `line_drawing_traits<D>` adapts a user's own drawing type;
/// `line_drawing<P>` is the plain default model.

#include <algorithm>
#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"

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

}  // namespace cellforge
