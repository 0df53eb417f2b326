// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// An open-addressing hash map from a directed vertex pair (tail, head) to a 32-bit
/// value. It is the "hash table of unlinked half-edges": small, flat, no node
/// allocations, and it shrinks when it empties so that iterating it costs O(size).

#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

#include "cellforge/core/detail/large_array.hpp"

namespace cellforge::detail {

template <class = void>
class basic_edge_table;
using edge_table = basic_edge_table<>;

template <class>
class basic_edge_table {
 public:
  static constexpr std::uint32_t not_found = 0xFFFFFFFFu;

  /// Key for the directed pair (tail, head). O(1).
  static constexpr std::uint64_t key(std::uint32_t tail, std::uint32_t head) noexcept {
    return (std::uint64_t{tail} << 32) | head;
  }

  std::size_t size() const noexcept { return size_; }
  bool empty() const noexcept { return size_ == 0; }
  std::size_t capacity() const noexcept { return slots_.size(); }

  void clear() noexcept {
    slots_.clear();
    size_ = 0;
  }

  /// Makes room for n entries without rehashing. O(n).
  void reserve(std::size_t n) {
    std::size_t cap = 16;
    while (cap < 2 * n) cap *= 2;
    if (cap > slots_.size()) rehash(cap);
  }

  /// Value stored under k, or not_found. O(1) expected.
  std::uint32_t find(std::uint64_t k) const noexcept {
    if (slots_.empty()) return not_found;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = slot_of(k);; i = (i + 1) & mask) {
      if (slots_[i].key == k) return slots_[i].value;
      if (slots_[i].key == empty_key) return not_found;
    }
  }

  /// Inserts or overwrites k -> v. O(1) expected, amortised.
  void insert(std::uint64_t k, std::uint32_t v) {
    if (2 * (size_ + 1) > slots_.size()) rehash(slots_.empty() ? 16 : slots_.size() * 2);
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = slot_of(k);; i = (i + 1) & mask) {
      if (slots_[i].key == k) {
        slots_[i].value = v;
        return;
      }
      if (slots_[i].key == empty_key) {
        slots_[i] = {k, v};
        ++size_;
        return;
      }
    }
  }

  /// Removes k; returns whether it was present. O(1) expected (backward-shift deletion,
  /// so no tombstones accumulate); shrinks the table when it is mostly empty.
  bool erase(std::uint64_t k) noexcept {
    if (slots_.empty()) return false;
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = slot_of(k);
    while (slots_[i].key != k) {
      if (slots_[i].key == empty_key) return false;
      i = (i + 1) & mask;
    }
    // Shift later members of the probe run back into the hole.
    for (std::size_t j = (i + 1) & mask; slots_[j].key != empty_key; j = (j + 1) & mask) {
      const std::size_t home = slot_of(slots_[j].key);
      if (((j - home) & mask) >= ((j - i) & mask)) {
        slots_[i] = slots_[j];
        i = j;
      }
    }
    slots_[i].key = empty_key;
    --size_;
    if (slots_.size() > 64 && 8 * size_ < slots_.size()) rehash_nothrow(slots_.size() / 4);
    return true;
  }

  /// Calls f(key, value) for every entry. O(size) thanks to the shrink policy.
  template <class F>
  void for_each(F&& f) const {
    for (const auto& s : slots_)
      if (s.key != empty_key) f(s.key, s.value);
  }

  struct slot {
    std::uint64_t key = empty_key;
    std::uint32_t value = not_found;
  };
  const std::vector<slot>& slots() const noexcept { return slots_; }
  static constexpr std::uint64_t empty_key = ~std::uint64_t{0};

  /// Replaces the contents by `entries` (distinct keys), inserted in order of their home slot
  /// so that the table is written nearly front to back instead of at random: several times
  /// faster than one insert per entry once the table outgrows the cache. O(n).
  void assign(const std::vector<slot>& entries) {
    clear();
    reserve(entries.size());
    if (entries.empty()) return;
    const int bits = std::countr_zero(slots_.size());
    const int shift = bits > 12 ? bits - 12 : 0;  // at most 4096 buckets of neighbouring slots
    std::vector<std::uint32_t> start((std::size_t{1} << (bits - shift)) + 1, 0);
    for (const slot& e : entries) ++start[(slot_of(e.key) >> shift) + 1];
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    std::vector<std::uint32_t> order(entries.size());
    for (std::uint32_t i = 0; i < entries.size(); ++i) order[start[slot_of(entries[i].key) >> shift]++] = i;
    for (const std::uint32_t i : order) insert(entries[i].key, entries[i].value);
  }

 private:
  std::size_t slot_of(std::uint64_t k) const noexcept {
    // Fibonacci hashing spreads the structured (tail, head) keys over the table.
    const std::uint64_t h = (k ^ (k >> 29)) * 0x9E3779B97F4A7C15ull;
    return static_cast<std::size_t>(h >> (64 - std::countr_zero(slots_.size())));
  }

  void rehash(std::size_t cap) {
    std::vector<slot> old;
    reserve_large(old, cap);
    old.resize(cap);
    old.swap(slots_);
    size_ = 0;
    for (const auto& s : old)
      if (s.key != empty_key) insert(s.key, s.value);
  }
  void rehash_nothrow(std::size_t cap) noexcept {
    try {
      rehash(cap);
    } catch (...) {  // shrinking is an optimisation; keep the larger table when memory is short
    }
  }

  std::vector<slot> slots_;
  std::size_t size_ = 0;
};

}  // namespace cellforge::detail
