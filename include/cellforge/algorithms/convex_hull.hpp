// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// 3D convex hull of a point set as a closed, outward-oriented half-edge mesh. Quickhull
/// with outside sets; every orientation decision goes through the exact orient3d, so
/// duplicate, collinear and coplanar points are handled without tolerances. Flat, linear
/// and single-point inputs give documented degenerate hulls. See docs/convex_hull.md.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <ranges>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/morton.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/detail/mesh_access.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

/// Which algorithm builds a 3D hull; the result is the same mesh up to the triangulation
/// of coplanar facets.
enum class convex_hull_method : std::uint8_t {
  automatic,    ///< incremental when a sample of the points is nearly all hull vertices, else quickhull
  quickhull,    ///< outside sets, furthest point first: fast when most points are inside
  incremental,  ///< randomised insertion with walk location: fast when most points are vertices
};

/// How convex_hull builds and shapes its output.
struct convex_hull_options {
  /// Output one polygon per planar facet (e.g. 6 quads for a cube) instead of triangles.
  bool merge_coplanar = false;
  /// Inputs spanning fewer than 3 dimensions (all coplanar, all collinear, one distinct
  /// point) give a degenerate hull described in the report; false makes them an error.
  bool allow_degenerate = true;
  /// The algorithm; the default picks by a sample (see convex_hull_method).
  convex_hull_method method = convex_hull_method::automatic;
  /// Before quickhull on 4096 points or more, drop the points strictly inside the polytope
  /// of 14 extreme points (along the axes and the cube diagonals; Akl and Toussaint): they
  /// cannot be corners. The same hull; false hulls every point.
  bool discard_interior = true;
};

/// What convex_hull found.
struct convex_hull_report {
  /// Affine dimension of the input: 3 solid, 2 flat (the hull is a polygon, returned as two
  /// faces back to back), 1 collinear (two vertices, no faces), 0 one distinct point
  /// (one vertex), -1 empty input.
  int dimension = -1;
  std::size_t input_points = 0;
  std::size_t vertices = 0, edges = 0, faces = 0;  ///< of the returned mesh
  /// Points that landed on the hull surface without being corners (inside a facet or an
  /// edge) in the first pass; when non-zero the hull was rebuilt from the corners alone.
  std::size_t non_corner_vertices_removed = 0;
  std::size_t exact_evaluations = 0;  ///< orient3d calls the floating-point filter could not decide
  /// Points dropped before the hull as strictly inside the polytope of extreme points
  /// (convex_hull_options::discard_interior).
  std::size_t interior_discarded = 0;
};

/// Name of the vertex property holding, for each hull vertex, its index in the input.
inline constexpr std::string_view input_index_property_name = "v:input_index";

/// The convex hull of `points` as a closed mesh whose faces point outward: triangles, or
/// one polygon per facet with options.merge_coplanar. Vertices are the hull's corners only
/// (no point inside a facet or an edge), with the input values as positions (the range's
/// own point type) and their input indices in "v:input_index". `points` is any contiguous
/// range: std::vector, std::array, std::span, a C array. Degenerate inputs (see
/// convex_hull_report::dimension) give a flat hull as two faces back to back, a segment as
/// two vertices, a point as one vertex, unless options.allow_degenerate is false.
/// Throws cellforge::error (invalid_input) for NaN/Inf coordinates. O(n log n) expected.
template <std::ranges::contiguous_range R>
requires std::ranges::sized_range<R> && Point3<std::ranges::range_value_t<R>>
    surface_mesh<std::ranges::range_value_t<R>> convex_hull(const R& input,
                                                            const convex_hull_options& options = {},
                                                            convex_hull_report* report = nullptr);

}  // namespace cellforge

#include "cellforge/algorithms/detail/convex_hull_impl.hpp"
