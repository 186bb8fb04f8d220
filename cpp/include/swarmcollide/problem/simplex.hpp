#pragma once

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Euclidean projection of `weights` onto the probability simplex {w >= 0, sum w = 1}.
VectorX project_onto_simplex(const WeightsRef& weights);

/// The same projection in place; `scratch` is reused between calls, so a solver that keeps it
/// allocates nothing once it has grown to the largest size.
void project_onto_simplex_in_place(Eigen::Ref<VectorX> weights, VectorX& scratch);

/// Weights on the probability simplex close to `weights`: nonnegative weights are rescaled to sum
/// to one (so a weight that is exactly 0 or 1 stays so), anything else is projected.
VectorX to_simplex(const WeightsRef& weights);

/// `to_simplex` in place, with `scratch` reused as by `project_onto_simplex_in_place`.
void to_simplex_in_place(Eigen::Ref<VectorX> weights, VectorX& scratch);

}  // namespace swarmcollide
