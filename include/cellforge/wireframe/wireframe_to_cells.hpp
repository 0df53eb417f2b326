// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The whole wireframe → cell complex (3DCL) pipeline of seed 000 §4: read (§4.1), trace
/// (§4.2), unique circuits (§4.3), face reduction (§4.4), face arrangement (§4.5), extra faces
/// (§4.6), objects and volumes (§4.7), relations (§4.8) and the cell list (§4.9,
/// cell_list.hpp), on anything that models Wireframe. Every stage's result (counts,
/// diagnostics, time) is returned too, and the answer's certificate (cells/certify.hpp) with a
/// status: solid, ambiguous, not a solid.

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/certify.hpp"
#include "cellforge/cells/validate.hpp"
#include "cellforge/core/detail/if_satisfied.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/wireframe.hpp"
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

namespace cellforge {

/// Options of every stage, with the seed's defaults.
struct wireframe_options {
  wireframe_read_options read{};
  /// The planarity tolerance of every stage chosen from the data (§4.1½, tolerance_estimate.hpp);
  /// `automatic = false` keeps the stages' own planarity options below.
  tolerance_options tolerance{};
  trace_options trace{};
  unique_circuits_options unique{};
  reduction_options reduction{};
  arrangement_options arrangement{};
  extra_face_options extra{};
  volume_options volume{};
  relations_options relations{};
  bool keep_dangling = false;  ///< put edges that bound no face into the cell complex too
  bool build_complex = true;   ///< call make_cell_complex on the result
  /// Validate the complex (cells/validate.hpp): a broken invariant (input this pipeline cannot
  /// read, such as edges crossing inside a face plane) makes the result not_a_solid, with the
  /// invariant named in status_reason. Needs build_complex.
  bool check_result = true;
  /// Certify the complex against the wireframe (cells/certify.hpp) and judge the status from
  /// the certificate; its tolerances are never finer than the stages' own. Needs build_complex.
  bool certify_result = true;
  certify_options certify{};
};

/// The validate() options that judge a complex wireframe_to_cells made with `options` as given
/// (the stages' tolerances; with the automatic tolerance the result's `check` holds the options
/// it was judged with): its faces are flat to the pipeline's own tolerances (fractions of the
/// model's diagonal), so they are judged no finer than ten times those. O(1).
template <class = void>
cells_validation_options wireframe_check_options(const wireframe_options& options) {
  cells_validation_options check;
  check.planarity_floor =
      std::max({check.planarity_floor, 10 * options.read.merge.relative,
                10 * options.trace.planarity.relative, 10 * options.reduction.planarity.relative,
                10 * options.arrangement.planarity.relative, 10 * options.extra.retrace.planarity.relative});
  return check;
}

/// The cell complex (positions in the wireframe's point type P), its input, and every stage's report.
/// milliseconds: the stages' times summed; complete: false when a budget stopped the reading
/// (status `budget`).
template <Point3 P>
struct wireframe_result : stage_report {
  using point_type = P;
  cell_complex_input<P> input;  ///< points, edges, faces (loops), volumes (signed faces)
  cell_complex<P> cells;        ///< make_cell_complex(input), when options.build_complex
  /// input.points[i] is the caller's point input_vertex[i]; input.edges[k] the caller's edge input_edge[k].
  std::vector<std::uint32_t> input_vertex, input_edge;
  std::vector<std::uint32_t> unforced;  ///< indices into input.faces of faces no edge needs (kept: undecided)
  /// Other readings (volume_result::alternatives): first each cycle the reading rule did not take
  /// (no edge needs it: "would close a hole or dent", "would split a volume in two"), then whole
  /// readings of groups as good in kept faces no edge needs; `undecided` ones make the answer
  /// ambiguous. See volume_options::reading.
  std::vector<reading_note> alternatives;
  /// Faces selected and then removed (a free edge, an overlap): never silent.
  std::vector<face_note> lost;
  wireframe_read_result read;
  /// The tolerance the stages used and how it was found; `tolerance.ambiguous` flags an answer
  /// the coordinates' noise may have spoilt (no clear gap, and part of the wireframe unexplained).
  tolerance_result tolerance;
  /// The validate() options the result was checked with (wireframe_check_options of the
  /// options as used, the automatic tolerance filled in).
  cells_validation_options check;
  trace_result trace;
  unique_circuits_result unique;
  reduction_result reduction;
  arrangement_result arrangement;
  extra_faces_result extra;
  volume_result volume;
  relations_result relations;
  double assembly_milliseconds = 0.0;  ///< the seed's "cell list assembly" row
  /// What the answer is: solid (the certificate passes, every face decided by the wireframe),
  /// ambiguous (it passes, but walls no edge needs were kept: `unforced`), not_a_solid (the
  /// certificate or validate failed, input edges on cycles lie on no face, or faces close no
  /// volume), budget (a stage's or the certificate's work budget ran out: the reason names the
  /// option to raise). Never solid unless certified.
  solid_status status = solid_status::not_a_solid;
  std::string status_reason;  ///< one line: what the input is, or what failed
  /// The certificate (cells/certify.hpp); empty, with status not_a_solid, when not run.
  certificate_result certificate;
  /// validate()'s verdict on `cells` (check_result; ok when not run), named in the output's
  /// numbering when it failed; signed volumes per volume (the per-object lists left empty).
  cells_validation validation;
};

namespace detail {
/// wireframe_to_cells' result type for wireframe type G (unconstrained, for if_satisfied_t).
template <class G>
using wireframe_result_for = wireframe_result<typename wireframe_traits<G>::point_type>;
}  // namespace detail

/// Converts a wireframe to a cell complex whose positions are the wireframe's (its point type),
/// certifies it against the wireframe and says what it is (status, status_reason). Faces that
/// close no volume (a lone planar loop, an open box) come back as faces without volumes,
/// not_a_solid, with a diagnostic; a stage out of its work budget ends the call with status
/// budget. Throws cellforge::error on bad input (see read_vertices) or when no face is found
/// (saying what the wireframe is).
/// With the automatic tolerance, exact input first: the stages' fixed tolerances, whose certified
/// solid is the answer; otherwise the estimated tolerance too, and the better answer of the two
/// (better_answer; a pass that throws is the worst, both: the estimated pass's error). A clear
/// gap at or above the fixed tolerance: the estimated pass only.
/// Polynomial with the default planar tracer: O(Σ deg² + Σ planes k log k + F·L + grid pairs),
/// twice only for input without a clear gap (or one below the fixed tolerance) that is no
/// certified solid at the fixed tolerance.
template <Wireframe G>
detail::if_satisfied_t<Wireframe<G>, detail::wireframe_result_for, G> wireframe_to_cells(
    const G& wire, const wireframe_options& options = {});

}  // namespace cellforge

#include "cellforge/wireframe/detail/wireframe_to_cells_impl.hpp"
