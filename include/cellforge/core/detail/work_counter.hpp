// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The counter a search spends its work budget (cellforge::work_budget) from, and how a stage
/// that ran out says so in its result.

#include <cstdint>
#include <string>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/work_budget.hpp"

namespace cellforge::detail {

/// Counts abstract work steps and throws a budget error naming the stage and the option to
/// raise when exhausted; the stage catches it (stop_at_budget) and returns its best answer
/// with complete = false.
template <class = void>
struct basic_work_counter {
  std::uint64_t limit = 0;  ///< 0 (cellforge::work_budget::unlimited) or automatic: no limit
  std::uint64_t used = 0;
  const char* stage = "";
  const char* option = "the stage's `work_budget` option";  ///< named in the message
  void spend(std::uint64_t n = 1) {
    used += n;
    if (limit != cellforge::work_budget::unlimited && limit != cellforge::work_budget::automatic &&
        used > limit)
      throw error(
          error_category::budget,
          cellforge::detail::cat(std::string(stage), ": work budget of ", std::to_string(limit),
                                 " steps exhausted; raise ", std::string(option), " or simplify the input"));
  }
};

using work_counter = basic_work_counter<>;

/// Called in a catch block: a budget error `e` of `counter` marks r (a stage_report) stopped,
/// complete = false, with the work spent and e's message as a diagnostic; any other error is
/// rethrown. O(1).
template <class R>
void stop_at_budget(R& r, const work_counter& counter, const error& e) {
  if (e.category() != error_category::budget) throw;
  r.complete = false;
  r.work = counter.used;
  r.diagnostics.emplace_back(e.what());
}

/// The last of r's diagnostics that says a work budget ran out (stop_at_budget's), or `fallback`.
/// O(diagnostics).
template <class R>
std::string budget_note(const R& r, const char* fallback) {
  for (auto d = r.diagnostics.rbegin(); d != r.diagnostics.rend(); ++d)
    if (d->find("work budget") != std::string::npos) return *d;
  return fallback;
}

}  // namespace cellforge::detail
