// wire2cells: the main job. Converts a wireframe (vertices and straight edges) into a
// three-dimensional cell list — vertices, edges, faces, volumes and their relations —
// and writes it with pictures.
//
//   wire2cells                  the bundled stepped block (examples/data/stepped_block.obj)
//   wire2cells model.obj        an OBJ wireframe (v and l lines)
//   wire2cells model.edges      a plain edge list (docs/formats.md)
//
// Writes <name>.3dcl, <name>.obj (one group per volume), <name>.ply (coloured by volume)
// and <name>.svg (volumes exploded apart) in the current directory and prints a per-stage
// table like the seed's table 1 (seed 000_6c43f981384fedb6.txt, §7.2).
#include <cstdio>
#include <string>

#include "cellforge/cells/validate.hpp"
#include "cellforge/io/cells_io.hpp"
#include "cellforge/io/edge_list.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

namespace {
void row(const char* stage, double ms, const char* what = nullptr, std::size_t count = 0) {
  if (what)
    std::printf("  %-26s %9.3f ms   %-18s %zu\n", stage, ms, what, count);
  else
    std::printf("  %-26s %9.3f ms\n", stage, ms);
}
}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path input = argc > 1
                                          ? std::filesystem::path(argv[1])
                                          : std::filesystem::path(CELLFORGE_DATA_DIR) / "stepped_block.obj";
  try {
    const auto wire = input.extension() == ".obj" ? cellforge::io::read_obj_wireframe<glm::dvec3>(input)
                                                  : cellforge::io::read_edge_list<glm::dvec3>(input);
    const cellforge::wireframe_result r = cellforge::wireframe_to_cells(wire);
    const cellforge::cell_complex& cells = r.cells;

    std::printf("wire2cells: %s\n\n", input.string().c_str());
    row("initial read", r.read.milliseconds, "vertices", r.read.input_vertices);
    std::printf("  %-26s %12s   %-18s %zu\n", "", "", "edges", r.read.input_edges);
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
    const double total = r.read.milliseconds + r.trace.milliseconds + r.unique.milliseconds +
                         r.reduction.milliseconds + r.arrangement.milliseconds + r.extra.milliseconds +
                         r.volume.milliseconds + r.relations.milliseconds + r.assembly_milliseconds;
    row("total", total);

    const cellforge::cells_validation_result valid = cellforge::validate(cells);
    std::printf("\ncell complex: %zu vertices, %zu edges, %zu faces, %zu volumes, %zu objects\n",
                cells.num_vertices(), cells.num_edges(), cells.num_faces(), cells.num_volumes(),
                cells.num_objects());
    for (auto o : cells.objects())
      std::printf("  object %u: V - E + F - C = %lld\n", o.idx(), cells.object_euler(o));
    std::printf("  walls no edge forces: %zu\n", r.unforced.size());
    for (const std::string& d : r.diagnostics) std::printf("  note: %s\n", d.c_str());
    std::printf("  validate: %s\n", valid.ok() ? "ok" : valid.message.c_str());

    const std::string stem = input.stem().string();
    cellforge::io::write_3dcl(std::filesystem::path(stem + ".3dcl"), cells);
    cellforge::io::write_cells_obj(std::filesystem::path(stem + ".obj"), cells);
    cellforge::io::write_cells_ply(std::filesystem::path(stem + ".ply"), cells);
    cellforge::io::write_cells_svg(std::filesystem::path(stem + ".svg"), cells);
    std::printf("\nwrote %s.3dcl, %s.obj, %s.ply and %s.svg\n", stem.c_str(), stem.c_str(), stem.c_str(),
                stem.c_str());
    return valid.ok() ? 0 : 1;
  } catch (const cellforge::error& e) {
    std::fprintf(stderr, "wire2cells: %s\n", e.what());
    return 1;
  }
}
