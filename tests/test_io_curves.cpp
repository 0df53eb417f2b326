// Curve file, polyline file, OBJ polylines and the SVG pictures of io/curves_io.hpp.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/io/curves_io.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/samples/thin_solids.hpp"
#include "cellforge/smooth/smooth_edges.hpp"
#include "cellforge/thin/thin_points.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace io_curves_tests {

namespace {

namespace io = cellforge::io;
using edge_curve = cellforge::edge_curve<glm::dvec3>;
using glm::dvec3;

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

bool same_bits(const dvec3& a, const dvec3& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

/// A temporary file path unique to this process and test.
std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("cellforge_curves_" + std::to_string(::getpid()) + "_" + name);
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Awkward numbers: negative, tiny and huge exponents, values with no short decimal form.
std::vector<edge_curve> awkward_curves() {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<edge_curve> out;
  for (int i = 0; i < 40; ++i) {
    const double scale = std::ldexp(1.0, (i % 9) * 15 - 60);  // 2^-60 .. 2^60
    const std::array<double, 2> limits{u(rng) * scale, u(rng) * scale + 3 * scale};
    std::array<std::array<double, 4>, 2> k{};
    for (auto& row : k)
      for (double& v : row) v = u(rng) * std::ldexp(1.0, static_cast<int>(u(rng) * 300));
    if (i % 5 == 1) k[0][0] = k[1][0] = 0.0;                      // quadratic
    if (i % 5 == 2) k[0][0] = k[1][0] = k[0][1] = k[1][1] = 0.0;  // straight
    out.push_back(cellforge::axis_curve<dvec3>(i % 3, limits, k));
    out.back().edge = static_cast<std::uint32_t>(out.size() - 1);
    const dvec3 p0(u(rng), -u(rng) * 1e-7, u(rng) * 1e200), p1(-0.1, 1.0 / 3.0, 2.5e-300);
    out.push_back(cellforge::hermite_curve(p0, dvec3(u(rng), u(rng), u(rng)), p1, dvec3(-1e-20, 0.0, -0.0)));
    out.back().edge = static_cast<std::uint32_t>(out.size() - 1);
  }
  return out;
}

void check_same_curves(const std::vector<edge_curve>& a, const std::vector<edge_curve>& b) {
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CAPTURE(i);
    CHECK(b[i].edge == i);
    CHECK(a[i].has_axis_form == b[i].has_axis_form);
    CHECK(a[i].kind == b[i].kind);
    if (a[i].has_axis_form) {
      CHECK(a[i].axis == b[i].axis);
      for (int k = 0; k < 2; ++k) CHECK(same_bits(a[i].limits[k], b[i].limits[k]));
      for (int r = 0; r < 2; ++r)
        for (int k = 0; k < 4; ++k) CHECK(same_bits(a[i].coefficients[r][k], b[i].coefficients[r][k]));
    }
    // The axis form is what the file stores; its Bézier is rebuilt by the same builder, so equal too.
    for (int k = 0; k < 4; ++k) CHECK(same_bits(a[i].bezier[k], b[i].bezier[k]));
  }
}

/// Parses text and returns the error it throws (fails the test when nothing is thrown).
cellforge::error parse_error(const std::string& text) {
  try {
    io::parse_curve_file<dvec3>(text, "bad.curves");
  } catch (const cellforge::error& e) {
    return e;
  }
  FAIL("no error for: " << text);
  return cellforge::error(cellforge::error_category::internal, "unreachable");
}

constexpr const char* seed_line =
    "0, 0, 0.38, -0.0123, 0.0021, -0.1043, 1.95, 0.0384, 0.0121, -0.0102, -9.81";

}  // namespace

TEST_CASE("curve file: the seed's example line means what the seed says (000 §6.5)") {
  const auto curves = io::parse_curve_file<dvec3>(seed_line);
  REQUIRE(curves.size() == 1);
  const edge_curve& c = curves[0];
  CHECK(c.has_axis_form);
  CHECK(c.axis == 0);
  CHECK(c.limits[0] == 0.0);
  CHECK(c.limits[1] == 0.38);
  CHECK(c.coefficients[0] == std::array<double, 4>{-0.0123, 0.0021, -0.1043, 1.95});
  CHECK(c.coefficients[1] == std::array<double, 4>{0.0384, 0.0121, -0.0102, -9.81});
  CHECK(c.kind == cellforge::curve_kind::cubic);
  // The curve itself: y and z follow the cubics in x along the whole edge.
  for (int i = 0; i <= 10; ++i) {
    const dvec3 p = c.point(i / 10.0);
    const double x = p.x;
    CHECK(x == doctest::Approx(0.038 * i).epsilon(1e-12));
    CHECK(p.y == doctest::Approx(-0.0123 * x * x * x + 0.0021 * x * x - 0.1043 * x + 1.95).epsilon(1e-13));
    CHECK(p.z == doctest::Approx(0.0384 * x * x * x + 0.0121 * x * x - 0.0102 * x - 9.81).epsilon(1e-13));
  }
  CHECK(same_bits(c.point(0.0), dvec3(0.0, 1.95, -9.81)));
  // Written back, the line is the seed's text exactly.
  CHECK(io::curve_file_text(curves) == std::string(seed_line) + "\n");
}

TEST_CASE("curve file: axis y and z, Bezier lines, comments, blanks and CRLF") {
  const std::string text =
      "# two curves\r\n"
      "\r\n"
      "1,2,-3,0,1,0,0,   0, 0, 0, 5   # y runs 2 -> -3\r\n"
      "3, 0, 0, 0, 1, 1, 0, 2, 2, 0, 3, 0, 0\r\n"
      "  2 , 1e-3 , -1E+2 , 0, 1, 0, 0, 0, 0, 0, 0";
  const auto curves = io::parse_curve_file<dvec3>(text);
  REQUIRE(curves.size() == 3);
  CHECK(curves[0].axis == 1);
  CHECK(curves[0].limits == std::array<double, 2>{2.0, -3.0});
  CHECK(curves[0].kind == cellforge::curve_kind::quadratic);
  // x = y^2 (the first other axis of y is x), z = 5.
  CHECK(same_bits(curves[0].bezier[0], dvec3(4.0, 2.0, 5.0)));
  CHECK(same_bits(curves[0].bezier[3], dvec3(9.0, -3.0, 5.0)));
  CHECK_FALSE(curves[1].has_axis_form);
  CHECK(curves[1].kind == cellforge::curve_kind::cubic);
  CHECK(same_bits(curves[1].bezier[2], dvec3(2.0, 2.0, 0.0)));
  CHECK(curves[2].axis == 2);
  CHECK(curves[2].limits == std::array<double, 2>{1e-3, -100.0});
  CHECK(curves[2].kind == cellforge::curve_kind::quadratic);
  for (std::size_t i = 0; i < curves.size(); ++i) CHECK(curves[i].edge == i);
}

TEST_CASE("curve file: write -> read is exact for axis-form and Bezier curves") {
  const auto curves = awkward_curves();
  const std::string text = io::curve_file_text(curves, {.comment = "awkward numbers\nsecond line"});
  CHECK(text.starts_with("# awkward numbers\n# second line\n"));
  check_same_curves(curves, io::parse_curve_file<dvec3>(text));
  // Through a file, and every line in the seed's ", " layout with 11 or 13 values.
  const auto path = temp_path("roundtrip.curves");
  io::write_curve_file(path, curves);
  check_same_curves(curves, io::read_curve_file<dvec3>(path));
  std::istringstream lines(slurp(path));
  std::size_t n = 0;
  for (std::string line; std::getline(lines, line); ++n) {
    const auto commas = std::count(line.begin(), line.end(), ',');
    CHECK(commas == (curves[n].has_axis_form ? 10 : 12));
    CHECK(std::count(line.begin(), line.end(), ' ') == commas);
  }
  CHECK(n == curves.size());
  std::filesystem::remove(path);
  // A stream works the same way.
  std::ostringstream os;
  io::write_curve_file(os, curves);
  CHECK(os.str() == io::curve_file_text(curves));
}

TEST_CASE("curve file: malformed lines give io errors at file:line") {
  const std::string ok = std::string(seed_line) + "\n";
  struct bad_case {
    std::string line;
    std::string says;
  };
  const std::vector<bad_case> cases = {
      {"0, 0, 0.38, 1, 2, 3, 4, 5, 6, 7", "needs 11 values"},
      {"0, 0, 0.38, 1, 2, 3, 4, 5, 6, 7, 8, 9", "needs 11 values"},
      {"3, 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3", "needs 13 values"},
      {"3, 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4", "too many values"},
      {"4, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0", "the axis must be 0, 1 or 2"},
      {"-1, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0", "the axis must be 0, 1 or 2"},
      {"0.5, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0", "the axis must be 0, 1 or 2"},
      {"0, 0, 1, 0, zero, 0, 0, 0, 0, 0, 0", "expected coefficient b, found 'zero'"},
      {"0, 0, 1, 0, 0, 0, 0, 0, 0, 0, nan", "coefficient h 'nan' is not finite"},
      {"0, 0, inf, 0, 0, 0, 0, 0, 0, 0, 0", "the limit at the end 'inf' is not finite"},
      {"0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 1e999", "out of range"},
      {"0, 0.5, 0.5, 0, 0, 0, 0, 0, 0, 0, 0", "the limits are equal"},
      {"3, 1, 2, 3, 0, 0, 0, 0, 0, 0, 1, 2, 3", "starts and ends at the same point"},
      {"0, 0, 1, 0, 0, 0, 0, 0, 0, 0,", "found end of"},
      {"0, 0, 1, 0, 0, 0, 0, 0, 0, 0 0", "expected ',' or the end of the line"},
      {"0; 0; 1", "expected ',' or the end of the line after the axis"},
      {"3, 0, 0, 0, 1, 1, 1, x, 2, 2, 3, 3, 3", "expected Bezier coordinate x2, found 'x'"},
  };
  for (const bad_case& bad : cases) {
    const std::string& line = bad.line;
    const std::string& says = bad.says;
    CAPTURE(line);
    const cellforge::error e = parse_error(ok + "# comment\n" + ok + line + "\n" + ok);
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(e.file() == "bad.curves");
    CHECK(e.line() == 4);
    CHECK(e.message().find(says) != std::string::npos);
    CHECK(std::string(e.what()).starts_with("bad.curves:4: "));
  }
  // A missing file names its path.
  try {
    io::read_curve_file<dvec3>(temp_path("does-not-exist.curves"));
    FAIL("no error");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(std::string(e.what()).find("does-not-exist.curves") != std::string::npos);
  }
}

TEST_CASE("curve file: the writer refuses curves its reader would reject") {
  edge_curve nan_coefficient = cellforge::axis_curve<dvec3>(0, {0.0, 1.0}, {});
  nan_coefficient.coefficients[1][2] = std::nan("");
  edge_curve flat = cellforge::axis_curve<dvec3>(1, {0.0, 1.0}, {});
  flat.limits = {2.0, 2.0};
  edge_curve bad_axis = flat;
  bad_axis.axis = 3;
  edge_curve closed = cellforge::hermite_curve(dvec3(1.0), dvec3(1, 0, 0), dvec3(1.0), dvec3(0, 1, 0));
  for (const edge_curve& c : {nan_coefficient, flat, bad_axis, closed}) {
    const std::vector<edge_curve> one{cellforge::straight_curve(dvec3(0.0), dvec3(1.0)), c};
    try {
      io::curve_file_text(one);
      FAIL("no error");
    } catch (const cellforge::error& e) {
      CHECK(e.category() == cellforge::error_category::invalid_input);
      CHECK(e.message().find("curve 1") != std::string::npos);
    }
  }
}

TEST_CASE("curve file: a file that cannot be written is an io error naming it") {
  const std::vector<edge_curve> one{cellforge::straight_curve(dvec3(0.0), dvec3(1.0))};
  const auto path = temp_path("no-such-dir") / "x.curves";
  try {
    io::write_curve_file(path, one);
    FAIL("no error");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(std::string(e.what()).find(path.string()) != std::string::npos);
  }
}

TEST_CASE("polyline file: 15 segments per curve, exact round trip, errors at file:line") {
  const auto curves = awkward_curves();
  const auto path = temp_path("curves.polylines");
  io::write_polyline_file(path, curves);
  const auto back = io::read_polyline_file<dvec3>(path);
  REQUIRE(back.size() == curves.size());
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const auto expected = curves[i].polyline(15);
    REQUIRE(back[i].size() == 16);
    for (std::size_t j = 0; j < 16; ++j) CHECK(same_bits(back[i][j], expected[j]));
  }
  std::filesystem::remove(path);
  CHECK(io::parse_polyline_file<dvec3>("0, 0, 0, 1, 2, 3\n# c\n\n1,1,1,2,2,2,3,3,3").size() == 2);
  for (const std::string bad : {"0, 0, 0, 1, 2", "0, 0, 0", "0, 0, 0, 1, 2, nan", "0, 0, 0, 1, 2, 3,"}) {
    CAPTURE(bad);
    try {
      io::parse_polyline_file<dvec3>("0, 0, 0, 1, 1, 1\n" + bad, "p.txt");
      FAIL("no error");
    } catch (const cellforge::error& e) {
      CHECK(e.category() == cellforge::error_category::io);
      CHECK(std::string(e.what()).starts_with("p.txt:2: "));
    }
  }
  CHECK_THROWS_AS(io::polyline_file_text(std::vector<std::vector<dvec3>>{{dvec3(0.0)}}), cellforge::error);
  CHECK_THROWS_AS(io::write_polyline_file(path, curves, {.segments = 0}), cellforge::error);
  CHECK_FALSE(std::filesystem::exists(path));
}

TEST_CASE("OBJ polylines: one l line per curve, read back by the OBJ reader") {
  const auto curves = awkward_curves();
  const auto cube = cellforge::hexahedron<dvec3>();
  const auto path = temp_path("curves.obj");
  io::write_polylines_obj(path, std::span<const edge_curve>(curves), &cube, {.segments = 15});
  const auto data = io::read_obj<dvec3>(path);
  CHECK(data.soup.num_faces() == cube.num_faces());
  REQUIRE(data.soup.points.size() == cube.points.size() + 16 * curves.size());
  REQUIRE(data.lines.size() == 15 * curves.size());  // the reader splits each l line into its edges
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const auto pl = curves[i].polyline(15);
    for (std::size_t j = 0; j < 15; ++j) {
      const auto& e = data.lines[15 * i + j];
      CHECK(same_bits(data.soup.points[e[0]], pl[j]));
      CHECK(same_bits(data.soup.points[e[1]], pl[j + 1]));
    }
  }
  // One l line per curve, each with 16 indices.
  std::istringstream lines(slurp(path));
  std::size_t l_lines = 0;
  for (std::string line; std::getline(lines, line);) {
    if (!line.starts_with("l ")) continue;
    ++l_lines;
    CHECK(std::count(line.begin(), line.end(), ' ') == 16);
  }
  CHECK(l_lines == curves.size());
  std::filesystem::remove(path);

  // Closed loops without faces: the l line returns to its first point.
  std::ostringstream os;
  const std::vector<std::vector<dvec3>> loops{{dvec3(0, 0, 0), dvec3(1, 0, 0), dvec3(0, 1, 0)}};
  io::write_polylines_obj(os, std::span<const std::vector<dvec3>>(loops), true);
  CHECK(os.str() == "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3 1\n");
}

TEST_CASE("SVG: thin loops on a solid and straight beside smoothed edges") {
  const auto soup = cellforge::cylinder<dvec3>(12, 3, true, false);
  // Two rings around the cylinder as stand-ins for thin loops.
  std::vector<std::vector<dvec3>> loops(2);
  for (int i = 0; i < 12; ++i) {
    const double a = 2 * std::numbers::pi * i / 12;
    loops[0].emplace_back(std::cos(a), std::sin(a), 0.5);
    loops[1].emplace_back(std::cos(a), std::sin(a), 0.25);
  }
  const auto path = temp_path("thin.svg");
  const io::svg_result r = io::write_thin_loops_svg(path, soup, std::span<const std::vector<dvec3>>(loops));
  const std::string text = slurp(path);
  CHECK(text.starts_with("<?xml"));
  CHECK(text.ends_with("</svg>\n"));
  CHECK(r.labels == 2);
  CHECK(r.faces_drawn == soup.num_faces());
  std::size_t mesh_edges = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) mesh_edges += soup.face(f).size();
  CHECK(r.edges == mesh_edges / 2 + 24);  // closed mesh: every edge in two faces; 12 + 12 loop segments
  // Each loop is its own path in its colour.
  CHECK(text.find("stroke=\"#d62728\" stroke-width=\"4\"") != std::string::npos);
  CHECK(text.find("stroke=\"#ff7f0e\" stroke-width=\"2.8\"") != std::string::npos);
  std::filesystem::remove(path);

  // Every edge of the solid as a straight curve, bulged outward a little.
  std::vector<edge_curve> curves;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto vs = soup.face(f);
    for (std::size_t i = 0; i < vs.size(); ++i) {
      const dvec3 a = soup.points[vs[i]], b = soup.points[vs[(i + 1) % vs.size()]];
      const dvec3 out = glm::normalize(dvec3(a.x + b.x, a.y + b.y, 0.0) + dvec3(1e-9)) * 0.2;
      curves.push_back(cellforge::hermite_curve(a, b - a + out, b, b - a - out));
    }
  }
  const auto path2 = temp_path("smooth.svg");
  const io::svg_result s = io::write_smoothing_svg(path2, soup, curves);
  CHECK(s.faces_drawn == 2 * soup.num_faces());
  CHECK(s.labels == 2);
  CHECK(s.edges == mesh_edges / 2 + 15 * curves.size());
  const std::string text2 = slurp(path2);
  CHECK(text2.find("smoothed edges (" + std::to_string(curves.size()) + " curves)") != std::string::npos);
  CHECK(text2.ends_with("</svg>\n"));
  std::filesystem::remove(path2);

  // The mesh overloads draw the same picture.
  const auto mesh = cellforge::make_mesh(soup);
  const auto r2 = io::write_smoothing_svg(path2, mesh, curves);
  CHECK(r2.edges == s.edges);
  std::filesystem::remove(path2);
  CHECK_THROWS_AS(io::write_smoothing_svg(path2, soup, curves, {.segments = 0}), cellforge::error);
}

TEST_CASE("curve file: smooth_edges' curves of a UV sphere round-trip") {
  const auto mesh = cellforge::make_mesh(cellforge::uv_sphere<dvec3>(16, 8, false));
  for (const auto& options : {cellforge::smooth_options{}, cellforge::seed_smooth_options()}) {
    const cellforge::smooth_result r = cellforge::smooth_edges(mesh, options);
    REQUIRE(r.curves.size() == mesh.num_edges());
    const std::string text = io::curve_file_text(r.curves);
    const auto back = io::parse_curve_file<dvec3>(text);
    REQUIRE(back.size() == r.curves.size());
    std::size_t cubic = 0;
    for (std::size_t i = 0; i < back.size(); ++i) {
      CAPTURE(i);
      const edge_curve &a = r.curves[i], &b = back[i];
      CHECK(b.edge == a.edge);  // one curve per edge, in edge order
      CHECK(a.has_axis_form == b.has_axis_form);
      if (a.has_axis_form) {
        CHECK(a.axis == b.axis);
        CHECK((same_bits(a.limits[0], b.limits[0]) && same_bits(a.limits[1], b.limits[1])));
        for (int k = 0; k < 2; ++k)
          for (int j = 0; j < 4; ++j) CHECK(same_bits(a.coefficients[k][j], b.coefficients[k][j]));
      }
      // The file keeps the axis form; the Bézier rebuilt from it is the same curve to rounding.
      for (int k = 0; k < 4; ++k) CHECK(glm::length(a.bezier[k] - b.bezier[k]) < 1e-12);
      CHECK(a.kind == b.kind);
      cubic += b.kind == cellforge::curve_kind::cubic;
    }
    CHECK(cubic > back.size() / 2);
    // Written again, the text is the same: the format is a fixed point after one round.
    CHECK(io::curve_file_text(back) == text);
  }
}

TEST_CASE_TEMPLATE("curves, polylines and pictures in other point types", P, std::array<float, 3>,
                   test_support::sealed_point) {
  using S = cellforge::scalar_t<P>;
  const auto mesh = cellforge::make_mesh(cellforge::uv_sphere<P>(10, 5));
  const auto r = cellforge::smooth_edges(mesh);
  const std::string text = io::curve_file_text(r.curves);  // a vector of edge_curve<P>
  const auto back = io::parse_curve_file<P>(text);
  static_assert(std::is_same_v<decltype(back), const std::vector<cellforge::edge_curve<P>>>);
  REQUIRE(back.size() == r.curves.size());
  // The same curves as glm::dvec3 (the double run on the very same points) write the same axis
  // lines: only the Bezier lines differ, written in P's own scalar.
  const auto d =
      cellforge::smooth_edges(cellforge::make_mesh(test_support::soup_as_dvec3(cellforge::to_soup(mesh))));
  std::size_t axis_lines = 0;
  for (std::size_t i = 0; i < back.size(); ++i) {
    CAPTURE(i);
    CHECK(back[i].has_axis_form == r.curves[i].has_axis_form);
    for (std::size_t k = 0; k < 4; ++k) {
      const double tol = std::is_same_v<S, float> ? 1e-6 : 1e-12;
      CHECK(glm::length(cellforge::to_dvec3(back[i].bezier[k]) -
                        cellforge::to_dvec3(r.curves[i].bezier[k])) <= tol);
      if (!r.curves[i].has_axis_form)  // Bezier points are written in P's scalar: exact
        CHECK(cellforge::to_dvec3(back[i].bezier[k]) == cellforge::to_dvec3(r.curves[i].bezier[k]));
    }
    if (r.curves[i].has_axis_form) {
      ++axis_lines;
      CHECK(io::curve_file_text(std::span(&r.curves[i], 1)) ==
            io::curve_file_text(std::span(&d.curves[i], 1)));
    }
  }
  CHECK(axis_lines > 0);
  CHECK(io::curve_file_text(back) == text);
  // Polylines: evaluated in P, written in P's scalar, read back as P.
  const auto polylines = io::curve_polylines(r.curves, 4);
  static_assert(std::is_same_v<decltype(polylines), const std::vector<std::vector<P>>>);
  const auto lines = io::parse_polyline_file<P>(io::polyline_file_text(polylines));
  REQUIRE(lines.size() == polylines.size());
  for (std::size_t i = 0; i < lines.size(); ++i)
    for (std::size_t j = 0; j < lines[i].size(); ++j)
      CHECK(cellforge::to_dvec3(lines[i][j]) == cellforge::to_dvec3(polylines[i][j]));
  // Pictures take the typed results: the smoothing and the thin loops of a P mesh.
  const auto path = temp_path("typed.svg");
  CHECK(io::write_smoothing_svg(path, mesh, r.curves).faces_drawn > 0);
  const auto dumbbell = cellforge::make_mesh(cellforge::samples::thin_dumbbell<P>(12, 21, false).soup);
  const auto thin = cellforge::find_thin_points(dumbbell);
  REQUIRE(!thin.loops.empty());
  CHECK(io::write_thin_loops_svg(path, dumbbell, thin).labels == std::min<std::size_t>(thin.loops.size(), 5));
  std::filesystem::remove(path);
}

}  // namespace io_curves_tests
