// sketch2cells: a wireframe line drawing (a parallel view of a polyhedron, every edge drawn,
// hidden ones too) becomes a solid (seed 003_be08eec927fcc329.txt: finding faces, inflation;
// then seed 000's wireframe pipeline).
//
//   sketch2cells                       the bundled stepped normalon (examples/data/stepped_normalon.svg)
//   sketch2cells drawing.svg|drawing.txt|drawing.dxf [--finder varley-company|shortest-loops] [--no-svg]
//
// Writes, in the current directory, <name>_faces.svg (the drawing with its faces shaded),
// <name>_wire.obj (the 3D wireframe), and the cell complex as <name>.3dcl, <name>.obj and
// <name>.svg (--no-svg leaves out both pictures); prints every stage's counts and times. Never writes over
// its input.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/cells/validate.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/io/cells_io.hpp"
#include "cellforge/io/drawing_svg.hpp"
#include "cellforge/io/drawing_text.hpp"
#include "cellforge/io/dxf_drawing.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/io/svg_drawing.hpp"
#include "cellforge/sketch/drawing_to_cells.hpp"
#include "example_support.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  example::stage_note stage;
  try {
    const example::command_line cl = example::parse_command_line(
        argc, argv, fs::path(CELLFORGE_DATA_DIR) / "stepped_normalon.svg", {"finder"}, {"no-svg"});
    const bool pictures = !cl.has("no-svg");
    cellforge::drawing_options options;
    const std::string finder = cl.text("finder", "varley-company");
    if (finder == "shortest-loops")
      options.faces.kind = cellforge::face_finder_kind::shortest_loops;
    else if (finder != "varley-company")
      throw cellforge::error(cellforge::error_category::invalid_input,
                             "--finder must be varley-company or shortest-loops, got '" + finder + "'");
    std::string ext = cl.input.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    cellforge::line_drawing<glm::dvec2> drawing;
    stage("reading " + example::file_and_size(cl.input));
    if (ext == ".svg") {
      const auto read = cellforge::io::read_svg_drawing(cl.input);
      drawing = read.drawing;
      std::printf("input              %s: %zu SVG elements, %zu strokes, %zu ends snapped\n",
                  cl.input.string().c_str(), read.elements, read.segments, read.snapped);
    } else if (ext == ".dxf") {
      // ASCII DXF: LINEs and polylines on every visible layer, blocks expanded (curves refused).
      const auto read = cellforge::io::read_dxf_drawing(cl.input);
      drawing = read.drawing;
      std::printf("input              %s: DXF %s, %zu entities, %zu strokes, %zu ends snapped\n",
                  cl.input.string().c_str(), read.version.c_str(), read.entities, read.segments,
                  read.snapped);
      for (const std::string& d : read.diagnostics) std::printf("note               %s\n", d.c_str());
    } else {
      drawing = cellforge::io::read_drawing_text(cl.input);
      std::printf("input              %s\n", cl.input.string().c_str());
    }
    const std::string stem = cl.input.stem().string();
    const fs::path outputs[] = {stem + "_faces.svg", stem + "_wire.obj", stem + ".3dcl", stem + ".obj",
                                stem + ".svg"};
    for (const fs::path& out : outputs) example::refuse_to_overwrite(out, cl.input);

    stage("reading the solid of a drawing of " + std::to_string(drawing.points.size()) + " junctions and " +
          std::to_string(drawing.edges.size()) + " lines");
    const auto r = cellforge::drawing_to_cells(drawing, options);
    std::printf("drawing            %zu junctions, %zu edges, %zu direction classes\n", r.faces.junctions,
                r.faces.edges, r.faces.direction_classes);
    std::printf(
        "faces              %9.3f ms   %zu loops (%zu forced concatenations, %zu voluntary mergers, "
        "%zu hypotheses, %zu rejected), check %s\n",
        r.faces.milliseconds, r.faces.loops.size(), r.faces.forced, r.faces.voluntary, r.faces.hypotheses,
        r.faces.rejected, r.faces.check.ok() ? "passed" : "FAILED");
    std::size_t holes = 0;
    for (const auto& f : r.face_loops) holes += f.size() - 1;
    std::printf("faces with holes   %zu faces, %zu hole loops\n", r.face_loops.size(), holes);
    std::printf(
        "tidy               %9.3f ms   %zu lines made parallel in %zu classes, largest move %.2g of the "
        "size\n",
        r.tidy.milliseconds, r.tidy.changed_lines, r.tidy.classes, r.tidy.largest_move);
    std::printf("inflation          %9.3f ms   %s, planar freedom %zu, reading %zu of %zu: %s\n",
                r.inflation.milliseconds,
                r.inflation.method == cellforge::inflation_method::direct ? "direct" : "optimisation",
                r.inflation.freedom, r.reading + 1, r.inflation.readings.size(),
                r.inflation.readings.empty() ? "" : r.inflation.readings[r.reading].reason.c_str());
    const auto& cells = r.cells.cells;
    const cellforge::cells_validation_result valid = cellforge::validate(cells);
    std::printf("cell complex       %zu vertices, %zu edges, %zu faces, %zu volumes; validate %s\n",
                cells.num_vertices(), cells.num_edges(), cells.num_faces(), cells.num_volumes(),
                valid.ok() ? "ok" : valid.message.c_str());
    std::printf("2D and 3D faces    %s\n", r.faces_agree ? "agree" : "DIFFER");
    std::printf("total              %9.3f ms\n", r.milliseconds);
    for (const std::string& d : r.diagnostics) std::printf("note               %s\n", d.c_str());

    stage("writing " + std::to_string(cells.num_faces()) + " faces");
    if (pictures) {
      cellforge::io::drawing_svg_options picture;
      picture.title = "sketch2cells: faces of " + cl.input.filename().string();
      picture.labels = drawing.points.size() <= 60;
      cellforge::io::write_drawing_svg(outputs[0], drawing, r.faces.loops, picture);
    }
    cellforge::io::write_obj(outputs[1], r.wire);
    cellforge::io::write_3dcl(outputs[2], cells);
    cellforge::io::write_cells_obj(outputs[3], cells);
    if (pictures) cellforge::io::write_cells_svg(outputs[4], cells);
    std::printf("wrote             ");
    for (const fs::path& out : outputs)
      if (pictures || out.extension() != ".svg") std::printf(" %s", out.string().c_str());
    std::printf("\n");
    return valid.ok() && r.faces_agree ? 0 : 1;
  } catch (const std::bad_alloc&) {
    example::report_out_of_memory("sketch2cells", stage);
    return 1;
  } catch (const std::exception& e) {  // cellforge::error among them: parse errors name file:line
    std::fprintf(stderr, "sketch2cells: %s\n", e.what());
    return 1;
  }
}
