// The main job on data nobody here made (issue 38): the wireframes of CGAL's demo meshes
// (scripts/fetch-cgal-data.sh, Debian's libcgal-demo) and of the Stanford bunny
// (scripts/fetch-bunny.sh). Each mesh becomes a wireframe, its truth and its class
// (tests/real_mesh_support.hpp); the wireframe is converted and the answer judged:
//   * clean closed meshes, and open ones whose every rim is planar (the wireframe of the solid
//     with lids), must come out exactly (faces as vertex sets, volume count), or say why not
//     (an error, or walls the wireframe cannot decide reported as unforced);
//   * closed meshes whose polygons are planar only to a noise far below their bends ("closed,
//     nearly planar": decimal quads) are judged as solids too, their polygons the faces: the
//     pipeline's tolerance may read them so (docs/wireframe.md, "Tolerances"), or flag them;
//   * open, self-intersecting, non-manifold and degenerate meshes must be reported as not a
//     closed solid, with no volume that is not a clean closed component of the mesh;
//   * no answer may pass as good when it is not.
// The test prints the totals, a table per class, every miss by name with the reason, and the
// times of the big meshes. The directory is CELLFORGE_REAL_MESH_DIR (CMake, or the environment);
// without the data the test skips, except under CI, where missing data is a failure. Release
// runs every mesh; the sanitizer build (no NDEBUG) a sample of the small ones.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/io/mesh_io.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"
#include "real_mesh_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace real_meshes_tests {

#ifndef CELLFORGE_REAL_MESH_DIR
#define CELLFORGE_REAL_MESH_DIR ""  // e.g. compiled outside CMake (test-all's clang stage)
#endif

namespace {

namespace fs = std::filesystem;
using real_mesh::mesh_class;

#ifdef NDEBUG
constexpr bool full = true;
#else
constexpr bool full = false;  // the sanitizer build: meshes of at most sample_faces faces
#endif
constexpr std::size_t sample_faces = 400;

fs::path data_dir() {
  if (const char* env = std::getenv("CELLFORGE_REAL_MESH_DIR"); env != nullptr && *env != '\0') return env;
  return CELLFORGE_REAL_MESH_DIR;
}

bool mesh_file(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl";
}

/// Every mesh of <dir>/cgal and <dir>/bunny.off, sorted by name; empty (after failing under CI
/// or printing why it skips) when the data is not there.
std::vector<fs::path> mesh_files() {
  const fs::path dir = data_dir();
  std::vector<fs::path> files;
  std::error_code ec;
  if (!dir.empty() && fs::is_directory(dir / "cgal", ec))
    for (const auto& entry : fs::directory_iterator(dir / "cgal", ec))
      if (entry.is_regular_file() && mesh_file(entry.path())) files.push_back(entry.path());
  const bool cgal = !files.empty(), bunny = !dir.empty() && fs::exists(dir / "bunny.off", ec);
  if (bunny) files.push_back(dir / "bunny.off");
  if (cgal && bunny) {
    std::sort(files.begin(), files.end());
    return files;
  }
  const std::string what =
      "real meshes missing in '" + dir.string() + "' (" +
      (cgal ? ""
            : "no meshes in cgal/: run `bash scripts/fetch-cgal-data.sh build/data`, needs libcgal-demo") +
      (!cgal && !bunny ? "; " : "") +
      (bunny ? "" : "no bunny.off: run `bash scripts/fetch-bunny.sh build/data`, needs node and npm") + ")";
  if (std::getenv("CI") != nullptr) FAIL(what);
  MESSAGE("skipped: " << what);
  return {};
}

/// The answer says the input is not a closed solid. (When cells/certify.hpp lands: the
/// result's status is solid_status::not_a_solid.)
template <class Result>
bool says_not_a_solid(const Result& r) {
  return r.status != cellforge::solid_status::solid && r.status != cellforge::solid_status::ambiguous;
}

/// How one mesh came out.
enum class outcome { exact, flagged, not_a_solid, refused, wrong };

const char* outcome_name(outcome o) {
  switch (o) {
    case outcome::exact:
      return "exact";
    case outcome::flagged:
      return "flagged";
    case outcome::not_a_solid:
      return "not a solid";
    case outcome::refused:
      return "refused";
    case outcome::wrong:
      return "WRONG";
  }
  return "?";
}

struct run {
  std::string name;
  std::string kind = "unreadable";
  outcome result = outcome::wrong;
  std::string why;    ///< for every outcome but exact
  std::string notes;  ///< what the mesh is (fixture::notes)
  std::size_t edges = 0;
  double convert_ms = 0.0, fixture_ms = 0.0;
};

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

/// Converts one mesh and judges the answer.
run judge(const fs::path& path) {
  run out;
  out.name = path.filename().string();
  auto t = std::chrono::steady_clock::now();
  cellforge::polygon_soup<glm::dvec3> soup;
  try {
    soup = cellforge::io::read_soup<glm::dvec3>(path.string());
  } catch (const cellforge::error& e) {
    // A file the reader refuses with its line (prim.off: more faces than its header says).
    out.result = e.category() == cellforge::error_category::io ? outcome::refused : outcome::wrong;
    out.why = e.what();
    return out;
  }
  if (soup.num_faces() == 0) {
    out.kind = "no faces";
    out.why = "a point set (" + std::to_string(soup.num_points()) + " points, no faces): ";
  }
  const real_mesh::fixture fx = real_mesh::make_fixture(soup);
  out.fixture_ms = ms_since(t);
  if (soup.num_faces() > 0) out.kind = real_mesh::class_name(fx.kind);
  out.notes = fx.notes;
  out.edges = fx.wire.edges.size();
  const bool solid =
      fx.kind == mesh_class::closed || fx.kind == mesh_class::rimmed || fx.kind == mesh_class::nearly_planar;
  t = std::chrono::steady_clock::now();
  cellforge::wireframe_result<glm::dvec3> r;
  try {
    r = cellforge::wireframe_to_cells(fx.wire);
  } catch (const cellforge::error& e) {
    out.convert_ms = ms_since(t);
    // An error is never a wrong answer; for a solid it is a miss all the same.
    out.result = soup.num_faces() == 0 ? outcome::refused : solid ? outcome::flagged : outcome::not_a_solid;
    out.why += std::string("error: ") + e.what();
    return out;
  }
  out.convert_ms = ms_since(t);

  // The answer's faces as vertex sets of the wireframe (the caller's labels).
  std::vector<std::vector<std::uint32_t>> got;
  for (const auto& f : r.input.faces) {
    std::vector<std::uint32_t> s;
    for (const auto& loop : f.loops)
      for (const auto v : loop) s.push_back(r.input_vertex[v]);
    std::sort(s.begin(), s.end());
    got.push_back(std::move(s));
  }
  std::map<std::vector<std::uint32_t>, bool> truth;  // face → in a clean closed component
  for (std::size_t i = 0; i < fx.faces.size(); ++i) truth[fx.faces[i]] = fx.face_in_solid[i] != 0;
  // Volumes made of anything but the faces of clean closed components are invented.
  std::size_t invented = 0;
  for (const auto& v : r.input.volumes) {
    bool real = true;
    for (const auto& [f, sign] : v.faces) {
      const auto it = truth.find(got[f]);
      real = real && it != truth.end() && it->second;
    }
    invented += !real;
  }
  std::size_t missing = 0, extra = 0;
  const std::set<std::vector<std::uint32_t>> have(got.begin(), got.end());
  for (const auto& [f, in_solid] : truth) missing += !have.count(f);
  for (const auto& f : have) extra += !truth.count(f);
  const bool not_solid = says_not_a_solid(r);
  const std::string counts =
      std::to_string(r.input.faces.size()) + " faces (" + std::to_string(fx.faces.size()) +
      " expected: " + std::to_string(missing) + " missing, " + std::to_string(extra) + " extra), " +
      std::to_string(r.input.volumes.size()) + " volumes (" + std::to_string(fx.volumes) + " expected)";
  // Exact only when also certified solid; anything not certified solid is flagged, never wrong.
  if (solid) {
    if (missing == 0 && extra == 0 && r.input.volumes.size() == fx.volumes &&
        r.status == cellforge::solid_status::solid) {
      out.result = outcome::exact;
    } else if (r.status != cellforge::solid_status::solid) {
      out.result = outcome::flagged;
      out.why = counts + "; status " + cellforge::to_string(r.status) + ": " + r.status_reason;
    } else {
      out.result = outcome::wrong;
      out.why = counts + ", passed as good";
    }
  } else {
    if (soup.num_faces() == 0) {
      out.result = outcome::wrong;
      out.why += "converted without an error";
    } else if (!not_solid || invented > 0 || r.input.volumes.size() > fx.volumes) {
      out.result = outcome::wrong;
      out.why = counts + "; " + std::to_string(invented) + " volumes invented" +
                (not_solid ? "" : ", and not reported as not a closed solid");
    } else {
      out.result = outcome::not_a_solid;
      out.why = counts + "; reported as not a closed solid";
    }
  }
  return out;
}

}  // namespace

TEST_CASE("real meshes: CGAL's demo meshes and the bunny as wireframes") {
  const std::vector<fs::path> all = mesh_files();
  if (all.empty()) return;
  std::vector<fs::path> files;
  for (const auto& p : all)
    if (full || fs::file_size(p) <= 40 * sample_faces)  // the sanitizer build: small files (~40 bytes a face)
      files.push_back(p);
  std::vector<run> runs;
  const auto start = std::chrono::steady_clock::now();
  for (const auto& p : files) runs.push_back(judge(p));
  const double total_ms = ms_since(start);

  // Totals, a table per class, every miss by name, the big meshes' times.
  std::map<std::string, std::map<outcome, std::size_t>> table;
  std::map<outcome, std::size_t> totals;
  for (const auto& x : runs) ++table[x.kind][x.result], ++totals[x.result];
  const outcome order[] = {outcome::exact, outcome::not_a_solid, outcome::flagged, outcome::refused,
                           outcome::wrong};
  std::string report = "real meshes: " + std::to_string(runs.size()) + " of " + std::to_string(all.size()) +
                       " files in " + std::to_string(static_cast<long>(total_ms)) + " ms;";
  for (const auto o : order) report += " " + std::string(outcome_name(o)) + " " + std::to_string(totals[o]);
  report += "\n  class                  meshes";
  for (const auto o : order) report += std::string("  ") + outcome_name(o);
  for (const auto& [kind, counts] : table) {
    std::size_t n = 0;
    for (const auto& [o, c] : counts) n += c;
    char line[160];
    std::snprintf(line, sizeof line, "\n  %-22s %6zu", kind.c_str(), n);
    report += line;
    for (const auto o : order) {
      std::snprintf(line, sizeof line, "  %*zu", static_cast<int>(std::string(outcome_name(o)).size()),
                    counts.count(o) ? counts.at(o) : std::size_t{0});
      report += line;
    }
  }
  for (const auto& x : runs)
    if (x.result != outcome::exact)
      report += "\n  " + std::string(outcome_name(x.result)) + ": " + x.name + " (" + x.kind + "): " + x.why;
  const std::string nearly = real_mesh::class_name(mesh_class::nearly_planar);
  for (const auto& x : runs)
    if (x.kind == nearly)
      report += "\n  " + nearly +
                ", judged as a solid (polygons flatter than every bend by 100 times): " + x.name + ": " +
                x.notes + ": " + outcome_name(x.result);
  std::vector<const run*> big;
  for (const auto& x : runs) big.push_back(&x);
  std::sort(big.begin(), big.end(), [](const run* a, const run* b) { return a->edges > b->edges; });
  report += "\n  the biggest (wireframe edges: convert ms, fixture ms):";
  for (std::size_t i = 0; i < std::min<std::size_t>(8, big.size()); ++i) {
    char line[200];
    std::snprintf(line, sizeof line, "\n    %-28s %7zu: %7.0f, %5.0f", big[i]->name.c_str(), big[i]->edges,
                  big[i]->convert_ms, big[i]->fixture_ms);
    report += line;
  }
  MESSAGE(report);

  // Required: no answer passes as good when it is not; every open, self-intersecting,
  // non-manifold or degenerate mesh is reported as not a solid with no volume invented.
  CHECK(totals[outcome::wrong] == 0);
  for (const auto& x : runs) {
    INFO(x.name << " (" << x.kind << "): " << outcome_name(x.result) << ": " << x.why);
    CHECK(x.result != outcome::wrong);
    if (x.kind == "open" || x.kind == "self-intersecting" || x.kind == "non-manifold" ||
        x.kind == "degenerate")
      CHECK(x.result == outcome::not_a_solid);
  }
  // Clean closed meshes: exact, or flagged with the reason (printed above). The flagged ones
  // today are walls the wireframe cannot decide (reported unforced): see docs/wireframe.md.
  std::size_t solids = 0, exact = 0;  // of the clean ones (closed, planar rims)
  for (const auto& x : runs)
    if (x.kind == "closed" || x.kind == "open, planar rims") ++solids, exact += x.result == outcome::exact;
  if (full) {
    // 87 of the 88 are exact today and hole.off is flagged ambiguous (its faces and volume are
    // the truth, but other solids share its wireframe: undecided readings); oblong and
    // oblong-shuffled were flagged until a nested outline stopped counting as a seam wall. A
    // regression in exactness fails here.
    CHECK(exact + 1 >= solids);
  }
}

}  // namespace real_meshes_tests
