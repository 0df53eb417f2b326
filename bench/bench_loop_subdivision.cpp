// SPDX-License-Identifier: MIT
// Loop subdivision, seed 001 tables 3 and 4 and beyond: one level of Loop subdivision on
// the seed's spheres (64 … 400 vertices), on stand-ins for its five table-4 meshes, and on
// spheres of 10k, 100k and 1M triangles. cellforge, OpenMesh (Subdivider::Uniform::LoopT)
// and CGAL (Subdivision_method_3::Loop_subdivision) subdivide the same meshes in one run,
// all with double-precision points and Loop's original weights. Only the subdivision is
// timed: each iteration first copies the prepared mesh, untimed.

#include "bench_support.hpp"

#include <malloc.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/algorithms/loop_subdivision.hpp"
#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/halfedge/conversion.hpp"

#ifdef CELLFORGE_HAVE_OPENMESH
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#endif
#ifdef CELLFORGE_HAVE_CGAL
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>
#endif

namespace {

namespace cb = cellforge::bench;
using point = glm::dvec3;
using soup = cellforge::polygon_soup<point>;

// ------------------------------------------------------------------------------ inputs

/// Seed 001 table 3 (C#, 996 MHz): sphere vertices before and after one level, the
/// "initial" (quadratic linking) and "improved" implementations' ms.
struct table3_figure {
  int vertices, seed_after;
  double initial_ms, improved_ms;
};
constexpr std::array<table3_figure, 4> table3{{{64, 270, 25.5166, 14.4952},
                                               {144, 598, 101.8767, 16.1378},
                                               {256, 1054, 291.7180, 18.9798},
                                               {400, 1638, 701.2819, 22.9138}}};

/// Seed 001 table 4: the seed's file, its C++ and C# ms, and the stand-in we generate.
struct table4_figure {
  const char* name;
  double cpp_ms, csharp_ms;
  const char* stand_in;
};
constexpr std::array<table4_figure, 5> table4{{
    {"eyespline", 51.93, 14.92, "spline_tube() (default curve, 8 around)"},
    {"Lattice_10_8_3", 2436, 1072, "lattice_tube_mesh(10, 8, 3), quads split"},
    {"Mobius_16_16", 902.6, 321.5, "mobius_band(16, 16)"},
    {"polyhedron", 203.6, 60.88, "icosphere(3)"},
    {"Tree3", 260.6, 76.83, "tree_tube_mesh(3), quads split"},
}};

soup make_table4(const std::string& name) {
  cellforge::lattice_tube_options tri;
  tri.triangles = true;
  if (name == "eyespline") return cellforge::spline_tube<point>();
  if (name == "Lattice_10_8_3") return cellforge::lattice_tube_mesh<point>(10, 8, 3, tri);
  if (name == "Mobius_16_16") return cellforge::mobius_band<point>(16, 16);
  if (name == "polyhedron") return cellforge::icosphere<point>(3);
  return cellforge::tree_tube_mesh<point>(3, tri);
}

/// The scaling series: triangles of the input spheres (a closed sphere of n vertices has 2n − 4).
constexpr std::array<int, 3> scaling_faces{10'000, 100'000, 1'000'000};

#ifdef CELLFORGE_HAVE_OPENMESH
using om_mesh = OpenMesh::TriMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;
#endif
#ifdef CELLFORGE_HAVE_CGAL
using cgal_point = CGAL::Simple_cartesian<double>::Point_3;
using cgal_mesh = CGAL::Surface_mesh<cgal_point>;
#endif

/// One input in each library's structure, built once and copied for every iteration.
struct prepared {
  soup source;
  cellforge::halfedge_mesh ours;
#ifdef CELLFORGE_HAVE_OPENMESH
  om_mesh om;
#endif
#ifdef CELLFORGE_HAVE_CGAL
  cgal_mesh cgal;
#endif
};

std::unique_ptr<prepared> prepare(soup s) {
  auto p = std::make_unique<prepared>();
  p->ours = cellforge::make_mesh(s);
#ifdef CELLFORGE_HAVE_OPENMESH
  p->om.reserve(s.num_points(), 3 * s.num_faces() / 2, s.num_faces());
  for (const point& q : s.points) p->om.add_vertex(om_mesh::Point(q.x, q.y, q.z));
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    const auto t = s.face(f);
    p->om.add_face(OpenMesh::VertexHandle(static_cast<int>(t[0])),
                   OpenMesh::VertexHandle(static_cast<int>(t[1])),
                   OpenMesh::VertexHandle(static_cast<int>(t[2])));
  }
#endif
#ifdef CELLFORGE_HAVE_CGAL
  using size_type = cgal_mesh::size_type;
  p->cgal.reserve(static_cast<size_type>(s.num_points()), static_cast<size_type>(3 * s.num_faces() / 2),
                  static_cast<size_type>(s.num_faces()));
  for (const point& q : s.points) p->cgal.add_vertex(cgal_point(q.x, q.y, q.z));
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    const auto t = s.face(f);
    p->cgal.add_face(cgal_mesh::Vertex_index(t[0]), cgal_mesh::Vertex_index(t[1]),
                     cgal_mesh::Vertex_index(t[2]));
  }
#endif
  p->source = std::move(s);
  return p;
}

/// Inputs by key ("t3/64", "t4/eyespline", "scale/10000"), made on first use.
std::map<std::string, std::unique_ptr<prepared>>& inputs() {
  static std::map<std::string, std::unique_ptr<prepared>> m;
  return m;
}
const prepared& input(const std::string& key) {
  auto& all = inputs();
  auto it = all.find(key);
  if (it == all.end()) {
    const std::string kind = key.substr(0, key.find('/')), arg = key.substr(key.find('/') + 1);
    soup s = kind == "t4"   ? make_table4(arg)
             : kind == "t3" ? cellforge::sphere_with_vertices<point>(std::stoi(arg))
                            : cellforge::sphere_with_vertices<point>(std::stoi(arg) / 2 + 2);
    it = all.emplace(key, prepare(std::move(s))).first;
  }
  return *it->second;
}

// ------------------------------------------------------------------------------ the three subdividers

std::size_t ours(const prepared& in, cellforge::halfedge_mesh& m) {
  cellforge::loop_subdivide<point>(m);
  return m.num_faces() == 4 * in.ours.num_faces() ? m.num_faces() : 0;
}
#ifdef CELLFORGE_HAVE_OPENMESH
std::size_t openmesh(const prepared& in, om_mesh& m) {
  OpenMesh::Subdivider::Uniform::LoopT<om_mesh> loop;
  loop.attach(m);
  loop(1);
  loop.detach();
  return m.n_faces() == 4 * in.om.n_faces() ? m.n_faces() : 0;
}
#endif
#ifdef CELLFORGE_HAVE_CGAL
std::size_t cgal(const prepared& in, cgal_mesh& m) {
  CGAL::Subdivision_method_3::Loop_subdivision(m, CGAL::parameters::number_of_iterations(1));
  return m.number_of_faces() == 4 * in.cgal.number_of_faces() ? m.number_of_faces() : 0;
}
#endif

/// Makes glibc keep freed memory and serve large blocks from the heap, so that a repeated
/// run reuses pages instead of faulting in fresh zeroed ones (process-wide, so the warm
/// series runs last). Returns whether glibc accepted it.
bool warm_heap() {
  static const bool ok = mallopt(M_MMAP_THRESHOLD, 1 << 30) == 1 && mallopt(M_TRIM_THRESHOLD, 1 << 30) == 1;
  return ok;
}

/// Registers one benchmark: each iteration copies the input's mesh (untimed) and times
/// `run` on it (CPU time of this thread; see bench_support.hpp).
template <class Mesh, class Run>
void add(const std::string& name, const std::string& key, Mesh prepared::*mesh, Run run, int faces) {
  const bool warm = name.starts_with("loop/warm/");
  auto* b = benchmark::RegisterBenchmark(name.c_str(), [key, mesh, run, warm](benchmark::State& state) {
    if (warm && !warm_heap()) state.SkipWithError("mallopt refused the warm-heap settings");
    const prepared& in = input(key);
    double best = std::numeric_limits<double>::infinity();
    bool checked = false;
    for (auto _ : state) {
      auto copy = std::make_unique<Mesh>(in.*mesh);
      const double t0 = cb::thread_cpu_ms();
      const std::size_t faces_after = run(in, *copy);
      const double ms = cb::thread_cpu_ms() - t0;
      state.SetIterationTime(ms * 1e-3);
      best = std::min(best, ms);
      if (!checked && faces_after == 0) state.SkipWithError("wrong face count after subdivision");
      checked = true;
      copy.reset();  // freed outside the timed span
    }
    state.counters["best_cpu_us"] = best * 1e3;
    state.counters["faces_in"] = static_cast<double>(in.source.num_faces());
  });
  b->UseManualTime()->Unit(benchmark::kMillisecond);
  if (faces >= 1'000'000)
    b->Iterations(3);
  else if (faces >= 100'000)
    b->MinTime(0.3);
  else
    b->MinTime(0.1);
}

void add_all(const std::string& what, const std::string& key, int faces) {
  add("loop/" + what + "/cellforge", key, &prepared::ours, ours, faces);
#ifdef CELLFORGE_HAVE_OPENMESH
  add("loop/" + what + "/openmesh", key, &prepared::om, openmesh, faces);
#endif
#ifdef CELLFORGE_HAVE_CGAL
  add("loop/" + what + "/cgal", key, &prepared::cgal, cgal, faces);
#endif
}

void register_all() {
  for (const auto& f : table3)
    add_all("t3/" + std::to_string(f.vertices), "t3/" + std::to_string(f.vertices), 0);
  for (const auto& f : table4) add_all(std::string("t4/") + f.name, std::string("t4/") + f.name, 0);
  for (const int f : scaling_faces) add_all("scale/" + std::to_string(f), "scale/" + std::to_string(f), f);
  for (const int f : scaling_faces) add_all("warm/" + std::to_string(f), "scale/" + std::to_string(f), f);
}

// ------------------------------------------------------------------------------ cross-check

/// Mean of the subdivided vertex positions in each library, for the same input: the three
/// implement the same masks, so the means must agree to rounding.
std::string cross_check(const std::string& key) {
  const prepared& in = input(key);
  cellforge::halfedge_mesh m = in.ours;
  ours(in, m);
  glm::dvec3 mean(0);
  for (const point& p : cellforge::points<point>(m).vector()) mean += p;
  mean /= static_cast<double>(m.num_vertices());
  std::string out = "mean of the new vertices: ours (" + cb::fixed(mean.x, 12) + ", " +
                    cb::fixed(mean.y, 12) + ", " + cb::fixed(mean.z, 12) + ")";
  double worst = 0;
#ifdef CELLFORGE_HAVE_OPENMESH
  {
    om_mesh o = in.om;
    openmesh(in, o);
    glm::dvec3 s(0);
    for (auto v : o.vertices()) s += glm::dvec3(o.point(v)[0], o.point(v)[1], o.point(v)[2]);
    s /= static_cast<double>(o.n_vertices());
    worst = std::max(worst, glm::length(s - mean));
  }
#endif
#ifdef CELLFORGE_HAVE_CGAL
  {
    cgal_mesh c = in.cgal;
    cgal(in, c);
    glm::dvec3 s(0);
    for (auto v : c.vertices()) s += glm::dvec3(c.point(v).x(), c.point(v).y(), c.point(v).z());
    s /= static_cast<double>(c.number_of_vertices());
    worst = std::max(worst, glm::length(s - mean));
  }
#endif
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1e", worst);
  return out + "; largest difference to OpenMesh / CGAL: " + buf;
}

// ------------------------------------------------------------------------------ tables

std::optional<double> get(const cb::collecting_reporter& rep, const std::string& what, const char* lib) {
  return rep.ms("loop/" + what + "/" + lib);
}

/// The prepared input `key`, if a benchmark made it (none is made while printing).
const prepared* made(const std::string& key) {
  const auto it = inputs().find(key);
  return it == inputs().end() ? nullptr : it->second.get();
}

/// A seed-table row: the seed's figures, then the three libraries' times for `what`.
cb::seed_row row(const cb::collecting_reporter& rep, const std::string& what, std::string label,
                 std::vector<std::optional<double>> seed) {
  return {std::move(label), std::move(seed), get(rep, what, "cellforge"), get(rep, what, "openmesh"),
          get(rep, what, "cgal")};
}

/// The largest scaling case's times, and time per triangle at 1M over that at 10k.
struct scaling {
  std::optional<double> ours, om, cgal, growth;
};

/// Prints one scaling series ("scale" or "warm") as a table. O(rows).
scaling print_scaling(const cb::collecting_reporter& rep, std::ostream& os, const std::string& series,
                      const std::string& title, const std::string& note) {
  cb::table t(title, {"triangles in", "ours ms", "ours ns/tri", "OpenMesh ms", "CGAL ms", "OpenMesh / ours",
                      "CGAL / ours"});
  scaling out;
  std::optional<double> first_ns;
  for (const int f : scaling_faces) {
    const std::string what = series + "/" + std::to_string(f);
    const auto o = get(rep, what, "cellforge"), om = get(rep, what, "openmesh"), cg = get(rep, what, "cgal");
    std::optional<double> ns;
    if (o) ns = *o * 1e6 / f;
    if (!first_ns) first_ns = ns;
    if (ns && first_ns) out.growth = *ns / *first_ns;
    out = {o, om, cg, out.growth};
    t.add_row({cb::count(static_cast<std::size_t>(f)), cb::ms(o), cb::fixed(ns, 1), cb::ms(om), cb::ms(cg),
               cb::ratio(om, o), cb::ratio(cg, o)});
  }
  t.add_note(note);
  if (series == "scale" && made("scale/10000"))
    t.add_note("Cross-check (10k): " + cross_check("scale/10000") + ".");
  t.print(os);
  return out;
}

void print_tables(const cb::collecting_reporter& rep, std::ostream& os) {
  os << "\n## Loop subdivision (seed 001, tables 3 and 4)\n\nOne level of Loop subdivision, double-precision "
        "points everywhere. OpenMesh: Subdivider::Uniform::LoopT on "
        "TriMesh_ArrayKernelT<DefaultTraitsDouble>. "
        "CGAL: Subdivision_method_3::Loop_subdivision on Surface_mesh<Simple_cartesian<double>::Point_3>.\n"
        "Times: CPU ms of the subdivision alone (the input copy each iteration needs is not timed), best of "
        "the iterations. Load average now: "
     << cb::load_average() << ".\n";

  std::vector<cb::seed_row> t3;
  for (const auto& f : table3) {
    const std::string what = "t3/" + std::to_string(f.vertices);
    const prepared* in = made(what);
    const std::size_t after = in ? in->ours.num_vertices() + in->ours.num_edges() : 0;
    t3.push_back(row(rep, what,
                     std::to_string(f.vertices) + " → " + std::to_string(after) + " (seed " +
                         std::to_string(f.seed_after) + ")",
                     {f.initial_ms, f.improved_ms}));
  }
  cb::table a = cb::seed_table("Table 3: one level on spheres", "vertices before → after",
                               {"seed initial ms", "seed improved ms"}, t3);
  a.add_note(
      "Seed: C# on a 996 MHz machine. Ours: sphere_with_vertices(n), closed, 2n − 4 triangles; one Loop "
      "step gives V + E = 4n − 6 vertices. The seed's counts are larger by 2√n + 4, so its spheres had "
      "seams or duplicated vertices (see docs/shapes.md).");
  a.print(os);

  std::vector<cb::seed_row> t4;
  for (const auto& f : table4) {
    const std::string what = std::string("t4/") + f.name;
    const prepared* in = made(what);
    const std::string size = in ? " (" + std::to_string(in->ours.num_vertices()) + " v, " +
                                      std::to_string(in->ours.num_faces()) + " tri)"
                                : "";
    t4.push_back(row(rep, what, std::string(f.name) + size, {f.cpp_ms, f.csharp_ms}));
  }
  cb::table b = cb::seed_table("Table 4: one level on the seed's five meshes (our stand-ins)", "mesh",
                               {"seed C++ ms", "seed C# ms"}, t4);
  for (const auto& f : table4) b.add_note(std::string("- ") + f.name + ": " + f.stand_in);
  b.add_note(
      "The seed gives no sizes for these files; the stand-ins are generated by shapes.hpp (sizes above).");
  b.print(os);

  const scaling cold =
      print_scaling(rep, os, "scale", "Scaling: one level on closed spheres (same meshes for all three)",
                    "Each run writes into freshly allocated memory, as a single call does; at 1M "
                    "triangles (over 300 MB of new arrays) the kernel's page faults and page "
                    "zeroing are a large share of every library's time.");
  const scaling warm = print_scaling(
      rep, os, "warm", "Scaling with a warm heap (glibc keeps and reuses freed memory: no fresh pages)",
      "mallopt(M_MMAP_THRESHOLD and M_TRIM_THRESHOLD = 1 GiB) before these runs, for all three libraries: "
      "this isolates the algorithms' own cost (what repeated subdivision in one process sees).");

  os << "\n### Targets (" << cb::count(static_cast<std::size_t>(scaling_faces.back())) << " triangles)\n\n";
  for (const scaling* sc : {&cold, &warm}) {
    const char* heap = sc == &cold ? "fresh memory" : "warm heap";
    if (sc->ours) {
      const char* verdict = !sc->om || !sc->cgal                                           ? "NOT CHECKED"
                            : (*sc->om >= 1.5 * *sc->ours && *sc->cgal >= 1.5 * *sc->ours) ? "MET"
                                                                                           : "NOT MET";
      os << "- " << heap
         << ": at least 1.5x faster than OpenMesh LoopT and CGAL Loop_subdivision: " << verdict
         << " (OpenMesh " << cb::ratio(sc->om, sc->ours) << ", CGAL " << cb::ratio(sc->cgal, sc->ours)
         << ")\n";
    }
    if (sc->growth)
      os << "- " << heap << ": linear growth, time per triangle at 1M within 1.5x of 10k: "
         << (*sc->growth <= 1.5 ? "MET" : "NOT MET") << " (" << cb::fixed(sc->growth, 2) << "x)\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  cb::collecting_reporter reporter;
  if (!cb::run_benchmarks(argc, argv, reporter)) return 1;
  print_tables(reporter, std::cout);
  return 0;
}
