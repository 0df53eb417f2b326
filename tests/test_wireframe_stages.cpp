// SPDX-License-Identifier: MIT
// The stages of the wireframe pipeline one at a time (seed 000 §4.1-4.8).

#include <doctest/doctest.h>

#include <algorithm>

#include "cellforge/core/detail/work_counter.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/wireframe/cell_list.hpp"
#include "cellforge/wireframe/circuit_tracer.hpp"
#include "cellforge/wireframe/extra_faces.hpp"
#include "cellforge/wireframe/face_arrangement.hpp"
#include "cellforge/wireframe/face_reduction.hpp"
#include "cellforge/wireframe/read_vertices.hpp"
#include "cellforge/wireframe/unique_circuits.hpp"
#include "cellforge/wireframe/volume_finder.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace wireframe_stages_tests {

using namespace cellforge;
using namespace cellforge::samples;

TEST_CASE("stages: reading labels vertices with incident edges and directions (4.1)") {
  const auto r = read_vertices(sample_cube().wire);
  const wire_graph& g = r.graph;
  REQUIRE(g.num_vertices() == 8);
  REQUIRE(g.num_edges() == 12);
  for (std::uint32_t v = 0; v < 8; ++v) {
    CHECK(g.degree(v) == 3);
    for (const auto& in : g.around(v)) {
      CHECK(g.edges[in.edge][in.outgoing ? 0 : 1] == v);
      CHECK(g.edges[in.edge][in.outgoing ? 1 : 0] == in.other);
      CHECK(g.find_edge(v, in.other) == in.edge);
    }
  }
  CHECK(g.find_edge(0, 0) == no_index);
  CHECK(g.size == doctest::Approx(std::sqrt(3.0)));
}

TEST_CASE("stages: the planar tracer finds each face once, holes included (4.2)") {
  const auto cube = read_vertices(sample_cube().wire).graph;
  const auto t = trace_circuits(cube);
  CHECK(t.faces.size() == 6);
  CHECK(t.planes == 6);
  const auto frame = read_vertices(sample_frame().wire).graph;
  const auto tf = trace_circuits(frame);
  CHECK(tf.holes == 2);  // top and bottom are faces with a hole
  std::size_t with_hole = 0, fillers = 0;
  for (const auto& f : tf.faces) {
    with_hole += f.loops.size() == 2;
    fillers += f.fills_hole;
    CHECK(f.area > 0.0);
  }
  CHECK(with_hole == 2);
  CHECK(fillers == 2);
  // A collinear chain does not split a face: the split-edge box still has 6 faces.
  const auto split = read_vertices(sample_split_edges().wire).graph;
  CHECK(trace_circuits(split).faces.size() == 6);
}

TEST_CASE("stages: the seed's search finds every face from each of its edges; unique keeps one (4.2, 4.3)") {
  const auto g = read_vertices(sample_cube().wire).graph;
  trace_options o;
  o.kind = tracer_kind::seed_bfs;
  const auto t = trace_circuits(g, o);
  CHECK(t.circuits == 24);  // 12 edges × 2 faces each
  const auto u = unique_circuits(g, t.faces);
  CHECK(u.faces.size() == 6);
  CHECK(u.duplicates == 18);
  for (const auto& f : u.faces) {
    // Canonical order: the smallest label first, then its smaller neighbour.
    CHECK(f.loops[0][0] == *std::min_element(f.loops[0].begin(), f.loops[0].end()));
    CHECK(f.loops[0][1] < f.loops[0].back());
  }
}

TEST_CASE("stages: reduction marks face sums and non-planar circuits (4.4)") {
  // Two cubes: the seed's search also finds the 2x1 rectangles, sums of two squares.
  const auto g = read_vertices(sample_two_cubes().wire).graph;
  trace_options o;
  o.kind = tracer_kind::seed_bfs;
  const auto u = unique_circuits(g, trace_circuits(g, o).faces);
  const auto red = reduce_faces(g, u.faces);
  CHECK(red.remaining == 11);
  CHECK(u.faces.size() - red.remaining == red.face_sums + red.not_planar + red.not_flat);
  for (std::size_t i = 0; i < u.faces.size(); ++i) {
    CHECK(red.quality[i].area > 0.0);
    if (red.quality[i].usable) CHECK(red.quality[i].flatness == doctest::Approx(1.0));
  }
}

TEST_CASE("stages: ranks and chains (4.5)") {
  const auto g = read_vertices(sample_split_edges().wire).graph;
  const auto u = unique_circuits(g, trace_circuits(g).faces);
  const auto red = reduce_faces(g, u.faces);
  const auto a = arrange_faces(g, u.faces, red);
  CHECK(a.chains == 7);  // seven box edges are split into chains
  for (std::uint32_t e = 0; e < g.num_edges(); ++e) CHECK(a.edge_rank[e] == 2);
  CHECK(a.rank_violations == 0);
  CHECK(a.selected.size() == 6);
}

namespace {

// The face stages (4.2 - 4.5) of a sample, up to the candidates and the arrangement's choice.
struct arranged {
  wire_graph graph;
  std::vector<wire_face> candidates;
  arrangement_result arrangement;
};
arranged arrange(const sample_model& m) {
  arranged a{read_vertices(m.wire).graph, {}, {}};
  a.candidates = unique_circuits(a.graph, trace_circuits(a.graph).faces).faces;
  a.arrangement = arrange_faces(a.graph, a.candidates, reduce_faces(a.graph, a.candidates));
  return a;
}

}  // namespace

TEST_CASE("stages: extra face processing puts back a missed face and keeps the true ones (4.6)") {
  const sample_model m = sample_two_cubes();
  const arranged a = arrange(m);
  const auto all = extra_faces(a.graph, a.candidates, a.arrangement.selected);
  CHECK(all.added == 0);
  CHECK(all.overlapping == 0);
  CHECK(all.free == 0);
  CHECK(same_faces(m.faces, all.faces));
  // Drop one selected face: its edges now lack a face, and the retrace finds it again.
  std::vector<std::uint32_t> missing = a.arrangement.selected;
  missing.erase(missing.begin() + 3);
  const auto repaired = extra_faces(a.graph, a.candidates, missing);
  CHECK(repaired.added == 1);
  CHECK(same_faces(m.faces, repaired.faces));
  // Without add_missed the hole stays; with remove_free the faces around it, which now have an
  // edge no other face shares, go too, until every edge left is shared.
  extra_face_options keep;
  keep.add_missed = false;
  keep.remove_free = false;
  CHECK(extra_faces(a.graph, a.candidates, missing, keep).faces.size() == m.faces.size() - 1);
  keep.remove_free = true;
  // The two cubes are one surface (they share edges), open at the hole: none of it bounds a
  // volume, so what the free-face removal leaves (the other cube) goes too.
  const auto open = extra_faces(a.graph, a.candidates, missing, keep);
  // Its open edges are edges of the missing face (the one it shares with the wall keeps two faces).
  const wire_face& gone = a.candidates[a.arrangement.selected[3]];
  REQUIRE(!open.open_edges.empty());
  for (const auto e : open.open_edges) CHECK(cellforge::detail::walk_direction(a.graph, gone, e) != 0);
  CHECK(open.faces.empty());
  CHECK(open.free + open.newly_needed + open.open_surface == m.faces.size() - 1);
  CHECK(open.open_surface > 0);
  keep.drop_open_surfaces = false;
  const auto trimmed = extra_faces(a.graph, a.candidates, missing, keep);
  CHECK(trimmed.free > 0);
  CHECK(trimmed.open_surface == 0);
  CHECK(trimmed.faces.size() == m.faces.size() - 1 - trimmed.free - trimmed.newly_needed);
  CHECK(!trimmed.faces.empty());
  std::vector<int> uses(a.graph.num_edges(), 0);
  for (const wire_face& f : trimmed.faces)
    for (const auto& loop : f.loops)
      for (std::size_t k = 0; k < loop.size(); ++k)
        ++uses[a.graph.find_edge(loop[k], loop[(k + 1) % loop.size()])];
  for (const int u : uses) CHECK(u != 1);
}

TEST_CASE("stages: the volume finder splits two cubes at their shared wall, drops a house's square (4.7)") {
  const std::string disjoint = sample_disjoint_solids().name, house = sample_house().name;
  for (const sample_model& m : {sample_two_cubes(), sample_house(), sample_disjoint_solids()}) {
    const std::string name = m.name;
    INFO(name);
    const arranged a = arrange(m);
    const auto faces = extra_faces(a.graph, a.candidates, a.arrangement.selected).faces;
    const auto v = find_volumes(a.graph, faces);
    CHECK(v.objects == (name == disjoint ? 2u : 1u));
    // The house's square is a candidate no edge needs: dropped, and named as an alternative.
    CHECK(v.dropped.size() == (name == house ? 1u : 0u));
    CHECK(v.alternatives.size() == v.dropped.size());
    std::vector<wire_face> kept;
    std::vector<std::uint32_t> index(faces.size(), no_index);
    for (std::uint32_t i = 0; i < faces.size(); ++i)
      if (v.face_kept[i]) index[i] = static_cast<std::uint32_t>(kept.size()), kept.push_back(faces[i]);
    // The graph numbers vertices spatially; the truth is in the caller's labels.
    for (auto& f : kept)
      for (auto& loop : f.loops)
        for (auto& x : loop) x = a.graph.input_vertex[x];
    auto volumes = v.volumes;
    for (auto& vol : volumes)
      for (auto& [f, sign] : vol) f = index[f];
    CHECK(same_volumes(m.faces, m.volumes, kept, volumes));
    CHECK(v.unforced.size() == m.unforced_faces);
    // §4.9 on its own: the cell list holds the kept faces and the volumes, every edge on a face.
    const auto list = assemble_cell_list(m.wire, a.graph, faces, v, {});
    CHECK(list.input.faces.size() == kept.size());
    CHECK(list.input.volumes.size() == v.volumes.size());
    CHECK(list.input.edges.size() == m.wire.edges.size());
    // Every kept face bounds a volume on at least one side; a shared wall bounds two.
    REQUIRE(v.face_volumes.size() == faces.size());
    std::size_t shared = 0;
    for (std::uint32_t i = 0; i < faces.size(); ++i) {
      const auto& sides = v.face_volumes[i];
      CHECK((sides[0] != no_index || sides[1] != no_index) == (v.face_kept[i] != 0));
      shared += sides[0] != no_index && sides[1] != no_index;
    }
    std::size_t uses = 0;
    for (const auto& vol : v.volumes) uses += vol.size();
    CHECK(uses == kept.size() + shared);
    // keep_walls keeps the square as a wall between box and roof; merging takes it out again.
    volume_options walls;
    walls.reading = face_reading::keep_walls;
    const auto w = find_volumes(a.graph, faces, walls);
    CHECK(w.volumes.size() == v.volumes.size() + v.dropped.size());
    CHECK(w.unforced.size() == v.dropped.size());
    walls.merge_unforced = true;
    const auto merged = find_volumes(a.graph, faces, walls);
    CHECK(merged.volumes.size() == v.volumes.size());
    CHECK(merged.merged.size() == v.dropped.size());
  }
}

TEST_CASE("stages: volumes and relations agree with the cell complex's rotation order (4.7, 4.8)") {
  for (const auto& m : {sample_house(), sample_grid(2, 2, 2), sample_frame(), sample_stepped_block()}) {
    const std::string name = m.name;
    INFO(name);
    const auto r = wireframe_to_cells(m.wire);
    // Edges of the result are the graph's edges in the caller's order here (clean input: the
    // graph's edge e is the output's read_order[e]); its faces are the kept ones of the face
    // stages, in order (the house's square is not one).
    const wire_graph& g = r.read.graph;
    REQUIRE(r.input.edges.size() == g.num_edges());
    REQUIRE(g.read_order.size() == g.num_edges());
    std::vector<std::uint32_t> graph_edge(g.num_edges(), no_index);
    for (std::uint32_t e = 0; e < g.num_edges(); ++e) graph_edge[g.read_order[e]] = e;
    std::vector<std::uint32_t> output_face(r.extra.faces.size(), no_index);
    for (std::uint32_t i = 0, k = 0; i < r.extra.faces.size(); ++i)
      if (r.volume.face_kept[i]) output_face[i] = k++;
    for (std::uint32_t e = 0; e < r.input.edges.size(); ++e) {
      REQUIRE(graph_edge[e] != no_index);
      CHECK(r.input_edge[e] == g.input_edge[graph_edge[e]]);
      auto ours = r.relations.edges[graph_edge[e]].faces;
      for (auto& f : ours) f = output_face[f];
      std::vector<std::uint32_t> theirs;
      for (const auto& of : r.cells.edge_faces(cell_edge(e))) theirs.push_back(of.handle.idx());
      REQUIRE(ours.size() == theirs.size());
      // Same cyclic order (the starting face may differ).
      const auto it = std::find(theirs.begin(), theirs.end(), ours.empty() ? 0u : ours[0]);
      REQUIRE((ours.empty() || it != theirs.end()));
      if (ours.empty()) continue;
      std::rotate(theirs.begin(), it, theirs.end());
      CHECK(ours == theirs);
    }
    // Outward pointers point out of each volume: their signs follow the volume's face signs.
    for (std::size_t v = 0; v < r.relations.outward.size(); ++v)
      CHECK(r.relations.outward[v].size() == r.volume.volumes[v].size());
  }
}

TEST_CASE("work_counter: the stages' budget counter, and a stage that ran out says so") {
  using cellforge::detail::work_counter;
  // 0 (unlimited) and automatic never stop a search; a limit stops it at the first step past it.
  for (const std::uint64_t open : {cellforge::work_budget::unlimited, cellforge::work_budget::automatic}) {
    work_counter c{open, 0, "trace_circuits", "trace_options::work_budget"};
    CHECK_NOTHROW(c.spend(1'000'000));
    CHECK(c.used == 1'000'000);
  }
  work_counter c{10, 0, "trace_circuits", "trace_options::work_budget"};
  CHECK_NOTHROW(c.spend(10));
  cellforge::stage_report r;
  r.diagnostics.push_back("an earlier note");
  try {
    c.spend();
    FAIL("the 11th step of a budget of 10 did not stop the search");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::budget);
    CHECK(std::string(e.what()).find("trace_circuits: work budget of 10 steps exhausted; raise "
                                     "trace_options::work_budget") != std::string::npos);
    cellforge::detail::stop_at_budget(r, c, e);
  }
  CHECK_FALSE(r.complete);
  CHECK(r.work == 11);
  REQUIRE(r.diagnostics.size() == 2);
  CHECK(cellforge::detail::budget_note(r, "none") == r.diagnostics.back());
  CHECK(cellforge::detail::budget_note(cellforge::stage_report{}, "none") == "none");
  // Any other error passes through stop_at_budget untouched.
  cellforge::stage_report other;
  CHECK_THROWS_AS(
      [&] {
        try {
          throw cellforge::error(cellforge::error_category::invalid_input, "not a budget");
        } catch (const cellforge::error& e) {
          cellforge::detail::stop_at_budget(other, c, e);
        }
      }(),
      cellforge::error);
  CHECK(other.complete);
  CHECK(other.diagnostics.empty());
}

}  // namespace wireframe_stages_tests
