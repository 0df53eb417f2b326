// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Files of the 3DCL, one header per format: the "3dcl" text format (seed 000 §4.9; written and
/// read back exactly), OBJ with one group per volume, PLY with faces coloured by volume and an
/// exploded, shaded SVG picture. This header includes the four.

#include "cellforge/io/cells_3dcl.hpp"
#include "cellforge/io/cells_obj.hpp"
#include "cellforge/io/cells_ply.hpp"
#include "cellforge/io/cells_svg.hpp"
