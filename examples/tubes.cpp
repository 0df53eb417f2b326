// tubes: a skeleton graph with radii becomes a closed tube mesh (seed 001 ch. V).
//
//   tubes                                the bundled vessel tree (examples/data/vessel_tree.swc)
//   tubes skeleton.swc|skeleton.obj      an SWC neuron/vessel file, or OBJ `v x y z r` + `l`
//         [--sides N] [--alignment none|local|global] [--radius R] [--levels L] [--check-pairs N]
//         [--no-svg]
//
// --radius gives OBJ vertices without a fourth value that radius; --levels applies 0 to 4
// levels of Loop subdivision; --check-pairs sets the self-intersection check's work budget (candidate
// pairs; 0, the default, is the check's own); --no-svg leaves the picture out. Writes, in the current
// directory, tubes.obj, tubes.ply, tubes.off and tubes.svg, and prints per-stage times, the mesh's counts,
// its genus beside the skeleton's cycle rank (they must agree), its folds and self-intersections (there
// must be none). Exits 1, saying why on stderr, when any of these checks fails or did not finish.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/algorithms/self_intersections.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "cellforge/io/mesh_io.hpp"
#include "cellforge/io/skeleton_obj.hpp"
#include "cellforge/io/svg.hpp"
#include "cellforge/io/swc.hpp"
#include "cellforge/tubes/tube_mesh.hpp"
#include "example_support.hpp"

namespace fs = std::filesystem;
using point = glm::dvec3;

int main(int argc, char** argv) {
  example::stage_note stage;
  try {
    const example::command_line cl =
        example::parse_command_line(argc, argv, fs::path(CELLFORGE_DATA_DIR) / "vessel_tree.swc",
                                    {"sides", "alignment", "radius", "levels", "check-pairs"}, {"no-svg"});
    const bool picture_wanted = !cl.has("no-svg");
    cellforge::tube_options options;
    options.sides = static_cast<std::uint32_t>(cl.number("sides", 8, 3, 64, true));
    options.subdivision_levels = static_cast<int>(cl.number("levels", 0, 0, 4, true));
    cellforge::self_intersection_options check;
    check.max_candidate_pairs = static_cast<std::size_t>(cl.number("check-pairs", 0, 0, 1e15, true));
    const std::string alignment = cl.text("alignment", "global");
    if (alignment == "none")
      options.alignment = cellforge::tube_alignment::none;
    else if (alignment == "local")
      options.alignment = cellforge::tube_alignment::local;
    else if (alignment != "global")
      throw cellforge::error(cellforge::error_category::invalid_input,
                             "--alignment must be none, local or global, got '" + alignment + "'");
    std::string ext = cl.input.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    cellforge::skeleton<point> skeleton;
    std::vector<std::int64_t> sample_ids;  // messages name an SWC file's samples by their ids
    stage("reading " + example::file_and_size(cl.input));
    if (ext == ".swc") {
      auto swc = cellforge::io::read_swc<point>(cl.input);
      skeleton = std::move(swc.skeleton);
      sample_ids = std::move(swc.ids);
      options.node_ids = sample_ids;
    } else if (ext == ".obj") {
      cellforge::io::skeleton_obj_read_options read;
      read.uniform_radius = cl.number("radius", 0, 0, 1e300);
      skeleton = cellforge::io::read_skeleton_obj<point>(cl.input, read).skeleton;
    } else {
      throw cellforge::error(cellforge::error_category::invalid_input,
                             "'" + cl.input.string() + "': give an .swc or .obj skeleton");
    }
    if (skeleton.points.empty())  // an empty mesh would "pass" every check below
      throw cellforge::error(cellforge::error_category::invalid_input,
                             "'" + cl.input.string() + "': the skeleton has no nodes (nothing to mesh)");
    const fs::path outputs[] = {"tubes.obj", "tubes.ply", "tubes.off", "tubes.svg"};
    for (const fs::path& out : outputs) example::refuse_to_overwrite(out, cl.input);
    stage("meshing " + std::to_string(skeleton.points.size()) + " nodes and " +
          std::to_string(skeleton.edges.size()) + " edges with " + std::to_string(options.sides) +
          " sides and " + std::to_string(options.subdivision_levels) + " Loop levels");

    const auto r = cellforge::make_tubes(skeleton, options);
    const cellforge::validation_result valid = cellforge::validate(r.mesh);
    std::printf("input              %s: %zu nodes, %zu edges, %zu components\n", cl.input.string().c_str(),
                skeleton.points.size(), skeleton.edges.size(), r.construct.components);
    std::printf(
        "construct          %9.3f ms   %zu junctions (%zu sharp bends), %zu paths (%zu rings), "
        "%zu nodes inserted\n",
        r.construct_ms, r.junctions, r.bend_junctions, r.paths, r.closed_paths, r.construct.inserted_nodes);
    std::printf("branch meshes      %9.3f ms   %zu hulls taken from a junction of the same shape\n",
                r.junctions_ms, r.reused_junction_hulls);
    std::printf("node paths         %9.3f ms   %zu end caps, %zu spheres\n", r.paths_ms, r.end_caps,
                r.spheres);
    std::printf("mesh               %9.3f ms\n", r.mesh_ms);
    if (options.subdivision_levels > 0)
      std::printf("Loop subdivision   %9.3f ms   %d levels\n", r.subdivision_ms, options.subdivision_levels);
    std::printf("total              %9.3f ms\n", r.total_ms);
    std::printf("mesh               %zu vertices, %zu edges, %zu faces, %zu shells, closed %s\n",
                r.mesh.num_vertices(), r.mesh.num_edges(), r.mesh.num_faces(), r.shells,
                r.mesh.is_closed() ? "yes" : "no");
    std::printf("genus              %lld (skeleton cycle rank %lld)%s\n", static_cast<long long>(r.genus),
                static_cast<long long>(r.cycle_rank), r.genus == r.cycle_rank ? "" : "  MISMATCH");
    std::printf("valid              %s\n", valid.ok() ? "yes" : valid.message.c_str());
    std::printf("folds              %zu edges whose faces point opposite ways\n", r.folded_edges);
    const cellforge::self_intersection_result si = cellforge::self_intersections(r.mesh, check);
    std::printf("self-intersections %zu intersecting face pairs (exact, %zu triangles, %.3f ms)%s\n",
                si.intersecting_face_pairs, si.triangles, si.time_ms,
                si.complete ? "" : ", budget exhausted: unchecked");
    std::printf("quality            corners %.1f to %.1f degrees, smallest cross-section %.2f of pi r^2\n",
                r.min_corner_deg, r.max_corner_deg, r.min_section_ratio);
    for (const std::string& d : r.diagnostics) std::printf("note               %s\n", d.c_str());

    stage("writing " + std::to_string(r.mesh.num_faces()) + " faces");
    cellforge::io::write_mesh(outputs[0], r.mesh);
    cellforge::io::write_mesh(outputs[1], r.mesh);
    cellforge::io::write_mesh(outputs[2], r.mesh);
    // What fails the mesh, one reason each: an unfinished check is no pass.
    std::string failed;
    const auto fail_if = [&](bool bad, const std::string& why) {
      if (bad) failed += (failed.empty() ? "" : "; ") + why;
    };
    fail_if(!valid.ok(), "the mesh is invalid: " + valid.message);
    fail_if(r.genus != r.cycle_rank, "the genus differs from the skeleton's cycle rank");
    fail_if(r.folded_edges > 0, std::to_string(r.folded_edges) + " edges fold back");
    fail_if(si.intersecting_face_pairs > 0,
            std::to_string(si.intersecting_face_pairs) + " face pairs intersect");
    fail_if(!si.complete, "the self-intersection check ran out of its budget before it finished");
    if (!failed.empty()) std::fprintf(stderr, "tubes: the mesh is written but not good: %s\n", failed.c_str());
    const bool ok = failed.empty();
    if (!picture_wanted) {
      std::printf("wrote              tubes.obj, tubes.ply, tubes.off\n");
      return ok ? 0 : 1;
    }
    stage("drawing " + std::to_string(r.mesh.num_faces()) + " faces");
    cellforge::io::svg_scene scene;
    cellforge::io::svg_style style;
    style.fill = "#e06666";
    style.stroke = "#5b1f1f";
    style.stroke_width = 0.4;
    style.draw_hidden = false;
    style.draw_edges = r.mesh.num_faces() <= 20000;  // beyond that the edges only darken the picture
    scene.add_mesh(cellforge::to_soup(r.mesh), style);
    cellforge::io::svg_options picture;
    picture.width = 900;
    picture.height = 700;
    picture.title = "tubes: " + cl.input.filename().string();
    scene.write(outputs[3], picture);
    std::printf("wrote              tubes.obj, tubes.ply, tubes.off, tubes.svg\n");
    return ok ? 0 : 1;
  } catch (const std::bad_alloc&) {  // a model too big for this machine: say so, do not abort
    example::report_out_of_memory("tubes", stage);
    return 1;
  } catch (const std::exception& e) {  // cellforge::error among them: its message says what to fix
    std::fprintf(stderr, "tubes: %s\n", e.what());
    return 1;
  }
}
