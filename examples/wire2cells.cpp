// wire2cells: the main job. Converts a wireframe (vertices and straight edges) into a
// three-dimensional cell list — vertices, edges, faces, volumes and their relations —
// and writes it with pictures.
//
//   wire2cells [options] [input]     input: an OBJ wireframe (v and l lines, f edges) or a plain edge
//                                    list (docs/formats.md); none: the bundled stepped block
//   wire2cells --help                every option with its default, the outputs, the exit codes
//
// Writes <name>.3dcl, <name>.obj (one group per volume), <name>.ply (coloured by volume) and
// <name>.svg (volumes exploded apart), and with --format step <name>.step (a solid per volume,
// ISO 10303-21 AP214), into the output folder (-o, default ./out/), never over
// the input, and prints a per-stage table like the seed's table 1 (seed
// 000_6c43f981384fedb6.txt, §7.2).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <system_error>
#include <vector>

#include "cellforge/io/cells_io.hpp"
#include "cellforge/io/edge_list.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/io/step.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"
#include "example_support.hpp"

namespace fs = std::filesystem;

namespace {

// Exit statuses (listed by --help and in the README).
constexpr int exit_ok = 0;     // a certified solid (status solid or ambiguous), every file written
constexpr int exit_input = 1;  // the input cannot be read (parse error, no faces, ...)
constexpr int exit_usage = 2;  // unknown option, bad value, too many arguments
constexpr int exit_output =
    3;  // the output folder cannot be made or written, or a file would replace the input
constexpr int exit_not_solid = 4;  // read, but not a closed solid: the files are written to look at

/// What the command line asks for.
struct settings {
  fs::path input = fs::path(CELLFORGE_DATA_DIR) / "stepped_block.obj";
  fs::path output = "out";
  std::vector<std::string> formats{"3dcl", "obj", "ply", "svg"};  ///< outputs, in this order
  bool help = false, quiet = false, keep_partial = false;
  unsigned jobs = 1;  ///< --jobs: runs of a batch at a time
  cellforge::wireframe_options pipeline{};
};

std::string number(double v) { return example::fmt(v); }

/// The options, each bound to the field it sets. To add one, add an entry here.
std::vector<example::option_spec> option_table(settings& s) {
  using example::option_count;
  using example::option_number;
  const cellforge::wireframe_options d{};
  cellforge::wireframe_options& p = s.pipeline;
  return {
      {{"-h", "--help"}, "", "print this help and exit", [&](std::string_view) { s.help = true; }},
      {{"-o", "--output"},
       "DIR",
       "folder for the output files, created if missing (default: ./out/)",
       [&](std::string_view v) {
         if (v.empty()) throw example::usage_error("-o/--output needs a folder name");
         s.output = fs::path(v);
       }},
      {{"--no-svg"},
       "",
       "do not write the picture (<name>.svg)",
       [&](std::string_view) { std::erase(s.formats, std::string("svg")); }},
      {{"--format"},
       "LIST",
       "the outputs, comma-separated among 3dcl, obj, ply, svg, step, or all (default: 3dcl,obj,ply,svg)",
       [&](std::string_view v) {
         static const std::vector<std::string> known{"3dcl", "obj", "ply", "svg", "step"};
         s.formats.clear();
         for (std::size_t i = 0; i <= v.size();) {
           const std::size_t comma = std::min(v.find(',', i), v.size());
           const std::string f(v.substr(i, comma - i));
           i = comma + 1;
           if (f == "all") {
             s.formats = known;
           } else if (std::find(known.begin(), known.end(), f) == known.end()) {
             throw example::usage_error("--format: '" + f + "' is none of 3dcl, obj, ply, svg, step, all");
           } else if (std::find(s.formats.begin(), s.formats.end(), f) == s.formats.end()) {
             s.formats.push_back(f);
           }
         }
       }},
      {{"--quiet"},
       "",
       "print nothing on stdout and no progress on stderr (errors still go to stderr)",
       [&](std::string_view) { s.quiet = true; }},
      {{"--jobs"},
       "N",
       "with several inputs or a folder: runs at a time, 1 to 256 (default: 1)",
       [&](std::string_view v) { s.jobs = example::program::parse_jobs(v); }},
      {{"--keep-partial"},
       "",
       "keep the outputs written before an output error (default: none are left; a result that is not "
       "a solid is written in any case, exit status 4)",
       [&](std::string_view) { s.keep_partial = true; }},
      {{"--tracer"},
       "planar|seed",
       "face tracer: each plane's planar arrangement, polynomial (default), or the seed's breadth-first "
       "circuit search",
       [&](std::string_view v) {
         p.trace.kind = example::option_choice<cellforge::tracer_kind>(
             "--tracer", v,
             {{"planar", cellforge::tracer_kind::planar}, {"seed", cellforge::tracer_kind::seed_bfs}});
       }},
      {{"--merge-tolerance"},
       "X",
       "points closer than X times their local edge length (the median edge at each) are one vertex "
       "(0 to 0.1, default " +
           number(d.read.merge.relative) + ")",
       [&](std::string_view v) { p.read.merge.relative = option_number("--merge-tolerance", v, 0.0, 0.1); }},
      {{"--planarity"},
       "X",
       "a point lies in a plane when closer than X times the model's size, in tracing, face reduction "
       "and arrangement, planes fitted to their vertices (0 to 0.1; default: chosen from the data, in the "
       "gap between the coordinates' "
       "noise and the shape, printed as the 'tolerance' row)",
       [&](std::string_view v) {
         const double x = option_number("--planarity", v, 0.0, 0.1);
         p.tolerance.automatic = false;
         p.trace.planarity.relative = p.extra.retrace.planarity.relative = x;
         p.reduction.planarity.relative = p.arrangement.planarity.relative = x;
         p.trace.fit_planes = true;  // a given tolerance is for noisy coordinates
       }},
      {{"--strict"},
       "",
       "refuse zero-length, duplicate and dangling edges instead of dropping them with a note",
       [&](std::string_view) { p.read.strict = true; }},
      {{"--reading"},
       "needed|keep-walls|keep-all",
       "which planar cycles are faces (docs/wireframe.md): only those some edge needs, so holes and dents "
       "stay open and walls no edge needs go (default); as that, but every wall between two volumes stays; "
       "or every cycle that crosses no face (holes plugged)",
       [&](std::string_view v) {
         p.volume.reading = example::option_choice<cellforge::face_reading>(
             "--reading", v,
             {{"needed", cellforge::face_reading::needed},
              {"keep-walls", cellforge::face_reading::keep_walls},
              {"keep-all", cellforge::face_reading::keep_all}});
       }},
      {{"--merge-unforced"},
       "",
       "also merge the volumes on both sides of walls kept although no edge needs them (the inner walls "
       "of a grid), one at a time, never across a needed face",
       [&](std::string_view) { p.volume.merge_unforced = true; }},
      {{"--keep-dangling"},
       "",
       "keep edges that bound no face in the cell complex (default: leave them out with a note)",
       [&](std::string_view) { p.keep_dangling = true; }},
      {{"--budget"},
       "N",
       "work budget of each search stage in steps, 0 = unlimited (default: tracing " +
           std::to_string(d.trace.work_budget) + ", face reduction " +
           std::to_string(d.reduction.work_budget) + ", arrangement " +
           std::to_string(d.arrangement.work_budget) + ")",
       [&](std::string_view v) {
         const std::uint64_t n = option_count("--budget", v);
         p.trace.work_budget = p.extra.retrace.work_budget = p.reduction.work_budget =
             p.arrangement.work_budget = n;
       }},
  };
}

void print_help(const std::vector<example::option_spec>& table) {
  std::printf(
      "usage: wire2cells [options] [input ...]\n\n"
      "Converts a wireframe into a three-dimensional cell list (vertices, edges, faces, volumes and\n"
      "their relations) and prints a per-stage table like the seed's table 1.\n\n"
      "input: an OBJ wireframe (.obj: 'v' and 'l' lines; the edges of 'f' faces count as lines too)\n"
      "       or a plain edge list (any other name;\n"
      "       docs/formats.md); default: the bundled %s\n\n"
      "options:\n%s\n"
      "outputs, in the output folder, <name> being the input's file name without extension:\n"
      "  <name>.3dcl   the cell list (docs/formats.md, \"3DCL text format\")\n"
      "  <name>.obj    every volume's outward faces, one group per volume\n"
      "  <name>.ply    the same faces coloured by volume (ASCII)\n"
      "  <name>.svg    the volumes exploded apart, shaded, hidden edges dashed\n"
      "  <name>.step   with --format step or all: a solid per volume (STEP AP214, millimetres,\n"
      "                docs/formats.md \"STEP\"), for CAD programs\n"
      "No output is written over the input file: wire2cells refuses before writing anything. Each\n"
      "output is written to a temporary file and renamed once all are written.\n\n"
      "Every answer is certified against the input (docs/cells.md, \"The certificate\") and printed\n"
      "with its status: solid, ambiguous (a solid with walls the wireframe does not decide), not a\n"
      "solid, or budget (a stage's or the certificate's work budget ran out).\n\n%s\n"
      "exit status:\n"
      "  %d  success: a certified solid (status solid or ambiguous), every file written\n"
      "  %d  the input cannot be read (the message says why, e.g. file:line of a parse error)\n"
      "  %d  usage error (unknown option, bad value)\n"
      "  %d  output error: the folder cannot be created or written, or an output would replace the input\n"
      "  %d  read, but not a closed solid (status not a solid or budget; the reason is printed and\n"
      "     the files are written so that you can look, unless a budget stopped it before any face)\n",
      (fs::path(CELLFORGE_DATA_DIR) / "stepped_block.obj").string().c_str(),
      example::options_help(table).c_str(), example::batch_help("wire2cells").c_str(), exit_ok, exit_input,
      exit_usage, exit_output, exit_not_solid);
}

void row(const char* stage, double ms, const char* what = nullptr, std::size_t count = 0) {
  if (what)
    std::printf("  %-26s %9.3f ms   %-18s %zu\n", stage, ms, what, count);
  else
    std::printf("  %-26s %9.3f ms\n", stage, ms);
}

void print_stages(const cellforge::wireframe_result<glm::dvec3>& r) {
  row("initial read", r.read.milliseconds, "vertices", r.read.input_vertices);
  std::printf("  %-26s %12s   %-18s %zu\n", "", "", "edges", r.read.input_edges);
  // §4.1½: the planarity tolerance, chosen from the data (or given), relative to the diagonal.
  const auto& t = r.tolerance;
  // Which pass made the answer: the stages' fixed tolerance (exact input first) or the estimate.
  std::printf("  %-26s %9.3f ms   %-18s %.3g%s\n", "tolerance", t.milliseconds, "planarity", t.planarity,
              !t.automatic   ? " (given)"
              : t.fixed_pass ? " (the stages' fixed one, not the estimate)"
              : t.ambiguous  ? " (estimated; NO CLEAR GAP: doubtful)"
              : !t.clear_gap ? " (estimated; no clear gap)"
                             : " (estimated)");
  if (t.automatic)
    std::printf("  %-26s %12s   %-18s %.2g .. %.2g (%.1f decades%s), estimate %.3g\n", "", "",
                "noise .. shape", t.noise, t.geometry, t.gap_decades,
                t.noise_gain ? ", over noise gains" : "", t.estimated_planarity);
  row("finding faces", r.trace.milliseconds, "circuits", r.trace.circuits);
  row("reducing to unique faces", r.unique.milliseconds, "faces found", r.unique.faces.size());
  row("area calculation", r.reduction.area_milliseconds);
  row("face reduction", r.reduction.milliseconds - r.reduction.area_milliseconds, "remaining faces",
      r.reduction.remaining);
  std::printf("  %-26s %12s   %-18s %zu\n", "", "", "secondary faces", r.reduction.secondary);
  row("face selection", r.arrangement.milliseconds, "faces selected", r.arrangement.selected.size());
  row("face analysis", r.extra.milliseconds, "faces", r.extra.faces.size());
  row("manifold analysis", r.volume.manifold_milliseconds);
  row("volume processing", r.volume.milliseconds - r.volume.manifold_milliseconds, "volumes",
      r.volume.volumes.size());
  row("cell list assembly", r.relations.milliseconds + r.assembly_milliseconds);
  row("certificate", r.certificate.milliseconds, "face pairs tested", r.certificate.face_pairs_tested);
  const double total = r.read.milliseconds + r.tolerance.milliseconds + r.trace.milliseconds +
                       r.unique.milliseconds + r.reduction.milliseconds + r.arrangement.milliseconds +
                       r.extra.milliseconds + r.volume.milliseconds + r.relations.milliseconds +
                       r.assembly_milliseconds + r.certificate.milliseconds;
  row("total", total);
}

}  // namespace

int main(int argc, char** argv) {
  settings s;
  example::program p;  // the shared output handling: its name, folder, --keep-partial, batches
  p.name = "wire2cells";
  p.takes = {example::input_kind::wireframe};
  std::vector<std::string> inputs;
  std::vector<int> positions;
  try {
    const std::vector<example::option_spec> table = option_table(s);
    inputs = example::apply_options(argc, argv, table, &positions);
    if (s.help) {
      print_help(table);
      return exit_ok;
    }
    if (inputs.size() == 1) s.input = inputs[0];
  } catch (const example::usage_error& e) {
    std::fprintf(stderr, "wire2cells: %s\nTry 'wire2cells --help'.\n", e.what());
    return exit_usage;
  }
  p.output = s.output;
  p.keep_partial = s.keep_partial;
  p.quiet = s.quiet;
  p.jobs = s.jobs;
  if (s.quiet) example::silence_stdout();
  if (const std::optional<int> batch = example::maybe_batch(p, argc, argv, inputs, positions)) return *batch;

  int failure = exit_input;  // the exit status of an exception thrown from here on
  example::stage_note& stage = p.stage;
  stage.start(p.name, !s.quiet);
  try {
    std::string ext = s.input.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    // An OBJ's faces are read as their edges: a mesh file is a wireframe too.
    stage("reading " + example::file_and_size(s.input));
    const auto wire = ext == ".obj" ? cellforge::io::read_obj_wireframe<glm::dvec3>(s.input, {}, true)
                                    : cellforge::io::read_edge_list<glm::dvec3>(s.input);

    const std::string stem = s.input.stem().string();
    failure = exit_output;
    example::output_files files(p, {s.input});
    std::vector<fs::path> outputs;
    for (const std::string& f : s.formats) outputs.push_back(files.add(stem + "." + f));
    failure = exit_input;

    stage("converting a wireframe of " + std::to_string(wire.points.size()) + " points and " +
          std::to_string(wire.edges.size()) + " edges");
    const cellforge::wireframe_result<glm::dvec3> r = cellforge::wireframe_to_cells(wire, s.pipeline);
    const cellforge::cell_complex<glm::dvec3>& cells = r.cells;
    std::printf("wire2cells: %s\n\n", s.input.string().c_str());
    print_stages(r);

    std::printf("\ncell complex: %zu vertices, %zu edges, %zu faces, %zu volumes, %zu objects\n",
                cells.num_vertices(), cells.num_edges(), cells.num_faces(), cells.num_volumes(),
                cells.num_objects());
    for (auto o : cells.objects())
      std::printf("  object %u: V - E + F - C = %lld\n", o.idx(), cells.object_euler(o));
    std::printf("  faces no edge needs, kept (undecided): %zu\n", r.unforced.size());
    for (const cellforge::reading_note& n : r.alternatives)
      if (n.add.size() == 1 && n.remove.empty() && n.set_aside_by == cellforge::reading_key::unneeded_faces)
        std::printf("  not a face: a %zu-gon at vertex %u (it %s)\n", n.add[0].loops[0].size(),
                    n.add[0].loops[0][0], n.reason.c_str());
      else
        std::printf("  %s reading: %s\n", n.undecided ? "undecided" : "another", n.reason.c_str());
    for (const cellforge::face_note& n : r.lost)
      std::printf("  lost: a %zu-gon at vertex %u (%s)\n", n.loops[0].size(), n.loops[0][0],
                  n.reason.c_str());
    for (const std::string& d : r.diagnostics) std::printf("  note: %s\n", d.c_str());
    const bool solid =
        r.status == cellforge::solid_status::solid || r.status == cellforge::solid_status::ambiguous;
    std::printf("  certificate: %zu of %zu input edges on faces%s\n", r.certificate.covered_input_edges,
                r.certificate.input_edges, r.certificate.ok() ? ", every check passed" : "");
    for (const cellforge::certificate_failure& f : r.certificate.failures)
      std::printf("  certificate failed (%s): %s\n", cellforge::to_string(f.what), f.message.c_str());
    std::printf("  status: %s (%s)\n", cellforge::to_string(r.status), r.status_reason.c_str());
    if (r.status == cellforge::solid_status::budget && cells.num_faces() == 0) {
      // A stage ran out before any face was read: nothing to write; the reason names the option.
      std::fprintf(stderr, "wire2cells: not read: %s (--budget N, 0 = unlimited)\n", r.status_reason.c_str());
      return exit_not_solid;
    }

    failure = exit_output;
    stage("writing a cell complex of " + std::to_string(cells.num_faces()) + " faces and " +
          std::to_string(cells.num_volumes()) + " volumes");
    for (std::size_t i = 0; i < s.formats.size(); ++i) {
      const std::string& f = s.formats[i];
      files.write(outputs[i], [&](const fs::path& to) {
        if (f == "3dcl") {
          cellforge::io::write_3dcl(to, cells);
        } else if (f == "obj") {
          cellforge::io::write_cells_obj(to, cells);
        } else if (f == "ply") {
          cellforge::io::write_cells_ply(to, cells);
        } else if (f == "svg") {
          stage("drawing " + std::to_string(cells.num_faces()) + " faces");
          const cellforge::io::svg_result picture = cellforge::io::write_cells_svg(to, cells);
          if (picture.approximate_edges + picture.untested_edges > 0)
            std::printf(
                "  picture: %zu of %zu edges past the hidden-line work budget (judged from one point)\n",
                picture.approximate_edges + picture.untested_edges, picture.edges);
        } else if (f == "step") {
          const cellforge::io::step_result step = cellforge::io::write_step(to, cells, {.name = stem});
          for (const std::string& d : step.diagnostics) std::printf("  step: %s\n", d.c_str());
        }
      });
    }
    files.commit();  // a result that is not a solid too: its files are there to look at
    std::printf("\nwrote");
    for (std::size_t i = 0; i < outputs.size(); ++i)
      std::printf("%s %s", i == 0 ? "" : i + 1 == outputs.size() ? " and" : ",", outputs[i].string().c_str());
    std::printf("\n");
    if (solid) return exit_ok;
    std::fprintf(
        stderr, "wire2cells: read, but not a closed solid: %s (the files are written so that you can look)\n",
        r.status_reason.c_str());
    if (ext == ".obj") {  // a mesh given for a wireframe: say which programs take it
      const example::obj_contents c = example::read_obj_contents(s.input);
      if (c.kind() == example::input_kind::mesh && c.lines == 0)
        std::fprintf(stderr, "wire2cells: '%s' is %s with no closed solid in its edges; %s\n",
                     s.input.string().c_str(), c.describe().c_str(), example::takers(c.kind()).c_str());
    }
    return exit_not_solid;
  } catch (const std::bad_alloc&) {
    example::report_out_of_memory("wire2cells", stage);
    return failure;
  } catch (const std::exception& e) {  // cellforge::error among them: its message names file:line
    std::fprintf(stderr, "wire2cells: %s\n", e.what());
    return failure;
  }
}
