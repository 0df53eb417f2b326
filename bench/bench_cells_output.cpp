// SPDX-License-Identifier: MIT
// The main job's output paths on k×k×k grids of unit cubes (sample_grid, every wall a face):
// each writer of io/cells_io.hpp (.3dcl text, OBJ per volume, PLY by volume, exploded SVG) on
// its own, reading and converting the OBJ wireframe (wireframe_to_cells), and the whole job as
// wire2cells runs it (read, convert, validate, write the four files). Prints a growth table of
// CPU and wall medians: near-linear growth keeps the ratio per 8x volumes near 8.

#include "bench_support.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cellforge/cells/validate.hpp"
#include "cellforge/io/cells_io.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/wireframe/sample_models.hpp"
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
    cellforge::io::write_obj(p, cellforge::sample_grid(n, n, n).wire);
    it = files.emplace(k, p).first;
  }
  return it->second;
}

/// The grid's cell complex, converted once.
const cellforge::cell_complex<glm::dvec3>& grid_cells(int k) {
  static std::map<int, cellforge::cell_complex<glm::dvec3>> cache;
  auto it = cache.find(k);
  if (it == cache.end()) {
    const auto n = static_cast<std::size_t>(k);
    it = cache.emplace(k, cellforge::wireframe_to_cells(cellforge::sample_grid(n, n, n).wire).cells).first;
  }
  return it->second;
}

/// The main job: what wire2cells does between reading its arguments and exiting. Returns the
/// picture's counts.
cellforge::io::svg_result end_to_end(const fs::path& input, const fs::path& out_dir) {
  const auto wire = cellforge::io::read_obj_wireframe<glm::dvec3>(input);
  const cellforge::wireframe_result<glm::dvec3> r = cellforge::wireframe_to_cells(wire);
  if (!cellforge::validate(r.cells).ok())
    throw cellforge::error(cellforge::error_category::topology, "the grid's complex does not validate");
  const std::string stem = input.stem().string();
  cellforge::io::write_3dcl(out_dir / (stem + ".3dcl"), r.cells);
  cellforge::io::write_cells_obj(out_dir / (stem + ".obj"), r.cells);
  cellforge::io::write_cells_ply(out_dir / (stem + ".ply"), r.cells);
  return cellforge::io::write_cells_svg(out_dir / (stem + ".svg"), r.cells);
}

void register_path(const std::string& path, int k, std::function<void(benchmark::State&)> body) {
  benchmark::RegisterBenchmark((path + "/grid_" + std::to_string(k)).c_str(),
                               [body](benchmark::State& s) {
                                 try {
                                   body(s);
                                 } catch (const std::exception& e) {
                                   s.SkipWithError(e.what());
                                 }
                               })
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(k >= 20 ? 5 : 11);
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
      cb::median_loop(s, [&] { return end_to_end(input, out).edges; });
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
      {"grid", "volumes", "faces", "read + convert ms", "3dcl ms", "OBJ ms", "PLY ms", "SVG ms", "job ms",
       "job wall ms", "job µs per volume", "job growth (8x volumes)"});
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
         cb::ms(job), cb::ms(median("end_to_end" + g, "median_wall_us")),
         job ? cb::fixed(*job * 1e3 / volumes, 1) : "—", cb::ratio(job, previous)});
    previous = job;
  }
  t.add_note("Target: the 20³ job under 3 s and near-linear growth (about 8x per row).");
  const std::optional<double> big = median("end_to_end/grid_20", "median_wall_us");
  t.add_note(std::string("Target 20³ job under 3 s wall: ") +
             (big ? (*big < 3000 ? "MET" : "NOT MET") : "not run") + ".");
  t.print(os);
}

}  // namespace

int main(int argc, char** argv) { return cb::table_main(argc, argv, register_all, print_tables); }
