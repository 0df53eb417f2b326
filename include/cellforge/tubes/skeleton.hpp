// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Skeleton graphs, the input of the tube mesher: nodes with a position and a radius, and
/// directed edges (from, to) between them. `skeleton_traits<G>` adapts a user's own graph
/// type; `skeleton<P>` is the plain default model; `validate(skeleton)` / `check_skeleton`
/// say what in a skeleton no tube mesh can be made of.

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"

namespace cellforge {

/// The plain skeleton: node positions and radii (same length), and directed edges as
/// (from, to) index pairs into them.
template <Point3 P>
struct skeleton {
  using point_type = P;
  std::vector<P> points;
  std::vector<double> radii;
  std::vector<std::array<std::uint32_t, 2>> edges;
};

/// Specialise for a graph type G with: `using point_type = ...;` (a Point3),
/// `static std::size_t num_nodes(const G&)`, `static point_type position(const G&, std::size_t i)`,
/// `static double radius(const G&, std::size_t i)` (any type convertible to double),
/// `static std::size_t num_edges(const G&)` and
/// `static std::array<std::size_t, 2> endpoints(const G&, std::size_t j)` (from, to).
/// The primary template is empty so that an unadapted type fails `Skeleton` at the call.
template <class G>
struct skeleton_traits {};

/// Anything cellforge can read as a skeleton graph through skeleton_traits.
template <class G>
concept Skeleton = requires {
  typename skeleton_traits<G>::point_type;
}
&&Point3<typename skeleton_traits<G>::point_type>&& requires(const G& g, std::size_t i) {
  { skeleton_traits<G>::num_nodes(g) } -> std::convertible_to<std::size_t>;
  { skeleton_traits<G>::position(g, i) } -> std::convertible_to<typename skeleton_traits<G>::point_type>;
  { skeleton_traits<G>::radius(g, i) } -> std::convertible_to<double>;
  { skeleton_traits<G>::num_edges(g) } -> std::convertible_to<std::size_t>;
  { skeleton_traits<G>::endpoints(g, i) } -> std::convertible_to<std::array<std::size_t, 2>>;
};

template <Point3 P>
struct skeleton_traits<skeleton<P>> {
  using point_type = P;
  static std::size_t num_nodes(const skeleton<P>& g) noexcept { return g.points.size(); }
  static const P& position(const skeleton<P>& g, std::size_t i) noexcept { return g.points[i]; }
  static double radius(const skeleton<P>& g, std::size_t i) noexcept { return g.radii[i]; }
  static std::size_t num_edges(const skeleton<P>& g) noexcept { return g.edges.size(); }
  static std::array<std::size_t, 2> endpoints(const skeleton<P>& g, std::size_t j) noexcept {
    return {g.edges[j][0], g.edges[j][1]};
  }
};

/// The point type of a Skeleton.
template <Skeleton G>
using skeleton_point_t = typename skeleton_traits<G>::point_type;

/// Copies any Skeleton into the plain struct, in point type Q (by default G's own). Throws
/// invalid_input when it has 2^32 nodes or more (the struct's index type). O(V + E).
template <class Q = void, Skeleton G>
requires(std::is_void_v<Q> || Point3<Q>) auto to_skeleton(const G& g) {
  using T = skeleton_traits<G>;
  using R = std::conditional_t<std::is_void_v<Q>, skeleton_point_t<G>, Q>;
  skeleton<R> s;
  const std::size_t nv = T::num_nodes(g), ne = T::num_edges(g);
  if (nv >= std::numeric_limits<std::uint32_t>::max())
    throw error(error_category::invalid_input, "to_skeleton: more than 2^32 - 2 nodes");
  s.points.reserve(nv);
  s.radii.reserve(nv);
  s.edges.reserve(ne);
  for (std::size_t i = 0; i < nv; ++i) {
    if constexpr (std::is_same_v<R, skeleton_point_t<G>>)
      s.points.push_back(T::position(g, i));
    else
      s.points.push_back(from_dvec3<R>(to_dvec3(skeleton_point_t<G>(T::position(g, i)))));
    s.radii.push_back(static_cast<double>(T::radius(g, i)));
  }
  for (std::size_t j = 0; j < ne; ++j) {
    const std::array<std::size_t, 2> ab = T::endpoints(g, j);
    // Out-of-range endpoints are kept (clamped to the sentinel) for validate(skeleton) to report.
    const auto narrow = [](std::size_t v) {
      return static_cast<std::uint32_t>(std::min<std::size_t>(v, std::numeric_limits<std::uint32_t>::max()));
    };
    s.edges.push_back({narrow(ab[0]), narrow(ab[1])});
  }
  return s;
}

/// What validate(skeleton) found wrong; `none` when the skeleton can be meshed as far as its
/// input goes.
enum class skeleton_defect : std::uint8_t {
  none,
  bad_radius,             ///< a radius that is not a positive finite number
  bad_position,           ///< a NaN or infinite coordinate
  endpoint_out_of_range,  ///< an edge names a node that does not exist
  self_loop,              ///< an edge from a node to itself
  duplicate_edge,         ///< two edges join the same two nodes (in either direction)
  coincident_nodes,       ///< two nodes at exactly the same position
};

/// The first defect of a skeleton, the node or edge it concerns, and a sentence saying so.
struct skeleton_validation {
  static constexpr std::size_t npos = ~std::size_t{0};
  skeleton_defect defect = skeleton_defect::none;
  std::size_t node = npos;   ///< the node concerned (the later of two coincident nodes)
  std::size_t other = npos;  ///< the earlier coincident node, or the edge a duplicate repeats
  std::size_t edge = npos;   ///< the edge concerned
  std::string message;
  bool ok() const noexcept { return defect == skeleton_defect::none; }
  explicit operator bool() const noexcept { return ok(); }
};

namespace detail {

/// Shortest round-trip text of a number, for messages. O(1).
template <class T>
std::string skeleton_number(T v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

/// "(x, y, z)" of a point, for messages. O(1).
template <class T>
std::string skeleton_point_text(const T& p) {
  std::string s = "(";
  for (std::size_t k = 0; k < 3; ++k) {
    if (k != 0) s += ", ";
    s += skeleton_number(coord(p, k));
  }
  return s + ")";
}

/// The first index j (ascending) whose key equals an earlier index's key, and the earliest such
/// earlier index; {npos, npos} when no key repeats. `key(j)` gives a value with ==, `hash` its
/// 64-bit hash. An open-addressed table of indices (a sort of the keys costs ten times as much
/// at 10^5 nodes). O(n) expected; n < 2^32.
template <class Key, class Hash>
std::array<std::size_t, 2> first_repeat(std::size_t n, Key&& key, Hash&& hash) {
  constexpr std::size_t npos = ~std::size_t{0};
  constexpr std::uint32_t empty = 0xFFFFFFFFu;
  std::size_t size = 16;
  while (size < 2 * n) size *= 2;
  std::vector<std::uint32_t> slot(size, empty);
  for (std::size_t j = 0; j < n; ++j) {
    const auto k = key(j);
    // A full mix (murmur's finaliser): lattice positions are doubles with all low bits zero.
    std::uint64_t h = hash(k);
    h = (h ^ (h >> 33)) * 0xFF51AFD7ED558CCDull;
    h = (h ^ (h >> 33)) * 0xC4CEB9FE1A85EC53ull;
    for (std::size_t at = (h ^ (h >> 33)) & (size - 1);; at = (at + 1) & (size - 1)) {
      if (slot[at] == empty) {
        slot[at] = static_cast<std::uint32_t>(j);
        break;
      }
      if (key(slot[at]) == k) return {j, slot[at]};
    }
  }
  return {npos, npos};
}

/// The earliest edge that joins the same two nodes as an earlier one (in either direction), and
/// that earlier one; {npos, npos} when no edge repeats. `endpoints(j)` gives edge j's nodes. O(E).
template <class Endpoints>
std::array<std::size_t, 2> first_repeated_edge(std::size_t ne, Endpoints&& endpoints) {
  return first_repeat(
      ne,
      [&](std::size_t j) {
        const std::array<std::size_t, 2> ab = endpoints(j);
        return std::array<std::size_t, 2>{std::min(ab[0], ab[1]), std::max(ab[0], ab[1])};
      },
      [](const std::array<std::size_t, 2>& k) { return (k[0] * 0xC2B2AE3D27D4EB4Full) ^ k[1]; });
}

}  // namespace detail

/// Checks a skeleton in this order: every node's radius (positive, finite) and position
/// (finite), every edge's endpoints (in range, distinct), no edge twice in either direction, no
/// two nodes at exactly the same position; returns the first defect. O(V + E) expected.
template <Skeleton G>
skeleton_validation validate(const G& g) {
  using T = skeleton_traits<G>;
  using R = skeleton_validation;
  const std::size_t nv = T::num_nodes(g), ne = T::num_edges(g);
  const auto node_name = [](std::size_t i) { return cellforge::detail::cat("node ", std::to_string(i)); };
  const auto edge_name = [](std::size_t j) { return cellforge::detail::cat("edge ", std::to_string(j)); };
  if constexpr (std::is_same_v<G, skeleton<skeleton_point_t<G>>>) {
    if (g.radii.size() != g.points.size())
      return {skeleton_defect::bad_radius, R::npos, R::npos, R::npos,
              cellforge::detail::cat("the skeleton has ", std::to_string(g.points.size()), " points but ",
                                     std::to_string(g.radii.size()), " radii")};
  }
  for (std::size_t i = 0; i < nv; ++i) {
    const double r = static_cast<double>(T::radius(g, i));
    if (!std::isfinite(r) || !(r > 0))
      return {skeleton_defect::bad_radius, i, R::npos, R::npos,
              node_name(i) + ": radius " + detail::skeleton_number(r) +
                  (std::isfinite(r) ? " is not positive" : " is not finite")};
    const auto p = skeleton_point_t<G>(T::position(g, i));
    if constexpr (std::is_floating_point_v<scalar_t<skeleton_point_t<G>>>) {
      for (std::size_t k = 0; k < 3; ++k)
        if (!std::isfinite(coord(p, k)))
          return {skeleton_defect::bad_position, i, R::npos, R::npos,
                  node_name(i) + ": position " + detail::skeleton_point_text(p) + " is not finite"};
    }
  }
  for (std::size_t j = 0; j < ne; ++j) {
    const std::array<std::size_t, 2> ab = T::endpoints(g, j);
    for (const std::size_t v : ab)
      if (v >= nv)
        return {skeleton_defect::endpoint_out_of_range, R::npos, R::npos, j,
                edge_name(j) + ": node " + std::to_string(v) + " out of range (" + std::to_string(nv) +
                    " nodes)"};
    if (ab[0] == ab[1])
      return {skeleton_defect::self_loop, ab[0], R::npos, j,
              edge_name(j) + " joins " + node_name(ab[0]) + " to itself"};
  }
  const auto [worst, first] = detail::first_repeated_edge(
      ne, [&](std::size_t j) -> std::array<std::size_t, 2> { return T::endpoints(g, j); });
  if (worst != R::npos) {
    const std::array<std::size_t, 2> ab = T::endpoints(g, worst);
    return {skeleton_defect::duplicate_edge, R::npos, first, worst,
            edge_name(worst) + " repeats " + edge_name(first) + " (nodes " + std::to_string(ab[0]) + " and " +
                std::to_string(ab[1]) + ")"};
  }
  // Coincident nodes: exact comparison; -0 and +0 are one position (adding +0 makes -0 +0).
  const auto [later, earlier] = detail::first_repeat(
      nv,
      [&](std::size_t i) {
        const auto p = skeleton_point_t<G>(T::position(g, i));
        return std::array<double, 3>{static_cast<double>(coord(p, 0)) + 0.0,
                                     static_cast<double>(coord(p, 1)) + 0.0,
                                     static_cast<double>(coord(p, 2)) + 0.0};
      },
      [](const std::array<double, 3>& k) {
        return std::bit_cast<std::uint64_t>(k[0]) ^ std::rotl(std::bit_cast<std::uint64_t>(k[1]), 21) ^
               std::rotl(std::bit_cast<std::uint64_t>(k[2]), 42);
      });
  if (later != R::npos) {
    const auto p = skeleton_point_t<G>(T::position(g, later));
    return {skeleton_defect::coincident_nodes, later, earlier, R::npos,
            cellforge::detail::cat("nodes ", std::to_string(earlier), " and ", std::to_string(later),
                                   " coincide (both at ", detail::skeleton_point_text(p), ")")};
  }
  return {};
}

/// Throws an invalid_input `cellforge::error` with validate(skeleton)'s message when the
/// skeleton has a defect; returns normally otherwise. O(V + E) expected.
template <Skeleton G>
void check_skeleton(const G& g) {
  skeleton_validation v = validate(g);
  if (!v.ok())
    throw error(error_category::invalid_input, cellforge::detail::cat("check_skeleton: ", v.message));
}

namespace detail {

/// Throws invalid_input, the message prefixed by `writer`, for any defect of g but coincident
/// nodes (which the readers accept): a writer never makes a file its reader would reject.
/// O(V log V + E log E).
template <Skeleton G>
void check_skeleton_writable(const G& g, std::string_view writer) {
  if (const skeleton_validation v = validate(g); !v.ok() && v.defect != skeleton_defect::coincident_nodes)
    throw error(error_category::invalid_input, cellforge::detail::cat(std::string(writer), ": ", v.message));
}

}  // namespace detail

}  // namespace cellforge
