// The paper's penalty-function baseline (method "penalty"); private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "answer.hpp"
#include "swarmcollide/queries/options.hpp"

namespace swarmcollide::detail {

/// Solves model (2) by the exterior quadratic penalty method (the schedule is in
/// `PenaltyOptions`) in the pair's frame. The raw penalty minimiser violates the constraints
/// slightly, as in the paper's Table 1 (weights a little below 0 or summing to a little more than
/// 1); the answer reports it moved onto the simplexes with `to_simplex`, so `upper` is achieved
/// by real points of the bodies, and `lower` is the best separation along the witnesses seen.
/// `iterations` counts L-BFGS iterations over the subproblems that ended normally (LBFGSpp
/// reports none for one whose line search stopped at rounding), `evaluations` penalty-function
/// evaluations, `history` the best distance after each subproblem. Deterministic.
Answer solve_penalty(const FramedPair& pair, const QueryOptions& options, Goal goal);

}  // namespace swarmcollide::detail
