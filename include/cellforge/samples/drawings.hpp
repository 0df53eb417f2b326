// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample line drawings with their ground truth: sample wireframes (samples/wireframe_models.hpp)
/// seen in generic parallel views (no two junctions on one point, no junction on another
/// edge's line, no face seen edge-on), with the true face loops, the true 3D positions in view
/// coordinates and the model (faces, volumes) the drawing shows. The fixtures and benchmark
/// inputs of the sketch stages; see docs/sketch.md.
///
/// The generators live in one header per family, all included here (namespace cellforge::samples):
/// drawings_views.hpp (the type and the views), drawings_polytopes.hpp and drawings_normalons.hpp
/// (one-volume solids), drawings_compound.hpp (several volumes, touching and revolved solids),
/// drawings_sweep.hpp (the classics and sketch_sweep).

#include "cellforge/samples/drawings_compound.hpp"
#include "cellforge/samples/drawings_normalons.hpp"
#include "cellforge/samples/drawings_polytopes.hpp"
#include "cellforge/samples/drawings_sweep.hpp"
#include "cellforge/samples/drawings_views.hpp"
