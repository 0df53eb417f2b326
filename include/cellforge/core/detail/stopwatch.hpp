// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The monotonic stopwatch behind every stage time in the result structs. On POSIX systems it
/// reads `clock_gettime(CLOCK_MONOTONIC)` from <time.h>: g++ 12's <chrono> (which pulls in
/// <sstream> and the locale machinery in C++20) costs over half the compile time of the
/// standard-headers baseline (docs/benchmarks.md, "Compile time"). Elsewhere it is
/// std::chrono::steady_clock.

#if defined(_WIN32) || !__has_include(<time.h>)
#include <chrono>
#define CELLFORGE_DETAIL_STD_CHRONO 1
#else
#include <time.h>
#endif

namespace cellforge::detail {

/// Seconds on a monotonic clock since an unspecified start. O(1).
template <class = void>
double monotonic_seconds() noexcept {
#if defined(CELLFORGE_DETAIL_STD_CHRONO)
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
#else
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
#endif
}

/// Wall-clock stopwatch for stage reports: started when made, read in ms or seconds. O(1).
template <class = void>
struct basic_stopwatch {
  double start = monotonic_seconds();
  [[nodiscard]] double seconds() const noexcept { return monotonic_seconds() - start; }
  [[nodiscard]] double ms() const noexcept { return 1e3 * seconds(); }
  void restart() noexcept { start = monotonic_seconds(); }
};

using stopwatch = basic_stopwatch<>;

}  // namespace cellforge::detail
