// SPDX-License-Identifier: MIT
// The DXF reader (io/dxf_drawing.hpp): drawings written by a third-party writer (ezdxf, through
// scripts/make-dxf-data.py, in R12, R2000 and R2018) read to the same junctions, edges, arcs,
// faces and cell complexes as their text versions; each entity's geometry on small hand-made
// files; malformed files refused with the file's line.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/io/detail/stroke_snapping.hpp"
#include "cellforge/io/drawing_text.hpp"
#include "cellforge/io/dxf_drawing.hpp"
#include "cellforge/sketch/drawing_to_cells.hpp"
#include "cellforge/sketch/face_finder.hpp"
#include "cellforge/sketch/rounds.hpp"

// Where tests/CMakeLists.txt has the ctest fixtures write the DXF data; "" without ezdxf.
#ifndef CELLFORGE_DXF_DATA_DIR
#define CELLFORGE_DXF_DATA_DIR ""
#endif

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace io_dxf_drawing_tests {

namespace {

namespace fs = std::filesystem;
using cellforge::arc_drawing;
using cellforge::io::dxf_drawing_options;
using cellforge::io::parse_dxf_arc_drawing;
using cellforge::io::parse_dxf_drawing;

/// A DXF file from its lines (group codes and values alternating).
std::string dxf_text(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

/// A minimal file: an ENTITIES section holding `entities` (group/value lines), R2000 header.
std::vector<std::string> dxf_file(const std::vector<std::string>& entities) {
  std::vector<std::string> l = {"  0",    "SECTION", "  2",    "HEADER", "  9",     "$ACADVER", "  1",
                                "AC1015", "  0",     "ENDSEC", "  0",    "SECTION", "  2",      "ENTITIES"};
  l.insert(l.end(), entities.begin(), entities.end());
  l.insert(l.end(), {"  0", "ENDSEC", "  0", "EOF"});
  return l;
}

std::vector<std::string> line_entity(double x0, double y0, double x1, double y1,
                                     const std::string& layer = "0") {
  return {"  0", "LINE",
          "  8", layer,
          " 10", std::to_string(x0),
          " 20", std::to_string(y0),
          " 30", "0.0",
          " 11", std::to_string(x1),
          " 21", std::to_string(y1),
          " 31", "0.0"};
}

std::vector<std::string> joined(std::initializer_list<std::vector<std::string>> parts) {
  std::vector<std::string> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

/// The junction of `d` at p (within tol), or -1.
long junction_at(const arc_drawing<glm::dvec2>& d, glm::dvec2 p, double tol = 1e-9) {
  for (std::size_t j = 0; j < d.lines.points.size(); ++j)
    if (glm::length(d.lines.points[j] - p) <= tol) return static_cast<long>(j);
  return -1;
}

/// Junction map from `read` to `truth` by position (nearest within 1e-9 of the diagonal),
/// required to be one-to-one.
std::vector<std::uint32_t> junction_map(const arc_drawing<glm::dvec2>& read,
                                        const arc_drawing<glm::dvec2>& truth) {
  glm::dvec2 lo = truth.lines.points.front(), hi = lo;
  for (const auto& p : truth.lines.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double tol = 1e-9 * glm::length(hi - lo);
  std::vector<std::uint32_t> map;
  std::set<std::uint32_t> used;
  for (const auto& p : read.lines.points) {
    const long j = junction_at(truth, p, tol);
    REQUIRE(j >= 0);
    map.push_back(static_cast<std::uint32_t>(j));
    used.insert(static_cast<std::uint32_t>(j));
  }
  CHECK(used.size() == map.size());
  return map;
}

/// Face loops as sets of junction sets (orientation- and start-free), junctions mapped.
std::multiset<std::vector<std::uint32_t>> loop_sets(const std::vector<std::vector<std::uint32_t>>& loops,
                                                    const std::vector<std::uint32_t>& map) {
  std::multiset<std::vector<std::uint32_t>> out;
  for (const auto& loop : loops) {
    std::vector<std::uint32_t> l;
    for (const std::uint32_t j : loop) l.push_back(map.empty() ? j : map[j]);
    std::sort(l.begin(), l.end());
    out.insert(l);
  }
  return out;
}

template <class Complex>
std::array<std::size_t, 4> complex_counts(const Complex& c) {
  return {c.num_vertices(), c.num_edges(), c.num_faces(), c.num_volumes()};
}

/// Checks a DXF reading against its text version: junctions, edges, arcs, faces, complex.
void compare(const arc_drawing<glm::dvec2>& read, const arc_drawing<glm::dvec2>& truth,
             std::size_t& faces_compared, std::size_t& rounds_compared) {
  REQUIRE(read.lines.points.size() == truth.lines.points.size());
  REQUIRE(read.lines.edges.size() == truth.lines.edges.size());
  REQUIRE(read.arcs.size() == truth.arcs.size());
  const std::vector<std::uint32_t> map = junction_map(read, truth);
  std::set<std::array<std::uint32_t, 2>> a, b;
  for (const auto& [p, q] : read.lines.edges) a.insert({std::min(map[p], map[q]), std::max(map[p], map[q])});
  for (const auto& [p, q] : truth.lines.edges) b.insert({std::min(p, q), std::max(p, q)});
  CHECK(a == b);
  // Each arc the same curve between the same junctions (DXF runs arcs counter-clockwise, so a
  // clockwise one comes back reversed).
  for (const auto& arc : read.arcs) {
    const std::array<std::uint32_t, 2> ends{map[arc.ends[0]], map[arc.ends[1]]};
    const auto same = std::find_if(truth.arcs.begin(), truth.arcs.end(), [&](const auto& t) {
      return (t.ends == ends) || (t.ends[0] == ends[1] && t.ends[1] == ends[0]);
    });
    REQUIRE(same != truth.arcs.end());
    const bool reversed = same->ends != ends;
    for (const double u : {0.0, 0.3, 0.5, 0.8, 1.0})
      CHECK(glm::length(cellforge::arc_point(arc.curve, u) -
                        cellforge::arc_point(same->curve, reversed ? 1 - u : u)) < 1e-9);
  }
  if (truth.arcs.empty()) {
    const auto fr = cellforge::find_faces(read.lines), ft = cellforge::find_faces(truth.lines);
    CHECK(fr.flagged == ft.flagged);
    CHECK(loop_sets(fr.loops, map) == loop_sets(ft.loops, {}));
    const auto cr = cellforge::drawing_to_cells(read.lines), ct = cellforge::drawing_to_cells(truth.lines);
    CHECK(cr.flagged == ct.flagged);
    CHECK(complex_counts(cr.cells.cells) == complex_counts(ct.cells.cells));
    CHECK(loop_sets(cr.faces.loops, map) == loop_sets(ct.faces.loops, {}));
    ++faces_compared;
  } else {
    const auto rr = cellforge::reconstruct_rounds(read), rt = cellforge::reconstruct_rounds(truth);
    CHECK(rr.skeleton.rounds == rt.skeleton.rounds);
    CHECK(rr.skeleton.fillets == rt.skeleton.fillets);
    REQUIRE(rr.rounds.size() == rt.rounds.size());
    std::vector<double> radii_r, radii_t;
    for (const auto& e : rr.rounds) radii_r.push_back(e.radius);
    for (const auto& e : rt.rounds) radii_t.push_back(e.radius);
    std::sort(radii_r.begin(), radii_r.end());
    std::sort(radii_t.begin(), radii_t.end());
    for (std::size_t k = 0; k < radii_r.size(); ++k)
      CHECK(radii_r[k] == doctest::Approx(radii_t[k]).epsilon(1e-9));
    CHECK(complex_counts(rr.reading.cells.cells) == complex_counts(rt.reading.cells.cells));
    CHECK(rr.reading.faces.loops.size() == rt.reading.faces.loops.size());
    ++rounds_compared;
  }
}

/// Expects an io error located at name:line whose message contains `text`.
void expect_error(const std::string& dxf, std::uint64_t line, const std::string& text,
                  const dxf_drawing_options& options = {}) {
  CAPTURE(text);
  CAPTURE(line);
  try {
    (void)parse_dxf_arc_drawing(dxf, "bad.dxf", options);
    FAIL("no error");
  } catch (const cellforge::error& e) {
    CAPTURE(std::string(e.what()));
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(e.where().file == "bad.dxf");
    CHECK(e.where().line == line);
    CHECK(e.message().find(text) != std::string::npos);
  }
}

}  // namespace

#ifdef NDEBUG
constexpr bool all_versions_compared = true;
#else
constexpr bool all_versions_compared = false;  // Eigen unoptimised under the sanitizers
#endif

TEST_CASE("dxf: drawings written by ezdxf read as their text versions, faces and complexes alike") {
  const std::string dir = CELLFORGE_DXF_DATA_DIR;
  if (dir.empty() || !fs::is_directory(dir)) {
    const std::string what =
        "no DXF test data (python3 with ezdxf, Debian's python3-ezdxf, writes it: "
        "scripts/make-dxf-data.py): the comparison is skipped";
    if (std::getenv("CI") != nullptr) FAIL(what);
    MESSAGE(what);
    return;
  }
  // The text versions: the bundled drawings and the generated ones beside the DXF files.
  const fs::path examples =
      fs::path(CELLFORGE_TEST_DATA_DIR).parent_path().parent_path() / "examples" / "data";
  std::size_t files = 0, faces_compared = 0, rounds_compared = 0;
  std::map<std::string, std::size_t> versions;
  std::vector<fs::path> dxf_files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".dxf") dxf_files.push_back(entry.path());
  std::sort(dxf_files.begin(), dxf_files.end());
  dxf_drawing_options options;
  options.layers = {"OUTLINE", "detail"};  // names compared ignoring case; the decoys are on Notes
  std::string last_stem;
  for (const fs::path& path : dxf_files) {
    CAPTURE(path.string());
    const std::string stem = path.stem().stem().string();
    fs::path text = fs::path(dir) / (stem + ".txt");
    if (!fs::exists(text)) text = examples / (stem + ".txt");
    REQUIRE(fs::exists(text));
    const auto truth = cellforge::io::read_arc_drawing_text(text);
    const auto read = cellforge::io::read_dxf_arc_drawing(path, options);
    ++versions[read.version];
    CHECK(read.skipped_by_layer == 3);  // a LINE and a CIRCLE on Notes, a LINE on the frozen layer
    CHECK(read.skipped_entities == 1);  // the TEXT
    // The sanitizer build compares each drawing in the first of its DXF versions (the files sort
    // by drawing, then version) and reads all of them.
    if (all_versions_compared || stem != last_stem)
      compare(read.drawing, truth, faces_compared, rounds_compared);
    last_stem = stem;
    if (truth.arcs.empty()) {
      // The line reader gives the same straight drawing.
      const auto lines = cellforge::io::read_dxf_drawing(path, options);
      CHECK(lines.drawing.edges.size() == truth.lines.edges.size());
      CHECK(lines.milliseconds > 0);  // stage_report: the whole read, the file's too
    }
    ++files;
  }
  MESSAGE(files << " DXF files (R12 " << versions["AC1009"] << ", R2000 " << versions["AC1015"] << ", R2018 "
                << versions["AC1032"] << "): " << faces_compared << " face and complex comparisons, "
                << rounds_compared << " rounds comparisons");
  CHECK(files >= 30);
  CHECK(versions["AC1009"] >= 10);
  CHECK(versions["AC1015"] >= 10);
  CHECK(versions["AC1032"] >= 10);
  CHECK(rounds_compared >= (all_versions_compared ? 6 : 4));  // 4 drawings with rounds
}

TEST_CASE("dxf: entities read to their geometry") {
  SUBCASE("LINEs snapped into junctions, split where a junction lies on one, duplicates merged") {
    const auto r = parse_dxf_drawing(
        dxf_text(dxf_file(joined({line_entity(0, 0, 2, 0), line_entity(1, 0, 1, 1), line_entity(2, 0, 0, 0),
                                  line_entity(1, 1, 1.0000001, 0)}))));
    CHECK(r.version == "AC1015");
    CHECK(r.entities == 4);
    CHECK(r.drawing.points.size() == 4);
    CHECK(r.drawing.edges.size() == 3);  // (0,0)-(1,0), (1,0)-(2,0), (1,0)-(1,1)
    CHECK(r.split_at_junctions == 2);    // the line (0,0)-(2,0) and its duplicate drawn backwards
    CHECK(r.merged_duplicates >= 1);
  }
  SUBCASE("LWPOLYLINE: closed, a bulge of 1 a half circle counter-clockwise, of -1 clockwise") {
    const std::vector<std::string> poly = {"  0", "LWPOLYLINE", "  8", "0", " 90", "3", " 70", "1",
                                           " 10", "0",          " 20", "0", " 42", "1", " 10", "2",
                                           " 20", "0",          " 10", "1", " 20", "-1"};
    const auto r = parse_dxf_arc_drawing(dxf_text(dxf_file(poly)));
    REQUIRE(r.drawing.arcs.size() == 1);
    CHECK(r.drawing.lines.edges.size() == 2);
    const auto& arc = r.drawing.arcs[0].curve;
    CHECK(arc.rx == doctest::Approx(1));
    CHECK(glm::length(arc.centre - glm::dvec2(1, 0)) < 1e-12);
    // Counter-clockwise from (0,0) to (2,0) about (1,0) passes below: through (1,-1).
    CHECK(glm::length(cellforge::arc_point(arc, 0.5) - glm::dvec2(1, -1)) < 1e-12);
    auto cw = poly;
    cw[13] = "-1";
    const auto c = parse_dxf_arc_drawing(dxf_text(dxf_file(cw)));
    REQUIRE(c.drawing.arcs.size() == 1);
    CHECK(glm::length(cellforge::arc_point(c.drawing.arcs[0].curve, 0.5) - glm::dvec2(1, 1)) < 1e-12);
    // The line reader refuses the bulge, or leaves it out.
    CHECK_THROWS_WITH_AS(parse_dxf_drawing(dxf_text(dxf_file(poly)), "p.dxf"),
                         doctest::Contains("p.dxf:23: LWPOLYLINE with a bulged"), cellforge::error);
    dxf_drawing_options skip;
    skip.curves = cellforge::io::dxf_curves::skip;
    const auto s = parse_dxf_drawing(dxf_text(dxf_file(poly)), "p.dxf", skip);
    CHECK(s.skipped_curves == 1);
    CHECK(s.drawing.edges.size() == 2);
  }
  SUBCASE("POLYLINE with VERTEXes and SEQEND (R12); ARC; CIRCLE as two half arcs") {
    const std::vector<std::string> ents = {
        "  0", "POLYLINE", "  8", "0",      " 66", "1",   " 70",    "0",   "  0", "VERTEX", "  8",
        "0",   " 10",      "0",   " 20",    "0",   "  0", "VERTEX", "  8", "0",   " 10",    "1",
        " 20", "0",        "  0", "VERTEX", " 10", "1",   " 20",    "1",   "  0", "SEQEND", "  0",
        "ARC", " 10",      "0",   " 20",    "1",   " 40", "1",      " 50", "270", " 51",    "0",
        "  0", "CIRCLE",   " 10", "5",      " 20", "5",   " 40",    "2"};
    const auto r = parse_dxf_arc_drawing(dxf_text(dxf_file(ents)));
    CHECK(r.entities == 3);
    CHECK(r.drawing.lines.edges.size() == 2);
    REQUIRE(r.drawing.arcs.size() == 3);
    // ARC 270° → 0° about (0,1), radius 1: from (0,0) to (1,1), counter-clockwise through the
    // point at 315°.
    const auto& arc = r.drawing.arcs[0];
    CHECK(glm::length(r.drawing.lines.points[arc.ends[0]] - glm::dvec2(0, 0)) < 1e-12);
    CHECK(glm::length(r.drawing.lines.points[arc.ends[1]] - glm::dvec2(1, 1)) < 1e-12);
    const double h = std::sqrt(0.5);
    CHECK(glm::length(cellforge::arc_point(arc.curve, 0.5) - glm::dvec2(h, 1 - h)) < 1e-12);
    CHECK(junction_at(r.drawing, {7, 5}) >= 0);
    CHECK(junction_at(r.drawing, {3, 5}) >= 0);
  }
  SUBCASE("ELLIPSE arcs; extrusion (0,0,-1) mirrors x") {
    const std::vector<std::string> ents = {
        "  0", "ELLIPSE", " 10", "0",   " 20", "0", " 11", "2",
        " 21", "0",       " 40", "0.5", " 41", "0", " 42", "1.5707963267948966",
        "  0", "ARC",     " 10", "3",   " 20", "0", " 40", "1",
        " 50", "0",       " 51", "90",  "210", "0", "220", "0",
        "230", "-1"};
    const auto r = parse_dxf_arc_drawing(dxf_text(dxf_file(ents)));
    REQUIRE(r.drawing.arcs.size() == 2);
    const auto& e = r.drawing.arcs[0];
    CHECK(glm::length(r.drawing.lines.points[e.ends[0]] - glm::dvec2(2, 0)) < 1e-12);
    CHECK(glm::length(r.drawing.lines.points[e.ends[1]] - glm::dvec2(0, 1)) < 1e-12);
    CHECK(glm::length(cellforge::arc_point(e.curve, 0.5) - glm::dvec2(2 * std::sqrt(0.5), std::sqrt(0.5))) <
          1e-12);
    // The mirrored ARC: centre (-3,0) in the world, from (-4,0)... its OCS (4,0) → world (-4,0).
    const auto& m = r.drawing.arcs[1];
    CHECK(glm::length(r.drawing.lines.points[m.ends[0]] - glm::dvec2(-4, 0)) < 1e-12);
    CHECK(glm::length(r.drawing.lines.points[m.ends[1]] - glm::dvec2(-3, 1)) < 1e-12);
    CHECK(glm::length(cellforge::arc_point(m.curve, 0.5) - glm::dvec2(-3 - std::sqrt(0.5), std::sqrt(0.5))) <
          1e-12);
  }
  SUBCASE("INSERT: base point, scales, rotation, MINSERT arrays, nested blocks, layer 0 inherited") {
    const std::vector<std::string> l = {
        "  0", "SECTION", "  2", "BLOCKS", "  0", "BLOCK", "  2", "Unit", " 10", "1", " 20", "1", "  0",
        "LINE", "  8", "0", " 10", "1", " 20", "1", " 11", "2", " 21", "1", "  0", "ENDBLK", "  0", "BLOCK",
        "  2", "Pair", " 10", "0", " 20", "0", "  0", "INSERT", "  2", "unit", " 10", "0", " 20", "0", "  0",
        "INSERT", "  2", "Unit", " 10", "0", " 20", "5", "  0", "ENDBLK", "  0", "ENDSEC", "  0", "SECTION",
        "  2", "ENTITIES",
        // Unit at (10,0), x scale 3, y scale 2, rotated 90°: its line (1,1)-(2,1) → (10,0)-(10,3).
        "  0", "INSERT", "  8", "Parts", "  2", "Unit", " 10", "10", " 20", "0", " 41", "3", " 42", "2",
        " 50", "90",
        // Pair as a 2 × 1 array, columns 20 apart: four lines.
        "  0", "INSERT", "  8", "Parts", "  2", "Pair", " 10", "0", " 20", "-10", " 70", "2", " 44", "20",
        "  0", "ENDSEC", "  0", "EOF"};
    const auto r = parse_dxf_drawing(dxf_text(l));
    CHECK(r.inserts == 1 + 2 + 4);
    CHECK(r.drawing.edges.size() == 5);
    const auto has = [&](glm::dvec2 a, glm::dvec2 b) {
      for (const auto& [p, q] : r.drawing.edges) {
        const glm::dvec2 u = r.drawing.points[p], v = r.drawing.points[q];
        if ((glm::length(u - a) < 1e-12 && glm::length(v - b) < 1e-12) ||
            (glm::length(u - b) < 1e-12 && glm::length(v - a) < 1e-12))
          return true;
      }
      return false;
    };
    CHECK(has({10, 0}, {10, 3}));
    CHECK(has({0, -10}, {1, -10}));
    CHECK(has({0, -5}, {1, -5}));
    CHECK(has({20, -10}, {21, -10}));
    CHECK(has({20, -5}, {21, -5}));
    // Layer 0 entities take the INSERT's layer: choosing "parts" reads them all, "0" none.
    dxf_drawing_options parts;
    parts.layers = {"parts"};
    CHECK(parse_dxf_drawing(dxf_text(l), "<memory>", parts).drawing.edges.size() == 5);
    dxf_drawing_options zero;
    zero.layers = {"0"};
    const auto z = parse_dxf_drawing(dxf_text(l), "<memory>", zero);
    CHECK(z.drawing.edges.empty());
    CHECK(z.skipped_by_layer == 2);
    // Refused when asked, at the INSERT's line.
    dxf_drawing_options refuse;
    refuse.expand_inserts = false;
    expect_error(dxf_text(l), 59, "block references are not read", refuse);
  }
  SUBCASE("unknown entities are noted with their line, not read") {
    const auto r =
        parse_dxf_drawing(dxf_text(dxf_file(joined({{"  0", "TEXT", " 10", "0", " 20", "0", "  1", "hello"},
                                                    line_entity(0, 0, 1, 1),
                                                    {"  0", "HATCH"}}))));
    CHECK(r.skipped_entities == 2);
    CHECK(r.drawing.edges.size() == 1);
    REQUIRE(r.diagnostics.size() == 2);
    CHECK(r.diagnostics[0] == "<memory>:15: 1 TEXT entity left out (not a line, polyline or arc)");
  }
}

TEST_CASE("dxf: malformed files are refused with the file's line") {
  const std::vector<std::string> good = dxf_file(joined({line_entity(0, 0, 1, 0), line_entity(1, 0, 1, 1)}));
  // The file's lines (1-based): 15 "  0" of the first LINE, 19 " 10", 20 its value, ...
  REQUIRE(good[14] == "  0");
  REQUIRE(good[18] == " 10");
  CHECK_NOTHROW(parse_dxf_drawing(dxf_text(good)));
  std::size_t kinds = 0;
  const auto edited = [&](auto edit) {
    auto l = good;
    edit(l);
    ++kinds;
    return dxf_text(l);
  };
  // 1. A group code that is not an integer.
  expect_error(edited([](auto& l) { l[18] = " 1x"; }), 19, "a group code (an integer 0 to 1071) expected");
  // 2. A group code out of range.
  expect_error(edited([](auto& l) { l[18] = "5000"; }), 19, "a group code (an integer 0 to 1071) expected");
  // 3. A value line missing (odd pairs from there on): the next value is read as a code.
  expect_error(edited([](auto& l) { l.erase(l.begin() + 19); }), 21, "found '0.000000'");
  // 4. A non-numeric coordinate, at the value's line.
  expect_error(edited([](auto& l) { l[19] = "zero"; }), 20,
               "a start point x (group code 10) is not a finite number");
  // 5. A NaN coordinate.
  expect_error(edited([](auto& l) { l[19] = "nan"; }), 20, "is not a finite number");
  // 6. Truncated inside the ENTITIES section.
  expect_error(edited([](auto& l) { l.resize(24); }), 23, "the file ends inside section ENTITIES");
  // 7. Truncated after a group code.
  expect_error(edited([](auto& l) { l.resize(23); }), 23, "with no value line");
  // 8. The HEADER's ENDSEC missing: the next SECTION is met inside it.
  expect_error(edited([](auto& l) { l.erase(l.begin() + 8, l.begin() + 10); }), 9, "its 0 ENDSEC is missing");
  // 9. No 0 EOF.
  expect_error(edited([](auto& l) { l.resize(l.size() - 2); }), 48, "without 0 EOF");
  // 10. Content outside any section.
  expect_error(edited([](auto& l) { l.insert(l.begin(), {"  0", "LINE"}); }), 1, "0 SECTION expected");
  // 11. A LINE without its end point.
  expect_error(edited([](auto& l) { l.erase(l.begin() + 26, l.begin() + 28); }), 15,
               "LINE without an end point y");
  // 12. A POLYLINE without SEQEND.
  expect_error(dxf_text(dxf_file({"  0", "POLYLINE", " 70", "0", "  0", "VERTEX", " 10", "0", " 20", "0"})),
               15, "no 0 SEQEND");
  ++kinds;
  // 13. A VERTEX outside a POLYLINE.
  expect_error(dxf_text(dxf_file({"  0", "VERTEX", " 10", "0", " 20", "0"})), 15, "outside a POLYLINE");
  ++kinds;
  // 14. An INSERT of an undefined block.
  expect_error(dxf_text(dxf_file({"  0", "INSERT", "  2", "Nowhere", " 10", "0", " 20", "0"})), 15,
               "which is not defined");
  ++kinds;
  // 15. A block that inserts itself (through another).
  expect_error(
      dxf_text({"  0", "SECTION", "  2", "BLOCKS", "  0", "BLOCK",  "  2", "A",       "  0", "INSERT",
                "  2", "B",       "  0", "ENDBLK", "  0", "BLOCK",  "  2", "B",       "  0", "INSERT",
                "  2", "A",       "  0", "ENDBLK", "  0", "ENDSEC", "  0", "SECTION", "  2", "ENTITIES",
                "  0", "INSERT",  "  2", "A",      "  0", "ENDSEC", "  0", "EOF"}),
      19, "inserts itself");
  ++kinds;
  // 16. A LWPOLYLINE vertex without its y.
  expect_error(
      dxf_text(dxf_file({"  0", "LWPOLYLINE", " 10", "0", " 20", "0", " 10", "1", " 10", "2", " 20", "0"})),
      23, "vertex without its y");
  ++kinds;
  // 17. An ARC with a negative radius; 18. an ELLIPSE with an axis ratio above 1.
  expect_error(
      dxf_text(dxf_file({"  0", "ARC", " 10", "0", " 20", "0", " 40", "-1", " 50", "0", " 51", "90"})), 15,
      "not positive");
  expect_error(
      dxf_text(dxf_file({"  0", "ELLIPSE", " 10", "0", " 20", "0", " 11", "1", " 21", "0", " 40", "2"})), 15,
      "axis ratio");
  kinds += 2;
  // 19. An entity in a tilted plane.
  expect_error(
      dxf_text(dxf_file({"  0", "CIRCLE", " 10", "0", " 20", "0", " 40", "1", "210", "1", "230", "1"})), 15,
      "tilted out of the drawing");
  ++kinds;
  // 20. A binary DXF file.
  expect_error(std::string("AutoCAD Binary DXF\r\n\x1a") + std::string(1, '\0') + "xx", 1, "binary DXF");
  ++kinds;
  // 21. Curves refused by the line reader, at the curve's line.
  CHECK_THROWS_WITH_AS(
      parse_dxf_drawing(
          dxf_text(dxf_file({"  0", "ARC", " 10", "0", " 20", "0", " 40", "1", " 50", "0", " 51", "90"})),
          "c.dxf"),
      doctest::Contains("c.dxf:15: ARC: curves are read by parse_dxf_arc_drawing"), cellforge::error);
  ++kinds;
  // 22. The work budget: blocks inserted too often.
  dxf_drawing_options small;
  small.max_strokes = 100;
  expect_error(
      dxf_text({"  0", "SECTION", "  2", "BLOCKS",  "  0", "BLOCK",    "  2", "A",      "  0", "LINE",
                " 10", "0",       " 20", "0",       " 11", "1",        " 21", "0",      "  0", "ENDBLK",
                "  0", "ENDSEC",  "  0", "SECTION", "  2", "ENTITIES", "  0", "INSERT", "  2", "A",
                " 70", "1000",    " 71", "1000",    "  0", "ENDSEC",   "  0", "EOF"}),
      27, "max_strokes", small);
  ++kinds;
  MESSAGE(kinds << " kinds of malformed DXF refused with their line");
  CHECK(kinds >= 20);
}

TEST_CASE("stroke snapping, shared by the SVG and DXF readers: ends, splits, duplicates, ellipses") {
  using cellforge::io::detail::stroke_arc;
  using seg = std::pair<glm::dvec2, glm::dvec2>;
  // A square's bottom drawn twice (once reversed), a right side whose foot misses the corner by
  // 1e-12, a zero-length stroke, a stroke standing on the bottom's midpoint, and an arc whose
  // first end misses the top right corner by 1e-12.
  const std::vector<seg> segments{
      {{0, 0}, {1, 0}}, {{1, 1e-12}, {1, 1}}, {{0, 0}, {0, 0}}, {{1, 0}, {0, 0}}, {{0.5, 0}, {0.5, 1}}};
  const std::vector<stroke_arc> arcs{{{1, 1 + 1e-12}, {0.5, 1}, 0.25, 0.25, 0.0, false, true}};
  cellforge::io::detail::stroke_snap_counts counts;
  std::vector<std::string> notes;
  const auto d = cellforge::io::detail::snap_strokes<glm::dvec2>(
      segments, arcs, 1e-9, true, "strokes", [](std::size_t) { return std::size_t{7}; }, counts, notes);
  // Junctions (0,0), (1,0), (1,1), (0.5,0), (0.5,1); the bottom split at (0.5,0) into two
  // edges, its reversed copy merged into them, the right side, the stroke on the midpoint.
  CHECK(d.lines.points.size() == 5);
  CHECK(d.lines.edges.size() == 4);
  CHECK(counts.dropped_zero_length == 1);
  CHECK(counts.merged_duplicates == 2);
  CHECK(counts.split_at_junctions >= 1);
  CHECK(counts.snapped >= 2);
  REQUIRE(d.arcs.size() == 1);
  const auto corner = d.lines.points[d.arcs[0].ends[0]];
  CHECK(std::abs(corner.x - 1) < 1e-9);
  CHECK(std::abs(corner.y - 1) < 1e-9);
  for (const auto& e : d.lines.edges) CHECK(e[0] != e[1]);

  // A reflection keeps the axes and turns the sweep; a flattening map is refused.
  double rx = 2, ry = 1, rotation = 0;
  bool sense = true;
  CHECK(cellforge::io::detail::map_ellipse({1, 0, 0, -1, 0, 0}, rx, ry, rotation, sense));
  CHECK(rx == doctest::Approx(2));
  CHECK(ry == doctest::Approx(1));
  CHECK(rotation == doctest::Approx(0));
  CHECK_FALSE(sense);
  CHECK(cellforge::io::detail::map_ellipse({3, 0, 0, 3, 5, 5}, rx, ry, rotation, sense));
  CHECK(rx == doctest::Approx(6));
  CHECK(ry == doctest::Approx(3));
  CHECK_FALSE(cellforge::io::detail::map_ellipse({1, 0, 0, 0, 0, 0}, rx, ry, rotation, sense));
}

TEST_CASE("dxf: empty and odd but valid files") {
  const auto empty = parse_dxf_drawing(dxf_text(dxf_file({})));
  CHECK(empty.drawing.edges.empty());
  CHECK(empty.diagnostics.back() == "<memory>: no straight line found");
  CHECK_THROWS_AS(parse_dxf_drawing(""), cellforge::error);
  // CRLF line ends, 999 comments, blank-padded codes and a byte-order mark.
  std::string crlf =
      "\xEF\xBB\xBF"
      "999\r\ncomment\r\n";
  for (const std::string& l : dxf_file(line_entity(0, 0, 1, 0))) crlf += l + "\r\n";
  const auto r = parse_dxf_drawing(crlf);
  CHECK(r.drawing.edges.size() == 1);
  // Hidden layers: a layer off (negative colour) in the LAYER table is left out unless asked.
  const std::vector<std::string> l = {"  0",   "SECTION", "  2",   "TABLES", "  0", "TABLE", "  2",
                                      "LAYER", "  0",     "LAYER", "  2",    "Off", " 70",   "0",
                                      " 62",   "-7",      "  0",   "ENDTAB", "  0", "ENDSEC"};
  std::vector<std::string> file = l;
  const auto rest = dxf_file(joined({line_entity(0, 0, 1, 0, "off"), line_entity(0, 0, 0, 1)}));
  file.insert(file.end(), rest.begin() + 10, rest.end());  // its ENTITIES section and EOF
  CHECK(parse_dxf_drawing(dxf_text(file)).drawing.edges.size() == 1);
  dxf_drawing_options all;
  all.skip_hidden_layers = false;
  CHECK(parse_dxf_drawing(dxf_text(file), "<memory>", all).drawing.edges.size() == 2);
}

}  // namespace io_dxf_drawing_tests
