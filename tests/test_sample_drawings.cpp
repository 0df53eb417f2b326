// SPDX-License-Identifier: MIT
// The test drawings of the sketch stages (samples/drawings.hpp): the sweep's size and
// families, and for every drawing its genericity and its ground truth (each edge on two face
// loops, simple planar loops, outer loops simple in 2D, Euler–Poincaré with the model's genus,
// the 3D model read back by wireframe_to_cells). Release checks every drawing; the sanitizer
// build (no NDEBUG) a deterministic sample of every family (sketch_sweep_options::limit).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/samples/drawings.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

// The pieces this file tests, named (its page above includes them).
#include "cellforge/samples/drawings_compound.hpp"
#include "cellforge/samples/drawings_normalons.hpp"
#include "cellforge/samples/drawings_polytopes.hpp"
#include "cellforge/samples/drawings_sweep.hpp"
#include "cellforge/samples/drawings_views.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace sample_drawings_tests {
namespace {

using cellforge::samples::sample_drawing;
using cellforge::samples::sample_model;

// Drawings whose truth the per-drawing cases check: all in Release, a sample under the
// sanitizers (10-50x slower). O(1).
std::size_t checked_limit() {
#ifdef NDEBUG
  return 0;
#else
  return 250;
#endif
}

// The sweep the cases check (full or sample), built once, with its report.
struct sweep_run {
  std::vector<sample_drawing> drawings;
  cellforge::samples::sketch_sweep_report report;
};
const sweep_run& run() {
  static const sweep_run r = [] {
    sweep_run x;
    cellforge::samples::sketch_sweep_options o;
    o.limit = checked_limit();
    x.drawings = cellforge::samples::sketch_sweep(o, &x.report);
    return x;
  }();
  return r;
}
const std::vector<sample_drawing>& checked() { return run().drawings; }

// What is wrong with a drawing's truth, empty when nothing. O(L log L + V·E).
std::string truth_faults(const sample_drawing& s) {
  std::ostringstream out;
  const auto& pts = s.drawing.points;
  const auto& model = s.model;
  if (pts.size() != model.wire.points.size() || s.points.size() != pts.size()) return "point counts differ";
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const glm::dvec3 q = s.view * model.wire.points[i];
    if (glm::length(q - s.points[i]) > 1e-12 * (1 + glm::length(q)) || pts[i].x != s.points[i].x ||
        pts[i].y != s.points[i].y)
      out << "junction " << i << " is not the view of its vertex; ";
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> sides;
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  std::vector<int> degree(pts.size(), 0);
  for (const auto& e : s.drawing.edges) {
    if (e[0] == e[1] || !edges.insert({std::min(e[0], e[1]), std::max(e[0], e[1])}).second)
      out << "edge " << e[0] << "-" << e[1] << " is a loop or repeated; ";
    ++degree[e[0]], ++degree[e[1]];
  }
  for (std::size_t v = 0; v < pts.size(); ++v)
    if (degree[v] < 3) out << "junction " << v << " has degree " << degree[v] << "; ";
  double diag = 0;
  for (const auto& p : s.points)
    for (const auto& q : s.points) diag = std::max(diag, glm::length(p - q));
  std::size_t holes = 0;
  std::vector<glm::dvec3> normals;
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const auto& face = model.faces[f];
    holes += face.size() - 1;
    const glm::dvec3 n = cellforge::samples::detail::newell_normal(s.points, face[0]);
    normals.push_back(glm::normalize(n));
    for (std::size_t l = 0; l < face.size(); ++l) {
      const auto& loop = face[l];
      if (loop.size() < 3 || std::set<std::uint32_t>(loop.begin(), loop.end()).size() != loop.size())
        out << "face " << f << " loop " << l << " is not a simple cycle; ";
      std::vector<glm::dvec2> poly;
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
        if (!edges.count({std::min(a, b), std::max(a, b)}))
          out << "face " << f << " side " << a << "-" << b << " is no edge; ";
        ++sides[{std::min(a, b), std::max(a, b)}];
        const double off = std::abs(glm::dot(s.points[a] - s.points[face[0][0]], normals.back()));
        if (off > 1e-9 * diag) out << "face " << f << " is not planar (" << off / diag << "); ";
        poly.push_back(pts[a]);
      }
      if (!cellforge::samples::detail::simple_polygon(poly))
        out << "face " << f << " loop " << l << " is not simple in 2D; ";
    }
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> faces_of;
  for (std::size_t f = 0; f < model.faces.size(); ++f)
    for (const auto& loop : model.faces[f])
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
        faces_of[{std::min(a, b), std::max(a, b)}].push_back(f);
      }
  // One solid: every edge on two loops. Several volumes: on two or more (walls, contacts).
  const bool one = model.volumes.size() == 1;
  for (const auto& e : edges) {
    const auto it = sides.find(e);
    if (it == sides.end() || it->second < 2 || (one && it->second != 2)) {
      out << "edge " << e.first << "-" << e.second << " is on " << (it == sides.end() ? 0 : it->second)
          << " loops; ";
      continue;
    }
    // Two faces at an edge are never coplanar (they would be one face, or the edge a seam
    // with a wall on it: then it has three faces or more).
    const auto& fs = faces_of[e];
    if (fs.size() == 2 && (fs[0] == fs[1] || glm::length(glm::cross(normals[fs[0]], normals[fs[1]])) < 1e-6))
      out << "edge " << e.first << "-" << e.second << " joins two coplanar loops; ";
  }
  const auto chi = static_cast<long>(pts.size()) - static_cast<long>(edges.size()) +
                   static_cast<long>(model.faces.size()) - static_cast<long>(holes);
  // One volume: its surface's Euler-Poincare count. Several, each a ball: the union's
  // characteristic, 1 - genus for a connected model.
  if (one && chi != 2 - 2 * s.genus) out << "V - E + F - R = " << chi << ", genus " << s.genus << "; ";
  const auto cells = static_cast<long>(model.volumes.size());
  if (!one && chi - cells != 1 - s.genus)
    out << "V - E + F - R - C = " << chi - cells << ", genus " << s.genus << "; ";
  if (one && model.volumes[0].size() != model.faces.size()) out << "not one volume of all faces; ";
  // Every face bounds one or two volumes; every volume's faces close (each edge twice).
  std::vector<int> bounds(model.faces.size(), 0);
  for (std::size_t c = 0; c < model.volumes.size(); ++c) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> twice;
    for (const auto f : model.volumes[c]) {
      ++bounds[f];
      for (const auto& loop : model.faces[f])
        for (std::size_t i = 0; i < loop.size(); ++i)
          ++twice[{std::min(loop[i], loop[(i + 1) % loop.size()]),
                   std::max(loop[i], loop[(i + 1) % loop.size()])}];
    }
    for (const auto& [e, n] : twice)
      if (n != 2) out << "volume " << c << " is not closed at edge " << e.first << "-" << e.second << "; ";
  }
  for (std::size_t f = 0; f < bounds.size(); ++f)
    if (bounds[f] < 1 || bounds[f] > 2) out << "face " << f << " bounds " << bounds[f] << " volumes; ";
  return out.str();
}

TEST_CASE("sketch_sweep: at least 2000 drawings of every family, none over 300 edges, deterministic") {
  const auto& rep = run().report;
  const auto& all = run().drawings;
  const bool full = checked_limit() == 0;
  std::ostringstream table;
  std::size_t emin = 1000, emax = 0, planned = 0;
  for (const auto& f : rep.families) {
    table << "  " << f.family << ": " << f.models << " models, " << f.drawings << " drawings (of "
          << f.planned << "), edges " << f.min_edges << ".." << f.max_edges << ", rejected draws "
          << f.rejected << ", no generic view " << f.no_view << "\n";
    CHECK_MESSAGE(f.drawings >= (full ? 10u : 1u), f.family);
    CHECK_MESSAGE(f.no_view * 50 <= f.drawings, f.family);  // at most 2 % without a generic view
    CHECK(f.drawings + f.no_view <= f.planned);
    emin = std::min(emin, f.min_edges);
    emax = std::max(emax, f.max_edges);
    planned += f.planned;
  }
  MESSAGE("sketch sweep" << std::string(full ? "" : " (sample)") << ": " << all.size() << " drawings of "
                         << planned << " planned, edges " << emin << ".." << emax << ", generated in "
                         << rep.ms << " ms\n"
                         << table.str());
  CHECK(planned >= 2000);
  if (full) CHECK(all.size() >= 2000);
  if (!full) CHECK(all.size() * 4 < planned);  // a sample indeed
  CHECK(rep.drawings == all.size());
  std::map<std::string, std::size_t> per_family;
  std::set<std::string> names;
  for (const auto& s : all) {
    ++per_family[s.family];
    CHECK(s.drawing.edges.size() <= 300);
    CHECK_MESSAGE(names.insert(s.name).second, s.name);
  }
  for (const auto& f : cellforge::samples::sketch_sweep_families()) CHECK_MESSAGE(per_family[f] > 0, f);
  CHECK(per_family.size() == cellforge::samples::sketch_sweep_families().size());
  // A smaller sample is a subset of the full sweep, drawing for drawing (compared on a few
  // families: the full sweep of just those).
  cellforge::samples::sketch_sweep_options o;
  o.limit = 100;
  const auto sample = cellforge::samples::sketch_sweep(o);
  CHECK(sample.size() >= 90);
  CHECK(sample.size() <= 130);
  cellforge::samples::sketch_sweep_options some;
  some.families = {"platonic", "cut cube", "stairs", "classic"};
  const auto reference = full ? all : cellforge::samples::sketch_sweep(some);
  std::map<std::string, const sample_drawing*> by_name;
  for (const auto& s : reference) by_name[s.name] = &s;
  std::set<std::string> sample_families;
  std::size_t compared = 0;
  for (const auto& s : sample) {
    sample_families.insert(s.family);
    if (!full && std::find(some.families.begin(), some.families.end(), s.family) == some.families.end())
      continue;
    const auto it = by_name.find(s.name);
    REQUIRE_MESSAGE(it != by_name.end(), s.name);
    CHECK(it->second->drawing.points == s.drawing.points);
    CHECK(it->second->loops == s.loops);
    ++compared;
  }
  CHECK(compared >= 10);
  CHECK(sample_families.size() == cellforge::samples::sketch_sweep_families().size());
  for (const auto& s : reference)
    if (!full) CHECK(std::find(some.families.begin(), some.families.end(), s.family) != some.families.end());
  // Another seed: other random models and views, the same fixed families.
  o.limit = 0;
  o.seed = 2;
  o.random_models = 3;
  o.max_edges = 60;
  const auto other = cellforge::samples::sketch_sweep(o);
  for (const auto& s : other) CHECK(s.drawing.edges.size() <= 60);
  CHECK(other.front().name == all.front().name);
  CHECK(other.front().drawing.points != all.front().drawing.points);
  some.families = {"no such family"};
  CHECK_THROWS_AS(cellforge::samples::sketch_sweep(some), cellforge::error);
}

TEST_CASE("sketch_sweep: every drawing generic, its truth solids or cells of the stated genus") {
  const cellforge::samples::sketch_sweep_options o;
  std::map<std::string, std::array<std::size_t, 3>> tally;  // drawings, faults, genus > 0
  std::size_t faults = 0;
  for (const auto& s : checked()) {
    auto& t = tally[s.family];
    ++t[0];
    t[2] += s.genus > 0;
    const double margin = cellforge::samples::generic_margin(s);
    CHECK_MESSAGE(margin >= cellforge::samples::sketch_margin_threshold(o, s.drawing.edges.size()), s.name);
    const std::string why = truth_faults(s);
    if (!why.empty()) {
      ++t[1];
      if (++faults <= 20) MESSAGE(s.name << ": " << why);
    }
  }
  std::ostringstream table;
  for (const auto& [family, t] : tally)
    table << "  " << family << ": " << t[0] << " drawings, " << t[1] << " faults, " << t[2]
          << " of genus > 0\n";
  MESSAGE("truth checked on " << checked().size() << " drawings:\n" << table.str());
  CHECK(faults == 0);
  CHECK(tally.size() == cellforge::samples::sketch_sweep_families().size());
}

TEST_CASE("sketch_sweep: wireframe_to_cells reads every model back to its truth") {
  std::set<std::string> done;
  std::size_t models = 0, exact = 0;
  std::map<std::string, std::size_t> misses;
  for (const auto& s : checked()) {
    if (!done.insert(s.model.name).second) continue;
    ++models;
    bool ok = false;
    try {
      const auto r = cellforge::wireframe_to_cells(s.model.wire);
      std::vector<std::vector<std::vector<std::uint32_t>>> faces;
      for (const auto& f : r.input.faces) {
        faces.push_back(f.loops);
        for (auto& loop : faces.back())
          for (auto& v : loop) v = r.input_vertex[v];
      }
      ok = cellforge::samples::same_volumes(s.model.faces, s.model.volumes, faces, r.input.volumes);
    } catch (const cellforge::error& e) {
      MESSAGE(s.model.name << ": " << e.what());
    }
    exact += ok;
    if (!ok && ++misses[s.family] <= 3) MESSAGE("wireframe_to_cells misses " << s.model.name);
  }
  MESSAGE("wireframe_to_cells exact on " << exact << " of " << models << " models");
  CHECK(exact == models);
}

// The 2D convex hull's corners of a drawing (monotone chain). O(V log V).
std::set<std::uint32_t> outline_corners(const sample_drawing& s) {
  std::vector<std::uint32_t> order(s.drawing.points.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto& p = s.drawing.points;
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return p[a].x < p[b].x || (p[a].x == p[b].x && p[a].y < p[b].y);
  });
  const auto turn = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return (p[b].x - p[a].x) * (p[c].y - p[a].y) - (p[b].y - p[a].y) * (p[c].x - p[a].x);
  };
  std::vector<std::uint32_t> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = hull.size();
    for (const std::uint32_t v : order) {
      while (hull.size() >= base + 2 && turn(hull[hull.size() - 2], hull.back(), v) <= 0) hull.pop_back();
      hull.push_back(v);
    }
    std::reverse(order.begin(), order.end());
  }
  return {hull.begin(), hull.end()};
}

TEST_CASE("sketch_classics: each shows the difficulty its name says, in every view") {
  std::set<std::string> seen;
  cellforge::samples::sketch_sweep_options o;
  o.families = {"classic"};
  const auto classics = cellforge::samples::sketch_sweep(o);
  CHECK(classics.size() == 3 * cellforge::samples::sketch_classics().size());
  for (const auto& s : classics) {
    CHECK(s.family == "classic");
    CAPTURE(s.name);
    const auto& m = s.model;
    const std::string& n = m.name;
    seen.insert(n);
    std::vector<glm::dvec3> normal;
    for (const auto& f : m.faces)
      normal.push_back(glm::normalize(cellforge::samples::detail::newell_normal(m.wire.points, f[0])));
    const auto plane_of = [&](std::size_t f) { return glm::dot(normal[f], m.wire.points[m.faces[f][0][0]]); };
    std::size_t holed = 0, holes = 0, coplanar_pairs = 0, hexagons = 0, internal = 0;
    const auto outline = outline_corners(s);
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
      holed += m.faces[f].size() > 1;
      holes += m.faces[f].size() - 1;
      hexagons += m.faces[f][0].size() == 6;
      for (std::size_t g = f + 1; g < m.faces.size(); ++g)
        coplanar_pairs += glm::length(glm::cross(normal[f], normal[g])) < 1e-9 &&
                          std::abs(plane_of(f) - plane_of(g)) < 1e-9;
      bool touches = false;
      for (const auto& loop : m.faces[f])
        for (std::size_t i = 0; i < loop.size(); ++i) {
          touches = touches || outline.count(loop[i]) > 0;
        }
      internal += !touches;
    }
    // Edge pairs at a vertex that no face has as consecutive sides.
    std::size_t lonely_pairs = 0;
    std::set<std::array<std::uint32_t, 3>> in_face;  // (neighbour, vertex, neighbour), sorted ends
    for (const auto& f : m.faces)
      for (const auto& loop : f)
        for (std::size_t i = 0; i < loop.size(); ++i) {
          const std::uint32_t a = loop[(i + loop.size() - 1) % loop.size()], c = loop[(i + 1) % loop.size()];
          in_face.insert({std::min(a, c), loop[i], std::max(a, c)});
        }
    for (std::uint32_t v = 0; v < m.wire.points.size(); ++v) {
      std::vector<std::uint32_t> nb;
      for (const auto& e : m.wire.edges)
        if (e[0] == v || e[1] == v) nb.push_back(e[0] == v ? e[1] : e[0]);
      for (std::size_t i = 0; i < nb.size(); ++i)
        for (std::size_t j = i + 1; j < nb.size(); ++j) {
          if (!in_face.count({std::min(nb[i], nb[j]), v, std::max(nb[i], nb[j])})) ++lonely_pairs;
        }
    }
    if (n.find("pocket") != std::string::npos) CHECK(internal >= 5);  // the pocket's walls and floor
    if (n.find("pocket") != std::string::npos || n.find("cube on a block") != std::string::npos)
      CHECK(holed == 1);
    if (n.find("U channel") != std::string::npos) CHECK(coplanar_pairs >= 1);
    if (n.find("cube on a block") != std::string::npos) CHECK(internal >= 1);  // the small cube's top
    if (n.find("corner step") != std::string::npos) CHECK(hexagons == 3);
    if (n.find("octahedron") != std::string::npos) CHECK(lonely_pairs == 12);  // two at each vertex
    if (n.find("slot") != std::string::npos || n.find("frame") != std::string::npos) {
      CHECK(s.genus >= 1);
      CHECK(holed == 2);  // front and back, or top and bottom
      CHECK(holes == 2 * static_cast<std::size_t>(s.genus));
    }
  }
  CHECK(seen.size() == cellforge::samples::sketch_classics().size());
}

TEST_CASE("convex_polytope_model: Platonic and Archimedean solids have their known counts") {
  struct expected {
    const char* name;
    std::size_t v, e, f;
  };
  const std::vector<expected> table{{"tetrahedron", 4, 6, 4},
                                    {"cube", 8, 12, 6},
                                    {"octahedron", 6, 12, 8},
                                    {"dodecahedron", 20, 30, 12},
                                    {"icosahedron", 12, 30, 20},
                                    {"truncated tetrahedron", 12, 18, 8},
                                    {"cuboctahedron", 12, 24, 14},
                                    {"truncated cube", 24, 36, 14},
                                    {"truncated octahedron", 24, 36, 14},
                                    {"rhombicuboctahedron", 24, 48, 26},
                                    {"truncated cuboctahedron", 48, 72, 26},
                                    {"snub cube", 24, 60, 38},
                                    {"icosidodecahedron", 30, 60, 32},
                                    {"truncated dodecahedron", 60, 90, 32},
                                    {"truncated icosahedron", 60, 90, 32},
                                    {"rhombicosidodecahedron", 60, 120, 62},
                                    {"truncated icosidodecahedron", 120, 180, 62}};
  auto solids = cellforge::samples::platonic_solids();
  for (auto& m : cellforge::samples::archimedean_solids()) solids.push_back(std::move(m));
  REQUIRE(solids.size() == table.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    CAPTURE(table[i].name);
    CHECK(solids[i].name == table[i].name);
    CHECK(solids[i].wire.points.size() == table[i].v);
    CHECK(solids[i].wire.edges.size() == table[i].e);
    CHECK(solids[i].faces.size() == table[i].f);
    // Uniform: every edge of the same length.
    const auto& p = solids[i].wire.points;
    const auto len = [&](const std::array<std::uint32_t, 2>& e) { return glm::length(p[e[0]] - p[e[1]]); };
    for (const auto& e : solids[i].wire.edges) CHECK(std::abs(len(e) - len(solids[i].wire.edges[0])) < 1e-9);
  }
  // Points on facets and edges are no corners; a flat set is refused.
  std::vector<glm::dvec3> pts;
  cellforge::samples::detail::signed_permutations(pts, {1, 1, 1}, true);
  pts.push_back({0, 0, 1});
  pts.push_back({1, 0, 1});
  pts.push_back({0, 0, 0});
  const sample_model cube = cellforge::samples::convex_polytope_model(pts, "cube with extras");
  CHECK(cube.wire.points.size() == 8);
  CHECK(cube.faces.size() == 6);
  for (const auto& f : cube.faces) CHECK(f[0].size() == 4);
  CHECK_THROWS_AS(
      cellforge::samples::convex_polytope_model({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, "flat"),
      cellforge::error);
}

TEST_CASE("sample solids: sizes by construction; bad sizes refused") {
  const auto count = [](const sample_model& m) {
    return std::array<std::size_t, 3>{m.wire.points.size(), m.wire.edges.size(), m.faces.size()};
  };
  CHECK(count(cellforge::samples::sample_antiprism(7)) == std::array<std::size_t, 3>{14, 28, 16});
  CHECK(count(cellforge::samples::sample_frustum(5)) == std::array<std::size_t, 3>{10, 15, 7});
  CHECK(count(cellforge::samples::sample_bipyramid(9)) == std::array<std::size_t, 3>{11, 27, 18});
  for (const std::size_t k : {1u, 4u, 17u})
    CHECK(count(cellforge::samples::sample_stairs(k, 3)) ==
          std::array<std::size_t, 3>{4 * k + 4, 6 * k + 6, 2 * k + 4});
  for (const std::size_t n : {4u, 20u, 100u}) {
    const sample_model m = cellforge::samples::random_convex_polytope(n, true, 9);
    CHECK(count(m) == std::array<std::size_t, 3>{n, 3 * n - 6, 2 * n - 4});  // points in general position
  }
  for (std::size_t holes = 1; holes <= 4; ++holes) {
    const auto s = cellforge::samples::through_slot(holes, 11);
    CHECK(s.genus == static_cast<int>(holes));
  }
  // A cut cube: polygon faces, every vertex of degree 3.
  const sample_model cut = cellforge::samples::cut_polytope(0, 4, 5);
  std::vector<int> degree(cut.wire.points.size(), 0);
  for (const auto& e : cut.wire.edges) ++degree[e[0]], ++degree[e[1]];
  CHECK(std::all_of(degree.begin(), degree.end(), [](int d) { return d == 3; }));
  CHECK(cut.faces.size() >= 7);
  // Non-manifold voxel sets are refused: two cells touching along an edge, or at a vertex.
  cellforge::samples::voxel_layout l = cellforge::samples::empty_layout({0, 1, 2}, {0, 1, 2}, {0, 1});
  l.at(0, 0, 0) = l.at(1, 1, 0) = 1;
  CHECK_FALSE(cellforge::samples::voxel_solid_model(l, "edge contact").has_value());
  cellforge::samples::voxel_layout w = cellforge::samples::empty_layout({0, 1, 2}, {0, 1, 2}, {0, 1, 2});
  w.at(0, 0, 0) = w.at(1, 1, 1) = 1;
  CHECK_FALSE(cellforge::samples::voxel_solid_model(w, "vertex contact").has_value());
  // Skylines: the height repair leaves no edge-only contact between columns.
  std::size_t skylines = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const auto sky = cellforge::samples::random_skyline(7, 6, 4, seed);
    skylines += sky.has_value();
    if (sky) CHECK(sky->genus == 0);
  }
  CHECK(skylines >= 16);
  // A hollow box (a cavity) is refused; a ring is genus 1.
  cellforge::samples::voxel_layout hollow =
      cellforge::samples::empty_layout({0, 1, 2, 3}, {0, 1, 2, 3}, {0, 1, 2, 3});
  std::fill(hollow.labels.begin(), hollow.labels.end(), 1);
  hollow.at(1, 1, 1) = 0;
  CHECK_FALSE(cellforge::samples::voxel_solid_model(hollow, "hollow").has_value());
  cellforge::samples::voxel_layout ring =
      cellforge::samples::empty_layout({0, 1, 2, 3}, {0, 1, 2, 3}, {0, 1});
  std::fill(ring.labels.begin(), ring.labels.end(), 1);
  ring.at(1, 1, 0) = 0;
  const auto r = cellforge::samples::voxel_solid_model(ring, "ring");
  REQUIRE(r.has_value());
  CHECK(r->genus == 1);
  CHECK_THROWS_AS(cellforge::samples::sample_antiprism(2), cellforge::error);
  CHECK_THROWS_AS(cellforge::samples::sample_stairs(0, 1), cellforge::error);
  // Lattices too big to hold are refused before their coordinates are drawn (10^15 cells would
  // be a bad_alloc, 10^7 per side an overflow of nx * ny * nz).
  CHECK_THROWS_WITH_AS(cellforge::samples::random_normalon(100000, 100000, 100000, 10, 1),
                       doctest::Contains("random_normalon: a lattice of 100000 x 100000 x 100000"),
                       cellforge::error);
  CHECK_THROWS_WITH_AS(cellforge::samples::random_skyline(10000000, 10000000, 3, 1),
                       doctest::Contains("at most 10^8"), cellforge::error);
  CHECK_THROWS_WITH_AS(cellforge::samples::random_normalon(0, 3, 3, 4, 1), doctest::Contains("1 or more"),
                       cellforge::error);
  CHECK_THROWS_WITH_AS(cellforge::samples::empty_layout({0}, {0, 1}, {0, 1}),
                       doctest::Contains("a lattice of 0 x 1 x 1"), cellforge::error);
  CHECK_THROWS_WITH_AS(cellforge::samples::empty_layout({}, {0, 1}, {0, 1}),
                       doctest::Contains("two coordinates"), cellforge::error);
  CHECK_THROWS_AS(cellforge::samples::extruded_polygon({{0, 0}, {1, 1}, {1, 0}, {0, 1}}, 1.0, "bow tie"),
                  cellforge::error);
  CHECK_THROWS_AS(cellforge::samples::extruded_polygon({{0, 0}, {1, 0}, {2, 0}, {0, 1}}, 1.0, "collinear"),
                  cellforge::error);
  cellforge::samples::sketch_sweep_options bad;
  bad.views_per_model = 0;
  CHECK_THROWS_AS(cellforge::samples::sketch_sweep(bad), cellforge::error);
}

TEST_CASE("project_model: normalon and quasi-normalon flags on known models") {
  cellforge::detail::splitmix rng{3};
  const glm::dmat3 view = cellforge::samples::detail::random_rotation(rng);
  const auto flags = [&](const sample_model& m) {
    const auto s = cellforge::samples::project_model(m, view, m.name, "test");
    return std::pair<bool, bool>{s.normalon, s.quasi_normalon};
  };
  using flag = std::pair<bool, bool>;
  CHECK(flags(cellforge::samples::sample_cube()) == flag{true, false});
  CHECK(flags(cellforge::samples::sample_L()) == flag{true, false});
  CHECK(flags(cellforge::samples::sample_stairs(3, 1)) == flag{true, false});
  CHECK(flags(cellforge::samples::through_slot(2, 1).model) == flag{true, false});
  CHECK(flags(cellforge::samples::sample_prism(4)) == flag{true, false});  // a square prism, axis-aligned
  // Quasi-normalons by the flag's rule: the axis-parallel edges alone connect every vertex (what
  // direct inflation propagates depth along). One chamfer keeps them connected; two cut the
  // axis edges between them off (a looser reading would call those quasi-normalons too).
  const std::vector<glm::dvec2> rect{{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const auto chamfered = [&](std::vector<bool> which) {
    return cellforge::samples::extruded_polygon(cellforge::samples::chamfered_corners(rect, which, 0.3), 1.5,
                                                "chamfered");
  };
  CHECK(flags(chamfered({true, false, false, false})) == flag{false, true});
  CHECK(flags(chamfered({true, false, true, false})) == flag{false, false});
  CHECK(flags(chamfered({true, true, false, false})) == flag{false, false});
  CHECK(flags(cellforge::samples::extruded_polygon({{0, 0}, {2, 0}, {0, 1}}, 1.0, "wedge")) ==
        flag{false, true});
  CHECK(flags(cellforge::samples::extruded_polygon({{0, 0}, {3, 0}, {3, 1}, {1, 1}}, 1.0, "ramp")) ==
        flag{false, true});
  // A box with corner (1,1,1) cut off: quasi; with (1,1,0) cut off too the x = 1, y = 1 edge
  // between the two cuts hangs on oblique edges only.
  std::vector<glm::dvec3> box;
  for (unsigned c = 0; c < 8; ++c) box.push_back({double(c & 1u), double(c >> 1 & 1u), double(c >> 2 & 1u)});
  const auto cut = [&](std::vector<glm::dvec3> pts, unsigned c) {
    const glm::dvec3 q = pts[c];
    pts.erase(pts.begin() + c);
    for (int axis = 0; axis < 3; ++axis) {
      glm::dvec3 r = q;
      r[axis] += r[axis] > 0.5 ? -0.3 : 0.3;
      pts.push_back(r);
    }
    return pts;
  };
  CHECK(flags(cellforge::samples::convex_polytope_model(cut(box, 7), "corner cut")) == flag{false, true});
  CHECK(flags(cellforge::samples::convex_polytope_model(cut(cut(box, 7), 3), "two corners cut")) ==
        flag{false, false});
  // The gable house's ridge joins the walls by oblique edges only: neither.
  CHECK(flags(cellforge::samples::random_quasi_normalon(5, 4)) == flag{false, false});
  CHECK(flags(cellforge::samples::platonic_solids()[2]) == flag{false, false});
  CHECK(flags(cellforge::samples::sample_prism(6)) == flag{false, false});
  // On the sweep: every normalon-family drawing is a normalon, no quasi-normalon-family one
  // is, and about half of those are quasi-normalons by the rule.
  std::size_t quasi = 0, family = 0;
  for (const auto& s : checked()) {
    CAPTURE(s.name);
    if (s.family == "normalon" || s.family == "stairs" || s.family == "through slot") CHECK(s.normalon);
    if (s.family == "quasi-normalon") {
      CHECK_FALSE(s.normalon);
      ++family;
      quasi += s.quasi_normalon;
      if (s.name.find("gable") != std::string::npos) CHECK_FALSE(s.quasi_normalon);
      if (s.name.find("wedge") != std::string::npos || s.name.find("ramp") != std::string::npos)
        CHECK(s.quasi_normalon);
    }
    if (s.family == "platonic" || s.family == "archimedean") CHECK(s.normalon == (s.model.name == "cube"));
    if (s.family == "prism" || s.family == "random convex") CHECK_FALSE(s.quasi_normalon);
  }
  MESSAGE(quasi << " of " << family << " quasi-normalon-family drawings are quasi-normalons by the rule");
  CHECK(quasi * 3 >= family);
}

}  // namespace
}  // namespace sample_drawings_tests
