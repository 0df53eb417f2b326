// SPDX-License-Identifier: MIT
// libFuzzer target for the 3DCL cell-list reader (io/cells_3dcl.hpp). Any input must parse or
// throw cellforge::error; whatever parses is a complex that validate() accepts, and it must
// survive a write and a re-read unchanged.

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include <glm/vec3.hpp>

#include "cellforge/cells/validate.hpp"
#include "cellforge/io/cells_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  cellforge::cell_complex<glm::dvec3> cc;
  try {
    cc = cellforge::io::parse_3dcl<glm::dvec3>(bytes, "fuzz.3dcl");
  } catch (const cellforge::error&) {
    return 0;  // a located error is the expected outcome for malformed input
  }
  (void)cellforge::validate(cc);  // must not crash; the reader checks relations, not geometry
  std::ostringstream first, second;
  cellforge::io::write_3dcl(first, cc);
  cellforge::io::write_3dcl(second, cellforge::io::parse_3dcl<glm::dvec3>(first.str(), "rewritten.3dcl"));
  if (first.str() != second.str()) __builtin_trap();
  return 0;
}
