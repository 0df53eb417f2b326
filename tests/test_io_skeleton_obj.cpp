// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/io/skeleton_obj.hpp"
#include "io_test_support.hpp"
#include "skeleton_test_support.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace io_skeleton_obj_tests {

namespace io = cellforge::io;
using edge = std::array<std::uint32_t, 2>;
using test_support::sealed_point;

namespace {

io::skeleton_obj_data<glm::dvec3> parse(const std::string& text,
                                        const io::skeleton_obj_read_options& o = {}) {
  return io::parse_skeleton_obj<glm::dvec3>(text, "s.obj", o);
}

template <class G>
std::string obj_text(const G& g, const io::skeleton_obj_write_options& o = {}) {
  std::ostringstream os;
  io::write_skeleton_obj(os, g, o);
  return os.str();
}

}  // namespace

TEST_CASE("skeleton obj: v with a radius, l polylines as directed edges") {
  const std::string text =
      "# a Y with a loop\n"
      "o vessels\n"
      "v 0 0 0 2\n"
      "v 0 0 5 1.5\n"
      "v 3 0 8 1\n"
      "v -3 0 8 0.5\n"
      "l 1 2 3\n"
      "l 2 -1\n"    // relative: the last vertex defined, 4
      "l 3 4/7\n";  // a texture index is allowed and ignored
  const auto d = parse(text);
  const auto& s = d.skeleton;
  REQUIRE(s.points.size() == 4);
  CHECK(s.points[3] == glm::dvec3(-3, 0, 8));
  CHECK(s.radii == std::vector<double>{2, 1.5, 1, 0.5});
  CHECK(s.edges == std::vector<edge>{{0, 1}, {1, 2}, {1, 3}, {2, 3}});
  CHECK(d.uniform_radius_nodes == 0);
  CHECK(d.skipped_statements == 0);
}

TEST_CASE("skeleton obj: the uniform radius stands in for a missing fourth value") {
  const std::string text = "v 0 0 0\nv 1 0 0 0.25\nv 2 0 0 1 0 0\nvn 0 0 1\nl 1 2 3\nusemtl red\nfoo bar\n";
  const auto d = parse(text, {.uniform_radius = 0.5});
  CHECK(d.skeleton.radii ==
        std::vector<double>{0.5, 0.25, 0.5});  // a fourth value wins; colours take the uniform one
  CHECK(d.uniform_radius_nodes == 2);
  CHECK(d.skipped_statements == 1);
  CHECK(d.first_skipped_line == 7);
  CHECK_THROWS_AS(parse(text, {.uniform_radius = 0.5, .strict = true}), cellforge::error);
  CHECK_THROWS_WITH_AS(parse(text, {.uniform_radius = -1}),
                       "skeleton_obj_read_options::uniform_radius must be positive (or 0 for none), found -1",
                       cellforge::error);
  CHECK_THROWS_AS(parse(text, {.uniform_radius = std::numeric_limits<double>::quiet_NaN()}),
                  cellforge::error);
}

TEST_CASE("skeleton obj: malformed files name the line and say exactly what is wrong") {
  const std::vector<skeleton_test::bad_input> cases = {
      {"no radius", "v 0 0 0 1\nv 1 0 0\n", 2,
       "vertex 2 has no radius: give it as a 4th value or set skeleton_obj_read_options::uniform_radius"},
      {"negative radius", "v 0 0 0 -2\n", 1,
       "the radius of vertex 1 (the 4th value), '-2', must be positive"},
      {"zero radius", "v 0 0 0 0\n", 1, "the radius of vertex 1 (the 4th value), '0', must be positive"},
      {"NaN radius", "v 0 0 0 nan\n", 1, "the radius of vertex 1 (the 4th value), 'nan', is not finite"},
      {"radius not a number", "v 0 0 0 r\n", 1, "expected value 4 of vertex 1, found 'r'"},
      {"five values", "v 0 0 0 1 2\n", 1,
       "'v' takes x y z r (or x y z [r g b [a]] with a uniform radius); found 5 values"},
      {"eight values", "v 0 0 0 1 1 1 1 1\n", 1,
       "too many values for 'v' (x y z r, or x y z r g b [a] with the uniform radius): unexpected '1'"},
      {"NaN coordinate", "v 0 nan 0 1\n", 1,
       "coordinate y of vertex 1 'nan' is not finite (NaN and Inf coordinates are rejected)"},
      {"two coordinates", "v 0 0\n", 1, "expected coordinate z of vertex 1, found end of line"},
      {"huge coordinate", "v 1e999 0 0 1\n", 1, "coordinate x of vertex 1 '1e999' is out of range"},
      {"index out of range", "v 0 0 0 1\nv 1 0 0 1\nl 1 3\n", 3,
       "line index 3 out of range (1..2); vertices must be defined before the lines that use them"},
      {"relative index out of range", "v 0 0 0 1\nl 1 -2\n", 2,
       "relative line index -2 out of range (-1..-1)"},
      {"index zero", "v 0 0 0 1\nl 0 1\n", 2, "vertex index 0 is invalid (OBJ indices start at 1)"},
      {"index not a number", "v 0 0 0 1\nl 1 x\n", 2,
       "expected a vertex reference (v, v/vt, v//vn or v/vt/vn), found 'x'"},
      {"zero-length segment", "v 0 0 0 1\nv 1 0 0 1\nl 1 2 2\n", 3,
       "line segment from vertex 2 to itself (zero length)"},
      {"one-vertex line", "v 0 0 0 1\nl 1\n", 2, "'l' needs at least 2 vertices, found 1"},
      {"repeated segment", "v 0 0 0 1\nv 1 0 0 1\nv 2 0 0 1\nl 1 2 3\n# back again\nl 3 2\n", 6,
       "the segment from vertex 3 to 2 repeats the one on line 4"},
      {"a face", "v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nf 1 2 3\n", 4,
       "a face in a skeleton file: skeletons are 'v' and 'l' (read surfaces with read_obj)"},
      {"not a statement", "v 0 0 0 1\n12 3\n", 2, "not an OBJ statement: '12'"},
      {"binary data", std::string("\x7f\x45\x4c\x46\x02", 5), 1, "not an OBJ statement: '\\x7fELF\\x02'"},
  };
  for (const auto& c : cases)
    skeleton_test::check_rejected(c, "s.obj", [](const std::string& t) { (void)parse(t); });
  skeleton_test::check_rejected(
      {"unknown statement when strict", "v 0 0 0 1\nvx 1\n", 2, "unknown statement 'vx'"}, "s.obj",
      [](const std::string& t) { (void)parse(t, {.strict = true}); });
}

TEST_CASE_TEMPLATE("skeleton obj: write then read gives the same skeleton bit for bit", P, glm::dvec3,
                   std::array<float, 3>, sealed_point) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const auto s = skeleton_test::awkward_skeleton<P>(seed, 60, 15);  // a forest plus cycles
    const std::string text = obj_text(s, {.comment = "awkward"});
    CAPTURE(text);
    const auto back = io::parse_skeleton_obj<P>(text, "back.obj");
    CHECK(skeleton_test::same_skeleton(s, back.skeleton));
    CHECK(obj_text(back.skeleton, {.comment = "awkward"}) == text);
  }
}

TEST_CASE("skeleton obj: the writer's form") {
  cellforge::skeleton<glm::dvec3> s;
  s.points = {{0, 0, 0}, {0.1, 0, 0}, {0, 0, 0}};  // coincident nodes are written: the reader accepts them
  s.radii = {1, 0.5, 0.25};
  s.edges = {{0, 1}, {2, 1}};
  CHECK(obj_text(s) == "v 0 0 0 1\nv 0.1 0 0 0.5\nv 0 0 0 0.25\nl 1 2\nl 3 2\n");
  s.edges.push_back({1, 0});
  CHECK_THROWS_WITH_AS(obj_text(s), "write_skeleton_obj: edge 2 repeats edge 0 (nodes 1 and 0)",
                       cellforge::error);
  s.edges.pop_back();
  s.radii[2] = -1;
  CHECK_THROWS_WITH_AS(obj_text(s), "write_skeleton_obj: node 2: radius -1 is not positive",
                       cellforge::error);

  // A refused skeleton leaves an existing file as it was.
  const io_test::temp_path file("keep.obj");
  std::ofstream(file.path, std::ios::binary) << "v 0 0 0 1\n";
  CHECK_THROWS_AS(io::write_skeleton_obj(file.path, s), cellforge::error);
  std::ifstream in(file.path, std::ios::binary);
  CHECK(std::string(std::istreambuf_iterator<char>(in), {}) == "v 0 0 0 1\n");
}

TEST_CASE("skeleton obj: files are read and written by path, errors naming the file") {
  const io_test::temp_path file("tree.obj");
  const auto s = skeleton_test::awkward_skeleton<glm::dvec3>(9, 20, 3);
  io::write_skeleton_obj(file.path, s);
  CHECK(skeleton_test::same_skeleton(io::read_skeleton_obj<glm::dvec3>(file.path).skeleton, s));
  io_test::check_file_errors("bad.obj", "v 0 0 0 1\nv 1 0 0\n", 2, [](const std::filesystem::path& p) {
    (void)io::read_skeleton_obj<glm::dvec3>(p);
  });
}

}  // namespace io_skeleton_obj_tests
