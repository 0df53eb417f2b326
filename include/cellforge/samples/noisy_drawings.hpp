// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Inexact test drawings: the sample drawings (samples/drawings.hpp) with every junction
/// moved at random by up to a fraction of the drawing's diagonal, as a hand or a pen would
/// place it. The measure of tidy_to_solid and of drawing_to_cells on sketches; see
/// docs/sketch.md, "Tidying".

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/samples/drawings.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge::samples {

/// The drawing with every junction moved in a uniformly random direction by a distance
/// uniform in [0, fraction × the bounding-box diagonal], from `seed`. O(V).
template <class = void>
line_drawing<glm::dvec2> jitter_drawing(const line_drawing<glm::dvec2>& d, double fraction,
                                        std::uint64_t seed) {
  line_drawing<glm::dvec2> out = d;
  if (d.points.empty()) return out;
  glm::dvec2 lo = d.points[0], hi = d.points[0];
  for (const auto& q : d.points) lo = glm::min(lo, q), hi = glm::max(hi, q);
  const double reach = fraction * glm::length(hi - lo);
  cellforge::detail::splitmix rng{seed};
  for (auto& q : out.points) {
    const double angle = rng.uniform(0, 2 * std::numbers::pi);
    const double distance = reach * rng.uniform(0, 1);
    q += distance * glm::dvec2(std::cos(angle), std::sin(angle));
  }
  return out;
}

/// Options of noisy_sweep.
struct noisy_sweep_options {
  sketch_sweep_options sweep{};  ///< the drawings jittered (its min_margin is raised, below)
  double jitter = 0.002;         ///< the largest move, relative to the drawing's diagonal
  std::uint64_t seed = 1;        ///< seed of the moves (each drawing its own, by its index)
};

/// A jittered sample drawing: the exact one with its truth, and the drawing as jittered.
struct noisy_drawing {
  sample_drawing exact;
  line_drawing<glm::dvec2> drawing;
  double spacing = 0.0;  ///< the exact drawing's junction spacing, relative to its diagonal
};

/// What noisy_sweep kept: the sweep's drawings, those left out because a junction of theirs is
/// within twice the jitter of another junction or of a line not at it, the drawings made.
struct noisy_sweep_report {
  sketch_sweep_report sweep;
  std::size_t too_close = 0, drawings = 0;
};

/// The sample drawings at one jitter: views chosen with generic margin at least 2.5 × jitter
/// (sweep.min_margin raised to it: a hand draws a view in which nothing is closer than its
/// precision), every drawing whose junction spacing exceeds twice the jitter (so no junction
/// can cross a line, which would make another drawing), each jittered by jitter_drawing. Views
/// and moves are deterministic. O(sweep + Σ (V² + V·E)).
template <class = void>
std::vector<noisy_drawing> noisy_sweep(const noisy_sweep_options& options,
                                       noisy_sweep_report* report = nullptr) {
  sketch_sweep_options o = options.sweep;
  o.min_margin = std::max(o.min_margin, 2.5 * options.jitter);
  noisy_sweep_report local;
  noisy_sweep_report& rep = report ? *report : local;
  std::vector<sample_drawing> drawings = sketch_sweep(o, &rep.sweep);
  std::vector<noisy_drawing> out;
  for (std::size_t i = 0; i < drawings.size(); ++i) {
    const auto& pts = drawings[i].drawing.points;
    const double spacing =
        detail::junction_spacing(pts, drawings[i].drawing.edges, detail::drawing_diagonal(pts));
    if (!(spacing > 2 * options.jitter)) {
      ++rep.too_close;
      continue;
    }
    noisy_drawing n;
    n.drawing = jitter_drawing(drawings[i].drawing, options.jitter, options.seed * 1000003u + i);
    n.spacing = spacing;
    n.exact = std::move(drawings[i]);
    out.push_back(std::move(n));
  }
  rep.drawings = out.size();
  return out;
}

}  // namespace cellforge::samples
