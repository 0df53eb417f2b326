#include <doctest/doctest.h>

#include <array>
#include <filesystem>
#include <fstream>

#include "cellforge/halfedge/validate.hpp"
#include "cellforge/io/mesh_io.hpp"
#include "mesh_fixtures.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace mesh_io_tests {

namespace {
std::filesystem::path temp_dir() {
  auto d = std::filesystem::temp_directory_path() / "cellforge_test_mesh_io";
  std::filesystem::create_directories(d);
  return d;
}
template <class P>
cellforge::polygon_soup<P> convert(const fixtures::soup& s) {
  cellforge::polygon_soup<P> out;
  for (const auto& p : s.points) out.points.push_back(cellforge::from_dvec3<P>(p));
  out.face_offsets = s.face_offsets;
  out.face_vertices = s.face_vertices;
  return out;
}
}  // namespace

TEST_CASE_TEMPLATE("meshes round-trip through OFF, OBJ and PLY for every point type", P, glm::dvec3,
                   std::array<float, 3>, test_support::user_point) {
  // A non-orientable mesh with quads: faces must come back with their own orientation.
  const auto src = convert<P>(fixtures::glued_grid(7, 3, true, true, false, false, false));
  const auto m = cellforge::make_mesh(src);
  REQUIRE(cellforge::validate(m).ok());
  for (const char* ext : {".off", ".obj", ".ply"}) {
    CAPTURE(ext);
    const auto path = temp_dir() / (std::string("mobius") + ext);
    cellforge::io::write_mesh(path, m);
    cellforge::build_report rep;
    const auto back = cellforge::io::read_mesh<P>(path, &rep);
    REQUIRE(cellforge::validate(back).ok());
    CHECK(rep.flipped_edges == m.num_flipped_edges());
    const auto a = cellforge::to_soup(m), b = cellforge::to_soup(back);
    CHECK(a.face_vertices == b.face_vertices);
    CHECK(a.face_offsets == b.face_offsets);
    for (std::size_t i = 0; i < a.points.size(); ++i)
      CHECK(cellforge::to_dvec3(a.points[i]) == cellforge::to_dvec3(b.points[i]));
  }
}

TEST_CASE("mesh files with bad topology or extension give located errors") {
  const auto path = temp_dir() / "three_faces_on_an_edge.off";
  {
    std::ofstream f(path);
    f << "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n";
  }
  try {
    (void)cellforge::io::read_mesh<glm::dvec3>(path);
    FAIL("expected an error");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::topology);
    CHECK(e.file() == path.string());
    CHECK(std::string(e.what()).find("edge (0, 1)") != std::string::npos);
  }
  CHECK_THROWS_WITH_AS((void)cellforge::io::read_mesh<glm::dvec3>(temp_dir() / "x.3mf"),
                       doctest::Contains("unknown mesh file extension '.3mf'"), cellforge::error);
}

}  // namespace mesh_io_tests
