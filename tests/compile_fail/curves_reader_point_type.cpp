// expect: parse_curve_file
// expect: (deduce|infer) template (argument|parameter)
// A curve reader has no point type to deduce: it takes one as a template argument, like
// read_mesh<P>, and there is no default that silently means glm::dvec3.
#include <array>

#include "cellforge/io/curves_io.hpp"

int main() {
#ifdef CELLFORGE_COMPILE_FAIL_CONTROL
  auto call = [] {
    return cellforge::io::parse_curve_file<std::array<float, 3>>("0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0");
  };
#else
  auto call = [] { return cellforge::io::parse_curve_file("0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0"); };
#endif
  return sizeof(call) > 0 ? 0 : 1;  // never run: the test is whether it compiles
}
