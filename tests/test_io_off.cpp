// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/io/off.hpp"
#include "io_test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace io_off_tests {

namespace io = cellforge::io;
using cellforge::polygon_soup;

namespace {

// A tetrahedron-ish fixture: 4 vertices, 2 faces; the malformed cases are edits of it.
const std::string tetra = "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 3\n";

polygon_soup<glm::dvec3> parse(const std::string& text, const io::off_read_options& o = {}) {
  return io::parse_off<glm::dvec3>(text, "t.off", o);
}

}  // namespace

TEST_CASE("OFF: a plain file reads points and faces") {
  const auto s = parse(tetra);
  REQUIRE(s.num_points() == 4);
  REQUIRE(s.num_faces() == 2);
  CHECK(s.points[1] == glm::dvec3(1, 0, 0));
  CHECK(std::vector<std::uint32_t>(s.face(1).begin(), s.face(1).end()) ==
        std::vector<std::uint32_t>{0, 2, 3});
}

TEST_CASE("OFF: layout variations all read the same soup") {
  const auto expected = parse(tetra);
  const std::vector<std::pair<const char*, std::string>> variants = {
      {"CRLF line ends", "OFF\r\n4 2 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n0 0 1\r\n3 0 1 2\r\n3 0 2 3\r\n"},
      {"lone CR line ends", "OFF\r4 2 0\r0 0 0\r1 0 0\r0 1 0\r0 0 1\r3 0 1 2\r3 0 2 3\r"},
      {"no final line end", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 3"},
      {"comments and blank lines",
       "# made by hand\nOFF # header\n\n# counts\n4 2 0\n0 0 0 # origin\n1 0 0\n\n"
       "0 1 0\n0 0 1\n# faces\n3 0 1 2\n3 0 2 3 # last\n# end\n\n"},
      {"tabs and spaces", "OFF\n\t4  2\t0\n 0\t0 0 \n1 0 0\n0 1 0\n0 0 1\n3\t0 1 2\n  3 0 2 3  \n"},
      {"counts on the header line", "OFF 4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 3\n"},
      {"no header keyword", "4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 3\n"},
      {"no edge count", "OFF\n4 2\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 3\n"},
      {"byte-order mark", "\xEF\xBB\xBFOFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 3\n"},
      {"number spellings", "OFF\n4 2 0\n0.0 -0e0 +0\n1. 0 0\n.0 1e0 0\n0 0 +1.0E+0\n3 0 1 2\n3 +0 2 3\n"},
      {"face colours", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2 255 0 0\n3 0 2 3 0.5 0.5 0.5 1\n"},
      {"COFF with rgb and rgba",
       "COFF\n4 2 0\n0 0 0 1 0 0\n1 0 0 0 1 0 1\n0 1 0 0 0 1\n0 0 1 1 1 1 1\n3 0 1 2\n3 0 2 3\n"},
      {"NOFF", "NOFF\n4 2 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n0 0 1 1 0 0\n3 0 1 2\n3 0 2 3\n"},
      {"CNOFF",
       "CNOFF\n4 2 0\n0 0 0 0 0 1 1 1 1\n1 0 0 0 0 1 1 1 1 1\n0 1 0 0 0 1 1 1 1\n0 0 1 1 0 0 0 0 0\n"
       "3 0 1 2\n3 0 2 3\n"},
      {"STOFF", "STOFF\n4 2 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n0 0 1 1 1\n3 0 1 2\n3 0 2 3\n"},
  };
  for (const auto& variant : variants) {
    const std::string what = variant.first;
    const std::string& text = variant.second;
    CAPTURE(what);
    const auto s = parse(text);
    CHECK(io_test::same_soup(s, expected) == (what != "number spellings"));
    CHECK(s.points == expected.points);  // -0 == 0 for the spelled-out variant
    CHECK(s.face_vertices == expected.face_vertices);
  }
}

TEST_CASE("OFF: at least 15 kinds of malformed input are rejected with the line and the reason") {
  const std::vector<io_test::bad_input> cases = {
      {"empty file", "", 1, "empty file"},
      {"only comments", "# nothing here\n\n   \n", 1, "empty file"},
      {"bad magic", "PLY\n4 2 0\n", 1, "expected an OFF header ('OFF', 'COFF'"},
      {"header misspelt", "OFFF\n4 2 0\n", 1, "found 'OFFF'"},
      {"4D OFF", "4OFF\n4 2 0\n", 1, "4D and n-dimensional OFF ('4OFF') are not supported"},
      {"binary OFF", "OFF BINARY\n", 1, "binary OFF is not supported"},
      {"no counts", "OFF\n", 1,
       "expected the vertex, face and edge counts after the header, found end of file"},
      {"missing face count", "OFF\n4\n0 0 0\n", 2, "expected the face count, found end of line"},
      {"non-numeric count", "OFF\nfour 2 0\n", 2, "expected the vertex count, found 'four'"},
      {"negative vertex count", "OFF\n-4 2 0\n", 2, "the vertex count must not be negative, found -4"},
      {"negative face count", "OFF\n4 -2 0\n", 2, "the face count must not be negative"},
      {"overflowing count", "OFF\n99999999999999999999 2 0\n", 2,
       "the vertex count '99999999999999999999' is out of range"},
      {"count beyond 32 bits", "OFF\n4294967296 2 0\n", 2,
       "the vertex count 4294967296 exceeds the 32-bit limit"},
      {"garbage after the counts", "OFF\n4 2 0 7\n", 2,
       "unexpected '7' after the vertex, face and edge counts"},
      {"truncated vertex list", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n", 5,
       "expected 4 vertices, found 3 before end of file"},
      {"huge vertex claim", "OFF\n4000000000 2 0\n0 0 0\n", 3,
       "expected 4000000000 vertices, found 1 before end of file"},
      {"non-numeric coordinate", "OFF\n4 2 0\n0 0 0\n1 zero 0\n", 4,
       "expected coordinate y of vertex 1, found 'zero'"},
      {"number with junk", "OFF\n4 2 0\n0 0 0\n1 0 0x\n", 4, "expected coordinate z of vertex 1, found '0x'"},
      {"NaN coordinate", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 nan 0\n", 5,
       "coordinate y of vertex 2 'nan' is not finite"},
      {"Inf coordinate", "OFF\n4 2 0\n0 0 0\n-inf 0 0\n", 4, "coordinate x of vertex 1 '-inf' is not finite"},
      {"overflowing coordinate", "OFF\n4 2 0\n0 0 1e999\n", 3,
       "coordinate z of vertex 0 '1e999' is out of range"},
      {"too few coordinates", "OFF\n4 2 0\n0 0 0\n1 0\n", 4,
       "expected coordinate z of vertex 1, found end of line"},
      {"too many coordinates", "OFF\n4 2 0\n0 0 0\n1 0 0 1\n", 4,
       "vertex 1 has more than 3 values: unexpected '1'"},
      {"COFF vertex short of a colour", "COFF\n1 0 0\n0 0 0 1 1\n", 3,
       "vertex 0 has 5 values; this OFF variant needs 6 or 7"},
      {"face with 2 vertices", tetra.substr(0, 34) + "2 0 1\n3 0 2 3\n", 7,
       "face 0 has 2 vertices; a face needs at least 3"},
      {"negative face size", tetra.substr(0, 34) + "-3 0 1 2\n", 7, "face 0 has -3 vertices"},
      {"face index out of range", tetra.substr(0, 42) + "3 0 2 4\n", 8,
       "face 1: vertex index 4 out of range (0..3)"},
      {"negative face index", tetra.substr(0, 34) + "3 0 -1 2\n", 7,
       "face 0: vertex index -1 out of range (0..3)"},
      {"fractional face index", tetra.substr(0, 34) + "3 0 1.5 2\n", 7,
       "expected vertex 1 of face 0, found '1.5'"},
      {"list shorter than its count", tetra.substr(0, 34) + "4 0 1 2\n", 7,
       "expected vertex 3 of face 0, found end of line"},
      {"unterminated last face", tetra.substr(0, 42) + "3 0 2", 8,
       "expected vertex 2 of face 1, found end of file"},
      {"face colour too long", tetra.substr(0, 34) + "3 0 1 2 1 1 1 1 1\n", 7,
       "than a colour (at most 4): unexpected '1'"},
      {"repeated vertex in a face", tetra.substr(0, 34) + "3 0 1 1\n", 7, "face 0 uses vertex 1 twice"},
      {"fewer faces than counted", tetra.substr(0, 42), 7, "expected 2 faces, found 1 before end of file"},
      {"more faces than counted", tetra + "3 1 2 3\n", 9, "unexpected '3' after the last of 2 faces"},
      {"trailing garbage", tetra + "\n\nend\n", 11, "unexpected 'end' after the last of 2 faces"},
      {"binary junk", std::string("\x01\x02\x00\xff", 4), 1, "found '\\x01\\x02\\x00\\xff'"},
  };
  CHECK(cases.size() >= 15);
  for (const auto& c : cases)
    io_test::check_rejected(c, "t.off", [](const std::string& s) { (void)parse(s); });
}

TEST_CASE("OFF: repeated vertices are accepted when asked") {
  const std::string text = tetra.substr(0, 34) + "3 0 1 1\n3 0 2 3\n";
  const auto s = parse(text, {.allow_repeated_vertices = true});
  CHECK(s.num_faces() == 2);
  CHECK(s.face(0)[2] == 1);
}

TEST_CASE("OFF: a large face's repeated vertex is found too") {
  std::string text = "OFF\n40 1 0\n";
  for (int i = 0; i < 40; ++i) text += std::to_string(i) + " 0 0\n";
  text += "40";
  for (int i = 0; i < 40; ++i) text += ' ' + std::to_string(i == 33 ? 5 : i);
  io_test::check_rejected({"big face", text, 43, "face 0 uses vertex 5 twice"}, "t.off",
                          [](const std::string& s) { (void)parse(s); });
}

TEST_CASE("OFF: float points read the nearest float directly, integer points need whole numbers") {
  const auto f = io::parse_off<std::array<float, 3>>("OFF\n1 0 0\n0.1 1e-50 3.4028235e38\n");
  CHECK(f.points[0][0] == 0.1f);
  CHECK(f.points[0][1] == 0.0f);  // underflow rounds to zero
  CHECK(f.points[0][2] == std::numeric_limits<float>::max());
  io_test::check_rejected(
      {"float overflow", "OFF\n1 0 0\n0 0 1e39\n", 3, "'1e39' is out of range"}, "t.off",
      [](const std::string& s) { (void)io::parse_off<std::array<float, 3>>(s, "t.off"); });
  const auto i = io::parse_off<std::array<int, 3>>("OFF\n1 0 0\n2.0 -3 4e2\n");
  CHECK(i.points[0] == std::array<int, 3>{2, -3, 400});
  io_test::check_rejected(
      {"fraction for int", "OFF\n1 0 0\n2.5 0 0\n", 3, "'2.5' does not fit the point's scalar type"}, "t.off",
      [](const std::string& s) { (void)io::parse_off<std::array<int, 3>>(s, "t.off"); });
}

TEST_CASE_TEMPLATE("OFF: write then read gives the same soup bit for bit", P, glm::dvec3,
                   std::array<float, 3>, io_test::user_point, std::array<int, 3>) {
  const auto soup = io_test::awkward_soup<P>(7, 300, 200);
  std::ostringstream os;
  io::write_off(os, soup, {.comment = "round trip\nsecond line"});
  CHECK(os.str().starts_with("OFF\n# round trip\n# second line\n300 200 0\n"));
  const auto back = io::parse_off<P>(os.str());
  CHECK(io_test::same_soup(back, soup));

  const io_test::temp_path file("rt.off");
  io::write_off(file.path, soup);
  CHECK(io_test::same_soup(io::read_off<P>(file.path), soup));
}

TEST_CASE("OFF: an empty soup round-trips") {
  std::ostringstream os;
  io::write_off(os, polygon_soup<glm::dvec3>{});
  CHECK(os.str() == "OFF\n0 0 0\n");
  const auto s = parse(os.str());
  CHECK(s.num_points() == 0);
  CHECK(s.num_faces() == 0);
}

TEST_CASE("OFF: writing refuses what reading would reject") {
  polygon_soup<glm::dvec3> s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}};
  s.add_face({0, 1, 2});
  std::ostringstream os;
  CHECK_THROWS_WITH_AS(io::write_off(os, s), "write_off: point 2 has a non-finite coordinate",
                       cellforge::error);
  s.points[2].y = 1;
  s.add_face({0, 1, 3});
  CHECK_THROWS_WITH_AS(io::write_off(os, s), "write_off: face vertex index 3 out of range (3 points)",
                       cellforge::error);
  s.face_vertices.pop_back();
  s.face_offsets.back() = 5;
  CHECK_THROWS_WITH_AS(io::write_off(os, s), "write_off: face 1 has fewer than 3 vertices", cellforge::error);
}

TEST_CASE("OFF: file errors name the path") {
  const auto dir = std::filesystem::temp_directory_path() / "cellforge_no_such_dir" / "out.off";
  CHECK_THROWS_WITH_AS(io::write_off(dir, polygon_soup<glm::dvec3>{}),
                       ("cannot open '" + dir.string() + "' for writing").c_str(), cellforge::error);
  if (std::filesystem::exists("/dev/full")) {  // a device where every write fails: disk full
    polygon_soup<glm::dvec3> s;
    s.points = {{0, 0, 0}};
    CHECK_THROWS_WITH_AS(io::write_off("/dev/full", s),
                         "cannot write '/dev/full': writing OFF failed (stream error)", cellforge::error);
  }
  io_test::check_file_errors("bad.off", "OFF\n1 0 0\n0 0\n", 3,
                             [](const std::filesystem::path& p) { (void)io::read_off<glm::dvec3>(p); });
}

TEST_CASE("OFF: a write that fails leaves the old file as it was, and no partial file") {
  const auto dir = std::filesystem::temp_directory_path() / "cellforge_write_atomic";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto path = dir / "kept.off";
  polygon_soup<glm::dvec3> good;
  good.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  good.add_face({0, 1, 2});
  io::write_off(path, good);
  const auto read_back = [&] {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  const std::string before = read_back();
  auto bad = good;
  bad.face_vertices.push_back(7);  // a face naming a point that does not exist
  bad.face_offsets.push_back(static_cast<std::uint32_t>(bad.face_vertices.size()));
  CHECK_THROWS_AS(io::write_off(path, bad), cellforge::error);
  CHECK(read_back() == before);
  CHECK(!std::filesystem::exists(dir / "kept.off.partial"));
  // A folder is refused by name, and nothing is created beside it.
  CHECK_THROWS_WITH_AS(io::write_off(dir, good),
                       ("cannot open '" + dir.string() + "' for writing: it is a folder").c_str(),
                       cellforge::error);
  CHECK(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator{}) == 1);
  std::filesystem::remove_all(dir);
}

}  // namespace io_off_tests
