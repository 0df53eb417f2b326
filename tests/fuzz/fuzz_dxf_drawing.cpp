// SPDX-License-Identifier: MIT
// libFuzzer target for the DXF drawing reader (io/dxf_drawing.hpp). Any input must parse or
// throw cellforge::error, within the work budget; what the arc reader reads has valid arcs, and
// what the line reader reads has no bad position, self-loop, duplicate edge or edge out of range.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include <glm/vec2.hpp>

#include "cellforge/io/dxf_drawing.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The last byte picks the options, so every reading sees every input shape.
  const std::uint8_t pick = size > 0 ? data[size - 1] : 0;
  cellforge::io::dxf_drawing_options options;
  options.curves = (pick & 1) != 0 ? cellforge::io::dxf_curves::skip : cellforge::io::dxf_curves::refuse;
  options.split_at_junctions = (pick & 2) == 0;
  options.expand_inserts = (pick & 4) == 0;
  options.skip_hidden_layers = (pick & 8) == 0;
  if ((pick & 16) != 0) options.layers = {"0", "Outline"};
  options.snap_tolerance = (pick & 32) == 0 ? 1e-3 : 0.0;
  options.max_strokes = 1 << 14;  // blocks inserted in blocks grow fast: the budget bounds them
  try {
    const auto r = cellforge::io::parse_dxf_arc_drawing(bytes, "fuzz.dxf", options);
    if (!cellforge::validate(r.drawing)) __builtin_trap();
  } catch (const cellforge::error&) {
  }
  try {
    const auto r = cellforge::io::parse_dxf_drawing(bytes, "fuzz.dxf", options);
    const auto v = cellforge::validate(r.drawing, {.tolerance = 0});
    if (v.defect == cellforge::drawing_defect::bad_position ||
        v.defect == cellforge::drawing_defect::self_loop ||
        v.defect == cellforge::drawing_defect::duplicate_edge ||
        v.defect == cellforge::drawing_defect::endpoint_out_of_range)
      __builtin_trap();  // the reader never makes these
    (void)cellforge::validate(r.drawing);
  } catch (const cellforge::error&) {
  }
  return 0;
}
