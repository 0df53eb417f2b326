// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// How cellforge reads and makes a user's 2D point type (the junctions of a line drawing):
/// `point2_traits<P>`, the concept `Point2<P>`, built-in support for GLM and std::array, and
/// a one-line registration macro for any struct with two named members.

#include <array>
#include <concepts>
#include <cstddef>
#include <type_traits>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/point_traits.hpp"

namespace cellforge {

/// Specialise for a 2D point type P with: `using scalar = ...;`,
/// `static scalar get(const P&, std::size_t i)` (i in 0..1) and `static P make(scalar x, scalar y)`.
/// The primary template is empty so that an unregistered type fails `Point2` at the call.
template <class P>
struct point2_traits {};

namespace detail {
template <class P>
using point2_scalar_t = typename point2_traits<P>::scalar;
}  // namespace detail

/// A copyable type registered through point2_traits: arithmetic scalar, coordinates read by
/// index, points made from two scalars.
template <class P>
concept Point2 = requires {
  typename point2_traits<P>::scalar;
}
&&std::is_arithmetic_v<detail::point2_scalar_t<P>>&& requires(const P& p, std::size_t i,
                                                              detail::point2_scalar_t<P> s) {
  { point2_traits<P>::get(p, i) } -> std::convertible_to<detail::point2_scalar_t<P>>;
  { point2_traits<P>::make(s, s) } -> std::same_as<P>;
}
&&std::copyable<P>;

/// GLM 2-vectors of any scalar and qualifier.
template <class T, glm::qualifier Q>
struct point2_traits<glm::vec<2, T, Q>> {
  using scalar = T;
  static constexpr T get(const glm::vec<2, T, Q>& p, std::size_t i) noexcept {
    return p[static_cast<typename glm::vec<2, T, Q>::length_type>(i)];
  }
  static constexpr glm::vec<2, T, Q> make(T x, T y) noexcept { return {x, y}; }
};

/// std::array<T, 2>.
template <class T>
requires std::is_arithmetic_v<T>
struct point2_traits<std::array<T, 2>> {
  using scalar = T;
  static constexpr T get(const std::array<T, 2>& p, std::size_t i) noexcept { return p[i]; }
  static constexpr std::array<T, 2> make(T x, T y) noexcept { return {x, y}; }
};

/// Scalar type of a registered 2D point.
template <Point2 P>
using scalar2_t = typename point2_traits<P>::scalar;

/// Converts any registered 2D point to the double-precision GLM vector algorithms compute in. O(1).
template <Point2 P>
constexpr glm::dvec2 to_dvec2(const P& p) {
  return {static_cast<double>(point2_traits<P>::get(p, 0)), static_cast<double>(point2_traits<P>::get(p, 1))};
}

/// Converts a double-precision GLM vector back to the user's 2D point type. O(1).
template <Point2 P>
constexpr P from_dvec2(const glm::dvec2& v) {
  using S = scalar2_t<P>;
  return point2_traits<P>::make(static_cast<S>(v.x), static_cast<S>(v.y));
}

/// The 3D point type that the sketch stages give back for a drawing in 2D point type P: for
/// `glm::vec<2, T>` it is `glm::vec<3, T>`, for `std::array<T, 2>` `std::array<T, 3>`. Specialise
/// it (`using type = my::vec3;`) for a user's 2D type, or name the 3D type at the call.
template <class P>
struct lifted_point {};

template <class T, glm::qualifier Q>
struct lifted_point<glm::vec<2, T, Q>> {
  using type = glm::vec<3, T, Q>;
};

template <class T>
struct lifted_point<std::array<T, 2>> {
  using type = std::array<T, 3>;
};

namespace detail {
/// lifted_point<P>::type, or a static assertion that says what to do (not "no type named
/// 'type' in lifted_point").
template <class P>
struct lifted_or_assert {
  static_assert(
      requires { typename lifted_point<P>::type; },
      "cellforge: no 3D point type is known for this 2D point type: name it at the call "
      "(e.g. drawing_to_cells<my::vec3>(drawing)) or specialise cellforge::lifted_point<P> "
      "with `using type = my::vec3;`");
  using type = typename lifted_point<P>::type;
};
/// The 3D point type a sketch stage returns: Q when the caller names one, else lifted_point_t<P>,
/// looked up only then, so that naming Q needs no lifted_point.
template <class Q, class P>
struct result_point {
  using type = Q;
};
template <class P>
struct result_point<void, P> {
  using type = typename lifted_or_assert<P>::type;
};
template <class Q, class P>
using result_point_t = typename result_point<Q, P>::type;
}  // namespace detail

/// The 3D point type of a 2D point type (see lifted_point).
template <class P>
using lifted_point_t = typename detail::lifted_or_assert<P>::type;

}  // namespace cellforge

/// Registers a struct with two public data members as a cellforge 2D point, in one line at
/// global scope: `CELLFORGE_REGISTER_POINT2(my::pt, double, x, y)`. A point is made by
/// assigning the members of a default-constructed one, or by the constructor `Type(x, y)`.
#define CELLFORGE_REGISTER_POINT2(Type, Scalar, MX, MY)                            \
  template <>                                                                      \
  struct cellforge::point2_traits<Type> {                                          \
    using scalar = Scalar;                                                         \
    static constexpr Scalar get(const Type& p, std::size_t i) noexcept {           \
      return i == 0 ? static_cast<Scalar>(p.MX) : static_cast<Scalar>(p.MY);       \
    }                                                                              \
    template <class T = Type> /* a template, so the untaken branch is discarded */ \
    static constexpr T make(Scalar x, Scalar y) {                                  \
      if constexpr (std::is_default_constructible_v<T>) {                          \
        T p{};                                                                     \
        p.MX = x;                                                                  \
        p.MY = y;                                                                  \
        return p;                                                                  \
      } else {                                                                     \
        return T(x, y);                                                            \
      }                                                                            \
    }                                                                              \
  }

// The `get` of the getter-based 2D registrations (not for direct use).
#define CELLFORGE_DETAIL_POINT2_GETTERS(Type, Scalar, GX, GY)                  \
  static Scalar get(const Type& p, std::size_t i) {                            \
    return i == 0 ? static_cast<Scalar>(p.GX()) : static_cast<Scalar>(p.GY()); \
  }

/// Registers a 2D point class with getters and setters, e.g. a CAD sketcher's point class:
/// `CELLFORGE_REGISTER_POINT2_GET_SET(cad::Pt2d, double, X, Y, SetX, SetY)`. Without a default
/// constructor, points are made by `Type(x, y)` instead of the setters.
#define CELLFORGE_REGISTER_POINT2_GET_SET(Type, Scalar, GX, GY, SX, SY)            \
  template <>                                                                      \
  struct cellforge::point2_traits<Type> {                                          \
    using scalar = Scalar;                                                         \
    CELLFORGE_DETAIL_POINT2_GETTERS(Type, Scalar, GX, GY)                          \
    template <class T = Type> /* a template, so the untaken branch is discarded */ \
    static T make(Scalar x, Scalar y) {                                            \
      if constexpr (std::is_default_constructible_v<T>) {                          \
        T p{};                                                                     \
        p.SX(x);                                                                   \
        p.SY(y);                                                                   \
        return p;                                                                  \
      } else {                                                                     \
        return T(x, y);                                                            \
      }                                                                            \
    }                                                                              \
  }

/// Registers an immutable 2D point class read through getters and made by its constructor
/// `Type(x, y)`: `CELLFORGE_REGISTER_POINT2_GET_CTOR(cad::Pt2d, double, x, y)`.
#define CELLFORGE_REGISTER_POINT2_GET_CTOR(Type, Scalar, GX, GY) \
  template <>                                                    \
  struct cellforge::point2_traits<Type> {                        \
    using scalar = Scalar;                                       \
    CELLFORGE_DETAIL_POINT2_GETTERS(Type, Scalar, GX, GY)        \
    static Type make(Scalar x, Scalar y) { return Type(x, y); }  \
  }
