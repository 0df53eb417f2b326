// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The one exception type of cellforge: a category, a message a person can act on,
/// and, for parsers, where in which file the problem was found.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace cellforge {

/// What kind of failure an error reports; lets callers react without parsing text.
enum class error_category : std::uint8_t {
  invalid_input,  ///< the caller passed something the function cannot accept
  topology,       ///< the input is well-formed but its connectivity is not representable
  io,             ///< a file could not be opened, read, parsed or written
  budget,         ///< a search hit its work budget before finishing
  internal,       ///< a broken invariant inside cellforge (a bug: please report it)
};

/// Human-readable name of a category ("invalid input", "topology", ...). O(1).
constexpr std::string_view to_string(error_category c) noexcept {
  switch (c) {
    case error_category::invalid_input:
      return "invalid input";
    case error_category::topology:
      return "topology";
    case error_category::io:
      return "io";
    case error_category::budget:
      return "budget";
    case error_category::internal:
      return "internal";
  }
  return "unknown";
}

/// Where in a file a parser found a problem. Empty file name: not from a file.
struct source_location {
  std::string file;
  std::uint64_t line = 0;                 ///< 1-based; 0 when unknown or binary data
  std::uint64_t byte_offset = no_offset;  ///< for binary formats
  static constexpr std::uint64_t no_offset = ~std::uint64_t{0};
};

/// Every failure cellforge reports. what() reads "file:line: message" for parsers.
class error : public std::runtime_error {
 public:
  error(error_category category, const std::string& message)
      : std::runtime_error(message), category_(category), message_(message) {}

  error(error_category category, const std::string& message, source_location where)
      : std::runtime_error(compose(message, where)),
        category_(category),
        message_(message),
        where_(std::move(where)) {}

  error_category category() const noexcept { return category_; }
  /// The message without the location prefix.
  const std::string& message() const noexcept { return message_; }
  const source_location& where() const noexcept { return where_; }
  const std::string& file() const noexcept { return where_.file; }
  std::uint64_t line() const noexcept { return where_.line; }
  std::uint64_t byte_offset() const noexcept { return where_.byte_offset; }

 private:
  static std::string compose(const std::string& message, const source_location& where) {
    if (where.file.empty() && where.line == 0 && where.byte_offset == source_location::no_offset)
      return message;
    // Appended piece by piece: `":" + std::to_string(n)` trips g++ 12's false -Wrestrict
    // (GCC PR 105329) in a user's -O2 -Werror build.
    std::string s = where.file.empty() ? std::string("<input>") : where.file;
    if (where.line != 0) {
      s += ':';
      s += std::to_string(where.line);
    }
    if (where.byte_offset != source_location::no_offset) {
      s += " (byte ";
      s += std::to_string(where.byte_offset);
      s += ')';
    }
    s += ": ";
    s += message;
    return s;
  }

  error_category category_;
  std::string message_;
  source_location where_;
};

}  // namespace cellforge
