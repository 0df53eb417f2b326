// mesh_info: reads a mesh (OFF, OBJ or PLY), builds the half-edge mesh, validates it,
// prints its statistics and draws it as an SVG picture with its boundary highlighted.
//
//   mesh_info                 the bundled Möbius band (a non-orientable mesh)
//   mesh_info model.off       any mesh file; writes mesh_info.svg in the current directory
//   mesh_info ... --no-svg    without the picture
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <new>

#include "cellforge/cellforge.hpp"
#include "cellforge/io/mesh_io.hpp"
#include "cellforge/io/svg.hpp"
#include "example_support.hpp"

int main(int argc, char** argv) {
  const bool picture = !example::take_flag(argc, argv, "--no-svg");
  if (argc > 2) {
    std::fprintf(stderr, "usage: mesh_info [model.off|.obj|.ply|.stl] [--no-svg]\n");
    return 2;
  }
  const std::filesystem::path input = argc > 1
                                          ? std::filesystem::path(argv[1])
                                          : std::filesystem::path(CELLFORGE_DATA_DIR) / "mobius_band.obj";
  example::stage_note stage;
  try {
    example::refuse_to_overwrite("mesh_info.svg", input);
    stage("reading " + example::file_and_size(input));
    using clock = std::chrono::steady_clock;
    const auto t0 = clock::now();
    const auto soup = cellforge::io::read_soup<glm::dvec3>(input);
    const auto t1 = clock::now();
    cellforge::build_report report;
    stage("building the mesh of " + std::to_string(soup.num_faces()) + " faces");
    const cellforge::surface_mesh<glm::dvec3> mesh =
        cellforge::make_mesh(soup, &report, {.split_nonmanifold_vertices = true});
    const auto t2 = clock::now();
    const cellforge::validation_result valid = cellforge::validate(mesh);
    const auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };

    std::map<std::size_t, std::size_t> face_sizes;
    for (auto f : mesh.faces()) ++face_sizes[mesh.valence(f)];
    std::size_t min_valence = ~std::size_t{0}, max_valence = 0;
    for (auto v : mesh.vertices()) {
      if (mesh.is_isolated(v)) continue;
      min_valence = std::min(min_valence, mesh.valence(v));
      max_valence = std::max(max_valence, mesh.valence(v));
    }
    const auto loops = mesh.boundary_loops();
    const long chi = static_cast<long>(mesh.num_vertices()) - static_cast<long>(mesh.num_edges()) +
                     static_cast<long>(mesh.num_faces());

    std::printf("file               %s\n", input.string().c_str());
    std::printf("vertices           %zu (%zu isolated, %zu split off non-manifold vertices)\n",
                mesh.num_vertices(), report.isolated_vertices, report.split_vertices.size());
    std::printf("edges              %zu (%zu on the boundary)\n", mesh.num_edges(),
                mesh.num_boundary_edges());
    std::printf("faces              %zu (", mesh.num_faces());
    for (auto [n, count] : face_sizes) std::printf(" %zu with %zu sides", count, n);
    std::printf(" )\n");
    std::printf("vertex valence     %zu .. %zu\n", min_valence == ~std::size_t{0} ? 0 : min_valence,
                max_valence);
    std::printf("boundary loops     %zu", loops.size());
    for (const auto& l : loops) std::printf(" [%zu edges]", l.size());
    std::printf("\nEuler char.        %ld\n", chi);
    std::printf("closed             %s\n", mesh.is_closed() ? "yes" : "no");
    std::printf("orientable         %s\n", cellforge::is_orientable(mesh) ? "yes" : "no");
    std::printf("flipped edges      %zu (faces on both sides run the same way)\n", mesh.num_flipped_edges());
    std::printf("memory             %.1f bytes per face (connectivity)\n",
                mesh.num_faces() ? double(mesh.memory_bytes()) / double(mesh.num_faces()) : 0.0);
    std::printf("read / build       %.3f ms / %.3f ms\n", ms(t0, t1), ms(t1, t2));
    std::printf("validate           %s\n", valid.ok() ? "ok" : valid.message.c_str());

    if (!picture) return valid.ok() ? 0 : 1;
    // The picture: shaded faces, hidden edges dashed, boundary loops in red on top.
    stage("drawing " + std::to_string(mesh.num_faces()) + " faces");
    cellforge::io::svg_scene scene;
    scene.add_mesh(cellforge::to_soup(mesh));
    const auto pts = mesh.positions();
    cellforge::io::svg_style boundary;
    boundary.stroke = "#c0392b";
    boundary.stroke_width = 2.5;
    for (const auto& loop : loops) {
      std::vector<glm::dvec3> line;
      for (auto h : loop) line.push_back(pts[mesh.tail(h)]);
      scene.add_polyline(line, boundary, true);
    }
    cellforge::io::svg_options options;
    options.title = "mesh_info: " + input.filename().string();
    options.view.elevation_deg = 35;
    const auto drawn = scene.write(std::filesystem::path("mesh_info.svg"), options);
    std::printf("picture            mesh_info.svg (%zu faces, %zu visible and %zu partly hidden edges)\n",
                drawn.faces_drawn, drawn.visible_edges, drawn.partly_hidden_edges);
    return valid.ok() ? 0 : 1;
  } catch (const std::bad_alloc&) {  // a model too big for this machine: say so, do not abort
    example::report_out_of_memory("mesh_info", stage);
    return 1;
  } catch (const std::exception& e) {  // cellforge::error among them: its message says what to fix
    std::fprintf(stderr, "mesh_info: %s\n", e.what());
    return 1;
  }
}
