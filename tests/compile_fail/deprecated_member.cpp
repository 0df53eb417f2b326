// SPDX-License-Identifier: MIT
// A deprecated data member warns where a program names it, so with -Werror it does not build and
// the message names the new spelling; copying the structs that hold such members does not warn
// (the control copies and default-constructs both, and builds with -Werror).
// expect: deprecated: use milliseconds; removed in 0.8
#include <vector>

#include "cellforge/algorithms/self_intersections.hpp"

double read_time(const cellforge::self_intersection_result& r) {
  cellforge::self_intersection_options options{.work_budget = 10};
  const cellforge::self_intersection_options copy = options;
  std::vector<cellforge::self_intersection_result> results{r, r};
  results.push_back(cellforge::self_intersection_result{});
  results[1] = r;
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
  return results.back().milliseconds + static_cast<double>(copy.max_reported);
#else
  return results.back().time_ms + static_cast<double>(copy.max_reported);
#endif
}
