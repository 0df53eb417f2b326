// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/io/edge_list.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "io_test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace io_edge_list_tests {

namespace io = cellforge::io;
using cellforge::wireframe;
using edge = std::array<std::uint32_t, 2>;

namespace {

// A triangle with a tail; the malformed cases are edits of it.
const std::string tri = "vertices 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nedges 4\n0 1\n1 2\n2 0\n0 3\n";

wireframe<glm::dvec3> parse(const std::string& text, const io::edge_list_read_options& o = {}) {
  return io::parse_edge_list<glm::dvec3>(text, "w.edges", o);
}

}  // namespace

TEST_CASE("edge list: a plain file reads points and edges") {
  const auto w = parse(tri);
  REQUIRE(w.points.size() == 4);
  CHECK(w.points[3] == glm::dvec3(0, 0, 1));
  CHECK(w.edges == std::vector<edge>{{0, 1}, {1, 2}, {2, 0}, {0, 3}});
}

TEST_CASE("edge list: layout variations read the same wireframe") {
  const auto expected = parse(tri);
  const std::vector<std::pair<const char*, std::string>> variants = {
      {"CRLF", "vertices 4\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n0 0 1\r\nedges 4\r\n0 1\r\n1 2\r\n2 0\r\n0 3\r\n"},
      {"lone CR", "vertices 4\r0 0 0\r1 0 0\r0 1 0\r0 0 1\redges 4\r0 1\r1 2\r2 0\r0 3\r"},
      {"no final line end", "vertices 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nedges 4\n0 1\n1 2\n2 0\n0 3"},
      {"comments and blank lines",
       "# a triangle with a tail\n\nvertices 4 # count\n0 0 0\n# x axis\n1 0 0\n\n0 1 0\n0 0 1\n"
       "edges 4\n0 1 # first\n1 2\n2 0\n\n0 3\n# end\n"},
      {"tabs and spaces",
       "  vertices\t4\n\t0 0\t0 \n1  0 0\n0 1 0\n0 0 1\nedges 4\n 0\t1\n1 2\n2 0  \n0 3\n"},
      {"byte-order mark",
       "\xEF\xBB\xBFvertices 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nedges 4\n0 1\n1 2\n2 0\n0 3\n"},
      {"number spellings",
       "vertices 4\n0.0 -0e0 +0\n1. 0 0\n.0 1e0 0\n0 0 +1.0E+0\nedges 4\n0 1\n1 2\n2 +0\n0 3\n"},
  };
  for (const auto& variant : variants) {
    const std::string what = variant.first;
    CAPTURE(what);
    const auto w = parse(variant.second);
    CHECK(w.points == expected.points);
    CHECK(w.edges == expected.edges);
  }
  // Zero vertices and zero edges make an empty wireframe, not an error.
  const auto empty = parse("vertices 0\nedges 0\n");
  CHECK(empty.points.empty());
  CHECK(empty.edges.empty());
}

TEST_CASE("edge list: malformed input names the line and says what is wrong") {
  const std::vector<io_test::bad_input> cases = {
      {"empty file", "", 1, "empty file"},
      {"only comments", "# nothing\n\n# here\n", 3, "empty file"},
      {"no header", "0 0 0\n", 1, "expected 'vertices <count>'"},
      {"misspelled header", "verts 1\n0 0 0\nedges 0\n", 1, "expected 'vertices <count>', found 'verts'"},
      {"header without count", "vertices\n", 1, "expected the vertex count"},
      {"negative vertex count", "vertices -2\n", 1, "must not be negative"},
      {"vertex count not a number", "vertices four\n", 1, "expected the vertex count, found 'four'"},
      {"vertex count too large", "vertices 99999999999\n", 1, "exceeds the 32-bit limit"},
      {"junk after the count", "vertices 1 2\n0 0 0\nedges 0\n", 1, "unexpected '2' after the vertex count"},
      {"two coordinates", "vertices 2\n0 0 0\n1 0\nedges 0\n", 3, "coordinate z of vertex 1"},
      {"four coordinates", "vertices 1\n0 0 0 1\nedges 0\n", 2, "more than 3 coordinates"},
      {"NaN coordinate", "vertices 1\n0 nan 0\nedges 0\n", 2, "not finite"},
      {"infinite coordinate", "vertices 1\n0 0 -inf\nedges 0\n", 2, "not finite"},
      {"coordinate not a number", "vertices 1\n0 x 0\nedges 0\n", 2,
       "expected coordinate y of vertex 0, found 'x'"},
      {"too few vertices", "vertices 3\n0 0 0\n1 0 0\nedges 1\n0 1\n", 4, "found 'edges' after 2 vertices"},
      {"a word in the vertices", "vertices 2\n0 0 0\nedgesX 1\n", 3,
       "expected coordinate x of vertex 1, found 'edgesX'"},
      {"end of file in the vertices", "vertices 3\n0 0 0\n1 0 0\n", 3,
       "expected vertex 2 of 3, found end of file"},
      {"no edges section", "vertices 1\n0 0 0\n", 2, "expected 'edges <count>'"},
      {"misspelled edges", "vertices 1\n0 0 0\nedge 0\n", 3, "expected 'edges <count>', found 'edge'"},
      {"negative edge count", "vertices 1\n0 0 0\nedges -1\n", 3, "the edge count must not be negative"},
      {"index out of range", "vertices 2\n0 0 0\n1 0 0\nedges 1\n0 2\n", 5,
       "vertex index 2 out of range (0..1"},
      {"1-based index hint", "vertices 2\n0 0 0\n1 0 0\nedges 1\n1 2\n", 5, "indices are 0-based"},
      {"negative index", "vertices 2\n0 0 0\n1 0 0\nedges 1\n-1 0\n", 5, "vertex index -1 out of range"},
      {"fractional index", "vertices 2\n0 0 0\n1 0 0\nedges 1\n0 1.5\n", 5,
       "the second vertex index of edge 0"},
      {"one index", "vertices 2\n0 0 0\n1 0 0\nedges 1\n0\n", 5,
       "expected the second vertex index of edge 0"},
      {"three indices", "vertices 3\n0 0 0\n1 0 0\n0 1 0\nedges 1\n0 1 2\n", 6, "more than 2 vertex indices"},
      {"self loop", "vertices 2\n0 0 0\n1 0 0\nedges 2\n0 1\n1 1\n", 6, "joins vertex 1 to itself"},
      {"duplicate edge", "vertices 3\n0 0 0\n1 0 0\n0 1 0\nedges 3\n0 1\n1 2\n1 0\n", 8,
       "edge 2 repeats edge 0"},
      {"too few edges", "vertices 2\n0 0 0\n1 0 0\nedges 2\n0 1\n", 5,
       "expected edge 1 of 2, found end of file"},
      {"content after the edges", "vertices 2\n0 0 0\n1 0 0\nedges 1\n0 1\n1 0\n", 6,
       "after the last of 1 edges"},
      {"no vertices but an edge", "vertices 0\nedges 1\n0 0\n", 3, "(the file has no vertices)"},
  };
  for (const auto& c : cases)
    io_test::check_rejected(c, "w.edges", [](const std::string& t) { (void)parse(t); });
}

TEST_CASE("edge list: options accept duplicates and self loops") {
  const std::string dup = "vertices 2\n0 0 0\n1 0 0\nedges 3\n0 1\n1 0\n1 1\n";
  const auto w = parse(dup, {.allow_duplicate_edges = true, .allow_self_loops = true});
  CHECK(w.edges == std::vector<edge>{{0, 1}, {1, 0}, {1, 1}});
  CHECK_THROWS_AS(parse(dup, {.allow_duplicate_edges = true}), cellforge::error);
  CHECK_THROWS_AS(parse(dup, {.allow_self_loops = true}), cellforge::error);
}

TEST_CASE("edge list: a coordinate that does not fit a float point is rejected") {
  io_test::check_rejected({"too big for float", "vertices 1\n0 1e300 0\nedges 0\n", 2, "is out of range"},
                          "f.edges",
                          [](const std::string& t) { (void)io::parse_edge_list<glm::vec3>(t, "f.edges"); });
}

TEST_CASE_TEMPLATE("edge list: write then read gives the same wireframe bit for bit", P, glm::dvec3,
                   std::array<float, 3>, io_test::user_point) {
  const auto soup = io_test::awkward_soup<P>(5, 300, 0);
  wireframe<P> w;
  w.points = soup.points;
  for (std::uint32_t i = 0; i + 1 < 300; i += 2) w.edges.push_back({i, (i * 7 + 3) % 300});
  w.edges.push_back({299, 0});
  std::ostringstream os;
  io::write_edge_list(os, w, {.comment = "cellforge test\nsecond line"});
  CHECK(os.str().starts_with("# cellforge test\n# second line\nvertices 300\n"));
  const auto back = io::parse_edge_list<P>(os.str(), "mem");
  REQUIRE(back.points.size() == w.points.size());
  for (std::size_t i = 0; i < w.points.size(); ++i) CHECK(io_test::same_bits(back.points[i], w.points[i]));
  CHECK(back.edges == w.edges);

  const io_test::temp_path file("rt.edges");
  io::write_edge_list(file.path, w);
  const auto read = io::read_edge_list<P>(file.path);
  CHECK(read.edges == w.edges);
  REQUIRE(read.points.size() == w.points.size());
  for (std::size_t i = 0; i < w.points.size(); ++i) CHECK(io_test::same_bits(read.points[i], w.points[i]));
}

TEST_CASE("edge list: writing refuses what reading would reject") {
  wireframe<glm::dvec3> w;
  w.points = {{0, 0, 0}, {1, 0, 0}};
  w.edges = {{0, 2}};
  std::ostringstream os;
  CHECK_THROWS_AS(io::write_edge_list(os, w), cellforge::error);
  w.edges = {{0, 1}};
  w.points[1].y = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(io::write_edge_list(os, w), cellforge::error);
}

TEST_CASE("edge list: file errors name the path, malformed files their line") {
  io_test::check_file_errors("bad.edges", "vertices 1\n0 0 0\nedges 1\n0 1\n", 4,
                             [](const std::filesystem::path& p) { (void)io::read_edge_list<glm::dvec3>(p); });
}

TEST_CASE("edge list and OBJ: every sample model's wireframe round-trips") {
  for (const auto& m : cellforge::samples::all_small_samples()) {
    const std::string name = m.name;
    CAPTURE(name);
    std::ostringstream os;
    io::write_edge_list(os, m.wire);
    const auto back = io::parse_edge_list<glm::dvec3>(os.str());
    CHECK(back.points == m.wire.points);
    CHECK(back.edges == m.wire.edges);
  }
}

TEST_CASE("the bundled stepped block is the generator's model and round-trips through OBJ") {
  const auto m = cellforge::samples::sample_stepped_block();
  const std::filesystem::path bundled =  // lexically: tests/data need not exist in a fresh checkout
      std::filesystem::path(CELLFORGE_TEST_DATA_DIR).parent_path().parent_path() / "examples" / "data" /
      "stepped_block.obj";
  const auto file = io::read_obj_wireframe<glm::dvec3>(bundled);
  CHECK(file.points == m.wire.points);
  CHECK(file.edges == m.wire.edges);

  const io_test::temp_path tmp("stepped.obj");
  io::write_obj(tmp.path, m.wire);
  const auto back = io::read_obj_wireframe<glm::dvec3>(tmp.path);
  CHECK(back.points == m.wire.points);
  CHECK(back.edges == m.wire.edges);
}

TEST_CASE("edge list: mutated files parse or throw an io error, never anything else") {
  // Byte edits of a valid file (ASan/UBSan builds check memory safety along the way).
  std::ostringstream os;
  io::write_edge_list(os, cellforge::samples::sample_house().wire, {.comment = "house"});
  const std::string valid = os.str();
  const std::string alphabet = "0123456789 -+.eE#\n\r\tvertices edgesnaif";
  std::mt19937 rng(2024);
  std::size_t parsed = 0, rejected = 0;
  for (int round = 0; round < 3000; ++round) {
    std::string text = valid;
    for (int edits = 1 + static_cast<int>(rng() % 4); edits > 0 && !text.empty(); --edits) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 3) {
        case 0:
          text.erase(at, 1 + rng() % 3);
          break;
        case 1:
          text.insert(at, 1, alphabet[rng() % alphabet.size()]);
          break;
        default:
          text[at] = alphabet[rng() % alphabet.size()];
      }
    }
    try {
      const auto w = io::parse_edge_list<glm::dvec3>(text, "m.edges");
      // Whatever parses is a well-formed wireframe.
      for (const auto& e : w.edges) {
        CHECK(e[0] < w.points.size());
        CHECK(e[1] < w.points.size());
        CHECK(e[0] != e[1]);
      }
      ++parsed;
    } catch (const cellforge::error& e) {
      CHECK(e.category() == cellforge::error_category::io);
      CHECK(e.file() == "m.edges");
      CHECK(e.line() >= 1);
      ++rejected;
    }
  }
  CHECK(parsed > 0);
  CHECK(rejected > 0);
}

}  // namespace io_edge_list_tests
