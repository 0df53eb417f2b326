// SPDX-License-Identifier: MIT
// libFuzzer target for the SVG line-drawing reader (io/svg_drawing.hpp). Any input must parse or
// throw cellforge::error; whatever parses is validated (validate(drawing) must not crash, hang or
// throw) and pictured with io/drawing_pictures.hpp; the picture must read back (exact, without
// snapping or splitting) to the same edges whenever the drawing has no two equal junctions. The
// same input goes through the arc reader (parse_svg_arc_drawing): what it reads has valid arcs
// and its picture (arc_drawing_svg_string) reads back with as many arcs and edges.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "cellforge/io/drawing_pictures.hpp"
#include "cellforge/io/svg_drawing.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace {

void check_arcs(std::string_view bytes, const cellforge::io::svg_drawing_options& options) {
  cellforge::io::svg_arc_drawing_result<glm::dvec2> r;
  try {
    r = cellforge::io::parse_svg_arc_drawing(bytes, "fuzz.svg", options);
  } catch (const cellforge::error&) {
    return;
  }
  if (!cellforge::validate(r.drawing)) __builtin_trap();
  const std::string picture = cellforge::io::arc_drawing_svg_string(r.drawing);
  const auto back = cellforge::io::parse_svg_arc_drawing(picture, "picture.svg",
                                                         {.snap_tolerance = 0, .split_at_junctions = false});
  const auto v = cellforge::validate(r.drawing.lines, {.tolerance = 0});
  if (v.defect != cellforge::drawing_defect::coincident_junctions &&
      (back.drawing.arcs.size() != r.drawing.arcs.size() ||
       back.drawing.lines.edges.size() != r.drawing.lines.edges.size()))
    __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The last byte picks the options, so every reading sees every input shape.
  const std::uint8_t pick = size > 0 ? data[size - 1] : 0;
  cellforge::io::svg_drawing_options options;
  options.curves = (pick & 1) != 0 ? cellforge::io::svg_curves::skip : cellforge::io::svg_curves::refuse;
  options.split_at_junctions = (pick & 2) == 0;
  options.skip_annotations = (pick & 4) == 0;
  options.snap_tolerance = (pick & 24) == 0 ? 1e-3 : (pick & 24) == 8 ? 0.0 : (pick & 24) == 16 ? 0.1 : 0.45;
  check_arcs(bytes, options);
  cellforge::io::svg_drawing_result<glm::dvec2> r;
  try {
    r = cellforge::io::parse_svg_drawing(bytes, "fuzz.svg", options);
  } catch (const cellforge::error&) {
    return 0;
  }
  const auto& d = r.drawing;
  const auto v = cellforge::validate(d, {.tolerance = 0});
  if (v.defect == cellforge::drawing_defect::bad_position ||
      v.defect == cellforge::drawing_defect::self_loop ||
      v.defect == cellforge::drawing_defect::duplicate_edge ||
      v.defect == cellforge::drawing_defect::endpoint_out_of_range)
    __builtin_trap();  // the reader never makes these
  (void)cellforge::validate(d);
  std::vector<std::vector<std::uint32_t>> faces;
  if (d.points.size() >= 3) faces = {{0, 1, 2}, {}};
  const std::string picture = cellforge::io::drawing_svg_string(d, faces);
  const auto back = cellforge::io::parse_svg_drawing(picture, "picture.svg",
                                                     {.snap_tolerance = 0, .split_at_junctions = false});
  if (v.defect != cellforge::drawing_defect::coincident_junctions &&
      (back.drawing.edges.size() != d.edges.size() || back.drawing.points.size() != d.points.size()))
    __builtin_trap();
  return 0;
}
