// SPDX-License-Identifier: MIT
// libFuzzer target for the STL reader (ASCII and binary). Any input must parse or throw
// cellforge::error; what parses must survive a write and a re-read unchanged in both
// encodings: read as float points (what binary stores) the second binary and ASCII files are
// the same bytes as the first, and read as double points so is the second ASCII text.

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "cellforge/io/stl.hpp"

namespace {

namespace io = cellforge::io;

/// Writes the soup with the solid's name when the encoding can hold it, else the default one.
template <class P>
std::string write(const io::stl_data<P>& d, bool binary) {
  io::stl_write_options o{.binary = binary};
  if (!d.solids.empty()) o.solid_name = d.solids.front().name;
  std::ostringstream os;
  try {
    io::write_stl(os, d.soup, o);
  } catch (const cellforge::error& e) {
    if (e.category() != cellforge::error_category::invalid_input) throw;
    o.solid_name = "fuzz";  // a name this encoding cannot carry (a line break, too long, ...)
    os.str({});
    io::write_stl(os, d.soup, o);
  }
  return os.str();
}

/// Write, re-read, write: the two files must be identical, and the names must come back.
template <class P>
void round_trip(const io::stl_data<P>& d, bool binary) {
  const std::string first = write(d, binary);
  const io::stl_data<P> back = io::parse_stl<P>(first, "rewritten.stl");
  if (back.soup.num_faces() != d.soup.num_faces() || back.soup.num_points() != d.soup.num_points())
    __builtin_trap();
  if (write(back, binary) != first) __builtin_trap();
}

/// The input parsed as points of type P, or false when it is rejected (with a located error,
/// the expected outcome for malformed input).
template <class P>
bool parse(std::string_view bytes, const io::stl_read_options& options, io::stl_data<P>& out) {
  try {
    out = io::parse_stl<P>(bytes, "fuzz.stl", options);
    return true;
  } catch (const cellforge::error&) {
    return false;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const io::stl_read_options options{.weld_tolerance = size % 4 == 3 ? 0.5 : 0.0};
  // Outside the parse, any exception escapes to libFuzzer: a writer or re-read failure is a bug.
  if (io::stl_data<glm::vec3> f; parse(bytes, options, f)) {
    round_trip(f, true);
    round_trip(f, false);
  }
  if (io::stl_data<glm::dvec3> d; parse(bytes, options, d)) round_trip(d, false);
  return 0;
}
