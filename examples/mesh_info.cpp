// mesh_info: reads a mesh (OFF, OBJ, PLY or STL), builds the half-edge mesh, validates it,
// prints its statistics and draws it as an SVG picture with its boundary highlighted.
//
//   mesh_info [options] [input]   input: any mesh file; none: the bundled Möbius band
//   mesh_info --help              every option with its default, the outputs, the exit statuses
//
// Writes mesh_info.svg into the output folder (-o, default ./out/; --no-svg: nothing).
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
  example::program p;
  p.name = "mesh_info";
  p.usage = "[options] [input ...]";
  p.takes = {example::input_kind::mesh};
  p.about =
      "Reads a mesh, builds its half-edge mesh (non-manifold vertices split), validates it, prints its\n"
      "statistics (faces by size, valence, boundary loops, Euler characteristic, orientability) and\n"
      "draws it with its boundary loops in red.";
  p.input_help = "a mesh: .off, .obj (with 'f' faces), .ply or .stl; default: the bundled mobius_band.obj";
  p.outputs_help = "  mesh_info.svg   the mesh shaded, hidden edges dashed, boundary loops in red\n";
  p.exit4_help =
      "read, but not a mesh (a wireframe, a skeleton, a point set, a drawing, a cell list: the\n"
      "     message names the program that takes it), or a mesh that fails validation";
  p.add_common_options();
  return example::run(p, argc, argv, [&](const std::vector<std::string>& args) -> int {
    const std::filesystem::path input =
        p.one_input(args, std::filesystem::path(CELLFORGE_DATA_DIR) / "mobius_band.obj");
    example::stage_note& stage = p.stage;
    example::output_files out(p, {input});
    const std::filesystem::path picture_path = out.add("mesh_info.svg");
    example::expect_extension(p.name, input, {example::input_kind::mesh}, "a mesh");
    stage("reading " + example::file_and_size(input));
    using clock = std::chrono::steady_clock;
    const auto t0 = clock::now();
    const auto soup = cellforge::io::read_soup<glm::dvec3>(input);
    if (soup.num_faces() == 0) example::refuse_faceless(p, input, soup.points.size(), "a mesh");
    const auto t1 = clock::now();
    cellforge::build_report report;
    stage("building the mesh of " + std::to_string(soup.num_faces()) + " faces");
    const cellforge::surface_mesh<glm::dvec3> mesh =
        cellforge::make_mesh(soup, &report, {.split_nonmanifold_vertices = true});
    const auto t2 = clock::now();
    const cellforge::mesh_validation valid = cellforge::validate(mesh);
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

    const int status = valid.ok() ? example::exit_ok : example::exit_not_for_this;
    if (!valid.ok())
      std::fprintf(stderr, "mesh_info: read, but the mesh is not valid: %s\n", valid.message.c_str());
    if (!p.svg) return status;
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
    cellforge::io::svg_result drawn;
    out.write(picture_path, [&](const std::filesystem::path& to) { drawn = scene.write(to, options); });
    if (status != example::exit_ok) return status;
    out.commit();
    std::printf("picture            %s (%zu faces, %zu visible and %zu partly hidden edges)\n",
                picture_path.string().c_str(), drawn.faces_drawn, drawn.visible_edges,
                drawn.partly_hidden_edges);
    return status;
  });
}
