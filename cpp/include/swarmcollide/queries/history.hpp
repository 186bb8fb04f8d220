#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// The best upper bound after initialisation and after each iteration of a search: a sequence of
/// values used as a `std::vector<Scalar>` is, which holds its first `kInline` values in place.
/// An exact search settled by its start records one value, and a query asks for its answer in
/// well under a microsecond: a heap block for that one value was a tenth of the query.
class History {
 public:
  using value_type = Scalar;
  using size_type = std::size_t;
  using iterator = Scalar*;
  using const_iterator = const Scalar*;
  /// Values held without a heap block.
  static constexpr size_type kInline = 2;

  History() = default;
  History(const History&) = default;
  History& operator=(const History&) = default;
  // A moved-from history is empty (its values may have gone with the heap block).
  History(History&& other) noexcept
      : inline_(other.inline_), heap_(std::move(other.heap_)), size_(other.size_) {
    other.size_ = 0;
  }
  History& operator=(History&& other) noexcept {
    inline_ = other.inline_;
    heap_ = std::move(other.heap_);
    size_ = other.size_;
    other.size_ = 0;
    return *this;
  }

  size_type size() const { return size_; }
  bool empty() const { return size_ == 0; }
  Scalar* data() { return size_ <= kInline ? inline_.data() : heap_.data(); }
  const Scalar* data() const { return size_ <= kInline ? inline_.data() : heap_.data(); }
  Scalar* begin() { return data(); }
  Scalar* end() { return data() + size_; }
  const Scalar* begin() const { return data(); }
  const Scalar* end() const { return data() + size_; }
  Scalar& operator[](size_type i) { return data()[i]; }
  Scalar operator[](size_type i) const { return data()[i]; }
  Scalar back() const { return data()[size_ - 1]; }

  /// Room for `count` values: a search that knows its iteration budget asks for it once.
  void reserve(size_type count) {
    if (count > kInline) heap_.reserve(count);
  }
  void push_back(Scalar value) {
    if (size_ < kInline) {
      inline_[size_++] = value;
      return;
    }
    // Past the inline values, all of them live on the heap.
    if (size_ == kInline) heap_.assign(inline_.begin(), inline_.end());
    heap_.push_back(value);
    ++size_;
  }

  friend bool operator==(const History& x, const History& y) {
    return x.size_ == y.size_ && std::equal(x.begin(), x.end(), y.begin());
  }
  friend bool operator!=(const History& x, const History& y) { return !(x == y); }

 private:
  std::array<Scalar, kInline> inline_{};
  std::vector<Scalar> heap_;
  size_type size_ = 0;
};

}  // namespace swarmcollide
