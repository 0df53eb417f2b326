// Shared by the thin_points and smooth_edges examples: command-line options and loading a
// closed solid from an OBJ/OFF/PLY mesh or from one volume of a .3dcl cell list.
#pragma once

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/io/cells_io.hpp"
#include "cellforge/io/mesh_io.hpp"

namespace example {

/// The command line: one optional input path, then `--name value` options and `--flag`s.
struct command_line {
  std::filesystem::path input;
  std::vector<std::pair<std::string, std::string>> values;  // --name value
  std::vector<std::string> flags;                           // --name

  bool has(std::string_view flag) const { return std::find(flags.begin(), flags.end(), flag) != flags.end(); }

  /// The number after --name, or `fallback`; throws invalid_input naming the option and its range.
  double number(std::string_view name, double fallback, double lo, double hi, bool whole = false) const {
    for (const auto& [n, v] : values) {
      if (n != name) continue;
      double x = 0;
      const auto r = std::from_chars(v.data(), v.data() + v.size(), x);
      if (r.ec != std::errc{} || r.ptr != v.data() + v.size() || !(x >= lo && x <= hi) ||
          (whole && x != static_cast<double>(static_cast<long long>(x))))
        throw cellforge::error(cellforge::error_category::invalid_input,
                               "--" + std::string(name) + " must be " +
                                   (whole ? "a whole number" : "a number") + " from " + fmt(lo) + " to " +
                                   fmt(hi) + ", got '" + v + "'");
      return x;
    }
    return fallback;
  }

  std::string text(std::string_view name, std::string fallback) const {
    for (const auto& [n, v] : values)
      if (n == name) return v;
    return fallback;
  }

  static std::string fmt(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
  }
};

/// Parses argv: `with_value` names the options that take a value, `flag_names` those that do not.
inline command_line parse_command_line(int argc, char** argv, const std::filesystem::path& default_input,
                                       const std::vector<std::string_view>& with_value,
                                       const std::vector<std::string_view>& flag_names) {
  command_line cl;
  cl.input = default_input;
  bool have_input = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a.starts_with("--")) {
      const std::string_view name = a.substr(2);
      if (std::find(with_value.begin(), with_value.end(), name) != with_value.end()) {
        if (i + 1 >= argc)
          throw cellforge::error(cellforge::error_category::invalid_input, std::string(a) + " needs a value");
        cl.values.emplace_back(std::string(name), argv[++i]);
      } else if (std::find(flag_names.begin(), flag_names.end(), name) != flag_names.end()) {
        cl.flags.emplace_back(name);
      } else {
        throw cellforge::error(cellforge::error_category::invalid_input,
                               "unknown option '" + std::string(a) + "'");
      }
    } else if (!have_input) {
      cl.input = std::filesystem::path(a);
      have_input = true;
    } else {
      throw cellforge::error(cellforge::error_category::invalid_input,
                             "more than one input file ('" + std::string(a) + "')");
    }
  }
  return cl;
}

/// A closed solid to work on: the mesh, and when it came from a .3dcl file, the complex and volume
/// (the algorithms then report cell ids).
struct solid {
  cellforge::halfedge_mesh mesh;
  std::optional<cellforge::cell_complex> cells;
  cellforge::cell_volume volume{};
  cellforge::polygon_soup<glm::dvec3> soup;  // for pictures and OBJ output
  double load_ms = 0;
};

/// Reads an OBJ/OFF/PLY mesh, or volume `volume` of a .3dcl file. Throws cellforge::error.
inline solid load_solid(const std::filesystem::path& path, int volume) {
  const auto t0 = std::chrono::steady_clock::now();
  solid s;
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".3dcl") {
    s.cells = cellforge::io::read_3dcl(path);
    if (volume < 0 || static_cast<std::size_t>(volume) >= s.cells->num_volumes())
      throw cellforge::error(cellforge::error_category::invalid_input,
                             "--volume " + std::to_string(volume) + ": '" + path.string() + "' has " +
                                 std::to_string(s.cells->num_volumes()) + " volumes (0-based)");
    s.volume = cellforge::cell_volume(static_cast<std::uint32_t>(volume));
    s.mesh = cellforge::volume_boundary_mesh<glm::dvec3>(*s.cells, s.volume);
  } else {
    s.mesh = cellforge::io::read_mesh<glm::dvec3>(path);
  }
  s.soup = cellforge::to_soup<glm::dvec3>(s.mesh);
  s.load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

/// Milliseconds spent in f().
template <class F>
double time_ms(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// Creates the output directory (and parents); throws io when it cannot.
inline std::filesystem::path output_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw cellforge::error(cellforge::error_category::io,
                           "cannot create the output directory '" + dir.string() + "': " + ec.message());
  return dir;
}

/// What both examples start from: the command line, the output directory and the loaded solid.
struct session {
  command_line cl;
  int volume = 0;
  std::filesystem::path out;
  solid s;
  std::string stem;  ///< the input's file name without extension, for output names

  /// Runs f(cells, volume) on a .3dcl input (cell ids in the result), else g(mesh); returns ms.
  template <class OnCells, class OnMesh>
  double run(OnCells&& f, OnMesh&& g) const {
    return time_ms([&] { s.cells ? f(*s.cells, s.volume) : g(s.mesh); });
  }

  /// Prints "<name>: <input>" and the solid's size.
  void print_solid(const char* name) const {
    std::printf("%s: %s%s\n", name, cl.input.string().c_str(),
                s.cells ? (" volume " + std::to_string(volume)).c_str() : "");
    std::printf("  solid            %zu vertices, %zu edges, %zu faces (read in %.2f ms)\n",
                s.mesh.num_vertices(), s.mesh.num_edges(), s.mesh.num_faces(), s.load_ms);
  }
};

/// Parses the command line (plus --out and --volume, which both examples take), creates the
/// output directory and loads the solid. Throws cellforge::error.
inline session open_session(int argc, char** argv, const std::filesystem::path& default_input,
                            std::initializer_list<std::string_view> with_value,
                            std::initializer_list<std::string_view> flag_names) {
  std::vector<std::string_view> names(with_value);
  names.insert(names.end(), {"out", "volume"});
  session x;
  x.cl = parse_command_line(argc, argv, default_input, names, flag_names);
  x.volume = static_cast<int>(x.cl.number("volume", 0, 0, 4e9, true));
  x.out = output_dir(x.cl.text("out", "out"));
  x.s = load_solid(x.cl.input, x.volume);
  x.stem = x.cl.input.stem().string();
  return x;
}

}  // namespace example
