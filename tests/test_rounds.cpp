// SPDX-License-Identifier: MIT
// Reconstruction with rounds (sketch/rounds.hpp, seed 003_be08eec927fcc329.txt, "Rounds and
// fillets", stage 4): on the generated round drawings (samples/round_drawings.hpp) every
// blend's radius, recovered from its end curves and the reconstructed face planes, must be within
// 1 % of the truth, its kind right and its end curves consistent with a circular blend. The
// reading keeps the drawing's x, y (a parallel view's scale) and only the Necker mirror is free,
// which keeps radii: they are compared as they are. Totals are printed and every miss named.
// Release runs 240 drawings, the sanitizer build (no NDEBUG) 40.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/error.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/io/ply.hpp"
#include "cellforge/io/step.hpp"
#include "cellforge/samples/round_drawings.hpp"
#include "cellforge/sketch/rounds.hpp"

// The pieces this file tests, named (its page above includes them).
#include "cellforge/sketch/detail/rounds_impl.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace rounds_tests {

#ifdef NDEBUG
constexpr std::size_t sweep_drawings = 240;
#else
constexpr std::size_t sweep_drawings = 40;  // the sanitizer build: Eigen unoptimised
#endif

double drawing_size(const std::vector<glm::dvec2>& p) {
  glm::dvec2 lo = p[0], hi = p[0];
  for (const auto& v : p) lo = glm::min(lo, v), hi = glm::max(hi, v);
  return glm::length(hi - lo);
}

TEST_CASE("rounds: every blend's radius within 1 % after reconstruction, its kind right") {
  cellforge::samples::round_sweep_options o;
  o.drawings = sweep_drawings;
  const auto drawings = cellforge::samples::round_drawing_sweep(o);
  REQUIRE(drawings.size() == sweep_drawings);
  std::size_t blends = 0, right = 0, kinds = 0, consistent = 0, oblique = 0, oblique_right = 0, slanted = 0,
              slanted_right = 0, fillets = 0, fillets_right = 0, flagged_wrong = 0, corrected = 0,
              categories_right = 0;
  double worst = 0, ms = 0;
  std::vector<std::string> misses;
  for (const auto& s : drawings) {
    const double size = drawing_size(s.drawing.lines.points);
    try {
      const auto r = cellforge::reconstruct_rounds(s.drawing);
      ms += r.milliseconds;
      corrected += r.depth_corrected;
      bool same = true, mirrored = true;  // categories as the truth's, or a and c swapped
      for (const auto& t : s.rounds) {
        ++blends;
        oblique += t.oblique, slanted += !t.perpendicular, fillets += !t.convex;
        const glm::dvec2 a = s.skeleton.drawing.points[t.vertices[0]],
                         b = s.skeleton.drawing.points[t.vertices[1]];
        const cellforge::edge_round* got = nullptr;
        for (const auto& e : r.rounds) {
          const glm::dvec2 u = r.skeleton.skeleton.points[e.junctions[0]],
                           v = r.skeleton.skeleton.points[e.junctions[1]];
          const double off =
              std::min(glm::length(u - a) + glm::length(v - b), glm::length(u - b) + glm::length(v - a));
          if (off < 1e-6 * size) got = &e;
        }
        if (!got) {
          misses.push_back(s.name + ": no blend on the true edge " + std::to_string(t.edge));
          continue;
        }
        const cellforge::blend_category m =
            t.category == cellforge::blend_category::a   ? cellforge::blend_category::c
            : t.category == cellforge::blend_category::c ? cellforge::blend_category::a
                                                         : t.category;
        same = same && got->category == t.category;
        mirrored = mirrored && got->category == m;
        const double err = std::abs(got->radius - t.radius) / t.radius;
        worst = std::max(worst, err);
        const bool ok = err <= 0.01;
        right += ok;
        oblique_right += ok && t.oblique, slanted_right += ok && !t.perpendicular;
        fillets_right += ok && !t.convex;
        kinds += got->convex == t.convex && got->kind != cellforge::blend_kind::unknown;
        consistent += got->consistent;
        flagged_wrong += !ok && !got->consistent;
        if (!ok || got->convex != t.convex || !got->consistent)
          misses.push_back(s.name + ": radius " + std::to_string(got->radius) + ", truth " +
                           std::to_string(t.radius) + (got->convex == t.convex ? "" : ", kind wrong") +
                           (got->consistent ? ""
                                            : ", inconsistent (spread " + std::to_string(got->radius_spread) +
                                                  ", centre " + std::to_string(got->centre_offset[0]) + ")"));
      }
      categories_right += same || mirrored;
      if (!same && !mirrored) misses.push_back(s.name + ": categories fit neither the view nor its mirror");
    } catch (const cellforge::error& e) {
      blends += s.rounds.size();
      misses.push_back(s.name + ": " + e.what());
    }
  }
  std::printf(
      "rounds: %zu of %zu blends within 1 %% of the true radius (worst %.2e; fillets %zu/%zu, oblique "
      "%zu/%zu, "
      "end faces not square to the edge %zu/%zu), kind right on %zu, consistent %zu, misses flagged "
      "inconsistent %zu of %zu; depths fitted to circular blends in %zu drawings; categories a/b/c of the "
      "reading those of the view or its mirror in %zu of %zu drawings; %.2f ms per drawing\n",
      right, blends, worst, fillets_right, fillets, oblique_right, oblique, slanted_right, slanted, kinds,
      consistent, flagged_wrong, blends - right, corrected, categories_right, drawings.size(),
      ms / static_cast<double>(drawings.size()));
  for (const auto& m : misses) std::printf("  miss: %s\n", m.c_str());
  CHECK(right == blends);
  CHECK(consistent == blends);
  CHECK(categories_right == drawings.size());
  CHECK(flagged_wrong == blends - right);  // no wrong radius is called consistent
  CHECK(kinds == blends);
  CHECK(fillets > 0);
  CHECK(slanted + oblique > 0);
}

// Signed volume of a closed polygon mesh with planar faces (divergence theorem, fans). O(size).
double soup_volume(const cellforge::polygon_soup<glm::dvec3>& m) {
  double v = 0;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const auto face = m.face(f);
    for (std::size_t k = 1; k + 1 < face.size(); ++k)
      v += glm::dot(m.points[face[0]], glm::cross(m.points[face[k]], m.points[face[k + 1]]));
  }
  return v / 6;
}

TEST_CASE("rounds: the rounded mesh is closed, oriented outward, and has the rounded solid's volume") {
  cellforge::samples::round_sweep_options o;
  o.drawings = sweep_drawings;
  const auto drawings = cellforge::samples::round_drawing_sweep(o);
  std::size_t meshed = 0, closed = 0, volume_right = 0, quads = 0;
  double worst = 0;
  std::vector<std::string> misses;
  for (const auto& s : drawings) {
    const auto r = cellforge::reconstruct_rounds(s.drawing);
    const auto m = cellforge::rounded_mesh(r);
    static_assert(std::is_base_of_v<cellforge::stage_report, std::remove_cvref_t<decltype(m)>>);
    CHECK(m.milliseconds > 0);
    ++meshed;
    quads += m.strip_quads;
    REQUIRE(m.face_source.size() == m.mesh.num_faces());
    // Closed and coherently oriented: every directed edge once, and its reverse once.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (std::size_t f = 0; f < m.mesh.num_faces(); ++f) {
      const auto face = m.mesh.face(f);
      for (std::size_t k = 0; k < face.size(); ++k) ++directed[{face[k], face[(k + 1) % face.size()]}];
    }
    bool ok = true;
    for (const auto& [e, c] : directed) ok = ok && c == 1 && directed.count({e.second, e.first}) == 1;
    closed += ok;
    // The skeleton's volume, less each round's strip region, plus each fillet's: the kite
    // between the edge, its tangent lines and the axis, less the fan of chords, times the edge.
    cellforge::polygon_soup<glm::dvec3> skeleton;
    skeleton.points = r.points;
    for (const auto& f : r.reading.face_loops) skeleton.add_face(f[0]);
    double expected = std::abs(soup_volume(skeleton));
    std::vector<std::size_t> segments(r.rounds.size(), 0);
    for (const auto src : m.face_source)
      if (src < 0) ++segments[static_cast<std::size_t>(-1 - src)];
    for (const auto& e : r.rounds) {
      const double n = static_cast<double>(segments[e.blend]);
      if (n == 0) continue;
      const double sweep = 3.141592653589793 - e.wedge_angle;
      const double area = e.radius * e.setback - 0.5 * n * e.radius * e.radius * std::sin(sweep / n);
      const double len = glm::length(r.points[e.junctions[1]] - r.points[e.junctions[0]]);
      expected += (e.convex ? -1 : 1) * area * len;
    }
    const double got = soup_volume(m.mesh), err = std::abs(got - expected) / expected;
    worst = std::max(worst, err);
    volume_right += got > 0 && err < 1e-9;
    if (!ok || !(got > 0 && err < 1e-9))
      misses.push_back(s.name + (ok ? "" : ": not closed") + ": volume " + std::to_string(got) +
                       ", expected " + std::to_string(expected));
  }
  std::printf(
      "rounded mesh: %zu drawings, closed and oriented %zu, volume right %zu (worst %.1e), %zu strip quads\n",
      meshed, closed, volume_right, worst, quads);
  for (const auto& mm : misses) std::printf("  miss: %s\n", mm.c_str());
  CHECK(closed == meshed);
  CHECK(volume_right == meshed);
  // The mesh goes out through the io writers as it is.
  const auto m = cellforge::rounded_mesh(cellforge::reconstruct_rounds(drawings[0].drawing));
  std::ostringstream obj, ply;
  cellforge::io::write_obj(obj, m.mesh);
  cellforge::io::write_ply(ply, m.mesh);
  std::size_t faces = 0;
  std::istringstream lines(obj.str());
  for (std::string line; std::getline(lines, line);) faces += line.rfind("f ", 0) == 0;
  CHECK(faces == m.mesh.num_faces());
  CHECK(ply.str().find("element face " + std::to_string(m.mesh.num_faces())) != std::string::npos);
}

TEST_CASE("rounds: the rounded B-rep is closed, on its surfaces, and has the mesh's volume in the limit") {
  cellforge::samples::round_sweep_options o;
  o.drawings = sweep_drawings;
  const auto drawings = cellforge::samples::round_drawing_sweep(o);
  std::size_t ok = 0, volume_right = 0, written = 0, blends = 0;
  double worst = 0;
  std::vector<std::string> misses;
  for (const auto& s : drawings) {
    const auto r = cellforge::reconstruct_rounds(s.drawing);
    const auto b = cellforge::rounded_brep(r);
    blends += r.rounds.size();
    const bool counts = b.planar_faces == r.reading.face_loops.size() && b.blend_faces == r.rounds.size() &&
                        b.arcs == 2 * r.rounds.size() &&
                        b.solid.faces.size() == b.planar_faces + b.blend_faces;
    ok += b.ok && counts;
    // The mesh's volume plus, per blend, what its chords cut off the exact arc (sector less fan,
    // times the edge's length: the end faces are parallel) is the exact solid's.
    const auto m = cellforge::rounded_mesh(r);
    double expected = soup_volume(m.mesh);
    std::vector<std::size_t> segments(r.rounds.size(), 0);
    for (const auto src : m.face_source)
      if (src < 0) ++segments[static_cast<std::size_t>(-1 - src)];
    for (const auto& e : r.rounds) {
      const double n = static_cast<double>(segments[e.blend]), sweep = 3.141592653589793 - e.wedge_angle;
      const double cut = 0.5 * e.radius * e.radius * (sweep - n * std::sin(sweep / n));
      expected +=
          (e.convex ? 1 : -1) * cut * glm::length(r.points[e.junctions[1]] - r.points[e.junctions[0]]);
    }
    const double err = std::abs(b.volume - expected) / expected;
    worst = std::max(worst, err);
    volume_right += err < 1e-9;
    // And STEP takes it as it is: one solid, a cylinder per blend, two end arcs each.
    std::ostringstream step;
    const auto w = cellforge::io::write_step(step, b.solid);
    const bool step_ok = w.solids == 1 && w.faces == b.solid.faces.size() && w.cylinders == r.rounds.size() &&
                         w.conics == 2 * r.rounds.size() && w.diagnostics.empty();
    written += step_ok;
    if (!(b.ok && counts) || !(err < 1e-9) || !step_ok)
      misses.push_back(
          s.name + (b.ok ? "" : ": " + (b.diagnostics.empty() ? std::string("not ok") : b.diagnostics[0])) +
          (counts ? "" : ": counts wrong") + ": volume " + std::to_string(b.volume) + ", the mesh's limit " +
          std::to_string(expected) + (step_ok ? "" : ": STEP counts wrong"));
  }
  std::printf(
      "rounded B-rep: %zu drawings (%zu blends), checked ok %zu, volume the mesh's limit %zu (worst %.1e), "
      "STEP as counted %zu\n",
      drawings.size(), blends, ok, volume_right, worst, written);
  for (const auto& mm : misses) std::printf("  miss: %s\n", mm.c_str());
  CHECK(ok == drawings.size());
  CHECK(volume_right == drawings.size());
  CHECK(written == drawings.size());
}

TEST_CASE("rounds: a finer chord tolerance gives more segments, each chord within it") {
  cellforge::samples::round_sweep_options o;
  o.drawings = 12;
  const auto drawings = cellforge::samples::round_drawing_sweep(o);
  for (const auto& s : drawings) {
    const auto r = cellforge::reconstruct_rounds(s.drawing);
    const double size = drawing_size(r.skeleton.skeleton.points);
    std::size_t last = 0;
    for (const double tol : {1e-2, 1e-3, 1e-4}) {
      cellforge::rounded_mesh_options mo;
      mo.chord_tolerance = tol;
      const auto m = cellforge::rounded_mesh(r, mo);
      CHECK(m.strip_quads >= last);
      last = m.strip_quads;
      // A chord's sagitta from the circle, per blend: radius (1 − cos(sweep / 2n)).
      for (const auto& e : r.rounds) {
        std::size_t n = 0;
        for (const auto src : m.face_source) n += src == -1 - static_cast<std::int64_t>(e.blend);
        REQUIRE(n > 0);
        const double sweep = 3.141592653589793 - e.wedge_angle;
        CHECK(e.radius * (1 - std::cos(sweep / (2.0 * static_cast<double>(n)))) <= tol * size * (1 + 1e-9));
      }
    }
  }
}

}  // namespace rounds_tests
