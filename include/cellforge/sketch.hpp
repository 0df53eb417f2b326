// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Every public header of the line-drawing part (seed 003): faces of a 2D wireframe drawing,
/// tidying, inflation to 3D and the wireframe pipeline on the result, arcs, rounds and fillets.
/// Needs Eigen 3.3+ on the include path (the tidy, inflation, arc-detection and rounds stages
/// solve with it). Not included: the generated drawings of the tests and benchmarks
/// (`samples/drawings.hpp`, `samples/round_drawings.hpp`, `samples/noisy_drawings.hpp`) and the
/// drawing readers and writers (`cellforge/io/drawing_text.hpp`, `io/svg_drawing.hpp`, `io/drawing_svg.hpp`),
/// and `sketch/instantiate.hpp` (the engines' explicit instantiations, for one file of a program
/// that defines CELLFORGE_EXTERN_SKETCH: docs/sketch.md, "Compile time").
/// The header hygiene test checks that this list is complete.

#include "cellforge/core/point2_traits.hpp"
#include "cellforge/sketch/arc_detection.hpp"
#include "cellforge/sketch/arc_pairing.hpp"
#include "cellforge/sketch/drawing_to_cells.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/face_finder.hpp"
#include "cellforge/sketch/inflation.hpp"
#include "cellforge/sketch/line_drawing.hpp"
#include "cellforge/sketch/round_skeleton.hpp"
#include "cellforge/sketch/rounds.hpp"
#include "cellforge/sketch/tidy.hpp"
