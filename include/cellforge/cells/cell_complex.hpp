// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The Three-dimensional Cell List (Kovalevsky's 3DCL, seed 000 §3.1 and §4.9): vertices,
/// edges, faces with holes and volumes, stored top-down (volumes → signed faces → loops of
/// signed edge uses → vertices) with every bottom-up relation derived once and cached:
/// vertex → edges with direction, edge → faces and volumes in right-hand rotation order,
/// face → volumes with signs, objects and their Euler characteristic. See docs/cells.md.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/newell.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/halfedge/handles.hpp"

namespace cellforge {

struct cell_vertex_tag {};
struct cell_edge_tag {};
struct cell_face_tag {};
struct cell_volume_tag {};
struct cell_object_tag {};
using cell_vertex = handle<cell_vertex_tag>;
using cell_edge = handle<cell_edge_tag>;
using cell_face = handle<cell_face_tag>;
using cell_volume = handle<cell_volume_tag>;
using cell_object = handle<cell_object_tag>;

/// A handle with a direction or orientation sign (+1 or -1); what the sign means is said by
/// the accessor that returns it.
template <class H>
struct oriented {
  H handle{};
  int sign = 1;
  friend bool operator==(const oriented&, const oriented&) = default;
};

/// One face of a cell_complex_input: loops[0] is the outer boundary, counter-clockwise
/// (right-hand) about the face's normal; loops[1..] are holes, clockwise about the same normal.
/// Consecutive vertices (cyclically) are joined by an edge of the input.
struct cell_input_face {
  std::vector<std::vector<std::uint32_t>> loops;
};
/// One volume of a cell_complex_input: (face index, +1 when the face's normal points OUT of this
/// volume, -1 when it points in).
struct cell_input_volume {
  std::vector<std::pair<std::uint32_t, int>> faces;
};

/// What make_cell_complex() takes: positions in the caller's point type P, edges, faces as
/// vertex loops, volumes as signed face sets.
template <Point3 P>
struct cell_complex_input {
  using point_type = P;
  using face = cell_input_face;
  using volume = cell_input_volume;
  std::vector<P> points;                            ///< vertex positions
  std::vector<std::array<std::uint32_t, 2>> edges;  ///< every edge, dangling ones included
  std::vector<face> faces;
  std::vector<volume> volumes;
};

template <class = void>
class basic_cell_topology;
/// The relations of a cell complex (see the class below); a class template on an unused
/// parameter only so that its members compile where they are used.
using cell_topology = basic_cell_topology<>;
template <Point3 P>
class cell_complex;

namespace detail::cells {
/// Handles 0 .. n-1 of one kind as a plain forward range (not a view_interface, which clang 14
/// with libstdc++ 12 refuses). O(1) to create.
template <class H>
class handle_range {
 public:
  class iterator {
   public:
    using value_type = H;
    using difference_type = std::ptrdiff_t;
    iterator() = default;
    explicit iterator(std::uint32_t i) : i_(i) {}
    H operator*() const { return H(i_); }
    iterator& operator++() {
      ++i_;
      return *this;
    }
    iterator operator++(int) {
      iterator t = *this;
      ++i_;
      return t;
    }
    friend bool operator==(iterator a, iterator b) { return a.i_ == b.i_; }

   private:
    std::uint32_t i_ = 0;
  };
  explicit handle_range(std::size_t n) : n_(static_cast<std::uint32_t>(n)) {}
  iterator begin() const { return iterator(0); }
  iterator end() const { return iterator(n_); }
  std::size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }

 private:
  std::uint32_t n_;
};
}  // namespace detail::cells

namespace detail::cells {
struct access;
template <class = void>
void build_topology(cell_topology& cc, std::span<const glm::dvec3> points,
                    std::vector<std::array<std::uint32_t, 2>>&& edges,
                    const std::vector<cell_input_face>& faces, const std::vector<cell_input_volume>& volumes);
template <class = void>
void renumber_topology(const cell_topology& from, cell_topology& to,
                       std::span<const std::uint32_t> vertex_label,
                       std::span<const std::uint32_t> edge_label);
}  // namespace detail::cells

/// Everything of a 3DCL but its positions: the relations, which do not depend on the point
/// type (cell_complex<P> adds the positions). Every relation is an O(1) span into cached arrays.
template <class>
class basic_cell_topology {
 public:
  basic_cell_topology() = default;

  /// Numbers of elements of each kind (handles run from 0 to the count - 1). O(1).
  std::size_t num_vertices() const noexcept { return vertex_edge_start_.size() - 1; }
  std::size_t num_edges() const noexcept { return ends_.size(); }
  std::size_t num_faces() const noexcept { return face_loop_start_.size() - 1; }
  std::size_t num_volumes() const noexcept { return volume_face_start_.size() - 1; }
  std::size_t num_objects() const noexcept { return object_volume_start_.size() - 1; }

  /// Handles of all elements of a kind, as ranges. O(1).
  auto vertices() const noexcept { return detail::cells::handle_range<cell_vertex>(num_vertices()); }
  auto edges() const noexcept { return detail::cells::handle_range<cell_edge>(num_edges()); }
  auto faces() const noexcept { return detail::cells::handle_range<cell_face>(num_faces()); }
  auto volumes() const noexcept { return detail::cells::handle_range<cell_volume>(num_volumes()); }
  auto objects() const noexcept { return detail::cells::handle_range<cell_object>(num_objects()); }

  // ---- vertices
  /// Edges at v; sign +1 when the edge starts at v, -1 when it ends there. O(1).
  std::span<const oriented<cell_edge>> vertex_edges(cell_vertex v) const {
    return csr(vertex_edges_, vertex_edge_start_, v.idx());
  }

  // ---- edges
  /// Start and end vertex of e (its direction, against which signs are given). O(1).
  cell_vertex source(cell_edge e) const { return cell_vertex(ends_[e.idx()][0]); }
  cell_vertex target(cell_edge e) const { return cell_vertex(ends_[e.idx()][1]); }
  std::array<cell_vertex, 2> edge_vertices(cell_edge e) const { return {source(e), target(e)}; }
  /// Faces at e in right-hand rotation order about source → target. Sign +1 when the face's
  /// loop runs along e (source → target); then its normal points in the direction of
  /// positive rotation. Starts after a wedge outside every volume, if there is one. O(1).
  std::span<const oriented<cell_face>> edge_faces(cell_edge e) const {
    return csr(edge_faces_, edge_face_start_, e.idx());
  }
  /// wedge k is the volume between edge_faces(e)[k] and edge_faces(e)[k+1] (cyclically), seen
  /// from face k; invalid where that wedge is outside every volume. O(1).
  std::span<const cell_volume> edge_wedges(cell_edge e) const {
    return csr(edge_wedges_, edge_face_start_, e.idx());
  }
  /// The distinct volumes at e in right-hand rotation order. O(faces at e).
  std::vector<cell_volume> edge_volumes(cell_edge e) const {
    std::vector<cell_volume> out;
    for (cell_volume c : edge_wedges(e))
      if (c.is_valid() && std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
    return out;
  }

  // ---- faces
  /// Number of loops of f: 1 + its number of holes. O(1).
  std::size_t num_loops(cell_face f) const {
    return face_loop_start_[f.idx() + 1] - face_loop_start_[f.idx()];
  }
  /// Vertices of loop i of f (0: outer, counter-clockwise about face_normal; others: holes,
  /// clockwise). O(1).
  std::span<const cell_vertex> loop_vertices(cell_face f, std::size_t i) const {
    return csr(loop_vertices_, loop_start_, face_loop_start_[f.idx()] + i);
  }
  /// Edges of loop i of f: edge k joins vertex k to vertex k+1; sign +1 when it runs
  /// source → target. O(1).
  std::span<const oriented<cell_edge>> loop_edges(cell_face f, std::size_t i) const {
    return csr(loop_edges_, loop_start_, face_loop_start_[f.idx()] + i);
  }
  /// The volumes of f (at most two); sign +1 when f's normal points out of the volume. O(1).
  std::span<const oriented<cell_volume>> face_volumes(cell_face f) const {
    return csr(face_volumes_, face_volume_start_, f.idx());
  }

  // ---- volumes
  /// Faces of c; sign +1 when the face's normal points out of c. O(1).
  std::span<const oriented<cell_face>> volume_faces(cell_volume c) const {
    return csr(volume_faces_, volume_face_start_, c.idx());
  }
  /// The object (connected component) volume c belongs to. O(1).
  cell_object volume_object(cell_volume c) const { return cell_object(volume_object_[c.idx()]); }

  // ---- objects: connected components through edges, face loops and volumes
  /// The object vertex v belongs to; an edge, face or volume is in its vertices' object. O(1).
  cell_object vertex_object(cell_vertex v) const { return cell_object(vertex_object_[v.idx()]); }
  /// The volumes of object o, in increasing order. O(1).
  std::span<const cell_volume> object_volumes(cell_object o) const {
    return csr(object_volumes_, object_volume_start_, o.idx());
  }
  /// Numbers of vertices, edges, faces and volumes of o. O(1).
  const std::array<std::size_t, 4>& object_counts(cell_object o) const { return object_counts_[o.idx()]; }
  /// V - E + F - C of o, counting every cell once whatever its shape. O(1).
  long long object_euler(cell_object o) const {
    const auto& n = object_counts_[o.idx()];
    return static_cast<long long>(n[0]) - static_cast<long long>(n[1]) + static_cast<long long>(n[2]) -
           static_cast<long long>(n[3]);
  }

 protected:
  /// The faces, edges and volumes of the input this complex was built from. O(size).
  template <Point3 P>
  void topology_to_input(cell_complex_input<P>& in) const;

 private:
  friend struct detail::cells::access;
  template <class>
  friend void detail::cells::build_topology(basic_cell_topology&, std::span<const glm::dvec3>,
                                            std::vector<std::array<std::uint32_t, 2>>&&,
                                            const std::vector<cell_input_face>&,
                                            const std::vector<cell_input_volume>&);
  template <class>
  friend void detail::cells::renumber_topology(const basic_cell_topology&, basic_cell_topology&,
                                               std::span<const std::uint32_t>,
                                               std::span<const std::uint32_t>);
  template <class T>
  static std::span<const T> csr(const std::vector<T>& data, const std::vector<std::uint32_t>& start,
                                std::size_t i) {
    return {data.data() + start[i], start[i + 1] - start[i]};
  }

  std::vector<std::uint32_t> vertex_edge_start_{0};
  std::vector<oriented<cell_edge>> vertex_edges_;
  std::vector<std::array<std::uint32_t, 2>> ends_;
  std::vector<std::uint32_t> edge_face_start_{0};
  std::vector<oriented<cell_face>> edge_faces_;
  std::vector<cell_volume> edge_wedges_;
  std::vector<std::uint32_t> face_loop_start_{0};  // into loop_start_
  std::vector<std::uint32_t> loop_start_{0};       // into loop_vertices_ / loop_edges_
  std::vector<cell_vertex> loop_vertices_;
  std::vector<oriented<cell_edge>> loop_edges_;
  std::vector<glm::dvec3>
      normals_;  // unit, in double whatever P is: the rotation orders were sorted with them
  std::vector<std::uint32_t> face_volume_start_{0};
  std::vector<oriented<cell_volume>> face_volumes_;
  std::vector<std::uint32_t> volume_face_start_{0};
  std::vector<oriented<cell_face>> volume_faces_;
  std::vector<std::uint32_t> volume_object_;
  std::vector<std::uint32_t> vertex_object_;
  std::vector<std::uint32_t> object_volume_start_{0};
  std::vector<cell_volume> object_volumes_;
  std::vector<std::array<std::size_t, 4>> object_counts_;
};

/// The 3DCL with positions in the caller's point type P: cell_topology's relations plus
/// point(v) and face_normal(f) in P. Immutable once built (make_cell_complex).
template <Point3 P>
class cell_complex : public cell_topology {
 public:
  using point_type = P;
  cell_complex() = default;

  /// Position of v; all positions as one span. O(1).
  const P& point(cell_vertex v) const { return points_[v.idx()]; }
  std::span<const P> points() const noexcept { return points_; }
  /// Unit Newell normal of f's outer loop (zero for a degenerate loop), in P. O(1).
  P face_normal(cell_face f) const;

  /// The input this complex was built from (indices and loop starts as given). O(size).
  cell_complex_input<P> to_input() const {
    cell_complex_input<P> in;
    in.points = points_;
    topology_to_input(in);
    return in;
  }

  template <Point3 Q>
  friend cell_complex<Q> make_cell_complex(cell_complex_input<Q> input);
  template <Point3 Q, Point3 R>
  friend cell_complex<Q> convert_points(const cell_complex<R>& cc);
  template <Point3 Q>
  friend cell_complex<Q> renumber_cells(const cell_complex<Q>& cc,
                                        std::span<const std::uint32_t> vertex_label,
                                        std::span<const std::uint32_t> edge_label);

 private:
  std::vector<P> points_;
};

namespace detail::cells {
/// What the library's own geometry code reads of a complex in double precision, whatever P is.
struct access {
  static const glm::dvec3& unit_normal(const cell_topology& cc, cell_face f) { return cc.normals_[f.idx()]; }
};

/// The positions of a complex as glm::dvec3 for the library's geometry code: a view of the
/// complex's own array when P is glm::dvec3, else a converted copy. O(1) or O(V).
template <Point3 P>
class dvec3_points {
 public:
  explicit dvec3_points(std::span<const P> points) {
    if constexpr (std::is_same_v<P, glm::dvec3>) {
      view_ = points;
    } else {
      copy_.reserve(points.size());
      for (const P& p : points) copy_.push_back(to_dvec3(p));
      view_ = detail::span_of(copy_);
    }
  }
  dvec3_points(const dvec3_points&) = delete;  // view_ may point into copy_
  dvec3_points& operator=(const dvec3_points&) = delete;
  std::span<const glm::dvec3> span() const noexcept { return view_; }
  const glm::dvec3& operator[](std::size_t i) const { return view_[i]; }

 private:
  std::vector<glm::dvec3> copy_;
  std::span<const glm::dvec3> view_;
};
}  // namespace detail::cells

/// Builds the 3DCL and derives every relation (vertex→edges with direction, edge→faces and
/// edge→volumes in right-hand rotation order about the edge, face→volumes with signs, objects).
/// Throws cellforge::error naming the element when the input is inconsistent: non-finite
/// points, bad or duplicate edges, loops not joined by edges, signs other than ±1, a face in
/// more than two volumes or twice on one side, a volume whose boundary is not closed.
/// O(n log n) for n = total size of the input (the sort of faces about each edge).
template <Point3 P>
cell_complex<P> make_cell_complex(cell_complex_input<P> input);

/// The same complex with its positions converted to point type Q (relations kept, face normals
/// as computed from the original positions). O(size of cc).
template <Point3 Q, Point3 P>
cell_complex<Q> convert_points(const cell_complex<P>& cc);

/// The same complex with vertex v renumbered vertex_label[v] and edge e edge_label[e] (both
/// permutations; faces and volumes keep theirs): equal to make_cell_complex of the input so
/// renumbered, without its sorts and look-ups. Throws cellforge::error on labels that are not
/// permutations. O(size of cc).
template <Point3 P>
cell_complex<P> renumber_cells(const cell_complex<P>& cc, std::span<const std::uint32_t> vertex_label,
                               std::span<const std::uint32_t> edge_label);

}  // namespace cellforge

#include "cellforge/cells/detail/cell_complex_impl.hpp"
