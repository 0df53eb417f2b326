// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Line drawings from ASCII DXF (R12 to current), as CAD programs write them: LINE, LWPOLYLINE
/// (bulges are arcs), POLYLINE/VERTEX/SEQEND, ARC, CIRCLE and ELLIPSE, on chosen layers, with
/// INSERTs of blocks expanded; stroke ends snapped into junctions as the SVG reader does. The
/// reader is our own (the DXF libraries in Debian are GPL). See docs/formats.md ("DXF drawings").

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/io/detail/numbers.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/stroke_snapping.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge::io {

/// What the DXF line reader (parse_dxf_drawing) does with curves: ARC, CIRCLE, ELLIPSE and
/// bulged polyline segments. parse_dxf_arc_drawing reads them all as elliptical arcs.
enum class dxf_curves : std::uint8_t {
  refuse,  ///< a located io error naming what to do instead
  skip,    ///< left out, counted in dxf_reading_counts::skipped_curves
};

/// How DXF drawings are read.
struct dxf_drawing_options {
  /// Stroke ends closer than this fraction of the drawing's bounding-box diagonal are one
  /// junction; a junction this close to a line's interior splits it (as svg_drawing_options).
  double snap_tolerance = 1e-3;
  dxf_curves curves = dxf_curves::refuse;
  /// Split a line where a junction (another stroke's end) lies on its interior.
  bool split_at_junctions = true;
  /// Layers to read (names compared ignoring ASCII case); empty: every layer. An entity of a
  /// block on layer "0" takes the layer of the INSERT that places it (DXF's rule).
  std::vector<std::string> layers{};
  /// Leave out entities on layers that are off (negative colour) or frozen in the LAYER table.
  bool skip_hidden_layers = true;
  /// INSERT (block references) expanded with their insertion point, scales, rotation and
  /// MINSERT arrays; false: an INSERT is a located io error.
  bool expand_inserts = true;
  /// Work budget: strokes (segments and arcs, after expanding blocks) before an io error.
  std::size_t max_strokes = std::size_t{1} << 24;
};

/// What reading a DXF drawing did: counts and diagnostics.
struct dxf_reading_counts : stage_report {
  std::string version;       ///< $ACADVER of the HEADER (AC1009 = R12, AC1015 = R2000, ...), or empty
  std::size_t entities = 0;  ///< drawing entities read (LINE, LWPOLYLINE, ..., each time a block places it)
  std::size_t segments = 0;  ///< straight segments in them, before snapping
  std::size_t inserts = 0;   ///< block references expanded (each MINSERT copy counts)
  std::size_t snapped = 0;   ///< segment ends moved by snapping onto a junction
  std::size_t dropped_zero_length = 0;  ///< strokes whose ends snapped to one junction
  std::size_t merged_duplicates = 0;    ///< edges drawn twice (after splitting), kept once
  std::size_t split_at_junctions = 0;   ///< junctions that split a line's interior
  std::size_t skipped_curves = 0;       ///< curves left out (dxf_curves::skip)
  std::size_t skipped_entities = 0;     ///< entities not read: TEXT, HATCH, DIMENSION, SPLINE, 3D ones, ...
  std::size_t skipped_by_layer = 0;     ///< entities on layers not chosen, off or frozen
  std::vector<std::string> layers;      ///< layers of the entities met, in order of first appearance
  // diagnostics (stage_report): what was left out or looks doubtful, with lines
};

/// A line drawing read from DXF (y up, as DXF's world coordinates) and what the reading did.
template <Point2 P2>
struct dxf_drawing_result : dxf_reading_counts {
  line_drawing<P2> drawing;
};

/// A drawing with arcs read from DXF (parse_dxf_arc_drawing) and what the reading did.
template <Point2 P2>
struct dxf_arc_drawing_result : dxf_reading_counts {
  arc_drawing<P2> drawing;
  std::size_t arcs = 0;  ///< arcs read (a circle or full ellipse is two), before dropping closed ones
};

/// Parses ASCII DXF text held in memory into a line drawing; `name` is used in error messages.
/// LINEs and polyline segments become edges (ends snapped into junctions, lines split at
/// junctions on them, as parse_svg_drawing); curves are refused or skipped as options.curves
/// says. Throws an io error with file and line on malformed DXF. O(size + S log S + K).
template <Point2 P2 = glm::dvec2>
dxf_drawing_result<P2> parse_dxf_drawing(std::string_view text, std::string_view name = "<memory>",
                                         const dxf_drawing_options& options = {});

/// Parses ASCII DXF text into a drawing with arcs: as parse_dxf_drawing, and ARCs, ELLIPSE arcs
/// and bulged polyline segments as elliptical arcs between snapped junctions (a CIRCLE or full
/// ELLIPSE as two half arcs). O(size + S log S + K).
template <Point2 P2 = glm::dvec2>
dxf_arc_drawing_result<P2> parse_dxf_arc_drawing(std::string_view text, std::string_view name = "<memory>",
                                                 const dxf_drawing_options& options = {});

/// Reads an ASCII DXF line drawing (see parse_dxf_drawing). Throws an io error naming the path
/// when it cannot be read, or with file and line when it is malformed. O(file size + S log S + K).
template <Point2 P2 = glm::dvec2>
dxf_drawing_result<P2> read_dxf_drawing(const file_path& path, const dxf_drawing_options& options = {});

/// Reads an ASCII DXF drawing with arcs (see parse_dxf_arc_drawing). O(file size + S log S + K).
template <Point2 P2 = glm::dvec2>
dxf_arc_drawing_result<P2> read_dxf_arc_drawing(const file_path& path,
                                                const dxf_drawing_options& options = {});

}  // namespace cellforge::io

#include "cellforge/io/detail/dxf_drawing_impl.hpp"
