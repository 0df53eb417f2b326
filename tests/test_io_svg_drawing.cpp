// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <unistd.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/io/drawing_pictures.hpp"
#include "cellforge/io/drawing_text.hpp"
#include "cellforge/io/svg_drawing.hpp"
#include "cellforge/samples/drawings.hpp"
#include "cellforge/samples/round_drawings.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace io_svg_drawing_tests {

namespace io = cellforge::io;
using cellforge::line_drawing;
using glm::dvec2;

namespace {

std::string svg(const std::string& body) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\">\n" + body + "\n</svg>\n";
}

io::svg_drawing_result<dvec2> read(const std::string& text, const io::svg_drawing_options& o = {}) {
  return io::parse_svg_drawing(text, "d.svg", o);
}

/// The edges of a drawing as sets of two positions (rounded to 1e-9), independent of numbering.
std::set<std::array<double, 4>> edge_set(const line_drawing<dvec2>& d) {
  const auto r = [](double v) { return std::round(v * 1e9) / 1e9 + 0.0; };
  std::set<std::array<double, 4>> out;
  for (const auto& [a, b] : d.edges) {
    dvec2 p = d.points[a], q = d.points[b];
    if (std::make_pair(q.x, q.y) < std::make_pair(p.x, p.y)) std::swap(p, q);
    out.insert({r(p.x), r(p.y), r(q.x), r(q.y)});
  }
  return out;
}

std::set<std::array<double, 4>> edges_of(std::initializer_list<std::array<double, 4>> list) {
  line_drawing<dvec2> d;
  for (const auto& e : list) {
    const auto n = static_cast<std::uint32_t>(d.points.size());
    d.points.push_back({e[0], e[1]});
    d.points.push_back({e[2], e[3]});
    d.edges.push_back({n, n + 1});
  }
  return edge_set(d);
}

/// The message and line of the io error parsing `text` throws.
std::pair<std::string, std::uint64_t> failure(const std::string& text,
                                              const io::svg_drawing_options& o = {}) {
  try {
    (void)read(text, o);
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(e.where().file == "d.svg");
    return {e.message(), e.where().line};
  }
  FAIL("no error for: " << text);
  return {};
}

}  // namespace

TEST_CASE("svg drawing: every stroke element, y flipped") {
  const auto r =
      read(svg("<line x1=\"0\" y1=\"0\" x2=\"10\" y2=\"0\"/>\n"
               "<polyline points=\"10,0 10,10 0,10\"/>\n"
               "<polygon points=\"20 0, 30 0 30 10\"/>\n"
               "<rect x=\"40\" y=\"0\" width=\"10\" height=\"5px\"/>\n"
               "<path d=\"M0 10 L0 0\"/>"));
  CHECK(r.elements == 5);
  CHECK(r.segments == 1 + 2 + 3 + 4 + 1);
  CHECK(r.drawing.points.size() == 4 + 3 + 4);
  CHECK(edge_set(r.drawing) == edges_of({{0, 0, 10, 0},
                                         {10, 0, 10, -10},
                                         {0, -10, 10, -10},
                                         {0, -10, 0, 0},
                                         {20, 0, 30, 0},
                                         {30, -10, 30, 0},
                                         {20, 0, 30, -10},
                                         {40, 0, 50, 0},
                                         {50, -5, 50, 0},
                                         {40, -5, 50, -5},
                                         {40, -5, 40, 0}}));
  // Junctions in order of first appearance: the line's ends first, y up.
  CHECK(r.drawing.points[0] == dvec2(0, 0));
  CHECK(r.drawing.points[1] == dvec2(10, 0));
  CHECK(r.drawing.points[2] == dvec2(10, -10));
  CHECK(r.snapped == 0);
  CHECK(r.dropped_zero_length == 0);
}

TEST_CASE("svg drawing: path commands, relative forms, implicit repeats, number syntax") {
  // M with repeated pairs (line-tos), relative m/l/h/v/z, "10-5" as two numbers, ".5", "1e1".
  auto r = read(svg("<path d=\"M0,0 10,0 10-5 m-10 5 h-1e1 v.5e1 l10-5z\"/>"));
  CHECK(edge_set(r.drawing) ==
        edges_of({{0, 0, 10, 0}, {10, 0, 10, 5}, {-10, 0, 0, 0}, {-10, -5, -10, 0}, {-10, -5, 0, 0}}));
  CHECK(r.segments == 5);  // the z is already back at (0, 0): no segment
  CHECK(r.dropped_zero_length == 0);
  // A stroke shorter than the snap distance is dropped.
  r = read(svg("<path d=\"M0 0 H100 V100 Z M50 10 l0.01 0.01\"/>"));
  CHECK(r.segments == 4);
  CHECK(r.dropped_zero_length == 1);
  CHECK(r.drawing.points.size() == 3);
  // A leading m is absolute; H/V absolute; Z then a new subpath from the start point.
  r = read(svg("<path d=\"m 5 5 H 15 V 15 Z L 5 25\"/>"));
  CHECK(edge_set(r.drawing) ==
        edges_of({{5, -5, 15, -5}, {15, -15, 15, -5}, {5, -5, 15, -15}, {5, -25, 5, -5}}));
  // Commas and no separators at all: "M1.5.5" is 1.5, .5.
  r = read(svg("<path d=\"M1.5.5L3.5.5 3.5,2.5+1.5,2.5Z\"/>"));
  CHECK(r.drawing.points.size() == 4);
  CHECK(r.drawing.points[0] == dvec2(1.5, -0.5));
  CHECK(r.drawing.edges.size() == 4);
}

TEST_CASE("svg drawing: transforms on elements and groups, composed as SVG says") {
  const auto ends = [](const std::string& body) {
    const auto r = read(svg(body), {.snap_tolerance = 0});
    REQUIRE(r.drawing.edges.size() == 1);
    return std::array<dvec2, 2>{r.drawing.points[r.drawing.edges[0][0]],
                                r.drawing.points[r.drawing.edges[0][1]]};
  };
  const auto near = [](dvec2 a, dvec2 b) { return glm::length(a - b) < 1e-12; };
  auto e =
      ends("<g transform=\"translate(100,0)\"><g transform=\"scale(2)\"><line x1=\"1\" x2=\"2\"/></g></g>");
  CHECK(e[0] == dvec2(102, 0));
  CHECK(e[1] == dvec2(104, 0));
  e = ends("<line transform=\"translate(100,0) scale(2)\" x1=\"1\" x2=\"2\"/>");
  CHECK(e[0] == dvec2(102, 0));
  e = ends("<line transform=\"scale(2),translate(100)\" x1=\"1\" x2=\"2\"/>");
  CHECK(e[0] == dvec2(202, 0));
  e = ends("<line transform=\"rotate(90 5 5)\" x1=\"6\" y1=\"5\" x2=\"7\" y2=\"5\"/>");
  CHECK(near(e[0], {5, -6}));
  CHECK(near(e[1], {5, -7}));
  e = ends("<line transform=\"matrix(1 0 0 1 3 4) skewX(45)\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"2\"/>");
  CHECK(near(e[0], {4, -5}));
  CHECK(near(e[1], {5, -6}));
  e = ends(
      "<g transform=\"skewY(45)\"><line transform=\"scale(1 3)\" x1=\"1\" y1=\"0\" x2=\"1\" y2=\"1\"/></g>");
  CHECK(near(e[0], {1, -1}));
  CHECK(near(e[1], {1, -4}));
}

TEST_CASE("svg drawing: snapping, chains placed at their mean, duplicates merged") {
  // A 100 x 100 square whose corners miss by up to 0.05 (snap distance 1e-3 x 141 = 0.14).
  const auto r =
      read(svg("<line x1=\"0\" y1=\"0\" x2=\"100\" y2=\"0.05\"/>\n"
               "<line x1=\"100\" y1=\"0\" x2=\"100.03\" y2=\"100\"/>\n"
               "<line x1=\"100\" y1=\"100\" x2=\"0\" y2=\"100\"/>\n"
               "<line x1=\"0.04\" y1=\"100\" x2=\"0\" y2=\"0\"/>\n"
               "<line x1=\"100\" y1=\"100\" x2=\"0\" y2=\"100.01\"/>"));  // the top edge drawn twice
  CHECK(r.drawing.points.size() == 4);
  CHECK(r.drawing.edges.size() == 4);
  CHECK(r.merged_duplicates == 1);
  CHECK(r.snapped > 0);
  CHECK(cellforge::validate(r.drawing).ok());
  // Corner (100, 0): the mean of (100, 0.05) and (100, 0), y flipped.
  CHECK(glm::length(r.drawing.points[1] - dvec2(100, -0.025)) < 1e-12);

  // A chain of ends 0.1 apart: (0,0), (0.1,0), (0.2,0) are one junction at (0.1, 0), though the
  // first and last are farther apart than the snap distance; a diagnostic says so.
  const auto c =
      read(svg("<line x1=\"0\" y1=\"0\" x2=\"100\" y2=\"0\"/>\n"
               "<line x1=\"0.1\" y1=\"0\" x2=\"0\" y2=\"100\"/>\n"
               "<line x1=\"0.2\" y1=\"0\" x2=\"100\" y2=\"100\"/>\n"
               "<line x1=\"100\" y1=\"0\" x2=\"100\" y2=\"100\"/>\n"
               "<line x1=\"100\" y1=\"100\" x2=\"0\" y2=\"100\"/>"));
  CHECK(c.drawing.points.size() == 4);
  CHECK(glm::length(c.drawing.points[0] - dvec2(0.1, 0)) < 1e-12);
  CHECK(c.drawing.edges.size() == 5);
  REQUIRE(!c.diagnostics.empty());
  CHECK(c.diagnostics[0].find("chain of 3") != std::string::npos);
  // Snap tolerance 0: only equal points meet.
  CHECK(read(svg("<line x1=\"0\" y1=\"0\" x2=\"1\" y2=\"0\"/><line x1=\"1\" y1=\"1e-9\" x2=\"0\" y2=\"0\"/>"),
             {.snap_tolerance = 0})
            .drawing.points.size() == 3);
}

TEST_CASE("svg drawing: a stroke end on another stroke's interior splits it") {
  // A T drawn as Inkscape users do: the stem ends on the bar (within the snap distance).
  const auto r =
      read(svg("<line x1=\"0\" y1=\"0\" x2=\"100\" y2=\"0\"/>\n"
               "<line x1=\"40\" y1=\"0.05\" x2=\"40\" y2=\"50\"/>\n"
               "<line x1=\"70\" y1=\"-0.02\" x2=\"70\" y2=\"50\"/>"));
  CHECK(r.split_at_junctions == 2);
  CHECK(r.drawing.points.size() == 6);
  CHECK(r.drawing.edges.size() == 5);
  // The bar is 0 -> (40, -0.05) -> (70, 0.02) -> 100: the junctions stay where the stems end.
  CHECK(edge_set(r.drawing) == edges_of({{0, 0, 40, -0.05},
                                         {40, -0.05, 70, 0.02},
                                         {70, 0.02, 100, 0},
                                         {40, -50, 40, -0.05},
                                         {70, -50, 70, 0.02}}));
  // Off: three edges, the T-junction left for validate(drawing) to report.
  const auto off =
      read(svg("<line x1=\"0\" y1=\"0\" x2=\"100\" y2=\"0\"/><line x1=\"40\" y1=\"0\" x2=\"40\" y2=\"50\"/>"),
           {.split_at_junctions = false});
  CHECK(off.drawing.edges.size() == 2);
  CHECK(cellforge::validate(off.drawing).defect == cellforge::drawing_defect::junction_on_edge);
  // Overlapping collinear strokes become one chain: the shorter one splits the longer.
  const auto o =
      read(svg("<line x1=\"0\" y1=\"0\" x2=\"100\" y2=\"0\"/><line x1=\"0\" y1=\"0\" x2=\"60\" y2=\"0\"/>"));
  CHECK(o.drawing.edges.size() == 2);
  CHECK(o.merged_duplicates == 1);
  // Crossing strokes (hidden lines) are not split.
  const auto x = read(
      svg("<line x1=\"0\" y1=\"0\" x2=\"100\" y2=\"100\"/><line x1=\"0\" y1=\"100\" x2=\"100\" y2=\"0\"/>"));
  CHECK(x.drawing.edges.size() == 2);
  CHECK(x.split_at_junctions == 0);
}

TEST_CASE("svg drawing: curves refused with their line, or skipped when asked") {
  const std::string text =
      svg("<line x1=\"0\" y1=\"0\" x2=\"10\" y2=\"0\"/>\n"
          "<circle cx=\"5\" cy=\"5\" r=\"2\"/>\n"
          "<path d=\"M10 0 C 10 5, 5 10, 0 10 L 0 0\"/>\n"
          "<path d=\"M20 0 a5 5 0 01 10 0 l 0 10\"/>\n"
          "<rect x=\"0\" y=\"0\" width=\"3\" height=\"3\" rx=\"1\"/>");
  const auto [message, line] = failure(text);
  CHECK(line == 3);
  CHECK(message.find("curves are not read yet: <circle>") != std::string::npos);
  CHECK(message.find("elliptical arcs are read by parse_svg_arc_drawing") != std::string::npos);
  CHECK(failure(svg("<path d=\"M0 0 L1 1\n Q 2 2 3 3\"/>")).second == 3);
  const auto r = read(text, {.curves = io::svg_curves::skip});
  CHECK(r.skipped_curves == 4);
  // The paths go on from the curves' ends: (0, 10) -> (0, 0) and (30, 0) -> (30, 10).
  CHECK(edge_set(r.drawing) == edges_of({{0, 0, 10, 0}, {0, -10, 0, 0}, {30, -10, 30, 0}}));
}

TEST_CASE("svg drawing: every error names its line and what was expected") {
  const auto check = [](const std::string& text, std::uint64_t line, const std::string& part) {
    const auto result = failure(text);
    CHECK_MESSAGE(result.second == line, result.first);
    CHECK_MESSAGE(result.first.find(part) != std::string::npos, result.first);
  };
  check("", 1, "no <svg> element");
  check("<?xml version=\"1.0\"?>\n<html></html>", 2, "expected the root element <svg>, found <html>");
  check(svg("<g>\n<line/>\n</svg>"), 4, "expected </g> closing <g> of line 2, found </svg>");
  check("<svg>\n<g>\n", 3, "the file ends inside <g> of line 2");
  check(svg("<!-- a comment\n that never ends"), 2, "the file ends inside a comment");
  check(svg("<line x1=\"0\"\n y1=0/>"), 3, "expected the value of y1 in quotes");
  check(svg("<line x1=\"0\" y1\n/>"), 3, "expected '=' after the attribute y1");
  check(svg("<line x1=\"abc\"/>"), 2, "attribute x1: expected a number, found 'abc'");
  check(svg("<line x1=\"3mm\"/>"), 2, "unexpected 'mm' after the number (only user units and px are read)");
  check(svg("<line x1=\"1e999\"/>"), 2, "the number '1e999' is out of range");
  check(svg("<polyline points=\"0 0 1 1 2\"/>"), 2, "an odd number of coordinates");
  check(svg("<path d=\"L 1 1\"/>"), 2, "the data must start with M or m");
  check(svg("<path d=\"M 1 1 L 2\"/>"), 2, "path command 'L' expects 2 numbers, found the end of the value");
  check(svg("<path d=\"M 1 1 X 2\"/>"), 2, "unknown command 'X");
  check(svg("<path d=\"M 1 1 L 2 2 z 3 3\"/>"), 2, "expected a command after 'z'");
  check(svg("<path\n d=\"M 1 1 L 2 2 # 3\"/>"), 3, "expected a command letter, found '#'");
  check(svg("<g transform=\"turn(3)\"><line/></g>"), 2, "unknown function 'turn(3)'");
  check(svg("<g transform=\"rotate(1 2)\"></g>"), 2, "transform rotate takes 1 or 3 numbers, found 2");
  check(svg("<g transform=\"scale(1 2\"></g>"), 2, "transform scale: expected a number or ')'");
  check(svg("<rect width=\"-1\" height=\"2\"/>"), 2, "a negative width or height");
  check(svg("<line x2=\"1e308\" transform=\"scale(10)\"/>"), 2, "overflows to infinity");
  check("<svg></svg>\n</g>", 2, "closing tag </g> without an open element");
  check("<svg></svg>\n<svg></svg>", 2, "content after the root element ends");
  CHECK_THROWS_WITH_AS(io::read_svg_drawing("/nonexistent/x.svg"), doctest::Contains("/nonexistent/x.svg"),
                       cellforge::error);
  CHECK_THROWS_AS(read(svg(""), {.snap_tolerance = -1}), cellforge::error);
}

TEST_CASE("svg drawing: an Inkscape file (namespaces, metadata, a layer with a transform)") {
  const std::string text = R"svg(<?xml version="1.0" encoding="UTF-8" standalone="no"?>
<!-- Created with Inkscape (http://www.inkscape.org/) -->
<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" "http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd" [
  <!ENTITY ns_svg "http://www.w3.org/2000/svg">
]>
<svg
   width="210mm"
   height="297mm"
   viewBox="0 0 210 297"
   version="1.1"
   id="svg5"
   inkscape:version="1.2.2 (b0a8486541, 2022-12-01)"
   sodipodi:docname="box.svg"
   xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
   xmlns:sodipodi="http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd"
   xmlns="http://www.w3.org/2000/svg"
   xmlns:svg="http://www.w3.org/2000/svg">
  <sodipodi:namedview
     id="namedview7"
     pagecolor="#ffffff"
     inkscape:zoom="0.7"><inkscape:grid type="xygrid" id="grid1"/></sodipodi:namedview>
  <defs id="defs2"><line x1="0" y1="0" x2="999" y2="999"/></defs>
  <style>line { stroke: black; } /* a < b */</style>
  <metadata><rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#"/></metadata>
  <g
     inkscape:label="Layer 1"
     inkscape:groupmode="layer"
     id="layer1"
     transform="translate(-10,20)">
    <path
       style="fill:none;stroke:#000000;stroke-width:0.264583px"
       d="m 10,10 h 50 v 30 H 10 Z"
       id="path1"
       sodipodi:nodetypes="ccccc" />
    <path style="fill:none;stroke:#000000" d="M 10.02,10.03 30,0 l 50,0 -20,10" id="path2" />
    <text x="0" y="0"><tspan>label</tspan></text>
  </g>
  <g inkscape:label="Hidden" inkscape:groupmode="layer" style="display:none">
    <line x1="500" y1="500" x2="600" y2="600"/>
  </g>
</svg>
)svg";
  const auto r = read(text);
  CHECK(r.elements == 2);
  // The rectangle (4 edges) and the roof (3 edges) sharing corners (10,10) and (60,10).
  CHECK(r.drawing.points.size() == 6);
  CHECK(r.drawing.edges.size() == 7);
  // (10, 10) twice and (10.02, 10.03) snapped to their mean, moved by the layer, y flipped.
  CHECK(glm::length(r.drawing.points[0] - dvec2(0.02 / 3, -30.01)) < 1e-12);
  CHECK(r.snapped == 3);
  CHECK(r.skipped_elements >= 5);
  CHECK(std::any_of(r.diagnostics.begin(), r.diagnostics.end(), [](const std::string& d) {
    return d.find("d.svg:38: <g> is hidden") != std::string::npos;
  }));
  CHECK(cellforge::validate(r.drawing).defect == cellforge::drawing_defect::none);
}

TEST_CASE("drawing svg: the picture reads back to the same junctions and edges") {
  for (const auto& model : {cellforge::samples::sample_L(), cellforge::samples::sample_house(),
                            cellforge::samples::sample_frame()}) {
    const auto s = cellforge::samples::generic_drawing(model, 11, "any", 0.01);
    const std::string text =
        io::drawing_svg_string(s.drawing, s.loops, {.labels = true, .title = s.name + " <faces & all>"});
    CHECK(text.find("data-cellforge=\"faces\"") != std::string::npos);
    CHECK(text.find("&lt;faces &amp; all&gt;") != std::string::npos);
    const auto r = read(text);
    CHECK(r.drawing.points.size() == s.drawing.points.size());
    CHECK(edge_set(r.drawing) == edge_set(s.drawing));
    CHECK(r.snapped == 0);
    CHECK(r.split_at_junctions == 0);
    // Junctions exactly where they were.
    for (const auto& p : r.drawing.points)
      CHECK(std::find(s.drawing.points.begin(), s.drawing.points.end(), p) != s.drawing.points.end());
    // Without skipping the annotations, the junction dots are circles: refused.
    CHECK_THROWS_AS(read(text, {.skip_annotations = false}), cellforge::error);
  }
  // Distinct hues for the faces.
  const auto s = cellforge::samples::generic_drawing(cellforge::samples::sample_L(), 11, "any", 0.01);
  const std::string text = io::drawing_svg_string(s.drawing, s.loops);
  std::set<std::string> fills;
  for (std::size_t at = text.find("<path fill=\""); at != std::string::npos;
       at = text.find("<path fill=\"", at + 1))
    fills.insert(text.substr(at + 12, 7));
  CHECK(fills.size() == s.loops.size());
  const auto path =
      std::filesystem::temp_directory_path() / ("cellforge_drawing_" + std::to_string(getpid()) + ".svg");
  io::write_drawing_svg(path, s.drawing, s.loops);
  CHECK(io::read_svg_drawing(path).drawing.edges.size() == s.drawing.edges.size());
  std::filesystem::remove(path);
  CHECK_THROWS_AS(io::drawing_svg_string(s.drawing, {{0, 1, 999}}), cellforge::error);
}

TEST_CASE("svg drawing: other point types, left-out elements and their diagnostics") {
  const std::string text =
      svg("<line x1=\"0\" y1=\"0\" x2=\"10\" y2=\"0\"/>\n"
          "<use href=\"#a\"/>\n"
          "<rect width=\"0\" height=\"4\"/>\n"
          "<g display=\"none\"><line x1=\"0\" y1=\"5\" x2=\"10\" y2=\"5\"/></g>\n"
          "<polyline points=\"3 3\"/>");
  const auto f = io::parse_svg_drawing<glm::vec2>(text, "d.svg");
  static_assert(std::is_base_of_v<cellforge::stage_report, std::remove_cvref_t<decltype(f)>>);
  CHECK(f.milliseconds > 0);
  CHECK(f.drawing.points == std::vector<glm::vec2>{{0, 0}, {10, 0}});
  CHECK(f.skipped_elements == 2);
  REQUIRE(f.diagnostics.size() == 4);
  CHECK(f.diagnostics[0] == "d.svg:3: <use> is not a stroke or a group: left out");
  CHECK(f.diagnostics[1] == "d.svg:4: <rect> of zero width or height draws nothing");
  CHECK(f.diagnostics[2] == "d.svg:5: <g> is hidden (display none): left out");
  CHECK(f.diagnostics[3].starts_with("d.svg:6: a polyline or polygon with fewer than 2 points"));
  const auto shown = io::parse_svg_drawing<std::array<double, 2>>(text, "d.svg", {.skip_hidden = false});
  CHECK(shown.drawing.edges.size() == 2);
  CHECK(shown.drawing.points[3] == std::array<double, 2>{10, -5});
  // Nothing to read: an empty drawing and a diagnostic, not an error.
  const auto none = read(svg("<text>only words</text>"));
  CHECK(none.drawing.points.empty());
  CHECK(none.diagnostics.back().find("no straight stroke") != std::string::npos);
}

TEST_CASE("svg drawing: a 10,000-edge lattice through a picture and back") {
  line_drawing<dvec2> d;
  const std::uint32_t n = 70;
  for (std::uint32_t i = 0; i <= n; ++i)
    for (std::uint32_t j = 0; j <= n; ++j) d.points.push_back({j * 1.5, i * 0.75});
  for (std::uint32_t i = 0; i <= n; ++i)
    for (std::uint32_t j = 0; j < n; ++j) {
      d.edges.push_back({i * (n + 1) + j, i * (n + 1) + j + 1});
      d.edges.push_back({j * (n + 1) + i, (j + 1) * (n + 1) + i});
    }
  const std::string text = io::drawing_svg_string(d);
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = read(text);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  MESSAGE("SVG with " << d.edges.size() << " lines read in " << ms << " ms");
  CHECK(r.drawing.points.size() == d.points.size());
  CHECK(edge_set(r.drawing) == edge_set(d));
  CHECK(r.snapped == 0);
}

TEST_CASE("svg drawing: the bundled stepped normalon reads to its text twin") {
  // tests/data may not exist: go up lexically to the repository.
  const auto dir =
      std::filesystem::path(CELLFORGE_TEST_DATA_DIR).parent_path().parent_path() / "examples" / "data";
  const auto svg_read = io::read_svg_drawing(dir / "stepped_normalon.svg");
  const auto text = io::read_drawing_text(dir / "stepped_normalon.txt");
  REQUIRE(svg_read.drawing.points.size() == text.points.size());
  // Each junction read is within 0.05 (the hand-drawn misses) of its twin; the edges agree.
  std::vector<std::uint32_t> twin;
  for (const auto& p : svg_read.drawing.points) {
    std::uint32_t best = 0;
    for (std::uint32_t j = 1; j < text.points.size(); ++j)
      if (glm::length(text.points[j] - p) < glm::length(text.points[best] - p)) best = j;
    CHECK(glm::length(text.points[best] - p) < 0.05);
    twin.push_back(best);
  }
  std::set<std::array<std::uint32_t, 2>> read_edges, text_edges;
  for (const auto& [a, b] : svg_read.drawing.edges)
    read_edges.insert({std::min(twin[a], twin[b]), std::max(twin[a], twin[b])});
  for (const auto& [a, b] : text.edges) text_edges.insert({std::min(a, b), std::max(a, b)});
  CHECK(read_edges.size() == svg_read.drawing.edges.size());
  CHECK(read_edges == text_edges);
  CHECK(svg_read.elements == 9);
  CHECK(svg_read.merged_duplicates == 0);
  CHECK(svg_read.split_at_junctions == 0);
  CHECK(cellforge::validate(text).ok());
  CHECK(cellforge::validate(svg_read.drawing).ok());
  CHECK(svg_read.snapped > 0);  // drawn by hand: ends meet within the snap distance
}

namespace {

using arc_drawing2 = cellforge::arc_drawing<dvec2>;

io::svg_arc_drawing_result<dvec2> read_arcs(const std::string& text, const io::svg_drawing_options& o = {}) {
  return io::parse_svg_arc_drawing(text, "d.svg", o);
}

/// The junction of `d` at p (within tol), or npos.
std::size_t junction_at(const line_drawing<dvec2>& d, dvec2 p, double tol) {
  for (std::size_t i = 0; i < d.points.size(); ++i)
    if (glm::length(d.points[i] - p) <= tol) return i;
  return ~std::size_t{0};
}

/// The largest distance between points at equal fractions along two arcs.
double arc_gap(const cellforge::elliptical_arc<dvec2>& a, const cellforge::elliptical_arc<dvec2>& b) {
  double gap = 0;
  for (int k = 0; k <= 20; ++k)
    gap = std::max(gap, glm::length(cellforge::arc_point(a, k / 20.0) - cellforge::arc_point(b, k / 20.0)));
  return gap;
}

}  // namespace

TEST_CASE("svg arc drawing: A commands become arcs, y flipped, ends snapped into junctions") {
  // A quarter circle of radius 2 round the origin from (2, 0) to (0, 2) (y up): in SVG from
  // (2, 0) to (0, -2), sweep flag 0 (counter-clockwise on screen), with lines at both ends and a
  // line end 1e-4 off the arc's start.
  const auto r =
      read_arcs(svg("<path d=\"M 2 3 V 0 A 2 2 0 0 0 0 -2 H -3\"/>\n"
                    "<line x1=\"2.0001\" y1=\"0\" x2=\"6\" y2=\"0\"/>"));
  REQUIRE(r.drawing.arcs.size() == 1);
  CHECK(r.arcs == 1);
  CHECK(r.drawing.lines.edges.size() == 3);
  CHECK(r.snapped == 3);  // the three ends at the arc's start meet at their mean
  const auto& a = r.drawing.arcs[0];
  const auto& pts = r.drawing.lines.points;
  CHECK(glm::length(pts[a.ends[0]] - dvec2(2 + 1e-4 / 3, 0)) < 1e-12);
  CHECK(glm::length(pts[a.ends[1]] - dvec2(0, 2)) < 1e-12);
  CHECK(a.curve.sweep > 0);
  CHECK(a.curve.sweep == doctest::Approx(std::numbers::pi / 2).epsilon(1e-4));
  CHECK(glm::length(cellforge::arc_point(a.curve, 0.5) - dvec2(std::sqrt(2.0), std::sqrt(2.0))) < 1e-4);
  CHECK(cellforge::validate(r.drawing).ok());
  // The text twin reads to the same arc (up to the snapped start).
  const auto t = io::parse_arc_drawing_text<dvec2>("j 2 0\nj 0 2\na 0 1 2 2 0 0 1\n");
  CHECK(arc_gap(t.arcs[0].curve, a.curve) < 1e-4);
  // Relative arcs, flags without separators, implicit repeats.
  const auto rel = read_arcs(svg("<path d=\"M0 0 a1 1 0 011 1 1 1 0 011 -1\"/>"));
  REQUIRE(rel.drawing.arcs.size() == 2);
  CHECK(glm::length(rel.drawing.lines.points[rel.drawing.arcs[1].ends[1]] - dvec2(2, 0)) < 1e-12);
  CHECK(rel.drawing.arcs[0].curve.sweep < 0);  // sweep 1 on screen is clockwise, y up
  // Float points: arcs checked to float precision.
  const auto f = io::parse_svg_arc_drawing<glm::vec2>(svg("<path d=\"M 2 3 V 0 A 2 2 0 0 0 0 -2 H -3\"/>"));
  REQUIRE(f.drawing.arcs.size() == 1);
  CHECK(cellforge::arc_point(f.drawing.arcs[0].curve, 0.5).y ==
        doctest::Approx(std::sqrt(2.0)).epsilon(1e-6));
  CHECK(io::parse_svg_arc_drawing<glm::vec2>(io::arc_drawing_svg_string(f.drawing)).drawing.arcs.size() == 1);
  // The plain reader still refuses them, naming the arc reader.
  CHECK(failure(svg("<path d=\"M0 0 a1 1 0 011 1\"/>")).first.find("parse_svg_arc_drawing") !=
        std::string::npos);
}

TEST_CASE("svg arc drawing: an ellipse through any affine transform is the transformed ellipse") {
  cellforge::detail::splitmix rng{3};
  for (int i = 0; i < 40; ++i) {
    CAPTURE(i);
    const double m[6] = {rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2),
                         rng.uniform(-2, 2), rng.uniform(-5, 5), rng.uniform(-5, 5)};
    if (std::abs(m[0] * m[3] - m[1] * m[2]) < 0.2) continue;
    const double rx = rng.uniform(0.5, 3), ry = rng.uniform(0.5, 3), deg = rng.uniform(-180, 180);
    const bool large = rng.uniform(0, 1) < 0.5, sweep = rng.uniform(0, 1) < 0.5;
    const dvec2 p0(rng.uniform(-1, 1), rng.uniform(-1, 1)), p1(rng.uniform(-1, 1), rng.uniform(-1, 1));
    std::string d = "M " + std::to_string(p0.x) + " " + std::to_string(p0.y) + " A " + std::to_string(rx) +
                    " " + std::to_string(ry) + " " + std::to_string(deg) + " " + (large ? "1 " : "0 ") +
                    (sweep ? "1 " : "0 ") + std::to_string(p1.x) + " " + std::to_string(p1.y);
    std::string matrix = "matrix(";
    for (int k = 0; k < 6; ++k) matrix += std::to_string(m[k]) + (k < 5 ? " " : ")");
    const auto r = read_arcs(svg("<g transform=\"" + matrix + "\"><path d=\"" + d + "\"/></g>"));
    REQUIRE(r.drawing.arcs.size() == 1);
    // The arc in its own frame (SVG's y down, so its sweep flag is the positive-angle sense
    // there), each point mapped by the matrix and the y flip.
    const auto parse = [](const std::string& v) { return std::stod(v); };
    const auto local =
        cellforge::arc_from_endpoints<dvec2>({{parse(std::to_string(p0.x)), parse(std::to_string(p0.y))},
                                              {parse(std::to_string(p1.x)), parse(std::to_string(p1.y))},
                                              parse(std::to_string(rx)),
                                              parse(std::to_string(ry)),
                                              parse(std::to_string(deg)) * std::numbers::pi / 180,
                                              large,
                                              sweep});
    double mm[6];
    for (int k = 0; k < 6; ++k) mm[k] = parse(std::to_string(m[k]));
    const auto& got = r.drawing.arcs[0].curve;
    double gap = 0;
    for (int k = 0; k <= 20; ++k) {
      const dvec2 q = cellforge::arc_point(local, k / 20.0);
      const dvec2 want(mm[0] * q.x + mm[2] * q.y + mm[4], -(mm[1] * q.x + mm[3] * q.y + mm[5]));
      gap = std::max(gap, glm::length(cellforge::arc_point(got, k / 20.0) - want));
    }
    CHECK(gap < 1e-9);
  }
  // A transform that flattens the ellipse is an error at the path's line.
  const auto flat = [] {
    (void)read_arcs(svg("<g transform=\"scale(1 0)\">\n<path d=\"M0 0 A1 1 0 0 1 1 1\"/></g>"));
  };
  CHECK_THROWS_WITH_AS(flat(), doctest::Contains("d.svg:3: an arc command's transforms flatten its ellipse"),
                       cellforge::error);
}

TEST_CASE("svg arc drawing: closed curves and Beziers refused or skipped, SVG's degenerate arcs") {
  const auto message = [](const std::string& text, const io::svg_drawing_options& o = {}) {
    try {
      (void)read_arcs(text, o);
    } catch (const cellforge::error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message(svg("<circle cx=\"5\" cy=\"5\" r=\"2\"/>")).find("d.svg:2:") == 0);
  CHECK(message(svg("<circle cx=\"5\" cy=\"5\" r=\"2\"/>"))
            .find("<circle> is a closed curve, no round or fillet") != std::string::npos);
  CHECK(message(svg("<ellipse cx=\"5\" cy=\"5\" rx=\"2\" ry=\"1\"/>")).find("closed curve") !=
        std::string::npos);
  CHECK(message(svg("<path d=\"M0 0\n C 1 1 2 2 3 0\"/>"))
            .find("d.svg:3: only straight strokes and elliptical arcs") == 0);
  const auto r =
      read_arcs(svg("<circle cx=\"5\" cy=\"5\" r=\"2\"/>\n"
                    "<path d=\"M0 0 Q 1 1 2 0 A 1 1 0 0 1 4 0 A 0 1 0 0 1 5 0 A 1 1 0 0 1 5 0\"/>"),
                {.curves = io::svg_curves::skip});
  CHECK(r.skipped_curves == 2);
  // (2, 0) -> (4, 0) an arc; a zero radius draws a straight line (SVG), equal ends draw nothing.
  REQUIRE(r.drawing.arcs.size() == 1);
  CHECK(r.drawing.lines.edges.size() == 1);
  CHECK(r.drawing.lines.points.size() == 3);
  CHECK(r.diagnostics.size() >= 3);
  // An arc whose ends snap together is left out with a diagnostic.
  const auto tiny = read_arcs(svg("<path d=\"M0 0 H 100 V 100 M 50 50 A 1 1 0 0 1 50.01 50\"/>"));
  CHECK(tiny.drawing.arcs.empty());
  CHECK(tiny.dropped_zero_length == 1);
  CHECK(std::any_of(tiny.diagnostics.begin(), tiny.diagnostics.end(), [](const std::string& s) {
    return s.find("d.svg:2: an arc whose ends snapped to one junction") != std::string::npos;
  }));
}

TEST_CASE("arc drawing svg: generated drawings with rounds through the picture and back") {
  const auto samples = cellforge::samples::round_drawing_sweep({.seed = 9, .drawings = 16});
  REQUIRE(samples.size() == 16);
  for (const auto& s : samples) {
    CAPTURE(s.name);
    const arc_drawing2& d = s.drawing;
    std::vector<std::size_t> colour(d.arcs.size());
    for (std::size_t k = 0; k < colour.size(); ++k) colour[k] = k / 2;
    const std::string text = io::arc_drawing_svg_string(d, {}, {.labels = true}, colour);
    const auto r = read_arcs(text);
    CHECK(r.snapped == 0);
    CHECK(r.drawing.lines.points.size() == d.lines.points.size());
    CHECK(r.drawing.lines.edges.size() == d.lines.edges.size());
    REQUIRE(r.drawing.arcs.size() == d.arcs.size());
    // Junctions come back bit for bit (renumbered by first appearance), arcs to rounding.
    const double tol = 1e-9;
    for (const auto& p : r.drawing.lines.points)
      CHECK(std::find(d.lines.points.begin(), d.lines.points.end(), p) != d.lines.points.end());
    for (std::size_t k = 0; k < d.arcs.size(); ++k) {
      const auto& a = d.arcs[k];
      const auto& b = r.drawing.arcs[k];
      CHECK(junction_at(r.drawing.lines, d.lines.points[a.ends[0]], 0) == b.ends[0]);
      CHECK(junction_at(r.drawing.lines, d.lines.points[a.ends[1]], 0) == b.ends[1]);
      CHECK(arc_gap(a.curve, b.curve) < tol);
    }
    // A drawing read from the picture comes back from its own picture bit for bit.
    const auto again = read_arcs(io::arc_drawing_svg_string(r.drawing)).drawing;
    REQUIRE(again.arcs.size() == r.drawing.arcs.size());
    CHECK(again.lines.points == r.drawing.lines.points);
    for (std::size_t k = 0; k < again.arcs.size(); ++k) {
      CHECK(again.arcs[k].curve.centre == r.drawing.arcs[k].curve.centre);
      CHECK(again.arcs[k].curve.sweep == r.drawing.arcs[k].curve.sweep);
      CHECK(again.arcs[k].curve.rotation == r.drawing.arcs[k].curve.rotation);
    }
  }
  // What the picture cannot hold is refused.
  arc_drawing2 bad = samples[0].drawing;
  bad.arcs[0].ends[1] = bad.arcs[0].ends[0];
  CHECK_THROWS_WITH_AS(io::arc_drawing_svg_string(bad), doctest::Contains("arc_drawing_svg: arc 0"),
                       cellforge::error);
  CHECK_THROWS_AS(io::arc_drawing_svg_string(samples[0].drawing, {}, {}, {1, 2}), cellforge::error);
  const auto path =
      std::filesystem::temp_directory_path() / ("cellforge_arcs_" + std::to_string(getpid()) + ".svg");
  io::write_arc_drawing_svg(path, samples[0].drawing);
  CHECK(io::read_svg_arc_drawing(path).drawing.arcs.size() == samples[0].drawing.arcs.size());
  std::filesystem::remove(path);
}

}  // namespace io_svg_drawing_tests
