// SPDX-License-Identifier: MIT
// libFuzzer target for the OFF reader. Any input must parse or throw cellforge::error (any
// other exception, crash or sanitizer report is a bug), and whatever parses must survive a
// write and a re-read unchanged: the writer's text is the same the second time round.

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include <glm/vec3.hpp>

#include "cellforge/io/off.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  cellforge::polygon_soup<glm::dvec3> soup;
  try {
    soup = cellforge::io::parse_off<glm::dvec3>(bytes, "fuzz.off");
  } catch (const cellforge::error&) {
    return 0;  // rejecting malformed input with a located error is the expected outcome
  }
  std::ostringstream first, second;
  cellforge::io::write_off(first, soup);
  cellforge::io::write_off(second, cellforge::io::parse_off<glm::dvec3>(first.str(), "rewritten.off"));
  if (first.str() != second.str()) __builtin_trap();
  return 0;
}
