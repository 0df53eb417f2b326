// SPDX-License-Identifier: MIT
// The wireframe pipeline on coordinates that carry noise (docs/wireframe.md, "Tolerances"): the
// sweep of tests/wireframe_sweep.hpp with every vertex moved by up to 1e-9, 1e-6 and 1e-4 of
// the diagonal, the sweep turned and written with 6 and 10 significant digits, parts of very
// different sizes side by side, and the tolerance estimator on its own. A miss must be flagged
// (wireframe_result::tolerance.ambiguous) or an error, never a wrong answer passed as good.
// Release runs every model; the sanitizer build a quarter of the sweep's sample.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/wireframe/tolerance_estimate.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"
#include "wireframe_sweep.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace wireframe_noise_tests {

namespace {

using cellforge::samples::sample_model;
using wireframe_sweep::noisy_outcome;

// The models: the full sweep in Release, every fourth model of the sample under the
// sanitizers (CELLFORGE_SWEEP=full|sample chooses the sweep). O(make_sweep).
std::vector<wireframe_sweep::sweep_model> models(bool& full) {
  full = true;
#ifndef NDEBUG
  full = false;
#endif
  if (const char* env = std::getenv("CELLFORGE_SWEEP")) full = std::string(env) == "full";
  auto set = wireframe_sweep::make_sweep(full ? wireframe_sweep::sweep_size::full
                                              : wireframe_sweep::sweep_size::sample);
  if (full) return set.models;
  std::vector<wireframe_sweep::sweep_model> quarter;
  for (std::size_t i = 0; i < set.models.size(); i += 4) quarter.push_back(set.models[i]);
  return quarter;
}

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

cellforge::samples::sample_model box(glm::dvec3 lo, glm::dvec3 hi, std::string name) {
  cellforge::samples::voxel_layout l =
      cellforge::samples::empty_layout({lo.x, hi.x}, {lo.y, hi.y}, {lo.z, hi.z});
  l.labels[0] = 1;
  return cellforge::samples::make_voxel_model(l, std::move(name));
}

// Converts with default options; empty when the result is the truth (checked with the
// options the pipeline used), else why.
std::string convert(const sample_model& m) {
  try {
    const auto r = cellforge::wireframe_to_cells(m.wire);
    return wireframe_sweep::miss_reason(m, r, r.check);
  } catch (const cellforge::error& e) {
    return std::string("error: ") + e.what();
  }
}

}  // namespace

TEST_CASE("wireframe noise: the sweep with every vertex moved by 1e-9, 1e-6 and 1e-4 of the diagonal") {
  bool full = true;
  const auto set = models(full);
  const char* names[] = {"exact", "flagged", "error", "WRONG"};
  for (const double eps : {1e-9, 1e-6, 1e-4}) {
    std::map<noisy_outcome, std::size_t> count;
    std::vector<std::string> misses;
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& s : set) {
      const sample_model m = wireframe_sweep::noisy(
          s.model, eps,
          wireframe_sweep::name_seed(s.model.name) ^ static_cast<std::uint64_t>(-std::log10(eps)));
      std::string why;
      const noisy_outcome o = wireframe_sweep::judge_noisy(m, why, s.family == "big polycube");
      ++count[o];
      if (o == noisy_outcome::exact) continue;
      // Would a fixed tolerance have read it? (Release only: up to 14 conversions a miss.)
      const char* kind = !full                                      ? ""
                         : wireframe_sweep::some_tolerance_reads(m) ? " [ours: a fixed tolerance reads it]"
                                                                    : " [no fixed tolerance reads it]";
      misses.push_back("[" + s.family + "] " + s.model.name + " (" + names[static_cast<int>(o)] + ")" + kind +
                       ": " + why.substr(0, 240));
    }
    const double ms = ms_since(t0);
    const std::size_t n = set.size(), exact = count[noisy_outcome::exact];
    const double rate = n == 0 ? 0.0 : 100.0 * double(exact) / double(n);
    std::printf(
        "\nwireframe noise %g (%s): %zu models, %zu exact (%.1f %%), %zu flagged, %zu errors, %zu wrong; "
        "%.0f ms\n",
        eps, full ? "full" : "sample", n, exact, rate, count[noisy_outcome::flagged],
        count[noisy_outcome::error], count[noisy_outcome::wrong], ms);
    for (const auto& line : misses) std::printf("  %s\n", line.c_str());
    std::fflush(stdout);
    CAPTURE(eps);
    CHECK(count[noisy_outcome::wrong] == 0);  // a miss is flagged or an error, at every level
    if (eps <= 1e-6)
      CHECK(exact == n);
    else if (full)
      CHECK(rate >= 95.0);
  }
}

TEST_CASE("wireframe noise: the sweep turned and written with 10 and 6 significant digits") {
  // The shuffled sweep: half its models stand up to ten sizes from the origin, where six
  // digits leave noise of up to 1e-5 of the diagonal.
  bool full = true;
  const auto set = models(full);
  for (const int digits : {10, 6}) {
    std::map<noisy_outcome, std::size_t> count;
    for (const auto& s : set) {
      wireframe_sweep::random_source rng(wireframe_sweep::name_seed(s.model.name) ^ 77);
      sample_model m = cellforge::samples::transformed(s.model, wireframe_sweep::detail::random_rotation(rng),
                                                       glm::dvec3(0.0));
      char text[64];
      for (auto& p : m.wire.points)
        for (int k = 0; k < 3; ++k) {
          std::snprintf(text, sizeof text, "%.*g", digits, p[k]);
          p[k] = std::strtod(text, nullptr);
        }
      std::string why;
      const noisy_outcome o = wireframe_sweep::judge_noisy(m, why, s.family == "big polycube");
      ++count[o];
      if (o != noisy_outcome::exact)
        std::printf("  %%.%dg [%s] %s (%s): %s\n", digits, s.family.c_str(), s.model.name.c_str(),
                    o == noisy_outcome::wrong   ? "WRONG"
                    : o == noisy_outcome::error ? "error"
                                                : "flagged",
                    why.substr(0, 200).c_str());
      const std::string name = s.model.name;
      CAPTURE(digits);
      CAPTURE(name);
      CHECK(o != noisy_outcome::wrong);
      if (digits == 10) CHECK_MESSAGE(o == noisy_outcome::exact, why);
    }
    std::printf("\nwireframe decimals %%.%dg: %zu of %zu exact, %zu flagged, %zu errors, %zu wrong\n", digits,
                count[noisy_outcome::exact], set.size(), count[noisy_outcome::flagged],
                count[noisy_outcome::error], count[noisy_outcome::wrong]);
  }
}

TEST_CASE("wireframe noise: the ordinary solids with every vertex moved by 1e-9, 1e-6 and 1e-4") {
  // wireframe_sweep::make_ordinary_sweep (height fields, boxes with fins, extrusions, turned
  // boxes): exact at 1e-9 and 1e-6, 95 % at 1e-4 (Release), and never a wrong answer passed as
  // good at any level; every miss named with its reason. The sample under the sanitizers.
  bool full = true;
#ifndef NDEBUG
  full = false;
#endif
  const auto set = wireframe_sweep::make_ordinary_sweep(full ? wireframe_sweep::sweep_size::full
                                                             : wireframe_sweep::sweep_size::sample);
  const char* names[] = {"exact", "flagged", "error", "WRONG"};
  for (const double eps : {1e-9, 1e-6, 1e-4}) {
    std::map<noisy_outcome, std::size_t> count;
    std::vector<std::string> misses;
    for (const auto& s : set.models) {
      const sample_model m = wireframe_sweep::noisy(
          s.model, eps,
          wireframe_sweep::name_seed(s.model.name) ^ static_cast<std::uint64_t>(-std::log10(eps)));
      std::string why;
      const noisy_outcome o = wireframe_sweep::judge_noisy(m, why);
      ++count[o];
      if (o != noisy_outcome::exact) {
        // Would a fixed tolerance have read it? (Release only: up to 14 conversions a miss.)
        const char* kind = !full                                      ? ""
                           : wireframe_sweep::some_tolerance_reads(m) ? " [ours: a fixed tolerance reads it]"
                                                                      : " [no fixed tolerance reads it]";
        // The estimate's figures: why the tolerance was not found (the error's text is long).
        const auto t = cellforge::estimate_tolerance(cellforge::read_vertices(m.wire).graph);
        char est[160];
        std::snprintf(est, sizeof est, "; estimate: noise %.2g, shape %.2g %s, %.2f decades%s", t.noise,
                      t.geometry,
                      t.noise_gain ? "(over noise gains, of the diagonal)" : "(over edges' lengths)",
                      t.gap_decades, t.clear_gap ? "" : " (no clear gap)");
        misses.push_back("[" + s.family + "] " + s.model.name + " (" + names[static_cast<int>(o)] + ")" +
                         kind + ": " +
                         why.substr(0, std::min<std::size_t>(160, why.find("; the residuals"))) + est);
      }
      const std::string name = s.model.name;
      CAPTURE(eps);
      CAPTURE(name);
      CHECK(o != noisy_outcome::wrong);
      if (eps <= 1e-6) CHECK_MESSAGE(o == noisy_outcome::exact, why);
    }
    const std::size_t n = set.models.size(), exact = count[noisy_outcome::exact];
    std::printf("\nordinary solids, noise %g: %zu of %zu exact, %zu flagged, %zu errors, %zu wrong\n", eps,
                exact, n, count[noisy_outcome::flagged], count[noisy_outcome::error],
                count[noisy_outcome::wrong]);
    for (const auto& line : misses) std::printf("  %s\n", line.c_str());
    CAPTURE(eps);
    if (full && eps > 1e-6) CHECK(100.0 * double(exact) >= 95.0 * double(n));
  }
  std::fflush(stdout);
}

TEST_CASE("wireframe noise: parts of very different sizes side by side") {
  SUBCASE("a 1e-4 L, T, U, frame or house beside a bar of 100 or 10^4: exact and quick") {
    // The arrangement's grid has cells of the small part's size: the bar's faces crossed
    // 10^10 cells, one by one, until the work budget ran out (about a minute).
    for (const auto& base :
         {cellforge::samples::sample_L(), cellforge::samples::sample_T(), cellforge::samples::sample_U(),
          cellforge::samples::sample_frame(), cellforge::samples::sample_house()})
      for (const double length : {1e2, 1e4}) {
        const sample_model m = cellforge::samples::disjoint_union(
            cellforge::samples::transformed(base, glm::dmat3(1e-4), glm::dvec3(0.0)),
            box({0, 0, 0}, {length, 1, 1}, "bar"), {0, 2, 0}, base.name);
        const std::string name = base.name;
        CAPTURE(name);
        CAPTURE(length);
        const auto r = cellforge::wireframe_to_cells(m.wire);
        CHECK(wireframe_sweep::miss_reason(m, r, r.check).empty());
        CHECK(r.arrangement.pairs_tested < 1000);
      }
  }
  SUBCASE("a unit cube beside a bar reaching 10^6 or 10^9, a 1e-4 cube beside a 10^4 bar") {
    // The merge tolerance was 1e-9 of the diagonal: a bar to 10^9 merged the cube into a point.
    // validate() asked a volume for 1e-12 of its diagonal cubed: a 10^4 x 1e-2 x 1e-2 bar failed.
    const sample_model parts[] = {
        cellforge::samples::disjoint_union(box({0, 0, 0}, {1, 1, 1}, "cube"),
                                           box({0, 0, 0}, {1e6, 1, 1}, "bar"), {0, 3, 0}, "1e6"),
        cellforge::samples::disjoint_union(box({0, 0, 0}, {1, 1, 1}, "cube"),
                                           box({0, 0, 0}, {1e9, 1, 1}, "bar"), {0, 3, 0}, "1e9"),
        cellforge::samples::disjoint_union(box({0, 0, 0}, {1e-4, 1e-4, 1e-4}, "cube"),
                                           box({0, 0, 0}, {1e4, 1e-2, 1e-2}, "bar"), {0, 1e-3, 0},
                                           "thin bar")};
    for (const auto& m : parts) {
      const std::string name = m.name;
      CAPTURE(name);
      const auto r = cellforge::wireframe_to_cells(m.wire);
      CHECK(r.read.merged_points == 0);
      CHECK(wireframe_sweep::miss_reason(m, r, r.check).empty());
    }
  }
  SUBCASE("points closer than 1e-9 of their own edges merge, however large the model") {
    sample_model m = cellforge::samples::disjoint_union(
        box({0, 0, 0}, {1, 1, 1}, "cube"), box({0, 0, 0}, {1e9, 1, 1}, "bar"), {0, 3, 0}, "twin");
    // A twin of cube vertex 0, 1e-10 away, carrying the cube's edge 0-1 in its place: merged back.
    const auto twin = static_cast<std::uint32_t>(m.wire.points.size());
    m.wire.points.push_back(m.wire.points[0] + glm::dvec3(1e-10, 0, 0));
    for (auto& e : m.wire.edges)
      if ((e[0] == 0 && e[1] == 1) || (e[0] == 1 && e[1] == 0)) e = {twin, 1};
    const auto r = cellforge::wireframe_to_cells(m.wire);
    CHECK(r.read.merged_points == 1);
    CHECK(r.input.faces.size() == 12);
    CHECK(r.input.volumes.size() == 2);
  }
}

TEST_CASE("wireframe noise: the tolerance estimator") {
  const sample_model cube = cellforge::samples::sample_cube();
  SUBCASE("exact input keeps the old default, with the rounding far below the shape") {
    for (const auto& m : {cube, cellforge::samples::sample_stepped_block(),
                          cellforge::samples::sample_frame(), cellforge::samples::sample_seed(2)}) {
      const std::string name = m.name;
      CAPTURE(name);
      const auto r = cellforge::wireframe_to_cells(m.wire);
      CHECK(r.tolerance.automatic);
      CHECK(r.tolerance.clear_gap);
      CHECK(!r.tolerance.ambiguous);
      CHECK(r.tolerance.planarity == 1e-9);
      CHECK(r.tolerance.gap_decades > 8.0);
    }
  }
  SUBCASE("noise of 1e-4: a clear gap, the tolerance inside it, the old default too small") {
    const sample_model m = wireframe_sweep::noisy(cellforge::samples::sample_grid(4, 3, 2), 1e-4, 7);
    const auto g = cellforge::read_vertices(m.wire).graph;
    const cellforge::tolerance_result t = cellforge::estimate_tolerance(g);
    CHECK(t.clear_gap);
    CHECK(t.gap_decades >= 1.5);
    CHECK(t.noise_distance > 1e-6 * g.size);  // the noise is seen
    CHECK(t.noise_distance < 4e-4 * g.size);
    CHECK(t.planarity_distance > 3 * t.noise_distance);
    CHECK(t.planarity_distance < t.geometry_distance / 3);
    CHECK(convert(m).empty());
    // The same file with the old fixed tolerance (automatic off) misses faces.
    cellforge::wireframe_options fixed;
    fixed.tolerance.automatic = false;
    bool missed = true;
    try {
      const auto r = cellforge::wireframe_to_cells(m.wire, fixed);
      missed = !wireframe_sweep::miss_reason(m, r, r.check).empty();
      CHECK(!r.tolerance.automatic);
      CHECK(r.tolerance.planarity == 1e-9);
    } catch (const cellforge::error&) {
    }
    CHECK(missed);
  }
  SUBCASE("noise as large as the shape: no clear gap, and the answer is flagged or refused") {
    // A 24-sided barrel's rings stand about 1e-2 of their edges off the bands' planes: noise
    // of 3e-3 of the diagonal is as large as that.
    cellforge::samples::ring_stack barrel;
    barrel.n = 24;
    barrel.radius = {1.0, 1.2, 1.25, 1.2, 1.0};
    barrel.height = {0.0, 1.0, 2.0, 3.0, 4.0};
    const sample_model exact = cellforge::samples::make_ring_stack(barrel, "barrel");
    const sample_model m = wireframe_sweep::noisy(exact, 3e-3, 11);
    std::string why;
    const noisy_outcome o = wireframe_sweep::judge_noisy(m, why);
    CHECK(o != noisy_outcome::wrong);
    const auto t = cellforge::estimate_tolerance(cellforge::read_vertices(m.wire).graph);
    CHECK(!t.clear_gap);
    CHECK(!t.reason.empty());
    CHECK(convert(exact).empty());
  }
  SUBCASE("edges' lengths first, noise gains where they find no clear gap") {
    // Exact antiprisms of 36-62 sides: over their noise gains, the bands' many shallow angles
    // outnumber the caps' residuals in plane and were once called noise (not a solid).
    for (const std::size_t n : {36u, 48u, 60u}) {
      cellforge::samples::ring_stack anti;
      anti.n = n;
      anti.radius = {1.0, 1.0};
      anti.height = {0.0, 1.0};
      anti.twist = {0.0, std::numbers::pi / static_cast<double>(n)};
      anti.triangles = true;
      const sample_model m = cellforge::samples::make_ring_stack(anti, "antiprism " + std::to_string(n));
      CAPTURE(n);
      const auto t = cellforge::estimate_tolerance(cellforge::read_vertices(m.wire).graph);
      CHECK(t.clear_gap);
      CHECK(!t.noise_gain);
      CHECK(t.planarity == 1e-9);
      CHECK(convert(m) == "");
    }
    // Extrusions with noise of 1e-4 whose short sides, measured far away, spread the noise
    // into their shallow corners over the edges' lengths: over the noise gains it is clear.
    for (const std::uint64_t draw : {11u, 17u, 35u}) {
      const sample_model exact = wireframe_sweep::detail::random_extrusion(draw);
      const sample_model m = wireframe_sweep::noisy(exact, 1e-4, wireframe_sweep::name_seed(exact.name) ^ 4u);
      const std::string name = m.name;
      CAPTURE(name);
      const auto t = cellforge::estimate_tolerance(cellforge::read_vertices(m.wire).graph);
      CHECK(t.clear_gap);
      CHECK(t.noise_gain);
      CHECK(t.noise < 4e-4);  // of the diagonal: at most 2 δ, and the corners' worst
      CHECK(convert(m) == "");
    }
  }
  SUBCASE("explicit stage tolerances when automatic is off (wire2cells --planarity)") {
    const sample_model m = wireframe_sweep::noisy(cube, 1e-6, 3);
    cellforge::wireframe_options o;
    o.tolerance.automatic = false;
    o.trace.planarity.relative = o.reduction.planarity.relative = 1e-3;
    o.arrangement.planarity.relative = o.extra.retrace.planarity.relative = 1e-3;
    const auto r = cellforge::wireframe_to_cells(m.wire, o);
    CHECK(r.tolerance.planarity == 1e-3);
    CHECK(r.check.planarity_floor >= 1e-2);
    CHECK(wireframe_sweep::miss_reason(m, r, r.check).empty());
  }
}

}  // namespace wireframe_noise_tests
