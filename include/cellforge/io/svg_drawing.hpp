// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Line drawings from SVG, as a person draws them in Inkscape: the straight strokes of
/// `<line>`, `<polyline>`, `<polygon>`, `<rect>` and `<path>` (M/L/H/V/Z, absolute and relative)
/// inside any nesting of groups with transforms, snapped into junctions; parse_svg_arc_drawing
/// also reads the elliptical arcs of `A` path commands (rounds and fillets) into an arc_drawing.
/// See docs/formats.md ("SVG line drawings") and docs/sketch.md ("Input: line drawings").

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/io/detail/arc_io.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/stroke_snapping.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/sketch/detail/drawing_grid.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge::io {

/// What the SVG reader does with curves (circles, ellipses, rounded rects, C/S/Q/T/A path
/// commands; parse_svg_arc_drawing reads A itself and applies this to the others).
enum class svg_curves : std::uint8_t {
  refuse,  ///< a located io error naming what to do instead
  skip,    ///< left out, counted in svg_drawing_result::skipped_curves (a path goes on from the curve's end)
};

/// How SVG line drawings are read.
struct svg_drawing_options {
  /// Stroke ends closer than this fraction of the drawing's bounding-box diagonal are one
  /// junction (clusters of close pairs, placed at their mean); a junction this close to the
  /// interior of a stroke splits it. 0: only equal points are one junction.
  double snap_tolerance = 1e-3;
  svg_curves curves = svg_curves::refuse;
  /// Split a stroke where a junction (another stroke's end) lies on its interior.
  bool split_at_junctions = true;
  /// Skip elements with a `data-cellforge` attribute other than "edges": the faces, junction
  /// dots and labels that write_drawing_svg adds to the edges.
  bool skip_annotations = true;
  /// Skip elements with display="none" (or `display:none` in their style): hidden Inkscape layers.
  bool skip_hidden = true;
};

/// What reading an SVG drawing did: counts and diagnostics (of svg_drawing_result and
/// svg_arc_drawing_result).
struct svg_reading_counts : stage_report {
  std::size_t elements = 0;             ///< stroke elements read (line, polyline, polygon, rect, path)
  std::size_t segments = 0;             ///< straight segments in them, before snapping
  std::size_t snapped = 0;              ///< segment ends moved by snapping onto a junction
  std::size_t dropped_zero_length = 0;  ///< segments whose ends snapped to one junction
  std::size_t merged_duplicates = 0;    ///< edges drawn twice (after splitting), kept once
  std::size_t split_at_junctions = 0;   ///< junctions that split a stroke's interior
  std::size_t skipped_curves = 0;       ///< curves left out (svg_curves::skip)
  std::size_t skipped_elements = 0;     ///< elements not read: defs, text, metadata, hidden, annotations, ...
  // diagnostics (stage_report): what was left out or looks doubtful, with lines
};

/// A line drawing read from SVG and what the reading did. The drawing is y-up: a junction's y
/// is minus the SVG y (after transforms). Junctions are numbered in order of first appearance.
template <Point2 P2>
struct svg_drawing_result : svg_reading_counts {
  line_drawing<P2> drawing;
};

/// A drawing with arcs read from SVG (parse_svg_arc_drawing) and what the reading did; y-up as
/// svg_drawing_result's.
template <Point2 P2>
struct svg_arc_drawing_result : svg_reading_counts {
  arc_drawing<P2> drawing;
  std::size_t arcs = 0;  ///< arcs read (A path commands), before dropping those whose ends snapped together
};

/// Parses SVG text held in memory into a line drawing; `name` is used in error messages. Each
/// straight stroke segment becomes an edge; stroke ends within the snap tolerance are one
/// junction; a junction on a stroke's interior splits it; y is flipped (drawings are y-up).
/// Throws an io error with file and line on malformed XML, path data, transforms or refused
/// curves. O(size + S log S + K), S segments, K the pairs sharing a cell of the snapping grids.
template <Point2 P2 = glm::dvec2>
svg_drawing_result<P2> parse_svg_drawing(std::string_view text, std::string_view name = "<memory>",
                                         const svg_drawing_options& options = {});

/// Parses SVG text into a drawing with arcs: as parse_svg_drawing, and each `A`/`a` path command
/// an elliptical arc (its ellipse carried exactly through the transforms and the y flip, which
/// reverses its sense), its ends snapped into junctions with the stroke ends. `<circle>`,
/// `<ellipse>` (closed curves, no rounds), rounded rects and C/S/Q/T are refused or skipped as
/// options.curves says. O(size + S log S + K).
template <Point2 P2 = glm::dvec2>
svg_arc_drawing_result<P2> parse_svg_arc_drawing(std::string_view text, std::string_view name = "<memory>",
                                                 const svg_drawing_options& options = {});

/// Reads an SVG drawing with arcs (see parse_svg_arc_drawing); io errors name the path, or the
/// file and line when it is malformed. O(file size + S log S + K).
template <Point2 P2 = glm::dvec2>
svg_arc_drawing_result<P2> read_svg_arc_drawing(const file_path& path,
                                                const svg_drawing_options& options = {});

/// Reads an SVG line drawing (see parse_svg_drawing). Throws an io error naming the path when
/// it cannot be read, or with file and line when it is malformed. O(file size + S log S + K).
template <Point2 P2 = glm::dvec2>
svg_drawing_result<P2> read_svg_drawing(const file_path& path, const svg_drawing_options& options = {});

}  // namespace cellforge::io

#include "cellforge/io/detail/svg_drawing_impl.hpp"
