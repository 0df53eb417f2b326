// SPDX-License-Identifier: MIT
// The deprecated spellings of the names renamed for one vocabulary (docs/vocabulary.md,
// CHANGELOG.md) still compile until 0.8 and mean the new names; the old functions give the new
// overloads' answers. This file alone is built with deprecation warnings allowed; the
// compile-fail test `deprecated_name` proves that they are warnings everywhere else.
#include <cstdio>
#include <type_traits>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/loop_subdivision.hpp"
#include "cellforge/algorithms/self_intersections.hpp"
#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/cells/validate.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "cellforge/io/drawing_svg.hpp"  // the old path of io/drawing_pictures.hpp
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/face_finder.hpp"
#include "cellforge/sketch/line_drawing.hpp"
#include "cellforge/thin/loop_detection.hpp"
#include "cellforge/tubes/skeleton.hpp"
#include "cellforge/tubes/tube_mesh.hpp"
#include "cellforge/wireframe/read_vertices.hpp"
#include "cellforge/wireframe/unique_circuits.hpp"

namespace cf = cellforge;

static_assert(std::is_same_v<cf::validation_result, cf::mesh_validation>);
static_assert(std::is_same_v<cf::cells_validation_result, cf::cells_validation>);
static_assert(std::is_same_v<cf::face_check, cf::face_validation>);
static_assert(std::is_same_v<cf::drawing_check_options, cf::drawing_validation_options>);
static_assert(std::is_same_v<cf::read_options, cf::wireframe_read_options>);
static_assert(std::is_same_v<cf::read_result, cf::wireframe_read_result>);
static_assert(std::is_same_v<cf::unique_options, cf::unique_circuits_options>);
static_assert(std::is_same_v<cf::unique_result, cf::unique_circuits_result>);
static_assert(std::is_same_v<cf::loop_options, cf::loop_subdivision_options>);
static_assert(std::is_same_v<cf::loop_result, cf::loop_subdivision_result>);
static_assert(std::is_same_v<cf::detection_options, cf::thin_detection_options>);
static_assert(std::is_same_v<cf::detection_result, cf::thin_detection_result>);
static_assert(std::is_same_v<cf::tube_options, cf::tubes_options>);
// Results derive from the one stage_report.
static_assert(std::is_base_of_v<cf::stage_report, cf::tubes_result<glm::dvec3>>);
static_assert(std::is_base_of_v<cf::stage_report, cf::loop_subdivision_result>);
static_assert(std::is_base_of_v<cf::stage_report, cf::wireframe_read_result>);
// One work_budget: 0 is unlimited, automatic is distinct from it, and plain numbers still work.
static_assert(cf::work_budget{}.is_unlimited() && cf::work_budget{0}.limit(7) == ~std::uint64_t{0});
static_assert(cf::work_budget{cf::work_budget::automatic}.limit(7) == 7 && cf::work_budget{5}.limit(7) == 5);

int main() {
  int failures = 0;
  const auto expect = [&](bool ok, const char* what) {
    if (!ok) {
      std::fprintf(stderr, "deprecated_names: %s\n", what);
      ++failures;
    }
  };
  // A skeleton whose one edge joins a node to itself.
  cf::skeleton<glm::dvec3> s;
  s.points = {{0, 0, 0}, {1, 0, 0}};
  s.radii = {0.1, 0.1};
  s.edges = {{0, 0}};
  const cf::skeleton_validation vs = cf::validate_skeleton(s), ns = cf::validate(s);
  expect(!vs.ok() && vs.defect == ns.defect && vs.message == ns.message, "validate_skeleton");
  // A drawing with a stroke from a corner to itself, and an arc drawing with none.
  cf::line_drawing<glm::dvec2> d;
  d.points = {{0, 0}, {1, 0}};
  d.edges = {{0, 1}, {1, 1}};
  const cf::drawing_check_options options{};
  const cf::drawing_validation vd = cf::validate_drawing(d, options), nd = cf::validate(d, options);
  expect(!vd.ok() && vd.defect == nd.defect && vd.message == nd.message, "validate_drawing");
  cf::arc_drawing<glm::dvec2> a;
  a.lines = d;
  a.lines.edges = {{0, 1}};
  expect(cf::validate_arcs(a).ok() == cf::validate(a).ok(), "validate_arcs");
  // The old header path names the new header's writer.
  expect(cf::io::drawing_svg_string(a.lines).find("<svg") != std::string::npos, "io/drawing_svg.hpp");
  // The deprecated data members: still honoured and filled.
  const cf::surface_mesh<glm::dvec3> ico = cf::make_mesh(cf::icosahedron<glm::dvec3>());
  cf::self_intersection_options si;
  expect(si.max_candidate_pairs == 0 && !si.throw_on_budget, "self_intersection_options' old defaults");
  const cf::self_intersection_result sr = cf::self_intersections(ico, si);
  expect(sr.time_ms == sr.milliseconds && sr.complete, "self_intersection_result::time_ms");
  si.max_candidate_pairs = 1;
  si.throw_on_budget = true;
  bool thrown = false;
  try {
    (void)cf::self_intersections(ico, si);
  } catch (const cf::error& e) {
    thrown = e.category() == cf::error_category::budget;
  }
  expect(thrown, "max_candidate_pairs and throw_on_budget");
  expect(cf::tubes_result<glm::dvec3>{}.total_ms == 0, "tubes_result::total_ms");
  if (failures == 0)
    std::printf("deprecated_names: 13 old type names, 3 old functions, 1 old header, 4 old members: ok\n");
  return failures == 0 ? 0 : 1;
}
