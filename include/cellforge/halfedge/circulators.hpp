// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Circulators as C++20 forward ranges: around a vertex (faces, edges, neighbouring
/// vertices, half-edges), around a face (half-edges, vertices) and along a boundary
/// loop. They work on non-orientable meshes: the vertex walk is guided by the vertex
/// it turns around, not by the faces' orientation.

#include <cstdint>
#include <iterator>
#include <ranges>

#include "cellforge/halfedge/handles.hpp"

namespace cellforge {

/// One step of a walk around a vertex: either crossing an edge or visiting a face.
enum class vertex_event : std::uint8_t { edge, face };

namespace detail {

/// The state machine that walks every fan of faces around a vertex. Works on any
/// mesh type exposing the walk primitives below; each step is O(1), except moving
/// from one fan to the next at a non-manifold vertex (O(1) as well: ring links).
template <class Mesh>
class vertex_walker {
 public:
  vertex_walker() = default;
  vertex_walker(const Mesh* m, vertex_handle v) : m_(m), v_(v) {
    const halfedge_handle a = m->anchor(v);
    anchor_ = a;
    cur_ = a;
    if (!a.is_valid())
      state_ = done;
    else
      state_ = m->is_boundary(a) ? fan_start : fan_edge;
  }

  bool at_end() const noexcept { return state_ == done; }
  vertex_event event() const noexcept { return state_ == fan_face ? vertex_event::face : vertex_event::edge; }
  /// Edge events: a half-edge on the edge crossed. Face events: the face's half-edge
  /// on the edge through which the walk entered it.
  halfedge_handle current() const noexcept { return cur_; }
  vertex_handle center() const noexcept { return v_; }

  void advance() noexcept {
    switch (state_) {
      case fan_start:  // cur_ is the face-less end of an open fan; step into its face
        cur_ = Mesh::twin(cur_);
        state_ = fan_face;
        break;
      case fan_edge:  // cur_ is a face half-edge on the edge just crossed
        state_ = fan_face;
        break;
      case fan_face: {
        const halfedge_handle out = m_->other_halfedge_at(cur_, v_);
        const halfedge_handle u = Mesh::twin(out);
        if (m_->is_boundary(u)) {
          cur_ = u;
          state_ = fan_end;
        } else if (u == anchor_) {
          state_ = done;  // a closed fan is back where it started
        } else {
          cur_ = u;
          state_ = fan_edge;
        }
        break;
      }
      case fan_end: {
        const halfedge_handle s = m_->ring_next(cur_, v_);
        if (s == anchor_) {
          state_ = done;
        } else {
          cur_ = s;
          state_ = fan_start;
        }
        break;
      }
      case done:
        break;
    }
  }

  friend bool operator==(const vertex_walker& a, const vertex_walker& b) noexcept {
    return a.state_ == b.state_ && (a.state_ == done || a.cur_ == b.cur_);
  }

 private:
  enum state_t : std::uint8_t { fan_start, fan_edge, fan_face, fan_end, done };
  const Mesh* m_ = nullptr;
  vertex_handle v_;
  halfedge_handle anchor_;
  halfedge_handle cur_;
  state_t state_ = done;
};

/// Forward iterator over the events of one kind, projected to a value.
template <class Mesh, vertex_event Kind, class Projection>
class vertex_iterator {
 public:
  using value_type = decltype(Projection{}(std::declval<const Mesh&>(), halfedge_handle{}, vertex_handle{}));
  using difference_type = std::ptrdiff_t;
  using iterator_concept = std::forward_iterator_tag;
  using iterator_category = std::input_iterator_tag;  // operator* returns a value, not a reference

  vertex_iterator() = default;
  vertex_iterator(const Mesh* m, vertex_handle v) : m_(m), w_(m, v) { skip(); }

  value_type operator*() const { return Projection{}(*m_, w_.current(), w_.center()); }
  vertex_iterator& operator++() {
    w_.advance();
    skip();
    return *this;
  }
  vertex_iterator operator++(int) {
    auto c = *this;
    ++*this;
    return c;
  }
  friend bool operator==(const vertex_iterator& a, const vertex_iterator& b) noexcept { return a.w_ == b.w_; }
  friend bool operator==(const vertex_iterator& a, std::default_sentinel_t) noexcept { return a.w_.at_end(); }

 private:
  void skip() {
    while (!w_.at_end() && w_.event() != Kind) w_.advance();
  }
  const Mesh* m_ = nullptr;
  vertex_walker<Mesh> w_;
};

// The ranges derive from nothing (not std::ranges::view_interface): clang 14 with
// libstdc++ 12 rejects view_interface over these iterator types. They are still views,
// and common ranges.
template <class Iterator>
class circulator_range {
 public:
  circulator_range() = default;
  explicit circulator_range(Iterator first) : first_(first) {}
  Iterator begin() const { return first_; }
  // A default-constructed iterator is an ended one, so begin and end have one type: the
  // ranges are common ranges (std::vector(r.begin(), r.end()) works).
  Iterator end() const noexcept { return Iterator{}; }
  bool empty() const { return first_ == std::default_sentinel; }

 private:
  Iterator first_;
};

struct project_face {
  template <class Mesh>
  face_handle operator()(const Mesh& m, halfedge_handle h, vertex_handle) const noexcept {
    return m.face(h);
  }
};
struct project_edge {
  template <class Mesh>
  edge_handle operator()(const Mesh&, halfedge_handle h, vertex_handle) const noexcept {
    return Mesh::edge(h);
  }
};
struct project_neighbour {
  template <class Mesh>
  vertex_handle operator()(const Mesh& m, halfedge_handle h, vertex_handle v) const noexcept {
    const vertex_handle a = m.head(h);
    return a == v ? m.tail(h) : a;
  }
};
/// The half-edge of the crossed edge that leaves the centre vertex; when the edge's two
/// faces disagree in orientation and both half-edges enter the centre, the one walked.
struct project_outgoing {
  template <class Mesh>
  halfedge_handle operator()(const Mesh& m, halfedge_handle h, vertex_handle v) const noexcept {
    if (m.tail(h) == v) return h;
    const halfedge_handle t = Mesh::twin(h);
    return m.tail(t) == v ? t : h;
  }
};

/// Iterator over the half-edges of a face loop (or along next links).
template <class Mesh, class Projection>
class face_iterator {
 public:
  using value_type = decltype(Projection{}(std::declval<const Mesh&>(), halfedge_handle{}));
  using difference_type = std::ptrdiff_t;
  using iterator_concept = std::forward_iterator_tag;
  using iterator_category = std::input_iterator_tag;  // operator* returns a value, not a reference

  face_iterator() = default;
  face_iterator(const Mesh* m, halfedge_handle start)
      : m_(m), start_(start), cur_(start), done_(!start.is_valid()) {}

  value_type operator*() const { return Projection{}(*m_, cur_); }
  face_iterator& operator++() {
    cur_ = m_->next(cur_);
    done_ = cur_ == start_;
    return *this;
  }
  face_iterator operator++(int) {
    auto c = *this;
    ++*this;
    return c;
  }
  friend bool operator==(const face_iterator& a, const face_iterator& b) noexcept {
    return a.done_ == b.done_ && (a.done_ || a.cur_ == b.cur_);
  }
  friend bool operator==(const face_iterator& a, std::default_sentinel_t) noexcept { return a.done_; }

 private:
  const Mesh* m_ = nullptr;
  halfedge_handle start_, cur_;
  bool done_ = true;
};

struct project_halfedge {
  template <class Mesh>
  halfedge_handle operator()(const Mesh&, halfedge_handle h) const noexcept {
    return h;
  }
};
struct project_tail {
  template <class Mesh>
  vertex_handle operator()(const Mesh& m, halfedge_handle h) const noexcept {
    return m.tail(h);
  }
};

/// Iterator along a boundary loop: from each boundary half-edge to the one that continues
/// the boundary at its far end (the other end of the same fan there).
template <class Mesh>
class boundary_iterator {
 public:
  using value_type = halfedge_handle;
  using difference_type = std::ptrdiff_t;
  using iterator_concept = std::forward_iterator_tag;
  using iterator_category = std::input_iterator_tag;  // operator* returns a value, not a reference

  boundary_iterator() = default;
  boundary_iterator(const Mesh* m, halfedge_handle start)
      : m_(m), start_(start), cur_(start), done_(!start.is_valid() || !m->is_boundary(start)) {
    if (!done_) far_ = m->head(start);
  }
  halfedge_handle operator*() const noexcept { return cur_; }
  boundary_iterator& operator++() {
    const halfedge_handle nxt = m_->boundary_successor(cur_, far_);
    if (!nxt.is_valid()) {  // only on a corrupted mesh
      done_ = true;
      return *this;
    }
    far_ = m_->head(nxt) == far_ ? m_->tail(nxt) : m_->head(nxt);
    cur_ = nxt;
    done_ = cur_ == start_;
    return *this;
  }
  boundary_iterator operator++(int) {
    auto c = *this;
    ++*this;
    return c;
  }
  friend bool operator==(const boundary_iterator& a, const boundary_iterator& b) noexcept {
    return a.done_ == b.done_ && (a.done_ || (a.cur_ == b.cur_ && a.far_ == b.far_));
  }
  friend bool operator==(const boundary_iterator& a, std::default_sentinel_t) noexcept { return a.done_; }

 private:
  const Mesh* m_ = nullptr;
  halfedge_handle start_, cur_;
  vertex_handle far_;
  bool done_ = true;
};

/// Iterator over the live elements of one kind (skips removed ones).
template <class Mesh, class Handle>
class element_iterator {
 public:
  using value_type = Handle;
  using difference_type = std::ptrdiff_t;
  using iterator_concept = std::forward_iterator_tag;
  using iterator_category = std::input_iterator_tag;  // operator* returns a value, not a reference

  element_iterator() = default;
  element_iterator(const Mesh* m, std::uint32_t i, std::uint32_t end) : m_(m), i_(i), end_(end) { skip(); }
  Handle operator*() const noexcept { return Handle(i_); }
  element_iterator& operator++() noexcept {
    ++i_;
    skip();
    return *this;
  }
  element_iterator operator++(int) noexcept {
    auto c = *this;
    ++*this;
    return c;
  }
  friend bool operator==(const element_iterator& a, const element_iterator& b) noexcept {
    return a.i_ == b.i_;
  }

 private:
  void skip() noexcept {
    while (i_ < end_ && m_->is_removed(Handle(i_))) ++i_;
  }
  const Mesh* m_ = nullptr;
  std::uint32_t i_ = 0, end_ = 0;
};

template <class Mesh, class Handle>
class element_range {
 public:
  element_range() = default;
  element_range(const Mesh* m, std::uint32_t end) : m_(m), end_(end) {}
  element_iterator<Mesh, Handle> begin() const { return {m_, 0, end_}; }
  element_iterator<Mesh, Handle> end() const { return {m_, end_, end_}; }
  bool empty() const { return begin() == end(); }

 private:
  const Mesh* m_ = nullptr;
  std::uint32_t end_ = 0;
};

}  // namespace detail
}  // namespace cellforge

// Circulator and element ranges only point into the mesh: iterators outlive the range object
// (specialisations of std templates, kept out of the Doxygen reference by the cond block).
/// @cond INTERNAL
template <class It>
inline constexpr bool std::ranges::enable_borrowed_range<cellforge::detail::circulator_range<It>> = true;
template <class Mesh, class Handle>
inline constexpr bool std::ranges::enable_borrowed_range<cellforge::detail::element_range<Mesh, Handle>> =
    true;
/// @endcond
