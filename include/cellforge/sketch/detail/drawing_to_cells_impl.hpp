// SPDX-License-Identifier: MIT
#pragma once
// The engine of drawing_to_cells (included by sketch/drawing_to_cells.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/work_counter.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/sketch/detail/parallel.hpp"
#include "cellforge/sketch/drawing_to_cells.hpp"
#include "cellforge/sketch/face_finder.hpp"
#include "cellforge/sketch/inflation.hpp"
#include "cellforge/sketch/line_drawing.hpp"
#include "cellforge/sketch/tidy.hpp"
#include "cellforge/wireframe/wire_graph.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

namespace cellforge {

namespace detail::sketch {

/// Signed area of a junction cycle in the drawing. O(L).
template <class = void>
double loop_area(const std::vector<glm::dvec2>& p, const std::vector<std::uint32_t>& loop) {
  double a = 0;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const glm::dvec2 u = p[loop[k]], v = p[loop[(k + 1) % loop.size()]];
    a += u.x * v.y - u.y * v.x;
  }
  return 0.5 * a;
}

using face_set = std::vector<std::vector<std::vector<std::uint32_t>>>;

/// Newell normal and centroid of a loop in 3D. O(L).
template <class = void>
std::pair<glm::dvec3, glm::dvec3> loop_plane(const std::vector<glm::dvec3>& p,
                                             const std::vector<std::uint32_t>& loop) {
  const glm::dvec3 n = cellforge::detail::newell(loop, [&](std::uint32_t v) { return p[v]; });
  glm::dvec3 c{0.0};
  for (const std::uint32_t v : loop) c += p[v];
  return {n, c / static_cast<double>(loop.size())};
}

/// Groups face loops into faces with holes (each face: outer loop, then holes).
/// - Within one connected part of the drawing, a hole loop is a loop whose junctions, taken
///   out, split the part (a hole's boundary separates what is inside it from the rest; outer
///   loops of a polyhedron's faces do not); its face is the smallest loop of the part around
///   it in the drawing traversed the other way (in the face's plane a hole runs against the
///   outer loop, and a parallel view keeps that).
/// - A part drawn inside a loop of another part (a hole through a block: the hole's walls are
///   edges of their own, joined to the block by no edge) is inflated alone; a loop of it whose
///   plane is parallel to a loop of the outer part around it in the drawing is a hole of that
///   loop when it can be moved in depth onto its plane, and the reading and depth that put the
///   most such loops onto their planes win. The Necker reading of each part is tried.
/// - Inexact parts (read by least squares, or every part when `inexact_drawing`: a drawing
///   tidied from an inexact one) match within 5° and 3 % of the size, and may also be moved by
///   the affine map z → k z + a x + b y + c that puts two of their loops on two planes.
/// Loops with no face around them stay faces of their own. O(parts · inflation + H · F · L
/// + offers² · L).
template <class = void>
face_set group_faces(const faces::drawing_graph& g, const std::vector<std::vector<std::uint32_t>>& loops,
                     const inflation_options& inflation, std::vector<std::string>& diagnostics,
                     std::size_t& ambiguous, bool inexact_drawing = false) {
  const face_finder_options o;
  work_counter budget{0, 0, "drawing_to_cells"};
  faces::finder f(g, o, budget);
  const std::size_t n = loops.size(), nv = g.num_junctions();
  std::vector<double> area(n);
  std::vector<std::uint32_t> part(n);
  std::vector<std::vector<glm::dvec2>> poly(n);
  for (std::size_t i = 0; i < n; ++i) {
    area[i] = loop_area(g.p, loops[i]);
    part[i] = f.component[loops[i][0]];
    for (const auto v : loops[i]) poly[i].push_back(g.p[v]);
  }
  const auto inside_loop = [&](std::size_t h, std::size_t c) {
    if (std::abs(area[c]) <= std::abs(area[h])) return false;
    for (const auto v : loops[h])
      if (!cellforge::detail::point_in_polygon(poly[c], g.p[v])) return false;
    return true;
  };
  std::vector<std::size_t> owner(n, n);
  for (std::size_t h = 0; h < n; ++h) {
    if (loops[h].size() < 3 || !f.separating(loops[h])) continue;
    std::size_t best = n;
    for (std::size_t c = 0; c < n; ++c)
      if (c != h && part[c] == part[h] && area[c] * area[h] < 0 && inside_loop(h, c) &&
          (best == n || std::abs(area[c]) < std::abs(area[best])))
        best = c;
    if (best == n)
      diagnostics.push_back(cellforge::detail::cat(
          "loop ", std::to_string(h), " splits the drawing but lies in no face loop running the other way"));
    owner[h] = best;
  }
  const auto faces_of = [&](const std::vector<std::size_t>& own, auto&& keep) {
    face_set out;
    std::vector<std::size_t> index(n, n);
    for (std::size_t i = 0; i < n; ++i)
      if (own[i] == n && keep(i)) index[i] = out.size(), out.push_back({loops[i]});
    for (std::size_t h = 0; h < n; ++h)
      if (own[h] != n && keep(h) && index[own[h]] != n) out[index[own[h]]].push_back(loops[h]);
    return out;
  };
  const std::size_t parts = f.component_size.size();
  std::vector<char> has_loop(parts, 0);
  for (std::size_t i = 0; i < n; ++i) has_loop[part[i]] = 1;
  if (std::count(has_loop.begin(), has_loop.end(), 1) < 2)
    return faces_of(owner, [](std::size_t) { return true; });

  // Each part alone: its drawing, its faces, both readings (junction depths, global indices).
  struct part_reading {
    std::vector<std::vector<glm::dvec3>> readings;  // [reading][junction]; empty: not inflated
    std::vector<double> outward;                    // per reading: +1 when the loops' sense is outward
    double span = 0;                                // bounding-box area in the drawing
  };
  std::vector<part_reading> pr(parts);
  double size = 0;
  // A part read by least squares, or a drawing tidied from an inexact one (its parts read alone
  // are affine relatives of each other): planes match only roughly.
  bool inexact = inexact_drawing;
  for (std::uint32_t c = 0; c < parts; ++c) {
    if (!has_loop[c]) continue;
    line_drawing<glm::dvec2> sub;
    std::vector<std::uint32_t> local(nv, faces::none), global;
    for (std::uint32_t v = 0; v < nv; ++v)
      if (f.component[v] == c)
        local[v] = static_cast<std::uint32_t>(global.size()), global.push_back(v),
        sub.points.push_back(g.p[v]);
    for (std::uint32_t h = 0; h < g.num_half_edges(); h += 2)
      if (f.component[g.head[h]] == c) sub.edges.push_back({local[g.tail(h)], local[g.head[h]]});
    face_set sub_faces = faces_of(owner, [&](std::size_t i) { return part[i] == c; });
    for (auto& face : sub_faces)
      for (auto& loop : face)
        for (auto& v : loop) v = local[v];
    glm::dvec2 lo = sub.points[0], hi = sub.points[0];
    for (const auto& q : sub.points) lo = glm::min(lo, q), hi = glm::max(hi, q);
    pr[c].span = (hi.x - lo.x) * (hi.y - lo.y);
    size = std::max(size, glm::length(hi - lo));
    try {
      // An inexact (sketched) part has only flat exact readings: read it by least squares.
      const auto res = [&] {
        try {
          return inflate<glm::dvec3>(sub, sub_faces, inflation);
        } catch (const error& e) {
          if (e.category() != error_category::topology) throw;
          inflation_options ls = inflation;
          ls.least_squares = true;
          ls.direction_tolerance = std::max(ls.direction_tolerance, 4.0 * 3.141592653589793 / 180.0);
          ls.closure_tolerance = std::max(ls.closure_tolerance, 0.05);
          inexact = true;
          return inflate<glm::dvec3>(sub, sub_faces, ls);
        }
      }();
      for (const auto& reading : res.readings) {
        std::vector<glm::dvec3> pts(nv, glm::dvec3(0.0));
        for (std::size_t k = 0; k < global.size(); ++k) pts[global[k]] = reading.points[k];
        // The loops' sense is outward when the volume they bound is positive (divergence theorem).
        double volume = 0;
        for (std::size_t i = 0; i < n; ++i)
          if (part[i] == c)
            for (std::size_t k = 1; k + 1 < loops[i].size(); ++k)
              volume += glm::dot(pts[loops[i][0]], glm::cross(pts[loops[i][k]], pts[loops[i][k + 1]]));
        pr[c].outward.push_back(volume >= 0 ? 1.0 : -1.0);
        pr[c].readings.push_back(std::move(pts));
      }
    } catch (const error& e) {
      diagnostics.push_back(cellforge::detail::cat("part ", std::to_string(c),
                                                   " of the drawing cannot be inflated alone: ", e.what()));
    }
  }
  // Place the parts, largest first: the first as read, each next one by the reading and depth
  // that put most of its loops onto the planes of loops of placed parts around them.
  std::vector<std::uint32_t> order;
  for (std::uint32_t c = 0; c < parts; ++c)
    if (has_loop[c] && !pr[c].readings.empty()) order.push_back(c);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return pr[a].span > pr[b].span; });
  std::vector<glm::dvec3> placed(nv, glm::dvec3(0.0));
  std::vector<char> is_placed(parts, 0);
  std::vector<double> placed_outward(parts, 1.0);
  const double parallel = std::sin((inexact ? 5.0 : 0.5) * 3.141592653589793 / 180.0),
               loose = std::sin(25.0 * 3.141592653589793 / 180.0),
               depth_tolerance = (inexact ? 3e-2 : 1e-3) * size;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::uint32_t c = order[k];
    std::size_t best_votes = 0, best_reading = 0;
    int best_outside = -1;
    std::vector<std::pair<std::size_t, double>>
        candidates;  // (loops on planes, centre's depth after the move)
    double best_dz = 0, best_centre = 0;
    Eigen::Vector3d best_affine = Eigen::Vector3d::Zero();  // z += (k − 1) z + a x + b y besides best_dz
    std::vector<std::pair<std::size_t, std::size_t>> best_pairs;
    std::vector<std::optional<std::pair<glm::dvec3, glm::dvec3>>> plane(
        n);  // placed loops' planes, as needed
    for (std::size_t r = 0; r < pr[c].readings.size() && k > 0; ++r) {
      const auto& pts = pr[c].readings[r];
      // (dz, hole, outer, parallel within the tolerance: else only for an affine move)
      std::vector<std::tuple<double, std::size_t, std::size_t, bool>> offers;
      glm::dvec3 centre{0.0};
      std::size_t members = 0;
      for (std::uint32_t v = 0; v < nv; ++v)
        if (f.component[v] == c) centre += pts[v], ++members;
      centre /= static_cast<double>(std::max<std::size_t>(members, 1));
      for (std::size_t h = 0; h < n; ++h) {
        if (part[h] != c) continue;
        const auto [nh0, ch] = loop_plane(pts, loops[h]);
        const glm::dvec3 nh = pr[c].outward[r] * nh0;
        for (std::size_t q = 0; q < n; ++q) {
          if (!is_placed[part[q]] || !inside_loop(h, q)) continue;
          const auto [nq0, cq] = loop_plane(placed, loops[q]);
          const glm::dvec3 nq = placed_outward[part[q]] * nq0;
          const double across = glm::length(glm::cross(nh, nq)) / (glm::length(nh) * glm::length(nq));
          if (!(across <= (inexact ? loose : parallel)) || std::abs(nq.z) < 1e-12) continue;
          // Depth of q's plane at h's centroid, minus h's centroid depth.
          const double zq = cq.z - (nq.x * (ch.x - cq.x) + nq.y * (ch.y - cq.y)) / nq.z;
          offers.emplace_back(zq - ch.z, h, q, across <= parallel);
        }
      }
      // A move of the part's depths: z → z + dz, or for an inexact part z → k z + a x + b y + dz
      // (`affine` = (k − 1, a, b)): a part read alone by least squares is an affine relative of
      // the one around it, so a through hole's two ends meet their faces only after its depth
      // scale and tilt are matched too. Loops of the part each on the plane of a loop of a
      // placed part around it, within the depth tolerance at every junction, vote for a move.
      const auto moved = [&](std::uint32_t v, double dz, const Eigen::Vector3d& affine) {
        return pts[v].z + affine[0] * pts[v].z + affine[1] * pts[v].x + affine[2] * pts[v].y + dz;
      };
      const auto plane_depth = [&](std::size_t q, double x, double y) {
        if (!plane[q]) plane[q] = loop_plane(placed, loops[q]);
        const auto& [nq, cq] = *plane[q];
        return cq.z - (nq.x * (x - cq.x) + nq.y * (y - cq.y)) / nq.z;
      };
      const auto consider = [&](double dz, const Eigen::Vector3d& affine, std::size_t q0, bool by_offset) {
        std::vector<std::pair<std::size_t, std::size_t>> agree;
        std::vector<char> used(n, 0);
        for (const auto& [dz2, h, q, close] : offers) {
          if (used[h] || (by_offset && !close)) continue;
          bool on = by_offset && std::abs(dz2 - dz) <= depth_tolerance;
          if (!by_offset) {
            on = true;
            for (const auto v : loops[h])
              on = on &&
                   std::abs(moved(v, dz, affine) - plane_depth(q, pts[v].x, pts[v].y)) <= depth_tolerance;
          }
          if (on) used[h] = 1, agree.push_back({h, q});
        }
        // Outside: the part's centre on the outer side of the face it meets (a boss, not a
        // pocket: a part joined by one loop is drawn alike either way; see docs/sketch.md).
        const auto [nq0, cq] = loop_plane(placed, loops[q0]);
        const double centre_z =
            centre.z + affine[0] * centre.z + affine[1] * centre.x + affine[2] * centre.y + dz;
        const double side =
            glm::dot(glm::dvec3(centre.x, centre.y, centre_z) - cq, placed_outward[part[q0]] * nq0);
        const int outside = side > 0 ? 1 : 0;
        candidates.push_back({agree.size(), centre_z});
        if (agree.size() > best_votes ||
            (agree.size() == best_votes && best_votes > 0 && outside > best_outside))
          best_votes = agree.size(), best_reading = r, best_dz = dz, best_affine = affine,
          best_centre = centre_z, best_pairs = agree, best_outside = outside;
      };
      for (const auto& [dz, h0, q0, close] : offers)
        if (close) consider(dz, Eigen::Vector3d::Zero(), q0, true);
      // Inexact: the affine move that puts two loops of the part on two planes (least squares
      // over their junctions, Eigen's QR), when it keeps the part's sense and scales its depth
      // by 1/3 to 3; loops within 25° of parallel offer (the move tilts them); at most 64
      // offers (pairs: a work budget).
      if (inexact && offers.size() <= 64)
        for (std::size_t i = 0; i < offers.size(); ++i)
          for (std::size_t j = i + 1; j < offers.size(); ++j) {
            const auto& [dzi, hi, qi, ci] = offers[i];
            const auto& [dzj, hj, qj, cj] = offers[j];
            if (hi == hj) continue;
            const auto rows = static_cast<Eigen::Index>(loops[hi].size() + loops[hj].size());
            Eigen::MatrixXd m(rows, 4);
            Eigen::VectorXd target(rows);
            Eigen::Index row = 0;
            for (const auto& [h, q] : {std::pair{hi, qi}, std::pair{hj, qj}})
              for (const auto v : loops[h]) {
                m.row(row) << pts[v].z, pts[v].x, pts[v].y, 1.0;
                target[row++] = plane_depth(q, pts[v].x, pts[v].y) - pts[v].z;
              }
            const Eigen::Vector4d fit = m.colPivHouseholderQr().solve(target);
            const double k = 1.0 + fit[0];
            if (!fit.allFinite() || !(k >= 1.0 / 3.0 && k <= 3.0)) continue;
            consider(fit[3], fit.head<3>(), qi, false);
          }
    }
    for (std::uint32_t v = 0; v < nv; ++v)
      if (f.component[v] == c) {
        const glm::dvec3 q = pr[c].readings[best_reading][v];
        placed[v] = glm::dvec3(
            q.x, q.y, q.z + best_affine[0] * q.z + best_affine[1] * q.x + best_affine[2] * q.y + best_dz);
      }
    // Another placement as good: the drawing shows two solids (a boss or a pocket) alike.
    bool tie = false;
    for (const auto& [votes, centre_z] : candidates)
      tie = tie || (votes == best_votes && std::abs(centre_z - best_centre) > depth_tolerance);
    if (k > 0 && best_votes > 0 && tie) {
      ++ambiguous;
      diagnostics.push_back(
          cellforge::detail::cat("part ", std::to_string(c),
                                 " of the drawing fits its face as a boss or as a pocket alike: read as ",
                                 (best_outside == 1 ? "a boss" : "a pocket")));
    }
    is_placed[c] = 1;
    placed_outward[c] = pr[c].outward[best_reading];
    for (const auto& [h, q] : best_pairs) owner[h] = owner[q] == n ? q : owner[q];
    if (k > 0 && best_votes == 0) {
      // Drawn inside a placed part, its depth decides the solid (in front, behind, through it):
      // the placement is a guess, flagged. Beside the others it changes nothing.
      bool drawn_inside = false;
      for (std::size_t h = 0; h < n && !drawn_inside; ++h)
        for (std::size_t q = 0; q < n && part[h] == c && !drawn_inside; ++q)
          drawn_inside = part[q] != c && is_placed[part[q]] && inside_loop(h, q);
      ambiguous += drawn_inside ? 1 : 0;
      diagnostics.push_back(cellforge::detail::cat(
          "part ", std::to_string(c),
          " of the drawing lies in no face of the others: its depth against them is free",
          (drawn_inside ? std::string(", and it is drawn inside another part (flagged)") : std::string())));
    }
  }
  return faces_of(owner, [](std::size_t) { return true; });
}

/// The 3D pipeline's result in another point type (the pipeline runs in double: its planarity
/// tolerances are relative to double rounding, which a float reading would not meet). O(size).
template <Point3 R>
wireframe_result<R> converted(wireframe_result<glm::dvec3>&& d) {
  if constexpr (std::is_same_v<R, glm::dvec3>) {
    return std::move(d);
  } else {
    wireframe_result<R> r;
    for (const auto& p : d.input.points) r.input.points.push_back(from_dvec3<R>(p));
    r.input.edges = std::move(d.input.edges);
    r.input.faces = std::move(d.input.faces);
    r.input.volumes = std::move(d.input.volumes);
    r.cells = convert_points<R>(d.cells);
    r.input_vertex = std::move(d.input_vertex);
    r.input_edge = std::move(d.input_edge);
    r.unforced = std::move(d.unforced);
    r.alternatives = std::move(d.alternatives);
    r.lost = std::move(d.lost);
    r.read = std::move(d.read);
    r.trace = std::move(d.trace);
    r.unique = std::move(d.unique);
    r.reduction = std::move(d.reduction);
    r.arrangement = std::move(d.arrangement);
    r.extra = std::move(d.extra);
    r.volume = std::move(d.volume);
    r.relations = std::move(d.relations);
    r.assembly_milliseconds = d.assembly_milliseconds;
    r.tolerance = std::move(d.tolerance);
    r.check = d.check;
    r.status = d.status;
    r.status_reason = std::move(d.status_reason);
    r.certificate = std::move(d.certificate);
    r.validation = std::move(d.validation);
    static_cast<stage_report&>(r) = std::move(static_cast<stage_report&>(d));  // times, diagnostics
    return r;
  }
}

/// The drawing's lines by direction: (angle in [0, π), line), sorted; zero-length lines left
/// out. O(E log E).
template <class = void>
std::vector<std::pair<double, std::uint32_t>> line_directions(const faces::drawing_graph& g) {
  const std::size_t ne = g.num_half_edges() / 2;
  std::vector<std::pair<double, std::uint32_t>> angle;
  angle.reserve(ne);
  for (std::uint32_t e = 0; e < ne; ++e) {
    const glm::dvec2 v = g.p[g.head[2 * e]] - g.p[g.head[2 * e + 1]];
    if (!(glm::length(v) > 0)) continue;
    double a = std::atan2(v.y, v.x);
    if (a < 0) a += 3.141592653589793;
    if (a >= 3.141592653589793) a -= 3.141592653589793;
    angle.push_back({a, e});
  }
  std::sort(angle.begin(), angle.end());
  return angle;
}

/// Whether two lines of the drawing that share no junction are nearly parallel (within
/// `degrees`) but not parallel to rounding: the drawing is inexact (sketched, jittered, typed
/// with few digits), since a parallel view keeps lines parallel in space exactly parallel.
/// O(E log E + pairs within the angle).
template <class = void>
bool nearly_parallel(const faces::drawing_graph& g, double degrees) {
  const std::vector<std::pair<double, std::uint32_t>> angle = line_directions(g);
  const double window = degrees * 3.141592653589793 / 180.0;
  const auto near = [&](std::uint32_t e, std::uint32_t f) {
    if (g.head[2 * e] == g.head[2 * f] || g.head[2 * e] == g.head[2 * f + 1] ||
        g.head[2 * e + 1] == g.head[2 * f] || g.head[2 * e + 1] == g.head[2 * f + 1])
      return false;
    return !parallel_within(g.p[g.head[2 * e]] - g.p[g.head[2 * e + 1]],
                            g.p[g.head[2 * f]] - g.p[g.head[2 * f + 1]], 1e-9);
  };
  const std::size_t n = angle.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 1; k < n; ++k) {  // forward around the circle of directions
      const std::size_t j = (i + k) % n;
      const double gap =
          j > i ? angle[j].first - angle[i].first : angle[j].first + 3.141592653589793 - angle[i].first;
      if (gap > window) break;
      if (near(angle[i].second, angle[j].second)) return true;
    }
  return false;
}

/// Angle in degrees between the planes of two loops of a reading (0: coplanar or parallel). O(L).
template <class = void>
double plane_angle(const std::vector<glm::dvec3>& p, const std::vector<std::uint32_t>& a,
                   const std::vector<std::uint32_t>& b) {
  const glm::dvec3 na = loop_plane(p, a).first, nb = loop_plane(p, b).first;
  const double la = glm::length(na), lb = glm::length(nb);
  if (!(la > 0) || !(lb > 0)) return 0.0;
  return std::asin(std::min(1.0, glm::length(glm::cross(na, nb)) / (la * lb))) * 180.0 / 3.141592653589793;
}

/// A doubt on a drawing's faces: a line (a, b) on just two faces, triangles (a, b, c) and
/// (a, b, d) whose quad c-a-d-b is drawn as a parallelogram (opposite sides parallel within
/// `parallel_degrees`), and a junction e joined to a and b whose triangle (a, b, e) is no face.
/// A parallelogram in the view is one in space, flat: a–b would be a seam and (a, b, e) a wall
/// (a square pyramid split on its base's diagonal). A sentence naming them, or empty.
/// O(Σ L log E + Σ_e deg).
template <class = void>
std::string hidden_wall(const faces::drawing_graph& g, const face_set& faces, double parallel_degrees) {
  std::map<std::array<std::uint32_t, 2>, std::vector<std::size_t>> on;  // line (ends sorted) -> faces
  std::set<std::array<std::uint32_t, 3>> triangles;                     // faces that are triangles
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (faces[f].size() == 1 && faces[f][0].size() == 3) {
      std::array<std::uint32_t, 3> t{faces[f][0][0], faces[f][0][1], faces[f][0][2]};
      std::sort(t.begin(), t.end());
      triangles.insert(t);
    }
    for (const auto& loop : faces[f])
      for (std::size_t k = 0, n = loop.size(); k < n; ++k) {
        const std::uint32_t u = loop[k], v = loop[(k + 1) % n];
        on[{std::min(u, v), std::max(u, v)}].push_back(f);
      }
  }
  const double sine = std::sin(parallel_degrees * 3.141592653589793 / 180.0);
  const auto parallel = [&](std::uint32_t u0, std::uint32_t u1, std::uint32_t v0, std::uint32_t v1) {
    return parallel_within(g.p[u1] - g.p[u0], g.p[v1] - g.p[v0], sine);
  };
  const auto third = [&](std::size_t f, std::uint32_t a, std::uint32_t b) {  // a triangle's corner off a-b
    const auto& t = faces[f][0];
    return t[0] != a && t[0] != b ? t[0] : t[1] != a && t[1] != b ? t[1] : t[2];
  };
  std::vector<std::uint32_t> mark(g.num_junctions(), 0);  // neighbours of a, stamped by a + 1
  for (const auto& [line, fs] : on) {
    const std::uint32_t a = line[0], b = line[1];
    if (fs.size() != 2 || fs[0] == fs[1] || faces[fs[0]].size() != 1 || faces[fs[1]].size() != 1 ||
        faces[fs[0]][0].size() != 3 || faces[fs[1]][0].size() != 3 || a >= g.num_junctions() ||
        b >= g.num_junctions())
      continue;
    const std::uint32_t c = third(fs[0], a, b), d = third(fs[1], a, b);
    if (!parallel(c, a, b, d) || !parallel(a, d, c, b)) continue;
    for (std::uint32_t i = g.out_begin[a]; i < g.out_begin[a + 1]; ++i) mark[g.head[g.outs[i]]] = a + 1;
    for (std::uint32_t i = g.out_begin[b]; i < g.out_begin[b + 1]; ++i) {
      const std::uint32_t e = g.head[g.outs[i]];
      if (e == a || mark[e] != a + 1) continue;
      std::array<std::uint32_t, 3> t{a, b, e};
      std::sort(t.begin(), t.end());
      if (triangles.count(t)) continue;
      return cellforge::detail::cat(
          "faces ", std::to_string(fs[0]), " and ", std::to_string(fs[1]),
          " make a parallelogram (junctions ", std::to_string(c), ", ", std::to_string(a), ", ",
          std::to_string(d), ", ", std::to_string(b), "), flat in space, whose diagonal from junction ",
          std::to_string(a), " to ", std::to_string(b),
          " would be a seam and the triangle it makes with junction ", std::to_string(e), " a wall");
    }
  }
  return {};
}

/// Whether a drawing whose reading as drawn gives a complex that agrees with its faces is an
/// exact view: two of its lines sharing no junction are parallel to rounding (lines parallel in
/// space drawn exactly), or its faces are all triangles (any drawing of them is the view of a
/// solid: jitter leaves no trace) with no hidden_wall within 5 degrees (a jittered split base
/// folds in every reading and hides its wall). A jittered quad-sided drawing realised as drawn
/// (a box whose top, split by a wall's diagonal, folds) has neither. O(E log E + Σ L log E).
template <class = void>
bool exact_view(const faces::drawing_graph& g, const face_set& face_loops) {
  bool triangles = true;
  for (const auto& face : face_loops)
    for (const auto& loop : face) triangles = triangles && loop.size() == 3;
  if (triangles && hidden_wall(g, face_loops, 5.0).empty()) return true;
  const std::vector<std::pair<double, std::uint32_t>> angle = line_directions(g);
  const auto direction = [&](std::uint32_t e) { return g.p[g.head[2 * e]] - g.p[g.head[2 * e + 1]]; };
  const auto disjoint = [&](std::uint32_t e, std::uint32_t f) {
    return g.head[2 * e] != g.head[2 * f] && g.head[2 * e] != g.head[2 * f + 1] &&
           g.head[2 * e + 1] != g.head[2 * f] && g.head[2 * e + 1] != g.head[2 * f + 1];
  };
  const std::size_t n = angle.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 1; k < n; ++k) {  // forward around the circle of directions, within 1e-8 rad
      const std::size_t j = (i + k) % n;
      const double gap =
          j > i ? angle[j].first - angle[i].first : angle[j].first + 3.141592653589793 - angle[i].first;
      if (gap > 1e-8) break;
      if (parallel_within(direction(angle[i].second), direction(angle[j].second), 1e-9) &&
          disjoint(angle[i].second, angle[j].second))
        return true;
    }
  return false;
}

/// Whether two loops at line (a, b) of a tidied drawing are coplanar because the drawing says
/// so: each has a line off the seam's direction in one parallel class (exactly parallel, as the
/// tidying leaves a class) that holds three lines or more, or two such classes join them (a
/// parallelogram split by its diagonal). One pair of lines parallel by chance (a random
/// polytope's, merged by the tidying) is no evidence. O(L² + L·E).
template <class = void>
bool seam_drawn(const faces::drawing_graph& g, const std::vector<std::uint32_t>& la,
                const std::vector<std::uint32_t>& lb, std::uint32_t a, std::uint32_t b) {
  const auto parallel = [](glm::dvec2 u, glm::dvec2 v) { return parallel_within(u, v, 1e-9); };
  const auto sides = [&](const std::vector<std::uint32_t>& loop) {  // its lines off the seam
    std::vector<glm::dvec2> d;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const std::uint32_t u = loop[k], v = loop[(k + 1) % loop.size()];
      if (!((u == a && v == b) || (u == b && v == a)) && !parallel(g.p[v] - g.p[u], g.p[b] - g.p[a]))
        d.push_back(g.p[v] - g.p[u]);
    }
    return d;
  };
  std::vector<glm::dvec2> linking;  // distinct directions with a line in each loop
  for (const auto& u : sides(la))
    for (const auto& v : sides(lb))
      if (parallel(u, v) &&
          std::none_of(linking.begin(), linking.end(), [&](glm::dvec2 w) { return parallel(u, w); }))
        linking.push_back(u);
  if (linking.size() >= 2) return true;
  for (const auto& d : linking) {
    std::size_t members = 0;
    for (std::uint32_t e = 0; e < g.num_half_edges() / 2; ++e)
      members += parallel(g.p[g.head[2 * e]] - g.p[g.head[2 * e + 1]], d) ? 1 : 0;
    if (members >= 3) return true;
  }
  return false;
}

/// Whether loops fail their check on a drawing at an edge on just two of them that are
/// coplanar in the drawing's reading `depth` (normals within 1e-6 rad) because the drawing
/// says so (seam_drawn): a seam in space, that a wall must meet, not only two faces alike in
/// the view. O(Σ L² + E).
template <class = void>
bool flat_seam(const faces::drawing_graph& g, const std::vector<double>& depth,
               const std::vector<std::vector<std::uint32_t>>& loops, double coplanar_degrees) {
  const face_validation c = faces::check_loops(g, loops, coplanar_degrees);
  if (c.seam_edges.empty() || depth.size() != g.num_junctions()) return false;
  std::vector<glm::dvec3> q(g.num_junctions());
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = glm::dvec3(g.p[i], depth[i]);
  for (const auto e : c.seam_edges) {
    const std::uint32_t a = g.head[2 * e + 1], b = g.head[2 * e];
    std::vector<glm::dvec3> normals;
    std::vector<const std::vector<std::uint32_t>*> at;  // the loops on the line
    for (const auto& loop : loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const std::uint32_t u = loop[k], v = loop[(k + 1) % loop.size()];
        if ((u == a && v == b) || (u == b && v == a))
          normals.push_back(loop_plane(q, loop).first), at.push_back(&loop);
      }
    if (normals.size() == 2 && glm::length(normals[0]) > 0 && glm::length(normals[1]) > 0 &&
        glm::length(glm::cross(glm::normalize(normals[0]), glm::normalize(normals[1]))) <= 1e-6 &&
        seam_drawn(g, *at[0], *at[1], a, b))
      return true;
  }
  return false;
}

/// A doubt on an inexact drawing's answer: a junction where lines a and b go straight on (within
/// `straight_degrees` in one of `views`: as drawn, as tidied) and no face turns from a to b,
/// while the two faces at a third line f there, one turning (a, f), the other (f, b), fold by at
/// most `fold_degrees` in `reading`. Were a and b straight, those faces would be coplanar and f
/// a seam that a wall must meet: the jitter hid a wall. A sentence naming them, or empty.
/// O(Σ L log F + Σ_v deg(v)³).
template <class = void>
std::string straight_fold(const faces::drawing_graph& g, const std::vector<std::vector<glm::dvec2>>& views,
                          const std::vector<glm::dvec3>& reading, const face_set& faces,
                          double straight_degrees, double fold_degrees) {
  std::map<std::array<std::uint32_t, 3>, std::size_t> turn;  // (junction, lines' far ends sorted) -> face
  std::map<std::array<std::uint32_t, 2>, std::size_t> uses;  // line (ends sorted) -> loops on it
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (const auto& loop : faces[f])
      for (std::size_t k = 0, n = loop.size(); k < n; ++k) {
        const std::uint32_t a = loop[k], v = loop[(k + 1) % n], b = loop[(k + 2) % n];
        turn[{v, std::min(a, b), std::max(a, b)}] = f;
        ++uses[{std::min(a, v), std::max(a, v)}];
      }
  const auto turning = [&](std::uint32_t v, std::uint32_t a, std::uint32_t b) {
    const auto it = turn.find({v, std::min(a, b), std::max(a, b)});
    return it == turn.end() ? faces.size() : it->second;
  };
  const auto bend = [&](std::uint32_t v, std::uint32_t a, std::uint32_t b) {  // degrees off straight
    double least = 180.0;
    for (const auto& p : views) {
      const glm::dvec2 u = p[a] - p[v], w = p[b] - p[v];
      least = std::min(least, 180.0 - std::abs(std::atan2(u.x * w.y - u.y * w.x, glm::dot(u, w))) * 180.0 /
                                          3.141592653589793);
    }
    return least;
  };
  for (std::uint32_t v = 0; v < g.num_junctions(); ++v)
    for (std::uint32_t i = g.out_begin[v]; i < g.out_begin[v + 1]; ++i)
      for (std::uint32_t j = i + 1; j < g.out_begin[v + 1]; ++j) {
        const std::uint32_t a = g.head[g.outs[i]], b = g.head[g.outs[j]];
        const double off = bend(v, a, b);
        if (off > straight_degrees || turning(v, a, b) != faces.size()) continue;
        for (std::uint32_t k = g.out_begin[v]; k < g.out_begin[v + 1]; ++k) {
          const std::uint32_t f = g.head[g.outs[k]];
          const std::size_t fa = turning(v, a, f), fb = turning(v, b, f);
          if (f == a || f == b || fa == faces.size() || fb == faces.size() || fa == fb ||
              uses[{std::min(v, f), std::max(v, f)}] != 2)
            continue;
          const double fold = plane_angle(reading, faces[fa][0], faces[fb][0]);
          if (fold <= fold_degrees)
            return cellforge::detail::cat(
                "lines to junctions ", std::to_string(a), " and ", std::to_string(b),
                " go straight on through junction ", std::to_string(v), " (within ", std::to_string(off),
                " degrees) where the faces at the line to ", std::to_string(f), " fold by only ",
                std::to_string(fold),
                " degrees: were the lines straight, that line would be a seam a wall must meet");
        }
      }
  return {};
}

/// A doubt on an inexact drawing's answer: a face drawn inside another face's outer loop (no
/// junction shared), parallel to it in `reading` within `parallel_degrees` and off its plane by
/// more than rounding but at most `gap` × the reading's size: within the drawing's precision a
/// hole of that face (a through hole) or a pocket or boss alike. A sentence, or empty. O(F² L).
template <class = void>
std::string nested_near_plane(const std::vector<glm::dvec2>& p, const std::vector<glm::dvec3>& reading,
                              const face_set& faces, double parallel_degrees, double gap) {
  if (reading.empty()) return {};
  glm::dvec3 lo = reading[0], hi = reading[0];
  for (const auto& q : reading) lo = glm::min(lo, q), hi = glm::max(hi, q);
  const double size = glm::length(hi - lo);
  for (std::size_t a = 0; a < faces.size(); ++a) {
    std::vector<glm::dvec2> poly;
    for (const auto v : faces[a][0]) poly.push_back(p[v]);
    const auto [na, ca] = loop_plane(reading, faces[a][0]);
    if (!(glm::length(na) > 0)) continue;
    for (std::size_t b = 0; b < faces.size(); ++b) {
      bool nested = b != a;
      for (const auto v : faces[b][0])
        nested = nested && std::find(faces[a][0].begin(), faces[a][0].end(), v) == faces[a][0].end() &&
                 cellforge::detail::point_in_polygon(poly, p[v]);
      if (!nested || plane_angle(reading, faces[a][0], faces[b][0]) > parallel_degrees) continue;
      const double off = std::abs(glm::dot(loop_plane(reading, faces[b][0]).second - ca, glm::normalize(na)));
      if (off > 1e-9 * size && off <= gap * size)
        return cellforge::detail::cat("face ", std::to_string(b), " lies inside face ", std::to_string(a),
                                      " in the drawing, parallel to it and only ", std::to_string(off / size),
                                      " of the size off its plane: a hole through it, or a pocket, alike");
    }
  }
  return {};
}

/// The doubts of an inexact drawing's answer (straight_fold, nested_near_plane, hidden_wall) on the complex
/// `cells` built from `reading`, counted in r.doubts and named in r.diagnostics. Thresholds: lines
/// straight within 3 degrees, folds under 10, faces within 2 % of the size; measured on the
/// jittered sweep (tests/test_tidy.cpp, docs/sketch.md "Tidying"). O(F² L + Σ deg³).
template <class Result>
void doubt_inexact(const faces::drawing_graph& g, Result& r, const std::vector<glm::dvec3>& reading,
                   const wireframe_result<glm::dvec3>& cells) {
  face_set faces;
  for (const auto& face : cells.input.faces) {
    faces.push_back(face.loops);
    for (auto& loop : faces.back())
      for (auto& v : loop) v = cells.input_vertex[v];
  }
  std::vector<glm::dvec2> tidied;
  for (const auto& q : r.tidy.drawing.points) tidied.push_back(to_dvec2(q));
  if (tidied.size() != g.p.size()) tidied = g.p;
  for (std::string doubt : {straight_fold(g, {g.p, tidied}, reading, faces, 3.0, 10.0),
                            nested_near_plane(g.p, reading, faces, 5.0, 0.02), hidden_wall(g, faces, 5.0)})
    if (!doubt.empty())
      ++r.doubts, r.diagnostics.push_back(cellforge::detail::cat("inexact drawing: ", doubt));
}

/// Canonical cycles of a set of loops, for comparison. O(Σ L log L).
template <class = void>
std::multiset<std::vector<std::uint32_t>> canonical_loops(
    const std::vector<std::vector<std::uint32_t>>& loops) {
  std::multiset<std::vector<std::uint32_t>> s;
  for (const auto& l : loops) s.insert(cellforge::detail::canonical_cycle(l));
  return s;
}

}  // namespace detail::sketch

namespace detail::sketch {

/// drawing_to_cells from the faces found (`found`, on the drawing or on a tidied copy of it: the
/// same junctions), on the drawing's own point types, into R. O(the stages after the faces).
template <class R, LineDrawing D>
drawing_result<R, drawing_point_t<D>> drawing_to_cells_from(const D& drawing, const drawing_options& options,
                                                            const face_finder_result& found,
                                                            const detail::stopwatch& clock) {
  drawing_result<R, drawing_point_t<D>> r;
  r.faces = found;
  if (!r.faces.complete && r.faces.loops.empty()) {
    // The face finder's last fallback ran out of its budget: nothing to inflate. Status budget,
    // the finder's message (naming the option) as the reason.
    r.cells.status = solid_status::budget;
    r.cells.status_reason = budget_note(r.faces, "find_faces ran out of its work budget");
    r.diagnostics.push_back(r.cells.status_reason);
    r.complete = false;
    r.flagged = true;
    r.work = r.faces.work;
    r.milliseconds = clock.ms();
    return r;
  }
  if (r.faces.flagged)
    r.diagnostics.push_back(cellforge::detail::cat(
        "the faces found fail their check (",
        (r.faces.diagnostics.empty() ? std::string("see faces.check") : r.faces.diagnostics.front()),
        "); inflating them anyway"));
  const detail::faces::drawing_graph g = detail::faces::make_graph(drawing, options.faces);
  r.face_loops =
      detail::sketch::group_faces(g, r.faces.loops, options.inflation, r.diagnostics, r.ambiguous_parts);
  // One attempt: inflate `used` (in double: a float reading would miss the pipeline's
  // planarity tolerance) and build the complex of each reading until one agrees.
  struct attempt {
    inflation_result<glm::dvec3> inflated;
    std::optional<wireframe_result<glm::dvec3>> cells;
    wireframe<glm::dvec3> wire;
    std::size_t reading = 0;
    bool agree = false;
    std::vector<std::vector<std::uint32_t>> only_in_drawing, only_in_3d;
    std::string error;
  };
  auto wanted = detail::sketch::canonical_loops(r.faces.loops);
  // `given`: a reading already made (tidy_to_solid's depths, drawing units), not inflated again.
  const auto run_with = [&](const line_drawing<drawing_point_t<D>>& used,
                            const detail::sketch::face_set& face_loops, std::vector<std::string>& notes,
                            const inflation_options& inflation, const std::vector<double>* given = nullptr) {
    attempt a;
    if (given) {
      std::vector<glm::dvec3> up, down;
      for (std::size_t i = 0; i < used.points.size(); ++i) {
        const glm::dvec2 q = to_dvec2(used.points[i]);
        up.push_back({q, (*given)[i]}), down.push_back({q, -(*given)[i]});
      }
      a.inflated.method = inflation_method::optimisation;
      a.inflated.points = up;
      a.inflated.readings.push_back({std::move(up), 0.0, "the reading tidy_to_solid made the drawing's"});
      a.inflated.readings.push_back({std::move(down), 0.0, "its Necker reversal"});
      a.inflated.diagnostics.push_back(
          "inflate not run: the reading is tidy_to_solid's own of the tidied drawing");
    } else {
      try {
        a.inflated = inflate<glm::dvec3>(used, face_loops, inflation);
      } catch (const error& e) {
        if (e.category() != error_category::topology && e.category() != error_category::invalid_input) throw;
        a.error = e.what();
        return a;
      }
    }
    const std::size_t readings = options.try_other_reading ? a.inflated.readings.size() : 1;
    for (std::size_t k = 0; k < readings && !(a.cells && a.agree); ++k) {
      wireframe<glm::dvec3> w;
      w.points = a.inflated.readings[k].points;
      w.edges = used.edges;
      try {
        wireframe_result<glm::dvec3> cells = wireframe_to_cells(w, options.cells);
        // Faces that make no valid complex: this reading is refused, as a throw would.
        if (!cells.validation.ok())
          throw error(error_category::topology,
                      cellforge::detail::cat("wireframe_to_cells: ", cells.status_reason));
        std::vector<std::vector<std::uint32_t>> found;
        for (const auto& f : cells.input.faces)
          for (const auto& loop : f.loops) {
            std::vector<std::uint32_t> l;
            for (const auto v : loop) l.push_back(cells.input_vertex[v]);
            found.push_back(std::move(l));
          }
        const auto got = detail::sketch::canonical_loops(found);
        const bool agree = got == wanted;
        if (a.cells && !agree) continue;  // keep the first complex unless this one agrees
        a.only_in_drawing.clear();
        a.only_in_3d.clear();
        std::set_difference(wanted.begin(), wanted.end(), got.begin(), got.end(),
                            std::back_inserter(a.only_in_drawing));
        std::set_difference(got.begin(), got.end(), wanted.begin(), wanted.end(),
                            std::back_inserter(a.only_in_3d));
        a.cells = std::move(cells);
        a.wire = std::move(w);
        a.reading = k;
        a.agree = agree;
      } catch (const error& e) {
        if (e.category() != error_category::topology && e.category() != error_category::invalid_input) throw;
        a.error = e.what();
        notes.push_back(
            cellforge::detail::cat("reading ", std::to_string(k), ": the 3D pipeline refused it: ", a.error));
      }
    }
    return a;
  };
  // The regular reading first; when neither of its readings gives a complex whose faces agree,
  // the compliance optimum as it is (a regular reading may fold a face another way).
  const auto run = [&](const line_drawing<drawing_point_t<D>>& used,
                       const detail::sketch::face_set& face_loops, std::vector<std::string>& notes,
                       bool tidied = false, bool direct_only = false) {
    // A tidied drawing is only near a view: its regular reading moves which faces of several
    // cells are coplanar (measured on tests/test_tidy.cpp), so it is read as before.
    if (tidied) {
      inflation_options plain = options.inflation;
      plain.regularity = false;
      plain.allow_optimisation = !direct_only;
      return run_with(used, face_loops, notes, plain);
    }
    attempt a = run_with(used, face_loops, notes, options.inflation);
    if (!(a.cells && a.agree) && options.inflation.regularity && a.inflated.readings.size() == 2 &&
        a.inflated.method == inflation_method::optimisation) {
      inflation_options plain = options.inflation;
      plain.regularity = false;
      attempt b = run_with(used, face_loops, notes, plain);
      if (b.cells && b.agree) {
        notes.push_back(
            "the regular reading's faces disagree with the drawing's; the compliance optimum's agree");
        return b;
      }
    }
    return a;
  };
  // As drawn first (a tidy drawing is left alone: merging near-parallel lines of an exact
  // drawing would change it); tidied when that gives no complex whose faces agree.
  std::vector<std::string> notes;
  r.tidy.drawing = to_line_drawing(drawing);
  attempt best = options.tidy == tidy_mode::always ? attempt{} : run(r.tidy.drawing, r.face_loops, notes);
  const auto direct = [](const attempt& a) {
    return a.cells && a.agree && a.inflated.method == inflation_method::direct;
  };
  // The drawing as drawn is the exact view of a solid with its faces: its reading keeps every
  // face planar to rounding (the planar basis, rank 1e-9), gives a complex that agrees, and the
  // drawing shows it is exact (exact_view).
  const bool realised = best.cells && best.agree && detail::sketch::exact_view(g, r.face_loops);
  if (options.tidy != tidy_mode::never && !direct(best)) {
    tidy_result<drawing_point_t<D>> t = tidy_drawing(drawing, options.tidying);
    for (const auto& d : t.diagnostics) r.diagnostics.push_back(d);
    if (t.applied) {
      std::vector<std::string> tidy_notes;
      // Beside an answer that agrees only a direct tidied reading wins (below): no optimisation.
      attempt tidied = run(t.drawing, r.face_loops, tidy_notes, true,
                           best.cells && best.agree && options.tidy != tidy_mode::always);
      // Tidied wins when it gives a complex where there was none, one whose faces agree where
      // they did not, or a direct (exact) reading where there was an optimised one.
      if ((tidied.cells && !best.cells) || (tidied.cells && tidied.agree && !best.agree) ||
          (direct(tidied) && best.agree) || options.tidy == tidy_mode::always) {
        best = std::move(tidied);
        notes = std::move(tidy_notes);
        r.tidy = std::move(t);
      }
    }
  }
  // Still no complex whose faces agree, or an inexact drawing (sketched: lines nearly parallel,
  // never exactly, and no exact reading as drawn): tidied to the nearest view of a solid with the
  // faces found (planar faces, lines parallel in 3D parallel). A drawing realised as drawn is
  // exact whatever its angles (an antiprism's or a random polytope's lines within 5°).
  const bool inexact = !realised && detail::sketch::nearly_parallel(g, 5.0);
  const auto say_tidied = [&r] {  // once r.tidy holds the drawing tidied to a solid
    r.diagnostics.push_back(cellforge::detail::cat(
        "tidied to the view of a solid: junctions moved by at most ", std::to_string(r.tidy.largest_move),
        " of the drawing's size (rms ", std::to_string(r.tidy.rms_move), ")"));
  };
  if (options.tidy != tidy_mode::never && r.face_loops.size() >= 4 &&
      (!(best.cells && best.agree) || inexact)) {
    try {
      tidy_result<drawing_point_t<D>> t = tidy_to_solid(drawing, r.face_loops, options.tidying);
      for (const auto& d : t.diagnostics) r.diagnostics.push_back(d);
      detail::sketch::face_set regrouped = r.face_loops;
      std::vector<std::string> regroup_notes;  // the grouping's doubts travel with its faces
      std::size_t regroup_ambiguous = 0;
      if (t.applied) {
        // Parts drawn inside others are placed by their planes, which an inexact drawing gives
        // only roughly: grouped again on the tidied drawing (one view for every part), and
        // tidied again from the drawing as drawn with holes the grouping found.
        const detail::faces::drawing_graph g2 = detail::faces::make_graph(t.drawing, options.faces);
        const bool moved = inexact && t.largest_move > 1e-7;
        regrouped = detail::sketch::group_faces(g2, r.faces.loops, options.inflation, regroup_notes,
                                                regroup_ambiguous, moved);
        // Kept only when it leaves no more parts undecided than the grouping as drawn.
        if (regrouped != r.face_loops && regroup_ambiguous > r.ambiguous_parts) regrouped = r.face_loops;
        if (regrouped != r.face_loops) {
          tidy_result<drawing_point_t<D>> t2 = tidy_to_solid(drawing, regrouped, options.tidying);
          for (const auto& d : t2.diagnostics) r.diagnostics.push_back(d);
          if (t2.applied)
            t = std::move(t2),
            r.diagnostics.push_back(cellforge::detail::cat(
                "faces grouped again on the tidied drawing: ", std::to_string(regrouped.size()), " faces"));
          else
            regrouped = r.face_loops;
        }
      }
      // The faces found again on the tidied drawing, whose lines parallel in space are exactly
      // parallel: a face finder tells coplanar faces (seams that need a wall) only there. They
      // replace the faces as found when those failed their check, or have a seam on the tidied
      // drawing whose two faces are coplanar in its reading (not just alike in the view), and
      // the new ones pass their check and give a complex that agrees with them.
      bool refound = false;
      if (t.applied && inexact && t.largest_move > 1e-7) {
        face_finder_result f2 = find_faces(t.drawing, options.faces);
        const auto found2 = detail::sketch::canonical_loops(f2.loops);
        const detail::faces::drawing_graph g2 = detail::faces::make_graph(t.drawing, options.faces);
        const double coplanar = std::max(options.faces.coplanar_tolerance_degrees, 1e-6);
        if (!f2.flagged && found2 != wanted &&
            (r.faces.flagged || detail::sketch::flat_seam(g2, t.depth, r.faces.loops, coplanar))) {
          std::vector<std::string> group_notes;
          std::size_t ambiguous = 0;
          detail::sketch::face_set grouped2 =
              detail::sketch::group_faces(g2, f2.loops, options.inflation, group_notes, ambiguous, true);
          tidy_result<drawing_point_t<D>> t2 = tidy_to_solid(drawing, grouped2, options.tidying);
          const auto before = std::move(wanted);
          wanted = found2;
          // The new faces' own nearest view first; else the drawing they were found on, a view of
          // a solid already (the new faces' nearest view may lose its parallel classes); else that
          // drawing's own reading (tidy_to_solid's depths), where the faces at each seam are
          // coplanar: inflated again with the wall as a face, a sliced prism's or a walled
          // cylinder's faces at the seam fold by a fraction of a degree and the wall is unforced.
          std::optional<tidy_result<drawing_point_t<D>>> t3;
          for (int k = 0; k < 4 && !refound; ++k) {
            if (k == 3) {  // that drawing tidied again with the new faces (a wall's plane too)
              try {
                t3 = tidy_to_solid(t.drawing, grouped2, options.tidying);
              } catch (const error& e) {
                if (e.category() != error_category::topology && e.category() != error_category::invalid_input)
                  throw;
                break;
              }
              // Its moves from the drawing as drawn (bounding-box diagonal units, as tidy's).
              std::vector<glm::dvec2> from0(g.p.size()), to3(g.p.size());
              glm::dvec2 lo = g.p.empty() ? glm::dvec2(0) : g.p[0], hi = lo;
              for (std::size_t i = 0; i < g.p.size(); ++i)
                lo = glm::min(lo, g.p[i]), hi = glm::max(hi, g.p[i]),
                to3[i] = to_dvec2(t3->drawing.points[i]);
              const double size = std::max(glm::length(hi - lo), 1e-300);
              for (std::size_t i = 0; i < g.p.size(); ++i) from0[i] = g.p[i] / size, to3[i] /= size;
              std::tie(t3->largest_move, t3->rms_move) = detail::tidy::moves(from0, to3);
            }
            const tidy_result<drawing_point_t<D>>& from = k == 3 ? *t3 : t;
            if ((k == 0 && !t2.applied) ||
                (k >= 2 && !(from.solid && from.depth.size() == from.drawing.points.size())))
              continue;
            std::vector<std::string> tidy_notes;
            attempt again =
                k < 2 ? run(k == 0 ? t2.drawing : t.drawing, grouped2, tidy_notes, true)
                      : run_with(from.drawing, grouped2, tidy_notes, options.inflation, &from.depth);
            if (!(again.cells && again.agree)) continue;
            refound = true;
            best = std::move(again);
            notes = std::move(tidy_notes);
            r.diagnostics.push_back(cellforge::detail::cat(
                "faces found again on the drawing tidied to a solid: ", std::to_string(f2.loops.size()),
                " loops where the drawing as drawn gave ", std::to_string(r.faces.loops.size()),
                " (those fail their check there)"));
            r.faces = std::move(f2);
            r.face_loops = std::move(grouped2);
            r.ambiguous_parts = ambiguous;
            r.tidy = k == 0 ? std::move(t2) : k == 3 ? std::move(*t3) : t;
            say_tidied();
          }
          if (!refound) wanted = before;
        }
      }
      if (t.applied && !refound && !(best.cells && best.agree)) {
        std::vector<std::string> tidy_notes;
        attempt tidied = run(t.drawing, regrouped, tidy_notes, true);
        if ((tidied.cells && !best.cells) || (tidied.cells && tidied.agree)) {
          best = std::move(tidied);
          notes = std::move(tidy_notes);
          if (regrouped != r.face_loops) {
            r.ambiguous_parts = regroup_ambiguous;
            for (auto& d : regroup_notes) r.diagnostics.push_back(std::move(d));
          }
          r.face_loops = std::move(regrouped);
          r.tidy = std::move(t);
          say_tidied();
        } else {
          r.diagnostics.push_back(cellforge::detail::cat(
              "tidied to the view of a solid, but its reading gives ",
              std::string(tidied.cells ? "a complex whose faces disagree" : "no complex"),
              (tidied.error.empty() ? std::string() : cellforge::detail::cat(" (", tidied.error, ")"))));
        }
      }
    } catch (const error& e) {
      if (e.category() != error_category::topology && e.category() != error_category::invalid_input) throw;
      r.diagnostics.push_back(cellforge::detail::cat(std::string("tidy_to_solid: "), e.what()));
    }
  }
  for (auto& n : notes) r.diagnostics.push_back(std::move(n));
  const bool built = best.cells.has_value();
  if (built && inexact) doubt_inexact(g, r, best.inflated.readings[best.reading].points, *best.cells);
  const std::string last_error = best.error;
  if (built) {
    const auto to_r = [](const std::vector<glm::dvec3>& pts) {
      std::vector<R> out;
      out.reserve(pts.size());
      for (const auto& p : pts) out.push_back(from_dvec3<R>(p));
      return out;
    };
    const inflation_result<glm::dvec3>& inflated = best.inflated;
    r.inflation.points = to_r(inflated.points);
    r.inflation.method = inflated.method;
    for (const auto& reading : inflated.readings)
      r.inflation.readings.push_back({to_r(reading.points), reading.score, reading.reason});
    r.inflation.before = inflated.before;
    r.inflation.after = inflated.after;
    r.inflation.freedom = inflated.freedom;
    r.inflation.iterations = inflated.iterations;
    r.inflation.starts = inflated.starts;
    r.inflation.milliseconds = inflated.milliseconds;
    r.inflation.diagnostics = inflated.diagnostics;
    r.inflation.view_found = inflated.view_found;
    r.inflation.axis_directions = inflated.axis_directions;
    r.inflation.foreshortening = inflated.foreshortening;
    r.inflation.view_rotation = inflated.view_rotation;
    r.inflation.misclosure = inflated.misclosure;
    r.cells = detail::sketch::converted<R>(std::move(*best.cells));
    r.wire.points = r.inflation.readings[best.reading].points;
    r.wire.edges = std::move(best.wire.edges);
    r.reading = best.reading;
    r.faces_agree = best.agree;
    r.only_in_drawing = std::move(best.only_in_drawing);
    r.only_in_3d = std::move(best.only_in_3d);
  }
  if (!built)
    throw error(error_category::topology,
                cellforge::detail::cat("drawing_to_cells: no reading of the drawing gives a cell complex (",
                                       last_error, ")"));
  if (!r.faces_agree)
    r.diagnostics.push_back(cellforge::detail::cat(
        "the 3D pipeline's faces differ from the drawing's: ", std::to_string(r.only_in_drawing.size()),
        " loops only in the drawing, ", std::to_string(r.only_in_3d.size()), " only in 3D"));
  if (r.reading != 0)
    r.diagnostics.push_back(
        "built from the other (Necker) reading: the preferred one did not give the drawing's faces");
  // Never silently wrong: every drawn edge bounds a face of the complex, the 2D and 3D faces
  // agree, and neither stage reports an ambiguity; otherwise the answer is flagged.
  std::set<std::pair<std::uint32_t, std::uint32_t>> sides;
  for (const auto& face : r.cells.input.faces)
    for (const auto& loop : face.loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const std::uint32_t a = r.cells.input_vertex[loop[k]],
                            b = r.cells.input_vertex[loop[(k + 1) % loop.size()]];
        sides.insert({std::min(a, b), std::max(a, b)});
      }
  for (std::uint32_t e = 0; e < r.wire.edges.size(); ++e) {
    const auto [a, b] = r.wire.edges[e];
    if (!sides.count({std::min(a, b), std::max(a, b)})) r.unused_edges.push_back(e);
  }
  if (!r.unused_edges.empty())
    r.diagnostics.push_back(std::to_string(r.unused_edges.size()) +
                            " drawn edges bound no face of the complex (first: edge " +
                            std::to_string(r.unused_edges.front()) + ")");
  if (!r.cells.unforced.empty())
    r.diagnostics.push_back(std::to_string(r.cells.unforced.size()) +
                            " faces of the 3D reading are walls no edge needs (kept, undecided)");
  r.flagged = r.faces.flagged || !r.faces_agree || !r.unused_edges.empty() || r.ambiguous_parts > 0 ||
              !r.cells.unforced.empty() || r.doubts > 0;
  r.complete = r.faces.complete && r.cells.complete;
  r.work = r.faces.work + r.cells.work;
  // Doubted for lines straight on through a fold: tidied again with such lines made one line,
  // which makes the faces there coplanar and shows the wall; kept when it clears every doubt.
  if (r.doubts > 0 && inexact && !options.tidying.straight_lines && options.tidy != tidy_mode::never) {
    drawing_options straight = options;
    straight.tidying.straight_lines = true;
    try {
      auto again = drawing_to_cells_from<R>(drawing, straight, found, clock);
      if (!again.flagged) {
        again.diagnostics.push_back(
            "tidied again with lines straight on through junctions made one line (an answer as drawn was "
            "doubted)");
        again.milliseconds = clock.ms();
        return again;
      }
    } catch (const error& e) {
      if (e.category() != error_category::topology && e.category() != error_category::invalid_input) throw;
    }
  }
  r.milliseconds = clock.ms();
  return r;
}

/// The faces of an inexact drawing found on it tidied first (tidy_drawing with its classes from a
/// precision, so that lines parallel in space are exactly parallel and the face finder tells
/// coplanar faces: seams a wall must meet), and the precision. The drawing's precision is read
/// from a ladder from 2.5e-4 to 4e-2 of the size in steps of 1.5: the largest step whose classes'
/// median offset (sketch/tidy_classes.hpp) is at least 1 / 2.5 of it (a uniform slip's median
/// offset across its class is about 0.4 of the largest). The faces found there, or else at the
/// next two finer classes of the ladder (fewer lines merged), or the next coarser, when they
/// pass their check and differ from `as_drawn`. No loops when there is none or no step is
/// self-consistent (no parallel structure); a note names the precision.
/// O(steps · E log E + 4 (sparse LDLᵀ + find_faces)).
template <LineDrawing D>
std::pair<face_finder_result, double> faces_tidied_first(
    const D& drawing, const faces::drawing_graph& g, const drawing_options& options,
    const std::vector<std::vector<std::uint32_t>>& as_drawn, std::vector<std::string>& notes) {
  std::pair<face_finder_result, double> none;
  if (g.num_junctions() < 3) return none;
  glm::dvec2 lo = g.p[0], hi = g.p[0];
  for (const auto& q : g.p) lo = glm::min(lo, q), hi = glm::max(hi, q);
  const double size = glm::length(hi - lo);
  if (!(size > 0)) return none;
  std::vector<glm::dvec2> unit(g.p.size());
  for (std::size_t i = 0; i < unit.size(); ++i) unit[i] = g.p[i] / size;
  std::vector<std::array<std::uint32_t, 2>> lines(g.num_half_edges() / 2);
  for (std::size_t e = 0; e < lines.size(); ++e) lines[e] = {g.head[2 * e + 1], g.head[2 * e]};
  // The ladder's distinct classes (the first precision of each) and the self-consistent step.
  std::vector<std::pair<double, std::vector<std::vector<std::uint32_t>>>> steps;
  std::size_t consistent = steps.max_size();
  for (double precision = 2.5e-4; precision <= 0.04; precision *= 1.5) {
    std::vector<std::vector<std::uint32_t>> classes = tidy::drawing_classes(unit, lines, precision);
    if (classes.empty()) continue;
    const bool self_consistent = 2.5 * tidy::median_offset(unit, lines, classes) >= precision;
    for (auto& c : classes) std::sort(c.begin(), c.end());
    std::sort(classes.begin(), classes.end());
    if (steps.empty() || classes != steps.back().second) steps.push_back({precision, std::move(classes)});
    if (self_consistent) consistent = steps.size() - 1;
  }
  if (consistent == steps.max_size()) return none;
  const auto skip = canonical_loops(as_drawn);
  face_finder_options fo = options.faces;
  fo.alternatives_when_flagged = false;  // only an answer that passes is used
  for (const std::size_t k : {consistent, consistent - 1, consistent - 2, consistent + 1}) {
    if (k >= steps.size()) continue;  // consistent − 1 wraps to max when consistent is 0
    tidy_options o = options.tidying;
    o.precision = steps[k].first;
    o.max_move = 3 * o.precision;
    const auto t = tidy_drawing(drawing, o);
    if (!t.applied) continue;
    face_finder_result f = find_faces(t.drawing, fo);
    if (f.flagged || !f.complete || canonical_loops(f.loops) == skip) continue;
    notes.push_back(cellforge::detail::cat(
        "faces found on the drawing tidied first (", std::to_string(t.classes), " classes at a precision of ",
        std::to_string(o.precision), " of its size, junctions moved by at most ",
        std::to_string(t.largest_move), "): ", std::to_string(f.loops.size()), " loops"));
    return {std::move(f), o.precision};
  }
  return none;
}

/// drawing_to_cells on the drawing's own point types, into R: from the faces as drawn; for an
/// inexact drawing whose faces fail their check or give a flagged answer, from the faces found on
/// it tidied first (faces_tidied_first) instead, kept when they give an answer not flagged (or the
/// faces as drawn failed). O(the stages).
template <class R, LineDrawing D>
drawing_result<R, drawing_point_t<D>> drawing_to_cells_on(const D& drawing, const drawing_options& options) {
  detail::stopwatch clock;
  const face_finder_result found = find_faces(drawing, options.faces);
  if (!found.complete && found.loops.empty()) return drawing_to_cells_from<R>(drawing, options, found, clock);
  std::optional<drawing_result<R, drawing_point_t<D>>> as_drawn;
  if (!found.flagged) {
    as_drawn = drawing_to_cells_from<R>(drawing, options, found, clock);
    if (!as_drawn->flagged) return std::move(*as_drawn);
  }
  const faces::drawing_graph g = faces::make_graph(drawing, options.faces);
  std::vector<std::string> notes;
  // An answer read from the drawing as drawn whose 2D and 3D faces agree is of an exact view
  // (drawing_to_cells_from: `realised`): tidying it would move a solid's exact junctions.
  const bool realised =
      as_drawn && !as_drawn->tidy.applied && as_drawn->faces_agree && exact_view(g, as_drawn->face_loops);
  const auto [first, precision] = options.tidy != tidy_mode::never && !realised && nearly_parallel(g, 5.0)
                                      ? faces_tidied_first(drawing, g, options, found.loops, notes)
                                      : std::pair<face_finder_result, double>{};
  if (!first.loops.empty()) {
    // The drawing's parallel tidy takes its classes from that precision too.
    drawing_options tidied = options;
    tidied.tidying.precision = precision;
    tidied.tidying.max_move = std::max(tidied.tidying.max_move, 3 * precision);
    try {
      auto r = drawing_to_cells_from<R>(drawing, tidied, first, clock);
      if (!r.flagged || !as_drawn) {
        r.diagnostics.insert(r.diagnostics.begin(), notes.begin(), notes.end());
        return r;
      }
    } catch (const error& e) {
      if (e.category() != error_category::topology && e.category() != error_category::invalid_input) throw;
    }
  }
  if (as_drawn) return std::move(*as_drawn);
  return drawing_to_cells_from<R>(drawing, options, found, clock);
}

/// A result computed on a line_drawing<glm::dvec2> into glm::dvec3, in the caller's types
/// (R, P2: P2's scalar is double, so the drawings convert exactly). O(size).
template <class R, class P2>
drawing_result<R, P2> result_in(drawing_result<glm::dvec3, glm::dvec2>&& d) {
  const auto points_in = [](const std::vector<glm::dvec3>& pts) {
    std::vector<R> out;
    out.reserve(pts.size());
    for (const auto& p : pts) out.push_back(from_dvec3<R>(p));
    return out;
  };
  drawing_result<R, P2> r;
  r.faces = std::move(d.faces);
  r.tidy.drawing = to_line_drawing<P2>(d.tidy.drawing);
  r.tidy.classes = d.tidy.classes;
  r.tidy.parallel_lines = d.tidy.parallel_lines;
  r.tidy.changed_lines = d.tidy.changed_lines;
  r.tidy.largest_move = d.tidy.largest_move;
  r.tidy.rms_move = d.tidy.rms_move;
  r.tidy.applied = d.tidy.applied;
  r.tidy.solid = d.tidy.solid;
  r.tidy.planarity = d.tidy.planarity;
  r.tidy.depth = std::move(d.tidy.depth);
  r.tidy.steps = d.tidy.steps;
  r.tidy.milliseconds = d.tidy.milliseconds;
  r.tidy.diagnostics = std::move(d.tidy.diagnostics);
  r.face_loops = std::move(d.face_loops);
  auto& in = d.inflation;
  auto& out = r.inflation;
  out.points = points_in(in.points);
  out.method = in.method;
  for (auto& reading : in.readings)
    out.readings.push_back({points_in(reading.points), reading.score, std::move(reading.reason)});
  out.before = in.before;
  out.after = in.after;
  out.freedom = in.freedom;
  out.iterations = in.iterations;
  out.starts = in.starts;
  out.milliseconds = in.milliseconds;
  out.diagnostics = std::move(in.diagnostics);
  out.view_found = in.view_found;
  out.axis_directions = in.axis_directions;
  out.foreshortening = in.foreshortening;
  out.view_rotation = in.view_rotation;
  out.misclosure = in.misclosure;
  out.least_squares = in.least_squares;
  out.near_readings = in.near_readings;
  out.regular_relations = in.regular_relations;
  out.relations = in.relations;
  out.crossing_readings = in.crossing_readings;
  out.self_intersecting = in.self_intersecting;
  out.face_changing_readings = in.face_changing_readings;
  r.reading = d.reading;
  r.wire.points = points_in(d.wire.points);
  r.wire.edges = std::move(d.wire.edges);
  r.cells = converted<R>(std::move(d.cells));
  r.ambiguous_parts = d.ambiguous_parts;
  r.faces_agree = d.faces_agree;
  r.only_in_drawing = std::move(d.only_in_drawing);
  r.only_in_3d = std::move(d.only_in_3d);
  r.unused_edges = std::move(d.unused_edges);
  r.doubts = d.doubts;
  r.flagged = d.flagged;
  r.milliseconds = d.milliseconds;
  r.diagnostics = std::move(d.diagnostics);
  return r;
}

}  // namespace detail::sketch

template <class Q, LineDrawing D>
detail::if_satisfied_t<LineDrawing<D>, detail::sketch::drawing_result_for, Q, D> drawing_to_cells(
    const D& drawing, const drawing_options& options) {
  using R = detail::result_point_t<Q, drawing_point_t<D>>;
  static_assert(Point3<R>, "drawing_to_cells: the result point type must be a registered Point3");
  using P2 = drawing_point_t<D>;
  if constexpr (std::is_same_v<D, line_drawing<glm::dvec2>> && std::is_same_v<R, glm::dvec3>)
    return detail::sketch::drawing_to_cells_on<glm::dvec3>(drawing, options);
  else if constexpr (std::is_same_v<detail::point2_scalar_t<P2>, double>)
    return detail::sketch::result_in<R, P2>(
        detail::sketch::drawing_to_cells_on<glm::dvec3>(to_line_drawing<glm::dvec2>(drawing), options));
  else  // float drawings: tolerances follow the drawing's own rounding (inflate, find_faces)
    return detail::sketch::drawing_to_cells_on<R>(drawing, options);
}

#if defined(CELLFORGE_EXTERN_SKETCH)
// Compiled once in the file that includes cellforge/sketch/instantiate.hpp (docs/sketch.md).
extern template drawing_result<glm::dvec3, glm::dvec2>
detail::sketch::drawing_to_cells_on<glm::dvec3, line_drawing<glm::dvec2>>(const line_drawing<glm::dvec2>&,
                                                                          const drawing_options&);
#endif

}  // namespace cellforge
