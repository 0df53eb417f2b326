// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Brackets around a struct with a `[[deprecated]]` data member, and around the library's own
/// uses of one: g++ and clang warn where they synthesize a copy or default constructor of such a
/// struct (at the struct), so without these every copy a user makes would warn; a user's own
/// read or write of the member still does (docs/vocabulary.md, "Deprecated spellings").

#if defined(__GNUC__)  // g++ and clang
#define CELLFORGE_DETAIL_ALLOW_DEPRECATED_BEGIN \
  _Pragma("GCC diagnostic push") _Pragma("GCC diagnostic ignored \"-Wdeprecated-declarations\"")
#define CELLFORGE_DETAIL_ALLOW_DEPRECATED_END _Pragma("GCC diagnostic pop")
#elif defined(_MSC_VER)
#define CELLFORGE_DETAIL_ALLOW_DEPRECATED_BEGIN __pragma(warning(push)) __pragma(warning(disable : 4996))
#define CELLFORGE_DETAIL_ALLOW_DEPRECATED_END __pragma(warning(pop))
#else
#define CELLFORGE_DETAIL_ALLOW_DEPRECATED_BEGIN
#define CELLFORGE_DETAIL_ALLOW_DEPRECATED_END
#endif
