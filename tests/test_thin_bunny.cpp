// The thin-point search on the Stanford bunny (seed 000 §7.3, threshold 1): it must finish
// with loops that are well formed on the mesh. The bunny comes from the npm package `bunny`
// through scripts/fetch-bunny.sh (test-all runs it); the path is CELLFORGE_BUNNY_FILE, from
// CMake or, overriding it, from the environment. Without the file the test skips, except
// under CI, where a missing bunny is a failure. Timing is the benchmark's business.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>

#include <glm/glm.hpp>

#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "cellforge/io/mesh_io.hpp"
#include "cellforge/thin/thin_points.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace thin_bunny_tests {

#ifndef CELLFORGE_BUNNY_FILE
#define CELLFORGE_BUNNY_FILE ""  // e.g. compiled outside CMake (test-all's clang stage)
#endif

namespace {

std::filesystem::path bunny_path() {
  if (const char* env = std::getenv("CELLFORGE_BUNNY_FILE"); env != nullptr && *env != '\0') return env;
  return CELLFORGE_BUNNY_FILE;
}

/// True when the bunny is there; otherwise fails under CI or skips with a message.
bool have_bunny(const std::filesystem::path& path) {
  if (!path.empty() && std::filesystem::exists(path)) return true;
  const std::string what = "the Stanford bunny '" + path.string() +
                           "' is missing: run `bash scripts/fetch-bunny.sh build/data` (needs node and npm)";
  if (std::getenv("CI") != nullptr) FAIL(what);
  MESSAGE("skipped: " << what);
  return false;
}

}  // namespace

TEST_CASE("thin points: the Stanford bunny with threshold 1 finishes with well-formed loops") {
  using cellforge::edge_handle;
  using cellforge::vertex_handle;
  const std::filesystem::path path = bunny_path();
  if (!have_bunny(path)) return;

  cellforge::build_report report;
  const auto m = cellforge::io::read_mesh<glm::dvec3>(path, &report);
  REQUIRE_VALID(m);
  // bunny@1.0.1 (pinned in fetch-bunny.sh): a closed genus-0 surface, nothing split.
  CHECK(report.split_vertices.empty());
  CHECK(m.num_vertices() == 1839);
  CHECK(m.num_faces() == 3674);
  REQUIRE(m.is_closed());
  REQUIRE(test_support::euler(m) == 2);

  cellforge::thin_options options;
  options.selection_cap = 1;
  const auto r = cellforge::find_thin_points(m, options);

  CHECK(std::abs(glm::length(r.axis_direction) - 1.0) < 1e-9);
  CHECK(r.start_face < m.num_faces());
  REQUIRE(!r.cycle_lengths.empty());
  for (const double l : r.cycle_lengths) CHECK((std::isfinite(l) && l >= 0));
  REQUIRE(!r.loops.empty());

  const auto pts = m.positions();
  for (std::size_t i = 0; i < r.loops.size(); ++i) {
    const auto& loop = r.loops[i];
    INFO("loop " << i << " of " << r.loops.size() << ", cycle " << loop.cycle);
    CHECK(loop.length > 0);
    CHECK(loop.axis_position >= 0.0);
    CHECK(loop.axis_position <= 1.0);
    CHECK(loop.cycle >= 1);
    CHECK(loop.cycle <= r.cycle_lengths.size());
    if (i > 0) CHECK(loop.strength <= r.loops[i - 1].strength);  // strongest first
    // A closed chain of distinct mesh vertices joined by the listed edges, whose lengths
    // add up to the reported length.
    const std::size_t n = loop.vertices.size();
    REQUIRE(n >= 3);
    REQUIRE(loop.edges.size() == n);
    REQUIRE(loop.points.size() == n);
    CHECK(std::set<std::uint32_t>(loop.vertices.begin(), loop.vertices.end()).size() == n);
    double length = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t a = loop.vertices[k], b = loop.vertices[(k + 1) % n];
      REQUIRE(a < m.vertices_size());
      REQUIRE(b < m.vertices_size());
      const edge_handle e = m.find_edge(vertex_handle(a), vertex_handle(b));
      REQUIRE(e.is_valid());
      CHECK(e.idx() == loop.edges[k]);
      CHECK(glm::length(loop.points[k] - pts[vertex_handle(a)]) == doctest::Approx(0.0));
      length += glm::length(pts[vertex_handle(b)] - pts[vertex_handle(a)]);
    }
    CHECK(loop.length == doctest::Approx(length).epsilon(1e-9));
  }
}

}  // namespace thin_bunny_tests
