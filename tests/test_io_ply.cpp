// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/io/ply.hpp"
#include "io_test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace io_ply_tests {

namespace io = cellforge::io;
using cellforge::polygon_soup;

namespace {

const std::string header_ascii =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n";  // 9 lines
const std::string vertices_ascii = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";           // lines 10-13
const std::string tetra_ascii = header_ascii + vertices_ascii + "3 0 1 2\n3 0 2 3\n";

polygon_soup<glm::dvec3> parse(const std::string& text, const io::ply_read_options& o = {}) {
  return io::parse_ply<glm::dvec3>(text, "t.ply", o);
}

/// Builds binary PLY bytes: a header, then values appended in the file's byte order.
struct binary_ply {
  std::string bytes;
  bool little = true;
  binary_ply(const std::string& body_header, bool little_endian = true) : little(little_endian) {
    bytes = std::string("ply\nformat ") + (little ? "binary_little_endian" : "binary_big_endian") + " 1.0\n" +
            body_header + "end_header\n";
  }
  template <class T>
  binary_ply& operator()(T v) {
    char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    if ((std::endian::native == std::endian::little) != little) std::reverse(raw, raw + sizeof(T));
    bytes.append(raw, sizeof(T));
    return *this;
  }
  template <class T>
  binary_ply& face(std::uint8_t n, std::initializer_list<T> indices) {
    (*this)(n);
    for (const T i : indices) (*this)(i);
    return *this;
  }
};

const std::string tetra_layout =
    "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 2\nproperty list uchar int vertex_indices\n";

binary_ply tetra_vertices(bool little = true) {
  binary_ply b(tetra_layout, little);
  for (const auto& p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
    b(p.x)(p.y)(p.z);
  return b;
}

/// A binary input that must fail at byte `offset` with `message` in the text.
void check_binary_rejected(const char* what, const std::string& bytes, std::size_t offset,
                           const char* message) {
  CAPTURE(std::string(what));
  try {
    (void)parse(bytes);
    FAIL("accepted malformed binary input");
  } catch (const cellforge::error& e) {
    const std::string text = e.what();
    CAPTURE(text);
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(e.line() == 0);
    CHECK(e.byte_offset() == offset);
    CHECK(e.message().find(message) != std::string::npos);
    CHECK(text.starts_with("t.ply (byte " + std::to_string(offset) + "): "));
  }
}

std::vector<std::uint32_t> face(const polygon_soup<glm::dvec3>& s, std::size_t f) {
  return {s.face(f).begin(), s.face(f).end()};
}

}  // namespace

TEST_CASE("PLY: ASCII, little- and big-endian files of one tetrahedron read alike") {
  const auto a = parse(tetra_ascii);
  REQUIRE(a.num_points() == 4);
  REQUIRE(a.num_faces() == 2);
  CHECK(a.points[3] == glm::dvec3(0, 0, 1));
  CHECK(face(a, 1) == std::vector<std::uint32_t>{0, 2, 3});
  for (const bool little : {true, false}) {
    CAPTURE(little);
    auto b = tetra_vertices(little);
    b.face<std::int32_t>(3, {0, 1, 2}).face<std::int32_t>(3, {0, 2, 3});
    CHECK(io_test::same_soup(parse(b.bytes), a));
  }
}

TEST_CASE("PLY: other properties and elements are skipped, whatever their types") {
  binary_ply b(
      "comment made by a test\nobj_info nothing\nelement material 2\nproperty list uint8 float32 params\n"
      "property uchar kind\nelement vertex 3\nproperty double z\nproperty uchar red\nproperty list ushort "
      "int16 "
      "rings\nproperty float64 x\nproperty short y\nelement face 1\nproperty uchar flags\nproperty list uint "
      "ushort vertex_index\nproperty list uchar double weights\nelement edge 2\nproperty int a\nproperty int "
      "b\n");
  b(std::uint8_t{2})(1.5f)(2.5f)(std::uint8_t{7});  // material 0
  b(std::uint8_t{0})(std::uint8_t{9});              // material 1
  for (int v = 0; v < 3; ++v) {
    b(double(v) / 4)(std::uint8_t{200})(std::uint16_t{1})(std::int16_t{-1})(double(v))(std::int16_t(-v));
  }
  b(std::uint8_t{1})(std::uint32_t{3})(std::uint16_t{2})(std::uint16_t{1})(std::uint16_t{0});
  b(std::uint8_t{1})(3.0);
  b(0)(1)(1)(2);  // the edges
  const auto s = parse(b.bytes);
  REQUIRE(s.num_points() == 3);
  CHECK(s.points[2] == glm::dvec3(2, -2, 0.5));
  CHECK(face(s, 0) == std::vector<std::uint32_t>{2, 1, 0});
}

TEST_CASE("PLY: ASCII header variations") {
  const auto expected = parse(tetra_ascii);
  std::string crlf;
  for (const char ch : tetra_ascii) crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
  CHECK(io_test::same_soup(parse(crlf), expected));
  const std::string sized =
      "ply\nformat ascii 1\ncomment sized names\nelement vertex 4\nproperty float32 x\nproperty int8 y\n"
      "property uint16 z\nelement face 2\nproperty list int8 uint32 vertex_indices\nend_header\n" +
      vertices_ascii + "\n3 0 1 2\n\n3 0 2 3";
  CHECK(io_test::same_soup(parse(sized), expected));
}

TEST_CASE("PLY: faces may come before the vertices") {
  const std::string text =
      "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\nend_header\n3 2 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  CHECK(face(parse(text), 0) == std::vector<std::uint32_t>{2, 1, 0});
  std::string bad = text;
  bad.replace(bad.find("3 2 1 0"), 7, "3 2 1 3");
  io_test::check_rejected({"late out of range", bad, 10, "face 0: vertex index 3 out of range (0..2)"},
                          "t.ply", [](const std::string& s) { (void)parse(s); });
}

TEST_CASE("PLY: at least 15 kinds of malformed ASCII input are rejected with the line and the reason") {
  const auto with = [](std::string text, const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const std::string& t = tetra_ascii;
  const std::vector<io_test::bad_input> cases = {
      {"empty file", "", 1, "empty file: expected 'ply'"},
      {"bad magic", "PLY\nformat ascii 1.0\n", 1,
       "not a PLY file: expected 'ply' on the first line, found 'PLY'"},
      {"an OFF file", "OFF\n4 2 0\n", 1, "found 'OFF'"},
      {"unknown format", with(t, "ascii", "binary_middle_endian"), 2,
       "unknown PLY format 'binary_middle_endian'"},
      {"unknown version", with(t, "1.0", "2.0"), 2, "unsupported PLY version '2.0'"},
      {"no format line", "ply\nelement vertex 0\nend_header\n", 1, "the header has no 'format' line"},
      {"no end_header", "ply\nformat ascii 1.0\nelement vertex 0\n", 3,
       "the header has no 'end_header' line"},
      {"unknown header keyword", with(t, "element face", "elemnt face"), 7,
       "unknown header line starting with 'elemnt'"},
      {"unknown property type", with(t, "float y", "float128 y"), 5, "unknown property type 'float128'"},
      {"property before element", "ply\nformat ascii 1.0\nproperty float x\n", 3,
       "'property' before any 'element'"},
      {"negative count", with(t, "vertex 4", "vertex -4"), 3,
       "the count of element 'vertex' must not be negative"},
      {"overflowing count", with(t, "vertex 4", "vertex 99999999999999999999"), 3,
       "'99999999999999999999' is out of range"},
      {"count beyond 32 bits", with(t, "vertex 4", "vertex 4294967295"), 3,
       "more than 32-bit indices can address"},
      {"element declared twice", with(t, "element face", "element vertex 1\nproperty int q\nelement face"), 7,
       "element 'vertex' is declared twice"},
      {"missing z", with(t, "property float z\n", ""), 3, "element 'vertex' has no property 'z'"},
      {"x is a list", with(t, "property float x", "property list uchar float x"), 3,
       "property 'x' of element 'vertex' is a list"},
      {"face without indices", with(t, "vertex_indices", "corners"), 7,
       "element 'face' has no 'vertex_indices'"},
      {"float indices", with(t, "uchar int", "uchar float"), 7,
       "the indices of 'vertex_indices' must have an integer type, not 'float'"},
      {"float list count", with(t, "uchar int", "float int"), 8,
       "a list count type must be an integer type, found 'float'"},
      {"truncated vertex list", header_ascii + "0 0 0\n1 0 0\n0 1 0\n", 12,
       "expected 4 'vertex' elements, found 3 before end of file"},
      {"non-numeric coordinate", with(t, "1 0 0", "1 a 0"), 11,
       "expected property 'y' of vertex 1, found 'a'"},
      {"NaN coordinate", with(t, "1 0 0", "NaN 0 0"), 11, "property 'x' of vertex 1 'NaN' is not finite"},
      {"too few values", with(t, "1 0 0", "1 0"), 11, "expected property 'z' of vertex 1, found end of line"},
      {"too many values", with(t, "1 0 0", "1 0 0 0"), 11,
       "unexpected '0' after the last property of vertex 1"},
      {"face with 2 vertices", with(t, "3 0 1 2", "2 0 1"), 14,
       "face 0 has 2 vertices; a face needs at least 3"},
      {"face index out of range", with(t, "3 0 2 3", "3 0 2 4"), 15,
       "face 1: vertex index 4 out of range (0..3)"},
      {"negative face index", with(t, "3 0 1 2", "3 0 -1 2"), 14,
       "face 0: vertex index -1 out of range (0..3)"},
      {"list longer than the line", with(t, "3 0 1 2", "5 0 1 2"), 14,
       "expected vertex 3 of face 0, found end of line"},
      {"list count beyond its type", with(t, "3 0 1 2", "300 0 1 2"), 14, "'300' is out of range"},
      {"fewer faces than counted", header_ascii + vertices_ascii + "3 0 1 2\n", 14,
       "expected 2 'face' elements, found 1"},
      {"trailing garbage", t + "garbage\n", 16, "unexpected 'garbage' after the last element"},
      {"repeated vertex in a face", with(t, "3 0 1 2", "3 0 1 1"), 14, "face 0 uses vertex 1 twice"},
      {"integer coordinate out of its type", with(with(t, "float x", "uchar x"), "1 0 0", "256 0 0"), 11,
       "'256' is out of range"},
  };
  CHECK(cases.size() >= 15);
  for (const auto& c : cases)
    io_test::check_rejected(c, "t.ply", [](const std::string& s) { (void)parse(s); });
}

TEST_CASE(
    "PLY: at least 15 kinds of malformed binary input are rejected with the byte offset and the reason") {
  const std::size_t data = tetra_vertices().bytes.size() - 48;  // where the body starts
  const auto complete = [] { return tetra_vertices().face<std::int32_t>(3, {0, 1, 2}); };

  check_binary_rejected("truncated vertex list", tetra_vertices().bytes.substr(0, data + 40), data + 40,
                        "file ends inside vertex 3");
  check_binary_rejected("no faces", tetra_vertices().bytes, data + 48, "file ends inside face 0");
  check_binary_rejected("truncated face", complete().bytes + std::string("\x03\x00\x00", 3), data + 64,
                        "file ends inside face 1");
  check_binary_rejected("list count too large", tetra_vertices().face<std::int32_t>(200, {0, 1, 2}).bytes,
                        data + 61, "file ends inside face 0");
  check_binary_rejected("index out of range", complete().face<std::int32_t>(3, {0, 2, 4}).bytes, data + 70,
                        "face 1: vertex index 4 out of range (0..3)");
  check_binary_rejected("negative index", complete().face<std::int32_t>(3, {0, -2, 3}).bytes, data + 66,
                        "face 1: vertex index -2 out of range (0..3)");
  check_binary_rejected("face with 2 vertices", complete().face<std::int32_t>(2, {0, 2}).bytes, data + 61,
                        "face 1 has 2 vertices; a face needs at least 3");
  check_binary_rejected("repeated vertex", complete().face<std::int32_t>(3, {0, 3, 3}).bytes, data + 61,
                        "face 1 uses vertex 3 twice");
  check_binary_rejected("trailing bytes", complete().face<std::int32_t>(3, {0, 2, 3}).bytes + "abc",
                        data + 74, "3 bytes of unexpected data after the last element");
  {
    binary_ply b(tetra_layout);
    b(0.f)(0.f)(0.f)(1.f)(std::numeric_limits<float>::quiet_NaN())(0.f);
    check_binary_rejected("NaN coordinate", b.bytes, data + 16,
                          "property 'y' of vertex 1 (nan) is not finite");
  }
  {
    binary_ply b(tetra_layout);
    b(0.f)(0.f)(std::numeric_limits<float>::infinity());
    check_binary_rejected("Inf coordinate", b.bytes, data + 8,
                          "property 'z' of vertex 0 (inf) is not finite");
  }
  {
    binary_ply b(
        "element vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
        "property list char int vertex_indices\n");
    b(0.f)(0.f)(0.f)(std::int8_t{-1});
    check_binary_rejected("negative list count", b.bytes, b.bytes.size() - 1,
                          "face 0 has a negative list length (-1)");
  }
  {
    binary_ply b("element vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n");
    b(0.f)(0.f)(0.f);
    check_binary_rejected("huge vertex claim", b.bytes, b.bytes.size(), "file ends inside vertex 1");
  }
  {
    binary_ply b("element edge 1000000000000000000\nproperty int a\nproperty int b\n");
    b(1)(2)(3);
    check_binary_rejected("huge skipped element claim", b.bytes, b.bytes.size(), "file ends inside edge 1");
  }
  {
    binary_ply b("element edge 1000000000000000000\nproperty list uchar int a\n");
    b(std::uint8_t{1})(2)(std::uint8_t{5})(3);
    check_binary_rejected("huge skipped list element claim", b.bytes, b.bytes.size(),
                          "file ends inside edge 1");
  }
  {
    binary_ply b(
        "element face 1\nproperty list uchar int vertex_indices\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\n");
    const std::size_t at = b.bytes.size();
    b.face<std::int32_t>(3, {0, 1, 3});
    for (int i = 0; i < 9; ++i) b(0.f);
    check_binary_rejected("faces before vertices, index out of range", b.bytes, at,
                          "face 0: vertex index 3 out of range (0..2)");
  }
}

TEST_CASE("PLY: repeated vertices are accepted when asked") {
  std::string t = tetra_ascii;
  t.replace(t.find("3 0 1 2"), 7, "3 0 1 1");
  CHECK(face(parse(t, {.allow_repeated_vertices = true}), 0) == std::vector<std::uint32_t>{0, 1, 1});
}

TEST_CASE_TEMPLATE("PLY: write then read gives the same soup bit for bit in every format", P, glm::dvec3,
                   std::array<float, 3>, io_test::user_point, std::array<std::int16_t, 3>) {
  auto soup = io_test::awkward_soup<P>(5, 400, 300);
  // One face over 255 vertices, so the list count needs a wider type than uchar.
  std::vector<std::uint32_t> big(300);
  for (std::uint32_t i = 0; i < 300; ++i) big[i] = i;
  soup.add_face(big);
  for (const auto format :
       {io::ply_format::ascii, io::ply_format::binary_little_endian, io::ply_format::binary_big_endian}) {
    CAPTURE(static_cast<int>(format));
    std::ostringstream os;
    io::write_ply(os, soup, {.format = format, .comment = "cellforge test"});
    CHECK(os.str().find("comment cellforge test\n") != std::string::npos);
    CHECK(os.str().find("property list ushort int vertex_indices\n") != std::string::npos);
    CHECK(io_test::same_soup(io::parse_ply<P>(os.str()), soup));
  }
  const io_test::temp_path file("rt.ply");
  io::write_ply(file.path, soup);
  CHECK(io_test::same_soup(io::read_ply<P>(file.path), soup));
}

TEST_CASE("PLY: the header declares the point's own scalar type") {
  polygon_soup<std::array<float, 3>> s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.add_face({0, 1, 2});
  std::ostringstream os;
  io::write_ply(os, s, {.format = io::ply_format::ascii});
  CHECK(os.str() ==
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
}

TEST_CASE("PLY: writing refuses what reading would reject") {
  polygon_soup<glm::dvec3> s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, std::numeric_limits<double>::infinity()}};
  s.add_face({0, 1, 2});
  std::ostringstream os;
  CHECK_THROWS_WITH_AS(io::write_ply(os, s), "write_ply: point 2 has a non-finite coordinate",
                       cellforge::error);
  s.points[2].z = 0;
  s.face_vertices[2] = 7;
  CHECK_THROWS_WITH_AS(io::write_ply(os, s), "write_ply: face vertex index 7 out of range (3 points)",
                       cellforge::error);
}

TEST_CASE("PLY: file errors name the path") {
  io_test::check_file_errors("bad.ply", tetra_vertices().bytes, 0,
                             [](const std::filesystem::path& p) { (void)io::read_ply<glm::dvec3>(p); });
}

}  // namespace io_ply_tests
