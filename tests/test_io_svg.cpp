#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/io/svg.hpp"
#include "mesh_fixtures.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace io_svg_tests {

namespace {

using cellforge::polygon_soup;
using cellforge::wireframe;
namespace io = cellforge::io;

template <class P>
P pt(double x, double y, double z) {
  return cellforge::from_dvec3<P>({x, y, z});
}

/// The unit cube [0,1]^3 as 6 quads with outward (right-hand) normals.
template <class P>
polygon_soup<P> unit_cube() {
  polygon_soup<P> s;
  for (int i = 0; i < 8; ++i) s.points.push_back(pt<P>(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  s.add_face({0, 2, 3, 1});  // z = 0, normal -z
  s.add_face({4, 5, 7, 6});  // z = 1, +z
  s.add_face({0, 1, 5, 4});  // y = 0, -y
  s.add_face({2, 6, 7, 3});  // y = 1, +y
  s.add_face({0, 4, 6, 2});  // x = 0, -x
  s.add_face({1, 3, 7, 5});  // x = 1, +x
  return s;
}

template <class P>
wireframe<P> cube_wireframe() {
  wireframe<P> w;
  for (int i = 0; i < 8; ++i) w.points.push_back(pt<P>(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  for (std::uint32_t a = 0; a < 8; ++a)
    for (std::uint32_t bit = 1; bit < 8; bit <<= 1)
      if (!(a & bit)) w.edges.push_back({a, a | bit});
  return w;
}

/// A UV sphere of radius 1 (quads, triangles at the poles).
polygon_soup<glm::dvec3> uv_sphere(int rings, int sectors) {
  polygon_soup<glm::dvec3> s;
  s.points.push_back({0, 0, 1});
  for (int r = 1; r < rings; ++r)
    for (int k = 0; k < sectors; ++k) {
      const double th = std::numbers::pi * r / rings, ph = 2 * std::numbers::pi * k / sectors;
      s.points.push_back({std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)});
    }
  s.points.push_back({0, 0, -1});
  const auto id = [&](int r, int k) {
    return static_cast<std::uint32_t>(1 + (r - 1) * sectors + (k % sectors));
  };
  const auto south = static_cast<std::uint32_t>(s.points.size() - 1);
  for (int k = 0; k < sectors; ++k) {
    s.add_face({0, id(1, k), id(1, k + 1)});
    for (int r = 1; r + 1 < rings; ++r) s.add_face({id(r, k), id(r + 1, k), id(r + 1, k + 1), id(r, k + 1)});
    s.add_face({south, id(rings - 1, k + 1), id(rings - 1, k)});
  }
  return s;
}

/// Balanced tags, quoted attributes, no stray '<' or '&' in text, comments closed: enough to catch
/// broken output.
bool well_formed(const std::string& s) {
  std::vector<std::string> open;
  std::size_t i = 0;
  while ((i = s.find('<', i)) != std::string::npos) {
    if (s.compare(i, 4, "<!--") == 0) {  // a comment: no "--" inside, ends with "-->"
      const std::size_t close = s.find("--", i + 4);
      if (close == std::string::npos || s.compare(close, 3, "-->") != 0) return false;
      i = close + 3;
      continue;
    }
    const std::size_t end = s.find('>', i);
    if (end == std::string::npos) return false;
    const std::string tag = s.substr(i + 1, end - i - 1);
    if (tag.empty()) return false;
    if (tag[0] == '?') {
      if (tag.back() != '?') return false;
    } else if (tag[0] == '/') {
      if (open.empty() || open.back() != tag.substr(1)) return false;
      open.pop_back();
    } else {
      if (std::count(tag.begin(), tag.end(), '"') % 2 != 0 || tag.find('<') != std::string::npos)
        return false;
      const std::string name = tag.substr(0, tag.find_first_of(" /"));
      if (tag.back() != '/') open.push_back(name);
    }
    // Text up to the next tag must have only entity references for '&'.
    const std::size_t next = s.find('<', end);
    const std::string text =
        s.substr(end + 1, next == std::string::npos ? std::string::npos : next - end - 1);
    for (std::size_t a = text.find('&'); a != std::string::npos; a = text.find('&', a + 1))
      if (text.find(';', a) == std::string::npos) return false;
    i = end;
  }
  return open.empty();
}

std::string render(const io::svg_scene& scene, const io::svg_options& o = {},
                   io::svg_result* result = nullptr) {
  std::ostringstream os;
  const auto r = scene.write(os, o);
  if (result) *result = r;
  return os.str();
}

bool is_full(const io::svg_edge_visibility& e) {
  return e.hidden.size() == 1 && e.hidden[0][0] == 0.0 && e.hidden[0][1] == 1.0;
}

/// Where segment a-b is hidden behind one triangle, seen with options o.
template <class P>
std::vector<std::array<double, 2>> hidden_behind(const std::array<P, 3>& triangle, const P& a, const P& b,
                                                 const io::svg_options& o, io::svg_result* result = nullptr) {
  polygon_soup<P> tri;
  tri.points.assign(triangle.begin(), triangle.end());
  tri.add_face({0, 1, 2});
  io::svg_scene scene;
  scene.add_mesh(tri);
  const std::vector<P> segment{a, b};
  const std::size_t line = scene.add_polyline(segment);
  render(scene, o, result);
  for (const auto& e : scene.edge_visibility(o))
    if (e.layer == line) return e.hidden;
  FAIL("the segment is missing from the scene");
  return {};
}

}  // namespace

TEST_CASE_TEMPLATE("a cube from a generic view: 3 faces toward the viewer, 9 visible and 3 hidden edges", P,
                   glm::dvec3, std::array<float, 3>, test_support::user_point) {
  io::svg_scene scene;
  scene.add_mesh(unit_cube<P>());
  io::svg_result r;
  const std::string text = render(scene, {}, &r);
  CHECK(r.faces_drawn == 6);
  CHECK(r.faces_facing_viewer == 3);
  CHECK(r.edges == 12);
  CHECK(r.visible_edges == 9);
  CHECK(r.hidden_edges == 3);
  CHECK(r.partly_hidden_edges == 0);
  CHECK(r.hidden_pieces == 3);
  CHECK(r.visible_pieces == 9);
  // The default camera is in the +x +y +z octant: the hidden edges are those meeting at the origin.
  for (const auto& e : scene.edge_visibility()) {
    const bool at_origin = e.a == glm::dvec3(0.0) || e.b == glm::dvec3(0.0);
    CHECK(at_origin == is_full(e));
    if (!at_origin) CHECK(e.hidden.empty());
  }
  CHECK(well_formed(text));
  CHECK(text.find("viewBox=\"0 0 800 600\"") != std::string::npos);
  CHECK(text.find("stroke-dasharray") != std::string::npos);
  CHECK(text.find("nan") == std::string::npos);
  CHECK(text.find("inf") == std::string::npos);

  io::svg_style culled;
  culled.cull_back_faces = true;
  io::svg_scene front_only;
  front_only.add_mesh(unit_cube<P>(), culled);
  io::svg_result rc;
  render(front_only, {}, &rc);
  CHECK(rc.faces_drawn == 3);
  CHECK(rc.faces_facing_viewer == 3);
  // The front faces still hide the three back edges.
  CHECK(rc.visible_edges == 9);
  CHECK(rc.hidden_edges == 3);
}

TEST_CASE_TEMPLATE("a wireframe cube without faces has 12 visible edges", P, glm::dvec3, std::array<float, 3>,
                   test_support::user_point) {
  io::svg_scene scene;
  scene.add_wireframe(cube_wireframe<P>());
  io::svg_result r;
  const std::string text = render(scene, {}, &r);
  CHECK(r.edges == 12);
  CHECK(r.visible_edges == 12);
  CHECK(r.hidden_edges == 0);
  CHECK(r.faces_drawn == 0);
  CHECK(text.find("stroke-dasharray") == std::string::npos);
  CHECK(well_formed(text));
}

TEST_CASE("lines along a mesh's edges are hidden exactly where the mesh's own edges are") {
  io::svg_scene scene;
  scene.add_mesh(unit_cube<glm::dvec3>());
  io::svg_style red;
  red.stroke = "#d00000";
  scene.add_wireframe(cube_wireframe<glm::dvec3>(), red);
  io::svg_result r;
  render(scene, {}, &r);
  CHECK(r.edges == 24);
  CHECK(r.visible_edges == 18);
  CHECK(r.hidden_edges == 6);
}

TEST_CASE("a soup with split vertices still draws each edge once") {
  const auto cube = unit_cube<glm::dvec3>();
  polygon_soup<glm::dvec3> split;
  for (std::size_t f = 0; f < cube.num_faces(); ++f) {
    std::vector<std::uint32_t> ids;
    for (const auto v : cube.face(f)) {
      ids.push_back(static_cast<std::uint32_t>(split.points.size()));
      split.points.push_back(cube.points[v]);
    }
    split.add_face(ids);
  }
  io::svg_scene scene;
  scene.add_mesh(split);
  io::svg_result r;
  render(scene, {}, &r);
  CHECK(r.edges == 12);
  CHECK(r.visible_edges == 9);
  CHECK(r.hidden_edges == 3);
}

TEST_CASE_TEMPLATE("a triangle in front of a long segment hides exactly its middle", P, glm::dvec3,
                   std::array<float, 3>) {
  // Camera on +x looking at -x: screen right is +y, screen up is +z; the segment runs along y.
  io::svg_options o;
  o.view.azimuth_deg = 0;
  o.view.elevation_deg = 0;
  const P a = pt<P>(0, -2, 0), b = pt<P>(0, 2, 0);

  SUBCASE("parallel to the segment: hidden for y in [-0.25, 0.25]") {
    io::svg_result r;
    const auto hidden =
        hidden_behind<P>({pt<P>(1, -0.5, -1), pt<P>(1, 0.5, -1), pt<P>(1, 0, 1)}, a, b, o, &r);
    REQUIRE(hidden.size() == 1);
    CHECK(std::abs(hidden[0][0] - 0.4375) < 1e-6);
    CHECK(std::abs(hidden[0][1] - 0.5625) < 1e-6);
    CHECK(r.partly_hidden_edges == 1);
    CHECK(r.visible_pieces == 3 + 2);  // triangle sides + the two ends of the segment
    CHECK(r.hidden_pieces == 1);
  }
  SUBCASE("piercing the segment's depth: hidden only where the triangle is in front") {
    // The triangle lies in the plane x = y, in front of the segment (x = 0) only for y > 0;
    // the depth margin moves that start by margin / slope, so make it tiny to see the exact end.
    o.depth_epsilon = 1e-10;
    const auto hidden =
        hidden_behind<P>({pt<P>(-0.5, -0.5, -1), pt<P>(0.5, 0.5, -1), pt<P>(0, 0, 1)}, a, b, o);
    REQUIRE(hidden.size() == 1);
    CHECK(std::abs(hidden[0][0] - 0.5) < 1e-6);
    CHECK(std::abs(hidden[0][1] - 0.5625) < 1e-6);
  }
}

TEST_CASE("hidden intervals agree with ray casting from a generic view") {
  // Independent reference: X(t) is hidden when the ray from X toward the camera hits the triangle.
  const glm::dvec3 A(-1.3, 0.2, -0.4), B(1.1, -0.3, 0.7);
  const std::array<glm::dvec3, 3> T{glm::dvec3(0.9, -0.8, -0.7), glm::dvec3(0.6, 1.0, -0.2),
                                    glm::dvec3(1.2, 0.1, 1.1)};
  io::svg_options o;
  o.view.azimuth_deg = 20;
  o.view.elevation_deg = 15;
  const double az = o.view.azimuth_deg * std::numbers::pi / 180,
               el = o.view.elevation_deg * std::numbers::pi / 180;
  const glm::dvec3 toward(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  const auto hidden_at = [&](double t) {
    const glm::dvec3 x = A + t * (B - A);
    const glm::dvec3 e1 = T[1] - T[0], e2 = T[2] - T[0], p = glm::cross(toward, e2);
    const double det = glm::dot(e1, p);
    const glm::dvec3 s = x - T[0];
    const double u = glm::dot(s, p) / det;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(toward, q) / det, dist = glm::dot(e2, q) / det;
    return u >= 0 && v >= 0 && u + v <= 1 && dist > 0;
  };
  // Bracket the hidden run by sampling, then bisect each end.
  double first = -1, last = -1;
  for (int i = 0; i <= 1000; ++i)
    if (hidden_at(i / 1000.0)) {
      if (first < 0) first = i / 1000.0;
      last = i / 1000.0;
    }
  REQUIRE(first > 0);
  REQUIRE(last < 1);
  const auto bisect = [&](double in, double out) {
    for (int k = 0; k < 60; ++k) {
      const double m = 0.5 * (in + out);
      (hidden_at(m) ? in : out) = m;
    }
    return in;
  };
  const double t0 = bisect(first, first - 1e-3), t1 = bisect(last, last + 1e-3);

  const auto hidden = hidden_behind<glm::dvec3>(T, A, B, o);
  REQUIRE(hidden.size() == 1);
  CHECK(std::abs(hidden[0][0] - t0) < 1e-6);
  CHECK(std::abs(hidden[0][1] - t1) < 1e-6);
}

TEST_CASE("many triangles and segments: the grid finds every occluder (checked by brute-force ray casting)") {
  // A fixed linear congruential generator keeps the test deterministic on every platform.
  std::uint64_t state = 12345;
  const auto uniform = [&](double lo, double hi) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  polygon_soup<glm::dvec3> tris;
  for (std::uint32_t i = 0; i < 300; ++i) {
    const glm::dvec3 c(uniform(-4, 4), uniform(-4, 4), uniform(-4, 4));
    for (int k = 0; k < 3; ++k)
      tris.points.push_back(c + glm::dvec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
    tris.add_face({3 * i, 3 * i + 1, 3 * i + 2});
  }
  io::svg_scene scene;
  scene.add_mesh(tris);
  std::vector<std::vector<glm::dvec3>> segments;
  for (int i = 0; i < 60; ++i) {
    segments.push_back(
        {{uniform(-5, 5), uniform(-5, 5), uniform(-5, 5)}, {uniform(-5, 5), uniform(-5, 5), uniform(-5, 5)}});
    scene.add_polyline(segments.back());
  }
  const io::svg_options o;  // the default, generic view
  const double az = o.view.azimuth_deg * std::numbers::pi / 180,
               el = o.view.elevation_deg * std::numbers::pi / 180;
  const glm::dvec3 toward(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  const auto ray_hits = [&](const glm::dvec3& x) {
    for (std::size_t f = 0; f < tris.num_faces(); ++f) {
      const glm::dvec3 &t0 = tris.points[3 * f], &t1 = tris.points[3 * f + 1], &t2 = tris.points[3 * f + 2];
      const glm::dvec3 e1 = t1 - t0, e2 = t2 - t0, p = glm::cross(toward, e2);
      const double det = glm::dot(e1, p);
      if (std::abs(det) < 1e-12) continue;
      const glm::dvec3 s = x - t0, q = glm::cross(s, e1);
      const double u = glm::dot(s, p) / det, v = glm::dot(toward, q) / det, dist = glm::dot(e2, q) / det;
      if (u >= 0 && v >= 0 && u + v <= 1 && dist > 1e-9) return true;
    }
    return false;
  };
  std::size_t checked = 0, hidden_samples = 0;
  for (const auto& e : scene.edge_visibility(o)) {
    if (e.layer == 0) continue;  // the triangles' own edges
    for (int i = 0; i <= 200; ++i) {
      const double t = i / 200.0;
      bool in = false, near_end = false;
      for (const auto& h : e.hidden) {
        in = in || (t > h[0] && t < h[1]);
        near_end = near_end || std::abs(t - h[0]) < 1e-4 || std::abs(t - h[1]) < 1e-4;
      }
      if (near_end) continue;  // a sample on a boundary may go either way
      CHECK(in == ray_hits(e.a + t * (e.b - e.a)));
      ++checked;
      hidden_samples += in ? 1 : 0;
    }
  }
  CHECK(checked > 10000);
  CHECK(hidden_samples > 500);  // the test does test occlusion
}

TEST_CASE("a sphere's own edges: hidden exactly where ray casting says, in every row of the grid") {
  // Short edges, many fully hidden behind the front half: they exercise the skipping of grid
  // cells whose part of an edge is already hidden, on the grid's outer rows and columns too.
  for (const double elevation : {25.0, -40.0, 70.0}) {
    const auto sphere = uv_sphere(16, 32);
    io::svg_scene scene;
    scene.add_mesh(sphere);
    io::svg_options o;
    o.view.elevation_deg = elevation;
    const double az = o.view.azimuth_deg * std::numbers::pi / 180, el = elevation * std::numbers::pi / 180;
    const glm::dvec3 toward(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    // The farthest hit along the ray toward the camera, over the faces split into triangles.
    const auto farthest_hit = [&](const glm::dvec3& x) {
      double best = -1;
      for (std::size_t f = 0; f < sphere.num_faces(); ++f) {
        const auto vs = sphere.face(f);
        for (std::size_t k = 1; k + 1 < vs.size(); ++k) {
          const glm::dvec3 &t0 = sphere.points[vs[0]], &t1 = sphere.points[vs[k]],
                           &t2 = sphere.points[vs[k + 1]];
          const glm::dvec3 e1 = t1 - t0, e2 = t2 - t0, p = glm::cross(toward, e2);
          const double det = glm::dot(e1, p);
          if (std::abs(det) < 1e-14) continue;
          const glm::dvec3 d = x - t0, q = glm::cross(d, e1);
          const double u = glm::dot(d, p) / det, v = glm::dot(toward, q) / det, dist = glm::dot(e2, q) / det;
          if (u >= 0 && v >= 0 && u + v <= 1) best = std::max(best, dist);
        }
      }
      return best;
    };
    std::size_t checked = 0, hidden_samples = 0;
    for (const auto& e : scene.edge_visibility(o)) {
      for (const double t : {0.25, 0.5, 0.75}) {
        bool in = false, near_end = false;
        for (const auto& h : e.hidden) {
          in = in || (t > h[0] && t < h[1]);
          near_end = near_end || std::abs(t - h[0]) < 1e-3 || std::abs(t - h[1]) < 1e-3;
        }
        const double hit = farthest_hit(e.a + t * (e.b - e.a));
        if (near_end || (hit > 1e-9 && hit < 1e-3)) continue;  // grazing: either answer is right
        CHECK(in == (hit >= 1e-3));
        ++checked;
        hidden_samples += in ? 1 : 0;
      }
    }
    INFO("elevation " << elevation << ": " << checked << " samples, " << hidden_samples << " hidden");
    CHECK(checked > 2000);
    CHECK(hidden_samples > 1000);
  }
}

TEST_CASE("the picture does not depend on the model's scale or position") {
  const auto scaled = [](double s, glm::dvec3 shift) {
    auto cube = unit_cube<glm::dvec3>();
    for (auto& p : cube.points) p = p * s + shift;
    io::svg_scene scene;
    scene.add_mesh(cube);
    io::svg_result r;
    const std::string text = render(scene, {}, &r);
    CHECK(r.visible_edges == 9);
    CHECK(r.hidden_edges == 3);
    return text;
  };
  const std::string unit = scaled(1, glm::dvec3(0.0));
  CHECK(scaled(1e-6, glm::dvec3(0.0)).size() == unit.size());
  CHECK(scaled(1e6, glm::dvec3(3e6, -1e6, 0)).size() == unit.size());
  CHECK(scaled(std::ldexp(1.0, -20), glm::dvec3(0.0)) == unit);  // exact in binary: the same picture
  CHECK(scaled(std::ldexp(1.0, 20), glm::dvec3(0.0)) == unit);
}

TEST_CASE("points behind faces are hidden, labels are escaped, output is deterministic") {
  io::svg_scene scene;
  scene.add_mesh(unit_cube<glm::dvec3>());
  const std::vector<glm::dvec3> pts{{0.5, 0.5, 0.5}, {1, 1, 1}, {0, 0, 0}, {2, 2, 2}};
  scene.add_points(pts, {}, 4);
  scene.add_label(glm::dvec3(1, 1, 1), "corner <a & \"b\">");
  io::svg_options o;
  o.title = "cube & points";
  io::svg_result r;
  const std::string text = render(scene, o, &r);
  CHECK(r.points_visible == 2);  // the front corner and the point outside
  CHECK(r.points_hidden == 2);   // the centre and the back corner
  CHECK(r.labels == 1);
  CHECK(text.find("corner &lt;a &amp; &quot;b&quot;&gt;") != std::string::npos);
  CHECK(text.find("<title>cube &amp; points</title>") != std::string::npos);
  CHECK(well_formed(text));
  CHECK(render(scene, o) == text);
}

TEST_CASE("feature edges: coplanar diagonals are skipped even when neighbours disagree on orientation") {
  io::svg_style features;
  features.feature_angle_deg = 20;
  for (const bool flip : {false, true}) {
    polygon_soup<glm::dvec3> quad;
    quad.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.add_face({0, 1, 2});
    if (flip)
      quad.add_face({0, 3, 2});  // runs 2 -> 0 along the diagonal, like the first: inconsistent
    else
      quad.add_face({0, 2, 3});  // runs 0 -> 2: consistent
    io::svg_scene scene;
    scene.add_mesh(quad, features);
    io::svg_result r;
    render(scene, {}, &r);
    CHECK(r.edges == 4);  // the boundary only
  }
  io::svg_scene cube;
  cube.add_mesh(unit_cube<glm::dvec3>(), features);
  io::svg_result r;
  render(cube, {}, &r);
  CHECK(r.edges == 12);  // every cube edge is a 90 degree edge
}

TEST_CASE("other up axes see the same cube from the matching corner") {
  for (const auto up : {io::svg_up_axis::x, io::svg_up_axis::y, io::svg_up_axis::z}) {
    io::svg_scene scene;
    scene.add_mesh(unit_cube<glm::dvec3>());
    io::svg_options o;
    o.view.up = up;
    for (const auto& e : scene.edge_visibility(o)) {
      const bool at_origin = e.a == glm::dvec3(0.0) || e.b == glm::dvec3(0.0);
      CHECK(at_origin == is_full(e));
    }
  }
}

TEST_CASE("a sphere: about half its edges are hidden, and the picture fits the viewport") {
  const auto sphere = uv_sphere(24, 48);
  io::svg_scene scene;
  scene.add_mesh(sphere);
  io::svg_result r;
  const std::string text = render(scene, {}, &r);
  CHECK(r.faces_drawn == sphere.num_faces());
  CHECK(r.edges == 48 * 23 + 48 * 24);
  const double hidden_share = static_cast<double>(r.hidden_edges) / static_cast<double>(r.edges);
  CHECK(hidden_share > 0.4);
  CHECK(hidden_share < 0.6);
  CHECK(well_formed(text));
  // Every coordinate of a polygon lies within the viewport.
  std::size_t at = 0;
  while ((at = text.find("points=\"", at)) != std::string::npos) {
    at += 8;
    std::istringstream in(text.substr(at, text.find('"', at) - at));
    double x = 0, y = 0;
    char comma = 0;
    while (in >> x >> comma >> y) {
      CHECK(x >= 19.99);
      CHECK(x <= 780.01);
      CHECK(y >= 19.99);
      CHECK(y <= 580.01);
    }
  }
}

TEST_CASE("an empty scene writes an empty picture") {
  io::svg_scene scene;
  io::svg_result r;
  io::svg_options o;
  o.background = "none";
  const std::string text = render(scene, o, &r);
  CHECK(r.faces_drawn == 0);
  CHECK(r.edges == 0);
  CHECK(well_formed(text));
  CHECK(text.find("<svg") != std::string::npos);
  CHECK(text.find("<rect") == std::string::npos);
}

TEST_CASE("bad input throws a cellforge::error instead of writing garbage") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  io::svg_scene scene;
  auto cube = unit_cube<glm::dvec3>();
  cube.points[5].y = nan;
  CHECK_THROWS_WITH_AS(scene.add_mesh(cube), doctest::Contains("point 5"), cellforge::error);
  auto wire = cube_wireframe<glm::dvec3>();
  wire.points[2].z = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(scene.add_wireframe(wire), cellforge::error);
  const std::vector<std::array<float, 3>> line{{0, 0, 0}, {std::numeric_limits<float>::quiet_NaN(), 1, 1}};
  CHECK_THROWS_AS(scene.add_polyline(line), cellforge::error);
  CHECK(scene.empty());  // failed calls leave the scene as it was

  auto bad_index = unit_cube<glm::dvec3>();
  bad_index.face_vertices[3] = 99;
  try {
    scene.add_mesh(bad_index);
    FAIL("expected an error");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::invalid_input);
    CHECK(std::string(e.what()).find("point 99") != std::string::npos);
  }
  io::svg_style bad_style;
  bad_style.opacity = nan;
  CHECK_THROWS_AS(scene.add_mesh(unit_cube<glm::dvec3>(), bad_style), cellforge::error);

  scene.add_mesh(unit_cube<glm::dvec3>());
  std::ostringstream os;
  io::svg_options o;
  o.width = 0;
  CHECK_THROWS_AS(scene.write(os, o), cellforge::error);
  o = {};
  o.margin = 400;
  CHECK_THROWS_AS(scene.write(os, o), cellforge::error);
  o = {};
  o.view.elevation_deg = nan;
  CHECK_THROWS_AS(scene.write(os, o), cellforge::error);
}

TEST_CASE("writing to a missing directory throws an io error naming the path") {
  const auto dir = std::filesystem::temp_directory_path() / "cellforge_svg_no_such_dir_7f3a";
  std::filesystem::remove_all(dir);
  const auto path = dir / "cube.svg";
  try {
    io::write_svg(path, unit_cube<glm::dvec3>());
    FAIL("expected an error");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(std::string(e.what()).find(path.string()) != std::string::npos);
  }
  // And a file that can be written is.
  const auto ok = std::filesystem::temp_directory_path() / "cellforge_svg_test_cube.svg";
  const auto r = io::write_svg(ok, cube_wireframe<std::array<float, 3>>());
  CHECK(r.visible_edges == 12);
  CHECK(std::filesystem::file_size(ok) > 100);
  std::filesystem::remove(ok);
  // A surface mesh in one call: the cube's 6 faces, 12 edges, 3 faces toward the viewer.
  const auto mesh = cellforge::make_mesh(fixtures::cube());
  const auto m = io::write_svg(ok, mesh);
  CHECK(m.faces_drawn == 6);
  CHECK(m.faces_facing_viewer == 3);
  CHECK(m.edges == 12);
  std::filesystem::remove(ok);
}

TEST_CASE("numbers are written with fixed precision, no trailing zeros, no negative zero") {
  const auto fmt = [](double v, int precision) {
    std::string s;
    io::detail::svg_number(s, v, precision);
    return s;
  };
  CHECK(fmt(12.5, 2) == "12.5");
  CHECK(fmt(3.0, 2) == "3");
  CHECK(fmt(0.0, 2) == "0");
  CHECK(fmt(-0.0, 2) == "0");
  CHECK(fmt(-0.004, 2) == "0");
  CHECK(fmt(-0.006, 2) == "-0.01");
  CHECK(fmt(660.8649, 2) == "660.86");
  CHECK(fmt(0.05, 2) == "0.05");
  CHECK(fmt(-123.456, 0) == "-123");
  CHECK(fmt(1.5e20, 2) == "150000000000000000000");  // beyond the fast path
  CHECK(fmt(7.25, 9) == "7.25");
}

TEST_CASE("shading is two-sided and a non-orientable strip draws every face") {
  const auto fill_of = [](std::initializer_list<std::uint32_t> order) {
    polygon_soup<glm::dvec3> tri;
    tri.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.3}};
    tri.add_face(order);
    io::svg_scene scene;
    scene.add_mesh(tri);
    const std::string text = render(scene);
    const std::size_t at = text.find("fill=\"#", text.find("<polygon"));
    return text.substr(at, 14);
  };
  CHECK(fill_of({0, 1, 2}) == fill_of({0, 2, 1}));
  CHECK(fill_of({0, 1, 2}) != "fill=\"#9fc5e8\"");  // shaded, not the flat colour

  // A Moebius strip: 40 quads, half a turn along the loop.
  polygon_soup<glm::dvec3> strip;
  const int n = 40;
  for (int i = 0; i < n; ++i) {
    const double u = 2 * std::numbers::pi * i / n;
    for (const double v : {-0.3, 0.3})
      strip.points.push_back({(1 + v * std::cos(u / 2)) * std::cos(u),
                              (1 + v * std::cos(u / 2)) * std::sin(u), v * std::sin(u / 2)});
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    if (j == 0)
      strip.add_face({2 * i, 2 * i + 1, 0, 1});  // the half turn glues the sides crosswise
    else
      strip.add_face({2 * i, 2 * i + 1, 2 * j + 1, 2 * j});
  }
  io::svg_style features;
  features.feature_angle_deg = 30;
  io::svg_scene scene;
  scene.add_mesh(strip, features);
  io::svg_result r;
  const std::string text = render(scene, {}, &r);
  CHECK(r.faces_drawn == static_cast<std::size_t>(n));
  CHECK(r.edges >= static_cast<std::size_t>(2 * n));  // the one boundary loop has 2n edges
  CHECK(r.edges < static_cast<std::size_t>(3 * n));   // and the smooth rungs are mostly skipped
  CHECK(well_formed(text));
}

namespace {

/// A regular n-gon of radius r about the z axis at height z, counter-clockwise seen from +z.
polygon_soup<glm::dvec3> disc(std::uint32_t n, double r, double z) {
  polygon_soup<glm::dvec3> s;
  std::vector<std::uint32_t> loop(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    s.points.push_back({r * std::cos(a), r * std::sin(a), z});
    loop[i] = i;
  }
  s.add_face(loop);
  return s;
}

/// Seen from straight above (+z), x to the right.
const io::svg_options from_above{.view = {.azimuth_deg = -90, .elevation_deg = 90}};

}  // namespace

TEST_CASE("a 4096-gon in front of segments hides exactly the chords inside it") {
  io::svg_scene scene;
  scene.add_mesh(disc(4096, 1.0, 1.0));
  std::vector<std::size_t> lines;
  std::vector<double> heights;
  for (int k = -12; k <= 12; ++k) {
    const double y = 0.1 * k + 0.013;  // not through a vertex of the polygon
    const std::vector<glm::dvec3> segment{{-2.0, y, 0.0}, {2.0, y, 0.0}};
    lines.push_back(scene.add_polyline(segment));
    heights.push_back(y);
  }
  io::svg_result r;
  render(scene, from_above, &r);
  CHECK(r.approximate_edges == 0);
  CHECK(r.untested_edges == 0);
  std::size_t checked = 0;
  for (const auto& e : scene.edge_visibility(from_above)) {
    if (e.layer == 0) {
      CHECK(e.hidden.empty());  // the polygon's own edges are in front of everything
      continue;
    }
    REQUIRE(e.exact);
    const double y = heights[e.layer - 1];
    if (std::abs(y) >= 1.0) {
      CHECK(e.hidden.empty());
    } else {
      // The chord of the unit circle, x in +-sqrt(1 - y^2); t = (x + 2) / 4. The polygon's sides
      // are within 1 - cos(pi / 4096) < 3e-7 of the circle.
      const double half = std::sqrt(1.0 - y * y) / 4.0;
      REQUIRE(e.hidden.size() == 1);
      CHECK(e.hidden[0][0] == doctest::Approx(0.5 - half).epsilon(1e-5));
      CHECK(e.hidden[0][1] == doctest::Approx(0.5 + half).epsilon(1e-5));
    }
    ++checked;
  }
  CHECK(checked == lines.size());
}

TEST_CASE(
    "two 20 000-gons: back to back every edge is visible, one above the other the lower one is hidden") {
  // Back to back: the same points, one face each way; every edge belongs to both faces.
  polygon_soup<glm::dvec3> both = disc(20000, 1.0, 0.0);
  std::vector<std::uint32_t> reversed(both.face(0).rbegin(), both.face(0).rend());
  both.add_face(reversed);
  io::svg_scene scene;
  scene.add_mesh(both);
  io::svg_result r;
  render(scene, {}, &r);
  CHECK(r.edges == 20000);
  CHECK(r.visible_edges == 20000);
  CHECK(r.approximate_edges + r.untested_edges == 0);

  // A smaller disc below a larger one, seen from above: its edges are all hidden.
  io::svg_scene stack;
  stack.add_mesh(disc(20000, 1.0, 0.0));
  stack.add_mesh(disc(20000, 0.9, -1.0));
  io::svg_result rs;
  const std::string text = render(stack, from_above, &rs);
  CHECK(rs.edges == 40000);
  CHECK(rs.visible_edges == 20000);
  CHECK(rs.hidden_edges == 20000);
  CHECK(rs.approximate_edges + rs.untested_edges == 0);
  CHECK(well_formed(text));
}

TEST_CASE("past the work budget, edges are judged from one point and the picture says so") {
  // A fan of sliver triangles meeting at one corner, with its points: every edge near the
  // corner crosses cells holding every triangle.
  polygon_soup<glm::dvec3> fan = disc(400, 1.0, 0.0);
  polygon_soup<glm::dvec3> sliver;
  sliver.points = fan.points;
  for (std::uint32_t i = 1; i + 1 < 400; ++i) sliver.add_face({0, i, i + 1});
  io::svg_scene scene;
  scene.add_mesh(sliver);
  scene.add_points(sliver.points);
  io::svg_result exact;
  const std::string full = render(scene, {}, &exact);
  CHECK(exact.approximate_edges + exact.untested_edges + exact.approximate_points + exact.untested_points ==
        0);
  CHECK(full.find("work budget") == std::string::npos);
  CHECK(exact.complete);
  CHECK(exact.diagnostics.empty());

  io::svg_options tight;
  tight.work_budget = 2000;
  io::svg_result r;
  const std::string text = render(scene, tight, &r);
  CHECK(r.edges == exact.edges);
  CHECK(r.approximate_edges > 0);
  CHECK(r.approximate_edges + r.untested_edges < r.edges);  // the first edges are still exact
  CHECK(r.work <= 2 * tight.work_budget + 1000);            // bounded: one query's overshoot at most
  CHECK(text.find("hidden-line work budget ran out") != std::string::npos);
  CHECK_FALSE(r.complete);  // the vocabulary's exhausted budget: a status and a diagnostic naming the option
  REQUIRE(r.diagnostics.size() == 1);
  CHECK(r.diagnostics[0].find("raise svg_options::work_budget") != std::string::npos);
  CHECK(r.milliseconds > 0);
  CHECK(well_formed(text));
  std::size_t inexact = 0;
  for (const auto& e : scene.edge_visibility(tight)) {
    if (e.exact) continue;
    ++inexact;
    CHECK((e.hidden.empty() || is_full(e)));  // hidden or visible as a whole
  }
  CHECK(inexact == r.approximate_edges + r.untested_edges);
  // A budget of 1 unit: next to nothing is exact, nothing throws.
  tight.work_budget = 1;
  CHECK_NOTHROW(render(scene, tight, &r));
  CHECK(r.approximate_edges + r.untested_edges > r.edges / 2);
}

TEST_CASE("a cube's hidden edges stay dashed and exact under any budget that fits it") {
  io::svg_scene scene;
  scene.add_mesh(unit_cube<glm::dvec3>());
  io::svg_options o;
  o.work_budget = 100000;
  io::svg_result r;
  const std::string text = render(scene, o, &r);
  CHECK(r.hidden_edges == 3);
  CHECK(r.visible_edges == 9);
  CHECK(r.approximate_edges == 0);
  CHECK(r.work > 0);
  CHECK(text.find("stroke-dasharray") != std::string::npos);
  CHECK(text == render(scene));  // the default budget draws the same picture
}

TEST_CASE("3000 stacked squares: the grid is coarsened, the top square still hides every other edge") {
  // Every square covers nearly the whole picture, so a grid of one cell per face would list
  // each of them in every cell (9 million entries).
  polygon_soup<glm::dvec3> stack;
  constexpr std::uint32_t n = 3000;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double r = 1.0 - 0.5 * i / n, z = -0.001 * i;
    const std::uint32_t b = static_cast<std::uint32_t>(stack.points.size());
    for (const auto& [x, y] : {std::pair{-r, -r}, {r, -r}, {r, r}, {-r, r}})
      stack.points.push_back({x, y, z});
    stack.add_face({b, b + 1, b + 2, b + 3});
  }
  io::svg_scene scene;
  scene.add_mesh(stack);
  io::svg_result r;
  render(scene, from_above, &r);
  CHECK(r.faces_drawn == n);
  CHECK(r.visible_edges == 4);
  CHECK(r.hidden_edges == 4 * (n - 1));
  CHECK(r.approximate_edges + r.untested_edges == 0);
}

}  // namespace io_svg_tests
