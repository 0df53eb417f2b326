// SPDX-License-Identifier: MIT
// Simplification by quadric-error edge collapses (seed 001 §IV.C; the seed gives no timing
// for it): spheres of 20k, 82k and 328k triangles and a 65k-triangle torus reduced to a
// target face count by cellforge (simplify, quadric cost), OpenMesh (DecimaterT with
// ModQuadricT and ModNormalFlippingT) and CGAL (edge_collapse with the Garland–Heckbert
// plane policies), all with double-precision points. Each iteration copies the prepared
// mesh untimed, then times the decimation and the garbage collection. The table also
// reports the result's worst distance from the sphere, a check that all did the same job.

#include "bench_support.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/algorithms/simplification.hpp"
#include "cellforge/halfedge/conversion.hpp"

#ifdef CELLFORGE_HAVE_OPENMESH
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#ifndef CELLFORGE_HAVE_OPENMESH_TOOLS
// The benchmarks link OpenMeshCore only. The decimater template refers to this one
// OpenMeshTools function, on its progress-observer path, which we never take (no
// observer is attached), so a stand-in lets it link; it is never called.
std::size_t OpenMesh::Decimater::Observer::get_interval() const { return 0; }
#endif
#endif
#ifdef CELLFORGE_HAVE_CGAL
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
// CGAL's Garland–Heckbert policies need Eigen on the include path; without it CGAL's
// default (Lindstrom–Turk, also a quadric-type cost with optimal placement) is timed.
#if __has_include(<Eigen/Dense>)
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#define CELLFORGE_BENCH_CGAL_GH 1
#endif
#endif

namespace {

namespace cb = cellforge::bench;
using point = glm::dvec3;
using soup = cellforge::polygon_soup<point>;

struct input_spec {
  std::string name;
  bool sphere;  // vertices should stay on the unit sphere
  std::size_t target_faces;
  std::function<soup()> make;
};
const std::vector<input_spec>& inputs() {
  static const std::vector<input_spec> in = {
      {"icosphere(5), 20 480 -> 2 000", true, 2000, [] { return cellforge::icosphere<point>(5); }},
      {"icosphere(6), 81 920 -> 5 000", true, 5000, [] { return cellforge::icosphere<point>(6); }},
      {"icosphere(7), 327 680 -> 10 000", true, 10000, [] { return cellforge::icosphere<point>(7); }},
      {"torus(256, 128), 65 536 -> 2 000", false, 2000,
       [] { return cellforge::torus<point>(256, 128, 1.0, 0.3, true); }},
  };
  return in;
}

// What a run left: faces, the worst |distance from the origin - 1| of a vertex, and the
// enclosed volume (a vertex can sit on the sphere while the faces cut inside it).
struct outcome {
  std::size_t faces = 0;
  double sphere_error = 0, volume = 0;
};
// Adds triangle (a, b, c)'s signed volume against the origin and the vertex's sphere error.
inline void add_triangle(outcome& o, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  o.volume += glm::dot(a, glm::cross(b, c)) / 6;
}
inline void add_vertex(outcome& o, const glm::dvec3& p) {
  o.sphere_error = std::max(o.sphere_error, std::abs(glm::length(p) - 1));
}

// ------------------------------------------------------------------------------ libraries

// A triangle soup in a baseline's mesh (add_vertex(point), add_face(a, b, c)).
template <class Mesh, class Point>
Mesh build_triangles(const soup& s) {
  Mesh m;
  std::vector<decltype(m.add_vertex(Point()))> vh;
  for (const point& p : s.points) vh.push_back(m.add_vertex(Point(p.x, p.y, p.z)));
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    const auto fv = s.face(f);
    m.add_face(vh[fv[0]], vh[fv[1]], vh[fv[2]]);
  }
  return m;
}

struct ours {
  using mesh = cellforge::surface_mesh<glm::dvec3>;
  static mesh build(const soup& s) { return cellforge::make_mesh(s); }
  static void run(mesh& m, std::size_t target) { cellforge::simplify(m, {.target_faces = target}); }
  static outcome look(const mesh& m) {
    outcome o{m.num_faces(), 0, 0};
    const auto pts = m.positions();
    for (auto v : m.vertices()) add_vertex(o, pts[v]);
    for (auto f : m.faces()) {
      std::vector<glm::dvec3> p;
      for (auto v : m.vertices_around(f)) p.push_back(pts[v]);
      add_triangle(o, p[0], p[1], p[2]);
    }
    return o;
  }
};

#ifdef CELLFORGE_HAVE_OPENMESH
struct openmesh {
  using mesh = OpenMesh::TriMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;
  static mesh build(const soup& s) {
    mesh m = build_triangles<mesh, mesh::Point>(s);
    m.request_face_normals();  // ModNormalFlippingT needs them; computed untimed, once
    m.update_face_normals();
    return m;
  }
  static void run(mesh& m, std::size_t target) {
    using decimater = OpenMesh::Decimater::DecimaterT<mesh>;
    decimater d(m);
    OpenMesh::Decimater::ModQuadricT<mesh>::Handle quadric;
    OpenMesh::Decimater::ModNormalFlippingT<mesh>::Handle normals;
    d.add(quadric);
    d.add(normals);
    d.module(quadric).unset_max_err();
    d.module(normals).set_max_normal_deviation(60.0);  // as our default max_normal_angle
    d.initialize();
    d.decimate_to_faces(0, target);
    m.garbage_collection();
  }
  static outcome look(const mesh& m) {
    outcome o{m.n_faces(), 0, 0};
    auto at = [&](mesh::VertexHandle v) { return glm::dvec3(m.point(v)[0], m.point(v)[1], m.point(v)[2]); };
    for (auto v : m.vertices()) add_vertex(o, at(v));
    for (auto f : m.faces()) {
      std::vector<glm::dvec3> p;
      for (auto v : m.fv_range(f)) p.push_back(at(v));
      add_triangle(o, p[0], p[1], p[2]);
    }
    return o;
  }
};
#endif

#ifdef CELLFORGE_HAVE_CGAL
struct cgal {
  using kernel = CGAL::Simple_cartesian<double>;
  using mesh = CGAL::Surface_mesh<kernel::Point_3>;
  static mesh build(const soup& s) { return build_triangles<mesh, kernel::Point_3>(s); }
  static void run(mesh& m, std::size_t target) {
    namespace sms = CGAL::Surface_mesh_simplification;
    // A closed triangle mesh has 3/2 edges per face; the predicate counts edges.
    sms::Count_stop_predicate<mesh> stop(target * 3 / 2);
#ifdef CELLFORGE_BENCH_CGAL_GH
    sms::GarlandHeckbert_plane_policies<mesh, kernel> gh(m);
    sms::edge_collapse(m, stop, CGAL::parameters::get_cost(gh.get_cost()).get_placement(gh.get_placement()));
#else
    sms::edge_collapse(m, stop);
#endif
    m.collect_garbage();
  }
  static outcome look(const mesh& m) {
    outcome o{m.number_of_faces(), 0, 0};
    auto at = [&](mesh::Vertex_index v) {
      return glm::dvec3(m.point(v).x(), m.point(v).y(), m.point(v).z());
    };
    for (auto v : m.vertices()) add_vertex(o, at(v));
    for (auto f : m.faces()) {
      std::vector<glm::dvec3> p;
      for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) p.push_back(at(v));
      add_triangle(o, p[0], p[1], p[2]);
    }
    return o;
  }
};
#endif

// Prepared inputs, built once per library and copied for each iteration.
template <class Lib>
const typename Lib::mesh& prepared(std::size_t i) {
  static std::map<std::size_t, std::unique_ptr<typename Lib::mesh>> cache;
  auto& slot = cache[i];
  if (!slot) slot = std::make_unique<typename Lib::mesh>(Lib::build(inputs()[i].make()));
  return *slot;
}

std::map<std::string, outcome>& outcomes() {
  static std::map<std::string, outcome> o;
  return o;
}

template <class Lib>
void register_one(const std::string& lib, std::size_t i) {
  const std::string name = lib + "/" + std::to_string(i);
  benchmark::RegisterBenchmark(name.c_str(),
                               [i, name](benchmark::State& state) {
                                 const auto& in = prepared<Lib>(i);
                                 std::vector<double> times;
                                 for (auto _ : state) {
                                   auto copy = std::make_unique<typename Lib::mesh>(in);  // untimed
                                   const double t0 = cb::thread_cpu_ms();
                                   Lib::run(*copy, inputs()[i].target_faces);
                                   const double ms = cb::thread_cpu_ms() - t0;
                                   state.SetIterationTime(ms * 1e-3);
                                   times.push_back(ms);
                                   outcomes()[name] = Lib::look(*copy);
                                 }
                                 if (times.empty()) return;
                                 state.counters["best_cpu_us"] =
                                     *std::min_element(times.begin(), times.end()) * 1e3;
                                 state.counters["median_cpu_us"] = cb::median(times) * 1e3;
                               })
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(5);
}

void register_all() {
  for (std::size_t i = 0; i < inputs().size(); ++i) {
    register_one<ours>("cellforge", i);
#ifdef CELLFORGE_HAVE_OPENMESH
    register_one<openmesh>("openmesh", i);
#endif
#ifdef CELLFORGE_HAVE_CGAL
    register_one<cgal>("cgal", i);
#endif
  }
}

#ifdef CELLFORGE_BENCH_CGAL_GH
constexpr const char* cgal_policy = "edge_collapse + GarlandHeckbert_plane_policies";
#else
constexpr const char* cgal_policy =
    "edge_collapse with its default Lindstrom-Turk policy (Eigen not on the include path)";
#endif

void print_tables(const cb::collecting_reporter& rep, std::ostream& os) {
  std::vector<double> volume0;  // the inputs' own volumes
  for (const input_spec& in : inputs()) volume0.push_back(ours::look(ours::build(in.make())).volume);
  os << "\n## Simplification (quadric error, to a face count)\n\nOpenMesh: "
     << (cb::have_openmesh ? "DecimaterT + ModQuadricT + ModNormalFlippingT(60°)" : "not found, skipped")
     << ". CGAL: " << (!cb::have_cgal ? "not found, skipped" : cgal_policy)
     << ". CPU ms, median of 5 runs; garbage collection included.\n";
  cb::table t("Decimate to a face count",
              {"input", "ours ms", "OpenMesh ms", "ratio", "CGAL ms", "ratio", "faces ours/OM/CGAL",
               "vertex radius error ours/OM/CGAL", "volume error % ours/OM/CGAL"});
  for (std::size_t i = 0; i < inputs().size(); ++i) {
    const std::string k = std::to_string(i);
    const auto o = rep.counter_ms("cellforge/" + k, "median_cpu_us"),
               om = rep.counter_ms("openmesh/" + k, "median_cpu_us"),
               cg = rep.counter_ms("cgal/" + k, "median_cpu_us");
    auto faces = [&](const std::string& lib) {
      const auto it = outcomes().find(lib + "/" + k);
      return it == outcomes().end() ? std::string("—") : std::to_string(it->second.faces);
    };
    auto err = [&](const std::string& lib) {
      const auto it = outcomes().find(lib + "/" + k);
      return it == outcomes().end() || !inputs()[i].sphere ? std::string("—")
                                                           : cb::fixed(it->second.sphere_error, 4);
    };
    auto vol = [&](const std::string& lib) {
      const auto it = outcomes().find(lib + "/" + k);
      return it == outcomes().end() ? std::string("—")
                                    : cb::fixed(100 * (it->second.volume / volume0[i] - 1), 3);
    };
    t.add_row({inputs()[i].name, cb::ms(o), cb::ms(om), cb::ratio(om, o), cb::ms(cg), cb::ratio(cg, o),
               faces("cellforge") + "/" + faces("openmesh") + "/" + faces("cgal"),
               err("cellforge") + "/" + err("openmesh") + "/" + err("cgal"),
               vol("cellforge") + "/" + vol("openmesh") + "/" + vol("cgal")});
  }
  t.add_note(
      "ratio = their time / ours (above 1: we are faster). Vertex radius error: the largest | |p| - 1 | "
      "over the result's vertices (0 for OpenMesh, whose half-edge collapses keep original vertices). "
      "Volume error: the result's enclosed volume against the input's, in percent (negative: it cuts "
      "inside).");
  t.print(os);
}

}  // namespace

int main(int argc, char** argv) { return cb::table_main(argc, argv, register_all, print_tables); }
