// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Picking the thin loops from the per-cycle least lengths (seed 000 §5.3): the seed's
/// position-weighted peak detector, and the default prominence detector that looks for
/// local minima of the loop length itself.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/stage_report.hpp"

namespace cellforge {

/// How thin loops are picked from the cycle lengths.
enum class thin_detection : std::uint8_t {
  prominence,  ///< local minima of the length, scored by how far the envelope drops (default)
  seed,        ///< §5.3 literally: min(i, f−i)/l_i, smoothing, ±window averages, peaks
};

/// Parameters of detect_thin_cycles (the thin_options fields of the same names).
struct thin_detection_options {
  thin_detection detection = thin_detection::prominence;
  double min_strength = 1.0 / 50;  ///< report scores above this × the largest (seed) / absolute (prominence)
  double suppression_fraction = 0.1;  ///< no stronger loop within this fraction of the cycles
  int averaging_window = 5;           ///< the seed's ±5 averaging
  /// Prominence: the rims are read from the least length within ±envelope_cycles (at least
  /// the candidate window); find_thin_points sets it to about one ring of faces.
  std::size_t envelope_cycles = 0;
};

/// One detected cycle: its 1-based cycle number, its strength (0..1, strongest first).
struct detected_cycle {
  std::size_t cycle = 0;
  double strength = 0;
  double score = 0;  ///< the detector's raw score (seed: the product of averages)
};

/// The detector's picks, strongest first, and what the seed detector did; milliseconds the call,
/// a diagnostic when the values were smoothed or nothing was picked.
struct thin_detection_result : stage_report {
  std::vector<detected_cycle> cycles;
  std::vector<double>
      values;             ///< seed: the weighted (and maybe smoothed) values; prominence: the wide envelope
  bool smoothed = false;  ///< seed: the values alternated and were smoothed
};

namespace detail::thin {

/// Keeps the candidates above `floor` with no stronger one (or an equally strong earlier
/// one) within `radius` cycles, strongest first. O(k²) in the candidates.
template <class = void>
std::vector<detected_cycle> suppress(std::vector<detected_cycle> cand, double floor, double radius) {
  std::vector<detected_cycle> out;
  for (const detected_cycle& c : cand) {
    if (!(c.strength > floor)) continue;
    const bool beaten = std::any_of(cand.begin(), cand.end(), [&](const detected_cycle& o) {
      const double d = std::abs(static_cast<double>(o.cycle) - static_cast<double>(c.cycle));
      return d > 0 && d <= radius &&
             (o.strength > c.strength || (o.strength == c.strength && o.cycle < c.cycle));
    });
    if (!beaten) out.push_back(c);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const detected_cycle& a, const detected_cycle& b) { return a.strength > b.strength; });
  return out;
}

template <class = void>
double mean(std::span<const double> v, std::ptrdiff_t lo, std::ptrdiff_t hi) {  // [lo, hi]
  double s = 0;
  for (std::ptrdiff_t j = lo; j <= hi; ++j) s += v[static_cast<std::size_t>(j)];
  return s / static_cast<double>(hi - lo + 1);
}

/// True when more than 60 % of the consecutive non-zero differences change sign: the
/// up-down-up pattern triangle faces give (the seed's "tendency to alternate").
template <class = void>
bool alternates(std::span<const double> v) {
  std::size_t flips = 0, pairs = 0;
  double last = 0;
  for (std::size_t i = 1; i < v.size(); ++i) {
    const double d = v[i] - v[i - 1];
    if (d == 0) continue;
    if (last != 0) {
      ++pairs;
      if ((d > 0) != (last > 0)) ++flips;
    }
    last = d;
  }
  return pairs > 0 && static_cast<double>(flips) > 0.6 * static_cast<double>(pairs);
}

template <class = void>
thin_detection_result detect_seed(std::span<const double> l, std::size_t faces,
                                  const thin_detection_options& o) {
  thin_detection_result r;
  const auto n = static_cast<std::ptrdiff_t>(l.size());
  std::vector<double> v(l.size());
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const double cycle = static_cast<double>(i + 1), rest = static_cast<double>(faces) - cycle;
    v[static_cast<std::size_t>(i)] =
        l[static_cast<std::size_t>(i)] > 0 ? std::min(cycle, rest) / l[static_cast<std::size_t>(i)] : 0;
  }
  if (n >= 3 && alternates(detail::span_of(v))) {
    // Averaging with the neighbours, weights 1/4, 1/2, 1/4: cancels a period-2 alternation.
    std::vector<double> s(v.size());
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      const double a = v[static_cast<std::size_t>(std::max<std::ptrdiff_t>(i - 1, 0))];
      const double b = v[static_cast<std::size_t>(std::min<std::ptrdiff_t>(i + 1, n - 1))];
      s[static_cast<std::size_t>(i)] = 0.25 * a + 0.5 * v[static_cast<std::size_t>(i)] + 0.25 * b;
    }
    v = std::move(s);
    r.smoothed = true;
  }
  const std::ptrdiff_t w = o.averaging_window;
  std::vector<double> avg(v.size());
  for (std::ptrdiff_t i = 0; i < n; ++i)
    avg[static_cast<std::size_t>(i)] =
        mean(detail::span_of(v), std::max<std::ptrdiff_t>(0, i - w), std::min(n - 1, i + w));
  std::vector<detected_cycle> cand;
  double best = 0;
  for (std::ptrdiff_t i = 1; i + 1 < n; ++i) {
    const double left = mean(detail::span_of(avg), std::max<std::ptrdiff_t>(0, i - w), i - 1);
    const double right = mean(detail::span_of(avg), i + 1, std::min(n - 1, i + w));
    const double x = v[static_cast<std::size_t>(i)];
    if (x > left && x > right && x > v[static_cast<std::size_t>(i - 1)] &&
        x > v[static_cast<std::size_t>(i + 1)]) {
      const double score = left * right * avg[static_cast<std::size_t>(i)];
      cand.push_back({static_cast<std::size_t>(i + 1), score, score});
      best = std::max(best, score);
    }
  }
  if (best > 0)
    for (detected_cycle& c : cand) c.strength = c.score / best;
  r.cycles = suppress(std::move(cand), o.min_strength, o.suppression_fraction * static_cast<double>(n));
  r.values = std::move(v);
  return r;
}

/// The least of v over [i − half, i + half] for every i (monotone deque). O(n).
template <class = void>
std::vector<double> window_min(std::span<const double> v, std::ptrdiff_t half) {
  const auto n = static_cast<std::ptrdiff_t>(v.size());
  std::vector<double> out(v.size());
  std::vector<std::ptrdiff_t> q(v.size());  // indices with increasing values
  std::ptrdiff_t head = 0, tail = 0, next = 0;
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    for (; next <= std::min(n - 1, i + half); ++next) {
      while (tail > head && v[static_cast<std::size_t>(q[static_cast<std::size_t>(tail - 1)])] >=
                                v[static_cast<std::size_t>(next)])
        --tail;
      q[static_cast<std::size_t>(tail++)] = next;
    }
    while (q[static_cast<std::size_t>(head)] < i - half) ++head;
    out[static_cast<std::size_t>(i)] = v[static_cast<std::size_t>(q[static_cast<std::size_t>(head)])];
  }
  return out;
}

template <class = void>
thin_detection_result detect_prominence(std::span<const double> l, const thin_detection_options& o) {
  thin_detection_result r;
  const auto n = static_cast<std::ptrdiff_t>(l.size());
  const auto half_of = [&](double fraction) {
    return std::max<std::ptrdiff_t>(1, static_cast<std::ptrdiff_t>(fraction * static_cast<double>(n) / 2));
  };
  const std::ptrdiff_t half = half_of(o.suppression_fraction);
  // m: the least length within ±half cycles (candidates); wide: the same over the wider
  // envelope window, which bridges the bump of a partly grown ring so that the rims measure
  // the solid's shape, not the ring-by-ring up and down of the growing.
  const std::vector<double> m = window_min(l, half);
  const std::vector<double> wide = window_min(
      l, std::max(half, static_cast<std::ptrdiff_t>(std::min<std::size_t>(o.envelope_cycles, l.size()))));
  std::vector<detected_cycle> cand;
  for (std::ptrdiff_t i = 1; i + 1 < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (l[k] != m[k]) continue;  // not the least length of its window
    // Topographic prominence: on each side, the highest wide-envelope value before it drops
    // below l_i (or the end). Both sides must rise: a neck, not the shrinking end of the
    // solid nor a step down a taper.
    double rim[2] = {0, 0};
    for (int side = 0; side < 2; ++side)
      for (std::ptrdiff_t j = side == 0 ? i - 1 : i + 1; j >= 0 && j < n; j += side == 0 ? -1 : 1) {
        if (wide[static_cast<std::size_t>(j)] < l[k]) break;
        rim[side] = std::max(rim[side], wide[static_cast<std::size_t>(j)]);
      }
    const double lowest_rim = std::min(rim[0], rim[1]);
    if (!(lowest_rim > 0)) continue;
    const double strength = std::max(0.0, 1.0 - l[k] / lowest_rim);
    cand.push_back({k + 1, strength, strength});
  }
  r.cycles = suppress(std::move(cand), o.min_strength, o.suppression_fraction * static_cast<double>(n));
  r.values = wide;
  return r;
}

}  // namespace detail::thin

/// The thin cycles among `lengths` (cycle i+1's least length at index i) of a solid with
/// `faces` faces. Prominence: O(n + k·n) for k candidates; seed: O(n · window + k²).
template <class = void>
thin_detection_result detect_thin_cycles(std::span<const double> lengths, std::size_t faces,
                                         const thin_detection_options& options = {}) {
  const detail::stopwatch clock;
  thin_detection_result r = options.detection == thin_detection::seed
                                ? detail::thin::detect_seed(lengths, faces, options)
                                : detail::thin::detect_prominence(lengths, options);
  if (r.smoothed)
    r.diagnostics.emplace_back("the weighted lengths alternated and were smoothed (the seed detector)");
  if (r.cycles.empty()) r.diagnostics.emplace_back("no cycle stands out as thin");
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
