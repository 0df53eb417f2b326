// The sketch part in a CAD codebase's own point types: a 2D point class with private members,
// getters and no default constructor (registered with CELLFORGE_REGISTER_POINT2_GET_CTOR), one
// with setters (CELLFORGE_REGISTER_POINT2_GET_SET), and a sealed 3D point; every stage from
// reading to rounds gives the same numbers as glm::dvec2 and hands the user's types back.
#include <doctest/doctest.h>

#include <array>
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

#include "cellforge/core/point2_traits.hpp"
#include "cellforge/io/drawing_pictures.hpp"
#include "cellforge/io/drawing_text.hpp"
#include "cellforge/io/svg_drawing.hpp"
#include "cellforge/sketch.hpp"
#include "test_support.hpp"

namespace sketch_point_type_tests {
class sealed2 {
 public:
  sealed2(double x, double y) : x_(x), y_(y) {}
  double X() const { return x_; }
  double Y() const { return y_; }

 private:
  double x_, y_;
};
class settable2 {  // default-constructible, written through setters
 public:
  float GetU() const { return u_; }
  float GetV() const { return v_; }
  void SetU(float u) { u_ = u; }
  void SetV(float v) { v_ = v; }

 private:
  float u_ = 0, v_ = 0;
};
}  // namespace sketch_point_type_tests
CELLFORGE_REGISTER_POINT2_GET_CTOR(sketch_point_type_tests::sealed2, double, X, Y);
CELLFORGE_REGISTER_POINT2_GET_SET(sketch_point_type_tests::settable2, float, GetU, GetV, SetU, SetV);

namespace sketch_point_type_tests {
using cellforge::to_dvec2;
using sealed3 = test_support::sealed_point;

/// A drawing bundled with the examples (tests/data may not exist: up lexically to the repository).
std::filesystem::path bundled(const char* name) {
  return std::filesystem::path(CELLFORGE_TEST_DATA_DIR).parent_path().parent_path() / "examples" / "data" /
         name;
}
static_assert(!std::is_default_constructible_v<sealed2>);
static_assert(cellforge::Point2<sealed2> && cellforge::Point2<settable2>);

template <class P, class S>
cellforge::arc_drawing<P> converted(const cellforge::arc_drawing<S>& d) {
  cellforge::arc_drawing<P> out;
  for (const auto& p : d.lines.points) out.lines.points.push_back(cellforge::from_dvec2<P>(to_dvec2(p)));
  out.lines.edges = d.lines.edges;
  for (const auto& a : d.arcs) {
    const auto& c = a.curve;
    out.arcs.push_back(
        {a.ends, {cellforge::from_dvec2<P>(to_dvec2(c.centre)), c.rx, c.ry, c.rotation, c.start, c.sweep}});
  }
  return out;
}

TEST_CASE("sketch point types: getters, setters and no default constructor") {
  const auto made = cellforge::point2_traits<sealed2>::make(1.5, -2.0);
  CHECK(cellforge::point2_traits<sealed2>::get(made, 0) == 1.5);
  CHECK(cellforge::point2_traits<sealed2>::get(made, 1) == -2.0);
  const auto set = cellforge::point2_traits<settable2>::make(0.25f, 4.0f);
  CHECK(set.GetU() == 0.25f);
  CHECK(set.GetV() == 4.0f);
}

TEST_CASE("sketch point types: a drawing of sealed points read, checked, tidied, faced and inflated") {
  const auto path = bundled("stepped_normalon.txt");
  const auto ref = cellforge::io::read_drawing_text<glm::dvec2>(path);
  const auto d = cellforge::io::read_drawing_text<sealed2>(path);
  REQUIRE(d.points.size() == ref.points.size());
  for (std::size_t i = 0; i < d.points.size(); ++i) CHECK(to_dvec2(d.points[i]) == ref.points[i]);
  CHECK(cellforge::validate(d).ok());
  const auto faces = cellforge::find_faces(d);
  const auto faces_ref = cellforge::find_faces(ref);
  CHECK(faces.loops == faces_ref.loops);
  const auto tidy = cellforge::tidy_drawing(d);
  static_assert(std::is_same_v<decltype(tidy.drawing), cellforge::line_drawing<sealed2>>);
  CHECK(tidy.drawing.points.size() == d.points.size());
  const auto cells = cellforge::drawing_to_cells<sealed3>(d);
  const auto cells_ref = cellforge::drawing_to_cells(ref);
  static_assert(std::is_same_v<decltype(cells.cells.cells), cellforge::cell_complex<sealed3>>);
  CHECK(cells.cells.cells.num_faces() == cells_ref.cells.cells.num_faces());
  CHECK(cells.cells.cells.num_volumes() == cells_ref.cells.cells.num_volumes());
  REQUIRE(cells.inflation.points.size() == cells_ref.inflation.points.size());
  for (std::size_t i = 0; i < cells.inflation.points.size(); ++i)
    CHECK(cellforge::to_dvec3(cells.inflation.points[i]) == cells_ref.inflation.points[i]);
  // Written back as text and as a picture, the same bytes as the glm drawing's.
  CHECK(cellforge::io::drawing_text_string(d) == cellforge::io::drawing_text_string(ref));
  CHECK(cellforge::io::drawing_svg_string(d, faces.loops) ==
        cellforge::io::drawing_svg_string(ref, faces.loops));
}

TEST_CASE_TEMPLATE("sketch point types: rounds and fillets in the user's types", P, sealed2, settable2) {
  const auto path = bundled("l_bracket_rounds.txt");
  const auto ref = cellforge::io::read_arc_drawing_text<glm::dvec2>(path);
  // float points (settable2) are compared with the same drawing rounded to float.
  const auto d = converted<P>(ref);
  const auto same = converted<glm::dvec2>(d);
  CHECK(cellforge::validate(d).ok());
  // The arcs' ends rounded to float are off the double curves by ~1e-7 of the size: both runs
  // take ends within 1e-5 (the float run would take 64 ε of float, 7.6e-6, by itself).
  const cellforge::arc_pairing_options pairing{.end_tolerance = 1e-5};
  cellforge::rounds_options ro;
  ro.skeleton.pairing = pairing;
  const auto pairs = cellforge::pair_arcs(d, pairing);
  const auto pairs_ref = cellforge::pair_arcs(same, pairing);
  CHECK(pairs.pairs.size() == 3);
  CHECK(pairs.pairs.size() == pairs_ref.pairs.size());
  const auto sk = cellforge::round_skeleton(d, ro.skeleton);
  static_assert(std::is_same_v<decltype(sk.skeleton), cellforge::line_drawing<P>>);
  CHECK(sk.blends.size() == 3);
  const auto r = cellforge::reconstruct_rounds<sealed3>(d, ro);
  const auto r_ref = cellforge::reconstruct_rounds(same, ro);
  static_assert(std::is_same_v<decltype(r.points), std::vector<sealed3>>);
  REQUIRE(r.rounds.size() == r_ref.rounds.size());
  for (std::size_t i = 0; i < r.rounds.size(); ++i)
    CHECK(r.rounds[i].radius == doctest::Approx(r_ref.rounds[i].radius).epsilon(1e-6));  // float positions
  const auto mesh = cellforge::rounded_mesh(r);
  static_assert(std::is_same_v<decltype(mesh.mesh), cellforge::polygon_soup<sealed3>>);
  CHECK(mesh.mesh.num_faces() == cellforge::rounded_mesh(r_ref).mesh.num_faces());
  // Written and read back in P, as text and as SVG, arcs included.
  const auto text = cellforge::io::parse_arc_drawing_text<P>(cellforge::io::arc_drawing_text_string(d));
  CHECK(text.lines.points.size() == d.lines.points.size());
  CHECK(text.arcs.size() == d.arcs.size());
  const auto svg = cellforge::io::parse_svg_arc_drawing<P>(cellforge::io::arc_drawing_svg_string(d), "l.svg");
  CHECK(svg.drawing.arcs.size() == d.arcs.size());
  // Arcs detected in strokes of P.
  std::vector<std::vector<P>> strokes(1);
  for (const auto& q : cellforge::sample_arc(d.arcs[0].curve, 40)) strokes[0].push_back(q);
  const auto found = cellforge::detect_arcs(strokes, {.drawing_size = 10.0});
  CHECK(found.strokes.size() == 1);
}

}  // namespace sketch_point_type_tests
