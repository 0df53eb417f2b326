// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Deprecated since 0.5, removed in 0.6: the generators moved to `cellforge/samples/thin_solids.hpp`,
/// their names to `cellforge::samples`. Until then this header includes it and names the
/// old spellings: types as `[[deprecated]]` aliases, functions by using-declarations.

#include "cellforge/samples/thin_solids.hpp"

#pragma message( \
    "cellforge/thin/sample_solids.hpp is deprecated: include cellforge/samples/thin_solids.hpp (names in cellforge::samples)")

namespace cellforge {

template <Point3 P = glm::dvec3>
using thin_sample [[deprecated("use cellforge::samples::thin_sample")]] = samples::thin_sample<P>;
using samples::thin_bottle;
using samples::thin_chain;
using samples::thin_cylinder;
using samples::thin_dumbbell;
using samples::thin_hourglass;
using samples::thin_sphere;
using samples::thin_table5_solid;
using samples::thin_vase;

}  // namespace cellforge
