// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Every public header of cellforge's 3D library (core, half-edge meshes and their
/// algorithms, cell complexes, the wireframe pipeline, thin points, edge smoothing, tube
/// networks) except three kinds, which you include by name when you want them: file I/O
/// (`cellforge/io/...`), the generators of test and benchmark inputs (`algorithms/shapes.hpp`,
/// `samples/wireframe_models.hpp`, `samples/skeletons.hpp`, `samples/drawings.hpp`,
/// `samples/round_drawings.hpp`) and the seed's sample solids (`samples/thin_solids.hpp`,
/// `samples/smooth_solids.hpp`), which are large and which an application rarely needs. Line
/// drawings (`sketch/...`, seed 003) have their own umbrella, `cellforge/sketch.hpp`, since
/// half of that part solves with Eigen: nothing here needs Eigen or pays for parsing it. The
/// header hygiene test checks that these lists are complete.

#include "cellforge/algorithms/convex_hull.hpp"
#include "cellforge/algorithms/ear_clipping.hpp"
#include "cellforge/algorithms/edits.hpp"
#include "cellforge/algorithms/loop_subdivision.hpp"
#include "cellforge/algorithms/self_intersections.hpp"
#include "cellforge/algorithms/simplification.hpp"
#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/certify.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/cells/validate.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/morton.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_intersection.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/core/rounded_solid.hpp"
#include "cellforge/core/tolerance.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/halfedge/circulators.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/handles.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/halfedge/mesh_geometry.hpp"
#include "cellforge/halfedge/orientation.hpp"
#include "cellforge/halfedge/properties.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "cellforge/smooth/continuous_surfaces.hpp"
#include "cellforge/smooth/edge_curve.hpp"
#include "cellforge/smooth/normals.hpp"
#include "cellforge/smooth/smooth_edges.hpp"
#include "cellforge/thin/central_axis.hpp"
#include "cellforge/thin/loop_detection.hpp"
#include "cellforge/thin/selection_growing.hpp"
#include "cellforge/thin/thin_points.hpp"
#include "cellforge/thin/thin_result.hpp"
#include "cellforge/tubes/branch_mesh.hpp"
#include "cellforge/tubes/node_path.hpp"
#include "cellforge/tubes/skeleton.hpp"
#include "cellforge/tubes/tube_construct.hpp"
#include "cellforge/tubes/tube_mesh.hpp"
#include "cellforge/version.hpp"
#include "cellforge/wireframe/cell_list.hpp"
#include "cellforge/wireframe/circuit_tracer.hpp"
#include "cellforge/wireframe/extra_faces.hpp"
#include "cellforge/wireframe/face_arrangement.hpp"
#include "cellforge/wireframe/face_reduction.hpp"
#include "cellforge/wireframe/read_vertices.hpp"
#include "cellforge/wireframe/relations.hpp"
#include "cellforge/wireframe/tolerance_estimate.hpp"
#include "cellforge/wireframe/unique_circuits.hpp"
#include "cellforge/wireframe/volume_finder.hpp"
#include "cellforge/wireframe/wire_graph.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"
