// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Every public header of the line-drawing part (seed 003): faces of a 2D wireframe drawing,
/// tidying, inflation to 3D and the wireframe pipeline on the result, arcs, rounds and fillets.
/// Needs Eigen 3.3+ on the include path (the tidy, inflation, arc-detection and rounds stages
/// solve with it). Like every umbrella it leaves out the test data (`cellforge/samples/...`: the
/// generated drawings) and file I/O (`cellforge/io/...`: the drawing readers and writers). The
/// header hygiene test checks that this holds. Nor is `sketch/instantiate.hpp` (the engines'
/// explicit instantiations, for one file of a program that defines CELLFORGE_EXTERN_SKETCH:
/// docs/sketch.md, "Compile time").

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
