// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 5 of the wireframe pipeline (seed 000 §4.5): smooth entity chains (straight runs of
/// edges through degree-2 vertices), the Shpitalni–Lipson maximum ranks of edges and vertices,
/// and the crossing rule of the face selection (docs/wireframe.md): of two candidates whose
/// interiors cross, the one some edge needs wins; the pairs no edge decides are decided by the
/// certified choice (no pair kept whole, every genuine edge kept genuine) that keeps the fewest.
/// Candidate pairs come from a uniform grid over face bounding boxes, so the cost is not
/// all-pairs; the rest of the reading rule (faces no edge needs) is decided with the volumes.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/morton.hpp"
#include "cellforge/core/polygon_intersection.hpp"
#include "cellforge/core/tolerance.hpp"
#include "cellforge/wireframe/face_reduction.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// Options of arrange_faces.
struct arrangement_options {
  tolerance planarity{1e-9};   ///< distances under this (relative to model size) count as zero
  bool drop_crossing = true;   ///< the selection rule; false keeps every usable candidate
  bool enforce_ranks = false;  ///< seed: drop the largest face at an edge exceeding its maximum rank
  cellforge::work_budget work_budget = 500'000'000;
};

/// The selection and the rank analysis.
struct arrangement_result : stage_report {
  std::vector<std::uint32_t> selected;                  ///< indices of kept candidates, increasing
  std::vector<std::array<std::uint32_t, 2>> crossings;  ///< pairs of candidates whose interiors cross
  std::vector<std::uint32_t> chain_of_edge;             ///< smooth entity chain id of each edge
  std::size_t chains = 0;                               ///< chains with more than one edge
  std::vector<std::uint32_t> edge_rank;                 ///< maximum rank R(e) of each edge
  std::vector<std::uint32_t> vertex_rank;               ///< maximum rank R(v) of each vertex
  std::size_t rank_violations = 0;                      ///< edges with more selected faces than R(e)
  std::uint64_t pairs_tested = 0;
  std::vector<std::uint32_t> crossed;  ///< candidates dropped by the crossing rule, increasing
};

/// Finds chains and ranks and selects the faces: the crossing rule of docs/wireframe.md (when
/// two candidates cross, the one some edge needs wins; the pairs left are decided by a
/// budgeted search for the certified choice that keeps the fewest). O(V + E + F·L + P·L log L) where P is the
/// number of candidate pairs the grid yields, plus O(rounds · F·L) for the needs, rounds being the chains of
/// decisions (one or two).
template <class = void>
arrangement_result arrange_faces(const wire_graph& g, const std::vector<wire_face>& faces,
                                 const reduction_result& reduction, const arrangement_options& options = {});

}  // namespace cellforge

#include "cellforge/wireframe/detail/face_arrangement_impl.hpp"
