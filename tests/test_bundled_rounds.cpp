// SPDX-License-Identifier: MIT
// The bundled drawing of examples/sketch_rounds (examples/data/l_bracket_rounds.txt): it is the
// drawing round_prism_drawing makes of the L-bracket its comment describes, and reconstructs,
// from its text and from its SVG picture, to that bracket's two rounds and fillet.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>

#include "cellforge/io/drawing_pictures.hpp"
#include "cellforge/io/drawing_text.hpp"
#include "cellforge/io/svg_drawing.hpp"
#include "cellforge/samples/round_drawings.hpp"
#include "cellforge/sketch/arc_detection.hpp"
#include "cellforge/sketch/rounds.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace bundled_rounds_tests {

namespace {

/// The L-bracket as the data file's comment describes it.
cellforge::samples::sample_round_drawing l_bracket() {
  const std::vector<glm::dvec2> footprint = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}};
  // Vertical edges (kind 0) at corners 1 and 5 rounded, at the inner corner 3 filleted.
  const std::vector<std::array<double, 3>> blends = {{0, 1, 0.5}, {0, 5, 0.4}, {0, 3, 0.3}};
  const glm::dmat3 view(glm::rotate(glm::dmat4(1.0), glm::radians(55.0), glm::dvec3(1, 0, 0)) *
                        glm::rotate(glm::dmat4(1.0), glm::radians(-70.0), glm::dvec3(0, 0, 1)));
  return cellforge::samples::round_prism_drawing(footprint, 1.5, blends, view, "L-bracket", "L");
}

}  // namespace

TEST_CASE("bundled rounds: the L-bracket of sketch_rounds is the generated drawing and reconstructs") {
  // tests/data may not exist: go up lexically to the repository.
  const auto path = std::filesystem::path(CELLFORGE_TEST_DATA_DIR).parent_path().parent_path() / "examples" /
                    "data" / "l_bracket_rounds.txt";
  const auto d = cellforge::io::read_arc_drawing_text(path);
  const auto truth = l_bracket();
  REQUIRE(d.lines.points.size() == truth.drawing.lines.points.size());
  CHECK(d.lines.edges == truth.drawing.lines.edges);
  for (std::size_t j = 0; j < d.lines.points.size(); ++j)
    CHECK(glm::length(d.lines.points[j] - truth.drawing.lines.points[j]) < 1e-12);
  REQUIRE(d.arcs.size() == truth.drawing.arcs.size());
  for (std::size_t k = 0; k < d.arcs.size(); ++k) {
    CHECK(d.arcs[k].ends == truth.drawing.arcs[k].ends);
    for (const double u : {0.0, 0.25, 0.5, 0.75, 1.0})
      CHECK(glm::length(cellforge::arc_point(d.arcs[k].curve, u) -
                        cellforge::arc_point(truth.drawing.arcs[k].curve, u)) < 1e-9);
  }
  REQUIRE(truth.rounds.size() == 3);
  // From the text and from its SVG picture, read back.
  const auto pictured =
      cellforge::io::parse_svg_arc_drawing(cellforge::io::arc_drawing_svg_string(d)).drawing;
  for (const auto& drawing : {d, pictured}) {
    const auto r = cellforge::reconstruct_rounds(drawing);
    CHECK(r.skeleton.pairing.pairs.size() == 3);
    CHECK(r.skeleton.pairing.unpaired.empty());
    CHECK(r.skeleton.rounds == 2);
    CHECK(r.skeleton.fillets == 1);
    CHECK(r.consistent == 3);
    REQUIRE(r.rounds.size() == 3);
    // Each true blend is found, with its kind and its radius.
    for (const auto& t : truth.rounds) {
      const auto at = std::find_if(r.rounds.begin(), r.rounds.end(), [&](const cellforge::edge_round& e) {
        return std::abs(e.radius - t.radius) < 1e-9;
      });
      REQUIRE(at != r.rounds.end());
      CHECK(at->convex == t.convex);
      CHECK(at->kind == (t.convex ? cellforge::blend_kind::round : cellforge::blend_kind::fillet));
    }
    const auto mesh = cellforge::rounded_mesh(r);
    CHECK(mesh.strips == 3);
    CHECK(mesh.skipped == 0);
  }
  // With one arc taken away its partner is alone: the error names it and why.
  auto lone = d;
  lone.arcs.erase(lone.arcs.begin() + 1);
  CHECK_THROWS_WITH_AS(cellforge::reconstruct_rounds(lone), doctest::Contains("arc 0 (junctions"),
                       cellforge::error);
  CHECK_THROWS_WITH_AS(cellforge::reconstruct_rounds(lone), doctest::Contains("has no partner"),
                       cellforge::error);
  // The cause leads, in the drawing's numbering; the skeleton's dangling junction (the skeleton
  // renumbers them: its 6 is the drawing's 10 once arc 3 is gone) is mapped back (issue 35).
  auto renumbered = d;
  renumbered.arcs.erase(renumbered.arcs.begin() + 3);
  try {
    (void)cellforge::reconstruct_rounds(renumbered);
    FAIL("an unpaired arc was read");
  } catch (const cellforge::error& e) {
    const std::string m = e.what();
    CHECK(m.rfind("reconstruct_rounds: arc 2 (junctions 10 to 11) has no partner: ", 0) == 0);
    CHECK(m.find("without a partner an arc cannot be a blend, so the skeleton is not a readable drawing: "
                 "junction 6 is on one edge only") != std::string::npos);
    CHECK(m.find("(skeleton junction 6 is junction 10 of the drawing)") != std::string::npos);
  }
}

TEST_CASE("bundled rounds: the L-bracket drawn as sampled strokes, its arcs found by detect_arcs") {
  // The drawing as a pen gives it: each line a stroke of its two ends, each arc a polyline of
  // 24 samples. detect_arcs reads the strokes back into lines and arcs; an arc_drawing is built
  // from the pieces (docs/formats.md, "Arcs in SVG", sampled strokes) and reconstructed.
  const auto truth = l_bracket();
  const auto& d = truth.drawing;
  std::vector<std::vector<glm::dvec2>> strokes;
  for (const auto& [a, b] : d.lines.edges) strokes.push_back({d.lines.points[a], d.lines.points[b]});
  for (const auto& a : d.arcs) strokes.push_back(cellforge::sample_arc(a.curve, 24));
  const auto found = cellforge::detect_arcs(strokes);
  CHECK(found.num_arcs == d.arcs.size());
  CHECK(found.num_lines == d.lines.edges.size());
  // A junction per piece end, ends closer than 1e-9 of the size taken as one.
  cellforge::arc_drawing<glm::dvec2> read;
  const auto junction = [&](glm::dvec2 p) {
    for (std::uint32_t j = 0; j < read.lines.points.size(); ++j)
      if (glm::length(read.lines.points[j] - p) <= 1e-9 * found.drawing_size) return j;
    read.lines.points.push_back(p);
    return static_cast<std::uint32_t>(read.lines.points.size() - 1);
  };
  for (const auto& piece : found.pieces) {
    const std::array<std::uint32_t, 2> ends{junction(piece.from), junction(piece.to)};
    if (piece.kind == cellforge::stroke_piece_kind::line)
      read.lines.edges.push_back(ends);
    else
      read.arcs.push_back({ends, piece.arc});
  }
  CHECK(read.lines.points.size() == d.lines.points.size());
  CHECK(cellforge::validate(read).ok());
  const auto r = cellforge::reconstruct_rounds(read);
  CHECK(r.skeleton.rounds == 2);
  CHECK(r.skeleton.fillets == 1);
  REQUIRE(r.rounds.size() == 3);
  for (const auto& t : truth.rounds)
    CHECK(std::any_of(r.rounds.begin(), r.rounds.end(),
                      [&](const cellforge::edge_round& e) { return std::abs(e.radius - t.radius) < 1e-6; }));
}

}  // namespace bundled_rounds_tests
