// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The exact self-intersection check of algorithms/self_intersections.hpp for a mesh whose faces
/// come in pieces (a tube mesh's bands between rings, its junctions): the same answer, found by
/// certifying each piece with its neighbours embedded as a whole (a star-shaped certificate, below)
/// and testing triangle pairs only between pieces that no certified group holds together. The
/// certificate, its proof and its cost: docs/tubes.md, "The check by pieces".

#include <cstdint>
#include <span>

#include "cellforge/algorithms/self_intersections.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"

namespace cellforge {

/// Finds the pairs of faces of m whose triangles intersect, exactly, with the same answer as
/// self_intersections(m, options) (pairs, counts, degenerate triangles) whatever the labelling;
/// `face_piece` (per face index, ids below faces_size()) only decides how much work that takes.
/// Each piece with its neighbours (the pieces across its edges) is certified embedded when the
/// group, its boundary loops closed by cones, is a closed oriented surface that every triangle
/// of sees facing away from one point and that covers one direction from it once; pairs of
/// pieces that a certified group holds are not tested. O(group sizes + the pairs of pieces
/// whose boxes overlap + the triangle pairs of the uncertified ones), bounded by the work budget.
template <Point3 P>
self_intersection_result self_intersections_by_pieces(const surface_mesh<P>& m,
                                                      std::span<const std::uint32_t> face_piece,
                                                      const self_intersection_options& options = {});

}  // namespace cellforge

#include "cellforge/algorithms/detail/piece_self_intersections_impl.hpp"
