// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// PLY (Stanford polygon file) reading and writing for polygon soups: ASCII, binary little-
/// and big-endian; vertex x/y/z of any scalar type, faces from a `vertex_indices` (or
/// `vertex_index`) list of any integer types; other properties and elements skipped.
/// See docs/formats.md.

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/io/detail/face_checks.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/ply_header.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"

namespace cellforge::io {

/// How PLY files are read.
struct ply_read_options {
  /// Accept faces that use a vertex twice (degenerate faces); by default they are an error.
  bool allow_repeated_vertices = false;
};

/// How PLY files are written.
struct ply_write_options {
  ply_format format = ply_format::binary_little_endian;  ///< binary is exact and compact
  std::string comment{};                                 ///< header 'comment' lines when not empty
};

namespace detail {

template <class = void>
class basic_ply_ascii_reader;
using ply_ascii_reader = basic_ply_ascii_reader<>;

/// Reads values of an ASCII PLY body: one element instance per line.
template <class>
class basic_ply_ascii_reader {
 public:
  explicit basic_ply_ascii_reader(text_cursor& c) : c_(c) {}

  std::size_t mark() {
    c_.skip_blanks();
    return static_cast<std::size_t>(c_.pos - c_.begin);
  }
  [[noreturn]] void fail_at(std::size_t at, const std::string& message) const {
    c_.fail_at(c_.begin + at, message);
  }
  [[noreturn]] void fail(const std::string& message) const { c_.fail(message); }

  void begin_instance(const ply_element& e, std::uint64_t i) {
    if (!c_.next_content()) {
      c_.fail_at(c_.content_end(),
                 cellforge::detail::cat("expected ", std::to_string(e.count), " '", e.name,
                                        "' elements, found ", std::to_string(i), " before end of file"));
    }
  }
  void end_instance(const ply_element& e, std::uint64_t i) {
    c_.skip_blanks();
    if (!c_.at_line_end())
      c_.fail(cellforge::detail::cat("unexpected ", c_.token(), " after the last property of ", e.name, " ",
                                     std::to_string(i)));
    c_.next_line();
  }
  /// Skips whole instances of an element nobody reads; in ASCII that is one line each.
  void skip_instances(const ply_element& e) {
    for (std::uint64_t i = 0; i < e.count; ++i) {
      begin_instance(e, i);
      c_.next_line();
    }
  }

  template <class What>
  std::int64_t integer(ply_type t, What&& what) {
    return with_ply_type(t, [&]<class T>(std::type_identity<T>) -> std::int64_t {
      if constexpr (std::is_integral_v<T>) {
        return c_.number<T>(what);
      } else {
        (void)c_.number<T>(what);
        return 0;  // not reached: the header only allows integer counts and indices
      }
    });
  }
  template <class S, class What>
  S coordinate(ply_type t, What&& what) {
    return with_ply_type(t, [&]<class T>(std::type_identity<T>) -> S {
      c_.skip_blanks();
      const char* at = c_.pos;
      const T v = c_.number<T>(what);
      S out{};
      if (!convert_coordinate(v, out)) c_.fail_at(at, not_a_coordinate(what(), quote_token(at, c_.end), v));
      return out;
    });
  }
  template <class What>
  void skip(ply_type t, What&& what) {
    with_ply_type(t, [&]<class T>(std::type_identity<T>) { (void)c_.number<T>(what); });
  }
  void finish() {
    if (c_.next_content())
      c_.fail(cellforge::detail::cat("unexpected ", c_.token(), " after the last element"));
  }

  template <class T>
  static std::string not_a_coordinate(const std::string& what, const std::string& text, T v) {
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(v))
        return what + " " + text + " is not finite (NaN and Inf coordinates are rejected)";
    }
    return what + " " + text + " does not fit the point's scalar type";
  }

 private:
  text_cursor& c_;
};

template <class = void>
class basic_ply_binary_reader;
using ply_binary_reader = basic_ply_binary_reader<>;

/// Reads values of a binary PLY body of either byte order; errors name the byte offset.
template <class>
class basic_ply_binary_reader {
 public:
  basic_ply_binary_reader(std::string_view bytes, std::size_t offset, bool little_endian,
                          std::string_view name)
      : begin_(bytes.data()),
        pos_(bytes.data() + offset),
        end_(bytes.data() + bytes.size()),
        swap_((std::endian::native == std::endian::little) != little_endian),
        name_(name) {}

  std::size_t mark() const noexcept { return static_cast<std::size_t>(pos_ - begin_); }
  [[noreturn]] void fail_at(std::size_t at, const std::string& message) const {
    throw error(error_category::io, message, source_location{std::string(name_), 0, at});
  }
  [[noreturn]] void fail(const std::string& message) const { fail_at(mark(), message); }

  void begin_instance(const ply_element& e, std::uint64_t i) noexcept {
    element_ = &e;
    index_ = i;
  }
  void end_instance(const ply_element&, std::uint64_t) noexcept {}

  /// Skips instances of an element nobody reads: in one step when its size is fixed.
  void skip_instances(const ply_element& e) {
    if (const std::size_t size = e.fixed_size(); size != 0) {
      const auto left = static_cast<std::uint64_t>(end_ - pos_);
      if (e.count > left / size) {
        element_ = &e;
        index_ = left / size;
        pos_ = end_;
        fail_truncated();
      }
      pos_ += e.count * size;
      return;
    }
    for (std::uint64_t i = 0; i < e.count; ++i) {
      begin_instance(e, i);
      for (const auto& p : e.properties) {
        if (!p.is_list) {
          skip(p.type, [] { return std::string(); });
          continue;
        }
        const std::int64_t n = integer(p.count_type, [] { return std::string(); });
        if (n < 0)
          fail(cellforge::detail::cat("negative list length ", std::to_string(n), " in ", e.name, " ",
                                      std::to_string(i)));
        const std::uint64_t bytes = static_cast<std::uint64_t>(n) * size_of(p.type);
        if (bytes > static_cast<std::uint64_t>(end_ - pos_)) {
          pos_ = end_;
          fail_truncated();
        }
        pos_ += bytes;
      }
    }
  }

  template <class What>
  std::int64_t integer(ply_type t, What&&) {
    return with_ply_type(t, [&]<class T>(std::type_identity<T>) -> std::int64_t {
      if constexpr (std::is_integral_v<T>)
        return load<T>();
      else
        return static_cast<std::int64_t>(load<T>());  // not reached: the header checks the types
    });
  }
  template <class S, class What>
  S coordinate(ply_type t, What&& what) {
    return with_ply_type(t, [&]<class T>(std::type_identity<T>) -> S {
      const std::size_t at = mark();
      const T v = load<T>();
      S out{};
      if (!convert_coordinate(v, out))
        fail_at(at, ply_ascii_reader::not_a_coordinate(
                        what(), cellforge::detail::cat("(", std::to_string(v), ")"), v));
      return out;
    });
  }
  template <class What>
  void skip(ply_type t, What&&) {
    if (static_cast<std::size_t>(end_ - pos_) < size_of(t)) fail_truncated();
    pos_ += size_of(t);
  }
  void finish() const {
    if (pos_ != end_) fail(std::to_string(end_ - pos_) + " bytes of unexpected data after the last element");
  }

  /// Bytes left to read.
  std::size_t left() const noexcept { return static_cast<std::size_t>(end_ - pos_); }

 private:
  template <class T>
  T load() {
    if (static_cast<std::size_t>(end_ - pos_) < sizeof(T)) fail_truncated();
    std::array<char, sizeof(T)> raw;
    std::memcpy(raw.data(), pos_, sizeof(T));
    if (swap_) std::reverse(raw.begin(), raw.end());
    pos_ += sizeof(T);
    return std::bit_cast<T>(raw);
  }
  [[noreturn]] void fail_truncated() const {
    fail_at(static_cast<std::size_t>(end_ - begin_),
            cellforge::detail::cat(
                "file ends inside ",
                (element_ ? element_->name + " " + std::to_string(index_) : std::string("the data"))));
  }

  const char* begin_;
  const char* pos_;
  const char* end_;
  bool swap_;
  std::string_view name_;
  const ply_element* element_ = nullptr;
  std::uint64_t index_ = 0;
};

/// The property roles of the vertex and face elements, checked against the header.
struct ply_layout {
  const ply_element* vertex = nullptr;
  const ply_element* face = nullptr;
  std::array<int, 3> xyz{-1, -1, -1};  ///< vertex property index of x, y, z
  int indices = -1;                    ///< face property index of the vertex index list
};

template <class = void>
ply_layout ply_check_layout(const ply_header& h, const text_cursor& c) {
  ply_layout l;
  for (const auto& e : h.elements) {
    if (e.name == "vertex") l.vertex = &e;
    if (e.name == "face") l.face = &e;
  }
  if (l.vertex) {
    if (l.vertex->count >= std::numeric_limits<std::uint32_t>::max())
      c.fail_at(l.vertex->declared_at,
                cellforge::detail::cat("element 'vertex' has ", std::to_string(l.vertex->count),
                                       " instances, more than 32-bit indices can address"));
    for (int axis = 0; axis < 3; ++axis) {
      const std::string name(1, "xyz"[axis]);
      for (std::size_t i = 0; i < l.vertex->properties.size(); ++i)
        if (l.vertex->properties[i].name == name) l.xyz[axis] = static_cast<int>(i);
      if (l.xyz[axis] < 0)
        c.fail_at(l.vertex->declared_at,
                  cellforge::detail::cat("element 'vertex' has no property '", name, "'"));
      if (l.vertex->properties[l.xyz[axis]].is_list)
        c.fail_at(
            l.vertex->declared_at,
            cellforge::detail::cat("property '", name, "' of element 'vertex' is a list, not a scalar"));
    }
  }
  if (l.face) {
    for (std::size_t i = 0; i < l.face->properties.size(); ++i) {
      const auto& p = l.face->properties[i];
      if ((p.name == "vertex_indices" || p.name == "vertex_index") && l.indices < 0)
        l.indices = static_cast<int>(i);
    }
    if (l.indices < 0)
      c.fail_at(l.face->declared_at, "element 'face' has no 'vertex_indices' (or 'vertex_index') list");
    const auto& p = l.face->properties[l.indices];
    if (!p.is_list)
      c.fail_at(l.face->declared_at,
                cellforge::detail::cat("property '", p.name, "' of element 'face' must be a list"));
    if (!is_integral(p.type))
      c.fail_at(l.face->declared_at,
                cellforge::detail::cat("the indices of '", p.name, "' must have an integer type, not '",
                                       std::string(ply_type_name(p.type)), "'"));
    if (l.face->count >= std::numeric_limits<std::uint32_t>::max())
      c.fail_at(l.face->declared_at, "element 'face' has too many instances for 32-bit offsets");
  }
  return l;
}

/// Reads the body with reader R (ASCII or binary) into the soup. O(body size).
template <Point3 P, class R>
void ply_read_body(R& r, const ply_header& h, const ply_layout& l, std::size_t bytes_left,
                   polygon_soup<P>& soup, const ply_read_options& options) {
  using S = scalar_t<P>;
  const std::uint64_t nv = l.vertex ? l.vertex->count : 0;
  bool vertices_read = false;
  // Faces read before the vertex element (legal, rare) are checked once the count is known.
  std::vector<std::size_t> deferred_face_at;
  std::vector<std::uint32_t> scratch;
  const auto check_index = [&](std::int64_t idx, std::uint64_t f, std::size_t at) {
    if (idx < 0 || static_cast<std::uint64_t>(idx) >= nv)
      r.fail_at(at, cellforge::detail::cat(
                        "face ", std::to_string(f), ": vertex index ", std::to_string(idx), " out of range ",
                        (nv == 0 ? std::string("(the file has no vertices)")
                                 : cellforge::detail::cat("(0..", std::to_string(nv - 1), ")"))));
  };
  for (const auto& e : h.elements) {
    if (&e == l.vertex) {
      soup.points.reserve(plausible_count(e.count, bytes_left, std::max<std::size_t>(e.min_size(), 2)));
      const auto& props = e.properties;
      for (std::uint64_t v = 0; v < e.count; ++v) {
        r.begin_instance(e, v);
        std::array<S, 3> xyz{};
        for (std::size_t i = 0; i < props.size(); ++i) {
          const auto& p = props[i];
          const auto what = [&] {
            return cellforge::detail::cat("property '", p.name, "' of vertex ", std::to_string(v));
          };
          const int axis = static_cast<int>(i) == l.xyz[0]   ? 0
                           : static_cast<int>(i) == l.xyz[1] ? 1
                           : static_cast<int>(i) == l.xyz[2] ? 2
                                                             : -1;
          if (axis >= 0) {
            xyz[axis] = r.template coordinate<S>(p.type, what);
          } else if (!p.is_list) {
            r.skip(p.type, what);
          } else {
            const std::size_t at = r.mark();
            const std::int64_t n = r.integer(p.count_type, what);
            if (n < 0)
              r.fail_at(at,
                        cellforge::detail::cat("negative list length ", std::to_string(n), " in ", what()));
            for (std::int64_t k = 0; k < n; ++k) r.skip(p.type, what);
          }
        }
        soup.points.push_back(point_traits<P>::make(xyz[0], xyz[1], xyz[2]));
        r.end_instance(e, v);
      }
      vertices_read = true;
    } else if (&e == l.face) {
      soup.face_offsets.reserve(plausible_count(e.count, bytes_left, std::max<std::size_t>(e.min_size(), 2)) +
                                1);
      for (std::uint64_t f = 0; f < e.count; ++f) {
        r.begin_instance(e, f);
        if (!vertices_read) deferred_face_at.push_back(r.mark());
        for (std::size_t i = 0; i < e.properties.size(); ++i) {
          const auto& p = e.properties[i];
          const auto what = [&] {
            return cellforge::detail::cat("property '", p.name, "' of face ", std::to_string(f));
          };
          if (!p.is_list) {
            r.skip(p.type, what);
            continue;
          }
          const std::size_t at = r.mark();
          const std::int64_t n = r.integer(p.count_type, what);
          if (n < 0)
            r.fail_at(at, cellforge::detail::cat("face ", std::to_string(f), " has a negative list length (",
                                                 std::to_string(n), ")"));
          if (static_cast<int>(i) != l.indices) {
            for (std::int64_t k = 0; k < n; ++k) r.skip(p.type, what);
            continue;
          }
          if (n < 3)
            r.fail_at(at, cellforge::detail::cat("face ", std::to_string(f), " has ", std::to_string(n),
                                                 " vertices; a face needs at least 3"));
          const std::size_t first = soup.face_vertices.size();
          for (std::int64_t k = 0; k < n; ++k) {
            const std::size_t iat = r.mark();
            const std::int64_t idx = r.integer(p.type, [&] {
              return cellforge::detail::cat("vertex ", std::to_string(k), " of face ", std::to_string(f));
            });
            if (vertices_read)
              check_index(idx, f, iat);
            else if (idx < 0 || idx >= std::int64_t{std::numeric_limits<std::uint32_t>::max()})
              check_index(idx, f, iat);
            soup.face_vertices.push_back(static_cast<std::uint32_t>(idx));
          }
          if (const auto problem =
                  close_face(soup, first, options.allow_repeated_vertices, scratch, 0, "ply_read_options"))
            r.fail_at(at, cellforge::detail::cat("face ", std::to_string(f), " ", *problem));
        }
        r.end_instance(e, f);
      }
    } else {
      r.skip_instances(e);
    }
  }
  r.finish();
  for (std::size_t f = 0; f < deferred_face_at.size(); ++f)
    for (const std::uint32_t v : soup.face(f)) check_index(v, f, deferred_face_at[f]);
}

}  // namespace detail

/// Parses PLY bytes held in memory; `name` is used in error messages. Throws an io error
/// with file and line (ASCII) or byte offset (binary) on malformed input. O(size of the data).
template <Point3 P>
polygon_soup<P> parse_ply(std::string_view bytes, std::string_view name = "<memory>",
                          const ply_read_options& options = {}) {
  detail::text_cursor c(bytes, name, '\0');
  const detail::ply_header h = detail::parse_ply_header(c);
  const detail::ply_layout layout = detail::ply_check_layout(h, c);
  polygon_soup<P> soup;
  const std::size_t left = bytes.size() - h.data_offset;
  if (h.format == ply_format::ascii) {
    detail::ply_ascii_reader r(c);
    detail::ply_read_body(r, h, layout, left, soup, options);
  } else {
    detail::ply_binary_reader r(bytes, h.data_offset, h.format == ply_format::binary_little_endian, name);
    detail::ply_read_body(r, h, layout, left, soup, options);
  }
  return soup;
}

/// Reads a PLY file. Throws an io error naming the path when it cannot be read, or with
/// the place (line, or byte offset for binary) when it is malformed. O(file size).
template <Point3 P>
polygon_soup<P> read_ply(const file_path& path, const ply_read_options& options = {}) {
  const std::string bytes = detail::read_file(path);
  return parse_ply<P>(bytes, detail::display_name(path), options);
}

/// Writes a soup as PLY (binary little-endian by default, or ASCII / big-endian). Vertex
/// coordinates keep the point's scalar type (double for types PLY lacks); ASCII uses shortest
/// round-trip text. Throws invalid_input on NaN/Inf points or bad indices. O(size).
template <Point3 P>
void write_ply(std::ostream& os, const polygon_soup<P>& soup, const ply_write_options& options = {}) {
  using S = scalar_t<P>;
  detail::check_face_indices(soup, "ply");
  constexpr auto exact = detail::ply_type_of<S>();
  constexpr detail::ply_type coord_type = exact ? *exact : detail::ply_type::float64;
  using C = std::conditional_t<exact.has_value(), S, double>;
  std::size_t max_face = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f)
    max_face = std::max<std::size_t>(max_face, soup.face(f).size());
  const detail::ply_type count_type = max_face <= 0xff     ? detail::ply_type::uint8
                                      : max_face <= 0xffff ? detail::ply_type::uint16
                                                           : detail::ply_type::uint32;
  const detail::ply_type index_type =
      soup.points.size() <= std::size_t{1} << 31 ? detail::ply_type::int32 : detail::ply_type::uint32;

  detail::output_buffer out(os);
  out.put("ply\nformat ");
  out.put(options.format == ply_format::ascii                  ? "ascii"
          : options.format == ply_format::binary_little_endian ? "binary_little_endian"
                                                               : "binary_big_endian");
  out.put(" 1.0\n");
  detail::put_comment_lines(out, options.comment, "comment ");
  out.put("element vertex ");
  out.number(soup.points.size());
  for (const char* axis : {"x", "y", "z"}) {
    out.put("\nproperty ");
    out.put(detail::ply_type_name(coord_type));
    out.put(' ');
    out.put(axis);
  }
  out.put("\nelement face ");
  out.number(soup.num_faces());
  out.put("\nproperty list ");
  out.put(detail::ply_type_name(count_type));
  out.put(' ');
  out.put(detail::ply_type_name(index_type));
  out.put(" vertex_indices\nend_header\n");

  const bool ascii = options.format == ply_format::ascii;
  const bool little = options.format == ply_format::binary_little_endian;
  const auto put_int = [&](detail::ply_type t, std::uint64_t v) {
    if (ascii) return out.number(v);
    detail::with_ply_type(t, [&]<class T>(std::type_identity<T>) { out.binary(static_cast<T>(v), little); });
  };
  for (std::size_t i = 0; i < soup.points.size(); ++i) {
    const P& p = soup.points[i];
    detail::check_point_finite(p, i, "ply");
    for (std::size_t k = 0; k < 3; ++k) {
      const auto v = static_cast<C>(coord(p, k));
      if (ascii) {
        if (k != 0) out.put(' ');
        out.number(v);
      } else {
        out.binary(v, little);
      }
    }
    if (ascii) out.put('\n');
  }
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto face = soup.face(f);
    put_int(count_type, face.size());
    for (const std::uint32_t v : face) {
      if (ascii) out.put(' ');
      put_int(index_type, v);
    }
    if (ascii) out.put('\n');
  }
  out.finish("PLY");
}

/// Writes a soup to a PLY file (see the stream overload). Throws an io error naming the
/// path when it cannot be written. O(size).
template <Point3 P>
void write_ply(const file_path& path, const polygon_soup<P>& soup, const ply_write_options& options = {}) {
  detail::write_file(path, [&](std::ostream& os) { write_ply(os, soup, options); });
}

}  // namespace cellforge::io
