// subdivide: Loop subdivision of a triangle mesh, with a before/after picture.
//
//   subdivide                       the bundled open cup (examples/data/cup.off), 2 levels
//   subdivide model.obj [levels]    any OFF, OBJ or PLY file (polygons are fan-triangulated)
//   subdivide ... --no-svg          without the picture
//
// Writes, in the current directory, subdivided.<ext> (the input's format) and
// subdivide.svg (input on the left, result on the right), and prints counts and times.
#include <algorithm>
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
  const bool picture_wanted = !example::take_flag(argc, argv, "--no-svg");
  if (argc > 3) {
    std::fprintf(stderr, "usage: subdivide [model.off|.obj|.ply [levels]] [--no-svg]\n");
    return 2;
  }
  const fs::path input = argc > 1 ? fs::path(argv[1]) : fs::path(CELLFORGE_DATA_DIR) / "cup.off";
  int levels = 2;
  if (argc > 2) {
    char* end = nullptr;
    const long n = std::strtol(argv[2], &end, 10);
    if (*end != '\0' || n < 0 || n > 12) {
      std::fprintf(stderr, "subdivide: levels must be a whole number from 0 to 12, got '%s'\n", argv[2]);
      return 2;
    }
    levels = static_cast<int>(n);
  }
  example::stage_note stage;
  try {
    std::string ext = input.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    const fs::path out = fs::path("subdivided" + ext);
    example::refuse_to_overwrite({out, "subdivide.svg"}, input);
    stage("reading " + example::file_and_size(input));
    cellforge::polygon_soup<point> soup = cellforge::io::read_soup<point>(input);
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
    const cellforge::loop_result r = cellforge::loop_subdivide(mesh, {.levels = levels});
    const cellforge::validation_result valid = cellforge::validate(mesh);

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
    std::printf("total              %.3f ms\n", r.total_ms());
    std::printf("valid              %s\n", valid.ok() ? "yes" : valid.message.c_str());

    stage("writing " + std::to_string(mesh.num_faces()) + " faces");
    cellforge::io::write_mesh(out, mesh);
    if (!picture_wanted) {
      std::printf("wrote              %s\n", out.string().c_str());
      return valid.ok() ? 0 : 1;
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
    scene.write(fs::path("subdivide.svg"), picture);
    std::printf("wrote              %s, subdivide.svg\n", out.string().c_str());
    return valid.ok() ? 0 : 1;
  } catch (const std::bad_alloc&) {  // a model too big for this machine: say so, do not abort
    example::report_out_of_memory("subdivide", stage);
    return 1;
  } catch (const std::exception& e) {  // cellforge::error among them: its message says what to fix
    std::fprintf(stderr, "subdivide: %s\n", e.what());
    return 1;
  }
}
