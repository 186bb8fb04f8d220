// Verdicts that the bodies' bounding balls prove before any solver runs; private to the library's
// sources.
#pragma once

#include <optional>

#include "../geometry/framed_body.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/queries/distance_result.hpp"

namespace swarmcollide::detail {

/// The radius of a ball about the centre of `body`'s box (`bounds().centre`) holding every point
/// of it, rounded up: computed on first use and kept with the body's derived data. Tighter than
/// the box's half diagonal (`bounds().radius`) by up to sqrt(3) for round bodies.
Scalar ball_radius(const ConvexPolyhedron& body);

/// The collision result for `pair` when the balls about its bodies' box centres, of radii
/// `radius_a` and `radius_b` (each body's own units, as `ball_radius` gives them), prove it apart:
/// the lower bound is the balls' separation along the line of their centres (the direction), the
/// upper bound the distance between the bodies' first points (the witnesses, with one weight
/// each). Nothing when the balls prove no verdict. `method` is the method asked for.
std::optional<DistanceResult> collision_by_balls(const FramedPair& pair, Scalar radius_a,
                                                 Scalar radius_b, Method method);

}  // namespace swarmcollide::detail
