// SPDX-License-Identifier: MIT
// io/step.hpp checked by another reader: OpenCASCADE (a test dependency only, built when CMake
// finds it). Every cell complex of the wireframe sweep (in Release all 1076; CELLFORGE_SWEEP=sample: its
// sample) is written as STEP and read back with STEPControl_Reader with OCCT's shape healing switched off, so
// that what is judged is the file as written: BRepCheck_Analyzer valid, one solid per volume, each solid's
// volume equal to ours to 1e-9 relative, and the face count. So is every rounded solid of the rounds sweep
// (sketch/rounds.hpp, rounded_brep): its blends cylinders.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "../rounded_fixtures.hpp"
#include "../wireframe_sweep.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/cells/validate.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/io/step.hpp"
#include "cellforge/samples/round_drawings.hpp"
#include "cellforge/samples/skeletons.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/sketch/rounds.hpp"
#include "cellforge/tubes/tube_mesh.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

// OpenCASCADE after cellforge: its Handle(...) macro would rewrite cellforge's template
// parameters of that name.
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <GeomAbs_SurfaceType.hxx>
#include <Message_ProgressRange.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeFix_Edge.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shape.hxx>
#include <XSAlgo.hxx>
#include <XSAlgo_AlgoContainer.hxx>
#include <gp_Trsf.hxx>
#include <gp_Vec.hxx>

namespace step_occt_tests {

namespace {

using cellforge::cell_complex;
using cellforge::cell_face;
using cellforge::cell_volume;

// OCCT's reader repairs what it reads (face orientation among it) by default; this returns
// the translated shape untouched, so that a wrongly oriented face shows as a wrong volume.
class no_healing : public XSAlgo_AlgoContainer {
 public:
  TopoDS_Shape ProcessShape(const TopoDS_Shape& shape, const Standard_Real, const Standard_Real,
                            const Standard_CString, const Standard_CString, Handle(Standard_Transient) &,
                            const Message_ProgressRange&, const Standard_Boolean) const override {
    return shape;
  }
};

// The same, except that an edge with no curve on a face's surface gets one computed (a STEP file
// need not carry pcurves; planes need none, cylinders do): nothing is turned round or rejoined,
// so a wrongly oriented face still shows. O(edges).
class pcurves_only : public XSAlgo_AlgoContainer {
 public:
  TopoDS_Shape ProcessShape(const TopoDS_Shape& shape, const Standard_Real precision, const Standard_Real,
                            const Standard_CString, const Standard_CString, Handle(Standard_Transient) &,
                            const Message_ProgressRange&, const Standard_Boolean) const override {
    for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next())
      for (TopExp_Explorer e(f.Current(), TopAbs_EDGE); e.More(); e.Next()) {
        ShapeFix_Edge fix;
        if (fix.FixAddPCurve(TopoDS::Edge(e.Current()), TopoDS::Face(f.Current()), Standard_False, precision))
          fix.FixSameParameter(TopoDS::Edge(e.Current()));
      }
    return shape;
  }
};

struct occt_view {
  bool read = false, valid = false;
  std::vector<double> solid_volumes, volumes_about_far;  ///< about the origin and a far point
  std::vector<int> solid_shells;
  std::size_t faces = 0, free_shells = 0, cylinders = 0;
};

// Reads STEP text with OCCT, healing off (pcurves: only missing pcurves added); volumes as read
// and moved by `far` (a face through the origin adds nothing to the divergence sum, so one place
// could miss a face turned the wrong way). O(file).
occt_view read_with_occt(const std::string& text, const glm::dvec3& far = {1e3, 2e3, 3e3},
                         bool pcurves = false) {
  occt_view v;
  std::istringstream is(text);
  STEPControl_Reader reader;
  // After the reader: its first construction installs OCCT's default container (XSAlgo::Init).
  if (pcurves)
    XSAlgo::SetAlgoContainer(new pcurves_only);
  else
    XSAlgo::SetAlgoContainer(new no_healing);
  if (reader.ReadStream("cellforge.step", is) != IFSelect_RetDone) return v;
  v.read = true;
  reader.TransferRoots();
  const TopoDS_Shape shape = reader.OneShape();
  v.valid = !shape.IsNull() && BRepCheck_Analyzer(shape).IsValid();
  for (TopExp_Explorer ex(shape, TopAbs_SOLID); ex.More(); ex.Next()) {
    GProp_GProps g;
    BRepGProp::VolumeProperties(ex.Current(), g);
    v.solid_volumes.push_back(g.Mass());
    // VolumeProperties integrates about the shape's own origin: a moved copy moves the faces instead.
    gp_Trsf shift;
    shift.SetTranslation(gp_Vec(far.x, far.y, far.z));
    GProp_GProps about;
    BRepGProp::VolumeProperties(BRepBuilderAPI_Transform(ex.Current(), shift, Standard_True).Shape(), about);
    v.volumes_about_far.push_back(about.Mass());
    int shells = 0;
    for (TopExp_Explorer sh(ex.Current(), TopAbs_SHELL); sh.More(); sh.Next()) ++shells;
    v.solid_shells.push_back(shells);
  }
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    ++v.faces;
    v.cylinders += BRepAdaptor_Surface(TopoDS::Face(ex.Current())).GetType() == GeomAbs_Cylinder;
  }
  for (TopExp_Explorer ex(shape, TopAbs_SHELL, TopAbs_SOLID); ex.More(); ex.Next()) ++v.free_shells;
  return v;
}

// Empty when OCCT reads cc's STEP as we wrote it, else why. O(size of cc).
template <class P>
std::string check_step(const cell_complex<P>& cc, std::size_t cavities = 0) {
  std::ostringstream os;
  const cellforge::io::step_result r = cellforge::io::write_step(os, cc);
  std::size_t uses = 0, loose = 0;
  for (cell_volume c : cc.volumes()) uses += cc.volume_faces(c).size();
  for (cell_face f : cc.faces()) loose += cc.face_volumes(f).empty();
  if (r.faces != uses + loose || r.solids != cc.num_volumes() || r.voids != cavities)
    return "write_step counted " + std::to_string(r.solids) + " solids, " + std::to_string(r.voids) +
           " voids, " + std::to_string(r.faces) + " faces; the complex has " +
           std::to_string(cc.num_volumes()) + ", " + std::to_string(cavities) + ", " +
           std::to_string(uses + loose);
  if (!r.diagnostics.empty()) return "write_step: " + r.diagnostics.front();
  cellforge::bounding_box box;
  for (const auto& p : cc.points()) box.add(cellforge::to_dvec3(p));
  const glm::dvec3 far = box.max + glm::dvec3(0.37, 0.61, 0.83) * (box.diagonal() + 1.0);
  const occt_view v = read_with_occt(os.str(), far);
  if (!v.read) return "OCCT cannot read it";
  if (!v.valid) return "BRepCheck_Analyzer: not valid";
  if (v.solid_volumes.size() != cc.num_volumes())
    return std::to_string(v.solid_volumes.size()) + " solids for " + std::to_string(cc.num_volumes()) +
           " volumes";
  for (cell_volume c : cc.volumes()) {
    const double ours = cellforge::signed_volume(cc, c);
    for (const double theirs : {v.solid_volumes[c.idx()], v.volumes_about_far[c.idx()]})
      if (!(std::abs(theirs - ours) <= 1e-9 * std::abs(ours)))
        return "volume " + std::to_string(c.idx()) + ": OCCT " + std::to_string(theirs) + ", ours " +
               std::to_string(ours);
  }
  std::size_t shells = 0;
  for (int s : v.solid_shells) shells += static_cast<std::size_t>(s);
  if (shells != cc.num_volumes() + cavities)
    return std::to_string(shells) + " shells in the solids for " + std::to_string(cc.num_volumes()) +
           " volumes and " + std::to_string(cavities) + " cavities";
  if (v.faces != uses + loose)
    return "OCCT has " + std::to_string(v.faces) + " faces, we wrote " + std::to_string(uses + loose);
  if (v.free_shells != r.open_shells)
    return "OCCT has " + std::to_string(v.free_shells) + " open shells, we wrote " +
           std::to_string(r.open_shells);
  return {};
}

// The whole sweep by default, as the file's head says (OCCT's reading and checking costs about
// 65 ms of CPU per model, 70 CPU-seconds for the 1076 models, most of it the big grids: the
// longest case of CI's Release stage, which starts it first); CELLFORGE_SWEEP=sample runs the
// sweep's sample (1 s). O(1).
wireframe_sweep::sweep_size chosen_size() {
  const char* env = std::getenv("CELLFORGE_SWEEP");
  return env && std::string(env) == "sample" ? wireframe_sweep::sweep_size::sample
                                             : wireframe_sweep::sweep_size::full;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The six faces of the box [lo, hi], counter-clockwise about their outward normals, appended
// to `in` (points, edges, faces); returns the face indices. O(1).
std::vector<std::uint32_t> add_box(cellforge::cell_complex_input<glm::dvec3>& in, glm::dvec3 lo,
                                   glm::dvec3 hi) {
  const auto base = static_cast<std::uint32_t>(in.points.size());
  for (int k = 0; k < 8; ++k)
    in.points.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
  const auto at = [&](int a, int side, int u, int w) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    return base + static_cast<std::uint32_t>((side << a) | (u << b) | (w << c));
  };
  std::vector<std::uint32_t> out;
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      std::vector<std::uint32_t> loop{at(a, side, 0, 0), at(a, side, 1, 0), at(a, side, 1, 1),
                                      at(a, side, 0, 1)};
      if (side == 0) std::reverse(loop.begin(), loop.end());  // b × c = a: reversed faces -a
      out.push_back(static_cast<std::uint32_t>(in.faces.size()));
      in.faces.push_back({{loop}});
    }
  for (int k = 0; k < 8; ++k)
    for (int a = 0; a < 3; ++a)
      if (!(k & (1 << a)))
        in.edges.push_back(
            {base + static_cast<std::uint32_t>(k), base + static_cast<std::uint32_t>(k | (1 << a))});
  return out;
}

}  // namespace

TEST_CASE("step: every cell complex of the wireframe sweep reads back in OpenCASCADE as written") {
  const auto size = chosen_size();
  const auto t0 = std::chrono::steady_clock::now();
  const wireframe_sweep::sweep_set set = wireframe_sweep::make_sweep(size);
  std::size_t complexes = 0, passed = 0, pipeline_errors = 0, solids = 0, faces = 0;
  std::vector<std::string> misses;
#ifdef NDEBUG
  const std::size_t stride = 1;
#else
  const std::size_t stride =
      size == wireframe_sweep::sweep_size::full ? 1 : 3;  // the sanitizers: every third
#endif
  for (std::size_t i = 0; i < set.models.size(); i += stride) {
    const auto& s = set.models[i];
    cellforge::wireframe_result<glm::dvec3> r;
    try {
      r = cellforge::wireframe_to_cells(s.model.wire);
    } catch (const cellforge::error&) {
      ++pipeline_errors;  // the pipeline's own misses are test_wireframe_sweep's business
      continue;
    }
    ++complexes;
    std::string why;
    try {
      why = check_step(r.cells);
    } catch (const std::exception& e) {
      why = std::string("error: ") + e.what();
    }
    if (why.empty()) {
      ++passed;
      solids += r.cells.num_volumes();
      for (cell_volume c : r.cells.volumes()) faces += r.cells.volume_faces(c).size();
    } else {
      misses.push_back(s.model.name + ": " + why);
    }
  }
  std::printf(
      "\nstep through OpenCASCADE (%s sweep%s): %zu of %zu complexes read back exactly (%zu solids, %zu "
      "faces); %zu models the pipeline refused; %.0f ms\n",
      size == wireframe_sweep::sweep_size::full ? "full" : "sample", stride > 1 ? ", every third model" : "",
      passed, complexes, solids, faces, pipeline_errors, ms_since(t0));
  for (const std::string& m : misses) std::printf("  miss: %s\n", m.c_str());
  CHECK(complexes > 0);
  CHECK(misses.empty());
}

// Empty when OCCT reads the rounded solid of r as we wrote it: valid, one solid of one shell,
// its volume ours (rounded_brep's: the skeleton's less each round's cross-section times its
// length, plus each fillet's) to 1e-9 relative, the planar and cylindrical faces written; else
// why. O(size of r).
template <class R>
std::string check_rounded_step(const R& r, std::size_t& faces_out, double& worst) {
  const cellforge::rounded_brep_result b = cellforge::rounded_brep(r);
  if (!b.ok) return "rounded_brep: " + (b.diagnostics.empty() ? std::string("not ok") : b.diagnostics.back());
  std::ostringstream os;
  const cellforge::io::step_result w = cellforge::io::write_step(os, b.solid);
  if (!w.diagnostics.empty()) return "write_step: " + w.diagnostics.front();
  if (w.faces != b.planar_faces + b.blend_faces || w.cylinders != b.blend_faces ||
      w.conics != 2 * b.blend_faces)
    return "write_step wrote " + std::to_string(w.faces) + " faces, " + std::to_string(w.cylinders) +
           " cylinders, " + std::to_string(w.conics) + " conics";
  cellforge::bounding_box box;
  for (const auto& p : b.solid.points) box.add(p);
  const glm::dvec3 far = box.max + glm::dvec3(0.37, 0.61, 0.83) * (box.diagonal() + 1.0);
  const occt_view v = read_with_occt(os.str(), far, true);
  if (!v.read) return "OCCT cannot read it";
  if (!v.valid) return "BRepCheck_Analyzer: not valid";
  if (v.solid_volumes.size() != 1 || v.solid_shells[0] != 1)
    return std::to_string(v.solid_volumes.size()) + " solids for one";
  for (const double theirs : {v.solid_volumes[0], v.volumes_about_far[0]})
    worst = std::max(worst, std::abs(theirs - b.volume) / b.volume);
  for (const double theirs : {v.solid_volumes[0], v.volumes_about_far[0]})
    if (!(std::abs(theirs - b.volume) <= 1e-9 * b.volume))
      return "volume: OCCT " + std::to_string(theirs) + ", ours " + std::to_string(b.volume) + " (relative " +
             std::to_string(std::abs(theirs - b.volume) / b.volume) + ")";
  if (v.faces != w.faces || v.cylinders != b.blend_faces)
    return "OCCT has " + std::to_string(v.faces) + " faces, " + std::to_string(v.cylinders) +
           " of them cylinders; we wrote " + std::to_string(w.faces) + ", " + std::to_string(b.blend_faces);
  faces_out = w.faces;
  return {};
}

TEST_CASE(
    "step: every rounded solid of the rounds sweep reads back in OpenCASCADE with its blends as cylinders") {
  const auto t0 = std::chrono::steady_clock::now();
  const auto drawings = cellforge::samples::round_drawing_sweep({});  // test_rounds' 240 drawings
  std::size_t passed = 0, blends = 0, fillets = 0, faces = 0;
  double worst = 0;
  std::vector<std::string> misses;
  for (const auto& s : drawings) {
    std::string why;
    std::size_t written = 0;
    try {
      const auto r = cellforge::reconstruct_rounds(s.drawing);
      why = check_rounded_step(r, written, worst);
      if (why.empty())
        for (const auto& e : r.rounds) ++blends, fillets += !e.convex;
    } catch (const std::exception& e) {
      why = std::string("error: ") + e.what();
    }
    if (why.empty())
      ++passed, faces += written;
    else
      misses.push_back(s.name + ": " + why);
  }
  std::printf(
      "\nrounded solids through OpenCASCADE: %zu of %zu valid, one solid each, volume and faces as written "
      "(worst relative volume difference %.1e; %zu faces, %zu blends of which %zu fillets); %.0f ms\n",
      passed, drawings.size(), worst, faces, blends, fillets, ms_since(t0));
  for (const std::string& m : misses) std::printf("  miss: %s\n", m.c_str());
  CHECK(drawings.size() == 240);
  CHECK(misses.empty());
}

TEST_CASE("step: a rounded box, square and with a tilted end (an ellipse), has its volume in OpenCASCADE") {
  for (const double tilt : {0.0, 0.3, -0.5}) {
    CAPTURE(tilt);
    std::ostringstream os;
    const auto w = cellforge::io::write_step(os, rounded_fixtures::rounded_box(0.25, true, tilt));
    CHECK(w.diagnostics.empty());
    const occt_view v = read_with_occt(os.str(), {1e3, 2e3, 3e3}, true);
    CHECK(v.valid);
    REQUIRE(v.solid_volumes.size() == 1);
    const double exact = rounded_fixtures::rounded_box_volume(0.25, tilt);
    for (const double theirs : {v.solid_volumes[0], v.volumes_about_far[0]})
      CHECK(theirs == doctest::Approx(exact).epsilon(1e-9));
    CHECK(v.faces == 7);
    CHECK(v.cylinders == 1);
  }
}

TEST_CASE("step: the OpenCASCADE check catches a rounded solid's blend turned inside out") {
  cellforge::samples::round_sweep_options o;
  o.drawings = 2;  // block #0 (rounds only) and L #1 (a round and a fillet)
  for (const auto& s : cellforge::samples::round_drawing_sweep(o)) {
    CAPTURE(s.name);
    const auto b = cellforge::rounded_brep(cellforge::reconstruct_rounds(s.drawing));
    REQUIRE(b.ok);
    std::ostringstream os;
    cellforge::io::write_step(os, b.solid);
    const std::string good = os.str();
    const occt_view v0 = read_with_occt(good, {1e3, 2e3, 3e3}, true);
    REQUIRE(v0.valid);
    REQUIRE(v0.solid_volumes.size() == 1);
    CHECK(v0.solid_volumes[0] == doctest::Approx(b.volume).epsilon(1e-9));
    // The first cylinder face turned: its same_sense flipped (its material on the wrong side of
    // its loop), then its bound's orientation too (the face facing into the solid).
    std::string bad = good;
    const std::size_t cyl = bad.find("=CYLINDRICAL_SURFACE(");
    REQUIRE(cyl != std::string::npos);
    const std::size_t hash = bad.rfind('#', cyl);
    const std::string id = bad.substr(hash + 1, cyl - hash - 1);
    const std::size_t face = bad.find("),#" + id + ",.");
    REQUIRE(face != std::string::npos);
    const auto flip = [&](std::size_t at) {
      REQUIRE((bad[at] == 'T' || bad[at] == 'F'));
      bad[at] = bad[at] == 'T' ? 'F' : 'T';
    };
    flip(face + 5 + id.size());
    const std::size_t open = bad.rfind("(#", face);
    const std::string bound = bad.substr(open + 2, face - open - 2);
    const std::size_t bound_line = bad.find("\n#" + bound + "=FACE_OUTER_BOUND(");
    REQUIRE(bound_line != std::string::npos);
    for (const bool with_bound : {false, true}) {
      CAPTURE(with_bound);
      if (with_bound) flip(bad.find(".);", bound_line) - 1);
      const occt_view v = read_with_occt(bad, {1e3, 2e3, 3e3}, true);
      REQUIRE(v.read);
      const bool caught = !v.valid || v.solid_volumes.size() != 1 ||
                          std::abs(v.solid_volumes[0] - b.volume) > 1e-9 * b.volume ||
                          std::abs(v.volumes_about_far[0] - b.volume) > 1e-9 * b.volume;
      CHECK(caught);
    }
  }
}

TEST_CASE("step: a cavity (BREP_WITH_VOIDS), a nested solid and an open face") {
  cellforge::cell_complex_input<glm::dvec3> in;
  const auto outer = add_box(in, {0, 0, 0}, {3, 3, 3});
  const auto inner = add_box(in, {1, 1, 1}, {2, 2, 2});
  cellforge::cell_input_volume hollow;
  for (auto f : outer) hollow.faces.emplace_back(f, +1);
  for (auto f : inner) hollow.faces.emplace_back(f, -1);  // out of the hollow box: into the cavity
  SUBCASE("the cavity empty") {
    in.volumes.push_back(hollow);
    const auto cc = cellforge::make_cell_complex(in);
    CHECK(cellforge::signed_volume(cc, cell_volume(0)) == doctest::Approx(26));
    CHECK(check_step(cc, 1) == "");
  }
  SUBCASE("the cavity filled by a second solid") {
    in.volumes.push_back(hollow);
    cellforge::cell_input_volume core;
    for (auto f : inner) core.faces.emplace_back(f, +1);
    in.volumes.push_back(core);
    CHECK(check_step(cellforge::make_cell_complex(in), 1) == "");
  }
  SUBCASE("a fin on the box: an open shell beside the solid") {
    cellforge::cell_complex_input<glm::dvec3> box;
    const auto fs = add_box(box, {0, 0, 0}, {1, 1, 1});
    cellforge::cell_input_volume c;
    for (auto f : fs) c.faces.emplace_back(f, +1);
    box.volumes.push_back(c);
    // The fin stands on the edge from corner 0 to corner 1 (along x at y = z = 0).
    box.points.push_back({1, -1, -1});
    box.points.push_back({0, -1, -1});
    box.edges.push_back({1, 8});
    box.edges.push_back({8, 9});
    box.edges.push_back({9, 0});
    box.faces.push_back({{{0, 1, 8, 9}}});
    const auto cc = cellforge::make_cell_complex(box);
    CHECK(check_step(cc) == "");
  }
}

TEST_CASE("step: meshes as faceted solids (a closed triangle mesh)") {
  // A closed mesh: the stepped block's boundary, every face triangulated.
  const auto m = cellforge::samples::sample_stepped_block();
  const auto r = cellforge::wireframe_to_cells(m.wire);
  REQUIRE(r.cells.num_volumes() >= 1);
  const auto mesh = cellforge::volume_boundary_mesh(r.cells, cell_volume(0), {true});
  std::ostringstream os;
  const auto written = cellforge::io::write_step(os, mesh);
  CHECK(written.solids == 1);
  const occt_view v = read_with_occt(os.str());
  CHECK(v.valid);
  REQUIRE(v.solid_volumes.size() == 1);
  CHECK(v.solid_volumes[0] ==
        doctest::Approx(cellforge::signed_volume(r.cells, cell_volume(0))).epsilon(1e-9));
  CHECK(v.faces == mesh.num_faces());
}

TEST_CASE("step: tube meshes, plain and Loop-subdivided, as faceted solids") {
  for (const int levels : {0, 1}) {
    CAPTURE(levels);
    cellforge::tubes_options options;
    options.subdivision_levels = levels;
    const auto tubes = cellforge::make_tubes(cellforge::samples::ring(6), options);
    const auto& mesh = tubes.mesh;
    REQUIRE(mesh.is_closed());
    // The mesh's own volume: fans from each face's first vertex (the writer's triangles too).
    double six_volume = 0;
    for (auto f : mesh.faces()) {
      std::vector<glm::dvec3> ps;
      for (auto v : mesh.vertices_around(f)) ps.push_back(mesh.position(v));
      for (std::size_t i = 1; i + 1 < ps.size(); ++i)
        six_volume += glm::dot(ps[0], glm::cross(ps[i], ps[i + 1]));
    }
    std::ostringstream os;
    const auto written = cellforge::io::write_step(os, mesh);
    CHECK(written.solids == 1);
    const occt_view v = read_with_occt(os.str());
    CHECK(v.valid);
    REQUIRE(v.solid_volumes.size() == 1);
    for (const double theirs : {v.solid_volumes[0], v.volumes_about_far[0]})
      CHECK(theirs == doctest::Approx(std::abs(six_volume) / 6).epsilon(1e-9));
    CHECK(v.faces == written.faces);
    std::printf("tube ring, %d subdivision levels: %zu mesh faces, %zu STEP faces, volume %.6g\n", levels,
                mesh.num_faces(), written.faces, v.solid_volumes[0]);
  }
}

TEST_CASE("step: the OpenCASCADE check catches a wrongly oriented face") {
  const auto r = cellforge::wireframe_to_cells(cellforge::samples::sample_two_cubes().wire);
  REQUIRE(check_step(r.cells) == "");
  std::ostringstream os;
  cellforge::io::write_step(os, r.cells);
  std::string text = os.str();
  // Write the first face used against its plane's normal the other way round: its same_sense
  // and its bounds' orientations flipped, so that it faces into its solid.
  const auto line_of = [&](const std::string& head) {
    const std::size_t at = text.find("\n" + head);
    REQUIRE(at != std::string::npos);
    return at + 1;
  };
  const auto flip_end = [&](std::size_t start) {
    const std::size_t end = text.find('\n', start);
    REQUIRE(text.compare(end - 6, 6, ",.F.);") == 0);
    text.replace(end - 6, 6, ",.T.);");
  };
  std::size_t face = std::string::npos;
  for (std::size_t start = 0; face == std::string::npos && start < text.size();) {
    const std::size_t end = text.find('\n', start);
    const std::string_view line(text.data() + start, end - start);
    if (line.find("=ADVANCED_FACE(") != std::string_view::npos && line.ends_with(",.F.);")) face = start;
    start = end + 1;
  }
  REQUIRE(face != std::string::npos);
  const std::size_t open = text.find("',(", face) + 2, close = text.find(')', open);
  const std::string bounds = text.substr(open + 1, close - open - 1);  // "#a,#b"
  flip_end(face);
  for (std::size_t i = 0; i < bounds.size();) {
    const std::size_t comma = std::min(bounds.find(',', i), bounds.size());
    flip_end(line_of(bounds.substr(i, comma - i) + "="));
    i = comma + 1;
  }
  const occt_view v = read_with_occt(text);
  REQUIRE(v.read);
  bool caught = !v.valid || v.solid_volumes.size() != 2;
  for (std::size_t i = 0; !caught && i < 2; ++i)
    caught = std::abs(v.solid_volumes[i] - 1) > 1e-9 || std::abs(v.volumes_about_far[i] - 1) > 1e-9;
  CHECK(caught);
}

}  // namespace step_occt_tests
