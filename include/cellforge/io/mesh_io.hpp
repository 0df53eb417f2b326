// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Reading and writing polygon soups and half-edge meshes by file extension
/// (.off, .obj, .ply), on top of the format readers and writers.

#include <algorithm>
#include <cctype>
#include <string>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/io/off.hpp"
#include "cellforge/io/ply.hpp"
#include "cellforge/io/stl.hpp"

namespace cellforge::io {

/// The file formats a mesh can be read from and written to.
enum class mesh_format { off, obj, ply, stl };

/// The format named by a path's extension (case-insensitive); throws for others. O(1).
template <class = void>
mesh_format format_of(const file_path& path) {
  std::string ext = path.extension();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".off") return mesh_format::off;
  if (ext == ".obj") return mesh_format::obj;
  if (ext == ".ply") return mesh_format::ply;
  if (ext == ".stl") return mesh_format::stl;
  throw error(
      error_category::io,
      cellforge::detail::cat("unknown mesh file extension '", ext, "' (expected .off, .obj, .ply or .stl)"),
      {path.string(), 0});
}

/// Reads the faces of an OFF, OBJ, PLY or STL file into a soup (STL: corners welded where
/// equal, degenerate facets dropped; see read_stl for the details). O(file size).
template <Point3 P>
polygon_soup<P> read_soup(const file_path& path) {
  switch (format_of(path)) {
    case mesh_format::off:
      return read_off<P>(path);
    case mesh_format::obj:
      return read_obj<P>(path).soup;
    case mesh_format::ply:
      return read_ply<P>(path);
    case mesh_format::stl:
      return read_stl<P>(path).soup;
  }
  return {};
}

/// Writes a soup in the format its path's extension names (STL: binary, float32, polygons
/// ear-clipped). O(size of the soup).
template <Point3 P>
void write_soup(const file_path& path, const polygon_soup<P>& soup) {
  switch (format_of(path)) {
    case mesh_format::off:
      write_off(path, soup);
      break;
    case mesh_format::obj:
      write_obj(path, soup);
      break;
    case mesh_format::ply:
      write_ply(path, soup);
      break;
    case mesh_format::stl:
      write_stl(path, soup);
      break;
  }
}

/// Reads an OFF, OBJ or PLY file into a surface mesh with positions of type P (the one
/// template argument a reader needs: a file has no point type). O(file size). Parse errors
/// name file:line; topology errors name the element.
template <Point3 P>
surface_mesh<P> read_mesh(const file_path& path, build_report* report = nullptr) {
  const polygon_soup<P> soup = read_soup<P>(path);
  try {
    return make_mesh(soup, report);
  } catch (const error& e) {
    throw error(e.category(), e.message(), {path.string(), 0});
  }
}

/// Writes the live part of a mesh by extension. O(size of the mesh).
template <Point3 P>
void write_mesh(const file_path& path, const surface_mesh<P>& mesh) {
  write_soup(path, to_soup(mesh));
}

}  // namespace cellforge::io
