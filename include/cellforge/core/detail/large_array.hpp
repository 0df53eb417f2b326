// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Large temporary and element arrays backed by huge pages where the kernel offers them.

#include <cstddef>
#include <cstdint>
#include <memory_resource>
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
template <class T, class A>
void reserve_large(std::vector<T, A>& v, std::size_t n) {
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

/// One call's scratch memory for many arrays (std::pmr::memory_resource): a block of address
/// space mapped once, huge-page hinted and handed out in order, freed whole at the end (a
/// deallocation only returns the block's top, so a grown array's old copy stays till the end).
/// Arrays of up to `largest` bytes then share 2 MB pages instead of faulting in 4 KiB pages of
/// their own (~10 µs each on a VM); larger ones, what the block cannot hold, everything under
/// AddressSanitizer and everything without Linux go to new/delete, where a warm heap hands back
/// memory already mapped (fresh huge pages cost their zeroing). The size rule (measured on one
/// VM, bench/results/2026-12-07-tubecheck-5.md): below 64 MB of room asked for nothing is mapped
/// (a small call's arrays fit the warm heap, and a huge page costs more than the 4 KiB faults it
/// saves); below 256 MB every array goes to the block; above, arrays over 2 MB stay on the heap
/// (zeroing ~100 MB of fresh pages a call lost at 100k tube nodes). O(1).
class scratch_arena : public std::pmr::memory_resource {
 public:
  static constexpr std::size_t from_room = std::size_t{64} << 20;     ///< no block below
  static constexpr std::size_t all_below = std::size_t{256} << 20;    ///< every array in the block
  static constexpr std::size_t largest_above = std::size_t{2} << 20;  ///< the largest array above
  /// The largest array the block takes for `bytes` of room. O(1).
  static constexpr std::size_t largest_for(std::size_t bytes) noexcept {
    return bytes < all_below ? bytes : largest_above;
  }
  /// Room for `bytes` by the size rule above. O(1).
  explicit scratch_arena(std::size_t bytes) : scratch_arena(bytes, largest_for(bytes), from_room) {}
  /// Reserves `bytes` of address space when they are at least `from` (touched pages only cost
  /// memory); arrays over `largest` bytes go to new/delete. O(1).
  scratch_arena(std::size_t bytes, std::size_t largest, std::size_t from) : largest_(largest) {
#if defined(__linux__) && defined(MAP_NORESERVE)
    // Under AddressSanitizer every array goes to new/delete, where overruns are caught.
#if defined(__SANITIZE_ADDRESS__)
    return;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    return;
#endif
#endif
    if (bytes < from) return;
    constexpr std::size_t huge = std::size_t{2} << 20;
    const std::size_t mapped = (bytes + 2 * huge - 1) & ~(huge - 1);
    void* p =
        ::mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (p == MAP_FAILED) return;
    map_ = static_cast<char*>(p), mapped_ = mapped;
    // From the first 2 MB boundary, so that the first arrays are on huge pages too.
    base_ =
        reinterpret_cast<char*>((reinterpret_cast<std::uintptr_t>(p) + huge - 1) & ~std::uintptr_t{huge - 1});
    size_ = static_cast<std::size_t>(map_ + mapped - base_);
    advise_huge_pages(base_, size_);
#else
    (void)bytes, (void)from;
#endif
  }
  /// Whether a block was mapped (false: every array goes to new/delete). O(1).
  bool mapped() const noexcept { return base_ != nullptr; }
  /// Whether p lies in the block. O(1).
  bool owns(const void* p) const noexcept {
    const auto at = reinterpret_cast<std::uintptr_t>(p), base = reinterpret_cast<std::uintptr_t>(base_);
    return base_ != nullptr && at >= base && at - base < size_;
  }
  scratch_arena(const scratch_arena&) = delete;
  scratch_arena& operator=(const scratch_arena&) = delete;
  ~scratch_arena() override {
#if defined(__linux__) && defined(MAP_NORESERVE)
    if (map_ != nullptr) ::munmap(map_, mapped_);
#endif
  }

 private:
  void* do_allocate(std::size_t bytes, std::size_t align) override {
    const std::size_t at = (used_ + align - 1) & ~(align - 1);
    if (base_ == nullptr || bytes > largest_ || at > size_ || bytes > size_ - at)
      return std::pmr::new_delete_resource()->allocate(bytes, align);
    used_ = at + bytes;
    return base_ + at;
  }
  void do_deallocate(void* p, std::size_t bytes, std::size_t align) override {
    if (!owns(p)) {
      std::pmr::new_delete_resource()->deallocate(p, bytes, align);
      return;
    }
    const auto at = static_cast<std::size_t>(static_cast<char*>(p) - base_);
    if (at + bytes == used_) used_ = at;  // the top: reused
  }
  bool do_is_equal(const std::pmr::memory_resource& other) const noexcept override { return this == &other; }

  char* map_ = nullptr;
  char* base_ = nullptr;
  std::size_t largest_, mapped_ = 0, size_ = 0, used_ = 0;
};

}  // namespace cellforge::detail
