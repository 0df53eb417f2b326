// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <glm/vec3.hpp>

#include "cellforge/io/mesh_io.hpp"
#include "cellforge/io/stl.hpp"
#include "io_test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace io_stl_tests {
/// A user point type with float coordinates (io_test::user_point has doubles).
struct float_point {
  float x, y, z;
};
/// A CAD-style point: read through getters, made by its constructor only (no default one).
class sealed_point {
 public:
  sealed_point(float x, float y, float z) : c_{x, y, z} {}
  float x() const { return c_[0]; }
  float y() const { return c_[1]; }
  float z() const { return c_[2]; }

 private:
  float c_[3];
};
}  // namespace io_stl_tests
// A point_traits specialisation must stand outside the tests' namespace.
CELLFORGE_REGISTER_POINT3(io_stl_tests::float_point, float, x, y, z);
namespace io_stl_tests {
/// A point with long double coordinates: the welder keys them by sign, exponent and mantissa.
struct wide_point {
  long double x, y, z;
};
}  // namespace io_stl_tests
CELLFORGE_REGISTER_POINT3(io_stl_tests::wide_point, long double, x, y, z);
CELLFORGE_REGISTER_POINT3_GET_CTOR(io_stl_tests::sealed_point, float, x, y, z);

namespace io_stl_tests {

namespace io = cellforge::io;
using cellforge::polygon_soup;

namespace {

// One triangle in a solid: the malformed cases are edits of it (line numbers in comments).
const std::string tri =
    "solid t\n"             // 1
    "facet normal 0 0 1\n"  // 2
    " outer loop\n"         // 3
    "  vertex 0 0 0\n"      // 4
    "  vertex 1 0 0\n"      // 5
    "  vertex 0 1 0\n"      // 6
    " endloop\n"            // 7
    "endfacet\n"            // 8
    "endsolid t\n";         // 9

io::stl_data<glm::dvec3> parse(const std::string& text, const io::stl_read_options& o = {}) {
  return io::parse_stl<glm::dvec3>(text, "t.stl", o);
}

/// Appends little-endian values: binary STL files made by hand.
struct binary_stl {
  std::string bytes;
  explicit binary_stl(std::uint32_t facets, std::string header = "made by hand") {
    header.resize(80, '\0');
    bytes = header;
    u32(facets);
  }
  binary_stl& u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes += static_cast<char>((v >> (8 * i)) & 0xff);
    return *this;
  }
  binary_stl& f32(float v) { return u32(std::bit_cast<std::uint32_t>(v)); }
  binary_stl& facet(std::array<std::array<float, 3>, 3> c, std::array<float, 3> normal = {0, 0, 0}) {
    for (const float v : normal) f32(v);
    for (const auto& p : c)
      for (const float v : p) f32(v);
    bytes += std::string(2, '\0');
    return *this;
  }
};

/// The 12 triangles of the unit cube, outward, as corner coordinates.
std::vector<std::array<std::array<float, 3>, 3>> cube_facets() {
  const std::array<std::array<float, 3>, 8> v = {
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::vector<std::array<std::array<float, 3>, 3>> out;
  for (const auto& q : quads) {
    out.push_back({v[q[0]], v[q[1]], v[q[2]]});
    out.push_back({v[q[0]], v[q[2]], v[q[3]]});
  }
  return out;
}

std::string cube_ascii() {
  std::string s = "solid cube\n";
  for (const auto& f : cube_facets()) {
    s += "facet normal 0 0 0\nouter loop\n";
    for (const auto& p : f)
      s += "vertex " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
    s += "endloop\nendfacet\n";
  }
  return s + "endsolid cube\n";
}

std::string cube_binary(const std::string& header = "cube") {
  const auto facets = cube_facets();
  binary_stl b(static_cast<std::uint32_t>(facets.size()), header);
  for (const auto& f : facets) b.facet(f);
  return b.bytes;
}

/// Triangles over points with awkward float-representable coordinates (negative zero, the
/// smallest subnormal and largest float, every magnitude); faces 0..n/3-1 use the points in
/// order, so a reader's first-use order is the soup's own.
template <cellforge::Point3 P>
polygon_soup<P> triangle_soup(unsigned seed, std::size_t triples, std::size_t extra_faces) {
  using S = cellforge::scalar_t<P>;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  const auto value = [&](std::size_t i) -> S {
    if constexpr (std::is_floating_point_v<S>) {
      using L = std::numeric_limits<float>;
      switch (i % 13) {
        case 0:
          return S(-0.0f);
        case 1:
          return S(L::denorm_min());
        case 2:
          return S(L::max());
        case 3:
          return S(L::lowest());
        case 4:
          return S(0.1f);
        default:
          return S(static_cast<float>(std::ldexp(mantissa(rng), exponent(rng))));
      }
    } else {
      return static_cast<S>(rng() % 2001) - S(1000);
    }
  };
  polygon_soup<P> soup;
  std::set<std::array<double, 3>> seen;  // distinct points (-0 equals 0, as for welding)
  for (std::size_t i = 0; soup.points.size() < 3 * triples; ++i) {
    const P p = cellforge::point_traits<P>::make(value(3 * i), value(3 * i + 1), value(3 * i + 2));
    const glm::dvec3 q = cellforge::to_dvec3(p);
    if (seen.insert({q.x, q.y, q.z}).second) soup.points.push_back(p);
  }
  for (std::uint32_t f = 0; f < triples; ++f) soup.add_face({3 * f, 3 * f + 1, 3 * f + 2});
  const auto n = static_cast<std::uint32_t>(soup.points.size());
  for (std::size_t f = 0; f < extra_faces; ++f) {
    const std::uint32_t a = static_cast<std::uint32_t>(rng() % n), b = (a + 1 + rng() % (n - 1)) % n;
    std::uint32_t c = static_cast<std::uint32_t>(rng() % n);
    while (c == a || c == b) c = (c + 1) % n;
    soup.add_face({a, b, c});
  }
  return soup;
}

template <cellforge::Point3 P>
std::string written(const polygon_soup<P>& soup, const io::stl_write_options& o = {}) {
  std::ostringstream os;
  io::write_stl(os, soup, o);
  return os.str();
}

/// A binary input that must fail at byte `offset` with `message` in the text.
void check_binary_rejected(const char* what, const std::string& bytes, std::uint64_t offset,
                           const char* message) {
  io_test::check_rejected_at_byte(what, bytes, offset, message, "t.stl",
                                  [](const std::string& s) { (void)parse(s); });
}

double area2(const std::array<double, 2>& a, const std::array<double, 2>& b, const std::array<double, 2>& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/// Even-odd test, true on the boundary too (within a small margin).
bool inside_or_on(const std::vector<std::array<double, 2>>& poly, std::array<double, 2> p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto &a = poly[i], &b = poly[j];
    const double cross = area2(a, b, p), len = std::hypot(b[0] - a[0], b[1] - a[1]);
    const bool between = std::min(a[0], b[0]) - 1e-12 <= p[0] && p[0] <= std::max(a[0], b[0]) + 1e-12 &&
                         std::min(a[1], b[1]) - 1e-12 <= p[1] && p[1] <= std::max(a[1], b[1]) + 1e-12;
    if (std::fabs(cross) <= 1e-12 * len && between) return true;
    if ((a[1] > p[1]) != (b[1] > p[1]) && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0])
      in = !in;
  }
  return in;
}

}  // namespace

TEST_CASE("STL: an ASCII cube welds 36 corners into 8 vertices") {
  const auto d = parse(cube_ascii());
  CHECK(d.encoding == io::stl_encoding::ascii);
  CHECK(d.facets_read == 12);
  CHECK(d.vertices_before_weld == 36);
  CHECK(d.vertices_after_weld == 8);
  CHECK(d.degenerate_facets == 0);
  REQUIRE(d.soup.num_faces() == 12);
  CHECK(d.soup.num_points() == 8);
  // Points come in the order of their first corner: facet 0 is (0,0,0) (0,1,0) (1,1,0).
  CHECK(d.soup.points[0] == glm::dvec3(0, 0, 0));
  CHECK(d.soup.points[1] == glm::dvec3(0, 1, 0));
  CHECK(d.soup.points[2] == glm::dvec3(1, 1, 0));
  CHECK(std::vector<std::uint32_t>(d.soup.face(1).begin(), d.soup.face(1).end()) ==
        std::vector<std::uint32_t>{0, 2, 3});
  REQUIRE(d.solids.size() == 1);
  CHECK(d.solids[0].name == "cube");
  CHECK(d.solids[0].end_name == "cube");
  CHECK(d.solids[0].num_faces == 12);
  // Every edge of the welded cube is shared by exactly two faces: a closed surface.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::size_t f = 0; f < 12; ++f)
    for (std::size_t k = 0; k < 3; ++k) edges.emplace_back(d.soup.face(f)[k], d.soup.face(f)[(k + 1) % 3]);
  for (const auto& [a, b] : edges)
    CHECK(std::count(edges.begin(), edges.end(), std::pair<std::uint32_t, std::uint32_t>{b, a}) == 1);
}

TEST_CASE("STL: long double points weld exactly as doubles do, -0 with +0") {
  const auto wide = io::parse_stl<wide_point>(cube_ascii(), "t.stl", {});
  const auto d = parse(cube_ascii());
  CHECK(wide.vertices_after_weld == 8);
  CHECK(wide.soup.face_vertices == d.soup.face_vertices);
  const std::string signed_zeros =
      "solid z\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
      "vertex 0 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\n"
      "vertex -0 -0 0\nvertex 0 -1 0\nvertex 1 0 -0\nendloop\nendfacet\nendsolid z\n";
  const auto z = io::parse_stl<wide_point>(signed_zeros, "z.stl", {});
  CHECK(z.vertices_before_weld == 6);
  CHECK(z.vertices_after_weld == 4);
  CHECK(z.soup.face_vertices == std::vector<std::uint32_t>{0, 1, 2, 0, 3, 1});
}

TEST_CASE("STL: a binary cube welds the same way; no welding keeps every corner") {
  const auto d = parse(cube_binary("cube header"));
  CHECK(d.encoding == io::stl_encoding::binary);
  CHECK(d.facets_read == 12);
  CHECK(d.vertices_before_weld == 36);
  CHECK(d.vertices_after_weld == 8);
  CHECK(d.soup.face_vertices == parse(cube_ascii()).soup.face_vertices);
  REQUIRE(d.solids.size() == 1);
  CHECK(d.solids[0].name == "cube header");  // the header text, NUL padding removed
  CHECK(d.solids[0].end_name.empty());

  const auto raw = parse(cube_binary(), {.weld = false});
  CHECK(raw.vertices_after_weld == 36);
  CHECK(raw.soup.num_points() == 36);
  CHECK(raw.soup.face(11)[2] == 35);
}

TEST_CASE("STL: tolerance welding merges into the first vertex within reach, deterministically") {
  // The cube with every corner moved by up to 3e-7: exact welding sees more vertices.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> jitter(-3e-7f, 3e-7f);
  auto facets = cube_facets();
  for (auto& f : facets)
    for (auto& p : f)
      for (float& v : p) v += jitter(rng);
  binary_stl b(12);
  for (const auto& f : facets) b.facet(f);
  const auto exact = parse(b.bytes);
  CHECK(exact.vertices_after_weld == 36);
  const auto near = parse(b.bytes, {.weld_tolerance = 1e-5});
  CHECK(near.vertices_after_weld == 8);
  CHECK(near.degenerate_facets == 0);
  CHECK(near.soup.num_faces() == 12);
  // The first corner read is the representative: its coordinates, bit for bit.
  CHECK(near.soup.points[0] == glm::dvec3(facets[0][0][0], facets[0][0][1], facets[0][0][2]));
  CHECK(near.soup.face_vertices == parse(cube_binary()).soup.face_vertices);

  // Not transitive: 0.6 joins 0, but 1.2 is 1.2 from the vertex at 0, so it is a vertex of its own.
  const std::string chain =
      "solid c\nfacet normal 0 0 0 outer loop vertex 0 0 0 vertex 0.6 0 0 vertex 0 5 0 endloop endfacet\n"
      "facet normal 0 0 0 outer loop vertex 1.2 0 0 vertex 9 9 0 vertex 0 9 0 endloop endfacet\nendsolid\n";
  const auto c = parse(chain, {.weld_tolerance = 1.0, .degenerate = io::stl_degenerate::keep});
  CHECK(c.soup.num_points() == 5);
  CHECK(c.degenerate_facets == 1);  // facet 0: 0.6 joined the vertex at 0
  CHECK(c.soup.points[1] == glm::dvec3(0, 5, 0));
  CHECK(c.soup.points[2] == glm::dvec3(1.2, 0, 0));

  // Far from the origin (cells are clamped) welding still finds its neighbours.
  const std::string far =
      "solid f\nfacet normal 0 0 0 outer loop vertex 1e15 0 0 vertex 0 1e300 0 vertex 0 0 -1e300 endloop "
      "endfacet\nfacet normal 0 0 0 outer loop vertex 1000000000000000.125 0 0 vertex 0 0 -1e300 vertex "
      "-1e300 0 0 endloop endfacet\nendsolid\n";
  const auto f = parse(far, {.weld_tolerance = 0.2});
  CHECK(f.soup.num_points() == 4);
  CHECK(f.soup.face(1)[0] == 0);
  CHECK(parse(far).soup.num_points() == 5);

  for (const double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()})
    CHECK_THROWS_AS(parse(tri, {.weld_tolerance = bad}), cellforge::error);
}

TEST_CASE("STL: welding matches the rule it states, checked against a brute-force reference") {
  // Corners drawn from a small cloud, so that many merge (and some facets become degenerate).
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  std::vector<std::array<float, 3>> cloud(60);
  for (auto& p : cloud) p = {coordinate(rng), coordinate(rng), coordinate(rng)};
  std::uniform_int_distribution<std::size_t> pick(0, cloud.size() - 1);
  std::uniform_real_distribution<float> jitter(-0.02f, 0.02f);
  binary_stl b(800);
  std::vector<std::array<glm::dvec3, 3>> facets;
  for (int f = 0; f < 800; ++f) {
    std::array<std::array<float, 3>, 3> c;
    std::array<glm::dvec3, 3> d;
    for (std::size_t k = 0; k < 3; ++k) {
      c[k] = cloud[pick(rng)];
      if (f % 2 == 1)
        for (float& v : c[k]) v += jitter(rng);
      d[k] = glm::dvec3(c[k][0], c[k][1], c[k][2]);
    }
    b.facet(c);
    facets.push_back(d);
  }
  for (const double tol : {0.0, 0.01, 0.05, 0.3}) {
    CAPTURE(tol);
    // The rule: a corner joins the earliest vertex within tol (equal for tol = 0), else it is
    // a new vertex; a facet with a repeated vertex is dropped with the vertices it created.
    std::vector<glm::dvec3> points;
    std::vector<std::uint32_t> faces;
    for (const auto& f : facets) {
      const std::size_t before = points.size();
      std::array<std::uint32_t, 3> v{};
      for (std::size_t k = 0; k < 3; ++k) {
        std::size_t j = 0;
        while (j < points.size() && !(glm::length(points[j] - f[k]) <= tol)) ++j;
        if (j == points.size()) points.push_back(f[k]);
        v[k] = static_cast<std::uint32_t>(j);
      }
      if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) {
        points.resize(before);
        continue;
      }
      faces.insert(faces.end(), v.begin(), v.end());
    }
    const auto d = parse(b.bytes, {.weld_tolerance = tol});
    CHECK(d.soup.points == points);
    CHECK(d.soup.face_vertices == faces);
    CHECK(d.facets_read == 800);
    CHECK(d.degenerate_facets == 800 - faces.size() / 3);
    CHECK(d.degenerate_facets > 0);
  }
}

TEST_CASE("STL: degenerate facets are dropped and counted, kept, or refused with their place") {
  // Facet 1 has two equal corners; facet 2 has three distinct ones on a line (kept: not a repeat).
  const std::string text =
      "solid d\n"
      "facet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 endloop endfacet\n"
      "facet normal 0 0 0 outer loop vertex 5 5 5 vertex 1 0 0 vertex 5 5 5 endloop endfacet\n"
      "facet normal 0 0 0 outer loop vertex 0 0 0 vertex 1 0 0 vertex 2 0 0 endloop endfacet\n"
      "endsolid d\n";
  const auto dropped = parse(text);
  CHECK(dropped.facets_read == 3);
  CHECK(dropped.degenerate_facets == 1);
  CHECK(dropped.soup.num_faces() == 2);
  CHECK(dropped.soup.num_points() == 4);  // (5,5,5) went with its facet
  CHECK(dropped.vertices_after_weld == 4);
  CHECK(dropped.solids[0].num_faces == 2);

  const auto kept = parse(text, {.degenerate = io::stl_degenerate::keep});
  CHECK(kept.soup.num_faces() == 3);
  CHECK(kept.degenerate_facets == 1);
  CHECK(kept.soup.face(1)[0] == kept.soup.face(1)[2]);

  // Only degenerate facets: dropping them all would read as an empty mesh without a word.
  const std::string all_degenerate =
      "solid d\n"
      "facet normal 0 0 0 outer loop vertex 5 5 5 vertex 1 0 0 vertex 5 5 5 endloop endfacet\n"
      "facet normal 0 0 0 outer loop vertex 0 0 0 vertex 0 0 0 vertex 0 0 0 endloop endfacet\n"
      "endsolid d\n";
  for (const bool weld : {true, false}) {
    try {
      (void)io::parse_stl<glm::dvec3>(all_degenerate, "t.stl", {.weld = weld});
      FAIL("read a file of degenerate facets as an empty mesh");
    } catch (const cellforge::error& e) {
      CHECK(e.file() == "t.stl");
      CHECK(std::string(e.what()) ==
            std::string("t.stl: all 2 facets are degenerate (two corners are one vertex") +
                (weld ? ", after welding" : "") +
                "): no triangle is left (stl_read_options::degenerate = keep reads them)");
    }
  }
  CHECK(parse(all_degenerate, {.degenerate = io::stl_degenerate::keep}).soup.num_faces() == 2);
  CHECK(parse("solid e\nendsolid e\n").soup.num_faces() == 0);  // no facets at all: empty, as it is

  const auto unwelded = parse(text, {.weld = false});  // without welding: equal coordinates count
  CHECK(unwelded.degenerate_facets == 1);
  CHECK(unwelded.soup.num_points() == 6);

  io_test::check_rejected(
      {"refused degenerate facet", text, 3, "facet 1 is degenerate: its corners 0 and 2 are one vertex"},
      "t.stl", [](const std::string& s) { (void)parse(s, {.degenerate = io::stl_degenerate::refuse}); });
  try {
    binary_stl b(2);
    b.facet({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}).facet({{{0, 0, 0}, {0, 0, 0}, {0, 1, 0}}});
    (void)parse(b.bytes, {.degenerate = io::stl_degenerate::refuse});
    FAIL("accepted a degenerate facet");
  } catch (const cellforge::error& e) {
    CHECK(e.byte_offset() == 134);
    CHECK(e.message() ==
          "facet 1 is degenerate: its corners 0 and 1 are one vertex (stl_read_options::degenerate = drop or "
          "keep accepts it)");
  }
}

TEST_CASE("STL: several solids keep their names and face ranges; endsolid names are recorded") {
  const std::string text =
      "solid first part\n"
      "facet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 endloop endfacet\n"
      "facet normal 0 0 1 outer loop vertex 1 0 0 vertex 1 1 0 vertex 0 1 0 endloop endfacet\n"
      "endsolid first part\n"
      "solid\n"
      "endsolid\n"
      "SOLID Second\n"
      "FACET NORMAL 0 0 1 OUTER LOOP VERTEX 0 0 0 VERTEX 1 0 0 VERTEX 0 0 1 ENDLOOP ENDFACET\n"
      "ENDSOLID other_name\n";
  const auto d = parse(text);
  REQUIRE(d.solids.size() == 3);
  CHECK(d.solids[0].name == "first part");
  CHECK(d.solids[0].first_face == 0);
  CHECK(d.solids[0].num_faces == 2);
  CHECK_FALSE(d.solids[0].name_mismatch());
  CHECK(d.solids[1].name.empty());
  CHECK(d.solids[1].first_face == 2);
  CHECK(d.solids[1].num_faces == 0);
  CHECK(d.solids[2].name == "Second");
  CHECK(d.solids[2].end_name == "other_name");
  CHECK(d.solids[2].name_mismatch());
  CHECK(d.solids[2].first_face == 2);
  CHECK(d.solids[2].num_faces == 1);
  CHECK(d.mismatched_end_names == 1);
  CHECK(d.soup.num_faces() == 3);
  CHECK(d.soup.num_points() == 5);  // welded across solids
}

TEST_CASE("STL: layout variations read the same triangle") {
  const auto expected = parse(tri);
  const std::vector<std::pair<const char*, std::string>> variants = {
      {"CRLF",
       "solid t\r\nfacet normal 0 0 1\r\nouter loop\r\nvertex 0 0 0\r\nvertex 1 0 0\r\nvertex 0 1 0\r\n"
       "endloop\r\nendfacet\r\nendsolid t\r\n"},
      {"one line",
       "solid t\nfacet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 endloop "
       "endfacet endsolid t"},
      {"tokens split over lines",
       "solid t\nfacet\nnormal\n0\n0 1\nouter\nloop vertex\n0 0 0 vertex 1\n0 0 "
       "vertex 0 1 0\nendloop\tendfacet\n\nendsolid"},
      {"byte-order mark and leading blanks", "\xEF\xBB\xBF  \n " + tri},
      {"upper case",
       "SOLID t\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 0 0\nVERTEX 0 1 0\n"
       "ENDLOOP\nENDFACET\nENDSOLID t\n"},
      {"number spellings and a NaN normal",
       "solid t\nfacet normal nan -nan inf\nouter loop\nvertex 0.0 -0e0 +0\nvertex 1. 0 0\nvertex .0 1e0 "
       "0\nendloop\nendfacet\nendsolid t\n"},
  };
  for (const auto& variant : variants) {
    const std::string what = variant.first, text = variant.second;
    CAPTURE(what);
    const auto d = parse(text);
    CHECK(d.soup.points == expected.soup.points);
    CHECK(d.soup.face_vertices == expected.soup.face_vertices);
    CHECK(d.solids.size() == 1);
  }
}

TEST_CASE("STL: at least 12 kinds of malformed ASCII are rejected with the line and the reason") {
  const auto edit = [](int line, const std::string& replacement) {
    std::istringstream in(tri);
    std::string out, l;
    for (int n = 1; std::getline(in, l); ++n) out += (n == line ? replacement : l + "\n");
    return out;
  };
  const std::vector<io_test::bad_input> cases = {
      {"empty file", "", 1, "empty file"},
      {"only white space", "\n \n\t\n", 1, "empty file"},
      {"facet without normal", edit(2, "facet\n"), 3,
       "facet 0: expected 'normal' after 'facet', found 'outer'"},
      {"two normal components", edit(2, "facet normal 0 1\n"), 3,
       "expected normal component z of facet 0, found 'outer'"},
      {"four normal components", edit(2, "facet normal 0 0 1 0\n"), 2,
       "facet 0: the normal has more than 3 components: unexpected '0'"},
      {"non-numeric normal", edit(2, "facet normal 0 up 1\n"), 2,
       "expected normal component y of facet 0, found 'up'"},
      {"outer loop missing", edit(3, ""), 3,
       "facet 0: expected 'outer loop' after the normal, found 'vertex'"},
      {"loop missing", edit(3, " outer\n"), 4, "facet 0: expected 'loop' after 'outer', found 'vertex'"},
      {"two vertices", edit(6, ""), 6, "facet 0 has 2 vertices; STL facets are triangles (3 vertices)"},
      {"no vertices", "solid t\nfacet normal 0 0 1\nouter loop\nendloop\n", 4, "facet 0 has 0 vertices"},
      {"four vertices", edit(6, "  vertex 0 1 0\n  vertex 1 1 0\n"), 7,
       "facet 0 has more than 3 vertices; STL facets are triangles"},
      {"non-numeric coordinate", edit(5, "  vertex 1 zero 0\n"), 5,
       "expected coordinate y of vertex 1 of facet 0, found 'zero'"},
      {"number with junk", edit(5, "  vertex 1 0 0x\n"), 5,
       "expected coordinate z of vertex 1 of facet 0, found '0x'"},
      {"NaN coordinate", edit(4, "  vertex 0 nan 0\n"), 4,
       "coordinate y of vertex 0 of facet 0 'nan' is not finite (NaN and Inf coordinates are rejected)"},
      {"Inf coordinate", edit(6, "  vertex -inf 1 0\n"), 6,
       "coordinate x of vertex 2 of facet 0 '-inf' is not finite"},
      {"overflowing coordinate", edit(6, "  vertex 0 1 1e999\n"), 6,
       "coordinate z of vertex 2 of facet 0 '1e999' is out of range"},
      {"four coordinates", edit(4, "  vertex 0 0 0 0\n"), 4,
       "vertex 0 of facet 0 has more than 3 coordinates: unexpected '0'"},
      {"two coordinates", edit(4, "  vertex 0 0\n"), 5,
       "expected coordinate z of vertex 0 of facet 0, found 'vertex'"},
      {"endloop missing", edit(7, ""), 7, "facet 0: expected 'endloop', found 'endfacet'"},
      {"endfacet missing", edit(8, ""), 8, "facet 0: expected 'endfacet' after 'endloop', found 'endsolid'"},
      {"endsolid missing", tri.substr(0, tri.size() - 11), 8,
       "file ends inside solid 't': expected 'facet' or 'endsolid'"},
      {"file ends inside a vertex", tri.substr(0, tri.find("0 0 0\n") + 3), 4,
       "expected coordinate z of vertex 0 of facet 0, found end of file"},
      {"garbage in a solid", edit(2, "face normal 0 0 1\n"), 2,
       "expected 'facet' or 'endsolid' in solid 't', found 'face'"},
      {"garbage after endsolid", tri + "\n\n% the end\n", 12,
       "unexpected '%' after 'endsolid' (only another 'solid' may follow)"},
      {"second solid unterminated", tri + "solid u\n", 10, "file ends inside solid 'u'"},
      {"error in a later facet names it",
       edit(8, "endfacet\nfacet normal 0 0 1 outer loop vertex 1 1 1 endloop\n"), 9,
       "facet 1 has 1 vertices"},
  };
  CHECK(cases.size() >= 12);
  for (const auto& c : cases)
    io_test::check_rejected(c, "t.stl", [](const std::string& s) { (void)parse(s); });
}

TEST_CASE("STL: malformed binary is rejected with the byte offset and the facet") {
  binary_stl one(1);
  one.facet({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}});
  const std::string ok = one.bytes;
  REQUIRE(parse(ok).soup.num_faces() == 1);

  check_binary_rejected("too short and not ASCII", "hello", 0,
                        "not an STL file: 5 bytes are too few for binary STL");
  check_binary_rejected(
      "truncated", ok.substr(0, 120), 80,
      "the header's facet count 1 needs 134 bytes (84 + 50 per facet) but the file has 120: "
      "truncated, or not an STL file");
  binary_stl huge(1000000);
  huge.facet({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}});
  check_binary_rejected("facet count larger than the file", huge.bytes, 80,
                        "the header's facet count 1000000 needs 50000084 bytes");
  check_binary_rejected("bytes after the last facet", ok + "xyz", 134,
                        "3 bytes of unexpected data after the last of 1 facets");
  binary_stl solid_header(3, "solid pretending");
  solid_header.facet({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}});
  check_binary_rejected("truncated, starting with solid", solid_header.bytes, 80,
                        "(the file starts with 'solid' but holds binary data, so it is read as binary)");

  std::string nan_y = ok;
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::memcpy(nan_y.data() + 84 + 12 + 12 + 4, &nan, 4);  // y of vertex 1
  check_binary_rejected(
      "NaN coordinate", nan_y, 112,
      "coordinate y of vertex 1 of facet 0 (nan) is not finite (NaN and Inf coordinates are "
      "rejected)");
  std::string inf_z = ok;
  std::memcpy(inf_z.data() + 84 + 12 + 24 + 8, &inf, 4);
  check_binary_rejected("Inf coordinate", inf_z, 128,
                        "coordinate z of vertex 2 of facet 0 (inf) is not finite");
  // A NaN normal and any attribute bytes are fine: neither is kept.
  std::string odd = ok;
  std::memcpy(odd.data() + 84, &nan, 4);
  odd[132] = '\x7f';
  CHECK(parse(odd).soup.num_faces() == 1);

  binary_stl half(1);
  half.facet({{{0.5f, 0, 0}, {1, 0, 0}, {0, 1, 0}}});
  try {
    (void)io::parse_stl<std::array<int, 3>>(half.bytes, "t.stl");
    FAIL("accepted 0.5 for an integer point");
  } catch (const cellforge::error& e) {
    CHECK(e.byte_offset() == 96);
    CHECK(e.message() ==
          "coordinate x of vertex 0 of facet 0 (0.500000) does not fit the point's scalar type");
  }
}

TEST_CASE("STL: binary with zero facets is an empty soup; a binary header may start with 'solid'") {
  const auto empty = parse(binary_stl(0, "nothing").bytes);
  CHECK(empty.encoding == io::stl_encoding::binary);
  CHECK(empty.soup.num_faces() == 0);
  CHECK(empty.soup.num_points() == 0);
  CHECK(empty.facets_read == 0);
  CHECK(empty.solids.at(0).name == "nothing");

  // Many exporters write "solid ..." into the binary header: the size decides first.
  const auto cube = parse(cube_binary("solid cube exported as binary"));
  CHECK(cube.encoding == io::stl_encoding::binary);
  CHECK(cube.soup.num_points() == 8);
  CHECK(cube.solids.at(0).name == "solid cube exported as binary");
  CHECK(parse(binary_stl(0, "solid").bytes).encoding == io::stl_encoding::binary);

  const auto ascii_empty = parse("solid nothing\nendsolid nothing\n");
  CHECK(ascii_empty.encoding == io::stl_encoding::ascii);
  CHECK(ascii_empty.soup.num_faces() == 0);
}

TEST_CASE("STL: a binary file beyond the 32-bit index limit is refused before anything is allocated") {
  // 84 + 50 n bytes with n = 2^32/3 + 1: a sparse file of 71.6 GB whose data is never read.
  const std::uint32_t n = static_cast<std::uint32_t>(io::detail::stl_max_facets + 1);
  const std::uint64_t size = 84 + 50 * std::uint64_t{n};
  const io_test::temp_path file("huge.stl");
  const int fd = ::open(file.path.c_str(), O_RDWR | O_CREAT | O_TRUNC, 0600);
  REQUIRE(fd >= 0);
  const std::string header = binary_stl(n, "huge").bytes;
  const bool made = ::ftruncate(fd, static_cast<off_t>(size)) == 0 &&
                    ::pwrite(fd, header.data(), header.size(), 0) == static_cast<ssize_t>(header.size());
  if (!made) {
    ::close(fd);
    MESSAGE("no sparse file of " << size << " bytes here; the limit test is skipped");
    return;
  }
  const std::string expected =
      "the header's facet count 1431655766 exceeds the 32-bit index limit (at most "
      "1431655765 facets, 3 corner indices each)";
  try {
    (void)io::read_stl<glm::dvec3>(file.path);
    FAIL("read a file beyond the 32-bit limit");
  } catch (const cellforge::error& e) {
    CHECK(e.byte_offset() == 80);
    CHECK(e.message() == expected);
  }
  // The same from memory: the mapped file's pages are never touched beyond the header.
  void* mapped = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_NORESERVE, fd, 0);
  if (mapped != MAP_FAILED) {
    try {
      (void)io::parse_stl<glm::dvec3>(std::string_view(static_cast<const char*>(mapped), size), "huge.stl");
      FAIL("parsed a file beyond the 32-bit limit");
    } catch (const cellforge::error& e) {
      CHECK(e.message() == expected);
    }
    ::munmap(mapped, size);
  }
  ::close(fd);
}

TEST_CASE_TEMPLATE("STL: binary write, read, write gives the same bytes; points equal as float32", P,
                   glm::dvec3, std::array<float, 3>, io_test::user_point, float_point, sealed_point,
                   std::array<int, 3>) {
  const auto soup = triangle_soup<P>(11, 100, 150);
  const std::string first = written(soup);
  REQUIRE(first.size() == 84 + 50 * soup.num_faces());
  CHECK(first.substr(0, 10) == std::string("cellforge\0", 10));
  CHECK(first.substr(80, 4) == std::string("\xfa\0\0\0", 4));  // 250 facets
  CHECK(first.substr(first.size() - 2) == std::string(2, '\0'));
  const auto back = io::parse_stl<P>(first, "first.stl");
  CHECK(back.encoding == io::stl_encoding::binary);
  CHECK(back.solids.at(0).name == "cellforge");
  CHECK(back.soup.face_vertices == soup.face_vertices);
  CHECK(back.vertices_after_weld == soup.num_points());
  CHECK(io_test::same_soup(back.soup, soup));  // the coordinates were floats: exact, -0 included
  CHECK(written(back.soup) == first);

  // Doubles that are not floats come back as the nearest float.
  polygon_soup<glm::dvec3> d;
  d.points = {{0.1, 1.0 / 3.0, -2e-40}, {1e30, 0, 0}, {0, 1, 1}};
  d.add_face({0, 1, 2});
  const auto r = parse(written(d));
  for (std::size_t i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a)
      CHECK(r.soup.points[i][a] == static_cast<double>(static_cast<float>(d.points[i][a])));
  CHECK(written(r.soup) == written(d));
}

TEST_CASE_TEMPLATE("STL: ASCII write, read, write gives the same text and the same values", P, glm::dvec3,
                   std::array<float, 3>, io_test::user_point, float_point, sealed_point, std::array<int, 3>) {
  auto soup = triangle_soup<P>(3, 60, 90);
  if constexpr (std::is_same_v<cellforge::scalar_t<P>, double>) {  // values only a double holds
    soup.points[5] = cellforge::point_traits<P>::make(0.1, std::numeric_limits<double>::max(), -1e-310);
    soup.points[6] = cellforge::point_traits<P>::make(-std::numeric_limits<double>::max(), 1.0 / 3.0, 5e-324);
  }
  const io::stl_write_options ascii{.binary = false, .solid_name = "my part 7"};
  const std::string first = written(soup, ascii);
  CHECK(first.starts_with("solid my part 7\n  facet normal "));
  CHECK(first.ends_with("    endloop\n  endfacet\nendsolid my part 7\n"));
  const auto back = io::parse_stl<P>(first, "first.stl");
  CHECK(back.encoding == io::stl_encoding::ascii);
  CHECK(back.solids.at(0).name == "my part 7");
  CHECK(io_test::same_soup(back.soup, soup));
  CHECK(written(back.soup, ascii) == first);

  const io_test::temp_path file("rt.stl");
  io::write_stl(file.path, soup, ascii);
  CHECK(io_test::same_soup(io::read_stl<P>(file.path).soup, soup));
}

TEST_CASE("STL: the writer's normals follow the right-hand rule and are zero for degenerate triangles") {
  polygon_soup<glm::dvec3> s;
  s.points = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {1e300, 0, 0}, {-1e300, 1e300, 0}, {5, 5, 5}};
  s.add_face({0, 1, 2});
  s.add_face({0, 2, 1});
  s.add_face({0, 1, 1});
  s.add_face({1, 3, 4});  // huge: the cross product would overflow without scaling
  s.add_face({0, 5, 5});
  const std::string text = written(s, {.binary = false});
  std::vector<std::string> normals;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.starts_with("  facet normal ")) normals.push_back(line.substr(15));
  CHECK(normals == std::vector<std::string>{"0 0 1", "0 0 -1", "0 0 0", "0 -0 1", "0 0 0"});
  s.face_offsets.resize(3);  // the first two triangles: binary cannot hold 1e300
  s.face_vertices.resize(6);
  const std::string bin = written(s);
  float n[3];
  std::memcpy(n, bin.data() + 84 + 50, 12);
  CHECK(n[0] == 0.0f);
  CHECK(n[2] == -1.0f);
}

TEST_CASE("STL: the writer ear-clips polygons: areas add up and no triangle leaves the polygon") {
  // A U shape: a fan from vertex 0 would cover the notch between the arms.
  const std::vector<std::array<double, 2>> u = {{0, 0}, {3, 0}, {3, 3}, {2, 3},
                                                {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  // The same polygon tilted out of its plane's axes: u along (1,0,1)/√2 ... as exact-enough doubles.
  for (const bool tilted : {false, true}) {
    CAPTURE(tilted);
    polygon_soup<glm::dvec3> s;
    for (const auto& p : u)
      s.points.push_back(tilted ? glm::dvec3(p[0], p[1], 0.5 * p[0]) : glm::dvec3(p[0], p[1], 0));
    s.add_face({0, 1, 2, 3, 4, 5, 6, 7});
    s.points.push_back({5, 0, 0});
    s.points.push_back({6, 0, 0});
    s.points.push_back({6, 1, 0});
    s.points.push_back({5, 1, 0});
    s.add_face({8, 9, 10, 11});  // a quad
    for (const bool binary : {true, false}) {
      const auto d = parse(written(s, {.binary = binary}));
      REQUIRE(d.soup.num_faces() == 6 + 2);
      CHECK(d.soup.num_points() == 12);
      double total = 0;
      for (std::size_t f = 0; f < 6; ++f) {
        std::array<std::array<double, 2>, 3> t;
        for (std::size_t k = 0; k < 3; ++k) {
          const glm::dvec3 p = d.soup.points[d.soup.face(f)[k]];
          t[k] = {p.x, p.y};  // the projection to z = 0 keeps the U's shape
          if (tilted) CHECK(p.z == 0.5 * p.x);
        }
        const double a = 0.5 * area2(t[0], t[1], t[2]);
        CHECK(a > 0);  // turns like the polygon
        total += a;
        const std::array<double, 2> centroid = {(t[0][0] + t[1][0] + t[2][0]) / 3,
                                                (t[0][1] + t[1][1] + t[2][1]) / 3};
        CHECK(inside_or_on(u, centroid));
        for (std::size_t k = 0; k < 3; ++k)
          CHECK(inside_or_on(u, {(t[k][0] + t[(k + 1) % 3][0]) / 2, (t[k][1] + t[(k + 1) % 3][1]) / 2}));
      }
      CHECK(total == doctest::Approx(7.0));  // 9 minus the 1 × 2 notch
      double quad = 0;
      for (std::size_t f = 6; f < 8; ++f) {
        const auto& p = d.soup.points;
        const auto face = d.soup.face(f);
        quad += 0.5 * area2({p[face[0]].x, p[face[0]].y}, {p[face[1]].x, p[face[1]].y},
                            {p[face[2]].x, p[face[2]].y});
      }
      CHECK(quad == doctest::Approx(1.0));
    }
  }
}

TEST_CASE("STL: writing refuses what reading would reject or binary cannot hold") {
  polygon_soup<glm::dvec3> s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}};
  s.add_face({0, 1, 2});
  std::ostringstream os;
  CHECK_THROWS_WITH_AS(io::write_stl(os, s), "write_stl: point 2 has a non-finite coordinate",
                       cellforge::error);
  s.points[2].y = 1e39;
  CHECK_THROWS_WITH_AS(io::write_stl(os, s),
                       "write_stl: point 2 has a coordinate beyond the float32 range of binary STL",
                       cellforge::error);
  CHECK_NOTHROW(io::write_stl(os, s, {.binary = false}));  // ASCII writes the double
  s.points[2].y = 1;
  s.add_face({0, 1, 3});
  CHECK_THROWS_WITH_AS(io::write_stl(os, s), "write_stl: face vertex index 3 out of range (3 points)",
                       cellforge::error);
  s.face_vertices.back() = 2;
  const auto refused = [&](const io::stl_write_options& o) {
    try {
      io::write_stl(os, s, o);
      return std::string("accepted");
    } catch (const cellforge::error& e) {
      CHECK(e.category() == cellforge::error_category::invalid_input);
      return e.message();
    }
  };
  CHECK(refused({.binary = false, .solid_name = "two\nlines"}).find("has a line break") != std::string::npos);
  CHECK(refused({.binary = false, .solid_name = " padded"}).find("starts or ends with a blank") !=
        std::string::npos);
  CHECK(refused({.binary = true, .solid_name = std::string(81, 'x')}).find("longer than the 80-byte") !=
        std::string::npos);
  CHECK(refused({.binary = true, .solid_name = "trailing "}).find("ends with a NUL or space") !=
        std::string::npos);
  CHECK(refused({.binary = true, .solid_name = std::string(80, 'x')}) == "accepted");
  // A polygon ear clipping refuses (not planar) is named.
  s.points.push_back({0, 1, 1});
  s.add_face({0, 1, 2, 3});
  s.points[2] = {1, 1, 0};
  CHECK(refused({}).starts_with("write_stl: triangulate: face 2: ear_clip: the polygon is not planar"));

  CHECK(written(polygon_soup<glm::dvec3>{}, {.binary = false}) == "solid cellforge\nendsolid cellforge\n");
  CHECK(written(polygon_soup<glm::dvec3>{}, {.binary = false, .solid_name = ""}) == "solid\nendsolid\n");
  CHECK(written(polygon_soup<glm::dvec3>{}).size() == 84);
}

TEST_CASE("STL: read_soup and write_soup pick STL by extension") {
  polygon_soup<glm::dvec3> s;
  for (const auto& f : cube_facets())
    for (const auto& p : f) s.points.push_back({p[0], p[1], p[2]});
  for (std::uint32_t f = 0; f < 12; ++f) s.add_face({3 * f, 3 * f + 1, 3 * f + 2});
  CHECK(io::format_of("part.STL") == io::mesh_format::stl);
  const io_test::temp_path file("cube.stl");
  io::write_soup(file.path, s);
  CHECK(std::filesystem::file_size(file.path) == 84 + 50 * 12);
  const auto back = io::read_soup<glm::dvec3>(file.path);
  CHECK(back.num_points() == 8);
  CHECK(back.face_vertices == parse(cube_ascii()).soup.face_vertices);
}

TEST_CASE("STL: file errors name the path") {
  const auto dir = std::filesystem::temp_directory_path() / "cellforge_no_such_dir" / "out.stl";
  CHECK_THROWS_WITH_AS(io::write_stl(dir, polygon_soup<glm::dvec3>{}),
                       ("cannot open '" + dir.string() + "' for writing").c_str(), cellforge::error);
  io_test::check_file_errors("bad.stl", "solid x\nfacet normal 0 0\n", 2,
                             [](const std::filesystem::path& p) { (void)io::read_stl<glm::dvec3>(p); });
  io_test::check_file_errors("bad_binary.stl", std::string(90, '\0'), 0,
                             [](const std::filesystem::path& p) { (void)io::read_stl<glm::dvec3>(p); });
}

}  // namespace io_stl_tests
