// Shared by the examples: command-line options (a `--name value` reader for thin_points and
// smooth_edges; a table of options with help text and usage errors for wire2cells) and loading a
// closed solid from an OBJ/OFF/PLY mesh or from one volume of a .3dcl cell list.
#pragma once

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
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

/// A usage error: an unknown option, a missing or malformed value, too many arguments. Programs
/// report it with a pointer to --help and exit status 2, apart from errors in the input or the output.
struct usage_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// One option of a program: its spellings ("-o", "--output"), the name of its value ("DIR"; empty
/// for a flag), one line of help that states the default, and what it does with the value.
struct option_spec {
  std::vector<std::string_view> names;
  std::string_view value;
  std::string help;
  std::function<void(std::string_view)> apply;  ///< gets the value ("" for a flag); throws usage_error
};

/// Applies the options in argv[1..] (`--name value`, `--name=value`, `-o value`) and returns the
/// other arguments in order; "--" ends the options. Throws usage_error naming an unknown option
/// or one without its value. O(arguments x options).
inline std::vector<std::string> apply_options(int argc, char** argv, const std::vector<option_spec>& specs) {
  std::vector<std::string> rest;
  bool only_arguments = false;
  for (int i = 1; i < argc; ++i) {
    std::string_view arg = argv[i];
    if (only_arguments || arg.size() < 2 || arg[0] != '-') {
      rest.emplace_back(arg);
      continue;
    }
    if (arg == "--") {
      only_arguments = true;
      continue;
    }
    std::optional<std::string_view> value;
    if (const std::size_t eq = arg.find('='); arg.starts_with("--") && eq != std::string_view::npos) {
      value = arg.substr(eq + 1);
      arg = arg.substr(0, eq);
    }
    const auto spec = std::find_if(specs.begin(), specs.end(), [&](const option_spec& o) {
      return std::find(o.names.begin(), o.names.end(), arg) != o.names.end();
    });
    if (spec == specs.end()) throw usage_error("unknown option '" + std::string(arg) + "'");
    if (spec->value.empty()) {
      if (value) throw usage_error(std::string(arg) + " takes no value");
      spec->apply("");
      continue;
    }
    if (!value) {
      if (i + 1 >= argc)
        throw usage_error(std::string(arg) + " needs a value (" + std::string(spec->value) + ")");
      value = argv[++i];
    }
    spec->apply(*value);
  }
  return rest;
}

/// The options as --help lists them: spellings and value, then the help text wrapped at 100
/// columns. O(options x help length).
inline std::string options_help(const std::vector<option_spec>& specs) {
  constexpr std::size_t indent = 28, width = 100;
  std::string out;
  for (const option_spec& o : specs) {
    std::string line = " ";
    for (const std::string_view n : o.names) line += (line.size() > 1 ? ", " : " ") + std::string(n);
    if (!o.value.empty()) line += " " + std::string(o.value);
    line.resize(std::max(indent, line.size() + 2), ' ');
    std::size_t column = line.size();
    for (std::size_t at = 0; at < o.help.size();) {
      const std::size_t end = std::min(o.help.find(' ', at), o.help.size());
      const std::string_view word = std::string_view(o.help).substr(at, end - at);
      if (column > indent && column + word.size() > width) {
        line.pop_back();  // the space after the last word
        out += line + "\n";
        line.assign(indent, ' ');
        column = indent;
      }
      line += std::string(word) + " ";
      column += word.size() + 1;
      at = end + 1;
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

/// The number `text` given to `option`, which must lie in [lo, hi]; throws usage_error naming
/// the option and the range. O(1).
inline double option_number(std::string_view option, std::string_view text, double lo, double hi) {
  double x = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), x);
  if (text.empty() || r.ec != std::errc{} || r.ptr != text.data() + text.size() || !(x >= lo && x <= hi))
    throw usage_error(std::string(option) + " must be a number from " + command_line::fmt(lo) + " to " +
                      command_line::fmt(hi) + ", got '" + std::string(text) + "'");
  return x;
}

/// The whole number `text` given to `option` (0 .. 2^64 - 1); throws usage_error naming the option. O(1).
inline std::uint64_t option_count(std::string_view option, std::string_view text) {
  std::uint64_t n = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), n);
  if (text.empty() || r.ec != std::errc{} || r.ptr != text.data() + text.size())
    throw usage_error(std::string(option) + " must be a whole number >= 0, got '" + std::string(text) + "'");
  return n;
}

/// The value named `text` among `choices` for `option`; throws usage_error listing the choices. O(choices).
template <class T>
T option_choice(std::string_view option, std::string_view text,
                std::initializer_list<std::pair<std::string_view, T>> choices) {
  std::string names;
  for (const auto& [name, value] : choices) {
    if (name == text) return value;
    names += (names.empty() ? "" : ", ") + std::string(name);
  }
  throw usage_error(std::string(option) + " must be one of " + names + ", got '" + std::string(text) + "'");
}

/// A closed solid to work on: the mesh, and when it came from a .3dcl file, the complex and volume
/// (the algorithms then report cell ids).
struct solid {
  cellforge::surface_mesh<glm::dvec3> mesh;
  std::optional<cellforge::cell_complex<glm::dvec3>> cells;
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
    s.cells = cellforge::io::read_3dcl<glm::dvec3>(path);
    if (volume < 0 || static_cast<std::size_t>(volume) >= s.cells->num_volumes())
      throw cellforge::error(cellforge::error_category::invalid_input,
                             "--volume " + std::to_string(volume) + ": '" + path.string() + "' has " +
                                 std::to_string(s.cells->num_volumes()) + " volumes (0-based)");
    s.volume = cellforge::cell_volume(static_cast<std::uint32_t>(volume));
    s.mesh = cellforge::volume_boundary_mesh<glm::dvec3>(*s.cells, s.volume);
  } else {
    s.mesh = cellforge::io::read_mesh<glm::dvec3>(path);
  }
  s.soup = cellforge::to_soup(s.mesh);
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

/// Throws io naming the file when writing `out` would replace `input` (the same path, or a
/// link to the same file): no example ever writes over what it read. O(path length).
inline void refuse_to_overwrite(const std::filesystem::path& out, const std::filesystem::path& input) {
  std::error_code ec, ec_out, ec_in;
  const bool same_file = std::filesystem::exists(out, ec) && std::filesystem::equivalent(out, input, ec);
  const std::filesystem::path out_path = std::filesystem::weakly_canonical(out, ec_out),
                              in_path = std::filesystem::weakly_canonical(input, ec_in);
  if (same_file || (!ec_out && !ec_in && out_path == in_path))
    throw cellforge::error(cellforge::error_category::io,
                           "refusing to write '" + out.string() +
                               "': it is the input file; run in another folder or choose another output");
}

/// refuse_to_overwrite for each output, before anything is written. O(outputs).
inline void refuse_to_overwrite(std::initializer_list<std::filesystem::path> outputs,
                                const std::filesystem::path& input) {
  for (const auto& out : outputs) refuse_to_overwrite(out, input);
}

/// What a program is doing, and on how much, for the one message it prints when memory runs
/// out: std::bad_alloc names no size, so each program notes what it is about to build.
struct stage_note {
  std::string what = "starting";
  void operator()(std::string now) { what = std::move(now); }
};

/// Prints "<program>: out of memory while <stage> (std::bad_alloc): ..." to stderr. O(1).
inline void report_out_of_memory(const char* program, const stage_note& stage) {
  std::fprintf(
      stderr,
      "%s: out of memory while %s (std::bad_alloc); try a smaller input or a machine with more memory\n",
      program, stage.what.c_str());
}

/// "'name' (12.3 MB)" for a stage note: the file and its size, or just the name when it has none. O(1).
inline std::string file_and_size(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  std::string s = "'" + path.string() + "'";
  if (ec) return s;
  char buf[48];
  std::snprintf(buf, sizeof buf, " (%.1f MB)", static_cast<double>(bytes) / 1e6);
  return s + buf;
}

/// A count for a stage note, to three figures ("1.68e+07"). O(1).
inline std::string about(double count) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", count);
  return buf;
}

/// Removes every `flag` from argv (moving the rest down, argc shrinking) and says whether it was
/// there: for the programs that read their arguments by position. O(argc).
inline bool take_flag(int& argc, char** argv, std::string_view flag) {
  int kept = 1;
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]) != flag) argv[kept++] = argv[i];
  const bool found = kept != argc;
  argc = kept;
  return found;
}

/// What both examples start from: the command line, the output directory and the loaded solid.
struct session {
  command_line cl;
  int volume = 0;
  std::filesystem::path out;
  solid s;
  std::string stem;     ///< the input's file name without extension, for output names
  bool picture = true;  ///< false: --no-svg, leave the picture out

  /// The path of output `name` in the output directory, refused if it is the input file.
  std::filesystem::path output(const std::string& name) const {
    std::filesystem::path p = out / name;
    refuse_to_overwrite(p, cl.input);
    return p;
  }

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

/// Parses the command line (plus --out, --volume and --no-svg, which both examples take), creates
/// the output directory and loads the solid, noting each step in `stage`. Throws cellforge::error.
inline session open_session(int argc, char** argv, const std::filesystem::path& default_input,
                            std::initializer_list<std::string_view> with_value,
                            std::initializer_list<std::string_view> flag_names, stage_note& stage) {
  std::vector<std::string_view> names(with_value), flags(flag_names);
  names.insert(names.end(), {"out", "volume"});
  flags.push_back("no-svg");
  session x;
  x.cl = parse_command_line(argc, argv, default_input, names, flags);
  x.volume = static_cast<int>(x.cl.number("volume", 0, 0, 2147483647.0, true));
  x.picture = !x.cl.has("no-svg");
  x.out = output_dir(x.cl.text("out", "out"));
  stage("reading " + file_and_size(x.cl.input));
  x.s = load_solid(x.cl.input, x.volume);
  stage("working on a solid of " + std::to_string(x.s.mesh.num_faces()) + " faces");
  x.stem = x.cl.input.stem().string();
  return x;
}

}  // namespace example
