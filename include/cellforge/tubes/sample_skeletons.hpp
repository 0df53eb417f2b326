// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Deprecated since 0.5, removed in 0.6: the generators moved to `cellforge/samples/skeletons.hpp`;
/// their names stay in `cellforge::samples`. This header only includes the new one.

#include "cellforge/samples/skeletons.hpp"

#pragma message( \
    "cellforge/tubes/sample_skeletons.hpp is deprecated: include cellforge/samples/skeletons.hpp (names in cellforge::samples)")
