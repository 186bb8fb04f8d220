#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Separation of A and B along a direction: `min_j n.y_j - max_i n.x_i` for the unit vector `n`
/// along `direction`. Every direction gives a lower bound on the distance (the width of the gap
/// between two parallel planes that separate the bodies); negative when the direction does not
/// separate them. Throws std::invalid_argument for a zero or non-finite direction.
Scalar separation(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const Vector3& direction);

}  // namespace swarmcollide
