#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Objective (5): `|| sum_j delta_j y_j - sum_i lambda_i x_i ||`.
Scalar objective(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const WeightsRef& lambda,
                 const WeightsRef& delta);

/// Constraint violation (6): `(sum lambda - 1)^2 + (sum delta - 1)^2`.
Scalar constraint_violation(const WeightsRef& lambda, const WeightsRef& delta);

/// True when every weight lies in [0, 1] and the violation (6) is at most `tolerance`.
bool is_feasible(const WeightsRef& lambda, const WeightsRef& delta, Scalar tolerance);

}  // namespace swarmcollide
