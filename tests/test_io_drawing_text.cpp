// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <glm/vec2.hpp>

#include "cellforge/io/drawing_text.hpp"
#include "cellforge/sketch/sample_drawings.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace io_drawing_text_tests {

namespace io = cellforge::io;
using cellforge::line_drawing;
using edge = std::array<std::uint32_t, 2>;

namespace {

line_drawing<glm::dvec2> parse(const std::string& text) { return io::parse_drawing_text(text, "d.txt"); }

/// The message and line of the io error parsing `text` throws.
std::pair<std::string, std::uint64_t> failure(const std::string& text) {
  try {
    (void)parse(text);
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(e.where().file == "d.txt");
    return {e.message(), e.where().line};
  }
  FAIL("no error for: " << text);
  return {};
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("drawing text: junctions in file order, edges by index, comments and blank lines") {
  const std::string text =
      "# a square with a diagonal\n"
      "\n"
      "j 0 0\n"
      "j 1 0   # junction 1\n"
      "e 0 1\n"
      "e 1 2\n"  // junction 2 comes later: fine
      "j 1 1\r\n"
      "j 0 1\n"
      "e 2 3\n"
      "\te 3 0\n"
      "e 0 2";
  const auto d = parse(text);
  CHECK(d.points == std::vector<glm::dvec2>{{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  CHECK(d.edges == std::vector<edge>{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}});
  CHECK(cellforge::validate_drawing(d).ok());
  CHECK(parse("").points.empty());
  CHECK(parse("\xEF\xBB\xBFj 1 2\nj 3 4\ne 1 0\n").edges.size() == 1);
  // Other point types: float, a std::array.
  const auto f = io::parse_drawing_text<glm::vec2>("j 0.1 2\nj 3 4\ne 0 1\n");
  CHECK(f.points[0].x == 0.1f);
  const auto a = io::parse_drawing_text<std::array<double, 2>>("j -1.5e3 +2\nj 3 4\ne 0 1\n");
  CHECK(a.points[0] == std::array<double, 2>{-1500, 2});
}

TEST_CASE("drawing text: every error names its line and what was expected") {
  const auto check = [](const std::string& text, std::uint64_t line, const std::string& part) {
    const auto result = failure(text);
    const std::string message = result.first;
    const std::uint64_t at = result.second;
    CHECK_MESSAGE(at == line, message);
    CHECK_MESSAGE(message.find(part) != std::string::npos, message);
  };
  check("j 0 0\nj x 0\n", 2, "expected coordinate x of junction 1 (j x y), found 'x'");
  check("j 0 0\nj 1\n", 2, "expected coordinate y of junction 1 (j x y), found end of line");
  check("j 0 0 7\n", 1, "unexpected '7' after the 2 coordinates of junction 0");
  check("j 0 nan\n", 1, "is not finite");
  check("j 0 inf\n", 1, "is not finite");
  check("j 0 1e999\n", 1, "out of range");
  check("j 0 0\nj 1 1\n\ne 0\n", 4,
        "expected the second junction index of edge 0 (e a b), found end of line");
  check("j 0 0\nj 1 1\ne 0 1.5\n", 3, "expected the second junction index of edge 0");
  check("j 0 0\nj 1 1\ne 0 1 2\n", 3, "unexpected '2' after the 2 junction indices of edge 0");
  check("j 0 0\nj 1 1\ne 0 -1\n", 3, "is negative");
  check("j 0 0\nj 1 1\ne 0 1\ne 1 5\nj 2 2\n", 4, "junction index 5 of edge 1 out of range (3 junctions");
  check("j 0 0\ne 0 0\n", 2, "edge 0 joins junction 0 to itself");
  check("j 0 0\nj 1 1\ne 0 1\n# x\ne 1 0\n", 5, "edge 1 repeats edge 0 (line 3");
  check("j 0 0\na 0 1 2\n", 2, "arcs are not read yet");
  check("j 0 0\nv 1 2 3\n", 2,
        "expected 'j x y' (a junction), 'e a b' (an edge) or a '#' comment, found 'v'");
  check("j0 0\n", 1, "found 'j0'");
}

TEST_CASE("drawing text: write then read gives the same drawing, bit for bit") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> ex(-300, 300);
  line_drawing<glm::dvec2> d;
  for (int i = 0; i < 200; ++i) d.points.push_back({std::ldexp(u(rng), ex(rng)), u(rng) / 3});
  d.points.push_back({-0.0, std::numeric_limits<double>::denorm_min()});
  d.points.push_back({std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest()});
  for (std::uint32_t i = 0; i + 1 < d.points.size(); ++i) d.edges.push_back({i, i + 1});
  const std::string text = io::drawing_text_string(d, {.comment = "random\nnumbers"});
  CHECK(text.starts_with("# random\n# numbers\n"));
  const auto back = parse(text);
  REQUIRE(back.points.size() == d.points.size());
  for (std::size_t i = 0; i < d.points.size(); ++i) {
    CHECK(same_bits(back.points[i].x, d.points[i].x));
    CHECK(same_bits(back.points[i].y, d.points[i].y));
  }
  CHECK(back.edges == d.edges);

  // A sample drawing through a file; and float points.
  const auto s = cellforge::generic_drawing(cellforge::sample_L(), 2, "normalon");
  const auto path =
      std::filesystem::temp_directory_path() / ("cellforge_drawing_" + std::to_string(getpid()) + ".txt");
  io::write_drawing_text(path, s.drawing);
  const auto read = io::read_drawing_text(path);
  CHECK(read.points == s.drawing.points);
  CHECK(read.edges == s.drawing.edges);
  std::filesystem::remove(path);
  line_drawing<glm::vec2> f{{{0.1f, 1e-30f}, {3e38f, -0.0f}}, {{1, 0}}};
  const auto fb = io::parse_drawing_text<glm::vec2>(io::drawing_text_string(f));
  CHECK(fb.points == f.points);
  CHECK(fb.edges == f.edges);
}

TEST_CASE("drawing text: the writer refuses what the reader rejects; io errors name the path") {
  line_drawing<glm::dvec2> d{{{0, 0}, {1, std::nan("")}}, {{0, 1}}};
  CHECK_THROWS_WITH_AS(io::drawing_text_string(d), doctest::Contains("junction 1"), cellforge::error);
  d.points[1].y = 0;
  d.edges.push_back({0, 2});
  CHECK_THROWS_WITH_AS(io::drawing_text_string(d), doctest::Contains("out of range"), cellforge::error);
  d.edges.back() = {1, 0};
  CHECK_THROWS_WITH_AS(io::drawing_text_string(d), doctest::Contains("repeats"), cellforge::error);
  d.edges.back() = {1, 1};
  CHECK_THROWS_WITH_AS(io::drawing_text_string(d), doctest::Contains("to itself"), cellforge::error);
  // Geometric defects are the validator's business, not the format's: written and read back.
  const line_drawing<glm::dvec2> tail{{{0, 0}, {1, 0}, {1, 0}}, {{0, 1}, {1, 2}}};
  CHECK(parse(io::drawing_text_string(tail)).edges.size() == 2);
  CHECK_THROWS_WITH_AS(io::read_drawing_text("/nonexistent/d.txt"), doctest::Contains("/nonexistent/d.txt"),
                       cellforge::error);
}

}  // namespace io_drawing_text_tests
