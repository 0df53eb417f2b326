// SPDX-License-Identifier: MIT
// Compiled twice: in the io group (the POSIX operations) and alone with
// CELLFORGE_IO_STD_FILESYSTEM=1 (the std::filesystem operations Windows uses).
#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/core/error.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/io/off.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace io_file_path_tests {

namespace io = cellforge::io;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const char* name) {
  const fs::path dir =
      fs::temp_directory_path() / (std::string(name) + (CELLFORGE_IO_STD_FILESYSTEM ? "_std" : "_posix"));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

cellforge::polygon_soup<glm::dvec3> triangle() {
  cellforge::polygon_soup<glm::dvec3> soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  soup.add_face({0, 1, 2});
  return soup;
}

}  // namespace

TEST_CASE(
    "file_path: built from every string kind and from std::filesystem::path, without <filesystem> in io") {
  static_assert(std::is_convertible_v<const char*, io::file_path>);
  static_assert(std::is_convertible_v<std::string, io::file_path>);
  static_assert(std::is_convertible_v<std::string_view, io::file_path>);
  static_assert(std::is_convertible_v<fs::path, io::file_path>);
  static_assert(!std::is_convertible_v<int, io::file_path>);
  const std::string name = "dir/mesh.off";
  CHECK(io::file_path("dir/mesh.off").string() == name);
  CHECK(io::file_path(name).string() == name);
  CHECK(io::file_path(std::string_view(name)).string() == name);
  CHECK(io::file_path(fs::path(name)).string() == name);
  CHECK(io::file_path(name).with_suffix(".partial").string() == "dir/mesh.off.partial");
}

TEST_CASE("file_path: extension() agrees with std::filesystem::path::extension") {
  for (const char* name : {"a.off", "A.OFF", "dir/a.b.ply", "noext", "dir.d/noext", ".profile", "dir/.hidden",
                           "a.", "..", ".", "dir/..", "a/b/c.stl", "", "x.tar.gz", "dir.x/"}) {
    CAPTURE(std::string(name));
    CHECK(io::file_path(name).extension() == fs::path(name).extension().string());
  }
}

TEST_CASE("file_path: status_of tells files, folders, devices and missing names apart") {
  const fs::path dir = fresh_dir("cellforge_file_path_status");
  const fs::path file = dir / "five.txt";
  std::ofstream(file) << "12345";
  auto s = io::detail::status_of(file);
  CHECK(s.kind == io::detail::file_kind::regular);
  CHECK(s.size == 5);
  CHECK(io::detail::status_of(dir).kind == io::detail::file_kind::directory);
  CHECK(io::detail::status_of(dir / "missing").kind == io::detail::file_kind::missing);
  if (fs::exists("/dev/null")) CHECK(io::detail::status_of("/dev/null").kind == io::detail::file_kind::other);
  fs::remove_all(dir);
}

TEST_CASE("file_path: readers and writers take strings and std::filesystem::path alike") {
  const fs::path dir = fresh_dir("cellforge_file_path_io");
  const auto soup = triangle();
  io::write_off(dir / "by_path.off", soup);
  io::write_off((dir / "by_string.off").string(), soup);
  io::write_off((dir / "by_chars.off").string().c_str(), soup);
  for (const char* name : {"by_path.off", "by_string.off", "by_chars.off"}) {
    const auto back = io::read_off<glm::dvec3>(dir / name);
    CHECK(back.points == soup.points);
    CHECK(back.face_vertices == soup.face_vertices);
    CHECK(!fs::exists(dir / (std::string(name) + ".partial")));  // the partial file was renamed
  }
  // A failed write removes its partial file and keeps what was there.
  const fs::path kept = dir / "kept.off";
  std::ofstream(kept) << "original";
  auto bad = soup;
  bad.face_vertices[0] = 7;  // out of range: the writer refuses
  CHECK_THROWS_AS(io::write_off(kept, bad), cellforge::error);
  CHECK(!fs::exists(dir / "kept.off.partial"));
  std::ifstream in(kept);
  std::string text;
  in >> text;
  CHECK(text == "original");
  // Reading a folder or a missing file names it; writing onto a folder is refused.
  try {
    (void)io::read_off<glm::dvec3>(dir);
    FAIL("read a folder");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(e.message().find(dir.string()) != std::string::npos);
  }
  CHECK_THROWS_AS((void)io::read_off<glm::dvec3>(dir / "missing.off"), cellforge::error);
  CHECK_THROWS_AS(io::write_off(dir, soup), cellforge::error);
  // Renaming into a folder that does not exist gives the system's reason.
  CHECK(!io::detail::rename_file(dir / "by_path.off", dir / "no" / "such" / "dir.off").empty());
  CHECK(io::detail::rename_file(dir / "by_path.off", dir / "renamed.off").empty());
  CHECK(fs::exists(dir / "renamed.off"));
  io::detail::remove_file(dir / "renamed.off");
  CHECK(!fs::exists(dir / "renamed.off"));
  fs::remove_all(dir);
}

}  // namespace io_file_path_tests
