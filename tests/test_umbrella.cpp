// Every header in one translation unit (no clashing names between parts), and the main job
// end to end through the umbrella header: a wireframe in, a valid cell complex out, written
// as 3DCL text and read back.
#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <type_traits>

#include "cellforge/cellforge.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/io/cells_io.hpp"
#include "cellforge/io/curves_io.hpp"
#include "cellforge/io/edge_list.hpp"
#include "cellforge/io/mesh_io.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/io/off.hpp"
#include "cellforge/io/ply.hpp"
#include "cellforge/io/svg.hpp"
#include "cellforge/samples/wireframe_models.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace umbrella_tests {

// Every result carries the one stage_report (docs/vocabulary.md); these are the ones that came last.
static_assert(std::is_base_of_v<cellforge::stage_report, cellforge::orient_result>);
static_assert(std::is_base_of_v<cellforge::stage_report, cellforge::fold_result>);
static_assert(std::is_base_of_v<cellforge::stage_report, cellforge::edit_result>);
static_assert(std::is_base_of_v<cellforge::stage_report, cellforge::simplify_result>);
static_assert(std::is_base_of_v<cellforge::stage_report, cellforge::central_axis_result>);
static_assert(std::is_base_of_v<cellforge::stage_report, cellforge::thin_detection_result>);
static_assert(std::is_base_of_v<cellforge::stage_report, cellforge::io::svg_result>);

TEST_CASE("detail::cat joins text, views, C strings and chars in order") {
  const std::string mid = "mid";
  const std::string_view view = "view";
  const char bang = '!';
  CHECK(cellforge::detail::cat("a", mid, 'x', bang, view, std::string("tmp"), "") == "amidx!viewtmp");
  CHECK(cellforge::detail::cat().empty());
  CHECK(cellforge::detail::cat(std::string(1000, 'q'), "z").size() == 1001);
}

TEST_CASE("umbrella: the version header agrees with itself and with the CMake project") {
  const std::string composed = std::to_string(CELLFORGE_VERSION_MAJOR) + "." +
                               std::to_string(CELLFORGE_VERSION_MINOR) + "." +
                               std::to_string(CELLFORGE_VERSION_PATCH);
  CHECK(composed == CELLFORGE_VERSION_STRING);
  CHECK(composed == CELLFORGE_TEST_PROJECT_VERSION);  // CMakeLists.txt parsed version.hpp
  CHECK(cellforge::version.minor == CELLFORGE_VERSION_MINOR);
  CHECK(std::string(cellforge::version.string) == CELLFORGE_VERSION_STRING);
}

TEST_CASE("umbrella: the main job on two cubes sharing a face") {
  const cellforge::samples::sample_model model = cellforge::samples::sample_two_cubes();
  const cellforge::wireframe_result<glm::dvec3> r = cellforge::wireframe_to_cells(model.wire);
  CHECK(r.cells.num_faces() == 11);
  CHECK(r.cells.num_volumes() == 2);
  CHECK(cellforge::validate(r.cells).ok());
  std::ostringstream text;
  cellforge::io::write_3dcl(text, r.cells);
  const cellforge::cell_complex<glm::dvec3> back =
      cellforge::io::parse_3dcl<glm::dvec3>(text.str(), "two_cubes.3dcl");
  CHECK(back.num_faces() == 11);
  CHECK(back.num_volumes() == 2);
  CHECK(back.num_edges() == r.cells.num_edges());
}

}  // namespace umbrella_tests
