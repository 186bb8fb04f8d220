#pragma once

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// How particles are kept on (or steered to) the feasible set of model (2).
enum class ConstraintHandling {
  /// The paper's rules: fitness (5) for feasible particles, violation (6) for infeasible ones,
  /// compared by Conditions 1-3. A particle is feasible when its weights lie in [0, 1] and (6) is
  /// at most the feasibility tolerance. r1 and r2 are one pair per particle, as (10) reads, so that
  /// a move keeps the sums of (2).
  feasibility,
  /// Each particle's lambda and delta are projected onto the probability simplex after every move,
  /// so every particle is feasible and optima on the simplexes' faces are reached exactly. r1 and
  /// r2 are drawn per weight, as (3) writes the update.
  projection,
};

/// Parameters of the primal swarms ("ipso", "pso"); the defaults are the paper's (Section IV).
/// The precision of Step 3 is the query's `tolerance` and the random stream its `seed`.
struct SwarmOptions {
  ConstraintHandling constraint_handling = ConstraintHandling::projection;
  /// N_p, the number of particles.
  int swarm_size = 40;
  /// G_m, the iteration budget.
  int max_iterations = 200;
  /// Smallest and largest inertia weight: w_min, w_max of (8), w_end, w_start of (7).
  Scalar w_min = 0.4;
  Scalar w_max = 0.9;
  /// Acceleration coefficients of the linear-decreasing PSO ("pso"); "ipso" derives its own
  /// from (9).
  Scalar c1 = 2.0;
  Scalar c2 = 2.0;
  /// Largest velocity component: with projection each component is clamped to it, with the
  /// paper's rules a velocity over it is scaled as a whole (which keeps the sums). The default was
  /// chosen by a sweep over 4-64 vertices for projection (docs/method.md); the paper's rules do
  /// better with 1.
  Scalar velocity_limit = 0.02;
  /// Largest violation (6) that still counts as feasible.
  Scalar feasibility_tolerance = 1e-10;
};

}  // namespace swarmcollide
