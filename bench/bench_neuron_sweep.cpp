// SPDX-License-Identifier: MIT
// The neuron-like set at full size (issue 35), too slow for CI: samples::neuron(seed) for seeds
// 1..count at a given number of samples, each meshed (make_tubes), checked exactly
// (tube_self_intersections) and for folds. Prints one line per neuron, names every miss, and the
// totals; the counters give the misses and the check's time over the meshing's. The tests run
// 100 of 1,000-10,000 samples (test_tubes.cpp).
//
//   build/bench/bench/bench_neuron_sweep                       every row (100k x 12, 30k x 20)
//   build/bench/bench/bench_neuron_sweep --benchmark_filter=100000

#include "bench_support.hpp"

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
  std::size_t misses = 0, folded = 0, intersecting = 0, refused = 0, merged = 0;
  double mesh_ms = 0, check_ms = 0;
  for (auto _ : state) {
    for (std::uint64_t seed = 1; seed <= count; ++seed) {
      const auto s = cellforge::samples::neuron(seed, {.samples = samples});
      try {
        const double t0 = cb::thread_cpu_ms();
        const auto r = cellforge::make_tubes(s);
        const double t1 = cb::thread_cpu_ms();
        const auto si = cellforge::tube_self_intersections(r.mesh);
        const double t2 = cb::thread_cpu_ms();
        const std::size_t folds = cellforge::folded_edges(r.mesh).edges.size();
        mesh_ms += t1 - t0, check_ms += t2 - t1, merged += r.merged_junctions;
        const bool good = folds == 0 && si.complete && si.intersecting_face_pairs == 0 &&
                          r.genus == r.cycle_rank && r.mesh.is_closed();
        std::printf(
            "neuron %llu (%zu samples): %.0f ms meshing, %.0f ms check, %zu merged, %zu folded edges, "
            "%zu intersecting face pairs%s%s\n",
            static_cast<unsigned long long>(seed), s.points.size(), t1 - t0, t2 - t1, r.merged_junctions,
            folds, si.intersecting_face_pairs, si.complete ? "" : " (incomplete)", good ? "" : "  <- miss");
        if (!good) ++misses;
        folded += folds != 0 ? 1 : 0, intersecting += si.intersecting_face_pairs != 0 ? 1 : 0;
      } catch (const std::exception& e) {
        ++misses, ++refused;
        std::printf("neuron %llu (%zu samples): refused: %s  <- miss\n",
                    static_cast<unsigned long long>(seed), s.points.size(), e.what());
      }
    }
  }
  std::printf(
      "neuron sweep, %zu samples: %llu neurons, %zu misses (%zu folded, %zu intersecting, %zu refused); "
      "check %.2fx the meshing\n",
      samples, static_cast<unsigned long long>(count), misses, folded, intersecting, refused,
      mesh_ms > 0 ? check_ms / mesh_ms : 0.0);
  state.counters["misses"] = static_cast<double>(misses);
  state.counters["merged"] = static_cast<double>(merged);
  state.counters["mesh_ms"] = mesh_ms;
  state.counters["check_over_mesh"] = mesh_ms > 0 ? check_ms / mesh_ms : 0.0;
}

BENCHMARK(neuron_sweep)->Args({100000, 12})->Args({30000, 20})->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
