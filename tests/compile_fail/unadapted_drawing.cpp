// expect: satisf.*LineDrawing
// expect: stroke_sketch
// expect: drawing_to_cells
// expect: inflate
// expect: tidy_drawing
// expect-count: 4 (does not satisfy|satisfaction of) [^ ]*LineDrawing
// A drawing type without a line_drawing_traits specialisation must be rejected at the call by
// the LineDrawing concept: validate(drawing), and drawing_to_cells, inflate and tidy_drawing,
// whose return types name the drawing's point type (clang 14 substitutes them first), so the
// concept is named at least four times. decltype: nothing is compiled. Needs Eigen.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "cellforge/sketch/drawing_to_cells.hpp"
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
  const std::vector<std::vector<std::uint32_t>> loops{{0, 1, 2}};
  using cells = decltype(cellforge::drawing_to_cells(s));
  using inflated = decltype(cellforge::inflate(s, loops));
  using tidied = decltype(cellforge::tidy_drawing(s));
  return cellforge::validate(s).ok() && sizeof(cells) + sizeof(inflated) + sizeof(tidied) > 0 ? 0 : 1;
}
