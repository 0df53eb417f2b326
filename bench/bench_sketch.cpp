// Sketches, seed 003 "Finding faces": the Varley–Company face finder beside the
// shortest-loops baseline on drawings of 10 to 1,000 edges — ms per drawing, right or wrong
// against the model's faces, and the practical growth exponent (the seed: about e^2.7, its
// largest drawing of 251 edges slightly over 1 s). Then inflation and the whole of
// drawing_to_cells per family of the generated sweep (ms, and how often the true cell complex
// comes out), and direct inflation of a ~100-line normalon (issue target: 50 ms). Every row is
// the median of its iterations. Last, rounds and fillets per family of the generated round
// drawings: pairing the arcs, the polyhedral skeleton, the reconstruction with rounds
// (radii against the truth) and the rounded mesh.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "bench_support.hpp"
#include "cellforge/samples/drawings.hpp"
#include "cellforge/samples/noisy_drawings.hpp"
#include "cellforge/samples/round_drawings.hpp"
#include "cellforge/sketch/arc_detection.hpp"
#include "cellforge/sketch/drawing_to_cells.hpp"
#include "cellforge/sketch/face_finder.hpp"
#include "cellforge/sketch/inflation.hpp"
#include "cellforge/sketch/round_skeleton.hpp"
#include "cellforge/sketch/rounds.hpp"
#include "cellforge/sketch/tidy.hpp"

namespace {

namespace cb = cellforge::bench;

struct drawing_case {
  std::string family, name;
  cellforge::samples::sample_drawing s;
};

std::vector<drawing_case>& cases() {
  static std::vector<drawing_case> c = [] {
    std::vector<drawing_case> out;
    // Edge counts 12 … 999 in each family; tiny margins are fine for timing large n-gons.
    for (std::size_t n : {4u, 10u, 20u, 40u, 84u, 160u, 333u})
      out.push_back(
          {"prism", "prism " + std::to_string(n),
           cellforge::samples::generic_drawing(cellforge::samples::sample_prism(n), 1, "prism", 1e-7)});
    for (auto [a, b] : std::vector<std::pair<std::size_t, std::size_t>>{
             {4, 3}, {6, 4}, {8, 6}, {12, 8}, {16, 10}, {24, 14}, {28, 18}})
      out.push_back({"uv sphere", "uv sphere " + std::to_string(a) + "x" + std::to_string(b),
                     cellforge::samples::generic_drawing(cellforge::samples::sample_uv_sphere(a, b), 1,
                                                         "sphere", 1e-7)});
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

// A few drawings of each sweep family, for the inflation and end-to-end rows.
struct family_case {
  std::string family;
  std::vector<cellforge::samples::sample_drawing> drawings;
  std::vector<std::vector<std::vector<std::uint32_t>>> loops;
};

std::vector<family_case>& families() {
  static std::vector<family_case> f = [] {
    cellforge::samples::sketch_sweep_options o;
    o.limit = 130;  // about ten per family
    std::vector<family_case> out;
    for (auto& s : cellforge::samples::sketch_sweep(o)) {
      auto it =
          std::find_if(out.begin(), out.end(), [&](const family_case& c) { return c.family == s.family; });
      if (it == out.end()) out.push_back({s.family, {}, {}}), it = out.end() - 1;
      it->loops.push_back(s.loops);
      it->drawings.push_back(std::move(s));
    }
    return out;
  }();
  return f;
}

std::map<std::string, std::pair<std::size_t, std::size_t>>& truth() {
  static std::map<std::string, std::pair<std::size_t, std::size_t>> m;
  return m;
}

// Per family: the median over its drawings of the depth error of the better Necker reading
// against the model, up to a depth offset, relative to the drawing's size.
std::map<std::string, double>& depth_error() {
  static std::map<std::string, double> m;
  return m;
}

template <class R>
double reading_error(const cellforge::samples::sample_drawing& s, const R& r) {
  double best = std::numeric_limits<double>::infinity();
  glm::dvec3 lo = s.points[0], hi = s.points[0];
  for (const auto& p : s.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double size = glm::length(hi - lo);
  for (const auto& reading : r.inflation.readings) {
    double mz = 0, mt = 0;
    for (std::size_t i = 0; i < s.points.size(); ++i) mz += reading.points[i].z, mt += s.points[i].z;
    mz /= static_cast<double>(s.points.size()), mt /= static_cast<double>(s.points.size());
    double worst = 0;
    for (std::size_t i = 0; i < s.points.size(); ++i)
      worst = std::max(worst, std::abs((reading.points[i].z - mz) - (s.points[i].z - mt)));
    best = std::min(best, worst / size);
  }
  return best;
}

bool true_complex(const cellforge::samples::sample_drawing& s,
                  const cellforge::drawing_result<glm::dvec3>& r) {
  std::vector<std::vector<std::vector<std::uint32_t>>> faces;
  for (const auto& f : r.cells.input.faces) {
    auto loops = f.loops;
    for (auto& l : loops)
      for (auto& v : l) v = r.cells.input_vertex[v];
    faces.push_back(std::move(loops));
  }
  return cellforge::samples::same_faces(s.model.faces, faces) &&
         cellforge::samples::same_volumes(s.model.faces, s.model.volumes, faces, r.cells.input.volumes);
}

// The direct-inflation case: a comb normalon of about 100 lines.
const cellforge::samples::sample_drawing& comb() {
  static const cellforge::samples::sample_drawing s = [] {
    cellforge::samples::voxel_layout l =
        cellforge::samples::empty_layout(cellforge::samples::detail::iota_coords(18), {0, 1, 2}, {0, 1});
    for (std::size_t i = 0; i + 1 < 18; ++i) l.at(i, 0, 0) = 1, l.at(i, 1, 0) = i % 2 == 0;
    return cellforge::samples::generic_drawing(cellforge::samples::make_voxel_model(l, "comb"), 1,
                                               "normalon");
  }();
  return s;
}

// Tidying at scale: a comb normalon of `teeth` teeth (about 11 lines a tooth: 1k and 10k
// lines), every junction jittered by a tenth of its spacing (the drawing stays the same drawing).
struct big_comb {
  cellforge::samples::sample_drawing s;
  cellforge::line_drawing<glm::dvec2> jittered;
};

const big_comb& comb_of(std::size_t teeth) {
  static std::map<std::size_t, big_comb> m;
  auto it = m.find(teeth);
  if (it != m.end()) return it->second;
  const std::size_t width = 2 * teeth;
  cellforge::samples::voxel_layout l =
      cellforge::samples::empty_layout(cellforge::samples::detail::iota_coords(width + 1), {0, 1, 2}, {0, 1});
  for (std::size_t i = 0; i < width; ++i) l.at(i, 0, 0) = 1, l.at(i, 1, 0) = i % 2 == 0;
  big_comb c;
  c.s = cellforge::samples::generic_drawing(cellforge::samples::make_voxel_model(l, "comb"), 1, "normalon",
                                            1e-9, 8);
  glm::dvec2 lo = c.s.drawing.points[0], hi = lo;
  for (const auto& q : c.s.drawing.points) lo = glm::min(lo, q), hi = glm::max(hi, q);
  const double spacing = cellforge::samples::detail::junction_spacing(c.s.drawing.points, c.s.drawing.edges,
                                                                      glm::length(hi - lo));
  c.jittered = cellforge::samples::jitter_drawing(c.s.drawing, 0.1 * spacing, 1);
  return m.emplace(teeth, std::move(c)).first->second;
}

// Interactive speed (issue 37): drawing_to_cells on every drawing of a sample of the sweep, each
// drawing timed alone (median CPU ms of 3 runs), by size band: a sketching program redraws the
// solid as the user draws, so every drawing must fit a frame, not only the median one.
struct frame_drawing {
  std::string name;
  std::size_t edges = 0;
  double ms = 0;
};
std::vector<frame_drawing>& frame_times() {
  static std::vector<frame_drawing> v;
  return v;
}

// The scale rows: right n-gon prisms and comb normalons of about 150 to 5,000 lines.
struct scale_case {
  std::string family, name;
  cellforge::samples::sample_drawing s;
};
std::vector<scale_case>& scale_cases() {
  static std::vector<scale_case> c = [] {
    std::vector<scale_case> out;
    for (std::size_t n : {50u, 100u, 200u, 334u, 667u, 1000u})  // sample_prism: n <= 1024
      out.push_back(
          {"prism", "prism " + std::to_string(n),
           cellforge::samples::generic_drawing(cellforge::samples::sample_prism(n), 1, "prism", 1e-9, 8)});
    for (std::size_t teeth : {7u, 14u, 28u, 45u, 90u, 225u, 450u})
      out.push_back({"comb normalon", "comb " + std::to_string(teeth), comb_of(teeth).s});
    return out;
  }();
  return c;
}
std::map<std::string, bool>& scale_right() {
  static std::map<std::string, bool> m;
  return m;
}

std::map<std::string, std::string>& tidy_rows() {
  static std::map<std::string, std::string> m;
  return m;
}

// The generated round drawings, per family.
struct round_family {
  std::string family;
  std::vector<cellforge::samples::sample_round_drawing> drawings;
  std::size_t blends = 0;
};

std::vector<round_family>& round_families() {
  static std::vector<round_family> f = [] {
    std::vector<round_family> out;
    for (auto& s : cellforge::samples::round_drawing_sweep()) {
      auto it =
          std::find_if(out.begin(), out.end(), [&](const round_family& c) { return c.family == s.family; });
      if (it == out.end()) out.push_back({s.family, {}, 0}), it = out.end() - 1;
      it->blends += s.rounds.size();
      it->drawings.push_back(std::move(s));
    }
    return out;
  }();
  return f;
}

// Per family: skeletons with the true junction and edge counts and no arc unpaired.
std::map<std::string, std::size_t>& round_right() {
  static std::map<std::string, std::size_t> m;
  return m;
}

// Per family: blends whose reconstructed radius is within 1 % of the truth, and rounded meshes made.
std::map<std::string, std::size_t>& radii_right() {
  static std::map<std::string, std::size_t> m;
  return m;
}

// Blends of one reconstruction within 1 % of their true radius: a blend is matched to its true
// edge by the skeleton junctions' positions.
std::size_t radii_within(const cellforge::samples::sample_round_drawing& s,
                         const cellforge::rounds_result<glm::dvec3, glm::dvec2>& r) {
  const auto& truth = s.skeleton.drawing.points;
  const auto& got = r.skeleton.skeleton.points;
  glm::dvec2 lo = truth[0], hi = truth[0];
  for (const auto& p : truth) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double close = 1e-6 * glm::length(hi - lo);
  std::size_t ok = 0;
  for (const auto& t : s.rounds)
    for (const auto& e : r.rounds) {
      const auto near = [&](std::uint32_t i, std::uint32_t j) {
        return glm::length(got[i] - truth[j]) < close;
      };
      const bool same = (near(e.junctions[0], t.vertices[0]) && near(e.junctions[1], t.vertices[1])) ||
                        (near(e.junctions[0], t.vertices[1]) && near(e.junctions[1], t.vertices[0]));
      if (same) ok += std::abs(e.radius - t.radius) <= 0.01 * t.radius;
    }
  return ok;
}

// A round drawing as a pen draws it: every edge and arc one stroke of samples about 1 % of the
// size apart, each jittered by up to 0.2 % of the size (uniform per coordinate, fixed seed).
struct sampled_drawing {
  std::vector<std::vector<glm::dvec2>> strokes;
  double size = 0;
  std::size_t arcs = 0, lines = 0;
};

std::vector<sampled_drawing> sampled(const round_family& f) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-1, 1);
  std::vector<sampled_drawing> out;
  for (const auto& s : f.drawings) {
    sampled_drawing d;
    const auto& p = s.drawing.lines.points;
    glm::dvec2 lo = p[0], hi = p[0];
    for (const auto& q : p) lo = glm::min(lo, q), hi = glm::max(hi, q);
    d.size = glm::length(hi - lo);
    const auto pen = [&](glm::dvec2 q) { return q + 2e-3 * d.size * glm::dvec2(jitter(rng), jitter(rng)); };
    for (const auto& e : s.drawing.lines.edges) {
      const glm::dvec2 a = p[e[0]], b = p[e[1]];
      const int n = std::max(4, static_cast<int>(glm::length(b - a) / (1e-2 * d.size)));
      std::vector<glm::dvec2> stroke;
      for (int i = 0; i <= n; ++i) stroke.push_back(pen(a + (b - a) * (static_cast<double>(i) / n)));
      d.strokes.push_back(std::move(stroke));
      ++d.lines;
    }
    for (const auto& a : s.drawing.arcs) {
      const double length = std::abs(a.curve.sweep) * std::max(a.curve.rx, a.curve.ry);
      const int n = std::max(8, static_cast<int>(length / (1e-2 * d.size)));
      std::vector<glm::dvec2> stroke;
      for (int i = 0; i <= n; ++i)
        stroke.push_back(pen(cellforge::arc_point(a.curve, static_cast<double>(i) / n)));
      d.strokes.push_back(std::move(stroke));
      ++d.arcs;
    }
    out.push_back(std::move(d));
  }
  return out;
}

// Per family: strokes found as exactly one arc or one line, as drawn, of all strokes.
std::map<std::string, std::pair<std::size_t, std::size_t>>& detect_right() {
  static std::map<std::string, std::pair<std::size_t, std::size_t>> m;
  return m;
}

void register_all() {
  for (const round_family& f : round_families()) {
    benchmark::RegisterBenchmark(
        ("rounds/detect/" + f.family).c_str(),
        [&f](benchmark::State& state) {
          const std::vector<sampled_drawing> drawn = sampled(f);
          std::size_t strokes = 0;
          for (const auto& d : drawn) strokes += d.strokes.size();
          cb::median_loop(
              state,
              [&] {
                std::size_t ok = 0;
                for (const auto& d : drawn) {
                  const auto r = cellforge::detect_arcs(d.strokes, {.drawing_size = d.size});
                  for (std::size_t k = 0; k < r.strokes.size(); ++k)
                    ok += r.strokes[k].num_pieces == 1 &&
                          (r.pieces[r.strokes[k].first_piece].kind == cellforge::stroke_piece_kind::arc) ==
                              (k >= d.lines);
                }
                return ok;
              },
              [&](std::size_t ok) {
                detect_right()[f.family] = {ok, strokes};
              });
        })
        ->Iterations(5)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("rounds/reconstruct/" + f.family).c_str(),
                                 [&f](benchmark::State& state) {
                                   cb::median_loop(
                                       state,
                                       [&] {
                                         std::size_t ok = 0;
                                         for (const auto& s : f.drawings)
                                           ok += radii_within(s, cellforge::reconstruct_rounds(s.drawing));
                                         return ok;
                                       },
                                       [&](std::size_t ok) { radii_right()[f.family] = ok; });
                                 })
        ->Iterations(5)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("rounds/mesh/" + f.family).c_str(),
                                 [&f](benchmark::State& state) {
                                   std::vector<cellforge::rounds_result<glm::dvec3, glm::dvec2>> read;
                                   for (const auto& s : f.drawings)
                                     read.push_back(cellforge::reconstruct_rounds(s.drawing));
                                   cb::median_loop(state, [&] {
                                     std::size_t faces = 0;
                                     for (const auto& r : read)
                                       faces += cellforge::rounded_mesh(r).mesh.num_faces();
                                     return faces;
                                   });
                                 })
        ->Iterations(9)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("rounds/pair_arcs/" + f.family).c_str(),
                                 [&f](benchmark::State& state) {
                                   cb::median_loop(state, [&] {
                                     std::size_t pairs = 0;
                                     for (const auto& s : f.drawings)
                                       pairs += cellforge::pair_arcs(s.drawing).pairs.size();
                                     return pairs;
                                   });
                                 })
        ->Iterations(9)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("rounds/skeleton/" + f.family).c_str(),
                                 [&f](benchmark::State& state) {
                                   cb::median_loop(
                                       state,
                                       [&] {
                                         std::size_t ok = 0;
                                         for (const auto& s : f.drawings) {
                                           const auto r = cellforge::round_skeleton(s.drawing);
                                           ok +=
                                               r.pairing.unpaired.empty() && r.unknown == 0 &&
                                               r.skeleton.points.size() == s.skeleton.drawing.points.size() &&
                                               r.skeleton.edges.size() == s.skeleton.drawing.edges.size();
                                         }
                                         return ok;
                                       },
                                       [&](std::size_t ok) { round_right()[f.family] = ok; });
                                 })
        ->Iterations(9)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  for (const family_case& f : families()) {
    benchmark::RegisterBenchmark(("inflate/" + f.family).c_str(),
                                 [&f](benchmark::State& state) {
                                   try {
                                     cb::median_loop(state, [&] {
                                       double sum = 0;
                                       for (std::size_t k = 0; k < f.drawings.size(); ++k)
                                         sum +=
                                             cellforge::inflate(f.drawings[k].drawing, f.loops[k]).after.msda;
                                       return sum;
                                     });
                                   } catch (const std::exception& e) {
                                     state.SkipWithError(e.what());
                                   }
                                 })
        ->Iterations(3)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("drawing_to_cells/" + f.family).c_str(),
                                 [&f](benchmark::State& state) {
                                   cb::median_loop(
                                       state,
                                       [&] {
                                         std::size_t ok = 0;
                                         std::vector<double> errors;
                                         for (const auto& s : f.drawings) {
                                           try {
                                             const auto r = cellforge::drawing_to_cells(s.drawing);
                                             ok += true_complex(s, r);
                                             errors.push_back(reading_error(s, r));
                                           } catch (const cellforge::error&) {
                                             errors.push_back(std::numeric_limits<double>::infinity());
                                           }
                                         }
                                         std::sort(errors.begin(), errors.end());
                                         return std::make_pair(
                                             ok, errors.empty() ? 0.0 : errors[errors.size() / 2]);
                                       },
                                       [&](const std::pair<std::size_t, double>& res) {
                                         truth()[f.family] = {res.first, f.drawings.size()};
                                         depth_error()[f.family] = res.second;
                                       });
                                 })
        ->Iterations(3)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark(
      "drawing_to_cells/frame",
      [](benchmark::State& state) {
        cellforge::samples::sketch_sweep_options o;
        o.limit = 600;
        const std::vector<cellforge::samples::sample_drawing> drawings = cellforge::samples::sketch_sweep(o);
        for (auto _ : state) {
          const double c0 = cb::thread_cpu_ms();
          frame_times().clear();
          for (const auto& s : drawings) {
            std::vector<double> ms;
            for (int k = 0; k < 3; ++k) {
              const double t0 = cb::thread_cpu_ms();
              try {
                benchmark::DoNotOptimize(cellforge::drawing_to_cells(s.drawing));
              } catch (const cellforge::error&) {
              }
              ms.push_back(cb::thread_cpu_ms() - t0);
            }
            frame_times().push_back({s.name, s.drawing.edges.size(), cb::median(ms)});
          }
          state.SetIterationTime((cb::thread_cpu_ms() - c0) * 1e-3);
        }
      })
      ->Iterations(1)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
  for (const scale_case& c : scale_cases())
    benchmark::RegisterBenchmark(("drawing_to_cells/scale/" + c.name).c_str(),
                                 [&c](benchmark::State& state) {
                                   cb::median_loop(
                                       state, [&] { return cellforge::drawing_to_cells(c.s.drawing); },
                                       [&](const auto& r) { scale_right()[c.name] = true_complex(c.s, r); });
                                 })
        ->Iterations(c.s.drawing.edges.size() > 1500 ? 1 : 3)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  for (const std::size_t teeth : {90u, 900u}) {
    const std::string lines = std::to_string(comb_of(teeth).s.drawing.edges.size());
    benchmark::RegisterBenchmark(("tidy/parallel/" + lines).c_str(),
                                 [teeth, lines](benchmark::State& state) {
                                   const big_comb& c = comb_of(teeth);
                                   cellforge::tidy_options o;
                                   o.parallel_tolerance_degrees = 2;
                                   cb::median_loop(
                                       state, [&] { return cellforge::tidy_drawing(c.jittered, o); },
                                       [&](const auto& t) {
                                         tidy_rows()["parallel " + lines] = std::to_string(t.classes) +
                                                                            " classes, largest move " +
                                                                            cb::fixed(t.largest_move, 7);
                                       });
                                 })
        ->Iterations(3)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    // tidy_to_solid at 10k lines does not finish in minutes yet (the first reading's O(E²)
    // direction clustering and sparse-QR freedom): 1k only (docs/sketch.md, "Tidying").
    if (teeth > 100) continue;
    benchmark::RegisterBenchmark(("tidy/solid/" + lines).c_str(),
                                 [teeth, lines](benchmark::State& state) {
                                   const big_comb& c = comb_of(teeth);
                                   std::vector<std::vector<std::vector<std::uint32_t>>> faces;
                                   for (const auto& l : c.s.loops) faces.push_back({l});
                                   cb::median_loop(
                                       state, [&] { return cellforge::tidy_to_solid(c.jittered, faces); },
                                       [&](const auto& t) {
                                         tidy_rows()["solid " + lines] =
                                             std::string(t.solid ? "solid" : "not solid") + ", " +
                                             std::to_string(t.classes) + " classes, " +
                                             std::to_string(t.steps) + " steps, largest move " +
                                             cb::fixed(t.largest_move, 7);
                                       });
                                 })
        ->Iterations(1)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark(
      "inflate/comb",
      [](benchmark::State& state) {
        cb::median_loop(state, [] { return cellforge::inflate(comb().drawing, comb().loops).method; });
      })
      ->Iterations(15)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
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
  cb::table in("Inflation and drawing_to_cells per family (about ten sweep drawings each)",
               {"family", "drawings", "inflate ms per drawing", "drawing_to_cells ms per drawing",
                "true cell complex", "median depth error"});
  for (const family_case& f : families()) {
    const double n = static_cast<double>(f.drawings.size());
    const std::optional<double> a = r.counter_ms("inflate/" + f.family, "median_cpu_us"),
                                b = r.counter_ms("drawing_to_cells/" + f.family, "median_cpu_us");
    in.add_row({f.family, cb::count(f.drawings.size()), a ? cb::ms(*a / n) : "—", b ? cb::ms(*b / n) : "—",
                std::to_string(truth()[f.family].first) + " of " + std::to_string(truth()[f.family].second),
                cb::fixed(depth_error()[f.family], 6)});
  }
  in.add_note(
      "Depth error: of the better Necker reading, up to a depth offset, over the drawing's size; the median "
      "of the "
      "family's drawings (optimised readings are regular shapes, not the model's exact depths).");
  for (const auto& [row, what] : tidy_rows())
    in.add_note(
        "Tidying a jittered comb, " + row + " lines: " +
        cb::ms(r.counter_ms("tidy/" + row.substr(0, row.find(' ')) + "/" + row.substr(row.find(' ') + 1),
                            "median_cpu_us")) +
        " ms (" + what + ").");
  in.add_note("Direct inflation of a " + std::to_string(comb().drawing.edges.size()) +
              "-line comb normalon: " + cb::ms(r.counter_ms("inflate/comb", "median_cpu_us")) +
              " ms (issue target: 100 lines in <= 50 ms).");
  in.print(os);
  cb::table fr("drawing_to_cells in a frame: every drawing of a sample of the sweep, by size",
               {"edges", "drawings", "median ms", "90th percentile ms", "worst ms", "worst drawing",
                "over target", "target"});
  for (const auto& [lo, hi, target] :
       std::vector<std::tuple<std::size_t, std::size_t, double>>{{0, 150, 16.0}, {151, 300, 50.0}}) {
    std::vector<frame_drawing> band;
    for (const frame_drawing& f : frame_times())
      if (f.edges >= lo && f.edges <= hi) band.push_back(f);
    if (band.empty()) continue;
    std::sort(band.begin(), band.end(), [](const auto& a, const auto& b) { return a.ms < b.ms; });
    const std::size_t over = static_cast<std::size_t>(
        std::count_if(band.begin(), band.end(), [t = target](const auto& f) { return f.ms > t; }));
    fr.add_row({std::to_string(lo) + "-" + std::to_string(hi), cb::count(band.size()),
                cb::ms(band[band.size() / 2].ms), cb::ms(band[band.size() * 9 / 10].ms),
                cb::ms(band.back().ms),
                band.back().name + " (" + std::to_string(band.back().edges) + " edges)", cb::count(over),
                "every drawing <= " + cb::fixed(target, 0) + " ms"});
  }
  fr.add_note(
      "Each drawing's median CPU ms of 3 runs of drawing_to_cells (a refused drawing counts its time).");
  fr.print(os);
  cb::table sc("drawing_to_cells at scale (median CPU ms of 3 runs; 1 run above 1,500 edges)",
               {"drawing", "edges", "ms", "true complex"});
  std::map<std::string, std::vector<std::pair<double, double>>> growth;
  for (const scale_case& c : scale_cases()) {
    const std::optional<double> a = r.counter_ms("drawing_to_cells/scale/" + c.name, "median_cpu_us");
    const double edges = static_cast<double>(c.s.drawing.edges.size());
    if (a) growth[c.family].push_back({edges, *a});
    sc.add_row({c.name, cb::count(c.s.drawing.edges.size()), cb::ms(a),
                !a                      ? "—"
                : scale_right()[c.name] ? "yes"
                                        : "NO"});
  }
  for (const auto& [family, xy] : growth)
    sc.add_note("Growth exponent, " + family + ": " + cb::fixed(exponent(xy), 2) +
                " (slope of log ms over log edges).");
  sc.add_note("Targets (issue 37): 1,000 edges <= 1 s, 5,000 edges <= 10 s.");
  sc.print(os);
  cb::table rt(
      "Rounds and fillets per family of the generated round drawings (ms per drawing)",
      {"family", "drawings", "blends", "detect_arcs (sampled)", "strokes right", "pair_arcs",
       "round_skeleton", "skeleton right", "reconstruct_rounds", "radii within 1 %", "rounded_mesh"});
  for (const round_family& f : round_families()) {
    const double n = static_cast<double>(f.drawings.size());
    const std::optional<double> x = r.counter_ms("rounds/detect/" + f.family, "median_cpu_us"),
                                a = r.counter_ms("rounds/pair_arcs/" + f.family, "median_cpu_us"),
                                b = r.counter_ms("rounds/skeleton/" + f.family, "median_cpu_us"),
                                c = r.counter_ms("rounds/reconstruct/" + f.family, "median_cpu_us"),
                                m = r.counter_ms("rounds/mesh/" + f.family, "median_cpu_us");
    const auto per = [&](const std::optional<double>& x) { return x ? cb::ms(*x / n) : std::string("—"); };
    const auto [found, strokes] = detect_right()[f.family];
    rt.add_row({f.family, cb::count(f.drawings.size()), cb::count(f.blends), per(x),
                std::to_string(found) + " of " + std::to_string(strokes), per(a), per(b),
                std::to_string(round_right()[f.family]) + " of " + std::to_string(f.drawings.size()), per(c),
                std::to_string(radii_right()[f.family]) + " of " + std::to_string(f.blends), per(m)});
  }
  rt.add_note(
      "detect_arcs: every edge and arc of the drawing one stroke, samples about 1 % of the size apart, each "
      "jittered by up to 0.2 % of the size; right = the stroke found as one piece of its own kind (arcs "
      "bulging "
      "less than 5 noise widths are lines at this noise: tests/test_arc_detection.cpp, docs/sketch.md).");
  rt.add_note(
      "reconstruct_rounds: the skeleton, drawing_to_cells on it, each blend's radius from its end curves "
      "(and, for readings that are not metric, the depth map fitted to circular blends); rounded_mesh: the "
      "rounded solid as a polygon soup, chord tolerance 1e-3 of the diagonal.");
  rt.add_note(
      "round_skeleton: pairing, the skeleton and face finding on it (round or fillet); right = no arc "
      "unpaired, every blend's kind found, the true junction and edge counts (tests/test_round_skeleton.cpp "
      "compares the drawings themselves).");
  rt.print(os);
}

}  // namespace

int main(int argc, char** argv) { return cb::table_main(argc, argv, register_all, print_tables); }
