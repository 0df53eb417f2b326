// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Stage 3 of the wireframe pipeline (seed 000 §4.3): reduce the traced circuits to unique
/// ones and put them in the seed's canonical order (each loop starts at its smallest label and
/// runs towards the smaller neighbour; faces sorted by their loops).

#include <algorithm>
#include <cstdint>
#include <vector>

#include "cellforge/wireframe/wire_graph.hpp"

namespace cellforge {

/// Options of unique_circuits (none yet; kept for a uniform stage interface).
struct unique_circuits_options {};

/// The unique candidate faces in canonical order.
struct unique_circuits_result : stage_report {
  std::vector<wire_face> faces;
  std::size_t duplicates =
      0;  ///< circuits that repeated an earlier one (same loops up to rotation and reversal)
};

/// Canonicalises every face and removes repeats; the comparison is by canonical loops, which
/// the seed's edge-by-edge walk decides the same way. O(F log F · L) for loops of length L.
template <class = void>
unique_circuits_result unique_circuits(const wire_graph& g, std::vector<wire_face> faces,
                                       const unique_circuits_options& = {}) {
  detail::stopwatch clock;
  unique_circuits_result r;
  // canonicalize turns the normal with the loop: a tracer's normal (the planar tracer gives a
  // face its plane's fitted normal) is kept; only a face without one gets its Newell normal.
  for (auto& f : faces) {
    canonicalize(f);
    if (f.normal == glm::dvec3(0.0)) update_normal(g, f);
  }
  // Sorted by loops, stably: the first of each run of equal faces is the earliest, which is kept.
  std::vector<std::uint32_t> order(faces.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return faces[a].loops < faces[b].loops; });
  for (const std::uint32_t i : order) {
    if (!r.faces.empty() && r.faces.back().loops == faces[i].loops)
      ++r.duplicates;
    else
      r.faces.push_back(std::move(faces[i]));
  }
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
