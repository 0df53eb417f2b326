// Edge smoothing (seed 000 chapter VI): curves on spheres approach the sphere, coplanar edges stay
// straight, every curve interpolates its ends and is perpendicular to the normals used there,
// creases (cylinder rims) become arcs, a quarter circle is parametric, bad input is refused, the
// readjustment converges (or averages when it stalls), over three point types and the cell complex.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/shapes.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/samples/smooth_solids.hpp"
#include "cellforge/smooth/smooth_edges.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace smooth_edges_tests {

namespace {

using namespace cellforge;  // test file only
using namespace cellforge::samples;
using soup = polygon_soup<glm::dvec3>;
using smooth_result = cellforge::smooth_result<glm::dvec3>;
using edge_curve = cellforge::edge_curve<glm::dvec3>;
using curve_end = cellforge::curve_end<glm::dvec3>;

constexpr curve_form all_forms[] = {curve_form::automatic, curve_form::axis_polynomial, curve_form::bezier};

smooth_options with_form(curve_form f, smooth_options o = {}) {
  o.form = f;
  return o;
}

// Mean | |p| − 1 | over the chord midpoints and over the curve midpoints point(0.5).
std::pair<double, double> radial_errors(const smooth_result& r) {
  double chord = 0, curve = 0;
  for (const edge_curve& c : r.curves) {
    chord += std::abs(glm::length(0.5 * (c.bezier[0] + c.bezier[3])) - 1.0);
    curve += std::abs(glm::length(c.point(0.5)) - 1.0);
  }
  const auto n = static_cast<double>(r.curves.size());
  return {chord / n, curve / n};
}

// Largest distance of the curve from the line through its ends, sampled at 65 points.
double sampled_chord_deviation(const edge_curve& c) {
  const glm::dvec3 a = c.bezier[0], d = glm::normalize(c.bezier[3] - c.bezier[0]);
  double worst = 0;
  for (int i = 0; i <= 64; ++i) worst = std::max(worst, glm::length(glm::cross(c.point(i / 64.0) - a, d)));
  return worst;
}

// An nx × ny × nz box of unit cells, its six sides split into grids of quads, outward.
soup box_grid(int nx, int ny, int nz, glm::dvec3 size) {
  soup s;
  std::map<std::array<int, 3>, std::uint32_t> id;
  auto vertex = [&](std::array<int, 3> k) {
    auto [it, fresh] = id.emplace(k, static_cast<std::uint32_t>(s.points.size()));
    if (fresh) s.points.push_back({size.x * k[0] / nx, size.y * k[1] / ny, size.z * k[2] / nz});
    return it->second;
  };
  const std::array<int, 3> n{nx, ny, nz};
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i < n[u]; ++i)
        for (int j = 0; j < n[v]; ++j) {
          std::array<std::array<int, 3>, 4> q{};
          const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
          for (int c = 0; c < 4; ++c) {
            q[c][axis] = side * n[axis];
            q[c][u] = i + du[c];
            q[c][v] = j + dv[c];
          }
          // (u, v, axis) is right-handed, so this order faces +axis; reverse on the low side.
          std::array<std::uint32_t, 4> f{vertex(q[0]), vertex(q[1]), vertex(q[2]), vertex(q[3])};
          if (side == 0) std::swap(f[1], f[3]);
          s.add_face({f[0], f[1], f[2], f[3]});
        }
  }
  return s;
}

glm::dmat4 some_rigid_motion() {
  // Rotation about (1, 2, 3) by 0.7 rad (Rodrigues), then a translation.
  const glm::dvec3 k = glm::normalize(glm::dvec3(1, 2, 3));
  const double c = std::cos(0.7), s = std::sin(0.7);
  glm::dmat4 m(1.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double cross = (i == j) ? 0 : ((j == (i + 1) % 3) ? -k[(i + 2) % 3] : k[(i + 1) % 3]);
      m[j][i] = (i == j ? c : 0) + (1 - c) * k[i] * k[j] + s * cross;
    }
  m[3] = glm::dvec4(0.3, -1.2, 2.5, 1.0);
  return m;
}

// Every curve: exact ends, tangents perpendicular to the normals used, and the axis form (when
// present) describing the same curve as the Bézier. `forced_axis`: the seed's form was forced, and
// an end tangent pointing back along the axis is then followed backwards (same line, other way).
void check_curves(const surface_mesh<glm::dvec3>& m, const smooth_result& r, bool forced_axis = false) {
  const auto pts = m.positions();
  REQUIRE(r.curves.size() == m.num_edges());
  REQUIRE(r.ends.size() == r.curves.size());
  for (std::size_t i = 0; i < r.curves.size(); ++i) {
    const edge_curve& c = r.curves[i];
    REQUIRE(c.edge == i);
    const glm::dvec3 p0 = pts[vertex_handle(c.v0)], p1 = pts[vertex_handle(c.v1)];
    CHECK(c.point(0.0) == p0);
    CHECK(c.point(1.0) == p1);
    CHECK(c.polyline().front() == p0);
    CHECK(c.polyline().back() == p1);
    for (int end = 0; end < 2; ++end) {
      const curve_end& e = r.ends[i][static_cast<std::size_t>(end)];
      if (!e.has_tangent) continue;
      const glm::dvec3 t = glm::normalize(c.tangent(end));
      CHECK(std::abs(glm::dot(t, e.normal_a)) < 1e-9);
      CHECK(std::abs(glm::dot(t, e.normal_b)) < 1e-9);
      const double along = glm::dot(t, e.direction);
      CHECK((forced_axis && c.has_axis_form ? std::abs(along) : along) > 1 - 1e-9);
    }
    const int tangents = r.ends[i][0].has_tangent + r.ends[i][1].has_tangent;
    CHECK(c.kind == (tangents == 2   ? curve_kind::cubic
                     : tangents == 1 ? curve_kind::quadratic
                                     : curve_kind::straight));
    if (c.has_axis_form) {
      CHECK(c.limits[0] == p0[c.axis]);
      CHECK(c.limits[1] == p1[c.axis]);
      for (double t : {0.0, 0.25, 0.5, 0.9, 1.0}) {
        const glm::dvec3 p = c.point(t);
        CHECK(glm::length(c.axis_point(p[c.axis]) - p) < 1e-12 * (1 + r.model_size));
      }
    }
  }
}

}  // namespace

TEST_CASE("edge_curve: builders are exact and agree with each other") {
  const glm::dvec3 a(0.2, -1, 3), b(1.7, 0.5, 2.5);
  const auto c = fit_axis_curve(a, b, 0, glm::dvec3(1, 2, 0.5), glm::dvec3(1, -0.5, -1));
  REQUIRE(c.has_value());
  CHECK(c->has_axis_form);
  CHECK(c->kind == curve_kind::cubic);
  CHECK(c->point(0) == a);
  CHECK(c->point(1) == b);
  // The axis form's slopes at the ends are the given directions' slopes (the seed's 6.4 system).
  const glm::dvec3 d0 = c->tangent(0), d1 = c->tangent(1);
  CHECK(d0.y / d0.x == doctest::Approx(2.0));
  CHECK(d0.z / d0.x == doctest::Approx(0.5));
  CHECK(d1.y / d1.x == doctest::Approx(-0.5));
  const edge_curve back = axis_curve<glm::dvec3>(c->axis, c->limits, c->coefficients);
  for (int i = 0; i < 4; ++i) CHECK(glm::length(back.bezier[i] - c->bezier[i]) < 1e-12);
  CHECK(back.kind == curve_kind::cubic);
  // One direction: a quadratic (no cubic coefficient).
  const auto q = fit_axis_curve(a, b, 0, glm::dvec3(1, 1, 0), std::nullopt);
  REQUIRE(q.has_value());
  CHECK(q->coefficients[0][0] == doctest::Approx(0.0).epsilon(1e-12));
  CHECK(q->coefficients[1][0] == doctest::Approx(0.0).epsilon(1e-12));
  CHECK(cellforge::detail::kind_of_bezier(q->bezier) == curve_kind::quadratic);
  // A direction with no component on the axis cannot be a function of it.
  CHECK_FALSE(fit_axis_curve(a, b, 0, glm::dvec3(0, 1, 0), std::nullopt).has_value());
  const edge_curve s = straight_curve(a, b);
  CHECK(s.kind == curve_kind::straight);
  CHECK(s.chord_deviation() < 1e-15);
  CHECK(s.polyline(15).size() == 16);
  CHECK_THROWS_AS(s.polyline(0), error);
  CHECK_THROWS_AS(axis_curve<glm::dvec3>(3, {0, 1}, {}), error);
  CHECK_THROWS_AS(axis_curve<glm::dvec3>(0, {0, std::numeric_limits<double>::quiet_NaN()}, {}), error);
}

TEST_CASE("edge_curve: a quarter circle is parametric and close to the arc") {
  const edge_curve c =
      fit_bezier_curve(glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 1, 0), glm::dvec3(-1, 0, 0));
  CHECK_FALSE(c.has_axis_form);
  double worst = 0;
  for (int i = 0; i <= 100; ++i) worst = std::max(worst, std::abs(glm::length(c.point(i / 100.0)) - 1));
  CHECK(worst < 3e-4);                                     // the classic 2.7e-4 of the 4/3·tan(θ/4) handle
  CHECK(std::abs(glm::length(c.point(0.5)) - 1) < 1e-15);  // exact at the middle
}

TEST_CASE("continuous surfaces of a cube, a sphere, and at angle 0") {
  const auto cube = make_mesh(box_grid(3, 3, 3, {1, 1, 1}));
  const solid_geometry g = solid_geometry_of(cube);
  const surface_partition p = continuous_surfaces(cube, g.face_normals, 45);
  REQUIRE(p.surfaces.size() == 6);
  for (const auto& s : p.surfaces) {
    CHECK(s.faces.size() == 9);
    CHECK(s.l2_edges.size() == 12);
    CHECK(s.l1_edges.size() == 12);
    CHECK(s.interior_vertices.size() == 4);
  }
  const auto sphere = make_mesh(uv_sphere(16, 8));
  const solid_geometry gs = solid_geometry_of(sphere);
  const surface_partition ps = continuous_surfaces(sphere, gs.face_normals, 45);
  REQUIRE(ps.surfaces.size() == 1);
  CHECK(ps.surfaces[0].interior_vertices.size() == sphere.num_vertices());
  CHECK(continuous_surfaces(sphere, gs.face_normals, 0).surfaces.size() == sphere.num_faces());
  CHECK_THROWS_AS(continuous_surfaces(sphere, gs.face_normals, 90.5), error);
}

TEST_CASE("UV sphere 16x8: curve midpoints are at least 5x closer to the sphere than the chords") {
  for (bool triangles : {true, false}) {
    const auto m = make_mesh(uv_sphere(16, 8, triangles));
    for (curve_form f : all_forms) {
      CAPTURE(triangles);
      CAPTURE(static_cast<int>(f));
      const smooth_result r = smooth_edges(m, with_form(f));
      const auto [chord, curve] = radial_errors(r);
      CHECK(curve * 5 < chord);
      // chord_deviation() bounds the sampled distance from the chord and is positive on a sphere.
      for (const edge_curve& c : r.curves) {
        CHECK(c.chord_deviation() > 1e-6);
        CHECK(sampled_chord_deviation(c) <= c.chord_deviation() * (1 + 1e-9) + 1e-15);
      }
      CHECK(r.num_surfaces == 1);
      CHECK(r.num_cubic == m.num_edges());
      CHECK(r.converged);
      check_curves(m, r);
      if (f == curve_form::bezier) CHECK(r.num_axis_form == 0);
      if (f == curve_form::axis_polynomial) CHECK(r.num_axis_form + r.num_axis_fallbacks == m.num_edges());
    }
    // The seed's rules give the same on a sphere: one surface, every vertex interior.
    const auto [chord, curve] = radial_errors(smooth_edges(m, seed_smooth_options()));
    CHECK(curve * 5 < chord);
  }
}

TEST_CASE("edges between coplanar faces stay straight (split cube, moved box)") {
  const soup boxes[] = {box_grid(3, 3, 3, {1, 1, 1}),
                        transformed(box_grid(1, 2, 3, {1, 2, 3}), some_rigid_motion()),
                        transformed(box_grid(2, 1, 4, {0.5, 0.1, 3}), some_rigid_motion())};
  for (const soup& s : boxes) {
    const auto m = make_mesh(s);
    for (curve_form f : all_forms)
      for (const smooth_options& base : {smooth_options{}, seed_smooth_options()}) {
        const smooth_result r = smooth_edges(m, with_form(f, base));
        check_curves(m, r);
        double worst = 0;
        for (const edge_curve& c : r.curves)
          worst = std::max({worst, sampled_chord_deviation(c), c.chord_deviation()});
        CHECK(worst < 1e-9 * r.model_size);
        CHECK(r.converged);
      }
  }
}

TEST_CASE("cylinder: rims become circle arcs with smooth_creases, stay straight with the seed's rules") {
  const auto m = make_mesh(cylinder(40, 1, true, false));
  const auto pts = m.positions();
  auto rim_errors = [&](const smooth_result& r) {
    double chord = 0, curve = 0;
    int n = 0;
    for (const edge_curve& c : r.curves) {
      const glm::dvec3 a = pts[vertex_handle(c.v0)], b = pts[vertex_handle(c.v1)];
      if (a.z != b.z) continue;  // a side edge
      const glm::dvec3 mid = 0.5 * (a + b), q = c.point(0.5);
      chord += std::abs(std::hypot(mid.x, mid.y) - 1);
      curve += std::abs(std::hypot(q.x, q.y) - 1);
      CHECK(std::abs(q.z - a.z) < 1e-12);  // the arc stays in the cap's plane
      ++n;
    }
    CHECK(n == 80);
    return std::pair{chord / n, curve / n};
  };
  for (curve_form f : all_forms) {
    const smooth_result r = smooth_edges(m, with_form(f));
    check_curves(m, r);
    CHECK(r.num_surfaces == 3);
    const auto [chord, curve] = rim_errors(r);
    CHECK(curve * 5 < chord);
    // The side edges are straight: their ends' normals are radial, the chord vertical.
    for (const edge_curve& c : r.curves)
      if (c.bezier[0].z != c.bezier[3].z) CHECK(c.chord_deviation() < 1e-12);
  }
  const smooth_result seed = smooth_edges(m, seed_smooth_options());
  check_curves(m, seed);
  const auto [chord, curve] = rim_errors(seed);
  CHECK(curve == doctest::Approx(chord).epsilon(1e-12));
  CHECK(seed.num_straight == m.num_edges());  // no interior vertex at all on a one-band cylinder
}

TEST_CASE("octahedron at 90 degrees: its edges become quarter circles in parametric form") {
  const auto m = make_mesh(octahedron());
  smooth_options o;
  o.angle_deg = 90;
  const smooth_result r = smooth_edges(m, o);
  check_curves(m, r);
  CHECK(r.num_surfaces == 1);
  CHECK(r.num_bezier_form == 12);
  for (const edge_curve& c : r.curves) {
    CHECK_FALSE(c.has_axis_form);
    double worst = 0;
    for (int i = 0; i <= 50; ++i) worst = std::max(worst, std::abs(glm::length(c.point(i / 50.0)) - 1));
    CHECK(worst < 3e-4);
  }
  // Forcing the seed's form is impossible here: every curve falls back and is counted.
  const smooth_result forced = smooth_edges(m, with_form(curve_form::axis_polynomial, o));
  CHECK(forced.num_axis_fallbacks == 12);
}

TEST_CASE("bad input is refused with a clear error") {
  const auto m = make_mesh(uv_sphere(8, 4));
  auto category = [&](auto&& call) {
    try {
      call();
    } catch (const error& e) {
      return e.category();
    }
    return error_category::internal;  // "no error" — never expected below
  };
  for (double angle : {-1.0, 91.0, std::numeric_limits<double>::quiet_NaN()}) {
    smooth_options o;
    o.angle_deg = angle;
    CHECK(category([&] { smooth_edges(m, o); }) == error_category::invalid_input);
  }
  smooth_options o;
  o.convergence = 0;
  CHECK(category([&] { smooth_edges(m, o); }) == error_category::invalid_input);
  o = {};
  o.max_iterations = 0;
  CHECK(category([&] { smooth_edges(m, o); }) == error_category::invalid_input);
  o = {};
  o.stall_cycles = 0;
  CHECK(category([&] { smooth_edges(m, o); }) == error_category::invalid_input);

  // Open: a cylinder without caps.
  CHECK(category([&] { smooth_edges(make_mesh(cylinder(8, 2, false))); }) == error_category::topology);
  // Not consistently oriented: one face of a cube reversed.
  soup flipped = box_grid(1, 1, 1, {1, 1, 1});
  std::reverse(flipped.face_vertices.begin() + 1, flipped.face_vertices.begin() + 4);
  CHECK(category([&] { smooth_edges(make_mesh(flipped)); }) == error_category::topology);
  // Degenerate: a tetrahedron whose fourth vertex lies on an edge.
  soup flat;
  flat.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0, 0}};
  for (auto f : {std::array<std::uint32_t, 3>{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}})
    flat.add_face({f[0], f[1], f[2]});
  try {
    smooth_edges(make_mesh(flat));
    FAIL("a degenerate face was accepted");
  } catch (const error& e) {
    CHECK(e.category() == error_category::invalid_input);
    CHECK(std::string(e.what()).find("face") != std::string::npos);
  }
  // Far out (issue 35): at 1e300 areas overflowed and every face read "degenerate"; the
  // message now says what is true, and names the range.
  for (const double far : {1e300, 1e-300}) {
    soup big = uv_sphere(8, 4);
    for (auto& p : big.points) p *= far;
    try {
      smooth_edges(make_mesh(big));
      FAIL("a sphere at scale ", far, " was accepted");
    } catch (const error& e) {
      CHECK(e.category() == error_category::invalid_input);
      CHECK(std::string(e.what()).find("smooth_edges: the model spans") == 0);
      CHECK(std::string(e.what()).find("scale the model into that range") != std::string::npos);
    }
  }
  soup fine = uv_sphere(8, 4);  // 1e40 is inside the range: smoothed as at 1
  for (auto& p : fine.points) p *= 1e40;
  CHECK_NOTHROW(smooth_edges(make_mesh(fine)));
  // Non-finite coordinate.
  soup nan = uv_sphere(8, 4);
  nan.points[3].y = std::numeric_limits<double>::quiet_NaN();
  CHECK(category([&] { smooth_edges(make_mesh(nan)); }) == error_category::invalid_input);
  // A reversed (inward) solid is smoothed as if it were outward: same curves.
  soup inward = uv_sphere(16, 8);
  for (std::size_t f = 0; f < inward.num_faces(); ++f)
    std::reverse(inward.face_vertices.begin() + inward.face_offsets[f],
                 inward.face_vertices.begin() + inward.face_offsets[f + 1]);
  const auto [chord, curve] = radial_errors(smooth_edges(make_mesh(inward)));
  CHECK(curve * 5 < chord);
}

TEST_CASE("readjustment: converges, midpoints lie on their curves, the budget and the averaging fallback") {
  const auto m = make_mesh(torus(12, 14, 1, 0.3, false));
  const smooth_result r = smooth_edges(m);
  REQUIRE(r.converged);
  CHECK_FALSE(r.averaged);
  CHECK(r.iterations >= 1);
  CHECK(r.moving.size() == static_cast<std::size_t>(r.iterations));
  CHECK(r.moving.back() == 0);
  for (std::size_t i = 0; i < r.curves.size(); ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= 2000; ++k)
      nearest = std::min(nearest, glm::length(r.curves[i].point(k / 2000.0) - r.midpoints[i]));
    CHECK(nearest < 1e-3 * r.model_size);
  }
  smooth_options budget;
  budget.max_iterations = 1;
  budget.convergence = 1e-9;
  const smooth_result b = smooth_edges(m, budget);
  CHECK(b.iterations == 1);
  CHECK_FALSE(b.converged);
  // A limit below rounding keeps the same midpoints "moving" cycle after cycle: the seed's
  // averaging ends the loop.
  smooth_options stall;
  stall.convergence = 1e-300;
  stall.stall_cycles = 2;
  const smooth_result s = smooth_edges(m, stall);
  CHECK(s.averaged);
  CHECK_FALSE(s.converged);
  CHECK(s.iterations < stall.max_iterations);
  check_curves(m, s);
}

TEST_CASE_TEMPLATE("point types give the same smoothing, in their own type", P, glm::dvec3,
                   std::array<float, 3>, test_support::user_point, test_support::sealed_point) {
  const auto sphere = uv_sphere<P>(16, 8);
  const auto m = make_mesh(sphere);
  const auto r = smooth_edges(m);
  static_assert(std::is_same_v<decltype(r), const cellforge::smooth_result<P>>);
  static_assert(std::is_same_v<decltype(r.curves), std::vector<cellforge::edge_curve<P>>>);
  static_assert(std::is_same_v<decltype(r.curves.front().bezier), std::array<P, 4>>);
  static_assert(std::is_same_v<decltype(r.curves.front().point(0.5)), P>);
  static_assert(std::is_same_v<decltype(r.curves.front().tangent(0.5)), P>);
  static_assert(std::is_same_v<decltype(r.curves.front().axis_point(0.5)), P>);
  static_assert(std::is_same_v<decltype(r.curves.front().polyline()), std::vector<P>>);
  static_assert(std::is_same_v<decltype(r.ends.front()[0].direction), P>);
  static_assert(std::is_same_v<decltype(r.ends.front()[0].normal_a), P>);
  static_assert(std::is_same_v<decltype(r.midpoints), std::vector<P>>);
  static_assert(std::is_same_v<decltype(r.vertex_normals), std::vector<P>>);
  CHECK(r.num_cubic == m.num_edges());
  const auto pts = m.positions();
  for (const auto& c : r.curves) {
    CHECK(to_dvec3(c.point(0)) == to_dvec3(pts[vertex_handle(c.v0)]));
    CHECK(to_dvec3(c.point(1)) == to_dvec3(pts[vertex_handle(c.v1)]));
  }
  // The glm::dvec3 run on the same numbers: the same curves, converted to P once at the end.
  const auto dm = make_mesh(test_support::soup_as_dvec3(sphere));
  const smooth_result d = smooth_edges(dm);
  const auto [chord, curve] = radial_errors(d);
  CHECK(curve * 5 < chord);
  const double tol = std::is_same_v<scalar_t<P>, float> ? 1e-6 : 0.0;  // float rounding of |p| <= 1
  const auto near = [&](const P& a, const glm::dvec3& b) { return glm::length(to_dvec3(a) - b) <= tol; };
  REQUIRE(r.curves.size() == d.curves.size());
  CHECK(r.iterations == d.iterations);
  CHECK(r.moving == d.moving);
  for (std::size_t i = 0; i < d.curves.size(); ++i) {
    CAPTURE(i);
    const auto& a = r.curves[i];
    const edge_curve& b = d.curves[i];
    CHECK((a.edge == b.edge && a.v0 == b.v0 && a.v1 == b.v1 && a.kind == b.kind));
    CHECK((a.has_axis_form == b.has_axis_form && a.axis == b.axis && a.limits == b.limits));
    CHECK(a.coefficients == b.coefficients);
    for (std::size_t k = 0; k < 4; ++k) CHECK(near(a.bezier[k], b.bezier[k]));
    CHECK(near(a.point(0.3), b.point(0.3)));
    CHECK(a.chord_deviation() == doctest::Approx(b.chord_deviation()).epsilon(1e-5));
    CHECK(near(r.midpoints[i], d.midpoints[i]));
    for (std::size_t e = 0; e < 2; ++e) {
      CHECK(r.ends[i][e].has_tangent == d.ends[i][e].has_tangent);
      CHECK(near(r.ends[i][e].direction, d.ends[i][e].direction));
      CHECK(near(r.ends[i][e].normal_a, d.ends[i][e].normal_a));
    }
  }
  for (std::size_t v = 0; v < d.vertex_normals.size(); ++v)
    CHECK(near(r.vertex_normals[v], d.vertex_normals[v]));
  // The glm::dvec3 sphere itself (not rounded to P) has the same curve ends within P's precision;
  // its inner control points may differ more for float, whose rounded input can tip the
  // per-edge form choice and the midpoint freezing (discrete decisions), not the conversion.
  const smooth_result g = smooth_edges(make_mesh(uv_sphere<glm::dvec3>(16, 8)));
  REQUIRE(g.curves.size() == r.curves.size());
  for (std::size_t i = 0; i < g.curves.size(); ++i)
    for (const std::size_t k : {0u, 3u})
      CHECK(glm::length(to_dvec3(r.curves[i].bezier[k]) - g.curves[i].bezier[k]) <= 1e-6);
}

TEST_CASE("edge_curve builders in a point type without a default constructor") {
  using test_support::sealed_point;
  const sealed_point a(0.2, -1, 3), b(1.7, 0.5, 2.5), t0(1, 2, 0.5), t1(1, -0.5, -1);
  const auto c = fit_axis_curve(a, b, 0, t0, t1);
  static_assert(std::is_same_v<decltype(c), const std::optional<cellforge::edge_curve<sealed_point>>>);
  const auto d = fit_axis_curve(glm::dvec3(0.2, -1, 3), glm::dvec3(1.7, 0.5, 2.5), 0, glm::dvec3(1, 2, 0.5),
                                glm::dvec3(1, -0.5, -1));
  REQUIRE((c && d));
  CHECK(c->coefficients == d->coefficients);
  for (std::size_t k = 0; k < 4; ++k) CHECK(to_dvec3(c->bezier[k]) == d->bezier[k]);
  CHECK(to_dvec3(c->tangent(0.25)) == d->tangent(0.25));
  const auto back = axis_curve<sealed_point>(c->axis, c->limits, c->coefficients);
  CHECK(glm::length(to_dvec3(back.axis_point(1.0)) - d->axis_point(1.0)) < 1e-12);
  cellforge::edge_curve<sealed_point> e =
      straight_curve(a, b);  // default member initialisers need no default constructor
  CHECK(e.has_axis_form);
  CHECK(set_axis_form(e, 1));
  CHECK(e.axis == 1);
  CHECK(largest_range_axis(a, b) == 0);
  CHECK(fit_bezier_curve(a, b, t0, std::nullopt).kind == curve_kind::quadratic);
  CHECK(hermite_curve(a, t0, b, t1).kind == curve_kind::cubic);
  CHECK(quadratic_bezier_curve(a, sealed_point(1, 1, 1), b).kind == curve_kind::quadratic);
  const cellforge::edge_curve<sealed_point> zero;
  CHECK(to_dvec3(zero.bezier[3]) == glm::dvec3(0.0));
  const cellforge::curve_end<sealed_point> end;
  CHECK(to_dvec3(end.direction) == glm::dvec3(0.0));
}

TEST_CASE("the cell complex overload matches the mesh call") {
  for (const soup& s :
       {uv_sphere(12, 6, false), cylinder(16, 2, true, false), box_grid(2, 2, 2, {1, 2, 1})}) {
    const auto m = make_mesh(s);
    const cell_complex<glm::dvec3> cc = mesh_to_cell_complex(m);
    const smooth_result rm = smooth_edges(m), rc = smooth_edges(cc, cell_volume(0));
    REQUIRE(rc.curves.size() == rm.curves.size());
    CHECK(rc.num_surfaces == rm.num_surfaces);
    std::map<std::array<double, 6>, const edge_curve*> by_ends;
    for (const edge_curve& c : rm.curves)
      by_ends[{c.bezier[0].x, c.bezier[0].y, c.bezier[0].z, c.bezier[3].x, c.bezier[3].y, c.bezier[3].z}] =
          &c;
    for (std::size_t i = 0; i < rc.curves.size(); ++i) {
      const edge_curve& c = rc.curves[i];
      if (i > 0) CHECK(rc.curves[i - 1].edge < c.edge);
      const auto ends = cc.edge_vertices(cell_edge(c.edge));
      CHECK(((ends[0].idx() == c.v0 && ends[1].idx() == c.v1) ||
             (ends[0].idx() == c.v1 && ends[1].idx() == c.v0)));
      CHECK(c.point(0) == cc.point(cell_vertex(c.v0)));
      CHECK(c.point(1) == cc.point(cell_vertex(c.v1)));
      const auto it = by_ends.find(
          {c.bezier[0].x, c.bezier[0].y, c.bezier[0].z, c.bezier[3].x, c.bezier[3].y, c.bezier[3].z});
      REQUIRE(it != by_ends.end());
      for (int k = 0; k < 4; ++k) CHECK(glm::length(it->second->bezier[k] - c.bezier[k]) < 1e-12);
    }
  }
}

TEST_CASE("the Table 7 stand-ins have the seed's edge counts and smooth") {
  const auto solids = table7_solids();
  REQUIRE(solids.size() == 4);
  for (const auto& s : solids) {
    CAPTURE(s.name);
    const auto m = make_mesh(s.soup);
    CHECK(std::abs(static_cast<double>(m.num_edges()) - static_cast<double>(s.seed_edges)) <= 1);
    const smooth_result r = smooth_edges(m);
    CHECK(r.converged);
    check_curves(m, r);
  }
}

TEST_CASE("smooth_table7_solid: figures 1..4 as meshes, others refused") {
  for (int figure = 1; figure <= 4; ++figure) {
    const smooth_table7_case<> c = smooth_table7_solid(figure);
    CHECK(c.mesh.is_closed());
    CHECK(std::abs(static_cast<double>(c.mesh.num_edges()) - static_cast<double>(c.seed_edges)) <= 1);
  }
  CHECK_THROWS_AS(smooth_table7_solid(0), error);
  CHECK_THROWS_AS(smooth_table7_solid(5), error);
}

TEST_CASE("seed rules: cubic between interior vertices, quadratic with one, straight with none") {
  // A 40-gon cylinder in 3 bands: interior vertices are the two middle rings (§6.2).
  const auto m = make_mesh(cylinder(40, 3, true, false));
  const smooth_result seed = smooth_edges(m, seed_smooth_options());
  check_curves(m, seed);
  CHECK(seed.num_cubic == 40 + 80);  // middle band's side edges + the middle rings
  CHECK(seed.num_quadratic == 80);   // outer bands' side edges
  CHECK(seed.num_straight == 80);    // the rims, between two surfaces
  CHECK(seed.num_axis_form == m.num_edges());
  const smooth_result ours = smooth_edges(m);
  CHECK(ours.num_cubic == m.num_edges());
}

TEST_CASE("a moved sphere smooths as well as the axis-aligned one") {
  const soup s = transformed(scaled(uv_sphere(16, 8), glm::dvec3(2.0)), some_rigid_motion());
  const auto m = make_mesh(s);
  const glm::dvec3 centre = glm::dvec3(some_rigid_motion()[3]);
  for (curve_form f : all_forms) {
    const smooth_result r = smooth_edges(m, with_form(f));
    check_curves(m, r);
    double chord = 0, curve = 0;
    for (const edge_curve& c : r.curves) {
      chord += std::abs(glm::length(0.5 * (c.bezier[0] + c.bezier[3]) - centre) - 2.0);
      curve += std::abs(glm::length(c.point(0.5) - centre) - 2.0);
    }
    CHECK(curve * 5 < chord);
  }
}

TEST_CASE("tolerances are relative: the same smoothing at 1e-6 and 1e6") {
  for (double scale : {1e-6, 1e6}) {
    const auto m = make_mesh(scaled(uv_sphere(16, 8), glm::dvec3(scale)));
    const smooth_result r = smooth_edges(m);
    CHECK(r.converged);
    CHECK(r.num_cubic == m.num_edges());
    double chord = 0, curve = 0;
    for (const edge_curve& c : r.curves) {
      chord += std::abs(glm::length(0.5 * (c.bezier[0] + c.bezier[3])) / scale - 1);
      curve += std::abs(glm::length(c.point(0.5)) / scale - 1);
    }
    CHECK(curve * 5 < chord);
  }
}

TEST_CASE("triangulated cylinder with fan caps: rims are arcs, cap spokes and side edges straight") {
  // The diagonals tilt the side's vertex normals a little (the seed's weighting), so the arcs are
  // checked on average, like the sphere.
  const auto m = make_mesh(cylinder(24, 2, true, true));
  const smooth_result r = smooth_edges(m);
  check_curves(m, r);
  CHECK(r.num_surfaces == 3);
  double chord = 0, curve = 0;
  int rings = 0, straight = 0;
  for (const edge_curve& c : r.curves) {
    const glm::dvec3 a = c.bezier[0], b = c.bezier[3];
    const bool on_circle =
        std::abs(std::hypot(a.x, a.y) - 1) < 1e-12 && std::abs(std::hypot(b.x, b.y) - 1) < 1e-12;
    if (on_circle && a.z == b.z) {
      const glm::dvec3 mid = 0.5 * (a + b), q = c.point(0.5);
      chord += std::abs(std::hypot(mid.x, mid.y) - 1);
      curve += std::abs(std::hypot(q.x, q.y) - 1);
      ++rings;
    } else if ((on_circle && a.x == b.x && a.y == b.y) ||
               (a.z == b.z && std::abs(std::abs(a.z) - 1) < 1e-12)) {
      CHECK(c.chord_deviation() < 1e-9);  // a vertical side edge or a cap spoke
      ++straight;
    }
  }
  CHECK(rings == 3 * 24);
  CHECK(straight == 2 * 24 + 2 * 24);
  CHECK(curve * 5 < chord);
}

TEST_CASE("a surface meeting itself at a sharp edge: crease_inside_surfaces keeps the edge sharp") {
  // A ring swept from a teardrop: an arc of 280° plus a tip whose faces meet at ~124°, while the
  // arc turns by ~31° per step, so the growth reaches round to the tip from both sides.
  const int around = 16, arc = 10;
  const double R = 1, r = 0.3;
  std::vector<glm::dvec2> section{{R + 2 * r, 0}};
  for (int j = 0; j < arc; ++j) {
    const double a = (40.0 + 280.0 * j / (arc - 1)) * std::numbers::pi / 180;
    section.push_back({R + r * std::cos(a), r * std::sin(a)});
  }
  soup s;
  const auto k = static_cast<int>(section.size());
  for (int i = 0; i < around; ++i) {
    const double u = 2 * std::numbers::pi * i / around;
    for (const glm::dvec2& q : section) s.points.push_back({q.x * std::cos(u), q.x * std::sin(u), q.y});
  }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>((i % around) * k + (j % k)); };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < k; ++j) s.add_face({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  const auto m = make_mesh(s);
  const smooth_result ours = smooth_edges(m);
  check_curves(m, ours);
  CHECK(ours.num_surfaces == 1);
  CHECK(ours.num_creases == static_cast<std::size_t>(around));
  // The tip ring (radius R + 2r) becomes arcs: both sides' normals cross along the ring.
  double chord = 0, curve = 0;
  for (const edge_curve& c : ours.curves) {
    const auto radius = [](const glm::dvec3& p) { return std::hypot(p.x, p.y); };
    if (std::abs(radius(c.bezier[0]) - (R + 2 * r)) > 1e-12 ||
        std::abs(radius(c.bezier[3]) - (R + 2 * r)) > 1e-12)
      continue;
    chord += std::abs(radius(0.5 * (c.bezier[0] + c.bezier[3])) - (R + 2 * r));
    curve += std::abs(radius(c.point(0.5)) - (R + 2 * r));
    CHECK(std::abs(c.point(0.5).z) < 1e-12);  // the crease stays in its plane
  }
  CHECK(curve * 5 < chord);
  smooth_options seed_like;
  seed_like.crease_inside_surfaces = false;
  const smooth_result seed = smooth_edges(m, seed_like);
  check_curves(m, seed);
  CHECK(seed.num_creases == 0);
  CHECK(seed.num_surfaces == 1);
}

TEST_CASE("noisy solids: every curve finite, exact at its ends, perpendicular to its normals") {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> jitter(-0.08, 0.08);
  for (int round = 0; round < 4; ++round) {
    soup s = round % 2 ? icosphere(2) : torus(10, 8, 1, 0.4, round == 2);
    for (auto& p : s.points) p += glm::dvec3(jitter(rng), jitter(rng), jitter(rng));
    const auto m = make_mesh(s);
    for (curve_form f : all_forms)
      for (double angle : {10.0, 45.0, 90.0}) {
        smooth_options o = with_form(f);
        o.angle_deg = angle;
        const smooth_result r = smooth_edges(m, o);
        check_curves(m, r, f == curve_form::axis_polynomial);
        for (const edge_curve& c : r.curves)
          for (const glm::dvec3& b : c.bezier)
            REQUIRE((std::isfinite(b.x) && std::isfinite(b.y) && std::isfinite(b.z)));
        CHECK((r.converged || r.averaged));
      }
  }
}

}  // namespace smooth_edges_tests
