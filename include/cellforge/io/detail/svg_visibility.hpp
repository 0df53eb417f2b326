// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Hidden-line computation for the SVG writer: projected faces (2D polygons with a depth
/// plane) binned in a uniform grid, queried by segments (exact hidden intervals) and points.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace cellforge::io::detail {

/// A half-open parameter interval [t0, t1] along a segment, t in [0, 1].
using svg_interval = std::array<double, 2>;

/// Faces projected to the screen: x, y in screen units, z = depth (larger is nearer the
/// viewer). Segments and points are tested against the faces whose grid cells they cross,
/// so a query costs O(cells crossed + faces in them), not O(all faces).
class occlusion_grid {
 public:
  /// Adds face `id` from its projected vertices (x, y, depth). Faces seen edge-on or of zero
  /// projected area cannot hide anything and are left out (returns false). O(size of the face).
  bool add_face(std::uint32_t id, std::span<const glm::dvec3> v) {
    if (v.size() < 3) return false;
    // Newell's normal in (x, y, depth) space: nz is twice the signed projected area.
    glm::dvec3 n(0.0), c(0.0);
    for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
      n.x += (v[j].y - v[i].y) * (v[j].z + v[i].z);
      n.y += (v[j].z - v[i].z) * (v[j].x + v[i].x);
      n.z += (v[j].x - v[i].x) * (v[j].y + v[i].y);
      c += v[i];
    }
    c /= static_cast<double>(v.size());
    if (!(std::abs(n.z) > 2e-9)) return false;  // below a billionth of a square pixel: edge-on
    face f;
    f.id = id;
    f.first = static_cast<std::uint32_t>(xy_.size());
    f.count = static_cast<std::uint32_t>(v.size());
    f.a = -n.x / n.z;
    f.b = -n.y / n.z;
    f.c = c.z - f.a * c.x - f.b * c.y;
    f.lo = glm::dvec2(v[0]);
    f.hi = f.lo;
    f.near = v[0].z;
    for (const auto& p : v) {
      f.near = std::max(f.near, p.z);
      xy_.emplace_back(p.x, p.y);
      f.lo = glm::min(f.lo, glm::dvec2(p));
      f.hi = glm::max(f.hi, glm::dvec2(p));
    }
    faces_.push_back(f);
    return true;
  }

  std::size_t num_faces() const noexcept { return faces_.size(); }

  /// Bins the faces in a grid of about one cell per face (at most 1024 x 1024 cells).
  /// O(F + cells covered by the faces' boxes).
  void build() {
    cells_.clear();
    entries_.clear();
    stamp_.assign(faces_.size(), 0);
    query_ = 0;
    if (faces_.empty()) return;
    lo_ = faces_[0].lo;
    hi_ = faces_[0].hi;
    for (const auto& f : faces_) {
      lo_ = glm::min(lo_, f.lo);
      hi_ = glm::max(hi_, f.hi);
    }
    const double w = std::max(hi_.x - lo_.x, 1e-12), h = std::max(hi_.y - lo_.y, 1e-12);
    const double cell = std::sqrt(w * h / static_cast<double>(faces_.size()));
    nx_ = static_cast<int>(std::clamp(std::ceil(w / cell), 1.0, 1024.0));
    ny_ = static_cast<int>(std::clamp(std::ceil(h / cell), 1.0, 1024.0));
    sx_ = nx_ / w;
    sy_ = ny_ / h;
    // Counting pass, then a filling pass: one flat array of face indices per cell (CSR).
    cells_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    const auto for_each_cell_of = [&](const face& f, auto&& fn) {
      const int c0 = col(f.lo.x), c1 = col(f.hi.x), r0 = row(f.lo.y), r1 = row(f.hi.y);
      for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) fn(static_cast<std::size_t>(r) * nx_ + c);
    };
    for (const auto& f : faces_) for_each_cell_of(f, [&](std::size_t k) { ++cells_[k + 1]; });
    for (std::size_t k = 1; k < cells_.size(); ++k) cells_[k] += cells_[k - 1];
    entries_.resize(cells_.back());
    std::vector<std::uint32_t> cursor(cells_.begin(), cells_.end() - 1);
    for (std::uint32_t fi = 0; fi < faces_.size(); ++fi)
      for_each_cell_of(faces_[fi], [&](std::size_t k) { entries_[cursor[k]++] = fi; });
  }

  /// Appends to `out` the parameter intervals of segment a-b (x, y, depth) hidden by some face.
  /// `eps(id)` gives the depth margin a face must be in front by, or a negative value to
  /// ignore that face (e.g. the faces the segment is an edge of). Intervals may overlap.
  /// O(cells crossed + candidate faces x their sizes).
  template <class EpsFn>
  void hidden_intervals(const glm::dvec3& a, const glm::dvec3& b, EpsFn&& eps,
                        std::vector<svg_interval>& out) {
    if (faces_.empty()) return;
    const glm::dvec2 a2(a), b2(b), d = b2 - a2;
    if (glm::dot(d, d) < 1e-18) {
      // Seen end-on: the segment is a point; the nearer end decides.
      const glm::dvec3& front = a.z >= b.z ? a : b;
      if (point_hidden(front, eps)) out.push_back({0.0, 1.0});
      return;
    }
    const glm::dvec2 slo = glm::min(a2, b2), shi = glm::max(a2, b2);
    const double far = std::min(a.z, b.z);
    ++query_;
    for_each_cell_on_segment(a2, b2, [&](std::size_t cell) {
      for (std::uint32_t k = cells_[cell]; k < cells_[cell + 1]; ++k) {
        const std::uint32_t fi = entries_[k];
        if (stamp_[fi] == query_) continue;
        stamp_[fi] = query_;
        const face& f = faces_[fi];
        if (f.hi.x < slo.x || f.lo.x > shi.x || f.hi.y < slo.y || f.lo.y > shi.y) continue;
        if (f.near <= far) continue;  // wholly behind the segment
        const double e = eps(f.id);
        if (e < 0.0) continue;
        clip(f, a, b, e, out);
      }
    });
  }

  /// True when a face (allowed by `eps`, as above) covers p and is in front of it by more
  /// than its margin. O(faces in p's cell).
  template <class EpsFn>
  bool point_hidden(const glm::dvec3& p, EpsFn&& eps) const {
    if (faces_.empty()) return false;
    if (p.x < lo_.x || p.x > hi_.x || p.y < lo_.y || p.y > hi_.y) return false;
    const auto cell = static_cast<std::size_t>(row(p.y)) * nx_ + col(p.x);
    for (std::uint32_t k = cells_[cell]; k < cells_[cell + 1]; ++k) {
      const face& f = faces_[entries_[k]];
      if (p.x < f.lo.x || p.x > f.hi.x || p.y < f.lo.y || p.y > f.hi.y || f.near <= p.z) continue;
      const double e = eps(f.id);
      if (e < 0.0) continue;
      if (f.a * p.x + f.b * p.y + f.c - p.z > e && inside(f, glm::dvec2(p))) return true;
    }
    return false;
  }

 private:
  struct face {
    std::uint32_t id = 0, first = 0, count = 0;
    double a = 0, b = 0, c = 0;  // depth(x, y) = a x + b y + c, the plane of Newell's normal
    double near = 0;             // depth of the vertex nearest the viewer
    glm::dvec2 lo{0.0}, hi{0.0};
  };

  int col(double x) const {
    return static_cast<int>(std::clamp(std::floor((x - lo_.x) * sx_), 0.0, static_cast<double>(nx_ - 1)));
  }
  int row(double y) const {
    return static_cast<int>(std::clamp(std::floor((y - lo_.y) * sy_), 0.0, static_cast<double>(ny_ - 1)));
  }

  /// Every cell the segment passes through (a supercover), column by column. O(cells).
  template <class Fn>
  void for_each_cell_on_segment(glm::dvec2 a, glm::dvec2 b, Fn&& fn) const {
    double ax = (a.x - lo_.x) * sx_, ay = (a.y - lo_.y) * sy_;
    double bx = (b.x - lo_.x) * sx_, by = (b.y - lo_.y) * sy_;
    if (ax > bx) {
      std::swap(ax, bx);
      std::swap(ay, by);
    }
    if (bx < 0.0 || ax > nx_ || std::max(ay, by) < 0.0 || std::min(ay, by) > ny_) return;
    const auto clamp_to = [](double v, int n) {
      return static_cast<int>(std::clamp(std::floor(v), 0.0, static_cast<double>(n - 1)));
    };
    const int c0 = clamp_to(ax, nx_), c1 = clamp_to(bx, nx_);
    const double dx = bx - ax;
    for (int c = c0; c <= c1; ++c) {
      // The part of the segment over this column; the end columns reach to the segment's ends.
      const double xl = c == c0 ? ax : c, xr = c == c1 ? bx : c + 1.0;
      double yl = ay, yr = by;
      if (dx > 0.0) {
        yl = ay + (by - ay) * ((xl - ax) / dx);
        yr = ay + (by - ay) * ((xr - ax) / dx);
      }
      const double lo = std::min(yl, yr) - 1e-9, hi = std::max(yl, yr) + 1e-9;
      if (hi < 0.0 || lo > ny_) continue;
      const int r0 = clamp_to(lo, ny_), r1 = clamp_to(hi, ny_);
      for (int r = r0; r <= r1; ++r) fn(static_cast<std::size_t>(r) * nx_ + c);
    }
  }

  /// Even-odd rule; points on the boundary may go either way. O(size of the face).
  bool inside(const face& f, glm::dvec2 p) const {
    bool in = false;
    const glm::dvec2* v = xy_.data() + f.first;
    for (std::uint32_t i = 0, j = f.count - 1; i < f.count; j = i++) {
      if ((v[i].y > p.y) != (v[j].y > p.y) &&
          p.x < (v[j].x - v[i].x) * (p.y - v[i].y) / (v[j].y - v[i].y) + v[i].x)
        in = !in;
    }
    return in;
  }

  /// Exact clipping: split the segment where it crosses the face's boundary, keep the pieces
  /// inside, and within each keep where the face is nearer than the segment by more than
  /// `margin` (both depths are linear in t, so that part is one interval found exactly).
  void clip(const face& f, const glm::dvec3& a, const glm::dvec3& b, double margin,
            std::vector<svg_interval>& out) {
    const glm::dvec2 a2(a), d = glm::dvec2(b) - a2;
    const glm::dvec2* v = xy_.data() + f.first;
    const auto gap = [&](double t) {
      return f.a * (a2.x + t * d.x) + f.b * (a2.y + t * d.y) + f.c - (a.z + t * (b.z - a.z)) - margin;
    };
    // Cheap rejections first: the face's plane behind the whole segment (the gap is linear
    // in t), or the whole face on one side of the segment's line.
    if (gap(0.0) <= 0.0 && gap(1.0) <= 0.0) return;
    int sides = 0;
    for (std::uint32_t i = 0; i < f.count; ++i) {
      const double side = d.x * (v[i].y - a2.y) - d.y * (v[i].x - a2.x);
      sides |= side > 0.0 ? 1 : side < 0.0 ? 2 : 3;
    }
    if (sides != 3) return;
    ts_.assign({0.0, 1.0});
    for (std::uint32_t i = 0, j = f.count - 1; i < f.count; j = i++) {
      const glm::dvec2 e = v[i] - v[j], w = v[j] - a2;
      const double den = d.x * e.y - d.y * e.x;
      if (den == 0.0) continue;  // parallel: touching along the boundary hides nothing
      const double t = (w.x * e.y - w.y * e.x) / den, s = (w.x * d.y - w.y * d.x) / den;
      if (t > 0.0 && t < 1.0 && s >= -1e-12 && s <= 1.0 + 1e-12) ts_.push_back(t);
    }
    std::sort(ts_.begin(), ts_.end());
    for (std::size_t k = 0; k + 1 < ts_.size(); ++k) {
      const double t0 = ts_[k], t1 = ts_[k + 1];
      if (!(t1 - t0 > 1e-12)) continue;
      if (!inside(f, a2 + (0.5 * (t0 + t1)) * d)) continue;
      const double g0 = gap(t0), g1 = gap(t1);
      if (g0 > 0.0 && g1 > 0.0)
        out.push_back({t0, t1});
      else if (g0 > 0.0)
        out.push_back({t0, t0 + (t1 - t0) * (g0 / (g0 - g1))});
      else if (g1 > 0.0)
        out.push_back({t0 + (t1 - t0) * (g0 / (g0 - g1)), t1});
    }
  }

  std::vector<face> faces_;
  std::vector<glm::dvec2> xy_;
  std::vector<std::uint32_t> cells_;    // CSR offsets, one per cell + 1
  std::vector<std::uint32_t> entries_;  // face indices, cell by cell
  std::vector<std::uint32_t> stamp_;    // last query that tested each face: no face tested twice
  std::vector<double> ts_;              // scratch: crossing parameters
  std::uint32_t query_ = 0;
  glm::dvec2 lo_{0.0}, hi_{0.0};
  double sx_ = 1, sy_ = 1;
  int nx_ = 1, ny_ = 1;
};

}  // namespace cellforge::io::detail
