// smooth_edges: the cubic edge fitter (seed 000_6c43f981384fedb6.txt, chapter VI). Every edge of
// a closed solid becomes a cubic, quadratic or straight curve through its end vertices.
//
//   smooth_edges [options] [input]   input: any closed mesh, or a .3dcl (--volume N, default 0; ids
//                                    are then cell ids); none: the bundled coarse cylinder
//   smooth_edges --help              every option with its default, the outputs, the exit statuses
//
// Writes into the output folder (-o, default ./out/): <name>.curves (the seed's curve file: axis, limits, two
// cubics per edge; docs/formats.md), <name>.polylines (15 segments per curve), <name>_curves.obj (the solid's
// faces plus one `l` line per curve) and <name>_smooth.svg (straight edges beside smoothed).
#include <cstdio>
#include <filesystem>
#include <new>
#include <string>

#include "cellforge/io/curves_io.hpp"
#include "cellforge/smooth/smooth_edges.hpp"
#include "example_support.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  example::program p;
  p.name = "smooth_edges";
  p.usage = "[options] [input ...]";
  p.takes = {example::input_kind::mesh, example::input_kind::cells};
  p.about =
      "The cubic edge fitter (seed 000 ch. VI): every edge of a closed solid becomes a cubic, quadratic or\n"
      "straight curve through its end vertices.";
  p.input_help =
      "a closed mesh (.off, .obj, .ply, .stl) or a cell list (.3dcl, one volume: --volume); default:\n"
      "       the bundled coarse cylinder (cylinder16.off)";
  p.outputs_help =
      "  <name>.curves       the seed's curve file: axis, limits, two cubics per edge (docs/formats.md)\n"
      "  <name>.polylines    15 segments per curve\n"
      "  <name>_curves.obj   the solid's faces plus one 'l' line per curve\n"
      "  <name>_smooth.svg   straight edges beside smoothed ones\n"
      "<name> is the input's file name without its extension.\n";
  p.exit4_help =
      "read, but not a closed solid (a wireframe, a point set, an open mesh, a skeleton, a drawing:\n"
      "     the message names the program that takes it)";
  cellforge::smooth_options options;
  bool faithful = false;
  double angle = options.angle_deg;
  int volume = 0;
  p.add_common_options();
  p.add_solid_options(volume);
  p.options.push_back(
      {{"--angle"},
       "DEG",
       "faces meeting at less than DEG degrees are one continuous surface, 0 to 90 (default: " +
           example::fmt(options.angle_deg) + ")",
       [&](std::string_view v) { angle = example::option_number("--angle", v, 0, 90); }});
  p.options.push_back({{"--faithful"},
                       "",
                       "the seed's rules: no crease smoothing, axis form only (default: the extended rules)",
                       [&](std::string_view) { faithful = true; }});
  return example::run(p, argc, argv, [&](const std::vector<std::string>& args) -> int {
    const fs::path input = p.one_input(args, fs::path(CELLFORGE_DATA_DIR) / "cylinder16.off");
    example::stage_note& stage = p.stage;
    const std::string stem = input.stem().string();
    example::output_files out(p, {input});
    const fs::path curves_path = out.add(stem + ".curves"), polylines_path = out.add(stem + ".polylines"),
                   obj_path = out.add(stem + "_curves.obj"), picture_path = out.add(stem + "_smooth.svg");
    const example::solid_input x = example::load_closed_solid(p, input, volume);
    if (faithful) options = cellforge::seed_smooth_options();
    options.angle_deg = angle;
    cellforge::smooth_result<glm::dvec3> r;  // the points of the example's meshes
    const double ms = x.run([&](const auto& cc, auto v) { r = cellforge::smooth_edges(cc, v, options); },
                            [&](const auto& mesh) { r = cellforge::smooth_edges(mesh, options); });
    x.print_solid("smooth_edges");
    std::printf("  rules            %s, angle %.4g degrees\n",
                faithful ? "the seed's (--faithful)" : "extended", options.angle_deg);
    std::printf("  surfaces         %zu (creases between sectors: %zu)\n", r.num_surfaces, r.num_creases);
    // Kinds count the vertex tangents that shaped a curve (seed 6.4); a cubic between coplanar
    // faces is still a straight segment, so say how many curves actually bend.
    std::size_t bending = 0;
    for (const auto& c : r.curves) bending += c.chord_deviation() > 1e-9 * r.model_size;
    std::printf("  curves           %zu: %zu cubic, %zu quadratic, %zu straight; %zu bend off their chords\n",
                r.curves.size(), r.num_cubic, r.num_quadratic, r.num_straight, bending);
    std::printf("  forms            %zu axis polynomials, %zu Bezier\n", r.num_axis_form, r.num_bezier_form);
    std::printf("  readjustment     %d cycles, %s\n", r.iterations,
                r.converged  ? "converged"
                : r.averaged ? "ended by averaging (seed 6.5)"
                             : "not converged");
    std::printf("  time             %.3f ms\n", ms);

    const auto& curves = r.curves;
    stage("writing " + std::to_string(curves.size()) + " curves");
    out.write(curves_path, [&](const fs::path& to) {
      cellforge::io::write_curve_file(to, curves,
                                      {.comment = "smooth_edges " + input.filename().string() +
                                                  ": one curve per edge, in edge order (docs/formats.md)"});
    });
    out.write(polylines_path, [&](const fs::path& to) { cellforge::io::write_polyline_file(to, curves); });
    out.write(obj_path,
              [&](const fs::path& to) { cellforge::io::write_polylines_obj(to, curves, &x.s.soup); });
    if (p.svg) {
      stage("drawing " + std::to_string(curves.size()) + " curves on " +
            std::to_string(x.s.soup.num_faces()) + " faces");
      cellforge::io::smoothing_svg_options picture;
      picture.picture.title = "smooth_edges: " + input.filename().string();
      picture.picture.view.elevation_deg = 30;
      out.write(picture_path, [&](const fs::path& to) {
        cellforge::io::write_smoothing_svg(to, x.s.soup, curves, picture);
      });
    }
    out.commit();
    std::printf("  wrote            %s\n", out.list().c_str());
    return example::exit_ok;
  });
}
