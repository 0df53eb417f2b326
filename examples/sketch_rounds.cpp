// sketch_rounds: a line drawing with rounds and fillets (a parallel view of a polyhedron whose
// edges are blended by circular arcs, every edge drawn, the blends' end curves as elliptical
// arcs) becomes its polyhedral skeleton, the skeleton's solid and the rounded solid (seed
// 003_be08eec927fcc329.txt, "Rounds and fillets").
//
//   sketch_rounds                      the bundled L-bracket (examples/data/l_bracket_rounds.txt)
//   sketch_rounds drawing.txt|drawing.svg|drawing.dxf
//
// A .txt drawing is the line-drawing text with arcs (`a i j rx ry rotation large ccw`), an .svg
// one has its arcs as path commands A, a .dxf (ASCII) one as ARC, ELLIPSE or bulged polyline
// entities, every visible layer read (docs/formats.md). Writes, in the current directory,
// <name>_arcs.svg (the drawing, each pair of arcs in its own colour), <name>_skeleton.txt and
// <name>_skeleton.svg (the skeleton drawing, its faces shaded), the skeleton's cell complex as
// <name>.3dcl and <name>.obj, the rounded solid as <name>_rounded.obj (a mesh) and as
// <name>_rounded.step (STEP AP214, its blends cylinders: a real round in a CAD kernel) and the
// round attribute of each skeleton edge as <name>_rounds.txt; prints the arcs, the pairs, and
// every blend's kind, category, radius and consistency. Never writes over its input.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <numbers>
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
#include "cellforge/io/step.hpp"
#include "cellforge/io/svg_drawing.hpp"
#include "cellforge/sketch/rounds.hpp"
#include "example_support.hpp"

namespace fs = std::filesystem;

namespace {

const char* kind_name(cellforge::blend_kind k) {
  return k == cellforge::blend_kind::round    ? "round"
         : k == cellforge::blend_kind::fillet ? "fillet"
                                              : "unknown";
}

const char* category_name(cellforge::blend_category c) {
  switch (c) {
    case cellforge::blend_category::a:
      return "a";
    case cellforge::blend_category::b:
      return "b";
    case cellforge::blend_category::c:
      return "c";
    default:
      return "a or c";
  }
}

// The skeleton's round attribute per edge, one line per blend, beside the .3dcl (whose edges
// the first column numbers): what a CAD engine needs to put the rounds back as features.
void write_round_attributes(const fs::path& path, const cellforge::rounds_result<glm::dvec3, glm::dvec2>& r,
                            const std::string& input) {
  std::ofstream out(path);
  out << "# the rounds of " << input << " (sketch_rounds), one line per blend of the skeleton:\n"
      << "# cell_edge junction junction kind category radius setback wedge_degrees consistent\n"
      << "# cell_edge numbers the edges of the .3dcl (-1: not in the complex); junctions are the skeleton\n"
      << "# drawing's; kind is round (convex) or fillet (concave); category a, b or c is this reading's\n";
  out.precision(17);
  for (const auto& e : r.rounds)
    out << (e.cell_edge == cellforge::edge_round::npos ? -1 : static_cast<long long>(e.cell_edge)) << ' '
        << e.junctions[0] << ' ' << e.junctions[1] << ' ' << kind_name(e.kind) << ' '
        << category_name(e.category) << ' ' << e.radius << ' ' << e.setback << ' '
        << e.wedge_angle * 180 / std::numbers::pi << ' ' << (e.consistent ? "yes" : "no") << '\n';
  if (!out) throw cellforge::error(cellforge::error_category::io, "cannot write " + path.string());
}

}  // namespace

int main(int argc, char** argv) {
  example::stage_note stage;
  try {
    const example::command_line cl = example::parse_command_line(
        argc, argv, fs::path(CELLFORGE_DATA_DIR) / "l_bracket_rounds.txt", {}, {});
    std::string ext = cl.input.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    const std::string stem = cl.input.stem().string();
    const fs::path outputs[] = {stem + "_arcs.svg",   stem + "_skeleton.txt", stem + "_skeleton.svg",
                                stem + ".3dcl",       stem + ".obj",          stem + "_rounded.obj",
                                stem + "_rounds.txt", stem + "_rounded.step"};
    for (const fs::path& out : outputs) example::refuse_to_overwrite(out, cl.input);

    stage("reading " + example::file_and_size(cl.input));
    cellforge::arc_drawing<glm::dvec2> drawing;
    if (ext == ".svg") {
      auto read = cellforge::io::read_svg_arc_drawing(cl.input);
      drawing = std::move(read.drawing);
      std::printf(
          "input              %s: %zu SVG elements, %zu straight segments, %zu arcs, %zu ends snapped\n",
          cl.input.string().c_str(), read.elements, read.segments, read.arcs, read.snapped);
      for (const std::string& d : read.diagnostics) std::printf("note               %s\n", d.c_str());
    } else if (ext == ".dxf") {
      auto read = cellforge::io::read_dxf_arc_drawing(cl.input);
      drawing = std::move(read.drawing);
      std::printf(
          "input              %s: DXF %s, %zu entities, %zu straight segments, %zu arcs, %zu ends snapped\n",
          cl.input.string().c_str(), read.version.c_str(), read.entities, read.segments, read.arcs,
          read.snapped);
      for (const std::string& d : read.diagnostics) std::printf("note               %s\n", d.c_str());
    } else {
      drawing = cellforge::io::read_arc_drawing_text(cl.input);
      std::printf("input              %s\n", cl.input.string().c_str());
    }
    std::printf("drawing            %zu junctions, %zu lines, %zu arcs\n", drawing.lines.points.size(),
                drawing.lines.edges.size(), drawing.arcs.size());
    if (const cellforge::arc_validation v = cellforge::validate_arcs(drawing); !v)
      throw cellforge::error(cellforge::error_category::invalid_input, "the drawing's arcs: " + v.message);

    stage("reconstructing a drawing of " + std::to_string(drawing.lines.points.size()) + " junctions and " +
          std::to_string(drawing.arcs.size()) + " arcs");
    const auto r = cellforge::reconstruct_rounds(drawing);
    const auto& sk = r.skeleton;
    const auto& pairing = sk.pairing;
    std::printf(
        "pairing            %9.3f ms   %zu arcs in %zu end curves, %zu pairs (%zu by a contour line, "
        "%zu by parallel lines), %zu arcs unpaired\n",
        pairing.milliseconds, pairing.arcs, pairing.curves, pairing.pairs.size(), pairing.by_contour,
        pairing.by_parallel_lines, pairing.unpaired.size());
    for (std::size_t k = 0; k < pairing.pairs.size(); ++k) {
      const auto& p = pairing.pairs[k];
      std::printf("  pair %-3zu         arcs", k);
      for (const auto& curve : p.arcs)
        for (const std::uint32_t a : curve) std::printf(" %u", a);
      std::printf(", %s, category %s\n",
                  p.rule == cellforge::pairing_rule::contour_line ? "a contour line tangent to both"
                                                                  : "translates with parallel lines",
                  category_name(p.category));
    }
    std::printf(
        "skeleton           %9.3f ms   %zu junctions, %zu edges; %zu rounds, %zu fillets, %zu unknown; "
        "validation %s\n",
        sk.milliseconds, sk.skeleton.points.size(), sk.skeleton.edges.size(), sk.rounds, sk.fillets,
        sk.unknown, sk.validation.ok() ? "ok" : sk.validation.message.c_str());
    const auto& cells = r.reading.cells.cells;
    const cellforge::cells_validation_result valid = cellforge::validate(cells);
    std::printf(
        "skeleton solid     %9.3f ms   %zu vertices, %zu edges, %zu faces, %zu volumes; validate %s\n",
        r.reading.milliseconds, cells.num_vertices(), cells.num_edges(), cells.num_faces(),
        cells.num_volumes(), valid.ok() ? "ok" : valid.message.c_str());
    // The drawing alone tells category b only by a contour line; the reading's depths tell a,
    // b and c apart (for this reading: its Necker mirror swaps a and c).
    for (const auto& e : r.rounds) {
      std::printf(
          "  blend %-3zu        %-6s on edge %u, category %s (the drawing's: %s), radius %.6g (ends %.6g, "
          "%.6g; spread %.2g), %s%s\n",
          e.blend, kind_name(e.kind), e.cell_edge, category_name(e.category),
          category_name(pairing.pairs[sk.blends[e.blend].pair].category), e.radius, e.end_radius[0],
          e.end_radius[1], e.radius_spread,
          e.source == cellforge::radius_source::lifted      ? "lifted"
          : e.source == cellforge::radius_source::circle_2d ? "from the 2D circles"
                                                            : "no radius",
          e.consistent ? ", consistent" : ", INCONSISTENT");
    }
    std::printf("blends             %zu consistent, %zu inconsistent%s\n", r.consistent, r.inconsistent,
                r.depth_corrected ? " (depths fitted to circular blends)" : "");
    const auto mesh = cellforge::rounded_mesh(r);
    std::printf(
        "rounded mesh       %zu vertices, %zu faces (%zu blend strips of %zu quads, %zu blends skipped)\n",
        mesh.mesh.points.size(), mesh.mesh.num_faces(), mesh.strips, mesh.strip_quads, mesh.skipped);
    const auto brep = cellforge::rounded_brep(r);
    std::printf(
        "rounded B-rep      %9.3f ms   %zu planar faces, %zu cylinders, %zu lines, %zu end arcs; volume "
        "%.9g; "
        "check %s\n",
        brep.milliseconds, brep.planar_faces, brep.blend_faces, brep.lines, brep.arcs, brep.volume,
        brep.ok ? "ok" : "FAILED");
    std::printf("total              %9.3f ms\n", r.milliseconds);
    for (const std::string& d : r.diagnostics) std::printf("note               %s\n", d.c_str());
    for (const std::string& d : mesh.diagnostics) std::printf("note               %s\n", d.c_str());
    for (const std::string& d : brep.diagnostics) std::printf("note               %s\n", d.c_str());

    stage("writing " + std::to_string(mesh.mesh.num_faces()) + " faces");
    // Each pair's arcs in one hue; unpaired arcs all in the next.
    std::vector<std::size_t> colour(drawing.arcs.size(), pairing.pairs.size());
    for (std::size_t k = 0; k < pairing.pairs.size(); ++k)
      for (const auto& curve : pairing.pairs[k].arcs)
        for (const std::uint32_t a : curve) colour[a] = k;
    cellforge::io::drawing_svg_options picture;
    picture.labels = drawing.lines.points.size() <= 60;
    picture.title = "sketch_rounds: the arcs of " + cl.input.filename().string() + ", a colour per pair";
    cellforge::io::write_arc_drawing_svg(outputs[0], drawing, {}, picture, colour);
    cellforge::io::write_drawing_text(outputs[1], sk.skeleton,
                                      {.comment = "the skeleton of " + cl.input.filename().string() +
                                                  " (sketch_rounds): its blends replaced by sharp edges"});
    picture.labels = sk.skeleton.points.size() <= 60;
    picture.title = "sketch_rounds: the skeleton of " + cl.input.filename().string() + " and its faces";
    cellforge::io::write_drawing_svg(outputs[2], sk.skeleton, r.reading.faces.loops, picture);
    cellforge::io::write_3dcl(outputs[3], cells);
    cellforge::io::write_cells_obj(outputs[4], cells);
    cellforge::io::write_obj(outputs[5], mesh.mesh);
    write_round_attributes(outputs[6], r, cl.input.filename().string());
    const auto step = cellforge::io::write_step(outputs[7], brep.solid, {.name = stem});
    for (const std::string& d : step.diagnostics) std::printf("note               STEP: %s\n", d.c_str());
    std::printf("wrote             ");
    for (const fs::path& out : outputs) std::printf(" %s", out.string().c_str());
    std::printf("\n");
    const bool ok = valid.ok() && pairing.unpaired.empty() && r.inconsistent == 0 && mesh.skipped == 0 &&
                    brep.ok && step.diagnostics.empty();
    return ok ? 0 : 1;
  } catch (const std::bad_alloc&) {
    example::report_out_of_memory("sketch_rounds", stage);
    return 1;
  } catch (const std::exception& e) {  // cellforge::error among them: parse errors name file:line
    std::fprintf(stderr, "sketch_rounds: %s\n", e.what());
    return 1;
  }
}
