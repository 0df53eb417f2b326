// Sketches, seed 003 "Finding faces": the Varley–Company face finder beside the
// shortest-loops baseline on drawings of 10 to 1,000 edges — ms per drawing, right or wrong
// against the model's faces, and the practical growth exponent (the seed: about e^2.7, its
// largest drawing of 251 edges slightly over 1 s). Every row is the median of its iterations.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "cellforge/sketch/face_finder.hpp"
#include "cellforge/sketch/sample_drawings.hpp"

namespace {

namespace cb = cellforge::bench;

struct drawing_case {
  std::string family, name;
  cellforge::sample_drawing s;
};

std::vector<drawing_case>& cases() {
  static std::vector<drawing_case> c = [] {
    std::vector<drawing_case> out;
    // Edge counts 12 … 999 in each family; tiny margins are fine for timing large n-gons.
    for (std::size_t n : {4u, 10u, 20u, 40u, 84u, 160u, 333u})
      out.push_back({"prism", "prism " + std::to_string(n),
                     cellforge::generic_drawing(cellforge::sample_prism(n), 1, "prism", 1e-7)});
    for (auto [a, b] : std::vector<std::pair<std::size_t, std::size_t>>{
             {4, 3}, {6, 4}, {8, 6}, {12, 8}, {16, 10}, {24, 14}, {28, 18}})
      out.push_back({"uv sphere", "uv sphere " + std::to_string(a) + "x" + std::to_string(b),
                     cellforge::generic_drawing(cellforge::sample_uv_sphere(a, b), 1, "sphere", 1e-7)});
    return out;
  }();
  return c;
}

std::map<std::string, std::size_t>& right() {
  static std::map<std::string, std::size_t> m;
  return m;
}

bool same_loops(const std::vector<std::vector<std::uint32_t>>& a,
                const std::vector<std::vector<std::uint32_t>>& b) {
  std::multiset<std::vector<std::uint32_t>> x, y;
  for (const auto& l : a) x.insert(cellforge::detail::canonical_cycle(l));
  for (const auto& l : b) y.insert(cellforge::detail::canonical_cycle(l));
  return x == y;
}

const char* kind_name(cellforge::face_finder_kind k) {
  return k == cellforge::face_finder_kind::varley_company ? "vc" : "sl";
}

void register_all() {
  for (const drawing_case& c : cases())
    for (const auto kind :
         {cellforge::face_finder_kind::varley_company, cellforge::face_finder_kind::shortest_loops}) {
      const std::string name = std::string("faces/") + kind_name(kind) + "/" + c.name;
      benchmark::RegisterBenchmark(
          name.c_str(),
          [&c, kind, name](benchmark::State& state) {
            cellforge::face_finder_options o;
            o.kind = kind;
            try {
              cb::median_loop(
                  state, [&] { return cellforge::find_faces(c.s.drawing, o); },
                  [&](const auto& r) { right()[name] = same_loops(r.loops, c.s.loops); });
            } catch (const std::exception& e) {
              state.SkipWithError(e.what());
            }
          })
          ->Iterations(c.s.drawing.edges.size() > 400 ? 5 : 9)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
    }
}

// Least-squares slope of log(ms) against log(edges). O(n).
std::optional<double> exponent(const std::vector<std::pair<double, double>>& xy) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  std::size_t n = 0;
  for (const auto& [x, y] : xy) {
    if (!(x > 0 && y > 0)) continue;
    const double lx = std::log(x), ly = std::log(y);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, ++n;
  }
  if (n < 2) return std::nullopt;
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

void print_tables(const cb::collecting_reporter& r, std::ostream& os) {
  os << "\n## Sketches: finding faces (seed 003)\n\nLoad average " << cb::load_average()
     << ". Median CPU ms of 5–9 iterations, one thread; right = exactly the model's face loops.\n";
  cb::table t("Face finding: Varley-Company (ours) and the shortest-loops baseline",
              {"drawing", "edges", "Varley-Company ms", "right", "shortest loops ms", "right",
               "seed ms (251 edges)", "ratio (seed / ours)"});
  std::map<std::string, std::vector<std::pair<double, double>>> growth_vc, growth_sl;
  for (const drawing_case& c : cases()) {
    const std::string vc = "faces/vc/" + c.name, sl = "faces/sl/" + c.name;
    const std::optional<double> a = r.counter_ms(vc, "median_cpu_us"), b = r.counter_ms(sl, "median_cpu_us");
    const double edges = static_cast<double>(c.s.drawing.edges.size());
    if (a) growth_vc[c.family].push_back({edges, *a});
    if (b) growth_sl[c.family].push_back({edges, *b});
    // The seed's figure at its largest drawing, scaled to this size by its own e^2.7.
    const double seed_ms = 1000.0 * std::pow(edges / 251.0, 2.7);
    t.add_row({c.name, cb::count(c.s.drawing.edges.size()), cb::ms(a), right()[vc] ? "yes" : "NO", cb::ms(b),
               right()[sl] ? "yes" : "no", cb::ms(seed_ms), cb::ratio(seed_ms, a)});
  }
  t.add_note(
      "Seed column: 'slightly more than one second' at 251 edges, scaled by the seed's practical e^2.7.");
  t.add_note("Targets (issue): 251 edges < 10 ms; 1,000 edges < 100 ms.");
  t.print(os);
  cb::table g("Practical growth exponent (slope of log ms over log edges)",
              {"family", "Varley-Company", "shortest loops", "seed"});
  for (const auto& [family, xy] : growth_vc)
    g.add_row({family, cb::fixed(exponent(xy), 2), cb::fixed(exponent(growth_sl[family]), 2), "2.7"});
  g.print(os);
}

}  // namespace

int main(int argc, char** argv) { return cb::table_main(argc, argv, register_all, print_tables); }
