// SPDX-License-Identifier: MIT
#pragma once
// The pipeline's passes and its messages (included by wireframe/wireframe_to_cells.hpp).

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
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/work_counter.hpp"
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
#include "cellforge/wireframe/wireframe_to_cells.hpp"

namespace cellforge {

namespace detail {

/// What a wireframe with edges on one face only is (docs/wireframe.md, "Open surfaces and
/// faces that cross"): the start of wireframe_result's diagnostic "not a closed solid: ...".
/// O(Σ L of the crossed candidates + open edges).
template <class = void>
std::string open_surface_message(const wire_graph& g, const std::vector<wire_face>& candidates,
                                 const arrangement_result& arrangement, const extra_faces_result& extra,
                                 bool faces_are_the_answer) {
  std::vector<char> cut(g.num_edges(), 0);  // edges of candidates the crossing rule dropped
  for (const auto i : arrangement.crossed)
    for (const auto& loop : candidates[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k)
        cut[g.find_edge(loop[k], loop[(k + 1) % loop.size()])] = 1;
  std::size_t pierced = 0;
  std::uint32_t first_rim = no_index, first_cut = no_index;  // caller's labels
  for (const auto e : extra.open_edges) {
    const std::uint32_t caller = g.input_edge[e];
    if (cut[e]) {
      ++pierced;
      first_cut = std::min(first_cut, caller);
    } else {
      first_rim = std::min(first_rim, caller);
    }
  }
  const std::size_t rim = extra.open_edges.size() - pierced;
  std::string what = "not a closed solid: ";
  if (rim > 0)
    what += std::to_string(rim) + " edges lie on one face only (an open surface; edge " +
            std::to_string(first_rim) + " is one)";
  if (pierced > 0)
    what += cellforge::detail::cat(
        std::string(rim > 0 ? "; " : ""), std::to_string(pierced),
        " edges lost a face to faces that cross each other, neither needed more (edges pierce faces: "
        "the surface intersects itself; edge ",
        std::to_string(first_cut), " is one)");
  const std::size_t gone = extra.free + extra.newly_needed + extra.open_surface;
  if (faces_are_the_answer)
    what += "; no volume: the faces are the answer";
  else if (gone > 0)
    what += cellforge::detail::cat("; ", std::to_string(gone), " faces there close no volume (see lost), ",
                                   "volumes come only from the closed parts");
  if (!extra.fins.empty())
    what += cellforge::detail::cat(
        "; ", std::to_string(extra.fins.size()),
        " flat faces with an edge on one face only stand on closed parts (fins): faces in no volume, "
        "the parts keep their volumes");
  return what;
}

/// What a wireframe in which no face survives is, for the error message. O(1).
template <class = void>
std::string no_face_message(const wire_graph& g, const arrangement_result& arrangement,
                            const std::vector<face_note>& lost) {
  const std::string edges = std::to_string(g.num_edges()) + " edges on cycles";
  std::string what;
  if (!lost.empty())
    what = cellforge::detail::cat("every planar cycle of the ", edges, " was removed (",
                                  std::to_string(lost.size()), " faces; the first because ",
                                  lost.front().reason, ")");
  else if (!arrangement.crossed.empty())
    what =
        cellforge::detail::cat("the planar cycles of the ", edges, " cross each other inside their planes (",
                               std::to_string(arrangement.crossed.size()), " dropped by the crossing rule)");
  else
    what = cellforge::detail::cat("none of the cycles of the ", edges, " lies in a plane (skew cycles only)");
  return cellforge::detail::cat("wireframe_to_cells: no face: ", what);
}
}  // namespace detail

namespace detail {
/// The certificate's options for a pipeline run: the caller's, with tolerances no finer than
/// the stages' own. O(1).
template <class = void>
certify_options pipeline_certify_options(const wireframe_options& options) {
  certify_options c = options.certify;
  // The reading rule keeps a seam only where the wireframe draws it and no wall (a tessellated
  // flat surface, seed sample 4): a drawn seam is no failure of the answer.
  c.seams_fail = false;
  c.merge.relative = std::max(c.merge.relative, options.read.merge.relative);
  c.planarity.relative =
      std::max({c.planarity.relative, options.trace.planarity.relative, options.reduction.planarity.relative,
                options.arrangement.planarity.relative, options.extra.retrace.planarity.relative});
  return c;
}

/// "volume v uses the edge between vertices a and b k times" for the first volume of `in` using an
/// edge more than twice (an even number of times), or empty. O(L log L) over the volumes' faces.
template <Point3 P>
std::string pinched_edge(const cell_complex_input<P>& in) {
  for (std::size_t v = 0; v < in.volumes.size(); ++v) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> uses;
    for (const auto& [f, sign] : in.volumes[v].faces)
      for (const auto& loop : in.faces[f].loops)
        for (std::size_t k = 0; k < loop.size(); ++k)
          ++uses[std::minmax(loop[k], loop[(k + 1) % loop.size()])];
    for (const auto& [e, n] : uses)
      if (n > 2 && n % 2 == 0)
        return cellforge::detail::cat("volume ", std::to_string(v), " uses the edge between vertices ",
                                      std::to_string(e.first), " and ", std::to_string(e.second), " ",
                                      std::to_string(n), " times");
  }
  return {};
}

/// r's stage_report: the stages' times summed, complete unless a budget stopped it. O(1).
template <Point3 P>
wireframe_result<P> sum_stages(wireframe_result<P> r) {
  r.milliseconds = r.read.milliseconds + r.tolerance.milliseconds + r.trace.milliseconds +
                   r.unique.milliseconds + r.reduction.milliseconds + r.arrangement.milliseconds +
                   r.extra.milliseconds + r.volume.milliseconds + r.relations.milliseconds +
                   r.assembly_milliseconds + r.certificate.milliseconds;
  r.work = r.trace.work + r.volume.work + r.certificate.work;
  r.complete = r.status != solid_status::budget;
  return r;
}

/// r as returned where `stage` ran out of its work budget (complete false): status budget, the
/// stage's budget diagnostic as the reason and a diagnostic, no cells. O(diagnostics).
template <Point3 P>
wireframe_result<P> stopped_by_budget(wireframe_result<P>& r, const stage_report& stage) {
  r.status = solid_status::budget;
  r.status_reason = budget_note(stage, "a stage ran out of its work budget");
  r.diagnostics.push_back(r.status_reason);
  return sum_stages(std::move(r));
}

/// Sets r.status and its one-line reason from the validation (`invalid`: the broken invariant,
/// or empty), the certificate and what the stages removed or left undecided. O(1).
template <Point3 P>
void judge(wireframe_result<P>& r, const std::string& invalid, bool certified) {
  const certificate_result& c = r.certificate;
  auto plural = [](std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
  };
  if (!invalid.empty()) {
    r.status = solid_status::not_a_solid;
    // A volume using an edge four times or more: the solid the faces bound touches itself along
    // that edge (two columns of a terrain meeting at a corner line), which no 2-manifold volume can.
    const std::string pinched = pinched_edge(r.input);
    r.status_reason =
        !pinched.empty()
            ? cellforge::detail::cat("not a 2-manifold solid: it touches itself along an edge (", pinched,
                                     "), which no volume of a cell complex may use more than twice")
            : cellforge::detail::cat(
                  "the faces found do not make a valid cell complex (", invalid,
                  "); edges crossing each other inside a plane or other input this pipeline "
                  "cannot read may cause this");
  } else if (!certified) {
    r.status = solid_status::not_a_solid;
    r.status_reason = "not certified (certify_result is off)";
  } else if (!c.complete) {
    r.status = solid_status::budget;
    r.status_reason = c.reason();
  } else if (!r.volume.complete) {
    r.status = solid_status::budget;
    r.status_reason =
        "the reading rule ran out of its work budget (volume_options::work_budget): the best "
        "certified reading found, not necessarily the best there is";
  } else if (!c.ok()) {
    r.status = solid_status::not_a_solid;
    // Piercing says what the input is (it intersects itself); the edges it leaves faceless follow.
    const certificate_failure* pierced = c.find(certificate_failure::kind::input_edge_pierces_face);
    r.status_reason =
        pierced ? cellforge::detail::cat("the input intersects itself: ", pierced->message) : c.reason();
  } else if (c.faces_without_volume > 0) {
    r.status = solid_status::not_a_solid;
    r.status_reason =
        !r.extra.fins.empty() && r.cells.num_volumes() > 0
            ? cellforge::detail::cat("a solid with fins: ",
                                     plural(c.faces_without_volume, "flat face stands", "flat faces stand"),
                                     " on its closed parts, in no volume (",
                                     plural(c.free_edges, "edge lies", "edges lie"), " on one face only)")
        : c.free_edges > 0
            ? cellforge::detail::cat("an open surface: ", plural(c.free_edges, "edge lies", "edges lie"),
                                     " on one face only")
            : plural(c.faces_without_volume, "face bounds", "faces bound") + " no volume";
  } else if (const auto open = std::find_if(r.extra.removed.begin(), r.extra.removed.end(),
                                            [](const dropped_face& d) { return d.free_edge; });
             open != r.extra.removed.end()) {
    // Faces removed for a free edge: part of the input is an open surface (a face that lost an
    // overlap to a smaller face in its plane is a spurious cycle, and says nothing of the kind).
    r.status = solid_status::not_a_solid;
    r.status_reason = plural(r.lost.size(), "face was", "faces were") + " removed (one because " +
                      open->reason + "): part of the input is an open surface";
  } else if (!r.unforced.empty()) {
    r.status = solid_status::ambiguous;
    r.status_reason = cellforge::detail::cat("a closed solid, but the wireframe does not decide ",
                                             plural(r.unforced.size(), "face", "faces"),
                                             " no edge needs (walls kept, listed in unforced)");
  } else if (const auto n =
                 static_cast<std::size_t>(std::count_if(r.alternatives.begin(), r.alternatives.end(),
                                                        [](const reading_note& a) { return a.undecided; }));
             n > 0) {
    r.status = solid_status::ambiguous;
    r.status_reason =
        cellforge::detail::cat("a closed solid, but another solid has this wireframe too: ",
                               plural(n, "undecided reading", "undecided readings"), " in alternatives");
  } else {
    r.status = solid_status::solid;
    r.status_reason = cellforge::detail::cat(
        "a closed solid: ", plural(r.cells.num_volumes(), "volume", "volumes"), ", ",
        plural(r.cells.num_faces(), "face", "faces"),
        c.acyclic_input_edges.empty()
            ? std::string(", every input edge on a face")
            : cellforge::detail::cat(", every input edge on a cycle on a face (",
                                     plural(c.acyclic_input_edges.size(), "edge", "edges"),
                                     " on no cycle, a dangling tree, left out; the first is input edge ",
                                     std::to_string(c.acyclic_input_edges.front()), ", 0-based)"),
        (c.seam_edges > 0
             ? cellforge::detail::cat(" (", plural(c.seam_edges, "edge is a seam", "edges are seams"),
                                      " of a tessellated flat surface)")
             : std::string()));
  }
  // The coordinates' noise may have hidden faces (tolerance_estimate.hpp): never a solid, and
  // the reason says why, whatever else the answer is.
  if (r.tolerance.ambiguous) {
    if (r.status == solid_status::solid) r.status = solid_status::ambiguous;
    r.status_reason += cellforge::detail::cat("; the tolerance is doubtful: ", r.tolerance.reason);
  }
}
}  // namespace detail

namespace detail {
/// One run of the pipeline (wireframe_to_cells' body) on the wireframe as read, with the
/// stages' tolerances of `used` (the caller's options, the planarity filled in); `tolerance` is
/// recorded in the result, and with `estimated` its doubts apply (no clear gap: a diagnostic,
/// an answer that leaves part of the wireframe unexplained flagged ambiguous). Throws as
/// wireframe_to_cells. The cost of wireframe_to_cells.
template <Wireframe G>
wireframe_result<typename wireframe_traits<G>::point_type> wireframe_pass(const G& wire,
                                                                          const wireframe_options& used,
                                                                          wireframe_read_result read,
                                                                          tolerance_result tolerance,
                                                                          bool estimated) {
  using P = typename wireframe_traits<G>::point_type;
  wireframe_result<P> r;
  r.read = std::move(read);
  r.tolerance = std::move(tolerance);
  const wire_graph& g = r.read.graph;
  if (estimated && !r.tolerance.clear_gap)
    r.diagnostics.push_back(cellforge::detail::cat("tolerance: ", r.tolerance.reason));
  r.check = cellforge::wireframe_check_options(used);
  r.trace = cellforge::trace_circuits(g, used.trace);
  // A stage out of its work budget ends the pass: the stages after it would read a part of the
  // candidates as the whole, so the answer is the status `budget` and the stage's message.
  if (!r.trace.complete) return stopped_by_budget(r, r.trace);
  r.unique = cellforge::unique_circuits(g, std::move(r.trace.faces), used.unique);
  r.trace.faces.clear();
  reduction_options reduction = used.reduction;
  // Faces of a planar arrangement are never the sum of two others; only the seed's search needs the test.
  if (used.trace.kind == tracer_kind::planar) reduction.remove_face_sums = false;
  r.reduction = cellforge::reduce_faces(g, r.unique.faces, reduction);
  if (!r.reduction.complete) return stopped_by_budget(r, r.reduction);
  r.arrangement = cellforge::arrange_faces(g, r.unique.faces, r.reduction, used.arrangement);
  if (!r.arrangement.complete) return stopped_by_budget(r, r.arrangement);
  extra_face_options extra = used.extra;
  // The planar tracer finds every planar face; only the seed's search can miss some.
  if (used.trace.kind == tracer_kind::planar) extra.add_missed = false;
  r.extra = cellforge::extra_faces(g, r.unique.faces, r.arrangement.selected, extra,
                                   span_of(r.arrangement.crossed));
  if (!r.extra.complete) return stopped_by_budget(r, r.extra);
  // Circuits that close no volume: when every face went for a free edge only, the faces are
  // the answer (a 3DCL holds faces without volumes), with a diagnostic saying so.
  bool open_surface = false;
  if (r.extra.faces.empty()) {
    for (const auto& d : r.extra.removed)
      if (d.free_edge) r.extra.faces.push_back(d.face);
    open_surface = !r.extra.faces.empty();
  }
  for (const auto& d : r.extra.removed)
    if (!(open_surface && d.free_edge)) r.lost.push_back(caller_face_note(g, d.face, d.reason));
  if (r.extra.faces.empty())
    throw error(error_category::topology,
                no_face_message(g, r.arrangement, r.lost) +
                    (!estimated || r.tolerance.clear_gap
                         ? std::string()
                         : cellforge::detail::cat("; ", r.tolerance.reason,
                                                  " (set wireframe_options::tolerance.automatic = false and "
                                                  "the stages' planarity, or wire2cells --planarity)")));
  if (!r.extra.open_edges.empty())
    r.diagnostics.push_back(open_surface_message(g, r.unique.faces, r.arrangement, r.extra, open_surface));
  if (open_surface) {
    const std::size_t n = r.extra.faces.size();
    r.diagnostics.push_back(
        n == 1
            ? std::string("a single planar loop: one face, no volume")
            : std::to_string(n) + " planar faces that close no volume (an open surface): faces, no volume");
    r.volume.face_kept.assign(n, 1);
    r.volume.face_volumes.assign(n, {no_index, no_index});
  } else {
    r.volume = cellforge::find_volumes(g, r.extra.faces, used.volume);
    r.relations = cellforge::find_relations(g, r.extra.faces, r.volume, used.relations);
    // Fins (flat flaps on closed parts) join the answer after the volumes, as faces in no volume
    // (not in the relations, which are the volumes'), in the object of a face they touch.
    if (!r.extra.fins.empty()) {
      std::vector<std::uint32_t> object_at(g.num_vertices(), no_index);
      for (std::uint32_t i = 0; i < r.extra.faces.size(); ++i)
        if (i < r.volume.object_of_face.size())
          for (const auto& loop : r.extra.faces[i].loops)
            for (const auto v : loop) object_at[v] = r.volume.object_of_face[i];
      for (auto& f : r.extra.fins) {
        std::uint32_t object = no_index;
        for (const auto v : f.loops[0]) object = std::min(object, object_at[v]);
        r.volume.object_of_face.push_back(object);
        r.volume.face_kept.push_back(1);
        r.volume.face_volumes.push_back({no_index, no_index});
        r.extra.faces.push_back(f);
      }
    }
  }

  stopwatch clock;
  cell_list_options list_options;
  list_options.keep_dangling = used.keep_dangling;
  cell_list_result<P> list =
      cellforge::assemble_cell_list(wire, g, r.extra.faces, r.volume, span_of(r.read.dangling), list_options);
  // No clear gap between noise and shape: the reading stands when it explains the whole
  // wireframe (every edge on a kept face, nothing lost, volumes closed); otherwise the noise
  // may have hidden faces, and the answer is flagged (the certificate also says what is left).
  if (estimated && !r.tolerance.clear_gap) {
    const bool explained = !open_surface && r.lost.empty() && list.faceless_edges == 0;
    r.tolerance.ambiguous = !explained;
    if (r.tolerance.ambiguous)
      r.diagnostics.push_back(
          "tolerance: the reading leaves part of the wireframe unexplained and the noise may have hidden "
          "faces; the answer is doubtful");
  }
  r.diagnostics.insert(r.diagnostics.end(), std::make_move_iterator(list.diagnostics.begin()),
                       std::make_move_iterator(list.diagnostics.end()));
  r.input = std::move(list.input);
  r.input_vertex = std::move(list.input_vertex);
  r.input_edge = std::move(list.input_edge);
  r.unforced = std::move(list.unforced);
  r.alternatives = std::move(list.alternatives);
  const std::vector<std::uint32_t>& label = list.output_vertex;         // caller's vertex → output
  const std::vector<std::uint32_t>& graph_edge_out = list.output_edge;  // graph edge → output edge

  if (used.build_complex) {
    // Built and checked in the graph's numbering (spatial: wireframe_read_options::spatial_order), where
    // the sorts and checks stay in cache, then renumbered to the output's: the same complex as
    // make_cell_complex(r.input), whatever order the caller numbered the wireframe in.
    const std::size_t nvo = r.input.points.size(), neo = r.input.edges.size();
    std::vector<std::uint32_t> vertex_label, edge_label;  // inner → output
    std::vector<std::uint32_t> inner(nvo, no_index);      // output vertex → inner
    vertex_label.reserve(nvo);
    edge_label.reserve(neo);
    for (std::uint32_t v = 0; v < g.num_vertices(); ++v) {
      const std::uint32_t out = label[g.input_vertex[v]];
      if (out == no_index) continue;
      inner[out] = static_cast<std::uint32_t>(vertex_label.size());
      vertex_label.push_back(out);
    }
    for (std::uint32_t out = 0; out < nvo; ++out)  // ends of dangling edges kept off the graph
      if (inner[out] == no_index) {
        inner[out] = static_cast<std::uint32_t>(vertex_label.size());
        vertex_label.push_back(out);
      }
    std::vector<char> placed(neo, 0);
    for (const std::uint32_t out : graph_edge_out)
      if (out != no_index) {
        edge_label.push_back(out);
        placed[out] = 1;
      }
    for (std::uint32_t out = 0; out < neo; ++out)
      if (!placed[out]) edge_label.push_back(out);
    cell_complex_input<P> in;
    in.points.reserve(nvo);
    for (const std::uint32_t out : vertex_label) in.points.push_back(r.input.points[out]);
    in.edges.reserve(neo);
    for (const std::uint32_t out : edge_label)
      in.edges.push_back({inner[r.input.edges[out][0]], inner[r.input.edges[out][1]]});
    in.faces = r.input.faces;
    for (auto& f : in.faces)
      for (auto& loop : f.loops)
        for (auto& v : loop) v = inner[v];
    in.volumes = r.input.volumes;
    cell_complex<P> inside;
    try {
      inside = cellforge::make_cell_complex(std::move(in));
    } catch (const error&) {
      r.cells = cellforge::make_cell_complex(r.input);  // the error in the output's numbering
      throw;
    }
    if (used.check_result) r.validation = cellforge::validate(inside, r.check);
    r.cells = cellforge::renumber_cells(inside, vertex_label, edge_label);
    if (!r.validation.ok()) r.validation = cellforge::validate(r.cells, r.check);  // output numbering
    r.validation.expected_euler.clear();  // per object, and objects were numbered otherwise inside
    r.validation.euler_checked.clear();
    r.assembly_milliseconds = clock.ms();
    if (used.certify_result) {
      const certify_options check = pipeline_certify_options(used);
      r.certificate = cellforge::certify(r.cells, wire, check);
      // A volume bounded by a face that an input edge pierces is no solid the input draws (the
      // surface intersects itself, as a triangle through a tetrahedron): its faces stay, the
      // volume goes, so that no volume is invented from a self-intersecting input.
      using K = certificate_failure::kind;
      if (const certificate_failure* pierced = r.certificate.find(K::input_edge_pierces_face);
          pierced && !r.input.volumes.empty()) {
        std::vector<char> hit(r.input.faces.size(), 0);
        for (std::size_t k = 1; k < pierced->elements.size(); k += 2) hit[pierced->elements[k]] = 1;
        const std::size_t before = r.input.volumes.size();
        std::erase_if(r.input.volumes, [&](const cell_input_volume& v) {
          return std::any_of(v.faces.begin(), v.faces.end(),
                             [&](const auto& f) { return hit[f.first] != 0; });
        });
        if (r.input.volumes.size() != before) {
          r.diagnostics.push_back(std::to_string(before - r.input.volumes.size()) +
                                  " volumes dropped: a face of each is pierced by an input edge (" +
                                  pierced->message + "), so the input intersects itself there");
          r.cells = cellforge::make_cell_complex(r.input);
          if (used.check_result) r.validation = cellforge::validate(r.cells, r.check);
          r.certificate = cellforge::certify(r.cells, wire, check);
        }
      }
    }
    judge(r, r.validation.ok() ? std::string() : r.validation.message, used.certify_result);
    return sum_stages(std::move(r));
  }
  r.assembly_milliseconds = clock.ms();
  r.status_reason = "no cell complex built (build_complex is off), so not certified";
  return sum_stages(std::move(r));
}

/// Whether answer a is better than b: solid > ambiguous > not_a_solid > budget, and between
/// two not_a_solid answers fewer input edges on no face; ties to b. O(1).
template <Point3 P>
bool better_answer(const wireframe_result<P>& a, const wireframe_result<P>& b) {
  auto rank = [](solid_status s) {
    return s == solid_status::solid         ? 3
           : s == solid_status::ambiguous   ? 2
           : s == solid_status::not_a_solid ? 1
                                            : 0;
  };
  if (rank(a.status) != rank(b.status)) return rank(a.status) > rank(b.status);
  return a.status == solid_status::not_a_solid &&
         a.certificate.unused_input_edges.size() < b.certificate.unused_input_edges.size();
}
}  // namespace detail

template <Wireframe G>
detail::if_satisfied_t<Wireframe<G>, detail::wireframe_result_for, G> wireframe_to_cells(
    const G& wire, const wireframe_options& options) {
  using P = typename wireframe_traits<G>::point_type;
  wireframe_read_result read = read_vertices(wire, options.read);
  if (!read.complete) {  // no graph to read: status budget, read_vertices' message
    wireframe_result<P> r;
    r.read = std::move(read);
    return detail::stopped_by_budget(r, r.read);
  }
  tolerance_result given;  // the stages' own planarity options
  given.planarity = options.trace.planarity.relative;
  given.planarity_distance = options.trace.planarity.relative * read.graph.size;
  if (!options.tolerance.automatic)
    return detail::wireframe_pass(wire, options, std::move(read), given, false);

  tolerance_result estimate = estimate_tolerance(read.graph, options.tolerance);
  wireframe_options at_estimate = options;
  at_estimate.trace.planarity.relative = at_estimate.reduction.planarity.relative = estimate.planarity;
  at_estimate.arrangement.planarity.relative = at_estimate.extra.retrace.planarity.relative =
      estimate.planarity;
  at_estimate.trace.fit_planes = true;  // planes fitted to their vertices: the coordinates may be noisy
  estimate.estimated_planarity = estimate.planarity;
  const bool same = options.trace.fit_planes && options.trace.planarity.relative == estimate.planarity &&
                    options.reduction.planarity.relative == estimate.planarity &&
                    options.arrangement.planarity.relative == estimate.planarity &&
                    options.extra.retrace.planarity.relative == estimate.planarity;
  // Exact input first: the stages' fixed tolerances, the estimate's figures kept beside them.
  tolerance_result fixed_tolerance = estimate;
  fixed_tolerance.planarity = given.planarity;
  fixed_tolerance.planarity_distance = given.planarity_distance;
  fixed_tolerance.fixed_pass = true;
  // A clear gap at or above the fixed tolerance: the estimated pass reads the input. Without
  // fitted planes, noise near the fixed tolerance bends a wall out of its plane, and the rest
  // still certifies as a solid (a 12 × 2 × 1 grid written with 10 digits lost a wall).
  const bool clear = estimate.clear_gap && estimate.planarity >= given.planarity;
  std::optional<wireframe_result<P>> fixed;
  try {
    if (!clear) fixed = detail::wireframe_pass(wire, options, read, std::move(fixed_tolerance), false);
  } catch (const error&) {  // the worst answer; the estimated pass's error is the one thrown
  }
  auto keep_fixed = [&](std::string why) {
    fixed->diagnostics.push_back(cellforge::detail::cat(
        "tolerance: the stages' fixed planarity (", detail::number_text(given.planarity),
        " of the diagonal) was used, not the estimate (", detail::number_text(estimate.planarity),
        "): ", std::move(why)));
    return std::move(*fixed);
  };
  if (fixed && fixed->status == solid_status::solid)
    return estimate.planarity == given.planarity
               ? std::move(*fixed)
               : keep_fixed("certified solid with it, the data's own precision is enough");
  if (fixed && same) return std::move(*fixed);  // the estimated pass would be this one

  wireframe_result<P> r;
  try {
    r = detail::wireframe_pass(wire, at_estimate, std::move(read), std::move(estimate), true);
  } catch (const error& e) {
    if (!fixed) throw;
    return keep_fixed(cellforge::detail::cat(std::string("the estimated one failed ("), e.what(), ")"));
  }
  if (fixed && !detail::better_answer(r, *fixed))
    return keep_fixed(cellforge::detail::cat(std::string("its answer ("), to_string(fixed->status),
                                             ") is no worse than the estimate's (", to_string(r.status),
                                             ")"));
  if (fixed)
    r.diagnostics.push_back(cellforge::detail::cat(
        std::string("tolerance: the estimated planarity was used: the stages' fixed one gives "),
        to_string(fixed->status), " (", fixed->status_reason, ")"));
  return r;
}

}  // namespace cellforge
