// SPDX-License-Identifier: MIT
// Bad wireframes: each gives a clear cellforge::error or a documented diagnostic, never a hang
// or a silently wrong complex.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "cellforge/cells/validate.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"
#include "cells_fixtures.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace wireframe_bad_input_tests {

using namespace cellforge;
using namespace cellforge::samples;

namespace {

using wire = wireframe<glm::dvec3>;

/// wireframe_to_cells(w, options) ends with status budget, no cells, a reason holding `fragment`
/// and naming `option`, the reason among the diagnostics.
void expect_budget(const wire& w, const std::string& fragment, const std::string& option,
                   const wireframe_options& options) {
  const auto r = wireframe_to_cells(w, options);
  CHECK(r.status == solid_status::budget);
  CHECK_FALSE(r.complete);
  CHECK(r.cells.num_faces() == 0);
  CHECK_MESSAGE(r.status_reason.find(fragment) != std::string::npos, r.status_reason);
  CHECK_MESSAGE(r.status_reason.find(option) != std::string::npos, r.status_reason);
  CHECK(std::find(r.diagnostics.begin(), r.diagnostics.end(), r.status_reason) != r.diagnostics.end());
}

// The error category and a fragment of its message.
void expect_error(const wire& w, error_category category, const std::string& fragment,
                  const wireframe_options& options = {}) {
  try {
    (void)wireframe_to_cells(w, options);
    FAIL("no error; expected: " << fragment);
  } catch (const error& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(e.category() == category);
    CHECK(what.find(fragment) != std::string::npos);
  }
}

// Whether a stage report (or the whole result) has a diagnostic containing fragment.
template <class Report>
bool has_note(const Report& r, const std::string& fragment) {
  for (const auto& d : r.diagnostics)
    if (d.find(fragment) != std::string::npos) return true;
  return false;
}

wire complete_graph(std::size_t n) {
  wire w;
  // Points on the moment curve: no four coplanar, so only triangles are planar circuits.
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) + 1.0;
    w.points.push_back({t, t * t, t * t * t});
  }
  for (std::uint32_t a = 0; a < n; ++a)
    for (std::uint32_t b = a + 1; b < n; ++b) w.edges.push_back({a, b});
  return w;
}

}  // namespace

TEST_CASE("bad input: errors") {
  wire empty;
  expect_error(empty, error_category::invalid_input, "no edges");
  wire points_only;
  points_only.points = {{0, 0, 0}, {1, 0, 0}};
  expect_error(points_only, error_category::invalid_input, "no edges");

  wire one;
  one.points = {{0, 0, 0}, {1, 0, 0}};
  one.edges = {{0, 1}};
  expect_error(one, error_category::topology, "no edge lies on a circuit");

  wire tree = one;  // a star: dangling edges only
  tree.points.push_back({0, 1, 0});
  tree.points.push_back({0, 0, 1});
  tree.edges.push_back({0, 2});
  tree.edges.push_back({0, 3});
  expect_error(tree, error_category::topology, "no edge lies on a circuit");

  wire nan = sample_cube().wire;
  nan.points[3].y = std::numeric_limits<double>::quiet_NaN();
  expect_error(nan, error_category::invalid_input, "vertex 3 has a NaN or infinite coordinate");
  wire inf = sample_cube().wire;
  inf.points[5].z = std::numeric_limits<double>::infinity();
  expect_error(inf, error_category::invalid_input, "vertex 5 has a NaN or infinite coordinate");

  wire range = sample_cube().wire;
  range.edges.push_back({2, 99});
  expect_error(range, error_category::invalid_input, "refers to vertex 99");

  wire all_zero;
  all_zero.points = {{1, 1, 1}, {1, 1, 1}};
  all_zero.edges = {{0, 1}};
  expect_error(all_zero, error_category::invalid_input, "zero length");

  // A skew quadrilateral is a circuit but not a face.
  wire skew;
  skew.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.3}, {0, 1, 0}};
  skew.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  expect_error(skew, error_category::topology,
               "no face: none of the cycles of the 4 edges on cycles lies in a plane");
  wireframe_options bfs;
  bfs.trace.kind = tracer_kind::seed_bfs;
  expect_error(skew, error_category::topology, "skew cycles only", bfs);

  // Strict reading turns notes into errors.
  wireframe_options strict;
  strict.read.strict = true;
  wire dup = sample_cube().wire;
  dup.edges.push_back({dup.edges[0][1], dup.edges[0][0]});
  expect_error(dup, error_category::invalid_input, "duplicates edge 0", strict);
  wire dangling = sample_cube().wire;
  dangling.points.push_back({5, 5, 5});
  dangling.edges.push_back({0, 8});
  expect_error(dangling, error_category::invalid_input, "dangling", strict);
}

TEST_CASE("bad input: every stage's work budget ends the call with status budget, naming the option") {
  // read_vertices: the merge search's first cell visits spend a budget of 1; the graph stays empty.
  wireframe_read_options read;
  read.work_budget = 1;
  const auto stopped = read_vertices(sample_cube().wire, read);
  CHECK_FALSE(stopped.complete);
  CHECK(stopped.graph.num_edges() == 0);
  CHECK(stopped.work > 1);
  REQUIRE_FALSE(stopped.diagnostics.empty());
  CHECK(stopped.diagnostics.back().find("read_vertices: work budget of 1 steps exhausted") !=
        std::string::npos);
  wireframe_options o;
  o.read.work_budget = 1;
  expect_budget(sample_cube().wire, "read_vertices: work budget of 1 steps",
                "wireframe_read_options::work_budget", o);
  // reduce_faces: the face-sum search (the seed's tracer only) stops; the verdicts so far stand.
  wireframe_options sums;
  sums.trace.kind = tracer_kind::seed_bfs;
  const auto full = wireframe_to_cells(sample_cube().wire, sums);
  REQUIRE(full.reduction.work > 2);
  sums.reduction.work_budget = 2;
  expect_budget(sample_cube().wire, "reduce_faces: work budget of 2 steps", "reduction_options::work_budget",
                sums);
  const auto g = read_vertices(sample_cube().wire).graph;
  trace_options bfs_trace;
  bfs_trace.kind = tracer_kind::seed_bfs;
  const auto candidates = unique_circuits(g, trace_circuits(g, bfs_trace).faces).faces;
  reduction_options small;
  small.work_budget = 2;
  const auto reduced = reduce_faces(g, candidates, small);
  CHECK_FALSE(reduced.complete);
  CHECK(reduced.quality.size() == candidates.size());
  CHECK(reduced.work > 2);
  // The extra stage's retrace: the seed's search with a budget that stops the retrace only.
  wireframe_options retrace = sums;
  retrace.reduction.work_budget = wireframe_options{}.reduction.work_budget;
  retrace.extra.retrace.work_budget = 1;
  const auto prism = wireframe_to_cells(sample_prism(40).wire, retrace);
  CHECK(prism.status == solid_status::budget);
  CHECK_FALSE(prism.complete);
  CHECK_FALSE(prism.extra.complete);
  CHECK(prism.status_reason.find("trace_circuits: work budget of 1 steps exhausted") != std::string::npos);
}

TEST_CASE("bad input: K12 and the work budget") {
  // The planar tracer is polynomial and the seed's pruning closes a triangle on every second
  // edge, so K12 finishes under the default budget with either tracer; whatever faces survive
  // the crossing rule form a valid complex (or none is found). A small budget stops both.
  wireframe_options bfs;
  bfs.trace.kind = tracer_kind::seed_bfs;
  for (const auto& options : {wireframe_options{}, bfs}) {
    try {
      const auto r = wireframe_to_cells(complete_graph(12), options);
      CHECK(validate(r.cells).ok());
      CHECK(r.trace.work < options.trace.work_budget);
    } catch (const error& e) {
      CHECK(e.category() == error_category::topology);
    }
  }
  const auto g = read_vertices(complete_graph(12)).graph;
  CHECK(trace_circuits(g).faces.size() == 220);
  bfs.trace.work_budget = 1000;
  expect_budget(complete_graph(12), "trace_circuits: work budget of 1000", "trace_options::work_budget", bfs);
  wireframe_options tiny;
  tiny.trace.work_budget = 10;
  expect_budget(sample_cube().wire, "trace_circuits: work budget of 10", "trace_options::work_budget", tiny);
  // The reading rule's rounds and the crossing rounds are budgeted too. Out of its budget the
  // reading rule returns what it decided so far (the house's square kept, undecided), flagged.
  wireframe_options rounds;
  rounds.volume.work_budget = 5;
  const auto house = wireframe_to_cells(sample_house().wire, rounds);
  CHECK_FALSE(house.volume.complete);
  CHECK(house.status == solid_status::budget);
  CHECK(house.unforced.size() == 1);
  CHECK(validate(house.cells).ok());
  wireframe_options crossing;
  crossing.arrangement.work_budget = 20;
  expect_budget(sample_octahedron().wire, "arrange_faces: work budget of 20",
                "arrangement_options::work_budget", crossing);
  // The seed's search misses a 40-gon prism's caps (shorter circuits prune them); extra face
  // processing (seed section 4.6) adds them back from the planar tracer.
  bfs.trace.work_budget = wireframe_options{}.trace.work_budget;
  const auto prism = wireframe_to_cells(sample_prism(40).wire, bfs);
  CHECK(prism.extra.added == 2);
  CHECK(same_faces(sample_prism(40).faces, prism.input.faces));
}

TEST_CASE("bad input: read_vertices stays linear and defined far from the origin and at tiny scales") {
  // A unit tetrahedron beside three cubes of side 1e-8: the median edge is tiny, and the
  // tetrahedron's edges once walked 1e8 grid cells each (a hang); the cell count overflowed.
  sample_model m = sample_tetrahedron();
  for (int k = 0; k < 3; ++k)
    m = disjoint_union(m, sample_cube({1e-8, 1e-8, 1e-8}), {2.0 + k, 0, 0}, "tetra and tiny cubes");
  wireframe_read_options exact;
  exact.merge = tolerance{0.0};  // keep the tiny cubes' corners apart
  const auto r = read_vertices(m.wire, exact);
  CHECK(r.graph.num_edges() == m.wire.edges.size());
  CHECK(r.split_edges == 0);
  // A small budget now stops the same searches, flagged, with a diagnostic naming the stage.
  wireframe_read_options tight = exact;
  tight.work_budget = 50;
  const auto stopped = read_vertices(m.wire, tight);
  CHECK_FALSE(stopped.complete);
  CHECK(stopped.graph.num_edges() == 0);
  REQUIRE_FALSE(stopped.diagnostics.empty());
  CHECK(stopped.diagnostics.back().find("read_vertices: work budget of 50") != std::string::npos);
  // A cube 1e12 from the origin with a T-junction: grid keys stay in range (UBSan), the
  // split is still found, and the complex is the cube's.
  sample_model far = transformed(split_edge(sample_cube(), 0, {0.5}), glm::dmat3(1.0), {1e12, -1e12, 1e12});
  far.wire.edges.push_back(
      {far.wire.edges[far.wire.edges.size() - 2][0], far.wire.edges.back()[1]});  // the whole edge again
  const auto fr = read_vertices(far.wire);
  CHECK(fr.split_edges >= 1);
  const auto cells = wireframe_to_cells(far.wire);
  CHECK(cells.cells.num_volumes() == 1);
  CHECK(validate(cells.cells).ok());
}

TEST_CASE("bad input: models beyond what a double can measure are named as such") {
  for (const double scale : {1e-300, 1e-60, 1e60, 1e300}) {
    CAPTURE(scale);
    expect_error(transformed(sample_cube(), glm::dmat3(scale), {0, 0, 0}).wire, error_category::invalid_input,
                 "scale the model into that range");
  }
  // Just inside the range the cube is read as a cube.
  for (const double scale : {1e-45, 1e45}) {
    CAPTURE(scale);
    CHECK(wireframe_to_cells(transformed(sample_cube(), glm::dmat3(scale), {0, 0, 0}).wire)
              .cells.num_volumes() == 1);
  }
}

TEST_CASE("bad input: edges dropped because their cycles cross say so") {
  // A cube with both diagonals of one face: they cross inside the face, at no vertex.
  sample_model m = sample_cube();
  const auto& f = m.faces[0][0];
  m.wire.edges.push_back({f[0], f[2]});
  m.wire.edges.push_back({f[1], f[3]});
  try {
    const auto r = wireframe_to_cells(m.wire);
    CHECK(has_note(r, "edge 12 bounds no face (it crosses edge 13 between their ends)"));
  } catch (const error& e) {
    CHECK(std::string(e.what()).find("cross") != std::string::npos);
  }
}

TEST_CASE("bad input: 10^5 duplicate edges are counted, not listed") {
  sample_model m = sample_cube();
  const std::size_t copies = 100'000;
  for (std::size_t i = 0; i < copies; ++i) m.wire.edges.push_back(m.wire.edges[i % 12]);
  const auto r = wireframe_to_cells(m.wire);
  CHECK(r.read.duplicate_edges == copies);
  CHECK(r.read.diagnostics.size() < 20);
  CHECK(has_note(r.read, "99992 more duplicate edges dropped (100000 in all)"));
  CHECK(r.cells.num_volumes() == 1);
}

TEST_CASE("bad input: diagnostics, and the right complex anyway") {
  const sample_model cube = sample_cube();
  SUBCASE("duplicate and reversed edges") {
    wire w = cube.wire;
    w.edges.push_back(w.edges[3]);
    w.edges.push_back({w.edges[4][1], w.edges[4][0]});
    const auto r = wireframe_to_cells(w);
    CHECK(r.read.duplicate_edges == 2);
    CHECK(has_note(r.read, "duplicates edge 3"));
    CHECK(same_faces(cube.faces, r.input.faces));
  }
  SUBCASE("zero-length edge between two copies of a point") {
    wire w = cube.wire;
    w.points.push_back(w.points[0]);
    w.edges.push_back({0, 8});
    const auto r = wireframe_to_cells(w);
    CHECK(r.read.merged_points == 1);
    CHECK(r.read.zero_length_edges == 1);
    CHECK(r.input.faces.size() == 6);
    CHECK(r.input.volumes.size() == 1);
  }
  SUBCASE("points within tolerance are one vertex") {
    wire w = cube.wire;
    // Vertex 8 is vertex 1 moved by 1e-12 of the model; edge 0-1 is redrawn to it.
    w.points.push_back(w.points[1] + glm::dvec3(1e-12, 0, 0));
    for (auto& e : w.edges)
      for (auto& v : e)
        if (v == 1 && (&e - w.edges.data()) % 2 == 0) v = 8;
    const auto r = wireframe_to_cells(w);
    CHECK(r.read.merged_points == 1);
    CHECK(has_note(r.read, "merged"));
    CHECK(r.input.faces.size() == 6);
    CHECK(r.input.volumes.size() == 1);
    CHECK(validate(r.cells).ok());
  }
  SUBCASE("points just outside tolerance stay apart") {
    wire w = cube.wire;
    w.points.push_back(w.points[1] + glm::dvec3(1e-6, 0, 0));
    const auto r = read_vertices(w);
    CHECK(r.merged_points == 0);
  }
  SUBCASE("dangling edges and a tree hanging off the cube") {
    wire w = cube.wire;
    w.points.push_back({2, 2, 2});
    w.points.push_back({3, 2, 2});
    w.edges.push_back({6, 8});
    w.edges.push_back({8, 9});
    const auto r = wireframe_to_cells(w);
    CHECK(r.read.dangling.size() == 2);
    CHECK(has_note(r.read, "dangling"));
    CHECK(r.input.faces.size() == 6);
    CHECK(r.input.edges.size() == 12);
    wireframe_options keep;
    keep.keep_dangling = true;
    const auto k = wireframe_to_cells(w, keep);
    CHECK(k.input.edges.size() == 14);
    CHECK(k.input.points.size() == 10);
    // Kept dangling edges and their ends off the graph: still the complex of the input.
    CHECK(cells_fixtures::same_complex(k.cells, make_cell_complex(k.input)));
    // A tree hanging off a solid lies on no cycle: dropped (or kept) with a note, still a solid.
    CHECK(r.status == solid_status::solid);
    CHECK(k.status == solid_status::solid);
    CHECK(r.certificate.acyclic_input_edges.size() == 2);
    // The reason says so rather than "every input edge on a face".
    CHECK(
        r.status_reason.find("2 edges on no cycle, a dangling tree, left out; the first is input edge 12") !=
        std::string::npos);
  }
  SUBCASE("an isolated point and a stray polygon") {
    wire w = cube.wire;
    w.points.push_back({9, 9, 9});  // used by nothing
    const std::uint32_t b = static_cast<std::uint32_t>(w.points.size());
    for (const auto& p : {glm::dvec3(5, 0, 0), glm::dvec3(6, 0, 0), glm::dvec3(6, 1, 0)})
      w.points.push_back(p);
    w.edges.push_back({b, b + 1});
    w.edges.push_back({b + 1, b + 2});
    w.edges.push_back({b + 2, b});
    const auto r = wireframe_to_cells(w);
    CHECK(r.input.faces.size() == 6);
    CHECK(r.extra.free == 1);
    CHECK(has_note(r.extra, "free edge"));
    CHECK(r.input.points.size() == 8);
    // The lost triangle is named in the caller's labels, with why.
    REQUIRE(r.lost.size() == 1);
    CHECK(r.lost[0].loops[0].size() == 3);
    CHECK(*std::min_element(r.lost[0].loops[0].begin(), r.lost[0].loops[0].end()) == b);
    CHECK(r.lost[0].reason.find("bounds no volume") != std::string::npos);
    // The triangle's edges lie on a cycle but on no face: the answer is flagged, not a solid.
    CHECK(r.status == solid_status::not_a_solid);
    CHECK(r.status_reason == "input edges 12, 13, 14 lie on a cycle of the wireframe but on no face");
    CHECK(r.certificate.unused_input_edges == std::vector<std::uint32_t>{12, 13, 14});
  }
  SUBCASE("a skew quadrilateral next to a cube is not a face") {
    // (It is a separate object; its circuit is traced by the seed's search and rejected.)
    wire w = cube.wire;
    const std::uint32_t b = static_cast<std::uint32_t>(w.points.size());
    for (const auto& p :
         {glm::dvec3(3, 0, 0), glm::dvec3(4, 0, 0), glm::dvec3(4, 1, 0.5), glm::dvec3(3, 1, 0)})
      w.points.push_back(p);
    for (std::uint32_t i = 0; i < 4; ++i) w.edges.push_back({b + i, b + (i + 1) % 4});
    wireframe_options bfs;
    bfs.trace.kind = tracer_kind::seed_bfs;
    const auto r = wireframe_to_cells(w, bfs);
    CHECK(r.reduction.not_planar >= 1);
    CHECK(same_faces(cube.faces, r.input.faces));
  }
  SUBCASE("T-junctions and overlapping edges are split") {
    // A 1x1x1 box standing on a 2x1x1 box, drawn as two separate boxes: the small box's bottom
    // edges overlap the big box's top edges, and two of its corners lie inside them.
    wire w;
    auto box = [&](glm::dvec3 a, glm::dvec3 b) {
      const auto base = static_cast<std::uint32_t>(w.points.size());
      for (std::uint32_t i = 0; i < 8; ++i)
        w.points.push_back({i & 1 ? b.x : a.x, i & 2 ? b.y : a.y, i & 4 ? b.z : a.z});
      const std::uint32_t edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                          {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
      for (const auto& e : edges) w.edges.push_back({base + e[0], base + e[1]});
    };
    box({0, 0, 0}, {2, 1, 1});
    box({0, 0, 1}, {1, 1, 2});
    const auto r = wireframe_to_cells(w);
    CHECK(r.read.split_edges == 2);
    CHECK(has_note(r.read, "split"));
    CHECK(r.input.faces.size() == 12);
    CHECK(r.input.volumes.size() == 2);
    CHECK(validate(r.cells).ok());
    wireframe_options no_split;
    no_split.read.split_at_vertices = false;
    // Unsplit, the boxes' shared faces do not meet edge to edge: their circuits close no
    // volume, and they come back as faces only, saying so.
    const auto bad = wireframe_to_cells(w, no_split);
    CHECK(bad.cells.num_volumes() == 0);
    CHECK(bad.cells.num_faces() == 10);
    CHECK(has_note(bad, "10 planar faces that close no volume"));
    CHECK(bad.status == solid_status::not_a_solid);
    CHECK(r.status == solid_status::solid);
  }
  SUBCASE("close adjacent edges make no spurious faces or pyramids (seed ch. VIII)") {
    // A cube whose top face carries a vertex 1e-7 above its centre, joined to two corners:
    // the seed's flatness 0.9 accepts the near-flat triangles; exact planarity does not.
    wire w = cube.wire;
    const std::uint32_t c = static_cast<std::uint32_t>(w.points.size());
    w.points.push_back({0.5, 0.5, 1.0 + 1e-7});
    std::uint32_t top[2] = {0, 0};
    std::size_t n = 0;
    for (std::uint32_t v = 0; v < 8 && n < 2; ++v)
      if (w.points[v].z == 1.0 && (n == 0 || glm::length(w.points[v] - w.points[top[0]]) > 1.2)) top[n++] = v;
    w.edges.push_back({c, top[0]});
    w.edges.push_back({c, top[1]});
    // At the fixed default tolerance (1e-9 of the diagonal) the offset is shape.
    wireframe_options fixed;
    fixed.tolerance.automatic = false;
    const auto r = wireframe_to_cells(w, fixed);
    CHECK(r.input.volumes.size() == 1);
    CHECK(same_faces(cube.faces, r.input.faces));
    CHECK(r.diagnostics.size() == 2);  // the two near-flat edges bound no face and are reported
    CHECK(validate(r.cells).ok());
    // They lie on cycles of the wireframe but on no face: not a solid's wireframe, flagged.
    CHECK(r.status == solid_status::not_a_solid);
    CHECK(r.status_reason == "input edges 12, 13 lie on a cycle of the wireframe but on no face");
    // The automatic tolerance cannot tell a vertex 1e-7 off a face from a file of seven digits
    // (two of the eight 4-cycles off their planes, the rest exact, as in a decimal file where
    // two faces of a box carry noise): it reads the offset as noise, and the path across the
    // top as a seam splitting it in two. Still no near-flat triangle, no pyramid.
    const auto noisy = wireframe_to_cells(w);
    CHECK(noisy.input.volumes.size() == 1);
    CHECK(noisy.input.faces.size() == 7);
    for (const auto& f : noisy.input.faces) CHECK(f.loops[0].size() == 4);
    CHECK(validate(noisy.cells, noisy.check).ok());
    CHECK(noisy.status == solid_status::solid);
  }
}

TEST_CASE("circuits that close no volume come back as faces without volumes, with a diagnostic") {
  SUBCASE("a lone planar square: one face") {
    wire square;
    square.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    square.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
    const auto r = wireframe_to_cells(square);
    CHECK(has_note(r, "a single planar loop: one face, no volume"));
    REQUIRE(r.cells.num_faces() == 1);
    CHECK(r.cells.num_volumes() == 0);
    CHECK(r.cells.num_edges() == 4);
    CHECK(r.cells.face_volumes(cell_face(0)).empty());
    CHECK(r.lost.empty());
    const auto v = validate(r.cells);
    INFO(v.message);
    CHECK(v.ok());
    CHECK(r.cells.object_euler(cell_object(0)) == 1);  // a disc: V - E + F = 4 - 4 + 1
    CHECK(r.status == solid_status::not_a_solid);
    CHECK(r.status_reason == "an open surface: 4 edges lie on one face only");
    CHECK(r.certificate.ok());  // a valid 3DCL, but no solid
  }
  SUBCASE("a U channel (a bottom and two walls): three faces") {
    wire channel;
    channel.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 1}, {1, 0, 1}, {1, 1, 1}};
    channel.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {3, 5}, {4, 5}, {1, 6}, {2, 7}, {6, 7}};
    const auto r = wireframe_to_cells(channel);
    CHECK(has_note(r, "3 planar faces that close no volume"));
    CHECK(r.cells.num_faces() == 3);
    CHECK(r.cells.num_volumes() == 0);
    REQUIRE_VALID(r.cells);
    CHECK(r.cells.object_euler(cell_object(0)) == 1);  // a strip: 8 - 10 + 3
    CHECK(r.status == solid_status::not_a_solid);
    CHECK(r.status_reason == "an open surface: 8 edges lie on one face only");
  }
}

}  // namespace wireframe_bad_input_tests

namespace wireframe_bad_input_tests {

namespace {
/// A cap of three triangles about a valence-3 vertex v over the triangle a b c, and three
/// triangles hanging outwards from a b, b c, c a: an open surface whose rim a d b e c f is not
/// planar. Triangle a b c is a planar cycle of its edges that no edge needs while the outer
/// triangles are there; once they go for their free edges it would close a tetrahedron.
wire open_cap(glm::dvec3 shift = glm::dvec3(0.0)) {
  wire w;
  w.points = {{0, 0, 1},         {1, 0, 0},       {-0.5, 0.866, 0},  {-0.5, -0.866, 0},
              {0.75, 1.3, -0.3}, {-1.5, 0, -0.6}, {0.75, -1.3, -0.1}};
  for (auto& p : w.points) p += shift;
  // v = 0, a = 1, b = 2, c = 3, d = 4, e = 5, f = 6.
  w.edges = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {2, 3}, {3, 1}, {1, 4}, {4, 2}, {2, 5}, {5, 3}, {3, 6}, {6, 1}};
  return w;
}

/// The faces of r as sorted vertex sets in the caller's labels.
template <class Result>
std::vector<std::vector<std::uint32_t>> face_sets(const Result& r) {
  std::vector<std::vector<std::uint32_t>> out;
  for (const auto& f : r.input.faces) {
    std::vector<std::uint32_t> s;
    for (const auto& loop : f.loops)
      for (const auto v : loop) s.push_back(r.input_vertex[v]);
    std::sort(s.begin(), s.end());
    out.push_back(std::move(s));
  }
  std::sort(out.begin(), out.end());
  return out;
}
}  // namespace

TEST_CASE("open surfaces and faces that cross each other invent no volume") {
  SUBCASE("an open cap: its six triangles, no tetrahedron at its valence-3 vertex") {
    const wire w = open_cap();
    const auto r = wireframe_to_cells(w);
    CHECK(r.cells.num_volumes() == 0);
    const std::vector<std::vector<std::uint32_t>> mesh = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3},
                                                          {1, 2, 4}, {1, 3, 6}, {2, 3, 5}};
    CHECK(face_sets(r) == mesh);  // the base 1 2 3 is not among them
    CHECK(r.extra.open_edges.size() == 6);
    CHECK(r.extra.newly_needed == 1);
    CHECK(has_note(r, "not a closed solid: 6 edges lie on one face only"));
    CHECK(has_note(r, "no volume: the faces are the answer"));
    REQUIRE_VALID(r.cells);
    // The cascade alone, as before the rule: the base becomes needed and closes a tetrahedron.
    wireframe_options old;
    old.extra.drop_newly_needed = false;
    old.extra.drop_open_surfaces = false;
    CHECK(wireframe_to_cells(w, old).cells.num_volumes() == 1);
  }
  SUBCASE("a cube beside an open cap keeps its volume") {
    wire w = sample_cube().wire;
    const wire cap = open_cap(glm::dvec3(5, 0, 0));
    const auto base = static_cast<std::uint32_t>(w.points.size());
    w.points.insert(w.points.end(), cap.points.begin(), cap.points.end());
    for (const auto& e : cap.edges) w.edges.push_back({e[0] + base, e[1] + base});
    const auto r = wireframe_to_cells(w);
    CHECK(r.cells.num_volumes() == 1);
    CHECK(r.cells.num_faces() == 6);
    CHECK(r.lost.size() == 7);  // the cap's six triangles and its base, each with why
    CHECK(has_note(r, "volumes come only from the closed parts"));
    REQUIRE_VALID(r.cells);
  }
  SUBCASE("a tetrahedron pierced by a triangle: no volume, and the piercing is named") {
    wire w;
    w.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.2, 0.2, -0.5}, {0.2, 0.2, 0.3}, {2, 2, -0.2}};
    w.edges = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}, {4, 5}, {5, 6}, {6, 4}};
    const auto r = wireframe_to_cells(w);
    CHECK(r.cells.num_volumes() == 0);  // the tetrahedron is pierced: no solid of this input
    CHECK(r.cells.num_faces() == 4);    // its faces stay, without the volume
    CHECK(r.status == solid_status::not_a_solid);
    CHECK(r.status_reason.find("the input intersects itself: input edges 6, 7 pierce") == 0);
    CHECK(has_note(r, "pierced by an input edge"));
    CHECK(!r.arrangement.crossed.empty());
  }
}

}  // namespace wireframe_bad_input_tests
