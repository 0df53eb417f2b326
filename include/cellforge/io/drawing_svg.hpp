// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Deprecated, removed in 0.8: this header is `cellforge/io/drawing_pictures.hpp` now (same names); it
/// includes it until then.

#include "cellforge/io/drawing_pictures.hpp"

#pragma message("cellforge/io/drawing_svg.hpp is deprecated: include cellforge/io/drawing_pictures.hpp")
