// SPDX-License-Identifier: MIT
// The add_subdirectory build of the consumer: the CAD types of cad.hpp through one mesh job.
// This build checks how cellforge behaves as a subproject (CMakeLists.txt); the library's
// breadth is main.cpp's job, built against the installed package with g++ and clang.
#include <cellforge/halfedge/conversion.hpp>
#include <cellforge/halfedge/mesh_geometry.hpp>
#include <cellforge/halfedge/validate.hpp>

#include <cstdio>

#include "cad.hpp"

int main() {
  const auto mesh = cellforge::make_mesh(cad::box<cad::Vector3>(2, 1, 0.5));
  const auto [lo, hi] = cellforge::bounds(mesh);
  static_assert(std::is_same_v<std::remove_cvref_t<decltype(hi)>, cad::Vector3>);
  if (!cellforge::validate(mesh).ok() || cellforge::euler_characteristic(mesh) != 2 || hi.x() != 2 ||
      lo.z() != 0) {
    std::fprintf(stderr, "consumer: FAILED: the box mesh\n");
    return 1;
  }
  std::printf("consumer ok: a cad::Vector3 box, %zu faces\n", mesh.num_faces());
  return 0;
}
