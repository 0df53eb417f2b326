// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Large temporary and element arrays backed by huge pages where the kernel offers them.

#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>
#include <vector>

#if defined(__linux__) && __has_include(<sys/mman.h>)
#include <sys/mman.h>
#endif

namespace cellforge::detail {

/// Asks the kernel to back [data, data + bytes) with huge pages where whole 2 MB pages fit
/// in it. Only a hint: without Linux or transparent huge pages it does nothing. O(1).
template <class = void>
void advise_huge_pages([[maybe_unused]] const void* data, [[maybe_unused]] std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t end = begin + bytes;
  const std::uintptr_t first = (begin + huge - 1) & ~(huge - 1), last = end & ~(huge - 1);
  if (last >= first + huge) (void)::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#endif
}

/// Reserves room for n elements in `v` and asks the kernel to back the new block with huge
/// pages when it is large: a fresh 200 MB array then costs ~100 page faults instead of
/// ~50 000 (at 10^6 faces the faults of fresh arrays cost as much as the work on them).
/// Only a hint: without Linux or transparent huge pages, this is a plain reserve. O(1).
template <class T>
void reserve_large(std::vector<T>& v, std::size_t n) {
  if (n <= v.capacity()) return;
  v.reserve(n);
  if constexpr (!std::is_same_v<T, bool>)  // std::vector<bool> has no data()
    advise_huge_pages(v.data(), n * sizeof(T));
}

/// A fixed-size scratch array whose elements start uninitialised (a std::vector would write
/// every element once before the caller does), huge-page hinted. Trivial types only. O(1).
template <class T>
class uninitialized_array {
  static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);

 public:
  explicit uninitialized_array(std::size_t n)
      : data_(n ? static_cast<T*>(::operator new(n * sizeof(T))) : nullptr), size_(n) {
    advise_huge_pages(data_, n * sizeof(T));
  }
  uninitialized_array(const uninitialized_array&) = delete;
  uninitialized_array& operator=(const uninitialized_array&) = delete;
  ~uninitialized_array() { ::operator delete(data_); }
  /// Frees the storage now; the array is empty afterwards.
  void free() noexcept {
    ::operator delete(data_);
    data_ = nullptr;
    size_ = 0;
  }

  T& operator[](std::size_t i) noexcept { return data_[i]; }
  const T& operator[](std::size_t i) const noexcept { return data_[i]; }
  T* begin() noexcept { return data_; }
  T* end() noexcept { return data_ + size_; }
  std::size_t size() const noexcept { return size_; }

 private:
  T* data_;
  std::size_t size_;
};

/// Frees the storage of `v` (assigning {} would keep the capacity). O(1).
template <class T>
void release(std::vector<T>& v) noexcept {
  std::vector<T>().swap(v);
}

}  // namespace cellforge::detail
