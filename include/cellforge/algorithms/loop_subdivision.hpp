// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Loop subdivision of triangle meshes in linear time: every level splits each triangle
/// into four with the children's connectivity written in closed form (no search for
/// twins, no hash table), then applies Loop's masks in a separate pass. Boundaries follow
/// the cubic B-spline rule; non-orientable meshes (Möbius strips, Klein bottles, faces of
/// random orientation) subdivide like any other. See docs/loop_subdivision.md.

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <typeinfo>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "cellforge/algorithms/detail/loop_masks.hpp"
#include "cellforge/algorithms/detail/loop_topology.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/detail/mesh_access.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

/// The interior vertex weight β(n) for a vertex of valence n.
enum class loop_weights : std::uint8_t {
  loop,    ///< Loop's original (5/8 − (3/8 + cos(2π/n)/4)²)/n, as OpenMesh and CGAL use
  warren,  ///< Warren's simplification 3/(8n), and 3/16 for n = 3
};

/// What happens to vertices on a boundary. Points on boundary edges are always the edge
/// midpoints, so a boundary curve depends only on the boundary's own vertices.
enum class loop_boundary : std::uint8_t {
  bspline,          ///< boundary curves are cubic B-splines: v' = ¾v + ⅛(left + right)
  bspline_corners,  ///< as bspline, but a vertex with a single face (a corner) stays put
  fixed,            ///< boundary vertices stay put (the boundary polygon is interpolated)
};

/// How an opted-in user vertex property is carried to the new vertices.
enum class loop_property_rule : std::uint8_t {
  linear,  ///< old vertices keep their value, an edge's new vertex takes the mean of its ends
  loop,    ///< the same masks as the positions (weights and boundary rule included)
};

/// A user vertex property to carry through subdivision. Its type must be float, double,
/// or a glm vector (2, 3 or 4 components) of either.
struct loop_property {
  std::string name;
  loop_property_rule rule = loop_property_rule::linear;
};

/// Options of loop_subdivide.
struct loop_subdivision_options {
  int levels = 1;  ///< number of 1→4 splits, ≥ 0 (0 leaves the mesh as it is)
  loop_weights weights = loop_weights::loop;
  loop_boundary boundary = loop_boundary::bspline;
  /// Vertex properties to interpolate. Every other vertex property keeps its values on the
  /// old vertices and takes its default on the new ones; half-edge, edge and face
  /// properties stay registered but are reset to their defaults (their elements are new).
  std::vector<loop_property> interpolate{};
  /// Most faces the result may have, checked before anything is allocated (a face costs about
  /// 80 bytes with its vertices and edges: 50M faces ≈ 4 GB). 0: only the 32-bit index limit.
  std::size_t max_faces = 50'000'000;
};

/// Counts before and after, and where the time went (milliseconds: the levels' sum).
struct loop_subdivision_result : stage_report {
  std::size_t vertices_before = 0, edges_before = 0, faces_before = 0;
  std::size_t vertices_after = 0, edges_after = 0, faces_after = 0;
  std::size_t boundary_edges_after = 0, flipped_edges_after = 0;
  /// Vertices kept in place because several fans meet there (summed over the levels).
  std::size_t fixed_vertices = 0;
  /// Milliseconds per level (the last one includes deriving vertex anchors and rings).
  std::vector<double> level_ms;
};

namespace detail::loop {

template <class T>
struct accumulator;
template <>
struct accumulator<float> {
  using type = double;
};
template <>
struct accumulator<double> {
  using type = double;
};
template <glm::length_t N, class T, glm::qualifier Q>
requires std::is_floating_point_v<T>
struct accumulator<glm::vec<N, T, Q>> {
  using type = glm::vec<N, double, Q>;
};

template <class Array>
struct array_value;
template <class T>
struct array_value<property_array<T>> {
  using type = T;
};

/// The value types a user vertex property may have to be interpolated; a job's `kind` indexes
/// this list (a tag list and a switch instead of std::variant, which every includer would parse).
template <class... T>
struct value_types {};
using attribute_types =
    value_types<float, double, glm::vec2, glm::vec3, glm::vec4, glm::dvec2, glm::dvec3, glm::dvec4>;

/// A user vertex property the masks can interpolate, with its rule.
struct attribute_job {
  property_array_base* array;
  std::uint8_t kind;  ///< index of the array's value type in attribute_types
  loop_property_rule rule;
};

/// The index of `a`'s value type in attribute_types; throws when it is not there. O(1).
template <class... T>
std::uint8_t attribute_kind(property_array_base& a, value_types<T...>) {
  std::uint8_t kind = 0;
  if (((a.type() == typeid(T) || (++kind, false)) || ...)) return kind;
  throw error(error_category::invalid_input,
              cellforge::detail::cat(
                  "loop_subdivide: vertex property '", a.name(), "' has type ", a.type().name(),
                  "; only float, double and glm vectors of them (2 to 4 components) can be interpolated"));
}

/// Calls f with the job's array cast to its own type. O(1) besides f.
template <class F, class... T>
void visit_attribute(const attribute_job& job, F&& f, value_types<T...>) {
  std::uint8_t kind = 0;
  (void)((job.kind == kind++ && (f(static_cast<property_array<T>*>(job.array)), true)) || ...);
}

/// Resolves the opted-in properties before anything changes. O(properties²).
template <class = void>
std::vector<attribute_job> resolve_attributes(halfedge_mesh& mesh, const std::vector<loop_property>& specs) {
  std::vector<attribute_job> jobs;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const std::string& name = specs[i].name;
    if (name == point_property_name)
      throw error(error_category::invalid_input,
                  "loop_subdivide: \"v:point\" is subdivided anyway; do not list it in "
                  "loop_subdivision_options::interpolate");
    for (std::size_t j = 0; j < i; ++j)
      if (specs[j].name == name)
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("loop_subdivide: vertex property '", name,
                                           "' is listed twice in loop_subdivision_options::interpolate"));
    property_array_base* a = mesh_access::vertex_properties(mesh).find(name);
    if (a == nullptr)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("loop_subdivide: there is no vertex property named '", name, "'"));
    if (specs[i].rule != loop_property_rule::linear && specs[i].rule != loop_property_rule::loop)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("loop_subdivide: unknown rule for vertex property '", name, "'"));
    jobs.push_back({a, attribute_kind(*a, attribute_types{}), specs[i].rule});
  }
  return jobs;
}

template <class = void>
mask_params to_params(const loop_subdivision_options& o) {
  if (o.weights != loop_weights::loop && o.weights != loop_weights::warren)
    throw error(error_category::invalid_input,
                "loop_subdivide: unknown loop_subdivision_options::weights value");
  if (o.boundary != loop_boundary::bspline && o.boundary != loop_boundary::bspline_corners &&
      o.boundary != loop_boundary::fixed)
    throw error(error_category::invalid_input,
                "loop_subdivide: unknown loop_subdivision_options::boundary value");
  return {o.weights == loop_weights::warren, o.boundary != loop_boundary::fixed,
          o.boundary == loop_boundary::bspline_corners};
}

/// Subdivides one user attribute in place (its array grows to the child's vertex count).
/// O(V + E).
template <class = void>
void subdivide_attribute(const attribute_job& job, std::span<const record> he, std::uint32_t nv,
                         std::size_t child_nv, std::span<const std::uint32_t> boundary_edges,
                         const mask_params& params) {
  visit_attribute(
      job,
      [&](auto* array) {
        using T = typename array_value<std::remove_pointer_t<decltype(array)>>::type;
        using A = typename accumulator<T>::type;
        const std::vector<T>& old = array->data();
        std::vector<T> out(child_nv);
        auto read = [&](std::uint32_t v) { return A(old[v]); };
        auto store = [&](std::uint32_t i, const A& value) { out[i] = T(value); };
        if (job.rule == loop_property_rule::loop)
          apply_masks<A>(he, nv, boundary_edges, params, read, store);
        else
          apply_linear<A>(he, nv, read, store);
        array->data().swap(out);
      },
      attribute_types{});
}

}  // namespace detail::loop

/// Applies `options.levels` levels of Loop subdivision to a triangle mesh in place.
/// O(output size) per level.
///
/// Numbering: the old vertices keep their handles; the vertex on old edge e is V + e.
/// Removed elements are garbage-collected first. Throws cellforge::error (invalid_input)
/// before changing anything when: levels < 0; the result would overflow 32-bit indices or
/// exceed options.max_faces;
/// a coordinate is NaN, infinite or beyond ±1e290; a
/// face is not a triangle (the error names it); an opted-in property is missing or of an
/// unsupported type; or the records are corrupted. A vertex where several fans meet stays
/// in place (counted in loop_subdivision_result::fixed_vertices). If allocation fails at a later level,
/// the mesh is left valid at the last completed level.
template <Point3 P>
loop_subdivision_result loop_subdivide(surface_mesh<P>& mesh, const loop_subdivision_options& options = {}) {
  namespace dl = detail::loop;
  using access = detail::mesh_access;

  if (options.levels < 0)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("loop_subdivide: levels must be at least 0, got ",
                                       std::to_string(options.levels)));
  const dl::mask_params params = dl::to_params(options);
  auto pts = mesh.positions();

  loop_subdivision_result result;
  result.vertices_before = result.vertices_after = mesh.num_vertices();
  result.edges_before = result.edges_after = mesh.num_edges();
  result.faces_before = result.faces_after = mesh.num_faces();
  result.boundary_edges_after = mesh.num_boundary_edges();
  result.flipped_edges_after = mesh.num_flipped_edges();
  if (options.levels == 0 || mesh.num_faces() == 0) return result;  // nothing would change

  // Every level's sizes, checked before anything is allocated.
  dl::counts c{mesh.num_vertices(), mesh.num_edges(), mesh.num_faces()};
  for (int level = 1; level <= options.levels; ++level) {
    c = c.next();
    if (!c.fits())
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("loop_subdivide: level ", std::to_string(level), " of ",
                                         std::to_string(options.levels), " would need ",
                                         std::to_string(c.faces), " faces and ", std::to_string(2 * c.edges),
                                         " half-edges, more than 32-bit indices allow"));
  }
  // Then memory: the result's size against the caller's limit.
  if (options.max_faces != 0 && c.faces > options.max_faces)
    throw error(error_category::invalid_input,
                cellforge::detail::cat(
                    "loop_subdivide: ", std::to_string(options.levels), " levels would make ",
                    std::to_string(c.faces), " faces (about ", std::to_string(c.faces * 80 / 1'000'000),
                    " MB), more than loop_subdivision_options::max_faces (",
                    std::to_string(options.max_faces), "); ask for fewer levels or raise the limit"));
  const std::vector<dl::attribute_job> jobs = dl::resolve_attributes(mesh, options.interpolate);

  // Loop's masks are convex combinations, so checking the input once covers every level;
  // the bound keeps a sum of up to 2^32 neighbours finite.
  for (std::size_t v = 0; v < pts.vector().size(); ++v) {
    if (mesh.is_removed(vertex_handle(static_cast<std::uint32_t>(v)))) continue;
    const P& p = pts.vector()[v];
    for (std::size_t i = 0; i < 3; ++i) {
      const double x = static_cast<double>(coord(p, i));
      if (!(std::abs(x) <= 1e290))
        throw error(error_category::invalid_input,
                    cellforge::detail::cat(
                        "loop_subdivide: vertex ", std::to_string(v), " has coordinate ", std::to_string(x),
                        (std::isfinite(x) ? " (beyond ±1e290, too large to subdivide)" : " (not finite)")));
    }
  }

  // Garbage collection renumbers faces, so with garbage the faces are checked here, by
  // their current handles; otherwise the split checks them as it goes.
  if (mesh.has_garbage()) {
    const std::vector<dl::record>& he = access::records(mesh);
    for (face_handle f : mesh.faces()) {
      const std::uint32_t h = mesh.halfedge(f).idx();
      if (const std::size_t n = dl::face_size(detail::span_of(he), h, he.size()); n != 3)
        dl::not_a_triangle(f.idx(), n, he.size());
    }
    mesh.garbage_collection();  // every check passed: from here on the mesh changes
  }
  std::vector<std::uint32_t> boundary_edges;
  boundary_edges.reserve(mesh.num_boundary_edges());
  for (halfedge_handle h : mesh.unlinked_halfedges()) boundary_edges.push_back(h.idx() >> 1);

  bool finished = true;  // vertex anchors, rings and the unlinked table match the records
  try {
    for (int level = 0; level < options.levels; ++level) {
      const detail::stopwatch t0;
      std::vector<dl::record>& he = access::records(mesh);
      const auto nv = static_cast<std::uint32_t>(mesh.vertices_size());
      const std::size_t ne = he.size() / 2, nf = access::face_anchors(mesh).size();
      const std::size_t child_nv = nv + ne, child_ne = 2 * ne + 3 * nf, child_nf = 4 * nf;

      const bool last = level + 1 == options.levels;
      // A closed child needs no finish(): its vertex anchors are written here in closed form
      // (only at the last level: nothing in between reads them), the unlinked table stays
      // empty and split_faces counts the flipped edges.
      const bool closed = boundary_edges.empty();

      // Topology: throws (naming the face) before the mesh changes.
      std::vector<dl::record> child_he;  // split_faces sizes it (2 * child_ne records)
      std::vector<std::uint32_t> child_anchors;
      detail::reserve_large(child_anchors, child_nf);
      child_anchors.resize(child_nf);
      std::vector<std::uint32_t> child_vertex_anchors;
      if (closed && last) {
        // Parent entries are kept for isolated vertices (npos) and overwritten for the rest.
        detail::reserve_large(child_vertex_anchors, child_nv);
        child_vertex_anchors = access::vertex_anchors(mesh);
        child_vertex_anchors.resize(child_nv);
        dl::write_edge_vertex_anchors(nv, static_cast<std::uint32_t>(ne), child_vertex_anchors.data());
      }
      const std::size_t child_flipped =
          dl::split_faces(he, access::face_anchors(mesh), nv, child_he, child_anchors,
                          closed && last ? child_vertex_anchors.data() : nullptr);

      // Geometry, in double precision, from the parent. The masks store the edge points in
      // order (nv + e for e = 0, 1, …) and then the vertex points, so the edge points are
      // appended rather than written over a zeroed array.
      std::vector<glm::dvec3> child_points;
      detail::reserve_large(child_points, child_nv);
      child_points.resize(nv);
      const std::vector<P>& parent_points = pts.vector();
      const dl::mask_stats stats = dl::apply_masks<glm::dvec3>(
          he, nv, boundary_edges, params, [&](std::uint32_t v) { return to_dvec3(parent_points[v]); },
          [&](std::uint32_t i, const glm::dvec3& p) {
            if (i < nv)
              child_points[i] = p;
            else
              child_points.push_back(p);
          });
      if (child_points.size() != child_nv)  // the masks' order changed: a bug, not bad input
        throw error(error_category::invalid_input,
                    "loop_subdivide: internal error: edge points out of order");
      result.fixed_vertices += stats.fixed_vertices;
      for (const dl::attribute_job& job : jobs)
        dl::subdivide_attribute(job, detail::span_of(he), nv, child_nv, detail::span_of(boundary_edges),
                                params);

      // Commit: nothing below throws except on allocation failure.
      finished = false;
      if constexpr (std::is_same_v<P, glm::dvec3>) {
        pts.vector().swap(child_points);
      } else {
        std::vector<P>& out = pts.vector();
        out.clear();  // rebuilt by push_back: P need not be default-constructible
        out.reserve(child_nv);
        for (std::size_t i = 0; i < child_nv; ++i) out.push_back(from_dvec3<P>(child_points[i]));
      }
      he.swap(child_he);
      access::face_anchors(mesh).swap(child_anchors);
      if (closed && last) access::vertex_anchors(mesh).swap(child_vertex_anchors);
      // Half-edge, edge and face properties restart from their defaults: their elements are new.
      access::halfedge_properties(mesh).resize(0);
      access::edge_properties(mesh).resize(0);
      access::face_properties(mesh).resize(0);
      access::resize(mesh, child_nv, child_ne, child_nf);
      dl::split_boundary(boundary_edges);
      if (last && closed) {
        access::finish_closed(mesh, child_flipped);
        finished = true;
      } else if (last) {
        // Splitting faces of a valid mesh keeps every fan as it was: no need to re-check them.
        access::finish(mesh, {}, access::fan_check::trust);
        finished = true;
      }
      result.level_ms.push_back(t0.ms());
    }
  } catch (...) {
    if (!finished)
      access::finish(mesh, {}, access::fan_check::trust);  // leave the last completed level valid
    throw;
  }

  result.vertices_after = mesh.num_vertices();
  result.edges_after = mesh.num_edges();
  result.faces_after = mesh.num_faces();
  result.boundary_edges_after = mesh.num_boundary_edges();
  result.flipped_edges_after = mesh.num_flipped_edges();
  for (const double ms : result.level_ms) result.milliseconds += ms;
  return result;
}

/// Returns a subdivided copy of `mesh` (which is left unchanged); see loop_subdivide.
/// O(input size + output size).
template <Point3 P>
surface_mesh<P> loop_subdivided(const surface_mesh<P>& mesh, const loop_subdivision_options& options = {},
                                loop_subdivision_result* result = nullptr) {
  surface_mesh<P> copy = mesh;
  loop_subdivision_result r = loop_subdivide(copy, options);
  if (result) *result = std::move(r);
  return copy;
}

}  // namespace cellforge
