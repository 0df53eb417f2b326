// SPDX-License-Identifier: MIT
// libFuzzer target for the tube mesher (tubes/tube_mesh.hpp) on SWC input (io/swc.hpp). A skeleton
// that parses must mesh or throw cellforge::error; a mesh must be a valid closed surface, and
// a defect the checks see (folds, intersecting pairs, a genus other than the cycle rank) must be
// said in the result's diagnostics, never left silent. At most 300 samples, so a run stays fast.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "cellforge/halfedge/validate.hpp"
#include "cellforge/io/swc.hpp"
#include "cellforge/tubes/tube_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The last byte picks the sides (3-10) and whether the exact check (and so its repair) runs.
  const std::uint8_t last = size > 0 ? data[size - 1] : 0;
  cellforge::io::swc_result<glm::dvec3> swc;
  try {
    swc = cellforge::io::parse_swc<glm::dvec3>(bytes, "fuzz.swc", {});
  } catch (const cellforge::error&) {
    return 0;
  }
  if (swc.skeleton.points.size() > 300) return 0;
  cellforge::tubes_options options;
  options.sides = 3 + (last & 7u);
  options.check_self_intersections = (last & 8u) != 0;
  options.node_ids = swc.ids;
  try {
    const auto r = cellforge::make_tubes(swc.skeleton, options);
    if (!cellforge::validate(r.mesh).ok() || !r.mesh.is_closed()) __builtin_trap();
    const auto said = [&](std::string_view what) {
      for (const std::string& d : r.diagnostics)
        if (d.find(what) != std::string::npos) return true;
      return false;
    };
    if (r.folded_edges > 0 && !said("edges fold")) __builtin_trap();
    if (r.self_intersecting_face_pairs > 0 && !said("face pairs intersect")) __builtin_trap();
    if (r.genus != r.cycle_rank && !said("differs from the skeleton's cycle rank")) __builtin_trap();
  } catch (const cellforge::error&) {
    return 0;
  }
  return 0;
}
