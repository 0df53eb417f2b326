// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/halfedge/surface_mesh.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "cellforge/samples/skeletons.hpp"
#include "cellforge/tubes/detail/closed_build.hpp"
#include "cellforge/tubes/tube_mesh.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace tube_halfedges_tests {

using namespace cellforge;

// Record for record and anchor for anchor the same mesh.
bool same_records(const halfedge_mesh& a, const halfedge_mesh& b) {
  if (a.halfedges_size() != b.halfedges_size() || a.vertices_size() != b.vertices_size() ||
      a.faces_size() != b.faces_size())
    return false;
  for (std::uint32_t h = 0; h < a.halfedges_size(); ++h) {
    const auto &x = a.raw(halfedge_handle(h)), &y = b.raw(halfedge_handle(h));
    if (x.head != y.head || x.next != y.next || x.prev != y.prev || x.face != y.face) return false;
  }
  for (std::uint32_t v = 0; v < a.vertices_size(); ++v)
    if (a.raw_vertex_anchor(vertex_handle(v)) != b.raw_vertex_anchor(vertex_handle(v))) return false;
  for (std::uint32_t f = 0; f < a.faces_size(); ++f)
    if (a.halfedge(face_handle(f)) != b.halfedge(face_handle(f))) return false;
  return true;
}

// The faces of a CSR list (over num_vertices) linked into mesh by the tube mesher's linker, as
// make_tubes links them: true when they form a closed, consistently oriented surface; false,
// with no connectivity, otherwise (a vertex with two closed fans throws as build does).
bool link_closed(halfedge_mesh& mesh, std::size_t num_vertices, std::span<const std::uint32_t> offsets,
                 std::span<const std::uint32_t> fv) {
  if (offsets.empty() || offsets[0] != 0 || offsets.back() != fv.size()) return false;
  detail::tubes::closed_linker linker;
  for (std::size_t f = 0; f + 1 < offsets.size(); ++f) {
    if (offsets[f + 1] < offsets[f] + 3 || offsets[f + 1] > fv.size()) return false;
    if (!linker.add_face(fv.subspan(offsets[f], offsets[f + 1] - offsets[f]))) return false;
  }
  return linker.finish(mesh, num_vertices) != detail::tubes::closed_linker::npos;
}

TEST_CASE("tube half-edge link (tubes/detail/closed_build.hpp): build's mesh, or build's report") {
  const std::vector<std::uint32_t> offsets{0, 3, 6, 9, 12}, tetra{0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
  SUBCASE("a closed surface: the records build writes") {
    halfedge_mesh ours, built;
    REQUIRE(link_closed(ours, 4, offsets, tetra));
    built.build(4, offsets, tetra);
    CHECK(same_records(ours, built));
    CHECK(validate(ours).ok());
    CHECK(ours.is_closed());
    CHECK(ours.num_flipped_edges() == 0);
    // A cube of quads (mixed sizes are tested through the tube meshes below).
    const std::vector<std::uint32_t> qo{0, 4, 8, 12, 16, 20, 24},
        cube{0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7};
    halfedge_mesh q1, q2;
    REQUIRE(link_closed(q1, 8, qo, cube));
    q2.build(8, qo, cube);
    CHECK(same_records(q1, q2));
    CHECK(validate(q1).ok());
  }
  SUBCASE("not a closed oriented surface: false and no connectivity, for build to report") {
    halfedge_mesh open;
    CHECK_FALSE(link_closed(open, 4, std::span(offsets).first(4), std::span(tetra).first(9)));
    CHECK(open.halfedges_size() == 0);
    CHECK(open.faces_size() == 0);
    const build_report r = open.build(4, std::span(offsets).first(4), std::span(tetra).first(9));
    CHECK(r.boundary_edges == 3);
    std::vector<std::uint32_t> flipped = tetra;
    std::swap(flipped[1], flipped[2]);  // face 0 turned over
    halfedge_mesh f;
    CHECK_FALSE(link_closed(f, 4, offsets, flipped));
    std::vector<std::uint32_t> repeated = tetra;
    repeated[2] = 0;
    halfedge_mesh rep;
    CHECK_FALSE(link_closed(rep, 4, offsets, repeated));
    CHECK_THROWS_AS(rep.build(4, offsets, repeated), error);
    halfedge_mesh out_of_range;
    CHECK_FALSE(link_closed(out_of_range, 3, offsets, tetra));
  }
  SUBCASE("the linker as faces come: components counted, or every face given back in order") {
    // Two tetrahedra (vertices 0-3 and 4-7): two components.
    std::vector<std::uint32_t> two = tetra;
    for (const std::uint32_t v : tetra) two.push_back(v + 4);
    detail::tubes::closed_linker linker;
    for (std::size_t f = 0; f < 8; ++f) CHECK(linker.add_face(std::span(two).subspan(3 * f, 3)));
    CHECK(linker.num_faces() == 8);
    halfedge_mesh m;
    CHECK(linker.finish(m, 8) == 2);
    CHECK(validate(m).ok());
    CHECK(m.num_faces() == 8);
    CHECK(m.is_closed());
    // One more vertex than the faces use: an isolated vertex is a component of its own.
    detail::tubes::closed_linker with_isolated;
    for (std::size_t f = 0; f < 4; ++f) with_isolated.add_face(std::span(tetra).subspan(3 * f, 3));
    halfedge_mesh mi;
    CHECK(with_isolated.finish(mi, 5) == 2);
    CHECK(validate(mi).ok());
    // A face with a repeated vertex in the middle: linking stops there, and faces() gives back
    // all of them (those linked before, read back from their records, and those after).
    const std::vector<std::uint32_t> faces{0, 2, 1, 0, 1, 3, 1, 1, 2, 1, 2, 3, 0, 3, 2};
    detail::tubes::closed_linker failing;
    bool all = true;
    for (std::size_t f = 0; f < 5; ++f) all = failing.add_face(std::span(faces).subspan(3 * f, 3)) && all;
    CHECK_FALSE(all);
    CHECK(failing.num_faces() == 5);
    halfedge_mesh untouched;
    CHECK(failing.finish(untouched, 4) == detail::tubes::closed_linker::npos);
    CHECK(untouched.halfedges_size() == 0);
    std::vector<std::uint32_t> back_offsets, back;
    failing.faces(back_offsets, back);
    CHECK(back == faces);
    CHECK(back_offsets == std::vector<std::uint32_t>{0, 3, 6, 9, 12, 15});
    // An open surface: every face linked, but finish refuses, and the faces come back as given.
    detail::tubes::closed_linker open;
    for (std::size_t f = 0; f < 3; ++f) CHECK(open.add_face(std::span(tetra).subspan(3 * f, 3)));
    halfedge_mesh mo;
    CHECK(open.finish(mo, 4) == detail::tubes::closed_linker::npos);
    open.faces(back_offsets, back);
    CHECK(back == std::vector<std::uint32_t>(tetra.begin(), tetra.begin() + 9));
    // Too few vertices for the faces given.
    detail::tubes::closed_linker short_of_vertices;
    for (std::size_t f = 0; f < 4; ++f) short_of_vertices.add_face(std::span(tetra).subspan(3 * f, 3));
    halfedge_mesh ms;
    CHECK(short_of_vertices.finish(ms, 3) == detail::tubes::closed_linker::npos);
  }
  SUBCASE("tube meshes linked as made: the records build makes of the same faces") {
    // Each mesh's faces, read back in order (a face starts at the tail of its anchor
    // half-edge, as build anchors it), are built again by build: the same records, anchors and
    // numbering, on every kind of face the mesher makes (quads, hull triangles, caps, spheres,
    // square sections, extra hull points, junctions in Morton order). With Loop levels the
    // records are subdivision's own; those meshes are validated in test_tubes.cpp.
    struct named {
      std::string name;
      skeleton<glm::dvec3> s;
      tubes_options o;
    };
    std::vector<named> set;
    set.push_back({"tree", samples::random_tree(7, {.nodes = 300}), {}});
    set.push_back({"K5", samples::complete_graph(5), {}});
    set.push_back({"ring", samples::ring(9, 4.0), {}});
    set.push_back({"mobius ladder", samples::mobius_ladder(8), {}});
    set.push_back({"lattice, square sections", samples::lattice(4, 3, 2), {.sides = 4}});
    set.push_back({"K6, extra hull points", samples::complete_graph(6), {.junction_extra_points = 40}});
    skeleton<glm::dvec3> lone = samples::ring(5, 3.0);
    lone.points.push_back({20, 0, 0});
    lone.radii.push_back(0.7);
    set.push_back({"ring and an isolated node", lone, {.sides = 5}});
    for (const named& c : set) {
      INFO(c.name);
      const auto r = make_tubes(c.s, c.o);
      const halfedge_mesh& ours = r.mesh;
      std::vector<std::uint32_t> offsets{0}, fv;
      for (const face_handle f : ours.faces()) {
        const halfedge_handle first = ours.halfedge(f);
        halfedge_handle h = first;
        do {
          fv.push_back(ours.head(ours.prev(h)).idx());
          h = ours.next(h);
        } while (h != first);
        offsets.push_back(static_cast<std::uint32_t>(fv.size()));
      }
      halfedge_mesh built;
      built.build(ours.vertices_size(), offsets, fv);
      CHECK(same_records(ours, built));
      CHECK(validate(ours).ok());
      CHECK(r.genus == r.cycle_rank);
    }
  }
  SUBCASE("two closed fans at a vertex: build's error") {
    // Two tetrahedra sharing vertex 3.
    const std::vector<std::uint32_t> o{0, 3, 6, 9, 12, 15, 18, 21, 24},
        fv{0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 3, 5, 4, 3, 4, 6, 4, 5, 6, 3, 6, 5};
    halfedge_mesh m;
    CHECK_THROWS_WITH_AS(link_closed(m, 7, o, fv), doctest::Contains("vertex 3 form several closed fans"),
                         error);
  }
  SUBCASE("tube meshes: valid, closed, the caller's point type kept") {
    const skeleton<glm::dvec3> s = samples::lattice(3, 3, 3);
    skeleton<glm::vec3> sf;
    for (const glm::dvec3& p : s.points) sf.points.push_back(glm::vec3(p));
    sf.radii = s.radii;
    sf.edges = s.edges;
    const auto rd = make_tubes(s);
    const auto rf = make_tubes(sf);
    CHECK(validate(rd.mesh).ok());
    CHECK(validate(rf.mesh).ok());
    CHECK(same_records(rd.mesh, rf.mesh));
    CHECK(rd.genus == rd.cycle_rank);
    CHECK(rf.genus == rf.cycle_rank);
    const auto src = rf.mesh.get_face_property<tube_face_source>(tube_source_property_name);
    REQUIRE(src);
    CHECK(src.vector().size() == rf.mesh.num_faces());
  }
}

}  // namespace tube_halfedges_tests
