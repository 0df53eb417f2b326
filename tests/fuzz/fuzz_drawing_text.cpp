// SPDX-License-Identifier: MIT
// libFuzzer target for the line-drawing text reader (io/drawing_text.hpp). Any input must parse
// or throw cellforge::error; whatever parses is validated (validate(drawing) must not crash, hang
// or throw), must be writable, and must come back bit for bit after a write and a re-read. The
// same input goes through the arc reader (parse_arc_drawing_text), with the same demands.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include <glm/vec2.hpp>

#include "cellforge/io/drawing_text.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace {

/// The arc reader: what parses is valid, writable, and comes back bit for bit after a write.
void check_arcs(std::string_view bytes) {
  cellforge::arc_drawing<glm::dvec2> d;
  try {
    d = cellforge::io::parse_arc_drawing_text(bytes, "fuzz.txt");
  } catch (const cellforge::error&) {
    return;
  }
  if (!cellforge::validate(d)) __builtin_trap();
  const std::string text = cellforge::io::arc_drawing_text_string(d);
  const auto again = cellforge::io::parse_arc_drawing_text(text, "rewritten.txt");
  if (again.lines.edges != d.lines.edges || again.lines.points.size() != d.lines.points.size() ||
      again.arcs.size() != d.arcs.size())
    __builtin_trap();
  if (!d.lines.points.empty() && std::memcmp(again.lines.points.data(), d.lines.points.data(),
                                             d.lines.points.size() * sizeof(glm::dvec2)) != 0)
    __builtin_trap();
  for (std::size_t k = 0; k < d.arcs.size(); ++k) {
    const auto &a = d.arcs[k].curve, &b = again.arcs[k].curve;
    const double x[] = {a.centre.x, a.centre.y, a.rx, a.ry, a.rotation, a.start, a.sweep};
    const double y[] = {b.centre.x, b.centre.y, b.rx, b.ry, b.rotation, b.start, b.sweep};
    if (d.arcs[k].ends != again.arcs[k].ends || std::memcmp(x, y, sizeof x) != 0) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  check_arcs(bytes);
  cellforge::line_drawing<glm::dvec2> d;
  try {
    d = cellforge::io::parse_drawing_text(bytes, "fuzz.txt");
  } catch (const cellforge::error&) {
    return 0;
  }
  // The last byte picks the tolerance, so coincidence and overlap tests see coarse and fine ones.
  const double tolerance = size > 0 && (data[size - 1] & 1) != 0 ? 0.05 : 1e-9;
  (void)cellforge::validate(d, {.tolerance = tolerance});
  const std::string text =
      cellforge::io::drawing_text_string(d);  // throws (a crash) if the reader let through junk
  const auto again = cellforge::io::parse_drawing_text(text, "rewritten.txt");
  if (again.edges != d.edges || again.points.size() != d.points.size()) __builtin_trap();
  if (!d.points.empty() &&
      std::memcmp(again.points.data(), d.points.data(), d.points.size() * sizeof(glm::dvec2)) != 0)
    __builtin_trap();
  return 0;
}
