// SPDX-License-Identifier: MIT
// libFuzzer target for the line-drawing text reader (io/drawing_text.hpp). Any input must parse
// or throw cellforge::error; whatever parses is validated (validate_drawing must not crash, hang
// or throw), must be writable, and must come back bit for bit after a write and a re-read.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include <glm/vec2.hpp>

#include "cellforge/io/drawing_text.hpp"
#include "cellforge/sketch/line_drawing.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  cellforge::line_drawing<glm::dvec2> d;
  try {
    d = cellforge::io::parse_drawing_text(bytes, "fuzz.txt");
  } catch (const cellforge::error&) {
    return 0;
  }
  // The last byte picks the tolerance, so coincidence and overlap tests see coarse and fine ones.
  const double tolerance = size > 0 && (data[size - 1] & 1) != 0 ? 0.05 : 1e-9;
  (void)cellforge::validate_drawing(d, {.tolerance = tolerance});
  const std::string text =
      cellforge::io::drawing_text_string(d);  // throws (a crash) if the reader let through junk
  const auto again = cellforge::io::parse_drawing_text(text, "rewritten.txt");
  if (again.edges != d.edges || again.points.size() != d.points.size()) __builtin_trap();
  if (!d.points.empty() &&
      std::memcmp(again.points.data(), d.points.data(), d.points.size() * sizeof(glm::dvec2)) != 0)
    __builtin_trap();
  return 0;
}
