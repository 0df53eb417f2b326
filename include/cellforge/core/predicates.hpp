// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Exact geometric predicates: orient2d and orient3d return the true sign of their
/// determinant for every finite double input. A floating-point filter with a proven error
/// bound decides almost every call in a few flops; when it cannot, the determinant is
/// evaluated exactly with multi-word integers. See docs/predicates.md.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/point_traits.hpp"

namespace cellforge {

namespace detail::exact {

// ------------------------------------------------------------------ words and products

/// 64 x 64 -> 128-bit product as (high, low) words.
template <class = void>
void mul_words(std::uint64_t a, std::uint64_t b, std::uint64_t& hi, std::uint64_t& lo) noexcept {
#if defined(__SIZEOF_INT128__)
  __extension__ typedef unsigned __int128 u128;
  const u128 p = static_cast<u128>(a) * b;
  hi = static_cast<std::uint64_t>(p >> 64);
  lo = static_cast<std::uint64_t>(p);
#else
  // Four 32 x 32 products; the middle sum cannot overflow 64 bits once split.
  const std::uint64_t a0 = a & 0xFFFFFFFFu, a1 = a >> 32, b0 = b & 0xFFFFFFFFu, b1 = b >> 32;
  const std::uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
  const std::uint64_t mid = (p00 >> 32) + (p01 & 0xFFFFFFFFu) + (p10 & 0xFFFFFFFFu);
  lo = (mid << 32) | (p00 & 0xFFFFFFFFu);
  hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
#endif
}

/// A finite double as sign · mant · 2^exp with an odd mantissa (mant = 0 for zero).
struct dyadic {
  std::uint64_t mant = 0;
  int exp = 0;
  bool negative = false;
};

/// Splits a double into its dyadic form, exactly, from its bit pattern; false for NaN
/// and infinities. O(1).
template <class = void>
bool decompose(double x, dyadic& d) noexcept {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const auto biased = static_cast<int>((bits >> 52) & 0x7FF);
  if (biased == 0x7FF) return false;
  const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
  d.negative = (bits >> 63) != 0;
  // Subnormals have no hidden bit and the exponent of the smallest normal.
  const std::uint64_t m = biased == 0 ? fraction : fraction | (std::uint64_t{1} << 52);
  if (m == 0) {
    d.mant = 0;
    d.exp = 0;
    return true;
  }
  const int tz = std::countr_zero(m);
  d.mant = m >> tz;
  d.exp = (biased == 0 ? -1074 : biased - 1075) + tz;
  return true;
}

/// A little-endian multi-word natural number with room for `Inline` words before it
/// spills to the heap: accumulators for the exact sums.
template <std::size_t Inline>
class words {
 public:
  explicit words(std::size_t n) : n_(n) {
    if (n > Inline)
      heap_.assign(n, 0);
    else
      std::fill_n(small_.data(), n, std::uint64_t{0});  // only the words in use
  }
  std::uint64_t* data() noexcept { return n_ > Inline ? heap_.data() : small_.data(); }
  const std::uint64_t* data() const noexcept { return n_ > Inline ? heap_.data() : small_.data(); }
  std::size_t size() const noexcept { return n_; }

 private:
  std::size_t n_;
  std::array<std::uint64_t, Inline> small_;
  std::vector<std::uint64_t> heap_;
};

/// acc += v · 2^shift, where v has n words; acc must be wide enough. O(size of acc).
template <class = void>
void add_shifted(std::uint64_t* acc, std::size_t acc_size, const std::uint64_t* v, std::size_t n,
                 std::size_t shift) noexcept {
  const std::size_t q = shift / 64;
  const unsigned r = static_cast<unsigned>(shift % 64);
  std::uint64_t carry = 0;
  std::size_t i = 0;
  for (; i <= n && q + i < acc_size; ++i) {
    const std::uint64_t low = i < n ? v[i] << r : 0;
    const std::uint64_t high = (r != 0 && i > 0) ? v[i - 1] >> (64 - r) : 0;
    const std::uint64_t w = low | high;
    std::uint64_t& slot = acc[q + i];
    const std::uint64_t s1 = slot + w;
    const std::uint64_t c1 = s1 < w ? 1 : 0;
    const std::uint64_t s2 = s1 + carry;
    const std::uint64_t c2 = s2 < carry ? 1 : 0;
    slot = s2;
    carry = c1 + c2;
  }
  for (std::size_t j = q + i; carry != 0 && j < acc_size; ++j) {
    acc[j] += carry;
    carry = acc[j] == 0 ? 1 : 0;
  }
}

/// Sign of (a - b) for two naturals of the same width. O(width).
template <class = void>
int compare(const std::uint64_t* a, const std::uint64_t* b, std::size_t n) noexcept {
  for (std::size_t i = n; i-- > 0;)
    if (a[i] != b[i]) return a[i] > b[i] ? 1 : -1;
  return 0;
}

/// The exact sign of Σ_t sign_t · Π_k v[index[t][k]], a sum of T products of K finite
/// doubles given in dyadic form. Every double is an odd integer times a power of two, so
/// after moving all terms to the smallest exponent the sum is an integer identity;
/// positive and negative parts are added separately and compared.
/// O(T · (K + width in words)); the width grows with the spread of the inputs' exponents.
template <std::size_t T, std::size_t K, std::size_t V>
int sign_of_sum(const std::array<dyadic, V>& v, const std::array<std::array<int, K>, T>& index,
                const std::array<int, T>& sign) noexcept {
  struct term {
    std::array<std::uint64_t, K> m{};  // product of the mantissas (53 · K bits fit in K words)
    std::size_t words = 0;             // 0: the term is zero
    long exp = 0;
    bool negative = false;
  };
  std::array<term, T> terms{};
  long min_exp = 0;
  bool any = false;
  for (std::size_t t = 0; t < T; ++t) {
    term& out = terms[t];
    out.negative = sign[t] < 0;
    out.m[0] = 1;
    out.words = 1;
    for (std::size_t k = 0; k < K && out.words != 0; ++k) {
      const dyadic& d = v[static_cast<std::size_t>(index[t][k])];
      if (d.mant == 0) {
        out.words = 0;
        break;
      }
      out.negative = out.negative != d.negative;
      out.exp += d.exp;
      std::uint64_t carry = 0;
      for (std::size_t w = 0; w < out.words; ++w) {
        std::uint64_t hi = 0, lo = 0;
        mul_words(out.m[w], d.mant, hi, lo);
        lo += carry;
        hi += lo < carry ? 1 : 0;
        out.m[w] = lo;
        carry = hi;
      }
      if (carry != 0) out.m[out.words++] = carry;
    }
    if (out.words == 0) continue;
    if (!any || out.exp < min_exp) min_exp = out.exp;
    any = true;
  }
  if (!any) return 0;
  std::size_t bits = 0;
  for (const term& t : terms)
    if (t.words != 0)
      bits = std::max<std::size_t>(bits, static_cast<std::size_t>(t.exp - min_exp) + 64 * t.words);
  const std::size_t width = bits / 64 + 2;  // one spare word absorbs the carries of T terms
  words<16> pos(width), neg(width);
  for (const term& t : terms) {
    if (t.words == 0) continue;
    words<16>& acc = t.negative ? neg : pos;
    add_shifted(acc.data(), width, t.m.data(), t.words, static_cast<std::size_t>(t.exp - min_exp));
  }
  return compare(pos.data(), neg.data(), width);
}

/// Sign of a permutation of {0, ..., n-1} given as an array. O(n²).
template <std::size_t N>
constexpr int permutation_sign(const std::array<int, N>& p) noexcept {
  int inversions = 0;
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = i + 1; j < N; ++j) inversions += p[i] > p[j] ? 1 : 0;
  return inversions % 2 == 0 ? 1 : -1;
}

/// The determinant of the (N+1) x (N+1) matrix whose row r is (p_r[0], ..., p_r[N-1], 1),
/// as a list of monomials: for each assignment of distinct rows to the N coordinate
/// columns (the remaining row takes the column of ones), the rows and the sign.
template <std::size_t N>
struct lifted_determinant {
  static constexpr std::size_t rows = N + 1;
  static constexpr std::size_t count = N == 2 ? 6 : 24;  // (N+1)!
  std::array<std::array<int, N>, count> row{};           // row[t][k]: row giving coordinate k
  std::array<int, count> sign{};
  constexpr lifted_determinant() {
    std::array<int, rows> perm{};  // perm[r] = column of row r
    for (std::size_t r = 0; r < rows; ++r) perm[r] = static_cast<int>(r);
    std::size_t t = 0;
    do {
      for (std::size_t r = 0; r < rows; ++r)
        if (perm[r] < static_cast<int>(N)) row[t][static_cast<std::size_t>(perm[r])] = static_cast<int>(r);
      sign[t] = permutation_sign(perm);
      ++t;
    } while (next_permutation(perm));
  }
  static constexpr bool next_permutation(std::array<int, rows>& p) {
    std::size_t i = rows - 1;
    while (i > 0 && p[i - 1] >= p[i]) --i;
    if (i == 0) return false;
    std::size_t j = rows - 1;
    while (p[j] <= p[i - 1]) --j;
    std::swap(p[i - 1], p[j]);
    for (std::size_t a = i, b = rows - 1; a < b; ++a, --b) std::swap(p[a], p[b]);
    return true;
  }
};

/// Exact sign of the lifted determinant det[(p_r, 1)] over N+1 points of dimension N;
/// 0 when a coordinate is NaN or infinite.
template <std::size_t N>
int lifted_sign(const std::array<std::array<double, N>, N + 1>& p) noexcept {
  static constexpr lifted_determinant<N> det{};
  std::array<dyadic, N*(N + 1)> v{};
  for (std::size_t r = 0; r <= N; ++r)
    for (std::size_t k = 0; k < N; ++k)
      if (!decompose(p[r][k], v[r * N + k])) return 0;
  // Monomial t takes coordinate k from row det.row[t][k]: value index row * N + k.
  static constexpr auto index = [] {
    std::array<std::array<int, N>, lifted_determinant<N>::count> ix{};
    for (std::size_t t = 0; t < ix.size(); ++t)
      for (std::size_t k = 0; k < N; ++k)
        ix[t][k] = det.row[t][k] * static_cast<int>(N) + static_cast<int>(k);
    return ix;
  }();
  return sign_of_sum(v, index, det.sign);
}

/// Exact sign of the plain determinant det[p_0; ...; p_{N-1}] of N vectors of dimension N
/// (N = 2 or 3); 0 when a coordinate is NaN or infinite.
template <std::size_t N>
int plain_sign(const std::array<std::array<double, N>, N>& p) noexcept {
  static_assert(N == 2 || N == 3);
  // Monomial: row r gives coordinate perm[r]; the sign is the permutation's.
  static constexpr auto table = [] {
    constexpr std::size_t count = N == 2 ? 2 : 6;
    std::pair<std::array<std::array<int, N>, count>, std::array<int, count>> out{};
    std::size_t t = 0;
    std::array<int, N> q{};
    for (std::size_t r = 0; r < N; ++r) q[r] = static_cast<int>(r);
    do {
      for (std::size_t r = 0; r < N; ++r)
        out.first[t][static_cast<std::size_t>(q[r])] = static_cast<int>(r * N) + q[r];
      out.second[t] = permutation_sign(q);
      ++t;
    } while (std::next_permutation(q.begin(), q.end()));
    return out;
  }();
  std::array<dyadic, N * N> v{};
  for (std::size_t r = 0; r < N; ++r)
    for (std::size_t k = 0; k < N; ++k)
      if (!decompose(p[r][k], v[r * N + k])) return 0;
  return sign_of_sum(v, table.first, table.second);
}

/// Knuth's two-difference: true when a - b rounds to itself, i.e. is exact (false on overflow).
template <class = void>
bool exact_difference(double a, double b, double& d) noexcept {
  d = a - b;
  const double b_virtual = a - d;
  const double a_virtual = d + b_virtual;
  const double error = (a - a_virtual) + (b_virtual - b);
  return error == 0.0;
}

}  // namespace detail::exact

namespace detail {

// Error-bound constants of the filters (Shewchuk, "Adaptive precision floating-point
// arithmetic and fast robust geometric predicates", 1997, section 4.2), with eps = 2^-53.
inline constexpr double predicate_eps = 0x1p-53;
inline constexpr double orient2d_bound = (3.0 + 16.0 * predicate_eps) * predicate_eps;
inline constexpr double orient3d_bound = (7.0 + 56.0 * predicate_eps) * predicate_eps;
// Gradual underflow adds at most 2^-1075 per rounded product; this absolute term covers
// those errors (times the largest factor they are multiplied by) with a wide margin, so a
// filter decision stays proven for tiny inputs too.
inline constexpr double underflow_guard = 0x1p-1000;

/// The part of an orient3d filter that depends only on the plane (a, b, c): many
/// queries against one plane (the hull's faces) reuse it.
struct orient3d_plane {
  glm::dvec3 a{0.0};      ///< the pivot
  glm::dvec3 minor{0.0};  ///< (b - a) × (c - a), rounded as the filter computes it
  glm::dvec3 perm{0.0};   ///< per coordinate, the sum of the absolute values of the minor's two products
};

/// Prepares the plane through a, b, c for orient3d_filter. O(1).
template <class = void>
orient3d_plane prepare_orient3d(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) noexcept {
  const glm::dvec3 u = b - a, v = c - a;
  const double yz = u.y * v.z, zy = u.z * v.y, zx = u.z * v.x, xz = u.x * v.z, xy = u.x * v.y, yx = u.y * v.x;
  orient3d_plane p;
  p.a = a;
  p.minor = {yz - zy, zx - xz, xy - yx};
  p.perm = {std::fabs(yz) + std::fabs(zy), std::fabs(zx) + std::fabs(xz), std::fabs(xy) + std::fabs(yx)};
  return p;
}

/// The filtered orient3d of the prepared plane and d: +1 or -1 when the floating-point
/// value provably has the true sign, 0 when the filter cannot decide (then the exact
/// evaluation must). `value` receives the approximate determinant. O(1), about 20 flops.
template <class = void>
int orient3d_filter(const orient3d_plane& p, const glm::dvec3& d, double& value) noexcept {
  const double wx = d.x - p.a.x, wy = d.y - p.a.y, wz = d.z - p.a.z;
  const double det = wx * p.minor.x + wy * p.minor.y + wz * p.minor.z;
  const double ax = std::fabs(wx), ay = std::fabs(wy), az = std::fabs(wz);
  const double permanent = ax * p.perm.x + ay * p.perm.y + az * p.perm.z;
  const double bound = orient3d_bound * permanent + underflow_guard * (1.0 + ax + ay + az);
  value = det;
  // NaN or overflow makes both comparisons false: the exact path then decides.
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return 0;
}

/// The exact orient3d, without a filter. O(1) (about 24 multi-word products).
template <class = void>
int orient3d_exact(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                   const glm::dvec3& d) noexcept {
  // When the nine differences are exact (integer grids, nearby points) the 3 x 3
  // determinant of the differences has 6 monomials instead of 24.
  std::array<std::array<double, 3>, 3> diff{};
  bool exact = true;
  const glm::dvec3* rows[3] = {&b, &c, &d};
  for (std::size_t r = 0; r < 3 && exact; ++r)
    for (int k = 0; k < 3 && exact; ++k)
      exact = exact::exact_difference((*rows[r])[k], a[k], diff[r][static_cast<std::size_t>(k)]);
  if (exact) return exact::plain_sign<3>(diff);
  // det[b-a; c-a; d-a] = -det[(a,1); (b,1); (c,1); (d,1)].
  return -exact::lifted_sign<3>({{{a.x, a.y, a.z}, {b.x, b.y, b.z}, {c.x, c.y, c.z}, {d.x, d.y, d.z}}});
}

/// The exact orient2d, without a filter. O(1) (six multi-word products).
template <class = void>
int orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy) noexcept {
  std::array<std::array<double, 2>, 2> diff{};
  if (exact::exact_difference(bx, ax, diff[0][0]) && exact::exact_difference(by, ay, diff[0][1]) &&
      exact::exact_difference(cx, ax, diff[1][0]) && exact::exact_difference(cy, ay, diff[1][1]))
    return exact::plain_sign<2>(diff);
  // det[b-a; c-a] = det[(a,1); (b,1); (c,1)].
  return exact::lifted_sign<2>({{{ax, ay}, {bx, by}, {cx, cy}}});
}

}  // namespace detail

/// Orientation of three 2D points: +1 when a, b, c turn counter-clockwise (positive
/// signed area), -1 when clockwise, 0 when collinear; exact for all finite inputs (0 for
/// NaN/Inf). O(1): a filter of ~15 flops, exact multi-word arithmetic when it cannot decide.
template <class = void>
int orient2d(double ax, double ay, double bx, double by, double cx, double cy) noexcept {
  const double left = (ax - cx) * (by - cy);
  const double right = (ay - cy) * (bx - cx);
  const double det = left - right;
  const double bound =
      detail::orient2d_bound * (std::fabs(left) + std::fabs(right)) + detail::underflow_guard;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return detail::orient2d_exact(ax, ay, bx, by, cx, cy);
}

/// orient2d on GLM 2-vectors. O(1).
template <class = void>
int orient2d(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) noexcept {
  return orient2d(a.x, a.y, b.x, b.y, c.x, c.y);
}

/// The approximate (rounded) value of the orient2d determinant, twice the signed area of
/// a, b, c; its sign may be wrong near zero. O(1).
template <class = void>
double orient2d_value(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) noexcept {
  return (a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x);
}

/// Orientation of d relative to the plane through a, b, c: +1 when d lies on the side
/// the right-hand normal (b - a) × (c - a) points to (a, b, c counter-clockwise seen from
/// d), -1 on the other side, 0 when the four points are coplanar; exact for all finite
/// inputs (0 for NaN/Inf). O(1): a ~30-flop filter, exact arithmetic when it cannot decide.
template <class = void>
int orient3d(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) noexcept {
  double value = 0.0;
  const int s = detail::orient3d_filter(detail::prepare_orient3d(a, b, c), d, value);
  return s != 0 ? s : detail::orient3d_exact(a, b, c, d);
}

/// orient3d on any registered point type (coordinates converted to double, which is
/// exact for float and for integers up to 2^53 in magnitude). O(1).
template <Point3 P>
int orient3d(const P& a, const P& b, const P& c, const P& d) {
  return orient3d(to_dvec3(a), to_dvec3(b), to_dvec3(c), to_dvec3(d));
}

/// The approximate (rounded) value of the orient3d determinant, six times the signed
/// volume of the tetrahedron a, b, c, d; its sign may be wrong near zero. O(1).
template <class = void>
double orient3d_value(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                      const glm::dvec3& d) noexcept {
  double value = 0.0;
  detail::orient3d_filter(detail::prepare_orient3d(a, b, c), d, value);
  return value;
}

/// True when three 3D points lie on one line (coincident points included); exact. O(1).
template <class = void>
bool collinear(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) noexcept {
  // Collinear in space exactly when collinear in all three coordinate projections.
  return orient2d(a.x, a.y, b.x, b.y, c.x, c.y) == 0 && orient2d(a.y, a.z, b.y, b.z, c.y, c.z) == 0 &&
         orient2d(a.z, a.x, b.z, b.x, c.z, c.x) == 0;
}

}  // namespace cellforge
