#include "swarmcollide/problem/simplex.hpp"

#include <algorithm>
#include <functional>

namespace swarmcollide {

VectorX project_onto_simplex(const WeightsRef& weights) {
  // Sort-based projection (Held, Wolfe and Crowder; Duchi et al. 2008): find the shift theta with
  // sum max(w - theta, 0) = 1.
  VectorX sorted = weights;
  std::sort(sorted.data(), sorted.data() + sorted.size(), std::greater<Scalar>());
  Scalar cumulative = 0;
  Scalar theta = 0;
  for (Eigen::Index k = 0; k < sorted.size(); ++k) {
    cumulative += sorted(k);
    const Scalar candidate = (cumulative - 1) / static_cast<Scalar>(k + 1);
    if (sorted(k) - candidate > 0) theta = candidate;
  }
  return (weights.array() - theta).cwiseMax(0).matrix();
}

VectorX to_simplex(const WeightsRef& weights) {
  const Scalar total = weights.sum();
  if ((weights.array() >= 0).all() && total > 0) return weights / total;
  return project_onto_simplex(weights);
}

}  // namespace swarmcollide
