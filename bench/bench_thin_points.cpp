// SPDX-License-Identifier: MIT
// Thin points, seed 000 §7.3 table 5 and the Stanford bunny: the seed's seconds for its six
// solids (quadrilateral and triangle versions, thresholds 40 and 100) beside ours on the
// stand-ins of samples/thin_solids.hpp (thin_table5_solid), in the fast mode and in the
// faithful mode (the seed's data structures), then the bunny at threshold 1 (and, beyond
// the seed, at 40 and 100).
//
// Extra flags (before Google Benchmark's own):
//   --faithful=all|quad|none  which table-5 cases also run in the faithful mode (default all)
//   --no_bunny_faithful       skip the bunny in the faithful mode (once, a few seconds)
// The bunny is read from CELLFORGE_BUNNY_FILE (environment, else the CMake cache variable;
// scripts/fetch-bunny.sh makes it); without the file its row says so and is skipped.

#include "bench_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "cellforge/algorithms/loop_subdivision.hpp"
#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/mesh.hpp"
#include "cellforge/io/mesh_io.hpp"
#include "cellforge/samples/thin_solids.hpp"
#include "cellforge/thin/thin_points.hpp"

#ifndef CELLFORGE_BUNNY_FILE
#define CELLFORGE_BUNNY_FILE ""
#endif

namespace {

namespace cb = cellforge::bench;

// ------------------------------------------------------------------------------ the seed's figures

/// Seed 000 §7.3 table 5 (VB.NET; the seed names no machine for §7.3, §7.4 says a 996 MHz
/// Pentium), seconds. Example 3's triangle time at threshold 40 reads "317176 s" in the
/// text (the decimal point lost in the scan); read as 317.176 s, since the other triangle
/// times at threshold 40 are 24–285 s and the same solid at threshold 100 took 1711 s.
struct seed_case {
  int faces;
  std::array<double, 2> seconds;  ///< thresholds 40 and 100
};
constexpr std::array<seed_case, 6> seed_quad{{{240, {12.648, 11.807}},
                                              {240, {12.318, 12.748}},
                                              {480, {47.759, 27.810}},
                                              {480, {34.309, 33.809}},
                                              {240, {12.167, 19.708}},
                                              {720, {34.089, 31.325}}}};
constexpr std::array<seed_case, 6> seed_tri{{{216, {26.298, 182.532}},
                                             {216, {56.511, 105.732}},
                                             {456, {317.176, 1711.090}},
                                             {456, {160.731, 584.390}},
                                             {222, {23.864, 58.795}},
                                             {696, {284.699, 1676.851}}}};
constexpr std::array<int, 2> thresholds{40, 100};
/// Seed 000 §7.3: the bunny at threshold 1 "took 83629223 ms" (23 h 14 min).
constexpr double seed_bunny_ms = 83'629'223;
/// The targets.
constexpr double target_case_ms = 50, target_bunny_ms = 1000;

// ------------------------------------------------------------------------------ inputs

/// A table-5 stand-in (samples/thin_solids.hpp: its soup and ground truth) and its mesh.
struct solid_case {
  cellforge::samples::thin_sample<glm::dvec3> sample;
  cellforge::surface_mesh<glm::dvec3> mesh;
};

const solid_case& solid(int example, bool triangles) {
  static std::map<std::pair<int, bool>, solid_case> cache;
  auto it = cache.find({example, triangles});
  if (it == cache.end()) {
    solid_case c{cellforge::samples::thin_table5_solid<glm::dvec3>(example, triangles), {}};
    c.mesh = cellforge::make_mesh(c.sample.soup);
    it = cache.emplace(std::pair{example, triangles}, std::move(c)).first;
  }
  return it->second;
}

std::filesystem::path bunny_path() {
  if (const char* env = std::getenv("CELLFORGE_BUNNY_FILE"); env != nullptr && *env != '\0') return env;
  return CELLFORGE_BUNNY_FILE;
}

/// The bunny, read once; empty when the file is absent.
const std::optional<cellforge::surface_mesh<glm::dvec3>>& bunny() {
  static const std::optional<cellforge::surface_mesh<glm::dvec3>> m =
      []() -> std::optional<cellforge::surface_mesh<glm::dvec3>> {
    const std::filesystem::path p = bunny_path();
    if (p.empty() || !std::filesystem::exists(p)) return std::nullopt;
    return cellforge::io::read_mesh<glm::dvec3>(p);
  }();
  return m;
}

// ------------------------------------------------------------------------------ runs

std::string case_name(const char* mode, int example, bool triangles, int threshold) {
  return std::string(mode) + "/" + (triangles ? "tri_" : "quad_") + std::to_string(example) + "/" +
         std::to_string(threshold);
}

cellforge::thin_options options_for(cellforge::thin_mode mode, int cap, bool cluster = false) {
  cellforge::thin_options o;
  o.mode = mode;
  o.selection_cap = cap;
  o.cluster_faces = cluster;  // seed 8.2: triangles grouped into fans and pairs before growing
  return o;
}

/// What the first run of each case found, for the table.
struct found {
  std::size_t loops = 0, cycles = 0;
  double thinnest = 0;  ///< length of the strongest loop
  double position = 0;  ///< its position along the axis, 0..1
  double z = 0;         ///< its centroid's z (the sample solids stand along z)
  std::vector<std::pair<std::size_t, double>> signature;  ///< (cycle, length) of every loop
  std::vector<std::string> described;                     ///< every loop in words, for notes
};
std::map<std::string, found>& findings() {
  static std::map<std::string, found> f;
  return f;
}

void register_case(const std::string& name, const cellforge::surface_mesh<glm::dvec3>* mesh,
                   cellforge::thin_options o, int iterations) {
  auto* b = benchmark::RegisterBenchmark(name.c_str(), [name, mesh, o](benchmark::State& s) {
    try {
      cb::timed_loop(
          s, [&] { return cellforge::find_thin_points(*mesh, o); },
          [&](const cellforge::thin_result<glm::dvec3>& r) {
            found f;
            f.loops = r.loops.size();
            f.cycles = r.cycle_lengths.size();
            for (const auto& l : r.loops) {
              f.signature.emplace_back(l.cycle, l.length);
              glm::dvec3 c(0.0);
              for (const glm::dvec3& p : l.points) c += p / static_cast<double>(l.points.size());
              f.described.push_back(
                  "length " + cb::fixed(l.length, 3) + " (" + std::to_string(l.vertices.size()) +
                  " edges) at " + cb::fixed(l.axis_position, 3) + " along the axis, cycle " +
                  std::to_string(l.cycle) + ", strength " + cb::fixed(l.strength, 3) + ", centroid (" +
                  cb::fixed(c.x, 2) + ", " + cb::fixed(c.y, 2) + ", " + cb::fixed(c.z, 2) + ")");
            }
            if (!r.loops.empty()) {
              f.thinnest = r.loops.front().length;
              f.position = r.loops.front().axis_position;
              for (const glm::dvec3& p : r.loops.front().points) f.z += p.z;
              f.z /= static_cast<double>(r.loops.front().points.size());
            }
            findings()[name] = f;
          });
    } catch (const cellforge::error& e) {
      s.SkipWithError(e.what());
    }
  });
  b->UseManualTime()->Unit(benchmark::kMillisecond);
  if (iterations > 0)
    b->Iterations(iterations);
  else
    b->MinTime(0.2);
}

// ------------------------------------------------------------------------------ growth

/// The growth rows: the 12-segment, 21-ring dumbbell (examples/data/dumbbell.off: 242 faces)
/// split into triangles (500) and Loop-subdivided 2 to 5 times (8k, 32k, 128k, 512k triangles), and
/// icospheres of 5k, 20k, 82k triangles (no neck: no loop expected).
struct growth_case {
  std::string name;
  std::size_t faces = 0;
  cellforge::surface_mesh<glm::dvec3> mesh;
};
std::vector<growth_case>& growth_cases() {
  static std::vector<growth_case> cases = [] {
    std::vector<growth_case> out;
    const auto base = cellforge::make_mesh(
        cellforge::triangulate_fan(cellforge::samples::thin_dumbbell<glm::dvec3>(12, 21, false).soup));
    for (const int levels : {2, 3, 4, 5}) {
      cellforge::loop_subdivision_options lo;
      lo.levels = levels;
      auto m = cellforge::loop_subdivided(base, lo);
      const std::size_t faces = m.num_faces();
      out.push_back({"dumbbell", faces, std::move(m)});
    }
    for (const int level : {4, 5, 6}) {
      auto m = cellforge::make_mesh(cellforge::icosphere<glm::dvec3>(level));
      const std::size_t faces = m.num_faces();
      out.push_back({"icosphere", faces, std::move(m)});
    }
    return out;
  }();
  return cases;
}

std::string growth_name(const growth_case& c, const char* mode) {
  return std::string("growth/") + c.name + "/" + std::to_string(c.faces) + "/" + mode;
}

void register_growth() {
  for (const growth_case& c : growth_cases())
    for (const auto& [mode, label] : {std::pair{cellforge::thin_mode::automatic, "default"},
                                      std::pair{cellforge::thin_mode::fast, "fast"}}) {
      // The seed's exact rule only where it finishes in seconds (it is O(faces^1.5) here).
      if (mode == cellforge::thin_mode::fast && c.faces > 10'000) continue;
      const std::string name = growth_name(c, label);
      const cellforge::surface_mesh<glm::dvec3>* mesh = &c.mesh;
      auto* b = benchmark::RegisterBenchmark(name.c_str(), [name, mesh, mode](benchmark::State& s) {
        cellforge::thin_options o;
        o.mode = mode;
        cb::median_loop(
            s, [&] { return cellforge::find_thin_points(*mesh, o); },
            [&](const cellforge::thin_result<glm::dvec3>& r) {
              found f;
              f.loops = r.loops.size();
              f.cycles = r.cycle_lengths.size();
              if (!r.loops.empty())
                f.thinnest = r.loops.front().length, f.position = r.loops.front().axis_position;
              findings()[name] = f;
            });
      });
      b->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
    }
}

void print_growth(const cb::collecting_reporter& reporter, std::ostream& os) {
  cb::table t("Growth: time to find thin points against faces (median of 3 runs, CPU ms)",
              {"solid", "triangles", "mode", "median ms", "× per 4× faces", "loops", "strongest loop"});
  std::map<std::string, double> previous;
  for (const growth_case& c : growth_cases())
    for (const char* label : {"default", "fast"}) {
      const std::string name = growth_name(c, label);
      if (reporter.find(name) == nullptr) continue;
      const std::optional<double> ms = reporter.counter_ms(name, "median_cpu_us");
      const std::string key = c.name + label;
      const auto prev = previous.find(key);
      const auto it = findings().find(name);
      std::string loop = "—";
      if (it != findings().end() && it->second.loops > 0)
        loop = "length " + cb::fixed(it->second.thinnest, 4) + " at " + cb::fixed(it->second.position, 3);
      t.add_row({c.name, cb::count(c.faces), label, cb::ms(ms),
                 prev != previous.end() && ms ? cb::fixed(*ms / prev->second, 2) : "",
                 it == findings().end() ? "not run" : std::to_string(it->second.loops), loop});
      if (ms) previous[key] = *ms;
    }
  t.add_note("default: thin_mode::automatic (the seed's rule up to 4000 faces, the scalable rule above).");
  t.add_note("Target (issue 35): the dumbbell at 128k triangles within 2 s; no loop on an icosphere.");
  t.print(os);
}

struct flags {
  std::string faithful = "all";
  bool bunny_faithful = true;
};

/// Takes our own flags out of argv (Google Benchmark rejects flags it does not know).
flags parse_flags(int& argc, char** argv) {
  flags f;
  int out = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--faithful=", 0) == 0)
      f.faithful = a.substr(std::strlen("--faithful="));
    else if (a == "--no_bunny_faithful")
      f.bunny_faithful = false;
    else
      argv[out++] = argv[i];
  }
  argc = out;
  return f;
}

void register_all(const flags& f) {
  register_growth();
  for (const bool tri : {false, true})
    for (int i = 1; i <= 6; ++i)
      for (const int t : thresholds) {
        const cellforge::surface_mesh<glm::dvec3>* m = &solid(i, tri).mesh;
        register_case(case_name("fast", i, tri, t), m, options_for(cellforge::thin_mode::fast, t), 0);
        if (tri)
          register_case(case_name("clustered", i, tri, t), m,
                        options_for(cellforge::thin_mode::fast, t, true), 0);
        if (f.faithful == "all" || (f.faithful == "quad" && !tri))
          register_case(case_name("faithful", i, tri, t), m, options_for(cellforge::thin_mode::faithful, t),
                        3);
      }
  if (const auto& b = bunny()) {
    register_case("fast/bunny/1", &*b, options_for(cellforge::thin_mode::fast, 1), 5);
    register_case("clustered/bunny/1", &*b, options_for(cellforge::thin_mode::fast, 1, true), 5);
    // Beyond the seed (it ran only threshold 1): the table-5 thresholds on the bunny.
    for (const int t : thresholds)
      register_case("fast/bunny/" + std::to_string(t), &*b, options_for(cellforge::thin_mode::fast, t), 3);
    if (f.bunny_faithful)
      register_case("faithful/bunny/1", &*b, options_for(cellforge::thin_mode::faithful, 1), 1);
  }
}

// ------------------------------------------------------------------------------ tables

std::string met(std::optional<double> ms, double target) {
  if (!ms) return "—";
  return *ms < target ? "MET" : "NOT MET";
}

/// "k loops, c cycles", and for a sample solid where the strongest loop is: at which neck
/// ring (within one ring spacing of it, the test) and its length against that ring's
/// polygon perimeter.
std::string outcome(const cb::collecting_reporter& reporter, const std::string& name,
                    const cellforge::samples::thin_sample<glm::dvec3>* truth = nullptr) {
  if (const cb::run_result* r = reporter.find(name); r != nullptr && !r->error.empty())
    return "error: " + r->error;
  const auto it = findings().find(name);
  if (it == findings().end()) return "not run";
  const found& f = it->second;
  std::string out = std::to_string(f.loops) + " loops, " + std::to_string(f.cycles) + " cycles";
  if (truth == nullptr || f.loops == 0) return out;
  int best = -1;
  for (const int k : truth->necks) {
    const auto ring = truth->profile[static_cast<std::size_t>(k)];
    if (std::abs(ring.y - f.z) <= truth->ring_spacing &&
        (best < 0 ||
         std::abs(ring.y - f.z) < std::abs(truth->profile[static_cast<std::size_t>(best)].y - f.z)))
      best = k;
  }
  if (best < 0) return out + "; strongest loop at z " + cb::fixed(f.z, 2) + ": at no neck";
  const double r = truth->profile[static_cast<std::size_t>(best)].x;
  const double perimeter = 2.0 * truth->segments * r * std::sin(std::numbers::pi / truth->segments);
  return out + "; strongest at neck z " + cb::fixed(truth->profile[static_cast<std::size_t>(best)].y, 2) +
         ", length " + (f.thinnest >= perimeter ? "+" : "") +
         cb::fixed(100.0 * (f.thinnest / perimeter - 1.0), 1) + " %";
}

/// Whether the faithful run reported the same loops (cycles, lengths to 1e-9) as the fast one.
std::string same_loops(const std::string& fast, const std::string& faithful) {
  const auto a = findings().find(fast), b = findings().find(faithful);
  if (a == findings().end() || b == findings().end()) return "—";
  const auto& x = a->second.signature;
  const auto& y = b->second.signature;
  bool same = x.size() == y.size();
  for (std::size_t i = 0; same && i < x.size(); ++i)
    same =
        x[i].first == y[i].first && std::abs(x[i].second - y[i].second) <= 1e-9 * std::max(1.0, x[i].second);
  return same ? "same" : "DIFFERENT";
}

void print_tables(const cb::collecting_reporter& reporter, const flags& f, std::ostream& os) {
  os << "\n## Thin points: seed 000 §7.3 table 5 and the Stanford bunny\n\nLoad average "
     << cb::load_average()
     << ". Seed: VB.NET (seconds in table 5, here in ms). Ours: CPU ms, best of the iterations "
        "(fast: ≥ 0.2 s of iterations; faithful: 3 iterations; the bunny: 5 at threshold 1, 3 at 40 "
        "and 100, faithful once).\n";
  cb::table t("Table 5: time to find thin points",
              {"ex.", "faces", "seed faces", "threshold", "seed ms", "fast ms", "ratio (seed / fast)",
               "faithful ms", "ratio (seed / faithful)", "faithful loops", "< 50 ms", "fast result",
               "clustered ms", "clustered result"});
  std::size_t met_count = 0, cases = 0;
  double worst = 0;
  std::string worst_name;
  for (const bool tri : {false, true})
    for (int i = 1; i <= 6; ++i)
      for (std::size_t k = 0; k < thresholds.size(); ++k) {
        const int thr = thresholds[k];
        const seed_case& s = (tri ? seed_tri : seed_quad)[static_cast<std::size_t>(i - 1)];
        const std::string fast = case_name("fast", i, tri, thr),
                          faithful = case_name("faithful", i, tri, thr);
        const std::optional<double> ours = reporter.ms(fast), slow = reporter.ms(faithful);
        const double seed = s.seconds[k] * 1e3;
        if (ours) ++cases;
        if (ours && *ours < target_case_ms) ++met_count;
        if (ours && *ours > worst) {
          worst = *ours;
          worst_name = fast;
        }
        const cb::run_result* fr = reporter.find(faithful);
        t.add_row(
            {std::to_string(i) + (tri ? " tri" : " quad"), cb::count(solid(i, tri).mesh.num_faces()),
             cb::count(static_cast<std::size_t>(s.faces)), std::to_string(thr), cb::ms(seed), cb::ms(ours),
             cb::ratio(seed, ours.value_or(std::numeric_limits<double>::quiet_NaN())),
             fr == nullptr       ? "not run"
             : fr->error.empty() ? cb::ms(slow)
                                 : "error",
             cb::ratio(seed, slow.value_or(std::numeric_limits<double>::quiet_NaN())),
             same_loops(fast, faithful), met(ours, target_case_ms),
             outcome(reporter, fast, &solid(i, tri).sample),
             tri ? cb::ms(reporter.ms(case_name("clustered", i, tri, thr))) : "(no pairs)",
             tri ? outcome(reporter, case_name("clustered", i, tri, thr), &solid(i, tri).sample) : "—"});
      }
  t.add_note(
      "Seed example 3 (triangles, threshold 40) reads \"317176 s\" in the seed's text; taken as 317.176 s.");
  t.add_note("Faithful mode run for: " + f.faithful +
             " (flag --faithful=all|quad|none); \"same\": the same loops (cycle, length) as the fast mode.");
  t.add_note(
      "clustered: the fast mode with cluster_faces (seed 8.2: flat triangle fans and mutual-best triangle "
      "pairs grown as one face; cycles count the groups). Quad solids have nothing to group.");
  t.add_note("Target: every case under 50 ms (fast mode): " + std::to_string(met_count) + " of " +
             std::to_string(cases) + " measured (of 24) MET; slowest " + worst_name + " " + cb::ms(worst) +
             " ms.");
  t.print(os);

  cb::table b("The Stanford bunny", {"model", "mode", "threshold", "vertices", "triangles", "seed ms",
                                     "ours ms", "ratio (seed / ours)", "< 1 s", "loops", "result"});
  if (const auto& m = bunny()) {
    const std::array<std::pair<const char*, int>, 5> runs{
        {{"fast", 1}, {"clustered", 1}, {"faithful", 1}, {"fast", thresholds[0]}, {"fast", thresholds[1]}}};
    for (const auto& [mode, cap] : runs) {
      const std::string name = std::string(mode) + "/bunny/" + std::to_string(cap);
      if (reporter.find(name) == nullptr) continue;
      const std::optional<double> ours = reporter.ms(name);
      const std::optional<double> seed = cap == 1 ? std::optional<double>(seed_bunny_ms) : std::nullopt;
      const bool target = cap == 1 && std::string(mode) == "fast";
      b.add_row({"bunny", mode, std::to_string(cap), cb::count(m->num_vertices()), cb::count(m->num_faces()),
                 cb::ms(seed), cb::ms(ours), cb::ratio(seed, ours),
                 target ? met(ours, target_bunny_ms) : "(not a target)",
                 std::string(mode) == "faithful" ? same_loops("fast/bunny/1", name) + " as fast" : "",
                 outcome(reporter, name)});
    }
    const auto& pts = m->get_vertex_property<glm::dvec3>("v:point").vector();
    glm::dvec3 lower(std::numeric_limits<double>::infinity()), upper(-lower);
    for (const glm::dvec3& p : pts) {
      lower = glm::min(lower, p);
      upper = glm::max(upper, p);
    }
    b.add_note("Bunny bounding box (" + cb::fixed(lower.x, 2) + ", " + cb::fixed(lower.y, 2) + ", " +
               cb::fixed(lower.z, 2) + ") to (" + cb::fixed(upper.x, 2) + ", " + cb::fixed(upper.y, 2) +
               ", " + cb::fixed(upper.z, 2) + ").");
    for (const int cap : {1, thresholds[0], thresholds[1]})
      if (const auto it = findings().find("fast/bunny/" + std::to_string(cap)); it != findings().end())
        for (const std::string& d : it->second.described)
          b.add_note("Threshold " + std::to_string(cap) + " loop: " + d + ".");
  } else {
    b.add_row({"bunny", "—", "1", "—", "—", cb::ms(seed_bunny_ms), "skipped", "—", "—", "",
               "no " + bunny_path().string() + ": run bash scripts/fetch-bunny.sh build/data"});
  }
  b.add_note(
      "Seed: \"The execution took 83629223 ms\" (§7.3). Bunny: npm package bunny@1.0.1 (fetch-bunny.sh).");
  b.print(os);
}

}  // namespace

int main(int argc, char** argv) {
  const flags f = parse_flags(argc, argv);
  if (f.faithful != "all" && f.faithful != "quad" && f.faithful != "none") {
    std::cerr << "bench_thin_points: --faithful=" << f.faithful << " is not one of all, quad, none\n";
    return 1;
  }
  return cb::table_main(
      argc, argv, [&] { register_all(f); },
      [&](const cb::collecting_reporter& r, std::ostream& os) {
        print_tables(r, f, os);
        print_growth(r, os);
      });
}
