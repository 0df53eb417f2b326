// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Deprecated since 0.5, removed in 0.6: the generators moved to `cellforge/samples/round_drawings.hpp`,
/// their names to `cellforge::samples`. Until then this header includes it and names the
/// old spellings: types as `[[deprecated]]` aliases, functions by using-declarations.

#include "cellforge/samples/round_drawings.hpp"

#pragma message( \
    "cellforge/sketch/sample_round_drawings.hpp is deprecated: include cellforge/samples/round_drawings.hpp (names in cellforge::samples)")

namespace cellforge {

using round_truth [[deprecated("use cellforge::samples::round_truth")]] = samples::round_truth;
using sample_round_drawing [[deprecated("use cellforge::samples::sample_round_drawing")]] =
    samples::sample_round_drawing;
using round_sweep_options [[deprecated("use cellforge::samples::round_sweep_options")]] =
    samples::round_sweep_options;
using round_sweep_report [[deprecated("use cellforge::samples::round_sweep_report")]] =
    samples::round_sweep_report;
using samples::round_drawing_sweep;
using samples::round_prism_drawing;
using samples::round_sweep_families;

}  // namespace cellforge
