// SPDX-License-Identifier: MIT
// Inflation (sketch/inflation.hpp) on sample drawings with ground truth: the direct method
// recovers normalon and quasi-normalon drawings exactly (up to the Necker mirror and a depth
// offset) and the wireframe pipeline then finds the model's faces and volumes; optimisation
// gives the true cell complex on most non-normalon drawings (rate and median angle error
// printed, every miss named); user point types; bad drawings and loops.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/samples/drawings.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/sketch/inflation.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

// The pieces this file tests, named (its page above includes them).
#include "cellforge/sketch/detail/inflation_impl.hpp"

namespace inflation_test {
struct pen_point {  // a user's 2D type
  double u = 0, v = 0;
};
struct solid_point {  // and its 3D counterpart
  double u = 0, v = 0, w = 0;
};
}  // namespace inflation_test
CELLFORGE_REGISTER_POINT2(inflation_test::pen_point, double, u, v);
CELLFORGE_REGISTER_POINT3(inflation_test::solid_point, double, u, v, w);
template <>
struct cellforge::lifted_point<inflation_test::pen_point> {
  using type = inflation_test::solid_point;
};

namespace {

using cellforge::samples::sample_drawing;
using cellforge::samples::sample_model;

// Views per model: more in Release, fewer under the sanitizers (10-50x slower).
#ifdef NDEBUG
constexpr std::uint64_t views = 6;
constexpr std::uint64_t heavy_views = 6;
#else
constexpr std::uint64_t views = 2;
constexpr std::uint64_t heavy_views = 1;  // the direct and optimised sweeps: one view each
#endif

// A model from points, edges, faces (one loop each) and one volume of all faces. O(size).
sample_model hand_model(std::string name, std::vector<glm::dvec3> pts,
                        std::vector<std::array<std::uint32_t, 2>> edges,
                        std::vector<std::vector<std::uint32_t>> faces) {
  sample_model m;
  m.name = std::move(name);
  m.wire.points = std::move(pts);
  m.wire.edges = std::move(edges);
  std::vector<std::uint32_t> all;
  for (const auto& f : faces) {
    all.push_back(static_cast<std::uint32_t>(m.faces.size()));
    m.faces.push_back({f});
  }
  m.volumes = {all};
  return m;
}

// A box with one edge chamfered (10 junctions, 15 lines, 7 faces). O(1).
sample_model chamfered_block() {
  return hand_model("chamfered block",
                    {{0, 0, 0},
                     {2, 0, 0},
                     {2, 1, 0},
                     {0, 1, 0},
                     {0, 0, 1},
                     {0, 1, 1},
                     {1.5, 0, 1},
                     {1.5, 1, 1},
                     {2, 0, 0.5},
                     {2, 1, 0.5}},
                    {{0, 1},
                     {1, 2},
                     {2, 3},
                     {3, 0},
                     {0, 4},
                     {3, 5},
                     {1, 8},
                     {2, 9},
                     {4, 6},
                     {5, 7},
                     {4, 5},
                     {6, 7},
                     {8, 9},
                     {6, 8},
                     {7, 9}},
                    {{0, 1, 2, 3},
                     {0, 3, 5, 4},
                     {0, 1, 8, 6, 4},
                     {3, 2, 9, 7, 5},
                     {4, 6, 7, 5},
                     {1, 2, 9, 8},
                     {6, 8, 9, 7}});
}

// A right-angled wedge (triangular prism). O(1).
sample_model wedge() {
  return hand_model("wedge", {{0, 0, 0}, {1.5, 0, 0}, {0, 0, 1}, {0, 2, 0}, {1.5, 2, 0}, {0, 2, 1}},
                    {{0, 1}, {0, 2}, {1, 2}, {3, 4}, {3, 5}, {4, 5}, {0, 3}, {1, 4}, {2, 5}},
                    {{0, 1, 2}, {3, 4, 5}, {0, 1, 4, 3}, {0, 2, 5, 3}, {1, 2, 5, 4}});
}

// A box with a sloped top (a ramp). O(1).
sample_model ramp() {
  return hand_model(
      "ramp", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 1}, {1, 0, 0.4}, {1, 1, 0.4}},
      {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {3, 5}, {1, 6}, {2, 7}, {4, 5}, {6, 7}, {4, 6}, {5, 7}},
      {{0, 1, 2, 3}, {0, 3, 5, 4}, {1, 2, 7, 6}, {0, 1, 6, 4}, {3, 2, 7, 5}, {4, 6, 7, 5}});
}

// A gable house: box and roof in one, the gable ends pentagons. The ridge is an axis line
// joined to the box only by oblique lines; its depth comes from the gables' planarity. O(1).
sample_model gable_house() {
  return hand_model("gable house",
                    {{0, 0, 0},
                     {2, 0, 0},
                     {2, 1, 0},
                     {0, 1, 0},
                     {0, 0, 1},
                     {2, 0, 1},
                     {2, 1, 1},
                     {0, 1, 1},
                     {0, 0.5, 1.6},
                     {2, 0.5, 1.6}},
                    {{0, 1},
                     {1, 2},
                     {2, 3},
                     {3, 0},
                     {0, 4},
                     {1, 5},
                     {2, 6},
                     {3, 7},
                     {4, 5},
                     {7, 6},
                     {8, 9},
                     {4, 8},
                     {7, 8},
                     {5, 9},
                     {6, 9}},
                    {{0, 1, 2, 3},
                     {0, 1, 5, 4},
                     {3, 2, 6, 7},
                     {0, 3, 7, 8, 4},
                     {1, 2, 6, 9, 5},
                     {4, 5, 9, 8},
                     {7, 6, 9, 8}});
}

// A box with a hip roof: the ridge height is free (the roof's pitch is not in the drawing's
// planarity), so it is no direct case; optimisation reads it. O(1).
sample_model hip_roof() {
  return hand_model("hip roof",
                    {{0, 0, 0},
                     {2, 0, 0},
                     {2, 1, 0},
                     {0, 1, 0},
                     {0, 0, 1},
                     {2, 0, 1},
                     {2, 1, 1},
                     {0, 1, 1},
                     {0.5, 0.5, 1.5},
                     {1.5, 0.5, 1.5}},
                    {{0, 1},
                     {1, 2},
                     {2, 3},
                     {3, 0},
                     {4, 5},
                     {5, 6},
                     {6, 7},
                     {7, 4},
                     {0, 4},
                     {1, 5},
                     {2, 6},
                     {3, 7},
                     {8, 9},
                     {4, 8},
                     {7, 8},
                     {5, 9},
                     {6, 9}},
                    {{0, 1, 2, 3},
                     {0, 1, 5, 4},
                     {1, 2, 6, 5},
                     {2, 3, 7, 6},
                     {3, 0, 4, 7},
                     {4, 5, 9, 8},
                     {7, 6, 9, 8},
                     {4, 8, 7},
                     {5, 6, 9}});
}

// Normalons: boxes, blocks, stairs, holes, random height fields (skipped when a face outline
// touches itself, which make_voxel_model refuses, or when the wireframe pipeline does not certify
// even the true wireframe as a solid: two cells touching along an edge only). O(models).
std::vector<sample_model> normalons() {
  std::vector<sample_model> out{cellforge::samples::sample_cube(),
                                cellforge::samples::sample_cube({3, 1, 0.4}),
                                cellforge::samples::sample_L(),
                                cellforge::samples::sample_T(),
                                cellforge::samples::sample_U(),
                                cellforge::samples::sample_frame(),
                                cellforge::samples::sample_block_with_hole(),
                                cellforge::samples::sample_two_cubes(),
                                cellforge::samples::sample_stepped_block()};
  {  // a comb of 8 teeth: 102 lines, the size of the 50 ms goal
    std::vector<double> xs;
    for (int i = 0; i <= 16; ++i) xs.push_back(0.5 * i);
    std::vector<std::array<std::size_t, 2>> cells;
    for (std::size_t i = 0; i < 16; ++i) cells.push_back({i, 0});
    for (std::size_t t = 0; t < 8; ++t) cells.push_back({2 * t, 1});
    out.push_back(cellforge::samples::detail::extruded_footprint(xs, {0, 1, 2.2}, cells, "comb"));
  }
  {
    cellforge::samples::voxel_layout l =
        cellforge::samples::empty_layout({0, 1, 2, 3}, {0, 1.5}, {0, 1, 2, 3});
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t k = 0; k <= i; ++k) l.at(i, 0, k) = 1;
    out.push_back(cellforge::samples::make_voxel_model(l, "stairs"));
  }
  cellforge::detail::splitmix rng{7};
  for (int attempt = 0, made = 0; attempt < 40 && made < 4; ++attempt) {
    cellforge::samples::voxel_layout l =
        cellforge::samples::empty_layout({0, 1, 2.5, 3, 4}, {0, 1, 2, 3.5, 4}, {0, 1, 2, 3});
    for (std::size_t i = 0; i < 4; ++i)
      for (std::size_t j = 0; j < 4; ++j) {
        const auto h = static_cast<std::size_t>(rng.uniform(1, 3.999));
        for (std::size_t k = 0; k < h; ++k) l.at(i, j, k) = 1;
      }
    try {
      sample_model m = cellforge::samples::make_voxel_model(l, "height field " + std::to_string(attempt));
      // Only fields whose true wireframe the 3D pipeline certifies as a solid: columns touching
      // along an edge only make a volume that uses the edge four times (not a 2-manifold).
      if (cellforge::wireframe_to_cells(m.wire).status != cellforge::solid_status::solid) continue;
      out.push_back(std::move(m));
      ++made;
    } catch (const cellforge::error&) {
    }
  }
  return out;
}

std::vector<sample_model> quasi_normalons() { return {wedge(), ramp(), chamfered_block(), gable_house()}; }

std::vector<sample_model> non_normalons() {
  cellforge::samples::ring_stack frustum;
  frustum.n = 5;
  frustum.radius = {1.0, 0.55};
  frustum.height = {0.0, 0.8};
  cellforge::samples::ring_stack antiprism;  // a pentagonal antiprism: triangles between two turned caps
  antiprism.n = 5;
  antiprism.radius = {1.0, 1.0};
  antiprism.height = {0.0, 0.9};
  antiprism.twist = {0.0, std::numbers::pi / 5};
  antiprism.triangles = true;
  cellforge::samples::ring_stack bipyramid;  // a hexagonal bipyramid: apexes of degree 6, no planar quad
  bipyramid.n = 6;
  bipyramid.radius = {1.0};
  bipyramid.height = {0.0};
  bipyramid.bottom = -1.2;
  bipyramid.top = 0.9;
  return {cellforge::samples::make_ring_stack(antiprism, "antiprism 5"),
          cellforge::samples::make_ring_stack(bipyramid, "bipyramid 6"),
          cellforge::samples::sample_tetrahedron(),
          cellforge::samples::sample_octahedron(),
          cellforge::samples::sample_prism(3),
          cellforge::samples::sample_prism(5),
          cellforge::samples::sample_prism(6),
          cellforge::samples::sample_prism(8),
          cellforge::samples::sample_pyramid(3),
          cellforge::samples::sample_pyramid(4),
          cellforge::samples::sample_pyramid(5),
          cellforge::samples::sample_pyramid(6),
          cellforge::samples::sample_house(),
          cellforge::samples::make_ring_stack(frustum, "frustum 5"),
          hip_roof()};
}

// Largest depth error of z against the truth, both centred, relative to the model's size. O(V).
double depth_error(const sample_drawing& s, const std::vector<glm::dvec3>& pts) {
  double mt = 0, mz = 0;
  glm::dvec3 lo = s.points[0], hi = s.points[0];
  for (std::size_t i = 0; i < pts.size(); ++i) {
    mt += s.points[i].z, mz += pts[i].z;
    lo = glm::min(lo, s.points[i]), hi = glm::max(hi, s.points[i]);
  }
  mt /= static_cast<double>(pts.size()), mz /= static_cast<double>(pts.size());
  double worst = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    worst = std::max(worst, std::abs((pts[i].z - mz) - (s.points[i].z - mt)));
    // x, y are the drawing's, exactly.
    worst = std::max(worst, std::abs(pts[i].x - s.points[i].x) + std::abs(pts[i].y - s.points[i].y));
  }
  return worst / glm::length(hi - lo);
}

// Regularities (right face corners, equal consecutive corners and sides) the true reading holds,
// counted as inflate counts them for its own readings (default tolerances). O(L).
std::size_t truth_regularities(const sample_drawing& s) {
  const auto pr = cellforge::detail::make_inflation_problem(s.drawing, s.model.faces);
  std::vector<double> z;
  for (const auto& p : s.points) z.push_back(p.z / pr.size);
  return cellforge::detail::held_relations(pr, cellforge::detail::make_regularity_terms(pr), z, 100 * 1e-8);
}

// Whether the wireframe pipeline finds the model's faces and volumes in these points. O(pipeline).
bool true_cells(const sample_drawing& s, const std::vector<glm::dvec3>& pts, std::string& why) {
  cellforge::wireframe<glm::dvec3> w;
  w.points = pts;
  w.edges = s.drawing.edges;
  try {
    const auto r = cellforge::wireframe_to_cells(w);
    std::vector<std::vector<std::vector<std::uint32_t>>> faces;
    for (const auto& f : r.input.faces) {
      auto loops = f.loops;
      for (auto& l : loops)
        for (auto& v : l) v = r.input_vertex[v];
      faces.push_back(std::move(loops));
    }
    if (!cellforge::samples::same_faces(s.model.faces, faces)) {
      why = std::to_string(faces.size()) + " faces instead of " + std::to_string(s.model.faces.size());
      return false;
    }
    if (!cellforge::samples::same_volumes(s.model.faces, s.model.volumes, faces, r.input.volumes)) {
      why = std::to_string(r.input.volumes.size()) + " volumes instead of " +
            std::to_string(s.model.volumes.size());
      return false;
    }
    return true;
  } catch (const cellforge::error& e) {
    why = e.what();
    return false;
  }
}

// Face-corner angles (degrees) of points at the truth's loops. O(L).
std::vector<double> corner_angles(const sample_drawing& s, const std::vector<glm::dvec3>& pts) {
  std::vector<double> out;
  for (const auto& loop : s.loops)
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const glm::dvec3 q = pts[loop[k]], a = pts[loop[(k + loop.size() - 1) % loop.size()]] - q,
                       b = pts[loop[(k + 1) % loop.size()]] - q;
      out.push_back(std::acos(std::clamp(glm::dot(a, b) / (glm::length(a) * glm::length(b)), -1.0, 1.0)) *
                    180 / std::numbers::pi);
    }
  return out;
}

}  // namespace

TEST_CASE("inflate: direct recovers normalon and quasi-normalon drawings exactly, and their cell complex") {
  std::size_t drawings = 0, first_right = 0, largest_edges = 0, ambiguous = 0;
  double worst = 0, largest_ms = 0;
  std::vector<sample_model> models = normalons();
  for (auto& m : quasi_normalons()) models.push_back(std::move(m));
  for (const auto& m : models)
    for (std::uint64_t view = 1; view <= heavy_views; ++view) {
      const sample_drawing s = cellforge::samples::generic_drawing(m, view, "direct");
      const std::string name = s.name;
      INFO(name);
      // The faces with their holes: a hole's own ring of edges is tied to its face's plane.
      const auto r = cellforge::inflate(s.drawing, s.model.faces);
      static_assert(std::is_same_v<decltype(r.points)::value_type, glm::dvec3>);
      if (r.method != cellforge::inflation_method::direct) {
        // A wedge or a ramp has as many oblique lines as one axis has: a second choice of axes
        // reads as well, or a reading of the planar family holds more regularities than the
        // right-angled one (a wedge read as a prism on an equilateral triangle). Either way the
        // cells are the model's, and a reading that is not the truth is at least as regular.
        REQUIRE((m.name == "wedge" || m.name == "ramp"));
        std::string why;
        CHECK_MESSAGE(true_cells(s, r.points, why), why);
        if (std::min(depth_error(s, r.readings[0].points), depth_error(s, r.readings[1].points)) >= 1e-9)
          CHECK(r.regular_relations >= truth_regularities(s));
        ++ambiguous;
        continue;
      }
      REQUIRE(r.readings.size() == 2);
      CHECK(r.view_found);
      CHECK(r.after.planarity < 1e-12);
      const double e0 = depth_error(s, r.readings[0].points), e1 = depth_error(s, r.readings[1].points);
      CHECK(std::min(e0, e1) < 1e-9);
      worst = std::max(worst, std::min(e0, e1));
      first_right += e0 < e1;
      ++drawings;
      // The recovered foreshortenings are those of the true view (column lengths of its top rows).
      for (std::size_t i = 0; i < 3; ++i) {
        double best = 1;
        for (int a = 0; a < 3; ++a)
          best = std::min(best, std::abs(r.foreshortening[i] - std::hypot(s.view[a][0], s.view[a][1])));
        CHECK(best < 1e-9);
      }
      // The view rotation is a rotation.
      const auto& q = r.view_rotation;
      const double det = q[0] * (q[4] * q[8] - q[5] * q[7]) - q[1] * (q[3] * q[8] - q[5] * q[6]) +
                         q[2] * (q[3] * q[7] - q[4] * q[6]);
      CHECK(det == doctest::Approx(1.0).epsilon(1e-9));
      std::string why;
      CHECK_MESSAGE(true_cells(s, r.readings[0].points, why), why);
      CHECK_MESSAGE(true_cells(s, r.readings[1].points, why), why);
      if (s.drawing.edges.size() >= largest_edges)
        largest_edges = s.drawing.edges.size(), largest_ms = r.milliseconds;
    }
  MESSAGE("direct: "
          << drawings << " drawings, worst depth error " << worst
          << " of the model size; first reading right on " << first_right << " ("
          << 100.0 * static_cast<double>(first_right) / static_cast<double>(drawings)
          << " %; the views are random rotations, so the view-from-above prior can only be a coin toss)");
  MESSAGE("direct: " << ambiguous
                     << " wedge or ramp drawings read otherwise (axes ambiguous, or a more regular reading)");
  MESSAGE("direct: " << largest_edges << " edges in " << largest_ms << " ms (this build)");
}

// A view from above: the model turned by `azimuth` about its z axis (up), seen from
// `elevation` above the horizon, model z going up the picture. O(1).
glm::dmat3 view_from_above(double azimuth, double elevation) {
  const double ca = std::cos(azimuth), sa = std::sin(azimuth), ce = std::cos(elevation),
               se = std::sin(elevation);
  const glm::dmat3 turn(glm::dvec3(ca, sa, 0), glm::dvec3(-sa, ca, 0), glm::dvec3(0, 0, 1));  // columns
  const glm::dmat3 look(glm::dvec3(1, 0, 0), glm::dvec3(0, se, -ce), glm::dvec3(0, ce, se));
  return look * turn;
}

TEST_CASE("inflate: in views from above, the first reading is the true one") {
  std::size_t drawings = 0, direct_right = 0, direct_total = 0, optimised_right = 0, optimised_total = 0;
  std::string misses;
  cellforge::detail::splitmix rng{42};
  std::vector<sample_model> models = normalons();
  for (auto& m : quasi_normalons()) models.push_back(std::move(m));
  const std::size_t first_non_normalon = models.size();
#ifdef NDEBUG  // their optimised readings are only counted: 30 of this case's 40 s under ASan
  for (auto& m : non_normalons()) models.push_back(std::move(m));
#endif
  for (std::size_t index = 0; index < models.size(); ++index)
    for (std::uint64_t view = 1; view <= views; ++view) {
      const sample_model& m = models[index];
      const sample_drawing s = cellforge::samples::project_model(
          m, view_from_above(rng.uniform(0.2, 1.4), rng.uniform(0.3, 1.1)), m.name + ", from above", "above");
      if (cellforge::samples::generic_margin(s) < 2e-3) continue;
      const std::string name = s.name;
      INFO(name);
      const auto r = cellforge::inflate(s.drawing, s.model.faces);
      const double e0 = depth_error(s, r.readings[0].points), e1 = depth_error(s, r.readings[1].points);
      ++drawings;
      if (r.method == cellforge::inflation_method::direct && index < first_non_normalon) {
        ++direct_total;
        direct_right += e0 < e1;
        if (index < first_non_normalon) CHECK(e0 < 1e-9);  // a prism may read as a right one
      } else {
        ++optimised_total;
        optimised_right += e0 < e1;
        if (e0 >= e1) misses += "\n  " + s.name + ": " + r.readings[0].reason;
      }
    }
  MESSAGE("views from above: first reading right on " << direct_right << " of " << direct_total
                                                      << " direct and " << optimised_right << " of "
                                                      << optimised_total << " optimised drawings" << misses);
  CHECK(drawings > 20);
  // The prior is made for the normalon's up axis; optimised readings are only printed.
  CHECK(static_cast<double>(direct_right) >= 0.9 * static_cast<double>(direct_total));
}

TEST_CASE("inflate: a model's axes need not be the drawing's: a rotated normalon is still read directly") {
  // A cube turned about the view axis after projection is a normalon drawing in other directions.
  const sample_drawing s =
      cellforge::samples::generic_drawing(cellforge::samples::sample_L(), 11, "normalon");
  auto d = s.drawing;
  for (auto& p : d.points) p = {0.6 * p.x - 0.8 * p.y, 0.8 * p.x + 0.6 * p.y};
  const auto r = cellforge::inflate(d, s.loops);
  CHECK(r.method == cellforge::inflation_method::direct);
  CHECK(r.after.planarity < 1e-12);
}

TEST_CASE("inflate: a drawing 4e300 across has an extent (its size is not squared out of range)") {
  // Issue 35: the size was the length of the box's diagonal, whose square overflowed at 4e300,
  // and inflate said "the drawing has no extent". Scaled first, it reads as at scale 1.
  const sample_drawing s =
      cellforge::samples::generic_drawing(cellforge::samples::sample_L(), 11, "normalon");
  auto far = s.drawing;
  for (auto& p : far.points) p *= 4e300;
  const auto r = cellforge::inflate(s.drawing, s.loops), f = cellforge::inflate(far, s.loops);
  CHECK(f.method == r.method);
  REQUIRE(f.points.size() == r.points.size());
  double worst = 0;
  for (std::size_t i = 0; i < r.points.size(); ++i)
    worst = std::max(worst, glm::length(f.points[i] / 4e300 - r.points[i]));
  CHECK(worst < 1e-9);
}

TEST_CASE("inflate: optimisation gives the true cell complex on the non-normalon drawings") {
  std::size_t drawings = 0, right = 0, read_directly = 0;
  std::vector<double> errors;
  std::string misses;
  for (const auto& m : non_normalons())
    for (std::uint64_t view = 1; view <= heavy_views; ++view) {
      const sample_drawing s = cellforge::samples::generic_drawing(m, view, "non-normalon");
      const std::string name = s.name;
      INFO(name);
      const auto r = cellforge::inflate(s.drawing, s.loops);
      // A prism whose view admits one right-angled axis reading is read directly (as a right
      // prism): a valid reading of the same drawing; the cell complex is checked either way.
      read_directly += r.method == cellforge::inflation_method::direct;
      CHECK(r.after.planarity < 1e-12);
      CHECK(r.freedom >= 3);
      ++drawings;
      std::string why;
      if (true_cells(s, r.points, why))
        ++right;
      else
        misses += "\n  " + s.name + ": " + why;
      const auto truth = corner_angles(s, s.points), ours = corner_angles(s, r.points);
      for (std::size_t k = 0; k < truth.size(); ++k) errors.push_back(std::abs(truth[k] - ours[k]));
    }
  std::sort(errors.begin(), errors.end());
  const double rate = static_cast<double>(right) / static_cast<double>(drawings);
  MESSAGE("optimisation: true cell complex on " << right << " of " << drawings << " drawings (" << 100 * rate
                                                << " %); median face-corner angle error "
                                                << errors[errors.size() / 2] << " degrees; " << read_directly
                                                << " read directly" << misses);
  CHECK(rate >= 0.9);
}

TEST_CASE("inflate: random convex polytopes (all faces triangles) are read convex, the true cell complex") {
  // Every triangle is planar at any depths: planarity fixes nothing, and without the convexity
  // prior 3 of 120 such drawings came out right (docs/sketch.md, Inflation).
  cellforge::samples::sketch_sweep_options options;
  options.families = {"random convex"};
#ifdef NDEBUG
  options.limit = 12;
#else
  options.limit = 4;                      // Eigen unoptimised under the sanitizers
  options.max_edges = 60;
#endif
  const auto sweep = cellforge::samples::sketch_sweep(options);
  REQUIRE(sweep.size() >= 3);
  std::size_t right = 0, convex = 0;
  std::string misses;
  for (const auto& s : sweep) {
    INFO(s.name);
    // The sample's loops are orientation-free: inflate orients them coherently itself.
    const auto r = cellforge::inflate(s.drawing, s.loops);
    CHECK(r.method == cellforge::inflation_method::optimisation);
    CHECK(r.after.planarity < 1e-12);
    const bool prior = std::any_of(r.diagnostics.begin(), r.diagnostics.end(), [](const std::string& d) {
      return d.find("admit a convex reading") != std::string::npos;
    });
    convex += prior;
    CHECK(prior);
    std::string why;
    if (true_cells(s, r.points, why))
      ++right;
    else
      misses += "\n  " + s.name + ": " + why;
  }
  MESSAGE("random convex polytopes: true cell complex on "
          << right << " of " << sweep.size() << "; convexity prior used on " << convex << misses);
  CHECK(10 * right >= 9 * sweep.size());  // measured: every one in both samples
}

TEST_CASE("inflate: the face check: the main job must find the drawing's faces in a reading") {
  // The check a regular reading must pass: the true reading of a random polytope keeps its
  // triangles; so does one where two neighbouring triangles are coplanar (their line still
  // parts them); a flat reading does not.
  cellforge::samples::sketch_sweep_options options;
  options.families = {"random convex"};
  options.limit = 4;
  options.max_edges = 40;
  const auto sweep = cellforge::samples::sketch_sweep(options);
  REQUIRE(!sweep.empty());
  const sample_drawing& s = sweep.front();
  INFO(s.name);
  const auto pr = cellforge::detail::make_inflation_problem(s.drawing, s.model.faces);
  std::vector<double> z;
  for (const auto& p : s.points) z.push_back(p.z / pr.size);
  CHECK(cellforge::detail::reading_keeps_faces(pr, z));
  // Faces (a, b, c) and (b, a, d) share the line a b: d moved onto the plane of a, b, c.
  const auto& f = pr.loops[0];
  const std::uint32_t a = f[0], b = f[1], c = f[2];
  std::uint32_t d = a;  // the other triangle on a b (loops in either sense)
  for (std::size_t l = 1; l < pr.loops.size(); ++l) {
    const auto& g = pr.loops[l];
    if (g.size() == 3 && std::count(g.begin(), g.end(), a) == 1 && std::count(g.begin(), g.end(), b) == 1)
      for (const auto v : g)
        if (v != a && v != b) d = v;
  }
  REQUIRE(d != a);
  REQUIRE(f.size() == 3);
  const glm::dvec3 pa(pr.p[a], z[a]), pb(pr.p[b], z[b]), pc(pr.p[c], z[c]);
  const glm::dvec3 n = glm::cross(pb - pa, pc - pa);
  REQUIRE(std::abs(n.z) > 1e-9);
  std::vector<double> moved = z;
  moved[d] = pa.z - (n.x * (pr.p[d].x - pa.x) + n.y * (pr.p[d].y - pa.y)) / n.z;
  CHECK(cellforge::detail::reading_keeps_faces(pr, moved));
  CHECK(!cellforge::detail::reading_keeps_faces(pr, std::vector<double>(z.size(), 0.0)));
}

#ifdef NDEBUG  // the sanitizer build reads this very sample in the test above
TEST_CASE("inflate: a regular reading that changes the faces is passed over") {
  // Snapping a random polytope's near relations made faces coplanar: the regular reading of
  // polytope 22 of this sample (the sanitizer build's) had 41 faces of 40. Every reading returned
  // must keep the drawing's faces; inflate says how many regular readings it passed over.
  cellforge::samples::sketch_sweep_options options;
  options.families = {"random convex"};
  options.limit = 4;
  options.max_edges = 60;
  std::size_t passed_over = 0;
  for (const auto& s : cellforge::samples::sketch_sweep(options)) {
    INFO(s.name);
    const auto r = cellforge::inflate(s.drawing, s.loops);
    passed_over += r.face_changing_readings;
    std::string why;
    CHECK_MESSAGE(true_cells(s, r.points, why), why);
  }
  MESSAGE("regular readings passed over because they change the faces: " << passed_over);
}
#endif

TEST_CASE("inflate: the caller's point types come back") {
  const sample_drawing s =
      cellforge::samples::generic_drawing(cellforge::samples::sample_prism(5), 3, "prism");
  // A user's 2D type, lifted through its lifted_point specialisation.
  cellforge::line_drawing<inflation_test::pen_point> pen;
  for (const auto& p : s.drawing.points) pen.points.push_back({p.x, p.y});
  pen.edges = s.drawing.edges;
  const auto a = cellforge::inflate(pen, s.loops);
  static_assert(std::is_same_v<decltype(a.points)::value_type, inflation_test::solid_point>);
  // The 3D type named at the call, from float drawing points.
  cellforge::line_drawing<std::array<float, 2>> flo;
  for (const auto& p : s.drawing.points)
    flo.points.push_back({static_cast<float>(p.x), static_cast<float>(p.y)});
  flo.edges = s.drawing.edges;
  const auto b = cellforge::inflate<glm::dvec3>(flo, s.loops);
  static_assert(std::is_same_v<decltype(b.points)::value_type, glm::dvec3>);
  const auto c = cellforge::inflate(flo, s.loops);
  static_assert(std::is_same_v<decltype(c.points)::value_type, std::array<float, 3>>);
  REQUIRE(a.points.size() == s.points.size());
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    CHECK(a.points[i].u == s.drawing.points[i].x);
    CHECK(a.points[i].v == s.drawing.points[i].y);
    CHECK(c.points[i][0] == flo.points[i][0]);
  }
  // Same drawing, same answer, whatever the point type.
  for (std::size_t i = 0; i < s.points.size(); ++i)
    CHECK(a.points[i].w == doctest::Approx(b.points[i].z).epsilon(1e-4));
}

TEST_CASE("inflate: bad drawings and loops are refused with a reason") {
  const sample_drawing s =
      cellforge::samples::generic_drawing(cellforge::samples::sample_cube(), 2, "normalon");
  const auto category = [&](const cellforge::line_drawing<glm::dvec2>& d,
                            const std::vector<std::vector<std::uint32_t>>& loops,
                            cellforge::inflation_options o = {}) {
    try {
      (void)cellforge::inflate(d, loops, o);
    } catch (const cellforge::error& e) {
      MESSAGE(std::string(e.what()));
      return static_cast<int>(e.category());
    }
    return -1;
  };
  const int invalid = static_cast<int>(cellforge::error_category::invalid_input);
  CHECK(category(s.drawing, {}) == invalid);                                    // no faces
  CHECK(category(s.drawing, {s.loops[0], s.loops[1], s.loops[2]}) == invalid);  // too few faces
  auto bad = s.loops;
  std::swap(bad[0][0], bad[0][1]);  // a step no edge makes
  CHECK(category(s.drawing, bad) == invalid);
  bad = s.loops;
  bad[1][0] = 99;
  CHECK(category(s.drawing, bad) == invalid);
  auto d = s.drawing;
  d.points[3].x = std::nan("");
  CHECK(category(d, s.loops) == invalid);
  d = s.drawing;
  d.edges.push_back({2, 2});
  CHECK(category(d, s.loops) == invalid);
  // A junction moved off its place: no reading keeps the faces planar except the flat ones.
  d = s.drawing;
  d.points[5] += glm::dvec2(0.05, -0.03);
  CHECK(category(d, s.loops) == static_cast<int>(cellforge::error_category::topology));
  // Direct only, on a non-normalon: refused, saying why.
  const sample_drawing p =
      cellforge::samples::generic_drawing(cellforge::samples::sample_pyramid(5), 2, "pyramid");
  cellforge::inflation_options o;
  o.allow_optimisation = false;
  CHECK(category(p.drawing, p.loops, o) == invalid);
}

TEST_CASE("inflate: a hole's ring tied to its face only when the face is given with its holes") {
  const sample_drawing s =
      cellforge::samples::generic_drawing(cellforge::samples::sample_frame(), 4, "normalon");
  const auto whole = cellforge::inflate(s.drawing, s.model.faces);
  CHECK(whole.method == cellforge::inflation_method::direct);
  CHECK(std::min(depth_error(s, whole.readings[0].points), depth_error(s, whole.readings[1].points)) < 1e-9);
  // As separate loops, the inner ring (joined to the outer one by no line) may slide in depth.
  const auto loose = cellforge::inflate(s.drawing, s.loops);
  CHECK(loose.method == cellforge::inflation_method::optimisation);
  REQUIRE(!loose.diagnostics.empty());
  CHECK(loose.diagnostics[0].find("fixed neither by axis edges nor by face planes") != std::string::npos);
  CHECK(loose.after.planarity < 1e-12);
}

TEST_CASE("inflate: the solid a person sees: metric readings of regular solids, per family") {
  // A parallel view fixes depth up to the mirror, an offset and, beyond those, the planar
  // family's freedom (at least z → kz + ax + by); only regularity (right corners, equal sides
  // and corners) picks the metric one. Families whose solids have it: regular prisms, pyramids,
  // frusta and bipyramids, antiprisms, Platonic and Archimedean solids, cut cubes and prisms,
  // quasi-normalons, classics. Random convex polytopes and jittered non-convex prisms have none
  // (not metric in principle) and are not swept here (their cells: the tests above).
  cellforge::samples::sketch_sweep_options options;
  options.families = {"prism",       "pyramid",  "antiprism",      "platonic",
                      "archimedean", "cut cube", "quasi-normalon", "classic"};
#ifdef NDEBUG
  options.limit = 100;
  options.max_edges = 150;
#else
  options.limit = 12;
  options.max_edges = 40;
#endif
  const auto sweep = cellforge::samples::sketch_sweep(options);
  struct tally {
    std::size_t drawings = 0, metric = 0;
  };
  std::map<std::string, tally> by;
  std::size_t drawings = 0, metric = 0;
  std::string misses;
  for (const auto& s : sweep) {
    if (s.normalon) continue;
    INFO(s.name);
    const auto r = cellforge::inflate(s.drawing, s.model.faces);
    const double e = std::min(depth_error(s, r.readings[0].points), depth_error(s, r.readings[1].points));
    auto& t = by[s.family];
    ++t.drawings, ++drawings;
    if (e < 1e-6)
      ++t.metric, ++metric;
    else
      misses += "\n  " + s.name + ": depth error " + std::to_string(e) + " of the size, " +
                std::to_string(r.regular_relations) + " of " + std::to_string(r.relations) +
                " regularities held";
  }
  std::string table;
  for (const auto& [family, t] : by)
    table += "\n  " + family + ": " + std::to_string(t.metric) + " of " + std::to_string(t.drawings);
  MESSAGE("metric readings (depth within 1e-6 of the size after mirror and offset): "
          << metric << " of " << drawings << table << misses);
  REQUIRE(drawings >= 10);
  // Measured: 91 of 97 in Release (0 before the regular reading, 77 before its hypotheses, 87
  // before the apex rows, refined scans and weighted relations), 13 of 15 in the sanitizer
  // sample; the floors are under them (Release: the 90 %).
#ifdef NDEBUG
  CHECK(10 * metric >= 9 * drawings);
#else
  CHECK(5 * metric >= 4 * drawings);
#endif
}

TEST_CASE("inflate: a reading whose faces cross is caught by the exact check") {
  // The check inflate runs on every judged reading: the true reading of a prism does not
  // self-intersect; pushing one junction far through the solid makes faces cross.
  const sample_drawing s =
      cellforge::samples::generic_drawing(cellforge::samples::sample_prism(5), 2, "prism");
  const auto pr = cellforge::detail::make_inflation_problem(s.drawing, s.model.faces);
  std::vector<double> z;
  for (const auto& p : s.points) z.push_back(p.z / pr.size);
  CHECK(cellforge::detail::reading_crosses(pr, z) == 0);
  // Junction 0 moved through the solid, far out beyond its other side: its faces cross others.
  glm::dvec3 centroid{0.0};
  for (std::size_t i = 0; i < z.size(); ++i) centroid += glm::dvec3(pr.p[i], z[i]);
  centroid /= static_cast<double>(z.size());
  const glm::dvec3 moved = centroid + 2.5 * (centroid - glm::dvec3(pr.p[0], z[0]));
  auto bent = pr;
  bent.p[0] = glm::dvec2(moved);
  std::vector<double> zb = z;
  zb[0] = moved.z;
  CHECK(cellforge::detail::reading_crosses(bent, zb) == 1);
  const auto r = cellforge::inflate(s.drawing, s.model.faces);
  CHECK(!r.self_intersecting);
}

TEST_CASE("inflate: the exact Jacobians of the compliance and regularity residuals match differences") {
  // Levenberg–Marquardt runs on hand-derived Jacobians; each is checked against central
  // differences of its own residuals at random planar readings of a prism and an octahedron.
  for (const auto& s :
       {cellforge::samples::generic_drawing(cellforge::samples::sample_prism(5), 3, "prism"),
        cellforge::samples::generic_drawing(cellforge::samples::sample_octahedron(), 2, "platonic")}) {
    INFO(s.name);
    auto pr = cellforge::detail::make_inflation_problem(s.drawing, s.model.faces);
    auto terms = cellforge::detail::make_compliance_terms(pr, 1e-6);
    terms.convex = cellforge::detail::make_convexity_rows(pr);
    terms.convex_margin = 0.01;
    const auto reg = cellforge::detail::make_regularity_terms(pr);
    const Eigen::MatrixXd basis = cellforge::detail::planar_readings(pr, 1e-9);
    const cellforge::detail::basis_rows rows = basis;
    REQUIRE(basis.cols() >= 3);
    std::size_t np = 0;
    for (const auto& c : terms.parallel) np += c.size();
    const auto m = static_cast<Eigen::Index>(terms.count() + pr.edges.size() + pr.p.size());
    cellforge::detail::inflation_functor<> f{&pr, &terms, &basis, &rows, cellforge::inflation_weights{}, m};
    std::vector<std::uint32_t> held;
    for (std::uint32_t i = 0; i < reg.relations(); i += 2) held.push_back(i);
    cellforge::detail::regularity_functor<> robust{&pr, &terms, &reg, &basis, &rows, nullptr, 0.1, 0.01, 0};
    robust.m = static_cast<Eigen::Index>(reg.relations() + np + terms.convex.size()) + basis.rows();
    cellforge::detail::regularity_functor<> plain{&pr, &terms, &reg, &basis, &rows, &held, 0.0, 0.0, 0};
    plain.m = static_cast<Eigen::Index>(held.size() + np + terms.convex.size()) + basis.rows();
    cellforge::detail::splitmix rng{7};
    double worst = 0;
    const auto check = [&](const auto& functor) {
      for (int trial = 0; trial < 3; ++trial) {
        Eigen::VectorXd t(basis.cols());
        for (Eigen::Index i = 0; i < t.size(); ++i) t[i] = rng.uniform(-0.5, 0.5);
        Eigen::MatrixXd jac(functor.values(), t.size());
        functor.df(t, jac);
        Eigen::VectorXd up(functor.values()), down(functor.values());
        for (Eigen::Index j = 0; j < t.size(); ++j) {
          const double h = 1e-6;
          Eigen::VectorXd a = t, b = t;
          a[j] += h, b[j] -= h;
          functor(a, up), functor(b, down);
          const Eigen::VectorXd diff = (up - down) / (2 * h);
          worst = std::max(
              worst, (diff - jac.col(j)).cwiseAbs().maxCoeff() / std::max(1.0, diff.cwiseAbs().maxCoeff()));
        }
      }
    };
    check(f);
    check(robust);
    check(plain);
    CHECK(worst < 1e-5);
  }
}
