// SPDX-License-Identifier: MIT
#pragma once
// The engine of the tube mesher (included by tubes/tube_mesh.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/loop_subdivision.hpp"
#include "cellforge/algorithms/piece_self_intersections.hpp"
#include "cellforge/algorithms/self_intersections.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/if_satisfied.hpp"
#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/morton.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/halfedge/mesh_geometry.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"
#include "cellforge/tubes/branch_mesh.hpp"
#include "cellforge/tubes/detail/closed_build.hpp"
#include "cellforge/tubes/detail/tube_buffer.hpp"
#include "cellforge/tubes/node_path.hpp"
#include "cellforge/tubes/skeleton.hpp"
#include "cellforge/tubes/tube_construct.hpp"
#include "cellforge/tubes/tube_mesh.hpp"

namespace cellforge {

namespace detail::tubes {

/// Unit points spread over the sphere (a Fibonacci lattice) for an isolated node. O(n).
template <class = void>
std::vector<glm::dvec3> sphere_directions(std::size_t n) {
  std::vector<glm::dvec3> d(n);
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (std::size_t i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * static_cast<double>(i) + 1.0) / static_cast<double>(n);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), a = golden * static_cast<double>(i);
    d[i] = {r * std::cos(a), r * std::sin(a), z};
  }
  return d;
}

/// The open paths' ends at each junction, in CSR form (one allocation, not one per node), in
/// path order, a path's start before its end: slot 2p / 2p + 1 is the start / end of path p.
struct junction_ends {
  std::vector<std::uint32_t> start, slots;
  std::span<const std::uint32_t> at(std::uint32_t v) const noexcept {
    return {slots.data() + start[v], start[v + 1] - start[v]};
  }
};

/// The ends of tc's open paths at junctions, grouped by junction. O(nodes + paths).
template <class = void>
junction_ends path_ends_at_junctions(const tube_construct& tc) {
  junction_ends e;
  e.start.assign(tc.nodes.size() + 1, 0);
  const auto is_junction = [&](std::uint32_t c) { return tc.nodes[c].kind == tube_node_kind::junction; };
  for (int pass = 0; pass < 2; ++pass) {
    for (std::uint32_t p = 0; p < tc.paths.size(); ++p) {
      const tube_path& path = tc.paths[p];
      if (path.closed) continue;
      const std::uint32_t ends_of[2] = {path.nodes.front(), path.nodes.back()};
      for (std::uint32_t k = 0; k < 2; ++k)
        if (is_junction(ends_of[k])) {
          if (pass == 0)
            ++e.start[ends_of[k] + 1];
          else
            e.slots[e.start[ends_of[k]]++] = 2 * p + k;
        }
    }
    if (pass == 0) {
      for (std::size_t v = 0; v < tc.nodes.size(); ++v) e.start[v + 1] += e.start[v];
      e.slots.resize(e.start.back());
    } else {  // filling advanced each start to the next node's: shift back
      for (std::size_t v = tc.nodes.size(); v > 0; --v) e.start[v] = e.start[v - 1];
      e.start[0] = 0;
    }
  }
  return e;
}

/// Moves the buffer's points (converted to P) and linked faces into `mesh` (empty), with the
/// face sources as the property "f:tube_source" when `sources_as_property`, and returns the
/// mesh's connected components. Faces that are not a closed oriented surface go to build,
/// which reports them (throws) or builds what they are. O(V + F).
template <Point3 P>
std::size_t take_mesh(buffer& out, surface_mesh<P>& mesh, bool sources_as_property) {
  const std::size_t num_points = out.points.size();
  // Positions in the buffer's own type and the sources move into the mesh instead of being
  // copied (the mesh's arrays are then already at their size).
  if constexpr (std::is_same_v<P, glm::dvec3>) mesh.positions().vector().swap(out.points);
  property<face_handle, tube_face_source> source;
  if (sources_as_property) {
    source = mesh.template add_face_property<tube_face_source>(tube_source_property_name);
    source.vector().swap(out.sources);
  }
  std::size_t shells = out.linker.finish(mesh, num_points);
  if (shells == closed_linker::npos) {  // not closed: build says what is wrong
    std::vector<std::uint32_t> offsets, fv;
    out.linker.faces(offsets, fv);
    if (sources_as_property) source.vector().swap(out.sources);  // build drops face properties' values
    mesh.build(num_points, offsets, fv);
    if (sources_as_property) std::copy(out.sources.begin(), out.sources.end(), source.vector().begin());
    shells = connected_components(mesh).count;
  }
  if constexpr (!std::is_same_v<P, glm::dvec3>) {
    const std::span<P> pts = mesh.points();
    for (std::size_t i = 0; i < num_points; ++i) pts[i] = from_dvec3<P>(out.points[i]);
  }
  return shells;
}

}  // namespace detail::tubes

namespace detail::tubes {

/// How a repair meshes a junction beside a defect (merged_skeleton::careful; docs/tubes.md).
inline constexpr std::uint8_t careful_chord = 1, careful_unmerged = 2;

/// A skeleton whose too-close junction pairs were merged: for each of its nodes and edges the
/// caller's (the mesh's sources and messages are given in the caller's numbering), and how many
/// rounds of merging made it.
struct merged_skeleton {
  std::vector<std::uint32_t> node_of, edge_of;  ///< empty: the caller's skeleton itself
  std::vector<std::uint32_t> now_of;            ///< per caller's node, the node it is now in
  std::size_t nodes = 0, edges = 0;             ///< the caller's counts
  std::size_t merged = 0;                       ///< junctions merged into another's set, over all rounds
  int round = 0;
  /// Per caller's node, how to mesh it if it is a junction: | careful_chord (its rings not moved
  /// along a winding path), | careful_unmerged (not merged with a neighbour); empty: all as usual.
  std::vector<std::uint8_t> careful;
  /// Where the last round puts the caller's numbers of the junctions beside a fold or an
  /// intersection (the repair's next careful ones); null: not wanted.
  std::vector<std::pair<std::uint32_t, std::uint8_t>>* suspects = nullptr;
  std::span<const glm::dvec3> caller_pos;  ///< the caller's node positions, for the suspects
};

/// make_tubes on g, which is `from`'s merged skeleton when `from` is given. O(V + E).
template <Skeleton G>
if_satisfied_t<Skeleton<G>, tubes_result_for, G> make_tubes_of(const G& g, const tubes_options& options,
                                                               const merged_skeleton* from);

}  // namespace detail::tubes

template <Skeleton G>
detail::if_satisfied_t<Skeleton<G>, detail::tubes::tubes_result_for, G> make_tubes(
    const G& g, const tubes_options& options) {
  if (options.repair_rounds < 0)
    throw error(error_category::invalid_input, "make_tubes: repair_rounds must not be negative");
  const detail::stopwatch clock;
  const std::size_t nv = skeleton_traits<G>::num_nodes(g), ne = skeleton_traits<G>::num_edges(g);
  std::vector<std::pair<std::uint32_t, std::uint8_t>> suspects;
  detail::tubes::merged_skeleton state;  // the caller's skeleton as it is, to carry the careful set
  state.nodes = nv, state.edges = ne, state.suspects = &suspects;
  std::vector<glm::dvec3> positions(nv);
  for (std::size_t v = 0; v < nv; ++v)
    positions[v] = to_dvec3(skeleton_point_t<G>(skeleton_traits<G>::position(g, v)));
  state.caller_pos = detail::span_of(positions);
  auto best = detail::tubes::make_tubes_of(g, options, options.repair_rounds > 0 ? &state : nullptr);
  // A fold or an intersection is mostly the work of one junction's choice (a ring moved along a
  // winding path, a merge): the junctions beside it are meshed again the careful way, the best
  // mesh (fewest defects) kept. Each round costs one meshing and its checks.
  // A mesh whose check stopped at its budget, or whose genus is off, is never preferred: its count
  // of pairs proves nothing (an unfinished check is no pass).
  const auto defects = [&](const auto& r) {
    const bool unsure =
        (options.check_self_intersections && !r.self_intersections_checked) || r.genus != r.cycle_rank;
    return unsure ? std::numeric_limits<std::size_t>::max() : r.folded_edges + r.self_intersecting_face_pairs;
  };
  if (defects(best) > 0 && options.repair_rounds > 0) {
    state.careful.assign(nv, 0);
    int rounds = 0;
    while (rounds < options.repair_rounds && defects(best) > 0) {
      std::size_t added = 0;
      for (const auto& [v, how] : suspects)
        added += (state.careful[v] | how) != state.careful[v] ? 1 : 0, state.careful[v] |= how;
      if (added == 0) break;  // the same junctions again: the careful way is all there is
      suspects.clear();
      ++rounds;
      auto again = detail::tubes::make_tubes_of(g, options, &state);
      again.careful_nodes = state.careful.size() - static_cast<std::size_t>(std::count(
                                                       state.careful.begin(), state.careful.end(), 0));
      if (defects(again) < defects(best)) best = std::move(again);
    }
    best.repair_rounds = rounds;
    if (best.careful_nodes > 0)
      best.diagnostics.push_back(cellforge::detail::cat(
          std::to_string(best.careful_nodes),
          " skeleton nodes beside a fold or an intersection meshed again the careful way (rings kept off "
          "winding paths, no merging)"));
  }
  best.milliseconds = clock.ms();
  return best;
}

namespace detail::tubes {

template <Skeleton G>
if_satisfied_t<Skeleton<G>, tubes_result_for, G> make_tubes_of(const G& g, const tubes_options& options,
                                                               const merged_skeleton* from) {
  namespace dt = detail::tubes;
  using P = skeleton_point_t<G>;
  using T = skeleton_traits<G>;
  const detail::stopwatch t_start;
  if (options.sides < 3 || options.sides > 1024)
    throw error(error_category::invalid_input, "make_tubes: sides must be between 3 and 1024");
  if (!(options.cap_separation > 0 && options.cap_separation < 1))
    throw error(error_category::invalid_input,
                "make_tubes: cap_separation must lie strictly between 0 and 1");
  // The caller's own skeleton (first or careful meshing), not a merged one.
  const bool callers = from == nullptr || from->node_of.empty();
  const auto caller_node = [&](std::uint32_t v) { return callers ? v : from->node_of[v]; };
  const auto caller_edge = [&](std::uint32_t j) { return callers ? j : from->edge_of[j]; };
  if (callers && !options.node_ids.empty() && options.node_ids.size() != T::num_nodes(g))
    throw error(error_category::invalid_input,
                cellforge::detail::cat("make_tubes: node_ids has ", std::to_string(options.node_ids.size()),
                                       " names for ", std::to_string(T::num_nodes(g)), " nodes"));
  if (const skeleton_validation v = validate(g); !v.ok()) {
    // check_skeleton's sentence, and the sample ids of the nodes it names when the caller has them.
    std::string message = cellforge::detail::cat("check_skeleton: ", v.message), named;
    std::vector<std::size_t> nodes;
    if (v.defect == skeleton_defect::coincident_nodes) nodes = {v.other, v.node};
    if (v.defect == skeleton_defect::duplicate_edge) {
      const auto ab = T::endpoints(g, v.edge);
      nodes = {ab[0], ab[1]};
    }
    if (v.defect == skeleton_defect::bad_radius || v.defect == skeleton_defect::bad_position ||
        v.defect == skeleton_defect::self_loop)
      nodes = {v.node};
    for (const std::size_t i : nodes)
      if (callers && i < options.node_ids.size())
        named += (named.empty() ? "" : ", ") + (cellforge::detail::cat("node ", std::to_string(i))) +
                 " is sample " + std::to_string(options.node_ids[i]);
    if (!named.empty()) message += cellforge::detail::cat(" (", named, ")");
    throw error(error_category::invalid_input, message);
  }
  constexpr int merge_rounds = 8;  // junction merging rounds; then what still lacks room is shrunk
  const std::uint32_t n = options.sides;
  const std::size_t nv = T::num_nodes(g), ne = T::num_edges(g);
  std::vector<glm::dvec3> pos(nv);
  std::vector<double> rad(nv);
  std::vector<std::array<std::uint32_t, 2>> edges(ne);
  for (std::size_t i = 0; i < nv; ++i) {
    pos[i] = to_dvec3(P(T::position(g, i)));
    rad[i] = static_cast<double>(T::radius(g, i));
  }
  {  // rings, areas and the checks square coordinates: 1e300 would read as a path turning back
    bounding_box box;
    for (std::size_t i = 0; i < nv; ++i) box.add(pos[i] - rad[i]), box.add(pos[i] + rad[i]);
    check_double_range(box, "make_tubes");
    // A ring of radius r about a node at coordinate x has only r / ulp(x) doubles across it: below
    // 1e-9 of the coordinates (2^23 steps) its points collapse and the hull reads NaN directions.
    const double span =
        std::max({std::abs(box.min.x), std::abs(box.min.y), std::abs(box.min.z), std::abs(box.max.x),
                  std::abs(box.max.y), std::abs(box.max.z), box.diagonal()});
    for (std::size_t i = 0; i < nv; ++i)
      if (rad[i] < 1e-9 * span) {
        const std::uint32_t v = caller_node(static_cast<std::uint32_t>(i));
        char text[96];
        std::snprintf(text, sizeof text,
                      " has radius %.6g, below 1e-9 of the skeleton's coordinates (up to %.6g)", rad[i],
                      span);
        throw error(error_category::invalid_input,
                    cellforge::detail::cat(
                        "make_tubes: ",
                        options.node_ids.empty()
                            ? cellforge::detail::cat("node ", std::to_string(v))
                            : cellforge::detail::cat("sample ", std::to_string(options.node_ids[v])),
                        text, ": too thin to mesh in double precision"));
      }
  }
  for (std::size_t j = 0; j < ne; ++j) {
    const auto ab = T::endpoints(g, j);
    edges[j] = {static_cast<std::uint32_t>(ab[0]), static_cast<std::uint32_t>(ab[1])};
  }
  tubes_result<P> res;

  // Sharp bends of degree-2 nodes become junctions (§V.D).
  std::vector<std::uint32_t> degree(nv, 0);
  std::vector<std::array<std::uint32_t, 2>> nbr(nv, {tube_node::none, tube_node::none});
  for (const auto& e : edges)
    for (int k = 0; k < 2; ++k) {
      const std::uint32_t v = e[k], w = e[1 - k];
      if (degree[v] < 2) nbr[v][degree[v]] = w;
      ++degree[v];
    }
  std::vector<std::uint8_t> bend(nv, 0);
  const double bend_cos = std::cos(options.bend_limit_degrees * std::numbers::pi / 180);
  // Once merging is over, a bend beside a branch point stays a mitre (below 90°): as a junction
  // it could no longer merge with it, and the shrunk ring between them flared into a fold.
  const bool merging_over = from != nullptr && from->round >= merge_rounds;
  for (std::size_t v = 0; v < nv; ++v)
    if (degree[v] == 2) {
      const glm::dvec3 a = glm::normalize(pos[v] - pos[nbr[v][0]]),
                       b = glm::normalize(pos[nbr[v][1]] - pos[v]);
      const bool beside_branch = degree[nbr[v][0]] > 2 || degree[nbr[v][1]] > 2;
      if (glm::dot(a, b) < bend_cos && !(merging_over && beside_branch && glm::dot(a, b) > 0))
        bend[v] = 1, ++res.bend_junctions;
    }
  res.construct = make_tube_construct(nv, edges, bend);
  const tube_construct& tc = res.construct;
  res.cycle_rank = tc.cycle_rank;
  res.construct_ms = t_start.ms();

  const auto node_pos = [&](std::uint32_t c) {
    const tube_node& t = tc.nodes[c];
    if (t.skeleton_node != tube_node::none) return pos[t.skeleton_node];
    return 0.5 * (pos[edges[t.split_edge][0]] + pos[edges[t.split_edge][1]]);
  };
  const auto node_radius = [&](std::uint32_t c) {
    const tube_node& t = tc.nodes[c];
    if (t.skeleton_node != tube_node::none) return rad[t.skeleton_node];
    return 0.5 * (rad[edges[t.split_edge][0]] + rad[edges[t.split_edge][1]]);
  };
  const auto is_junction = [&](std::uint32_t c) { return tc.nodes[c].kind == tube_node_kind::junction; };
  const auto careful = [&](std::uint32_t c, std::uint8_t how) {  // a junction to mesh the careful way
    const std::uint32_t v = tc.nodes[c].skeleton_node;
    return from != nullptr && !from->careful.empty() && v != tube_node::none &&
           (from->careful[caller_node(v)] & how) != 0;
  };
  const auto node_name = [&](std::uint32_t v) {  // in the caller's numbering
    v = caller_node(v);
    return options.node_ids.empty() ? cellforge::detail::cat("node ", std::to_string(v))
                                    : cellforge::detail::cat("sample ", std::to_string(options.node_ids[v]));
  };
  const auto skeleton_name = [&](std::uint32_t c) {
    const tube_node& t = tc.nodes[c];
    return t.skeleton_node != tube_node::none
               ? node_name(t.skeleton_node)
               : cellforge::detail::cat("the midpoint of edge ", std::to_string(t.split_edge));
  };

  // Branch meshes: one ring per path end at a junction.
  const detail::stopwatch t_junctions;
  dt::buffer out;
  struct end_ring {
    dt::junction_ring ring;
    glm::dvec3 centre;
    std::uint32_t first_vertex = 0;
  };
  // The ring at the start / end (slot 2p / 2p + 1) of path p, when that end is a junction, from
  // when the junction is built until the path is: a slot names its ring in a pool whose freed
  // rings are taken again (a path is meshed once both its junctions are, so few wait at once).
  std::vector<std::uint32_t> end_of_slot(2 * tc.paths.size(), tube_node::none), free_ends;
  std::vector<end_ring> ends;
  const auto keep_end = [&](std::uint32_t slot, const end_ring& e) {
    if (free_ends.empty()) {
      end_of_slot[slot] = static_cast<std::uint32_t>(ends.size());
      ends.push_back(e);
    } else {
      end_of_slot[slot] = free_ends.back();
      free_ends.pop_back();
      ends[end_of_slot[slot]] = e;
    }
  };
  const dt::junction_ends ends_by_junction = dt::path_ends_at_junctions(tc);
  const auto at_junction = [&](std::uint32_t v) { return ends_by_junction.at(v); };
  {  // Room for every ring's vertices and every face, so that the buffer grows once.
    std::size_t stations = 0, ends_at_junctions = 0;
    for (const tube_path& path : tc.paths) stations += path.nodes.size();
    for (const std::uint32_t b : tc.junctions) ends_at_junctions += at_junction(b).size();
    // Huge-page hints: these arrays are fresh every call, and 4 KB faults cost as much as filling them.
    detail::reserve_large(out.points, n * (stations + ends_at_junctions));
    detail::reserve_large(out.sources, n * stations + 2 * n * ends_at_junctions);
    out.linker.reserve(n * (stations + ends_at_junctions), 4 * n * stations + 6 * n * ends_at_junctions,
                       n * stations + 2 * n * ends_at_junctions);
  }
  // The faces are closed and oriented by construction: linked as they come, while their twins
  // are near (build, which reports what is wrong, only if they are not).
  if (options.subdivision_levels < 0 || options.subdivision_levels > 8)
    throw error(error_category::invalid_input, "make_tubes: subdivision_levels must be between 0 and 8");
  out.triangulate = options.subdivision_levels > 0;  // Loop subdivision takes triangles
  // Node paths: each meshed as soon as the junctions at its ends are (below), so that its first
  // ring's corners meet their twins at the junction while those are still in cache.
  out.section_ratio.assign(ne, std::numeric_limits<double>::infinity());
  std::vector<dt::station> stations;
  dt::path_scratch path_buffers;
  std::vector<std::uint8_t> path_done(tc.paths.size(), 0), junction_done(tc.nodes.size(), 0);
  std::vector<std::uint32_t> station_node, segment_edge;  // per station / segment, after merging
  // Per path end at a junction (slot 2p / 2p + 1): the path nodes its ring moved past.
  std::vector<std::uint32_t> taken_of_slot(2 * tc.paths.size(), 0);
  const auto mesh_path = [&](std::uint32_t p) {
    path_done[p] = 1;
    const tube_path& path = tc.paths[p];
    const std::size_t m = path.nodes.size();
    stations.assign(m, {});
    station_node.assign(path.nodes.begin(), path.nodes.end());
    segment_edge.assign(path.edges.begin(), path.edges.end());
    for (std::size_t i = 0; i < m; ++i) {
      dt::station& s = stations[i];
      const std::uint32_t c = path.nodes[i];
      const bool start_ring = i == 0 && !path.closed && is_junction(c);
      const bool at_end_ring = i == m - 1 && !path.closed && is_junction(c);
      if (start_ring || at_end_ring) {
        const std::uint32_t slot = 2 * p + (start_ring ? 0 : 1);
        const end_ring& e = ends[end_of_slot[slot]];
        free_ends.push_back(end_of_slot[slot]);  // read now, before the next keep_end
        s.fixed = true;
        s.reversed = at_end_ring;
        s.centre = e.centre + e.ring.distance * e.ring.direction;
        s.tangent = at_end_ring ? -e.ring.direction : e.ring.direction;
        s.radius = e.ring.radius;
        s.first_vertex = e.first_vertex;
        s.fixed_first = e.ring.first;
        continue;
      }
      s.centre = node_pos(c);
      s.radius = node_radius(c);
    }
    // Nodes a junction's ring moved past are inside its surface: no station (the end's first,
    // at the higher indices, so that the start's indices hold).
    for (std::uint32_t end = 2; end-- > 0;) {
      const std::uint32_t taken = path.closed ? 0 : taken_of_slot[2 * p + end];
      if (taken == 0) continue;
      const std::size_t k = stations.size(), from = end == 0 ? 1 : k - 1 - taken;
      const std::size_t segment_from = end == 0 ? 0 : k - 1 - taken;
      stations.erase(stations.begin() + static_cast<std::ptrdiff_t>(from),
                     stations.begin() + static_cast<std::ptrdiff_t>(from + taken));
      station_node.erase(station_node.begin() + static_cast<std::ptrdiff_t>(from),
                         station_node.begin() + static_cast<std::ptrdiff_t>(from + taken));
      segment_edge.erase(segment_edge.begin() + static_cast<std::ptrdiff_t>(segment_from),
                         segment_edge.begin() + static_cast<std::ptrdiff_t>(segment_from + taken));
    }
    // The directions in and out of station i (zero at an open path's ends); a path that turns
    // back on itself has no mitre.
    const auto in_out = [&](std::size_t i) {
      const std::size_t k = stations.size();
      const bool has_prev = i > 0 || path.closed, has_next = i + 1 < k || path.closed;
      const glm::dvec3 c = stations[i].centre;
      const glm::dvec3 din =
          has_prev ? dt::safe_unit(c - stations[i == 0 ? k - 1 : i - 1].centre) : glm::dvec3(0.0);
      const glm::dvec3 dout =
          has_next ? dt::safe_unit(stations[i + 1 == k ? 0 : i + 1].centre - c) : glm::dvec3(0.0);
      if (!(glm::length(din + dout) > 1e-9))
        throw error(error_category::invalid_input,
                    skeleton_name(station_node[i]) +
                        ": the path turns back on itself there (raise bend_limit_degrees' "
                        "junction handling: it must stay below 180)");
      return std::array<glm::dvec3, 2>{din, dout};
    };
    // A mitred ring reaches r tan(β/2) along the path on either side of its node (β the turn):
    // two nodes closer than their reaches would fold the quads between them back onto the
    // wall before, so such a pair is merged (an end keeps its place, two inner nodes meet
    // at their midpoint), until none is left. Each merge removes a station.
    const auto is_end = [&](std::size_t i) {
      return stations[i].fixed || (!path.closed && (i == 0 || i + 1 == stations.size()));
    };
    const auto reach_of = [&](std::size_t i) {
      if (is_end(i)) return 0.0;
      const auto [din, dout] = in_out(i);
      const double c = std::clamp(glm::dot(din, dout), -1.0, 1.0);
      return stations[i].radius * std::sqrt((1 - c) / (1 + c));  // r tan(β/2)
    };
    // One scan, stepping back after a merge (it changes the turns of the two neighbours, and
    // so the pairs they are in): O(stations); scanned again until a scan merges nothing.
    for (bool again = true; again;) {
      again = false;
      for (std::size_t i = 0; i < (path.closed ? stations.size() : stations.size() - 1);) {
        const std::size_t k = stations.size(), j = i + 1 == k ? 0 : i + 1;
        if (!(reach_of(i) + reach_of(j) >= dt::safe_length(stations[j].centre - stations[i].centre))) {
          ++i;
          continue;
        }
        if (path.closed && k <= 3)
          throw error(error_category::invalid_input,
                      skeleton_name(station_node[i]) +
                          ": the ring of nodes through it is too small for its "
                          "radius (its nodes are closer than its turns allow)");
        // An end keeps its place; two inner nodes meet at their midpoint (in station 0 of a
        // ring, whose segment must stay first).
        const bool i_end = is_end(i), j_end = is_end(j);
        if (i_end && j_end) {  // two ends reach nothing: only coincident ones, refused before
          ++i;
          continue;
        }
        std::size_t drop = i_end ? j : (j_end || j == 0) ? i : j;
        // The station next to a junction's ring stays on the ring's axis (the junction chose
        // it so): moved off it, the tube would leave the ring askew and fold against the
        // junction's surface. Its partner goes instead, or, when the ring would take it, the
        // station beyond it (which straightens its turn), while there is one.
        const bool start_pin = !path.closed && stations[0].fixed,
                   end_pin = !path.closed && stations[k - 1].fixed;
        const bool pin_i = start_pin && i == 1, pin_j = end_pin && j + 2 == k;
        bool moved = !i_end && !j_end;
        if (moved && (pin_i || pin_j)) {
          drop = pin_i ? j : i;
          moved = false;
        } else if (i_end && start_pin && i == 0 && k > 3 && !is_end(2)) {
          drop = 2, i = 1;
        } else if (j_end && end_pin && j + 1 == k && k > 3 && !is_end(k - 3)) {
          drop = k - 3, i = k - 3;
        }
        if (moved) {
          dt::station& keep = stations[drop == i ? j : i];
          keep.centre = 0.5 * (stations[i].centre + stations[j].centre);
          keep.radius = 0.5 * (stations[i].radius + stations[j].radius);
        }
        // The segment between the two goes; the other segments keep their edges.
        stations.erase(stations.begin() + static_cast<std::ptrdiff_t>(drop));
        station_node.erase(station_node.begin() + static_cast<std::ptrdiff_t>(drop));
        segment_edge.erase(segment_edge.begin() + static_cast<std::ptrdiff_t>(i));
        ++res.merged_nodes;
        again = true;
        i = i >= 2 ? i - 2 : 0;
      }
    }
    for (std::size_t i = 0; i < stations.size(); ++i) {
      dt::station& s = stations[i];
      if (s.fixed) continue;
      const auto [din, dout] = in_out(i);
      s.tangent = glm::normalize(din + dout);
      if (glm::dot(din, din) > 0 && glm::dot(dout, dout) > 0) {
        const double cos_turn = std::clamp(glm::dot(din, dout), -1.0, 1.0);
        const glm::dvec3 side = dout - din;
        if (glm::length(side) > 1e-12 && cos_turn < 1.0) {
          s.bend = glm::normalize(side - glm::dot(side, s.tangent) * s.tangent);
          s.widen = 1.0 / std::cos(0.5 * std::acos(cos_turn));  // a mitre keeps the tube's width
        }
      }
    }
    // The stations at junction rings replace the junction nodes themselves.
    const bool cap_start = !path.closed && !is_junction(path.nodes.front());
    const bool cap_end = !path.closed && !is_junction(path.nodes.back());
    dt::build_path(out, detail::span_of(stations), path.closed, n, options.alignment,
                   detail::span_of(segment_edge), cap_start, tc.nodes[path.nodes.front()].skeleton_node,
                   cap_end, tc.nodes[path.nodes.back()].skeleton_node, &path_buffers);
    ++res.paths;
    res.closed_paths += path.closed ? 1 : 0;
    res.end_caps += (cap_start ? 1 : 0) + (cap_end ? 1 : 0);
  };
  const auto ready = [&](std::uint32_t c) { return !is_junction(c) || junction_done[c] != 0; };
  double paths_seconds = 0;  // of the paths meshed between junctions
  std::vector<dt::junction_ring> rings;
  std::vector<double> own_distance;  // each ring's distance before the 60° rule moved it out
  std::vector<std::uint32_t> ring_edges, first_vertex, target, last;
  std::string first_shrunk;  // for the diagnostic
  const std::vector<glm::dvec3> extra_candidates = dt::sphere_directions(options.junction_extra_points);
  std::vector<glm::dvec3> extra;
  dt::junction_scratch scratch;
  // Junctions along a Z-curve: a path is meshed once the junctions at both its ends are, and its
  // end rings link to twins made there. In node order a lattice's neighbour along z was built a
  // whole layer of junctions before (at 46^3, ~20 MB of output back, out of cache); along the
  // curve it is nearly always a few junctions before.
  const std::vector<std::uint32_t> junction_order =
      detail::morton_order(detail::span_of(tc.junctions), node_pos);
  std::uint32_t building = 0;  // the junction being built, for its messages
  const std::function<std::string()> junction_name = [&] { return skeleton_name(building); };
  std::vector<std::uint32_t> merge_paths;  // paths between junctions too short for their rings
  for (const std::uint32_t b : junction_order) {
    building = b;
    const glm::dvec3 c = node_pos(b);
    const double rb = node_radius(b);
    // Ring i points at node `target[i]` along its path (1: the path's first node). A ring
    // that must sit farther out than 0.95 of that node's distance to clear the other edges
    // moves past it to the next one (the nodes it passes are inside the junction's surface),
    // as far as `last[i]`: a free end stays, and a path between two junctions keeps a node
    // for each (the second built takes what the first left). A ring that still lacks room
    // keeps its cap on the sphere and moves in to 0.9 of its node's distance, narrower in
    // proportion: the hull is the same (it sees directions only), so the junction is as
    // embedded as before, and the tube widens to the node's ring over the last tenth.
    const std::span<const std::uint32_t> slots = at_junction(b);
    const std::size_t real = slots.size();
    target.assign(real, 1);
    last.assign(real, 1);
    const auto path_node = [&](std::uint32_t slot, std::uint32_t k) {
      const tube_path& path = tc.paths[slot / 2];
      return slot % 2 == 0 ? path.nodes[k] : path.nodes[path.nodes.size() - 1 - k];
    };
    for (std::size_t i = 0; i < real; ++i) {
      const tube_path& path = tc.paths[slots[i] / 2];
      const auto m = static_cast<std::uint32_t>(path.nodes.size());
      const std::uint32_t other = path_node(slots[i] ^ 1u, 0);
      last[i] = !is_junction(other)         ? m - 1
                : junction_done[other] != 0 ? m - 2 - taken_of_slot[slots[i] ^ 1u]
                                            : (m - 1) / 2;
      last[i] = std::max<std::uint32_t>(last[i], 1);
    }
    const auto set_up_rings = [&] {
      rings.clear();
      ring_edges.clear();
      for (std::size_t i = 0; i < real; ++i) {
        const tube_path& path = tc.paths[slots[i] / 2];
        const std::uint32_t q = path_node(slots[i], target[i]);
        dt::junction_ring r;
        r.direction = glm::normalize(node_pos(q) - c);
        r.radius = node_radius(q);
        r.first = dt::any_perpendicular(r.direction);
        rings.push_back(r);
        // The edge into the target node: its faces are the tube from the ring on.
        const std::size_t segment = slots[i] % 2 == 0 ? target[i] - 1 : path.edges.size() - target[i];
        ring_edges.push_back(path.edges[segment]);
      }
      // The junction is star-shaped about its centre only if the centre lies inside the hull of
      // its directions: a junction whose edges all leave into one half-space (a bend; a root whose
      // branches all go one way) gets a virtual section on the empty side (§V.D method 1).
      glm::dvec3 sum(0.0);
      for (std::size_t i = 0; i < real; ++i) sum += rings[i].direction;
      bool one_side = glm::length(sum) > 1e-9;
      for (std::size_t i = 0; one_side && i < real; ++i)
        one_side = glm::dot(rings[i].direction, glm::normalize(sum)) > 1e-9;
      if (one_side && (real >= 3 || options.bend_virtual_section)) {
        dt::junction_ring r;
        r.direction = -glm::normalize(sum);
        r.radius = rb;
        r.first = dt::any_perpendicular(r.direction);
        r.is_virtual = true;
        rings.push_back(r);
        ring_edges.push_back(tube_node::none);
      }
      dt::place_rings(detail::span_of(rings), rb, options.cap_separation);
      own_distance.clear();
      for (const dt::junction_ring& r : rings) own_distance.push_back(r.distance);
      // A ring behind a neighbour's within 60° (whose centre lies ahead of its plane) would leave
      // a narrow crevice between its tube and the hull's flank towards the neighbour, faces
      // nearly back to back: it moves out along its axis to the neighbour's (its cap narrows).
      for (int pass = 0; pass < 2; ++pass)
        for (std::size_t i = 0; i < real; ++i)
          for (std::size_t j = 0; j < real; ++j) {
            if (j == i) continue;
            const double cosine = glm::dot(rings[i].direction, rings[j].direction);
            if (cosine > 0.5) rings[i].distance = std::max(rings[i].distance, rings[j].distance * cosine);
          }
    };
    const auto reach = [&](std::size_t i) {
      return glm::length(node_pos(path_node(slots[i], target[i])) - c);
    };
    // How far the mitred ring of ring i's node reaches back towards the junction (r tan(β/2),
    // β its turn; 0 at the path's end): the ring must clear it, or the path would merge the
    // node into the ring and leave it at an angle, folding against the junction.
    const auto mitre = [&](std::size_t i) {
      const tube_path& path = tc.paths[slots[i] / 2];
      if (target[i] + 1 >= path.nodes.size()) return 0.0;
      const std::uint32_t q = path_node(slots[i], target[i]), next = path_node(slots[i], target[i] + 1);
      const glm::dvec3 din = dt::safe_unit(node_pos(q) - c),
                       dout = dt::safe_unit(node_pos(next) - node_pos(q));
      const double cosine = std::clamp(glm::dot(din, dout), -1.0, 1.0);
      return cosine > -0.9 ? node_radius(q) * std::sqrt((1 - cosine) / (1 + cosine)) : reach(i);
    };
    const auto lacks_room = [&](std::size_t i) { return !(rings[i].distance + mitre(i) < 0.95 * reach(i)); };
    // Lacks room at its own distance, not only because a neighbour within 60° moved it out.
    const auto lacks_own_room = [&](std::size_t i) {
      return !(own_distance[i] + mitre(i) < 0.95 * reach(i));
    };
    // A careful junction's ring moved on to node k replaces the path up to k by the chord from
    // the centre only while the nodes it passes lie within their radius of that chord: a winding
    // path's chord leaves its tube and can cut through a neighbour's (the ring narrows instead).
    const bool careful_here = careful(b, careful_chord);
    const auto chord_holds = [&](std::size_t i, std::uint32_t k) {
      if (!careful_here) return true;
      const glm::dvec3 chord = node_pos(path_node(slots[i], k)) - c;
      const double square = glm::dot(chord, chord);
      for (std::uint32_t j = 1; j < k; ++j) {
        const std::uint32_t q = path_node(slots[i], j);
        const glm::dvec3 d = node_pos(q) - c;
        const double t = square > 0 ? std::clamp(glm::dot(d, chord) / square, 0.0, 1.0) : 0.0;
        if (!(glm::length(d - t * chord) <= node_radius(q))) return false;
      }
      return true;
    };
    // Each round moves at least one ring on by a node: at most the paths' inner nodes in all.
    for (bool moved = true; moved;) {
      set_up_rings();
      moved = false;
      for (std::size_t i = 0; i < real; ++i)
        while (lacks_room(i) && target[i] < last[i] && chord_holds(i, target[i] + 1))
          ++target[i], moved = true;
    }
    res.virtual_sections += rings.size() > real ? 1 : 0;
    // A ring that lacks room only because the 60° rule moved it out behind a neighbour waits while
    // a ring here lacks room of its own: merging that one's junction first changes the neighbour's
    // place. Merging every such ring's junction too made one junction swallow its neighbours round
    // after round (near-parallel branches of the merged junction pushing all rings out).
    bool own_shortage = false;
    for (std::size_t i = 0; i < real; ++i) {
      const std::uint32_t other = path_node(slots[i] ^ 1u, 0);
      own_shortage = own_shortage || (lacks_own_room(i) && is_junction(other) && other != b);
    }
    for (std::size_t i = 0; i < real; ++i) {
      taken_of_slot[slots[i]] = target[i] - 1;
      res.absorbed_nodes += target[i] - 1;
      const double length = reach(i);
      if (!lacks_room(i)) continue;
      if (!(length > 0 && std::isfinite(rings[i].distance)))
        throw error(error_category::invalid_input,
                    skeleton_name(b) + ": the cross-section of edge " + std::to_string(ring_edges[i]) +
                        " cannot be placed (radius " + std::to_string(rings[i].radius) + ", distance " +
                        std::to_string(rings[i].distance) + ")");
      const std::uint32_t other = path_node(slots[i] ^ 1u, 0);
      const bool free_end = !is_junction(other);
      if (free_end) {
        // The free end itself is too near: the ring moves in to it, narrower, and its cap
        // closes the branch there (a stub; the cap's disc is star-shaped about the centre too).
        ++taken_of_slot[slots[i]];
        ++res.absorbed_nodes;
        const double scale = std::min(1.0, length / rings[i].distance);
        rings[i].distance *= scale;
        rings[i].radius *= scale;
        if (scale < 1 && res.shrunk_sections++ == 0)
          first_shrunk = skeleton_name(b) + ", edge " + std::to_string(ring_edges[i]) + ", to " +
                         std::to_string(static_cast<int>(std::lround(100 * scale))) + " % of its radius";
        continue;
      }
      // Between two junctions (not one path from a junction back to itself): merge them.
      const tube_path& between = tc.paths[slots[i] / 2];
      if (other != b && (from == nullptr || from->round < merge_rounds) &&
          std::none_of(between.nodes.begin(), between.nodes.end(),
                       [&](std::uint32_t q) { return careful(q, careful_unmerged); }) &&
          (!own_shortage || lacks_own_room(i)))
        merge_paths.push_back(slots[i] / 2);
      if (!lacks_own_room(i)) {  // short of room only where the 60° rule put it: back, not narrowed
        rings[i].distance = own_distance[i];
        continue;
      }
      const double scale = std::max(0.9 * (length - mitre(i)), 0.5 * length) / rings[i].distance;
      rings[i].distance *= scale;
      rings[i].radius *= scale;
      if (res.shrunk_sections++ == 0)
        first_shrunk = skeleton_name(b) + ", edge " + std::to_string(ring_edges[i]) + ", to " +
                       std::to_string(static_cast<int>(std::lround(100 * scale))) + " % of its radius";
    }
    if (!merge_paths.empty()) {  // the skeleton is meshed again after merging: plan, do not build
      junction_done[b] = 1;
      continue;
    }
    extra.clear();
    for (const glm::dvec3& d : extra_candidates) {  // method 3: clear of every cap, with a margin
      bool clear = true;
      for (const dt::junction_ring& r : rings)
        clear = clear && glm::dot(d, r.direction) < std::cos(1.25 * std::atan2(r.radius, r.distance));
      if (clear) extra.push_back(d);
    }
    dt::build_junction(out, c, detail::span_of(rings), n,
                       {tube_face_kind::junction, tc.nodes[b].skeleton_node}, detail::span_of(ring_edges),
                       first_vertex, scratch, detail::span_of(extra), rb, &junction_name);
    for (std::size_t i = 0; i < real; ++i) keep_end(slots[i], {rings[i], c, first_vertex[i]});
    ++res.junctions;
    junction_done[b] = 1;
    const detail::stopwatch t_these_paths;
    for (const std::uint32_t slot : at_junction(b)) {
      const tube_path& path = tc.paths[slot / 2];
      if (!path_done[slot / 2] && ready(path.nodes.front()) && ready(path.nodes.back())) mesh_path(slot / 2);
    }
    paths_seconds += t_these_paths.seconds();
  }
  res.reused_junction_hulls = scratch.reused;
  res.junctions_ms = t_junctions.ms() - 1e3 * paths_seconds;
  if (!merge_paths.empty()) {
    // Two junctions too close for their rings become one, at the mean of their centres with
    // the larger radius, and the skeleton is meshed again (at most three rounds; what is left
    // then is shrunk). A path that closes a cycle is not merged (the genus would drop), nor
    // is anything when merging would join two nodes twice.
    // Junctions after the first path to merge were planned, not built: when no merge can be
    // made, the skeleton is meshed again as it is, with merging off.
    for (int attempt = 0; attempt < 2; ++attempt) {
      std::vector<std::uint32_t> set(nv);
      for (std::uint32_t v = 0; v < nv; ++v) set[v] = v;
      const auto find = [&](std::uint32_t v) {
        while (set[v] != v) v = set[v] = set[set[v]];
        return v;
      };
      std::size_t merged = 0, junctions_merged = 0;  // nodes joined to another's set; of them junctions
      for (const std::uint32_t p :
           attempt == 0 ? detail::span_of(merge_paths) : std::span<const std::uint32_t>{}) {
        const tube_path& path = tc.paths[p];
        const std::uint32_t a = find(tc.nodes[path.nodes.front()].skeleton_node);
        if (a == find(tc.nodes[path.nodes.back()].skeleton_node)) continue;
        for (const std::uint32_t c : path.nodes) {
          const std::uint32_t v = tc.nodes[c].skeleton_node;
          if (v == tube_node::none || find(v) == a) continue;
          set[find(v)] = a;
          ++merged;
          junctions_merged += is_junction(c) ? 1 : 0;
        }
      }
      merged_skeleton next;
      next.nodes = from != nullptr && !callers ? from->nodes : nv;
      next.edges = from != nullptr && !callers ? from->edges : ne;
      if (from != nullptr)
        next.careful = from->careful, next.suspects = from->suspects, next.caller_pos = from->caller_pos;
      next.merged = junctions_merged + (from != nullptr ? from->merged : 0);
      next.round = attempt == 1 ? merge_rounds : from != nullptr ? from->round + 1 : 1;
      std::vector<std::uint32_t> new_id(nv, tube_node::none), junctions_in(nv, 0);
      std::vector<glm::dvec3> centre(nv, glm::dvec3(0.0));
      std::vector<double> radius(nv, 0.0);
      // A set's centre: the mean of its junctions weighted by r³ (a soma keeps its place when a
      // thin branch point beside it joins it; like branch points meet in the middle, where their
      // paths' directions stay apart); its radius the largest.
      std::vector<double> weight(nv, 0.0);
      for (std::uint32_t v = 0; v < nv; ++v) {
        const std::uint32_t root = find(v);
        radius[root] = std::max(radius[root], rad[v]);
        if (tc.nodes[v].kind != tube_node_kind::junction) continue;
        const double w = rad[v] / rad[root];  // relative, so that r³ cannot overflow
        centre[root] += (w * w * w) * pos[v], weight[root] += w * w * w, ++junctions_in[root];
      }
      skeleton<P> g2;
      for (std::uint32_t v = 0; v < nv; ++v) {
        const std::uint32_t root = find(v);
        if (new_id[root] != tube_node::none) continue;
        new_id[root] = static_cast<std::uint32_t>(g2.points.size());
        g2.points.push_back(from_dvec3<P>(junctions_in[root] > 0 ? centre[root] / weight[root] : pos[root]));
        g2.radii.push_back(radius[root]);
        next.node_of.push_back(caller_node(root));
      }
      for (std::uint32_t u = 0; u < next.nodes; ++u)
        next.now_of.push_back(new_id[find(callers ? u : from->now_of[u])]);
      std::vector<std::array<std::uint32_t, 2>> pairs;
      for (std::uint32_t j = 0; j < ne; ++j) {
        const std::uint32_t a = new_id[find(edges[j][0])], b = new_id[find(edges[j][1])];
        if (a == b) continue;
        g2.edges.push_back({a, b});
        next.edge_of.push_back(caller_edge(j));
        pairs.push_back({std::min(a, b), std::max(a, b)});
      }
      std::sort(pairs.begin(), pairs.end());
      if (attempt == 1 || (merged > 0 && std::adjacent_find(pairs.begin(), pairs.end()) == pairs.end() &&
                           validate(g2).ok())) {
        tubes_result<P> again = make_tubes_of(g2, options, &next);
        again.milliseconds = t_start.ms();
        return again;
      }
    }
  }

  // Paths not yet meshed: those with no junction at either end (free paths, rings).
  const detail::stopwatch t_paths;
  for (std::uint32_t p = 0; p < tc.paths.size(); ++p)
    if (!path_done[p]) mesh_path(p);
  // Isolated nodes: spheres.
  // One unit sphere, hulled once, placed and scaled at every isolated node.
  const std::vector<glm::dvec3> dirs = tc.isolated.empty()
                                           ? std::vector<glm::dvec3>{}
                                           : dt::sphere_directions(std::max<std::size_t>(12, n * n / 2));
  const detail::hull::result h =
      tc.isolated.empty() ? detail::hull::result{} : detail::hull::compute(detail::span_of(dirs), {});
  std::vector<std::uint32_t> id(dirs.size());
  for (const std::uint32_t v : tc.isolated) {
    for (std::size_t k = 0; k < h.vertices.size(); ++k)
      id[k] = out.add_point(pos[v] + rad[v] * dirs[h.vertices[k]]);
    for (std::size_t f = 0; f + 1 < h.face_offsets.size(); ++f) {
      std::uint32_t tri[3];
      for (std::size_t k = 0; k < 3; ++k) tri[k] = id[h.face_vertices[h.face_offsets[f] + k]];
      out.add_face(tri, {tube_face_kind::sphere, v});
    }
    ++res.spheres;
  }
  res.paths_ms = t_paths.ms() + 1e3 * paths_seconds;

  if (!callers) {  // sources and sections in the caller's numbering
    for (tube_face_source& f : out.sources)
      f.index = f.kind == tube_face_kind::extrusion ? from->edge_of[f.index] : from->node_of[f.index];
    std::vector<double> ratio(from->edges, std::numeric_limits<double>::infinity());
    for (std::size_t j = 0; j < ne; ++j) ratio[from->edge_of[j]] = out.section_ratio[j];
    out.section_ratio.swap(ratio);
    res.merged_junctions = from->merged;
  }
  // Corner angles of the faces as built (before any subdivision), taken by add_face.
  const double cos_lo = out.cos_lo, cos_hi = out.cos_hi;
  res.min_corner_deg = std::acos(std::clamp(cos_hi, -1.0, 1.0)) * 180 / std::numbers::pi;
  res.max_corner_deg = std::acos(std::clamp(cos_lo, -1.0, 1.0)) * 180 / std::numbers::pi;
  // The mesh, in the skeleton's point type.
  const detail::stopwatch t_mesh;
  surface_mesh<P> mesh;
  const int shift = 2 * options.subdivision_levels;
  const std::size_t shells = dt::take_mesh(out, mesh, shift == 0);
  res.mesh_ms = t_mesh.ms();
  if (options.subdivision_levels > 0) {
    const detail::stopwatch t_sub;
    loop_subdivide(mesh, {.levels = options.subdivision_levels});
    res.subdivision_ms = t_sub.ms();
    // Face 4f + k of a Loop level is a child of face f: a face's source is its ancestor's.
    auto source = mesh.template add_face_property<tube_face_source>(tube_source_property_name);
    for (const face_handle f : mesh.faces()) source[f] = out.sources[f.idx() >> shift];
  }
  res.min_section_ratio = std::numeric_limits<double>::infinity();
  for (double& q : out.section_ratio) {
    if (std::isinf(q))
      q = std::numeric_limits<double>::quiet_NaN();
    else
      res.min_section_ratio = std::min(res.min_section_ratio, q);
  }
  if (std::isinf(res.min_section_ratio)) res.min_section_ratio = std::numeric_limits<double>::quiet_NaN();
  if (mesh.num_faces() == 0)  // no corner was measured
    res.min_corner_deg = res.max_corner_deg = std::numeric_limits<double>::quiet_NaN();
  res.section_ratio = std::move(out.section_ratio);
  res.shells = shells;
  res.genus = (2 * static_cast<std::int64_t>(shells) - euler_characteristic(mesh)) / 2;
  res.mesh = std::move(mesh);
  const auto say = [&](std::size_t count, const std::string& what) {
    if (count > 0) res.diagnostics.push_back(std::to_string(count) + " " + what);
  };
  say(res.bend_junctions, "nodes of degree 2 turn by more than bend_limit_degrees: meshed as junctions");
  say(res.virtual_sections,
      "junctions have all their edges on one side: a virtual cross-section closes the other");
  say(tc.inserted_nodes, "nodes inserted between adjacent junctions (at the middle of their edge)");
  say(res.merged_nodes,
      "path nodes merged with a neighbour closer than their turns allow (the tube would fold there)");
  say(res.merged_junctions,
      "junctions merged into a neighbouring one (the path between them too short for their cross-sections)");
  say(res.absorbed_nodes,
      "path nodes lie inside a junction's surface (nearer it than its cross-section must sit): no ring of "
      "their own");
  if (res.shrunk_sections > 0)
    res.diagnostics.push_back(
        std::to_string(res.shrunk_sections) +
        " junction cross-sections shrunk to fit an edge too short for them (first: " + first_shrunk + ")");
  say(res.spheres, "isolated nodes meshed as spheres");
  // A fold is no intersection (the faces only touch), so it is looked for on its own: O(E).
  const fold_result folds = folded_edges(res.mesh);
  std::vector<face_handle> bad_faces;  // those of the folds and intersections, for a repair
  if (from != nullptr && from->suspects != nullptr)
    for (const edge_handle e : folds.edges)
      bad_faces.push_back(res.mesh.face(e, 0)), bad_faces.push_back(res.mesh.face(e, 1));
  res.folded_edges = folds.edges.size();
  if (res.folded_edges > 0)
    res.diagnostics.push_back(
        std::to_string(res.folded_edges) +
        " edges fold: the faces on either side point opposite ways (the mesh is not good)");
  if (options.check_self_intersections) {
    const self_intersection_result si = tube_self_intersections(res.mesh);
    res.self_intersecting_face_pairs = si.intersecting_face_pairs;
    res.self_intersections_checked = si.complete;
    res.check_ms = si.milliseconds;
    res.work = si.work;
    res.complete = si.complete;
    if (si.intersecting_face_pairs > 0)
      res.diagnostics.push_back(
          std::to_string(si.intersecting_face_pairs) +
          " face pairs intersect (tubes closer than their radii: the skeleton lacks clearance)");
    if (!si.complete) res.diagnostics.push_back("the self-intersection check stopped at its work budget");
    if (from != nullptr && from->suspects != nullptr)
      for (const auto& [f1, f2] : si.face_pairs) bad_faces.push_back(f1), bad_faces.push_back(f2);
  }
  if (from != nullptr && from->suspects != nullptr && !bad_faces.empty()) {
    // The junctions beside each defect, in the caller's numbering: a junction face's own; an
    // extrusion's or a cap's, those at the ends of its path. O(V + E), only for a defective mesh.
    const auto source = res.mesh.template get_face_property<tube_face_source>(tube_source_property_name);
    const std::size_t caller_nodes = callers ? nv : from->nodes;
    const auto now = [&](std::uint32_t u) { return callers ? u : from->now_of[u]; };
    std::vector<std::uint8_t> bad_edge(callers ? ne : from->edges, 0), bad_end(caller_nodes, 0),
        bad_now(nv, 0);
    // A merged junction's face: the node merged into it nearest the face (its merge is the one
    // undone; making every node of the set careful undid merges that were right, and folded).
    struct spot {
      std::uint32_t now;
      glm::dvec3 at;
      double distance;
      std::uint32_t nearest;
    };
    std::vector<spot> spots;
    for (const face_handle f : bad_faces) {
      const tube_face_source at = source[f];
      if (at.kind == tube_face_kind::junction && (callers || from->caller_pos.empty()))
        bad_now[now(at.index)] = careful_chord | careful_unmerged;
      if (at.kind == tube_face_kind::junction && !(callers || from->caller_pos.empty())) {
        glm::dvec3 centroid(0.0);
        double corners = 0;
        for (const vertex_handle v : res.mesh.vertices_around(f))
          centroid += to_dvec3(res.mesh.position(v)), ++corners;
        spots.push_back(
            {now(at.index), centroid / corners, std::numeric_limits<double>::infinity(), at.index});
      }
      if (at.kind == tube_face_kind::extrusion) bad_edge[at.index] = 1;
      if (at.kind == tube_face_kind::end_cap) bad_end[at.index] = 1;
    }
    std::sort(spots.begin(), spots.end(), [](const spot& a, const spot& b) { return a.now < b.now; });
    for (std::uint32_t u = 0; u < caller_nodes && !spots.empty(); ++u) {  // O(V log spots)
      auto it = std::lower_bound(spots.begin(), spots.end(), now(u),
                                 [](const spot& s, std::uint32_t t) { return s.now < t; });
      for (; it != spots.end() && it->now == now(u); ++it)
        if (const double d = glm::length(from->caller_pos[u] - it->at); d < it->distance)
          it->distance = d, it->nearest = u;
    }
    for (const spot& s : spots) from->suspects->emplace_back(s.nearest, careful_chord | careful_unmerged);
    for (const tube_path& path : tc.paths) {
      bool beside = false;
      for (const std::uint32_t j : path.edges) beside = beside || bad_edge[caller_edge(j)] != 0;
      for (const std::uint32_t c : {path.nodes.front(), path.nodes.back()}) {
        const std::uint32_t v = tc.nodes[c].skeleton_node;
        beside = beside || (v != tube_node::none && bad_end[caller_node(v)] != 0);
      }
      if (!beside) continue;
      for (const std::uint32_t c : {path.nodes.front(), path.nodes.back()})
        if (is_junction(c) && tc.nodes[c].skeleton_node != tube_node::none)
          bad_now[tc.nodes[c].skeleton_node] |= careful_chord;
    }
    // A merged junction's: every node merged into it.
    for (std::uint32_t u = 0; u < caller_nodes; ++u)
      if (bad_now[now(u)] != 0) from->suspects->emplace_back(u, bad_now[now(u)]);
  }
  if (res.genus != res.cycle_rank)
    res.diagnostics.push_back(cellforge::detail::cat("the mesh's genus ", std::to_string(res.genus),
                                                     " differs from the skeleton's cycle rank ",
                                                     std::to_string(res.cycle_rank)));
  res.milliseconds = t_start.ms();
  return res;
}

}  // namespace detail::tubes

template <Point3 P>
std::vector<std::uint32_t> tube_pieces(const surface_mesh<P>& mesh) {
  std::vector<std::uint32_t> piece;
  detail::reserve_large(piece, mesh.faces_size());
  piece.assign(mesh.faces_size(), 0);
  const auto source = mesh.template get_face_property<tube_face_source>(tube_source_property_name);
  if (!source) return piece;
  // Per kind, the piece of each index (sources index skeleton edges and nodes: O(F) of them).
  std::array<std::vector<std::uint32_t>, 4> of_kind;
  std::uint32_t next = 0;
  for (const face_handle f : mesh.faces()) {
    const tube_face_source s = source[f];
    const auto kind = static_cast<std::size_t>(s.kind);
    if (kind >= of_kind.size() || s.index >= mesh.faces_size()) {  // not a tube's source: its own piece
      piece[f.idx()] = next++;
      continue;
    }
    std::vector<std::uint32_t>& ids = of_kind[kind];
    if (ids.size() <= s.index) ids.resize(std::max<std::size_t>(s.index + 1, 2 * ids.size()), 0xFFFFFFFFu);
    if (ids[s.index] == 0xFFFFFFFFu) ids[s.index] = next++;
    piece[f.idx()] = ids[s.index];
  }
  return piece;
}

template <Point3 P>
self_intersection_result tube_self_intersections(const surface_mesh<P>& mesh,
                                                 const self_intersection_options& options) {
  if (!mesh.template get_face_property<tube_face_source>(tube_source_property_name))
    return self_intersections(mesh, options);
  const detail::stopwatch start;
  const std::vector<std::uint32_t> pieces = tube_pieces(mesh);
  self_intersection_result r = self_intersections_by_pieces(mesh, detail::span_of(pieces), options);
  r.milliseconds = start.ms();  // with the labelling
  return r;
}

}  // namespace cellforge
