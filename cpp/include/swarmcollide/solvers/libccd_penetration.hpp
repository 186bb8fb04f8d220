#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/solvers/distance_result.hpp"
#include "swarmcollide/solvers/exact_options.hpp"

namespace swarmcollide {

/// Intersection test by libccd's GJK (ccdGJKIntersect) on the bodies' support functions. libccd
/// cannot prove a "no" (it has no distance, and its MPR misses touching pairs such as the paper's),
/// so a "no" is checked by `exact_nearest_points` and the verdict is that of its certified
/// distance: true exactly when the distance is at most `options.tolerance`.
bool libccd_intersect(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                      const ExactOptions& options = {});

/// Signed distance with libccd's penetration depth (ccdGJKPenetration, i.e. GJK + EPA, or
/// ccdMPRPenetration, per `options.penetration`, both at `options.penetration_tolerance`) for
/// intersecting bodies. libccd has no distance function: for bodies apart, and for touching
/// ones, the answer is `exact_nearest_points`' (with `method` "libccd"). See `signed_distance`.
DistanceResult libccd_signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                      const ExactOptions& options = {});

}  // namespace swarmcollide
