// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/io/swc.hpp"
#include "cellforge/samples/skeletons.hpp"
#include "io_test_support.hpp"
#include "skeleton_test_support.hpp"

// A user's own tree: sealed CAD points, diameters in float, links as int pairs.
namespace swc_cad {
struct tree {
  std::vector<test_support::sealed_point> at;
  std::vector<float> diameters;
  std::vector<std::array<int, 2>> links;
};
}  // namespace swc_cad

template <>
struct cellforge::skeleton_traits<swc_cad::tree> {
  using point_type = test_support::sealed_point;
  static std::size_t num_nodes(const swc_cad::tree& t) { return t.at.size(); }
  static const point_type& position(const swc_cad::tree& t, std::size_t i) { return t.at[i]; }
  static float radius(const swc_cad::tree& t, std::size_t i) { return t.diameters[i] / 2; }
  static std::size_t num_edges(const swc_cad::tree& t) { return t.links.size(); }
  static std::array<std::size_t, 2> endpoints(const swc_cad::tree& t, std::size_t j) {
    return {static_cast<std::size_t>(t.links[j][0]), static_cast<std::size_t>(t.links[j][1])};
  }
};

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace io_swc_tests {

namespace io = cellforge::io;
using edge = std::array<std::uint32_t, 2>;
using test_support::sealed_point;

namespace {

const std::string field_list = " of 7: id type x y z radius parent)";

io::swc_result<glm::dvec3> parse(const std::string& text, const io::swc_read_options& o = {}) {
  return io::parse_swc<glm::dvec3>(text, "n.swc", o);
}

template <class G>
std::string swc_text(const G& g, const io::swc_write_options& o = {}) {
  std::ostringstream os;
  io::write_swc(os, g, o);
  return os.str();
}

}  // namespace

TEST_CASE("swc: samples become nodes in file order, parents -> children edges") {
  // Ids neither contiguous nor ordered, a parent after its child, two trees, comments.
  const std::string text =
      "# a small neuron\n"
      "#  id type x y z radius parent\n"
      "\n"
      "10 1 0 0 0 5 -1\n"
      "30 3 0 10 0 1.5 20   # a dendrite, its parent below\n"
      "20 3 0 5 0 2 10\n"
      "7 2 0 -8 0 0.5 10\n"
      "100 4 50 50 50 1 -1\n"
      "101 4 50 55 50 1 100\n";
  const auto r = parse(text);
  const auto& s = r.skeleton;
  REQUIRE(s.points.size() == 6);
  CHECK(s.points[1] == glm::dvec3(0, 10, 0));
  CHECK(s.radii == std::vector<double>{5, 1.5, 2, 0.5, 1, 1});
  CHECK(r.ids == std::vector<std::int64_t>{10, 30, 20, 7, 100, 101});
  CHECK(r.types == std::vector<std::int32_t>{1, 3, 3, 2, 4, 4});
  CHECK(s.edges == std::vector<edge>{{2, 1}, {0, 2}, {0, 3}, {4, 5}});
  CHECK(r.collapsed_somas == 0);
  CHECK(cellforge::validate(s).ok());
}

TEST_CASE("swc: layout variations read the same samples") {
  const std::string plain = "1 1 0 0 0 2 -1\n2 3 0 4 0 1 1\n3 3 0 8 0 0.5 2\n";
  const auto expected = parse(plain);
  const std::vector<std::pair<const char*, std::string>> variants = {
      {"CRLF", "1 1 0 0 0 2 -1\r\n2 3 0 4 0 1 1\r\n3 3 0 8 0 0.5 2\r\n"},
      {"lone CR", "1 1 0 0 0 2 -1\r2 3 0 4 0 1 1\r3 3 0 8 0 0.5 2\r"},
      {"no final line end", "1 1 0 0 0 2 -1\n2 3 0 4 0 1 1\n3 3 0 8 0 0.5 2"},
      {"tabs and spaces", "  1\t1 0 0 0 2 -1\n2 3\t\t0 4 0 1 1  \n\t3 3 0 8 0 0.5 2\n"},
      {"byte-order mark", "\xEF\xBB\xBF" + plain},
      {"number spellings", "+1 1 0.0 -0e0 +0 2.0 -1\n2 +3 0 4e0 0 1. 1\n3 3 0 8 .0 5e-1 +2\n"},
  };
  for (const auto& variant : variants) {
    const std::string what = variant.first;
    CAPTURE(what);
    const auto r = parse(variant.second);
    CHECK(r.skeleton.points == expected.skeleton.points);
    CHECK(r.skeleton.radii == expected.skeleton.radii);
    CHECK(r.skeleton.edges == expected.skeleton.edges);
    CHECK(r.ids == expected.ids);
  }
  const auto empty = parse("# only a header\n\n");
  CHECK(empty.skeleton.points.empty());
  CHECK(parse("").skeleton.points.empty());
}

TEST_CASE("swc: soma conventions") {
  SUBCASE("a single-point soma is one node like any other") {
    const auto r = parse("1 1 3 4 5 6 -1\n2 3 3 14 5 1 1\n");
    CHECK(r.skeleton.points.size() == 2);
    CHECK(r.types[0] == 1);
    CHECK(r.skeleton.radii[0] == 6);
    CHECK(r.collapsed_somas == 0);
  }
  // NeuroMorpho's three-point soma: the centre, and two points at -r and +r along y, parent the centre.
  const std::string three =
      "1 1 10 20 30 4 -1\n"
      "2 1 10 16 30 4 1\n"
      "3 1 10 24 30 4 1\n"
      "4 3 20 20 30 1 1\n"    // a dendrite on the centre
      "5 2 10 10 30 0.5 2\n"  // an axon on the lower soma point
      "6 3 10 40 30 1 3\n";   // a dendrite on the upper one
  SUBCASE("a three-point soma becomes its centre, the outer points' children attached to it") {
    const auto r = parse(three);
    CHECK(r.collapsed_somas == 1);
    REQUIRE(r.diagnostics.size() == 1);  // stage_report: the collapse said, with its option
    CHECK(r.diagnostics[0].find("collapse_three_point_soma") != std::string::npos);
    CHECK(r.milliseconds >= 0);
    CHECK(r.ids == std::vector<std::int64_t>{1, 4, 5, 6});
    CHECK(r.types == std::vector<std::int32_t>{1, 3, 2, 3});
    CHECK(r.skeleton.points[0] == glm::dvec3(10, 20, 30));
    CHECK(r.skeleton.radii[0] == 4);
    CHECK(r.skeleton.edges == std::vector<edge>{{0, 1}, {0, 2}, {0, 3}});
  }
  SUBCASE("or is kept as three nodes and two edges") {
    const auto r = parse(three, {.collapse_three_point_soma = false});
    CHECK(r.collapsed_somas == 0);
    CHECK(r.skeleton.points.size() == 6);
    CHECK(r.skeleton.edges == std::vector<edge>{{0, 1}, {0, 2}, {0, 3}, {1, 4}, {2, 5}});
  }
  SUBCASE("rounded offsets within 1 % of the radius still count") {
    const auto r = parse("1 1 1.234 5.678 0 2.345 -1\n2 1 1.234 3.33 0 2.345 1\n3 1 1.234 8.02 0 2.35 1\n");
    CHECK(r.collapsed_somas == 1);
    CHECK(r.skeleton.points.size() == 1);
  }
  SUBCASE("type-1 points that do not follow the convention stay as they are") {
    const std::vector<std::string> others = {
        "1 1 0 0 0 4 -1\n2 1 4 0 0 4 1\n3 1 -4 0 0 4 1\n",                 // along x, not y
        "1 1 0 0 0 4 -1\n2 1 0 -4 0 4 1\n3 1 0 -4 0 4 1\n",                // both on one side
        "1 1 0 0 0 4 -1\n2 1 0 -4 0 2 1\n3 1 0 4 0 4 1\n",                 // another radius
        "1 1 0 0 0 4 -1\n2 1 0 -4 0 4 1\n3 1 0 4 0 4 1\n4 1 0 0 4 4 1\n",  // three soma children
        "1 1 0 0 0 4 -1\n2 3 0 -4 0 4 1\n3 1 0 4 0 4 1\n",                 // one is a dendrite
        "1 1 0 0 0 4 -1\n2 1 0 4 0 4 1\n3 1 0 8 0 4 2\n",                  // a soma contour chain
    };
    for (const auto& text : others) {
      CAPTURE(text);
      const auto r = parse(text);
      CHECK(r.collapsed_somas == 0);
      CHECK(r.skeleton.points.size() == r.ids.size());
    }
  }
}

TEST_CASE("swc: malformed files name the line and say exactly what is wrong") {
  const std::vector<skeleton_test::bad_input> cases = {
      {"too few fields", "1 1 0 0 0 2 -1\n2 3 0 4 0 1\n", 2,
       "expected the parent of sample 2 (field 7" + field_list + ", found end of line"},
      {"a blank-separated line cut short", "1 1 0 0\n", 1,
       "expected the z coordinate of sample 1 (field 5" + field_list + ", found end of line"},
      {"trailing garbage", "1 1 0 0 0 2 -1 extra\n", 1,
       "unexpected 'extra' after the 7 fields of sample 1 (id type x y z radius parent)"},
      {"an eighth number", "1 1 0 0 0 2 -1\n2 3 0 4 0 1 1 0\n", 2,
       "unexpected '0' after the 7 fields of sample 2 (id type x y z radius parent)"},
      {"id not a number", "one 1 0 0 0 2 -1\n", 1,
       "expected the sample id (field 1" + field_list + ", found 'one'"},
      {"fractional id", "1.5 1 0 0 0 2 -1\n", 1,
       "expected the sample id (field 1" + field_list + ", found '1.5'"},
      {"coordinate not a number", "1 1 0 y 0 2 -1\n", 1,
       "expected the y coordinate of sample 1 (field 4" + field_list + ", found 'y'"},
      {"a comma between fields", "1 1 0, 0 0 2 -1\n", 1,
       "expected the x coordinate of sample 1 (field 3" + field_list + ", found '0,'"},
      {"negative radius", "1 1 0 0 0 2 -1\n2 3 0 4 0 -1 1\n", 2,
       "the radius of sample 2, '-1', must be positive"},
      {"zero radius", "1 1 0 0 0 0 -1\n", 1, "the radius of sample 1, '0', must be positive"},
      {"NaN radius", "1 1 0 0 0 nan -1\n", 1, "the radius of sample 1, 'nan', is not finite"},
      {"infinite radius", "1 1 0 0 0 inf -1\n", 1, "the radius of sample 1, 'inf', is not finite"},
      {"NaN coordinate", "1 1 0 0 NaN 2 -1\n", 1,
       "the z coordinate of sample 1 (field 5" + field_list +
           " 'NaN' is not finite (NaN and Inf coordinates are rejected)"},
      {"huge coordinate", "1 1 1e999 0 0 2 -1\n", 1,
       "the x coordinate of sample 1 (field 3" + field_list + " '1e999' is out of range"},
      {"huge radius", "1 1 0 0 0 1e400 -1\n", 1,
       "the radius of sample 1 (field 6" + field_list + " '1e400' is out of range"},
      {"huge id", "99999999999999999999 1 0 0 0 2 -1\n", 1,
       "the sample id (field 1" + field_list + " '99999999999999999999' is out of range"},
      {"huge type", "1 99999999999 0 0 0 2 -1\n", 1, "the type 99999999999 of sample 1 is too large"},
      {"negative type", "1 -2 0 0 0 2 -1\n", 1, "the type -2 of sample 1 must not be negative"},
      {"id zero", "0 1 0 0 0 2 -1\n", 1, "sample id 0 must be positive (SWC ids start at 1)"},
      {"negative id", "1 1 0 0 0 2 -1\n-3 3 0 4 0 1 1\n", 2,
       "sample id -3 must be positive (SWC ids start at 1)"},
      {"parent zero", "1 1 0 0 0 2 -1\n2 3 0 4 0 1 0\n", 2,
       "the parent 0 of sample 2 is neither -1 (a root) nor a sample id (ids are positive)"},
      {"parent below -1", "1 1 0 0 0 2 -2\n", 1,
       "the parent -2 of sample 1 is neither -1 (a root) nor a sample id (ids are positive)"},
      {"self parent", "1 1 0 0 0 2 -1\n2 3 0 4 0 1 2\n", 2, "sample 2 is its own parent"},
      {"duplicate id", "1 1 0 0 0 2 -1\n2 3 0 4 0 1 1\n# again\n2 3 0 8 0 1 1\n", 4,
       "sample id 2 is used twice (first on line 2)"},
      {"missing parent", "1 1 0 0 0 2 -1\n2 3 0 4 0 1 1\n3 3 0 8 0 1 9\n", 3,
       "the parent 9 of sample 3 is not in the file"},
      {"parent cycle", "1 1 0 0 0 2 -1\n5 3 0 4 0 1 6\n6 3 0 8 0 1 7\n7 3 0 9 0 1 5\n8 3 0 9 0 1 7\n", 2,
       "the parents form a cycle with no root: 5 -> 6 -> 7 -> 5 (each arrow leads to the parent; a tree "
       "starts "
       "at a parent -1)"},
      {"two samples each the other's parent", "4 3 0 0 0 1 3\n3 3 0 1 0 1 4\n", 1,
       "the parents form a cycle with no root: 4 -> 3 -> 4 (each arrow leads to the parent; a tree starts at "
       "a "
       "parent -1)"},
      {"binary data", std::string("\x01\x02\x00\xff", 4), 1,
       "expected the sample id (field 1" + field_list + ", found '\\x01\\x02\\x00\\xff'"},
      {"another format's header", "ply\nformat ascii 1.0\n", 1,
       "expected the sample id (field 1" + field_list + ", found 'ply'"},
      {"a LINK with one sample", "1 1 0 0 0 2 -1\n2 3 0 4 0 1 1\n# LINK 2\n", 3,
       "expected the second sample of a LINK line (# LINK from to), found end of line"},
      {"a LINK with three samples", "1 1 0 0 0 2 -1\n# LINK 1 2 3\n2 3 0 4 0 1 1\n", 2,
       "unexpected '3' after the two samples of a LINK line (# LINK from to)"},
      {"a LINK to a missing sample", "1 1 0 0 0 2 -1\n2 3 0 4 0 1 1\n# LINK 2 7\n", 3,
       "the LINK's sample 7 is not in the file"},
      {"a LINK of a sample to itself", "1 1 0 0 0 2 -1\n2 3 0 4 0 1 1\n# LINK 2 2\n", 3,
       "the LINK 2 2 joins a sample to itself"},
      {"a LINK that repeats a parent edge", "1 1 0 0 0 2 -1\n2 3 0 4 0 1 1\n# LINK 2 1\n", 3,
       "the LINK 2 1 repeats an edge between the same two samples"},
      {"a LINK that repeats a LINK", "1 1 0 0 0 2 -1\n2 3 0 4 0 1 1\n3 3 4 4 0 1 2\n# LINK 1 3\n# LINK 3 1\n",
       5, "the LINK 3 1 repeats an edge between the same two samples"},
      {"a LINK inside a three-point soma", "1 1 0 0 0 2 -1\n2 1 0 -2 0 2 1\n3 1 0 2 0 2 1\n# LINK 2 3\n", 4,
       "the LINK 2 3 joins two samples read as one soma node"},
  };
  for (const auto& c : cases)
    skeleton_test::check_rejected(c, "n.swc", [](const std::string& t) { (void)parse(t); });
  // A coordinate a float point cannot hold.
  skeleton_test::check_rejected(
      {"too big for float", "1 1 0 1e300 0 2 -1\n", 1,
       "the y coordinate of sample 1 (field 4" + field_list + " '1e300' is out of range"},
      "n.swc", [](const std::string& t) { (void)io::parse_swc<std::array<float, 3>>(t, "n.swc"); });
}

TEST_CASE("swc: a long cycle is named by its first sample, shortened") {
  std::string text;
  for (int i = 1; i <= 20; ++i)
    text += std::to_string(i) + " 3 0 " + std::to_string(i) + " 0 1 " + std::to_string(i == 20 ? 1 : i + 1) +
            "\n";
  skeleton_test::check_rejected({"long cycle", text, 1,
                                 "the parents form a cycle with no root: 1 -> 2 -> 3 -> 4 -> 5 -> 6 -> 7 -> "
                                 "8 -> 9 -> ... (each arrow leads to "
                                 "the parent; a tree starts at a parent -1)"},
                                "n.swc", [](const std::string& t) { (void)parse(t); });
}

TEST_CASE("swc: a 100,000-sample chain reads without deep recursion") {
  std::string text = "1 1 0 0 0 1 -1\n";
  for (int i = 2; i <= 100000; ++i)
    text += std::to_string(i) + " 3 " + std::to_string(i) + " 0 0 0.5 " + std::to_string(i - 1) + "\n";
  const auto r = parse(text);
  CHECK(r.skeleton.points.size() == 100000);
  CHECK(r.skeleton.edges.back() == edge{99998, 99999});
}

TEST_CASE_TEMPLATE("swc: write then read gives the same skeleton bit for bit", P, glm::dvec3,
                   std::array<float, 3>, sealed_point) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const auto s = skeleton_test::awkward_skeleton<P>(seed, 60);
    const std::string text = swc_text(s, {.comment = "awkward\nnumbers", .type = 3});
    CAPTURE(text);
    const auto back = io::parse_swc<P>(text, "back.swc");
    CHECK(skeleton_test::same_skeleton(s, back.skeleton));
    CHECK(back.types == std::vector<std::int32_t>(60, 3));
    // Writing what was read keeps its ids and types, and gives the same text.
    CHECK(swc_text(back, {.comment = "awkward\nnumbers"}) == text);
  }
}

TEST_CASE("swc: ids and types survive a round trip of a file") {
  const std::string text =
      "# morphology\n10 1 0 0 0 5 -1\n30 3 0 10 0 1.5 20\n20 3 0 5 0 2 10\n7 2 0 -8 0 0.5 10\n";
  const auto r = parse(text);
  // Parents first: sample 30 moves after its parent 20; ids and types stay.
  CHECK(swc_text(r) == "10 1 0 0 0 5 -1\n20 3 0 5 0 2 10\n30 3 0 10 0 1.5 20\n7 2 0 -8 0 0.5 10\n");
  const auto again = parse(swc_text(r));
  CHECK(again.ids == std::vector<std::int64_t>{10, 20, 30, 7});
  CHECK(again.types == std::vector<std::int32_t>{1, 3, 3, 2});
}

TEST_CASE("swc: a skeleton out of order is written parents first, numbered in written order") {
  cellforge::skeleton<glm::dvec3> s;
  s.points = {{0, 2, 0}, {0, 1, 0}, {0, 0, 0}, {5, 5, 5}};
  s.radii = {1, 2, 3, 4};
  s.edges = {{2, 1}, {1, 0}};
  CHECK(swc_text(s) == "1 0 0 0 0 3 -1\n2 0 0 1 0 2 1\n3 0 0 2 0 1 2\n4 0 5 5 5 4 -1\n");
}

TEST_CASE("swc: a user's skeleton type is written through its traits") {
  swc_cad::tree t;
  t.at = {{0, 0, 0}, {0, 0, 0.1}, {0.25, 0, 1e-300}};
  t.diameters = {1, 0.5, 0.25};
  t.links = {{0, 1}, {0, 2}};
  const std::string text = swc_text(t, {.type = 3});
  CHECK(text == "1 3 0 0 0 0.5 -1\n2 3 0 0 0.1 0.25 1\n3 3 0.25 0 1e-300 0.125 1\n");
  const auto back = io::parse_swc<sealed_point>(text, "t.swc");
  CHECK(back.skeleton.points == t.at);
  CHECK(back.skeleton.radii == std::vector<double>{0.5, 0.25, 0.125});
}

TEST_CASE("swc: the writer refuses what SWC cannot hold, before touching the file") {
  const auto refused = [](const cellforge::skeleton<glm::dvec3>& s, const std::string& message) {
    CAPTURE(message);
    try {
      (void)swc_text(s);
      FAIL("wrote a skeleton SWC cannot hold");
    } catch (const cellforge::error& e) {
      CHECK(e.category() == cellforge::error_category::invalid_input);
      CHECK(std::string(e.what()) == message);
    }
  };
  cellforge::skeleton<glm::dvec3> s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.radii = {1, 1, 1};
  s.edges = {{0, 2}, {1, 2}};
  s.edges = {{0, 1}};
  s.radii[1] = 0;
  refused(s, "write_swc: node 1: radius 0 is not positive");
  s.radii[1] = 1;
  s.edges = {{0, 3}};
  refused(s, "write_swc: edge 0: node 3 out of range (3 nodes)");
  s.edges = {{1, 1}};
  refused(s, "write_swc: edge 0 joins node 1 to itself");

  io::swc_result<glm::dvec3> r = parse("1 1 0 0 0 1 -1\n2 3 0 1 0 1 1\n");
  r.ids[1] = 1;
  CHECK_THROWS_WITH_AS(swc_text(r), "write_swc: sample id 1 is used twice", cellforge::error);
  r.ids[1] = 2;
  r.types[0] = -1;
  CHECK_THROWS_WITH_AS(swc_text(r), "write_swc: node 0 has the negative type -1", cellforge::error);

  s.edges = {{0, 1}, {1, 0}};
  refused(s, "write_swc: edge 1 repeats edge 0 (nodes 1 and 0)");

  // A refused skeleton leaves an existing file as it was.
  const io_test::temp_path file("keep.swc");
  std::ofstream(file.path, std::ios::binary) << "1 1 0 0 0 1 -1\n";
  s.edges = {{0, 2}, {2, 2}};
  CHECK_THROWS_AS(io::write_swc(file.path, s), cellforge::error);
  std::ifstream in(file.path, std::ios::binary);
  CHECK(std::string(std::istreambuf_iterator<char>(in), {}) == "1 1 0 0 0 1 -1\n");
}

TEST_CASE("swc: edges beyond a forest are LINK lines, written and read back") {
  // A node with two incoming edges, and a cycle: the first edge into a node that closes no
  // cycle is its parent, every other edge a LINK at the end.
  cellforge::skeleton<glm::dvec3> s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.radii = {1, 1, 1};
  s.edges = {{0, 2}, {1, 2}};
  CHECK(swc_text(s) == "1 0 0 0 0 1 -1\n2 0 1 0 0 1 -1\n3 0 0 1 0 1 1\n# LINK 2 3\n");
  s.edges = {{0, 1}, {1, 2}, {2, 0}};
  const std::string ring = swc_text(s);
  CHECK(ring == "1 0 0 0 0 1 -1\n2 0 1 0 0 1 1\n3 0 0 1 0 1 2\n# LINK 3 1\n");
  const auto back = parse(ring);
  CHECK(back.skeleton.edges == std::vector<edge>{{0, 1}, {1, 2}, {2, 0}});
  // Graphs with cycles round-trip: the same nodes and the same directed edges (tree edges
  // first, in written order, then the LINKs).
  for (const auto& g : {cellforge::samples::lattice(3, 3, 2), cellforge::samples::petersen(),
                        cellforge::samples::mobius_ladder(8)}) {
    const auto r = parse(swc_text(g));
    CHECK(r.skeleton.points == g.points);
    CHECK(r.skeleton.radii == g.radii);
    std::vector<edge> a(g.edges.begin(), g.edges.end()), b = r.skeleton.edges;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    CHECK(a == b);
    CHECK(swc_text(r) == swc_text(g));
  }
  // LINK lines may come anywhere, a LINK may name a sample defined after it, and a comment that
  // only starts with the word is prose.
  const auto early = parse(
      "# LINK 3 1\n# LINK to the paper: see the header\n1 1 0 0 0 1 -1\n2 3 0 5 0 1 1\n3 3 5 5 0 1 2\n");
  CHECK(early.skeleton.edges == std::vector<edge>{{0, 1}, {1, 2}, {2, 0}});
  // A LINK to a three-point soma's outer point joins its centre.
  const auto soma =
      parse("1 1 0 0 0 2 -1\n2 1 0 -2 0 2 1\n3 1 0 2 0 2 1\n4 3 10 0 0 1 1\n5 3 0 10 0 1 4\n# LINK 5 3\n");
  CHECK(soma.collapsed_somas == 1);
  CHECK(soma.skeleton.edges == std::vector<edge>{{0, 1}, {1, 2}, {2, 0}});
}

TEST_CASE("swc: files are read and written by path, errors naming the file") {
  const io_test::temp_path file("tree.swc");
  const auto r = parse("1 1 0 0 0 2 -1\n2 3 0 4 0 1 1\n");
  io::write_swc(file.path, r, {.comment = "written by a test"});
  const auto back = io::read_swc<glm::dvec3>(file.path);
  CHECK(back.skeleton.points == r.skeleton.points);
  CHECK(back.ids == r.ids);
  io::write_swc(file.path, r.skeleton);
  CHECK(io::read_swc<glm::dvec3>(file.path).types == std::vector<std::int32_t>{0, 0});
  io_test::check_file_errors("bad.swc", "1 1 0 0 0 2 -1\n2 3 0 4 0 -1 1\n", 2,
                             [](const std::filesystem::path& p) { (void)io::read_swc<glm::dvec3>(p); });
}

}  // namespace io_swc_tests
