// thin_points: the selection-growing thin-point finder (seed 000_6c43f981384fedb6.txt, chapter V).
// Grows face selections from the end of a closed solid's central axis and reports the loops
// around it that are markedly shorter than their neighbours: necks, waists, handles.
//
//   thin_points                          the bundled dumbbell (examples/data/dumbbell.off)
//   thin_points model.off|obj|ply        any closed mesh
//   thin_points cells.3dcl [--volume N]  volume N (default 0) of a cell list; ids are cell ids
//   options: --cap N (the selection cap n_s of seed 5.4, 1..1000, default 40)
//            --faithful (the seed's data structures and its literal 5.3 detection)
//            (default: the seed's rule up to 4000 faces, the scalable rule above; docs/thin.md)
//            --cluster (seed 8.2: grow over flat triangle fans and triangle pairs; for triangle meshes)
//            --out DIR (default out)
//            --no-svg (leave the picture out)
//
// Writes into DIR: <name>_loops.obj (the solid's faces plus one closed `l` line per loop) and
// <name>_thin.svg (the solid with its loops drawn thick, strongest first).
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
  example::stage_note stage;
  try {
    const example::session x = example::open_session(
        argc, argv, fs::path(CELLFORGE_DATA_DIR) / "dumbbell.off", {"cap"}, {"faithful", "cluster"}, stage);
    const example::command_line& cl = x.cl;
    cellforge::thin_options options;
    options.selection_cap = static_cast<int>(cl.number("cap", options.selection_cap, 1, 1000, true));
    if (cl.has("faithful")) {
      options.mode = cellforge::thin_mode::faithful;
      options.detection = cellforge::thin_detection::seed;
    }
    options.cluster_faces = cl.has("cluster");
    cellforge::thin_result<glm::dvec3> r;  // the points of the example's meshes
    const double ms = x.run([&](const auto& cc, auto v) { r = cellforge::find_thin_points(cc, v, options); },
                            [&](const auto& mesh) { r = cellforge::find_thin_points(mesh, options); });
    x.print_solid("thin_points");
    std::printf("  rules            %s, selection cap %d%s\n",
                cl.has("faithful") ? "the seed's (--faithful)" : "fast", options.selection_cap,
                options.cluster_faces ? ", clustered faces" : "");
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
    const std::string& stem = x.stem;
    cellforge::io::write_polylines_obj(x.output(stem + "_loops.obj"), loops, true, &x.s.soup,
                                       {.comment = "thin_points " + cl.input.filename().string() +
                                                   ": the solid, then one closed l line per thin loop"});
    if (x.picture) {
      stage("drawing " + std::to_string(r.loops.size()) + " loops on " +
            std::to_string(x.s.soup.num_faces()) + " faces");
      cellforge::io::thin_loops_svg_options picture;
      picture.picture.title = "thin_points: " + cl.input.filename().string();
      picture.picture.view.elevation_deg = 20;
      cellforge::io::write_thin_loops_svg(x.output(stem + "_thin.svg"), x.s.soup, r, picture);
    }
    std::printf("  wrote            %s/%s_loops.obj%s\n", x.out.string().c_str(), stem.c_str(),
                x.picture ? (", " + stem + "_thin.svg").c_str() : "");
    return 0;
  } catch (const std::bad_alloc&) {  // a model too big for this machine: say so, do not abort
    example::report_out_of_memory("thin_points", stage);
    return 1;
  } catch (const std::exception& e) {  // cellforge::error included: its message says what to fix
    std::fprintf(stderr, "thin_points: %s\n", e.what());
    return 1;
  }
}
