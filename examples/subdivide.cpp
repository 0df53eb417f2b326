// subdivide: Loop subdivision of a triangle mesh, with a before/after picture.
//
//   subdivide [options] [input]   input: any OFF, OBJ, PLY or STL mesh (polygons are fan-triangulated);
//                                 none: the bundled open cup (examples/data/cup.off); --levels N (2)
//   subdivide --help              every option with its default, the outputs, the exit statuses
//
// Writes into the output folder (-o, default ./out/) subdivided.<format> (the input's, or
// --format) and subdivide.svg (input on the left, result on the right); prints counts and times.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string>

#include <glm/geometric.hpp>

#include "cellforge/algorithms/loop_subdivision.hpp"
#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "cellforge/io/mesh_io.hpp"
#include "cellforge/io/svg.hpp"

#include "example_support.hpp"

namespace fs = std::filesystem;
using point = glm::dvec3;

int main(int argc, char** argv) {
  example::program p;
  p.name = "subdivide";
  p.usage = "[options] [input ...]";
  p.takes = {example::input_kind::mesh};
  p.one_run = [](const std::vector<std::string>& a) {  // the old spelling: subdivide model.off 3
    std::error_code ec;
    return a.size() == 2 && !a[1].empty() && std::isdigit(static_cast<unsigned char>(a[1][0])) &&
           !std::filesystem::exists(a[1], ec);
  };
  p.about =
      "Loop subdivision of a triangle mesh (polygons are fan-triangulated first), with a before/after "
      "picture.";
  p.input_help = "a mesh: .off, .obj (with 'f' faces), .ply or .stl; default: the bundled open cup (cup.off)";
  p.outputs_help =
      "  subdivided.<format>   the subdivided mesh (--format; default: the input's format, .off for\n"
      "                        the bundled cup)\n"
      "  subdivide.svg         the input on the left, the result on the right\n";
  p.exit4_help =
      "read, but not a mesh (a wireframe, a skeleton, a point set, a drawing, a cell list: the\n"
      "     message names the program that takes it), or a result that fails validation";
  int levels = 2;
  p.add_common_options("obj", "the input's format");
  const auto set_levels = [&](std::string_view v) {
    levels = static_cast<int>(example::option_number("--levels", v, 0, 12));
    if (levels != example::option_number("--levels", v, 0, 12))
      throw example::usage_error("--levels must be a whole number from 0 to 12, got '" + std::string(v) +
                                 "'");
  };
  p.options.push_back({{"--levels"}, "N", "levels of subdivision, 0 to 12 (default: 2)", set_levels});
  return example::run(p, argc, argv, [&](std::vector<std::string> args) -> int {
    if (args.size() == 2) {  // the old spelling: subdivide model.off 3
      std::fprintf(stderr, "subdivide: a second argument as the levels is deprecated; use --levels N\n");
      set_levels(args[1]);
      args.pop_back();
    }
    const fs::path input = p.one_input(args, fs::path(CELLFORGE_DATA_DIR) / "cup.off");
    example::stage_note& stage = p.stage;
    std::string ext = example::lower_extension(input);
    if (!p.format_given)
      p.formats = {ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl" ? ext.substr(1) : "obj"};
    example::output_files out(p, {input});
    bool failed = false;  // a result that fails its check: written only with --keep-partial
    std::vector<fs::path> mesh_paths;
    for (const std::string& f : p.formats) mesh_paths.push_back(out.add("subdivided." + f));
    const fs::path picture_path = out.add("subdivide.svg");
    example::expect_extension(p.name, input, {example::input_kind::mesh}, "a mesh");
    stage("reading " + example::file_and_size(input));
    cellforge::polygon_soup<point> soup = cellforge::io::read_soup<point>(input);
    if (soup.num_faces() == 0) example::refuse_faceless(p, input, soup.points.size(), "a mesh");
    stage("building the mesh of " + std::to_string(soup.num_faces()) + " faces");
    const bool polygons = std::any_of(soup.face_offsets.begin() + 1, soup.face_offsets.end(),
                                      [&, prev = std::uint32_t{0}](std::uint32_t o) mutable {
                                        const bool big = o - prev > 3;
                                        prev = o;
                                        return big;
                                      });
    // Loop subdivision needs triangles; the library refuses other faces rather than guess.
    if (polygons) soup = cellforge::triangulate_fan(soup);
    auto mesh = cellforge::make_mesh(soup);
    const cellforge::polygon_soup<point> before = cellforge::to_soup(mesh);

    stage("subdividing " + std::to_string(mesh.num_faces()) + " faces " + std::to_string(levels) +
          " times (about " + example::about(static_cast<double>(mesh.num_faces()) * std::pow(4.0, levels)) +
          " faces)");
    const cellforge::loop_subdivision_result r = cellforge::loop_subdivide(mesh, {.levels = levels});
    const cellforge::mesh_validation valid = cellforge::validate(mesh);

    std::printf("input              %s%s\n", input.string().c_str(),
                polygons ? " (polygon faces fan-triangulated first)" : "");
    std::printf("levels             %d\n", levels);
    std::printf("before             %zu vertices, %zu edges, %zu triangles\n", r.vertices_before,
                r.edges_before, r.faces_before);
    std::printf("after              %zu vertices, %zu edges, %zu triangles\n", r.vertices_after,
                r.edges_after, r.faces_after);
    std::printf("boundary edges     %zu, flipped edges %zu, vertices kept (several fans) %zu\n",
                r.boundary_edges_after, r.flipped_edges_after, r.fixed_vertices);
    for (std::size_t i = 0; i < r.level_ms.size(); ++i)
      std::printf("level %zu            %.3f ms\n", i + 1, r.level_ms[i]);
    std::printf("total              %.3f ms\n", r.milliseconds);
    std::printf("valid              %s\n", valid.ok() ? "yes" : valid.message.c_str());
    if (!valid.ok()) {
      std::fprintf(stderr, "subdivide: the result fails validation: %s\n", valid.message.c_str());
      if (!p.keep_partial) return example::exit_not_for_this;
      failed = true;
    }

    stage("writing " + std::to_string(mesh.num_faces()) + " faces");
    for (const fs::path& path : mesh_paths)
      out.write(path, [&](const fs::path& to) { example::write_mesh_file(to, mesh); });
    if (!p.svg) {
      if (failed) return example::exit_not_for_this;  // the outputs kept as partial
      out.commit();
      std::printf("wrote              %s\n", out.list().c_str());
      return example::exit_ok;
    }

    // Input and result side by side: shift the result 1.3 widths to the right of the screen.
    stage("drawing " + std::to_string(before.num_faces() + mesh.num_faces()) + " faces");
    const cellforge::polygon_soup<point> after = cellforge::to_soup(mesh);
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (const point& p : before.points) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const double width = std::max(hi.x - lo.x, hi.y - lo.y);
    cellforge::io::svg_scene scene;
    cellforge::io::svg_style coarse;
    coarse.fill = "#f6b26b";
    coarse.stroke = "#7f4f1f";
    coarse.hidden_stroke = "#7f4f1f";
    cellforge::io::svg_style smooth;
    smooth.offset =
        1.3 * width * glm::dvec3(std::sqrt(0.5), std::sqrt(0.5), 0);  // screen right at azimuth -45°
    smooth.stroke_width = levels > 2 ? 0.3 : 0.6;
    smooth.draw_edges = after.num_faces() <= 20000;  // beyond that the edges only darken the picture
    smooth.draw_hidden = false;
    scene.add_mesh(before, coarse);
    scene.add_mesh(after, smooth);
    cellforge::io::svg_options picture;
    picture.width = 1000;
    picture.height = 560;
    picture.title = "Loop subdivision, " + std::to_string(levels) + " levels: " + input.filename().string();
    picture.view.azimuth_deg = -45;
    picture.view.elevation_deg = 20;
    out.write(picture_path, [&](const fs::path& to) { scene.write(to, picture); });
    if (failed) return example::exit_not_for_this;  // the outputs kept as partial
    out.commit();
    std::printf("wrote              %s\n", out.list().c_str());
    return example::exit_ok;
  });
}
