// SPDX-License-Identifier: MIT
// libFuzzer target for the curve file and the polyline file readers (io/curves_io.hpp). Any
// input must parse or throw cellforge::error (any other exception, crash or sanitizer report
// is a bug), and whatever parses must survive a write and a re-read: the writer's text is the
// same the second time round.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "cellforge/io/curves_io.hpp"

namespace {

// Parses with `parse`, writes with `write`, re-parses and re-writes; traps if the texts differ.
template <class Parse, class Write>
void round_trip(std::string_view bytes, Parse&& parse, Write&& write) {
  std::string first;
  try {
    first = write(parse(bytes, "fuzz.txt"));
  } catch (const cellforge::error&) {
    return;  // rejecting malformed input with a located error is the expected outcome
  }
  if (write(parse(first, "rewritten.txt")) != first) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  round_trip(
      bytes,
      [](std::string_view t, std::string_view n) {
        return cellforge::io::parse_curve_file<glm::dvec3>(t, n);
      },
      [](const auto& curves) { return cellforge::io::curve_file_text(curves); });
  round_trip(
      bytes,
      [](std::string_view t, std::string_view n) {
        return cellforge::io::parse_polyline_file<glm::dvec3>(t, n);
      },
      [](const auto& lines) { return cellforge::io::polyline_file_text(lines); });
  return 0;
}
