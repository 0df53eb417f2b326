// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// cat(): the one way the library builds a message from pieces. `"text" + s` inserts at the
/// front of a temporary string, which GCC 12 at -O2/-O3 misreads as an overlapping copy
/// (-Wrestrict) in the user's -Werror build; appending to a reserved string does not.

#include <initializer_list>
#include <string>
#include <string_view>
#include <type_traits>

namespace cellforge::detail {

/// The pieces appended in order to one string. O(total length); one allocation.
template <class = void>
std::string cat_views(std::initializer_list<std::string_view> pieces) {
  std::size_t size = 0;
  for (const std::string_view p : pieces) size += p.size();
  std::string out;
  out.reserve(size);
  for (const std::string_view p : pieces) out.append(p);
  return out;
}

/// A piece as text: a char is the one character it holds (alive for the whole call).
template <class T>
std::string_view text_piece(const T& piece) {
  static_assert(std::is_same_v<T, char> || std::is_convertible_v<const T&, std::string_view>,
                "cat: every piece is text or a char (numbers go through std::to_string)");
  if constexpr (std::is_same_v<T, char>)
    return std::string_view(&piece, 1);
  else
    return std::string_view(piece);
}

/// The pieces (strings, string views, C strings, chars) appended in order to one string.
/// O(total length); one allocation. A thin forwarder, so each call's signature costs little.
template <class... Pieces>
std::string cat(const Pieces&... pieces) {
  return cat_views({text_piece(pieces)...});
}

}  // namespace cellforge::detail
