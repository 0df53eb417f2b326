// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Newell's vector now lives with the other small geometry helpers in core/detail/geometry.hpp;
/// this include keeps code written against the old detail path compiling.

#include "cellforge/core/detail/geometry.hpp"
