// SPDX-License-Identifier: MIT
// The wireframe → cell complex pipeline (seed 000 ch. IV) against the ground truth of the
// sample models: faces as vertex cycles, volumes as face sets, signs checked by validate().

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "cellforge/cells/validate.hpp"
#include "cellforge/wireframe/sample_models.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

using namespace cellforge;

namespace {

// Maps result vertices back to the caller's labels, the ones the ground truth uses.
std::vector<std::vector<std::vector<std::uint32_t>>> faces_in_input_labels(const wireframe_result& r) {
  std::vector<std::vector<std::vector<std::uint32_t>>> out;
  for (const auto& f : r.input.faces) {
    auto loops = f.loops;
    for (auto& l : loops)
      for (auto& v : l) v = r.input_vertex[v];
    out.push_back(std::move(loops));
  }
  return out;
}

void check_model(const sample_model& m, const wireframe_options& options = {}) {
  const std::string name = m.name;
  INFO(name);
  const wireframe_result r = wireframe_to_cells(m.wire, options);
  const auto faces = faces_in_input_labels(r);
  CHECK(faces.size() == m.faces.size());
  CHECK(r.input.volumes.size() == m.volumes.size());
  CHECK(same_faces(m.faces, faces));
  CHECK(same_volumes(m.faces, m.volumes, faces, r.input.volumes));
  CHECK(r.unforced.size() == m.unforced_faces);
  const auto v = validate(r.cells);
  const std::string why = v.message;
  INFO(why);
  CHECK(v.ok());
}

}  // namespace

TEST_CASE("pipeline: every small sample model, planar tracer") {
  for (const auto& m : all_small_samples()) check_model(m);
}
