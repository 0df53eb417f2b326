// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// cat(): the one way the library builds a message from pieces. `"text" + s` inserts at the
/// front of a temporary string, which GCC 12 at -O2/-O3 misreads as an overlapping copy
/// (-Wrestrict) in the user's -Werror build; appending to a reserved string does not.

#include <string>
#include <string_view>
#include <type_traits>

namespace cellforge::detail {

/// The pieces (strings, string views, C strings, chars) appended in order to one string.
/// O(total length); one allocation.
template <class... Pieces>
std::string cat(const Pieces&... pieces) {
  static_assert(
      ((std::is_same_v<Pieces, char> || std::is_convertible_v<const Pieces&, std::string_view>)&&...),
      "cat: every piece is text or a char (numbers go through std::to_string)");
  const auto size = [](const auto& p) -> std::size_t {
    if constexpr (std::is_same_v<std::decay_t<decltype(p)>, char>)
      return 1;
    else
      return std::string_view(p).size();
  };
  std::string out;
  out.reserve((size(pieces) + ... + 0));
  const auto add = [&out](const auto& p) {
    if constexpr (std::is_same_v<std::decay_t<decltype(p)>, char>)
      out.push_back(p);
    else
      out.append(std::string_view(p));
  };
  (add(pieces), ...);
  return out;
}

}  // namespace cellforge::detail
