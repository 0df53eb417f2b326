// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The work budget every search's options hold: a number of abstract steps (each option says
/// what a step is), where 0 means unlimited in every part and `work_budget::automatic` a budget
/// scaled to the input's size (the option says how). Exhausted, a search stops with the best
/// answer it has and says so in its result (`stage_report::complete`; docs/vocabulary.md).

#include <cstdint>

namespace cellforge {

/// A search's allowance of work steps. It converts from and to std::uint64_t, so that
/// `options.work_budget = 1'000'000` and comparisons with a step count read as plain numbers.
class work_budget {
 public:
  static constexpr std::uint64_t unlimited = 0;                  ///< no limit, in every part
  static constexpr std::uint64_t automatic = ~std::uint64_t{0};  ///< scaled to the input's size

  constexpr work_budget() noexcept = default;
  constexpr work_budget(std::uint64_t steps) noexcept : steps_(steps) {}  // implicit: a number of steps
  constexpr operator std::uint64_t() const noexcept { return steps_; }

  constexpr bool is_unlimited() const noexcept { return steps_ == unlimited; }
  constexpr bool is_automatic() const noexcept { return steps_ == automatic; }
  /// The steps a search may spend: `scaled` (the part's size-scaled budget) when automatic,
  /// the largest count when unlimited, else the number given. O(1).
  constexpr std::uint64_t limit(std::uint64_t scaled) const noexcept {
    return is_automatic() ? scaled : is_unlimited() ? ~std::uint64_t{0} : steps_;
  }

 private:
  std::uint64_t steps_ = unlimited;
};

}  // namespace cellforge
