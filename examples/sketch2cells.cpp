// sketch2cells: a wireframe line drawing (a parallel view of a polyhedron, every edge drawn,
// hidden ones too) becomes a solid (seed 003_be08eec927fcc329.txt: finding faces, inflation;
// then seed 000's wireframe pipeline).
//
//   sketch2cells [options] [input]   input: drawing.svg|drawing.txt|drawing.dxf; none: the bundled
//                                    stepped normalon (examples/data/stepped_normalon.svg)
//   sketch2cells --help              every option with its default, the outputs, the exit statuses
//
// Writes, into the output folder (-o, default ./out/), <name>_faces.svg (the drawing with its faces shaded),
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
#include "cellforge/io/drawing_pictures.hpp"
#include "cellforge/io/drawing_text.hpp"
#include "cellforge/io/dxf_drawing.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/io/step.hpp"
#include "cellforge/io/svg_drawing.hpp"
#include "cellforge/sketch/drawing_to_cells.hpp"
#include "example_support.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  example::program p;
  p.name = "sketch2cells";
  p.usage = "[options] [input ...]";
  p.takes = {example::input_kind::drawing};
  p.about =
      "A wireframe line drawing (a parallel view of a polyhedron, every edge drawn, hidden ones too)\n"
      "becomes a solid (seed 003: finding faces, inflation; then seed 000's wireframe pipeline).";
  p.input_help =
      "a line drawing: .svg (strokes), .dxf (ASCII: LINEs and polylines) or the text format (any other\n"
      "       name; docs/formats.md); default: the bundled stepped_normalon.svg";
  p.outputs_help =
      "  <name>_faces.svg   the drawing with its faces shaded\n"
      "  <name>_wire.obj    the 3D wireframe\n"
      "  <name>.3dcl        the cell complex (docs/formats.md)\n"
      "  <name>.obj         the cell complex's faces, one group per volume\n"
      "  <name>.svg         the solid, volumes exploded apart\n"
      "  <name>.step        with --step: a solid per volume (STEP AP214, docs/formats.md \"STEP\")\n"
      "<name> is the input's file name without its extension; --no-svg leaves out both pictures.\n";
  p.exit4_help =
      "read, but not a line drawing (a mesh, a wireframe, a skeleton, a drawing with arcs: the message\n"
      "     names the program that takes it), or no good solid: the cell complex fails validation or its\n"
      "     faces differ from the drawing's, a drawn edge bounds no face, or the 3D reading is not a\n"
      "     closed solid (its status, as wire2cells prints it)";
  cellforge::drawing_options options;
  bool step = false;
  p.add_common_options();
  p.options.push_back({{"--step"},
                       "",
                       "also write <name>.step, a solid per volume for CAD programs (default: off)",
                       [&](std::string_view) { step = true; }});
  p.options.push_back({{"--finder"},
                       "varley-company|shortest-loops",
                       "how faces are found in the drawing (default: varley-company)",
                       [&](std::string_view v) {
                         options.faces.kind = example::option_choice<cellforge::face_finder_kind>(
                             "--finder", v,
                             {{"varley-company", cellforge::face_finder_kind::varley_company},
                              {"shortest-loops", cellforge::face_finder_kind::shortest_loops}});
                       }});
  p.options.push_back(
      {{"--budget"},
       "N",
       "work budget of the face finder in steps, 0 = unlimited (default: " +
           std::to_string(options.faces.work_budget) + ")",
       [&](std::string_view v) { options.faces.work_budget = example::option_count("--budget", v); }});
  return example::run(p, argc, argv, [&](const std::vector<std::string>& args) -> int {
    const fs::path input = p.one_input(args, fs::path(CELLFORGE_DATA_DIR) / "stepped_normalon.svg");
    example::stage_note& stage = p.stage;
    const std::string stem = input.stem().string();
    example::output_files out(p, {input});
    bool failed = false;  // a result that fails its check: written only with --keep-partial
    const fs::path faces_path = out.add(stem + "_faces.svg"), wire_path = out.add(stem + "_wire.obj"),
                   cells_path = out.add(stem + ".3dcl"), obj_path = out.add(stem + ".obj"),
                   picture_path = out.add(stem + ".svg"),
                   step_path = step ? out.add(stem + ".step") : fs::path();
    example::expect_extension(p.name, input, {example::input_kind::drawing}, "a line drawing");
    const std::string ext = example::lower_extension(input);
    if (ext == ".obj") {
      const example::obj_contents c = example::read_obj_contents(input);
      example::not_for_this(p.name, input, c.describe(), "a line drawing", c.kind());
    }
    cellforge::line_drawing<glm::dvec2> drawing;
    stage("reading " + example::file_and_size(input));
    try {
      if (ext == ".svg") {
        const auto read = cellforge::io::read_svg_drawing(input);
        drawing = read.drawing;
        std::printf("input              %s: %zu SVG elements, %zu strokes, %zu ends snapped\n",
                    input.string().c_str(), read.elements, read.segments, read.snapped);
      } else if (ext == ".dxf") {
        // ASCII DXF: LINEs and polylines on every visible layer, blocks expanded (curves refused).
        const auto read = cellforge::io::read_dxf_drawing(input);
        drawing = read.drawing;
        std::printf("input              %s: DXF %s, %zu entities, %zu strokes, %zu ends snapped\n",
                    input.string().c_str(), read.version.c_str(), read.entities, read.segments, read.snapped);
        for (const std::string& d : read.diagnostics) std::printf("note               %s\n", d.c_str());
      } else {
        drawing = cellforge::io::read_drawing_text(input);
        std::printf("input              %s\n", input.string().c_str());
      }
    } catch (const cellforge::error& e) {
      // A drawing with arcs or curves: the reader names the library's arc readers; name the program.
      if (e.message().find("arc_drawing") == std::string::npos) throw;
      std::string what = "a drawing with arcs or curves";
      if (e.line() > 0) what += ", the first at line " + std::to_string(e.line());
      example::not_for_this(p.name, input, what, "a drawing of straight lines", example::input_kind::drawing);
    }
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
    const cellforge::cells_validation valid = cellforge::validate(cells);
    std::printf("cell complex       %zu vertices, %zu edges, %zu faces, %zu volumes; validate %s\n",
                cells.num_vertices(), cells.num_edges(), cells.num_faces(), cells.num_volumes(),
                valid.ok() ? "ok" : valid.message.c_str());
    std::printf("2D and 3D faces    %s\n", r.faces_agree ? "agree" : "DIFFER");
    std::printf("status             %s (%s)%s\n", cellforge::to_string(r.cells.status),
                r.cells.status_reason.c_str(), r.flagged ? "; flagged, not certified: see the notes" : "");
    std::printf("total              %9.3f ms\n", r.milliseconds);
    for (const std::string& d : r.diagnostics) std::printf("note               %s\n", d.c_str());

    stage("writing " + std::to_string(cells.num_faces()) + " faces");
    // A solid only when certified as wire2cells certifies one (solid or ambiguous), its faces
    // the drawing's and every drawn edge on a face.
    const bool closed = r.cells.status == cellforge::solid_status::solid ||
                        r.cells.status == cellforge::solid_status::ambiguous;
    if (!valid.ok() || !r.faces_agree || !r.unused_edges.empty() || !closed) {
      const std::string why = r.cells.status == cellforge::solid_status::budget
                                  ? "a work budget ran out: " + r.cells.status_reason
                              : !valid.ok()    ? "the cell complex fails validation: " + valid.message
                              : !r.faces_agree ? std::string("the solid's faces differ from the drawing's")
                              : !r.unused_edges.empty()
                                  ? std::to_string(r.unused_edges.size()) +
                                        " drawn edges bound no face (first: edge " +
                                        std::to_string(r.unused_edges.front()) + ", 0-based)"
                                  : std::string("the 3D reading is ") + cellforge::to_string(r.cells.status) +
                                        ": " + r.cells.status_reason;
      std::fprintf(stderr, "sketch2cells: read, but no good solid: %s\n", why.c_str());
      if (!p.keep_partial) return example::exit_not_for_this;
      failed = true;
    }
    if (p.svg) {
      cellforge::io::drawing_svg_options picture;
      picture.title = "sketch2cells: faces of " + input.filename().string();
      picture.labels = drawing.points.size() <= 60;
      out.write(faces_path, [&](const fs::path& to) {
        cellforge::io::write_drawing_svg(to, drawing, r.faces.loops, picture);
      });
    }
    out.write(wire_path, [&](const fs::path& to) { cellforge::io::write_obj(to, r.wire); });
    out.write(cells_path, [&](const fs::path& to) { cellforge::io::write_3dcl(to, cells); });
    out.write(obj_path, [&](const fs::path& to) { cellforge::io::write_cells_obj(to, cells); });
    if (p.svg)
      out.write(picture_path, [&](const fs::path& to) { cellforge::io::write_cells_svg(to, cells); });
    if (step)
      out.write(step_path, [&](const fs::path& to) { cellforge::io::write_step(to, cells, {.name = stem}); });
    if (failed) return example::exit_not_for_this;  // the outputs kept as partial
    out.commit();
    std::printf("wrote              %s\n", out.list().c_str());
    return example::exit_ok;
  });
}
