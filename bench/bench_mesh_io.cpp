// SPDX-License-Identifier: MIT
// STL reading and writing (io/stl.hpp) on the spheres of bench_mesh_creation (10k, 100k and
// 1M triangles): binary and ASCII STL read into a half-edge mesh (read + weld + make_mesh)
// and parsed alone (file to welded soup), and written from the mesh, next to OpenMesh
// (IO::read_mesh / write_mesh) and CGAL (IO::read_STL / write_STL) in the same run on the same
// files, and next to our own OFF reader on the same mesh. Medians of a fixed number of
// iterations (CPU ms); the tables print at the end.

#include "bench_support.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/io/off.hpp"
#include "cellforge/io/stl.hpp"

#ifdef CELLFORGE_HAVE_OPENMESH
#include <OpenMesh/Core/IO/MeshIO.hh>  // must come before the mesh kernel headers
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#endif
#ifdef CELLFORGE_HAVE_CGAL
#include <CGAL/IO/STL.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/STL.h>
#endif

namespace {

namespace cb = cellforge::bench;
namespace fs = std::filesystem;
using point = glm::dvec3;
using soup = cellforge::polygon_soup<point>;
using mesh = cellforge::surface_mesh<point>;

/// Triangle counts of the spheres (sphere_with_vertices(f / 2 + 2): closed, f triangles).
constexpr std::array<int, 3> sizes{10'000, 100'000, 1'000'000};
constexpr int vertices_for_faces(int faces) { return faces / 2 + 2; }
/// Iterations per benchmark: the tables give their median.
int iterations_for(int faces) { return faces >= 1'000'000 ? 5 : faces >= 100'000 ? 9 : 21; }

enum class file_kind { off, stl_binary, stl_ascii };
const char* extension(file_kind k) {
  return k == file_kind::off ? ".off" : k == file_kind::stl_binary ? ".binary.stl" : ".ascii.stl";
}

/// The spheres, their files (written once by our writers) and the written files' folder.
class inputs {
 public:
  const soup& sphere(int faces) {
    auto it = spheres_.find(faces);
    if (it == spheres_.end())
      it = spheres_.emplace(faces, cellforge::sphere_with_vertices<point>(vertices_for_faces(faces))).first;
    return it->second;
  }
  const mesh& ours(int faces) {
    auto it = meshes_.find(faces);
    if (it == meshes_.end()) it = meshes_.emplace(faces, cellforge::make_mesh(sphere(faces))).first;
    return it->second;
  }
  const fs::path& file(int faces, file_kind k) {
    const auto key = std::make_pair(faces, k);
    auto it = files_.find(key);
    if (it == files_.end()) {
      const fs::path path = dir_ / ("sphere_" + std::to_string(faces) + extension(k));
      if (k == file_kind::off)
        cellforge::io::write_off(path, sphere(faces));
      else
        cellforge::io::write_stl(path, sphere(faces), {.binary = k == file_kind::stl_binary});
      it = files_.emplace(key, path).first;
    }
    return it->second;
  }
  /// Where a writer benchmark puts its file.
  fs::path output(const std::string& name) const { return dir_ / name; }

 private:
  cb::scratch_dir dir_{"bench-mesh-io"};
  std::map<int, soup> spheres_;
  std::map<int, mesh> meshes_;
  std::map<std::pair<int, file_kind>, fs::path> files_;
};
inputs& data() {
  static inputs d;
  return d;
}

// ------------------------------------------------------------------------------ cellforge

mesh cf_read_stl(const fs::path& p) { return cellforge::make_mesh(cellforge::io::read_stl<point>(p).soup); }
cellforge::io::stl_data<point> cf_parse_stl(const fs::path& p, double weld_tolerance = 0) {
  return cellforge::io::read_stl<point>(p, {.weld_tolerance = weld_tolerance});
}
/// The welding tolerance of the tolerance column: far below the spheres' edge lengths
/// (about 0.005 on the 1M-triangle unit sphere), so it merges nothing the exact weld keeps.
constexpr double tolerance = 1e-6;
mesh cf_read_off(const fs::path& p) { return cellforge::make_mesh(cellforge::io::read_off<point>(p)); }
/// What a caller holding a surface_mesh does to write STL: to_soup, then write_stl.
std::uintmax_t cf_write_mesh(const fs::path& p, const mesh& m, bool binary) {
  cellforge::io::write_stl(p, cellforge::to_soup(m), {.binary = binary});
  return fs::file_size(p);
}
std::uintmax_t cf_write_soup(const fs::path& p, const soup& s, bool binary) {
  cellforge::io::write_stl(p, s, {.binary = binary});
  return fs::file_size(p);
}
std::size_t faces_of(const mesh& m) { return m.is_closed() ? m.num_faces() : 0; }
/// The faces, or 0 unless welding left the sphere's vertex count (f / 2 + 2 for f triangles).
std::size_t faces_of(const cellforge::io::stl_data<point>& d) {
  const std::size_t f = d.soup.num_faces();
  return d.soup.num_points() == f / 2 + 2 ? f : 0;
}

// ------------------------------------------------------------------------------ OpenMesh

#ifdef CELLFORGE_HAVE_OPENMESH
// Double points, as ours; DefaultTraits would store floats. Held by pointer: OpenMesh meshes
// copy (not move) when returned through a wrapper.
using om_mesh = OpenMesh::TriMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;
std::unique_ptr<om_mesh> om_read(const fs::path& p) {
  auto m = std::make_unique<om_mesh>();
  if (!OpenMesh::IO::read_mesh(*m, p.string())) m->clean();
  return m;
}
std::size_t faces_of(const std::unique_ptr<om_mesh>& m) { return m->n_faces(); }
/// OpenMesh's mesh of the sphere, read once from our OFF file (the same double points).
const om_mesh& om_sphere(int faces) {
  static std::map<int, std::unique_ptr<om_mesh>> cache;
  auto it = cache.find(faces);
  if (it == cache.end()) it = cache.emplace(faces, om_read(data().file(faces, file_kind::off))).first;
  return *it->second;
}
/// Binary: IO::Options::Binary; ASCII: the default options with 17 significant digits.
std::uintmax_t om_write(const fs::path& p, const om_mesh& m, bool binary) {
  const bool ok = binary ? OpenMesh::IO::write_mesh(m, p.string(), OpenMesh::IO::Options::Binary)
                         : OpenMesh::IO::write_mesh(m, p.string(), OpenMesh::IO::Options::Default, 17);
  return ok ? fs::file_size(p) : 0;
}
#endif

// ------------------------------------------------------------------------------ CGAL

#ifdef CELLFORGE_HAVE_CGAL
using cgal_point = CGAL::Simple_cartesian<double>::Point_3;
using cgal_mesh = CGAL::Surface_mesh<cgal_point>;
/// CGAL's STL soup: points merged where equal, triangles as index triples.
struct cgal_soup {
  std::vector<cgal_point> points;
  std::vector<std::array<std::size_t, 3>> triangles;
};
/// The one call that gives a mesh: IO::read_STL into a FaceGraph reads the soup, checks that it
/// is a polygon mesh and runs polygon_soup_to_polygon_mesh. use_binary_mode says the encoding
/// (with true, an ASCII file is read only after the binary attempt fails).
cgal_mesh cgal_read(const fs::path& p, bool binary) {
  cgal_mesh m;
  if (!CGAL::IO::read_STL(p.string(), m, CGAL::parameters::use_binary_mode(binary))) m.clear();
  return m;
}
cgal_soup cgal_parse(const fs::path& p, bool binary) {
  cgal_soup s;
  if (!CGAL::IO::read_STL(p.string(), s.points, s.triangles, CGAL::parameters::use_binary_mode(binary)))
    s.triangles.clear();
  return s;
}
std::size_t faces_of(const cgal_mesh& m) { return m.number_of_faces(); }
std::size_t faces_of(const cgal_soup& s) { return s.triangles.size(); }
const cgal_mesh& cgal_sphere(int faces) {
  static std::map<int, cgal_mesh> cache;
  auto it = cache.find(faces);
  if (it == cache.end()) {
    cgal_mesh m;
    if (!CGAL::IO::read_OFF(data().file(faces, file_kind::off).string(), m)) m.clear();
    it = cache.emplace(faces, std::move(m)).first;
  }
  return it->second;
}
/// ASCII with 17 significant digits (stream_precision), as OpenMesh's and ours round-trip.
std::uintmax_t cgal_write(const fs::path& p, const cgal_mesh& m, bool binary) {
  const bool ok =
      CGAL::IO::write_STL(p.string(), m, CGAL::parameters::use_binary_mode(binary).stream_precision(17));
  return ok ? fs::file_size(p) : 0;
}
#endif

// ------------------------------------------------------------------------------ registration

std::string name(const std::string& what, const char* lib, int faces) {
  return what + "/" + lib + "/" + std::to_string(faces);
}

/// Registers `name`: the median of `make()` over the size's iterations; `check(made)` on the
/// first result. An exception skips the benchmark with its message.
template <class Make, class Check>
void add(const std::string& bench_name, int faces, Make make, Check check) {
  benchmark::RegisterBenchmark(bench_name.c_str(),
                               [make, check](benchmark::State& state) {
                                 try {
                                   cb::median_loop(state, make,
                                                   [&](const auto& made) { check(state, made); });
                                 } catch (const std::exception& e) {
                                   state.SkipWithError(e.what());
                                 }
                               })
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(iterations_for(faces));
}

/// A reader's benchmark: the result must hold the sphere's triangles (a closed mesh for ours).
template <class Make>
void add_read(const std::string& what, const char* lib, int faces, Make make) {
  add(name(what, lib, faces), faces, make, [faces](benchmark::State& state, const auto& made) {
    if (faces_of(made) != static_cast<std::size_t>(faces)) state.SkipWithError("wrong face count");
  });
}

/// A writer's benchmark: make() returns the bytes written; the file must read back (with our
/// reader) as the sphere's triangles, and its size is kept in the counter "bytes".
template <class Make>
void add_write(const std::string& what, const char* lib, int faces, const std::string& file, Make make) {
  add(name(what, lib, faces), faces, make, [faces, file](benchmark::State& state, std::uintmax_t bytes) {
    state.counters["bytes"] = static_cast<double>(bytes);
    const auto back = cellforge::io::read_stl<point>(data().output(file));
    if (back.soup.num_faces() != static_cast<std::size_t>(faces))
      state.SkipWithError("the written file does not read back as the sphere");
  });
}

void register_all() {
#ifdef CELLFORGE_HAVE_OPENMESH
  omlog().disable();  // its STL writer logs every file written
#endif
  for (const int f : sizes) {
    for (const bool binary : {true, false}) {
      const file_kind k = binary ? file_kind::stl_binary : file_kind::stl_ascii;
      const std::string enc = binary ? "binary" : "ascii";
      auto in = [f, k] { return data().file(f, k); };
      add_read("read_" + enc, "cellforge", f, [in] { return cf_read_stl(in()); });
      add_read("parse_" + enc, "cellforge", f, [in] { return cf_parse_stl(in()); });
      if (binary)
        add_read("parse_binary", "cellforge_tolerance", f, [in] { return cf_parse_stl(in(), tolerance); });
#ifdef CELLFORGE_HAVE_OPENMESH
      add_read("read_" + enc, "openmesh", f, [in] { return om_read(in()); });
#endif
#ifdef CELLFORGE_HAVE_CGAL
      add_read("read_" + enc, "cgal", f, [in, binary] { return cgal_read(in(), binary); });
      add_read("parse_" + enc, "cgal", f, [in, binary] { return cgal_parse(in(), binary); });
#endif
    }
    add_read("read_off", "cellforge", f, [f] { return cf_read_off(data().file(f, file_kind::off)); });

    for (const bool binary : {true, false}) {
      const std::string what = binary ? "write_binary" : "write_ascii";
      const auto file = [&](const char* lib) { return what + "_" + lib + "_" + std::to_string(f) + ".stl"; };
      const std::string ours = file("cellforge"), soup_file = file("cellforge_soup");
      add_write(what, "cellforge", f, ours,
                [f, binary, ours] { return cf_write_mesh(data().output(ours), data().ours(f), binary); });
      add_write(what, "cellforge_soup", f, soup_file, [f, binary, soup_file] {
        return cf_write_soup(data().output(soup_file), data().sphere(f), binary);
      });
#ifdef CELLFORGE_HAVE_OPENMESH
      const std::string om = file("openmesh");
      add_write(what, "openmesh", f, om,
                [f, binary, om] { return om_write(data().output(om), om_sphere(f), binary); });
#endif
#ifdef CELLFORGE_HAVE_CGAL
      const std::string cg = file("cgal");
      add_write(what, "cgal", f, cg,
                [f, binary, cg] { return cgal_write(data().output(cg), cgal_sphere(f), binary); });
#endif
    }
  }
}

// ------------------------------------------------------------------------------ tables

void print_tables(const cb::collecting_reporter& rep, std::ostream& os) {
  const auto med = [&](const std::string& what, const char* lib, int f) {
    return rep.counter_ms(name(what, lib, f), "median_cpu_us");
  };
  const auto mb = [](std::optional<double> bytes) {
    return cb::fixed(bytes ? std::optional<double>(*bytes / 1e6) : std::nullopt, 1);
  };
  const auto file_bytes = [](int f, file_kind k) -> std::optional<double> {
    std::error_code ec;
    const auto size = fs::file_size(data().file(f, k), ec);
    return ec ? std::nullopt : std::optional<double>(static_cast<double>(size));
  };
  os << "\n## STL reading and writing (io/stl.hpp)\n\nPoints are double precision in every structure. "
        "OpenMesh: "
     << (cb::have_openmesh ? "TriMesh_ArrayKernelT<DefaultTraitsDouble>" : "not found, skipped") << ". CGAL: "
     << (cb::have_cgal ? "Surface_mesh<Simple_cartesian<double>::Point_3>" : "not found, skipped")
     << ".\nTimes: median CPU ms of the iterations (21 at 10k triangles, 9 at 100k, 5 at 1M); freeing the "
        "result is not timed. Load average now: "
     << cb::load_average() << ".\n";

  for (const bool binary : {true, false}) {
    const std::string enc = binary ? "binary" : "ascii";
    const file_kind k = binary ? file_kind::stl_binary : file_kind::stl_ascii;
    cb::table t(std::string("Read ") + (binary ? "binary" : "ASCII") + " STL into a half-edge mesh",
                {"triangles", "file MB", "ours ms", "of which parse ms", "OpenMesh ms", "CGAL ms",
                 "OpenMesh / ours", "CGAL / ours", "our OFF read ms"});
    bool any = false;
    for (const int f : sizes) {
      if (!rep.find(name("read_" + enc, "cellforge", f))) continue;
      any = true;
      const auto ours = med("read_" + enc, "cellforge", f), om = med("read_" + enc, "openmesh", f),
                 cgal = med("read_" + enc, "cgal", f);
      t.add_row({cb::count(static_cast<std::size_t>(f)), mb(file_bytes(f, k)), cb::ms(ours),
                 cb::ms(med("parse_" + enc, "cellforge", f)), cb::ms(om), cb::ms(cgal), cb::ratio(om, ours),
                 cb::ratio(cgal, ours), cb::ms(med("read_off", "cellforge", f))});
    }
    t.add_note(
        "Ours: io::read_stl (exact welding, the default) + make_mesh; 'of which parse': read_stl alone. "
        "OpenMesh: IO::read_mesh (.stl, encoding detected). CGAL: IO::read_STL(path, Surface_mesh, "
        "use_binary_mode(" +
        std::string(binary ? "true" : "false") +
        ")), which reads a soup and runs polygon_soup_to_polygon_mesh. Our OFF read: io::read_off + "
        "make_mesh of the same sphere (file written by io::write_off).");
    if (any) t.print(os);
  }

  cb::table parse("Parse alone: an STL file to a welded triangle soup",
                  {"triangles", "ours binary ms", "ours binary, tolerance ms", "CGAL binary ms",
                   "CGAL / ours", "ours ASCII ms", "CGAL ASCII ms", "CGAL / ours"});
  bool any_parse = false;
  for (const int f : sizes) {
    if (!rep.find(name("parse_binary", "cellforge", f))) continue;
    any_parse = true;
    const auto ob = med("parse_binary", "cellforge", f), cbin = med("parse_binary", "cgal", f),
               oa = med("parse_ascii", "cellforge", f), ca = med("parse_ascii", "cgal", f);
    parse.add_row({cb::count(static_cast<std::size_t>(f)), cb::ms(ob),
                   cb::ms(med("parse_binary", "cellforge_tolerance", f)), cb::ms(cbin), cb::ratio(cbin, ob),
                   cb::ms(oa), cb::ms(ca), cb::ratio(ca, oa)});
  }
  parse.add_note(
      "Ours: io::read_stl<glm::dvec3> (stl_data: soup, solids, counts). CGAL: IO::read_STL(path, points, "
      "triangles) into std::vector<Point_3> and std::vector<std::array<std::size_t, 3>> (equal points "
      "merged through a std::map). OpenMesh has no soup reader. 'tolerance': "
      "stl_read_options::weld_tolerance = 1e-6 "
      "(grid welding; far below the edge lengths, about 0.005 at 1M triangles: both welds give the "
      "sphere's vertex count).");
  if (any_parse) parse.print(os);

  for (const bool binary : {true, false}) {
    const std::string what = binary ? "write_binary" : "write_ascii";
    cb::table t(std::string("Write ") + (binary ? "binary" : "ASCII") + " STL from the mesh",
                {"triangles", "ours ms", "of which write_stl ms", "OpenMesh ms", "CGAL ms", "OpenMesh / ours",
                 "CGAL / ours", "ours MB", "OpenMesh MB", "CGAL MB"});
    bool any = false;
    const auto bytes = [&](const char* lib, int f) -> std::optional<double> {
      const cb::run_result* r = rep.find(name(what, lib, f));
      if (!r || !r->error.empty()) return std::nullopt;
      const auto it = r->counters.find("bytes");
      return it == r->counters.end() ? std::nullopt : std::optional<double>(it->second);
    };
    for (const int f : sizes) {
      if (!rep.find(name(what, "cellforge", f))) continue;
      any = true;
      const auto ours = med(what, "cellforge", f), om = med(what, "openmesh", f), cgal = med(what, "cgal", f);
      t.add_row({cb::count(static_cast<std::size_t>(f)), cb::ms(ours), cb::ms(med(what, "cellforge_soup", f)),
                 cb::ms(om), cb::ms(cgal), cb::ratio(om, ours), cb::ratio(cgal, ours),
                 mb(bytes("cellforge", f)), mb(bytes("openmesh", f)), mb(bytes("cgal", f))});
    }
    t.add_note(binary
                   ? "Ours: to_soup + io::write_stl({.binary = true}); 'of which write_stl': from the soup. "
                     "OpenMesh: IO::write_mesh with IO::Options::Binary. CGAL: IO::write_STL with "
                     "use_binary_mode(true). Every file is read back (untimed) as the sphere's triangles."
                   : "Ours: to_soup + io::write_stl({.binary = false}) (shortest round-trip doubles); "
                     "'of which write_stl': from the soup. OpenMesh: IO::write_mesh with default options "
                     "and precision 17. CGAL: IO::write_STL with use_binary_mode(false), "
                     "stream_precision(17). Every file is read back (untimed) as the sphere's triangles.");
    if (any) t.print(os);
  }
}

}  // namespace

int main(int argc, char** argv) { return cb::table_main(argc, argv, register_all, print_tables); }
