// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// What every result reports besides its own counts: wall time, the work its searches spent,
/// whether a work budget stopped one of them, and notes for a person (docs/vocabulary.md).

#include <cstdint>
#include <string>
#include <vector>

namespace cellforge {

/// The common part of every `<thing>_result`: a result derives from it and adds its counts.
struct stage_report {
  double milliseconds = 0.0;  ///< wall time of the call
  std::uint64_t work = 0;     ///< steps spent from the call's work budget (0 where it has none)
  /// False when a work budget stopped a search: the answer is the best found, flagged, and a
  /// diagnostic says which budget to raise.
  bool complete = true;
  std::vector<std::string> diagnostics;  ///< things the call changed or doubted, one per line
};

}  // namespace cellforge
