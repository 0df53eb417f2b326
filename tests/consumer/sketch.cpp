// SPDX-License-Identifier: MIT
// The CAD application's sketch module: its own 2D point (private members, no default
// constructor) and its own sketch class, read through the whole sketch umbrella. Built with
// both compilers in Debug and Release: GCC 12's -Wrestrict at -O3 fired in sketch headers that
// the rest of the consumer never included.
#include <cellforge/sketch.hpp>

#include <array>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace cad {

class Point2 {
 public:
  Point2(double x, double y) : x_(x), y_(y) {}
  double X() const { return x_; }
  double Y() const { return y_; }

 private:
  double x_, y_;
};

/// A sketch as the CAD program keeps it: corners, and strokes between them.
class Sketch {
 public:
  std::size_t add(double x, double y) {
    corners_.emplace_back(x, y);
    return corners_.size() - 1;
  }
  void stroke(std::size_t a, std::size_t b) { strokes_.push_back({a, b}); }
  const std::vector<Point2>& corners() const { return corners_; }
  const std::vector<std::array<std::size_t, 2>>& strokes() const { return strokes_; }

 private:
  std::vector<Point2> corners_;
  std::vector<std::array<std::size_t, 2>> strokes_;
};

}  // namespace cad

CELLFORGE_REGISTER_POINT2_GET_CTOR(cad::Point2, double, X, Y);
static_assert(!std::is_default_constructible_v<cad::Point2>);

template <>
struct cellforge::line_drawing_traits<cad::Sketch> {
  using point_type = cad::Point2;
  static std::size_t num_junctions(const cad::Sketch& s) { return s.corners().size(); }
  static cad::Point2 position(const cad::Sketch& s, std::size_t i) { return s.corners()[i]; }
  static std::size_t num_edges(const cad::Sketch& s) { return s.strokes().size(); }
  static std::array<std::size_t, 2> endpoints(const cad::Sketch& s, std::size_t e) { return s.strokes()[e]; }
};

/// A cube in a generic parallel view: validated, and its six faces found; each failed check is
/// named on stderr through `expect`.
void run_sketch(void (*expect)(bool, const char*, const char*)) {
  cad::Sketch s;
  // Front square, back square moved up and to the right: a cube in oblique view.
  const double c[8][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {0.9, 0.6}, {2.9, 0.6}, {2.9, 2.6}, {0.9, 2.6}};
  for (const auto& p : c) s.add(p[0], p[1]);
  for (std::size_t i = 0; i < 4; ++i) {
    s.stroke(i, (i + 1) % 4);
    s.stroke(4 + i, 4 + (i + 1) % 4);
    s.stroke(i, 4 + i);
  }
  const auto check = cellforge::validate(s);
  expect(check.ok(), "Sketch", "validate(drawing): a cube's drawing is valid");
  const auto faces = cellforge::find_faces(s);
  expect(faces.loops.size() == 6 && !faces.flagged, "Sketch", "find_faces: a cube's drawing has six faces");
  cad::Sketch broken = s;
  broken.stroke(0, 0);
  expect(!cellforge::validate(broken).ok(), "Sketch", "validate(drawing): a stroke from a corner to itself");
}
