// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// STEP (ISO 10303-21 text, AP214 "automotive_design") of a cell complex: every volume a
/// MANIFOLD_SOLID_BREP (BREP_WITH_VOIDS with cavities) of planar ADVANCED_FACEs, all solids
/// sharing their vertices, edges, loops and planes; faces in no volume as an OPEN_SHELL of a
/// SHELL_BASED_SURFACE_MODEL; half-edge meshes as faceted B-reps; a rounded solid with its
/// blends as CYLINDRICAL_SURFACE faces trimmed by CIRCLE or ELLIPSE end arcs. See docs/formats.md "STEP".

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/newell.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/rounded_solid.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/version.hpp"

namespace cellforge::io {

/// The length unit a model unit stands for in the STEP file (an SI_UNIT, no conversion).
enum class step_length_unit : std::uint8_t { millimetre, centimetre, metre };

/// How a STEP file is written.
struct step_write_options {
  std::string name = "cellforge";                        ///< the product's name (any UTF-8 text)
  std::string timestamp{};                               ///< FILE_NAME's time stamp (ISO 8601); empty: none
  step_length_unit unit = step_length_unit::millimetre;  ///< what one model unit means
  /// The distance_accuracy_value in the header context, in model units; 0: 1e-9 times the
  /// bounding-box diagonal (the pipeline's merge tolerance), or 1e-9 for an empty model.
  double uncertainty = 0;
};

/// What write_step wrote: solids (one per volume), their cavities, open shells, ADVANCED_FACEs
/// (a face shared by two volumes counts twice), edges, vertices and planes (each once), entities;
/// diagnostics: what the file's reader may object to (faces not flat to the uncertainty, volumes
/// whose outer shell encloses no positive volume, written all the same).
struct step_result : stage_report {
  std::size_t solids = 0;
  std::size_t voids = 0;
  std::size_t open_shells = 0;
  std::size_t faces = 0;
  std::size_t edges = 0;
  std::size_t vertices = 0;
  std::size_t planes = 0;
  std::size_t cylinders = 0;  ///< CYLINDRICAL_SURFACEs (a rounded solid's blends)
  std::size_t conics = 0;     ///< CIRCLEs and ELLIPSEs (a blend's end arcs)
  std::size_t entities = 0;
  double uncertainty = 0;  ///< the distance accuracy written, in model units
};

/// Writes cc as STEP AP214: one MANIFOLD_SOLID_BREP per volume (BREP_WITH_VOIDS with cavities)
/// sharing vertices, edges and planes, faces in no volume as open shells; see docs/formats.md.
/// O(size of cc · log). Throws invalid_input on a non-finite point, a zero-length edge or a face
/// without area; io when the stream fails.
template <Point3 P>
step_result write_step(std::ostream& os, const cell_complex<P>& cc, const step_write_options& options = {});

/// Writes cc to a STEP file (beside it, then renamed over it). O(size of cc · log). Throws
/// as the stream version, and io naming the path.
template <Point3 P>
step_result write_step(const file_path& path, const cell_complex<P>& cc,
                       const step_write_options& options = {});

/// Writes a half-edge mesh (a tube, a subdivided surface) as a faceted B-rep: one solid of
/// planar faces when it is closed and consistently oriented, else an open shell. O(size of m).
template <Point3 P>
step_result write_step(std::ostream& os, const surface_mesh<P>& m, const step_write_options& options = {});
/// The mesh to a STEP file (beside it, then renamed over it). O(size of m).
template <Point3 P>
step_result write_step(const file_path& path, const surface_mesh<P>& m,
                       const step_write_options& options = {});

/// Writes a rounded solid (rounded_brep in sketch/rounds.hpp) as STEP AP214: one
/// MANIFOLD_SOLID_BREP of planar faces and a CYLINDRICAL_SURFACE face per blend, trimmed by
/// LINE edges and CIRCLE or ELLIPSE end arcs. O(size of s). Throws invalid_input on a
/// non-finite point, a zero-length line, an end plane holding its blend's axis; io on failure.
template <class = void>
step_result write_step(std::ostream& os, const rounded_solid& s, const step_write_options& options = {});
/// The rounded solid to a STEP file (beside it, then renamed over it). O(size of s).
template <class = void>
step_result write_step(const file_path& path, const rounded_solid& s, const step_write_options& options = {});

}  // namespace cellforge::io

#include "cellforge/io/detail/step_impl.hpp"
