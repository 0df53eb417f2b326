// SPDX-License-Identifier: MIT
// The exact self-intersection check (algorithms/self_intersections.hpp) on closed spheres of
// 100k and 1M triangles (sphere_with_vertices, as in bench_mesh_creation) and on a quad tube
// mesh (lattice_tube_mesh 20 x 20 x 20), next to CGAL's
// Polygon_mesh_processing::does_self_intersect and self_intersections on the same spheres in
// the same run (Surface_mesh with the exact-predicates kernel). Medians of a fixed number of
// iterations (CPU ms); the table prints at the end.

#include "bench_support.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/algorithms/self_intersections.hpp"
#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/samples/tube_soups.hpp"

#ifdef CELLFORGE_HAVE_CGAL
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#endif

namespace {

namespace cb = cellforge::bench;
using point = glm::dvec3;
using soup = cellforge::polygon_soup<point>;
using mesh = cellforge::surface_mesh<point>;

/// Triangle counts of the spheres (sphere_with_vertices(f / 2 + 2): closed, f triangles).
constexpr std::array<int, 2> sizes{100'000, 1'000'000};
constexpr int lattice_side = 20;
int iterations_for(int faces) { return faces >= 1'000'000 ? 3 : 7; }

const soup& sphere(int faces) {
  static std::map<int, soup> spheres;
  auto it = spheres.find(faces);
  if (it == spheres.end())
    it = spheres.emplace(faces, cellforge::sphere_with_vertices<point>(faces / 2 + 2)).first;
  return it->second;
}
const mesh& ours(int faces) {
  static std::map<int, mesh> meshes;
  auto it = meshes.find(faces);
  if (it == meshes.end()) it = meshes.emplace(faces, cellforge::make_mesh(sphere(faces))).first;
  return it->second;
}
const mesh& lattice() {
  static const mesh m =
      cellforge::make_mesh(cellforge::samples::lattice_tube_mesh(lattice_side, lattice_side, lattice_side));
  return m;
}

#ifdef CELLFORGE_HAVE_CGAL
using kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using cgal_mesh = CGAL::Surface_mesh<kernel::Point_3>;
const cgal_mesh& cgal_sphere(int faces) {
  static std::map<int, cgal_mesh> meshes;
  auto it = meshes.find(faces);
  if (it == meshes.end()) {
    const soup& s = sphere(faces);
    cgal_mesh m;
    std::vector<cgal_mesh::Vertex_index> v;
    for (const point& p : s.points) v.push_back(m.add_vertex(kernel::Point_3(p.x, p.y, p.z)));
    for (std::size_t f = 0; f < s.num_faces(); ++f) {
      const auto face = s.face(f);
      m.add_face(v[face[0]], v[face[1]], v[face[2]]);
    }
    it = meshes.emplace(faces, std::move(m)).first;
  }
  return it->second;
}
#endif

std::string name(const char* what, const char* lib, int faces) {
  return std::string(what) + "/" + lib + "/" + std::to_string(faces);
}

template <class Make>
void add(const char* what, const char* lib, int faces, Make make) {
  benchmark::RegisterBenchmark(name(what, lib, faces).c_str(),
                               [make](benchmark::State& state) {
                                 cb::median_loop(state, make, [&](const auto& r) {
                                   if (r.first != 0)
                                     state.SkipWithError("the sphere was found to intersect itself");
                                   state.counters["pairs"] = static_cast<double>(r.second);
                                 });
                               })
      ->Iterations(iterations_for(faces))
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
}

/// (intersecting pairs, candidate pairs examined) of our check.
std::pair<std::size_t, std::size_t> cf_check(const mesh& m) {
  const cellforge::self_intersection_result r = cellforge::self_intersections(m);
  if (!r.complete) return {~std::size_t{0}, 0};
  return {r.intersecting_face_pairs, r.candidate_pairs};
}

void register_all() {
  for (const int f : sizes) {
    add("check", "cellforge", f, [f] { return cf_check(ours(f)); });
#ifdef CELLFORGE_HAVE_CGAL
    add("does_self_intersect", "cgal", f, [f] {
      return std::pair<std::size_t, std::size_t>(
          CGAL::Polygon_mesh_processing::does_self_intersect(cgal_sphere(f)) ? 1 : 0, 0);
    });
    add("self_intersections", "cgal", f, [f] {
      std::vector<std::pair<cgal_mesh::Face_index, cgal_mesh::Face_index>> out;
      CGAL::Polygon_mesh_processing::self_intersections(cgal_sphere(f), std::back_inserter(out));
      return std::pair<std::size_t, std::size_t>(out.size(), 0);
    });
#endif
  }
  const int lattice_faces = static_cast<int>(lattice().num_faces());
  add("check_lattice", "cellforge", lattice_faces, [] { return cf_check(lattice()); });
}

void print_tables(const cb::collecting_reporter& rep, std::ostream& os) {
  const auto med = [&](const char* what, const char* lib, int f) {
    return rep.counter_ms(name(what, lib, f), "median_cpu_us");
  };
  cb::table t("Exact self-intersection check of a closed sphere",
              {"triangles", "ours ms", "ours ns/tri", "candidate pairs/tri", "CGAL does_self_intersect ms",
               "CGAL self_intersections ms", "does_self_intersect / ours", "self_intersections / ours"});
  for (const int f : sizes) {
    const auto o = med("check", "cellforge", f), d = med("does_self_intersect", "cgal", f),
               s = med("self_intersections", "cgal", f);
    const cb::run_result* r = rep.find(name("check", "cellforge", f));
    std::optional<double> per_tri, pairs;
    if (o) per_tri = *o * 1e6 / f;
    if (r && r->counters.count("pairs")) pairs = r->counters.at("pairs") / f;
    t.add_row({cb::count(static_cast<std::size_t>(f)), cb::ms(o), cb::fixed(per_tri, 0), cb::fixed(pairs, 1),
               cb::ms(d), cb::ms(s), cb::ratio(d, o), cb::ratio(s, o)});
  }
  t.add_note(
      "Ours: self_intersections(surface_mesh) with default options (all intersecting pairs, exact). CGAL: "
      "Polygon_mesh_processing::does_self_intersect and self_intersections on a Surface_mesh with "
      "Exact_predicates_inexact_constructions_kernel (a box-intersection broad phase and exact predicates). "
      "'—': CGAL not found at configure time.");
  const int lf = static_cast<int>(lattice().num_faces());
  const auto lo = med("check_lattice", "cellforge", lf);
  t.add_note("Quad tube mesh lattice_tube_mesh(" + std::to_string(lattice_side) + ", " +
             std::to_string(lattice_side) + ", " + std::to_string(lattice_side) + "), " +
             cb::count(static_cast<std::size_t>(lf)) + " quads: ours " + cb::ms(lo) + " ms.");
  t.print(os);
}

}  // namespace

int main(int argc, char** argv) { return cb::table_main(argc, argv, register_all, print_tables); }
