// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// A cell complex as OBJ: the outward faces of each volume as one group "volume_<i>", then
/// the faces of no volume, faces with holes triangulated, edges in no face as lines.

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <ostream>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/io/obj.hpp"

namespace cellforge::io {

namespace detail {
/// cells_obj_data on double positions (one copy of the code for every point type). O(size of cc).
/// cells_obj_data without its points (the caller puts them in, in the type it wants); pts
/// are needed only to triangulate faces with holes. O(size of cc).
template <class = void>
obj_data<glm::dvec3> cells_obj_faces(const cell_topology& cc, std::span<const glm::dvec3> pts) {
  obj_data<glm::dvec3> data;
  std::vector<std::uint32_t> face;
  auto add = [&](cell_face f, int sign) {
    if (cc.num_loops(f) == 1) {
      face.clear();
      for (cell_vertex v : cc.loop_vertices(f, 0)) face.push_back(v.idx());
      if (sign < 0) std::reverse(face.begin(), face.end());
      data.soup.add_face(cellforge::detail::span_of(face));
      return;
    }
    std::vector<std::vector<glm::dvec3>> loops(cc.num_loops(f));
    std::vector<std::uint32_t> flat;
    for (std::size_t l = 0; l < loops.size(); ++l)
      for (cell_vertex v : cc.loop_vertices(f, l)) loops[l].push_back(pts[v.idx()]), flat.push_back(v.idx());
    for (const auto& t : cellforge::detail::cells::triangulate_face(
             loops, cellforge::detail::cells::access::unit_normal(cc, f),
             cellforge::detail::cat("cells obj: face ", std::to_string(f.idx()))))
      data.soup.add_face(sign < 0 ? std::initializer_list<std::uint32_t>{flat[t[0]], flat[t[2]], flat[t[1]]}
                                  : std::initializer_list<std::uint32_t>{flat[t[0]], flat[t[1]], flat[t[2]]});
  };
  for (cell_volume c : cc.volumes()) {
    data.groups.push_back({cellforge::detail::cat("volume_", std::to_string(c.idx())),
                           static_cast<std::uint32_t>(data.soup.num_faces())});
    for (const auto& [f, sign] : cc.volume_faces(c)) add(f, sign);
  }
  // Faces of no volume (an open surface), as they are oriented, in a group of their own.
  bool open_group = false;
  for (cell_face f : cc.faces())
    if (cc.face_volumes(f).empty()) {
      if (!open_group)
        data.groups.push_back({"faces_without_volume", static_cast<std::uint32_t>(data.soup.num_faces())});
      open_group = true;
      add(f, +1);
    }
  for (cell_edge e : cc.edges())
    if (cc.edge_faces(e).empty()) data.lines.push_back({cc.source(e).idx(), cc.target(e).idx()});
  return data;
}

template <Point3 P>
obj_data<glm::dvec3> cells_obj_data_dvec3(const cell_complex<P>& cc) {
  const cellforge::detail::cells::dvec3_points<P> pts(cc.points());
  obj_data<glm::dvec3> data = cells_obj_faces(cc, pts.span());
  data.soup.points.assign(pts.span().begin(), pts.span().end());
  return data;
}
}  // namespace detail

/// The faces of every volume, outward, as an OBJ model in the complex's point type with one
/// group "volume_<i>" per volume (a face between two volumes appears in both), then the faces
/// of no volume in a group "faces_without_volume", faces with holes triangulated, edges in no
/// face as `l` lines. O(size of cc).
template <Point3 P>
obj_data<P> cells_obj_data(const cell_complex<P>& cc) {
  if constexpr (std::is_same_v<P, glm::dvec3>) {
    return detail::cells_obj_data_dvec3(cc);
  } else {
    const cellforge::detail::cells::dvec3_points<P> pts(cc.points());
    obj_data<glm::dvec3> data = detail::cells_obj_faces(cc, pts.span());
    obj_data<P> out;
    out.soup.points.assign(cc.points().begin(), cc.points().end());
    out.soup.face_offsets = std::move(data.soup.face_offsets);
    out.soup.face_vertices = std::move(data.soup.face_vertices);
    out.groups = std::move(data.groups);
    out.lines = std::move(data.lines);
    return out;
  }
}

/// Writes cells_obj_data(cc) with write_obj. O(size of cc).
template <Point3 P>
void write_cells_obj(std::ostream& os, const cell_complex<P>& cc, const obj_write_options& options = {}) {
  write_obj(os, detail::cells_obj_data_dvec3(cc), options);
}
template <Point3 P>
void write_cells_obj(const file_path& path, const cell_complex<P>& cc,
                     const obj_write_options& options = {}) {
  write_obj(path, detail::cells_obj_data_dvec3(cc), options);
}

}  // namespace cellforge::io
