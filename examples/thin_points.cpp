// thin_points: the selection-growing thin-point finder (seed 000_6c43f981384fedb6.txt, chapter V).
// Grows face selections from the end of a closed solid's central axis and reports the loops
// around it that are markedly shorter than their neighbours: necks, waists, handles.
//
//   thin_points [options] [input]   input: any closed mesh, or a .3dcl (--volume N, default 0; ids
//                                   are then cell ids); none: the bundled dumbbell
//   thin_points --help              every option with its default, the outputs, the exit statuses
//
// Writes into the output folder (-o, default ./out/): <name>_loops.obj (the solid's faces plus one closed `l`
// line per loop) and <name>_thin.svg (the solid with its loops drawn thick, strongest first).
#include <cstdio>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include "cellforge/io/curves_io.hpp"
#include "cellforge/thin/thin_points.hpp"
#include "example_support.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  example::program p;
  p.name = "thin_points";
  p.usage = "[options] [input ...]";
  p.takes = {example::input_kind::mesh, example::input_kind::cells};
  p.about =
      "The selection-growing thin-point finder (seed 000 ch. V): grows face selections from the end of a\n"
      "closed solid's central axis and reports the loops around it that are markedly shorter than their\n"
      "neighbours: necks, waists, handles.";
  p.input_help =
      "a closed mesh (.off, .obj, .ply, .stl) or a cell list (.3dcl, one volume: --volume); default:\n"
      "       the bundled dumbbell (dumbbell.off)";
  p.outputs_help =
      "  <name>_loops.obj   the solid's faces plus one closed 'l' line per thin loop\n"
      "  <name>_thin.svg    the solid with its loops drawn thick, strongest first\n"
      "<name> is the input's file name without its extension.\n";
  p.exit4_help =
      "read, but not a closed solid (a wireframe, a point set, an open mesh, a skeleton, a drawing:\n"
      "     the message names the program that takes it)";
  cellforge::thin_options options;
  bool faithful = false;
  int volume = 0;
  p.add_common_options();
  p.add_solid_options(volume);
  p.options.push_back({{"--cap"},
                       "N",
                       "the selection cap n_s of seed 5.4, a whole number from 1 to 1000 (default: " +
                           std::to_string(options.selection_cap) + ")",
                       [&](std::string_view v) {
                         const double n = example::option_number("--cap", v, 1, 1000);
                         if (n != static_cast<int>(n))
                           throw example::usage_error("--cap must be a whole number, got '" + std::string(v) +
                                                      "'");
                         options.selection_cap = static_cast<int>(n);
                       }});
  p.options.push_back(
      {{"--faithful"},
       "",
       "the seed's data structures and its literal 5.3 detection (default: the seed's rule up to "
       "4000 faces, the scalable rule above; docs/thin.md)",
       [&](std::string_view) { faithful = true; }});
  p.options.push_back(
      {{"--cluster"},
       "",
       "seed 8.2: grow over flat triangle fans and triangle pairs, for triangle meshes (default: off)",
       [&](std::string_view) { options.cluster_faces = true; }});
  return example::run(p, argc, argv, [&](const std::vector<std::string>& args) -> int {
    const fs::path input = p.one_input(args, fs::path(CELLFORGE_DATA_DIR) / "dumbbell.off");
    example::stage_note& stage = p.stage;
    const std::string stem = input.stem().string();
    example::output_files out(p, {input});
    const fs::path loops_path = out.add(stem + "_loops.obj"), picture_path = out.add(stem + "_thin.svg");
    const example::solid_input x = example::load_closed_solid(p, input, volume);
    if (faithful) {
      options.mode = cellforge::thin_mode::faithful;
      options.detection = cellforge::thin_detection::seed;
    }
    cellforge::thin_result<glm::dvec3> r;  // the points of the example's meshes
    const double ms = x.run([&](const auto& cc, auto v) { r = cellforge::find_thin_points(cc, v, options); },
                            [&](const auto& mesh) { r = cellforge::find_thin_points(mesh, options); });
    x.print_solid("thin_points");
    std::printf("  rules            %s, selection cap %d%s\n", faithful ? "the seed's (--faithful)" : "fast",
                options.selection_cap, options.cluster_faces ? ", clustered faces" : "");
    if (options.cluster_faces)
      std::printf("  clusters         grew over %u faces (%u mesh faces merged into fans or pairs)\n",
                  r.grown_faces, r.clustered_faces);
    std::printf("  central axis     through (%.4g, %.4g, %.4g) along (%.4g, %.4g, %.4g)\n", r.axis_origin.x,
                r.axis_origin.y, r.axis_origin.z, r.axis_direction.x, r.axis_direction.y, r.axis_direction.z);
    std::printf("  start face       %u\n", r.start_face);
    std::printf("  cycles           %zu\n", r.cycle_lengths.size());
    std::printf("  thin loops       %zu (strongest first)\n", r.loops.size());
    for (std::size_t i = 0; i < r.loops.size(); ++i) {
      const auto& l = r.loops[i];
      std::printf("    %2zu: %3zu edges, length %.5g, at %.3f of the axis, cycle %zu, strength %.4g\n", i + 1,
                  l.edges.size(), l.length, l.axis_position, l.cycle, l.strength);
    }
    if (!r.complete) std::printf("  INCOMPLETE       the work budget ran out\n");
    for (const std::string& d : r.diagnostics) std::printf("  note             %s\n", d.c_str());
    std::printf("  time             %.3f ms\n", ms);

    stage("writing " + std::to_string(r.loops.size()) + " loops");
    std::vector<std::vector<glm::dvec3>> loops;
    for (const auto& l : r.loops) loops.push_back(l.points);
    out.write(loops_path, [&](const fs::path& to) {
      cellforge::io::write_polylines_obj(to, loops, true, &x.s.soup,
                                         {.comment = "thin_points " + input.filename().string() +
                                                     ": the solid, then one closed l line per thin loop"});
    });
    if (p.svg) {
      stage("drawing " + std::to_string(r.loops.size()) + " loops on " +
            std::to_string(x.s.soup.num_faces()) + " faces");
      cellforge::io::thin_loops_svg_options picture;
      picture.picture.title = "thin_points: " + input.filename().string();
      picture.picture.view.elevation_deg = 20;
      out.write(picture_path,
                [&](const fs::path& to) { cellforge::io::write_thin_loops_svg(to, x.s.soup, r, picture); });
    }
    out.commit();
    std::printf("  wrote            %s\n", out.list().c_str());
    return example::exit_ok;
  });
}
