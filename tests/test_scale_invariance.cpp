// SPDX-License-Identifier: MIT
// Scale-free geometry: every small sample model, scaled by 1e-9 … 1e9 and turned by random
// rotations, gives the same cell complex as at scale 1 (the same face and volume counts, the
// same face vertex sets, validate() passes), and the cases that once failed: a thin wedge at
// 1e-7, a dodecahedron at 1e10 (edge angles from unnormalised edge vectors underflowed /
// overflowed), a 1e-4 cube beside a unit cube (a volume threshold relative to the whole
// model). Totals and every miss are printed. Release: 40 rotations per scale; the sanitizer
// build fewer.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "cellforge/cells/validate.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace scale_invariance_tests {

namespace {

using cellforge::samples::sample_model;

#ifdef NDEBUG
constexpr int rotations = 40;
#else
constexpr int rotations = 4;  // the sanitizer build: 10-50x slower
#endif

constexpr double scales[] = {1e-9, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9};

// A uniformly random rotation (from a random unit quaternion). O(1).
glm::dmat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  double w = n(rng), x = n(rng), y = n(rng), z = n(rng);
  const double l = std::sqrt(w * w + x * x + y * y + z * z);
  w /= l, x /= l, y /= l, z /= l;
  // Column-major: m[c][r].
  return glm::dmat3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y),  //
                    2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x),  //
                    2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));
}

using faces_t = std::vector<std::vector<std::vector<std::uint32_t>>>;

// The result's faces in the caller's vertex labels. O(size).
faces_t faces_in_input_labels(const cellforge::wireframe_result<glm::dvec3>& r) {
  faces_t out;
  for (const auto& f : r.input.faces) {
    auto loops = f.loops;
    for (auto& l : loops)
      for (auto& v : l) v = r.input_vertex[v];
    out.push_back(std::move(loops));
  }
  return out;
}

// One conversion's outcome: the faces, the volume count, and what went wrong (empty when the
// complex is valid).
struct outcome {
  faces_t faces;
  std::size_t volumes = 0;
  std::string error;
};

// Converts m with default options and validates the complex. O(pipeline).
outcome convert(const sample_model& m) {
  outcome o;
  try {
    const auto r = cellforge::wireframe_to_cells(m.wire);
    o.faces = faces_in_input_labels(r);
    o.volumes = r.input.volumes.size();
    const auto v = cellforge::validate(r.cells);
    if (!v.ok()) o.error = "validate: " + v.message;
  } catch (const std::exception& e) {
    o.error = std::string("threw: ") + e.what();
  }
  return o;
}

// Why `got` differs from the reference (empty when it does not). O(F log F).
std::string differs(const outcome& ref, const outcome& got) {
  if (!got.error.empty()) return got.error;
  if (got.faces.size() != ref.faces.size())
    return std::to_string(got.faces.size()) + " faces, not " + std::to_string(ref.faces.size());
  if (got.volumes != ref.volumes)
    return std::to_string(got.volumes) + " volumes, not " + std::to_string(ref.volumes);
  if (!cellforge::samples::same_faces(ref.faces, got.faces)) return "other face vertex sets";
  return {};
}

// The model scaled by s and turned by rot, with an offset of the same scale. O(V).
sample_model placed(const sample_model& m, double s, const glm::dmat3& rot) {
  return cellforge::samples::transformed(m, s * rot, s * glm::dvec3(0.25, -0.5, 0.75));
}

// A wedge: a triangle with a 1e-3-radian corner, extruded by 1 (5 faces, 1 volume). O(1).
sample_model thin_wedge() {
  sample_model m;
  m.name = "thin wedge";
  const double t = 1e-3;
  m.wire.points = {{0, 0, 0}, {1, 0, 0}, {std::cos(t), std::sin(t), 0},
                   {0, 0, 1}, {1, 0, 1}, {std::cos(t), std::sin(t), 1}};
  m.wire.edges = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
  return m;
}

// A regular dodecahedron about the origin (20 vertices, 30 edges of length 2/φ). O(V²).
sample_model dodecahedron() {
  sample_model m;
  m.name = "dodecahedron";
  const double p = (1 + std::sqrt(5.0)) / 2, q = 1 / p;
  for (int a : {-1, 1})
    for (int b : {-1, 1}) {
      for (int c : {-1, 1}) m.wire.points.push_back({a, b, c});
      m.wire.points.push_back({0, a * q, b * p});
      m.wire.points.push_back({a * q, b * p, 0});
      m.wire.points.push_back({a * p, 0, b * q});
    }
  for (std::uint32_t i = 0; i < m.wire.points.size(); ++i)
    for (std::uint32_t j = i + 1; j < m.wire.points.size(); ++j)
      if (std::abs(glm::length(m.wire.points[i] - m.wire.points[j]) - 2 * q) < 1e-9)
        m.wire.edges.push_back({i, j});
  return m;
}

// Runs m at every scale and `n` random rotations against its conversion at scale 1; prints
// and returns the misses. O(scales · n · pipeline).
std::size_t sweep(const sample_model& m, std::span<const double> ss, int n, std::mt19937_64& rng,
                  std::size_t& runs, const outcome* expected = nullptr) {
  const outcome ref = expected ? *expected : convert(m);
  std::size_t misses = 0;
  if (!ref.error.empty()) {
    std::printf("  miss: %s at scale 1: %s\n", m.name.c_str(), ref.error.c_str());
    return 1;
  }
  for (double s : ss)
    for (int k = 0; k < n; ++k) {
      ++runs;
      const std::string why = differs(ref, convert(placed(m, s, random_rotation(rng))));
      if (!why.empty()) {
        ++misses;
        std::printf("  miss: %s at scale %g, rotation %d: %s\n", m.name.c_str(), s, k, why.c_str());
      }
    }
  return misses;
}

}  // namespace

TEST_CASE("scale invariance: every small sample model at scales 1e-9 .. 1e9, random rotations") {
  std::mt19937_64 rng(20261202);
  std::size_t runs = 0, misses = 0, models = 0;
  for (const auto& m : cellforge::samples::all_small_samples()) {
    const outcome ref = convert(m);
    INFO(m.name);
    // The reference itself is the truth (test_wireframe_pipeline checks it in detail).
    CHECK(ref.error.empty());
    CHECK(cellforge::samples::same_faces(m.faces, ref.faces));
    CHECK(ref.volumes == m.volumes.size());
    misses += sweep(m, scales, rotations, rng, runs, &ref);
    ++models;
  }
  std::printf("scale invariance: %zu models x %zu scales x %d rotations: %zu runs, %zu misses\n", models,
              std::size(scales), rotations, runs, misses);
  CHECK(runs == models * std::size(scales) * rotations);
  CHECK(misses == 0);
}

TEST_CASE("scale invariance: a thin wedge at 1e-7 and a dodecahedron at 1e10") {
  std::mt19937_64 rng(7);
  std::size_t runs = 0;
  const sample_model wedge = thin_wedge(), dodeca = dodecahedron();
  REQUIRE(dodeca.wire.edges.size() == 30);
  const outcome w1 = convert(wedge), d1 = convert(dodeca);
  CHECK(w1.error.empty());
  CHECK(w1.faces.size() == 5);
  CHECK(w1.volumes == 1);
  CHECK(d1.error.empty());
  CHECK(d1.faces.size() == 12);
  CHECK(d1.volumes == 1);
  const double tiny[] = {1e-7}, huge[] = {1e10};
  const std::size_t misses =
      sweep(wedge, tiny, rotations, rng, runs, &w1) + sweep(dodeca, huge, rotations, rng, runs, &d1);
  std::printf("thin wedge at 1e-7, dodecahedron at 1e10: %zu runs, %zu misses\n", runs, misses);
  CHECK(misses == 0);
}

TEST_CASE("scale invariance: a 1e-4 cube beside a unit cube is two volumes") {
  const sample_model m = cellforge::samples::disjoint_union(
      cellforge::samples::sample_cube(), cellforge::samples::sample_cube({1e-4, 1e-4, 1e-4}), {2, 0, 0},
      "unit cube and 1e-4 cube");
  const outcome o = convert(m);
  INFO(o.error);
  CHECK(o.error.empty());
  CHECK(o.volumes == 2);
  CHECK(o.faces.size() == 12);
  CHECK(cellforge::samples::same_faces(m.faces, o.faces));
}

}  // namespace scale_invariance_tests
