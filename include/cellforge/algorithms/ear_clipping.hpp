// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Ear-clipping triangulation of planar polygons in 3D (seed 001 §III, algorithm 2), with
/// exact orientation tests, collinear vertices, repeated vertices and a grid that keeps a
/// 10,000-vertex comb or star fast; plus helpers that triangulate every face of a soup or
/// a half-edge mesh. See docs/convex_hull.md (ear clipping section).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <ranges>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/edge_table.hpp"
#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

/// How ear_clip treats its polygon.
struct ear_clip_options {
  /// Largest distance of a vertex from the polygon's plane (through the centroid, normal
  /// to the Newell normal), as a fraction of the polygon's bounding-box diagonal; a
  /// polygon further from planar is rejected.
  double planarity_tolerance = 1e-6;
  /// When no ear can be found (only a polygon that crosses or touches itself gets there):
  /// false throws; true finishes with forced ears, counted in the report, whose triangles
  /// may overlap.
  bool allow_non_simple = false;
};

/// What ear_clip found.
struct ear_clip_report {
  glm::dvec3 normal{0.0};    ///< unit Newell normal: the triangles turn about it as the polygon does
  double area = 0;           ///< the polygon's area
  double max_deviation = 0;  ///< largest distance of a vertex from the plane
  /// Zero-area triangles emitted to keep repeated consecutive vertices (zero-length
  /// edges) in the triangulation; no other zero-area triangle is ever emitted.
  std::size_t degenerate_triangles = 0;
  std::size_t forced_ears = 0;  ///< ears clipped without the containment test (non-simple input)
};

/// A triangle as three indices into the polygon (or the soup's points).
using index_triangle = std::array<std::uint32_t, 3>;

namespace detail::ears {

/// Newell's normal of polygon p, summed about its centroid for accuracy (not normalised); for a
/// polygon of N corners known when compiling (a quad's) the loop unrolled, the same sums in the
/// same order. O(n).
template <std::size_t N = std::dynamic_extent>
glm::dvec3 newell_normal(std::span<const glm::dvec3, N> p, const glm::dvec3& centroid) noexcept {
  if constexpr (N == std::dynamic_extent) {
    return cellforge::detail::newell(cellforge::detail::index_range{p.size()},
                                     [&](std::size_t i) { return p[i] - centroid; });
  } else {
    glm::dvec3 n(0.0);
    for (std::size_t i = 0; i < N; ++i) {
      const glm::dvec3 a = p[i] - centroid, b = p[(i + 1) % N] - centroid;
      n += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    return n;
  }
}

/// The axis clipping projects along: the normal's largest component (the first on a tie). O(1).
template <class = void>
int dominant_axis(const glm::dvec3& normal) noexcept {
  int k = 0;
  for (int a = 1; a < 3; ++a)
    if (std::fabs(normal[a]) > std::fabs(normal[k])) k = a;
  return k;
}

inline constexpr std::uint32_t none = 0xFFFFFFFFu;

template <class = void>
struct basic_cell_grid;
using cell_grid = basic_cell_grid<>;

/// A uniform grid over a 2D box with about `count` roughly square cells; cover() lists the
/// cells a small convex polygon (a segment or a triangle) overlaps, slab by slab, so that
/// long thin shapes visit the cells they cross rather than their whole bounding box.
template <class>
struct basic_cell_grid {
  double lx = 0, ly = 0, hx = 0, hy = 0, sx = 0, sy = 0, margin_x = 0, margin_y = 0;
  std::size_t nx = 1, ny = 1;

  basic_cell_grid(double lx_, double ly_, double hx_, double hy_, std::size_t count)
      : lx(lx_), ly(ly_), hx(hx_), hy(hy_) {
    const double w = hx - lx, h = hy - ly, cells = static_cast<double>(std::max<std::size_t>(1, count));
    // Square cells: nx / ny follows the box's aspect ratio (a long comb gets many columns).
    const double side = w > 0 && h > 0 ? std::sqrt(w * h / cells) : std::max(w, h) / cells;
    auto fit = [&](double extent) {
      return side > 0 ? static_cast<std::size_t>(std::clamp(extent / side, 1.0, cells)) : std::size_t{1};
    };
    nx = fit(w);
    ny = fit(h);
    sx = w > 0 ? static_cast<double>(nx) / w : 0.0;
    sy = h > 0 ? static_cast<double>(ny) / h : 0.0;
    // Cell bounds are rounded; a margin of a millionth of a cell keeps cover() conservative.
    margin_x = 1e-6 * w / static_cast<double>(nx);
    margin_y = 1e-6 * h / static_cast<double>(ny);
  }
  std::size_t size() const noexcept { return nx * ny; }
  std::size_t col(double x) const {
    const double t = (x - lx) * sx;
    return t <= 0 ? 0 : std::min(nx - 1, static_cast<std::size_t>(t));
  }
  std::size_t row(double y) const {
    const double t = (y - ly) * sy;
    return t <= 0 ? 0 : std::min(ny - 1, static_cast<std::size_t>(t));
  }
  std::size_t cell(double x, double y) const { return row(y) * nx + col(x); }
  /// Calls visit(cell) for every cell the convex polygon (px, py)[0..k) may overlap. O(cells).
  template <class Visit>
  void cover(const double* px, const double* py, int k, Visit&& visit) const {
    double y_lo = py[0], y_hi = py[0], x_lo = px[0], x_hi = px[0];
    for (int i = 1; i < k; ++i)
      y_lo = std::min(y_lo, py[i]), y_hi = std::max(y_hi, py[i]), x_lo = std::min(x_lo, px[i]),
      x_hi = std::max(x_hi, px[i]);
    const std::size_t r0 = row(y_lo - margin_y), r1 = row(y_hi + margin_y);
    for (std::size_t r = r0; r <= r1; ++r) {
      // The polygon's x-extent within this row's slab: its vertices inside the slab and
      // its edges' crossings of the slab's two lines.
      const double s0 = r == r0 ? y_lo : ly + static_cast<double>(r) / sy - margin_y;
      const double s1 = r == r1 ? y_hi : ly + static_cast<double>(r + 1) / sy + margin_y;
      double a = x_hi, b = x_lo;
      for (int i = 0; i < k; ++i) {
        if (py[i] >= s0 && py[i] <= s1) a = std::min(a, px[i]), b = std::max(b, px[i]);
        const int j = (i + 1) % k;
        if (py[i] == py[j]) continue;
        for (const double line : {s0, s1})
          if ((line - py[i]) * (line - py[j]) <= 0) {
            const double x = px[i] + (line - py[i]) * (px[j] - px[i]) / (py[j] - py[i]);
            a = std::min(a, x), b = std::max(b, x);
          }
      }
      if (a > b) a = x_lo, b = x_hi;  // nothing found (rounding): fall back to the box
      const std::size_t c0 = col(std::max(x_lo, a) - margin_x), c1 = col(std::min(x_hi, b) + margin_x);
      for (std::size_t c = c0; c <= c1; ++c) visit(r * nx + c);
    }
  }
};

/// Items bucketed by grid cell in CSR form: entries[start[c] .. start[c+1]) lie in cell c.
struct buckets {
  std::vector<std::uint32_t> start, entries;

  /// `each(item, emit)` calls emit(cell) for every cell of the item. O(total entries).
  template <class Each>
  void build(std::size_t cells, std::uint32_t items, Each&& each) {
    start.assign(cells + 1, 0);
    for (std::uint32_t i = 0; i < items; ++i) each(i, [&](std::size_t c) { ++start[c + 1]; });
    for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
    entries.resize(start.back());
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t i = 0; i < items; ++i) each(i, [&](std::size_t c) { entries[fill[c]++] = i; });
  }
};

/// True when the closed segments ab and cd share a point (exact).
template <class = void>
bool segments_meet(const double* x, const double* y, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                   std::uint32_t d) {
  return cellforge::detail::segments_meet(glm::dvec2(x[a], y[a]), glm::dvec2(x[b], y[b]),
                                          glm::dvec2(x[c], y[c]), glm::dvec2(x[d], y[d]));
}

/// True when the walk p -> q -> s, with s on the line pq, turns back over itself (exact).
template <class = void>
bool folds_back(const double* x, const double* y, std::uint32_t p, std::uint32_t q, std::uint32_t s) {
  if (orient2d(x[p], y[p], x[q], y[q], x[s], y[s]) != 0) return false;
  // On one line, compare directions along an axis on which the line is not constant.
  const bool use_x = x[q] != x[p];
  const double in = use_x ? x[q] - x[p] : y[q] - y[p], out = use_x ? x[s] - x[q] : y[s] - y[q];
  return (in > 0 && out < 0) || (in < 0 && out > 0);
}

/// The first pair of ring edges (edge k runs from ring[k] to ring[k+1]) that cross or touch
/// other than adjacent edges at their shared vertex, or {none, none} for a simple polygon.
/// Edges are bucketed in a grid by the cells they cross; pairs sharing a cell are tested
/// exactly. O(n + pairs of edges sharing a cell).
template <class = void>
std::pair<std::uint32_t, std::uint32_t> first_crossing(const std::vector<double>& x,
                                                       const std::vector<double>& y,
                                                       const std::vector<std::uint32_t>& ring) {
  const auto m = static_cast<std::uint32_t>(ring.size());
  double lx = x[ring[0]], hx = lx, ly = y[ring[0]], hy = ly;
  for (std::uint32_t v : ring)
    lx = std::min(lx, x[v]), hx = std::max(hx, x[v]), ly = std::min(ly, y[v]), hy = std::max(hy, y[v]);
  const cell_grid grid(lx, ly, hx, hy, 2 * static_cast<std::size_t>(m));
  buckets cells;
  cells.build(grid.size(), m, [&](std::uint32_t e, auto&& emit) {
    const std::uint32_t a = ring[e], b = ring[(e + 1) % m];
    const double px[2] = {x[a], x[b]}, py[2] = {y[a], y[b]};
    grid.cover(px, py, 2, emit);
  });
  for (std::size_t k = 0; k + 1 < cells.start.size(); ++k)
    for (std::uint32_t i = cells.start[k]; i < cells.start[k + 1]; ++i)
      for (std::uint32_t j = i + 1; j < cells.start[k + 1]; ++j) {
        std::uint32_t e = cells.entries[i], f = cells.entries[j];
        if (e > f) std::swap(e, f);
        const std::uint32_t a = ring[e], b = ring[(e + 1) % m], c = ring[f], d = ring[(f + 1) % m];
        if (f == e + 1) {  // adjacent: they share b == c and meet elsewhere only by folding back
          if (folds_back(x.data(), y.data(), a, b, d)) return {e, f};
        } else if (e == 0 && f == m - 1) {  // adjacent across the ring's start: d == a
          if (folds_back(x.data(), y.data(), c, a, b)) return {e, f};
        } else if (segments_meet(x.data(), y.data(), a, b, c, d)) {
          return {e, f};
        }
      }
  return {none, none};
}

template <class = void>
class basic_clipper;
using clipper = basic_clipper<>;

/// The ear-clipping state over a 2D projection of the polygon (a ring of kept vertices).
template <class>
class basic_clipper {
 public:
  basic_clipper(std::vector<double> x, std::vector<double> y, std::vector<std::uint32_t> ring, int sense)
      : x_(std::move(x)), y_(std::move(y)), sense_(sense), grid_(0, 0, 0, 0, 1) {
    const std::size_t n = x_.size();
    prev_.assign(n, none);
    next_.assign(n, none);
    convex_.assign(n, 0);
    active_.assign(n, 0);
    for (std::size_t k = 0; k < ring.size(); ++k) {
      next_[ring[k]] = ring[(k + 1) % ring.size()];
      prev_[ring[(k + 1) % ring.size()]] = ring[k];
    }
    ring_ = std::move(ring);
    // Only non-convex (reflex or flat) vertices can block an ear of a simple polygon.
    std::vector<std::uint32_t> candidates;
    double lx = x_[ring_[0]], hx = lx, ly = y_[ring_[0]], hy = ly;
    for (std::uint32_t v : ring_) {
      convex_[v] = turn(prev_[v], v, next_[v]) > 0;
      if (!convex_[v]) candidates.push_back(v), active_[v] = 1;
      lx = std::min(lx, x_[v]), hx = std::max(hx, x_[v]), ly = std::min(ly, y_[v]), hy = std::max(hy, y_[v]);
    }
    grid_ = cell_grid(lx, ly, hx, hy, candidates.size());
    cells_.build(
        grid_.size(), static_cast<std::uint32_t>(candidates.size()),
        [&](std::uint32_t k, auto&& emit) { emit(grid_.cell(x_[candidates[k]], y_[candidates[k]])); });
    for (auto& e : cells_.entries) e = candidates[e];
  }

  /// Clips ears until one triangle is left. O(n²) worst case, near O(n) for most shapes.
  void run(bool allow_non_simple, std::vector<index_triangle>& out, ear_clip_report& report) {
    std::size_t remaining = ring_.size();
    std::uint32_t i = ring_[0];
    std::size_t stall = 0;
    bool thin_ok = false;  // slivers (rounding-level area) wait until a lap finds nothing better
    while (remaining > 3) {
      if (convex_[i] && is_ear(i)) {
        const bool thin = is_thin(i);
        if (!thin || thin_ok) {
          thin_ok = thin_ok && thin;
          i = clip(i, out);
          --remaining;
          stall = 0;
          continue;
        }
      }
      i = next_[i];
      if (++stall <= remaining) continue;
      stall = 0;
      if (!thin_ok) {
        thin_ok = true;
        continue;
      }
      // A whole lap without an ear: the polygon crosses or touches itself.
      if (!allow_non_simple)
        throw error(
            error_category::invalid_input,
            cellforge::detail::cat("ear_clip: the polygon is not simple (no ear left among ",
                                   std::to_string(remaining), " vertices around vertex ", std::to_string(i),
                                   "); set allow_non_simple to triangulate it anyway"));
      std::uint32_t pick = i;
      for (std::size_t k = 0; k < remaining && !convex_[pick]; ++k) pick = next_[pick];
      ++report.forced_ears;
      i = clip(pick, out);
      --remaining;
    }
    const std::uint32_t p = prev_[i], n = next_[i];
    if (turn(p, i, n) <= 0) {
      if (!allow_non_simple)
        throw error(error_category::invalid_input,
                    "ear_clip: the polygon is not simple (its last triangle is inverted or flat)");
      ++report.forced_ears;
    }
    out.push_back({p, i, n});
  }

 private:
  int turn(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    return sense_ * orient2d(x_[a], y_[a], x_[b], y_[b], x_[c], y_[c]);
  }

  // An ear whose area is at rounding level for its size: its vertices are collinear up to
  // the rounding of a projection or transformation of the input.
  bool is_thin(std::uint32_t i) const {
    const std::uint32_t a = prev_[i], c = next_[i];
    const double ux = x_[i] - x_[a], uy = y_[i] - y_[a], vx = x_[c] - x_[a], vy = y_[c] - y_[a];
    const double wx = x_[c] - x_[i], wy = y_[c] - y_[i];
    const double longest = std::max({ux * ux + uy * uy, vx * vx + vy * vy, wx * wx + wy * wy});
    return std::fabs(ux * vy - uy * vx) <= 1e-12 * longest;
  }

  // True when no other active vertex lies in the closed triangle (prev, i, next).
  bool is_ear(std::uint32_t i) const {
    const std::uint32_t a = prev_[i], c = next_[i];
    const double lx = std::min({x_[a], x_[i], x_[c]}), hx = std::max({x_[a], x_[i], x_[c]});
    const double ly = std::min({y_[a], y_[i], y_[c]}), hy = std::max({y_[a], y_[i], y_[c]});
    // Each side's line as n·q + k, scaled so that rounding cannot push a point of the
    // closed triangle below -slack: a cheap rejection before the exact tests.
    struct side {
      double nx, ny, k, slack;
    };
    auto make_side = [&](std::uint32_t p, std::uint32_t q) {
      const double nx = (y_[p] - y_[q]) * sense_, ny = (x_[q] - x_[p]) * sense_;
      const double k = -(nx * x_[p] + ny * y_[p]);
      const double size = std::fabs(nx) * (std::fabs(x_[p]) + std::fabs(hx) + std::fabs(lx)) +
                          std::fabs(ny) * (std::fabs(y_[p]) + std::fabs(hy) + std::fabs(ly));
      return side{nx, ny, k, 1e-9 * size};
    };
    const side sides[3] = {make_side(a, i), make_side(i, c), make_side(c, a)};
    auto blocks = [&](std::uint32_t r) {
      if (!active_[r] || r == a || r == i || r == c) return false;
      if (x_[r] < lx || x_[r] > hx || y_[r] < ly || y_[r] > hy) return false;
      for (const side& s : sides)
        if (s.nx * x_[r] + s.ny * y_[r] + s.k < -s.slack) return false;
      return turn(a, i, r) >= 0 && turn(i, c, r) >= 0 && turn(c, a, r) >= 0;
    };
    for (std::uint32_t r : late_)
      if (blocks(r)) return false;
    const double px[3] = {x_[a], x_[i], x_[c]}, py[3] = {y_[a], y_[i], y_[c]};
    bool blocked = false;
    grid_.cover(px, py, 3, [&](std::size_t k) {
      for (std::uint32_t e = cells_.start[k]; e < cells_.start[k + 1] && !blocked; ++e)
        blocked = blocks(cells_.entries[e]);
    });
    return !blocked;
  }

  // Emits the ear at i, unlinks i, reclassifies its neighbours; returns where to go on
  // (one past the next vertex, which spreads the ears and avoids long fans of slivers).
  std::uint32_t clip(std::uint32_t i, std::vector<index_triangle>& out) {
    const std::uint32_t p = prev_[i], n = next_[i];
    out.push_back({p, i, n});
    next_[p] = n;
    prev_[n] = p;
    active_[i] = 0;
    for (std::uint32_t v : {p, n}) {
      const bool was_convex = convex_[v] != 0;
      convex_[v] = turn(prev_[v], v, next_[v]) > 0;
      if (convex_[v]) {
        active_[v] = 0;
      } else if (was_convex) {  // only a non-simple polygon turns a convex vertex reflex
        active_[v] = 1;
        late_.push_back(v);
      }
    }
    return next_[n];
  }

  std::vector<double> x_, y_;
  int sense_;
  std::vector<std::uint32_t> ring_, prev_, next_;
  std::vector<std::uint8_t> convex_, active_;
  std::vector<std::uint32_t> late_;  // vertices that became non-convex after the grid was built
  cell_grid grid_;
  buckets cells_;
};

/// Puts back the vertices dropped as repeats of their predecessor: each splits the one
/// triangle on the edge it interrupts into a zero-area one and a copy. O(n) expected.
template <class = void>
void restore_repeats(std::span<const std::uint8_t> kept, std::vector<index_triangle>& tris,
                     ear_clip_report& report) {
  const auto n = static_cast<std::uint32_t>(kept.size());
  const auto key = edge_table::key;
  edge_table owner;  // directed edge -> triangle
  owner.reserve(3 * tris.size());
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) owner.insert(key(tris[t][k], tris[t][(k + 1) % 3]), t);
  std::uint32_t start = 0;
  while (!kept[start]) ++start;
  std::uint32_t u = start;  // the last vertex already in the ring
  for (std::uint32_t step = 1; step <= n; ++step) {
    const std::uint32_t c = (start + step) % n;
    if (kept[c]) {
      u = c;
      continue;
    }
    std::uint32_t w = (c + 1) % n;
    while (!kept[w]) w = (w + 1) % n;
    const std::uint32_t t = owner.find(key(u, w));
    if (t == edge_table::not_found) throw error(error_category::internal, "ear_clip: lost a boundary edge");
    index_triangle tri = tris[t];
    while (tri[0] != u) std::rotate(tri.begin(), tri.begin() + 1, tri.end());
    const std::uint32_t y = tri[2];  // tri = (u, w, y)
    tris[t] = {u, c, y};             // zero area: c repeats u
    tris.push_back({c, w, y});
    owner.erase(key(u, w));
    owner.insert(key(u, c), t);
    owner.insert(key(c, y), t);
    owner.insert(key(y, u), t);
    const auto t2 = static_cast<std::uint32_t>(tris.size() - 1);
    owner.insert(key(c, w), t2);
    owner.insert(key(w, y), t2);
    owner.insert(key(y, c), t2);
    ++report.degenerate_triangles;
    u = c;
  }
}

/// Ear clipping on double-precision points; see ear_clip.
template <class = void>
std::vector<index_triangle> clip_polygon(std::span<const glm::dvec3> p, const ear_clip_options& options,
                                         ear_clip_report& report) {
  const std::size_t n = p.size();
  if (n < 3)
    throw error(
        error_category::invalid_input,
        cellforge::detail::cat("ear_clip: a polygon needs at least 3 vertices, got ", std::to_string(n)));
  if (n >= none) throw error(error_category::invalid_input, "ear_clip: too many vertices for 32-bit indices");
  if (!(options.planarity_tolerance >= 0))
    throw error(error_category::invalid_input, "ear_clip: planarity_tolerance must be >= 0");
  glm::dvec3 lo(p[0]), hi(p[0]), centroid(0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("ear_clip: vertex ", std::to_string(i),
                                         " has a NaN or infinite coordinate"));
    lo = glm::min(lo, p[i]);
    hi = glm::max(hi, p[i]);
    centroid += p[i];
  }
  centroid /= static_cast<double>(n);
  const glm::dvec3 newell = newell_normal(p, centroid);
  const double diagonal = glm::length(hi - lo), length = glm::length(newell);
  if (!(length > 1e-14 * diagonal * diagonal))
    throw error(error_category::invalid_input,
                cellforge::detail::cat("ear_clip: the polygon has no area (all ", std::to_string(n),
                                       " vertices on one line or point)"));
  report.normal = newell / length;
  report.area = 0.5 * length;
  for (std::size_t i = 0; i < n; ++i)
    report.max_deviation =
        std::max(report.max_deviation, std::fabs(glm::dot(p[i] - centroid, report.normal)));
  if (report.max_deviation > options.planarity_tolerance * diagonal)
    throw error(error_category::invalid_input,
                cellforge::detail::cat("ear_clip: the polygon is not planar: a vertex lies ",
                                       std::to_string(report.max_deviation),
                                       " from its plane, more than planarity_tolerance (",
                                       std::to_string(options.planarity_tolerance), ") times its size ",
                                       std::to_string(diagonal)));

  // Project by dropping the dominant axis of the normal: exact (no rounding), so the
  // orientation tests are exact on the input coordinates. The kept axes (k+1, k+2) in
  // cyclic order see the polygon turn with the sign of that normal component.
  const int k = dominant_axis(newell);
  const int u = (k + 1) % 3, v = (k + 2) % 3;
  const int sense = newell[k] > 0 ? 1 : -1;
  std::vector<double> x(n), y(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = p[i][u], y[i] = p[i][v];

  // A vertex repeating its predecessor is a zero-length edge: clip without it, put it back.
  std::vector<std::uint8_t> kept(n, 1);
  std::vector<std::uint32_t> ring;
  for (std::uint32_t i = 0; i < n; ++i) {
    const auto before = static_cast<std::uint32_t>((i + n - 1) % n);
    if (p[i] == p[before]) kept[i] = 0;
  }
  if (std::none_of(kept.begin(), kept.end(), [](std::uint8_t b) { return b != 0; })) kept[0] = 1;
  for (std::uint32_t i = 0; i < n; ++i)
    if (kept[i]) ring.push_back(i);
  if (ring.size() < 3)
    throw error(error_category::invalid_input, "ear_clip: the polygon has fewer than 3 distinct vertices");

  if (!options.allow_non_simple) {
    const auto [e, f] = first_crossing(x, y, ring);
    if (e != none)
      throw error(
          error_category::invalid_input,
          cellforge::detail::cat("ear_clip: the polygon is not simple: its edges from vertex ",
                                 std::to_string(ring[e]), " and from vertex ", std::to_string(ring[f]),
                                 " cross or touch; set allow_non_simple to triangulate it anyway"));
  }
  std::vector<index_triangle> tris;
  tris.reserve(n - 2);
  clipper c(std::move(x), std::move(y), std::move(ring), sense);
  c.run(options.allow_non_simple, tris, report);
  // Every ring edge lies in exactly one clipped triangle (forced ears included), so the
  // repeats can always go back in.
  if (std::find(kept.begin(), kept.end(), 0) != kept.end())
    restore_repeats(detail::span_of(kept), tris, report);
  return tris;
}

}  // namespace detail::ears

/// Triangulates a simple planar polygon given in order (either orientation, concave,
/// with collinear or repeated vertices) into n - 2 triangles of polygon indices, each
/// turning like the polygon. Zero-area triangles appear only for repeated consecutive
/// vertices (counted in the report). Throws cellforge::error for fewer than 3 vertices,
/// NaN/Inf, zero area, non-planar or (unless allowed) non-simple polygons.
/// O(n²) worst case; a grid of reflex vertices makes common shapes near O(n).
template <Point3 P>
std::vector<index_triangle> ear_clip(std::span<const P> polygon, const ear_clip_options& options = {},
                                     ear_clip_report* report = nullptr) {
  std::vector<glm::dvec3> p(polygon.size());
  for (std::size_t i = 0; i < polygon.size(); ++i) p[i] = to_dvec3(polygon[i]);
  ear_clip_report r;
  std::vector<index_triangle> tris = detail::ears::clip_polygon(detail::span_of(p), options, r);
  if (report) *report = r;
  return tris;
}

/// ear_clip of a vector of points. O(n²) worst case.
template <Point3 P>
std::vector<index_triangle> ear_clip(const std::vector<P>& polygon, const ear_clip_options& options = {},
                                     ear_clip_report* report = nullptr) {
  return ear_clip(std::span<const P>(polygon), options, report);
}

/// What triangulating every face of a soup or mesh did.
struct triangulate_report {
  std::size_t polygons = 0;              ///< faces with more than 3 vertices that were clipped
  std::size_t triangles_added = 0;       ///< triangles that replaced them
  std::size_t degenerate_triangles = 0;  ///< zero-area triangles for repeated vertices
  std::size_t forced_ears = 0;           ///< non-simple faces (with allow_non_simple)
  /// Soup version: for each output triangle, the input face it came from.
  std::vector<std::uint32_t> source_face;
};

/// A soup with every face of more than 3 vertices ear-clipped; triangles keep their
/// face's orientation and report.source_face says where each came from. Errors name the
/// face. O(Σ face size²) worst case.
template <Point3 P>
polygon_soup<P> triangulate(const polygon_soup<P>& soup, const ear_clip_options& options = {},
                            triangulate_report* report = nullptr) {
  polygon_soup<P> out;
  out.points = soup.points;
  triangulate_report r;
  std::vector<glm::dvec3> corners;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto face = soup.face(f);
    for (std::uint32_t v : face)
      if (v >= soup.points.size())
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("triangulate: face ", std::to_string(f), " uses vertex ",
                                           std::to_string(v), " of ", std::to_string(soup.points.size())));
    if (face.size() == 3) {
      out.add_face(face);
      r.source_face.push_back(static_cast<std::uint32_t>(f));
      continue;
    }
    corners.clear();
    for (std::uint32_t v : face) corners.push_back(to_dvec3(soup.points[v]));
    ear_clip_report er;
    std::vector<index_triangle> tris;
    try {
      tris = detail::ears::clip_polygon(detail::span_of(corners), options, er);
    } catch (const error& e) {
      throw error(e.category(),
                  cellforge::detail::cat("triangulate: face ", std::to_string(f), ": ", e.message()));
    }
    ++r.polygons;
    r.degenerate_triangles += er.degenerate_triangles;
    r.forced_ears += er.forced_ears;
    for (const index_triangle& t : tris) {
      out.add_face({face[t[0]], face[t[1]], face[t[2]]});
      r.source_face.push_back(static_cast<std::uint32_t>(f));
      ++r.triangles_added;
    }
  }
  if (report) *report = std::move(r);
  return out;
}

/// Replaces every face of more than 3 vertices of m by
/// its ear-clipped triangles, in place: vertices and their properties stay, the new faces
/// get default face properties (with `source_face_property` non-empty, a uint32 face
/// property of that name records each face's original index). Everything is checked before
/// the mesh is touched: on error it is unchanged. Removed faces stay as garbage until
/// garbage_collection(). O(Σ face size²) worst case.
template <Point3 P>
triangulate_report triangulate_faces(surface_mesh<P>& m, const ear_clip_options& options = {},
                                     std::string_view source_face_property = {}) {
  const std::span<const P> pos = m.points();
  triangulate_report r;
  struct job {
    face_handle face;
    std::vector<vertex_handle> vs;
    std::vector<index_triangle> tris;
  };
  std::vector<job> jobs;
  std::vector<glm::dvec3> corners;
  detail::edge_table diagonals;  // undirected vertex pairs of the diagonals so far
  auto key = [](vertex_handle a, vertex_handle b) {
    return (static_cast<std::uint64_t>(std::min(a.idx(), b.idx())) << 32) | std::max(a.idx(), b.idx());
  };
  for (face_handle f : m.faces()) {
    if (m.valence(f) == 3) continue;
    job j;
    j.face = f;
    for (vertex_handle v : m.vertices_around(f)) j.vs.push_back(v);
    corners.clear();
    for (vertex_handle v : j.vs) corners.push_back(to_dvec3(pos[v.idx()]));
    ear_clip_report er;
    try {
      j.tris = detail::ears::clip_polygon(detail::span_of(corners), options, er);
    } catch (const error& e) {
      throw error(e.category(), cellforge::detail::cat("triangulate_faces: face ", std::to_string(f.idx()),
                                                       ": ", e.message()));
    }
    // A diagonal that is already an edge (or another face's diagonal) would give an edge
    // more than two faces: refuse before changing anything.
    const std::size_t n = j.vs.size();
    for (const index_triangle& t : j.tris)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = t[k], b = t[(k + 1) % 3];
        if ((a + 1) % n == b || (b + 1) % n == a) continue;  // a polygon side
        const vertex_handle va = j.vs[a], vb = j.vs[b];
        if (a < b && (m.find_edge(va, vb).is_valid() || !diagonals.try_insert(key(va, vb), 0)))
          throw error(error_category::topology,
                      cellforge::detail::cat("triangulate_faces: face ", std::to_string(f.idx()),
                                             " needs the diagonal ", std::to_string(va.idx()), "-",
                                             std::to_string(vb.idx()),
                                             ", which already is an edge: the result would not be manifold"));
      }
    r.degenerate_triangles += er.degenerate_triangles;
    r.forced_ears += er.forced_ears;
    jobs.push_back(std::move(j));
  }
  property<face_handle, std::uint32_t> source;
  if (!source_face_property.empty()) {
    source =
        m.template property_or_add<face_handle, std::uint32_t>(source_face_property, halfedge_mesh::npos);
    for (face_handle f : m.faces()) source[f] = f.idx();
  }
  for (const job& j : jobs) {
    m.remove_face(j.face);
    for (const index_triangle& t : j.tris) {
      const face_handle nf = m.add_face({j.vs[t[0]], j.vs[t[1]], j.vs[t[2]]});
      if (source) source[nf] = j.face.idx();
      ++r.triangles_added;
    }
    ++r.polygons;
  }
  return r;
}

}  // namespace cellforge
