// SPDX-License-Identifier: MIT
// Loop subdivision, seed 001 tables 3 and 4 and beyond: one level of Loop subdivision on
// the seed's spheres (64 … 400 vertices), on stand-ins for its five table-4 meshes, and on
// spheres of 10k, 100k and 1M triangles under three glibc heap settings (default, cold:
// fresh pages at every size, warm: reused pages). cellforge, OpenMesh (Subdivider::Uniform::LoopT)
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
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/algorithms/loop_subdivision.hpp"
#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/samples/tube_soups.hpp"

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
using cb::heap;
using cb::set_heap;
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
  cellforge::samples::lattice_tube_options tri;
  tri.triangles = true;
  if (name == "eyespline") return cellforge::samples::spline_tube<point>();
  if (name == "Lattice_10_8_3") return cellforge::samples::lattice_tube_mesh<point>(10, 8, 3, tri);
  if (name == "Mobius_16_16") return cellforge::mobius_band<point>(16, 16);
  if (name == "polyhedron") return cellforge::icosphere<point>(3);
  return cellforge::samples::tree_tube_mesh<point>(3, tri);
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
  cellforge::surface_mesh<glm::dvec3> ours;
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

std::size_t ours(const prepared& in, cellforge::surface_mesh<glm::dvec3>& m) {
  cellforge::loop_subdivide(m);
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

/// Registers one benchmark: each iteration copies the input's mesh (untimed) and times
/// `run` on it (CPU time of this thread; see bench_support.hpp), counting its page faults.
template <class Mesh, class Run>
void add(const std::string& name, const std::string& key, Mesh prepared::*mesh, Run run, int faces, heap h) {
  auto* b = benchmark::RegisterBenchmark(name.c_str(), [key, mesh, run, h](benchmark::State& state) {
    if (const char* error = set_heap(h)) {
      state.SkipWithError(error);
      return;
    }
    const prepared& in = input(key);
    std::vector<double> times;
    bool checked = false;
    long faults = 0, huge = 0;
    for (auto _ : state) {
      auto copy = std::make_unique<Mesh>(in.*mesh);
      // glibc serves a large request from a free heap chunk before it considers mmap; this
      // hands those chunks' pages back (MADV_DONTNEED), so reusing them faults in zeroed pages.
      if (h == heap::cold) malloc_trim(0);
      const long f0 = cb::minor_faults(), h0 = cb::huge_faults();
      const double t0 = cb::thread_cpu_ms();
      const std::size_t faces_after = run(in, *copy);
      const double ms = cb::thread_cpu_ms() - t0;
      faults += cb::minor_faults() - f0;
      huge += cb::huge_faults() - h0;
      state.SetIterationTime(ms * 1e-3);
      times.push_back(ms);
      if (!checked && faces_after == 0) state.SkipWithError("wrong face count after subdivision");
      checked = true;
      copy.reset();  // freed outside the timed span
    }
    if (times.empty()) return;
    state.counters["best_cpu_us"] = *std::min_element(times.begin(), times.end()) * 1e3;
    state.counters["median_cpu_us"] = cb::median(times) * 1e3;
    state.counters["faces_in"] = static_cast<double>(in.source.num_faces());
    // Per run and input triangle; huge faults are system-wide, so capped at our own faults.
    const double per = static_cast<double>(std::max<std::int64_t>(state.iterations(), 1)) *
                       static_cast<double>(in.source.num_faces());
    state.counters["faults_per_tri"] = static_cast<double>(faults) / per;
    state.counters["zeroed_kib_per_tri"] = (4.0 * static_cast<double>(faults - std::min(huge, faults)) +
                                            2048.0 * static_cast<double>(std::min(huge, faults))) /
                                           per;
  });
  b->UseManualTime()->Unit(benchmark::kMillisecond);
  if (faces >= 1'000'000)
    b->Iterations(5);
  else if (faces >= 100'000)
    b->MinTime(0.3);
  else
    b->MinTime(0.1);
}

void add_all(const std::string& what, const std::string& key, int faces, heap h = heap::default_glibc) {
  add("loop/" + what + "/cellforge", key, &prepared::ours, ours, faces, h);
#ifdef CELLFORGE_HAVE_OPENMESH
  add("loop/" + what + "/openmesh", key, &prepared::om, openmesh, faces, h);
#endif
#ifdef CELLFORGE_HAVE_CGAL
  add("loop/" + what + "/cgal", key, &prepared::cgal, cgal, faces, h);
#endif
}

/// The benchmark-name prefix of a scaling series.
std::string series_name(heap h) { return h == heap::cold ? "cold" : h == heap::warm ? "warm" : "default"; }

void register_all() {
  for (const auto& f : table3)
    add_all("t3/" + std::to_string(f.vertices), "t3/" + std::to_string(f.vertices), 0);
  for (const auto& f : table4) add_all(std::string("t4/") + f.name, std::string("t4/") + f.name, 0);
  // Registration order is run order: glibc's defaults first, then cold, then warm.
  for (const heap h : {heap::default_glibc, heap::cold, heap::warm})
    for (const int f : scaling_faces)
      add_all(series_name(h) + "/" + std::to_string(f), "scale/" + std::to_string(f), f, h);
}

// ------------------------------------------------------------------------------ cross-check

/// Mean of the subdivided vertex positions in each library, for the same input: the three
/// implement the same masks, so the means must agree to rounding.
std::string cross_check(const std::string& key) {
  const prepared& in = input(key);
  auto m = in.ours;
  ours(in, m);
  glm::dvec3 mean(0);
  for (const point& p : m.positions().vector()) mean += p;
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
  return rep.counter_ms("loop/" + what + "/" + lib, "median_cpu_us");
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

/// A scaling series' largest-case times, and each library's time per triangle at 1M over
/// that at 10k.
struct scaling {
  std::optional<double> ours, om, cgal;
  std::optional<double> growth, om_growth, cgal_growth;
};

/// Counter `name` (per input triangle) of one run of `what` by `lib`, if it ran.
std::optional<double> per_tri_counter(const cb::collecting_reporter& rep, const std::string& what,
                                      const char* lib, const char* name) {
  const cb::run_result* r = rep.find("loop/" + what + "/" + lib);
  if (!r || !r->error.empty()) return std::nullopt;
  const auto it = r->counters.find(name);
  return it == r->counters.end() ? std::nullopt : std::optional<double>(it->second);
}

/// "ours / OpenMesh / CGAL" for counter `name` of `what`, with `digits` decimals.
std::string three(const cb::collecting_reporter& rep, const std::string& what, const char* name, int digits) {
  return cb::fixed(per_tri_counter(rep, what, "cellforge", name), digits) + " / " +
         cb::fixed(per_tri_counter(rep, what, "openmesh", name), digits) + " / " +
         cb::fixed(per_tri_counter(rep, what, "cgal", name), digits);
}

/// Prints one scaling series ("default", "cold" or "warm") as a table. O(rows).
scaling print_scaling(const cb::collecting_reporter& rep, std::ostream& os, const std::string& series,
                      const std::string& title, const std::string& note) {
  cb::table t(title,
              {"triangles in", "ours ms", "ours ns/tri", "OpenMesh ns/tri", "CGAL ns/tri", "OpenMesh / ours",
               "CGAL / ours", "page faults/tri ours / OM / CGAL", "zeroed KiB/tri ours / OM / CGAL"});
  scaling out;
  std::array<std::optional<double>, 3> first_ns;  // ours, OpenMesh, CGAL at the smallest size
  const auto per_tri = [](std::optional<double> ms, int f) {
    return ms ? std::optional<double>(*ms * 1e6 / f) : std::nullopt;
  };
  const auto growth = [](std::optional<double> now, std::optional<double> first) {
    return now && first ? std::optional<double>(*now / *first) : std::nullopt;
  };
  for (const int f : scaling_faces) {
    const std::string what = series + "/" + std::to_string(f);
    const auto o = get(rep, what, "cellforge"), om = get(rep, what, "openmesh"), cg = get(rep, what, "cgal");
    const std::array<std::optional<double>, 3> ns{per_tri(o, f), per_tri(om, f), per_tri(cg, f)};
    if (f == scaling_faces.front()) first_ns = ns;
    out = {o, om, cg, growth(ns[0], first_ns[0]), growth(ns[1], first_ns[1]), growth(ns[2], first_ns[2])};
    t.add_row({cb::count(static_cast<std::size_t>(f)), cb::ms(o), cb::fixed(ns[0], 1), cb::fixed(ns[1], 0),
               cb::fixed(ns[2], 0), cb::ratio(om, o), cb::ratio(cg, o), three(rep, what, "faults_per_tri", 3),
               three(rep, what, "zeroed_kib_per_tri", 2)});
  }
  t.add_row({"growth 1M / 10k", "", cb::fixed(out.growth, 2) + "x", cb::fixed(out.om_growth, 2) + "x",
             cb::fixed(out.cgal_growth, 2) + "x", "", "", "", ""});
  t.add_note(note);
  if (series == "default" && made("scale/10000"))
    t.add_note("Cross-check (10k): " + cross_check("scale/10000") + ".");
  t.print(os);
  return out;
}

void print_tables(const cb::collecting_reporter& rep, std::ostream& os) {
  os << "\n## Loop subdivision (seed 001, tables 3 and 4)\n\nOne level of Loop subdivision, double-precision "
        "points everywhere. OpenMesh: Subdivider::Uniform::LoopT on "
        "TriMesh_ArrayKernelT<DefaultTraitsDouble>. "
        "CGAL: Subdivision_method_3::Loop_subdivision on Surface_mesh<Simple_cartesian<double>::Point_3>.\n"
        "Times: CPU ms of the subdivision alone (the input copy each iteration needs is not timed), median "
        "of "
        "the iterations (at least 5). Load average now: "
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

  const std::string faults_note =
      " Page faults: minor faults of the process during the timed run (getrusage ru_minflt), per "
      "input triangle; a fault maps one 4 KiB page, or one 2 MiB page where transparent huge "
      "pages apply (our large arrays carry a MADV_HUGEPAGE hint), zero-filled when it is new.";
  const scaling dflt = print_scaling(
      rep, os, "default",
      "Scaling, default glibc settings: small runs recycle memory, large ones map fresh pages",
      "No mallopt: these run first, with glibc's dynamic mmap threshold. At 10k and 100k glibc "
      "serves the arrays from memory the process already has; at 1M (about 280 MB of new arrays) "
      "they exceed the mmap threshold, so every run faults in and zeroes brand-new pages. The "
      "sizes do not run under the same conditions." +
          faults_note);
  const scaling cold = print_scaling(
      rep, os, "cold", "Scaling, cold: fresh zeroed pages at every size",
      "mallopt(M_MMAP_THRESHOLD = 64 KiB, M_TRIM_THRESHOLD = 0, M_TOP_PAD = 0) before each of "
      "these benchmarks and malloc_trim(0) before every iteration (untimed), for all three libraries: every "
      "block of 64 KiB or more is "
      "its own mmap, unmapped when freed, so each run, at 10k as at 1M, writes into new pages the "
      "kernel zero-fills (the page-fault column shows it). Same memory conditions at every size: "
      "this is the like-for-like growth measure for a single call on fresh memory." +
          faults_note);
  const scaling warm = print_scaling(
      rep, os, "warm", "Scaling, warm heap: glibc keeps and reuses freed memory at every size",
      "mallopt(M_MMAP_THRESHOLD and M_TRIM_THRESHOLD = 1 GiB) before each of these benchmarks, for all "
      "three libraries: after the first iteration no fresh pages, which isolates the algorithms' own "
      "cost (what repeated subdivision in one process sees)." +
          faults_note);

  os << "\n### Targets (" << cb::count(static_cast<std::size_t>(scaling_faces.back())) << " triangles)\n\n";
  for (const auto& [sc, heap_name] :
       {std::pair{&dflt, "default glibc settings"}, std::pair{&cold, "cold (fresh pages at every size)"},
        std::pair{&warm, "warm heap"}}) {
    if (sc->ours) {
      const char* verdict = !sc->om || !sc->cgal                                           ? "NOT CHECKED"
                            : (*sc->om >= 1.5 * *sc->ours && *sc->cgal >= 1.5 * *sc->ours) ? "MET"
                                                                                           : "NOT MET";
      os << "- " << heap_name
         << ": at least 1.5x faster than OpenMesh LoopT and CGAL Loop_subdivision: " << verdict
         << " (OpenMesh " << cb::ratio(sc->om, sc->ours) << ", CGAL " << cb::ratio(sc->cgal, sc->ours)
         << ")\n";
    }
    if (sc->growth)
      os << "- " << heap_name << ": linear growth, time per triangle at 1M within 1.5x of 10k: "
         << (*sc->growth <= 1.5 ? "MET" : "NOT MET") << " (" << cb::fixed(sc->growth, 2) << "x; OpenMesh "
         << cb::fixed(sc->om_growth, 2) << "x, CGAL " << cb::fixed(sc->cgal_growth, 2) << "x)\n";
  }
  os << "\nThe like-for-like growth measure is the cold series: the same memory conditions "
        "(new zero-filled pages) at every size.\n";
}

}  // namespace

int main(int argc, char** argv) { return cb::table_main(argc, argv, register_all, print_tables); }
