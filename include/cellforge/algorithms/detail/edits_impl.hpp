// SPDX-License-Identifier: MIT
#pragma once
// The engine of the edits (included by algorithms/edits.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/edits.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/detail/mesh_access.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"

namespace cellforge {

namespace detail::edits {

// ------------------------------------------------------------------ small queries

template <class = void>
bool is_triangle(const halfedge_mesh& m, face_handle f) noexcept {
  const halfedge_handle h = m.halfedge(f);
  return m.next(m.next(m.next(h))) == h;
}
template <class = void>
bool face_has(const halfedge_mesh& m, face_handle f, vertex_handle x) {
  for (vertex_handle v : m.vertices_around(f))
    if (v == x) return true;
  return false;
}
// The corner of triangle f that is neither x nor y.
template <class = void>
vertex_handle third_corner(const halfedge_mesh& m, face_handle f, vertex_handle x, vertex_handle y) {
  for (vertex_handle v : m.vertices_around(f))
    if (v != x && v != y) return v;
  return {};
}
// The half-edge of face f joining x and y in either direction (invalid if none).
template <class = void>
halfedge_handle side_of(const halfedge_mesh& m, face_handle f, vertex_handle x, vertex_handle y) {
  for (halfedge_handle h : m.halfedges_around(f)) {
    const vertex_handle a = m.tail(h), b = m.head(h);
    if ((a == x && b == y) || (a == y && b == x)) return h;
  }
  return {};
}
// True when the side x-y of face f has no face on its other side.
template <class = void>
bool side_is_boundary(const halfedge_mesh& m, face_handle f, vertex_handle x, vertex_handle y) {
  return m.is_boundary(halfedge_mesh::twin(side_of(m, f, x, y)));
}
// Number of fans of faces at v: 0 isolated, 1 manifold, more for a bow-tie. O(#fans).
template <class = void>
std::size_t count_fans(const halfedge_mesh& m, vertex_handle v) {
  const halfedge_handle a = m.anchor(v);
  if (!a.is_valid()) return 0;
  if (!m.is_boundary(a)) return 1;
  std::size_t n = 0;
  halfedge_handle s = a;
  do {
    s = m.ring_next(m.ring_next(s, v), v);  // a fan's start -> its end -> the next fan's start
    ++n;
  } while (s != a && n <= m.halfedges_size());
  return n;
}
// The faces of an edge (one or two).
template <class = void>
std::vector<face_handle> edge_faces(const halfedge_mesh& m, edge_handle e) {
  std::vector<face_handle> out;
  for (unsigned i = 0; i < 2; ++i) {
    const halfedge_handle h = halfedge_mesh::halfedge(e, i);
    if (!m.is_boundary(h)) out.push_back(m.face(h));
  }
  return out;
}
// Sorted neighbour indices of v, skipping the listed vertices.
template <class = void>
std::vector<std::uint32_t> neighbours(const halfedge_mesh& m, vertex_handle v,
                                      std::initializer_list<vertex_handle> skip) {
  std::vector<std::uint32_t> out;
  for (vertex_handle w : m.vertices_around(v))
    if (std::find(skip.begin(), skip.end(), w) == skip.end()) out.push_back(w.idx());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}
// True when some face at v, other than those in `skip`, is a triangle through x and y.
template <class = void>
bool has_triangle_at(const halfedge_mesh& m, vertex_handle v, vertex_handle x, vertex_handle y,
                     std::span<const face_handle> skip) {
  for (face_handle g : m.faces_around(v)) {
    if (std::find(skip.begin(), skip.end(), g) != skip.end()) continue;
    if (is_triangle(m, g) && face_has(m, g, x) && face_has(m, g, y)) return true;
  }
  return false;
}
template <class = void>
bool all_triangles_at(const halfedge_mesh& m, vertex_handle v) {
  for (face_handle g : m.faces_around(v))
    if (!is_triangle(m, g)) return false;
  return true;
}

// ------------------------------------------------------------------ the link condition

// Everything the link condition of a collapse u -> v looks at. Filled from the mesh for a
// half-edge collapse, or from the mesh *as it would be* after a first collapse, for the
// second step of a face collapse.
struct link_query {
  bool u_boundary = false, v_boundary = false;
  int faces = 0;                               // faces on the edge
  std::array<vertex_handle, 2> opp;            // their third corners
  std::array<std::array<bool, 2>, 2> outer{};  // [i]: sides (u, opp_i) and (v, opp_i) are boundary
  std::vector<std::uint32_t> nu, nv;           // sorted neighbours of u and v, without u and v
  bool tetra = false;                          // triangles (u, opp0, opp1) and (v, opp0, opp1) both exist
};

// The combinatorial link condition for surfaces with boundary: Lk(u) ∩ Lk(v) = Lk(uv) in
// the mesh completed by a dummy vertex joined to every boundary edge. O(|nu| + |nv|).
template <class = void>
edit_refusal evaluate(const link_query& q) {
  if (q.faces == 0) return edit_refusal::isolated_triangle;
  if (q.faces == 2 && q.opp[0] == q.opp[1]) return edit_refusal::degenerate;
  // The dummy vertex is in both links but not in the edge's: the fan would pinch.
  if (q.u_boundary && q.v_boundary && q.faces == 2) return edit_refusal::boundary_vertices;
  for (int i = 0; i < q.faces; ++i)
    if (q.outer[i][0] && q.outer[i][1]) return edit_refusal::isolated_triangle;
  std::vector<std::uint32_t> common;
  std::set_intersection(q.nu.begin(), q.nu.end(), q.nv.begin(), q.nv.end(), std::back_inserter(common));
  std::vector<std::uint32_t> expected;
  for (int i = 0; i < q.faces; ++i) expected.push_back(q.opp[i].idx());
  std::sort(expected.begin(), expected.end());
  if (common != expected) return edit_refusal::link_condition;
  // The edge opp0-opp1 in both links: triangles u-opp0-opp1 and v-opp0-opp1 would coincide.
  if (q.tetra) return edit_refusal::tetrahedron;
  return edit_refusal::none;
}

// A half-edge collapse u -> v over edge e, checked; `faces` receives the edge's faces.
template <class = void>
edit_refusal check_collapse(const halfedge_mesh& m, edge_handle e, vertex_handle u, vertex_handle v,
                            std::vector<face_handle>& faces) {
  faces = edge_faces(m, e);
  for (face_handle f : faces)
    if (!is_triangle(m, f)) return edit_refusal::not_triangle;
  if (count_fans(m, u) != 1 || count_fans(m, v) != 1) return edit_refusal::nonmanifold_vertex;
  if (!all_triangles_at(m, u)) return edit_refusal::not_triangle;
  link_query q;
  q.u_boundary = m.is_boundary(u);
  q.v_boundary = m.is_boundary(v);
  q.faces = static_cast<int>(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) {
    q.opp[i] = third_corner(m, faces[i], u, v);
    q.outer[i] = {side_is_boundary(m, faces[i], u, q.opp[i]), side_is_boundary(m, faces[i], v, q.opp[i])};
  }
  q.nu = neighbours(m, u, {u, v});
  q.nv = neighbours(m, v, {u, v});
  if (q.faces == 2 && q.opp[0] != q.opp[1])
    q.tetra = has_triangle_at(m, u, q.opp[0], q.opp[1], detail::span_of(faces)) &&
              has_triangle_at(m, v, q.opp[0], q.opp[1], detail::span_of(faces));
  return evaluate(q);
}

// The pieces of a face collapse of triangle (k, a, c) into k: a -> k first, then c -> k.
struct face_collapse_plan {
  vertex_handle k, a, c;
  std::vector<face_handle> removed;  // the face and its (up to three) neighbours
};

// The other face across side x-y of face f (invalid at the boundary).
template <class = void>
face_handle across(const halfedge_mesh& m, face_handle f, vertex_handle x, vertex_handle y) {
  const halfedge_handle t = halfedge_mesh::twin(side_of(m, f, x, y));
  return m.is_boundary(t) ? face_handle() : m.face(t);
}

// Checks one order of a face collapse of triangle f = {k, a, c}: the collapse a -> k on the
// mesh, then c -> k on the mesh as the first would leave it, read off the current mesh.
template <class = void>
edit_refusal check_face_collapse_order(const halfedge_mesh& m, face_handle f, vertex_handle k,
                                       vertex_handle a, vertex_handle c) {
  std::vector<face_handle> first;
  const edge_handle ak = halfedge_mesh::edge(side_of(m, f, a, k));
  if (auto r = check_collapse(m, ak, a, k, first); r != edit_refusal::none) return r;
  if (count_fans(m, c) != 1) return edit_refusal::nonmanifold_vertex;
  if (!all_triangles_at(m, c)) return edit_refusal::not_triangle;

  const face_handle n_ak = across(m, f, a, k), n_kc = across(m, f, k, c), n_ca = across(m, f, c, a);
  std::vector<face_handle> removed{f};
  for (face_handle g : {n_ak, n_kc, n_ca})
    if (g.is_valid()) removed.push_back(g);
  // A neighbour through all three corners is a pillow: nothing would be left between them.
  if ((n_kc.is_valid() && face_has(m, n_kc, a)) || (n_ca.is_valid() && face_has(m, n_ca, k)))
    return edit_refusal::degenerate;
  const vertex_handle p = n_ak.is_valid() ? third_corner(m, n_ak, a, k) : vertex_handle();

  // After a -> k, the edge c-k has the faces n_kc (corner k) and n_ca (corner a, renamed k).
  link_query q;
  q.u_boundary = m.is_boundary(c);
  q.v_boundary = m.is_boundary(a) || m.is_boundary(k);
  const auto other = [&](vertex_handle y) { return y == k ? a : k; };
  for (const auto& [g, y] : {std::pair{n_kc, k}, std::pair{n_ca, a}}) {
    if (!g.is_valid()) continue;
    const vertex_handle x = third_corner(m, g, c, y);
    const int i = q.faces++;
    q.opp[i] = x;
    // Side k-x after the first collapse: when x is p, a-p and k-p merge and only the side
    // not in n_ak is left; otherwise it is the side y-x of g itself.
    const bool kx_boundary = x == p ? side_is_boundary(m, n_ak, other(y), p) : side_is_boundary(m, g, y, x);
    q.outer[i] = {side_is_boundary(m, g, c, x), kx_boundary};
  }
  q.nu = neighbours(m, c, {a, k, c});
  q.nv = neighbours(m, a, {a, k, c});
  {
    std::vector<std::uint32_t> nk = neighbours(m, k, {a, k, c}), merged;
    std::set_union(q.nv.begin(), q.nv.end(), nk.begin(), nk.end(), std::back_inserter(merged));
    q.nv = std::move(merged);
  }
  if (q.faces == 2 && q.opp[0] != q.opp[1])
    q.tetra = has_triangle_at(m, c, q.opp[0], q.opp[1], detail::span_of(removed)) &&
              (has_triangle_at(m, a, q.opp[0], q.opp[1], detail::span_of(removed)) ||
               has_triangle_at(m, k, q.opp[0], q.opp[1], detail::span_of(removed)));
  return evaluate(q);
}

// Checks a face collapse. Its result does not depend on the order in which the three
// corners merge, so it is allowed when some order is two valid edge collapses (a corner of
// valence 3 fails one order and passes another). Reports the first order's refusal.
template <class = void>
edit_refusal check_face_collapse(const halfedge_mesh& m, face_handle f, face_collapse_plan& plan) {
  if (!is_triangle(m, f)) return edit_refusal::not_triangle;
  const halfedge_handle h0 = m.halfedge(f);
  const std::array<vertex_handle, 3> v{m.tail(h0), m.head(h0), m.head(m.next(h0))};
  plan = {v[0], v[1], v[2], {f}};
  edit_refusal first = edit_refusal::none;
  for (std::size_t i = 0; i < 3; ++i) {
    const edit_refusal r = check_face_collapse_order(m, f, v[i], v[(i + 1) % 3], v[(i + 2) % 3]);
    if (r == edit_refusal::none) {
      first = r;
      break;
    }
    if (i == 0) first = r;
  }
  if (first != edit_refusal::none) return first;
  for (const auto& [x, y] : {std::pair{v[0], v[1]}, std::pair{v[1], v[2]}, std::pair{v[2], v[0]}})
    if (const face_handle g = across(m, f, x, y); g.is_valid()) plan.removed.push_back(g);
  return edit_refusal::none;
}

// ------------------------------------------------------------------ rewriting faces

// A face to add: its vertices and, for properties, the face it replaces and per side
// i (vertices[i] -> vertices[i+1]) the old half-edge it continues (invalid: defaults).
struct face_spec {
  std::vector<vertex_handle> vertices;
  face_handle source;
  std::vector<halfedge_handle> sources;
};

// The spec re-adding triangle or polygon g with vertex `from` renamed `to` (same order).
template <class = void>
face_spec renamed(const halfedge_mesh& m, face_handle g, vertex_handle from, vertex_handle to,
                  vertex_handle from2 = {}) {
  face_spec s{{}, g, {}};
  for (halfedge_handle h : m.halfedges_around(g)) {
    const vertex_handle t = m.tail(h);
    s.vertices.push_back(t == from || (from2.is_valid() && t == from2) ? to : t);
    s.sources.push_back(h);
  }
  return s;
}

// Gives each (dst, src) pair's dst the property values of src (a src may feed several dsts).
template <class = void>
void carry(detail::property_registry& r, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
  for (const auto& [dst, src] : pairs) r.copy_element(dst, src);
}

// Moves properties from the replaced faces (and their half-edges and edges) to `added`.
template <class = void>
void carry_properties(halfedge_mesh& m, std::span<const face_spec> specs, std::span<const face_handle> added,
                      std::size_t old_edges) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> fp, hp, ep;
  std::vector<std::uint8_t> edge_done;
  for (std::size_t i = 0; i < added.size(); ++i) {
    const face_spec& s = specs[i];
    if (s.source.is_valid()) fp.emplace_back(added[i].idx(), s.source.idx());
    std::size_t side = 0;
    for (halfedge_handle h : m.halfedges_around(added[i])) {
      const halfedge_handle src = side < s.sources.size() ? s.sources[side] : halfedge_handle();
      ++side;
      if (!src.is_valid()) continue;
      hp.emplace_back(h.idx(), src.idx());
      const std::uint32_t e = halfedge_mesh::edge(h).idx();
      if (e < old_edges) continue;  // an edge that survived keeps its own values
      edge_done.resize(std::max<std::size_t>(edge_done.size(), e - old_edges + 1), 0);
      if (edge_done[e - old_edges]++) continue;
      ep.emplace_back(e, halfedge_mesh::edge(src).idx());
    }
  }
  carry(mesh_access::face_properties(m), fp);
  carry(mesh_access::halfedge_properties(m), hp);
  carry(mesh_access::edge_properties(m), ep);
}

// Removes `old_faces` and adds `specs` in their place, carrying properties. The caller has
// checked that the result is representable; should add_face still refuse, the old faces
// are restored (under new handles) and error(internal) is thrown. O(total face size).
template <class = void>
std::vector<face_handle> replace_faces(halfedge_mesh& m, std::span<const face_handle> old_faces,
                                       std::span<const face_spec> specs) {
  std::vector<face_spec> originals;
  originals.reserve(old_faces.size());
  for (face_handle f : old_faces) originals.push_back(renamed(m, f, {}, {}));
  const std::size_t old_edges = m.edges_size();
  for (face_handle f : old_faces) m.remove_face(f);
  std::vector<face_handle> added;
  added.reserve(specs.size());
  try {
    for (const face_spec& s : specs) added.push_back(m.add_face(detail::span_of(s.vertices)));
  } catch (const error& ex) {
    for (face_handle f : added) m.remove_face(f);
    std::vector<face_handle> restored;
    for (const face_spec& s : originals) restored.push_back(m.add_face(detail::span_of(s.vertices)));
    carry_properties(m, detail::span_of(originals), detail::span_of(restored), old_edges);
    throw error(error_category::internal,
                cellforge::detail::cat(
                    std::string("a checked mesh edit was refused by add_face (the mesh is restored; please "
                                "report): "),
                    ex.what()));
  }
  carry_properties(m, specs, detail::span_of(added), old_edges);
  return added;
}

template <class = void>
edit_result refused(edit_refusal why) {
  edit_result r;
  r.refusal = why;
  r.diagnostics.emplace_back(to_string(why));
  return r;
}

/// r with its wall time since `clock` started. O(1).
template <class = void>
edit_result timed(edit_result r, const detail::stopwatch& clock) {
  r.milliseconds = clock.ms();
  return r;
}

template <class = void>
void check_handle(bool ok, const char* what, const char* kind, std::uint32_t idx) {
  if (!ok)
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(what), ": ", kind, " ", std::to_string(idx),
                                       " does not exist or was removed"));
}
template <class = void>
void check_finite(const glm::dvec3& p, const char* what) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(what), ": the position is not finite"));
}

// Collapse u -> v over edge e after the check passed.
template <class = void>
edit_result do_collapse(halfedge_mesh& m, vertex_handle u, vertex_handle v,
                        std::span<const face_handle> edge_faces_) {
  std::vector<face_handle> around;
  std::vector<face_spec> specs;
  for (face_handle g : m.faces_around(u)) {
    around.push_back(g);
    if (std::find(edge_faces_.begin(), edge_faces_.end(), g) == edge_faces_.end())
      specs.push_back(renamed(m, g, u, v));
  }
  replace_faces(m, detail::span_of(around), detail::span_of(specs));
  m.remove_vertex(u);
  edit_result r;
  r.vertex = v;
  r.vertices_removed = 1;
  r.faces_removed = edge_faces_.size();
  return r;
}

template <class = void>
void check_edge_endpoint(const halfedge_mesh& m, edge_handle e, vertex_handle keep, const char* what) {
  check_handle(m.is_valid(e), what, "edge", e.idx());
  if (keep != m.vertex(e, 0) && keep != m.vertex(e, 1))
    throw error(error_category::invalid_input,
                cellforge::detail::cat(std::string(what), ": vertex ", std::to_string(keep.idx()),
                                       " is not an end of edge ", std::to_string(e.idx())));
}

template <Point3 P>
void place(surface_mesh<P>& m, vertex_handle v, const glm::dvec3& p) {
  m.set_position(v, from_dvec3<P>(p));
}

}  // namespace detail::edits

template <class>
edit_refusal can_collapse(const halfedge_mesh& m, halfedge_handle h) {
  detail::edits::check_handle(m.is_valid(h), "can_collapse", "half-edge", h.idx());
  std::vector<face_handle> faces;
  return detail::edits::check_collapse(m, halfedge_mesh::edge(h), m.tail(h), m.head(h), faces);
}
template <class>
edit_refusal can_collapse(const halfedge_mesh& m, edge_handle e, vertex_handle keep) {
  detail::edits::check_edge_endpoint(m, e, keep, "can_collapse");
  const vertex_handle u = keep == m.vertex(e, 0) ? m.vertex(e, 1) : m.vertex(e, 0);
  std::vector<face_handle> faces;
  return detail::edits::check_collapse(m, e, u, keep, faces);
}

template <class>
edit_result collapse_halfedge(halfedge_mesh& m, halfedge_handle h) {
  const detail::stopwatch clock;
  detail::edits::check_handle(m.is_valid(h), "collapse_halfedge", "half-edge", h.idx());
  const vertex_handle u = m.tail(h), v = m.head(h);
  std::vector<face_handle> faces;
  if (auto r = detail::edits::check_collapse(m, halfedge_mesh::edge(h), u, v, faces); r != edit_refusal::none)
    return detail::edits::timed(detail::edits::refused(r), clock);
  return detail::edits::timed(detail::edits::do_collapse(m, u, v, detail::span_of(faces)), clock);
}

template <class>
edit_result collapse_edge(halfedge_mesh& m, edge_handle e, vertex_handle keep) {
  const detail::stopwatch clock;
  detail::edits::check_edge_endpoint(m, e, keep, "collapse_edge");
  const vertex_handle u = keep == m.vertex(e, 0) ? m.vertex(e, 1) : m.vertex(e, 0);
  std::vector<face_handle> faces;
  if (auto r = detail::edits::check_collapse(m, e, u, keep, faces); r != edit_refusal::none)
    return detail::edits::timed(detail::edits::refused(r), clock);
  return detail::edits::timed(detail::edits::do_collapse(m, u, keep, detail::span_of(faces)), clock);
}

template <Point3 P>
edit_result collapse_halfedge(surface_mesh<P>& m, halfedge_handle h, const collapse_options& options) {
  const detail::stopwatch clock;
  detail::edits::check_handle(m.is_valid(h), "collapse_halfedge", "half-edge", h.idx());
  const glm::dvec3 a = to_dvec3(m.position(m.tail(h))), b = to_dvec3(m.position(m.head(h)));
  glm::dvec3 target = b;
  if (options.position == collapse_position::midpoint) target = 0.5 * (a + b);
  if (options.position == collapse_position::custom) target = options.point;
  detail::edits::check_finite(target, "collapse_halfedge");
  edit_result r = collapse_halfedge(static_cast<halfedge_mesh&>(m), h);
  if (r) detail::edits::place(m, r.vertex, target);
  return detail::edits::timed(r, clock);
}

template <class>
edit_refusal can_collapse_face(const halfedge_mesh& m, face_handle f) {
  detail::edits::check_handle(m.is_valid(f), "can_collapse_face", "face", f.idx());
  detail::edits::face_collapse_plan plan;
  return detail::edits::check_face_collapse(m, f, plan);
}

template <class>
edit_result collapse_face(halfedge_mesh& m, face_handle f) {
  const detail::stopwatch clock;
  detail::edits::check_handle(m.is_valid(f), "collapse_face", "face", f.idx());
  detail::edits::face_collapse_plan plan;
  if (auto r = detail::edits::check_face_collapse(m, f, plan); r != edit_refusal::none)
    return detail::edits::timed(detail::edits::refused(r), clock);
  std::vector<face_handle> around;
  std::vector<detail::edits::face_spec> specs;
  for (vertex_handle x : {plan.a, plan.c})
    for (face_handle g : m.faces_around(x)) {
      if (std::find(around.begin(), around.end(), g) != around.end()) continue;
      around.push_back(g);
      if (std::find(plan.removed.begin(), plan.removed.end(), g) == plan.removed.end())
        specs.push_back(detail::edits::renamed(m, g, plan.a, plan.k, plan.c));
    }
  detail::edits::replace_faces(m, detail::span_of(around), detail::span_of(specs));
  m.remove_vertex(plan.a);
  m.remove_vertex(plan.c);
  edit_result r;
  r.vertex = plan.k;
  r.vertices_removed = 2;
  r.faces_removed = plan.removed.size();
  return detail::edits::timed(r, clock);
}

template <Point3 P>
edit_result collapse_face(surface_mesh<P>& m, face_handle f) {
  const detail::stopwatch clock;
  detail::edits::check_handle(m.is_valid(f), "collapse_face", "face", f.idx());
  glm::dvec3 centroid(0.0);
  std::size_t n = 0;
  for (vertex_handle v : m.vertices_around(f)) {
    centroid += to_dvec3(m.position(v));
    ++n;
  }
  centroid /= static_cast<double>(n);
  edit_result r = collapse_face(static_cast<halfedge_mesh&>(m), f);
  if (r) detail::edits::place(m, r.vertex, centroid);
  return detail::edits::timed(r, clock);
}

template <class>
edit_result split_edge(halfedge_mesh& m, edge_handle e) {
  const detail::stopwatch clock;
  detail::edits::check_handle(m.is_valid(e), "split_edge", "edge", e.idx());
  const std::vector<face_handle> faces = detail::edits::edge_faces(m, e);
  const vertex_handle a = m.vertex(e, 0), b = m.vertex(e, 1);
  const vertex_handle w = m.add_vertex();
  std::vector<detail::edits::face_spec> specs;
  for (face_handle g : faces) {
    detail::edits::face_spec s = detail::edits::renamed(m, g, {}, {});
    const std::size_t n = s.vertices.size();
    std::size_t i = 0;  // the side vertices[i] -> vertices[i+1] lies on e
    while (!((s.vertices[i] == a || s.vertices[i] == b) &&
             (s.vertices[(i + 1) % n] == a || s.vertices[(i + 1) % n] == b)))
      ++i;
    std::rotate(s.vertices.begin(), s.vertices.begin() + static_cast<std::ptrdiff_t>(i), s.vertices.end());
    std::rotate(s.sources.begin(), s.sources.begin() + static_cast<std::ptrdiff_t>(i), s.sources.end());
    // Now the face reads x, y, z...: x -> y is on e.
    const halfedge_handle on_e = s.sources[0];
    if (n == 3) {
      const vertex_handle x = s.vertices[0], y = s.vertices[1], z = s.vertices[2];
      specs.push_back({{x, w, z}, g, {on_e, halfedge_handle(), s.sources[2]}});
      specs.push_back({{w, y, z}, g, {on_e, s.sources[1], halfedge_handle()}});
    } else {
      s.vertices.insert(s.vertices.begin() + 1, w);
      s.sources.insert(s.sources.begin() + 1, on_e);
      specs.push_back(std::move(s));
    }
  }
  detail::edits::replace_faces(m, detail::span_of(faces), detail::span_of(specs));
  edit_result r;
  r.vertex = w;
  r.faces_added = specs.size() - faces.size();
  return detail::edits::timed(r, clock);
}

template <Point3 P>
edit_result split_edge(surface_mesh<P>& m, edge_handle e, const std::type_identity_t<P>& position) {
  const detail::stopwatch clock;
  detail::edits::check_handle(m.is_valid(e), "split_edge", "edge", e.idx());
  detail::edits::check_finite(to_dvec3(position), "split_edge");
  edit_result r = split_edge(static_cast<halfedge_mesh&>(m), e);
  m.set_position(r.vertex, position);
  return detail::edits::timed(r, clock);
}

template <class>
edit_refusal can_flip(const halfedge_mesh& m, edge_handle e) {
  detail::edits::check_handle(m.is_valid(e), "can_flip", "edge", e.idx());
  const std::vector<face_handle> faces = detail::edits::edge_faces(m, e);
  if (faces.size() != 2) return edit_refusal::boundary_edge;
  if (!detail::edits::is_triangle(m, faces[0]) || !detail::edits::is_triangle(m, faces[1]))
    return edit_refusal::not_triangle;
  const vertex_handle a = m.vertex(e, 0), b = m.vertex(e, 1);
  const vertex_handle c = detail::edits::third_corner(m, faces[0], a, b);
  const vertex_handle d = detail::edits::third_corner(m, faces[1], a, b);
  if (c == d) return edit_refusal::degenerate;
  if (m.find_edge(c, d).is_valid()) return edit_refusal::edge_exists;
  return edit_refusal::none;
}

template <class>
edit_result flip_edge(halfedge_mesh& m, edge_handle e) {
  const detail::stopwatch clock;
  if (auto r = can_flip(m, e); r != edit_refusal::none)
    return detail::edits::timed(detail::edits::refused(r), clock);
  const halfedge_handle h = halfedge_mesh::halfedge(e, 0);
  const face_handle f0 = m.face(h), f1 = m.face(halfedge_mesh::twin(h));
  const vertex_handle x = m.tail(h), y = m.head(h);  // f0 runs x -> y -> c
  const vertex_handle c = m.head(m.next(h));
  const vertex_handle d = detail::edits::third_corner(m, f1, x, y);
  const halfedge_handle yc = m.next(h), cx = m.prev(h);
  const halfedge_handle xd = detail::edits::side_of(m, f1, x, d), dy = detail::edits::side_of(m, f1, d, y);
  const std::array<face_handle, 2> old{f0, f1};
  const std::array<detail::edits::face_spec, 2> specs{
      detail::edits::face_spec{{x, d, c}, f0, {xd, halfedge_handle(), cx}},
      detail::edits::face_spec{{d, y, c}, f1, {dy, yc, halfedge_handle()}}};
  detail::edits::replace_faces(m, old, specs);
  edit_result r;
  r.edge = m.find_edge(c, d);
  return detail::edits::timed(r, clock);
}

}  // namespace cellforge
