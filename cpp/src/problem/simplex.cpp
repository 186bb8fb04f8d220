#include "swarmcollide/problem/simplex.hpp"

#include <algorithm>
#include <functional>

namespace swarmcollide {

void project_onto_simplex_in_place(Eigen::Ref<VectorX> weights, VectorX& scratch) {
  // Sort-based projection (Held, Wolfe and Crowder; Duchi et al. 2008): find the shift theta with
  // sum max(w - theta, 0) = 1. Solvers mostly project short vectors, where insertion sort is
  // fastest.
  const Eigen::Index n = weights.size();
  if (scratch.size() < n) scratch.resize(n);
  Scalar* sorted = scratch.data();
  constexpr Eigen::Index kInsertionSortLimit = 32;
  if (n <= kInsertionSortLimit) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const Scalar value = weights(i);
      Eigen::Index j = i;
      for (; j > 0 && sorted[j - 1] < value; --j) sorted[j] = sorted[j - 1];
      sorted[j] = value;
    }
  } else {
    std::copy(weights.data(), weights.data() + n, sorted);
    std::sort(sorted, sorted + n, std::greater<Scalar>());
  }
  // The support is a prefix of the sorted weights: the largest k with
  // sorted[k] > (sum of the first k + 1 - 1) / (k + 1).
  Scalar cumulative = 0;
  Scalar support_sum = 0;
  Eigen::Index support = 1;
  for (Eigen::Index k = 0; k < n; ++k) {
    cumulative += sorted[k];
    if (sorted[k] * static_cast<Scalar>(k + 1) > cumulative - 1) {
      support = k + 1;
      support_sum = cumulative;
    }
  }
  const Scalar theta = (support_sum - 1) / static_cast<Scalar>(support);
  for (Eigen::Index i = 0; i < n; ++i) weights(i) = std::max(weights(i) - theta, Scalar(0));
}

VectorX project_onto_simplex(const WeightsRef& weights) {
  VectorX projected = weights;
  VectorX scratch;
  project_onto_simplex_in_place(projected, scratch);
  return projected;
}

void to_simplex_in_place(Eigen::Ref<VectorX> weights, VectorX& scratch) {
  const Scalar total = weights.sum();
  if (weights.minCoeff() >= 0 && total > 0) {
    weights /= total;
  } else {
    project_onto_simplex_in_place(weights, scratch);
  }
}

VectorX to_simplex(const WeightsRef& weights) {
  VectorX result = weights;
  VectorX scratch;
  to_simplex_in_place(result, scratch);
  return result;
}

}  // namespace swarmcollide
