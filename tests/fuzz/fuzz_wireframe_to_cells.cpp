// SPDX-License-Identifier: MIT
// libFuzzer target for the whole wireframe pipeline (wireframe/wireframe_to_cells.hpp) on
// small fuzzed wireframes: the bytes are read as up to 24 points on a 4x4x4 lattice (so that
// coplanar cycles, crossings, T-junctions and overlaps are common) and edges between them.
// Every run must end in a complex that validate() accepts, in status budget with its reason, or
// in a cellforge::error — never a crash, a sanitizer report, a hang or any other exception.

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "cellforge/cells/validate.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  cellforge::wireframe<glm::dvec3> wire;
  const std::size_t n = std::min<std::size_t>(2 + data[0] % 23, (size - 1) / 2 + 1);
  std::size_t at = 1;
  for (std::size_t i = 0; i < n && at < size; ++i, ++at) {
    const std::uint8_t b = data[at];  // two bits per axis
    wire.points.push_back({double(b & 3), double((b >> 2) & 3), double((b >> 4) & 3)});
  }
  for (; at + 1 < size && wire.edges.size() < 96; at += 2)
    wire.edges.push_back({static_cast<std::uint32_t>(data[at] % wire.points.size()),
                          static_cast<std::uint32_t>(data[at + 1] % wire.points.size())});
  cellforge::wireframe_options options;  // budgets small enough that one input stays well under a second
  options.read.work_budget = 1'000'000;
  options.trace.work_budget = 2'000'000;
  options.arrangement.work_budget = 2'000'000;
  options.reduction.work_budget = 2'000'000;
  options.volume.work_budget = 2'000'000;
  try {
    const auto r = cellforge::wireframe_to_cells(wire, options);
    // An answer reported as a solid was validated and certified: both must hold, checked again
    // here from scratch. Seams are counted, not failed, as the pipeline counts them: a
    // wireframe may draw the seams of a tessellated flat face (docs/cells.md, "The certificate").
    const bool solid =
        r.status == cellforge::solid_status::solid || r.status == cellforge::solid_status::ambiguous;
    cellforge::certify_options check;
    check.seams_fail = false;
    if (solid && (!cellforge::validate(r.cells).ok() || !cellforge::certify(r.cells, wire, check).ok()))
      __builtin_trap();
    if (r.status == cellforge::solid_status::budget && (r.complete || r.status_reason.empty()))
      __builtin_trap();
  } catch (const cellforge::error&) {
    return 0;  // located, categorised refusals are expected outcomes
  }
  return 0;
}
