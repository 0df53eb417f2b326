// expect: satisf.*LineDrawing
// expect: stroke_sketch
// A drawing type without a line_drawing_traits specialisation must be rejected at the call by
// the LineDrawing concept.
#include <array>
#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

#include "cellforge/sketch/line_drawing.hpp"

struct stroke_sketch {
  std::vector<glm::dvec2> nodes;
  std::vector<std::array<std::size_t, 2>> strokes;
};
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
template <>
struct cellforge::line_drawing_traits<stroke_sketch> {
  using point_type = glm::dvec2;
  static std::size_t num_junctions(const stroke_sketch& s) { return s.nodes.size(); }
  static glm::dvec2 position(const stroke_sketch& s, std::size_t i) { return s.nodes[i]; }
  static std::size_t num_edges(const stroke_sketch& s) { return s.strokes.size(); }
  static std::array<std::size_t, 2> endpoints(const stroke_sketch& s, std::size_t e) { return s.strokes[e]; }
};
#endif

int main() {
  const stroke_sketch s{{{0, 0}, {1, 0}, {0, 1}}, {{0, 1}, {1, 2}, {2, 0}}};
  return cellforge::validate_drawing(s).ok() ? 0 : 1;
}
