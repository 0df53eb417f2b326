// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Deprecated since 0.5, removed in 0.6: the generators moved to `cellforge/samples/drawings.hpp`,
/// their names to `cellforge::samples`. Until then this header includes it and names the
/// old spellings: types as `[[deprecated]]` aliases, functions by using-declarations.

#include "cellforge/samples/drawings.hpp"

#pragma message( \
    "cellforge/sketch/sample_drawings.hpp is deprecated: include cellforge/samples/drawings.hpp (names in cellforge::samples)")

namespace cellforge {

using sample_drawing [[deprecated("use cellforge::samples::sample_drawing")]] = samples::sample_drawing;
using voxel_solid [[deprecated("use cellforge::samples::voxel_solid")]] = samples::voxel_solid;
using sketch_sweep_options [[deprecated("use cellforge::samples::sketch_sweep_options")]] =
    samples::sketch_sweep_options;
using sketch_sweep_family [[deprecated("use cellforge::samples::sketch_sweep_family")]] =
    samples::sketch_sweep_family;
using sketch_sweep_report [[deprecated("use cellforge::samples::sketch_sweep_report")]] =
    samples::sketch_sweep_report;
using samples::archimedean_solids;
using samples::bar_frame;
using samples::cell_block;
using samples::chamfered_corners;
using samples::convex_cells_model;
using samples::convex_polytope_model;
using samples::cut_polytope;
using samples::extruded_polygon;
using samples::generic_drawing;
using samples::generic_margin;
using samples::letter_footprint;
using samples::notched_block;
using samples::platonic_solids;
using samples::project_model;
using samples::random_convex_polytope;
using samples::random_normalon;
using samples::random_quasi_normalon;
using samples::random_skyline;
using samples::random_star_polygon;
using samples::revolved_solid;
using samples::roof_on_box;
using samples::sample_antiprism;
using samples::sample_bipyramid;
using samples::sample_frustum;
using samples::sample_stairs;
using samples::sketch_classics;
using samples::sketch_margin_threshold;
using samples::sketch_sweep;
using samples::sketch_sweep_families;
using samples::sliced_polytope;
using samples::through_slot;
using samples::touching_solids;
using samples::voxel_solid_model;

}  // namespace cellforge
