// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 7 of the wireframe pipeline (seed 000 §4.7): objects and volumes. The seed walks
/// from the leftmost face and chooses the next face around an edge by a "turn direction",
/// which fails when two of its vectors are parallel (fig. 24, patched there by nudging
/// coordinates). Here the same choice — the next face in rotation order around the edge — is
/// made for every face side at once, so no turn direction is ever needed: sort the faces
/// around each edge by angle; the side of one face facing the next face continues the same
/// shell. Connected face sides are shells; a shell of negative signed volume is a surface's
/// outside and bounds no volume (the seed's outside-surface removal); an outside surface
/// nested in another surface's volume (a solid in a cavity) becomes part of that volume's
/// boundary, found by an exact point-in-solid test. Then the reading rule (docs/wireframe.md)
/// drops the faces no edge needs — the mouths of holes and dents, walls such as the square
/// under a roof — and joins the regions on their sides, each group of such faces decided by
/// an exact, budgeted search for the best certified reading.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/polygon_intersection.hpp"
#include "cellforge/wireframe/circuit_tracer.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// How the faces no edge needs are read (docs/wireframe.md, "The reading rule").
enum class face_reading : std::uint8_t {
  /// A face only where some edge needs it: holes and dents stay open, walls no edge needs
  /// go (the square under a roof), except where the wireframe cannot decide which to drop
  /// (the inner walls of a grid): those stay and are reported as unforced. The default.
  needed,
  /// As `needed`, but every wall between two volumes stays (and is reported as unforced):
  /// the seed's reading of its sample 6, a vase cut into 13 volumes by its rings.
  keep_walls,
  /// Every selected face stays: holes and dents are plugged, every wall is kept.
  keep_all,
};

/// Options of find_volumes.
struct volume_options {
  face_reading reading = face_reading::needed;
  /// Also merge the volumes on both sides of the walls the reading kept although no edge needs
  /// them (reported in volume_result::unforced), one wall at a time and only while no needed
  /// face ends up inside a volume and no edge is left on fewer than two faces or on two
  /// coplanar ones; the walls merged are listed in volume_result::merged.
  bool merge_unforced = false;
  /// Abstract steps of the reading rule (faces looked at by its rounds and its group searches);
  /// 0 = none. A group search that reaches it (or 2^15 nodes) takes its best certified reading,
  /// says so in a diagnostic and clears volume_result::complete; the rounds then stop, so that
  /// the answer is the best reading found, never a throw.
  cellforge::work_budget work_budget = 200'000'000;
  /// Whole readings of each group searched that keep no more faces no edge needs than the one
  /// taken, reported in volume_result::alternatives (at most this many per group).
  std::size_t alternatives_per_group = 8;
};

/// The key of the reading rule's order that set a reading aside (docs/wireframe.md, "The
/// order"): more kept faces no edge needs, more volumes, more faces, less area dropped, or none.
enum class reading_key : std::uint8_t { unneeded_faces, volumes, faces, area, none };

/// Another reading of faces no edge needs: the faces it keeps that the answer drops (`add`),
/// the faces of the answer it drops (`remove`), what it stands for and what set it aside.
struct volume_alternative {
  std::vector<std::uint32_t> add, remove;  ///< indices into find_volumes' faces, increasing
  std::string reading;  ///< "would close a hole or dent", "would split a volume in two", ...
  /// The first key of the order that ranks it below the answer; `none`: as good in every key.
  reading_key set_aside_by = reading_key::unneeded_faces;
  /// The wireframe does not decide between it and the answer: it keeps no more faces no edge
  /// needs, and only the order's tie-breaks (volumes, faces, area) or nothing set it aside.
  bool undecided = false;
};

/// One face around an edge: the face, and +1 when it walks the edge from start to end.
struct edge_fan_entry {
  std::uint32_t face = 0;
  int walk = 0;
  double angle = 0.0;  ///< right-hand angle about the edge (start → end), in (-π, π]
};

/// Objects, shells and volumes of a set of faces.
struct volume_result : stage_report {
  std::size_t objects = 0;
  std::vector<std::uint32_t> object_of_face;
  std::size_t shells = 0, outside_shells = 0, nested_shells = 0;
  /// Per face: the volume on its normal's side and on the other side (no_index: outside).
  std::vector<std::array<std::uint32_t, 2>> face_volumes;
  /// Per volume: (face, +1 when the face's normal points out of the volume, -1 when in).
  std::vector<std::vector<std::pair<std::uint32_t, int>>> volumes;
  std::vector<char>
      face_kept;  ///< false for faces the reading dropped, merged or with one region on both sides
  std::vector<std::uint32_t> unforced;  ///< kept faces no edge needs: the wireframe does not decide them
  std::vector<std::uint32_t> dropped;  ///< faces no edge needs that the reading removed (holes, roofs, rings)
  std::vector<std::uint32_t> merged;   ///< walls merge_unforced removed
  /// Other readings: first one per dropped face (same order as `dropped`: keeping it "would
  /// close a hole or dent" or "would split a volume in two", set aside for keeping a face no
  /// edge needs), then the whole readings of groups that keep no more such faces than the one
  /// taken (`undecided` ones make the answer ambiguous, as `unforced` faces do).
  std::vector<volume_alternative> alternatives;
  // complete (stage_report): false when a group search ran out of the work budget (or its node
  // limit): the answer is the best certified reading found, not necessarily the best there is.
  double manifold_milliseconds = 0.0;  ///< the seed's "manifold analysis" row: rotation order and shells
  std::size_t groups = 0;              ///< groups of faces no edge needs that the reading searched
  std::size_t readings = 0;  ///< certified readings the searches met (the best of each group is taken)
};

/// Finds objects and volumes and applies the reading rule to the faces no edge needs (see the
/// file comment and docs/wireframe.md). O(Σ L + E·k log k) for the shells and the rule, plus
/// the exact nesting tests when several surfaces may nest (O(surfaces · shells) box tests and
/// O(Σ L) per test).
template <class = void>
volume_result find_volumes(const wire_graph& g, const std::vector<wire_face>& faces,
                           const volume_options& options = {});

}  // namespace cellforge

#include "cellforge/wireframe/detail/volume_finder_impl.hpp"
