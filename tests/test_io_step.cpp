// io/step.hpp on its own (OpenCASCADE reads the files back in tests/occt): the file's
// structure, its counts, orientation flags, strings and numbers, errors, files and meshes.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/step.hpp"
#include "cells_fixtures.hpp"
#include "io_test_support.hpp"
#include "mesh_fixtures.hpp"
#include "rounded_fixtures.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace io_step_tests {

namespace {

std::string step_of(const cellforge::cell_complex<glm::dvec3>& cc, cellforge::io::step_result* r = nullptr,
                    const cellforge::io::step_write_options& options = {}) {
  std::ostringstream os;
  const auto result = cellforge::io::write_step(os, cc, options);
  if (r) *r = result;
  return os.str();
}

// The DATA section's entities: number → text after '='. Fails the test on a line that is not
// "#n=...;" or on a number defined twice. O(file).
std::map<std::size_t, std::string> entities(const std::string& text) {
  std::map<std::size_t, std::string> out;
  const std::size_t data = text.find("\nDATA;\n"), end = text.find("\nENDSEC;\nEND-ISO-10303-21;\n");
  REQUIRE(data != std::string::npos);
  REQUIRE(end != std::string::npos);
  for (std::size_t at = data + 7; at < end + 1;) {
    const std::size_t eol = text.find('\n', at);
    const std::string line = text.substr(at, eol - at);
    at = eol + 1;
    const std::size_t eq = line.find('=');
    REQUIRE(line.size() > 2);
    REQUIRE(line[0] == '#');
    REQUIRE(line.back() == ';');
    const std::size_t n = std::stoul(line.substr(1, eq - 1));
    CHECK(out.emplace(n, line.substr(eq + 1, line.size() - eq - 2)).second);
  }
  return out;
}

std::size_t count(const std::map<std::size_t, std::string>& es, std::string_view head) {
  std::size_t n = 0;
  for (const auto& [k, text] : es) n += text.starts_with(head);
  return n;
}

}  // namespace

TEST_CASE("step: two cubes sharing a face, entity by entity") {
  const auto cc = cellforge::make_cell_complex(cells_fixtures::two_cubes());
  cellforge::io::step_result r;
  const std::string text = step_of(cc, &r);
  CHECK(text.starts_with("ISO-10303-21;\nHEADER;\n"));
  CHECK(text.find("FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));") != std::string::npos);
  CHECK(text.ends_with("ENDSEC;\nEND-ISO-10303-21;\n"));
  const auto es = entities(text);
  // Numbered 1..n without gaps, and every reference names an entity.
  REQUIRE(es.size() == r.entities);
  CHECK(es.begin()->first == 1);
  CHECK(es.rbegin()->first == r.entities);
  for (const auto& entry : es) {  // no structured binding: clang 14 cannot capture one in CHECK_MESSAGE
    const std::size_t k = entry.first;
    const std::string& body = entry.second;
    for (std::size_t at = body.find('#'); at != std::string::npos; at = body.find('#', at + 1)) {
      std::size_t end = at + 1;
      while (end < body.size() && body[end] >= '0' && body[end] <= '9') ++end;
      const std::size_t ref = std::stoul(body.substr(at + 1, end - at - 1));
      CHECK_MESSAGE(es.count(ref) == 1, "#", k, " names #", ref);
    }
  }
  // 12 vertices and 20 edges written once; 11 planes; 12 faces, the shared one twice.
  CHECK(r.solids == 2);
  CHECK(r.voids == 0);
  CHECK(r.open_shells == 0);
  CHECK(r.vertices == 12);
  CHECK(r.edges == 20);
  CHECK(r.planes == 11);
  CHECK(r.faces == 12);
  CHECK(r.diagnostics.empty());
  CHECK(count(es, "VERTEX_POINT(") == 12);
  CHECK(count(es, "EDGE_CURVE(") == 20);
  CHECK(count(es, "PLANE(") == 11);
  CHECK(count(es, "EDGE_LOOP(") == 11);
  CHECK(count(es, "ADVANCED_FACE(") == 12);
  CHECK(count(es, "CLOSED_SHELL(") == 2);
  CHECK(count(es, "MANIFOLD_SOLID_BREP(") == 2);
  CHECK(count(es, "ADVANCED_BREP_SHAPE_REPRESENTATION(") == 1);
  CHECK(count(es, "SHAPE_DEFINITION_REPRESENTATION(") == 1);
  CHECK(count(es, "(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))") == 1);
  // A face used against its normal has same_sense .F. and bounds .F.: as many as sign -1 uses.
  std::size_t against = 0;
  for (cellforge::cell_volume c : cc.volumes())
    for (const auto& [f, s] : cc.volume_faces(c)) against += s < 0;
  CHECK(against > 0);
  std::size_t false_faces = 0, false_bounds = 0;
  for (const auto& [k, body] : es) {
    if (body.starts_with("ADVANCED_FACE(")) false_faces += body.ends_with(",.F.)");
    if (body.starts_with("FACE_OUTER_BOUND(")) false_bounds += body.ends_with(",.F.)");
  }
  CHECK(false_faces == against);
  CHECK(false_bounds == against);
  // The default uncertainty: 1e-9 of the diagonal (sqrt 6 for the 2 × 1 × 1 block).
  CHECK(r.uncertainty == doctest::Approx(1e-9 * std::sqrt(6.0)));
  // The same complex gives the same bytes.
  CHECK(step_of(cc) == text);
}

TEST_CASE("step: holes, cavities and open faces") {
  SUBCASE("a face with a hole: a FACE_BOUND beside its FACE_OUTER_BOUND") {
    const auto cc = cellforge::make_cell_complex(cells_fixtures::block_with_hole());
    std::size_t holes = 0;
    for (cellforge::cell_face f : cc.faces()) holes += cc.num_loops(f) - 1;
    REQUIRE(holes > 0);
    const auto es = entities(step_of(cc));
    std::size_t hole_uses = 0;
    for (cellforge::cell_volume c : cc.volumes())
      for (const auto& [f, s] : cc.volume_faces(c)) hole_uses += cc.num_loops(f) - 1;
    CHECK(count(es, "FACE_BOUND(") == hole_uses);
  }
  SUBCASE("faces in no volume: open shells, one per edge-connected set") {
    auto in = cells_fixtures::two_cubes();
    in.volumes.clear();
    cellforge::io::step_result r;
    const auto es = entities(step_of(cellforge::make_cell_complex(in), &r));
    CHECK(r.solids == 0);
    CHECK(r.open_shells == 1);
    CHECK(r.faces == 11);
    CHECK(count(es, "OPEN_SHELL(") == 1);
    CHECK(count(es, "SHELL_BASED_SURFACE_MODEL(") == 1);
    CHECK(count(es, "MANIFOLD_SURFACE_SHAPE_REPRESENTATION(") == 1);
    CHECK(count(es, "SHAPE_REPRESENTATION_RELATIONSHIP(") == 1);
  }
  SUBCASE("disjoint cubes as faces alone: two open shells") {
    auto in = cells_fixtures::disjoint_cubes();
    in.volumes.clear();
    cellforge::io::step_result r;
    step_of(cellforge::make_cell_complex(in), &r);
    CHECK(r.open_shells == 2);
  }
}

TEST_CASE("step: numbers, names and units") {
  auto in = cells_fixtures::cube();
  for (auto& p : in.points) p = p * 1e20 + glm::dvec3(-3, 0.5, 0);
  cellforge::io::step_result r;
  const std::string text = step_of(cellforge::make_cell_complex(in), &r,
                                   {.name = "it's a \\ \xC3\xBC \xF0\x9F\x98\x80",
                                    .unit = cellforge::io::step_length_unit::metre,
                                    .uncertainty = 1e-12});
  CHECK(text.find("PRODUCT('it''s a \\\\ \\X2\\00FC\\X0\\ \\X2\\D83DDE00\\X0\\',") != std::string::npos);
  CHECK(text.find("SI_UNIT($,.METRE.)") != std::string::npos);
  CHECK(text.find("LENGTH_MEASURE(1.E-12)") != std::string::npos);
  CHECK(r.uncertainty == 1e-12);
  // Every real has a decimal point and an upper-case exponent.
  CHECK(text.find("CARTESIAN_POINT('',(-3.,0.5,0.))") != std::string::npos);
  CHECK(text.find("CARTESIAN_POINT('',(1.E+20,1.E+20,1.E+20))") != std::string::npos);
  for (auto& p : in.points) p = p * 2.5e-27;
  const std::string small = step_of(cellforge::make_cell_complex(in));
  CHECK(small.find("CARTESIAN_POINT('',(2.5E-07,2.5E-07,2.5E-07))") != std::string::npos);
  CHECK(small.find("SI_UNIT(.MILLI.,.METRE.)") != std::string::npos);
  for (const auto& entry : entities(small)) {
    const std::string& body = entry.second;
    if (!body.starts_with("CARTESIAN_POINT(")) continue;
    CHECK_MESSAGE(body.find('e') == std::string::npos, body);
    const std::string list = body.substr(20, body.size() - 22);
    for (std::size_t start = 0; start < list.size();) {
      const std::size_t comma = std::min(list.find(',', start), list.size());
      CHECK_MESSAGE(list.substr(start, comma - start).find('.') != std::string::npos, body);
      start = comma + 1;
    }
  }
}

TEST_CASE("step: refused input and files") {
  auto in = cells_fixtures::cube();
  in.points[3].y = std::numeric_limits<double>::quiet_NaN();
  std::ostringstream os;
  CHECK_THROWS_WITH_AS(cellforge::io::write_step(os, cellforge::make_cell_complex(cells_fixtures::cube()),
                                                 {.uncertainty = -1}),
                       doctest::Contains("uncertainty"), cellforge::error);
  // A NaN point never reaches the writer: the complex refuses it (write_step checks again).
  CHECK_THROWS_AS(cellforge::make_cell_complex(in), cellforge::error);
  // To a file: the same bytes as to a stream; a folder in the way is an io error naming the path.
  const auto cc = cellforge::make_cell_complex(cells_fixtures::two_cubes());
  const io_test::temp_path file("two.step");
  cellforge::io::write_step(file.path, cc);
  CHECK(cellforge::io::detail::read_file(file.path) == step_of(cc));
  try {
    cellforge::io::write_step(std::filesystem::temp_directory_path(), cc);
    FAIL("wrote over a folder");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::io);
  }
}

TEST_CASE("step: faces not flat to the uncertainty are named in the diagnostics") {
  auto in = cells_fixtures::cube();
  in.points[6] += glm::dvec3(1e-6);  // out of each of the three faces meeting at corner 6
  const auto cc = cellforge::make_cell_complex(in);
  cellforge::io::step_result r;
  step_of(cc, &r);
  CHECK(r.diagnostics.size() == 3);
  for (const std::string& d : r.diagnostics) CHECK(d.find("from the face's plane") != std::string::npos);
  step_of(cc, &r, {.uncertainty = 1e-5});
  CHECK(r.diagnostics.empty());
}

TEST_CASE("step: meshes as faceted solids or open shells") {
  const auto closed = cellforge::make_mesh(fixtures::cube());
  cellforge::io::step_result r;
  std::ostringstream os;
  r = cellforge::io::write_step(os, closed);
  CHECK(r.solids == 1);
  CHECK(r.faces == 6);
  CHECK(r.open_shells == 0);
  // A face removed: an open shell of five faces, no solid.
  auto open_soup = fixtures::cube();
  open_soup.face_offsets.pop_back();
  open_soup.face_vertices.resize(open_soup.face_offsets.back());
  std::ostringstream os2;
  r = cellforge::io::write_step(os2, cellforge::make_mesh(open_soup));
  CHECK(r.solids == 0);
  CHECK(r.open_shells == 1);
  CHECK(r.faces == 5);
  // A bent quad (not flat) becomes two triangles, each on its own plane.
  cellforge::polygon_soup<glm::dvec3> bent;
  bent.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0}};
  bent.add_face({0, 1, 2, 3});
  std::ostringstream os3;
  r = cellforge::io::write_step(os3, cellforge::make_mesh(bent));
  CHECK(r.faces == 2);
  CHECK(r.planes == 2);
  CHECK(r.edges == 5);
}

TEST_CASE("step: a rounded solid, its blend a cylinder face trimmed by end circles") {
  const auto box = rounded_fixtures::rounded_box(0.25);
  std::ostringstream os;
  const auto r = cellforge::io::write_step(os, box, {.name = "rounded box"});
  CHECK(r.solids == 1);
  CHECK(r.faces == 7);
  CHECK(r.planes == 6);
  CHECK(r.cylinders == 1);
  CHECK(r.conics == 2);
  CHECK(r.edges == 15);
  CHECK(r.vertices == 10);
  CHECK(r.diagnostics.empty());
  const auto es = entities(os.str());
  CHECK(es.size() == r.entities);
  CHECK(count(es, "CYLINDRICAL_SURFACE(") == 1);
  CHECK(count(es, "CIRCLE(") == 2);
  CHECK(count(es, "ELLIPSE(") == 0);
  CHECK(count(es, "ADVANCED_FACE(") == 7);
  CHECK(count(es, "MANIFOLD_SOLID_BREP('rounded box'") == 1);
  // Every reference names an entity.
  // Plain names, not a structured binding: clang 14 cannot capture one in a doctest check.
  for (const auto& entity : es) {
    const std::size_t k = entity.first;
    const std::string& text = entity.second;
    for (std::size_t at = text.find('#'); at != std::string::npos; at = text.find('#', at + 1))
      CHECK_MESSAGE(es.count(std::stoul(text.substr(at + 1))) == 1, "#", k, " names ", text.substr(at));
  }
  // The cylinder face: same_sense .T. for a round, .F. for a fillet (the solid outside it).
  const auto cylinder_face_sense = [&](const std::map<std::size_t, std::string>& m) {
    std::size_t cyl = 0;
    for (const auto& [k, text] : m)
      if (text.starts_with("CYLINDRICAL_SURFACE(")) cyl = k;
    for (const auto& [k, text] : m)
      if (text.starts_with("ADVANCED_FACE(") &&
          text.find("),#" + std::to_string(cyl) + ",") != std::string::npos)
        return text.substr(text.size() - 4);
    return std::string("none");
  };
  CHECK(cylinder_face_sense(es) == ".T.)");
  std::ostringstream fillet;
  cellforge::io::write_step(fillet, rounded_fixtures::rounded_box(0.25, false));
  CHECK(cylinder_face_sense(entities(fillet.str())) == ".F.)");
  // An end plane tilted about y: that end's curve becomes an ellipse of semi-axes r / cos and r.
  std::ostringstream tilted;
  const auto r2 = cellforge::io::write_step(tilted, rounded_fixtures::rounded_box(0.25, true, 0.3));
  CHECK(r2.diagnostics.empty());
  const auto es2 = entities(tilted.str());
  CHECK(count(es2, "CIRCLE(") == 1);
  REQUIRE(count(es2, "ELLIPSE(") == 1);
  for (const auto& [k, text] : es2)
    if (text.starts_with("ELLIPSE(")) {
      const std::size_t comma = text.find(',', text.find('#'));
      CHECK(std::stod(text.substr(comma + 1)) == doctest::Approx(0.25 / std::cos(0.3)).epsilon(1e-12));
    }
}

TEST_CASE("step: a rounded solid's refused input and defects") {
  std::ostringstream os;
  auto nan = rounded_fixtures::rounded_box(0.25);
  nan.points[2].y = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(cellforge::io::write_step(os, nan), doctest::Contains("non-finite"), cellforge::error);
  auto along = rounded_fixtures::rounded_box(0.25);
  for (auto& e : along.edges)
    if (e.blend == 0) e.plane_normal = {0, 0, 1};  // a plane holding the axis cuts no arc
  CHECK_THROWS_WITH_AS(cellforge::io::write_step(os, along), doctest::Contains("holds its cylinder's axis"),
                       cellforge::error);
  auto missing = rounded_fixtures::rounded_box(0.25);
  missing.faces[0].loop[0].first = 99;
  CHECK_THROWS_WITH_AS(cellforge::io::write_step(os, missing), doctest::Contains("missing edge"),
                       cellforge::error);
  CHECK_THROWS_AS(cellforge::io::write_step(os, cellforge::rounded_solid{}), cellforge::error);
  // A tangent point moved off the cylinder (and its plane) is named, the file written anyway.
  auto off = rounded_fixtures::rounded_box(0.25);
  off.points[6].z -= 1e-6;
  const auto r = cellforge::io::write_step(os, off);
  REQUIRE(r.diagnostics.size() == 1);
  CHECK(r.diagnostics[0].find("from a curve or surface") != std::string::npos);
  // To a file: the same bytes as to a stream.
  const io_test::temp_path file("rounded.step");
  cellforge::io::write_step(file.path, rounded_fixtures::rounded_box(0.25));
  std::ostringstream same;
  cellforge::io::write_step(same, rounded_fixtures::rounded_box(0.25));
  CHECK(cellforge::io::detail::read_file(file.path) == same.str());
}

}  // namespace io_step_tests
