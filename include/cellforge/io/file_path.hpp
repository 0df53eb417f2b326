// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The file name every reader and writer of `cellforge/io/` takes, and the few file-system
/// operations they need (what a path is, its size, remove, rename).
///
/// `file_path` converts implicitly from `const char*`, `std::string`, `std::string_view` and
/// `std::filesystem::path` (any type with a `string()` member), so calls read as they would
/// with `std::filesystem::path` parameters, but the io headers do not include `<filesystem>`:
/// on g++ 12 it cost about 4 % of the instructions of a translation unit that includes the
/// umbrella and the io headers (docs/benchmarks.md, "Compile time").
///
/// On POSIX systems the operations are `stat`, `std::remove` and `std::rename` on the name's
/// bytes. On Windows, or wherever `CELLFORGE_IO_STD_FILESYSTEM` is defined to 1 before the
/// first cellforge header (define it for the whole program, as it changes `file_path`), a
/// `file_path` holds a `std::filesystem::path` and the operations are `std::filesystem`'s,
/// so wide file names reach the system unchanged.

#include <cerrno>
#include <concepts>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

#if !defined(CELLFORGE_IO_STD_FILESYSTEM)
#if defined(_WIN32)
#define CELLFORGE_IO_STD_FILESYSTEM 1
#else
#define CELLFORGE_IO_STD_FILESYSTEM 0
#endif
#endif

#if CELLFORGE_IO_STD_FILESYSTEM
#include <filesystem>
#include <system_error>
#else
#include <sys/stat.h>
#endif

namespace cellforge::io {

namespace detail {
/// A path type other than a string that gives its name with `string()`: std::filesystem::path.
template <class Path>
concept path_like = !std::convertible_to<const Path&, std::string_view> && requires(const Path& p) {
  { p.string() } -> std::convertible_to<std::string>;
};
}  // namespace detail

/// A file name for the io functions, from a string or a `std::filesystem::path`.
class file_path {
 public:
  file_path(const char* name) : name_(name) {}                    // NOLINT: implicit on purpose
  file_path(std::string name) : name_(std::move(name)) {}         // NOLINT
  file_path(std::string_view name) : name_(std::string(name)) {}  // NOLINT
  /// From `std::filesystem::path` or any path type with `string()` (and, for the
  /// std::filesystem mode, convertible to `std::filesystem::path`).
  template <detail::path_like Path>
  file_path(const Path& path) : name_(stored(path)) {}  // NOLINT

  /// The name as text, for messages (narrow; on Windows in the current code page). O(length).
  [[nodiscard]] std::string string() const {
#if CELLFORGE_IO_STD_FILESYSTEM
    return name_.string();
#else
    return name_;
#endif
  }

  /// The part after the last '.' of the last component, with the dot (".off"), or "". O(length).
  [[nodiscard]] std::string extension() const {
#if CELLFORGE_IO_STD_FILESYSTEM
    return name_.extension().string();
#else
    const std::size_t slash = name_.find_last_of('/');
    const std::string_view last =
        slash == std::string::npos ? std::string_view(name_) : std::string_view(name_).substr(slash + 1);
    const std::size_t dot = last.find_last_of('.');
    // ".profile" and ".." have no extension, as std::filesystem::path::extension says.
    if (dot == std::string_view::npos || dot == 0 || last == "..") return {};
    return std::string(last.substr(dot));
#endif
  }

  /// This name with `suffix` appended to its last component ("a.off" + ".partial"). O(length).
  [[nodiscard]] file_path with_suffix(std::string_view suffix) const {
    file_path p = *this;
#if CELLFORGE_IO_STD_FILESYSTEM
    p.name_ += std::string(suffix);
#else
    p.name_.append(suffix);
#endif
    return p;
  }

#if CELLFORGE_IO_STD_FILESYSTEM
  [[nodiscard]] const std::filesystem::path& native() const noexcept { return name_; }
#else
  [[nodiscard]] const std::string& native() const noexcept { return name_; }
#endif

 private:
  template <class Path>
  static auto stored(const Path& path) {
#if CELLFORGE_IO_STD_FILESYSTEM
    return std::filesystem::path(path);
#else
    return path.string();
#endif
  }

#if CELLFORGE_IO_STD_FILESYSTEM
  std::filesystem::path name_;
#else
  std::string name_;
#endif
};

namespace detail {

/// What a name refers to, as the readers and writers need to know it.
enum class file_kind { missing, regular, directory, other };

/// The kind of the file a name refers to (following links) and its size when it is a
/// regular file (0 otherwise, or when the size cannot be read). O(1) system calls.
struct file_status {
  file_kind kind = file_kind::missing;
  std::uint64_t size = 0;
};

template <class = void>
file_status status_of(const file_path& path) {
  file_status s;
#if CELLFORGE_IO_STD_FILESYSTEM
  std::error_code ec;
  const auto st = std::filesystem::status(path.native(), ec);
  if (std::filesystem::is_directory(st)) {
    s.kind = file_kind::directory;
  } else if (std::filesystem::is_regular_file(st)) {
    s.kind = file_kind::regular;
    const auto size = std::filesystem::file_size(path.native(), ec);
    if (!ec) s.size = static_cast<std::uint64_t>(size);
  } else if (std::filesystem::exists(st)) {
    s.kind = file_kind::other;
  }
#else
  struct stat st {};
  if (::stat(path.native().c_str(), &st) != 0) return s;  // missing, or not reachable: the open says why
  if (S_ISDIR(st.st_mode)) {
    s.kind = file_kind::directory;
  } else if (S_ISREG(st.st_mode)) {
    s.kind = file_kind::regular;
    s.size = st.st_size > 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
  } else {
    s.kind = file_kind::other;
  }
#endif
  return s;
}

/// Opens a file with std::fopen's modes ("rb", "wb"); null with errno set on failure. O(1).
template <class = void>
std::FILE* open_file(const file_path& path, const char* mode) {
#if CELLFORGE_IO_STD_FILESYSTEM && defined(_WIN32)
  const std::wstring wide_mode(mode, mode + std::char_traits<char>::length(mode));
  return ::_wfopen(path.native().c_str(), wide_mode.c_str());
#else
  return std::fopen(path.native().c_str(), mode);
#endif
}

/// Owns an open std::FILE and closes it when it goes out of scope (what a
/// std::unique_ptr with fclose would do, without <memory> in every io header).
template <class = void>
class basic_file_handle {
 public:
  explicit basic_file_handle(std::FILE* file) noexcept : file_(file) {}
  basic_file_handle(const basic_file_handle&) = delete;
  basic_file_handle& operator=(const basic_file_handle&) = delete;
  ~basic_file_handle() {
    if (file_ != nullptr) std::fclose(file_);
  }
  [[nodiscard]] std::FILE* get() const noexcept { return file_; }
  explicit operator bool() const noexcept { return file_ != nullptr; }

 private:
  std::FILE* file_;
};
using file_handle = basic_file_handle<>;

/// Removes a file, ignoring failure (used to clean up a partial output). O(1).
template <class = void>
void remove_file(const file_path& path) noexcept {
#if CELLFORGE_IO_STD_FILESYSTEM
  std::error_code ignored;
  std::filesystem::remove(path.native(), ignored);
#else
  (void)std::remove(path.native().c_str());
#endif
}

/// Renames `from` over `to` (replacing it); the system's reason on failure, "" on success. O(1).
template <class = void>
std::string rename_file(const file_path& from, const file_path& to) {
#if CELLFORGE_IO_STD_FILESYSTEM
  std::error_code ec;
  std::filesystem::rename(from.native(), to.native(), ec);
  return ec ? ec.message() : std::string();
#else
  errno = 0;
  if (std::rename(from.native().c_str(), to.native().c_str()) == 0) return {};
  return errno != 0 ? std::string(std::strerror(errno)) : std::string("rename failed");
#endif
}

}  // namespace detail
}  // namespace cellforge::io
