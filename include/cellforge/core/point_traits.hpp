// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// How cellforge reads and makes a user's 3D point type: `point_traits<P>`, the
/// concept `Point3<P>`, built-in support for GLM and std::array, and a one-line
/// registration macro for any struct with three named members.

#include <array>
#include <concepts>
#include <cstddef>
#include <type_traits>

#include <glm/vec3.hpp>

#include "cellforge/core/detail/if_satisfied.hpp"

namespace cellforge {

/// Specialise for a point type P with: `using scalar = ...;`,
/// `static scalar get(const P&, std::size_t i)` (i in 0..2) and
/// `static P make(scalar x, scalar y, scalar z)`. That is all cellforge needs: P must be
/// copyable, never default-constructible. The primary template is empty on purpose so that
/// an unregistered type, or a trait that lacks one of the three, fails the `Point3` concept
/// at the call.
template <class P>
struct point_traits {};

namespace detail {
template <class P>
using point_scalar_t = typename point_traits<P>::scalar;
}  // namespace detail

/// A copyable type registered through point_traits: its scalar is a floating-point or
/// integral arithmetic type, coordinates can be read by index and a point made.
template <class P>
concept Point3 = requires {
  typename point_traits<P>::scalar;
}
&&std::is_arithmetic_v<detail::point_scalar_t<P>>&& requires(const P& p, std::size_t i,
                                                             detail::point_scalar_t<P> s) {
  { point_traits<P>::get(p, i) } -> std::convertible_to<detail::point_scalar_t<P>>;
  { point_traits<P>::make(s, s, s) } -> std::same_as<P>;
}
&&std::copyable<P>;

/// GLM 3-vectors of any scalar and qualifier.
template <class T, glm::qualifier Q>
struct point_traits<glm::vec<3, T, Q>> {
  using scalar = T;
  static constexpr T get(const glm::vec<3, T, Q>& p, std::size_t i) noexcept {
    return p[static_cast<typename glm::vec<3, T, Q>::length_type>(i)];
  }
  static constexpr glm::vec<3, T, Q> make(T x, T y, T z) noexcept { return {x, y, z}; }
};

/// std::array<T, 3>.
template <class T>
requires std::is_arithmetic_v<T>
struct point_traits<std::array<T, 3>> {
  using scalar = T;
  static constexpr T get(const std::array<T, 3>& p, std::size_t i) noexcept { return p[i]; }
  static constexpr std::array<T, 3> make(T x, T y, T z) noexcept { return {x, y, z}; }
};

/// Scalar type of a registered point.
template <Point3 P>
using scalar_t = typename point_traits<P>::scalar;

namespace detail {
/// The scalar type of P (unconstrained, for if_satisfied_t).
template <class P>
using scalar_for = typename point_traits<P>::scalar;
}  // namespace detail

/// Coordinate i (0, 1, 2) of p. O(1).
template <Point3 P>
constexpr detail::if_satisfied_t<Point3<P>, detail::scalar_for, P> coord(const P& p, std::size_t i) noexcept(
    noexcept(point_traits<P>::get(p, i))) {
  return point_traits<P>::get(p, i);
}

/// Converts any registered point to the double-precision GLM vector algorithms compute in. O(1).
template <Point3 P>
constexpr glm::dvec3 to_dvec3(const P& p) {
  return {static_cast<double>(point_traits<P>::get(p, 0)), static_cast<double>(point_traits<P>::get(p, 1)),
          static_cast<double>(point_traits<P>::get(p, 2))};
}

/// Converts a double-precision GLM vector back to the user's point type. O(1).
template <Point3 P>
constexpr P from_dvec3(const glm::dvec3& v) {
  using S = scalar_t<P>;
  return point_traits<P>::make(static_cast<S>(v.x), static_cast<S>(v.y), static_cast<S>(v.z));
}

}  // namespace cellforge

/// Registers a struct with three public data members as a cellforge point, in one line
/// at global scope: `CELLFORGE_REGISTER_POINT3(my::vec, double, x, y, z)`. A point is made by
/// assigning the members of a default-constructed one, or, for a type without a default
/// constructor, by its constructor `Type(x, y, z)`.
#define CELLFORGE_REGISTER_POINT3(Type, Scalar, MX, MY, MZ)                        \
  template <>                                                                      \
  struct cellforge::point_traits<Type> {                                           \
    using scalar = Scalar;                                                         \
    static constexpr Scalar get(const Type& p, std::size_t i) noexcept {           \
      return i == 0   ? static_cast<Scalar>(p.MX)                                  \
             : i == 1 ? static_cast<Scalar>(p.MY)                                  \
                      : static_cast<Scalar>(p.MZ);                                 \
    }                                                                              \
    template <class T = Type> /* a template, so the untaken branch is discarded */ \
    static constexpr T make(Scalar x, Scalar y, Scalar z) {                        \
      if constexpr (std::is_default_constructible_v<T>) {                          \
        T p{};                                                                     \
        p.MX = x;                                                                  \
        p.MY = y;                                                                  \
        p.MZ = z;                                                                  \
        return p;                                                                  \
      } else {                                                                     \
        return T(x, y, z);                                                         \
      }                                                                            \
    }                                                                              \
  }

// The `get` of the getter-based registrations (not for direct use).
#define CELLFORGE_DETAIL_POINT3_GETTERS(Type, Scalar, GX, GY, GZ) \
  static Scalar get(const Type& p, std::size_t i) {               \
    return i == 0   ? static_cast<Scalar>(p.GX())                 \
           : i == 1 ? static_cast<Scalar>(p.GY())                 \
                    : static_cast<Scalar>(p.GZ());                \
  }

/// Registers a class with getters and setters, e.g. a CAD kernel's point class:
/// `CELLFORGE_REGISTER_POINT3_GET_SET(cad::Pt, double, X, Y, Z, SetX, SetY, SetZ)`.
/// Without a default constructor, points are made by `Type(x, y, z)` instead of the setters.
#define CELLFORGE_REGISTER_POINT3_GET_SET(Type, Scalar, GX, GY, GZ, SX, SY, SZ)    \
  template <>                                                                      \
  struct cellforge::point_traits<Type> {                                           \
    using scalar = Scalar;                                                         \
    CELLFORGE_DETAIL_POINT3_GETTERS(Type, Scalar, GX, GY, GZ)                      \
    template <class T = Type> /* a template, so the untaken branch is discarded */ \
    static T make(Scalar x, Scalar y, Scalar z) {                                  \
      if constexpr (std::is_default_constructible_v<T>) {                          \
        T p{};                                                                     \
        p.SX(x);                                                                   \
        p.SY(y);                                                                   \
        p.SZ(z);                                                                   \
        return p;                                                                  \
      } else {                                                                     \
        return T(x, y, z);                                                         \
      }                                                                            \
    }                                                                              \
  }

/// Registers an immutable class read through getters and made by its constructor
/// `Type(x, y, z)`: `CELLFORGE_REGISTER_POINT3_GET_CTOR(cad::Pt, double, x, y, z)`.
#define CELLFORGE_REGISTER_POINT3_GET_CTOR(Type, Scalar, GX, GY, GZ)         \
  template <>                                                                \
  struct cellforge::point_traits<Type> {                                     \
    using scalar = Scalar;                                                   \
    CELLFORGE_DETAIL_POINT3_GETTERS(Type, Scalar, GX, GY, GZ)                \
    static Type make(Scalar x, Scalar y, Scalar z) { return Type(x, y, z); } \
  }
