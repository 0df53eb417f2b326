// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 4 of the wireframe pipeline (seed 000 §4.4): area, flatness and planarity of every
/// candidate; faces that are the sum of two smaller adjacent faces are unusable; faces sharing
/// a corner (two consecutive edges) with a smaller face are secondary, the others primary.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/tolerance.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// Options of reduce_faces.
struct reduction_options {
  double min_flatness = 0.9;     ///< seed default: faces flatter than this are kept
  bool require_planar = true;    ///< beyond the seed: every vertex within `planarity` of the face plane
  tolerance planarity{1e-9};     ///< relative to model size
  bool remove_face_sums = true;  ///< seed: a face equal to the sum of two adjacent smaller faces is unusable
  cellforge::work_budget work_budget = 200'000'000;
};

/// Per candidate: the measures the seed uses and the verdict.
struct face_quality {
  double area = 0.0;
  double flatness = 1.0;       ///< seed §4.4: smallest |cos| between two corner normals (1 = flat)
  double max_deviation = 0.0;  ///< largest distance of a vertex from the face's plane
  bool usable = true;
  bool primary = true;
};

/// Verdicts for every candidate (same indices as the input faces).
struct reduction_result : stage_report {
  std::vector<face_quality> quality;
  std::size_t remaining = 0;  ///< usable faces
  std::size_t secondary = 0;  ///< usable secondary faces
  std::size_t not_flat = 0, not_planar = 0, face_sums = 0;
  double area_milliseconds = 0.0;  ///< the seed's "area calculation" row
};

/// Measures and reduces the candidates; out of work budget the face-sum search stops there,
/// complete false. O(F·L) for measures, O(Σ adjacent pairs · L) for sums.
template <class = void>
reduction_result reduce_faces(const wire_graph& g, const std::vector<wire_face>& faces,
                              const reduction_options& options = {}) {
  detail::stopwatch clock;
  reduction_result r;
  const double tol = options.planarity.relative * g.size;
  r.quality.resize(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const wire_face& f = faces[i];
    face_quality& q = r.quality[i];
    q.area = f.area;
    // Flatness: corner normals (cross products at each corner) compared pairwise by |cos|;
    // collinear corners (a vertex inside a straight chain, within tolerance) have no normal and
    // are skipped.
    std::vector<glm::dvec3> corner;
    for (const auto& loop : f.loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const glm::dvec3 p = g.points[loop[k]];
        const glm::dvec3 a = g.points[loop[(k + loop.size() - 1) % loop.size()]] - p;
        const glm::dvec3 b = g.points[loop[(k + 1) % loop.size()]] - p;
        const glm::dvec3 c = glm::cross(b, a);
        const double l = glm::length(c);
        if (l > tol * std::max(glm::length(a), glm::length(b))) corner.push_back(c / l);
      }
    q.flatness = 1.0;
    // Against the face normal rather than all pairs: the same minimum for planar faces, linear cost.
    if (glm::length(f.normal) > 0.0)
      for (const auto& c : corner) q.flatness = std::min(q.flatness, std::abs(glm::dot(c, f.normal)));
    else
      q.flatness = 0.0;
    const glm::dvec3 o = g.points[f.loops[0][0]];
    for (const auto& loop : f.loops)
      for (const auto v : loop)
        q.max_deviation = std::max(q.max_deviation, std::abs(glm::dot(f.normal, g.points[v] - o)));
    if (q.flatness < options.min_flatness) {
      q.usable = false;
      ++r.not_flat;
    } else if (options.require_planar && q.max_deviation > tol) {
      q.usable = false;
      ++r.not_planar;
      r.diagnostics.push_back(
          cellforge::detail::cat("candidate ", std::to_string(i), " is not planar (a vertex lies ",
                                 std::to_string(q.max_deviation), " off its plane) and was rejected"));
    }
  }
  r.area_milliseconds = clock.ms();

  // Edge sets, for face sums and corners.
  std::vector<std::vector<std::uint32_t>> edge_set(faces.size());
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> faces_at_edge;
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    for (const auto& loop : faces[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k)
        edge_set[i].push_back(g.find_edge(loop[k], loop[(k + 1) % loop.size()]));
    std::sort(edge_set[i].begin(), edge_set[i].end());
    if (r.quality[i].usable && options.remove_face_sums)
      for (const auto e : edge_set[i]) faces_at_edge[e].push_back(i);
  }
  detail::work_counter budget{options.work_budget, 0, "reduce_faces",
                              "reduction_options::work_budget (wireframe_options::reduction)"};
  // Out of budget the face-sum search stops (sums found so far rejected), complete false.
  try {
    if (options.remove_face_sums) {
      // Usable faces by edge set, stably sorted: among equal sets the first face is found.
      std::vector<std::uint32_t> by_edges;
      for (std::uint32_t i = 0; i < faces.size(); ++i)
        if (r.quality[i].usable) by_edges.push_back(i);
      std::stable_sort(by_edges.begin(), by_edges.end(),
                       [&](std::uint32_t a, std::uint32_t b) { return edge_set[a] < edge_set[b]; });
      std::vector<std::uint32_t> sum;
      for (std::uint32_t i = 0; i < faces.size(); ++i) {
        if (!r.quality[i].usable) continue;
        std::vector<std::uint32_t> partners;
        for (const auto e : edge_set[i])
          for (const auto j : faces_at_edge[e])
            if (j > i) partners.push_back(j);
        std::sort(partners.begin(), partners.end());
        partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
        for (const auto j : partners) {
          budget.spend(edge_set[i].size() + edge_set[j].size());
          sum.clear();
          std::set_symmetric_difference(edge_set[i].begin(), edge_set[i].end(), edge_set[j].begin(),
                                        edge_set[j].end(), std::back_inserter(sum));
          const auto it = std::lower_bound(
              by_edges.begin(), by_edges.end(), sum,
              [&](std::uint32_t a, const std::vector<std::uint32_t>& key) { return edge_set[a] < key; });
          if (it == by_edges.end() || edge_set[*it] != sum) continue;
          const std::uint32_t h_index = *it;
          face_quality& h = r.quality[h_index];
          if (h.usable && h.area > r.quality[i].area && h.area > r.quality[j].area) {
            h.usable = false;
            ++r.face_sums;
            r.diagnostics.push_back(cellforge::detail::cat("candidate ", std::to_string(h_index),
                                                           " is the sum of candidates ", std::to_string(i),
                                                           " and ", std::to_string(j), " and was rejected"));
          }
        }
      }
    }
  } catch (const error& e) {
    detail::stop_at_budget(r, budget, e);
  }
  // Secondary faces: two usable faces through the same corner; the larger one is secondary.
  std::unordered_map<std::uint64_t, std::uint32_t> smallest_at_corner;
  smallest_at_corner.reserve(4 * faces.size());
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    if (!r.quality[i].usable) continue;
    for (const auto& loop : faces[i].loops)
      for (std::size_t k = 0; k < loop.size(); ++k) {
        std::uint32_t a = g.find_edge(loop[k], loop[(k + 1) % loop.size()]);
        std::uint32_t b = g.find_edge(loop[(k + 1) % loop.size()], loop[(k + 2) % loop.size()]);
        if (a > b) std::swap(a, b);
        const auto [it, fresh] = smallest_at_corner.emplace((std::uint64_t{a} << 32) | b, i);
        if (fresh) continue;
        const std::uint32_t other = it->second;
        const std::uint32_t larger = r.quality[other].area >= r.quality[i].area ? other : i;
        r.quality[larger].primary = false;
        it->second = larger == other ? i : other;
      }
  }
  for (const auto& q : r.quality) {
    r.remaining += q.usable;
    r.secondary += q.usable && !q.primary;
  }
  r.work = budget.used;
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
