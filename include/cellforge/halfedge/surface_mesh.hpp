// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// `surface_mesh<P>`: a half-edge mesh whose vertices have positions of the caller's point
/// type P, fixed at compile time. Every algorithm that needs positions takes a
/// `surface_mesh<P>` and deduces P, so a wrong point type does not compile; algorithms on
/// connectivity alone take the untyped base `halfedge_mesh`. See docs/traits.md.

#include <algorithm>
#include <cstddef>
#include <span>
#include <string_view>
#include <type_traits>
#include <utility>

#include "cellforge/core/point_traits.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

/// Name of the vertex property that holds a surface_mesh's positions (it is pinned: it
/// cannot be removed, and adding another property of that name fails).
inline constexpr std::string_view point_property_name = "v:point";

/// A half-edge mesh with a position of type P at every vertex. The positions live in the
/// mesh's vertex property "v:point", so every edit, garbage collection and copy keeps them
/// in step with the vertices; P needs no default constructor (new slots hold the origin,
/// made by point_traits<P>::make(0, 0, 0)).
template <Point3 P>
class surface_mesh : public halfedge_mesh {
 public:
  using point_type = P;
  using scalar_type = scalar_t<P>;

  /// An empty mesh. O(1).
  surface_mesh() : positions_(add_vertex_property<P>(point_property_name, origin())) {
    positions_.array()->pin();
  }
  surface_mesh(const surface_mesh& other) : halfedge_mesh(other), positions_(find_positions()) {}
  surface_mesh(surface_mesh&& other) noexcept
      : halfedge_mesh(std::move(other)), positions_(std::exchange(other.positions_, {})) {}
  surface_mesh& operator=(const surface_mesh& other) {
    if (this != &other) {
      halfedge_mesh::operator=(other);
      positions_ = find_positions();
    }
    return *this;
  }
  surface_mesh& operator=(surface_mesh&& other) noexcept {
    if (this != &other) {
      halfedge_mesh::operator=(std::move(other));
      positions_ = std::exchange(other.positions_, {});
    }
    return *this;
  }
  ~surface_mesh() = default;

  /// Adds an isolated vertex at p. O(1) amortised.
  vertex_handle add_vertex(const P& p) {
    const vertex_handle v = halfedge_mesh::add_vertex();
    positions_[v] = p;
    return v;
  }
  /// Adds isolated vertices at the given points; returns the first. O(points).
  vertex_handle add_vertices(std::span<const P> points) {
    const vertex_handle first = halfedge_mesh::add_vertices(points.size());
    std::copy(points.begin(), points.end(), positions_.vector().begin() + first.idx());
    return first;
  }

  /// The position of vertex v. O(1).
  const P& position(vertex_handle v) const noexcept { return positions_[v]; }
  /// Moves vertex v to p. O(1).
  void set_position(vertex_handle v, const P& p) noexcept(std::is_nothrow_copy_assignable_v<P>) {
    positions_[v] = p;
  }
  /// Every position slot, indexed by vertex index (removed vertices included until
  /// garbage_collection()). Valid until the next vertex insertion. O(1).
  std::span<const P> points() const noexcept { return positions_.vector(); }
  std::span<P> points() noexcept { return positions_.vector(); }
  /// The positions as the vertex property they are stored in, for algorithms that replace
  /// the whole array (its size must stay vertices_size()). O(1).
  property<vertex_handle, P> positions() const noexcept { return positions_; }

 private:
  static P origin() { return point_traits<P>::make(scalar_type{0}, scalar_type{0}, scalar_type{0}); }
  property<vertex_handle, P> find_positions() const { return get_vertex_property<P>(point_property_name); }

  property<vertex_handle, P> positions_;
};

/// True for the surface_mesh types. Use it to constrain a function on "any mesh with positions".
template <class M>
inline constexpr bool is_surface_mesh_v = false;
template <Point3 P>
inline constexpr bool is_surface_mesh_v<surface_mesh<P>> = true;

}  // namespace cellforge
