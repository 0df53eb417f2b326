// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Hidden-line computation for the SVG writer: projected faces (2D polygons with a depth
/// plane) binned in a uniform grid, queried by segments (exact hidden intervals) and points.
/// Every query counts its work, and stops when the caller's limit is reached.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <span>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/geometry.hpp"

namespace cellforge::io::detail {

/// A half-open parameter interval [t0, t1] along a segment, t in [0, 1].
using svg_interval = std::array<double, 2>;

template <class = void>
class basic_occlusion_grid;
using occlusion_grid = basic_occlusion_grid<>;

/// Faces projected to the screen: x, y in screen units, z = depth (larger is nearer the
/// viewer). Segments and points are tested against the faces whose grid cells they cross,
/// nearest faces first, so a query costs O(cells crossed + faces in front of it there), not
/// O(all faces). Work is counted in units (a grid cell visited, a face considered, a polygon
/// side examined); queries take a limit on the running total and report when they hit it.
template <class>
class basic_occlusion_grid {
 public:
  /// Faces with more sides than this get their sides indexed by horizontal bands, so a test
  /// against them examines the sides near the query, not all of them.
  static constexpr std::uint32_t banded_face_size = 32;
  static constexpr std::uint64_t no_limit = std::numeric_limits<std::uint64_t>::max();

  /// Adds face `id` from its projected vertices (x, y, depth). Faces seen edge-on or of zero
  /// projected area cannot hide anything and are left out (returns false). O(size of the face).
  bool add_face(std::uint32_t id, std::span<const glm::dvec3> v) {
    if (v.size() < 3 || v.size() >= 0xffffffffu - xy_.size()) return false;
    // Newell's normal in (x, y, depth) space: nz is twice the signed projected area. Summed
    // from the closing side n-1 -> 0 on, the order the visibility always had.
    const std::size_t m = v.size();
    const glm::dvec3 n = cellforge::detail::newell(cellforge::detail::index_range{m},
                                                   [&](std::size_t k) { return v[(k + m - 1) % m]; });
    glm::dvec3 c(0.0);
    for (const glm::dvec3& p : v) c += p;
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
      // The plane's depth over the polygon is at most its largest value at a vertex.
      f.near = std::max({f.near, p.z, f.a * p.x + f.b * p.y + f.c});
      xy_.emplace_back(p.x, p.y);
      f.lo = glm::min(f.lo, glm::dvec2(p));
      f.hi = glm::max(f.hi, glm::dvec2(p));
    }
    if (f.count > banded_face_size) index_bands(f);
    faces_.push_back(f);
    return true;
  }

  std::size_t num_faces() const noexcept { return faces_.size(); }

  /// Work units spent by the queries so far.
  std::uint64_t work() const noexcept { return work_; }

  /// Bins the faces in a grid of about one cell per face (at most 1024 x 1024 cells): each face
  /// in the cells its rows actually reach (a sliver crossing the picture is not binned by its
  /// bounding box), nearest faces first in every cell. When the faces would fill more than
  /// 64 entries per face (plus 4M), the grid is coarsened until they do not, so memory stays
  /// linear. `min_margin` is the least depth margin the queries' eps will ask for: faces nearer
  /// than that are passed over without calling eps.
  /// O(F log F + sides x rows they span, per coarsening + entries), entries bounded as said.
  void build(double min_margin = 0.0) {
    min_margin_ = std::max(0.0, min_margin);
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
    double cell = std::sqrt(w * h / static_cast<double>(faces_.size()));
    const std::size_t cap = std::min(64 * faces_.size() + (std::size_t{1} << 22), std::size_t{1} << 31);
    for (;;) {
      nx_ = static_cast<int>(std::clamp(std::ceil(w / cell), 1.0, 1024.0));
      ny_ = static_cast<int>(std::clamp(std::ceil(h / cell), 1.0, 1024.0));
      sx_ = nx_ / w;
      sy_ = ny_ / h;
      std::size_t total = 0;
      for (const face& f : faces_)
        row_spans(f, [&](int, int c0, int c1) { total += static_cast<std::size_t>(c1 - c0 + 1); });
      if (total <= cap || (nx_ == 1 && ny_ == 1)) break;  // one cell: one entry per face
      cell *= std::max(1.25, std::sqrt(static_cast<double>(total) / static_cast<double>(cap)));
    }
    // Faces nearest first, then a counting pass and a filling pass: one flat array of face
    // indices per cell (CSR), each cell's list sorted by nearness.
    std::vector<std::uint32_t> order(faces_.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t p, std::uint32_t q) { return faces_[p].near > faces_[q].near; });
    cells_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    const auto for_each_cell_of = [&](std::uint32_t fi, auto&& fn) {
      row_spans(faces_[fi], [&](int r, int c0, int c1) {
        for (int c = c0; c <= c1; ++c) fn(static_cast<std::size_t>(r) * nx_ + c);
      });
    };
    for (std::uint32_t fi = 0; fi < faces_.size(); ++fi)
      for_each_cell_of(fi, [&](std::size_t k) { ++cells_[k + 1]; });
    for (std::size_t k = 1; k < cells_.size(); ++k) cells_[k] += cells_[k - 1];
    entries_.resize(cells_.back());
    std::vector<std::uint32_t> cursor(cells_.begin(), cells_.end() - 1);
    for (const std::uint32_t fi : order)
      for_each_cell_of(fi, [&](std::size_t k) { entries_[cursor[k]++] = fi; });
  }

  /// Appends to `out` the parameter intervals of segment a-b (x, y, depth) hidden by some face.
  /// `eps(id)` gives the depth margin a face must be in front by, or a negative value to
  /// ignore that face (e.g. the faces the segment is an edge of). Intervals may overlap.
  /// Returns false, with `out` incomplete, when the work total passed `limit`.
  /// O(cells crossed + faces in front of the segment there x their sides near it).
  template <class EpsFn>
  bool hidden_intervals(const glm::dvec3& a, const glm::dvec3& b, EpsFn&& eps, std::vector<svg_interval>& out,
                        std::uint64_t limit = no_limit) {
    if (faces_.empty()) return true;
    const glm::dvec2 a2(a), b2(b), d = b2 - a2;
    if (glm::dot(d, d) < 1e-18) {
      // Seen end-on: the segment is a point; the nearer end decides.
      const glm::dvec3& front = a.z >= b.z ? a : b;
      const int hidden = point_test(front, eps, limit, std::numeric_limits<std::size_t>::max());
      if (hidden > 0) out.push_back({0.0, 1.0});
      return hidden >= 0;
    }
    const glm::dvec2 slo = glm::min(a2, b2), shi = glm::max(a2, b2);
    ++query_;
    cover_.clear();
    bool complete = true;
    for_each_cell_on_segment(a2, b2, [&](std::size_t cell, double t0, double t1) {
      ++work_;
      if (work_ > limit) return complete = false;
      if (covered(t0, t1)) return true;  // this part is hidden already: no face here can add to it
      const double far = std::min(a.z + t0 * (b.z - a.z), a.z + t1 * (b.z - a.z));
      for (std::uint32_t k = cells_[cell]; k < cells_[cell + 1]; ++k) {
        const std::uint32_t fi = entries_[k];
        const face& f = faces_[fi];
        if (f.near <= far) break;  // this face and all after it are behind the segment here
        ++work_;
        if (stamp_[fi] == query_) continue;
        stamp_[fi] = query_;
        if (f.hi.x < slo.x || f.lo.x > shi.x || f.hi.y < slo.y || f.lo.y > shi.y) continue;
        if (f.a * a.x + f.b * a.y + f.c - a.z <= min_margin_ &&
            f.a * b.x + f.b * b.y + f.c - b.z <= min_margin_)
          continue;  // the face's plane is not in front of the segment anywhere
        work_ += std::min(f.count, banded_face_size);  // eps looks at the face's corners
        const double e = eps(f.id);
        if (e < 0.0) continue;
        const std::size_t before = out.size();
        if (!clip(f, a, b, e, out, limit)) return complete = false;
        if (out.size() == before) continue;
        for (std::size_t i = before; i < out.size(); ++i) cover(out[i]);
        if (covered(t0, t1)) break;
      }
      return true;
    });
    return complete;
  }

  /// True when a face (allowed by `eps`, as above) covers p and is in front of it by more
  /// than its margin. O(faces in front of p in its cell x their sides near p).
  template <class EpsFn>
  bool point_hidden(const glm::dvec3& p, EpsFn&& eps) {
    return point_test(p, eps, no_limit, std::numeric_limits<std::size_t>::max()) > 0;
  }

  /// As point_hidden, looking at no more than `max_faces` of the nearest faces in p's cell:
  /// 1 hidden, 0 not (as far as it looked), -1 the work total passed `limit`.
  template <class EpsFn>
  int point_test(const glm::dvec3& p, EpsFn&& eps, std::uint64_t limit, std::size_t max_faces) {
    if (faces_.empty()) return 0;
    if (p.x < lo_.x || p.x > hi_.x || p.y < lo_.y || p.y > hi_.y) return 0;
    const auto cell = static_cast<std::size_t>(row(p.y)) * nx_ + col(p.x);
    std::size_t looked = 0;
    for (std::uint32_t k = cells_[cell]; k < cells_[cell + 1] && looked < max_faces; ++k) {
      const face& f = faces_[entries_[k]];
      if (f.near <= p.z) break;  // sorted nearest first: the rest are behind p
      if (++work_ > limit) return -1;
      if (p.x < f.lo.x || p.x > f.hi.x || p.y < f.lo.y || p.y > f.hi.y) continue;
      if (f.a * p.x + f.b * p.y + f.c - p.z <= min_margin_) continue;  // plane not in front of p
      work_ += std::min(f.count, banded_face_size);
      const double e = eps(f.id);
      if (e < 0.0) continue;
      ++looked;
      if (f.a * p.x + f.b * p.y + f.c - p.z > e && inside(f, glm::dvec2(p))) return 1;
    }
    return 0;
  }

 private:
  struct face {
    std::uint32_t id = 0, first = 0, count = 0;
    double a = 0, b = 0, c = 0;  // depth(x, y) = a x + b y + c, the plane of Newell's normal
    double near = 0;             // the largest depth of the face (vertices and plane) toward the viewer
    glm::dvec2 lo{0.0}, hi{0.0};
    // Banded faces: bands of equal height over [lo.y, hi.y]; band k lists its sides in
    // band_sides_[band_offsets_[band_first + k] .. band_offsets_[band_first + k + 1]).
    std::uint32_t bands = 0, band_first = 0;
    double band_scale = 0;  // bands per unit of y
  };

  int col(double x) const {
    return static_cast<int>(std::clamp(std::floor((x - lo_.x) * sx_), 0.0, static_cast<double>(nx_ - 1)));
  }
  int row(double y) const {
    return static_cast<int>(std::clamp(std::floor((y - lo_.y) * sy_), 0.0, static_cast<double>(ny_ - 1)));
  }
  static int band(const face& f, double y) {
    return static_cast<int>(
        std::clamp(std::floor((y - f.lo.y) * f.band_scale), 0.0, static_cast<double>(f.bands - 1)));
  }

  /// Side i of a face runs from vertex i - 1 (cyclically) to vertex i.
  std::array<glm::dvec2, 2> side(const face& f, std::uint32_t i) const {
    const glm::dvec2* v = xy_.data() + f.first;
    return {v[i == 0 ? f.count - 1 : i - 1], v[i]};
  }

  /// Lists a large face's sides by the horizontal bands they reach: about one band per 4
  /// sides, fewer when long sides would list more than 16 entries per side. O(entries).
  void index_bands(face& f) {
    const double h = std::max(f.hi.y - f.lo.y, 1e-300);
    std::uint32_t n = std::clamp<std::uint32_t>(f.count / 4, 1, 4096);
    for (;; n /= 2) {
      f.bands = n;
      f.band_scale = n / h;
      if (!std::isfinite(f.band_scale)) f.band_scale = 0.0;
      std::size_t total = 0;
      for (std::uint32_t i = 0; i < f.count; ++i) {
        const auto [p, q] = side(f, i);
        total += static_cast<std::size_t>(band(f, std::max(p.y, q.y)) - band(f, std::min(p.y, q.y)) + 1);
      }
      if (total <= 16 * std::size_t{f.count} || n == 1) break;
    }
    f.band_first = static_cast<std::uint32_t>(band_offsets_.size());
    const std::size_t base = band_offsets_.size();
    band_offsets_.resize(base + f.bands + 1, 0);
    for (std::uint32_t i = 0; i < f.count; ++i) {
      const auto [p, q] = side(f, i);
      for (int k = band(f, std::min(p.y, q.y)), k1 = band(f, std::max(p.y, q.y)); k <= k1; ++k)
        ++band_offsets_[base + k + 1];
    }
    band_offsets_[base] = static_cast<std::uint32_t>(band_sides_.size());
    for (std::size_t k = base + 1; k < band_offsets_.size(); ++k) band_offsets_[k] += band_offsets_[k - 1];
    band_sides_.resize(band_offsets_.back());
    std::vector<std::uint32_t> cursor(band_offsets_.begin() + static_cast<std::ptrdiff_t>(base),
                                      band_offsets_.end() - 1);
    for (std::uint32_t i = 0; i < f.count; ++i) {
      const auto [p, q] = side(f, i);
      for (int k = band(f, std::min(p.y, q.y)), k1 = band(f, std::max(p.y, q.y)); k <= k1; ++k)
        band_sides_[cursor[k]++] = i;
    }
  }

  /// The sides of face f to examine for something in the y range [y0, y1], each once:
  /// fn(side index). All sides for a small face. O(sides listed).
  template <class Fn>
  void for_each_side_near(const face& f, double y0, double y1, Fn&& fn) const {
    if (f.bands == 0) {
      for (std::uint32_t i = 0; i < f.count; ++i) fn(i);
      return;
    }
    const int k0 = band(f, y0), k1 = band(f, y1);
    for (int k = k0; k <= k1; ++k)
      for (std::uint32_t s = band_offsets_[f.band_first + k]; s < band_offsets_[f.band_first + k + 1]; ++s) {
        const std::uint32_t i = band_sides_[s];
        const auto [p, q] = side(f, i);
        if (std::max(k0, band(f, std::min(p.y, q.y))) == k) fn(i);  // listed in its first band we visit
      }
  }

  /// The cells each row of face f reaches, as emit(row, first column, last column): per row,
  /// from the leftmost to the rightmost point of the face's sides within it. O(rows the sides span).
  template <class Emit>
  void row_spans(const face& f, Emit&& emit) {
    const int r0 = row(f.lo.y), r1 = row(f.hi.y);
    span_lo_.assign(static_cast<std::size_t>(r1 - r0 + 1), std::numeric_limits<double>::infinity());
    span_hi_.assign(span_lo_.size(), -std::numeric_limits<double>::infinity());
    const auto reach = [&](int r, double x0, double x1) {
      const auto k = static_cast<std::size_t>(r - r0);
      span_lo_[k] = std::min({span_lo_[k], x0, x1});
      span_hi_[k] = std::max({span_hi_[k], x0, x1});
    };
    for (std::uint32_t i = 0; i < f.count; ++i) {
      auto [p, q] = side(f, i);
      if (p.y > q.y) std::swap(p, q);
      const int ra = row(p.y), rb = row(q.y);
      if (ra == rb) {
        reach(ra, p.x, q.x);
        continue;
      }
      const double slope = (q.x - p.x) / (q.y - p.y), x_lo = std::min(p.x, q.x), x_hi = std::max(p.x, q.x);
      double x = p.x;  // where the side enters the current row
      for (int r = ra; r <= rb; ++r) {
        const double x_next =
            r == rb ? q.x : std::clamp(p.x + slope * (lo_.y + (r + 1) / sy_ - p.y), x_lo, x_hi);
        reach(r, x, x_next);
        x = x_next;
      }
    }
    const double slack = 1e-7 / sx_;  // rounding of the interpolated ends
    for (int r = r0; r <= r1; ++r) {
      const auto k = static_cast<std::size_t>(r - r0);
      if (span_lo_[k] <= span_hi_[k]) emit(r, col(span_lo_[k] - slack), col(span_hi_[k] + slack));
    }
  }

  /// Every cell the segment passes through (a supercover), column by column, with the range
  /// of t (a + t (b - a)) the segment spends in it, widened slightly: fn(cell, t0, t1), which
  /// returns false to stop. O(cells).
  template <class Fn>
  void for_each_cell_on_segment(glm::dvec2 a, glm::dvec2 b, Fn&& fn) const {
    double ax = (a.x - lo_.x) * sx_, ay = (a.y - lo_.y) * sy_;
    double bx = (b.x - lo_.x) * sx_, by = (b.y - lo_.y) * sy_;
    const bool swapped = ax > bx;
    if (swapped) {
      std::swap(ax, bx);
      std::swap(ay, by);
    }
    if (bx < 0.0 || ax > nx_ || std::max(ay, by) < 0.0 || std::min(ay, by) > ny_) return;
    const auto clamp_to = [](double v, int n) {
      return static_cast<int>(std::clamp(std::floor(v), 0.0, static_cast<double>(n - 1)));
    };
    const int c0 = clamp_to(ax, nx_), c1 = clamp_to(bx, nx_);
    const double dx = bx - ax, dy = by - ay;
    for (int c = c0; c <= c1; ++c) {
      // The part of the segment over this column; the end columns reach to the segment's ends.
      const double xl = c == c0 ? ax : c, xr = c == c1 ? bx : c + 1.0;
      double yl = ay, yr = by, ul = 0.0, ur = 1.0;  // u: the parameter from the left end
      if (dx > 0.0) {
        ul = (xl - ax) / dx;
        ur = (xr - ax) / dx;
        yl = ay + dy * ul;
        yr = ay + dy * ur;
      }
      const double lo = std::min(yl, yr) - 1e-9, hi = std::max(yl, yr) + 1e-9;
      if (hi < 0.0 || lo > ny_) continue;
      const int r0 = clamp_to(lo, ny_), r1 = clamp_to(hi, ny_);
      for (int r = r0; r <= r1; ++r) {
        double u0 = ul, u1 = ur;
        if (dy != 0.0 && r0 != r1) {
          // Within the column, the part in this row (the outer rows reach beyond the grid).
          constexpr double inf = std::numeric_limits<double>::infinity();
          const double y0 = r == 0 ? -inf : r, y1 = r == ny_ - 1 ? inf : r + 1.0;
          double s0 = (y0 - ay) / dy, s1 = (y1 - ay) / dy;
          if (s0 > s1) std::swap(s0, s1);
          if (std::max(u0, s0) <= std::min(u1, s1)) {
            u0 = std::max(u0, s0);
            u1 = std::min(u1, s1);
          }
        }
        u0 = std::clamp(u0 - 1e-9, 0.0, 1.0);
        u1 = std::clamp(u1 + 1e-9, 0.0, 1.0);
        const std::size_t cell = static_cast<std::size_t>(r) * nx_ + c;
        if (!(swapped ? fn(cell, 1.0 - u1, 1.0 - u0) : fn(cell, u0, u1))) return;
      }
    }
  }

  /// The merged hidden parts found so far in this query: what a cell's faces need not cover.
  void cover(svg_interval x) {
    constexpr double join = 1e-9;
    auto it = std::lower_bound(cover_.begin(), cover_.end(), x);
    it = cover_.insert(it, x);
    if (it != cover_.begin() && std::prev(it)->at(1) + join >= (*it)[0]) --it;
    auto last = it + 1;
    while (last != cover_.end() && (*it)[1] + join >= (*last)[0]) {
      (*it)[1] = std::max((*it)[1], (*last)[1]);
      ++last;
    }
    cover_.erase(it + 1, last);
  }
  bool covered(double t0, double t1) const {
    auto it = std::upper_bound(cover_.begin(), cover_.end(), svg_interval{t0, 2.0});
    return it != cover_.begin() && (*std::prev(it))[0] <= t0 && (*std::prev(it))[1] >= t1;
  }

  /// Even-odd rule, each side decided exactly (cellforge::detail::crosses_ray); points on the
  /// boundary may go either way. O(sides near p.y).
  bool inside(const face& f, glm::dvec2 p) {
    bool in = false;
    for_each_side_near(f, p.y, p.y, [&](std::uint32_t i) {
      ++work_;
      const auto [vj, vi] = side(f, i);
      if (cellforge::detail::crosses_ray(vi, vj, p)) in = !in;
    });
    return in;
  }

  /// Exact clipping: split the segment where it crosses the face's boundary, keep the pieces
  /// inside, and within each keep where the face is nearer than the segment by more than
  /// `margin` (both depths are linear in t, so that part is one interval found exactly).
  /// False when the work total passed `limit`.
  bool clip(const face& f, const glm::dvec3& a, const glm::dvec3& b, double margin,
            std::vector<svg_interval>& out, std::uint64_t limit) {
    const glm::dvec2 a2(a), d = glm::dvec2(b) - a2;
    const auto gap = [&](double t) {
      return f.a * (a2.x + t * d.x) + f.b * (a2.y + t * d.y) + f.c - (a.z + t * (b.z - a.z)) - margin;
    };
    // Cheap rejections first: the face's plane behind the whole segment (the gap is linear
    // in t), or (small faces) the whole face on one side of the segment's line.
    if (gap(0.0) <= 0.0 && gap(1.0) <= 0.0) return true;
    if (f.bands == 0) {
      const glm::dvec2* v = xy_.data() + f.first;
      int sides = 0;
      for (std::uint32_t i = 0; i < f.count; ++i) {
        const double side = d.x * (v[i].y - a2.y) - d.y * (v[i].x - a2.x);
        sides |= side > 0.0 ? 1 : side < 0.0 ? 2 : 3;
      }
      work_ += f.count;
      if (sides != 3) return true;
    }
    ts_.assign({0.0, 1.0});
    const double y0 = std::min(a.y, b.y), y1 = std::max(a.y, b.y);
    for_each_side_near(f, y0, y1, [&](std::uint32_t i) {
      ++work_;
      const auto [vj, vi] = side(f, i);
      const glm::dvec2 e = vi - vj, w = vj - a2;
      const double den = d.x * e.y - d.y * e.x;
      if (den == 0.0) return;  // parallel: touching along the boundary hides nothing
      const double t = (w.x * e.y - w.y * e.x) / den, s = (w.x * d.y - w.y * d.x) / den;
      if (t > 0.0 && t < 1.0 && s >= -1e-12 && s <= 1.0 + 1e-12) ts_.push_back(t);
    });
    std::sort(ts_.begin(), ts_.end());
    for (std::size_t k = 0; k + 1 < ts_.size(); ++k) {
      if (work_ > limit) return false;
      const double t0 = ts_[k], t1 = ts_[k + 1];
      if (!(t1 - t0 > 1e-12)) continue;
      const double g0 = gap(t0), g1 = gap(t1);
      if (!(g0 > 0.0 || g1 > 0.0)) continue;
      if (!inside(f, a2 + (0.5 * (t0 + t1)) * d)) continue;
      if (g0 > 0.0 && g1 > 0.0)
        out.push_back({t0, t1});
      else if (g0 > 0.0)
        out.push_back({t0, t0 + (t1 - t0) * (g0 / (g0 - g1))});
      else
        out.push_back({t0 + (t1 - t0) * (g0 / (g0 - g1)), t1});
    }
    return true;
  }

  std::vector<face> faces_;
  std::vector<glm::dvec2> xy_;
  std::vector<std::uint32_t> band_offsets_, band_sides_;  // banded faces' sides by band (CSR)
  std::vector<std::uint32_t> cells_;                      // CSR offsets, one per cell + 1
  std::vector<std::uint32_t> entries_;                    // face indices, cell by cell, nearest first
  std::vector<std::uint32_t> stamp_;            // last query that tested each face: no face tested twice
  std::vector<double> span_lo_, span_hi_, ts_;  // scratch: a face's reach per row; crossing parameters
  std::vector<svg_interval> cover_;             // scratch: merged hidden parts of the current segment
  std::uint64_t work_ = 0;
  double min_margin_ = 0.0;
  std::uint32_t query_ = 0;
  glm::dvec2 lo_{0.0}, hi_{0.0};
  double sx_ = 1, sy_ = 1;
  int nx_ = 1, ny_ = 1;
};

}  // namespace cellforge::io::detail
