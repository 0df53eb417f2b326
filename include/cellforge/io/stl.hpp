// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// STL (stereolithography) reading and writing for polygon soups: ASCII and binary. Reading
/// welds the corners STL repeats into shared vertices (exactly, within a tolerance, or not at
/// all) and keeps each solid's name with its faces; writing triangulates polygons by ear
/// clipping and computes the facet normals. See docs/formats.md.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/ear_clipping.hpp"
#include "cellforge/core/detail/edge_table.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/io/detail/numbers.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"

namespace cellforge::io {

/// How an STL file stores its facets.
enum class stl_encoding : std::uint8_t { ascii, binary };

/// What reading does with a facet two of whose corners are one vertex (after welding).
enum class stl_degenerate : std::uint8_t {
  drop,    ///< leave it out of the soup and count it in stl_data::degenerate_facets
  keep,    ///< keep it as a face that uses a vertex twice (and count it)
  refuse,  ///< throw an io error naming the facet
};

/// How STL files are read.
struct stl_read_options {
  /// Merge the corners STL repeats for every facet into shared vertices; false gives every
  /// facet three points of its own.
  bool weld = true;
  /// 0: corners are one vertex when their coordinates are equal (-0 equals +0). Above 0: a
  /// corner at most this far (absolute distance) from an earlier vertex becomes the first
  /// such vertex; the vertex keeps its first corner's coordinates.
  double weld_tolerance = 0;
  /// Facets with two corners on one vertex (or, without welding, at one place).
  stl_degenerate degenerate = stl_degenerate::drop;
};

/// How STL files are written.
struct stl_write_options {
  bool binary = true;                    ///< little-endian float32 facets; false writes ASCII
  std::string solid_name = "cellforge";  ///< ASCII `solid NAME`; binary: the 80-byte header
  ear_clip_options triangulation{};      ///< how faces of more than 3 vertices are triangulated
};

/// One solid of an STL file: its name and the range of soup faces that came from it.
struct stl_solid {
  /// ASCII: the text after `solid` on its line, blanks trimmed. Binary: the 80-byte header,
  /// trailing NUL bytes and spaces removed.
  std::string name;
  /// ASCII: the text after `endsolid` (often empty, sometimes another name: accepted as is).
  std::string end_name;
  std::uint32_t first_face = 0;  ///< faces [first_face, first_face + num_faces) of the soup
  std::uint32_t num_faces = 0;

  /// True when `endsolid` names a different solid than `solid` did. O(name length).
  bool name_mismatch() const noexcept { return !end_name.empty() && end_name != name; }
};

/// What reading an STL file gives: the welded triangles, the solids and the counts. Facet
/// normals are checked (ASCII: three numbers) but not kept; writers recompute them.
template <Point3 P>
struct stl_data {
  polygon_soup<P> soup;  ///< triangles; points in the order of their first corner
  stl_encoding encoding = stl_encoding::ascii;
  std::vector<stl_solid> solids;           ///< in file order; a binary file has one
  std::uint64_t facets_read = 0;           ///< facets in the file, degenerate ones included
  std::uint64_t vertices_before_weld = 0;  ///< corners read: 3 per facet
  std::uint64_t vertices_after_weld = 0;   ///< the soup's points
  std::uint64_t degenerate_facets = 0;     ///< facets with a repeated vertex (dropped or kept)
  std::uint64_t mismatched_end_names = 0;  ///< solids whose `endsolid` names another solid
};

/// Parses STL bytes held in memory (ASCII or binary: binary when the size is 84 + 50 × the
/// header's facet count, else ASCII when the text starts with `solid`); `name` is used in
/// error messages. Throws an io error with file:line (ASCII) or byte offset (binary), or naming
/// the file when degenerate facets are dropped and they were all there was. O(size).
template <Point3 P>
stl_data<P> parse_stl(std::string_view bytes, std::string_view name = "<memory>",
                      const stl_read_options& options = {});

/// Reads an STL file. Throws an io error naming the path when it cannot be read, or with the
/// place when it is malformed; a binary file beyond the 32-bit limit is refused unread. O(file size).
template <Point3 P>
stl_data<P> read_stl(const file_path& path, const stl_read_options& options = {});

/// Writes a soup as STL, binary (float32) by default or ASCII (shortest round-trip text);
/// polygons ear-clipped, normals from the corners. Throws invalid_input on NaN/Inf or (binary)
/// beyond-float32 corners, bad indices or names, polygons ear clipping refuses. O(size).
template <Point3 P>
void write_stl(std::ostream& os, const polygon_soup<P>& soup, const stl_write_options& options = {});

/// Writes a soup to an STL file (see the stream overload). Throws an io error naming the
/// path when it cannot be written. O(size).
template <Point3 P>
void write_stl(const file_path& path, const polygon_soup<P>& soup, const stl_write_options& options = {});

}  // namespace cellforge::io

#include "cellforge/io/detail/stl_impl.hpp"
