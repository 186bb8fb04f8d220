#pragma once

#include <array>
#include <optional>
#include <utility>

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Convex-combination weights over a body's points (the lambda or delta of model (2)): stored
/// sparsely when at most four are nonzero, as the exact methods give them, and densely
/// otherwise, as the swarms give them. The dense vector is built only when asked for, so an
/// answer costs nothing in the size of large bodies.
class ConvexWeights {
 public:
  /// Largest number of nonzero weights held without a dense vector.
  static constexpr int kSparseCapacity = 4;

  ConvexWeights() = default;
  /// Weights given densely, one per point.
  explicit ConvexWeights(VectorX dense) : count_(static_cast<int>(dense.size())) {
    if (count_ > 0) dense_.emplace(std::move(dense));
  }
  /// Weights `weight[k]` at points `index[k]`, k < nonzeros <= kSparseCapacity, of a body of
  /// `count` points; an index may repeat (its weights add up).
  ConvexWeights(int count, const std::array<int, kSparseCapacity>& index,
                const std::array<Scalar, kSparseCapacity>& weight, int nonzeros)
      : count_(count), nonzeros_(nonzeros), index_(index), weight_(weight) {}

  /// Number of points of the body.
  int count() const { return count_; }
  /// One weight per point.
  VectorX dense() const {
    if (dense_) return *dense_;
    VectorX weights = VectorX::Zero(count_);
    for (int k = 0; k < nonzeros_; ++k) weights(index_[k]) += weight_[k];
    return weights;
  }
  /// Calls `visit(index, weight)` for every stored weight (for dense weights, every point's).
  template <typename Visit>
  void for_each(const Visit& visit) const {
    if (dense_) {
      for (int i = 0; i < count_; ++i) visit(i, (*dense_)(i));
    } else {
      for (int k = 0; k < nonzeros_; ++k) visit(index_[k], weight_[k]);
    }
  }

 private:
  int count_ = 0;
  int nonzeros_ = 0;
  std::array<int, kSparseCapacity> index_{};
  std::array<Scalar, kSparseCapacity> weight_{};
  // Dense weights only when given so: a vector's destructor calls free() even when it holds
  // nothing, and every query makes and drops a few sparse weights (an answer's, a result's).
  std::optional<VectorX> dense_;
};

}  // namespace swarmcollide
