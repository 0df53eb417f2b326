// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Large temporary and element arrays backed by huge pages where the kernel offers them.

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#if defined(__linux__) && __has_include(<sys/mman.h>)
#include <sys/mman.h>
#endif

namespace cellforge::detail {

/// Reserves room for n elements in `v` and asks the kernel to back the new block with huge
/// pages when it is large: a fresh 200 MB array then costs ~100 page faults instead of
/// ~50 000 (at 10^6 faces the faults of fresh arrays cost as much as the work on them).
/// Only a hint: without Linux or transparent huge pages, this is a plain reserve. O(1).
template <class T>
void reserve_large(std::vector<T>& v, std::size_t n) {
  if (n <= v.capacity()) return;
  v.reserve(n);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if constexpr (!std::is_same_v<T, bool>) {  // std::vector<bool> has no data()
    constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
    const auto begin = reinterpret_cast<std::uintptr_t>(v.data());
    const std::uintptr_t end = begin + n * sizeof(T);
    const std::uintptr_t first = (begin + huge - 1) & ~(huge - 1), last = end & ~(huge - 1);
    if (last >= first + huge) (void)::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  }
#endif
}

/// Frees the storage of `v` (assigning {} would keep the capacity). O(1).
template <class T>
void release(std::vector<T>& v) noexcept {
  std::vector<T>().swap(v);
}

}  // namespace cellforge::detail
