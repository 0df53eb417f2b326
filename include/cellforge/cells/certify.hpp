// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// certify(cells, wire): the check that an answer of the wireframe → cell complex job is a solid
/// made of its input, not merely a complex that looks right. It checks that every input edge lies
/// on a face, that every face edge is a genuine edge of a solid, that every volume is closed,
/// oriented, manifold and of positive volume, and that no two faces cross and no input edge
/// pierces a face — the last two exactly (signs of orient3d / orient2d on the input points; the
/// tolerances only match positions and judge flat seams). See docs/cells.md, "The certificate".

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/core/tolerance.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/core/work_budget.hpp"

namespace cellforge {

/// What an answer of the wireframe → cell complex job is, judged by its certificate:
/// a closed solid the wireframe decides (solid), a closed solid with faces the wireframe does
/// not decide (ambiguous), anything else (not_a_solid), or not judged to the end (budget).
enum class solid_status : std::uint8_t { solid, ambiguous, not_a_solid, budget };

/// "solid", "ambiguous", "not a solid", "budget". O(1).
constexpr const char* to_string(solid_status s) noexcept {
  switch (s) {
    case solid_status::solid:
      return "solid";
    case solid_status::ambiguous:
      return "ambiguous";
    case solid_status::not_a_solid:
      return "not a solid";
    case solid_status::budget:
      return "budget";
  }
  return "?";
}

/// How certify measures and which checks it runs.
struct certify_options {
  /// An input vertex is the complex vertex within this distance (relative to the diagonal of the
  /// input's and the complex's points), and a complex vertex lies on an input edge when within
  /// it of the edge (an edge split at T-junctions). The pipeline's own merge tolerance by default.
  tolerance merge{1e-9};
  /// Two faces on an edge are coplanar (the edge is a seam in a flat surface, not an edge of a
  /// solid) when one departs from the other's plane by less than this (relative to the diagonal)
  /// across its own extent: |n_a × n_b| · extent ≤ planarity. The pipeline's planarity by default.
  tolerance planarity{1e-9};
  /// Work budget in steps (grid pairs, exact pair tests, chain steps). 0: unlimited;
  /// `automatic` (the default): 256 steps per face, edge and input edge, plus 2^22.
  /// Past it certify stops with complete = false (and ok() false).
  cellforge::work_budget work_budget = cellforge::work_budget::automatic;
  static constexpr std::uint64_t automatic = cellforge::work_budget::automatic;  ///< the same constant
  bool check_input_edges = true;  ///< every input edge on a face (needs the wireframe)
  bool check_edges = true;        ///< every face edge genuine (no seams in a flat surface)
  /// An edge on just two coplanar faces (a seam in a flat surface) fails as seam_edge; false:
  /// only counted in seam_edges. wireframe_to_cells sets false: its reading rule keeps a seam
  /// only where the wireframe draws one and no wall for it (a tessellated flat surface).
  bool seams_fail = true;
  bool check_volumes = true;    ///< every volume closed, oriented, manifold, of positive volume
  bool check_crossings = true;  ///< no two faces cross, no edge off the faces pierces a face
  std::size_t max_named = 10;   ///< elements named in each failure's message (all are listed)
};

/// One way the certificate failed: its kind, a message naming the elements, and the elements.
struct certificate_failure {
  enum class kind : std::uint8_t {
    unused_input_edge,        ///< input edges on a cycle of the wireframe that lie on no face
    seam_edge,                ///< edges on exactly two coplanar faces: a seam, not an edge of a solid
    open_volume,              ///< a volume whose faces use an edge once, three times or twice one way
    non_manifold_volume,      ///< a volume using an edge four or more times, or pinched at a vertex
    inverted_volume,          ///< a closed volume whose signed volume is zero or negative
    faces_cross,              ///< two faces meeting other than along shared edges or at shared vertices
    input_edge_pierces_face,  ///< an input edge off the faces meets a face other than at its ends
    edge_pierces_face,        ///< a complex edge on no face meets a face other than at its ends
  };
  kind what{};
  std::string message;
  /// By kind: input edges (wireframe numbering); edges; (volume, edge or vertex) pairs; volumes;
  /// (face, face) pairs; (input edge, face) pairs; (edge, face) pairs. Complex numbering otherwise.
  std::vector<std::uint32_t> elements;
};

/// The name of a failure kind ("unused input edge", ...). O(1).
constexpr const char* to_string(certificate_failure::kind k) noexcept {
  using K = certificate_failure::kind;
  switch (k) {
    case K::unused_input_edge:
      return "unused input edge";
    case K::seam_edge:
      return "seam edge";
    case K::open_volume:
      return "open volume";
    case K::non_manifold_volume:
      return "non-manifold volume";
    case K::inverted_volume:
      return "inverted volume";
    case K::faces_cross:
      return "faces cross";
    case K::input_edge_pierces_face:
      return "input edge pierces face";
    case K::edge_pierces_face:
      return "edge pierces face";
  }
  return "?";
}

/// What certify found: ok() when every check ran to the end and none failed; the failures, one
/// per kind, and what was counted on the way.
struct certificate_result : stage_report {
  std::vector<certificate_failure> failures;
  bool ok() const noexcept { return complete && failures.empty(); }
  explicit operator bool() const noexcept { return ok(); }
  /// The failure of kind k, or nullptr. O(kinds).
  const certificate_failure* find(certificate_failure::kind k) const noexcept {
    for (const auto& f : failures)
      if (f.what == k) return &f;
    return nullptr;
  }
  /// One line: the first failure's message, "work budget exhausted", or "" when ok. O(1).
  std::string reason() const {
    if (!failures.empty()) return failures.front().message;
    return complete ? std::string() : std::string("the certificate's work budget ran out");
  }

  // The complex.
  std::size_t faces_without_volume = 0;  ///< faces bounding no volume (allowed in a 3DCL; not solid)
  std::size_t free_edges = 0;            ///< edges on one face only, that face bounding no volume
  std::size_t dangling_edges = 0;        ///< edges on no face
  std::size_t seam_edges = 0;            ///< edges on two coplanar faces
  // The input edges (wireframe numbering).
  std::size_t input_edges = 0;
  std::size_t covered_input_edges = 0;            ///< on faces: one complex edge, or a collinear chain
  std::size_t split_input_edges = 0;              ///< of those, covered by a chain of two or more edges
  std::size_t zero_length_input_edges = 0;        ///< ends at one complex vertex (not a failure)
  std::size_t duplicate_input_edges = 0;          ///< joining the same two vertices as an earlier one
  std::vector<std::uint32_t> unused_input_edges;  ///< on a cycle, on no face (each a failure)
  /// On no cycle of the wireframe (a dangling tree or a bridge between cycles): they cannot bound
  /// a face, so lying on none is no failure; they are still tested against the faces.
  std::vector<std::uint32_t> acyclic_input_edges;
  // The crossing test.
  std::size_t face_pairs_tested = 0;      ///< face (or face-edge) pairs with overlapping boxes
  std::size_t triangle_pairs_tested = 0;  ///< of those decided triangle by triangle
};

namespace detail::certify {
/// The wireframe as certify reads it: positions and edges in the caller's numbering.
struct input_wire {
  std::vector<glm::dvec3> points;
  std::vector<std::array<std::uint32_t, 2>> edges;
};
/// certify on double positions (one copy for every point type); in certify_impl.hpp.
template <class = void>
certificate_result run(const cell_topology& cc, std::span<const glm::dvec3> pts, const input_wire* wire,
                       const certify_options& options);
}  // namespace detail::certify

/// Certifies a complex against its own invariants only: genuine edges, closed oriented manifold
/// volumes of positive volume, no crossing faces, no faceless edge through a face.
/// O(n log n + pairs of faces with overlapping boxes · their sizes), n = size of c.
template <Point3 P>
certificate_result certify(const cell_complex<P>& c, const certify_options& options = {}) {
  const detail::cells::dvec3_points<P> pts(c.points());
  return detail::certify::run(c, pts.span(), nullptr, options);
}

/// Certifies a complex as the answer for `wire`: the checks above, and every input edge (in the
/// wireframe's numbering) on a face, matched by position (merge tolerance; split edges accepted
/// as collinear chains); input edges on no cycle are listed, not failed. O(n log n + V + E +
/// pairs of faces with overlapping boxes · their sizes) for a wireframe of V vertices, E edges.
template <Point3 P, Wireframe G>
certificate_result certify(const cell_complex<P>& c, const G& wire, const certify_options& options = {}) {
  using T = wireframe_traits<G>;
  const detail::cells::dvec3_points<P> pts(c.points());
  detail::certify::input_wire in;
  const std::size_t nv = T::num_vertices(wire), ne = T::num_edges(wire);
  in.points.reserve(nv);
  for (std::size_t v = 0; v < nv; ++v) in.points.push_back(to_dvec3(T::position(wire, v)));
  in.edges.reserve(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    const auto ab = T::endpoints(wire, e);
    in.edges.push_back({static_cast<std::uint32_t>(ab[0]), static_cast<std::uint32_t>(ab[1])});
  }
  return detail::certify::run(c, pts.span(), &in, options);
}

}  // namespace cellforge

#include "cellforge/cells/detail/certify_impl.hpp"
