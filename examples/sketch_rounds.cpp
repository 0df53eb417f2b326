// sketch_rounds: a line drawing with rounds and fillets (a parallel view of a polyhedron whose
// edges are blended by circular arcs, every edge drawn, the blends' end curves as elliptical
// arcs) becomes its polyhedral skeleton, the skeleton's solid and the rounded solid (seed
// 003_be08eec927fcc329.txt, "Rounds and fillets").
//
//   sketch_rounds [options] [input]   input: drawing.txt|drawing.svg|drawing.dxf; none: the bundled
//                                     L-bracket (examples/data/l_bracket_rounds.txt)
//   sketch_rounds --help              every option with its default, the outputs, the exit statuses
//
// A .txt drawing is the line-drawing text with arcs (`a i j rx ry rotation large ccw`), an .svg
// one has its arcs as path commands A, a .dxf (ASCII) one as ARC, ELLIPSE or bulged polyline
// entities, every visible layer read (docs/formats.md). Writes, into the output folder (-o,
// default ./out/; --no-svg leaves out the two pictures),
// <name>_arcs.svg (the drawing, each pair of arcs in its own colour), <name>_skeleton.txt and
// <name>_skeleton.svg (the skeleton drawing, its faces shaded), the skeleton's cell complex as
// <name>.3dcl and <name>.obj, the rounded solid as <name>_rounded.obj (a mesh, --format) and as
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
#include "cellforge/io/drawing_pictures.hpp"
#include "cellforge/io/drawing_text.hpp"
#include "cellforge/io/dxf_drawing.hpp"
#include "cellforge/io/mesh_io.hpp"
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
  example::program p;
  p.name = "sketch_rounds";
  p.usage = "[options] [input ...]";
  p.takes = {example::input_kind::drawing};
  p.about =
      "A line drawing with rounds and fillets (a parallel view of a polyhedron whose edges are blended by\n"
      "circular arcs, every edge drawn) becomes its polyhedral skeleton, the skeleton's solid and the\n"
      "rounded solid (seed 003, \"Rounds and fillets\"); prints the arcs, the pairs, and every blend's\n"
      "kind, category, radius and consistency.";
  p.input_help =
      "a drawing with arcs: the text format with 'a' lines (.txt or any other name), .svg (arcs as path\n"
      "       commands A) or .dxf (ASCII: ARC, ELLIPSE, bulged polylines); docs/formats.md; default: the\n"
      "       bundled l_bracket_rounds.txt";
  p.outputs_help =
      "  <name>_arcs.svg          the drawing, each pair of arcs in its own colour\n"
      "  <name>_skeleton.txt      the skeleton drawing (blends replaced by sharp edges)\n"
      "  <name>_skeleton.svg      the skeleton drawing, its faces shaded\n"
      "  <name>.3dcl, <name>.obj  the skeleton's cell complex\n"
      "  <name>_rounded.<format>  the rounded solid (--format, default obj)\n"
      "  <name>_rounds.txt        the round attribute of each skeleton edge\n"
      "  <name>_rounded.step      the rounded solid as STEP AP214, its blends cylinders\n"
      "<name> is the input's file name without its extension; --no-svg leaves out both pictures.\n";
  p.exit4_help =
      "read, but not a drawing (a mesh, a wireframe, a skeleton: the message names the program that\n"
      "     takes it), or no consistent reading: unpaired arcs, inconsistent blends, blends the rounded\n"
      "     mesh skips, a skeleton solid that fails validation, or a rounded B-rep that fails its check";
  p.add_common_options("obj");
  return example::run(p, argc, argv, [&](const std::vector<std::string>& args) -> int {
    const fs::path input = p.one_input(args, fs::path(CELLFORGE_DATA_DIR) / "l_bracket_rounds.txt");
    example::stage_note& stage = p.stage;
    const std::string stem = input.stem().string();
    const std::string ext = example::lower_extension(input);
    example::output_files out(p, {input});
    bool failed = false;  // a result that fails its check: written only with --keep-partial
    const fs::path arcs_path = out.add(stem + "_arcs.svg"),
                   skeleton_text_path = out.add(stem + "_skeleton.txt"),
                   skeleton_picture_path = out.add(stem + "_skeleton.svg"),
                   cells_path = out.add(stem + ".3dcl"), obj_path = out.add(stem + ".obj"),
                   attributes_path = out.add(stem + "_rounds.txt");
    std::vector<fs::path> mesh_paths;
    for (const std::string& f : p.formats) mesh_paths.push_back(out.add(stem + "_rounded." + f));
    const fs::path step_path = out.add(stem + "_rounded.step");
    example::expect_extension(p.name, input, {example::input_kind::drawing}, "a drawing");
    if (ext == ".obj") {
      const example::obj_contents c = example::read_obj_contents(input);
      example::not_for_this(p.name, input, c.describe(), "a drawing", c.kind());
    }
    stage("reading " + example::file_and_size(input));
    cellforge::arc_drawing<glm::dvec2> drawing;
    if (ext == ".svg") {
      auto read = cellforge::io::read_svg_arc_drawing(input);
      drawing = std::move(read.drawing);
      std::printf(
          "input              %s: %zu SVG elements, %zu straight segments, %zu arcs, %zu ends snapped\n",
          input.string().c_str(), read.elements, read.segments, read.arcs, read.snapped);
      for (const std::string& d : read.diagnostics) std::printf("note               %s\n", d.c_str());
    } else if (ext == ".dxf") {
      auto read = cellforge::io::read_dxf_arc_drawing(input);
      drawing = std::move(read.drawing);
      std::printf(
          "input              %s: DXF %s, %zu entities, %zu straight segments, %zu arcs, %zu ends snapped\n",
          input.string().c_str(), read.version.c_str(), read.entities, read.segments, read.arcs,
          read.snapped);
      for (const std::string& d : read.diagnostics) std::printf("note               %s\n", d.c_str());
    } else {
      drawing = cellforge::io::read_arc_drawing_text(input);
      std::printf("input              %s\n", input.string().c_str());
    }
    std::printf("drawing            %zu junctions, %zu lines, %zu arcs\n", drawing.lines.points.size(),
                drawing.lines.edges.size(), drawing.arcs.size());
    if (const cellforge::arc_validation v = cellforge::validate(drawing); !v)
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
    const cellforge::cells_validation valid = cellforge::validate(cells);
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
        "%.9g; check %s\n",
        brep.milliseconds, brep.planar_faces, brep.blend_faces, brep.lines, brep.arcs, brep.volume,
        brep.ok ? "ok" : "FAILED");
    std::printf("total              %9.3f ms\n", r.milliseconds);
    for (const std::string& d : r.diagnostics) std::printf("note               %s\n", d.c_str());
    for (const std::string& d : mesh.diagnostics) std::printf("note               %s\n", d.c_str());
    for (const std::string& d : brep.diagnostics) std::printf("note               %s\n", d.c_str());

    const bool ok =
        valid.ok() && pairing.unpaired.empty() && r.inconsistent == 0 && mesh.skipped == 0 && brep.ok;
    if (!ok) {
      std::string why;
      const auto add = [&](bool bad, const std::string& what) {
        if (bad) why += (why.empty() ? "" : "; ") + what;
      };
      add(!valid.ok(), "the skeleton solid fails validation: " + valid.message);
      add(!pairing.unpaired.empty(), std::to_string(pairing.unpaired.size()) + " arcs unpaired");
      add(r.inconsistent > 0, std::to_string(r.inconsistent) + " blends inconsistent");
      add(mesh.skipped > 0, std::to_string(mesh.skipped) + " blends skipped by the rounded mesh");
      add(!brep.ok, "the rounded B-rep fails its check");
      std::fprintf(stderr, "sketch_rounds: read, but no consistent reading: %s\n", why.c_str());
      if (!p.keep_partial) return example::exit_not_for_this;
      failed = true;
    }
    stage("writing " + std::to_string(mesh.mesh.num_faces()) + " faces");
    // Each pair's arcs in one hue; unpaired arcs all in the next.
    std::vector<std::size_t> colour(drawing.arcs.size(), pairing.pairs.size());
    for (std::size_t k = 0; k < pairing.pairs.size(); ++k)
      for (const auto& curve : pairing.pairs[k].arcs)
        for (const std::uint32_t a : curve) colour[a] = k;
    cellforge::io::drawing_svg_options picture;
    picture.labels = drawing.lines.points.size() <= 60;
    picture.title = "sketch_rounds: the arcs of " + input.filename().string() + ", a colour per pair";
    if (p.svg)
      out.write(arcs_path, [&](const fs::path& to) {
        cellforge::io::write_arc_drawing_svg(to, drawing, {}, picture, colour);
      });
    out.write(skeleton_text_path, [&](const fs::path& to) {
      cellforge::io::write_drawing_text(to, sk.skeleton,
                                        {.comment = "the skeleton of " + input.filename().string() +
                                                    " (sketch_rounds): its blends replaced by sharp edges"});
    });
    picture.labels = sk.skeleton.points.size() <= 60;
    picture.title = "sketch_rounds: the skeleton of " + input.filename().string() + " and its faces";
    if (p.svg)
      out.write(skeleton_picture_path, [&](const fs::path& to) {
        cellforge::io::write_drawing_svg(to, sk.skeleton, r.reading.faces.loops, picture);
      });
    out.write(cells_path, [&](const fs::path& to) { cellforge::io::write_3dcl(to, cells); });
    out.write(obj_path, [&](const fs::path& to) { cellforge::io::write_cells_obj(to, cells); });
    for (const fs::path& path : mesh_paths)
      out.write(path, [&](const fs::path& to) { example::write_mesh_file(to, mesh.mesh); });
    out.write(attributes_path,
              [&](const fs::path& to) { write_round_attributes(to, r, input.filename().string()); });
    cellforge::io::step_result step;
    out.write(step_path,
              [&](const fs::path& to) { step = cellforge::io::write_step(to, brep.solid, {.name = stem}); });
    for (const std::string& d : step.diagnostics) std::printf("note               STEP: %s\n", d.c_str());
    if (!step.diagnostics.empty()) {
      std::fprintf(stderr,
                   "sketch_rounds: read, but the STEP writer reports %zu problems (printed as notes)\n",
                   step.diagnostics.size());
      failed = true;
    }
    if (failed) return example::exit_not_for_this;  // the outputs kept as partial with --keep-partial
    out.commit();
    std::printf("wrote              %s\n", out.list().c_str());
    return example::exit_ok;
  });
}
