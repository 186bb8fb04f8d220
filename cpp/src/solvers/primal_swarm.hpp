// The paper's swarm on model (2) (methods "ipso" and "pso"); private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "answer.hpp"
#include "swarmcollide/queries/options.hpp"

namespace swarmcollide::detail {

/// How each particle's inertia weight and acceleration coefficients are chosen.
enum class InertiaStrategy {
  /// The paper's improved PSO ("ipso"): per-particle values from the rank of its personal best,
  /// (8)-(9).
  rank_adaptive,
  /// The standard PSO ("pso"): one inertia weight decreasing linearly over the iterations, (7).
  linear_decreasing,
};

/// Solves model (2) with a particle swarm (Steps 1-3) in the pair's frame: rank-adaptive for
/// "ipso", linearly decreasing inertia for "pso". The precision of Step 3 is the pair's
/// tolerance (zero runs the whole budget); the verdict goal stops as soon as a bound proves it.
/// Deterministic for a given seed. Throws std::invalid_argument for signed distances and for a
/// swarm whose arrays would exceed 2 GiB.
Answer solve_primal_swarm(const FramedPair& pair, const QueryOptions& options, Goal goal);

}  // namespace swarmcollide::detail
