// SPDX-License-Identifier: MIT
// Rounds and fillets (seed 003_be08eec927fcc329.txt): the generated round drawings
// (samples/round_drawings.hpp) are checked against their own geometry, then paired
// (sketch/arc_pairing.hpp) and reduced to their polyhedral skeleton (sketch/round_skeleton.hpp),
// which must be the true skeleton drawing — same junctions to 1e-6 of the drawing's size, same
// edges — with every blend read as a round or a fillet rightly, on random radii and on one radius
// per drawing; the skeleton read by drawing_to_cells must be the prism, and its reading decide
// categories a and c (the true view's or its mirror's: a wireframe cannot tell which); a drawing
// typed to four decimals must still give its skeleton. Totals are printed and every miss named.
// Release runs 240 drawings per sweep, the sanitizer build (no NDEBUG) 60. Bad input: an arc with
// no partner, arcs in non-parallel faces, a zero-radius arc, a line off an arc's interior.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/error.hpp"
#include "cellforge/samples/round_drawings.hpp"
#include "cellforge/sketch/arc_pairing.hpp"
#include "cellforge/sketch/drawing_to_cells.hpp"
#include "cellforge/sketch/round_skeleton.hpp"

// Own namespace: the test files of a group may be compiled as one translation unit.
namespace round_skeleton_tests {

using cellforge::blend_category;
using cellforge::blend_kind;
using cellforge::samples::sample_round_drawing;

#ifdef NDEBUG
constexpr std::size_t sweep_drawings = 240;
#else
constexpr std::size_t sweep_drawings = 60;  // the sanitizer build: 10-50x slower
#endif

std::vector<sample_round_drawing> sweep(cellforge::samples::round_sweep_report* report = nullptr,
                                        bool equal_radii = false) {
  cellforge::samples::round_sweep_options o;
  o.drawings = sweep_drawings;
  o.equal_radii = equal_radii;
  return cellforge::samples::round_drawing_sweep(o, report);
}

double diagonal(const std::vector<glm::dvec2>& p) {
  glm::dvec2 lo = p[0], hi = p[0];
  for (const auto& v : p) lo = glm::min(lo, v), hi = glm::max(hi, v);
  return glm::length(hi - lo);
}

// Why the recovered skeleton differs from the truth, empty when it is the same drawing: every
// junction within tol of exactly one true junction (a bijection), and the same edges under it.
// `map` receives recovered → true junctions.
std::string skeleton_difference(const cellforge::line_drawing<glm::dvec2>& got,
                                const cellforge::line_drawing<glm::dvec2>& truth, double tol,
                                std::vector<std::uint32_t>& map) {
  if (got.points.size() != truth.points.size())
    return std::to_string(got.points.size()) + " junctions, truth " + std::to_string(truth.points.size());
  map.assign(got.points.size(), ~std::uint32_t{0});
  std::vector<bool> hit(truth.points.size(), false);
  for (std::size_t i = 0; i < got.points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    std::uint32_t at = 0;
    for (std::uint32_t j = 0; j < truth.points.size(); ++j) {
      const double dist = glm::length(got.points[i] - truth.points[j]);
      if (dist < best) best = dist, at = j;
    }
    if (best > tol || hit[at])
      return "junction " + std::to_string(i) + " is " + std::to_string(best) + " from the nearest true one";
    hit[at] = true;
    map[i] = at;
  }
  const auto key = [](std::uint32_t a, std::uint32_t b) {
    return std::array<std::uint32_t, 2>{std::min(a, b), std::max(a, b)};
  };
  std::vector<std::array<std::uint32_t, 2>> a, b;
  for (const auto& e : got.edges) a.push_back(key(map[e[0]], map[e[1]]));
  for (const auto& e : truth.edges) b.push_back(key(e[0], e[1]));
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  if (a != b)
    return std::to_string(got.edges.size()) + " edges, not the true " + std::to_string(truth.edges.size());
  return {};
}

const char* category_name(blend_category c) {
  return c == blend_category::a ? "a" : c == blend_category::b ? "b" : c == blend_category::c ? "c" : "a/c";
}

TEST_CASE("round drawings: the generator's arcs meet their lines tangentially, the truth is consistent") {
  cellforge::samples::round_sweep_report rep;
  const auto drawings = sweep(&rep);
  std::printf(
      "round drawings: %zu (%zu models dropped), %zu blends: %zu rounds, %zu fillets, %zu oblique "
      "(%zu with end faces not square to the edge); categories a %zu, b %zu, c %zu\n",
      rep.drawings, rep.dropped, rep.blends, rep.rounds, rep.fillets, rep.oblique, rep.not_perpendicular,
      rep.category[0], rep.category[1], rep.category[2]);
  REQUIRE(drawings.size() == sweep_drawings);
  CHECK(rep.fillets > 0);
  CHECK(rep.oblique > 0);
  for (const std::size_t c : rep.category) CHECK(c > 0);
  std::map<std::string, std::size_t> families;
  std::size_t bad = 0;
  for (const auto& s : drawings) {
    ++families[s.family];
    INFO(s.name);
    CHECK(s.rounds.size() >= 1);
    CHECK(s.rounds.size() <= 6);
    const auto v = cellforge::validate(s.drawing);
    INFO(v.message);
    CHECK(v.ok());
    // The skeleton is the polyhedron's own drawing, readable as such.
    CHECK(cellforge::validate(s.skeleton.drawing).ok());
    const auto& q = s.drawing.lines.points;
    std::vector<std::vector<std::uint32_t>> lines_at(q.size());
    for (std::uint32_t e = 0; e < s.drawing.lines.edges.size(); ++e)
      for (const auto j : s.drawing.lines.edges[e]) lines_at[j].push_back(e);
    for (const auto& t : s.rounds) {
      CHECK(t.radius > 0);
      CHECK(t.arcs.size() == (t.contour == cellforge::samples::round_truth::npos ? 2u : 4u));
      CHECK((t.contour != cellforge::samples::round_truth::npos) ==
            (t.convex && t.category == blend_category::b));
      for (const auto a : t.arcs) {
        const auto& arc = s.drawing.arcs[a];
        for (int side = 0; side < 2; ++side) {
          const std::uint32_t j = arc.ends[static_cast<std::size_t>(side)];
          const glm::dvec2 tan = cellforge::arc_tangent(arc.curve, side);
          // Every arc end is on one line, tangent there (the blend is tangent to both faces,
          // and a contour line is tangent to the cylinder).
          REQUIRE(lines_at[j].size() == 1);
          const auto& ln = s.drawing.lines.edges[lines_at[j][0]];
          const glm::dvec2 dir = glm::normalize(q[ln[1]] - q[ln[0]]);
          const double off = std::abs(dir.x * tan.y - dir.y * tan.x);
          bad += off > 1e-9;
          CHECK(off < 1e-9);
        }
      }
      // The truth's edge is a skeleton edge between its two vertices.
      const auto& e = s.skeleton.drawing.edges[t.edge];
      CHECK(std::minmax(e[0], e[1]) == std::minmax(t.vertices[0], t.vertices[1]));
    }
  }
  for (const auto& f : cellforge::samples::round_sweep_families()) CHECK(families[f] > 0);
  CHECK(bad == 0);
}

// The sweep: pairing and skeleton on every drawing against the truth; prints totals and misses.
void skeleton_sweep(const std::vector<sample_round_drawing>& drawings, const char* label) {
  std::size_t exact = 0, kinds_right = 0, blends = 0, b_right = 0, b_total = 0;
  std::array<std::size_t, 3> by_category{}, by_category_exact{};
  std::size_t oblique = 0, oblique_exact = 0;
  double ms = 0;
  std::vector<std::string> misses;
  for (const auto& s : drawings) {
    const auto r = cellforge::round_skeleton(s.drawing);
    ms += r.milliseconds;
    std::vector<std::uint32_t> map;
    const double tol = 1e-6 * diagonal(s.drawing.lines.points);
    std::string why =
        r.pairing.unpaired.empty() ? "" : std::to_string(r.pairing.unpaired.size()) + " arcs unpaired";
    if (why.empty()) why = skeleton_difference(r.skeleton, s.skeleton.drawing, tol, map);
    bool kinds = why.empty();
    if (why.empty()) {
      // Each true blend: the recovered blend on its edge, with its kind and, for rule 1, category b.
      for (const auto& t : s.rounds) {
        bool found = false;
        for (const auto& b : r.blends) {
          const auto u = std::minmax(map[b.junctions[0]], map[b.junctions[1]]);
          if (u != std::minmax(t.vertices[0], t.vertices[1])) continue;
          found = true;
          const bool right = b.kind == (t.convex ? blend_kind::round : blend_kind::fillet);
          if (!right) {
            kinds = false;
            misses.push_back(s.name + ": a " + (t.convex ? "round" : "fillet") + " read as " +
                             (b.kind == blend_kind::round    ? "a round"
                              : b.kind == blend_kind::fillet ? "a fillet"
                                                             : "unknown"));
          }
          if (t.convex && t.category == blend_category::b)
            ++b_total, b_right += b.category == blend_category::b;
          if (!(t.convex && t.category == blend_category::b)) CHECK(b.category == blend_category::a_or_c);
        }
        if (!found) {
          kinds = false;
          misses.push_back(s.name + ": no blend on the true edge " + std::to_string(t.edge));
        }
      }
    } else {
      std::string diag;
      for (const auto& dd : r.diagnostics) diag += "; " + dd;
      misses.push_back(s.name + ": " + why + diag);
    }
    // The 2D geometry kept per blend: each end curve runs from its first end junction to its
    // second (split arcs joined into one), and the second is the first moved along the new edge.
    const double size = diagonal(s.drawing.lines.points);
    for (const auto& b : r.blends) {
      const auto& p = r.pairing.pairs[b.pair];
      for (std::size_t k = 0; k < 2; ++k) {
        CHECK(glm::length(cellforge::arc_point(b.curves[k], 0.0) - s.drawing.lines.points[p.ends[k][0]]) <
              1e-9 * size);
        CHECK(glm::length(cellforge::arc_point(b.curves[k], 1.0) - s.drawing.lines.points[p.ends[k][1]]) <
              1e-9 * size);
      }
      CHECK(glm::length(b.curves[1].centre - b.curves[0].centre - b.axis) < 1e-9 * size);
      CHECK(glm::length(cellforge::arc_point(b.curves[1], 0.5) - cellforge::arc_point(b.curves[0], 0.5) -
                        b.axis) < 1e-9 * size);
    }
    exact += why.empty();
    kinds_right += kinds;
    for (const auto& t : s.rounds) {
      ++blends;
      ++by_category[static_cast<std::size_t>(t.category)];
      by_category_exact[static_cast<std::size_t>(t.category)] += why.empty();
      oblique += t.oblique;
      oblique_exact += t.oblique && why.empty();
    }
  }
  std::printf(
      "round skeleton, %s: %zu of %zu drawings exact (%zu blends; category a %zu/%zu, b %zu/%zu, c %zu/%zu "
      "in exact drawings; oblique %zu/%zu), round or fillet right in %zu; rule 1 found %zu of %zu "
      "contour rounds; %.2f ms per drawing\n",
      label, exact, drawings.size(), blends, by_category_exact[0], by_category[0], by_category_exact[1],
      by_category[1], by_category_exact[2], by_category[2], oblique_exact, oblique, kinds_right, b_right,
      b_total, ms / static_cast<double>(drawings.size()));
  for (const auto& m : misses) std::printf("  miss: %s\n", m.c_str());
  CHECK(static_cast<double>(exact) >= 0.95 * static_cast<double>(drawings.size()));
  CHECK(kinds_right == exact);  // convex or concave right on every drawing whose skeleton is found
  CHECK(b_right == b_total);
}

TEST_CASE("round skeleton: the sweep recovers the skeleton drawing and tells rounds from fillets") {
  skeleton_sweep(sweep(), "random radii");
  // One radius for every blend of a drawing, as parts are often designed: neighbouring blends
  // of one orientation then have congruent end curves, and pairing must still find partners.
  skeleton_sweep(sweep(nullptr, true), "equal radii");
}

// A pair of end curves of a blend on the vertical edge of a unit box's corner, the second end
// plane tilted by `tilt` (0: parallel end faces), each with its two lines, in a fixed view.
cellforge::arc_drawing<glm::dvec2> box_corner_blend(double tilt) {
  namespace r = cellforge::samples::detail::rounds;
  const glm::dvec3 A(0, 0, 0), B(0, 0, 1), n1(0, -1, 0), n2(-1, 0, 0);
  const glm::dvec3 gB = glm::normalize(glm::dvec3(tilt, 0.3 * tilt, 1));
  const r::blend g = r::make_blend(A, B, n1, n2, true, 0.2, glm::dvec3(0, 0, -1), gB);
  cellforge::detail::splitmix rng{7};
  const glm::dmat3 view = cellforge::samples::detail::random_rotation(rng);
  const auto proj = [&](glm::dvec3 v) { return glm::dvec2((view * v).x, (view * v).y); };
  cellforge::arc_drawing<glm::dvec2> d;
  for (std::size_t k = 0; k < 2; ++k) {
    const r::end_curve& e = g.ends[k];
    const glm::dvec3 corner = k == 0 ? A : B + glm::dvec3(0, 0, 0);
    const auto j = static_cast<std::uint32_t>(d.lines.points.size());
    for (const double phi : {0.0, g.Phi}) {
      const glm::dvec3 t = e.at(phi);
      d.lines.points.push_back(proj(t));
      d.lines.points.push_back(proj(t + 4.0 * (t - corner)));
    }
    d.lines.edges.push_back({j, j + 1});
    d.lines.edges.push_back({j + 2, j + 3});
    d.arcs.push_back({{j, j + 2}, r::affine_arc(proj(e.c), proj(e.u), proj(e.v), 0, g.Phi)});
  }
  return d;
}

TEST_CASE("round skeleton: the skeleton reads as the solid; its reading decides categories a and c") {
  const auto drawings = sweep();
  std::size_t solids = 0, as_truth = 0, as_mirror = 0, tried = 0;
  std::vector<std::string> misses;
  for (const auto& s : drawings) {
    auto r = cellforge::round_skeleton(s.drawing);
    std::vector<std::uint32_t> map;
    if (!skeleton_difference(r.skeleton, s.skeleton.drawing, 1e-6 * diagonal(s.drawing.lines.points), map)
             .empty())
      continue;  // named by the sweep above
    ++tried;
    const auto cells = cellforge::drawing_to_cells<glm::dvec3>(r.skeleton);
    // The complex's faces, in the truth's junction numbers, against the prism's.
    auto faces = cells.face_loops;
    for (auto& f : faces)
      for (auto& loop : f)
        for (auto& j : loop) j = map[j];
    const bool solid = cells.faces_agree && cellforge::samples::same_faces(s.skeleton.model.faces, faces);
    solids += solid;
    if (!solid) {
      misses.push_back(s.name + ": the skeleton's cell complex is not the prism");
      continue;
    }
    std::vector<double> depth;
    for (const auto& p : cells.wire.points) depth.push_back(p.z);
    cellforge::resolve_blend_categories(r, depth);
    // The reading is the true one or its mirror: every category as the truth's, or a and c swapped.
    bool same = true, mirrored = true;
    for (const auto& t : s.rounds)
      for (const auto& b : r.blends) {
        if (std::minmax(map[b.junctions[0]], map[b.junctions[1]]) !=
            std::minmax(t.vertices[0], t.vertices[1]))
          continue;
        const blend_category m = t.category == blend_category::a   ? blend_category::c
                                 : t.category == blend_category::c ? blend_category::a
                                                                   : t.category;
        same = same && b.category == t.category;
        mirrored = mirrored && b.category == m;
      }
    as_truth += same;
    as_mirror += mirrored && !same;
    if (!same && !mirrored) {
      std::string got;
      for (const auto& b : r.blends) got += std::string(" ") + category_name(b.category);
      misses.push_back(s.name + ": categories" + got + " fit neither reading");
    }
  }
  std::printf(
      "round skeleton read by drawing_to_cells: the prism's cell complex on %zu of %zu; categories from "
      "the reading: the true view's on %zu, its mirror's on %zu, neither on %zu\n",
      solids, tried, as_truth, as_mirror, solids - as_truth - as_mirror);
  for (const auto& m : misses) std::printf("  miss: %s\n", m.c_str());
  CHECK(solids == tried);
  CHECK(as_truth + as_mirror == solids);
}

TEST_CASE("round skeleton: a drawing typed to four decimals pairs with tolerances to match") {
  // Every coordinate, centre and semi-axis rounded to 1e-4 (drawings about 3 to 6 units
  // across): arc ends move off their curves and lines turn by up to ~1e-3 rad on short lines.
  const auto drawings = sweep();
  const auto typed = [](double x) { return std::round(x * 1e4) * 1e-4; };
  cellforge::round_skeleton_options o;
  o.pairing.tolerance = 1e-3;
  o.pairing.end_tolerance = 1e-4;
  o.pairing.angle_tolerance = 3e-3;
  std::size_t right = 0;
  double worst = 0;
  std::vector<std::string> misses;
  for (auto s : drawings) {
    for (auto& p : s.drawing.lines.points) p = {typed(p.x), typed(p.y)};
    for (auto& a : s.drawing.arcs) {
      a.curve.centre = {typed(a.curve.centre.x), typed(a.curve.centre.y)};
      a.curve.rx = typed(a.curve.rx), a.curve.ry = typed(a.curve.ry);
    }
    const auto r = cellforge::round_skeleton(s.drawing, o);
    std::vector<std::uint32_t> map;
    const double size = diagonal(s.drawing.lines.points);
    // The same drawing to the precision the typing leaves (corners from extended short lines
    // move more than the junctions typed).
    const std::string why = r.pairing.unpaired.empty()
                                ? skeleton_difference(r.skeleton, s.skeleton.drawing, 2e-3 * size, map)
                                : std::to_string(r.pairing.unpaired.size()) + " arcs unpaired";
    bool kinds = why.empty();
    if (why.empty())
      for (std::size_t j = 0; j < r.skeleton.points.size(); ++j)
        worst = std::max(worst, glm::length(r.skeleton.points[j] - s.skeleton.drawing.points[map[j]]) / size);
    for (const auto& b : r.blends) kinds = kinds && b.kind != blend_kind::unknown;
    right += kinds;
    if (!kinds) misses.push_back(s.name + ": " + (why.empty() ? std::string("a kind unknown") : why));
  }
  std::printf("typed to 1e-4: %zu of %zu skeletons right (worst junction %.2e of the size)\n", right,
              drawings.size(), worst);
  for (const auto& m : misses) std::printf("  miss: %s\n", m.c_str());
  CHECK(static_cast<double>(right) >= 0.95 * static_cast<double>(drawings.size()));
}

TEST_CASE("arc pairing: bad input is refused or reported") {
  SUBCASE("a blend with parallel end faces pairs; tilt one end face and neither arc has a partner") {
    const auto good = cellforge::pair_arcs(box_corner_blend(0.0));
    CHECK(good.pairs.size() == 1);
    CHECK(good.unpaired.empty());
    const auto tilted = cellforge::pair_arcs(box_corner_blend(0.25));
    CHECK(tilted.pairs.empty());
    CHECK(tilted.unpaired == std::vector<std::uint32_t>{0, 1});
    REQUIRE(tilted.diagnostics.size() == 2);
    for (const auto& m : tilted.diagnostics) {
      INFO(m);
      CHECK(m.find("has no partner") != std::string::npos);
      CHECK(m.find("parallel faces") != std::string::npos);
    }
  }
  const auto drawings = sweep();
  SUBCASE("an arc with no partner: reported, and the skeleton says its lines dangle") {
    bool tried = false;
    for (const auto& s : drawings) {
      for (const auto& t : s.rounds) {
        if (t.arcs.size() != 2 || tried) continue;
        tried = true;
        auto d = s.drawing;
        const std::uint32_t keep = t.arcs[1];
        d.arcs.erase(d.arcs.begin() + t.arcs[0]);
        const std::uint32_t left = keep > t.arcs[0] ? keep - 1 : keep;
        const auto p = cellforge::pair_arcs(d);
        CHECK(p.pairs.size() == s.rounds.size() - 1);
        CHECK(p.unpaired == std::vector<std::uint32_t>{left});
        bool said = false;
        for (const auto& m : p.diagnostics) said = said || m.find("arc " + std::to_string(left)) == 0;
        CHECK(said);
        const auto r = cellforge::round_skeleton(d);
        CHECK_FALSE(r.validation.ok());
        CHECK(r.validation.defect == cellforge::drawing_defect::dangling_junction);
        CHECK(r.blends.size() == s.rounds.size() - 1);
      }
    }
    CHECK(tried);
  }
  SUBCASE("a zero-radius arc is refused with a sentence") {
    auto d = drawings[0].drawing;
    d.arcs[0].curve.rx = 0;
    bool threw = false;
    try {
      (void)cellforge::pair_arcs(d);
    } catch (const cellforge::error& e) {
      threw = true;
      CHECK(e.category() == cellforge::error_category::invalid_input);
      CHECK(std::string(e.what()).find("radius") != std::string::npos);
    }
    CHECK(threw);
    CHECK_THROWS_AS(cellforge::round_skeleton(d), cellforge::error);
  }
  SUBCASE("a line off an arc's interior that joins no second arc is no contour line") {
    bool tried = false;
    for (const auto& s : drawings)
      for (const auto& t : s.rounds) {
        if (t.contour == cellforge::samples::round_truth::npos || tried) continue;
        tried = true;
        auto d = s.drawing;
        const auto ln = d.lines.edges[t.contour];
        // Move the contour line's second end off the arc: a new junction of its own.
        d.lines.points.push_back(d.lines.points[ln[1]] * 1.01);
        d.lines.edges[t.contour][1] = static_cast<std::uint32_t>(d.lines.points.size() - 1);
        const auto p = cellforge::pair_arcs(d);
        bool said = false;
        for (const auto& m : p.diagnostics) said = said || m.find("not a contour line") != std::string::npos;
        CHECK(said);
      }
    CHECK(tried);
  }
}

TEST_CASE("round skeleton: a user point type (float arrays)") {
  const auto drawings = sweep();
  const auto& s = drawings[3];
  using F = std::array<float, 2>;
  cellforge::arc_drawing<F> d;
  for (const auto& p : s.drawing.lines.points) d.lines.points.push_back({float(p.x), float(p.y)});
  d.lines.edges = s.drawing.lines.edges;
  for (const auto& a : s.drawing.arcs)
    d.arcs.push_back({a.ends,
                      {F{float(a.curve.centre.x), float(a.curve.centre.y)}, a.curve.rx, a.curve.ry,
                       a.curve.rotation, a.curve.start, a.curve.sweep}});
  cellforge::round_skeleton_options o;
  const auto r = cellforge::round_skeleton(d, o);
  INFO(s.name);
  CHECK(r.pairing.unpaired.empty());
  CHECK(r.blends.size() == s.rounds.size());
  CHECK(r.skeleton.edges.size() == s.skeleton.drawing.edges.size());
  CHECK(r.validation.ok());
}

}  // namespace round_skeleton_tests
