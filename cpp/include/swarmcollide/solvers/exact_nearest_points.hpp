#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/solvers/distance_result.hpp"
#include "swarmcollide/solvers/exact_options.hpp"

namespace swarmcollide {

/// The library's own exact distance, independent of FCL and libccd: Wolfe's nearest-point
/// algorithm (1976) on the Minkowski difference B - A, driven by the bodies' support functions.
/// Finite and exact up to rounding for every body, flat, collinear and single-point ones
/// included, and for touching and overlapping pairs (distance 0 with a common point). The
/// weights are those of the final corral (at most four point pairs). The "fcl", "fcl-indep" and
/// "libccd" methods fall back to it whenever their library gives no, or no optimal, answer.
/// `method` of the result is "wolfe".
DistanceResult exact_nearest_points(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                    const ExactOptions& options = {});

}  // namespace swarmcollide
