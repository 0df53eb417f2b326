// SPDX-License-Identifier: MIT
// libFuzzer target for the OBJ reader (strict and lenient). Any input must parse or throw
// cellforge::error; what parses (faces, lines and groups) must come back unchanged after a
// write and a re-read.

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include <glm/vec3.hpp>

#include "cellforge/io/obj.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The last byte picks the options, so both reading modes see every input shape.
  const bool strict = size > 0 && (data[size - 1] & 1) != 0;
  const bool repeats = size > 0 && (data[size - 1] & 2) != 0;
  const cellforge::io::obj_read_options options{.allow_repeated_vertices = repeats, .strict = strict};
  cellforge::io::obj_data<glm::dvec3> obj;
  try {
    obj = cellforge::io::parse_obj<glm::dvec3>(bytes, "fuzz.obj", options);
  } catch (const cellforge::error&) {
    return 0;
  }
  std::ostringstream first, second;
  cellforge::io::write_obj(first, obj);
  const auto again = cellforge::io::parse_obj<glm::dvec3>(first.str(), "rewritten.obj", options);
  cellforge::io::write_obj(second, again);
  if (first.str() != second.str() || again.skipped_statements != 0) __builtin_trap();
  return 0;
}
