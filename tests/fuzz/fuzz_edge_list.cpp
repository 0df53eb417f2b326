// SPDX-License-Identifier: MIT
// libFuzzer target for the edge-list reader (io/edge_list.hpp). Any input must parse or throw
// cellforge::error; whatever parses must survive a write and a re-read unchanged.

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include <glm/vec3.hpp>

#include "cellforge/io/edge_list.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The last byte picks the options, so every input shape is read both ways.
  const cellforge::io::edge_list_read_options options{
      .allow_duplicate_edges = size > 0 && (data[size - 1] & 1) != 0,
      .allow_self_loops = size > 0 && (data[size - 1] & 2) != 0};
  cellforge::wireframe<glm::dvec3> wire;
  try {
    wire = cellforge::io::parse_edge_list<glm::dvec3>(bytes, "fuzz.edges", options);
  } catch (const cellforge::error&) {
    return 0;  // a located error is the expected outcome for malformed input
  }
  std::ostringstream first, second;
  cellforge::io::write_edge_list(first, wire);
  const auto again = cellforge::io::parse_edge_list<glm::dvec3>(first.str(), "rewritten.edges", options);
  cellforge::io::write_edge_list(second, again);
  if (first.str() != second.str() || again.edges.size() != wire.edges.size()) __builtin_trap();
  return 0;
}
