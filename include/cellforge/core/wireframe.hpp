// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Wireframes: vertices and straight edges between them. `wireframe_traits<G>` adapts
/// a user's own graph type; `wireframe<P>` is the plain default model.

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cellforge/core/point_traits.hpp"

namespace cellforge {

/// The plain wireframe: points, and edges as index pairs into them.
template <Point3 P>
struct wireframe {
  using point_type = P;
  std::vector<P> points;
  std::vector<std::array<std::uint32_t, 2>> edges;
};

/// Specialise for a graph type G with: `using point_type = ...;` (a Point3),
/// `static std::size_t num_vertices(const G&)`, `static point_type position(const G&, std::size_t v)`,
/// `static std::size_t num_edges(const G&)` and
/// `static std::array<std::size_t, 2> endpoints(const G&, std::size_t e)`.
/// The primary template is empty so that an unadapted type fails `Wireframe` at the call.
template <class G>
struct wireframe_traits {};

/// Anything cellforge can read as a wireframe through wireframe_traits.
template <class G>
concept Wireframe = requires {
  typename wireframe_traits<G>::point_type;
}
&&Point3<typename wireframe_traits<G>::point_type>&& requires(const G& g, std::size_t i) {
  { wireframe_traits<G>::num_vertices(g) } -> std::convertible_to<std::size_t>;
  { wireframe_traits<G>::num_edges(g) } -> std::convertible_to<std::size_t>;
  { wireframe_traits<G>::position(g, i) } -> std::convertible_to<typename wireframe_traits<G>::point_type>;
  { wireframe_traits<G>::endpoints(g, i) } -> std::convertible_to<std::array<std::size_t, 2>>;
};

template <Point3 P>
struct wireframe_traits<wireframe<P>> {
  using point_type = P;
  static std::size_t num_vertices(const wireframe<P>& g) noexcept { return g.points.size(); }
  static const P& position(const wireframe<P>& g, std::size_t v) noexcept { return g.points[v]; }
  static std::size_t num_edges(const wireframe<P>& g) noexcept { return g.edges.size(); }
  static std::array<std::size_t, 2> endpoints(const wireframe<P>& g, std::size_t e) noexcept {
    return {g.edges[e][0], g.edges[e][1]};
  }
};

/// Copies any Wireframe into the plain struct with point type Q. O(V + E).
template <Point3 Q = glm::dvec3, Wireframe G>
wireframe<Q> to_wireframe(const G& g) {
  using T = wireframe_traits<G>;
  wireframe<Q> w;
  const std::size_t nv = T::num_vertices(g), ne = T::num_edges(g);
  w.points.reserve(nv);
  w.edges.reserve(ne);
  for (std::size_t v = 0; v < nv; ++v) w.points.push_back(from_dvec3<Q>(to_dvec3(T::position(g, v))));
  for (std::size_t e = 0; e < ne; ++e) {
    const auto ab = T::endpoints(g, e);
    w.edges.push_back({static_cast<std::uint32_t>(ab[0]), static_cast<std::uint32_t>(ab[1])});
  }
  return w;
}

}  // namespace cellforge
