// tubes: a skeleton graph with radii becomes a closed tube mesh (seed 001 ch. V).
//
//   tubes [options] [input]   input: an SWC neuron/vessel file, or OBJ `v x y z r` + `l`; none: the
//                             bundled vessel tree (examples/data/vessel_tree.swc)
//   tubes --help              every option with its default, the outputs, the exit statuses
//
// Writes into the output folder (-o, default ./out/) tubes.obj (or --format) and tubes.svg, and
// prints per-stage times, the mesh's counts, its genus beside the skeleton's cycle rank (they
// must agree), its folds and (--check exact, the default below 250,000 faces) self-intersections
// (there must be none). Exits 4, saying why on stderr and writing nothing, when a check fails.
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

namespace {

// Below this many faces the default --check is exact, above it fast: the exact check costs about
// 3.7 microseconds a face on this machine (8.2 s for the 2.2 million faces of a 28^3 lattice), so
// the default stays under a second of checking.
constexpr std::size_t exact_check_faces = 250000;

enum class check_level { automatic, none, fast, exact };

}  // namespace

int main(int argc, char** argv) {
  example::program p;
  p.name = "tubes";
  p.usage = "[options] [input ...]";
  p.takes = {example::input_kind::skeleton};
  p.about =
      "Meshes a skeleton graph with radii as closed tubes (seed 001 ch. V) and checks the mesh: valid,\n"
      "closed, its genus the skeleton's cycle rank, no folds and (--check exact) no self-intersections.";
  p.input_help =
      "an SWC neuron/vessel file (.swc), or an OBJ skeleton (.obj: 'v x y z r' and 'l' lines; an OBJ\n"
      "       wireframe without radii with --radius); default: the bundled vessel_tree.swc";
  p.outputs_help =
      "  tubes.<format>   the tube mesh (--format, default obj)\n"
      "  tubes.svg        the mesh shaded\n";
  p.exit4_help =
      "read, but not a skeleton (a mesh, a wireframe without --radius, a drawing: the message names\n"
      "     the program that takes it), or a mesh that fails a check (the reasons are printed)";
  p.notes = "Progress goes to stderr once a run passes a second (--quiet: none).";
  cellforge::tubes_options options;
  cellforge::self_intersection_options pairs;
  double radius = 0;
  check_level level = check_level::automatic;
  p.add_common_options("obj");
  p.options.push_back({{"--sides"}, "N", "sides of each tube, 3 to 64 (default: 8)", [&](std::string_view v) {
                         const double n = example::option_number("--sides", v, 3, 64);
                         if (n != static_cast<int>(n))
                           throw example::usage_error("--sides must be a whole number");
                         options.sides = static_cast<std::uint32_t>(n);
                       }});
  p.options.push_back({{"--alignment"},
                       "none|local|global",
                       "how the rings of a path are turned to each other (default: global)",
                       [&](std::string_view v) {
                         options.alignment = example::option_choice<cellforge::tube_alignment>(
                             "--alignment", v,
                             {{"none", cellforge::tube_alignment::none},
                              {"local", cellforge::tube_alignment::local},
                              {"global", cellforge::tube_alignment::global}});
                       }});
  p.options.push_back({{"--radius"},
                       "R",
                       "radius of the OBJ vertices that give none (default: none; each vertex needs its own)",
                       [&](std::string_view v) {
                         radius = example::option_number("--radius", v, 0, 1e300);
                         if (!(radius > 0))
                           throw example::usage_error("--radius must be positive, got '" + std::string(v) +
                                                      "'");
                       }});
  p.options.push_back(
      {{"--levels"}, "L", "levels of Loop subdivision, 0 to 4 (default: 0)", [&](std::string_view v) {
         const double n = example::option_number("--levels", v, 0, 4);
         if (n != static_cast<int>(n)) throw example::usage_error("--levels must be a whole number");
         options.subdivision_levels = static_cast<int>(n);
       }});
  p.options.push_back(
      {{"--check"},
       "none|fast|exact",
       "checks of the mesh: none (only the genus and folds the mesher reports), fast (also "
       "validity and closedness, linear time), exact (also the exact self-intersection test, about "
       "4 microseconds a face); with exact and the default the mesher also checks by pieces (exact, "
       "about the meshing's time) and repairs the junctions beside what it finds; default: exact below " +
           std::to_string(exact_check_faces) + " faces, above it the mesher's check by pieces",
       [&](std::string_view v) {
         level = example::option_choice<check_level>(
             "--check", v,
             {{"none", check_level::none}, {"fast", check_level::fast}, {"exact", check_level::exact}});
       }});
  p.options.push_back({{"--check-pairs"},
                       "N",
                       "work budget of the exact check in candidate box pairs; 0 = the check's own, 256 per "
                       "triangle plus 2^20 (default: 0)",
                       [&](std::string_view v) {
                         const std::size_t n = example::option_count("--check-pairs", v);
                         pairs.work_budget = n == 0 ? cellforge::work_budget::automatic : n;
                       }});
  return example::run(p, argc, argv, [&](const std::vector<std::string>& args) -> int {
    const fs::path input = p.one_input(args, fs::path(CELLFORGE_DATA_DIR) / "vessel_tree.swc");
    example::stage_note& stage = p.stage;
    example::output_files out(p, {input});
    std::vector<fs::path> mesh_paths;
    for (const std::string& f : p.formats) mesh_paths.push_back(out.add("tubes." + f));
    const fs::path picture_path = out.add("tubes.svg");
    const std::string ext = example::lower_extension(input);
    example::expect_extension(p.name, input, {example::input_kind::skeleton}, "a skeleton");
    cellforge::skeleton<point> skeleton;
    std::vector<std::int64_t> sample_ids;  // messages name an SWC file's samples by their ids
    stage("reading " + example::file_and_size(input), 0);
    if (ext == ".swc") {
      auto swc = cellforge::io::read_swc<point>(input);
      skeleton = std::move(swc.skeleton);
      sample_ids = std::move(swc.ids);
      options.node_ids = sample_ids;
    } else if (ext == ".obj") {
      const example::obj_contents c = example::read_obj_contents(input);
      if (c.kind() == example::input_kind::mesh || c.kind() == example::input_kind::point_set ||
          (c.kind() == example::input_kind::wireframe && radius == 0))
        example::not_for_this(
            p.name, input, c.describe() + (c.kind() == example::input_kind::wireframe ? ", no radii" : ""),
            c.kind() == example::input_kind::wireframe ? "a skeleton with radii (or give --radius R)"
                                                       : "a skeleton",
            c.kind());
      cellforge::io::skeleton_obj_read_options read;
      read.uniform_radius = radius;
      try {
        skeleton = cellforge::io::read_skeleton_obj<point>(input, read).skeleton;
      } catch (const cellforge::error& e) {  // name the program's flag, not the library's option
        std::string m = e.what();
        const std::string library = "set skeleton_obj_read_options::uniform_radius";
        if (const std::size_t at = m.find(library); at != std::string::npos)
          m.replace(at, library.size(), "give --radius R");
        throw cellforge::error(e.category(), m);
      }
    } else {
      throw cellforge::error(cellforge::error_category::invalid_input,
                             "'" + input.string() + "': give an .swc or .obj skeleton");
    }
    if (skeleton.points.empty())  // an empty mesh would "pass" every check below
      throw cellforge::error(cellforge::error_category::invalid_input,
                             "'" + input.string() + "': the skeleton has no nodes (nothing to mesh)");
    stage("meshing " + std::to_string(skeleton.points.size()) + " nodes and " +
              std::to_string(skeleton.edges.size()) + " edges with " + std::to_string(options.sides) +
              " sides and " + std::to_string(options.subdivision_levels) + " Loop levels",
          10);

    // The mesher's own exact check (by pieces, about the meshing's time) lets it repair the
    // junctions beside what it finds; --check fast and none keep to linear time.
    options.check_self_intersections = level == check_level::exact || level == check_level::automatic;
    const auto r = cellforge::make_tubes(skeleton, options);
    const check_level check = level != check_level::automatic          ? level
                              : r.mesh.num_faces() < exact_check_faces ? check_level::exact
                                                                       : check_level::fast;
    std::printf("input              %s: %zu nodes, %zu edges, %zu components\n", input.string().c_str(),
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
    std::printf("total              %9.3f ms\n", r.milliseconds);
    std::printf("mesh               %zu vertices, %zu edges, %zu faces, %zu shells, closed %s\n",
                r.mesh.num_vertices(), r.mesh.num_edges(), r.mesh.num_faces(), r.shells,
                r.mesh.is_closed() ? "yes" : "no");
    std::printf("genus              %lld (skeleton cycle rank %lld)%s\n", static_cast<long long>(r.genus),
                static_cast<long long>(r.cycle_rank), r.genus == r.cycle_rank ? "" : "  MISMATCH");
    std::printf("folds              %zu edges whose faces point opposite ways\n", r.folded_edges);
    // What fails the mesh, one reason each: an unfinished check is no pass.
    std::string failed;
    const auto fail_if = [&](bool bad, const std::string& why) {
      if (bad) failed += (failed.empty() ? "" : "; ") + why;
    };
    fail_if(r.genus != r.cycle_rank, "the genus differs from the skeleton's cycle rank");
    fail_if(r.folded_edges > 0, std::to_string(r.folded_edges) + " edges fold back");
    const char* check_name = check == check_level::none   ? "none"
                             : check == check_level::fast ? "fast"
                                                          : "exact";
    const char* why_check = level != check_level::automatic ? " (--check)"
                            : check == check_level::exact   ? " (the default below "
                                                            : " (the default from ";
    if (level == check_level::automatic)
      std::printf("checks             %s%s%zu faces)\n", check_name, why_check, exact_check_faces);
    else
      std::printf("checks             %s%s\n", check_name, why_check);
    if (check != check_level::none) {
      stage("validating a mesh of " + std::to_string(r.mesh.num_faces()) + " faces", 50);
      const cellforge::mesh_validation valid = cellforge::validate(r.mesh);
      std::printf("valid              %s\n", valid.ok() ? "yes" : valid.message.c_str());
      fail_if(!valid.ok(), "the mesh is invalid: " + valid.message);
      fail_if(!r.mesh.is_closed(), "the mesh is not closed");
    }
    if (check == check_level::exact) {
      stage("checking " + std::to_string(r.mesh.num_faces()) +
                " faces for self-intersections (exact; --check fast skips it)",
            60);
      const cellforge::self_intersection_result si = cellforge::self_intersections(r.mesh, pairs);
      std::printf("self-intersections %zu intersecting face pairs (exact, %zu triangles, %.3f ms)%s\n",
                  si.intersecting_face_pairs, si.triangles, si.milliseconds,
                  si.complete ? "" : ", budget exhausted: unchecked");
      fail_if(si.intersecting_face_pairs > 0,
              std::to_string(si.intersecting_face_pairs) + " face pairs intersect");
      fail_if(!si.complete,
              "the self-intersection check ran out of its budget before it finished (--check-pairs)");
    } else if (options.check_self_intersections) {  // above the full check's size: the mesher's
      std::printf("self-intersections %zu intersecting face pairs (exact, by pieces, %.3f ms)%s\n",
                  r.self_intersecting_face_pairs, r.check_ms,
                  r.self_intersections_checked ? "" : ", budget exhausted: unchecked");
      fail_if(r.self_intersecting_face_pairs > 0,
              std::to_string(r.self_intersecting_face_pairs) + " face pairs intersect");
      fail_if(!r.self_intersections_checked,
              "the self-intersection check ran out of its budget before it finished");
    } else {
      std::printf("self-intersections not checked (--check exact checks them)\n");
    }
    std::printf("quality            corners %.1f to %.1f degrees, smallest cross-section %.2f of pi r^2\n",
                r.min_corner_deg, r.max_corner_deg, r.min_section_ratio);
    for (const std::string& d : r.diagnostics) std::printf("note               %s\n", d.c_str());
    if (!failed.empty()) {
      std::fprintf(stderr, "tubes: read, but the mesh is not good: %s\n", failed.c_str());
      if (!p.keep_partial) return example::exit_not_for_this;
    }

    stage("writing " + std::to_string(r.mesh.num_faces()) + " faces", 85);
    for (const fs::path& path : mesh_paths)
      out.write(path, [&](const fs::path& to) { example::write_mesh_file(to, r.mesh); });
    if (p.svg) {
      stage("drawing " + std::to_string(r.mesh.num_faces()) + " faces", 95);
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
      picture.title = "tubes: " + input.filename().string();
      out.write(picture_path, [&](const fs::path& to) { scene.write(to, picture); });
    }
    if (!failed.empty()) return example::exit_not_for_this;  // the outputs kept as partial
    out.commit();
    std::printf("wrote              %s\n", out.list().c_str());
    return example::exit_ok;
  });
}
