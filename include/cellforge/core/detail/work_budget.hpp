// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The counter a search spends its work budget (cellforge::work_budget) from.

#include <cstdint>
#include <string>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/work_budget.hpp"

namespace cellforge::detail {

/// Counts abstract work steps and throws a budget error naming the stage when exhausted; the
/// stage catches it and returns its best answer with complete = false where it has one.
template <class = void>
struct basic_work_budget {
  std::uint64_t limit = 0;  ///< 0 (cellforge::work_budget::unlimited) or automatic: no limit
  std::uint64_t used = 0;
  const char* stage = "";
  void spend(std::uint64_t n = 1) {
    used += n;
    if (limit != cellforge::work_budget::unlimited && limit != cellforge::work_budget::automatic &&
        used > limit)
      throw error(error_category::budget,
                  cellforge::detail::cat(std::string(stage), ": work budget of ", std::to_string(limit),
                                         " steps exhausted; raise the stage's `work_budget` option "
                                         "or simplify the input"));
  }
};

using work_budget = basic_work_budget<>;

}  // namespace cellforge::detail
