// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Tolerances relative to a model's size, so that the same model gives the same
/// answer whether it is measured in micrometres or kilometres.

#include <cmath>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"

namespace cellforge {

/// A length tolerance expressed as a fraction of the model's bounding-box diagonal.
struct tolerance {
  double relative = 1e-9;  ///< fraction of the bounding-box diagonal

  /// The absolute distance for a model with this bounding box. O(1).
  /// A degenerate (empty or single-point) box gives the smallest positive tolerance,
  /// so that "closer than tolerance" still means "identical".
  double absolute(const bounding_box& box) const {
    if (!(relative >= 0.0) || !std::isfinite(relative))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("tolerance: relative tolerance must be finite and >= 0, got ",
                                         std::to_string(relative)));
    const double d = box.diagonal();
    if (!std::isfinite(d))
      throw error(error_category::invalid_input,
                  "tolerance: the model's bounding box is not finite (NaN or Inf coordinates)");
    return d > 0.0 ? relative * d : std::numeric_limits<double>::denorm_min();
  }
};

/// True when a and b are equal to within `tol` (absolute). O(1).
template <class = void>
bool nearly_equal(double a, double b, double tol) noexcept {
  return std::abs(a - b) <= tol;
}

}  // namespace cellforge
