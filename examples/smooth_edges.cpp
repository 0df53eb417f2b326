// smooth_edges: the cubic edge fitter (seed 000_6c43f981384fedb6.txt, chapter VI). Every edge of
// a closed solid becomes a cubic, quadratic or straight curve through its end vertices.
//
//   smooth_edges                          the bundled coarse cylinder (examples/data/cylinder16.off)
//   smooth_edges model.off|obj|ply        any closed mesh
//   smooth_edges cells.3dcl [--volume N]  volume N (default 0) of a cell list; ids are cell ids
//   options: --angle DEG (continuous-surface threshold, 0..90, default 45)
//            --faithful (the seed's rules: no crease smoothing, axis form only)
//            --out DIR (default out)
//            --no-svg (leave the picture out)
//
// Writes into DIR: <name>.curves (the seed's curve file: axis, limits, two cubics per edge;
// docs/formats.md), <name>.polylines (15 segments per curve), <name>_curves.obj (the solid's
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
  example::stage_note stage;
  try {
    const example::session x = example::open_session(
        argc, argv, fs::path(CELLFORGE_DATA_DIR) / "cylinder16.off", {"angle"}, {"faithful"}, stage);
    const example::command_line& cl = x.cl;
    cellforge::smooth_options options =
        cl.has("faithful") ? cellforge::seed_smooth_options() : cellforge::smooth_options{};
    options.angle_deg = cl.number("angle", options.angle_deg, 0, 90);
    cellforge::smooth_result<glm::dvec3> r;  // the points of the example's meshes
    const double ms = x.run([&](const auto& cc, auto v) { r = cellforge::smooth_edges(cc, v, options); },
                            [&](const auto& mesh) { r = cellforge::smooth_edges(mesh, options); });
    x.print_solid("smooth_edges");
    std::printf("  rules            %s, angle %.4g degrees\n",
                cl.has("faithful") ? "the seed's (--faithful)" : "extended", options.angle_deg);
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

    const std::string& stem = x.stem;
    const auto& curves = r.curves;
    stage("writing " + std::to_string(curves.size()) + " curves");
    cellforge::io::write_curve_file(x.output(stem + ".curves"), curves,
                                    {.comment = "smooth_edges " + cl.input.filename().string() +
                                                ": one curve per edge, in edge order (docs/formats.md)"});
    cellforge::io::write_polyline_file(x.output(stem + ".polylines"), curves);
    cellforge::io::write_polylines_obj(x.output(stem + "_curves.obj"), curves, &x.s.soup);
    if (x.picture) {
      stage("drawing " + std::to_string(curves.size()) + " curves on " +
            std::to_string(x.s.soup.num_faces()) + " faces");
      cellforge::io::smoothing_svg_options picture;
      picture.picture.title = "smooth_edges: " + cl.input.filename().string();
      picture.picture.view.elevation_deg = 30;
      cellforge::io::write_smoothing_svg(x.output(stem + "_smooth.svg"), x.s.soup, curves, picture);
    }
    std::printf("  wrote            %s/%s.curves, .polylines, _curves.obj%s\n", x.out.string().c_str(),
                stem.c_str(), x.picture ? ", _smooth.svg" : "");
    return 0;
  } catch (const std::bad_alloc&) {  // a model too big for this machine: say so, do not abort
    example::report_out_of_memory("smooth_edges", stage);
    return 1;
  } catch (const std::exception& e) {  // cellforge::error included: its message says what to fix
    std::fprintf(stderr, "smooth_edges: %s\n", e.what());
    return 1;
  }
}
