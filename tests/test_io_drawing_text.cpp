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

#include "cellforge/io/detail/arc_io.hpp"
#include "cellforge/io/drawing_text.hpp"
#include "cellforge/samples/drawings.hpp"
#include "cellforge/samples/round_drawings.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace io_drawing_text_tests {

namespace io = cellforge::io;
using cellforge::line_drawing;
using edge = std::array<std::uint32_t, 2>;

namespace {

line_drawing<glm::dvec2> parse(const std::string& text) { return io::parse_drawing_text(text, "d.txt"); }

/// The message and line of the io error parsing `text` (by the arc reader when `arcs`) throws.
std::pair<std::string, std::uint64_t> failure(const std::string& text, bool arcs = false) {
  try {
    if (arcs)
      (void)io::parse_arc_drawing_text(text, "d.txt");
    else
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
  CHECK(cellforge::validate(d).ok());
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
  check("j 0 0\nj 1 0\na 0 1 1 1 0 0 1\n", 3,
        "this reader takes straight edges only; read drawings with arcs by read_arc_drawing_text");
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
  const auto s = cellforge::samples::generic_drawing(cellforge::samples::sample_L(), 2, "normalon");
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

namespace {

using arc_drawing2 = cellforge::arc_drawing<glm::dvec2>;

arc_drawing2 parse_arcs(const std::string& text) { return io::parse_arc_drawing_text(text, "d.txt"); }

/// The statements of a drawing text, without its comment lines.
std::string statements(const std::string& text) {
  std::istringstream in(text);
  std::string out, line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') out += line + "\n";
  return out;
}

bool same_arcs(const arc_drawing2& a, const arc_drawing2& b) {
  if (a.lines.edges != b.lines.edges || a.lines.points.size() != b.lines.points.size() ||
      a.arcs.size() != b.arcs.size())
    return false;
  for (std::size_t i = 0; i < a.lines.points.size(); ++i)
    if (!same_bits(a.lines.points[i].x, b.lines.points[i].x) ||
        !same_bits(a.lines.points[i].y, b.lines.points[i].y))
      return false;
  for (std::size_t k = 0; k < a.arcs.size(); ++k) {
    const auto &p = a.arcs[k], &q = b.arcs[k];
    if (p.ends != q.ends) return false;
    for (const auto& [u, v] : {std::pair{p.curve.centre.x, q.curve.centre.x},
                               {p.curve.centre.y, q.curve.centre.y},
                               {p.curve.rx, q.curve.rx},
                               {p.curve.ry, q.curve.ry},
                               {p.curve.rotation, q.curve.rotation},
                               {p.curve.start, q.curve.start},
                               {p.curve.sweep, q.curve.sweep}})
      if (!same_bits(u, v)) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("arc rotations: degrees written are the shortest that read back to the same radians") {
  using cellforge::io::detail::arc_degrees;
  using cellforge::io::detail::arc_radians;
  // Round degrees come back as they were typed.
  for (const double d : {0.0, 30.0, -45.0, 90.0, 12.5, 179.99}) CHECK(arc_degrees(arc_radians(d)) == d);
  // A rotation read from text (the image of some degrees) comes back bit for bit through the
  // text of the degrees written for it: what makes drawings read and written again exact.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(-400, 400);
  int exact = 0;
  for (int k = 0; k < 2000; ++k) {
    const double r = arc_radians(angle(rng));
    std::ostringstream os;
    os.precision(17);
    os << arc_degrees(r);
    exact += arc_radians(std::stod(os.str())) == r;
  }
  CHECK(exact == 2000);
  // Any other rotation gets the nearest degrees.
  const double r = std::nextafter(arc_radians(1.0), 1.0);
  CHECK(std::abs(arc_radians(arc_degrees(r)) - r) <= 2 * std::numeric_limits<double>::epsilon());
  CHECK(std::signbit(arc_degrees(-0.0)));  // -0 stays -0: the text differs
}

TEST_CASE("arc drawing text: an arc between two junctions in SVG's endpoint form, y up") {
  // A quarter circle of radius 2 round (0, 0) from (2, 0) to (0, 2), counter-clockwise, and
  // the same ends the long way round clockwise.
  const arc_drawing2 d = parse_arcs(
      "j 2 0\nj 0 2\nj 2 -3\ne 0 2\n"
      "a 0 1 2 2 0 0 1   # the short way, counter-clockwise\n"
      "a 1 0 2 2 0 1 1\n");
  REQUIRE(d.arcs.size() == 2);
  CHECK(d.lines.edges == std::vector<edge>{{0, 2}});
  const auto& q = d.arcs[0];
  CHECK(q.ends == std::array<std::uint32_t, 2>{0, 1});
  CHECK(std::abs(q.curve.centre.x) < 1e-12);
  CHECK(std::abs(q.curve.centre.y) < 1e-12);
  CHECK(q.curve.rx == 2);
  CHECK(q.curve.sweep == doctest::Approx(std::numbers::pi / 2));
  const glm::dvec2 mid = cellforge::arc_point(q.curve, 0.5);
  CHECK(mid.x == doctest::Approx(std::sqrt(2.0)));
  CHECK(mid.y == doctest::Approx(std::sqrt(2.0)));
  // From (0, 2) counter-clockwise three quarters to (2, 0), through (-2, 0) and (0, -2).
  const auto& l = d.arcs[1];
  CHECK(l.curve.sweep == doctest::Approx(1.5 * std::numbers::pi));
  const glm::dvec2 far = cellforge::arc_point(l.curve, 1.0 / 3);
  CHECK(far.x == doctest::Approx(-2));
  CHECK(std::abs(far.y) < 1e-12);
  CHECK(cellforge::validate(d).ok());
  // The plain reader still reads the straight part of a file without arcs.
  CHECK(io::parse_drawing_text("j 2 0\nj 0 2\ne 0 1\n").edges.size() == 1);
}

TEST_CASE("arc drawing text: text -> drawing -> text is exact, and so is drawing -> text -> drawing") {
  const std::string text =
      "j 0 0\nj 4 0\nj 4 3\nj 0 3\nj 1.25 -0.1\nj -2.5 7\ne 0 1\ne 1 2\ne 3 0\n"
      "a 2 3 2 1.5 0 0 1\n"                    // a half ellipse: either flag pair draws it
      "a 3 2 2 1.5 0 1 0\n"                    // the other half, the large flag kept
      "a 0 4 5 0.7 30 0 0\n"                   // rotated by a whole number of degrees
      "a 4 5 3.3 9.1 -12.5 1 1\n"              // large, counter-clockwise
      "a 1 5 7.000000000000001 5.5 0.1 0 1\n"  // awkward numbers
      "a 5 2 12 12 123456.75 1 0\n";           // a rotation far past a turn
  const arc_drawing2 d = parse_arcs(text);
  REQUIRE(d.arcs.size() == 6);
  CHECK(cellforge::validate(d).ok());
  const std::string written = io::arc_drawing_text_string(d);
  CHECK(statements(written) == text);
  CHECK(same_arcs(parse_arcs(written), d));
  // Radii too small to span the ends are scaled up as in SVG: the text changes once, then stays.
  const arc_drawing2 small = parse_arcs("j 0 0\nj 4 0\na 0 1 1 1 0 0 1\n");
  CHECK(small.arcs[0].curve.rx == doctest::Approx(2));
  const std::string once = io::arc_drawing_text_string(small);
  CHECK(statements(once) == "j 0 0\nj 4 0\na 0 1 2 2 0 0 1\n");
  CHECK(same_arcs(parse_arcs(once), small));
}

TEST_CASE("arc drawing text: generated drawings with rounds come back to rounding, then exactly") {
  const auto samples = cellforge::samples::round_drawing_sweep({.seed = 5, .drawings = 24});
  REQUIRE(samples.size() == 24);
  std::size_t arcs = 0;
  for (const auto& s : samples) {
    CAPTURE(s.name);
    const std::string text = io::arc_drawing_text_string(s.drawing, {.comment = s.name});
    const arc_drawing2 back = parse_arcs(text);
    REQUIRE(back.arcs.size() == s.drawing.arcs.size());
    CHECK(back.lines.edges == s.drawing.lines.edges);
    CHECK(back.lines.points == s.drawing.lines.points);
    for (std::size_t k = 0; k < back.arcs.size(); ++k) {
      CHECK(back.arcs[k].ends == s.drawing.arcs[k].ends);
      // The same curve: the points along both agree (the centre form is recomputed from the ends).
      for (const double u : {0.0, 0.3, 0.5, 0.8, 1.0})
        CHECK(glm::length(cellforge::arc_point(back.arcs[k].curve, u) -
                          cellforge::arc_point(s.drawing.arcs[k].curve, u)) < 1e-9);
      ++arcs;
    }
    CHECK(io::arc_drawing_text_string(back, {.comment = s.name}) == text);
    CHECK(same_arcs(parse_arcs(io::arc_drawing_text_string(back)), back));
  }
  CHECK(arcs >= 48);
}

TEST_CASE("arc drawing text: float points, their arcs checked to float precision") {
  const std::string text = "j 2 0\nj 0 2\nj -1.7 0.3\na 0 1 2 2 0 0 1\na 1 2 3.5 1.25 -33 1 0\n";
  const auto d = io::parse_arc_drawing_text<glm::vec2>(text, "f.txt");
  REQUIRE(d.arcs.size() == 2);
  CHECK(cellforge::arc_point(d.arcs[0].curve, 0.5).x == doctest::Approx(std::sqrt(2.0)).epsilon(1e-6));
  const std::string written = io::arc_drawing_text_string(d);
  CHECK(statements(written) == text);
  const auto again = io::parse_arc_drawing_text<glm::vec2>(written, "f.txt");
  CHECK(again.arcs[1].curve.centre == d.arcs[1].curve.centre);
  CHECK(again.arcs[1].curve.sweep == d.arcs[1].curve.sweep);
}

TEST_CASE("arc drawing text: malformed arcs give located errors saying what was expected") {
  const std::string ends = "j 0 0\nj 4 0\nj 4 4\n";  // lines 1-3
  const auto check = [&](const std::string& arc_lines, std::uint64_t line, const std::string& part) {
    const auto failed = failure(ends + arc_lines, true);
    const std::string& message = failed.first;
    CHECK_MESSAGE(failed.second == line, message);
    CHECK_MESSAGE(message.find(part) != std::string::npos, message);
  };
  check("a 0 1 2 2 0 0\n", 4,
        "expected the ccw flag (0 or 1) of arc 0 (a i j rx ry rotation large ccw), found end of line");
  check("a 0 1 2 x 0 0 1\n", 4, "expected the radius ry of arc 0");
  check("a 0 1 2 2 0 2 1\n", 4,
        "the large-arc flag of arc 0 (a i j rx ry rotation large ccw) is 2: expected 0 or 1");
  check("a 0 1 2 2 0 0 0.5\n", 4, "expected the ccw flag (0 or 1) of arc 0");
  check("a 0 1 0 2 0 0 1\n", 4,
        "the radius rx of arc 0 (a i j rx ry rotation large ccw) is 0: radii must be > 0");
  check("\na 0 1 2 -2 0 0 1\n", 5, "the radius ry of arc 0 (a i j rx ry rotation large ccw) is -2");
  check("a 0 1 nan 2 0 0 1\n", 4, "is not finite");
  check("a 0 1 2 2 inf 0 1\n", 4,
        "the rotation in degrees of arc 0 (a i j rx ry rotation large ccw) 'inf' is not finite");
  check("a 0 1 2 2 0 0 1\na 0 9 2 2 0 0 1\n", 5, "junction index 9 of arc 1 out of range (3 junctions");
  check("a 0 -1 2 2 0 0 1\n", 4, "junction index -1 of arc 0 (a i j rx ry rotation large ccw) is negative");
  check("a 2 2 2 2 0 0 1\n", 4, "arc 0 starts and ends at junction 2: a closed curve is no round or fillet");
  check("j 4 4\na 2 3 2 2 0 0 1\n", 5, "arc 0 joins junctions 2 and 3, both at (4, 4)");
  check("a 0 1 2 2 0 0 1 7\n", 4, "unexpected '7' after the 7 values of arc 0");
  check("a 0 1 2 2 1e999 0 1\n", 4, "out of range");
  check("b 0 1\n", 4,
        "expected 'j x y' (a junction), 'e a b' (an edge), 'a i j rx ry rotation large ccw' (an arc)");
  // The straight part keeps its own checks in the arc reader.
  check("e 0 1\ne 1 0\n", 5, "edge 1 repeats edge 0");
}

TEST_CASE("arc drawing text: the writer refuses arcs the reader would reject or move") {
  arc_drawing2 d = parse_arcs("j 2 0\nj 0 2\na 0 1 2 2 0 0 1\n");
  const auto refused = [](const arc_drawing2& x, const std::string& part) {
    try {
      (void)io::arc_drawing_text_string(x);
    } catch (const cellforge::error& e) {
      CHECK(e.category() == cellforge::error_category::invalid_input);
      CHECK_MESSAGE(std::string(e.what()).find(part) != std::string::npos, e.what());
      return;
    }
    FAIL("not refused: " << part);
  };
  arc_drawing2 x = d;
  x.arcs[0].ends[1] = 7;
  refused(x, "write_arc_drawing_text: arc 0: junction 7 out of range");
  x = d;
  x.arcs[0].ends[1] = 0;
  refused(x, "starts and ends at junction 0");
  x = d;
  x.lines.points[1].x += 1e-3;  // the curve no longer ends at its junction
  refused(x, "from the curve's last point");
  x = d;
  x.arcs[0].curve.ry = 0;
  refused(x, "a radius of zero");
  x = d;
  x.arcs[0].curve.sweep = std::numeric_limits<double>::quiet_NaN();
  refused(x, "non-finite");
  x = d;
  x.lines.edges.push_back({0, 0});
  refused(x, "itself");
  const auto dir =
      std::filesystem::temp_directory_path() / ("cellforge_arc_text_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  io::write_arc_drawing_text(dir / "a.txt", d);
  CHECK(same_arcs(io::read_arc_drawing_text(dir / "a.txt"), d));
  CHECK_THROWS_WITH_AS(io::read_drawing_text(dir / "a.txt"), doctest::Contains("a.txt:4:"), cellforge::error);
  std::filesystem::remove_all(dir);
}

}  // namespace io_drawing_text_tests
