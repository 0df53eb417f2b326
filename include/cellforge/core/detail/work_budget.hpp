// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The stage reports' clock and the work budget every search spends from.

#include <chrono>
#include <cstdint>
#include <string>

#include "cellforge/core/error.hpp"

namespace cellforge::detail {

/// Wall-clock stopwatch for stage reports.
template <class = void>
struct basic_stopwatch {
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  double ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
};

/// Counts abstract work steps and throws a budget error naming the stage when exhausted.
template <class = void>
struct basic_work_budget {
  std::uint64_t limit = 0;  ///< 0: unlimited
  std::uint64_t used = 0;
  const char* stage = "";
  void spend(std::uint64_t n = 1) {
    used += n;
    if (limit != 0 && used > limit)
      throw error(error_category::budget, std::string(stage) + ": work budget of " + std::to_string(limit) +
                                              " steps exhausted; raise the stage's `work_budget` option "
                                              "or simplify the input");
  }
};

using stopwatch = basic_stopwatch<>;
using work_budget = basic_work_budget<>;

}  // namespace cellforge::detail
