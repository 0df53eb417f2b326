// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// XML text escaping for the SVG writers.

#include <string>
#include <string_view>

namespace cellforge::io::detail {

/// Appends text escaped for XML content and attribute values; control characters become spaces.
template <class = void>
void svg_escape(std::string& out, std::string_view text) {
  for (const char ch : text) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += (static_cast<unsigned char>(ch) < 0x20 && ch != '\t' && ch != '\n' && ch != '\r') ? ' ' : ch;
    }
  }
}

}  // namespace cellforge::io::detail
