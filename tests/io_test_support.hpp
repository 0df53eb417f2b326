// SPDX-License-Identifier: MIT
#pragma once
// Shared by the io tests (test_io_off.cpp, test_io_obj.cpp, test_io_ply.cpp, test_io_stl.cpp): point types,
// random soups with awkward coordinates, bitwise comparison and the malformed-input checker.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <unistd.h>

#include <glm/vec3.hpp>

#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "test_support.hpp"

namespace io_test {

/// A user point type registered by the one-line macro (the tests' shared one).
using user_point = test_support::user_point;

}  // namespace io_test

namespace io_test {

/// Coordinates equal bit for bit (so -0.0 differs from 0.0 and NaNs compare by payload).
template <cellforge::Point3 P>
bool same_bits(const P& a, const P& b) {
  using S = cellforge::scalar_t<P>;
  for (std::size_t i = 0; i < 3; ++i) {
    const S u = cellforge::coord(a, i), v = cellforge::coord(b, i);
    if (std::memcmp(&u, &v, sizeof(S)) != 0) return false;
  }
  return true;
}

template <cellforge::Point3 P>
bool same_soup(const cellforge::polygon_soup<P>& a, const cellforge::polygon_soup<P>& b) {
  if (a.points.size() != b.points.size()) return false;
  for (std::size_t i = 0; i < a.points.size(); ++i)
    if (!same_bits(a.points[i], b.points[i])) return false;
  return a.face_offsets == b.face_offsets && a.face_vertices == b.face_vertices;
}

/// A soup with coordinates that stress number formatting: every magnitude, negative zero,
/// subnormals, the largest finite values; faces of 3 to 7 distinct vertices.
template <cellforge::Point3 P>
cellforge::polygon_soup<P> awkward_soup(unsigned seed, std::size_t n_points, std::size_t n_faces) {
  using S = cellforge::scalar_t<P>;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-40, 40);
  const auto value = [&](std::size_t i) -> S {
    if constexpr (std::is_floating_point_v<S>) {
      using L = std::numeric_limits<S>;
      switch (i % 17) {
        case 0:
          return S(-0.0);
        case 1:
          return L::denorm_min();
        case 2:
          return L::max();
        case 3:
          return L::lowest();
        case 4:
          return L::min();
        case 5:
          return S(0.1);
        default:
          return static_cast<S>(std::ldexp(mantissa(rng), exponent(rng)));
      }
    } else {
      return static_cast<S>(rng() % 2001) - S(1000);
    }
  };
  cellforge::polygon_soup<P> soup;
  for (std::size_t i = 0; i < n_points; ++i)
    soup.points.push_back(cellforge::point_traits<P>::make(value(3 * i), value(3 * i + 1), value(3 * i + 2)));
  for (std::size_t f = 0; f < n_faces && n_points >= 7; ++f) {
    const std::size_t k = 3 + rng() % 5;
    std::vector<std::uint32_t> face;
    while (face.size() < k) {
      const auto v = static_cast<std::uint32_t>(rng() % n_points);
      if (std::find(face.begin(), face.end(), v) == face.end()) face.push_back(v);
    }
    soup.add_face(face);
  }
  return soup;
}

/// A malformed input, the line (or byte offset) the error must name and a part of its message.
struct bad_input {
  const char* what;
  std::string text;
  std::uint64_t line;
  const char* message;
};

/// Parses with `parse` and checks for an io error at the given line with the message part;
/// what() must read "name:line: message".
template <class Parse>
void check_rejected(const bad_input& c, const char* name, Parse&& parse) {
  const std::string what = c.what;
  CAPTURE(what);
  CAPTURE(c.text);
  try {
    parse(c.text);
    FAIL("accepted malformed input: " << c.what);
  } catch (const cellforge::error& e) {
    const std::string error_text = e.what();
    CAPTURE(error_text);
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(e.file() == name);
    CHECK(e.line() == c.line);
    CHECK(e.message().find(c.message) != std::string::npos);
    CHECK(std::string(e.what()).starts_with(std::string(name) + ":" + std::to_string(c.line) + ": "));
  }
}

/// Parses binary `bytes` with `parse` and checks for an io error at byte `offset` (no line)
/// with the message part; what() must read "name (byte offset): message".
template <class Parse>
void check_rejected_at_byte(const char* what, const std::string& bytes, std::uint64_t offset,
                            const char* message, const char* name, Parse&& parse) {
  CAPTURE(std::string(what));
  try {
    parse(bytes);
    FAIL("accepted malformed binary input");
  } catch (const cellforge::error& e) {
    const std::string text = e.what();
    CAPTURE(text);
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(e.file() == name);
    CHECK(e.line() == 0);
    CHECK(e.byte_offset() == offset);
    CHECK(e.message().find(message) != std::string::npos);
    CHECK(text.starts_with(std::string(name) + " (byte " + std::to_string(offset) + "): "));
  }
}

/// A fresh path in the temporary directory, removed when the object dies.
struct temp_path {
  std::filesystem::path path;
  explicit temp_path(const std::string& name) {
    static std::atomic<unsigned> counter{0};
    path = std::filesystem::temp_directory_path() /
           ("cellforge_io_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" + name);
  }
  ~temp_path() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
};

/// Reading from files: a nonexistent path gives an io error naming it, and a malformed file
/// (`content`) an error located in that file at `line` (0 for binary data). O(size of content).
template <class Read>
void check_file_errors(const std::string& name, const std::string& content, std::uint64_t line, Read&& read) {
  const std::filesystem::path missing =
      std::filesystem::temp_directory_path() / "cellforge_no_such_dir" / name;
  try {
    read(missing);
    FAIL("read a file that does not exist");
  } catch (const cellforge::error& e) {
    CHECK(e.category() == cellforge::error_category::io);
    CHECK(std::string(e.what()).find(missing.string()) != std::string::npos);
  }
  // A device that never ends is refused by name, not read until memory runs out.
  if (std::filesystem::exists("/dev/zero")) {
    try {
      read(std::filesystem::path("/dev/zero"));
      FAIL("read /dev/zero");
    } catch (const cellforge::error& e) {
      CHECK(e.category() == cellforge::error_category::io);
      CHECK(std::string(e.what()).find("'/dev/zero': not a regular file") != std::string::npos);
    }
  }
  const temp_path file(name);
  std::ofstream(file.path, std::ios::binary) << content;
  try {
    read(file.path);
    FAIL("accepted a malformed file");
  } catch (const cellforge::error& e) {
    CHECK(e.file() == file.path.string());
    CHECK(e.line() == line);
    CHECK(std::string(e.what()).starts_with(file.path.string() + (line != 0 ? ":" : " (byte ")));
  }
}

}  // namespace io_test
