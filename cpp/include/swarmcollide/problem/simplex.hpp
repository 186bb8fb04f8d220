#pragma once

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Euclidean projection of `weights` onto the probability simplex {w >= 0, sum w = 1}.
VectorX project_onto_simplex(const WeightsRef& weights);

/// Weights on the probability simplex close to `weights`: nonnegative weights are rescaled to sum
/// to one (so a weight that is exactly 0 or 1 stays so), anything else is projected.
VectorX to_simplex(const WeightsRef& weights);

}  // namespace swarmcollide
