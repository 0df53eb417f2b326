// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Deprecated since 0.5, removed in 0.6: the generators moved to `cellforge/samples/wireframe_models.hpp`,
/// their names to `cellforge::samples`. Until then this header includes it and names the
/// old spellings: types as `[[deprecated]]` aliases, functions by using-declarations.

#include "cellforge/samples/wireframe_models.hpp"

#pragma message( \
    "cellforge/wireframe/sample_models.hpp is deprecated: include cellforge/samples/wireframe_models.hpp (names in cellforge::samples)")

namespace cellforge {

using sample_model [[deprecated("use cellforge::samples::sample_model")]] = samples::sample_model;
using voxel_layout [[deprecated("use cellforge::samples::voxel_layout")]] = samples::voxel_layout;
using ring_stack [[deprecated("use cellforge::samples::ring_stack")]] = samples::ring_stack;
using samples::all_small_samples;
using samples::disjoint_union;
using samples::empty_layout;
using samples::make_ring_stack;
using samples::make_voxel_model;
using samples::same_faces;
using samples::same_volumes;
using samples::sample_block_with_hole;
using samples::sample_close_edges;
using samples::sample_cube;
using samples::sample_disjoint_solids;
using samples::sample_frame;
using samples::sample_grid;
using samples::sample_house;
using samples::sample_L;
using samples::sample_octahedron;
using samples::sample_prism;
using samples::sample_pyramid;
using samples::sample_seed;
using samples::sample_split_edges;
using samples::sample_stepped_block;
using samples::sample_T;
using samples::sample_tetrahedron;
using samples::sample_thin_slab;
using samples::sample_two_cubes;
using samples::sample_U;
using samples::sample_uv_sphere;
using samples::split_edge;
using samples::transformed;

}  // namespace cellforge
