// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Buffered output for the writers: numbers formatted with std::to_chars (shortest
/// round-trip text, locale-independent) into a large buffer flushed to a stream in chunks.

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ostream>
#include <streambuf>
#include <string>
#include <string_view>
#include <type_traits>

#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/io/detail/read_file.hpp"

namespace cellforge::io::detail {

template <class = void>
class basic_output_buffer;
using output_buffer = basic_output_buffer<>;

/// Collects output in a 1 MiB buffer and hands it to the stream in big writes.
template <class>
class basic_output_buffer {
 public:
  // Uninitialised storage: small outputs touch only the pages they use.
  explicit basic_output_buffer(std::ostream& os) : os_(os), buf_(new char[capacity]) {}
  basic_output_buffer(const basic_output_buffer&) = delete;
  basic_output_buffer& operator=(const basic_output_buffer&) = delete;
  ~basic_output_buffer() { delete[] buf_; }
  // No flush in the destructor: it would hide write errors during unwinding; callers call finish().

  void put(std::string_view s) {
    if (s.size() > capacity - used_) {
      flush();
      if (s.size() > capacity) {
        os_.write(s.data(), static_cast<std::streamsize>(s.size()));
        return;
      }
    }
    std::memcpy(buf_ + used_, s.data(), s.size());
    used_ += s.size();
  }
  void put(char c) {
    if (used_ == capacity) flush();
    buf_[used_++] = c;
  }

  /// Appends a number as text: shortest round-trip form for floating point.
  template <class T>
  requires std::is_arithmetic_v<T>
  void number(T value) {
    if (capacity - used_ < max_number_chars) flush();
    const auto r = std::to_chars(buf_ + used_, buf_ + capacity, value);
    used_ = static_cast<std::size_t>(r.ptr - buf_);
  }

  /// Appends the raw bytes of a value in little- or big-endian order.
  template <class T>
  requires std::is_arithmetic_v<T>
  void binary(T value, bool little_endian) {
    if (capacity - used_ < sizeof(T)) flush();
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if ((std::endian::native == std::endian::little) != little_endian) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
    }
    std::memcpy(buf_ + used_, bytes, sizeof(T));
    used_ += sizeof(T);
  }

  void flush() {
    if (used_ != 0) os_.write(buf_, static_cast<std::streamsize>(used_));
    used_ = 0;
  }

  /// Flushes and reports a failed stream as an io error.
  void finish(std::string_view what) {
    flush();
    os_.flush();
    if (!os_)
      throw error(error_category::io,
                  cellforge::detail::cat("writing ", std::string(what), " failed (stream error)"));
  }

 private:
  static constexpr std::size_t capacity = std::size_t{1} << 20;
  static constexpr std::size_t max_number_chars = 64;  // longest to_chars output of any scalar
  std::ostream& os_;
  char* buf_;  // new char[] leaves it uninitialised, as make_unique_for_overwrite would (no <memory>)
  std::size_t used_ = 0;
};

/// Writes `text` as comment lines, each prefixed (e.g. "# " or "comment "); empty lines are
/// dropped because a line break inside a comment would end it. O(text).
template <class = void>
void put_comment_lines(output_buffer& out, std::string_view text, std::string_view prefix) {
  while (!text.empty()) {
    const std::size_t eol = std::min(text.find_first_of("\r\n"), text.size());
    if (eol != 0) {
      out.put(prefix);
      out.put(text.substr(0, eol));
      out.put('\n');
    }
    text.remove_prefix(std::min(eol + 1, text.size()));
  }
}

/// A stream buffer over a std::FILE opened for writing: the writers' std::ostream for a file
/// without <fstream> (which every includer would parse). Writes go straight to fwrite, which
/// buffers; output_buffer hands it 1 MiB at a time. close() reports whether everything reached
/// the file. O(1) per call besides the bytes.
template <class = void>
class basic_file_sink : public std::streambuf {
 public:
  explicit basic_file_sink(const file_path& path) : file_(open_file(path, "wb")) {}
  basic_file_sink(const basic_file_sink&) = delete;
  basic_file_sink& operator=(const basic_file_sink&) = delete;
  ~basic_file_sink() override {
    if (file_ != nullptr) std::fclose(file_);
  }
  [[nodiscard]] bool is_open() const noexcept { return file_ != nullptr; }
  /// Closes the file; false when a write or the close failed.
  bool close() noexcept {
    if (file_ == nullptr) return false;
    const bool ok = std::ferror(file_) == 0;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    return ok && closed;
  }

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    const char byte = traits_type::to_char_type(c);
    return std::fwrite(&byte, 1, 1, file_) == 1 ? c : traits_type::eof();
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    return static_cast<std::streamsize>(std::fwrite(s, 1, static_cast<std::size_t>(n), file_));
  }
  int sync() override { return std::fflush(file_) == 0 ? 0 : -1; }

 private:
  std::FILE* file_;
};
using file_sink = basic_file_sink<>;

/// Runs `write(stream)` into a file beside `path` and renames it over `path` only when all of
/// it is written, so a failure (a writer's check, a full disk) never leaves a broken, empty or
/// half-replaced file; a device or pipe is written in place. Errors name the path. O(what write costs).
template <class Write>
void write_file(const file_path& path, Write&& write) {
  const file_kind kind = status_of(path).kind;
  if (kind == file_kind::directory)
    throw error(error_category::io,
                cellforge::detail::cat("cannot open '", display_name(path), "' for writing: it is a folder"));
  const bool in_place = kind == file_kind::other;
  const file_path target = in_place ? path : path.with_suffix(".partial");
  const auto discard = [&] {
    if (!in_place) remove_file(target);
  };
  {
    file_sink sink(target);
    if (!sink.is_open())
      throw error(error_category::io,
                  cellforge::detail::cat("cannot open '", display_name(path), "' for writing"));
    std::ostream os(&sink);
    try {
      write(os);
    } catch (const error& e) {
      sink.close();
      discard();
      if (e.category() != error_category::io) throw;
      throw error(error_category::io,
                  cellforge::detail::cat("cannot write '", display_name(path), "': ", e.message()));
    } catch (...) {
      sink.close();
      discard();
      throw;
    }
    if (!os.flush() || !sink.close()) {
      discard();
      throw error(error_category::io,
                  cellforge::detail::cat("cannot write '", display_name(path), "': closing the file failed"));
    }
  }
  if (in_place) return;
  const std::string why = rename_file(target, path);
  if (!why.empty()) {
    discard();
    throw error(error_category::io,
                cellforge::detail::cat("cannot write '", display_name(path),
                                       "': moving the finished file into place failed (", why, ")"));
  }
}

/// Throws invalid_input when point i has a NaN or infinite coordinate: writing it would make
/// a file that our readers (rightly) reject. O(1).
template <Point3 P>
void check_point_finite(const P& p, std::size_t i, std::string_view format) {
  if constexpr (std::is_floating_point_v<scalar_t<P>>) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (!std::isfinite(coord(p, k)))
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("write_", std::string(format), ": point ", std::to_string(i),
                                           " has a non-finite coordinate"));
    }
  }
}

/// Throws invalid_input unless the offsets are well formed, every face has 3+ vertices and every
/// index names a point: a writer never makes a file its reader would reject. O(indices).
template <class Soup>
void check_face_indices(const Soup& soup, std::string_view format) {
  const std::size_t n = soup.points.size();
  if (soup.face_offsets.empty() || soup.face_offsets.front() != 0 ||
      soup.face_offsets.back() != soup.face_vertices.size())
    throw error(error_category::invalid_input,
                cellforge::detail::cat("write_", std::string(format), ": malformed face offsets"));
  for (std::size_t f = 0; f + 1 < soup.face_offsets.size(); ++f) {
    if (soup.face_offsets[f] > soup.face_offsets[f + 1])
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_", std::string(format), ": malformed face offsets"));
    if (soup.face_offsets[f + 1] - soup.face_offsets[f] < 3)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_", std::string(format), ": face ", std::to_string(f),
                                         " has fewer than 3 vertices"));
  }
  for (std::size_t i = 0; i < soup.face_vertices.size(); ++i) {
    if (soup.face_vertices[i] >= n)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_", std::string(format), ": face vertex index ",
                                         std::to_string(soup.face_vertices[i]), " out of range (",
                                         std::to_string(n), " points)"));
  }
}

}  // namespace cellforge::io::detail
