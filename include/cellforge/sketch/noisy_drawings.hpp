// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Deprecated since 0.5, removed in 0.6: the generators moved to `cellforge/samples/noisy_drawings.hpp`,
/// their names to `cellforge::samples`. Until then this header includes it and names the
/// old spellings: types as `[[deprecated]]` aliases, functions by using-declarations.

#include "cellforge/samples/noisy_drawings.hpp"

#pragma message( \
    "cellforge/sketch/noisy_drawings.hpp is deprecated: include cellforge/samples/noisy_drawings.hpp (names in cellforge::samples)")

namespace cellforge {

using noisy_sweep_options [[deprecated("use cellforge::samples::noisy_sweep_options")]] =
    samples::noisy_sweep_options;
using noisy_drawing [[deprecated("use cellforge::samples::noisy_drawing")]] = samples::noisy_drawing;
using noisy_sweep_report [[deprecated("use cellforge::samples::noisy_sweep_report")]] =
    samples::noisy_sweep_report;
using samples::jitter_drawing;
using samples::noisy_sweep;

}  // namespace cellforge
