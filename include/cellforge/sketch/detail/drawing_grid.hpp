// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Uniform grids for the pairwise tests on line drawings (validate(drawing), the SVG reader's
/// snapping and splitting): points in a normalised frame, close point pairs, and the
/// segment-segment and segment-point pairs that share a grid cell.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace cellforge::detail {

/// Points moved into a frame about the origin by a power-of-two scale (exact, so every test in
/// it gives the same answer at any scale) with the bounding-box diagonal `diag` in that frame.
struct drawing_frame {
  std::vector<glm::dvec2> points;
  double diag = 0;  ///< 0 when the points are all equal (or there are none)
};

/// Normalises finite points so that the larger half-extent of their box is in [0.5, 1). O(n).
template <class = void>
drawing_frame make_drawing_frame(std::vector<glm::dvec2> pts) {
  drawing_frame f;
  if (pts.empty()) return f;
  glm::dvec2 lo = pts[0], hi = pts[0];
  for (const auto& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::dvec2 centre = lo / 2.0 + hi / 2.0;
  const double half = std::max(hi.x / 2 - lo.x / 2, hi.y / 2 - lo.y / 2);
  const double scale = half > 0 && std::isfinite(half) ? std::ldexp(1.0, std::ilogb(half) + 1) : 1.0;
  for (auto& p : pts) p = (p - centre) / scale;
  f.points = std::move(pts);
  glm::dvec2 a = f.points[0], b = f.points[0];
  for (const auto& p : f.points) a = glm::min(a, p), b = glm::max(b, p);
  f.diag = glm::length(b - a);
  return f;
}

/// Calls `f(i, j)`, i < j, for every pair of points at most `eps` apart (eps >= 0; 0 finds
/// equal points), through a sorted grid of cells of side ≥ eps. Points are in a frame from
/// make_drawing_frame (|coordinates| ≤ 1). O(n log n + pairs in neighbouring cells).
template <class F>
void for_close_points(const std::vector<glm::dvec2>& pts, double eps, F&& f) {
  const std::size_t n = pts.size();
  if (n < 2) return;
  const double cell = std::max(eps, std::ldexp(1.0, -28));
  const auto cell_of = [&](double v) { return static_cast<std::int64_t>(std::floor((v + 1.0) / cell)); };
  constexpr std::int64_t stride = std::int64_t{1} << 31;
  std::vector<std::pair<std::int64_t, std::uint32_t>> at(n);
  for (std::size_t i = 0; i < n; ++i)
    at[i] = {cell_of(pts[i].x) * stride + cell_of(pts[i].y), static_cast<std::uint32_t>(i)};
  std::sort(at.begin(), at.end());
  const auto close = [&](std::uint32_t i, std::uint32_t j) {
    const glm::dvec2 d = pts[i] - pts[j];
    return glm::dot(d, d) <= eps * eps;
  };
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t i = at[k].second;
    // Same cell: the later entries only; then four of the eight neighbours (each pair once).
    for (std::size_t m = k + 1; m < n && at[m].first == at[k].first; ++m)
      if (close(i, at[m].second)) f(std::min(i, at[m].second), std::max(i, at[m].second));
    static constexpr std::int64_t dx[] = {0, 1, 1, 1}, dy[] = {1, -1, 0, 1};
    for (int q = 0; q < 4; ++q) {
      const std::int64_t key = at[k].first + dx[q] * stride + dy[q];
      auto it = std::lower_bound(at.begin(), at.end(), std::pair{key, std::uint32_t{0}});
      for (; it != at.end() && it->first == key; ++it)
        if (close(i, it->second)) f(std::min(i, it->second), std::max(i, it->second));
    }
  }
}

/// Every segment (a, b) of `segs` and every point of `pts` entered into the cells their
/// eps-neighbourhood meets; calls `on_pair(s, t)` (s < t) for two segments sharing a cell and
/// `on_point(s, p)` for a point in a cell of segment s. A pair sharing several cells is reported
/// once per cell. Coordinates in a make_drawing_frame frame. The cell side is the mean segment
/// length (at least 2^-12 of the frame, and eps), so each segment meets O(1 + length / side)
/// cells. O((S + P) log(S + P) + pairs sharing a cell).
template <class OnPair, class OnPoint>
void for_grid_neighbours(const std::vector<std::pair<glm::dvec2, glm::dvec2>>& segs,
                         const std::vector<glm::dvec2>& pts, double eps, OnPair&& on_pair,
                         OnPoint&& on_point) {
  if (segs.empty()) return;
  double mean = 0;
  for (const auto& [a, b] : segs) mean += glm::length(b - a);
  mean /= static_cast<double>(segs.size());
  const double cell = std::max({mean, std::ldexp(1.0, -12), 2 * eps});
  const double lo = -1.0 - eps;  // every coordinate is in [-1, 1]
  const auto n_cells = static_cast<std::int64_t>(std::floor((2.0 + 2 * eps) / cell)) + 1;
  const auto cell_of = [&](double v) {
    return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((v - lo) / cell)), 0, n_cells - 1);
  };
  std::vector<std::pair<std::int64_t, std::uint32_t>> seg_cells, pt_cells;
  for (std::size_t s = 0; s < segs.size(); ++s) {
    const auto [a, b] = segs[s];
    const double x_min = std::min(a.x, b.x), x_max = std::max(a.x, b.x);
    for (std::int64_t cx = cell_of(x_min - eps), cx_end = cell_of(x_max + eps); cx <= cx_end; ++cx) {
      // The part of the segment whose x lies within eps of this column, then its y range ± eps.
      const double x0 = std::max(lo + static_cast<double>(cx) * cell - eps, x_min);
      const double x1 = std::min(lo + static_cast<double>(cx + 1) * cell + eps, x_max);
      double y0 = std::min(a.y, b.y), y1 = std::max(a.y, b.y);
      if (b.x != a.x && x0 <= x1) {
        const double t0 = std::clamp((x0 - a.x) / (b.x - a.x), 0.0, 1.0);
        const double t1 = std::clamp((x1 - a.x) / (b.x - a.x), 0.0, 1.0);
        const double ya = a.y + t0 * (b.y - a.y), yb = a.y + t1 * (b.y - a.y);
        y0 = std::min(ya, yb);
        y1 = std::max(ya, yb);
      }
      for (std::int64_t cy = cell_of(y0 - eps), cy_end = cell_of(y1 + eps); cy <= cy_end; ++cy)
        seg_cells.push_back({cx * n_cells + cy, static_cast<std::uint32_t>(s)});
    }
  }
  for (std::size_t p = 0; p < pts.size(); ++p)
    pt_cells.push_back({cell_of(pts[p].x) * n_cells + cell_of(pts[p].y), static_cast<std::uint32_t>(p)});
  std::sort(seg_cells.begin(), seg_cells.end());
  std::sort(pt_cells.begin(), pt_cells.end());
  std::size_t pk = 0;
  for (std::size_t k = 0; k < seg_cells.size();) {
    std::size_t end = k;
    while (end < seg_cells.size() && seg_cells[end].first == seg_cells[k].first) ++end;
    for (std::size_t i = k; i < end; ++i)
      for (std::size_t j = i + 1; j < end; ++j) on_pair(seg_cells[i].second, seg_cells[j].second);
    while (pk < pt_cells.size() && pt_cells[pk].first < seg_cells[k].first) ++pk;
    for (std::size_t q = pk; q < pt_cells.size() && pt_cells[q].first == seg_cells[k].first; ++q)
      for (std::size_t i = k; i < end; ++i) on_point(seg_cells[i].second, pt_cells[q].second);
    k = end;
  }
}

/// Distance from q to the segment ab. O(1).
template <class = void>
double segment_distance(glm::dvec2 q, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 d = b - a;
  const double len2 = glm::dot(d, d);
  const double t = len2 > 0 ? std::clamp(glm::dot(q - a, d) / len2, 0.0, 1.0) : 0.0;
  return glm::length(q - (a + t * d));
}

}  // namespace cellforge::detail
