// SPDX-License-Identifier: MIT
// The CAD application's own types, as it had them before it met cellforge: an immutable-ish
// vector class with private members and no default constructor, a float vector struct, and
// a wire model (nodes and bars) of either. The registrations at the bottom are all the
// application adds to use cellforge.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include <cellforge/core/point_traits.hpp>
#include <cellforge/core/polygon_soup.hpp>
#include <cellforge/core/wireframe.hpp>

namespace cad {

/// The kernel's vector: private members, read by getters, changed by setters, made only
/// from three coordinates.
class Vector3 {
 public:
  Vector3(double x, double y, double z) : x_(x), y_(y), z_(z) {}
  double x() const { return x_; }
  double y() const { return y_; }
  double z() const { return z_; }
  void setX(double v) { x_ = v; }
  void setY(double v) { y_ = v; }
  void setZ(double v) { z_ = v; }

 private:
  double x_, y_, z_;
};

/// The renderer's vector: three public floats.
struct Vec3f {
  float x, y, z;
};

/// A wire model as the modeller stores it: nodes and bars between node numbers.
template <class P>
class WireModel {
 public:
  int add_node(const P& p) {
    nodes_.push_back(p);
    return static_cast<int>(nodes_.size()) - 1;
  }
  void add_bar(int a, int b) { bars_.emplace_back(a, b); }
  std::size_t node_count() const { return nodes_.size(); }
  std::size_t bar_count() const { return bars_.size(); }
  const P& node(std::size_t i) const { return nodes_[i]; }
  std::pair<int, int> bar(std::size_t i) const { return bars_[i]; }

 private:
  std::vector<P> nodes_;
  std::vector<std::pair<int, int>> bars_;
};

}  // namespace cad

// What the application adds to use cellforge: one line per point type, one trait for its graph.
CELLFORGE_REGISTER_POINT3_GET_SET(cad::Vector3, double, x, y, z, setX, setY, setZ);
CELLFORGE_REGISTER_POINT3(cad::Vec3f, float, x, y, z);

template <class P>
struct cellforge::wireframe_traits<cad::WireModel<P>> {
  using point_type = P;
  static std::size_t num_vertices(const cad::WireModel<P>& g) { return g.node_count(); }
  static const P& position(const cad::WireModel<P>& g, std::size_t v) { return g.node(v); }
  static std::size_t num_edges(const cad::WireModel<P>& g) { return g.bar_count(); }
  static std::array<std::size_t, 2> endpoints(const cad::WireModel<P>& g, std::size_t e) {
    const auto [a, b] = g.bar(e);
    return {static_cast<std::size_t>(a), static_cast<std::size_t>(b)};
  }
};

static_assert(!std::is_default_constructible_v<cad::Vector3>);
static_assert(cellforge::Point3<cad::Vector3> && cellforge::Point3<cad::Vec3f>);
static_assert(cellforge::Wireframe<cad::WireModel<cad::Vector3>> &&
              cellforge::Wireframe<cad::WireModel<cad::Vec3f>>);

namespace cad {

template <class P>
P make(double x, double y, double z) {
  using S = cellforge::scalar_t<P>;
  return cellforge::point_traits<P>::make(static_cast<S>(x), static_cast<S>(y), static_cast<S>(z));
}

/// Axis-aligned box [0,a]x[0,b]x[0,c] as six outward quads.
template <class P>
cellforge::polygon_soup<P> box(double a, double b, double c) {
  cellforge::polygon_soup<P> s;
  for (int i = 0; i < 8; ++i) s.points.push_back(make<P>(i & 1 ? a : 0, i & 2 ? b : 0, i & 4 ? c : 0));
  s.add_face({0, 2, 3, 1});
  s.add_face({4, 5, 7, 6});
  s.add_face({0, 1, 5, 4});
  s.add_face({2, 6, 7, 3});
  s.add_face({0, 4, 6, 2});
  s.add_face({1, 3, 7, 5});
  return s;
}

/// The regular octahedron with unit circumradius, eight outward triangles.
template <class P>
cellforge::polygon_soup<P> octahedron() {
  cellforge::polygon_soup<P> s;
  s.points = {make<P>(1, 0, 0),  make<P>(-1, 0, 0), make<P>(0, 1, 0),
              make<P>(0, -1, 0), make<P>(0, 0, 1),  make<P>(0, 0, -1)};
  for (std::uint32_t top : {4u, 5u})
    for (std::uint32_t k = 0; k < 4; ++k) {
      const std::uint32_t ring[4] = {0, 2, 1, 3};
      const std::uint32_t a = ring[k], b = ring[(k + 1) % 4];
      if (top == 4)
        s.add_face({a, b, top});
      else
        s.add_face({b, a, top});
    }
  return s;
}

/// An hourglass along z in [-2, 2], radius 0.3 + 0.7 z^2 / 4, as triangles: `rings` rings
/// of `segments` points, a flat fan cap at each end. The neck ring is at z = 0 for odd rings.
template <class P>
cellforge::polygon_soup<P> hourglass(int segments, int rings) {
  cellforge::polygon_soup<P> s;
  const auto n = static_cast<std::uint32_t>(segments);
  for (int k = 0; k < rings; ++k) {
    const double z = -2.0 + 4.0 * k / (rings - 1), r = 0.3 + 0.7 * z * z / 4;
    for (int i = 0; i < segments; ++i) {
      const double phi = 2.0 * 3.14159265358979323846 * i / segments;
      s.points.push_back(make<P>(r * std::cos(phi), r * std::sin(phi), z));
    }
  }
  const auto id = [&](int k, std::uint32_t i) { return static_cast<std::uint32_t>(k) * n + i % n; };
  for (int k = 0; k + 1 < rings; ++k)
    for (std::uint32_t i = 0; i < n; ++i) {
      s.add_face({id(k, i), id(k, i + 1), id(k + 1, i + 1)});
      s.add_face({id(k, i), id(k + 1, i + 1), id(k + 1, i)});
    }
  const auto bottom = static_cast<std::uint32_t>(s.points.size());
  s.points.push_back(make<P>(0, 0, -2));
  s.points.push_back(make<P>(0, 0, 2));
  for (std::uint32_t i = 0; i < n; ++i) {
    s.add_face({bottom, id(0, i + 1), id(0, i)});
    s.add_face({bottom + 1, id(rings - 1, i), id(rings - 1, i + 1)});
  }
  return s;
}

/// A block [0,2]x[0,1]x[0,1] as a wire model, its two unit cubes split by the wall x = 1
/// when `wall`, or just the unit cube [0,1]^3 when `wall` is false.
template <class P>
WireModel<P> block(bool wall) {
  WireModel<P> g;
  const int nx = wall ? 3 : 2;
  auto id = [&](int i, int j, int k) { return (k * 2 + j) * nx + i; };
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < nx; ++i) g.add_node(make<P>(i, j, k));
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < nx; ++i) {
        if (i + 1 < nx) g.add_bar(id(i, j, k), id(i + 1, j, k));
        if (j == 0) g.add_bar(id(i, 0, k), id(i, 1, k));
        if (k == 0) g.add_bar(id(i, j, 0), id(i, j, 1));
      }
  return g;
}

}  // namespace cad
