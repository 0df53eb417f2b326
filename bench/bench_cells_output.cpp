// SPDX-License-Identifier: MIT
// The main job's output paths on k×k×k grids of unit cubes (sample_grid, every wall a face):
// each writer of io/cells_io.hpp (.3dcl text, OBJ per volume, PLY by volume, exploded SVG) and
// io/step.hpp (a STEP solid per volume) on its own, reading and converting the OBJ wireframe
// (wireframe_to_cells), and the whole job as wire2cells runs it (read, convert, validate, write the four
// files). Prints a growth table of CPU and wall medians: near-linear growth keeps the ratio per 8x volumes
// near 8. The whole job is also timed on UV spheres (rings and meridians that are not faces) and on stacks of
// n-gon cylinders (large planar walls) up to about 50 000 edges.

#include "bench_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "cellforge/cells/validate.hpp"
#include "cellforge/io/cells_io.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/io/step.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

namespace {

namespace cb = cellforge::bench;
namespace fs = std::filesystem;

constexpr std::array<int, 3> grid_sizes{5, 10, 20};

/// The scratch folder for the input wireframes and the written files.
const cb::scratch_dir& scratch() {
  static const cb::scratch_dir dir("bench-cells-output");
  return dir;
}

/// The k×k×k grid's wireframe written as an OBJ (v and l lines), once.
const fs::path& grid_file(int k) {
  static std::map<int, fs::path> files;
  auto it = files.find(k);
  if (it == files.end()) {
    const auto n = static_cast<std::size_t>(k);
    const fs::path p = scratch() / ("grid" + std::to_string(k) + ".obj");
    cellforge::io::write_obj(p, cellforge::samples::sample_grid(n, n, n).wire);
    it = files.emplace(k, p).first;
  }
  return it->second;
}

/// k cylinders of n sides stacked on each other: rings at heights 0..k (each a planar n-gon
/// face, the inner ones walls between two volumes), vertical edges between them.
cellforge::wireframe<glm::dvec3> cylinder_stack(int n, int k) {
  cellforge::wireframe<glm::dvec3> w;
  for (int z = 0; z <= k; ++z)
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n;
      w.points.push_back({std::cos(a), std::sin(a), 0.05 * z});
    }
  auto id = [n](int z, int i) { return static_cast<std::uint32_t>(z * n + (i % n)); };
  for (int z = 0; z <= k; ++z)
    for (int i = 0; i < n; ++i) {
      w.edges.push_back({id(z, i), id(z, i + 1)});
      if (z < k) w.edges.push_back({id(z, i), id(z + 1, i)});
    }
  return w;
}

/// A model of the end-to-end table: name, wireframe file, edges and expected volumes.
struct job_model {
  std::string name;
  fs::path file;
  std::size_t edges, volumes;
};

/// The spheres and cylinder stacks of the end-to-end table, written as OBJ once.
const std::vector<job_model>& job_models() {
  static const std::vector<job_model> models = [] {
    std::vector<job_model> out;
    auto add = [&](std::string name, const cellforge::wireframe<glm::dvec3>& w, std::size_t volumes) {
      const fs::path p = scratch() / (name + ".obj");
      cellforge::io::write_obj(p, w);
      out.push_back({std::move(name), p, w.edges.size(), volumes});
    };
    for (const auto& [slices, stacks] : {std::pair{64, 32}, std::pair{128, 48}, std::pair{180, 70}})
      add("sphere_" + std::to_string(slices) + "x" + std::to_string(stacks),
          cellforge::samples::sample_uv_sphere(static_cast<std::size_t>(slices),
                                               static_cast<std::size_t>(stacks))
              .wire,
          1);
    for (const auto& [n, k] : {std::pair{64, 8}, std::pair{256, 24}, std::pair{500, 50}})
      add("cylinders_" + std::to_string(n) + "x" + std::to_string(k), cylinder_stack(n, k),
          static_cast<std::size_t>(k));
    return out;
  }();
  return models;
}

/// The grid's cell complex, converted once.
const cellforge::cell_complex<glm::dvec3>& grid_cells(int k) {
  static std::map<int, cellforge::cell_complex<glm::dvec3>> cache;
  auto it = cache.find(k);
  if (it == cache.end()) {
    const auto n = static_cast<std::size_t>(k);
    it = cache.emplace(k, cellforge::wireframe_to_cells(cellforge::samples::sample_grid(n, n, n).wire).cells)
             .first;
  }
  return it->second;
}

/// What the main job made: the complex's volume count and the picture's counts.
struct job_result {
  std::size_t volumes = 0;
  cellforge::io::svg_result picture;
};

/// The main job: what wire2cells does between reading its arguments and exiting.
job_result end_to_end(const fs::path& input, const fs::path& out_dir) {
  const auto wire = cellforge::io::read_obj_wireframe<glm::dvec3>(input);
  const cellforge::wireframe_result<glm::dvec3> r = cellforge::wireframe_to_cells(wire);
  if (!cellforge::validate(r.cells).ok())
    throw cellforge::error(cellforge::error_category::topology,
                           input.stem().string() + ": the complex does not validate");
  const std::string stem = input.stem().string();
  cellforge::io::write_3dcl(out_dir / (stem + ".3dcl"), r.cells);
  cellforge::io::write_cells_obj(out_dir / (stem + ".obj"), r.cells);
  cellforge::io::write_cells_ply(out_dir / (stem + ".ply"), r.cells);
  return {r.cells.num_volumes(), cellforge::io::write_cells_svg(out_dir / (stem + ".svg"), r.cells)};
}

void register_named(const std::string& name, int iterations, std::function<void(benchmark::State&)> body) {
  benchmark::RegisterBenchmark(name.c_str(),
                               [body](benchmark::State& s) {
                                 try {
                                   body(s);
                                 } catch (const std::exception& e) {
                                   s.SkipWithError(e.what());
                                 }
                               })
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(iterations);
}

void register_path(const std::string& path, int k, std::function<void(benchmark::State&)> body) {
  register_named(path + "/grid_" + std::to_string(k), k >= 20 ? 5 : 11, std::move(body));
}

/// Registers `name`/grid_k: write(file, complex) of the k-grid's complex into one scratch file.
template <class Write>
void register_writer(const char* name, int k, const char* ext, Write write) {
  register_path(name, k, [=](benchmark::State& s) {
    const cellforge::cell_complex<glm::dvec3>& cc = grid_cells(k);
    const fs::path file = scratch() / ("cells" + std::to_string(k) + ext);
    cb::median_loop(s, [&] { return write(file, cc); });
  });
}

void register_all() {
  using cellforge::cell_complex;
  for (const job_model& m : job_models())
    register_named("end_to_end/" + m.name, m.edges > 20000 ? 5 : 11, [&m](benchmark::State& s) {
      const fs::path out = scratch() / ("out_" + m.name);
      fs::create_directories(out);
      cb::median_loop(
          s, [&] { return end_to_end(m.file, out).volumes; },
          [&](std::size_t volumes) {
            if (volumes != m.volumes) s.SkipWithError("wrong volume count");
          });
    });
  for (const int k : grid_sizes) {
    register_writer("write_3dcl", k, ".3dcl", [](const fs::path& p, const cell_complex<glm::dvec3>& cc) {
      cellforge::io::write_3dcl(p, cc);
      return 0;
    });
    register_writer("write_obj", k, ".obj", [](const fs::path& p, const cell_complex<glm::dvec3>& cc) {
      cellforge::io::write_cells_obj(p, cc);
      return 0;
    });
    register_writer("write_ply", k, ".ply", [](const fs::path& p, const cell_complex<glm::dvec3>& cc) {
      cellforge::io::write_cells_ply(p, cc);
      return 0;
    });
    register_writer("write_step", k, ".step", [](const fs::path& p, const cell_complex<glm::dvec3>& cc) {
      return cellforge::io::write_step(p, cc).faces;
    });
    register_path("write_svg", k, [k](benchmark::State& s) {
      const cell_complex<glm::dvec3>& cc = grid_cells(k);
      const fs::path file = scratch() / ("cells" + std::to_string(k) + ".svg");
      cb::median_loop(s, [&] {
        const cellforge::io::svg_result r = cellforge::io::write_cells_svg(file, cc);
        if (r.approximate_edges + r.untested_edges > 0)
          s.SkipWithError("the picture ran out of its work budget");
        return r.edges;
      });
    });
    register_path("read_convert", k, [k](benchmark::State& s) {
      const fs::path& input = grid_file(k);
      cb::median_loop(s, [&] {
        return cellforge::wireframe_to_cells(cellforge::io::read_obj_wireframe<glm::dvec3>(input))
            .cells.num_volumes();
      });
    });
    register_path("end_to_end", k, [k](benchmark::State& s) {
      const fs::path& input = grid_file(k);
      const fs::path out = scratch() / ("out" + std::to_string(k));
      fs::create_directories(out);
      cb::median_loop(s, [&] { return end_to_end(input, out).picture.edges; });
    });
  }
}

void print_tables(const cb::collecting_reporter& reporter, std::ostream& os) {
  const auto median = [&](const std::string& name, const char* counter) -> std::optional<double> {
    const cb::run_result* r = reporter.find(name);
    if (r == nullptr || !r->error.empty()) return std::nullopt;
    const auto it = r->counters.find(counter);
    return it == r->counters.end() ? std::nullopt : std::optional<double>(it->second * 1e-3);
  };
  os << "\n## The main job's outputs on k×k×k grids of cubes\n\nLoad average " << cb::load_average()
     << ". Medians of the iterations (5 for 20³, 11 otherwise), CPU ms of the benchmarking thread; "
        "wall ms of the end-to-end job in its own column.\n";
  cb::table t(
      "Growth: reading and converting, each writer, and the whole job (read, convert, validate, four files)",
      {"grid", "volumes", "faces", "read + convert ms", "3dcl ms", "OBJ ms", "PLY ms", "SVG ms", "STEP ms",
       "job ms", "job wall ms", "job µs per volume", "job growth (8x volumes)"});
  std::optional<double> previous;
  for (const int k : grid_sizes) {
    const std::string g = "/grid_" + std::to_string(k);
    const std::optional<double> job = median("end_to_end" + g, "median_cpu_us");
    const double volumes = static_cast<double>(k) * k * k;
    t.add_row(
        {std::to_string(k) + "³", cb::count(static_cast<std::size_t>(volumes)),
         cb::count(static_cast<std::size_t>(3 * k * k * (k + 1))),
         cb::ms(median("read_convert" + g, "median_cpu_us")),
         cb::ms(median("write_3dcl" + g, "median_cpu_us")), cb::ms(median("write_obj" + g, "median_cpu_us")),
         cb::ms(median("write_ply" + g, "median_cpu_us")), cb::ms(median("write_svg" + g, "median_cpu_us")),
         cb::ms(median("write_step" + g, "median_cpu_us")), cb::ms(job),
         cb::ms(median("end_to_end" + g, "median_wall_us")), job ? cb::fixed(*job * 1e3 / volumes, 1) : "—",
         cb::ratio(job, previous)});
    previous = job;
  }
  t.add_note("Target: the 20³ job under 3 s and near-linear growth (about 8x per row).");
  const std::optional<double> big = median("end_to_end/grid_20", "median_wall_us");
  t.add_note(std::string("Target 20³ job under 3 s wall: ") +
             (big ? (*big < 3000 ? "MET" : "NOT MET") : "not run") + ".");
  t.print(os);

  cb::table jobs("The whole job on spheres and cylinder stacks (read, convert, validate, four files)",
                 {"model", "edges", "volumes", "job ms", "job wall ms", "µs per edge"});
  for (const job_model& m : job_models()) {
    const std::optional<double> job = median("end_to_end/" + m.name, "median_cpu_us");
    jobs.add_row({m.name, cb::count(m.edges), cb::count(m.volumes), cb::ms(job),
                  cb::ms(median("end_to_end/" + m.name, "median_wall_us")),
                  job ? cb::fixed(*job * 1e3 / static_cast<double>(m.edges), 2) : "—"});
  }
  jobs.add_note(
      "UV spheres: sample_uv_sphere(slices, stacks), one volume, planar rings and meridians that are not "
      "faces. "
      "Cylinder stacks: k cylinders of n sides on each other, k volumes, inner rings are walls. Medians of "
      "11 "
      "runs (5 above 20 000 edges); each run writes .3dcl, OBJ, PLY and SVG as wire2cells does.");
  jobs.print(os);
}

}  // namespace

int main(int argc, char** argv) { return cb::table_main(argc, argv, register_all, print_tables); }
