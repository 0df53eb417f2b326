// hull: the 3D convex hull of a point set, written as a mesh and drawn as a picture.
//
//   hull [options]            2000 random points in a ball (fixed seed)
//   hull [options] points.off the vertices of any OFF, OBJ, PLY or STL file (faces and lines ignored)
//   hull --help               every option with its default, the outputs, the exit statuses
//
// Writes into the output folder (-o, default ./out/) hull.off (or --format) and hull.svg (the
// hull over the points: red points are hull vertices, grey ones lie inside).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <new>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/convex_hull.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "cellforge/io/mesh_io.hpp"
#include "cellforge/io/svg.hpp"

#include "example_support.hpp"

namespace fs = std::filesystem;
using point = glm::dvec3;

namespace {

// Uniform in the unit ball: Gaussian directions, radius by the cube root of a uniform.
std::vector<point> random_ball(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<point> p(n);
  for (point& q : p) {
    q = glm::normalize(point(gauss(rng), gauss(rng), gauss(rng))) * std::cbrt(uniform(rng));
  }
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  example::program p;
  p.name = "hull";
  p.usage = "[options] [input ...]";
  p.takes = {example::input_kind::mesh};
  p.one_run = [](const std::vector<std::string>& a) { return a.size() == 2 && a[1] == "merge"; };
  p.about =
      "The 3D convex hull of a point set: the vertices of a mesh or wireframe file (its faces and\n"
      "lines are ignored), or 2000 random points in a ball; prints what it found and draws it.";
  p.input_help =
      "points: the vertices of an .off, .obj, .ply or .stl file; default: 2000 random points in a\n"
      "       unit ball (seed 2024)";
  p.outputs_help =
      "  hull.<format>   the hull (--format, default off)\n"
      "  hull.svg        the hull see-through over the points: hull vertices red, inner points grey\n";
  p.exit4_help =
      "read, but not points (a skeleton, a drawing, a cell list: the message names the program\n"
      "     that takes it), or a hull that fails validation";
  bool merge = false;
  p.add_common_options("off");
  p.options.push_back({{"--merge"},
                       "",
                       "one polygon per planar facet instead of triangles (default: triangles)",
                       [&](std::string_view) { merge = true; }});
  return example::run(p, argc, argv, [&](std::vector<std::string> args) -> int {
    if (args.size() == 2 && args[1] == "merge") {  // the old spelling: hull points.off merge
      std::fprintf(stderr, "hull: the argument 'merge' is deprecated; use --merge\n");
      merge = true;
      args.pop_back();
    }
    const bool from_file = !args.empty();
    const fs::path input = p.one_input(args, {});
    example::stage_note& stage = p.stage;
    example::output_files out(p, from_file ? std::vector<fs::path>{input} : std::vector<fs::path>{});
    bool failed = false;  // a result that fails its check: written only with --keep-partial
    std::vector<fs::path> mesh_paths;
    for (const std::string& f : p.formats) mesh_paths.push_back(out.add("hull." + f));
    const fs::path picture_path = out.add("hull.svg");
    if (from_file) {
      example::expect_extension(p.name, input, {example::input_kind::mesh}, "a file of points");
      stage("reading " + example::file_and_size(input));
    }
    const std::vector<point> points =  // an OBJ wireframe's vertices too
        from_file ? cellforge::io::read_soup<point>(input).points : random_ball(2000, 2024);
    stage("building the hull of " + std::to_string(points.size()) + " points");

    cellforge::convex_hull_report report;
    const auto t0 = std::chrono::steady_clock::now();
    const auto hull = cellforge::convex_hull(points, {.merge_coplanar = merge}, &report);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

    const char* kind[] = {"empty", "one point", "a segment", "flat (a polygon, two faces back to back)",
                          "solid"};
    std::printf("input            %s\n",
                from_file ? input.string().c_str() : "2000 random points in a ball (seed 2024)");
    std::printf("points           %zu\n", report.input_points);
    std::printf("hull             %s\n", kind[report.dimension + 1]);
    std::printf("hull vertices    %zu\n", report.vertices);
    std::printf("hull edges       %zu\n", report.edges);
    std::printf("hull faces       %zu%s\n", report.faces, merge ? " (planar facets merged)" : " (triangles)");
    std::printf("exact fallbacks  %zu orientation tests the filter could not decide\n",
                report.exact_evaluations);
    std::printf("time             %.3f ms\n", ms);
    const cellforge::mesh_validation valid = cellforge::validate(hull);
    std::printf("valid            %s, %s\n", valid.ok() ? "yes" : valid.message.c_str(),
                hull.is_closed() ? "closed" : "not closed");
    if (!valid.ok()) {
      std::fprintf(stderr, "hull: the hull fails validation: %s\n", valid.message.c_str());
      if (!p.keep_partial) return example::exit_not_for_this;
      failed = true;
    }

    stage("writing the hull of " + std::to_string(hull.num_faces()) + " faces");
    if (hull.num_faces() > 0)
      for (const fs::path& path : mesh_paths)
        out.write(path, [&](const fs::path& to) { example::write_mesh_file(to, hull); });

    if (p.svg) {
      // The picture: the hull see-through over every point, vertices in red.
      stage("drawing " + std::to_string(hull.num_faces()) + " faces and " + std::to_string(points.size()) +
            " points");
      cellforge::io::svg_scene scene;
      std::vector<point> inside, corners;
      std::vector<char> is_corner(points.size(), 0);
      const auto index = hull.get_vertex_property<std::uint32_t>(cellforge::input_index_property_name);
      for (cellforge::vertex_handle v : hull.vertices()) is_corner[index[v]] = 1;
      for (std::size_t i = 0; i < points.size(); ++i) (is_corner[i] ? corners : inside).push_back(points[i]);
      if (hull.num_faces() > 0)
        scene.add_mesh(cellforge::to_soup(hull), {.opacity = 0.5, .hidden_opacity = 0.25});
      scene.add_points(inside, {.fill = "#7a7a7a", .stroke = "none", .hidden_opacity = 0.6}, 1.2);
      scene.add_points(corners, {.fill = "#d0312d", .stroke = "#5a0f0d"}, 2.5);
      out.write(picture_path, [&](const fs::path& to) { scene.write(to, {.title = "convex hull"}); });
    }
    if (failed) return example::exit_not_for_this;  // the outputs kept as partial
    out.commit();
    std::printf("wrote            %s\n", out.list().c_str());
    return example::exit_ok;
  });
}
