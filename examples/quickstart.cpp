// The README's usage example, compiled so that it stays true. It reads and writes no files; it
// takes the toolkit's shared options (quickstart --help) like every other program.
#include <cstdio>

#include "cellforge/cellforge.hpp"
#include "example_support.hpp"

namespace cad {
struct Vec {
  double x, y, z;
};
}  // namespace cad
CELLFORGE_REGISTER_POINT3(cad::Vec, double, x, y, z);  // one line registers it

int main(int argc, char** argv) {
  example::program p;
  p.name = "quickstart";
  p.usage = "[options]";
  p.batch = false;  // no input
  p.about =
      "The README's usage example: a Moebius strip of 3 quads in a user's own point type, built into a\n"
      "half-edge mesh; prints the faces around vertex 0, validity, orientability and boundary loops.";
  p.notes =
      "It reads no input and writes no files: -o and --no-svg are accepted, as by every program, and\n"
      "change nothing.";
  p.exit4_help = "not used by quickstart";
  p.add_common_options();
  return example::run(p, argc, argv, [&](const std::vector<std::string>& args) -> int {
    if (!args.empty()) throw example::usage_error("quickstart takes no input ('" + args[0] + "')");
    cellforge::polygon_soup<cad::Vec> soup;  // a Möbius strip of 3 quads
    soup.points = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {2, 0, 1}, {2, 1, 1}};
    soup.add_face({0, 2, 3, 1});
    soup.add_face({2, 4, 5, 3});
    soup.add_face({4, 1, 0, 5});  // glued with a half twist
    auto mesh = cellforge::make_mesh(soup);
    for (auto f : mesh.faces_around(cellforge::vertex_handle(0))) std::printf("face %u\n", f.idx());
    std::printf("valid: %d, orientable: %d, boundary loops: %zu\n", cellforge::validate(mesh).ok(),
                cellforge::is_orientable(mesh), mesh.boundary_loops().size());
    return example::exit_ok;
  });
}
