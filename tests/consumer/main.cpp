// SPDX-License-Identifier: MIT
// A CAD application's use of cellforge, against the installed package: its own point types
// (cad::Vector3: private members, no default constructor; cad::Vec3f: floats) and wire model
// (cad.hpp) go through every job of the library and every reader and writer, and each result
// comes back in the application's own types. The application never includes the vector
// library cellforge computes with (CMakeLists.txt checks that these sources never name it).
// Usage: consumer [scratch-dir]
#include <cellforge/cellforge.hpp>
#include <cellforge/io/cells_io.hpp>
#include <cellforge/io/curves_io.hpp>
#include <cellforge/io/edge_list.hpp>
#include <cellforge/io/mesh_io.hpp>
#include <cellforge/io/svg.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ranges>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "cad.hpp"

namespace fs = std::filesystem;
namespace cf = cellforge;

namespace {

int failures = 0;
void expect(bool ok, const char* type, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "consumer: FAILED [%s]: %s\n", type, what);
    ++failures;
  }
}

/// The type of a result, without reference and const, is P.
template <class P, class T>
inline constexpr bool is_p = std::is_same_v<std::remove_cvref_t<T>, P>;

/// The element type of a range.
template <class R>
using elem = std::ranges::range_value_t<R>;

template <class A, class B>
double dist(const A& a, const B& b) {
  double s = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const double d = static_cast<double>(cf::coord(a, i)) - static_cast<double>(cf::coord(b, i));
    s += d * d;
  }
  return std::sqrt(s);
}
template <class A>
double norm(const A& a) {
  return dist(a, cad::make<cad::Vec3f>(0, 0, 0));
}
bool near(double a, double b, double tol) { return std::abs(a - b) <= tol; }

template <class T>
std::span<const T> cspan(const std::vector<T>& v) {
  return v;
}

/// The same points and faces, bit for bit.
template <class P>
bool same_soup(const cf::polygon_soup<P>& a, const cf::polygon_soup<P>& b) {
  if (a.points.size() != b.points.size() || a.face_vertices != b.face_vertices ||
      a.face_offsets != b.face_offsets)
    return false;
  for (std::size_t i = 0; i < a.points.size(); ++i)
    if (dist(a.points[i], b.points[i]) != 0) return false;
  return true;
}

std::string head(const fs::path& p, std::size_t n) {
  std::ifstream in(p, std::ios::binary);
  std::string s(n, '\0');
  in.read(s.data(), static_cast<std::streamsize>(n));
  s.resize(static_cast<std::size_t>(in.gcount()));
  return s;
}

/// Volume enclosed by a closed outward mesh, through the library's own cell complex.
template <class P>
double enclosed_volume(const cf::surface_mesh<P>& m) {
  const auto cc = cf::mesh_to_cell_complex(m);
  // the complex of a mesh in the mesh's point type.
  static_assert(is_p<P, decltype(cc.point(cf::cell_vertex(0)))>);
  const auto v = cf::validate(cc);
  return v.ok() && cc.num_volumes() == 1 ? v.signed_volumes[0] : -1;
}

template <class P>
void run(const char* T, const fs::path& dir) {
  using S = cf::scalar_t<P>;
  const double eps = std::is_same_v<S, float> ? 1e-5 : 1e-12;

  // --- make_mesh from a polygon soup, circulators, validate, mesh geometry
  const auto box_soup = cad::box<P>(2, 1, 0.5);
  auto box = cf::make_mesh(box_soup);
  static_assert(is_p<P, decltype(box.position(cf::vertex_handle(0)))>);
  expect(cf::validate(box).ok() && cf::is_orientable(box), T, "box: valid, orientable");
  expect(box.num_vertices() == 8 && box.num_edges() == 12 && box.num_faces() == 6, T, "box: 8 V, 12 E, 6 F");
  expect(cf::euler_characteristic(box) == 2 && cf::connected_components(box).count == 1, T,
         "box: Euler 2, one component");
  std::size_t fans = 0, ring = 0, loop = 0;
  for (const auto f : box.faces_around(cf::vertex_handle(7))) fans += f.is_valid() ? 1 : 0;
  for (const auto v : box.vertices_around(cf::vertex_handle(7))) ring += v.is_valid() ? 1 : 0;
  for (const auto v : box.vertices_around(cf::face_handle(0))) loop += v.idx() < 8 ? 1 : 0;
  expect(fans == 3 && ring == 3 && loop == 4, T,
         "circulators: 3 faces and 3 neighbours at a corner, 4 per face");
  expect(box.boundary_loops().empty(), T, "box: no boundary");
  const auto [lo, hi] = cf::bounds(box);
  static_assert(is_p<P, decltype(lo)>);
  expect(dist(lo, cad::make<P>(0, 0, 0)) == 0 && dist(hi, cad::make<P>(2, 1, 0.5)) == 0, T, "box: bounds");
  expect(near(cf::surface_area(box), 2 * (2 + 1 + 0.5), eps), T, "box: area 7");
  const auto n0 = cf::face_normal(box, cf::face_handle(0));
  static_assert(is_p<P, decltype(n0)>);
  expect(dist(n0, cad::make<P>(0, 0, -1)) < eps, T, "box: bottom normal -z");
  const auto vn = cf::vertex_normals(box);
  static_assert(is_p<P, elem<decltype(vn)>>);
  expect(vn.size() == 8 && near(norm(vn[7]), 1, eps) && cf::coord(vn[7], 0) > 0, T, "box: vertex normals");
  expect(dist(cf::face_centroid(box, cf::face_handle(1)), cad::make<P>(1, 0.5, 0.5)) < eps, T,
         "box: centroid");
  expect(near(enclosed_volume(box), 1, eps), T, "box: volume 1");

  // --- Loop subdivision and simplification
  auto octa = cf::make_mesh(cad::octahedron<P>());
  const cf::loop_subdivision_result lr = cf::loop_subdivide(octa, {.levels = 2});
  expect(lr.faces_after == 128 && octa.num_faces() == 128 && octa.num_vertices() == 66, T,
         "loop: 8 -> 128 faces, 66 vertices");
  expect(cf::validate(octa).ok() && cf::euler_characteristic(octa) == 2, T, "loop: valid, Euler 2");
  double rmin = 1, rmax = 0;
  for (const auto v : octa.vertices()) {
    rmin = std::min(rmin, norm(octa.position(v)));
    rmax = std::max(rmax, norm(octa.position(v)));
  }
  expect(rmin > 0.42 && rmax < 0.46, T, "loop: points moved in to radius 0.44 +- 0.01");
  const auto sub = cf::loop_subdivided(octa);
  static_assert(is_p<P, decltype(sub.position(cf::vertex_handle(0)))>);
  expect(sub.num_faces() == 512, T, "loop_subdivided: 512 faces");
  const cf::simplify_result sr = cf::simplify(octa, {.target_faces = 32});
  expect(sr.reached_target && octa.num_faces() <= 32 && octa.num_faces() >= 8, T, "simplify: to <= 32 faces");
  expect(cf::validate(octa).ok() && cf::euler_characteristic(octa) == 2, T, "simplify: valid, Euler 2");

  // --- convex hulls of a std::vector and a std::array of the user's points
  const auto glass_soup = cad::hourglass<P>(12, 15);
  const auto glass = cf::make_mesh(glass_soup);
  expect(cf::validate(glass).ok() && cf::euler_characteristic(glass) == 2, T, "hourglass: valid, Euler 2");
  const std::vector<P> cloud = glass_soup.points;
  const auto hull = cf::convex_hull(cloud);
  static_assert(is_p<P, decltype(hull.position(cf::vertex_handle(0)))>);
  expect(hull.num_vertices() == 24 && hull.num_faces() == 44 && cf::validate(hull).ok(), T,
         "hull of a vector: the two end rings, 24 V, 44 F");
  expect(near(enclosed_volume(hull), 12, 1e-4), T, "hull of a vector: volume 12");
  const std::array<P, 5> tet{cad::make<P>(0, 0, 0), cad::make<P>(1, 0, 0), cad::make<P>(0, 1, 0),
                             cad::make<P>(0, 0, 1), cad::make<P>(0.1, 0.1, 0.1)};
  const auto hull4 = cf::convex_hull(tet);
  static_assert(is_p<P, decltype(hull4.position(cf::vertex_handle(0)))>);
  expect(hull4.num_vertices() == 4 && hull4.num_faces() == 4 && near(enclosed_volume(hull4), 1.0 / 6, eps), T,
         "hull of an array: tetrahedron, volume 1/6");

  // --- wire models -> cell complexes
  const auto cube_wire = cad::block<P>(false), block_wire = cad::block<P>(true);
  const auto cube = cf::wireframe_to_cells(cube_wire);
  const auto blk = cf::wireframe_to_cells(block_wire);
  // the cells' points in the wire model's point type.
  static_assert(is_p<P, decltype(cube.cells.point(cf::cell_vertex(0)))>);
  const auto& cc = blk.cells;
  expect(cube.cells.num_vertices() == 8 && cube.cells.num_edges() == 12 && cube.cells.num_faces() == 6 &&
             cube.cells.num_volumes() == 1,
         T, "cube wire: 8 V, 12 E, 6 F, 1 volume");
  expect(cc.num_vertices() == 12 && cc.num_edges() == 20 && cc.num_faces() == 11 && cc.num_volumes() == 2 &&
             cc.num_objects() == 1,
         T, "block wire: 12 V, 20 E, 11 F, 2 volumes, 1 object");
  expect(cube.cells.object_euler(cf::cell_object(0)) == 1 && cc.object_euler(cf::cell_object(0)) == 1, T,
         "cells: V - E + F - C = 1");
  const auto cv = cf::validate(cc);
  expect(cv.ok() && cv.signed_volumes.size() == 2 && near(cv.signed_volumes[0], 1, eps) &&
             near(cv.signed_volumes[1], 1, eps),
         T, "block cells: valid, two unit volumes");
  expect(cf::validate(cube.cells).ok(), T, "cube cells: valid");
  bool back = blk.input_vertex.size() == cc.num_vertices();
  for (const auto v : cc.vertices())
    back = back && dist(cc.point(v), block_wire.node(blk.input_vertex[v.idx()])) == 0;
  expect(back, T, "block cells: every point is the wire model's node");

  // --- thin points and smoothing
  const auto thin = cf::find_thin_points(glass);
  // thin_result<P>: loop points in the mesh's point type.
  static_assert(is_p<P, elem<decltype(thin.loops.at(0).points)>>);
  expect(!thin.loops.empty(), T, "thin: the hourglass has a thin loop");
  if (!thin.loops.empty()) {
    const auto& neck = thin.loops.front();
    double z = 0;
    for (const auto& p : neck.points) z += cf::coord(p, 2);
    z /= static_cast<double>(neck.points.size());
    const double perimeter = 12 * 2 * 0.3 * std::sin(3.14159265358979323846 / 12);
    expect(std::abs(z) <= 4.0 / 14 && near(neck.length, perimeter, 0.05 * perimeter), T,
           "thin: the strongest loop is the neck at z = 0");
    expect(near(neck.axis_position, 0.5, 0.05), T, "thin: halfway along the axis");
  }
  const auto octa90 = cf::make_mesh(cad::octahedron<P>());
  const auto smooth = cf::smooth_edges(octa90, {.angle_deg = 90});
  // smooth_result<P>, edge_curve<P>: curve points in the mesh's point type.
  static_assert(is_p<P, decltype(smooth.curves.at(0).point(0.5))>);
  static_assert(is_p<P, elem<decltype(smooth.midpoints)>>);
  expect(smooth.curves.size() == 12 && smooth.num_surfaces == 1, T, "smooth: 12 curves, one surface");
  double worst = 0;
  for (const auto& c : smooth.curves) {
    worst = std::max(worst, std::abs(norm(c.point(0.5)) - 1));
    worst = std::max(worst, dist(c.point(0), octa90.position(cf::vertex_handle(c.v0))));
  }
  expect(worst < 3e-4, T, "smooth: octahedron edges become quarter circles on the unit sphere");
  const auto cube_smooth = cf::smooth_edges(cube.cells, cf::cell_volume(0));
  expect(cube_smooth.curves.size() == 12, T, "smooth: the cube cell's 12 edges");

  // --- readers and writers, through files in the scratch directory
  const std::string t = T;
  auto file = [&](const char* name) { return dir / (t + "_" + name); };
  cf::io::write_off(file("glass.off"), glass_soup);
  expect(same_soup(cf::io::read_off<P>(file("glass.off")), glass_soup), T, "OFF round trip");
  cf::io::write_obj(file("glass.obj"), glass_soup);
  expect(same_soup(cf::io::read_obj<P>(file("glass.obj")).soup, glass_soup), T, "OBJ round trip");
  cf::io::write_ply(file("glass_bin.ply"), glass_soup);
  cf::io::write_ply(file("glass_txt.ply"), glass_soup, {.format = cf::io::ply_format::ascii});
  expect(same_soup(cf::io::read_ply<P>(file("glass_bin.ply")), glass_soup) &&
             same_soup(cf::io::read_ply<P>(file("glass_txt.ply")), glass_soup) &&
             head(file("glass_txt.ply"), 16) == "ply\nformat ascii",
         T, "PLY binary and ASCII round trips");
  cf::io::write_stl(file("box_bin.stl"), box_soup);
  cf::io::write_stl(file("box_txt.stl"), box_soup, {.binary = false});
  for (const char* stl : {"box_bin.stl", "box_txt.stl"}) {
    const auto data = cf::io::read_stl<P>(file(stl));
    const auto m = cf::make_mesh(data.soup);
    expect(data.soup.points.size() == 8 && data.soup.num_faces() == 12 && near(enclosed_volume(m), 1, eps), T,
           "STL round trip: 8 welded points, 12 triangles, volume 1");
  }
  cf::io::write_mesh(file("glass_mesh.ply"), glass);
  const auto glass2 = cf::io::read_mesh<P>(file("glass_mesh.ply"));
  static_assert(is_p<P, decltype(glass2.position(cf::vertex_handle(0)))>);
  expect(same_soup(cf::to_soup(glass2), cf::to_soup(glass)), T, "write_mesh / read_mesh round trip");
  const auto svg = cf::io::write_svg(file("glass.svg"), glass);
  expect(
      svg.faces_drawn == glass.num_faces() && head(file("glass.svg"), 200).find("<svg") != std::string::npos,
      T, "mesh SVG");

  // wire models: edge list, OBJ lines, SVG
  cf::io::write_edge_list(file("block.txt"), block_wire);
  const auto wire = cf::io::read_edge_list<P>(file("block.txt"));
  static_assert(is_p<P, elem<decltype(wire.points)>>);
  bool same_wire =
      wire.points.size() == block_wire.node_count() && wire.edges.size() == block_wire.bar_count();
  for (std::size_t i = 0; same_wire && i < wire.points.size(); ++i)
    same_wire = dist(wire.points[i], block_wire.node(i)) == 0;
  expect(same_wire, T, "edge list round trip");
  cf::io::write_obj(file("block.obj"), wire);
  const auto wire2 = cf::io::read_obj_wireframe<P>(file("block.obj"));
  expect(wire2.points.size() == 12 && wire2.edges.size() == 20, T, "OBJ wireframe round trip");
  expect(cf::io::write_svg(file("block.svg"), block_wire).edges == 20, T, "wire model SVG");

  // cell complexes: 3DCL, OBJ, PLY, SVG
  cf::io::write_3dcl(file("block.3dcl"), cc);
  // A file has no point type: the reader is told P.
  const auto cc2 = cf::io::read_3dcl<P>(file("block.3dcl"));
  expect(cc2.num_vertices() == 12 && cc2.num_faces() == 11 && cc2.num_volumes() == 2 &&
             cf::validate(cc2).ok() && dist(cc2.point(cf::cell_vertex(5)), cc.point(cf::cell_vertex(5))) == 0,
         T, "3DCL round trip");
  cf::io::write_cells_obj(file("cells.obj"), cc);
  const auto cobj = cf::io::read_obj<P>(file("cells.obj"));
  expect(cobj.groups.size() == 2 && cobj.soup.num_faces() == 12, T,
         "cells OBJ: a group per volume, wall twice");
  cf::io::write_cells_ply(file("cells.ply"), cc);
  expect(cf::io::read_ply<P>(file("cells.ply")).num_faces() >= 11, T, "cells PLY");
  expect(cf::io::write_cells_svg(file("cells.svg"), cc).faces_drawn >= 11, T, "cells SVG");

  // curves: curve file, polyline file, OBJ polylines, pictures
  cf::io::write_curve_file(file("curves.txt"), smooth.curves);
  // The curve readers are told P too.
  const auto curves = cf::io::read_curve_file<P>(file("curves.txt"));
  bool same_curves = curves.size() == smooth.curves.size();
  for (std::size_t i = 0; same_curves && i < curves.size(); ++i)
    for (double u : {0.0, 0.3, 1.0})
      same_curves = same_curves && dist(curves[i].point(u), smooth.curves[i].point(u)) < 1e-9;
  expect(same_curves, T, "curve file round trip");
  cf::io::write_polyline_file(file("polylines.txt"), smooth.curves);
  const auto polylines = cf::io::read_polyline_file<P>(file("polylines.txt"));
  expect(polylines.size() == 12 && polylines[0].size() == 16 &&
             dist(polylines[3].back(), smooth.curves[3].point(1)) < 1e-9,
         T, "polyline file round trip");
  cf::io::write_polylines_obj(file("curves.obj"), smooth.curves);
  expect(cf::io::read_obj<P>(file("curves.obj")).lines.size() == 12 * 15, T, "curves as OBJ lines");
  expect(cf::io::write_smoothing_svg(file("smooth.svg"), octa90, smooth.curves).faces_drawn > 0, T,
         "smoothing SVG");
  std::vector<std::remove_cvref_t<decltype(thin.loops.at(0).points)>> loops;
  for (const auto& l : thin.loops) loops.push_back(l.points);
  expect(cf::io::write_thin_loops_svg(file("thin.svg"), glass, cspan(loops)).faces_drawn > 0, T,
         "thin loops SVG");
}

}  // namespace

void run_sketch(void (*expect)(bool, const char*, const char*));  // sketch.cpp

int main(int argc, char** argv) {
  const fs::path dir = argc > 1 ? fs::path(argv[1]) : fs::temp_directory_path() / "cellforge-consumer";
  fs::remove_all(dir);
  fs::create_directories(dir);
  try {
    run<cad::Vector3>("Vector3", dir);
    run<cad::Vec3f>("Vec3f", dir);
#ifndef CONSUMER_NO_SKETCH
    run_sketch(&expect);
#endif
  } catch (const cf::error& e) {
    std::fprintf(stderr, "consumer: cellforge::error: %s\n", e.what());
    return 1;
  }
  if (failures != 0) return 1;
  std::printf(
      "consumer ok: cad::Vector3 and cad::Vec3f through every job and file format, cad::Sketch through the "
      "sketch part\n");
  return 0;
}
