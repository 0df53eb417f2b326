// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Open-addressing hash maps keyed by a directed vertex pair (tail, head): edge_table stores
/// the key beside a 32-bit value (16 B a slot); derived_key_table, the half-edge mesh's
/// "hash table of unlinked half-edges", stores only the value and 32 hash bits (8 B a slot)
/// because the mesh can read an entry's key off its records. Both are flat, allocate no
/// nodes, and shrink when they empty so that iterating them costs O(size).

#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

#include "cellforge/core/detail/large_array.hpp"

namespace cellforge::detail {

/// The indices 0..n-1 of a table's new entries ordered by home slot (home_of(i) < capacity, a
/// power of two) to within 1/4096 of the table, so that filling the table in this order
/// writes it nearly front to back instead of at random. O(n).
template <class HomeOf>
std::vector<std::uint32_t> order_by_home(std::size_t n, std::size_t capacity, const HomeOf& home_of) {
  const int bits = std::countr_zero(capacity);
  const int shift = bits > 12 ? bits - 12 : 0;  // at most 4096 buckets of neighbouring slots
  std::vector<std::uint32_t> start((std::size_t{1} << (bits - shift)) + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++start[(home_of(i) >> shift) + 1];
  for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[start[home_of(i) >> shift]++] = static_cast<std::uint32_t>(i);
  return order;
}

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
  void insert(std::uint64_t k, std::uint32_t v) { slots_[claim(k, v)].value = v; }

  /// Inserts k -> v unless k is present; returns whether it inserted (a set's insert). O(1)
  /// expected, amortised.
  bool try_insert(std::uint64_t k, std::uint32_t v) {
    const std::size_t before = size_;
    claim(k, v);
    return size_ != before;
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
    const auto order =
        order_by_home(entries.size(), slots_.size(), [&](std::size_t i) { return slot_of(entries[i].key); });
    for (const std::uint32_t i : order) insert(entries[i].key, entries[i].value);
  }

 private:
  /// The slot holding k, which gets k -> v first if k was absent (one probe sequence). O(1)
  /// expected, amortised.
  std::size_t claim(std::uint64_t k, std::uint32_t v) {
    if (2 * (size_ + 1) > slots_.size()) rehash(slots_.empty() ? 16 : slots_.size() * 2);
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = slot_of(k);; i = (i + 1) & mask) {
      if (slots_[i].key == k) return i;
      if (slots_[i].key == empty_key) {
        slots_[i] = {k, v};
        ++size_;
        return i;
      }
    }
  }
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

/// The unlinked table of a half-edge mesh: a set of 32-bit values (face half-edges) whose
/// 64-bit key (tail, head) the mesh can read off its records, so a slot holds the value and
/// 32 bits of the key's hash, 8 bytes instead of edge_table's 16, and the table fills to 3/4
/// instead of 1/2. Lookups compare the hash bits and call key_of(value) only when they agree
/// (almost always the entry sought); the hash bits also give an entry's home slot, so
/// rehashing and deletion never call key_of. Linear probing, backward-shift deletion,
/// shrinks when it empties so iterating it is O(size).
template <class = void>
class basic_derived_key_table;
using derived_key_table = basic_derived_key_table<>;

template <class>
class basic_derived_key_table {
 public:
  static constexpr std::uint32_t not_found = 0xFFFFFFFFu;
  /// A stored entry: the top 32 bits of the key's hash and the value (not_found: empty slot).
  struct slot {
    std::uint32_t tag = 0;
    std::uint32_t value = not_found;
  };

  /// Key for the directed pair (tail, head), as edge_table's. O(1).
  static constexpr std::uint64_t key(std::uint32_t tail, std::uint32_t head) noexcept {
    return basic_edge_table<>::key(tail, head);
  }
  /// The slot that stores value v under key k (for assign). O(1).
  static constexpr slot entry(std::uint64_t k, std::uint32_t v) noexcept { return {tag_of(k), v}; }

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
    while (4 * n > 3 * cap) cap *= 2;
    if (cap > slots_.size()) rehash(cap);
  }

  /// Value stored under k, or not_found; key_of(value) gives a stored value's key. O(1) expected.
  template <class KeyOf>
  std::uint32_t find(std::uint64_t k, const KeyOf& key_of) const {
    if (slots_.empty()) return not_found;
    const std::uint32_t t = tag_of(k);
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = home(t);; i = (i + 1) & mask) {
      const slot s = slots_[i];
      if (s.value == not_found) return not_found;
      if (s.tag == t && key_of(s.value) == k) return s.value;
    }
  }

  /// Inserts or overwrites k -> v. O(1) expected, amortised.
  template <class KeyOf>
  void insert(std::uint64_t k, std::uint32_t v, const KeyOf& key_of) {
    grow_for(size_ + 1);
    const std::uint32_t t = tag_of(k);
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = home(t);; i = (i + 1) & mask) {
      slot& s = slots_[i];
      if (s.value == not_found) {
        s = {t, v};
        ++size_;
        return;
      }
      if (s.tag == t && key_of(s.value) == k) {
        s.value = v;
        return;
      }
    }
  }

  /// Removes k; returns whether it was present. O(1) expected (backward-shift deletion, so
  /// no tombstones accumulate); shrinks the table when it is mostly empty.
  template <class KeyOf>
  bool erase(std::uint64_t k, const KeyOf& key_of) noexcept {
    if (slots_.empty()) return false;
    const std::uint32_t t = tag_of(k);
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = home(t);
    for (;; i = (i + 1) & mask) {
      if (slots_[i].value == not_found) return false;
      if (slots_[i].tag == t && key_of(slots_[i].value) == k) break;
    }
    // Shift later members of the probe run back into the hole.
    for (std::size_t j = (i + 1) & mask; slots_[j].value != not_found; j = (j + 1) & mask) {
      if (((j - home(slots_[j].tag)) & mask) >= ((j - i) & mask)) {
        slots_[i] = slots_[j];
        i = j;
      }
    }
    slots_[i].value = not_found;
    --size_;
    if (slots_.size() > 64 && 8 * size_ < slots_.size()) {
      try {
        rehash(slots_.size() / 4);
      } catch (...) {  // shrinking is an optimisation; keep the larger table when memory is short
      }
    }
    return true;
  }

  /// Calls f(value) for every entry. O(size) thanks to the shrink policy.
  template <class F>
  void for_each(F&& f) const {
    for (const slot& s : slots_)
      if (s.value != not_found) f(s.value);
  }

  /// Replaces the contents by `entries` (made by entry(), distinct keys), placed in order of
  /// their home slot so that the table is written nearly front to back instead of at random.
  /// O(n).
  void assign(const std::vector<slot>& entries) {
    clear();
    reserve(entries.size());
    if (entries.empty()) return;
    const auto order =
        order_by_home(entries.size(), slots_.size(), [&](std::size_t i) { return home(entries[i].tag); });
    for (const std::uint32_t i : order) place(entries[i]);
  }

 private:
  static constexpr std::uint32_t tag_of(std::uint64_t k) noexcept {
    // Fibonacci hashing spreads the structured (tail, head) keys; the top bits pick the slot.
    return static_cast<std::uint32_t>(((k ^ (k >> 29)) * 0x9E3779B97F4A7C15ull) >> 32);
  }
  std::size_t home(std::uint32_t t) const noexcept { return t >> (32 - std::countr_zero(slots_.size())); }

  // Puts an entry known to be absent into its first free slot (no key comparison).
  void place(slot e) noexcept {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = home(e.tag);
    while (slots_[i].value != not_found) i = (i + 1) & mask;
    slots_[i] = e;
    ++size_;
  }
  void grow_for(std::size_t n) {
    if (4 * n > 3 * slots_.size()) rehash(slots_.empty() ? 16 : slots_.size() * 2);
  }
  void rehash(std::size_t cap) {
    std::vector<slot> old;
    reserve_large(old, cap);
    old.resize(cap);
    old.swap(slots_);
    size_ = 0;
    for (const slot& s : old)
      if (s.value != not_found) place(s);
  }

  std::vector<slot> slots_;
  std::size_t size_ = 0;
};

}  // namespace cellforge::detail
