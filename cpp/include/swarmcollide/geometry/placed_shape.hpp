#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"

namespace swarmcollide {

/// `body` moved by `pose` (valid: see validate_pose), as a body of its own: a polyhedron's points
/// at `rotation * x + translation` (rounded; the rounding radius kept), a curved shape with its
/// support function moved alike (the moved shape's support point along `d` is the moved support
/// point along `rotation^T d`, so it stays exact to its error bound; its points and box are the
/// moved shape's). A compound body's parts with poses (CompoundBody) are these.
ConvexPolyhedron placed(const ConvexPolyhedron& body, const Pose& pose);

}  // namespace swarmcollide
