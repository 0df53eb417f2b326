// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Whole-file reading for the parsers: one allocation and one read call, so that the
/// parsers work on a contiguous buffer instead of streaming through iostreams.

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/io/file_path.hpp"

namespace cellforge::io::detail {

/// The display name of a path in error messages (the path as given, not made absolute).
template <class = void>
std::string display_name(const file_path& path) {
  return path.string();
}

/// Reads the whole file into a string; throws an io error naming the path and the
/// reason when it cannot be opened or read. O(file size).
template <class = void>
std::string read_file(const file_path& path) {
  const auto fail = [&](const char* what, int err) -> error {
    return error(error_category::io,
                 cellforge::detail::cat(std::string("cannot "), what, " '", display_name(path),
                                        "': ", (err != 0 ? std::strerror(err) : "read error")));
  };
  const file_status status = status_of(path);
  if (status.kind == file_kind::directory) throw fail("read", EISDIR);
  // A pipe or device (/dev/zero, a FIFO) has no end we can trust: it could block forever or
  // never stop. Readers take regular files; copy the data to one first.
  if (status.kind == file_kind::other)
    throw error(
        error_category::io,
        cellforge::detail::cat("cannot read '", display_name(path),
                               "': not a regular file (a pipe or device); save the data to a file first"));
  errno = 0;
  const file_handle file(open_file(path, "rb"));
  if (!file) throw fail("open", errno);
  std::string bytes;
  // Size from the file; the chunked reads below catch a file that grew since.
  bytes.resize(static_cast<std::size_t>(status.size));
  std::size_t used = std::fread(bytes.data(), 1, bytes.size(), file.get());
  if (used < bytes.size()) {
    if (std::ferror(file.get())) throw fail("read", errno);
    bytes.resize(used);  // the file shrank while we read it
  }
  char chunk[65536];
  while (!std::feof(file.get())) {
    const std::size_t n = std::fread(chunk, 1, sizeof chunk, file.get());
    if (std::ferror(file.get())) throw fail("read", errno);
    bytes.append(chunk, n);
  }
  return bytes;
}

/// parse(bytes, name) of the file at `path`, its result's milliseconds (stage_report) the whole
/// read, the file's too. O(file size + the parse).
template <class Parse>
auto read_and_parse(const file_path& path, Parse&& parse) {
  const cellforge::detail::stopwatch clock;
  const std::string bytes = read_file(path);
  auto r = parse(std::string_view(bytes), display_name(path));
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge::io::detail
