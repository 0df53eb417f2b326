// SPDX-License-Identifier: MIT
#pragma once
// The engine of the STL reader and writer (included by io/stl.hpp).

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/ear_clipping.hpp"
#include "cellforge/core/detail/edge_table.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/io/detail/numbers.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/io/stl.hpp"

namespace cellforge::io {

namespace detail {

/// Most facets a binary STL may hold: 3 corner indices each must fit the soup's 32-bit offsets.
inline constexpr std::uint64_t stl_max_facets = std::numeric_limits<std::uint32_t>::max() / 3;

template <class = void>
std::uint32_t stl_load_u32(const char* p) noexcept {
  std::array<char, 4> raw;
  std::memcpy(raw.data(), p, 4);
  if constexpr (std::endian::native == std::endian::big) std::reverse(raw.begin(), raw.end());
  return std::bit_cast<std::uint32_t>(raw);
}
template <class = void>
float stl_load_f32(const char* p) noexcept {
  return std::bit_cast<float>(stl_load_u32(p));
}

[[noreturn]] inline void stl_fail_at_byte(std::string_view name, std::uint64_t at,
                                          const std::string& message) {
  throw error(error_category::io, message, source_location{std::string(name), 0, at});
}

/// Refuses a binary facet count whose facets would overflow the soup's 32-bit indices, from
/// the 84-byte header alone, before anything is allocated. O(1).
template <class = void>
void stl_check_facet_limit(std::uint32_t n, std::string_view name) {
  if (n > stl_max_facets)
    stl_fail_at_byte(
        name, 80,
        cellforge::detail::cat("the header's facet count ", std::to_string(n),
                               " exceeds the 32-bit index limit (at most ", std::to_string(stl_max_facets),
                               " facets, 3 corner indices each)"));
}

/// True when the token at the cursor is `word` (lower case here, any case in the file). O(|word|).
template <class = void>
bool stl_at_keyword(const text_cursor& c, std::string_view word) noexcept {
  if (static_cast<std::size_t>(c.end - c.pos) < word.size()) return false;
  for (std::size_t i = 0; i < word.size(); ++i) {
    const char ch = c.pos[i];
    if ((ch >= 'A' && ch <= 'Z' ? static_cast<char>(ch - 'A' + 'a') : ch) != word[i]) return false;
  }
  const char* q = c.pos + word.size();
  return q == c.end || is_blank(*q) || is_eol(*q);
}

/// A cursor on the first token of the bytes (past a UTF-8 byte-order mark and white space),
/// or at the end when there is none. O(leading white space).
template <class = void>
text_cursor stl_first_token(std::string_view bytes) noexcept {
  text_cursor c(bytes, {}, '\0');
  if (bytes.starts_with("\xEF\xBB\xBF")) c.pos += 3;
  (void)c.next_content();
  return c;
}

/// True when the text starts with `solid` (any case). O(leading white space).
template <class = void>
bool stl_starts_with_solid(std::string_view bytes) noexcept {
  return stl_at_keyword(stl_first_token(bytes), "solid");
}

/// True when bytes that are not sized like binary STL are to be read as ASCII: they start
/// with `solid` and (if long enough to be binary) hold no NUL byte, or they hold nothing but
/// white space (the ASCII reader then reports an empty file). O(size).
template <class = void>
bool stl_read_as_ascii(std::string_view bytes) noexcept {
  if (stl_first_token(bytes).at_end()) return true;
  return stl_starts_with_solid(bytes) && (bytes.size() < 84 || bytes.find('\0') == std::string_view::npos);
}

/// Maps corners to vertex indices: exact (equal coordinates), within a tolerance (a grid of
/// cells of side 4·tolerance) or not at all. Vertices are chained by a 64-bit key (the hash
/// of the coordinates, or of the cell) in an open-addressing table: a key collision only adds
/// a candidate, since each is compared before it is taken. A merged corner becomes the
/// earliest vertex it matches; the latest vertices can be taken back (for dropped facets).
template <Point3 P>
class stl_welder {
 public:
  stl_welder(std::vector<P>& points, const stl_read_options& o)
      : points_(points), weld_(o.weld), tol_(o.weld_tolerance), side_(4.0 * o.weld_tolerance) {
    if (!(o.weld_tolerance >= 0.0) || !std::isfinite(o.weld_tolerance))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("stl_read_options::weld_tolerance must be finite and >= 0, got ",
                                         std::to_string(o.weld_tolerance)));
  }

  void reserve(std::size_t n) {
    if (!weld_) return;
    heads_.reserve(n);
    next_.reserve(n);
  }

  /// The vertex of corner p, new (appended to the points) or earlier. O(1) expected.
  std::uint32_t add(const P& p) {
    const auto fresh = static_cast<std::uint32_t>(points_.size());
    if (weld_) {
      std::uint32_t best = none;
      if (tol_ == 0.0) {
        for (std::uint32_t j = heads_.find(exact_key(p)); j != none && best == none; j = next_[j])
          if (equal(points_[j], p)) best = j;
      } else {
        const glm::dvec3 q = to_dvec3(p);
        const auto lo = cell_of(q - tol_), hi = cell_of(q + tol_);
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
          for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
            for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
              for (std::uint32_t j = heads_.find(cell_key({x, y, z})); j != none; j = next_[j])
                if (j < best && near(to_dvec3(points_[j]), q)) best = j;
      }
      if (best != none) return best;
      const std::uint64_t k = key_of(p);
      next_.push_back(heads_.find(k));
      heads_.insert(k, fresh);
    }
    points_.push_back(p);
    return fresh;
  }

  /// Takes back the vertices from index n on (the latest ones). O(vertices taken back).
  void undo_to(std::size_t n) {
    while (points_.size() > n) {
      if (weld_) {
        const std::uint64_t k = key_of(points_.back());  // the latest vertex heads its chain
        if (next_.back() == none)
          heads_.erase(k);
        else
          heads_.insert(k, next_.back());
        next_.pop_back();
      }
      points_.pop_back();
    }
  }

  /// True when the corners welded to vertices a and b are one: the same vertex, or without
  /// welding the same place. O(1).
  bool same(std::uint32_t a, std::uint32_t b) const { return weld_ ? a == b : equal(points_[a], points_[b]); }

 private:
  using S = scalar_t<P>;
  static constexpr std::uint32_t none = cellforge::detail::edge_table::not_found;

  static bool equal(const P& a, const P& b) {
    for (std::size_t k = 0; k < 3; ++k)
      if (coord(a, k) != coord(b, k)) return false;
    return true;
  }
  bool near(const glm::dvec3& a, const glm::dvec3& b) const {
    const glm::dvec3 d = a - b;  // each axis first: the exact distance only for real candidates
    return std::fabs(d.x) <= tol_ && std::fabs(d.y) <= tol_ && std::fabs(d.z) <= tol_ &&
           std::hypot(d.x, d.y, d.z) <= tol_;
  }

  /// Mixes three 64-bit words into a key; never the table's empty key. O(1).
  static std::uint64_t mix(std::uint64_t a, std::uint64_t b, std::uint64_t c) noexcept {
    std::uint64_t h = a * 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 29) ^ b) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 31) ^ c) * 0x94D049BB133111EBull;
    h ^= h >> 32;
    return h == cellforge::detail::edge_table::empty_key ? 0 : h;
  }
  static std::uint64_t word(S v) noexcept {
    if constexpr (std::is_floating_point_v<S>) {
      v += S(0);  // -0 becomes +0: equal values, equal keys
      if constexpr (sizeof(S) == 8) return std::bit_cast<std::uint64_t>(v);
      if constexpr (sizeof(S) == 4) return std::bit_cast<std::uint32_t>(v);
      if constexpr (sizeof(S) != 4 && sizeof(S) != 8) {
        // Wider floats: sign, exponent and the top 63 bits of the mantissa (equal values, equal words).
        if (!std::isfinite(v)) return 0x7FF0000000000000ull;
        int e = 0;
        const S m = std::frexp(v, &e);
        return static_cast<std::uint64_t>(std::ldexp(std::fabs(m), 63)) ^
               (static_cast<std::uint64_t>(e) << 1) ^ static_cast<std::uint64_t>(m < 0);
      }
    } else {
      return static_cast<std::uint64_t>(v);
    }
  }
  static std::uint64_t exact_key(const P& p) noexcept {
    return mix(word(coord(p, 0)), word(coord(p, 1)), word(coord(p, 2)));
  }
  static std::uint64_t cell_key(const std::array<std::int64_t, 3>& c) noexcept {
    return mix(static_cast<std::uint64_t>(c[0]), static_cast<std::uint64_t>(c[1]),
               static_cast<std::uint64_t>(c[2]));
  }
  std::uint64_t key_of(const P& p) const noexcept {
    return tol_ == 0.0 ? exact_key(p) : cell_key(cell_of(to_dvec3(p)));
  }

  /// The grid cell of q. Cell indices are clamped to ±2^50, where doubles still resolve
  /// whole cells, so far-away points share the outermost cells (slower, still correct).
  std::array<std::int64_t, 3> cell_of(const glm::dvec3& q) const noexcept {
    constexpr double limit = 1125899906842624.0;  // 2^50
    std::array<std::int64_t, 3> c{};
    for (int k = 0; k < 3; ++k) {
      double v = std::floor(q[k] / side_);
      if (!(v > -limit)) v = -limit;
      if (!(v < limit)) v = limit;
      c[k] = static_cast<std::int64_t>(v);
    }
    return c;
  }

  std::vector<P>& points_;
  bool weld_;
  double tol_, side_;
  cellforge::detail::edge_table heads_;  // key -> the latest vertex with that key
  std::vector<std::uint32_t> next_;      // per vertex: the one before it with the same key
};

/// Turns facets (three corners each) into welded soup faces and keeps the counts and solids.
template <Point3 P>
class stl_builder {
 public:
  stl_builder(stl_data<P>& d, const stl_read_options& o) : d_(d), o_(o), welder_(d.soup.points, o) {}

  void reserve(std::size_t facets) {
    d_.soup.face_offsets.reserve(facets + 1);
    d_.soup.face_vertices.reserve(3 * facets);
    const std::size_t vertices = o_.weld ? facets / 2 + 8 : 3 * facets;
    d_.soup.points.reserve(vertices);
    welder_.reserve(vertices);
  }

  void begin_solid(std::string name) {
    d_.solids.push_back({std::move(name), {}, static_cast<std::uint32_t>(d_.soup.num_faces()), 0});
  }
  void end_solid(std::string end_name) {
    d_.solids.back().end_name = std::move(end_name);
    if (d_.solids.back().name_mismatch()) ++d_.mismatched_end_names;
  }

  /// Index of the next facet, for messages.
  std::uint64_t facet_index() const noexcept { return d_.facets_read; }

  /// Adds a facet; `fail(message)` throws the caller's located error. O(1) expected.
  template <class Fail>
  void facet(const std::array<P, 3>& corners, Fail&& fail) {
    const std::uint64_t f = d_.facets_read++;
    d_.vertices_before_weld += 3;
    auto& soup = d_.soup;
    if (soup.points.size() > std::numeric_limits<std::uint32_t>::max() - 3 ||
        soup.face_vertices.size() > std::numeric_limits<std::uint32_t>::max() - 3)
      fail(
          cellforge::detail::cat("facet ", std::to_string(f), " exceeds the 32-bit index limit of the soup"));
    const std::size_t before = soup.points.size();
    std::array<std::uint32_t, 3> v{};
    for (std::size_t k = 0; k < 3; ++k) v[k] = welder_.add(corners[k]);
    for (std::size_t a = 0; a < 3; ++a) {
      const std::size_t b = (a + 1) % 3;
      if (!welder_.same(v[a], v[b])) continue;
      ++d_.degenerate_facets;
      if (o_.degenerate == stl_degenerate::refuse)
        fail(cellforge::detail::cat(
            "facet ", std::to_string(f), " is degenerate: its corners ", std::to_string(std::min(a, b)),
            " and ", std::to_string(std::max(a, b)),
            " are one vertex (stl_read_options::degenerate = drop or keep accepts it)"));
      if (o_.degenerate == stl_degenerate::drop) {
        welder_.undo_to(before);
        return;
      }
      break;
    }
    soup.add_face({v[0], v[1], v[2]});
    ++d_.solids.back().num_faces;
  }

  void finish() { d_.vertices_after_weld = d_.soup.points.size(); }

 private:
  stl_data<P>& d_;
  const stl_read_options& o_;
  stl_welder<P> welder_;
};

/// Reads a binary STL: an 80-byte header, a little-endian uint32 facet count, then 50 bytes
/// per facet (normal, three corners as float32, a 16-bit attribute). O(size).
template <Point3 P>
void stl_read_binary(std::string_view bytes, std::string_view name, bool starts_with_solid,
                     stl_builder<P>& b) {
  if (bytes.size() < 84)
    stl_fail_at_byte(name, 0,
                     cellforge::detail::cat(
                         "not an STL file: ", std::to_string(bytes.size()),
                         " bytes are too few for binary STL (an 84-byte header and facet count) and the "
                         "file does not start with 'solid' (ASCII STL)"));
  const std::uint32_t n = stl_load_u32(bytes.data() + 80);
  const std::uint64_t needed = 84 + 50 * std::uint64_t{n};
  const std::string hint =
      starts_with_solid ? " (the file starts with 'solid' but holds binary data, so it is read as binary)"
                        : "";
  if (needed > bytes.size())
    stl_fail_at_byte(
        name, 80,
        cellforge::detail::cat("the header's facet count ", std::to_string(n), " needs ",
                               std::to_string(needed), " bytes (84 + 50 per facet) but the file has ",
                               std::to_string(bytes.size()), ": truncated, or not an STL file", hint));
  if (needed < bytes.size())
    stl_fail_at_byte(name, needed,
                     std::to_string(bytes.size() - needed) + " bytes of unexpected data after the last of " +
                         std::to_string(n) + " facets (the header's facet count)" + hint);
  stl_check_facet_limit(n, name);

  std::string_view header = bytes.substr(0, 80);
  while (!header.empty() && (header.back() == '\0' || header.back() == ' ')) header.remove_suffix(1);
  b.begin_solid(std::string(header));
  b.reserve(n);
  using S = scalar_t<P>;
  for (std::uint32_t f = 0; f < n; ++f) {
    const std::size_t at = 84 + std::size_t{50} * f;  // the normal (12 bytes) is not used
    const auto corner = [&](std::size_t k) {
      std::array<S, 3> xyz{};
      for (std::size_t a = 0; a < 3; ++a) {
        const std::size_t vat = at + 12 + 12 * k + 4 * a;
        const float value = stl_load_f32(bytes.data() + vat);
        if (!convert_coordinate(value, xyz[a]))
          stl_fail_at_byte(
              name, vat,
              cellforge::detail::cat(
                  "coordinate ", std::string(1, "xyz"[a]), " of vertex ", std::to_string(k), " of facet ",
                  std::to_string(f), " (", std::to_string(value), ") ",
                  (std::isfinite(value) ? "does not fit the point's scalar type"
                                        : "is not finite (NaN and Inf coordinates are rejected)")));
      }
      return point_traits<P>::make(xyz[0], xyz[1], xyz[2]);
    };
    const std::array<P, 3> corners{corner(0), corner(1), corner(2)};  // P needs no default constructor
    b.facet(corners, [&](const std::string& message) { stl_fail_at_byte(name, at, message); });
  }
  b.end_solid({});
}

/// Reads ASCII STL: `solid name`, facets, `endsolid [name]`, as often as the file repeats
/// them. Keywords in any case; tokens may be split over lines in any way except that a
/// solid's name is the rest of its line. O(size).
template <Point3 P>
class stl_ascii_reader {
 public:
  stl_ascii_reader(std::string_view bytes, std::string_view name, stl_builder<P>& b)
      : c_(bytes, name, '\0'), b_(b) {
    if (bytes.starts_with("\xEF\xBB\xBF")) c_.pos += 3;  // a UTF-8 byte-order mark some editors add
  }

  void run() {
    if (!c_.next_content())
      c_.fail_at(c_.content_end(),
                 "empty file: an STL file starts with 'solid' (ASCII) or an 84-byte header (binary)");
    for (;;) {
      if (!stl_at_keyword(c_, "solid")) expected("'solid'");
      c_.pos += 5;
      std::string name = rest_of_line();
      const std::string solid = cellforge::detail::cat("solid '", name, "'");
      b_.begin_solid(std::move(name));
      for (;;) {
        if (!c_.next_content())
          c_.fail_at(c_.content_end(),
                     cellforge::detail::cat("file ends inside ", solid, ": expected 'facet' or 'endsolid'"));
        if (stl_at_keyword(c_, "endsolid")) break;
        if (!stl_at_keyword(c_, "facet"))
          expected(cellforge::detail::cat("'facet' or 'endsolid' in ", solid));
        facet();
      }
      c_.pos += 8;
      b_.end_solid(rest_of_line());
      if (!c_.next_content()) return;
      if (!stl_at_keyword(c_, "solid"))
        c_.fail(cellforge::detail::cat("unexpected ", c_.token(),
                                       " after 'endsolid' (only another 'solid' may follow)"));
    }
  }

 private:
  using S = scalar_t<P>;

  [[noreturn]] void expected(const std::string& what) const {
    if (c_.at_end()) c_.fail_at(c_.content_end(), where_ + "expected " + what + ", found end of file");
    c_.fail(where_ + "expected " + what + ", found " + c_.token());
  }

  /// Reads `word` as the next token, or fails with "expected <what>".
  void keyword(std::string_view word, const char* what) {
    if (!c_.next_content() || !stl_at_keyword(c_, word)) expected(what);
    c_.pos += word.size();
  }

  /// The rest of the current line, blanks trimmed at both ends.
  std::string rest_of_line() {
    c_.skip_blanks();
    const char* start = c_.pos;
    while (c_.pos != c_.end && !is_eol(*c_.pos)) ++c_.pos;
    const char* stop = c_.pos;
    while (stop != start && is_blank(stop[-1])) --stop;
    return std::string(start, stop);
  }

  /// True when the next token is a number (one value too many).
  bool number_follows() {
    if (!c_.next_content()) return false;
    const char* p = c_.pos;
    double value = 0;
    return parse_number(p, c_.end, value) != parse_status::bad && (p == c_.end || is_blank(*p) || is_eol(*p));
  }

  /// A normal component: any number, NaN included (some exporters write NaN for degenerate facets).
  template <class What>
  void normal_component(What&& what) {
    if (!c_.next_content())
      c_.fail_at(c_.content_end(), cellforge::detail::cat("expected ", what(), ", found end of file"));
    (void)c_.number<double>(what);
  }

  /// A corner coordinate: finite and representable in the point's scalar type.
  template <class What>
  S coordinate(What&& what) {
    if (!c_.next_content())
      c_.fail_at(c_.content_end(), cellforge::detail::cat("expected ", what(), ", found end of file"));
    return c_.coordinate<S>(what);
  }

  void facet() {
    const char* at = c_.pos;
    const std::uint64_t f = b_.facet_index();
    const std::string facet_name = cellforge::detail::cat("facet ", std::to_string(f));
    where_ = facet_name + ": ";
    c_.pos += 5;
    keyword("normal", "'normal' after 'facet'");
    // The normal is checked to be three numbers (NaN allowed: some exporters write it for
    // degenerate facets) and not kept: writers recompute it from the corners.
    for (int a = 0; a < 3; ++a)
      normal_component([&] {
        return cellforge::detail::cat("normal component ", std::string(1, "xyz"[a]), " of ", facet_name);
      });
    if (number_follows()) c_.fail(where_ + "the normal has more than 3 components: unexpected " + c_.token());
    keyword("outer", "'outer loop' after the normal");
    keyword("loop", "'loop' after 'outer'");
    std::array<std::array<S, 3>, 3> xyz{};  // points made at the end: P needs no default constructor
    std::size_t k = 0;
    for (;;) {
      if (!c_.next_content()) expected(k < 3 ? "'vertex'" : "'endloop'");
      if (stl_at_keyword(c_, "endloop")) break;
      if (!stl_at_keyword(c_, "vertex")) expected(k < 3 ? "'vertex'" : "'endloop'");
      if (k == 3) c_.fail(facet_name + " has more than 3 vertices; STL facets are triangles");
      c_.pos += 6;
      const auto what = [&](int a) {
        return [&, a] {
          return cellforge::detail::cat("coordinate ", std::string(1, "xyz"[a]), " of vertex ",
                                        std::to_string(k), " of ", facet_name);
        };
      };
      const S x = coordinate(what(0)), y = coordinate(what(1)), z = coordinate(what(2));
      if (number_follows())
        c_.fail(cellforge::detail::cat("vertex ", std::to_string(k), " of ", facet_name,
                                       " has more than 3 coordinates: unexpected ", c_.token()));
      xyz[k++] = {x, y, z};
    }
    if (k < 3)
      c_.fail(facet_name + " has " + std::to_string(k) + " vertices; STL facets are triangles (3 vertices)");
    c_.pos += 7;
    keyword("endfacet", "'endfacet' after 'endloop'");
    where_.clear();
    const auto corner = [&](std::size_t i) { return point_traits<P>::make(xyz[i][0], xyz[i][1], xyz[i][2]); };
    b_.facet(std::array<P, 3>{corner(0), corner(1), corner(2)},
             [&](const std::string& message) { c_.fail_at(at, message); });
  }

  text_cursor c_;
  stl_builder<P>& b_;
  std::string where_;  // "facet N: " inside a facet, for messages
};

}  // namespace detail

template <Point3 P>
stl_data<P> parse_stl(std::string_view bytes, std::string_view name, const stl_read_options& options) {
  stl_data<P> d;
  detail::stl_builder<P> b(d, options);
  const bool binary_size =
      bytes.size() >= 84 && 84 + 50 * std::uint64_t{detail::stl_load_u32(bytes.data() + 80)} == bytes.size();
  if (!binary_size && detail::stl_read_as_ascii(bytes)) {
    d.encoding = stl_encoding::ascii;
    detail::stl_ascii_reader<P>(bytes, name, b).run();
  } else {
    d.encoding = stl_encoding::binary;
    detail::stl_read_binary(bytes, name, detail::stl_starts_with_solid(bytes), b);
  }
  b.finish();
  // Dropping every facet would read as an empty mesh, which the file is not: say so.
  if (options.degenerate == stl_degenerate::drop && d.facets_read > 0 && d.degenerate_facets == d.facets_read)
    throw error(
        error_category::io,
        cellforge::detail::cat("all ", std::to_string(d.facets_read),
                               " facets are degenerate (two corners are one vertex",
                               (options.weld ? ", after welding" : ""),
                               "): no triangle is left (stl_read_options::degenerate = keep reads them)"),
        source_location{std::string(name), 0, source_location::no_offset});
  return d;
}

template <Point3 P>
stl_data<P> read_stl(const file_path& path, const stl_read_options& options) {
  // A file large enough to exceed the limit is checked from its header before it is loaded.
  const std::uint64_t size = detail::status_of(path).size;
  if (size > 84 + 50 * detail::stl_max_facets) {
    const detail::file_handle file(detail::open_file(path, "rb"));
    char head[84];
    if (file && std::fread(head, 1, sizeof head, file.get()) == sizeof head) {
      const std::uint32_t n = detail::stl_load_u32(head + 80);
      if (84 + 50 * std::uint64_t{n} == size) detail::stl_check_facet_limit(n, detail::display_name(path));
    }
  }
  const std::string bytes = detail::read_file(path);
  return parse_stl<P>(bytes, detail::display_name(path), options);
}

namespace detail {

/// The unit normal of triangle abc by the right-hand rule, zero when it has no area; scaled
/// first so that no product overflows or underflows. O(1).
template <class = void>
glm::dvec3 stl_facet_normal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  glm::dvec3 u = b - a, v = c - a;
  const auto finite = [](const glm::dvec3& w) {
    return std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z);
  };
  if (!finite(u) || !finite(v)) u = 0.5 * b - 0.5 * a, v = 0.5 * c - 0.5 * a;
  const auto largest = [](const glm::dvec3& w) {
    return std::max({std::fabs(w.x), std::fabs(w.y), std::fabs(w.z)});
  };
  const double m = std::max(largest(u), largest(v));
  if (!(m > 0.0)) return glm::dvec3(0.0);
  glm::dvec3 n = glm::cross(u / m, v / m);
  const double k = largest(n);
  if (!(k > 0.0)) return glm::dvec3(0.0);
  n /= k;
  return n / glm::length(n);
}

/// Throws invalid_input unless `name` survives the trip through the chosen encoding: at
/// most 80 bytes without trailing NUL or space (binary); one line without leading or
/// trailing blanks or control characters (ASCII). O(name length).
template <class = void>
void stl_check_name(std::string_view name, bool binary) {
  const auto refuse = [&](const std::string& why) {
    throw error(error_category::invalid_input,
                cellforge::detail::cat("write_stl: stl_write_options::solid_name ", why));
  };
  if (binary) {
    if (name.size() > 80) refuse("is longer than the 80-byte binary header");
    if (!name.empty() && (name.back() == '\0' || name.back() == ' '))
      refuse("ends with a NUL or space (the binary header is padded with those)");
    return;
  }
  for (const char ch : name)
    if ((static_cast<unsigned char>(ch) < 0x20 && ch != '\t') || ch == 0x7f)
      refuse("has a line break or control character (ASCII STL keeps the name on the 'solid' line)");
  if (!name.empty() && (is_blank(name.front()) || is_blank(name.back())))
    refuse("starts or ends with a blank (ASCII STL trims those)");
}

}  // namespace detail

template <Point3 P>
void write_stl(std::ostream& os, const polygon_soup<P>& soup, const stl_write_options& options) {
  detail::check_face_indices(soup, "stl");
  detail::stl_check_name(options.solid_name, options.binary);
  // Only the points that faces use are written, so only they are checked.
  for (const std::uint32_t v : soup.face_vertices) {
    const P& p = soup.points[v];
    detail::check_point_finite(p, v, "stl");
    for (std::size_t k = 0; options.binary && k < 3; ++k)
      if (!(std::fabs(static_cast<double>(coord(p, k))) <=
            static_cast<double>(std::numeric_limits<float>::max())))
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("write_stl: point ", std::to_string(v),
                                           " has a coordinate beyond the float32 range of binary STL"));
  }
  // Only a soup with polygons is copied: triangles are written as they stand.
  bool polygons = false;
  for (std::size_t f = 0; f < soup.num_faces() && !polygons; ++f) polygons = soup.face(f).size() != 3;
  polygon_soup<P> clipped;
  if (polygons) {
    try {
      clipped = triangulate(soup, options.triangulation);
    } catch (const error& e) {
      throw error(e.category(), cellforge::detail::cat("write_stl: ", e.message()));
    }
  }
  const polygon_soup<P>* tris = polygons ? &clipped : &soup;
  const std::size_t n = tris->num_faces();
  detail::output_buffer out(os);
  const auto corner = [&](std::size_t f, std::size_t k) -> const P& {
    return tris->points[tris->face(f)[k]];
  };
  if (options.binary) {
    if (n > std::numeric_limits<std::uint32_t>::max())
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_stl: ", std::to_string(n),
                                         " triangles are more than binary STL can count"));
    std::array<char, 80> header{};
    std::memcpy(header.data(), options.solid_name.data(), options.solid_name.size());
    out.put(std::string_view(header.data(), header.size()));
    out.binary(static_cast<std::uint32_t>(n), true);
    for (std::size_t f = 0; f < n; ++f) {
      std::array<glm::dvec3, 3> q;  // float32 corners: the normal is that of what the file holds
      for (std::size_t k = 0; k < 3; ++k)
        for (std::size_t a = 0; a < 3; ++a)
          q[k][static_cast<int>(a)] = static_cast<double>(static_cast<float>(coord(corner(f, k), a)));
      const glm::dvec3 normal = detail::stl_facet_normal(q[0], q[1], q[2]);
      for (int a = 0; a < 3; ++a) out.binary(static_cast<float>(normal[a]), true);
      for (const glm::dvec3& p : q)
        for (int a = 0; a < 3; ++a) out.binary(static_cast<float>(p[a]), true);
      out.binary(std::uint16_t{0}, true);
    }
    out.finish("STL");
    return;
  }
  out.put("solid");
  if (!options.solid_name.empty()) out.put(' ');
  out.put(options.solid_name);
  out.put('\n');
  for (std::size_t f = 0; f < n; ++f) {
    const glm::dvec3 normal =
        detail::stl_facet_normal(to_dvec3(corner(f, 0)), to_dvec3(corner(f, 1)), to_dvec3(corner(f, 2)));
    out.put("  facet normal ");
    for (int a = 0; a < 3; ++a) {
      if (a != 0) out.put(' ');
      out.number(static_cast<float>(normal[a]));
    }
    out.put("\n    outer loop\n");
    for (std::size_t k = 0; k < 3; ++k) {
      out.put("      vertex ");
      for (std::size_t a = 0; a < 3; ++a) {
        if (a != 0) out.put(' ');
        out.number(coord(corner(f, k), a));
      }
      out.put('\n');
    }
    out.put("    endloop\n  endfacet\n");
  }
  out.put("endsolid");
  if (!options.solid_name.empty()) out.put(' ');
  out.put(options.solid_name);
  out.put('\n');
  out.finish("STL");
}

template <Point3 P>
void write_stl(const file_path& path, const polygon_soup<P>& soup, const stl_write_options& options) {
  detail::write_file(path, [&](std::ostream& os) { write_stl(os, soup, options); });
}

}  // namespace cellforge::io
