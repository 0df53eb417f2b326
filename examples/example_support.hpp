// Shared by the example programs, which make one toolkit: a table of options with help text and
// usage errors, the options every program takes (-h, -o, --no-svg, --format, --quiet,
// --keep-partial), the exit statuses 0-4, outputs checked before any is written and written to
// temporaries renamed on success, progress on stderr, telling a user which program takes an
// input, and loading a closed solid from an OBJ/OFF/PLY mesh or one volume of a .3dcl cell list.
#pragma once

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#if __has_include(<spawn.h>) && __has_include(<sys/wait.h>)
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstring>
extern char** environ;  // the environment a batch's runs inherit (POSIX)
#define EXAMPLE_HAS_SPAWN 1
#else
#include <cstdlib>
#endif

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/io/cells_io.hpp"
#include "cellforge/io/mesh_io.hpp"

namespace example {

/// A number as the shortest text that reads back the same ("0.1", "1e-09"). O(1).
inline std::string fmt(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
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
/// other arguments in order; "--" ends the options. `positions`, when given, receives the argv
/// indices of those arguments and of "--" (what a batch leaves out when it runs one input).
/// Throws usage_error naming an unknown option or one without its value. O(arguments x options).
inline std::vector<std::string> apply_options(int argc, char** argv, const std::vector<option_spec>& specs,
                                              std::vector<int>* positions = nullptr) {
  std::vector<std::string> rest;
  bool only_arguments = false;
  for (int i = 1; i < argc; ++i) {
    std::string_view arg = argv[i];
    if (only_arguments || arg.size() < 2 || arg[0] != '-') {
      rest.emplace_back(arg);
      if (positions) positions->push_back(i);
      continue;
    }
    if (arg == "--") {
      only_arguments = true;
      if (positions) positions->push_back(i);
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
    throw usage_error(std::string(option) + " must be a number from " + fmt(lo) + " to " + fmt(hi) +
                      ", got '" + std::string(text) + "'");
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
      throw usage_error("--volume " + std::to_string(volume) + ": '" + path.string() + "' has " +
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

// ---- One convention for every program: options, help, exit statuses, outputs, progress ----

/// The exit statuses every program shares (each --help lists them).
inline constexpr int exit_ok = 0;            // success, every output written
inline constexpr int exit_input = 1;         // the input cannot be read
inline constexpr int exit_usage = 2;         // unknown option, bad value, too many arguments
inline constexpr int exit_output = 3;        // an output cannot be written, or would replace an input
inline constexpr int exit_not_for_this = 4;  // read, but not what this program needs (or no good result)

/// An input that was read but is not what the program needs (exit 4); the message says what the
/// input is and which program takes it.
struct wrong_input : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// An output that cannot be written or would replace an input (exit 3).
struct output_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Throws output_error naming the file when writing `out` would replace `input` (the same path,
/// or a link to the same file): no program ever writes over what it read. O(path length).
inline void refuse_to_overwrite(const std::filesystem::path& out, const std::filesystem::path& input) {
  std::error_code ec, ec_out, ec_in;
  const bool same_file = std::filesystem::exists(out, ec) && std::filesystem::equivalent(out, input, ec);
  const std::filesystem::path out_path = std::filesystem::weakly_canonical(out, ec_out),
                              in_path = std::filesystem::weakly_canonical(input, ec_in);
  if (same_file || (!ec_out && !ec_in && out_path == in_path))
    throw output_error("refusing to write '" + out.string() +
                       "': it is the input file; run in another folder or choose another output (-o DIR)");
}

/// What a program is doing, for the progress lines on stderr and the one message it prints
/// when memory runs out (std::bad_alloc names no size). Once start()ed, a watcher thread prints
/// "<program>: <seconds> s: <stage>" when a run has passed a second, at each new stage and every
/// 5 s within one. Cost: one thread waking 10 times a second.
class stage_note {
 public:
  stage_note() = default;
  stage_note(const stage_note&) = delete;
  stage_note& operator=(const stage_note&) = delete;
  ~stage_note() { stop(); }

  /// Starts the progress lines of `program` (show = false: none, as with --quiet).
  void start(std::string program, bool show) {
    program_ = std::move(program);
    if (!show) return;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      watcher_ = std::jthread([this, t0](std::stop_token stop) { watch(stop, t0); });
    } catch (const std::system_error&) {  // no thread to spare (a memory cap): no progress lines
    }
  }

 private:
  void watch(const std::stop_token& stop, std::chrono::steady_clock::time_point t0) {
    unsigned shown = 0;
    auto last = t0;
    std::unique_lock lock(mutex_);
    while (!stop.stop_requested()) {
      wake_.wait_for(lock, stop, std::chrono::milliseconds(100), [] { return false; });
      if (stop.stop_requested()) break;
      const auto now = std::chrono::steady_clock::now();
      if (now - t0 < std::chrono::seconds(1)) continue;
      if (shown == serial_ && now - last < std::chrono::seconds(5)) continue;
      const double s = std::chrono::duration<double>(now - t0).count();
      if (percent_ >= 0)
        std::fprintf(stderr, "%s: %.1f s: %s (%d%% of the stages done)\n", program_.c_str(), s, what_.c_str(),
                     percent_);
      else
        std::fprintf(stderr, "%s: %.1f s: %s\n", program_.c_str(), s, what_.c_str());
      shown = serial_;
      last = now;
    }
  }

 public:
  /// Ends the progress lines. O(1).
  void stop() {
    if (watcher_.joinable()) {
      watcher_.request_stop();
      watcher_.join();
    }
  }

  /// Notes the stage now starting and, when known, the share of the stages done (0..100).
  void operator()(std::string now, int percent = -1) {
    const std::lock_guard lock(mutex_);
    what_ = std::move(now);
    percent_ = percent;
    ++serial_;
  }

  std::string what() const {
    const std::lock_guard lock(mutex_);
    return what_;
  }
  const std::string& program() const { return program_; }

 private:
  mutable std::mutex mutex_;
  std::condition_variable_any wake_;
  std::string program_, what_ = "starting";
  int percent_ = -1;
  unsigned serial_ = 0;
  std::jthread watcher_;
};

/// Prints "<program>: out of memory while <stage> (std::bad_alloc): ..." to stderr. O(1).
inline void report_out_of_memory(const char* program, const stage_note& stage) {
  std::fprintf(
      stderr,
      "%s: out of memory while %s (std::bad_alloc); try a smaller input or a machine with more memory\n",
      program, stage.what().c_str());
}

/// "'name' (12.3 MB)" for a stage note: the file and its size, or just the name when it has none. O(1).
inline std::string file_and_size(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  std::string s = "'";  // appended, not "'" + string: GCC 12 -O3 misreads that as overlapping (-Wrestrict)
  s += path.string();
  s += '\'';
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

/// A path's extension in lower case (".obj"). O(length).
inline std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// The kinds of input the programs read, to tell a user which program takes a file.
enum class input_kind { unknown, mesh, point_set, wireframe, skeleton, drawing, cells };

/// Which programs take an input of kind k, as a clause ("wire2cells takes a wireframe").
inline std::string takers(input_kind k) {
  switch (k) {
    case input_kind::mesh:
      return "mesh_info, subdivide and hull take a mesh, smooth_edges and thin_points a closed one";
    case input_kind::point_set:
      return "hull takes a point set";
    case input_kind::wireframe:
      return "wire2cells takes a wireframe (tubes an OBJ one, given a radius with --radius)";
    case input_kind::skeleton:
      return "tubes takes a skeleton with radii";
    case input_kind::drawing:
      return "sketch2cells takes a line drawing, sketch_rounds one with arcs";
    case input_kind::cells:
      return "smooth_edges and thin_points take a volume of a cell list (--volume N)";
    case input_kind::unknown:
      break;
  }
  return "no program here knows it";
}

/// What --help says about batches: several inputs or a folder, --jobs, the output folders and
/// the exit status. O(1).
inline std::string batch_help(const std::string& program) {
  return "several inputs (files, or folders: their files that " + program +
         " reads, in name order) run as a batch:\n"
         "each input runs as its own " +
         program +
         " with the same options, --jobs N at a time, its outputs in a folder\n"
         "named after the input (-o DIR/<name>/); one line per input and a summary are printed, and the\n"
         "batch exits with the worst status of its runs (1, then 3, then 4; 2 for a usage error).\n";
}

/// What the file's extension says it is (unknown for .obj, which holds several kinds, and for
/// names no program reads). O(1).
inline input_kind kind_by_extension(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".off" || ext == ".ply" || ext == ".stl") return input_kind::mesh;
  if (ext == ".swc") return input_kind::skeleton;
  if (ext == ".svg" || ext == ".dxf" || ext == ".txt") return input_kind::drawing;
  if (ext == ".3dcl") return input_kind::cells;
  if (ext == ".edges") return input_kind::wireframe;
  return input_kind::unknown;
}

/// What an OBJ file holds, from its statements: counts of `v`, `l` and `f` lines and whether the
/// first `v` carries a fourth value (a radius). O(file size); an unreadable file counts nothing.
struct obj_contents {
  std::size_t vertices = 0, lines = 0, faces = 0;
  bool radii = false;

  input_kind kind() const {
    if (faces > 0) return input_kind::mesh;
    if (lines > 0) return radii ? input_kind::skeleton : input_kind::wireframe;
    return vertices > 0 ? input_kind::point_set : input_kind::unknown;
  }
  /// "a wireframe OBJ (28 vertices, 49 lines, no faces)".
  std::string describe() const {
    const input_kind k = kind();
    const char* what = k == input_kind::mesh        ? "a mesh OBJ"
                       : k == input_kind::skeleton  ? "a skeleton OBJ (vertices with radii)"
                       : k == input_kind::wireframe ? "a wireframe OBJ"
                       : k == input_kind::point_set ? "an OBJ of points only"
                                                    : "an OBJ with no vertices";
    return std::string(what) + " (" + std::to_string(vertices) + " vertices, " + std::to_string(lines) +
           " lines, " + (faces ? std::to_string(faces) : std::string("no")) + " faces)";
  }
};

inline obj_contents read_obj_contents(const std::filesystem::path& path) {
  obj_contents c;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return c;
  std::FILE* f = std::fopen(path.string().c_str(), "rb");
  if (!f) return c;
  std::string line;
  for (int ch = 0; ch != EOF;) {
    line.clear();
    while ((ch = std::fgetc(f)) != EOF && ch != '\n') line.push_back(static_cast<char>(ch));
    const std::size_t at = line.find_first_not_of(" \t");
    if (at == std::string::npos || at + 1 >= line.size() || (line[at + 1] != ' ' && line[at + 1] != '\t'))
      continue;
    const char s = line[at];
    if (s == 'f') ++c.faces;
    if (s == 'l') ++c.lines;
    if (s != 'v') continue;
    if (c.vertices++ == 0) {  // count the first vertex's values
      int values = 0;
      for (std::size_t i = at + 1; i < line.size() && line[i] != '#';) {
        const std::size_t b = line.find_first_not_of(" \t\r", i);
        if (b == std::string::npos || line[b] == '#') break;
        ++values;
        i = std::min(line.find_first_of(" \t\r", b), line.size());
      }
      c.radii = values == 4;
    }
  }
  std::fclose(f);
  return c;
}

/// Throws wrong_input: "'<input>' is <what>, not <wanted>; <who takes it>" (exit 4).
[[noreturn]] inline void not_for_this(const std::string& program, const std::filesystem::path& input,
                                      const std::string& what, const std::string& wanted, input_kind kind) {
  throw wrong_input("'" + input.string() + "' is " + what + ", not " + wanted + " as " + program +
                    " needs; " + takers(kind));
}

/// Refuses (exit 4) an input whose extension names a kind not in `accepted`. O(1).
inline void expect_extension(const std::string& program, const std::filesystem::path& input,
                             std::initializer_list<input_kind> accepted, const std::string& wanted) {
  const input_kind k = kind_by_extension(input);
  if (k == input_kind::unknown || std::find(accepted.begin(), accepted.end(), k) != accepted.end()) return;
  const char* what = k == input_kind::mesh        ? "a mesh file"
                     : k == input_kind::skeleton  ? "an SWC skeleton"
                     : k == input_kind::drawing   ? "a drawing file (.svg, .dxf or .txt)"
                     : k == input_kind::cells     ? "a cell list (.3dcl)"
                     : k == input_kind::wireframe ? "an edge list (a wireframe)"
                                                  : "a file of another kind";
  not_for_this(program, input, what, wanted, k);
}

/// One program of the toolkit: its name and help text, the options every program shares (and
/// its own), and what the shared ones set. See run() for how a program's main uses it.
struct program {
  std::string name;
  std::string usage;         ///< after the name: "[options] [input]"
  std::string about;         ///< what it does, a paragraph
  std::string input_help;    ///< what it reads (and the default input)
  std::string outputs_help;  ///< its outputs, one line each
  std::string exit4_help;    ///< when it exits 4
  std::string notes;         ///< anything else --help should say (may be empty)

  std::filesystem::path output = "out";
  bool svg = true, quiet = false, keep_partial = false, help = false;
  std::vector<std::string> formats;  ///< mesh output formats, when the program has --format
  bool format_given = false;         ///< --format was on the command line
  std::vector<option_spec> options;
  stage_note stage;
  unsigned jobs = 1;              ///< --jobs: runs of a batch at a time
  std::vector<input_kind> takes;  ///< the kinds a folder's files are taken by (.obj always)
  bool batch = true;              ///< several inputs or a folder run as a batch (run_batch)
  /// Arguments that are one run although there are several (a deprecated spelling such as
  /// `hull points.off merge`); none when empty.
  std::function<bool(const std::vector<std::string>&)> one_run;

  /// Adds the shared options: -h, -o, --no-svg, --format (when `mesh_formats` names the
  /// default format(s): the program writes meshes; --help shows `shown_default` instead when
  /// given), --quiet, --keep-partial.
  void add_common_options(const std::string& mesh_formats = {}, const std::string& shown_default = {}) {
    options.push_back(
        {{"-h", "--help"}, "", "print this help and exit", [this](std::string_view) { help = true; }});
    options.push_back({{"-o", "--output"},
                       "DIR",
                       "folder for the output files, created if missing (default: ./out/)",
                       [this](std::string_view v) {
                         if (v.empty()) throw usage_error("-o/--output needs a folder name");
                         output = std::filesystem::path(v);
                       }});
    options.push_back(
        {{"--no-svg"}, "", "do not write the pictures (.svg)", [this](std::string_view) { svg = false; }});
    if (!mesh_formats.empty()) {
      formats = split_formats("--format", mesh_formats);
      options.push_back(
          {{"--format"},
           "obj|off|ply|stl",
           "file format of the mesh outputs; several comma-separated write one file each (default: " +
               (shown_default.empty() ? mesh_formats : shown_default) + ")",
           [this](std::string_view v) {
             formats = split_formats("--format", v);
             format_given = true;
           }});
    }
    options.push_back({{"--quiet"},
                       "",
                       "print nothing on stdout and no progress on stderr (errors still go to stderr)",
                       [this](std::string_view) { quiet = true; }});
    options.push_back({{"--jobs"},
                       "N",
                       "with several inputs or a folder: runs at a time, 1 to 256 (default: 1)",
                       [this](std::string_view v) { jobs = parse_jobs(v); }});
    options.push_back({{"--keep-partial"},
                       "",
                       "keep the outputs of a failed run: those written before an error, and all of a result "
                       "that fails its check (default: a run that exits non-zero leaves no output)",
                       [this](std::string_view) { keep_partial = true; }});
  }

  /// Adds the options of the programs that work on a closed solid (smooth_edges, thin_points):
  /// --volume N of a .3dcl input, and --out DIR, the deprecated spelling of -o.
  void add_solid_options(int& volume) {
    add_deprecated("--out", "DIR", "-o/--output",
                   [this](std::string_view v) { output = std::filesystem::path(v); });
    options.push_back({{"--volume"},
                       "N",
                       "the volume of a .3dcl input, 0-based (default: 0)",
                       [&volume](std::string_view v) {
                         volume = static_cast<int>(
                             std::min<std::uint64_t>(option_count("--volume", v), 2147483647));
                       }});
  }

  /// Adds `old_name` as a deprecated spelling of `new_names`: it does what apply does and says
  /// so on stderr.
  void add_deprecated(std::string_view old_name, std::string_view value, const std::string& new_names,
                      std::function<void(std::string_view)> apply) {
    options.push_back({{old_name},
                       value,
                       "deprecated spelling of " + new_names,
                       [this, old_name, new_names, apply](std::string_view v) {
                         std::fprintf(stderr, "%s: %.*s is deprecated; use %s\n", name.c_str(),
                                      static_cast<int>(old_name.size()), old_name.data(), new_names.c_str());
                         apply(v);
                       }});
  }

  /// The value of --jobs, 1 to 256; throws usage_error. O(1).
  static unsigned parse_jobs(std::string_view v) {
    const double n = option_number("--jobs", v, 1, 256);
    if (n != static_cast<unsigned>(n))
      throw usage_error("--jobs must be a whole number, got '" + std::string(v) + "'");
    return static_cast<unsigned>(n);
  }

  /// "obj,ply" as formats, each one of obj, off, ply, stl; throws usage_error. O(length).
  static std::vector<std::string> split_formats(std::string_view option, std::string_view v) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i <= v.size();) {
      const std::size_t comma = std::min(v.find(',', i), v.size());
      const std::string f(v.substr(i, comma - i));
      i = comma + 1;
      if (f != "obj" && f != "off" && f != "ply" && f != "stl")
        throw usage_error(std::string(option) + ": '" + f + "' is none of obj, off, ply, stl");
      if (std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
    }
    return out;
  }

  /// The one input among the arguments, or `fallback` when there is none; throws usage_error
  /// for more than one.
  std::filesystem::path one_input(const std::vector<std::string>& args,
                                  const std::filesystem::path& fallback) const {
    if (args.size() > 1) throw usage_error("more than one input ('" + args[1] + "')");
    return args.empty() ? fallback : std::filesystem::path(args[0]);
  }

  void print_help() const {
    std::printf("usage: %s %s\n\n%s\n\n", name.c_str(), usage.c_str(), about.c_str());
    if (!input_help.empty()) std::printf("input: %s\n\n", input_help.c_str());
    std::printf("options:\n%s\n", options_help(options).c_str());
    if (!outputs_help.empty())
      std::printf(
          "outputs, in the output folder (-o, default ./out/):\n%s"
          "No output is written over an input: %s checks every output before it writes any. Each is\n"
          "written to a temporary file and renamed when the run succeeds; a run that exits non-zero\n"
          "leaves no output unless --keep-partial is given.\n\n",
          outputs_help.c_str(), name.c_str());
    if (!notes.empty()) std::printf("%s\n\n", notes.c_str());
    if (batch) std::printf("%s\n", batch_help(name).c_str());
    std::printf(
        "exit status:\n"
        "  0  success%s\n"
        "  1  the input cannot be read (the message says why, with file:line for a parse error)\n"
        "  2  usage error (unknown option, bad value, too many arguments)\n"
        "  3  output error: the output folder cannot be created or written, or an output would\n"
        "     replace an input\n"
        "  4  %s\n",
        outputs_help.empty() ? "" : ", every output written", exit4_help.c_str());
  }
};

/// A program's outputs: each is checked when it is added (not an input, not a folder, its
/// folder can be made), written to a temporary file beside its name, and renamed by commit().
/// Without a commit (a failure) the destructor removes the temporaries and the folders it made,
/// or with --keep-partial renames what was written. O(outputs) file-system calls.
class output_files {
 public:
  output_files(const program& p, std::vector<std::filesystem::path> inputs)
      : program_(p), inputs_(std::move(inputs)) {
    // The folder: the nearest part of it that exists must be a folder.
    std::filesystem::path dir = p.output;
    std::error_code ec;
    for (std::filesystem::path at = dir; !at.empty(); at = at.parent_path()) {
      if (std::filesystem::exists(at, ec)) {
        if (!std::filesystem::is_directory(at, ec))
          throw output_error("cannot create the output folder '" + dir.string() + "': '" + at.string() +
                             "' is a file");
        break;
      }
      if (at == at.parent_path()) break;
    }
  }
  output_files(const output_files&) = delete;
  output_files& operator=(const output_files&) = delete;

  ~output_files() {
    if (committed_) return;
    std::error_code ec;
    if (program_.keep_partial) {
      for (const auto& [temp, final] : written_) std::filesystem::rename(temp, final, ec);
      if (!written_.empty())
        std::fprintf(stderr, "%s: --keep-partial: kept the %zu outputs the failed run wrote\n",
                     program_.name.c_str(), written_.size());
      return;
    }
    for (const auto& [temp, final] : written_) std::filesystem::remove(temp, ec);
    for (auto d = made_.rbegin(); d != made_.rend(); ++d) std::filesystem::remove(*d, ec);  // only if empty
    if (!written_.empty())
      std::fprintf(stderr, "%s: no output written (--keep-partial keeps the outputs of a failed run)\n",
                   program_.name.c_str());
  }

  /// The path of output `file_name` in the output folder, after checking that it replaces no
  /// input and is no folder; throws output_error.
  std::filesystem::path add(const std::string& file_name) {
    const std::filesystem::path p = program_.output / file_name;
    for (const auto& in : inputs_) refuse_to_overwrite(p, in);
    std::error_code ec;
    if (std::filesystem::is_directory(p, ec))
      throw output_error("cannot write '" + p.string() + "': it is a folder");
    return p;
  }

  /// Writes output `path` (from add()) by calling writer(temporary path); a failure is an
  /// output_error naming the file.
  template <class F>
  void write(const std::filesystem::path& path, F&& writer) {
    make_folder();
    std::filesystem::path temp = path;
    temp.replace_filename("." + path.stem().string() + ".partial" + path.extension().string());
    const auto discard = [&] {  // a half-written temporary (never a folder in its way)
      std::error_code ec;
      if (std::filesystem::is_regular_file(temp, ec)) std::filesystem::remove(temp, ec);
    };
    try {
      writer(temp);
    } catch (const std::bad_alloc&) {
      discard();
      throw;
    } catch (const std::exception& e) {
      discard();
      throw output_error("cannot write '" + path.string() + "': " + e.what());
    }
    written_.emplace_back(temp, path);
  }

  /// Renames every temporary to its name: the run's outputs are all there. Throws output_error.
  void commit() {
    for (const auto& [temp, final] : written_) {
      std::error_code ec;
      std::filesystem::rename(temp, final, ec);
      if (ec)
        throw output_error("cannot rename '" + temp.string() + "' to '" + final.string() +
                           "': " + ec.message());
    }
    committed_ = true;
  }

  /// "out/hull.off, out/hull.svg": the outputs written.
  std::string list() const {
    std::string s;
    for (const auto& w : written_) s += (s.empty() ? "" : ", ") + w.second.string();
    return s;
  }

 private:
  void make_folder() {
    if (folder_made_) return;
    std::vector<std::filesystem::path> missing;
    std::error_code ec;
    for (std::filesystem::path at = program_.output; !at.empty() && !std::filesystem::exists(at, ec);
         at = at.parent_path()) {
      missing.push_back(at);
      if (at == at.parent_path()) break;
    }
    for (auto d = missing.rbegin(); d != missing.rend(); ++d) {
      if (!std::filesystem::create_directory(*d, ec) && ec)
        throw output_error("cannot create the output folder '" + program_.output.string() +
                           "': " + ec.message());
      made_.push_back(*d);
    }
    folder_made_ = true;
  }

  const program& program_;
  std::vector<std::filesystem::path> inputs_, made_;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> written_;  // temporary, name
  bool folder_made_ = false, committed_ = false;
};

/// Writes a mesh file in the format its extension names. For STL, quads are split first along
/// the diagonal whose two triangles agree best with the quad's normal: the library's STL writer
/// ear-clips polygons and refuses non-planar ones, as a tube's quads are by rounding. O(faces).
inline void write_mesh_file(const std::filesystem::path& path,
                            const cellforge::polygon_soup<glm::dvec3>& soup) {
  if (lower_extension(path) != ".stl") {
    cellforge::io::write_soup(path, soup);
    return;
  }
  cellforge::polygon_soup<glm::dvec3> split;
  split.points = soup.points;
  const auto normal = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return glm::cross(soup.points[b] - soup.points[a], soup.points[c] - soup.points[a]);
  };
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto v = soup.face(f);
    if (v.size() != 4) {
      split.add_face(v);
      continue;
    }
    // Diagonal 0-2 gives (0,1,2) and (0,2,3); diagonal 1-3 gives (1,2,3) and (1,3,0).
    const glm::dvec3 n02a = normal(v[0], v[1], v[2]), n02b = normal(v[0], v[2], v[3]);
    const glm::dvec3 n13a = normal(v[1], v[2], v[3]), n13b = normal(v[1], v[3], v[0]);
    if (glm::dot(n02a, n02b) >= glm::dot(n13a, n13b)) {
      split.add_face({v[0], v[1], v[2]});
      split.add_face({v[0], v[2], v[3]});
    } else {
      split.add_face({v[1], v[2], v[3]});
      split.add_face({v[1], v[3], v[0]});
    }
  }
  cellforge::io::write_soup(path, split);
}

/// write_mesh_file for a half-edge mesh. O(size of the mesh).
inline void write_mesh_file(const std::filesystem::path& path,
                            const cellforge::surface_mesh<glm::dvec3>& mesh) {
  write_mesh_file(path, cellforge::to_soup(mesh));
}

/// Sends stdout to the null device (--quiet). O(1).
inline void silence_stdout() {
#ifdef _WIN32
  if (!std::freopen("NUL", "w", stdout)) return;
#else
  if (!std::freopen("/dev/null", "w", stdout)) return;
#endif
}

/// The inputs of a batch: each file argument, and each folder's regular files whose extension
/// names a kind in `takes` (every file when empty; .obj always), in name order. Throws
/// usage_error for a folder with no such file. O(files log files).
inline std::vector<std::filesystem::path> batch_inputs(const std::vector<std::string>& args,
                                                       const std::vector<input_kind>& takes) {
  namespace fs = std::filesystem;
  std::vector<fs::path> inputs;
  for (const std::string& a : args) {
    std::error_code ec;
    if (!fs::is_directory(a, ec)) {
      inputs.emplace_back(a);
      continue;
    }
    std::vector<fs::path> found;
    for (const fs::directory_entry& e : fs::directory_iterator(a, ec)) {
      if (!e.is_regular_file(ec)) continue;
      const input_kind k = kind_by_extension(e.path());
      if (takes.empty() || lower_extension(e.path()) == ".obj" ||
          std::find(takes.begin(), takes.end(), k) != takes.end())
        found.push_back(e.path());
    }
    if (found.empty()) throw usage_error("the folder '" + a + "' holds no file this program reads");
    std::sort(found.begin(), found.end());
    inputs.insert(inputs.end(), found.begin(), found.end());
  }
  std::vector<fs::path> seen;  // a file named twice runs once (both runs would write one folder)
  std::erase_if(inputs, [&](const fs::path& in) {
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(in, ec);
    if (ec) canonical = in;
    if (std::find(seen.begin(), seen.end(), canonical) != seen.end()) return true;
    seen.push_back(std::move(canonical));
    return false;
  });
  return inputs;
}

/// How one run of a batch ended: its exit status (-1 when it could not start; 128 + the signal
/// when killed) and the first line it wrote on stderr.
struct batch_run {
  int status = -1;
  std::string first_error;
};

/// Runs `args` (args[0] the program) with stdout discarded and stderr kept; waits. Processes
/// rather than threads: a run that fails, exhausts memory or crashes takes no other with it.
inline batch_run run_child(const std::vector<std::string>& args, const std::filesystem::path& err_log) {
  batch_run r;
#if defined(EXAMPLE_HAS_SPAWN)
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&files, 2, err_log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  pid_t pid = 0;
  const int started = posix_spawnp(&pid, argv[0], &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (started != 0) {
    r.first_error = std::string("cannot start '") + args[0] + "': " + std::strerror(started);
    return r;
  }
  int wait_status = 0;
  while (waitpid(pid, &wait_status, 0) < 0)
    if (errno != EINTR) return r;
  r.status = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : 128 + WTERMSIG(wait_status);
#else  // no posix_spawn: the shell, one run at a time
  std::string command;
  for (const std::string& a : args) command += "\"" + a + "\" ";
  command += "> NUL 2> \"" + err_log.string() + "\"";
  r.status = std::system(command.c_str());
#endif
  if (std::FILE* f = std::fopen(err_log.string().c_str(), "rb")) {
    for (int ch; (ch = std::fgetc(f)) != EOF && ch != '\n';) r.first_error.push_back(static_cast<char>(ch));
    std::fclose(f);
  }
  if (const std::string own = std::filesystem::path(args[0]).filename().string() + ": ";
      r.first_error.starts_with(own))  // the batch's line names the program already
    r.first_error.erase(0, own.size());
  return r;
}

/// A batch: runs the program once per input (argv without its inputs and "--", then
/// `-o <output>/<input name> --quiet -- <input>`), p.jobs at a time, prints one line per input
/// as it ends and a summary, and returns the worst status (1, then 3, then 4). O(inputs) runs.
inline int run_batch(const program& p, char** argv, int argc, const std::vector<int>& positions,
                     const std::vector<std::filesystem::path>& inputs) {
  namespace fs = std::filesystem;
  std::vector<std::string> common{argv[0]};
  for (int i = 1; i < argc; ++i)
    if (std::find(positions.begin(), positions.end(), i) == positions.end()) common.emplace_back(argv[i]);
  // Each input's output folder: its name without extension, or with it where two names meet.
  std::vector<std::string> folders;
  for (const fs::path& in : inputs) {
    const auto same_stem = [&](const fs::path& o) { return &o != &in && o.stem() == in.stem(); };
    std::string f =
        std::any_of(inputs.begin(), inputs.end(), same_stem) ? in.filename().string() : in.stem().string();
    std::replace(f.begin(), f.end(), '.', '_');
    folders.push_back(f);
  }
  std::vector<batch_run> runs(inputs.size());
  std::mutex print;
  std::size_t next = 0, ended = 0;
  const fs::path temp = fs::temp_directory_path();
  const auto worker = [&](unsigned w) {
    for (;;) {
      std::size_t k = 0;
      {
        const std::lock_guard lock(print);
        if (next == inputs.size()) return;
        k = next++;
      }
      std::vector<std::string> args = common;
      args.insert(args.end(), {"-o", (p.output / folders[k]).string(), "--quiet", "--", inputs[k].string()});
      const fs::path log =
          temp /
          (p.name + "-batch-" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) +
           "-" + std::to_string(w) + ".err");
      runs[k] = run_child(args, log);
      std::error_code ec;
      fs::remove(log, ec);
      const std::lock_guard lock(print);
      ++ended;
      const batch_run& r = runs[k];
      const std::string what = r.status == exit_ok ? "ok -> " + (p.output / folders[k]).string() + "/"
                               : r.status < 0      ? "not run: " + r.first_error
                               : r.status >= 128   ? "crashed (signal " + std::to_string(r.status - 128) + ")"
                                                 : "exit " + std::to_string(r.status) + ": " + r.first_error;
      std::printf("[%zu/%zu] %s: %s\n", ended, inputs.size(), inputs[k].string().c_str(), what.c_str());
      if (r.status != exit_ok && p.quiet)
        std::fprintf(stderr, "%s: %s: %s\n", p.name.c_str(), inputs[k].string().c_str(), what.c_str());
      std::fflush(stdout);
    }
  };
  {
    std::vector<std::jthread> pool;
    for (unsigned w = 0; w < std::min<std::size_t>(p.jobs, inputs.size()); ++w) pool.emplace_back(worker, w);
  }
  std::size_t count[5] = {};
  std::size_t other = 0;
  for (const batch_run& r : runs) (r.status >= 0 && r.status <= 4 ? count[r.status] : other) += 1;
  std::printf("%s: %zu inputs: %zu ok, %zu unreadable (1), %zu output errors (3), %zu not for %s (4)",
              p.name.c_str(), inputs.size(), count[0], count[1], count[3], count[4], p.name.c_str());
  if (count[2] + other) std::printf(", %zu usage errors or crashes", count[2] + other);
  std::printf("\n");
  if (other || count[1]) return exit_input;
  if (count[2]) return exit_usage;
  if (count[3]) return exit_output;
  return count[4] ? exit_not_for_this : exit_ok;
}

/// Whether the arguments make a batch (several inputs, or one folder), and then its status: the
/// batch's when they do. O(arguments) plus the batch.
inline std::optional<int> maybe_batch(const program& p, int argc, char** argv,
                                      const std::vector<std::string>& args,
                                      const std::vector<int>& positions) {
  std::error_code ec;
  if (!p.batch || args.empty() || (args.size() == 1 && !std::filesystem::is_directory(args[0], ec)) ||
      (p.one_run && p.one_run(args)))
    return std::nullopt;
  try {
    return run_batch(p, argv, argc, positions, batch_inputs(args, p.takes));
  } catch (const usage_error& e) {
    std::fprintf(stderr, "%s: %s\nTry '%s --help'.\n", p.name.c_str(), e.what(), p.name.c_str());
    return exit_usage;
  }
}

/// A program's main: parses the options (exit 2 on a usage error, 0 after --help), then runs
/// body(arguments) and maps what it throws to the exit statuses: usage_error 2, wrong_input 4,
/// output_error 3, anything else (a cellforge::error from a reader, std::bad_alloc) 1.
template <class Body>
int run(program& p, int argc, char** argv, Body&& body) {
  std::vector<std::string> args;
  std::vector<int> positions;
  try {
    args = apply_options(argc, argv, p.options, &positions);
    if (p.help) {
      p.print_help();
      return exit_ok;
    }
  } catch (const usage_error& e) {
    std::fprintf(stderr, "%s: %s\nTry '%s --help'.\n", p.name.c_str(), e.what(), p.name.c_str());
    return exit_usage;
  }
  if (p.quiet) silence_stdout();
  if (const std::optional<int> batch = maybe_batch(p, argc, argv, args, positions)) return *batch;
  p.stage.start(p.name, !p.quiet);
  int status = exit_input;
  try {
    status = body(args);
  } catch (const usage_error& e) {
    std::fprintf(stderr, "%s: %s\nTry '%s --help'.\n", p.name.c_str(), e.what(), p.name.c_str());
    status = exit_usage;
  } catch (const wrong_input& e) {
    std::fprintf(stderr, "%s: %s\n", p.name.c_str(), e.what());
    status = exit_not_for_this;
  } catch (const output_error& e) {
    std::fprintf(stderr, "%s: %s\n", p.name.c_str(), e.what());
    status = exit_output;
  } catch (const std::bad_alloc&) {  // a model too big for this machine: say so, do not abort
    report_out_of_memory(p.name.c_str(), p.stage);
    status = exit_input;
  } catch (const std::exception& e) {  // cellforge::error among them: its message says what to fix
    std::fprintf(stderr, "%s: %s\n", p.name.c_str(), e.what());
    status = exit_input;
  }
  p.stage.stop();
  std::fflush(stdout);
  return status;
}

/// What smooth_edges and thin_points start from: the loaded solid (refused with exit 4 when it
/// is a wireframe, a point set or an open mesh), its stem for output names.
struct solid_input {
  std::filesystem::path path;
  int volume = 0;
  solid s;
  std::string stem;  ///< the input's file name without extension, for output names

  /// Runs f(cells, volume) on a .3dcl input (cell ids in the result), else g(mesh); returns ms.
  template <class OnCells, class OnMesh>
  double run(OnCells&& f, OnMesh&& g) const {
    return time_ms([&] { s.cells ? f(*s.cells, s.volume) : g(s.mesh); });
  }

  /// Prints "<name>: <input>" and the solid's size.
  void print_solid(const char* name) const {
    std::printf("%s: %s%s\n", name, path.string().c_str(),
                s.cells ? (" volume " + std::to_string(volume)).c_str() : "");
    std::printf("  solid            %zu vertices, %zu edges, %zu faces (read in %.2f ms)\n",
                s.mesh.num_vertices(), s.mesh.num_edges(), s.mesh.num_faces(), s.load_ms);
  }
};

/// Loads a closed solid for `p` (a mesh, or volume `volume` of a .3dcl), refusing other kinds
/// of input with exit 4. Throws cellforge::error when the file cannot be read.
inline solid_input load_closed_solid(program& p, const std::filesystem::path& path, int volume) {
  expect_extension(p.name, path, {input_kind::mesh, input_kind::cells}, "a closed mesh or a .3dcl volume");
  solid_input x;
  x.path = path;
  x.volume = volume;
  x.stem = path.stem().string();
  if (lower_extension(path) == ".obj") {
    const obj_contents c = read_obj_contents(path);
    if (c.faces == 0 && c.vertices > 0) not_for_this(p.name, path, c.describe(), "a closed mesh", c.kind());
  }
  p.stage("reading " + file_and_size(path));
  x.s = load_solid(path, volume);
  if (x.s.mesh.num_faces() == 0)
    not_for_this(p.name, path,
                 "a mesh with no faces (" + std::to_string(x.s.mesh.num_vertices()) + " points)",
                 "a closed mesh", input_kind::point_set);
  if (!x.s.mesh.is_closed())
    not_for_this(p.name, path,
                 "an open mesh (" + std::to_string(x.s.mesh.num_boundary_edges()) + " boundary edges)",
                 "a closed mesh", input_kind::mesh);
  p.stage("working on a solid of " + std::to_string(x.s.mesh.num_faces()) + " faces");
  return x;
}

/// Refuses (exit 4) a mesh program's input that has no faces: a wireframe or a skeleton OBJ, or
/// a file of points only, saying what it is and which program takes it. O(file size) for an OBJ.
inline void refuse_faceless(const program& p, const std::filesystem::path& path, std::size_t points,
                            const std::string& wanted) {
  if (lower_extension(path) == ".obj") {
    const obj_contents c = read_obj_contents(path);
    if (c.kind() != input_kind::mesh && c.kind() != input_kind::unknown)
      not_for_this(p.name, path, c.describe(), wanted, c.kind());
  }
  not_for_this(p.name, path, "a file of " + std::to_string(points) + " points and no faces", wanted,
               input_kind::point_set);
}

}  // namespace example
