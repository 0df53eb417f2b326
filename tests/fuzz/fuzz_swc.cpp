// SPDX-License-Identifier: MIT
// libFuzzer target for the SWC reader (io/swc.hpp). Any input must parse or throw
// cellforge::error; whatever parses must be writable (the reader only accepts a forest plus
// LINK edges, no self-loop or repeated edge, positive radii) and come back unchanged after a
// write and a re-read.

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "cellforge/io/swc.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The last byte picks the soma option, so both readings see every input shape.
  const bool collapse = size > 0 && (data[size - 1] & 1) != 0;
  cellforge::io::swc_result<glm::dvec3> swc;
  try {
    swc = cellforge::io::parse_swc<glm::dvec3>(bytes, "fuzz.swc", {.collapse_three_point_soma = collapse});
  } catch (const cellforge::error&) {
    return 0;
  }
  (void)cellforge::validate(swc.skeleton);
  std::ostringstream first, second;
  cellforge::io::write_swc(first,
                           swc);  // throws (uncaught: a crash) if the reader let through what SWC cannot hold
  // Re-read as written: collapsing again could fold a soma that the first collapse exposed.
  const auto again = cellforge::io::parse_swc<glm::dvec3>(first.str(), "rewritten.swc",
                                                          {.collapse_three_point_soma = false});
  cellforge::io::write_swc(second, again);
  if (first.str() != second.str() || again.skeleton.points.size() != swc.skeleton.points.size())
    __builtin_trap();
  return 0;
}
