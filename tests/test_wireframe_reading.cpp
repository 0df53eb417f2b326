// SPDX-License-Identifier: MIT
// The reading rule of docs/wireframe.md, one failure mechanism at a time: each case takes
// models of the generated sweep (tests/wireframe_sweep.hpp, labels shuffled as in the sweep)
// that an earlier rule misread, and checks the exact faces, volumes and objects, what the
// result says about the cycles it did not take, and the crossing test on its own.

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "cellforge/cells/validate.hpp"
#include "cellforge/wireframe/face_arrangement.hpp"
#include "cellforge/wireframe/sample_models.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"
#include "wireframe_sweep.hpp"

using namespace cellforge;

namespace {

const wireframe_sweep::sweep_set& sweep() {
  static const wireframe_sweep::sweep_set s = wireframe_sweep::make_sweep(wireframe_sweep::sweep_size::full);
  return s;
}

const sample_model& model(const std::string& name) {
  for (const auto& m : sweep().models)
    if (m.model.name == name) return m.model;
  FAIL("no sweep model named " << name);
  return sweep().models.front().model;
}

// Converts and compares with the truth; returns the result for further checks.
wireframe_result exact(const sample_model& m, const wireframe_options& options = {}) {
  const std::string name = m.name;
  INFO(name);
  const wireframe_result r = wireframe_to_cells(m.wire, options);
  const std::string why = wireframe_sweep::miss_reason(m, r);
  INFO(why);
  CHECK(why.empty());
  return r;
}

std::size_t count_reason(const wireframe_result& r, const std::string& reason) {
  return static_cast<std::size_t>(std::count_if(r.alternatives.begin(), r.alternatives.end(),
                                                [&](const face_note& n) { return n.reason == reason; }));
}

}  // namespace

TEST_CASE("reading: holes and dents stay open whatever bounds their mouth") {
  // Mouths bounded by a ring of several faces (cells, bars, boxes, quads of a torus), and
  // dents whose pit is a pyramid: each mouth is a planar cycle no edge needs.
  for (const char* name : {"frame holes=1 cells", "frame holes=4 cells", "plate holes=9 cells",
                           "frame holes=1 one", "plate holes=3 one rot#1"}) {
    const auto r = exact(model(name));
    CHECK(r.cells.num_volumes() >= 1);
    CHECK(count_reason(r, "would close a hole or dent") >= 2);  // top and bottom of every hole
  }
  for (const auto& m : sweep().models) {
    if (m.family != "box ring" && m.family != "torus" && m.family != "dent") continue;
    const auto r = exact(m.model);
    if (m.family == "torus") {
      // A solid torus: one volume bounded by a surface of genus 1, V - E + F = 2 - 2g = 0,
      // so V - E + F - C = -1 for its one object.
      CHECK(r.cells.num_volumes() == 1);
      for (auto o : r.cells.objects()) CHECK(r.cells.object_euler(o) == -1);
    }
  }
}

TEST_CASE("reading: planar cycles no edge needs are not walls") {
  // The equator of a bipyramid, the rectangle under a roof, the rings of a solid of
  // revolution, a geodesic sphere's pentagons, a 3D cross's inner cube, the separating
  // triangles of a convex polytope: one volume each, the cycles reported as alternatives.
  for (const auto& m : sweep().models) {
    if (m.family != "bipyramid" && m.family != "house" && m.family != "barrel" && m.family != "hourglass" &&
        m.family != "geodesic" && m.family != "cross" && m.family != "polytope")
      continue;
    const auto r = exact(m.model);
    CHECK(r.cells.num_volumes() == 1);
  }
  const auto house = exact(model("house pyramid n=4"));
  CHECK(count_reason(house, "would split a volume in two") == 1);
  const auto geodesic = exact(model("geodesic f=2"));
  CHECK(count_reason(geodesic, "would split a volume in two") == 12);  // the pentagons
  // keep_walls reads the other way: the house's rectangle is a wall, reported unforced.
  wireframe_options walls;
  walls.volume.reading = face_reading::keep_walls;
  const auto walled = wireframe_to_cells(model("house pyramid n=4").wire, walls);
  CHECK(walled.input.volumes.size() == 2);
  CHECK(walled.unforced.size() == 1);
  CHECK(validate(walled.cells).ok());
}

TEST_CASE("crossing: real faces that meet only at an edge do not cross") {
  // Unions of boxes with merged non-convex faces, whose boundary edges lie on each other's
  // planes: an earlier test took such pairs to cross, dropped both and lost every face.
  for (const char* name :
       {"polycube #75 6x2x4 n=16", "polycube #42 4x5x5 n=15 rot#1", "polycube #74 6x5x2 n=18 rot#1"}) {
    const auto r = exact(model(name));
    CHECK(r.lost.empty());
    CHECK(r.arrangement.crossings.empty());
  }
}

TEST_CASE("crossing: the exact test, on its own") {
  // Points in the plane z = 0 and y = 0; faces as loops; planes as the arrangement builds them.
  wire_graph g;
  g.points = {{0, 0, 0},    {2, 0, 0},   {2, 0, 1},   {1, 0, 1},   {1, 0, 2}, {0, 0, 2},  // L in y = 0 (x, z)
              {1, 0, 1},    {2, 0, 1},   {2, -1, 1},  {3, -1, 1},  {3, 1, 1}, {1, 1, 1},  // in z = 1
              {0.5, -1, 1}, {0.5, 1, 1}, {0.5, 1, 3}, {0.5, -1, 3}};  // x = 0.5, through the L
  g.size = 4.0;
  g.center = {1.5, 0, 1.5};
  auto face = [&](std::vector<std::uint32_t> loop) {
    wire_face f;
    f.loops.push_back(std::move(loop));
    update_normal(g, f);
    return f;
  };
  auto plane = [&](const wire_face& f) { return detail::face_plane{f.normal, g.points[f.loops[0][0]], {}}; };
  detail::crossing_test cross(g);
  const double tol = 1e-9 * g.size;
  // The L has its edge (1,0,1)-(2,0,1) on the plane z = 1 and straddles that plane; a face of
  // z = 1 through that edge whose interior meets y = 0 only beyond x = 2 does not cross it.
  const wire_face l = face({0, 1, 2, 3, 4, 5});
  wire_face flat = face({6, 7, 8, 9, 10, 11});
  CHECK_FALSE(cross(l, plane(l), flat, plane(flat), tol));
  CHECK_FALSE(cross(flat, plane(flat), l, plane(l), tol));
  // A square in x = 0.5 through the L's lower arm crosses it, in either loop direction.
  wire_face through = face({12, 13, 14, 15});
  CHECK(cross(l, plane(l), through, plane(through), tol));
  std::reverse(through.loops[0].begin(), through.loops[0].end());
  update_normal(g, through);
  CHECK(cross(through, plane(through), l, plane(l), tol));
  // Coplanar faces never cross; nor do two faces sharing an edge at an angle.
  CHECK_FALSE(cross(l, plane(l), l, plane(l), tol));
}

TEST_CASE("crossing: a cycle that pierces real faces loses to them") {
  // The plug of a frame's hole, pierced by a bar of a linked frame or by a solid through the
  // hole: the real faces stay, the plug goes (an earlier rule dropped both).
  for (const char* name :
       {"linked frames", "linked frames thin cells", "box through frame", "sphere in frame",
        "sphere through frame", "box in frame flush top", "box in frame flush both"}) {
    const auto r = exact(model(name));
    CHECK(r.cells.num_objects() == 2);
    CHECK(r.lost.empty());
  }
}

TEST_CASE("touching solids: one object, volumes decided off each other's boundary") {
  // Cubes [0,1]^3 and [1,2]^3 share one vertex: one object, two volumes; the nesting test
  // must not start on the shared vertex (it found volume 1 inside volume 0 with volume 0).
  voxel_layout l = empty_layout({0, 1, 2}, {0, 1, 2}, {0, 1, 2});
  l.at(0, 0, 0) = 1;
  l.at(1, 1, 1) = 2;
  const sample_model corner = make_voxel_model(l, "cubes touching at a vertex");
  const auto r = wireframe_to_cells(corner.wire);
  CHECK(r.input.volumes.size() == 2);
  CHECK(r.cells.num_objects() == 1);
  CHECK(r.volume.nested_shells == 0);
  const auto v = validate(r.cells);
  const std::string why = v.message;
  INFO(why);
  REQUIRE(v.ok());
  for (const double volume : v.signed_volumes) CHECK(volume == doctest::Approx(1.0));
  for (const auto& m : sweep().models)
    if (m.family == "touching") exact(m.model);
}

TEST_CASE("reading: the same answer at scale 1e-6 and 1e6 after a rigid motion") {
  // One model of each family (its first in the sweep), scaled about its place.
  std::vector<std::string> seen;
  for (const auto& m : sweep().models) {
    if (std::find(seen.begin(), seen.end(), m.family) != seen.end() || m.family == "grid") continue;
    seen.push_back(m.family);
    for (const double scale : {1e-6, 1e6}) {
      sample_model s =
          transformed(m.model, glm::dmat3(scale), glm::dvec3(3.0 * scale, -2.0 * scale, 5.0 * scale));
      s.name = m.model.name + " scaled " + std::to_string(scale);
      exact(s);
    }
  }
  CHECK(seen.size() + 1 == wireframe_sweep::sweep_families().size());
}
