// SPDX-License-Identifier: MIT
// The neuron-like set at full size (issue 35), too slow for CI: samples::neuron(seed) for seeds
// 1..count at a given number of samples, each meshed alone (make_tubes, no check, no repair) and
// end to end as the tubes program meshes (check_self_intersections, and so the repair of what it
// finds), the end-to-end mesh taken as good only with 0 folds, 0 intersecting pairs (the exact
// check of the result, run again here), genus = cycle rank. Prints one line per neuron, names
// every miss, and the totals; the counters give the misses and end to end over meshing alone.
// The tests run 100 of 1,000-10,000 samples (test_tubes.cpp).
//
//   build/bench/bench/bench_neuron_sweep                       every row (100k x 12, 30k x 20,
//                                                              the tests' 100 of 1k-10k: "0/100")
//   build/bench/bench/bench_neuron_sweep --benchmark_filter=100000

#include "bench_support.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>

#include "cellforge/algorithms/piece_self_intersections.hpp"
#include "cellforge/halfedge/mesh_geometry.hpp"
#include "cellforge/samples/skeletons.hpp"
#include "cellforge/tubes/tube_mesh.hpp"

namespace {

namespace cb = cellforge::bench;

void neuron_sweep(benchmark::State& state) {
  const auto samples = static_cast<std::size_t>(state.range(0));
  const auto count = static_cast<std::uint64_t>(state.range(1));
  std::size_t misses = 0, folded = 0, intersecting = 0, refused = 0, merged = 0, repaired = 0;
  double mesh_ms = 0, full_ms = 0;
  for (auto _ : state) {
    for (std::uint64_t seed = 1; seed <= count; ++seed) {
      // samples 0: the tests' sweep (test_tubes.cpp), neuron t = seed - 1 of seed 7000 + t, most
      // of 1,000-2,000 samples and every tenth of up to 10,000.
      const std::uint64_t t = seed - 1;
      const double u = static_cast<double>(t) * 0.6180339887498949 -
                       std::floor(static_cast<double>(t) * 0.6180339887498949);
      const std::size_t n = samples != 0  ? samples
                            : t % 10 == 9 ? static_cast<std::size_t>(2000 * std::pow(5.0, u))
                                          : static_cast<std::size_t>(1000 * std::pow(2.0, u));
      const auto s = cellforge::samples::neuron(samples != 0 ? seed : 7000 + t, {.samples = n});
      const auto name = static_cast<unsigned long long>(samples != 0 ? seed : t);  // as the tests say
      try {
        cellforge::tubes_options alone, full;
        alone.repair_rounds = 0;
        full.check_self_intersections = true;
        const double t0 = cb::thread_cpu_ms();
        benchmark::DoNotOptimize(cellforge::make_tubes(s, alone));
        const double t1 = cb::thread_cpu_ms();
        const auto r = cellforge::make_tubes(s, full);
        const double t2 = cb::thread_cpu_ms();
        const auto si = cellforge::tube_self_intersections(r.mesh);
        const std::size_t folds = cellforge::folded_edges(r.mesh).edges.size();
        mesh_ms += t1 - t0, full_ms += t2 - t1, merged += r.merged_junctions;
        repaired += r.careful_nodes > 0 ? 1 : 0;
        const bool good = folds == 0 && si.complete && si.intersecting_face_pairs == 0 &&
                          r.genus == r.cycle_rank && r.mesh.is_closed();
        std::printf(
            "neuron %llu (%zu samples): %.0f ms meshing alone, %.0f ms end to end (%d repair rounds, %zu "
            "careful nodes), %zu merged, %zu folded edges, %zu intersecting face pairs%s%s\n",
            name, s.points.size(), t1 - t0, t2 - t1, r.repair_rounds, r.careful_nodes, r.merged_junctions,
            folds, si.intersecting_face_pairs, si.complete ? "" : " (incomplete)", good ? "" : "  <- miss");
        if (!good) ++misses;
        folded += folds != 0 ? 1 : 0, intersecting += si.intersecting_face_pairs != 0 ? 1 : 0;
      } catch (const std::exception& e) {
        ++misses, ++refused;
        std::printf("neuron %llu (%zu samples): refused: %s  <- miss\n", name, s.points.size(), e.what());
      }
    }
  }
  std::printf(
      "neuron sweep, %zu samples: %llu neurons, %zu misses (%zu folded, %zu intersecting, %zu refused), "
      "%zu repaired; end to end %.2fx the meshing alone\n",
      samples, static_cast<unsigned long long>(count), misses, folded, intersecting, refused, repaired,
      mesh_ms > 0 ? full_ms / mesh_ms : 0.0);
  state.counters["misses"] = static_cast<double>(misses);
  state.counters["merged"] = static_cast<double>(merged);
  state.counters["repaired"] = static_cast<double>(repaired);
  state.counters["mesh_ms"] = mesh_ms;
  state.counters["full_over_mesh"] = mesh_ms > 0 ? full_ms / mesh_ms : 0.0;
}

BENCHMARK(neuron_sweep)
    ->Args({100000, 12})
    ->Args({30000, 20})
    ->Args({0, 100})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
