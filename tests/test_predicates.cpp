// Exact predicates: every sign is checked against an independent exact reference written
// here (a schoolbook big integer on 32-bit limbs, and __int128 on integer inputs), on
// near-degenerate inputs where plain floating point gets the sign wrong.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/geometry.hpp"
#include "cellforge/core/detail/union_find.hpp"
#include "cellforge/core/predicates.hpp"
#include "test_support.hpp"

// Own namespace: the test files of a group are compiled as one translation unit.
namespace predicates_tests {

namespace {

__extension__ typedef __int128 i128;

// ------------------------------------------------------------------ reference arithmetic

// A signed big integer: magnitude in base 2^32 (little-endian, no leading zero limbs).
struct big {
  bool negative = false;
  std::vector<std::uint32_t> mag;

  bool zero() const { return mag.empty(); }
  void trim() {
    while (!mag.empty() && mag.back() == 0) mag.pop_back();
    if (mag.empty()) negative = false;
  }
  // m · 2^shift with sign.
  static big shifted(std::uint64_t m, int shift, bool neg) {
    big r;
    r.negative = neg;
    r.mag.assign(static_cast<std::size_t>(shift / 32) + 4, 0);
    const int bit = shift % 32;
    const std::size_t word = static_cast<std::size_t>(shift / 32);
    // Spread the 64-bit value over three limbs, then shift by `bit`.
    std::uint64_t lo = m & 0xFFFFFFFFu, hi = m >> 32;
    std::uint64_t limbs[3] = {lo << bit, hi << bit, 0};
    limbs[1] += limbs[0] >> 32;
    limbs[0] &= 0xFFFFFFFFu;
    limbs[2] = limbs[1] >> 32;
    limbs[1] &= 0xFFFFFFFFu;
    for (int i = 0; i < 3; ++i)
      r.mag[word + static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(limbs[i]);
    r.trim();
    return r;
  }
};

int compare_mag(const big& a, const big& b) {
  if (a.mag.size() != b.mag.size()) return a.mag.size() < b.mag.size() ? -1 : 1;
  for (std::size_t i = a.mag.size(); i-- > 0;)
    if (a.mag[i] != b.mag[i]) return a.mag[i] < b.mag[i] ? -1 : 1;
  return 0;
}

big add(const big& a, const big& b) {
  big r;
  if (a.negative == b.negative) {
    r.negative = a.negative;
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i < std::max(a.mag.size(), b.mag.size()) || carry; ++i) {
      const std::uint64_t s = carry + (i < a.mag.size() ? a.mag[i] : 0) + (i < b.mag.size() ? b.mag[i] : 0);
      r.mag.push_back(static_cast<std::uint32_t>(s));
      carry = s >> 32;
    }
  } else {
    const bool a_bigger = compare_mag(a, b) >= 0;
    const big& x = a_bigger ? a : b;
    const big& y = a_bigger ? b : a;
    r.negative = x.negative;
    std::int64_t borrow = 0;
    for (std::size_t i = 0; i < x.mag.size(); ++i) {
      std::int64_t d = static_cast<std::int64_t>(x.mag[i]) - borrow - (i < y.mag.size() ? y.mag[i] : 0);
      borrow = d < 0 ? 1 : 0;
      if (d < 0) d += std::int64_t{1} << 32;
      r.mag.push_back(static_cast<std::uint32_t>(d));
    }
  }
  r.trim();
  return r;
}

big negate(big a) {
  if (!a.zero()) a.negative = !a.negative;
  return a;
}
big sub(const big& a, const big& b) { return add(a, negate(b)); }

big mul(const big& a, const big& b) {
  big r;
  if (a.zero() || b.zero()) return r;
  r.mag.assign(a.mag.size() + b.mag.size(), 0);
  for (std::size_t i = 0; i < a.mag.size(); ++i) {
    std::uint64_t carry = 0;
    for (std::size_t j = 0; j < b.mag.size(); ++j) {
      const std::uint64_t t = static_cast<std::uint64_t>(a.mag[i]) * b.mag[j] + r.mag[i + j] + carry;
      r.mag[i + j] = static_cast<std::uint32_t>(t);
      carry = t >> 32;
    }
    r.mag[i + b.mag.size()] = static_cast<std::uint32_t>(carry);
  }
  r.negative = a.negative != b.negative;
  r.trim();
  return r;
}

int sign(const big& a) { return a.zero() ? 0 : (a.negative ? -1 : 1); }

// Every finite double is m · 2^e with an integer m < 2^53; all inputs of one determinant
// are written over the smallest such exponent, so the determinant is an integer one.
std::vector<big> to_common_integers(const std::vector<double>& xs) {
  int min_exp = std::numeric_limits<int>::max();
  for (double x : xs)
    if (x != 0) {
      int e = 0;
      std::frexp(x, &e);
      min_exp = std::min(min_exp, e - 53);
    }
  std::vector<big> out;
  for (double x : xs) {
    if (x == 0) {
      out.emplace_back();
      continue;
    }
    int e = 0;
    const double f = std::frexp(std::fabs(x), &e);
    const auto m = static_cast<std::uint64_t>(std::ldexp(f, 53));
    out.push_back(big::shifted(m, e - 53 - min_exp, x < 0));
  }
  return out;
}

// det[b-a; c-a; d-a], evaluated by the textbook cofactor expansion on exact integers.
int reference_orient3d(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
  const auto v = to_common_integers({a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z});
  auto at = [&](int point, int k) { return v[static_cast<std::size_t>(3 * point + k)]; };
  big u[3], w[3], t[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = sub(at(1, k), at(0, k));
    w[k] = sub(at(2, k), at(0, k));
    t[k] = sub(at(3, k), at(0, k));
  }
  const big m0 = sub(mul(u[1], w[2]), mul(u[2], w[1]));
  const big m1 = sub(mul(u[2], w[0]), mul(u[0], w[2]));
  const big m2 = sub(mul(u[0], w[1]), mul(u[1], w[0]));
  return sign(add(add(mul(t[0], m0), mul(t[1], m1)), mul(t[2], m2)));
}

int reference_orient2d(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  const auto v = to_common_integers({a.x, a.y, b.x, b.y, c.x, c.y});
  const big ux = sub(v[2], v[0]), uy = sub(v[3], v[1]), wx = sub(v[4], v[0]), wy = sub(v[5], v[1]);
  return sign(sub(mul(ux, wy), mul(uy, wx)));
}

// The same on small integer coordinates with __int128 (a second, independent reference).
int int128_orient3d(const std::array<std::int64_t, 12>& p) {
  const i128 ux = p[3] - p[0], uy = p[4] - p[1], uz = p[5] - p[2];
  const i128 vx = p[6] - p[0], vy = p[7] - p[1], vz = p[8] - p[2];
  const i128 wx = p[9] - p[0], wy = p[10] - p[1], wz = p[11] - p[2];
  const i128 d = wx * (uy * vz - uz * vy) + wy * (uz * vx - ux * vz) + wz * (ux * vy - uy * vx);
  return d > 0 ? 1 : d < 0 ? -1 : 0;
}

glm::dvec3 nudge(glm::dvec3 p, int coordinate, int ulps) {
  for (int i = 0; i < std::abs(ulps); ++i)
    p[coordinate] = std::nextafter(p[coordinate], ulps > 0 ? std::numeric_limits<double>::infinity()
                                                           : -std::numeric_limits<double>::infinity());
  return p;
}

}  // namespace

using cellforge::orient2d;
using cellforge::orient3d;

TEST_CASE("orient2d and orient3d follow the documented sign conventions") {
  CHECK(orient2d(glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(0, 1)) == 1);
  CHECK(orient2d(glm::dvec2(0, 0), glm::dvec2(0, 1), glm::dvec2(1, 0)) == -1);
  CHECK(orient2d(glm::dvec2(0, 0), glm::dvec2(1, 1), glm::dvec2(3, 3)) == 0);
  const glm::dvec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  CHECK(orient3d(o, x, y, z) == 1);  // z is on the side of (x - o) × (y - o)
  CHECK(orient3d(o, y, x, z) == -1);
  CHECK(orient3d(o, x, y, glm::dvec3(5, -7, 0)) == 0);
  CHECK(cellforge::orient3d_value(o, x, y, z) == doctest::Approx(1.0));
  CHECK(cellforge::orient2d_value(glm::dvec2(0, 0), glm::dvec2(2, 0), glm::dvec2(0, 2)) ==
        doctest::Approx(4.0));
}

TEST_CASE("orient3d agrees with __int128 on integer grids, zeros included") {
  std::mt19937_64 rng(7);
  for (const int range : {2, 50, 1 << 20}) {
    std::uniform_int_distribution<std::int64_t> coord(-range, range);
    int zeros = 0;
    for (int trial = 0; trial < 20000; ++trial) {
      std::array<std::int64_t, 12> p{};
      for (auto& c : p) c = coord(rng);
      if (trial % 3 == 0)  // force coplanarity: d = a + (b - a) + (c - a)
        for (int k = 0; k < 3; ++k) p[9 + k] = p[3 + k] + p[6 + k] - p[k];
      glm::dvec3 v[4];
      for (int i = 0; i < 4; ++i)
        v[i] = glm::dvec3(static_cast<double>(p[3 * i]), static_cast<double>(p[3 * i + 1]),
                          static_cast<double>(p[3 * i + 2]));
      const int expected = int128_orient3d(p);
      zeros += expected == 0;
      REQUIRE(orient3d(v[0], v[1], v[2], v[3]) == expected);
      REQUIRE(cellforge::detail::orient3d_exact(v[0], v[1], v[2], v[3]) == expected);
    }
    CHECK(zeros >= 20000 / 3);
  }
}

TEST_CASE("orient2d agrees with __int128 on integer grids") {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::int64_t> coord(-(1 << 26), 1 << 26);
  for (int trial = 0; trial < 20000; ++trial) {
    std::int64_t ax = coord(rng), ay = coord(rng), bx = coord(rng), by = coord(rng);
    std::int64_t cx = coord(rng), cy = coord(rng);
    if (trial % 2 == 0) {  // c on the line through a and b
      cx = ax + 3 * (bx - ax);
      cy = ay + 3 * (by - ay);
    }
    const i128 det = static_cast<i128>(bx - ax) * (cy - ay) - static_cast<i128>(by - ay) * (cx - ax);
    const int expected = det > 0 ? 1 : det < 0 ? -1 : 0;
    auto d = [](std::int64_t v) { return static_cast<double>(v); };
    REQUIRE(orient2d(d(ax), d(ay), d(bx), d(by), d(cx), d(cy)) == expected);
  }
}

TEST_CASE("orient2d: the classic failure of naive evaluation near a line") {
  // a walks a 64 x 64 grid of ulps around (0.5, 0.5); b and c lie on the line y = x.
  // Plain floating point gets many of these signs wrong; the predicate must not.
  const glm::dvec2 b(12, 12), c(24, 24);
  int naive_wrong = 0, zeros = 0, positives = 0;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const glm::dvec2 a(0.5 + i * 0x1p-53, 0.5 + j * 0x1p-53);
      const int expected = reference_orient2d(a, b, c);
      REQUIRE(orient2d(a, b, c) == expected);
      const double naive = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      naive_wrong += (naive > 0 ? 1 : naive < 0 ? -1 : 0) != expected;
      zeros += expected == 0;
      positives += expected > 0;
    }
  CHECK(naive_wrong > 100);  // the test has teeth: the naive formula fails here
  CHECK(zeros >= 32);        // the diagonal i == j is exactly on the line
  CHECK(positives > 1000);
}

TEST_CASE("orient3d: points on a plane perturbed by single ulps") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int naive_wrong = 0, decided_by_exact = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const glm::dvec3 a(unit(rng), unit(rng), unit(rng)), b(unit(rng), unit(rng), unit(rng)),
        c(unit(rng), unit(rng), unit(rng));
    // d is (a rounding of) a point of the plane, then moved by -2..2 ulps in one coordinate.
    const double s = unit(rng), t = unit(rng);
    glm::dvec3 d = a + s * (b - a) + t * (c - a);
    d = nudge(d, trial % 3, trial % 5 - 2);
    const int expected = reference_orient3d(a, b, c, d);
    REQUIRE(orient3d(a, b, c, d) == expected);
    // Symmetries of the determinant: an even permutation keeps the sign, an odd one flips it.
    REQUIRE(orient3d(b, c, a, d) == expected);
    REQUIRE(orient3d(b, a, c, d) == -expected);
    REQUIRE(orient3d(a, b, d, c) == -expected);
    double value = 0;
    const int filtered =
        cellforge::detail::orient3d_filter(cellforge::detail::prepare_orient3d(a, b, c), d, value);
    if (filtered != 0) REQUIRE(filtered == expected);  // the filter never claims a wrong sign
    decided_by_exact += filtered == 0;
    naive_wrong += (value > 0 ? 1 : value < 0 ? -1 : 0) != expected;
  }
  CHECK(decided_by_exact > 1000);
  CHECK(naive_wrong > 100);
}

TEST_CASE("orient3d: exactly coplanar dyadic points, then one ulp off the plane") {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> small(-1000, 1000);
  for (int trial = 0; trial < 2000; ++trial) {
    // Coordinates k / 1024: sums and the combination below are exact in doubles.
    auto r = [&] { return small(rng) / 1024.0; };
    const glm::dvec3 a(r(), r(), r()), b(r(), r(), r()), c(r(), r(), r());
    const double s = small(rng) / 8.0, t = small(rng) / 8.0;
    const glm::dvec3 d = a + s * (b - a) + t * (c - a);
    REQUIRE(reference_orient3d(a, b, c, d) == 0);
    REQUIRE(orient3d(a, b, c, d) == 0);
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 up = nudge(d, k, 1), down = nudge(d, k, -1);
      REQUIRE(orient3d(a, b, c, up) == reference_orient3d(a, b, c, up));
      REQUIRE(orient3d(a, b, c, down) == reference_orient3d(a, b, c, down));
    }
  }
}

TEST_CASE("orient3d stays exact for tiny, huge, subnormal and mixed magnitudes") {
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<std::int64_t> coord(-30, 30);
  for (int trial = 0; trial < 3000; ++trial) {
    std::array<std::int64_t, 12> p{};
    for (auto& c : p) c = coord(rng);
    if (trial % 2 == 0)
      for (int k = 0; k < 3; ++k) p[9 + k] = 2 * p[3 + k] - p[k];  // d on the line a-b: coplanar
    const int expected = int128_orient3d(p);
    // Scaling every coordinate by a power of two keeps the sign (det scales by s³ > 0).
    for (const int e : {-1074 + 5, -1060, -600, -30, 0, 200, 900, 1015}) {
      glm::dvec3 v[4];
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k)
          v[i][k] = std::ldexp(static_cast<double>(p[static_cast<std::size_t>(3 * i + k)]), e);
      REQUIRE(orient3d(v[0], v[1], v[2], v[3]) == expected);
    }
  }
  // Mixed: a far-away translation plus tiny offsets; the reference sees every bit.
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 500; ++trial) {
    const glm::dvec3 far(1e300, -1e299, 3e298);
    const glm::dvec3 a = far, b = far + glm::dvec3(1e284, 0, 0), c = far + glm::dvec3(0, 1e284, 0);
    const glm::dvec3 d(unit(rng) * 1e-300, unit(rng) * 1e-290, unit(rng));
    REQUIRE(orient3d(a, b, c, d) == reference_orient3d(a, b, c, d));
    const glm::dvec3 e(std::ldexp(unit(rng), -1070), 0x1p-1074 * (trial % 7), std::ldexp(unit(rng), 1000));
    REQUIRE(orient3d(glm::dvec3(0), glm::dvec3(0x1p-1074, 0, 0), glm::dvec3(0, 0x1p-1074, 0), e) ==
            reference_orient3d(glm::dvec3(0), glm::dvec3(0x1p-1074, 0, 0), glm::dvec3(0, 0x1p-1074, 0), e));
  }
  // Differences that overflow: the filter gives up and the exact path still answers.
  const double big_value = 1.7e308;
  const glm::dvec3 a(-big_value, 0, 0), b(big_value, 0, 0), c(0, big_value, 0);
  CHECK(orient3d(a, b, c, glm::dvec3(0, 0, 1)) == 1);
  CHECK(orient3d(a, b, c, glm::dvec3(0, 0, -1)) == -1);
  CHECK(orient3d(a, b, c, glm::dvec3(5, -3, 0)) == 0);
}

TEST_CASE("non-finite inputs give 0, never undefined behaviour") {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const glm::dvec3 o(0), x(1, 0, 0), y(0, 1, 0);
  CHECK(orient3d(o, x, y, glm::dvec3(0, 0, nan)) == 0);
  CHECK(orient3d(o, x, y, glm::dvec3(inf, 0, 1)) == 0);
  CHECK(orient2d(0, 0, 1, 0, nan, 1) == 0);
  CHECK(orient2d(0, 0, inf, 0, 0, 1) == 0);
}

TEST_CASE_TEMPLATE("orient3d works on every registered point type", P, glm::dvec3, std::array<float, 3>,
                   test_support::user_point) {
  auto make = [](double x, double y, double z) { return cellforge::point_traits<P>::make(x, y, z); };
  const P a = make(0.1f, 0.2f, 0.3f), b = make(1, 0.25f, 0.5f), c = make(0.125f, 1, 0.75f);
  CHECK(orient3d(a, b, c, make(0.5f, 0.5f, 2)) == 1);
  CHECK(orient3d(a, b, c, make(0.5f, 0.5f, -2)) == -1);
  // Float inputs are exact in double: the reference sees the same values.
  const P d = make(0.3f, 0.7f, 0.2f);
  CHECK(orient3d(a, b, c, d) == reference_orient3d(cellforge::to_dvec3(a), cellforge::to_dvec3(b),
                                                   cellforge::to_dvec3(c), cellforge::to_dvec3(d)));
}

TEST_CASE("collinear is exact in 3D") {
  const glm::dvec3 a(0.1, 0.2, 0.3), b(0.4, 0.8, 1.2);
  CHECK(cellforge::collinear(glm::dvec3(1, 2, 3), glm::dvec3(2, 4, 6), glm::dvec3(-1, -2, -3)));
  CHECK(cellforge::collinear(a, a, b));
  CHECK_FALSE(
      cellforge::collinear(glm::dvec3(1, 2, 3), glm::dvec3(2, 4, 6), nudge(glm::dvec3(3, 6, 9), 2, 1)));
  CHECK_FALSE(cellforge::collinear(glm::dvec3(0), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1)));
}

}  // namespace predicates_tests

TEST_CASE("union_find: sets join, the smaller root survives, joining twice reports no change") {
  cellforge::detail::union_find u(6);
  for (std::uint32_t i = 0; i < 6; ++i) CHECK(u.find(i) == i);
  CHECK(u.unite(4, 2));
  CHECK(u.unite(5, 4));
  CHECK_FALSE(u.unite(2, 5));  // already one set
  CHECK(u.find(5) == 2);       // the smallest member is the representative
  CHECK(u.find(4) == 2);
  CHECK(u.unite(3, 0));
  CHECK(u.find(3) == 0);
  CHECK(u.find(1) == 1);
  CHECK(u.find(2) != u.find(0));
  CHECK(u.unite(5, 3));
  for (const std::uint32_t i : {0u, 2u, 3u, 4u, 5u}) CHECK(u.find(i) == 0);
}

TEST_CASE("core/detail/geometry.hpp: any_perpendicular's three rules, each pinned to its axis") {
  namespace cd = cellforge::detail;
  using rule = cd::perpendicular_rule;
  // The axis each rule must cross with, written out independently of the helper.
  const auto expected_axis = [](const glm::dvec3& n, rule r) {
    const double x = std::abs(n.x), y = std::abs(n.y), z = std::abs(n.z);
    if (r == rule::least_aligned)
      return x <= y && x <= z ? glm::dvec3(1, 0, 0) : y <= z ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    const double limit = r == rule::x_below_0_6 ? 0.6 : 0.9;
    return x < limit ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  };
  std::mt19937_64 rng(34);
  std::normal_distribution<double> g;
  std::vector<glm::dvec3> dirs{{1, 0, 0},
                               {0, -1, 0},
                               {0, 0, 1},
                               glm::normalize(glm::dvec3(0.7, 0.5, 0.5)),
                               glm::dvec3(0.6, 0.8, 0),
                               glm::dvec3(-0.9, 0, std::sqrt(1 - 0.81))};
  for (int i = 0; i < 200; ++i) dirs.push_back(glm::normalize(glm::dvec3(g(rng), g(rng), g(rng))));
  for (const rule r : {rule::least_aligned, rule::x_below_0_6, rule::x_below_0_9})
    for (const glm::dvec3& n : dirs) {
      const glm::dvec3 u = cd::any_perpendicular(n, r);
      CHECK(std::abs(glm::dot(u, n)) < 1e-15);
      CHECK(std::abs(glm::length(u) - 1.0) < 1e-15);
      CHECK(u == glm::normalize(glm::cross(n, expected_axis(n, r))));
    }
  // The rules differ: |n.x| = 0.77 is x for the soups' rule, y for the wireframe's and the tubes'.
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.7, 0.5, 0.5));
  CHECK(cd::any_perpendicular(n, rule::x_below_0_9) == glm::normalize(glm::cross(n, glm::dvec3(1, 0, 0))));
  CHECK(cd::any_perpendicular(n, rule::x_below_0_6) == glm::normalize(glm::cross(n, glm::dvec3(0, 1, 0))));
  CHECK(cd::any_perpendicular(n) == cd::any_perpendicular(n, rule::least_aligned));
}

TEST_CASE("core/detail/geometry.hpp: point_in_polygon splits a shared side exactly") {
  namespace cd = cellforge::detail;
  // Two quadrilaterals sharing the side from s0 to s1 (neither coordinate a round number):
  // every point of the strip between them lies in exactly one, on the shared side too, even
  // one ulp from it, where a rounded crossing abscissa can put it in both or in neither.
  const glm::dvec2 s0(0.1, 0.1), s1(0.7, 0.9);
  const std::vector<glm::dvec2> left{s0, s1, {-1, 0.9}, {-1, 0.1}}, right{s1, s0, {2, 0.1}, {2, 0.9}};
  std::size_t both = 0, neither = 0, points = 0;
  for (int k = 1; k < 64; ++k) {
    const double y = 0.1 + 0.8 * k / 64.0;
    double x = s0.x + (s1.x - s0.x) * (y - s0.y) / (s1.y - s0.y);  // near the shared side
    for (int i = 0; i < 8; ++i) x = std::nextafter(x, -1.0);
    for (int i = 0; i < 16; ++i, x = std::nextafter(x, 2.0)) {
      const bool a = cd::point_in_polygon(left, {x, y}), b = cd::point_in_polygon(right, {x, y});
      both += a && b, neither += !a && !b, ++points;
    }
  }
  CHECK(points == 63 * 16);
  CHECK(both == 0);
  CHECK(neither == 0);
  CHECK(cd::point_in_polygon(left, {-0.5, 0.5}));
  CHECK_FALSE(cd::point_in_polygon(left, {1.5, 0.5}));
  CHECK_FALSE(cd::point_in_polygon(left, {-0.5, 1.5}));
  CHECK(cd::point_in_polygon(right, {1.5, 0.5}));
}

TEST_CASE("core/detail/geometry.hpp: canonical_cycle is one form up to rotation and reversal") {
  namespace cd = cellforge::detail;
  const std::vector<std::uint32_t> want{1, 7, 5, 3, 8};
  CHECK(cd::canonical_cycle({5, 3, 8, 1, 7}) == want);
  CHECK(cd::canonical_cycle({8, 3, 5, 7, 1}) == want);  // reversed
  std::vector<std::uint32_t> c{8, 3, 5, 7, 1};
  CHECK(cd::make_canonical_cycle(c));  // reports the reversal
  CHECK(c == want);
  CHECK_FALSE(cd::make_canonical_cycle(c));
  CHECK(cd::canonical_cycle({4, 2}) == std::vector<std::uint32_t>{2, 4});
}
