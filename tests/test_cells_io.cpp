#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/validate.hpp"
#include "cellforge/io/cells_io.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/io/ply.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"
#include "cells_fixtures.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace cells_io_tests {

using namespace cellforge;
using namespace cellforge::samples;
namespace fx = cells_fixtures;

namespace {

std::string text_of(const cell_complex<glm::dvec3>& cc) {
  std::ostringstream os;
  io::write_3dcl(os, cc);
  return os.str();
}

std::vector<std::string> split_lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream is(s);
  for (std::string line; std::getline(is, line);) out.push_back(line);
  return out;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

void same_complex(const cell_complex<glm::dvec3>& a, const cell_complex<glm::dvec3>& b) {
  CHECK(fx::same_input(a.to_input(), b.to_input()));
}

}  // namespace

TEST_CASE("3dcl: written in the seed's order and read back identically") {
  const std::vector<cell_complex_input<glm::dvec3>> inputs{fx::cube(),           fx::two_cubes(),
                                                           fx::grid(2, 2, 1),    fx::frame(),
                                                           fx::disjoint_cubes(), fx::block_with_hole()};
  for (const auto& in : inputs) {
    auto moved = in;
    for (auto& p : moved.points) p = p * 0.1 + glm::dvec3(1.0 / 3.0, -2e-7, 1e5);  // not short decimals
    const cell_complex<glm::dvec3> cc = make_cell_complex(moved);
    const std::string text = text_of(cc);
    const cell_complex<glm::dvec3> back = io::parse_3dcl<glm::dvec3>(text, "t.3dcl");
    same_complex(cc, back);
    CHECK(text_of(back) == text);
    CHECK(validate(back).ok());
  }
  const std::string cube = text_of(make_cell_complex(fx::cube()));
  const auto lines = split_lines(cube);
  REQUIRE(lines.size() == 33);
  CHECK(lines[0] == "3dcl 1");
  CHECK(lines[1] == "vertices 8");
  CHECK(lines[2].rfind("v 0 0 0 0 edges ", 0) == 0);
  CHECK(lines[10] == "edges 12");
  CHECK(lines[11].rfind("e 0 0 1 faces ", 0) == 0);
  CHECK(lines[11].find(" volumes 0 -") != std::string::npos);  // the cube, then outside
  CHECK(lines[23] == "faces 6");
  CHECK(lines[24].rfind("f 0 volumes -0 loop ", 0) == 0);  // face x = 0: its normal (+x) points in
  CHECK(lines[30] == "volumes 1");
  CHECK(lines[31].rfind("c 0 faces ", 0) == 0);
  CHECK(lines[32] == "end");
  const std::string hole = text_of(make_cell_complex(fx::block_with_hole()));
  CHECK(hole.find("f 0 volumes +0 loop 4 5 6 7 edges") != std::string::npos);
  CHECK(hole.find(" loop 12 15 14 13 edges") != std::string::npos);

  // Comments, blank lines, CRLF line ends and a byte-order mark are accepted.
  std::string decorated = "\xEF\xBB\xBF# made by hand\r\n";
  for (const auto& l : lines) decorated += l + "   # note\r\n\r\n";
  same_complex(io::parse_3dcl<glm::dvec3>(decorated), make_cell_complex(fx::cube()));

  // Files.
  const auto path = std::filesystem::temp_directory_path() / "cellforge_test_cells.3dcl";
  const cell_complex<glm::dvec3> two = make_cell_complex(fx::two_cubes());
  io::write_3dcl(path, two, {.comment = "two cubes\nsharing a face"});
  same_complex(io::read_3dcl<glm::dvec3>(path), two);
  std::filesystem::remove(path);
  CHECK_THROWS_AS((void)io::read_3dcl<glm::dvec3>(path), error);
}

TEST_CASE("3dcl: malformed files give file:line and what was expected") {
  const auto good = split_lines(text_of(make_cell_complex(fx::cube())));
  auto with = [&](std::size_t line, const std::string& text) {
    auto l = good;
    l[line - 1] = text;
    return join_lines(l);
  };
  auto first = [&](std::size_t n) {
    return join_lines(std::vector<std::string>(good.begin(), good.begin() + n));
  };
  auto replaced = [&](std::size_t line, const std::string& from, const std::string& to) {
    auto l = good;
    const auto at = l[line - 1].find(from);
    REQUIRE(at != std::string::npos);
    l[line - 1].replace(at, from.size(), to);
    return join_lines(l);
  };
  // Line 25 is face 0 (x = 0, normal +x into the cube): "f 0 volumes -0 loop 0 1 2 3 edges
  // +0 +1 +2 +3"; line 12 is edge 0 "e 0 0 1 faces +0 -4 volumes 0 -".
  const std::string face0 = good[24], edge0 = good[11];
  const auto swap_two = [](std::string s, const std::string& key) {
    // Swaps the first two signed entries after `key`.
    const auto at = s.find(key) + key.size();
    const auto a_end = s.find(' ', at + 1), b_end = s.find(' ', a_end + 1);
    const std::string a = s.substr(at + 1, a_end - at - 1),
                      b = s.substr(a_end + 1, (b_end == std::string::npos ? s.size() : b_end) - a_end - 1);
    return s.substr(0, at + 1) + b + " " + a + (b_end == std::string::npos ? "" : s.substr(b_end));
  };
  struct bad_case {
    std::string text;
    std::uint64_t line;
    std::string message;
  };
  const std::vector<bad_case> cases{
      {"", 1, "expected the header '3dcl 1', found end of file"},
      {"# only a comment\n\n", 2, "expected the header '3dcl 1', found end of file"},
      {with(1, "3dcl 2"), 1, "unsupported 3dcl version '2'"},
      {with(1, "cells 1"), 1, "expected '3dcl' at the start of the file"},
      {with(2, "verts 8"), 2, "expected 'vertices'"},
      {with(2, "vertices x"), 2, "expected the number of vertices (a non-negative integer), found 'x'"},
      {with(2, "vertices -1"), 2, "found '-1'"},
      {with(2, "vertices 9"), 11, "expected 'v' at the start of vertex 8 (there are 9), found 'edges'"},
      {replaced(3, "v 0 ", "v 5 "), 3, "expected vertex number 0, found '5'"},
      {replaced(3, "v 0 0 0 0", "v 0 0 0"), 3, "expected coordinate z of vertex 0 (a number), found 'edges'"},
      {replaced(3, "v 0 0", "v 0 nan"), 3, "coordinate x of vertex 0 'nan' is not finite"},
      {replaced(3, "v 0 0", "v 0 1.5x"), 3, "expected coordinate x of vertex 0 (a number), found '1.5x'"},
      {replaced(12, "e 0 0 1", "e 0 0 99"), 12, "the end vertex of edge 0 99 out of range (0..7)"},
      {replaced(12, "faces +", "faces "), 12, "expected a face with its sign (like +3 or -3)"},
      {replaced(12, " volumes", " vols"), 12, "expected 'volumes' after the faces of edge 0, found 'vols'"},
      {first(20), 20, "expected edge 9 of 12, found end of file"},
      {first(32), 32, "expected 'end' after the last volume, found end of file"},
      {join_lines(good) + "v 9\n", 34, "unexpected content after 'end'"},
      {with(33, "end now"), 33, "unexpected 'now' at the end of the file"},
      {with(25, "f 0 volumes -0"), 25, "face 0 has no 'loop'"},
      {replaced(25, " loop ", " lop "), 25, "expected 'loop' (a vertex loop) in face 0, found 'lop'"},
      {replaced(25, " edges", " x"), 25,
       "expected 'edges' after the vertices of a loop of face 0, found 'x'"},
  };
  auto run = [](const bad_case& c) {
    try {
      (void)io::parse_3dcl<glm::dvec3>(c.text, "bad.3dcl");
      FAIL("no error for: " << c.message);
    } catch (const error& e) {
      INFO(e.what());
      CHECK(e.category() == error_category::io);
      CHECK(e.file() == "bad.3dcl");
      CHECK(e.line() == c.line);
      CHECK(std::string(e.what()).find(c.message) != std::string::npos);
      CHECK(std::string(e.what()).rfind("bad.3dcl:" + std::to_string(c.line) + ": ", 0) == 0);
    }
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    INFO("case " << i);
    run(cases[i]);
  }

  // Relations that disagree with the cells, and cells make_cell_complex refuses.
  std::string v0 = good[2];
  const auto plus = v0.find(" +");
  v0[plus + 1] = '-';  // an edge leaving vertex 0 listed as arriving
  const std::vector<bad_case> relations{
      {with(3, v0), 3, "vertex 0: the listed edges are not those at it"},
      {with(12, swap_two(edge0, " faces")), 12, "edge 0: the listed faces are not those at it"},
      {replaced(12, "volumes 0 -", "volumes - 0"), 12, "edge 0: the listed volumes are not those between"},
      {replaced(25, "volumes -0", "volumes +0"), 25, "face 0: the listed volumes are not the face's"},
      {replaced(25, "loop 0 1 2 3", "loop 0 2 1 3"), 25, "face 0 loop 0: consecutive vertices 0 and 2"},
      {replaced(32, "faces -0", "faces +0"), 32, "the boundary of volume 0 is not closed"},
  };
  for (std::size_t i = 0; i < relations.size(); ++i) {
    INFO("relation case " << i);
    run(relations[i]);
  }
  // A repeated edge: edge 1 given edge 0's endpoints.
  auto l = good;
  l[12] = "e 1 0 1" + l[12].substr(l[12].find(" faces"));
  run({join_lines(l), 13, "edge 1 repeats edge 0"});
  CHECK(cases.size() + relations.size() + 1 >= 25);
}

TEST_CASE("cells OBJ: one group per volume") {
  const cell_complex<glm::dvec3> cc = make_cell_complex(fx::two_cubes());
  std::ostringstream os;
  io::write_cells_obj(os, cc, {.comment = "two cubes"});
  const auto data = io::parse_obj<glm::dvec3>(os.str(), "two.obj");
  REQUIRE(data.groups.size() == 2);
  CHECK(data.groups[0].name == "volume_0");
  CHECK(data.groups[1].name == "volume_1");
  CHECK(data.groups[1].first_face == 6);
  CHECK(data.soup.num_faces() == 12);  // the shared face in both groups
  CHECK(data.soup.points.size() == 12);
  // Each group is a closed box with outward faces.
  for (std::size_t g = 0; g < 2; ++g) {
    polygon_soup<glm::dvec3> box;
    box.points = data.soup.points;
    for (std::size_t f = 6 * g; f < 6 * g + 6; ++f) box.add_face(data.soup.face(f));
    const cell_complex<glm::dvec3> one = mesh_to_cell_complex(make_mesh(box));
    CHECK(validate(one).signed_volumes == std::vector<double>{1.0});
  }
  // Faces with holes are triangulated; dangling edges become lines.
  auto in = fx::block_with_hole();
  in.points.push_back({5, 5, 5});
  in.edges.push_back({0, 16});
  const auto holed = io::cells_obj_data(make_cell_complex(in));
  CHECK(holed.soup.num_faces() == 8 + 2 * 8);
  CHECK(holed.lines == std::vector<std::array<std::uint32_t, 2>>{{0, 16}});
}

TEST_CASE("cells PLY: faces coloured by volume") {
  const cell_complex<glm::dvec3> cc = make_cell_complex(fx::grid(2, 1, 1));
  std::ostringstream os;
  io::write_cells_ply(os, cc);
  const std::string text = os.str();
  CHECK(text.find("property uchar red") != std::string::npos);
  const auto soup = io::parse_ply<glm::dvec3>(text, "grid.ply");
  CHECK(soup.num_faces() == 12);
  CHECK(soup.points.size() == 12);
  // The colour columns: six faces of one colour, six of another.
  std::set<std::string> colours;
  for (const auto& line : split_lines(text))
    if (line.rfind("4 ", 0) == 0)
      colours.insert(line.substr(line.rfind(' ', line.rfind(' ', line.rfind(' ') - 1) - 1)));
  CHECK(colours.size() == 2);
  CHECK(io::volume_colour(0) != io::volume_colour(1));
}

TEST_CASE("cells SVG: volumes exploded apart, faces shaded") {
  const cell_complex<glm::dvec3> cc = make_cell_complex(fx::grid(2, 2, 1));
  std::ostringstream a, b;
  const auto ra = io::write_cells_svg(a, cc, {.explode = 0.0});
  const auto rb = io::write_cells_svg(b, cc);
  CHECK(ra.faces_drawn == 24);
  CHECK(rb.faces_drawn == 24);
  CHECK(a.str().rfind("<?xml", 0) == 0);
  CHECK(a.str() != b.str());
  // Exploded, the four volumes' layers are offset away from the centre by 35% of their
  // centres' distance from it.
  const auto scene = io::cells_svg_scene(cc);
  CHECK(scene.num_layers() == 4);
  const auto vis = scene.edge_visibility();
  double max_x = -1e9;
  for (const auto& e : vis) max_x = std::max({max_x, e.a.x, e.b.x});
  CHECK(max_x == doctest::Approx(2.0 + 0.35 * 0.5));
  CHECK_THROWS_AS((void)io::cells_svg_scene(cc, {.explode = -1}), error);
  // A face with a hole is drawn without its triangulation's diagonals.
  const auto holed = io::cells_svg_scene(make_cell_complex(fx::block_with_hole()));
  std::size_t drawn_edges = 0;
  for (const auto& e : holed.edge_visibility()) drawn_edges += e.layer == 0 ? 1 : 0;
  CHECK(drawn_edges >= 24);
}

TEST_CASE("3dcl, OBJ and SVG of the sample models' complexes") {
  for (const auto& m : all_small_samples()) {
    INFO(m.name);
    const cell_complex<glm::dvec3> cc = wireframe_to_cells(m.wire).cells;
    const std::string text = text_of(cc);
    const cell_complex<glm::dvec3> back = io::parse_3dcl<glm::dvec3>(text, m.name);
    same_complex(cc, back);
    CHECK(text_of(back) == text);
    const auto obj = io::cells_obj_data(cc);
    CHECK(obj.groups.size() == cc.num_volumes());
    std::ostringstream svg;
    CHECK(io::write_cells_svg(svg, cc).faces_drawn == obj.soup.num_faces());
  }
}

TEST_CASE("cells SVG of 1000 volumes: one layer and six faces per volume, the nearest cube as if alone") {
  const cell_complex<glm::dvec3> cc = make_cell_complex(fx::grid(10, 10, 10));
  const io::svg_scene scene = io::cells_svg_scene(cc);
  CHECK(scene.num_layers() == 1000);
  std::ostringstream os;
  const io::svg_result r = io::write_cells_svg(os, cc);
  const std::string text = os.str();
  CHECK(r.faces_drawn == 6000);
  CHECK(r.edges == 12000);  // each cube's own 12 edges, in its own layer
  CHECK(r.visible_edges + r.hidden_edges + r.partly_hidden_edges == 12000);
  CHECK(r.approximate_edges + r.untested_edges == 0);
  std::size_t polygons = 0;
  for (std::size_t at = text.find("<polygon"); at != std::string::npos; at = text.find("<polygon", at + 1))
    ++polygons;
  CHECK(polygons == 6000);
  CHECK(text.find("stroke-dasharray") != std::string::npos);
  // The default camera looks from the +x +y +z side: cube (9, 9, 9), volume 999, is in front of
  // everything, so exactly its three edges at its far corner are hidden, by its own faces.
  std::size_t visible = 0, hidden = 0, layer_edges = 0;
  glm::dvec3 lo(1e9), hi(-1e9);
  for (const auto& e : scene.edge_visibility()) {
    if (e.layer != 999) continue;
    ++layer_edges;
    visible += e.hidden.empty() ? 1 : 0;
    hidden += e.hidden.size() == 1 && e.hidden[0] == std::array<double, 2>{0.0, 1.0} ? 1 : 0;
    lo = glm::min(lo, glm::min(e.a, e.b));
    hi = glm::max(hi, glm::max(e.a, e.b));
  }
  CHECK(layer_edges == 12);
  CHECK(visible == 9);
  CHECK(hidden == 3);
  // Exploded: the cube keeps its size and moves away from the centre (5, 5, 5).
  CHECK(hi.x - lo.x == doctest::Approx(1.0));
  CHECK(lo.x == doctest::Approx(9.0 + 0.35 * 4.5));
}

TEST_CASE("cells SVG of 512 separate cubes: every object drawn, its layer holding only its own cube") {
  std::vector<fx::cube_cell> cubes;
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; ++y)
      for (int z = 0; z < 8; ++z) cubes.push_back({2 * x, 2 * y, 2 * z});
  const cell_complex<glm::dvec3> cc = make_cell_complex(fx::lattice(cubes));
  CHECK(cc.num_objects() == 512);
  const io::svg_scene scene = io::cells_svg_scene(cc, {.explode = 0.0});
  CHECK(scene.num_layers() == 512);
  std::ostringstream os;
  const io::svg_result r = scene.write(os);
  CHECK(r.faces_drawn == 512 * 6);
  CHECK(r.edges == 512 * 12);
  CHECK(r.approximate_edges + r.untested_edges == 0);
  // Unexploded, each layer's edges lie on its own cube.
  for (const auto& e : scene.edge_visibility()) {
    const auto& c = cubes[e.layer];
    for (const glm::dvec3& p : {e.a, e.b})
      for (int k = 0; k < 3; ++k) CHECK((p[k] == c[k] || p[k] == c[k] + 1));
  }
}

TEST_CASE("cells PLY: a face of more than 255 vertices gets a wider count type and reads back") {
  // A prism over a 300-gon: two 300-gon caps and 300 side quads, one volume.
  constexpr std::uint32_t n = 300;
  cell_complex_input<glm::dvec3> in;
  for (std::uint32_t z = 0; z < 2; ++z)
    for (std::uint32_t i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n;
      in.points.push_back({std::cos(a), std::sin(a), double(z)});
    }
  std::vector<std::uint32_t> bottom, top;
  cell_input_volume vol;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    in.edges.push_back({i, j});
    in.edges.push_back({n + i, n + j});
    in.edges.push_back({i, n + i});
    bottom.push_back(i);
    top.push_back(n + i);
  }
  in.faces.push_back({{bottom}});  // normal +z, into the prism
  in.faces.push_back({{top}});     // normal +z, out of it
  vol.faces = {{0, -1}, {1, +1}};
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    vol.faces.emplace_back(static_cast<std::uint32_t>(in.faces.size()), +1);
    in.faces.push_back({{{i, j, n + j, n + i}}});  // normal outward
  }
  in.volumes.push_back(vol);
  const cell_complex<glm::dvec3> cc = make_cell_complex(in);
  std::ostringstream os;
  io::write_cells_ply(os, cc);
  const std::string text = os.str();
  CHECK(text.find("property list ushort int vertex_indices") != std::string::npos);
  const auto soup = io::parse_ply<glm::dvec3>(text, "prism.ply");
  REQUIRE(soup.num_faces() == n + 2);
  std::size_t largest = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) largest = std::max(largest, soup.face(f).size());
  CHECK(largest == n);
}

TEST_CASE("cells io: faces with two to nine holes are written as triangles enclosing the volume") {
  // Plates with 2..9 square through-holes in rows and grids: the top and bottom faces have
  // one loop per hole, and the holes' bridges are crossed by the next holes' rays.
  for (std::size_t holes = 2; holes <= 9; ++holes) {
    const std::size_t cols = holes <= 3 ? holes : 3, rows = (holes + cols - 1) / cols;
    std::vector<double> xs, ys;
    for (std::size_t c = 0; c <= 2 * cols + 1; ++c)
      xs.push_back(static_cast<double>(c) + 0.1 * double(c % 3));
    for (std::size_t c = 0; c <= 2 * rows + 1; ++c)
      ys.push_back(static_cast<double>(c) + 0.2 * double(c % 2));
    voxel_layout l = empty_layout(xs, ys, {0.0, 0.5});
    for (std::size_t j = 0; j <= 2 * rows; ++j)
      for (std::size_t i = 0; i <= 2 * cols; ++i) l.at(i, j, 0) = 1;
    for (std::size_t h = 0; h < holes; ++h) l.at(2 * (h % cols) + 1, 2 * (h / cols) + 1, 0) = 0;
    const sample_model m = make_voxel_model(l, "plate with " + std::to_string(holes) + " holes");
    INFO(m.name);
    const cell_complex<glm::dvec3> cc = wireframe_to_cells(m.wire).cells;
    REQUIRE(cc.num_volumes() == 1);
    std::size_t most_loops = 0;
    for (const auto f : cc.faces()) most_loops = std::max(most_loops, cc.num_loops(f));
    CHECK(most_loops == holes + 1);
    std::ostringstream os;
    io::write_cells_obj(os, cc);  // threw "no ear found" on the second hole's bridge
    const io::obj_data<glm::dvec3> back = io::parse_obj<glm::dvec3>(os.str(), m.name);
    double volume = 0.0;  // the triangles' signed volume is the plate's: no face lost or folded
    for (std::size_t f = 0; f < back.soup.num_faces(); ++f) {
      const auto t = back.soup.face(f);
      for (std::size_t k = 1; k + 1 < t.size(); ++k)
        volume +=
            glm::dot(back.soup.points[t[0]], glm::cross(back.soup.points[t[k]], back.soup.points[t[k + 1]])) /
            6.0;
    }
    double solid = (xs.back() - xs.front()) * (ys.back() - ys.front()) * 0.5;
    for (std::size_t h = 0; h < holes; ++h) {
      const std::size_t i = 2 * (h % cols) + 1, j = 2 * (h / cols) + 1;
      solid -= (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]) * 0.5;
    }
    CHECK(volume == doctest::Approx(solid).epsilon(1e-12));
  }
}

TEST_CASE_TEMPLATE("cells io in the caller's point type: the same files as glm::dvec3, read back typed", P,
                   test_support::sealed_point, std::array<float, 3>) {
  for (const auto& m : {sample_two_cubes(), sample_block_with_hole(), sample_stepped_block()}) {
    INFO(m.name);
    const cell_complex<glm::dvec3> ref = wireframe_to_cells(m.wire).cells;
    const cell_complex<P> cc = wireframe_to_cells(to_wireframe<P>(m.wire)).cells;
    auto text = [](const auto& c) {
      std::ostringstream os;
      io::write_3dcl(os, c, {.comment = "typed"});
      return os.str();
    };
    // The models' coordinates are exact in float, so every writer writes the same bytes.
    CHECK(text(cc) == text(ref));
    std::ostringstream obj, obj_ref, ply, ply_ref, svg, svg_ref;
    io::write_cells_obj(obj, cc);
    io::write_cells_obj(obj_ref, ref);
    CHECK(obj.str() == obj_ref.str());
    io::write_cells_ply(ply, cc);
    io::write_cells_ply(ply_ref, ref);
    CHECK(ply.str() == ply_ref.str());
    CHECK(io::write_cells_svg(svg, cc).visible_pieces == io::write_cells_svg(svg_ref, ref).visible_pieces);
    CHECK(svg.str() == svg_ref.str());
    const io::obj_data<P> data = io::cells_obj_data(cc);
    CHECK(data.soup.num_faces() == io::cells_obj_data(ref).soup.num_faces());
    // Read back in P: the same complex.
    const cell_complex<P> back = io::parse_3dcl<P>(text(cc), m.name);
    CHECK(fx::same_input(convert_points<glm::dvec3>(back).to_input(), ref.to_input()));
    REQUIRE_VALID(back);
  }
}

}  // namespace cells_io_tests
