// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Dynamic, typed, named properties attached to mesh elements (any copyable type).
/// Arrays grow with the mesh; a `property<Handle, T>` is a cheap typed view into one.

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <typeinfo>
#include <utility>
#include <vector>

#include "cellforge/core/detail/large_array.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"

namespace cellforge {

namespace detail {

/// Type-erased storage of one property: the operations the mesh needs to keep
/// every array the same length as its element array.
class property_array_base {
 public:
  explicit property_array_base(std::string name) : name_(std::move(name)) {}
  virtual ~property_array_base() = default;
  property_array_base(const property_array_base&) = default;
  property_array_base& operator=(const property_array_base&) = delete;

  const std::string& name() const noexcept { return name_; }
  /// A pinned array (a surface_mesh's positions) cannot be removed while its mesh lives.
  bool pinned() const noexcept { return pinned_; }
  void pin() noexcept { pinned_ = true; }
  virtual const std::type_info& type() const noexcept = 0;
  virtual std::size_t size() const noexcept = 0;
  virtual void reserve(std::size_t n) = 0;
  virtual void resize(std::size_t n) = 0;
  virtual void push_back() = 0;
  /// Moves element src to dst (used by garbage collection, dst <= src).
  virtual void move_element(std::size_t dst, std::size_t src) = 0;
  /// Copies element src to dst (used by edits whose new elements inherit a value).
  virtual void copy_element(std::size_t dst, std::size_t src) = 0;
  /// Resets element i to the default value (used when an element is reused or removed).
  virtual void reset(std::size_t i) = 0;
  /// A heap copy; the caller owns it (see owned_array).
  virtual property_array_base* clone() const = 0;

 private:
  std::string name_;
  bool pinned_ = false;
};

template <class T>
class property_array final : public property_array_base {
 public:
  property_array(std::string name, T default_value)
      : property_array_base(std::move(name)), default_(std::move(default_value)) {}

  const std::type_info& type() const noexcept override { return typeid(T); }
  std::size_t size() const noexcept override { return data_.size(); }
  void reserve(std::size_t n) override { data_.reserve(n); }
  void resize(std::size_t n) override {
    detail::reserve_large(data_, n);
    data_.resize(n, default_);
  }
  void push_back() override { data_.push_back(default_); }
  void move_element(std::size_t dst, std::size_t src) override {
    if (dst != src) data_[dst] = std::move(data_[src]);
  }
  void copy_element(std::size_t dst, std::size_t src) override {
    if (dst != src) data_[dst] = data_[src];
  }
  void reset(std::size_t i) override { data_[i] = default_; }
  property_array_base* clone() const override { return new property_array(*this); }

  std::vector<T>& data() noexcept { return data_; }
  const std::vector<T>& data() const noexcept { return data_; }
  const T& default_value() const noexcept { return default_; }

 private:
  std::vector<T> data_;
  T default_;
};

/// Sole owner of one heap-allocated array. A unique_ptr would do, but <memory> costs more to
/// compile than this whole header (docs/benchmarks.md, compile time).
class owned_array {
 public:
  explicit owned_array(property_array_base* a) noexcept : a_(a) {}
  owned_array(owned_array&& o) noexcept : a_(std::exchange(o.a_, nullptr)) {}
  owned_array& operator=(owned_array&& o) noexcept {
    std::swap(a_, o.a_);
    return *this;
  }
  owned_array(const owned_array&) = delete;
  owned_array& operator=(const owned_array&) = delete;
  ~owned_array() { delete a_; }
  property_array_base* get() const noexcept { return a_; }
  property_array_base* operator->() const noexcept { return a_; }
  property_array_base& operator*() const noexcept { return *a_; }

 private:
  property_array_base* a_;
};

template <class = void>
class basic_property_registry;
using property_registry = basic_property_registry<>;

/// All properties of one element kind. Copying clones every array.
template <class>
class basic_property_registry {
 public:
  basic_property_registry() = default;
  basic_property_registry(const basic_property_registry& o) : size_(o.size_) {
    arrays_.reserve(o.arrays_.size());
    for (const auto& a : o.arrays_) {
      owned_array copy(a->clone());
      arrays_.push_back(std::move(copy));
    }
  }
  basic_property_registry& operator=(const basic_property_registry& o) {
    if (this != &o) {
      basic_property_registry copy(o);
      swap(copy);
    }
    return *this;
  }
  basic_property_registry(basic_property_registry&&) noexcept = default;
  basic_property_registry& operator=(basic_property_registry&&) noexcept = default;
  void swap(basic_property_registry& o) noexcept {
    arrays_.swap(o.arrays_);
    std::swap(size_, o.size_);
  }

  template <class T>
  property_array<T>* add(std::string_view name, T default_value) {
    if (find(name) != nullptr)
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("a property named '", std::string(name), "' already exists"));
    auto* raw = new property_array<T>(std::string(name), std::move(default_value));
    owned_array a(raw);
    raw->resize(size_);
    arrays_.push_back(std::move(a));
    return raw;
  }

  /// The array named `name` if it holds T; nullptr if there is none; throws on a type mismatch.
  template <class T>
  property_array<T>* get(std::string_view name) const {
    property_array_base* a = find(name);
    if (a == nullptr) return nullptr;
    if (a->type() != typeid(T))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("property '", std::string(name), "' exists with another type (",
                                         a->type().name(), "), not ", typeid(T).name()));
    return static_cast<property_array<T>*>(a);
  }

  property_array_base* find(std::string_view name) const noexcept {
    for (const auto& a : arrays_)
      if (a->name() == name) return a.get();
    return nullptr;
  }

  /// Removes array a; a pinned array is refused with an error (its owner's typed view would dangle).
  bool remove(const property_array_base* a) {
    auto it = std::find_if(arrays_.begin(), arrays_.end(), [&](const auto& p) { return p.get() == a; });
    if (it == arrays_.end()) return false;
    if ((*it)->pinned())
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("property '", (*it)->name(),
                                         "' holds the positions of a surface_mesh and cannot be removed"));
    arrays_.erase(it);
    return true;
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& a : arrays_) out.push_back(a->name());
    return out;
  }

  std::size_t size() const noexcept { return size_; }
  std::size_t num_properties() const noexcept { return arrays_.size(); }
  const property_array_base& array(std::size_t i) const noexcept { return *arrays_[i]; }

  void reserve(std::size_t n) {
    for (auto& a : arrays_) a->reserve(n);
  }
  void resize(std::size_t n) {
    for (auto& a : arrays_) a->resize(n);
    size_ = n;
  }
  void push_back() {
    for (auto& a : arrays_) a->push_back();
    ++size_;
  }
  void move_element(std::size_t dst, std::size_t src) {
    for (auto& a : arrays_) a->move_element(dst, src);
  }
  void copy_element(std::size_t dst, std::size_t src) {
    for (auto& a : arrays_) a->copy_element(dst, src);
  }
  void reset(std::size_t i) {
    for (auto& a : arrays_) a->reset(i);
  }
  void clear() noexcept {
    arrays_.clear();
    size_ = 0;
  }

 private:
  std::vector<owned_array> arrays_;
  std::size_t size_ = 0;
};

}  // namespace detail

/// A typed view of one property array, indexed by a handle. Invalid when
/// default-constructed or when a lookup found nothing. Stays valid while the
/// property exists; element insertions may reallocate, so re-read references.
template <class Handle, class T>
class property {
 public:
  using reference = typename std::vector<T>::reference;
  using const_reference = typename std::vector<T>::const_reference;

  property() = default;
  explicit property(detail::property_array<T>* a) noexcept : array_(a) {}

  bool is_valid() const noexcept { return array_ != nullptr; }
  explicit operator bool() const noexcept { return is_valid(); }
  const std::string& name() const noexcept { return array_->name(); }

  reference operator[](Handle h) noexcept { return array_->data()[h.idx()]; }
  const_reference operator[](Handle h) const noexcept { return array_->data()[h.idx()]; }
  /// The whole array, one entry per element including removed ones not yet collected.
  std::vector<T>& vector() noexcept { return array_->data(); }
  const std::vector<T>& vector() const noexcept { return array_->data(); }

  detail::property_array<T>* array() const noexcept { return array_; }

 private:
  detail::property_array<T>* array_ = nullptr;
};

}  // namespace cellforge
