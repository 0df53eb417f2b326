// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The "3dcl" text format of cell complexes (seed 000 §4.9: vertices, edges, faces, volumes,
/// each with all its relations; docs/formats.md "3DCL text format"), written and read back exactly.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/io/detail/cells_writing.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/file_path.hpp"

namespace cellforge::io {

/// How a 3DCL text file is written.
struct cells_write_options {
  std::string comment{};  ///< written as '#' lines after the header when not empty
};

/// Writes cc as 3DCL text (docs/formats.md). O(size of cc). Throws io when the stream fails.
template <Point3 P>
void write_3dcl(std::ostream& os, const cell_complex<P>& cc, const cells_write_options& options = {});

/// Writes cc to a 3DCL text file. O(size of cc). Throws io naming the path on failure.
template <Point3 P>
void write_3dcl(const file_path& path, const cell_complex<P>& cc, const cells_write_options& options = {});

/// Parses 3DCL text into a complex with positions of type P: builds it from its coordinates,
/// edges, face loops and volumes, then checks that every relation the file lists is the one
/// the complex derives. Errors name file:line and what was expected. O(size of the text + n log n).
template <Point3 P>
cell_complex<P> parse_3dcl(std::string_view text, std::string_view name = "<memory>");

/// Reads a 3DCL text file (see parse_3dcl). O(file size + n log n).
template <Point3 P>
cell_complex<P> read_3dcl(const file_path& path);

}  // namespace cellforge::io

#include "cellforge/io/detail/cells_3dcl_impl.hpp"
