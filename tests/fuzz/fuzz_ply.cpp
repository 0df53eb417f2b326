// SPDX-License-Identifier: MIT
// libFuzzer target for the PLY reader (ASCII and binary bodies). Any input must parse or
// throw cellforge::error; what parses must be written (in the format the input's length
// picks) and read back to the same bytes.

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include <glm/vec3.hpp>

#include "cellforge/io/ply.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace io = cellforge::io;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  cellforge::polygon_soup<glm::dvec3> soup;
  try {
    soup = io::parse_ply<glm::dvec3>(bytes, "fuzz.ply");
  } catch (const cellforge::error&) {
    return 0;
  }
  const io::ply_write_options options{.format = static_cast<io::ply_format>(size % 3)};
  std::ostringstream first, second;
  io::write_ply(first, soup, options);
  io::write_ply(second, io::parse_ply<glm::dvec3>(first.str(), "rewritten.ply"), options);
  if (first.str() != second.str()) __builtin_trap();
  return 0;
}
