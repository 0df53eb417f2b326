// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Everything in cellforge except file I/O (include "cellforge/io/..." for that).

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/core/tolerance.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/algorithms/convex_hull.hpp"
#include "cellforge/algorithms/ear_clipping.hpp"
#include "cellforge/algorithms/edits.hpp"
#include "cellforge/algorithms/loop_subdivision.hpp"
#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/algorithms/simplification.hpp"
#include "cellforge/halfedge/circulators.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/handles.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/halfedge/orientation.hpp"
#include "cellforge/halfedge/properties.hpp"
#include "cellforge/halfedge/validate.hpp"
