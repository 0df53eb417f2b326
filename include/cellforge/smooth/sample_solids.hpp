// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Deprecated since 0.5, removed in 0.6: the generators moved to `cellforge/samples/smooth_solids.hpp`,
/// their names to `cellforge::samples`. Until then this header includes it and names the
/// old spellings: types as `[[deprecated]]` aliases, functions by using-declarations.

#include "cellforge/samples/smooth_solids.hpp"

#pragma message( \
    "cellforge/smooth/sample_solids.hpp is deprecated: include cellforge/samples/smooth_solids.hpp (names in cellforge::samples)")

namespace cellforge {

template <Point3 P = glm::dvec3>
using smooth_sample_solid [[deprecated("use cellforge::samples::smooth_sample_solid")]] =
    samples::smooth_sample_solid<P>;
template <Point3 P = glm::dvec3>
using smooth_table7_case [[deprecated("use cellforge::samples::smooth_table7_case")]] =
    samples::smooth_table7_case<P>;
using samples::smooth_table7_solid;
using samples::table7_solids;

}  // namespace cellforge
