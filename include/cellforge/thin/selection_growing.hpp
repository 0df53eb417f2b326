// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Selection growing (seed 000 §5.2 and §5.4): from a start face, every cycle grows each
/// kept selection by one face among those adjacent to the most selected faces, drops
/// duplicates, cuts selections longer than keep_ratio × the least boundary length, applies
/// the §5.4 tolerance schedule down to the selection cap and records the least length and
/// its boundary ("loop") per cycle. Two implementations give identical results: `fast`
/// (hashed children, shared bitsets, only survivors materialised) and `faithful` (the seed's
/// Boolean arrays and L1/L2 edge lists, duplicates found by comparing arrays). `scalable`
/// keeps the cap least children instead of the §5.4 schedule, with per-selection frontier
/// heaps, so that a cycle costs what it keeps (docs/thin.md); `automatic` picks by size.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/core/work_budget.hpp"

namespace cellforge {

/// Which implementation grows the selections; both give the same lengths and loops.
enum class thin_mode : std::uint8_t {
  fast,       ///< hashed (parent, face) children, bitsets, only survivors materialised
  faithful,   ///< the seed's data structures: Boolean arrays, L1/L2 lists, array comparison
  scalable,   ///< per-selection frontier heaps, the cap least children kept (docs/thin.md)
  automatic,  ///< fast up to growing_options::scalable_above faces, scalable above (default)
};

/// Faces and their edges as the growing sees them. A "slot" is one face's use of an edge
/// (a half-edge): slots of face f are face_start[f] .. face_start[f+1], in boundary order.
struct thin_face_graph {
  std::uint32_t num_faces = 0;
  std::vector<std::uint32_t> face_start{0};
  std::vector<std::uint32_t> slot_edge;                  ///< edge of each slot (0 .. edge_length.size())
  std::vector<std::uint32_t> slot_other;                 ///< face on the other side of the slot's edge
  std::vector<std::uint32_t> slot_face;                  ///< face owning the slot
  std::vector<double> edge_length;                       ///< cached edge lengths (§5.1's pre-processing)
  std::vector<std::array<std::uint32_t, 2>> edge_slots;  ///< the two slots of each edge
};

/// Parameters of grow_selections (the thin_options fields of the same names).
struct growing_options {
  int selection_cap = 40;
  double keep_ratio = 1.1;
  thin_mode mode = thin_mode::automatic;
  cellforge::work_budget work_budget = 2'000'000'000;
  std::uint32_t scalable_above = 4000;  ///< automatic mode: more faces than this grow scalably
};

/// Per cycle (selection size 1 .. faces−1, fewer when the budget ran out) the least boundary
/// length and a way to that selection's boundary (cycle_loop below).
/// complete (stage_report): false when work_budget ran out; cycles stop early.
struct growing_result : stage_report {
  static constexpr std::uint32_t no_node = 0xFFFFFFFF;
  std::vector<double> cycle_lengths;
  /// Faithful mode: each cycle's loop as sorted inner slots (slots whose face is selected and
  /// whose twin's is not), from the seed's L1 lists. Fast mode leaves it empty (see cycle_node).
  std::vector<std::vector<std::uint32_t>> cycle_loops;
  /// Fast mode: the lineage of every kept selection (the parent's node, or no_node, and the
  /// face it added) and each cycle's least selection, so that loops are built only on demand.
  std::vector<std::uint32_t> node_parent, node_face, cycle_node;
  std::uint64_t selections_examined = 0;  ///< candidate selections generated
  std::uint64_t duplicates_dropped = 0;
  std::uint64_t selections_kept = 0;  ///< survivors summed over the cycles
  std::size_t max_kept = 0;           ///< most survivors in one cycle
};

/// Grows selections from face `start` until all but one face are selected (seed §5.2,
/// §5.4); per cycle the least boundary length and its loop (cycle_loop). Fast: O(faces · cap ·
/// (boundary + candidates · degree + faces/4096 + 64)); faithful: O(faces² · cap · candidates)
/// and more. Throws invalid_input for a graph that is not a closed surface; past work_budget
/// it stops with growing_result::complete false and a diagnostic.
template <class = void>
growing_result grow_selections(const thin_face_graph& g, std::uint32_t start, const growing_options& o = {});

/// The loop of cycle `cycle` (1-based): the least selection's boundary as sorted inner slots
/// (face selected, twin face not). O(faces) per call in fast mode (the lineage is replayed).
template <class = void>
std::vector<std::uint32_t> cycle_loop(const thin_face_graph& g, const growing_result& r, std::size_t cycle);

}  // namespace cellforge

#include "cellforge/thin/detail/selection_growing_impl.hpp"
