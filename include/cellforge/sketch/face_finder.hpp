// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Faces of a wireframe line drawing (seed 003 §"Finding faces"): the
/// Varley–Company string algorithm — strings of half-edges, concatenation and cyclisation
/// under the two rules, a master list of what must be true and a working list for hypotheses,
/// a start at a trihedral junction, forced concatenations, voluntary mergers and hypotheses by
/// priority and mating value — and the Dijkstra-style baseline it beats (shortest loops picked
/// one by one at fixed edge costs). Every answer is checked and flagged when the check fails.
/// The priority and mating-value formulas are ours: docs/sketch.md, "Finding faces".

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iterator>
#include <limits>
#include <numbers>
#include <queue>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/work_counter.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/core/work_budget.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge {

/// Which face finder.
enum class face_finder_kind : std::uint8_t {
  varley_company,  ///< strings of half-edges with context-dependent costs (the seed's algorithm)
  shortest_loops,  ///< the baseline: the shortest loop through an edge, one by one, fixed edge costs
};

/// Options of find_faces, with the defaults docs/sketch.md explains.
struct face_finder_options {
  face_finder_kind kind = face_finder_kind::varley_company;
  /// Mating value: cost of a turn against the loop's turning sense so far (a reflex corner), in
  /// edges. Convex faces are the common case; a non-convex loop must be that much shorter to win.
  double reflex_turn_cost = 0.35;
  /// Mating value: cost of an edge whose drawing direction is a third main direction of the loop
  /// (a planar face of a normalon-like drawing holds edges of two of its three main directions).
  double third_direction_cost = 2.0;
  /// Mating value: cost of a loop whose junctions, taken out, split the drawing (a ring around a
  /// cap, an equator). Faces of a polyhedron whose graph is 3-connected never do (Tutte); hole
  /// loops do, so this is a cost, not a rule.
  double separating_loop_cost = 1.5;
  /// Priority: the starting cost of a hypothesis seed per candidate beyond the first at its end
  /// (a string with fewer ways on is more likely right), in edges.
  double candidate_cost = 0.5;
  /// Drawing lines closer than this to parallel (degrees) share a direction class.
  double parallel_tolerance_degrees = 0.5;
  /// Check each hypothesis by propagating its forced consequences on a copy of the master list
  /// and reject it when they reach a dead end (a half-edge that no face can continue).
  bool look_ahead = true;
  /// Work budget in abstract steps (string joins tried); 0 = unlimited. Exhausted: a budget error.
  cellforge::work_budget work_budget = 400'000'000;
  /// Compute ranked alternatives (the other finder, other starts) when the answer fails its check.
  bool alternatives_when_flagged = true;
  /// Faces beyond two per edge: after the finder, search the loops its edges still need (internal
  /// walls, solids touching along an edge; docs/sketch.md, "Walls and contacts").
  bool walls = true;
  /// Lines closer than this to parallel (degrees) are parallel in space, for the coplanarity of
  /// two faces at an edge (an exact drawing: rounding only; a tidied one: its tidying tolerance).
  double coplanar_tolerance_degrees = 1e-6;
  /// Paths one wall search tries before it gives up on an edge.
  std::size_t wall_expansions = 20000;
};

/// What the check of an answer found. An answer passes when every edge lies on two loops or
/// more, every loop is a simple polygon of the drawing without an edge across its inside, no
/// two loops turn the same corner or overlap as coplanar faces at an edge, no edge holds more
/// loops than its junctions allow, and no edge lies on just two coplanar loops (a seam no wall
/// meets). Coplanar: docs/sketch.md, "Walls and contacts".
struct face_validation {
  std::size_t edges_on_two_loops = 0;
  std::vector<std::uint32_t> edges_with_fewer_loops;  ///< edge indices, with 0 or 1 loops
  std::vector<std::uint32_t> edges_with_more_loops;   ///< edge indices on 3 or more loops (walls, contacts)
  std::vector<std::uint32_t> bad_loops;   ///< loops that are not simple polygons or have an inner chord
  std::vector<std::uint32_t> seam_edges;  ///< edges on just two loops, coplanar: a wall must meet them
  /// Loops that turn a corner an earlier loop turns, overlap a coplanar one at an edge, or put
  /// an edge over the faces its junctions can hold.
  std::vector<std::uint32_t> rule_breaking_loops;
  /// V − E + L per connected component summed, and 2 × components: equal for spheres (and for a
  /// genus-g solid with 2g hole loops); less means a higher genus or a loop too few.
  long long euler = 0, euler_sphere = 0;
  bool ok() const noexcept {
    return edges_with_fewer_loops.empty() && bad_loops.empty() && seam_edges.empty() &&
           rule_breaking_loops.empty();
  }
};

/// Another answer, when the first failed its check: loops, its check, and why it ranks there.
struct face_alternative {
  std::vector<std::vector<std::uint32_t>> loops;
  face_validation check;
  std::string reason;
};

/// The faces of a drawing: loops as junction cycles (each edge's two half-edges on two loops,
/// traversed in opposite directions), the check, counts, time and diagnostics.
struct face_finder_result : stage_report {
  face_finder_kind kind = face_finder_kind::varley_company;
  std::vector<std::vector<std::uint32_t>> loops;
  face_validation check;
  bool flagged = false;                        ///< the check failed: see diagnostics and alternatives
  std::vector<face_alternative> alternatives;  ///< best first, when flagged
  std::size_t junctions = 0, edges = 0, direction_classes = 0;
  std::size_t forced = 0;      ///< forced concatenations (one candidate left)
  std::size_t voluntary = 0;   ///< voluntary mergers (a string closed into a face)
  std::size_t hypotheses = 0;  ///< faces found by the working list
  std::size_t rejected = 0;    ///< hypotheses whose consequences reached a dead end
  std::size_t walls = 0;       ///< loops the wall search added (faces beyond two per edge)
  std::size_t unneeded = 0;    ///< loops dropped because no edge needs them (a hole's mouth)
  std::size_t unforced = 0;    ///< loops kept that no edge needs (walls inside a grid): flagged ambiguous
  /// The finder ran out of budget: the baseline's answer, or no loops when the baseline (the
  /// last fallback) ran out too (complete false, a diagnostic names the option); flagged.
  bool budget_fallback = false;
  /// Loops were added or dropped after the string algorithm, and the wall search from no loops
  /// found others (in `alternatives`): flagged.
  bool ambiguous = false;
};

/// Finds the faces of a wireframe line drawing (every edge drawn, hidden ones too, a parallel
/// view of a polyhedron): loops as junction cycles, checked; flagged with ranked alternatives
/// when the check fails. Throws invalid_input on a malformed drawing; out of work budget, the
/// baseline's loops (or none, when it runs out too), flagged, complete false. Practical cost about O(E · L²)
/// for Varley–Company (L: loop length), O(F·E log E) baseline.
template <LineDrawing D>
face_finder_result find_faces(const D& drawing, const face_finder_options& options = {});

}  // namespace cellforge

#include "cellforge/sketch/detail/face_finder_impl.hpp"
