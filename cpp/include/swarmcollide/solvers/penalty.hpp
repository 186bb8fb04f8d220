#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/solvers/distance_result.hpp"
#include "swarmcollide/solvers/penalty_options.hpp"

namespace swarmcollide {

/// Solves model (2) by the exterior quadratic penalty method (the schedule is in
/// `PenaltyOptions`). The raw penalty minimiser violates the constraints slightly, as in the
/// paper's Table 1 (weights a little below 0 or summing to a little more than 1); the result
/// reports it moved onto the simplexes with `to_simplex`, so `distance` is achieved by real
/// points of the bodies and stays an upper bound, and `lower_bound` is the separation along the
/// witness points. `iterations` counts L-BFGS iterations over the subproblems that ended normally
/// (LBFGSpp reports none for one whose line search stopped at rounding), `evaluations`
/// penalty-function evaluations, `history` the best distance after each subproblem; `status` is
/// `converged` when the tolerance test was met. Deterministic.
DistanceResult solve_penalty(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                             const PenaltyOptions& options = {});

}  // namespace swarmcollide
