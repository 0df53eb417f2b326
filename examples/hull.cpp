// hull: the 3D convex hull of a point set, written as a mesh and drawn as a picture.
//
//   hull                    2000 random points in a ball (fixed seed)
//   hull points.off         the vertices of any OFF, OBJ or PLY file (its faces are ignored)
//   hull points.off merge   the same, one polygon per planar facet instead of triangles
//   hull ... --no-svg       without the picture
//
// Writes, in the current directory, hull.off (the hull) and hull.svg (the hull over the
// points: red points are hull vertices, grey ones lie inside), and prints what it found.
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
  const bool picture = !example::take_flag(argc, argv, "--no-svg");
  const bool from_file = argc > 1;
  const bool merge = argc > 2 && std::string(argv[2]) == "merge";
  if (argc > 3 || (argc > 2 && !merge)) {
    std::fprintf(stderr, "usage: hull [points.off|.obj|.ply [merge]] [--no-svg]\n");
    return 2;
  }
  example::stage_note stage;
  try {
    if (from_file) example::refuse_to_overwrite({"hull.off", "hull.svg"}, argv[1]);
    if (from_file) stage("reading " + example::file_and_size(argv[1]));
    const std::vector<point> points =
        from_file ? cellforge::io::read_soup<point>(argv[1]).points : random_ball(2000, 2024);
    stage("building the hull of " + std::to_string(points.size()) + " points");

    cellforge::convex_hull_report report;
    const auto t0 = std::chrono::steady_clock::now();
    const auto hull = cellforge::convex_hull(points, {.merge_coplanar = merge}, &report);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

    const char* kind[] = {"empty", "one point", "a segment", "flat (a polygon, two faces back to back)",
                          "solid"};
    std::printf("input            %s\n", from_file ? argv[1] : "2000 random points in a ball (seed 2024)");
    std::printf("points           %zu\n", report.input_points);
    std::printf("hull             %s\n", kind[report.dimension + 1]);
    std::printf("hull vertices    %zu\n", report.vertices);
    std::printf("hull edges       %zu\n", report.edges);
    std::printf("hull faces       %zu%s\n", report.faces, merge ? " (planar facets merged)" : " (triangles)");
    std::printf("exact fallbacks  %zu orientation tests the filter could not decide\n",
                report.exact_evaluations);
    std::printf("time             %.3f ms\n", ms);
    const cellforge::validation_result valid = cellforge::validate(hull);
    std::printf("valid            %s, %s\n", valid.ok() ? "yes" : valid.message.c_str(),
                hull.is_closed() ? "closed" : "not closed");

    const fs::path out = "hull.off";
    stage("writing the hull of " + std::to_string(hull.num_faces()) + " faces");
    if (hull.num_faces() > 0) {
      cellforge::io::write_mesh(out, hull);
      std::printf("wrote            %s\n", out.string().c_str());
    }

    if (!picture) return valid.ok() ? 0 : 1;
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
    scene.write(fs::path("hull.svg"), {.title = "convex hull"});
    std::printf("wrote            hull.svg\n");
    return valid.ok() ? 0 : 1;
  } catch (const std::bad_alloc&) {  // a model too big for this machine: say so, do not abort
    example::report_out_of_memory("hull", stage);
    return 1;
  } catch (const std::exception& e) {  // cellforge::error among them: its message says what to fix
    std::fprintf(stderr, "hull: %s\n", e.what());
    return 1;
  }
}
