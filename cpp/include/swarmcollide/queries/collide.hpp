#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/queries/distance.hpp"
#include "swarmcollide/solvers/distance_result.hpp"

namespace swarmcollide {

/// The distance tolerance at which `options.method` calls two bodies colliding.
Scalar collision_tolerance(const DistanceOptions& options);

/// The result that decides whether A and B collide.
///
/// A result whose bounds prove its verdict (`certified`) decides. Otherwise, with `escalate`, the
/// exact "fcl" method decides at the same tolerance, and the result names the method it was
/// escalated from; without, the method's own unproven verdict stands. For "libccd", which has no
/// distance, the result is its signed distance (negative when the bodies overlap).
DistanceResult collision(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                         const DistanceOptions& options = {}, bool escalate = true);

/// True when A and B intersect: `collision(a, b, options, escalate).colliding`, except that
/// "libccd" answers with its GJK intersection test.
bool collide(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
             const DistanceOptions& options = {}, bool escalate = true);

}  // namespace swarmcollide
