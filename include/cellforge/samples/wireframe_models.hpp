// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample wireframe models with their ground truth (faces as vertex cycles with holes,
/// volumes as face-index sets): the fixtures and benchmark inputs of the wireframe → cell
/// complex pipeline, and same_faces / same_volumes to compare a result with them.
/// See docs/sample_models.md.
///
/// The models live in three headers, all included here (namespace cellforge::samples):
/// wireframe_models_core.hpp (the type and the comparisons), wireframe_models_builders.hpp
/// (voxel layouts, ring stacks, edits) and wireframe_models_fixtures.hpp (the named models).

#include "cellforge/samples/wireframe_models_builders.hpp"
#include "cellforge/samples/wireframe_models_core.hpp"
#include "cellforge/samples/wireframe_models_fixtures.hpp"
