// SPDX-License-Identifier: MIT
// libFuzzer target for the OBJ skeleton reader (io/skeleton_obj.hpp), with and without a
// uniform radius. Any input must parse or throw cellforge::error; whatever parses must be
// writable (the reader rejects what the writer refuses) and come back unchanged after a write
// and a re-read.

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include <glm/vec3.hpp>

#include "cellforge/io/skeleton_obj.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The last byte picks the options, so every reading mode sees every input shape.
  const bool strict = size > 0 && (data[size - 1] & 1) != 0;
  const double uniform = size > 0 && (data[size - 1] & 2) != 0 ? 0.5 : 0.0;
  cellforge::io::skeleton_obj_data<glm::dvec3> obj;
  try {
    obj = cellforge::io::parse_skeleton_obj<glm::dvec3>(bytes, "fuzz.obj",
                                                        {.uniform_radius = uniform, .strict = strict});
  } catch (const cellforge::error&) {
    return 0;
  }
  (void)cellforge::validate(obj.skeleton);
  std::ostringstream first, second;
  cellforge::io::write_skeleton_obj(first, obj.skeleton);  // an uncaught refusal is a crash: a bug
  const auto again =
      cellforge::io::parse_skeleton_obj<glm::dvec3>(first.str(), "rewritten.obj", {.strict = true});
  cellforge::io::write_skeleton_obj(second, again.skeleton);
  if (first.str() != second.str() || again.uniform_radius_nodes != 0) __builtin_trap();
  return 0;
}
