// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Include in exactly one .cpp file of a program built with CELLFORGE_EXTERN_SKETCH defined in
/// every file: it compiles, once, the line-drawing engines that the other files then only
/// declare (`extern template`), so that a file calling find_faces, drawing_to_cells, inflate,
/// the tidying, the rounds or io::read_drawing_text compiles in a fraction of the time. Without the macro
/// nothing changes: every file compiles what it calls, as any header-only library (docs/sketch.md, "Compile
/// time"). The engines run in double: they serve every drawing type whose scalar is double.

#include <string_view>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/io/drawing_text.hpp"
#include "cellforge/sketch/drawing_to_cells.hpp"
#include "cellforge/sketch/face_finder.hpp"
#include "cellforge/sketch/inflation.hpp"
#include "cellforge/sketch/rounds.hpp"
#include "cellforge/sketch/tidy.hpp"

/// \cond INTERNAL
namespace cellforge {
template face_finder_result detail::faces::find_faces_in<void>(const detail::faces::drawing_graph&,
                                                               const face_finder_options&, double,
                                                               const detail::stopwatch&);
template drawing_result<glm::dvec3, glm::dvec2>
detail::sketch::drawing_to_cells_on<glm::dvec3, line_drawing<glm::dvec2>>(const line_drawing<glm::dvec2>&,
                                                                          const drawing_options&);
template inflation_result<glm::dvec3> detail::inflate_faces<glm::dvec3, line_drawing<glm::dvec2>>(
    const line_drawing<glm::dvec2>&, const std::vector<std::vector<std::vector<std::uint32_t>>>&,
    const inflation_options&);
template tidy_result<glm::dvec2> tidy_drawing<line_drawing<glm::dvec2>>(const line_drawing<glm::dvec2>&,
                                                                        const tidy_options&);
template tidy_result<glm::dvec2> tidy_to_solid<line_drawing<glm::dvec2>>(
    const line_drawing<glm::dvec2>&, const std::vector<std::vector<std::vector<std::uint32_t>>>&,
    const tidy_options&);
template arc_drawing<glm::dvec2> io::detail::parse_drawing_text_statements<glm::dvec2>(std::string_view,
                                                                                       std::string_view,
                                                                                       bool);
template line_drawing<glm::dvec2> io::read_drawing_text<glm::dvec2>(const io::file_path&);
template line_drawing<glm::dvec2> io::parse_drawing_text<glm::dvec2>(std::string_view, std::string_view);
template rounds_result<glm::dvec3, glm::dvec2> reconstruct_rounds<glm::dvec3, glm::dvec2>(
    const arc_drawing<glm::dvec2>&, const rounds_options&);
template rounded_mesh_result<glm::dvec3> rounded_mesh<glm::dvec3, glm::dvec2>(
    const rounds_result<glm::dvec3, glm::dvec2>&, const rounded_mesh_options&);
template rounded_brep_result rounded_brep<glm::dvec3, glm::dvec2>(
    const rounds_result<glm::dvec3, glm::dvec2>&, const rounded_brep_options&);
}  // namespace cellforge
/// \endcond
