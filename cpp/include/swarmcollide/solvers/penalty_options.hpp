#pragma once

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Parameters of the exterior quadratic penalty method (the paper's "penalty function
/// algorithm" baseline, Table 1).
///
/// Schedule: subproblem `k = 0, ..., outer_iterations - 1` minimises
/// `|sum delta y - sum lambda x|^2 + mu_k * P(lambda, delta)` with
/// `mu_k = initial_weight * growth_factor^k`, where `P` is the violation (6) plus
/// `sum min(w, 0)^2 + sum max(w - 1, 0)^2` over all weights (the bounds 0 <= w <= 1). Each
/// subproblem is solved by L-BFGS for at most `inner_iterations` iterations, warm-started at the
/// previous solution. The outer loop stops early once the answer is within the query's tolerance.
struct PenaltyOptions {
  /// mu_0, the first penalty weight.
  Scalar initial_weight = 1;
  /// Factor by which the penalty weight grows between subproblems (> 1).
  Scalar growth_factor = 10;
  /// Number of subproblems.
  int outer_iterations = 8;
  /// L-BFGS iteration cap of each subproblem.
  int inner_iterations = 200;
};

}  // namespace swarmcollide
