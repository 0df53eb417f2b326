// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Orientation queries and repair: is the surface orientable, and make the faces'
/// orientations agree wherever the topology allows.

#include <cstdint>
#include <string>
#include <vector>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/halfedge/mesh.hpp"

namespace cellforge {

/// What orient() did; milliseconds the call, a diagnostic per non-orientable component count.
struct orient_result : stage_report {
  std::size_t components = 0;  ///< connected components (through edges)
  std::size_t non_orientable_components = 0;
  std::size_t faces_reversed = 0;
  std::size_t flipped_edges_left = 0;  ///< seams that no choice of orientations can remove
  bool orientable() const noexcept { return non_orientable_components == 0; }
};

namespace detail {
// Breadth-first 2-colouring of faces: sign[f] says whether f must be reversed to agree
// with its component's first face. Reports components that admit no such colouring.
template <class = void>
orient_result orientation_signs(const halfedge_mesh& m, std::vector<std::int8_t>& sign) {
  orient_result r;
  sign.assign(m.faces_size(), 0);
  std::vector<face_handle> queue;
  for (face_handle seed : m.faces()) {
    if (sign[seed.idx()] != 0) continue;
    ++r.components;
    bool conflict = false;
    sign[seed.idx()] = 1;
    queue.assign(1, seed);
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const face_handle f = queue[q];
      for (halfedge_handle h : m.halfedges_around(f)) {
        const halfedge_handle t = halfedge_mesh::twin(h);
        if (m.is_boundary(t)) continue;
        const face_handle g = m.face(t);
        // Same direction across the edge: g must have the opposite sign to agree with f.
        const std::int8_t want =
            m.is_flipped(halfedge_mesh::edge(h)) ? static_cast<std::int8_t>(-sign[f.idx()]) : sign[f.idx()];
        if (sign[g.idx()] == 0) {
          sign[g.idx()] = want;
          queue.push_back(g);
        } else if (sign[g.idx()] != want) {
          conflict = true;
        }
      }
    }
    if (conflict) ++r.non_orientable_components;
  }
  return r;
}
}  // namespace detail

/// True when the faces can be oriented consistently (no Möbius-like component). O(n).
template <class = void>
bool is_orientable(const halfedge_mesh& m) {
  std::vector<std::int8_t> sign;
  return detail::orientation_signs(m, sign).orientable();
}

/// Reverses faces so that neighbours agree in orientation, per connected component
/// (keeping each component's first face as given). On a non-orientable component the
/// seams that remain are reported. O(n).
template <class = void>
orient_result orient(halfedge_mesh& m) {
  const detail::stopwatch clock;
  std::vector<std::int8_t> sign;
  orient_result r = detail::orientation_signs(m, sign);
  for (face_handle f : m.faces())
    if (sign[f.idx()] < 0) {
      m.reverse_face(f);
      ++r.faces_reversed;
    }
  r.flipped_edges_left = m.num_flipped_edges();
  if (!r.orientable())
    r.diagnostics.push_back(cellforge::detail::cat(
        std::to_string(r.non_orientable_components), " of ", std::to_string(r.components),
        " components are not orientable: ", std::to_string(r.flipped_edges_left),
        " edges still join faces of opposite orientation"));
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge
