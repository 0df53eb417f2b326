#include <doctest/doctest.h>

#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <set>
#include <string>

#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/cells/validate.hpp"
#include "cellforge/halfedge/validate.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"
#include "cells_fixtures.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace cell_complex_tests {

using namespace cellforge;
using namespace cellforge::samples;
namespace fx = cells_fixtures;

namespace {

// The edge joining the vertices at positions a and b (by coordinates).
cell_edge edge_at(const cell_complex<glm::dvec3>& cc, glm::dvec3 a, glm::dvec3 b) {
  for (cell_edge e : cc.edges()) {
    const glm::dvec3 p = cc.point(cc.source(e)), q = cc.point(cc.target(e));
    if ((p == a && q == b) || (p == b && q == a)) return e;
  }
  return {};
}

// The message of the error make_cell_complex throws on `in`, or "" if it does not throw.
std::string build_error(cell_complex_input<glm::dvec3> in) {
  try {
    (void)make_cell_complex(std::move(in));
  } catch (const error& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("cell complex: a cube") {
  const cell_complex<glm::dvec3> cc = make_cell_complex(fx::cube());
  CHECK(cc.num_vertices() == 8);
  CHECK(cc.num_edges() == 12);
  CHECK(cc.num_faces() == 6);
  CHECK(cc.num_volumes() == 1);
  REQUIRE(cc.num_objects() == 1);
  CHECK(cc.object_euler(cell_object(0)) == 1);
  for (cell_vertex v : cc.vertices()) {
    CHECK(cc.vertex_edges(v).size() == 3);
    for (const auto& [e, s] : cc.vertex_edges(v)) CHECK((s > 0 ? cc.source(e) : cc.target(e)) == v);
  }
  for (cell_edge e : cc.edges()) {
    REQUIRE(cc.edge_faces(e).size() == 2);
    // Canonical start: after the outside wedge, so the cube is wedge 0 and outside wedge 1.
    CHECK(cc.edge_wedges(e)[0] == cell_volume(0));
    CHECK_FALSE(cc.edge_wedges(e)[1].is_valid());
    CHECK(cc.edge_volumes(e) == std::vector<cell_volume>{cell_volume(0)});
  }
  for (cell_face f : cc.faces()) {
    REQUIRE(cc.face_volumes(f).size() == 1);
    // Unit normals pointing out of the cube carry sign +1.
    const glm::dvec3 n = cc.face_normal(f);
    CHECK(glm::length(n) == doctest::Approx(1.0));
    const glm::dvec3 c = cc.point(cc.loop_vertices(f, 0)[0]) - glm::dvec3(0.5);
    CHECK((glm::dot(n, c) > 0 ? 1 : -1) == cc.face_volumes(f)[0].sign);
    // Loop edges join consecutive loop vertices in the stated direction.
    const auto vs = cc.loop_vertices(f, 0);
    const auto es = cc.loop_edges(f, 0);
    REQUIRE(vs.size() == es.size());
    for (std::size_t i = 0; i < vs.size(); ++i) {
      const auto [e, s] = es[i];
      CHECK((s > 0 ? cc.source(e) : cc.target(e)) == vs[i]);
      CHECK((s > 0 ? cc.target(e) : cc.source(e)) == vs[(i + 1) % vs.size()]);
    }
  }
  // About the edge (0,0,0)→(1,0,0): rotating from +y toward +z, the bottom face (reaching
  // into +y) comes first, then the front face (reaching into +z); the cube lies between.
  const cell_edge e = edge_at(cc, {0, 0, 0}, {1, 0, 0});
  REQUIRE(e.is_valid());
  const bool forward = cc.point(cc.source(e)) == glm::dvec3(0, 0, 0);
  const auto ef = cc.edge_faces(e);
  const glm::dvec3 n0 = cc.face_normal(ef[0].handle), n1 = cc.face_normal(ef[1].handle);
  if (forward) {
    CHECK(std::abs(n0.z) == 1.0);  // bottom
    CHECK(std::abs(n1.y) == 1.0);  // front
  } else {
    CHECK(std::abs(n0.y) == 1.0);
    CHECK(std::abs(n1.z) == 1.0);
  }
}

TEST_CASE("cell complex: two cubes sharing a face") {
  const cell_complex<glm::dvec3> cc = make_cell_complex(fx::two_cubes());
  CHECK(cc.num_vertices() == 12);
  CHECK(cc.num_edges() == 20);
  CHECK(cc.num_faces() == 11);
  CHECK(cc.num_volumes() == 2);
  REQUIRE(cc.num_objects() == 1);
  CHECK(cc.object_euler(cell_object(0)) == 1);
  CHECK(cc.object_volumes(cell_object(0)).size() == 2);
  std::size_t shared = 0;
  for (cell_face f : cc.faces())
    if (cc.face_volumes(f).size() == 2) {
      ++shared;
      CHECK(cc.face_volumes(f)[0].sign == -cc.face_volumes(f)[1].sign);
      CHECK(cc.face_volumes(f)[0].handle != cc.face_volumes(f)[1].handle);
    }
  CHECK(shared == 1);
  // An edge of the shared face has three faces: cube, cube, outside.
  const cell_edge e = edge_at(cc, {1, 0, 0}, {1, 1, 0});
  REQUIRE(e.is_valid());
  REQUIRE(cc.edge_faces(e).size() == 3);
  const auto w = cc.edge_wedges(e);
  CHECK(w[0].is_valid());
  CHECK(w[1].is_valid());
  CHECK(w[0] != w[1]);
  CHECK_FALSE(w[2].is_valid());
  CHECK(cc.edge_volumes(e).size() == 2);
}

TEST_CASE("cell complex: a 2x2x1 grid has an edge with four volumes around it") {
  const cell_complex<glm::dvec3> cc = make_cell_complex(fx::grid(2, 2, 1));
  CHECK(cc.num_vertices() == 18);
  CHECK(cc.num_edges() == 33);
  CHECK(cc.num_faces() == 20);
  CHECK(cc.num_volumes() == 4);
  CHECK(cc.object_euler(cell_object(0)) == 1);
  const cell_edge e = edge_at(cc, {1, 1, 0}, {1, 1, 1});
  REQUIRE(e.is_valid());
  REQUIRE(cc.edge_faces(e).size() == 4);
  for (cell_volume c : cc.edge_wedges(e)) CHECK(c.is_valid());
  CHECK(cc.edge_volumes(e).size() == 4);
  // Rotation order about +z (or -z): the directions into the faces turn monotonically.
  const bool up = cc.point(cc.target(e)).z > cc.point(cc.source(e)).z;
  // Rotation order about the edge: the directions into the faces turn the same way, one
  // full turn in all.
  std::vector<double> angles;
  for (const auto& [f, s] : cc.edge_faces(e)) {
    const glm::dvec3 d = glm::dvec3(0, 0, up ? 1 : -1) * double(s);
    const glm::dvec3 into = glm::cross(cc.face_normal(f), d);
    angles.push_back(std::atan2(into.y, into.x) * (up ? 1 : -1));
  }
  double turn = 0;
  for (std::size_t k = 0; k < angles.size(); ++k) {
    double step = angles[(k + 1) % angles.size()] - angles[k];
    while (step <= 0) step += 2 * 3.141592653589793;
    CHECK(step == doctest::Approx(3.141592653589793 / 2));
    turn += step;
  }
  CHECK(turn == doctest::Approx(2 * 3.141592653589793));
  // Consecutive faces about the edge share the volume between them.
  const auto ef = cc.edge_faces(e);
  for (std::size_t k = 0; k < 4; ++k) {
    const cell_volume c = cc.edge_wedges(e)[k];
    auto has = [&](cell_face f) {
      for (const auto& fv : cc.face_volumes(f))
        if (fv.handle == c) return true;
      return false;
    };
    CHECK(has(ef[k].handle));
    CHECK(has(ef[(k + 1) % 4].handle));
  }
}

TEST_CASE("cell complex: objects and Euler characteristics") {
  const cell_complex<glm::dvec3> two = make_cell_complex(fx::disjoint_cubes());
  REQUIRE(two.num_objects() == 2);
  for (cell_object o : two.objects()) {
    CHECK(two.object_euler(o) == 1);
    CHECK(two.object_volumes(o).size() == 1);
    CHECK(two.object_counts(o) == std::array<std::size_t, 4>{8, 12, 6, 1});
  }
  CHECK(two.volume_object(cell_volume(0)) != two.volume_object(cell_volume(1)));

  const cell_complex<glm::dvec3> frame = make_cell_complex(fx::frame());
  REQUIRE(frame.num_objects() == 1);
  CHECK(frame.num_volumes() == 8);
  CHECK(frame.object_euler(cell_object(0)) == 0);  // a solid torus made of balls

  const cell_complex<glm::dvec3> g = make_cell_complex(fx::grid(3, 2, 2));
  CHECK(g.object_euler(cell_object(0)) == 1);
  CHECK(g.num_volumes() == 12);

  const cell_complex<glm::dvec3> hole = make_cell_complex(fx::block_with_hole());
  CHECK(hole.num_vertices() == 16);
  CHECK(hole.num_edges() == 24);
  CHECK(hole.num_faces() == 10);
  CHECK(hole.num_loops(cell_face(0)) == 2);
  CHECK(hole.loop_edges(cell_face(0), 1).size() == 4);
  CHECK(hole.face_normal(cell_face(0)) == glm::dvec3(0, 0, 1));
  // Non-ball cells: annular faces and a genus-1 volume are each counted once.
  CHECK(hole.object_euler(cell_object(0)) == 1);
}

TEST_CASE("cell complex: to_input gives back the input") {
  for (const auto& in : {fx::cube(), fx::two_cubes(), fx::block_with_hole(), fx::frame()}) {
    const cell_complex<glm::dvec3> cc = make_cell_complex(in);
    CHECK(fx::same_input(cc.to_input(), in));
  }
}

TEST_CASE("cell complex: renumber_cells is make_cell_complex of the renumbered input") {
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  const auto permutation = [&](std::size_t n) {
    std::vector<std::uint32_t> p(n);
    for (std::uint32_t i = 0; i < n; ++i) p[i] = i;
    for (std::size_t i = n; i > 1; --i) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      std::swap(p[i - 1], p[(state >> 33) % i]);
    }
    return p;
  };
  for (const auto& in : {fx::cube(), fx::two_cubes(), fx::grid(3, 2, 2), fx::block_with_hole(), fx::frame(),
                         fx::disjoint_cubes()}) {
    for (int round = 0; round < 3; ++round) {
      const auto vl = permutation(in.points.size()), el = permutation(in.edges.size());
      cell_complex_input<glm::dvec3> moved = in;
      for (std::size_t v = 0; v < vl.size(); ++v) moved.points[vl[v]] = in.points[v];
      for (std::size_t e = 0; e < el.size(); ++e)
        moved.edges[el[e]] = {vl[in.edges[e][0]], vl[in.edges[e][1]]};
      for (auto& f : moved.faces)
        for (auto& loop : f.loops)
          for (auto& v : loop) v = vl[v];
      const auto direct = make_cell_complex(moved);
      const auto renumbered = renumber_cells(make_cell_complex(in), vl, el);
      CHECK(fx::same_complex(direct, renumbered));
      CHECK(fx::same_input(renumbered.to_input(), moved));
    }
    // The identity changes nothing.
    const auto cc = make_cell_complex(in);
    std::vector<std::uint32_t> vi(in.points.size()), ei(in.edges.size());
    std::iota(vi.begin(), vi.end(), 0u);
    std::iota(ei.begin(), ei.end(), 0u);
    CHECK(fx::same_complex(renumber_cells(cc, vi, ei), cc));
  }
  // Labels that are not permutations are refused.
  const auto cc = make_cell_complex(fx::cube());
  std::vector<std::uint32_t> v(cc.num_vertices()), e(cc.num_edges());
  std::iota(v.begin(), v.end(), 0u);
  std::iota(e.begin(), e.end(), 0u);
  auto twice = v;
  twice[1] = 0;
  CHECK_THROWS_WITH_AS(renumber_cells(cc, twice, e),
                       "renumber_cells: the vertex labels are not a permutation of 0..7", cellforge::error);
  CHECK_THROWS_WITH_AS(renumber_cells(cc, v, std::vector<std::uint32_t>(3, 0)),
                       "renumber_cells: 3 edge labels for 12 edges", cellforge::error);
}

TEST_CASE("cell complex: inconsistent input is refused, naming the element") {
  const cell_complex_input<glm::dvec3> good = fx::two_cubes();
  {
    auto in = good;
    in.points[3].y = std::nan("");
    CHECK(contains(build_error(in), "vertex 3 has a non-finite"));
  }
  {
    auto in = good;
    in.points[2].x = INFINITY;
    CHECK(contains(build_error(in), "vertex 2"));
  }
  {
    auto in = good;
    in.edges.push_back({0, 99});
    CHECK(contains(build_error(in), "edge 20 joins vertex 99"));
  }
  {
    auto in = good;
    in.edges.push_back({4, 4});
    CHECK(contains(build_error(in), "edge 20 joins vertex 4 to itself"));
  }
  {  // edge 0 bad: no edge is linked, and the empty per-vertex lists are walked without
     // stepping past their null start (clang's UBSan saw "add 8 to a null pointer")
    auto in = good;
    in.edges[0] = {4, 4};
    CHECK(contains(build_error(in), "edge 0 joins vertex 4 to itself"));
    in.edges[0] = {0, 99};
    CHECK(contains(build_error(in), "edge 0 joins vertex 99"));
  }
  {
    auto in = good;
    in.edges.push_back({in.edges[5][1], in.edges[5][0]});
    CHECK(contains(build_error(in), "edge 20 repeats edge 5"));
  }
  {
    auto in = good;
    in.faces[2].loops.clear();
    CHECK(contains(build_error(in), "face 2 has no loop"));
  }
  {
    auto in = good;
    in.faces[1].loops[0].resize(2);
    CHECK(contains(build_error(in), "face 1 loop 0 has 2 vertices"));
  }
  {
    auto in = good;
    std::swap(in.faces[0].loops[0][1], in.faces[0].loops[0][2]);  // a diagonal is not an edge
    CHECK(contains(build_error(in), "face 0 loop 0: consecutive vertices"));
  }
  {
    auto in = good;
    in.faces[0].loops[0][1] = 1000;
    CHECK(contains(build_error(in), "face 0 loop 0 uses vertex 1000"));
  }
  {
    auto in = good;
    in.faces[3].loops[0] = {in.faces[3].loops[0][0], in.faces[3].loops[0][1], in.faces[3].loops[0][0],
                            in.faces[3].loops[0][1]};
    CHECK(contains(build_error(in), "face 3 loop 0"));
    CHECK(contains(build_error(in), "a second time in the face"));
  }
  {
    auto in = good;
    in.volumes[0].faces[0].second = 2;
    CHECK(contains(build_error(in), "with sign 2"));
  }
  {
    auto in = good;
    in.volumes[1].faces[0].second = 0;
    CHECK(contains(build_error(in), "volume 1 uses face"));
  }
  {
    auto in = good;
    in.volumes[0].faces.push_back({99, 1});
    CHECK(contains(build_error(in), "volume 0 uses face 99"));
  }
  {
    auto in = good;
    in.volumes.push_back(in.volumes[0]);  // a copy of volume 0: its faces get a second volume on one side
    const std::string msg = build_error(in);
    CHECK((contains(msg, "on the same side") || contains(msg, "more than two volumes")));
  }
  {
    auto in = fx::cube();
    in.volumes.push_back(in.volumes[0]);
    for (auto& fs : in.volumes[1].faces) fs.second = -fs.second;  // the cube's outside as a volume
    CHECK(build_error(in).empty());
    in.volumes.push_back(in.volumes[0]);
    CHECK(contains(build_error(in), "face 0 is in more than two volumes (0, 1, 2)"));
  }
  {
    auto in = good;
    in.volumes[0].faces.pop_back();  // an open box
    CHECK(contains(build_error(in), "the boundary of volume 0 is not closed: edge"));
  }
  {
    auto in = good;
    in.volumes[1].faces[2].second = -in.volumes[1].faces[2].second;  // one face turned inside out
    CHECK(contains(build_error(in), "volume 1 is not closed"));
  }
  {
    auto in = good;
    in.volumes[0].faces.push_back(in.volumes[0].faces[0]);
    CHECK(contains(build_error(in), "volume 0 uses face"));
  }
  {
    auto in = good;
    in.volumes[1].faces.clear();
    CHECK(contains(build_error(in), "volume 1 has no face"));
  }
  {
    auto in = good;
    in.faces.push_back(in.faces[4]);  // a face using the edges of face 4 again is fine ...
    CHECK(build_error(in).empty());
    in.volumes[0].faces.push_back({11, 1});  // ... but not closing volume 0 any more
    CHECK(contains(build_error(in), "volume 0"));
  }
  CHECK(build_error(good).empty());
  CHECK(build_error({}).empty());
}

TEST_CASE("cell complex: a face in three volumes") {
  // Three volumes at one face is refused: sides would have to repeat.
  auto in = fx::two_cubes();
  // The shared face is the one used by both volumes.
  std::uint32_t shared = 0;
  for (const auto& [f, s] : in.volumes[0].faces)
    for (const auto& [g, t] : in.volumes[1].faces)
      if (f == g) shared = f;
  cell_input_volume v;
  v.faces.emplace_back(shared, 1);
  in.volumes.push_back(v);
  const std::string msg = build_error(in);
  CHECK(contains(msg, "face " + std::to_string(shared) + " is in more than two volumes (0, 1, 2)"));
}

// ---------------------------------------------------------------- validate

namespace {

// All volumes of `in` merged into one: faces between two of them, and edges left in no face,
// are dropped (indices renumbered).
cell_complex_input<glm::dvec3> merged(const cell_complex_input<glm::dvec3>& in) {
  std::vector<int> count(in.faces.size(), 0);
  for (const auto& v : in.volumes)
    for (const auto& fs : v.faces) ++count[fs.first];
  cell_complex_input<glm::dvec3> out;
  out.points = in.points;
  std::vector<std::uint32_t> new_face(in.faces.size(), 0xFFFFFFFFu);
  std::set<std::pair<std::uint32_t, std::uint32_t>> used;
  for (std::size_t f = 0; f < in.faces.size(); ++f)
    if (count[f] == 1) {
      new_face[f] = static_cast<std::uint32_t>(out.faces.size());
      out.faces.push_back(in.faces[f]);
      for (const auto& loop : in.faces[f].loops)
        for (std::size_t i = 0; i < loop.size(); ++i)
          used.insert(std::minmax(loop[i], loop[(i + 1) % loop.size()]));
    }
  for (const auto& e : in.edges)
    if (used.count(std::minmax(e[0], e[1]))) out.edges.push_back(e);
  cell_input_volume all;
  for (const auto& v : in.volumes)
    for (const auto& fs : v.faces)
      if (count[fs.first] == 1) all.faces.emplace_back(new_face[fs.first], fs.second);
  out.volumes = {all};
  return out;
}

std::uint32_t point_index(const cell_complex_input<glm::dvec3>& in, glm::dvec3 p) {
  return static_cast<std::uint32_t>(std::find(in.points.begin(), in.points.end(), p) - in.points.begin());
}

}  // namespace

TEST_CASE("validate: valid complexes and the Euler characteristic their topology implies") {
  std::vector<fx::cube_cell> shell;  // a 3x3x3 grid without its middle cube: a cavity
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y)
      for (int z = 0; z < 3; ++z)
        if (x != 1 || y != 1 || z != 1) shell.push_back({x, y, z});
  struct named {
    const char* name;
    cell_complex_input<glm::dvec3> in;
    long long euler;
    double volume;
  };
  const std::vector<named> cases{
      {"cube", fx::cube(), 1, 1},
      {"two cubes", fx::two_cubes(), 1, 2},
      {"2x2x1 grid", fx::grid(2, 2, 1), 1, 4},
      {"3x2x4 grid", fx::grid(3, 2, 4), 1, 24},
      {"frame of eight cubes (genus 1)", fx::frame(), 0, 8},
      {"frame as one volume", merged(fx::frame()), -1, 8},
      {"block with a hole (annular faces, genus-1 volume)", fx::block_with_hole(), 1, 8},
      {"grid with a cavity", fx::lattice(shell), 2, 26},
      {"hollow block as one volume", merged(fx::lattice(shell)), 3, 26},
  };
  for (const auto& c : cases) {
    INFO(c.name);
    const cell_complex<glm::dvec3> cc = make_cell_complex(c.in);
    const auto r = validate(cc);
    INFO(r.message);
    REQUIRE(r.ok());
    REQUIRE(cc.num_objects() == 1);
    CHECK(r.euler_checked[0] == 1);
    CHECK(r.expected_euler[0] == c.euler);
    CHECK(cc.object_euler(cell_object(0)) == c.euler);
    double total = 0;
    for (double v : r.signed_volumes) total += v;
    CHECK(total == doctest::Approx(c.volume));
  }
  const cell_complex<glm::dvec3> two = make_cell_complex(fx::disjoint_cubes());
  const auto r = validate(two);
  REQUIRE(r.ok());
  CHECK(r.expected_euler == std::vector<long long>{1, 1});
  CHECK(r.signed_volumes == std::vector<double>{1.0, 1.0});
  const auto hole = validate(make_cell_complex(fx::block_with_hole()));
  REQUIRE(hole.signed_volumes.size() == 1);
  CHECK(hole.signed_volumes[0] == doctest::Approx(8.0));
}

TEST_CASE("validate: the same answers after scaling and a rigid motion") {
  for (double scale : {1e-6, 1.0, 1e6}) {
    auto in = fx::grid(2, 1, 2);
    const double a = 0.7, b = 1.9;
    for (auto& p : in.points) {
      glm::dvec3 q{std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y, p.z};
      q = {q.x, std::cos(b) * q.y - std::sin(b) * q.z, std::sin(b) * q.y + std::cos(b) * q.z};
      p = scale * q + glm::dvec3(3 * scale, -5 * scale, 11 * scale);
    }
    const cell_complex<glm::dvec3> cc = make_cell_complex(in);
    const auto r = validate(cc);
    INFO(r.message);
    REQUIRE(r.ok());
    for (double v : r.signed_volumes) CHECK(v == doctest::Approx(scale * scale * scale));
    const cell_complex<glm::dvec3> ref = make_cell_complex(fx::grid(2, 1, 2));
    for (cell_edge e : cc.edges()) {
      REQUIRE(cc.edge_faces(e).size() == ref.edge_faces(e).size());
      for (std::size_t k = 0; k < cc.edge_faces(e).size(); ++k) {
        CHECK(cc.edge_faces(e)[k] == ref.edge_faces(e)[k]);
        CHECK(cc.edge_wedges(e)[k] == ref.edge_wedges(e)[k]);
      }
    }
  }
}

TEST_CASE("validate: each broken invariant is named with its element") {
  {
    auto in = fx::two_cubes();
    for (auto& v : in.volumes[1].faces) v.second = -v.second;  // volume 1 inside out
    // The shared face now has both volumes on one side: make_cell_complex refuses that.
    CHECK_THROWS_AS((void)make_cell_complex(in), error);
    auto single = fx::cube();
    for (auto& v : single.volumes[0].faces) v.second = -v.second;
    const auto r = validate(make_cell_complex(single));
    CHECK(r.broken == cells_invariant::orientation);
    CHECK(r.element == 0);
    CHECK(contains(r.message, "volume 0 has signed volume -1"));
  }
  {
    auto in = fx::cube();
    in.points[point_index(in, {1, 1, 1})] = {1, 1, 1.1};
    const auto r = validate(make_cell_complex(in));
    CHECK(r.broken == cells_invariant::non_planar);
    CHECK(contains(r.message, "from the face's plane"));
    cells_validation_options loose;
    loose.planarity = 0.1;
    CHECK(validate(make_cell_complex(in), loose).ok());
  }
  {
    // A small face is judged at its own scale: a cube of side 1e-3 beside a unit cube, one corner
    // lifted by 1e-6 (a tenth of a percent of its size) is bent; 1e-6 of the model's diagonal
    // (the tolerance once used) would have passed it.
    auto in = fx::disjoint_cubes();
    for (auto& p : in.points)
      if (p.x > 1.5) p = glm::dvec3(2, 0, 0) + 1e-3 * (p - glm::dvec3(2, 0, 0));
    CHECK(validate(make_cell_complex(in)).ok());
    const auto corner = std::find_if(in.points.begin(), in.points.end(), [](const glm::dvec3& p) {
      return p.x > 2.0005 && p.y > 0.0005 && p.z > 0.0005;
    });
    REQUIRE(corner != in.points.end());
    corner->z += 1e-6;
    const auto r = validate(make_cell_complex(in));
    CHECK(r.broken == cells_invariant::non_planar);
    CHECK(contains(r.message, "from the face's plane"));
    cells_validation_options model_scale;
    model_scale.planarity_floor = 1e-6;
    CHECK(validate(make_cell_complex(in), model_scale).ok());
  }
  {
    auto in = fx::cube();
    in.points[point_index(in, {1, 1, 1})] = {1, 1, 0};
    in.points[point_index(in, {1, 1, 0})] = {1, 1, 0};
    const auto r = validate(make_cell_complex(in));
    CHECK(r.broken == cells_invariant::degenerate_edge);
  }
  {
    // A tall box on the cube's bottom: its bottom and front faces coincide with the cube's
    // near their common edges.
    auto in = fx::cube();
    std::uint32_t b[4], t[4];
    const glm::dvec3 corners[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (int i = 0; i < 4; ++i) {
      b[i] = point_index(in, corners[i]);
      t[i] = static_cast<std::uint32_t>(in.points.size());
      in.points.push_back(corners[i] + glm::dvec3(0, 0, 2));
    }
    for (int i = 0; i < 4; ++i) {
      in.edges.push_back({b[i], t[i]});
      in.edges.push_back({t[i], t[(i + 1) % 4]});
    }
    cell_input_volume tall;
    const auto f0 = static_cast<std::uint32_t>(in.faces.size());
    in.faces.push_back({{{b[0], b[3], b[2], b[1]}}});
    in.faces.push_back({{{t[0], t[1], t[2], t[3]}}});
    for (int i = 0; i < 4; ++i) in.faces.push_back({{{b[i], b[(i + 1) % 4], t[(i + 1) % 4], t[i]}}});
    for (std::uint32_t f = f0; f < in.faces.size(); ++f) tall.faces.emplace_back(f, 1);
    in.volumes.push_back(tall);
    const cell_complex<glm::dvec3> cc = make_cell_complex(in);
    const auto r = validate(cc);
    CHECK(r.broken == cells_invariant::rotation_order);
    CHECK(contains(r.message, "lie on the same side of the edge"));
  }
  {
    const auto r = validate(make_cell_complex(merged(fx::lattice({{0, 0, 0}, {1, 1, 0}}))));
    CHECK(r.broken == cells_invariant::open_boundary);
    CHECK(contains(r.message, "volume 0: edge"));
  }
  {
    const auto r = validate(make_cell_complex(merged(fx::lattice({{0, 0, 0}, {1, 1, 1}}))));
    CHECK(r.broken == cells_invariant::euler);
    CHECK(contains(r.message, "pinched"));
  }
  {
    // Cubes meeting at an edge or a vertex are valid; their outer surface is not a manifold,
    // so the Euler check is skipped for them (and says so).
    for (const auto& cubes : {std::vector<fx::cube_cell>{{0, 0, 0}, {1, 1, 0}},
                              std::vector<fx::cube_cell>{{0, 0, 0}, {1, 1, 1}}}) {
      const auto r = validate(make_cell_complex(fx::lattice(cubes)));
      INFO(r.message);
      CHECK(r.ok());
      CHECK(r.euler_checked == std::vector<std::uint8_t>{0});
    }
  }
  {
    auto in = fx::cube();
    in.edges.push_back({0, 7});  // a dangling edge: valid, Euler not checked
    const auto r = validate(make_cell_complex(in));
    CHECK(r.ok());
    CHECK(r.euler_checked == std::vector<std::uint8_t>{0});
  }
}

// ---------------------------------------------------------------- conversions

namespace {

double mesh_volume(const surface_mesh<glm::dvec3>& m) { return signed_volume(to_soup(m)); }

// Faces of a complex as cycles of positions, each rotated to start at its smallest point and
// read in the smaller direction, so two complexes with the same faces (whatever their numbering) compare
// equal.
std::multiset<std::vector<std::vector<std::array<double, 3>>>> face_shapes(
    const cell_complex<glm::dvec3>& cc) {
  std::multiset<std::vector<std::vector<std::array<double, 3>>>> out;
  for (cell_face f : cc.faces()) {
    std::vector<std::vector<std::array<double, 3>>> loops;
    for (std::size_t l = 0; l < cc.num_loops(f); ++l) {
      std::vector<std::array<double, 3>> loop;
      for (cell_vertex v : cc.loop_vertices(f, l))
        loop.push_back({cc.point(v).x, cc.point(v).y, cc.point(v).z});
      std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
      auto reversed = loop;
      std::reverse(reversed.begin() + 1, reversed.end());
      loops.push_back(std::min(loop, reversed));
    }
    std::sort(loops.begin() + 1, loops.end());
    out.insert(loops);
  }
  return out;
}

}  // namespace

TEST_CASE("conversion: triangulating a face with holes") {
  // An L-shaped outer loop (counter-clockwise about +z) with two square holes (clockwise).
  const std::vector<std::vector<glm::dvec3>> loops{
      {{0, 0, 0}, {6, 0, 0}, {6, 2, 0}, {2, 2, 0}, {2, 6, 0}, {0, 6, 0}},
      {{3, 0.5, 0}, {3, 1.5, 0}, {4, 1.5, 0}, {4, 0.5, 0}},
      {{0.5, 3, 0}, {0.5, 4, 0}, {1.5, 4, 0}, {1.5, 3, 0}}};
  for (double sz : {1.0, -1.0}) {
    auto ls = loops;
    if (sz < 0)  // the same face seen from below: reverse every loop, normal -z
      for (auto& l : ls) std::reverse(l.begin(), l.end());
    const auto tris = cellforge::detail::cells::triangulate_face(ls, {0, 0, sz}, "test");
    CHECK(tris.size() == 14 + 2 * 2 - 2);
    std::vector<glm::dvec3> flat;
    for (const auto& l : ls) flat.insert(flat.end(), l.begin(), l.end());
    double area = 0;
    for (const auto& t : tris) {
      const glm::dvec3 n = glm::cross(flat[t[1]] - flat[t[0]], flat[t[2]] - flat[t[0]]);
      CHECK(n.z * sz >= 0);
      area += 0.5 * std::abs(n.z);
    }
    CHECK(area == doctest::Approx(20.0 - 2.0));
  }
  // Nine holes in rows (rays from one hole hit the others) inside a zigzag outer loop whose
  // teeth reach in front of the holes (bridges must pick a vertex inside the ray's triangle).
  std::vector<std::vector<glm::dvec3>> many{{{0, 0, 0}, {12, 0, 0}}};
  for (int t = 0; t < 6; ++t) {
    many[0].push_back({12, 2 * t + 1, 0});
    many[0].push_back({9.5, 2 * t + 1.2, 0});
    many[0].push_back({12, 2 * t + 2, 0});
  }
  many[0].push_back({0, 12, 0});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double x = 1 + 2.5 * i, y = 1 + 3.5 * j;
      many.push_back({{x, y, 0}, {x, y + 1, 0}, {x + 1, y + 1, 0}, {x + 1, y, 0}});
    }
  std::size_t corners = 0;
  for (const auto& l : many) corners += l.size();
  const auto tris = cellforge::detail::cells::triangulate_face(many, {0, 0, 1}, "test");
  CHECK(tris.size() == corners + 2 * 9 - 2);

  // The second hole's ray hits the first hole's bridge, which is on the ring twice (there and
  // back): the copy facing the hole must be taken, or the splice crosses the first hole.
  const std::vector<std::vector<glm::dvec3>> bridge_hit{{{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}},
                                                        {{6, 6, 0}, {6, 7, 0}, {7, 7, 0}, {7, 6, 0}},
                                                        {{1, 7.5, 0}, {1, 8.5, 0}, {2, 8.5, 0}, {2, 7.5, 0}}};
  CHECK(cellforge::detail::cells::triangulate_face(bridge_hit, {0, 0, 1}, "test").size() == 12 + 2 * 2 - 2);
  // Grids of 1..6 × 1..6 aligned square holes (rays along rows and columns through every
  // bridge), straight, sheared and staggered: 2 to 37 loops.
  for (int n = 1; n <= 6; ++n)
    for (int shift = 0; shift < 3; ++shift) {
      const double side = 3.0 * n + 1;
      std::vector<std::vector<glm::dvec3>> grid{{{0, 0, 0}, {side, 0, 0}, {side, side, 0}, {0, side, 0}}};
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const double x = 1 + 3 * i, y = 1 + 3 * j +
                                          (shift == 1   ? 0.5 * i
                                           : shift == 2 ? (i % 2) * 2.0
                                                        : 0.0);
          if (y + 1 < side) grid.push_back({{x, y, 0}, {x, y + 1, 0}, {x + 1, y + 1, 0}, {x + 1, y, 0}});
        }
      CAPTURE(n);
      CAPTURE(shift);
      const std::size_t holes = grid.size() - 1;
      CHECK(cellforge::detail::cells::triangulate_face(grid, {0, 0, 1}, "test").size() ==
            4 + 4 * holes + 2 * holes - 2);
    }

  // A hole outside the outer loop, or turning the wrong way, is refused.
  auto outside = loops;
  for (auto& p : outside[1]) p.x += 10;
  CHECK_THROWS_AS((void)cellforge::detail::cells::triangulate_face(outside, {0, 0, 1}, "test"), error);
  auto wrong = loops;
  std::reverse(wrong[2].begin(), wrong[2].end());
  CHECK_THROWS_AS((void)cellforge::detail::cells::triangulate_face(wrong, {0, 0, 1}, "test"), error);
}

TEST_CASE("conversion: volume boundaries to meshes and back") {
  SUBCASE("cube") {
    const cell_complex<glm::dvec3> cc = make_cell_complex(fx::cube());
    const auto m = volume_boundary_mesh(cc, cell_volume(0));
    REQUIRE_VALID(m);
    CHECK(m.num_vertices() == 8);
    CHECK(m.num_faces() == 6);
    CHECK(m.is_closed());
    CHECK(mesh_volume(m) == doctest::Approx(1.0));
    const cell_complex<glm::dvec3> back = make_cell_complex(mesh_to_cell_complex(m).to_input());
    REQUIRE_VALID(back);
    CHECK(face_shapes(back) == face_shapes(cc));
    CHECK(back.num_edges() == 12);

    const auto tri = volume_boundary_mesh(cc, cell_volume(0), {.triangulate_all = true});
    REQUIRE_VALID(tri);
    CHECK(tri.num_faces() == 12);
    CHECK(mesh_volume(tri) == doctest::Approx(1.0));
    const cell_complex<glm::dvec3> unmerged = mesh_to_cell_complex(tri);
    REQUIRE_VALID(unmerged);
    CHECK(unmerged.num_faces() == 12);
    CHECK(unmerged.num_edges() == 18);
    const cell_complex<glm::dvec3> merged_back = mesh_to_cell_complex(tri, {.merge_coplanar = true});
    REQUIRE_VALID(merged_back);
    CHECK(merged_back.num_faces() == 6);
    CHECK(merged_back.num_edges() == 12);
    CHECK(face_shapes(merged_back) == face_shapes(cc));
  }
  SUBCASE("every volume of a grid, with the complex's vertex and face of each element") {
    const cell_complex<glm::dvec3> cc = make_cell_complex(fx::grid(2, 2, 1));
    for (cell_volume c : cc.volumes()) {
      const auto m = volume_boundary_mesh(cc, c);
      REQUIRE_VALID(m);
      CHECK(m.is_closed());
      CHECK(mesh_volume(m) == doctest::Approx(1.0));
      const auto cv = m.get_vertex_property<std::uint32_t>("v:cell_vertex");
      const auto pts = m.positions();
      for (vertex_handle v : m.vertices()) CHECK(cc.point(cell_vertex(cv[v])) == pts[v]);
      const auto cf = m.get_face_property<std::uint32_t>("f:cell_face");
      for (face_handle f : m.faces()) {
        bool in_volume = false;
        for (const auto& fs : cc.volume_faces(c)) in_volume = in_volume || fs.handle.idx() == cf[f];
        CHECK(in_volume);
      }
    }
  }
  SUBCASE("block with a hole: annular faces are triangulated, and merged back") {
    const cell_complex<glm::dvec3> cc = make_cell_complex(fx::block_with_hole());
    const auto m = volume_boundary_mesh(cc, cell_volume(0));
    REQUIRE_VALID(m);
    CHECK(m.is_closed());
    CHECK(m.num_vertices() == 16);
    CHECK(m.num_faces() == 8 + 2 * 8);
    CHECK(long(m.num_vertices()) - long(m.num_edges()) + long(m.num_faces()) == 0);  // a torus
    CHECK(mesh_volume(m) == doctest::Approx(8.0));
    const cell_complex<glm::dvec3> back = mesh_to_cell_complex(m, {.merge_coplanar = true});
    const auto r = validate(back);
    INFO(r.message);
    REQUIRE(r.ok());
    CHECK(back.num_vertices() == 16);
    CHECK(back.num_edges() == 24);
    CHECK(back.num_faces() == 10);
    CHECK(face_shapes(back) == face_shapes(cc));
    CHECK(r.signed_volumes[0] == doctest::Approx(8.0));
    CHECK(back.object_euler(cell_object(0)) == 1);
  }
}

TEST_CASE("conversion: closed meshes to one-volume complexes") {
  SUBCASE("torus and sphere") {
    const cell_complex<glm::dvec3> torus_cells = mesh_to_cell_complex(make_mesh(torus<glm::dvec3>(12, 8)));
    const auto r = validate(torus_cells);
    INFO(r.message);
    REQUIRE(r.ok());
    CHECK(torus_cells.num_volumes() == 1);
    CHECK(torus_cells.object_euler(cell_object(0)) == -1);  // faces are disks, the volume is not a ball
    CHECK(r.expected_euler[0] == -1);
    const cell_complex<glm::dvec3> sphere = mesh_to_cell_complex(make_mesh(uv_sphere<glm::dvec3>(16, 8)));
    REQUIRE_VALID(sphere);
    CHECK(sphere.object_euler(cell_object(0)) == 1);
  }
  SUBCASE("an inside-out mesh gives faces with sign -1 and a positive volume") {
    auto soup = hexahedron<glm::dvec3>();
    polygon_soup<glm::dvec3> flipped;
    flipped.points = soup.points;
    for (std::size_t f = 0; f < soup.num_faces(); ++f) {
      std::vector<std::uint32_t> face(soup.face(f).begin(), soup.face(f).end());
      std::reverse(face.begin(), face.end());
      flipped.add_face(face);
    }
    const cell_complex<glm::dvec3> cc = mesh_to_cell_complex(make_mesh(flipped));
    REQUIRE_VALID(cc);
    for (const auto& fs : cc.volume_faces(cell_volume(0))) CHECK(fs.sign == -1);
  }
  SUBCASE("an open mesh is refused") {
    auto soup = hexahedron<glm::dvec3>();
    polygon_soup<glm::dvec3> open;
    open.points = soup.points;
    for (std::size_t f = 1; f < soup.num_faces(); ++f) open.add_face(soup.face(f));
    try {
      (void)mesh_to_cell_complex(make_mesh(open));
      FAIL("no error");
    } catch (const error& e) {
      CHECK(e.category() == error_category::topology);
      CHECK(contains(e.what(), "4 boundary edges"));
    }
  }
}

TEST_CASE("sample models through the wireframe pipeline: valid complexes, closed outward boundaries") {
  auto models = all_small_samples();
  models.push_back(sample_seed(2));
  models.push_back(sample_seed(3));
  for (const auto& m : models) {
    INFO(m.name);
    const wireframe_result<glm::dvec3> r = wireframe_to_cells(m.wire);
    const cell_complex<glm::dvec3>& cc = r.cells;
    const auto v = validate(cc);
    INFO(v.message);
    REQUIRE(v.ok());
    CHECK(cc.num_faces() == m.faces.size());
    CHECK(cc.num_volumes() == m.volumes.size());
    for (cell_object o : cc.objects())
      if (v.euler_checked[o.idx()]) CHECK(v.expected_euler[o.idx()] == cc.object_euler(o));
    for (cell_volume c : cc.volumes()) {
      const auto mesh = volume_boundary_mesh(cc, c);
      CHECK(mesh.is_closed());
      CHECK(mesh_volume(mesh) == doctest::Approx(v.signed_volumes[c.idx()]));
      const cell_complex<glm::dvec3> one = mesh_to_cell_complex(mesh, {.merge_coplanar = true});
      const auto w = validate(one);
      INFO(w.message);
      CHECK(w.ok());
      // Coplanar neighbours split only by another volume's wall (stepped block) merge here.
      CHECK(one.num_faces() <= cc.volume_faces(c).size());
      CHECK(w.signed_volumes[0] == doctest::Approx(v.signed_volumes[c.idx()]));
    }
  }
}

TEST_CASE_TEMPLATE("cell complexes keep the caller's point type: build, normals, validate, conversions", P,
                   test_support::sealed_point, std::array<float, 3>) {
  // The sample models (glm::dvec3) converted to P through the wireframe: the pipeline, the
  // complex and the boundary meshes all come back in P, with the same cells and volumes.
  for (const auto& m : {sample_two_cubes(), sample_block_with_hole(), sample_house()}) {
    INFO(m.name);
    const wireframe<P> wire = to_wireframe<P>(m.wire);
    const auto r = wireframe_to_cells(wire);
    static_assert(std::is_same_v<std::remove_cvref_t<decltype(r.cells)>, cell_complex<P>>);
    static_assert(std::is_same_v<decltype(r.input.points), std::vector<P>>);
    const auto ref = wireframe_to_cells(m.wire);
    const cell_complex<P>& cc = r.cells;
    REQUIRE(cc.num_faces() == ref.cells.num_faces());
    REQUIRE(cc.num_volumes() == ref.cells.num_volumes());
    static_assert(std::is_same_v<decltype(cc.point(cell_vertex(0))), const P&>);
    static_assert(std::is_same_v<decltype(cc.face_normal(cell_face(0))), P>);
    // The caller's points come back unchanged, at the vertices the double run gives them.
    for (cell_vertex v : cc.vertices()) {
      REQUIRE(r.input_vertex[v.idx()] == ref.input_vertex[v.idx()]);
      CHECK(to_dvec3(cc.point(v)) == to_dvec3(wire.points[r.input_vertex[v.idx()]]));
      CHECK(glm::length(to_dvec3(cc.point(v)) - ref.cells.point(v)) < 1e-6);
    }
    for (cell_face f : cc.faces())
      CHECK(glm::length(to_dvec3(cc.face_normal(f)) - ref.cells.face_normal(f)) < 1e-6);
    const auto v = validate(cc), vref = validate(ref.cells);
    INFO(v.message);
    REQUIRE(v.ok());
    for (cell_volume c : cc.volumes()) {
      CHECK(v.signed_volumes[c.idx()] == doctest::Approx(vref.signed_volumes[c.idx()]));
      CHECK(signed_volume(cc, c) == doctest::Approx(signed_volume(ref.cells, c)));
      CHECK(signed_volume(cc, c, from_dvec3<P>(glm::dvec3(5, 6, 7))) ==
            doctest::Approx(signed_volume(cc, c)));
      const surface_mesh<P> mesh = volume_boundary_mesh(cc, c);
      CHECK(mesh.is_closed());
      const cell_complex<P> one = mesh_to_cell_complex(mesh, {.merge_coplanar = true});
      REQUIRE_VALID(one);
    }
    // to_input and convert_points keep everything but the type.
    const cell_complex_input<P> in = cc.to_input();
    CHECK(make_cell_complex(in).num_faces() == cc.num_faces());
    const cell_complex<glm::dvec3> back = convert_points<glm::dvec3>(cc);
    CHECK(fx::same_input(back.to_input(), convert_points<glm::dvec3>(make_cell_complex(in)).to_input()));
    REQUIRE_VALID(back);
  }
}

}  // namespace cell_complex_tests
