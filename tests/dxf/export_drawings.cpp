// SPDX-License-Identifier: MIT
// Writes a sample of the generated drawings as text for scripts/make-dxf-data.py (ezdxf) to write
// as DXF: test_io_dxf_drawing reads both and compares. Usage: export_drawings OUT_DIR
#include <cstdio>
#include <filesystem>
#include <string>

#include "cellforge/core/error.hpp"
#include "cellforge/io/drawing_text.hpp"
#include "cellforge/samples/drawings.hpp"
#include "cellforge/samples/round_drawings.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: export_drawings OUT_DIR\n");
    return 2;
  }
  try {
    const std::filesystem::path out(argv[1]);
    std::filesystem::create_directories(out);
    cellforge::samples::sketch_sweep_options options;
    options.limit = 8;
    options.max_edges = 60;
    options.families = {"prism", "normalon", "through slot", "platonic"};
    std::size_t written = 0;
    for (const auto& s : cellforge::samples::sketch_sweep(options)) {
      cellforge::io::write_drawing_text(out / ("sample_" + std::to_string(written++) + ".txt"), s.drawing,
                                        {"generated: " + s.name});
    }
    cellforge::samples::round_sweep_options rounds;
    rounds.drawings = 3;
    std::size_t k = 0;
    for (const auto& s : cellforge::samples::round_drawing_sweep(rounds)) {
      cellforge::io::write_arc_drawing_text(out / ("rounds_" + std::to_string(k++) + ".txt"), s.drawing,
                                            {"generated: " + s.name});
      ++written;
    }
    std::printf("export_drawings: %zu drawings in %s\n", written, out.string().c_str());
  } catch (const cellforge::error& e) {
    std::fprintf(stderr, "export_drawings: %s\n", e.what());
    return 1;
  }
  return 0;
}
