// Face finding on line drawings (sketch/face_finder.hpp): the Varley–Company string algorithm
// and the shortest-loops baseline on drawings of models with known faces, the check of every
// answer, flagged answers with alternatives, bad drawings, a user's own drawing type, budgets.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cellforge/samples/drawings.hpp"
#include "cellforge/sketch/face_finder.hpp"

// The pieces this file tests, named (its page above includes them).
#include "cellforge/sketch/detail/face_finder_impl.hpp"

namespace {

using loops_t = std::vector<std::vector<std::uint32_t>>;

// Loops as a multiset of canonical cycles (orientation and start free). O(Σ L log L).
std::multiset<std::vector<std::uint32_t>> canonical(const loops_t& loops) {
  std::multiset<std::vector<std::uint32_t>> s;
  for (const auto& l : loops) s.insert(cellforge::detail::canonical_cycle(l));
  return s;
}

bool same_loops(const loops_t& a, const loops_t& b) { return canonical(a) == canonical(b); }

// Every directed junction pair of the answer is used once: each edge's two half-edges lie on
// two loops, in opposite directions (the answer is an oriented surface). O(Σ L).
bool half_edges_once(const loops_t& loops) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> used;
  for (const auto& l : loops)
    for (std::size_t k = 0; k < l.size(); ++k)
      if (++used[{l[k], l[(k + 1) % l.size()]}] > 1) return false;
  return true;
}

std::vector<cellforge::samples::sample_model> classic_models() {
  using namespace cellforge;
  using namespace cellforge::samples;
  return {sample_tetrahedron(),
          sample_cube(),
          sample_octahedron(),
          sample_prism(3),
          sample_prism(5),
          sample_prism(12),
          sample_pyramid(4),
          sample_pyramid(9),
          sample_L(),
          sample_T(),
          sample_U(),
          sample_house(),
          sample_block_with_hole(),
          sample_frame(),
          sample_split_edges(),
          sample_uv_sphere(8, 5)};
}

}  // namespace

TEST_CASE("find_faces: Varley-Company returns exactly the true loops on drawings of classic solids") {
  std::size_t drawings = 0, vc_right = 0, baseline_right = 0;
  std::vector<std::string> misses;
  for (const auto& m : classic_models())
    for (std::uint64_t view = 1; view <= 4; ++view) {
      const cellforge::samples::sample_drawing s = cellforge::samples::generic_drawing(m, view, "classic");
      ++drawings;
      const auto r = cellforge::find_faces(s.drawing);
      CHECK(half_edges_once(r.loops));
      if (same_loops(r.loops, s.loops)) {
        ++vc_right;
        CHECK(r.check.ok());
        CHECK_FALSE(r.flagged);
        CHECK(r.check.edges_on_two_loops == s.drawing.edges.size());
      } else {
        misses.push_back(s.name);
      }
      cellforge::face_finder_options base;
      base.kind = cellforge::face_finder_kind::shortest_loops;
      base.walls = false;  // the baseline alone (the wall search repairs some of its answers)
      baseline_right += same_loops(cellforge::find_faces(s.drawing, base).loops, s.loops);
    }
  for (const auto& n : misses) MESSAGE("Varley-Company miss: " << n);
  MESSAGE("classic drawings: Varley-Company " << vc_right << "/" << drawings << ", shortest loops "
                                              << baseline_right << "/" << drawings);
  CHECK(vc_right == drawings);
  CHECK(baseline_right < drawings);  // the baseline's known failures (a loop taken twice, long loops)
}

TEST_CASE("find_faces: counts, the Euler check, and the stages it used") {
  const auto s = cellforge::samples::generic_drawing(cellforge::samples::sample_prism(6), 3, "prism");
  const auto r = cellforge::find_faces(s.drawing);
  CHECK(r.junctions == 12);
  CHECK(r.edges == 18);
  CHECK(r.loops.size() == 8);
  CHECK(r.check.euler == 2);
  CHECK(r.check.euler_sphere == 2);
  CHECK(r.forced > 0);  // a prism is read mostly by forced concatenations
  CHECK(r.work > 0);
  CHECK(r.milliseconds >= 0.0);
  CHECK(r.diagnostics.empty());
  // A genus-1 block with a through hole: V - E + L is still 2 (the hole's two loops).
  const auto h = cellforge::find_faces(
      cellforge::samples::generic_drawing(cellforge::samples::sample_block_with_hole(), 2, "slot").drawing);
  CHECK(h.check.ok());
  CHECK(h.check.euler == h.check.euler_sphere);
}

TEST_CASE("find_faces: an answer that fails its check comes back flagged with ranked alternatives") {
  // A cube with one extra edge hanging off a corner: that edge can be on no loop.
  auto s = cellforge::samples::generic_drawing(cellforge::samples::sample_cube(), 1, "cube");
  const glm::dvec2 far = s.drawing.points[0] + glm::dvec2(0.37, -0.21);
  s.drawing.points.push_back(far);
  s.drawing.edges.push_back({0, static_cast<std::uint32_t>(s.drawing.points.size() - 1)});
  const auto r = cellforge::find_faces(s.drawing);
  CHECK(r.flagged);
  CHECK_FALSE(r.check.ok());
  REQUIRE_FALSE(r.check.edges_with_fewer_loops.empty());
  CHECK(std::find(r.check.edges_with_fewer_loops.begin(), r.check.edges_with_fewer_loops.end(), 12u) !=
        r.check.edges_with_fewer_loops.end());
  REQUIRE_FALSE(r.diagnostics.empty());
  CHECK(std::any_of(r.diagnostics.begin(), r.diagnostics.end(), [](const std::string& d) {
    return d.find("fewer than two loops") != std::string::npos;
  }));
  REQUIRE(r.alternatives.size() >= 2);
  for (const auto& a : r.alternatives) CHECK_FALSE(a.reason.empty());
  // Ranked: an alternative that passes never comes after one that fails.
  for (std::size_t k = 1; k < r.alternatives.size(); ++k)
    CHECK((r.alternatives[k - 1].check.ok() || !r.alternatives[k].check.ok()));
  // A tree has no closed loop at all.
  cellforge::line_drawing<glm::dvec2> tree;
  tree.points = {{0, 0}, {1, 0}, {0, 1}, {-1, -1}};
  tree.edges = {{0, 1}, {0, 2}, {0, 3}};
  const auto t = cellforge::find_faces(tree);
  CHECK(t.loops.empty());
  CHECK(t.flagged);
  CHECK(std::any_of(t.diagnostics.begin(), t.diagnostics.end(),
                    [](const std::string& d) { return d.find("no closed loop") != std::string::npos; }));
}

TEST_CASE("find_faces: malformed drawings are refused with a clear error") {
  using cellforge::error;
  cellforge::line_drawing<glm::dvec2> d;
  CHECK_THROWS_AS(cellforge::find_faces(d), error);  // no edge
  d.points = {{0, 0}, {1, 0}, {std::nan(""), 1}};
  d.edges = {{0, 1}, {1, 2}, {2, 0}};
  CHECK_THROWS_WITH_AS(cellforge::find_faces(d), doctest::Contains("NaN"), error);
  d.points[2] = {0, 1};
  d.edges.push_back({1, 1});
  CHECK_THROWS_WITH_AS(cellforge::find_faces(d), doctest::Contains("to itself"), error);
  d.edges.back() = {1, 7};
  CHECK_THROWS_WITH_AS(cellforge::find_faces(d), doctest::Contains("does not exist"), error);
}

TEST_CASE("find_faces: a budget that stops the last fallback too: no loops, flagged, the option named") {
  const auto s = cellforge::samples::generic_drawing(cellforge::samples::sample_uv_sphere(8, 5), 1, "sphere");
  for (const auto kind :
       {cellforge::face_finder_kind::varley_company, cellforge::face_finder_kind::shortest_loops}) {
    CAPTURE(static_cast<int>(kind));
    cellforge::face_finder_options o;
    o.kind = kind;
    o.work_budget = 50;
    const auto r = cellforge::find_faces(s.drawing, o);
    CHECK_FALSE(r.complete);
    CHECK(r.flagged);
    CHECK(r.budget_fallback);
    CHECK(r.loops.empty());
    CHECK_FALSE(r.check.ok());
    CHECK(r.work > 50);
    const bool named = std::any_of(r.diagnostics.begin(), r.diagnostics.end(), [](const std::string& d) {
      return d.find(
                 "find_faces: work budget of 50 steps exhausted; raise face_finder_options::work_budget") !=
             std::string::npos;
    });
    CHECK(named);
  }
}

namespace user {
struct pt {
  float u, v;
};
// A user's drawing: strokes as pairs of junction names, positions elsewhere.
struct sketch {
  std::vector<pt> where;
  std::vector<std::pair<int, int>> strokes;
};
}  // namespace user
CELLFORGE_REGISTER_POINT2(user::pt, float, u, v);
template <>
struct cellforge::line_drawing_traits<user::sketch> {
  using point_type = user::pt;
  static std::size_t num_junctions(const user::sketch& s) { return s.where.size(); }
  static user::pt position(const user::sketch& s, std::size_t i) { return s.where[i]; }
  static std::size_t num_edges(const user::sketch& s) { return s.strokes.size(); }
  static std::array<std::size_t, 2> endpoints(const user::sketch& s, std::size_t e) {
    return {static_cast<std::size_t>(s.strokes[e].first), static_cast<std::size_t>(s.strokes[e].second)};
  }
};

TEST_CASE("find_faces: a user's own drawing type and float points") {
  static_assert(cellforge::LineDrawing<user::sketch>);
  const auto s = cellforge::samples::generic_drawing(cellforge::samples::sample_prism(4), 5, "prism");
  user::sketch u;
  for (const auto& p : s.drawing.points)
    u.where.push_back({static_cast<float>(p.x), static_cast<float>(p.y)});
  for (const auto& e : s.drawing.edges) u.strokes.push_back({static_cast<int>(e[0]), static_cast<int>(e[1])});
  const auto r = cellforge::find_faces(u);
  CHECK(same_loops(r.loops, s.loops));
  CHECK_FALSE(r.flagged);
}

// Whether every edge of a drawing's truth lies on exactly two loops (one solid, no walls).
bool two_per_edge(const cellforge::samples::sample_drawing& s) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& l : s.loops)
    for (std::size_t k = 0; k < l.size(); ++k)
      ++uses[{std::min(l[k], l[(k + 1) % l.size()]), std::max(l[k], l[(k + 1) % l.size()])}];
  return std::all_of(uses.begin(), uses.end(), [](const auto& u) { return u.second == 2; });
}

TEST_CASE("find_faces: the generated sweep — exact or flagged, none silently wrong") {
  // Release: the whole sweep (>= 2,000 drawings up to 300 edges, 19 families, one solid or
  // several volumes); the sanitizer build a sample of every family (the same drawings).
  cellforge::samples::sketch_sweep_options options;
#ifndef NDEBUG
  options.limit = 120;
#endif
  const auto sweep = cellforge::samples::sketch_sweep(options);
#ifdef NDEBUG
  CHECK(sweep.size() >= 2000);
#endif
  struct tally {
    std::size_t drawings = 0, vc = 0, baseline = 0, flagged = 0, max_edges = 0;
  };
  std::map<std::string, tally> family;
  tally two, more;  // drawings whose every edge has two faces, and the rest
  std::size_t silent = 0;
  std::vector<std::string> misses;
  double slowest = 0;
  std::string slowest_name;
  for (const auto& s : sweep) {
    const auto r = cellforge::find_faces(s.drawing);
    cellforge::face_finder_options base;
    base.kind = cellforge::face_finder_kind::shortest_loops;
    base.alternatives_when_flagged = false;
    base.walls = false;
    const bool right = same_loops(r.loops, s.loops);
    const bool base_right = same_loops(cellforge::find_faces(s.drawing, base).loops, s.loops);
    for (tally* t : {&family[s.family], two_per_edge(s) ? &two : &more}) {
      ++t->drawings, t->vc += right, t->baseline += base_right, t->flagged += r.flagged;
      t->max_edges = std::max(t->max_edges, s.drawing.edges.size());
    }
    if (r.milliseconds > slowest) slowest = r.milliseconds, slowest_name = s.name;
    if (!right) {
      misses.push_back(s.name + (r.flagged ? " (flagged: " + r.diagnostics.front() + ")" : " (NOT flagged)"));
      silent += !r.flagged;
    }
  }
  for (const auto& [name, t] : family)
    MESSAGE(name << ": " << t.drawings << " drawings up to " << t.max_edges << " edges, exact " << t.vc
                 << ", flagged " << t.flagged << ", shortest loops " << t.baseline);
  for (const auto& m : misses) MESSAGE("miss: " << m);
  const auto pct = [](std::size_t a, std::size_t b) {
    return 100.0 * static_cast<double>(a) / static_cast<double>(b);
  };
  MESSAGE("sweep: " << sweep.size() << " drawings; two faces per edge: exact " << two.vc << " of "
                    << two.drawings << " (" << pct(two.vc, two.drawings) << " %); several: exact " << more.vc
                    << " of " << more.drawings << " (" << pct(more.vc, more.drawings) << " %); misses "
                    << misses.size() << ", silently wrong " << silent << "; shortest loops exact on "
                    << two.baseline + more.baseline << "; slowest " << slowest << " ms (" << slowest_name
                    << ")");
  CHECK(silent == 0);
  CHECK(100 * two.vc >= 99 * two.drawings);
  CHECK(100 * more.vc >= 95 * more.drawings);
  CHECK(more.drawings * 5 >= sweep.size());  // the families of several volumes are a fifth at least
  CHECK(family.size() == cellforge::samples::sketch_sweep_families().size());
}

TEST_CASE("find_faces: internal walls, solids along an edge and a roof's square are found in 2D") {
  using cellforge::find_faces;
  struct expect {
    cellforge::samples::sample_model model;
    std::size_t most_loops_on_an_edge;
  };
  cellforge::samples::voxel_layout row = cellforge::samples::empty_layout({0, 1.3, 2.1}, {0, 1}, {0, 0.8});
  row.labels = {1, 2};
  const std::vector<expect> cases{
      {cellforge::samples::make_voxel_model(row, "row of two boxes"), 3},
      {cellforge::samples::sample_grid(2, 2, 1), 4},
      {*cellforge::samples::sliced_polytope(0, 0, true, 3), 3},
      {cellforge::samples::roof_on_box(0, 5), 3},
      {cellforge::samples::touching_solids(0, 2), 4},
      {cellforge::samples::touching_solids(3, 2), 2},
      {cellforge::samples::bar_frame(1, 4), 4}};  // a corner block of its own: four bars meet at its edges
  for (const auto& c : cases)
    for (std::uint64_t view = 1; view <= 3; ++view) {
      const auto s = cellforge::samples::generic_drawing(c.model, view, "walls");
      CAPTURE(s.name);
      const auto r = find_faces(s.drawing);
      CHECK(same_loops(r.loops, s.loops));
      CHECK_FALSE(r.flagged);
      CHECK(r.check.ok());
      std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> uses;
      for (const auto& l : r.loops)
        for (std::size_t k = 0; k < l.size(); ++k)
          ++uses[{std::min(l[k], l[(k + 1) % l.size()]), std::max(l[k], l[(k + 1) % l.size()])}];
      std::size_t most = 0;
      for (const auto& [e, n] : uses) most = std::max(most, n);
      CHECK(most == c.most_loops_on_an_edge);
      // Without the wall search the string algorithm's answer misses faces, and its check says so
      // (the silent answers: the outer boundary alone, seams no wall meets).
      cellforge::face_finder_options plain;
      plain.walls = false;
      const auto p = find_faces(s.drawing, plain);
      if (!same_loops(p.loops, s.loops)) CHECK((p.flagged || c.model.name.find("roof") != std::string::npos));
    }
}

TEST_CASE("find_faces: the check names seams, shared corners and loops a line in their plane enters") {
  // A row of two boxes without its wall: four edges on two coplanar loops each.
  cellforge::samples::voxel_layout row = cellforge::samples::empty_layout({0, 1.3, 2.1}, {0, 1}, {0, 0.8});
  row.labels = {1, 2};
  const auto s =
      cellforge::samples::generic_drawing(cellforge::samples::make_voxel_model(row, "row"), 2, "walls");
  loops_t outer;
  for (const auto& l : s.loops) {
    std::size_t inner = 0;  // the wall's junctions lie at x = 1.3
    for (const auto v : l) inner += std::abs(s.model.wire.points[v].x - 1.3) < 1e-12;
    if (inner < l.size()) outer.push_back(l);
  }
  REQUIRE(outer.size() + 1 == s.loops.size());
  const auto g = cellforge::detail::faces::make_graph(s.drawing, {});
  const auto c = cellforge::detail::faces::check_loops(g, outer);
  CHECK(c.seam_edges.size() == 4);
  CHECK_FALSE(c.ok());
  CHECK(c.edges_with_fewer_loops.empty());
  // The same loop twice turns the same corners.
  loops_t twice = s.loops;
  twice.push_back(s.loops.front());
  CHECK_FALSE(cellforge::detail::faces::check_loops(g, twice).rule_breaking_loops.empty());
  // The truth passes.
  CHECK(cellforge::detail::faces::check_loops(g, s.loops).ok());
}

TEST_CASE("find_faces: out of budget, the baseline answers, flagged") {
  const auto s = cellforge::samples::generic_drawing(cellforge::samples::sample_uv_sphere(8, 5), 1, "sphere");
  cellforge::face_finder_options full;
  full.walls = false;
  const auto vc = cellforge::find_faces(s.drawing, full);
  cellforge::face_finder_options base = full;
  base.kind = cellforge::face_finder_kind::shortest_loops;
  const auto bl = cellforge::find_faces(s.drawing, base);
  REQUIRE(bl.work < vc.work);
  cellforge::face_finder_options tight = full;
  tight.work_budget = (bl.work + vc.work) / 2;
  const auto r = cellforge::find_faces(s.drawing, tight);
  CHECK(r.budget_fallback);
  CHECK(r.flagged);
  CHECK_FALSE(r.complete);
  CHECK(same_loops(r.loops, bl.loops));
  CHECK(std::any_of(r.diagnostics.begin(), r.diagnostics.end(), [](const std::string& d) {
    return d.find("baseline answers instead") != std::string::npos;
  }));
}
