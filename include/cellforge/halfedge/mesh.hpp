// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The half-edge mesh: polygon faces, strong index handles, arrays of records, a hash
/// table of unlinked half-edges (O(1) face insertion, O(boundary edges) boundary queries),
/// non-orientable surfaces and vertices with several open fans. See docs/halfedge.md.

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cellforge/core/detail/edge_table.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/halfedge/circulators.hpp"
#include "cellforge/halfedge/handles.hpp"
#include "cellforge/halfedge/properties.hpp"

namespace cellforge {

namespace detail {
template <class>
struct basic_mesh_access;
}

template <class = void>
class basic_halfedge_mesh;
/// The half-edge mesh. It is a class template on an unused parameter only so that its members
/// are compiled where they are used, not in every file that includes this header.
using halfedge_mesh = basic_halfedge_mesh<>;

/// Counts and diagnostics from building a mesh from a face list.
struct build_report {
  std::size_t vertices = 0, edges = 0, faces = 0;
  std::size_t boundary_edges = 0;     ///< edges with one face
  std::size_t flipped_edges = 0;      ///< edges whose two faces disagree in orientation
  std::size_t isolated_vertices = 0;  ///< vertices no face uses
  /// (new vertex, original vertex) for each vertex added by splitting a non-manifold one.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> split_vertices;
};

/// How a mesh is built from a face list.
struct build_options {
  /// A vertex whose faces form a closed fan plus other fans (e.g. two cones touching at
  /// their tips) cannot be walked around; by default it is an error, with this set the
  /// vertex is duplicated, one copy per closed fan (reported in build_report).
  bool split_nonmanifold_vertices = false;
};

/// A polygon mesh in the half-edge representation.
///
/// Layout: edge e owns half-edges 2e and 2e+1 (so twin(h) = h ^ 1 is implicit). Every
/// face half-edge stores {head, next, prev, face}: 16 bytes, as in OpenMesh. A half-edge
/// with no face is a *boundary* half-edge; its next/prev fields are reused as links of a
/// small ring through the boundary half-edges around each of its two end vertices.
/// Two faces may traverse their shared edge in the same direction (a non-orientable
/// seam): the edge is then *flipped*, which is read off the two heads, not stored.
template <class>
class basic_halfedge_mesh {
 public:
  static constexpr std::uint32_t npos = 0xFFFFFFFFu;

  basic_halfedge_mesh() = default;

  // ---------------------------------------------------------------- sizes

  /// Number of vertex/edge/face/half-edge slots, removed elements included. O(1).
  std::size_t vertices_size() const noexcept { return vertex_anchor_.size(); }
  std::size_t halfedges_size() const noexcept { return he_.size(); }
  std::size_t edges_size() const noexcept { return he_.size() / 2; }
  std::size_t faces_size() const noexcept { return face_anchor_.size(); }
  /// Number of live elements. O(1).
  std::size_t num_vertices() const noexcept { return vertices_size() - removed_vertices_; }
  std::size_t num_edges() const noexcept { return edges_size() - removed_edges_; }
  std::size_t num_halfedges() const noexcept { return 2 * num_edges(); }
  std::size_t num_faces() const noexcept { return faces_size() - removed_faces_; }
  bool empty() const noexcept { return num_vertices() == 0; }
  /// Bytes held by the connectivity arrays and the unlinked table (capacity, not
  /// size; properties excluded). O(1).
  std::size_t memory_bytes() const noexcept {
    return he_.capacity() * sizeof(record) + (vertex_anchor_.capacity() + face_anchor_.capacity()) * 4 +
           unlinked_.capacity() * sizeof(detail::derived_key_table::slot);
  }
  /// True when any element was removed and garbage_collection() would compact. O(1).
  bool has_garbage() const noexcept { return removed_vertices_ + removed_edges_ + removed_faces_ > 0; }

  // ---------------------------------------------------------------- element ranges

  /// Live vertices/edges/half-edges/faces, as forward ranges. O(1) to create.
  auto vertices() const noexcept {
    return detail::element_range<basic_halfedge_mesh, vertex_handle>(this, n32(vertices_size()));
  }
  auto edges() const noexcept {
    return detail::element_range<basic_halfedge_mesh, edge_handle>(this, n32(edges_size()));
  }
  auto halfedges() const noexcept {
    return detail::element_range<basic_halfedge_mesh, halfedge_handle>(this, n32(halfedges_size()));
  }
  auto faces() const noexcept {
    return detail::element_range<basic_halfedge_mesh, face_handle>(this, n32(faces_size()));
  }

  bool is_removed(vertex_handle v) const noexcept { return vertex_anchor_[v.idx()] == removed_mark; }
  bool is_removed(edge_handle e) const noexcept { return he_[2 * e.idx()].head == npos; }
  bool is_removed(halfedge_handle h) const noexcept { return he_[h.idx()].head == npos; }
  bool is_removed(face_handle f) const noexcept { return face_anchor_[f.idx()] == npos; }
  /// True for a handle that indexes a live element of this mesh. O(1).
  bool is_valid(vertex_handle v) const noexcept { return v.idx() < vertices_size() && !is_removed(v); }
  bool is_valid(edge_handle e) const noexcept { return e.idx() < edges_size() && !is_removed(e); }
  bool is_valid(halfedge_handle h) const noexcept { return h.idx() < halfedges_size() && !is_removed(h); }
  bool is_valid(face_handle f) const noexcept { return f.idx() < faces_size() && !is_removed(f); }

  // ---------------------------------------------------------------- navigation (all O(1))

  static constexpr halfedge_handle twin(halfedge_handle h) noexcept { return halfedge_handle(h.idx() ^ 1u); }
  static constexpr edge_handle edge(halfedge_handle h) noexcept { return edge_handle(h.idx() >> 1); }
  /// Half-edge i (0 or 1) of edge e.
  static constexpr halfedge_handle halfedge(edge_handle e, unsigned i = 0) noexcept {
    return halfedge_handle(2 * e.idx() + (i & 1u));
  }
  vertex_handle head(halfedge_handle h) const noexcept { return vertex_handle(he_[h.idx()].head); }
  vertex_handle tail(halfedge_handle h) const noexcept {
    const record& r = he_[h.idx()];
    // A face half-edge starts where its predecessor ends; a boundary one where its twin ends.
    return vertex_handle(r.face != npos ? he_[r.prev].head : he_[h.idx() ^ 1u].head);
  }
  /// Next/previous half-edge around the face (only for face half-edges).
  halfedge_handle next(halfedge_handle h) const noexcept { return halfedge_handle(he_[h.idx()].next); }
  halfedge_handle prev(halfedge_handle h) const noexcept { return halfedge_handle(he_[h.idx()].prev); }
  face_handle face(halfedge_handle h) const noexcept { return face_handle(he_[h.idx()].face); }
  /// A half-edge of face f (the one from its first vertex to its second). O(1).
  halfedge_handle halfedge(face_handle f) const noexcept { return halfedge_handle(face_anchor_[f.idx()]); }
  /// The vertex's anchor: a boundary half-edge at the start of its first open fan, or
  /// a face half-edge incident to it when it is interior; invalid when isolated.
  halfedge_handle anchor(vertex_handle v) const noexcept {
    const std::uint32_t a = vertex_anchor_[v.idx()];
    return a == removed_mark ? halfedge_handle() : halfedge_handle(a);
  }
  vertex_handle vertex(edge_handle e, unsigned i) const noexcept {
    const halfedge_handle h = halfedge(e, 0);
    return i == 0 ? tail(h) : head(h);
  }
  face_handle face(edge_handle e, unsigned i) const noexcept { return face(halfedge(e, i)); }

  /// True for a half-edge with no face (the outside of a boundary edge).
  bool is_boundary(halfedge_handle h) const noexcept { return he_[h.idx()].face == npos; }
  bool is_boundary(edge_handle e) const noexcept {
    return is_boundary(halfedge(e, 0)) || is_boundary(halfedge(e, 1));
  }
  /// True for a vertex on a boundary (its anchor is a boundary half-edge). O(1).
  bool is_boundary(vertex_handle v) const noexcept {
    const std::uint32_t a = vertex_anchor_[v.idx()];
    return a != npos && a != removed_mark && he_[a].face == npos;
  }
  bool is_isolated(vertex_handle v) const noexcept { return vertex_anchor_[v.idx()] == npos; }
  /// True when the two faces of e traverse it in the same direction. O(1).
  bool is_flipped(edge_handle e) const noexcept {
    const record& a = he_[2 * e.idx()];
    const record& b = he_[2 * e.idx() + 1];
    return a.face != npos && b.face != npos && a.head == b.head;
  }
  /// Number of flipped edges; 0 means the faces' orientations agree everywhere. O(1).
  std::size_t num_flipped_edges() const noexcept { return flipped_edges_; }
  bool is_consistently_oriented() const noexcept { return flipped_edges_ == 0; }

  /// True when every edge has two faces: the unlinked table is empty. O(1).
  bool is_closed() const noexcept { return unlinked_.empty(); }
  /// Number of boundary edges. O(1).
  std::size_t num_boundary_edges() const noexcept { return unlinked_.size(); }

  /// In the face of h (a face half-edge whose edge touches v), the other half-edge at v.
  halfedge_handle other_halfedge_at(halfedge_handle h, vertex_handle v) const noexcept {
    const record& r = he_[h.idx()];
    return halfedge_handle(r.head == v.idx() ? r.next : r.prev);
  }
  /// Next boundary half-edge in the ring around v (b must be a boundary half-edge at v).
  halfedge_handle ring_next(halfedge_handle b, vertex_handle v) const noexcept {
    return halfedge_handle(ring_slot(b.idx(), v.idx()));
  }

  /// The half-edge from a to b, if there is one (either orientation of a face half-edge or
  /// the boundary one). O(degree of a).
  halfedge_handle find_halfedge(vertex_handle a, vertex_handle b) const noexcept;
  /// The edge between a and b, if any. O(degree of a).
  edge_handle find_edge(vertex_handle a, vertex_handle b) const noexcept;

  // ---------------------------------------------------------------- circulators

  /// Faces around v, fan after fan (a face appears once per fan it is in). O(1) per step.
  auto faces_around(vertex_handle v) const {
    using it = detail::vertex_iterator<basic_halfedge_mesh, vertex_event::face, detail::project_face>;
    return detail::circulator_range<it>(it(this, v));
  }
  /// Edges incident to v in rotation order. O(1) per step.
  auto edges_around(vertex_handle v) const {
    using it = detail::vertex_iterator<basic_halfedge_mesh, vertex_event::edge, detail::project_edge>;
    return detail::circulator_range<it>(it(this, v));
  }
  /// Neighbouring vertices of v in rotation order. O(1) per step.
  auto vertices_around(vertex_handle v) const {
    using it = detail::vertex_iterator<basic_halfedge_mesh, vertex_event::edge, detail::project_neighbour>;
    return detail::circulator_range<it>(it(this, v));
  }
  /// For each incident edge, its half-edge that leaves v (on a flipped edge whose two
  /// half-edges both enter v, the one walked). O(1) per step.
  auto halfedges_around(vertex_handle v) const {
    using it = detail::vertex_iterator<basic_halfedge_mesh, vertex_event::edge, detail::project_outgoing>;
    return detail::circulator_range<it>(it(this, v));
  }
  /// Half-edges of face f in order, starting at halfedge(f). O(1) per step.
  auto halfedges_around(face_handle f) const {
    using it = detail::face_iterator<basic_halfedge_mesh, detail::project_halfedge>;
    return detail::circulator_range<it>(it(this, halfedge(f)));
  }
  /// Vertices of face f in the order the face was given. O(1) per step.
  auto vertices_around(face_handle f) const {
    using it = detail::face_iterator<basic_halfedge_mesh, detail::project_tail>;
    return detail::circulator_range<it>(it(this, halfedge(f)));
  }
  /// Number of faces/edges around v, or vertices of f. O(result).
  std::size_t valence(vertex_handle v) const {
    return static_cast<std::size_t>(std::ranges::distance(edges_around(v)));
  }
  std::size_t valence(face_handle f) const {
    return static_cast<std::size_t>(std::ranges::distance(halfedges_around(f)));
  }

  /// Boundary half-edges (one per boundary edge, the faceless side), unordered. O(boundary edges).
  std::vector<halfedge_handle> boundary_halfedges() const {
    std::vector<halfedge_handle> out;
    out.reserve(unlinked_.size());
    unlinked_.for_each([&](std::uint32_t h) { out.push_back(twin(halfedge_handle(h))); });
    return out;
  }
  /// The unlinked face half-edges (whose twin has no face), unordered. O(boundary edges).
  std::vector<halfedge_handle> unlinked_halfedges() const {
    std::vector<halfedge_handle> out;
    out.reserve(unlinked_.size());
    unlinked_.for_each([&](std::uint32_t h) { out.push_back(halfedge_handle(h)); });
    return out;
  }
  /// The face half-edge from tail to head whose twin is unlinked, if any. O(1) expected.
  halfedge_handle find_unlinked(vertex_handle tail_v, vertex_handle head_v) const noexcept {
    const std::uint32_t h = unlinked_.find(table_key(tail_v.idx(), head_v.idx()), unlinked_key());
    return h == detail::derived_key_table::not_found ? halfedge_handle() : halfedge_handle(h);
  }

  /// The boundary loop through boundary half-edge b, as a range of boundary half-edges in
  /// order. O(1) per step (times the number of fans at a non-manifold vertex on it).
  auto halfedges_around_boundary(halfedge_handle b) const {
    using it = detail::boundary_iterator<basic_halfedge_mesh>;
    return detail::circulator_range<it>(it(this, b));
  }
  /// The same loop collected into a vector. O(loop length).
  std::vector<halfedge_handle> boundary_loop(halfedge_handle b) const {
    std::vector<halfedge_handle> loop;
    for (halfedge_handle h : halfedges_around_boundary(b)) {
      loop.push_back(h);
      if (loop.size() > unlinked_.size()) break;  // only on a corrupted mesh
    }
    return loop;
  }
  /// The boundary half-edge that continues the boundary from b at its end vertex v. O(fans at v).
  halfedge_handle boundary_successor(halfedge_handle b, vertex_handle v) const { return fan_partner(b, v); }
  /// All boundary loops. O(b log b) for b boundary edges.
  std::vector<std::vector<halfedge_handle>> boundary_loops() const {
    std::vector<std::vector<halfedge_handle>> loops;
    std::vector<halfedge_handle> all = boundary_halfedges();
    std::sort(all.begin(), all.end());
    std::vector<std::uint8_t> seen(all.size(), 0);
    auto index_of = [&](halfedge_handle h) {
      return static_cast<std::size_t>(std::lower_bound(all.begin(), all.end(), h) - all.begin());
    };
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (seen[i]) continue;
      loops.push_back(boundary_loop(all[i]));
      for (halfedge_handle h : loops.back()) seen[index_of(h)] = 1;
    }
    return loops;
  }

  // ---------------------------------------------------------------- construction

  /// Adds an isolated vertex. O(1) amortised.
  vertex_handle add_vertex() {
    vertex_anchor_.push_back(npos);
    vprops_.push_back();
    return vertex_handle(vertex_anchor_.size() - 1);
  }
  /// Adds n isolated vertices; returns the first. O(n).
  vertex_handle add_vertices(std::size_t n) {
    const std::size_t first = vertex_anchor_.size();
    vertex_anchor_.resize(first + n, npos);
    vprops_.resize(first + n);
    return vertex_handle(first);
  }

  /// Adds a face through the given distinct vertices (n >= 3), linking it to its
  /// neighbours through the unlinked table: O(n) table operations, plus O(degree)
  /// at a vertex whose fans must be checked. Neighbours may disagree in orientation.
  /// Throws cellforge::error (topology) naming the edge or vertex that would become
  /// non-manifold; the mesh is unchanged then.
  face_handle add_face(std::span<const vertex_handle> vs);
  face_handle add_face(std::initializer_list<vertex_handle> vs) {
    return add_face(std::span(vs.begin(), vs.size()));
  }
  face_handle add_triangle(vertex_handle a, vertex_handle b, vertex_handle c) { return add_face({a, b, c}); }

  /// Replaces the connectivity by the faces of a CSR face list over n vertices, linking
  /// all half-edges in one pass without hashing: O(total face size). Throws
  /// cellforge::error naming the face, edge or vertex that cannot be represented.
  build_report build(std::size_t num_vertices, std::span<const std::uint32_t> face_offsets,
                     std::span<const std::uint32_t> face_vertices, const build_options& options = {});

  /// Removes face f; its edges shared with other faces become boundary edges (their
  /// half-edges return to the unlinked table), edges it alone used disappear. O(|f|).
  void remove_face(face_handle f);
  /// Removes vertex v and every face around it. O(sum of the sizes of those faces).
  void remove_vertex(vertex_handle v);
  /// Reverses the orientation of face f (its vertex order). O(|f|).
  void reverse_face(face_handle f);

  /// Drops removed elements and compacts every array and property. Handles change.
  /// O(size of the mesh).
  void garbage_collection();

  /// Removes everything, properties included. O(size).
  void clear() {
    he_.clear();
    vertex_anchor_.clear();
    face_anchor_.clear();
    unlinked_.clear();
    flipped_edges_ = removed_vertices_ = removed_edges_ = removed_faces_ = 0;
    vprops_.resize(0);
    hprops_.resize(0);
    eprops_.resize(0);
    fprops_.resize(0);
  }
  /// Reserves room for the given numbers of elements. O(1) amortised.
  void reserve(std::size_t nv, std::size_t ne, std::size_t nf) {
    vertex_anchor_.reserve(nv);
    he_.reserve(2 * ne);
    face_anchor_.reserve(nf);
    vprops_.reserve(nv);
    hprops_.reserve(2 * ne);
    eprops_.reserve(ne);
    fprops_.reserve(nf);
  }

  // ---------------------------------------------------------------- properties

  /// Adds a property named `name` with a default value; throws if the name is taken. O(n).
  template <class Handle, class T>
  property<Handle, T> add_property(std::string_view name, T default_value = T()) {
    return property<Handle, T>(registry<Handle>().template add<T>(name, std::move(default_value)));
  }
  /// The property named `name` (invalid if none); throws if it holds another type. O(properties).
  template <class Handle, class T>
  property<Handle, T> get_property(std::string_view name) const {
    return property<Handle, T>(registry<Handle>().template get<T>(name));
  }
  /// The property named `name`, added with the default value if absent. O(n) when added.
  template <class Handle, class T>
  property<Handle, T> property_or_add(std::string_view name, T default_value = T()) {
    auto p = get_property<Handle, T>(name);
    return p ? p : add_property<Handle, T>(name, std::move(default_value));
  }
  template <class Handle>
  bool has_property(std::string_view name) const noexcept {
    return registry<Handle>().find(name) != nullptr;
  }
  /// Removes a property; its handles become dangling. O(properties).
  template <class Handle, class T>
  void remove_property(property<Handle, T>& p) {
    if (p) registry<Handle>().remove(p.array());
    p = {};
  }
  template <class Handle>
  bool remove_property(std::string_view name) {
    return registry<Handle>().remove(registry<Handle>().find(name));
  }
  template <class Handle>
  std::vector<std::string> property_names() const {
    return registry<Handle>().names();
  }

  template <class T>
  property<vertex_handle, T> add_vertex_property(std::string_view name, T d = T()) {
    return add_property<vertex_handle, T>(name, std::move(d));
  }
  template <class T>
  property<halfedge_handle, T> add_halfedge_property(std::string_view name, T d = T()) {
    return add_property<halfedge_handle, T>(name, std::move(d));
  }
  template <class T>
  property<edge_handle, T> add_edge_property(std::string_view name, T d = T()) {
    return add_property<edge_handle, T>(name, std::move(d));
  }
  template <class T>
  property<face_handle, T> add_face_property(std::string_view name, T d = T()) {
    return add_property<face_handle, T>(name, std::move(d));
  }
  template <class T>
  property<vertex_handle, T> get_vertex_property(std::string_view name) const {
    return get_property<vertex_handle, T>(name);
  }
  template <class T>
  property<halfedge_handle, T> get_halfedge_property(std::string_view name) const {
    return get_property<halfedge_handle, T>(name);
  }
  template <class T>
  property<edge_handle, T> get_edge_property(std::string_view name) const {
    return get_property<edge_handle, T>(name);
  }
  template <class T>
  property<face_handle, T> get_face_property(std::string_view name) const {
    return get_property<face_handle, T>(name);
  }

  /// Read-only access to a registry, for validation and I/O. O(1).
  template <class Handle>
  const detail::property_registry& registry() const noexcept {
    return const_cast<basic_halfedge_mesh*>(this)->registry<Handle>();
  }

  // ---------------------------------------------------------------- for validate()

  /// The raw record of a half-edge, for checkers. O(1).
  struct record {
    std::uint32_t head = npos;
    std::uint32_t next = npos;
    std::uint32_t prev = npos;
    std::uint32_t face = npos;
  };
  const record& raw(halfedge_handle h) const noexcept { return he_[h.idx()]; }
  const detail::derived_key_table& unlinked_table() const noexcept { return unlinked_; }
  std::uint32_t raw_vertex_anchor(vertex_handle v) const noexcept { return vertex_anchor_[v.idx()]; }
  static constexpr std::uint32_t removed_mark = 0xFFFFFFFEu;

 private:
  template <class Handle>
  detail::property_registry& registry() noexcept {
    if constexpr (std::is_same_v<Handle, vertex_handle>)
      return vprops_;
    else if constexpr (std::is_same_v<Handle, halfedge_handle>)
      return hprops_;
    else if constexpr (std::is_same_v<Handle, edge_handle>)
      return eprops_;
    else
      return fprops_;
  }

  static std::uint32_t n32(std::size_t n) noexcept { return static_cast<std::uint32_t>(n); }

  static constexpr std::uint64_t table_key(std::uint32_t tail, std::uint32_t head) noexcept {
    return detail::derived_key_table::key(tail, head);
  }
  // The unlinked table's key of face half-edge h, read off the records: its boundary twin's
  // head is h's tail. The table stores no keys, so every edit keeps that head up to date
  // before it inserts or erases h.
  auto unlinked_key() const noexcept {
    return [this](std::uint32_t h) { return table_key(he_[h ^ 1u].head, he_[h].head); };
  }

  // The ring slot of boundary half-edge b at its end vertex v: next at its head, prev at its tail.
  std::uint32_t& ring_slot(std::uint32_t b, std::uint32_t v) noexcept {
    return he_[b].head == v ? he_[b].next : he_[b].prev;
  }
  std::uint32_t ring_slot(std::uint32_t b, std::uint32_t v) const noexcept {
    return he_[b].head == v ? he_[b].next : he_[b].prev;
  }

  // A fan of faces around a vertex, given by its two boundary end half-edges.
  struct fan {
    std::uint32_t start, end;
  };
  // The fan of a list that ends at boundary half-edge x (fans.end() if none). O(#fans).
  static typename std::vector<fan>::iterator fan_ending_at(std::vector<fan>& fans, std::uint32_t x) {
    return std::find_if(fans.begin(), fans.end(), [x](const fan& f) { return f.start == x || f.end == x; });
  }
  // The end of fan f that is not x.
  static std::uint32_t other_end(const fan& f, std::uint32_t x) noexcept {
    return f.start == x ? f.end : f.start;
  }
  // A fan grew or shrank by one face at its end `from`: that end is now `to`. O(#fans).
  static void move_fan_end(std::vector<fan>& fans, std::uint32_t from, std::uint32_t to) {
    const auto it = fan_ending_at(fans, from);
    if (it != fans.end()) (it->start == from ? it->start : it->end) = to;
  }
  // The open fans of boundary vertex v in ring order (empty for interior/isolated).
  void read_fans(std::uint32_t v, std::vector<fan>& out) const {
    out.clear();
    const std::uint32_t a = vertex_anchor_[v];
    if (a == npos || a == removed_mark || he_[a].face != npos) return;
    std::uint32_t s = a;
    do {
      const std::uint32_t e = ring_slot(s, v);
      out.push_back({s, e});
      s = ring_slot(e, v);
    } while (s != a);
  }
  // Rewrites the ring and anchor of v from its fans; `interior_anchor` is used when none is left.
  void write_fans(std::uint32_t v, const std::vector<fan>& fans, std::uint32_t interior_anchor) {
    if (fans.empty()) {
      vertex_anchor_[v] = interior_anchor;
      return;
    }
    for (std::size_t i = 0; i < fans.size(); ++i) {
      ring_slot(fans[i].start, v) = fans[i].end;
      ring_slot(fans[i].end, v) = fans[(i + 1) % fans.size()].start;
    }
    vertex_anchor_[v] = fans[0].start;
  }
  // The other end of the open fan at v that boundary half-edge b ends. O(#fans at v).
  halfedge_handle fan_partner(halfedge_handle b, vertex_handle v) const {
    // Rings alternate start, end: a start's successor is its end, so only ends need a search.
    const std::uint32_t a = vertex_anchor_[v.idx()];
    std::uint32_t s = a;
    do {
      const std::uint32_t e = ring_slot(s, v.idx());
      if (s == b.idx()) return halfedge_handle(e);
      if (e == b.idx()) return halfedge_handle(s);
      s = ring_slot(e, v.idx());
    } while (s != a);
    return {};  // b is not in the ring of v: the mesh is invalid
  }
  // Walks the open fan at v from boundary half-edge s; returns the other end and counts faces.
  std::uint32_t walk_fan(std::uint32_t s, std::uint32_t v, std::size_t* faces = nullptr,
                         std::uint32_t find_face = npos, std::uint32_t* entry = nullptr) const {
    std::uint32_t t = s ^ 1u;
    std::size_t n = 0;
    for (;;) {
      ++n;
      if (he_[t].face == find_face && entry) *entry = t;
      const std::uint32_t out = he_[t].head == v ? he_[t].next : he_[t].prev;
      const std::uint32_t u = out ^ 1u;
      if (he_[u].face == npos) {
        if (faces) *faces = n;
        return u;
      }
      t = u;
    }
  }
  // From face records (and boundary half-edges' heads) alone, derives everything else:
  // vertex anchors, boundary rings, the unlinked table, the flipped count. O(n).
  // With verify_fans false (a construction that is valid by design) the O(n) walk that
  // checks each interior vertex has a single closed fan is skipped.
  void link_fans(const build_options& options, build_report& report, bool verify_fans = true);
  // What build's last pass already knows, so that link_fans need not read every record
  // again: corners per vertex and the number of boundary half-edges (the caller has also
  // set the vertex anchors and the flipped count, as link_fans' first pass would).
  struct known_counts {
    std::vector<std::uint32_t> corners;
    std::size_t boundary = 0;
    // The unlinked table's entry of each face half-edge whose twin is on the boundary, in
    // increasing half-edge order (8 bytes each: built from the face list, no record is read).
    std::vector<detail::derived_key_table::slot> unlinked;
  };
  void link_fans(const build_options& options, build_report& report, bool verify_fans, known_counts* known);
  // build's passes; with Triangles every face f is known to have the three corners 3f, 3f+1, 3f+2.
  template <bool Triangles>
  build_report build_faces(std::size_t nv, std::span<const std::uint32_t> offsets,
                           std::span<const std::uint32_t> fv, const build_options& options);
  template <class>
  friend struct detail::basic_mesh_access;

  // Gives each closed fan of the listed vertices that their anchors do not reach a vertex of its own.
  void split_fans(const std::vector<std::uint32_t>& bad, build_report& report);

  // Drops faces, edges and half-edges (and their properties); vertices stay.
  void clear_connectivity() {
    he_.clear();
    face_anchor_.clear();
    unlinked_.clear();
    std::fill(vertex_anchor_.begin(), vertex_anchor_.end(), npos);
    flipped_edges_ = removed_edges_ = removed_faces_ = 0;
    hprops_.resize(0);
    eprops_.resize(0);
    fprops_.resize(0);
  }

  void check_vertex(vertex_handle v, const char* what) const {
    if (!is_valid(v))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat(std::string(what), ": vertex ", std::to_string(v.idx()),
                                         " does not exist or was removed"));
  }
  std::uint32_t new_edge() {
    he_.emplace_back();
    he_.emplace_back();
    hprops_.push_back();
    hprops_.push_back();
    eprops_.push_back();
    return n32(he_.size() / 2 - 1);
  }

  // Reused working arrays of add_face/remove_face, so that an edit allocates nothing once
  // warm. Per mesh (no global state); copying a mesh does not copy them.
  struct scratch_buffers {
    scratch_buffers() = default;
    scratch_buffers(const scratch_buffers&) {}
    scratch_buffers& operator=(const scratch_buffers&) { return *this; }
    scratch_buffers(scratch_buffers&&) noexcept = default;
    scratch_buffers& operator=(scratch_buffers&&) noexcept = default;

    std::vector<std::uint32_t>& assign_u32(std::size_t slot, std::size_t n, std::uint32_t value) {
      u32[slot].assign(n, value);
      return u32[slot];
    }
    std::vector<std::uint8_t>& assign_u8(std::size_t slot, std::size_t n, std::uint8_t value) {
      u8[slot].assign(n, value);
      return u8[slot];
    }
    std::vector<std::vector<fan>>& fan_lists(std::size_t n) {
      if (fans.size() < n) fans.resize(n);
      for (std::size_t i = 0; i < n; ++i) fans[i].clear();
      return fans;
    }
    std::vector<std::uint32_t> u32[4];
    std::vector<std::uint8_t> u8[2];
    std::vector<std::vector<fan>> fans;
  };

  std::vector<record> he_;
  std::vector<std::uint32_t> vertex_anchor_;
  std::vector<std::uint32_t> face_anchor_;
  detail::derived_key_table unlinked_;  // (tail, head) of face half-edges whose twin has no face
  std::size_t flipped_edges_ = 0;
  std::size_t removed_vertices_ = 0, removed_edges_ = 0, removed_faces_ = 0;
  detail::property_registry vprops_, hprops_, eprops_, fprops_;
  scratch_buffers scratch_;
};

}  // namespace cellforge

#include "cellforge/halfedge/detail/mesh_impl.hpp"
