// Real meshes as wireframe fixtures (issue 38): a polygon mesh nobody here made becomes a
// wireframe (its creases, boundary and non-manifold edges), the cell complex it stands for
// (its faces merged across flat edges, a volume per clean closed component) and a description
// of what it is (closed, open, self-intersecting, non-manifold, degenerate). Used by
// tests/test_real_meshes.cpp on CGAL's demo meshes (scripts/fetch-cgal-data.sh).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/algorithms/self_intersections.hpp"
#include "cellforge/core/detail/union_find.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/predicates.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/wireframe/wire_graph.hpp"

namespace real_mesh {

/// What a mesh is, worst first: the class a mesh is tabled under is the first that applies.
/// `rimmed`: open, but every boundary loop is a planar rim and the lids close every component
/// into a clean solid: its wireframe is that solid's (an open box's is a box's).
/// `nearly_planar`: closed and clean but for polygons off their planes beyond rounding, all
/// far flatter than any bend between neighbouring faces (decimal noise on flat quads): the
/// wireframe still draws a solid, whose faces are the polygons.
enum class mesh_class { degenerate, non_manifold, self_intersecting, open, rimmed, nearly_planar, closed };

inline const char* class_name(mesh_class c) {
  switch (c) {
    case mesh_class::degenerate:
      return "degenerate";
    case mesh_class::non_manifold:
      return "non-manifold";
    case mesh_class::self_intersecting:
      return "self-intersecting";
    case mesh_class::open:
      return "open";
    case mesh_class::rimmed:
      return "open, planar rims";
    case mesh_class::nearly_planar:
      return "closed, nearly planar";
    case mesh_class::closed:
      return "closed";
  }
  return "?";
}

/// A mesh as a wireframe fixture: the wireframe, its truth and what the mesh is.
struct fixture {
  cellforge::wireframe<glm::dvec3> wire;
  /// The faces of the truth as sorted sets of wireframe vertices: the mesh's faces merged
  /// across edges between coplanar faces (holes included), every face of the mesh.
  std::vector<std::vector<std::uint32_t>> faces;
  /// For each truth face, whether it belongs to a clean closed component (one that bounds a volume).
  std::vector<char> face_in_solid;
  std::size_t volumes = 0;  ///< clean closed components: closed, manifold, not self-intersecting

  // What the mesh is.
  std::size_t mesh_vertices = 0, mesh_faces = 0;
  std::size_t duplicate_vertices = 0;     ///< vertices at exactly the position of an earlier one (welded)
  std::size_t repeated_corner_faces = 0;  ///< faces using one vertex twice after welding (dropped)
  std::size_t zero_area_faces = 0;        ///< faces whose corners are all collinear, exactly (dropped)
  std::size_t non_planar_faces =
      0;  ///< polygons with a corner off their plane by more than the rounding tolerance
  std::size_t nearly_planar_faces = 0;  ///< polygons planar within the rounding tolerance, not exactly
  /// The largest departure of a non-planar polygon from its plane, over its longest edge (the
  /// sine of its corners' tilt; 0: none), and the smallest bend between two faces across a
  /// wireframe edge (the sine of their planes' angle; 1 when there is none).
  double flatness = 0.0, smallest_bend = 1.0;
  std::size_t boundary_edges = 0, boundary_loops = 0;
  /// Boundary loops that are simple and exactly planar: the wireframe holds the cycle of a face
  /// across each (the lid), so it reads as the mesh with those lids (an open box is a box).
  std::size_t planar_rims = 0;
  std::size_t non_manifold_edges = 0;     ///< edges of three or more faces
  std::size_t non_manifold_vertices = 0;  ///< vertices whose faces form more than one fan
  std::size_t folded_edges = 0;           ///< two coplanar faces on the same side of their edge
  std::size_t flat_edges = 0;             ///< edges between exactly coplanar faces (not in the wireframe)
  std::size_t nearly_flat_edges =
      0;  ///< between faces coplanar within the rounding tolerance only (merged too)
  std::size_t intersecting_face_pairs = 0;
  bool intersections_known = true;  ///< false when the exact check could not run (non-manifold edges, budget)
  std::size_t components = 0, closed_components = 0;
  mesh_class kind = mesh_class::closed;
  std::string notes;  ///< the figures above that are not zero, for the sweep's table

  bool open() const { return boundary_edges > 0; }
  /// Open, but every boundary loop is a planar rim: the wireframe is that of the mesh with lids.
  bool lidded() const { return open() && planar_rims == boundary_loops; }
  bool self_intersecting() const { return intersecting_face_pairs > 0 || folded_edges > 0; }
};

namespace detail {

using cellforge::detail::union_find;

/// All corners on one line, exactly (every coordinate projection of every triple is flat).
inline bool collinear(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return cellforge::orient2d(a.x, a.y, b.x, b.y, c.x, c.y) == 0 &&
         cellforge::orient2d(a.y, a.z, b.y, b.z, c.y, c.z) == 0 &&
         cellforge::orient2d(a.z, a.x, b.z, b.x, c.z, c.x) == 0;
}

}  // namespace detail

inline fixture make_fixture(const cellforge::polygon_soup<glm::dvec3>& soup);

namespace detail {

/// make_fixture's engine. Vertices at exactly one position are welded (the
/// wireframe reader would merge them anyway); faces that repeat a vertex or have no area
/// (collinear corners, decided exactly) are dropped and make the mesh degenerate. Two faces
/// sharing an edge are coplanar when every corner of both lies on one plane by exact orient3d,
/// or, failing that, within 1e-9 of the bounding-box diagonal (the pipeline's planarity
/// tolerance) of both faces' planes and of the planes of the groups they join: a flat face
/// written in decimal text is rarely exactly flat, and the pipeline cannot tell such faces
/// from coplanar ones, where an edge in between would stand for a wall meeting the face
/// (counted in nearly_flat_edges). Coplanar faces on opposite sides of their edge merge into
/// one face and the edge leaves the wireframe; on the same side they fold (self-intersecting).
/// A polygon with a corner farther than the tolerance from its plane is non-planar (degenerate).
/// O(n log n) for n corners, plus the exact self-intersection check.
/// `keep` (sorted (lo, hi) vertex pairs of the soup, after welding) are edges that stay in the
/// wireframe and are never merged across (a lid's rim); the planar rims go to `rims`.
inline fixture analyse(const cellforge::polygon_soup<glm::dvec3>& soup,
                       const std::vector<std::array<std::uint32_t, 2>>& keep,
                       std::vector<std::vector<std::uint32_t>>* rims) {
  using glm::dvec3;
  fixture fx;
  fx.mesh_vertices = soup.num_points();
  fx.mesh_faces = soup.num_faces();
  const auto& pts = soup.points;

  // Weld exact duplicates: sort by position, the first index of a run represents it.
  std::vector<std::uint32_t> rep(pts.size());
  {
    std::vector<std::uint32_t> order(pts.size());
    std::iota(order.begin(), order.end(), 0u);
    auto less = [&](std::uint32_t a, std::uint32_t b) {
      const dvec3 &p = pts[a], &q = pts[b];
      return p.x != q.x ? p.x < q.x : p.y != q.y ? p.y < q.y : p.z != q.z ? p.z < q.z : a < b;
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t i = 0; i < order.size(); ++i) {
      const bool same = i > 0 && pts[order[i]] == pts[order[i - 1]];
      rep[order[i]] = same ? rep[order[i - 1]] : order[i];
      fx.duplicate_vertices += same;
    }
  }

  // Clean faces: welded corners, consecutive repeats removed; repeats and no area drop a face.
  std::vector<std::vector<std::uint32_t>> faces;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    std::vector<std::uint32_t> loop;
    for (const auto v : soup.face(f))
      if (loop.empty() || rep[v] != loop.back()) loop.push_back(rep[v]);
    while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
    std::vector<std::uint32_t> sorted = loop;
    std::sort(sorted.begin(), sorted.end());
    if (loop.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      ++fx.repeated_corner_faces;
      continue;
    }
    bool area = false;
    for (std::size_t k = 2; k < loop.size() && !area; ++k)
      area = !detail::collinear(pts[loop[0]], pts[loop[1]], pts[loop[k]]);
    if (!area) {
      ++fx.zero_area_faces;
      continue;
    }
    faces.push_back(std::move(loop));
  }
  const std::size_t nf = faces.size();

  // Each face's plane: three corners not on a line. planar[f]: 2 when every corner is on it
  // exactly, 1 within the rounding tolerance, 0 beyond (a non-planar polygon).
  const dvec3 lo_box = [&] {
    dvec3 m(std::numeric_limits<double>::infinity());
    for (const auto& p : pts) m = glm::min(m, p);
    return m;
  }();
  const dvec3 hi_box = [&] {
    dvec3 m(-std::numeric_limits<double>::infinity());
    for (const auto& p : pts) m = glm::max(m, p);
    return m;
  }();
  const double tol = pts.empty() ? 0.0 : 1e-9 * glm::length(hi_box - lo_box);  // the pipeline's planarity
  std::vector<std::array<std::uint32_t, 3>> frame(nf);
  std::vector<dvec3> unit_normal(nf);
  std::vector<char> planar(nf, 2), face_bad(nf, 0);
  auto distance = [&](std::uint32_t f, const dvec3& p) {
    return std::abs(glm::dot(unit_normal[f], p - pts[frame[f][0]]));
  };
  for (std::uint32_t f = 0; f < nf; ++f) {
    const auto& l = faces[f];
    std::size_t k = 2;
    while (detail::collinear(pts[l[0]], pts[l[1]], pts[l[k]])) ++k;  // some k has area
    frame[f] = {l[0], l[1], l[k]};
    unit_normal[f] = glm::normalize(glm::cross(pts[l[1]] - pts[l[0]], pts[l[k]] - pts[l[0]]));
    for (const auto v : l)
      if (cellforge::orient3d(pts[l[0]], pts[l[1]], pts[l[k]], pts[v]) != 0) planar[f] = 1;
    if (planar[f] == 2) continue;
    for (const auto v : l)
      if (distance(f, pts[v]) > tol) planar[f] = 0;
    if (planar[f] == 0) {
      ++fx.non_planar_faces;  // bad unless the mesh is nearly planar (decided below)
      double longest = 0.0, off = 0.0;
      for (std::size_t k = 0; k < l.size(); ++k) {
        longest = std::max(longest, glm::length(pts[l[(k + 1) % l.size()]] - pts[l[k]]));
        off = std::max(off, distance(f, pts[l[k]]));
      }
      fx.flatness = std::max(fx.flatness, off / longest);
    } else {
      ++fx.nearly_planar_faces;
    }
  }

  // Edges: (lo, hi, face) sorted, a run per edge.
  struct side {
    std::uint32_t lo, hi, face, from;
  };
  std::vector<side> sides;
  for (std::uint32_t f = 0; f < nf; ++f) {
    const auto& l = faces[f];
    for (std::size_t k = 0; k < l.size(); ++k) {
      const std::uint32_t a = l[k], b = l[(k + 1) % l.size()];
      sides.push_back({std::min(a, b), std::max(a, b), f, a});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const side& x, const side& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.face < y.face;
  });
  // Per vertex, its corners' fans: union of (vertex, face) corners across manifold edges.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> corners;  // (vertex, face), sorted
  for (std::uint32_t f = 0; f < nf; ++f)
    for (const auto v : faces[f]) corners.push_back({v, f});
  std::sort(corners.begin(), corners.end());
  auto corner_id = [&](std::uint32_t v, std::uint32_t f) {
    return static_cast<std::uint32_t>(std::lower_bound(corners.begin(), corners.end(), std::make_pair(v, f)) -
                                      corners.begin());
  };
  detail::union_find fans(corners.size()), flat(nf), component(nf);
  std::vector<std::array<std::uint32_t, 2>> wire_edges, boundary;
  std::vector<char> face_open(nf, 0);
  std::vector<std::uint32_t> plane_of(nf);  // per group root, the face whose plane the group keeps
  std::iota(plane_of.begin(), plane_of.end(), 0u);
  for (std::size_t b = 0, e = 0; b < sides.size(); b = e) {
    while (e < sides.size() && sides[e].lo == sides[b].lo && sides[e].hi == sides[b].hi) ++e;
    const std::size_t n = e - b;
    const std::uint32_t u = sides[b].lo, v = sides[b].hi;
    for (std::size_t i = b + 1; i < e; ++i) component.unite(sides[b].face, sides[i].face);
    if (n == 1) {
      ++fx.boundary_edges;
      boundary.push_back({u, v});
      face_open[sides[b].face] = 1;
      wire_edges.push_back({u, v});
      continue;
    }
    if (n > 2) {
      ++fx.non_manifold_edges;
      for (std::size_t i = b; i < e; ++i) face_bad[sides[i].face] = 1;
      wire_edges.push_back({u, v});
      continue;
    }
    const std::uint32_t f = sides[b].face, g = sides[b + 1].face;
    fans.unite(corner_id(u, f), corner_id(u, g));
    fans.unite(corner_id(v, f), corner_id(v, g));
    // Coplanar: every corner of both on one plane, exactly; or, failing that, within the
    // rounding of the coordinates (the pipeline's planarity tolerance), and within it of both
    // merged groups' planes too, so that a gently curved surface does not merge into one face.
    const auto& pf = frame[f];
    bool exact = planar[f] == 2 && planar[g] == 2;
    for (std::size_t k = 0; k < 3 && exact; ++k)
      exact = cellforge::orient3d(pts[pf[0]], pts[pf[1]], pts[pf[2]], pts[frame[g][k]]) == 0;
    bool near = false;
    if (!exact && planar[f] && planar[g]) {
      const auto rf = plane_of[flat.find(f)], rg = plane_of[flat.find(g)];
      near = true;
      for (const auto h : {f, g})
        for (const auto r : {f, g, rf, rg})
          for (const auto w : faces[h]) near = near && distance(r, pts[w]) <= tol;
    }
    const bool kept = std::binary_search(keep.begin(), keep.end(), std::array<std::uint32_t, 2>{u, v});
    if (exact || near) {
      // The far corners: a corner of each face off the line uv.
      auto off_line = [&](std::uint32_t face) {
        for (const auto w : frame[face])
          if (!detail::collinear(pts[u], pts[v], pts[w])) return w;
        return frame[face][2];
      };
      // Seen along the axis nearest f's normal, where neither far corner's triangle with uv
      // collapses (a nearly coplanar pair seen edge-on would get its sides by rounding).
      const dvec3 n = glm::abs(unit_normal[f]);
      const int axis = n.x >= n.y && n.x >= n.z ? 0 : n.y >= n.z ? 1 : 2;
      const int uu = (axis + 1) % 3, ww = (axis + 2) % 3;
      const dvec3 &a = pts[u], &c = pts[v], &b = pts[off_line(f)], &d = pts[off_line(g)];
      const int sf = cellforge::orient2d(a[uu], a[ww], c[uu], c[ww], b[uu], b[ww]);
      const int sg = cellforge::orient2d(a[uu], a[ww], c[uu], c[ww], d[uu], d[ww]);
      if (sf * sg < 0 && !kept) {
        ++(exact ? fx.flat_edges : fx.nearly_flat_edges);
        const auto keep_plane = plane_of[flat.find(f)];
        flat.unite(f, g);
        plane_of[flat.find(f)] = keep_plane;
        continue;
      }
      if (sf * sg > 0) {
        ++fx.folded_edges;  // the two faces overlap beyond the edge
        face_bad[f] = face_bad[g] = 1;
      }
    }
    fx.smallest_bend = std::min(fx.smallest_bend, glm::length(glm::cross(unit_normal[f], unit_normal[g])));
    wire_edges.push_back({u, v});
  }
  for (std::size_t b = 0, e = 0; b < corners.size(); b = e) {
    while (e < corners.size() && corners[e].first == corners[b].first) ++e;
    std::size_t roots = 0;
    for (std::size_t i = b; i < e; ++i) roots += fans.find(static_cast<std::uint32_t>(i)) == i;
    if (roots > 1) {
      ++fx.non_manifold_vertices;
      for (std::size_t i = b; i < e; ++i) face_bad[corners[i].second] = 1;
    }
  }
  // Boundary loops: components of the boundary edges; a simple, exactly planar one is a rim.
  {
    detail::union_find loops(pts.size());
    std::vector<std::uint32_t> degree(pts.size(), 0);
    for (const auto& [a, b] : boundary) loops.unite(a, b), ++degree[a], ++degree[b];
    std::vector<std::vector<std::uint32_t>> next(pts.size());
    for (const auto& [a, b] : boundary) next[a].push_back(b), next[b].push_back(a);
    std::vector<char> simple(pts.size(), 1), seen(pts.size(), 0);
    for (std::uint32_t v = 0; v < pts.size(); ++v)
      if (degree[v] > 0 && degree[v] != 2) simple[loops.find(v)] = 0;
    for (std::uint32_t v = 0; v < pts.size(); ++v) {
      if (degree[v] == 0 || loops.find(v) != v) continue;
      ++fx.boundary_loops;
    }
    for (std::uint32_t v = 0; v < pts.size(); ++v) {
      if (degree[v] == 0 || seen[loops.find(v)] || !simple[loops.find(v)]) continue;
      seen[loops.find(v)] = 1;
      std::vector<std::uint32_t> loop{v};
      for (std::uint32_t prev = v, at = next[v][0]; at != v;) {
        loop.push_back(at);
        const std::uint32_t to = next[at][0] == prev ? next[at][1] : next[at][0];
        prev = at;
        at = to;
      }
      std::size_t k = 2;
      while (k < loop.size() && collinear(pts[loop[0]], pts[loop[1]], pts[loop[k]])) ++k;
      bool flat = k < loop.size();
      for (std::size_t i = 0; i < loop.size() && flat; ++i)
        flat = cellforge::orient3d(pts[loop[0]], pts[loop[1]], pts[loop[k]], pts[loop[i]]) == 0;
      if (!flat) continue;
      ++fx.planar_rims;
      if (rims) rims->push_back(std::move(loop));
    }
  }

  // Self-intersections, exactly, when the faces make a half-edge mesh (edge-manifold).
  if (fx.non_manifold_edges == 0 && nf > 0) {
    cellforge::polygon_soup<dvec3> clean;
    clean.points = pts;
    for (const auto& l : faces) clean.add_face(l);
    try {
      cellforge::build_options split;
      split.split_nonmanifold_vertices = true;  // their copies touch: counted as intersections
      const auto m = cellforge::make_mesh(clean, nullptr, split);
      cellforge::self_intersection_options options;
      options.max_reported = std::size_t(-1);
      // Gears and blades have long thin triangles sharing many grid cells: pinion.off needs
      // more than the default 256 pairs per triangle.
      options.work_budget = std::size_t{1} << 28;
      const auto si = cellforge::self_intersections(m, options);
      fx.intersections_known = si.complete;
      fx.intersecting_face_pairs = si.intersecting_face_pairs;
      for (const auto& [a, b] : si.face_pairs) face_bad[a.idx()] = face_bad[b.idx()] = 1;
    } catch (const cellforge::error&) {
      fx.intersections_known = false;
    }
  } else {
    fx.intersections_known = nf == 0;
  }

  // Nearly planar: non-planar polygons (nothing else wrong with the faces), each flatter by two
  // decades than the smallest bend between faces, so that their noise never reads as a bend.
  // Only a mesh clean in every other way is tabled so.
  const bool nearly_planar = fx.non_planar_faces > 0 && fx.repeated_corner_faces + fx.zero_area_faces == 0 &&
                             100.0 * fx.flatness <= fx.smallest_bend &&
                             fx.non_manifold_edges + fx.non_manifold_vertices == 0 &&
                             !fx.self_intersecting() && fx.intersections_known && !fx.open();
  if (!nearly_planar)
    for (std::uint32_t f = 0; f < nf; ++f) face_bad[f] |= planar[f] == 0;

  // Components and their volumes.
  std::vector<char> comp_open(nf, 0), comp_bad(nf, 0);
  for (std::uint32_t f = 0; f < nf; ++f) {
    const auto c = component.find(f);
    comp_open[c] |= face_open[f];
    comp_bad[c] |= face_bad[f];
  }
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (component.find(f) != f) continue;
    ++fx.components;
    fx.closed_components += !comp_open[f];
    fx.volumes += !comp_open[f] && !comp_bad[f] && fx.intersections_known;
  }

  // The wireframe: vertices of its edges, renumbered in the mesh's order.
  std::vector<std::uint32_t> id(pts.size(), cellforge::no_index);
  for (const auto& e : wire_edges)
    for (const auto v : e) id[v] = 0;
  for (std::uint32_t v = 0; v < pts.size(); ++v)
    if (id[v] == 0) {
      id[v] = static_cast<std::uint32_t>(fx.wire.points.size());
      fx.wire.points.push_back(pts[v]);
    }
  std::sort(wire_edges.begin(), wire_edges.end());
  for (const auto& [a, b] : wire_edges) fx.wire.edges.push_back({id[a], id[b]});

  // Truth faces: groups of flat-joined faces; a group's vertices are those on wireframe edges.
  std::vector<std::vector<std::uint32_t>> group(nf);
  for (std::uint32_t f = 0; f < nf; ++f)
    for (const auto v : faces[f])
      if (id[v] != cellforge::no_index) group[flat.find(f)].push_back(id[v]);
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (flat.find(f) != f) continue;
    auto& s = group[f];
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
    const auto c = component.find(f);
    fx.faces.push_back(std::move(s));
    fx.face_in_solid.push_back(!comp_open[c] && !comp_bad[c] && fx.intersections_known);
  }

  // The class, worst first.
  const bool bad_faces = fx.repeated_corner_faces + fx.zero_area_faces + fx.non_planar_faces > 0;
  fx.kind = nearly_planar                                          ? mesh_class::nearly_planar
            : bad_faces                                            ? mesh_class::degenerate
            : fx.non_manifold_edges + fx.non_manifold_vertices > 0 ? mesh_class::non_manifold
            : fx.self_intersecting() || !fx.intersections_known    ? mesh_class::self_intersecting
            : fx.open()                                            ? mesh_class::open
                                                                   : mesh_class::closed;
  auto add = [&](std::size_t n, const char* what) {
    if (n == 0) return;
    if (!fx.notes.empty()) fx.notes += ", ";
    fx.notes += std::to_string(n) + " " + what;
  };
  add(fx.duplicate_vertices, "duplicate vertices (welded)");
  add(fx.repeated_corner_faces, "faces repeating a vertex (dropped)");
  add(fx.zero_area_faces, "zero-area faces (dropped)");
  add(fx.non_planar_faces, "non-planar faces");
  if (fx.non_planar_faces > 0) {
    char figures[96];
    std::snprintf(figures, sizeof figures, " (flat to %.2g of their edges; the smallest bend %.2g)",
                  fx.flatness, fx.smallest_bend);
    fx.notes += figures;
  }
  add(fx.non_manifold_edges, "non-manifold edges");
  add(fx.non_manifold_vertices, "non-manifold vertices");
  add(fx.folded_edges, "folded edges");
  add(fx.intersecting_face_pairs, "intersecting face pairs");
  if (!fx.intersections_known) add(1, "self-intersection check not run");
  add(fx.boundary_loops, "boundary loops");
  add(fx.planar_rims, "planar rims");
  add(fx.nearly_planar_faces, "faces planar within rounding only");
  add(fx.nearly_flat_edges, "edges flat within rounding only (merged)");
  if (fx.components > 1) add(fx.components, "components");
  return fx;
}

}  // namespace detail

/// Converts a polygon soup to a fixture (see detail::analyse for the rules). Planar rims
/// (simple, exactly planar boundary loops) are read as the wireframe reads them: the truth is
/// that of the mesh with a lid across each rim (the rim edges stay in the wireframe, unmerged),
/// so an open box is a box and a lid coplanar with its neighbours folds onto them (no volume);
/// every count but the truth's describes the mesh as given. O(n log n) for n corners, plus the
/// exact self-intersection check, twice when there are rims.
inline fixture make_fixture(const cellforge::polygon_soup<glm::dvec3>& soup) {
  std::vector<std::vector<std::uint32_t>> rims;
  fixture fx = detail::analyse(soup, {}, &rims);
  if (rims.empty()) return fx;
  // Welded indices are indices into soup.points (a run's first), so the lids use them as they are.
  cellforge::polygon_soup<glm::dvec3> lidded = soup;
  std::vector<std::array<std::uint32_t, 2>> keep;
  for (const auto& rim : rims) {
    lidded.add_face(rim);
    for (std::size_t k = 0; k < rim.size(); ++k) {
      const std::uint32_t a = rim[k], b = rim[(k + 1) % rim.size()];
      keep.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(keep.begin(), keep.end());
  fixture with_lids = detail::analyse(lidded, keep, nullptr);
  if (with_lids.wire.edges != fx.wire.edges || with_lids.wire.points != fx.wire.points)
    throw std::logic_error("make_fixture: the lids changed the wireframe");  // a bug here, not in the mesh
  fx.faces = std::move(with_lids.faces);
  fx.face_in_solid = std::move(with_lids.face_in_solid);
  fx.volumes = with_lids.volumes;
  if (fx.kind == mesh_class::open && fx.lidded() && fx.volumes == fx.components) fx.kind = mesh_class::rimmed;
  return fx;
}

}  // namespace real_mesh
