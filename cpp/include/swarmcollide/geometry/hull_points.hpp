#pragma once

#include <vector>

#include "swarmcollide/geometry/hull.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// The given points of a body that its exact solvers read: every vertex of its hull, and every
/// other point that is not proven to lie in the hull of those. A support maximum over all the
/// points is attained among them, so supports, separations and the lower bounds built on them
/// are the same as over all the points; the paper's model (2) stays over all of them.
struct HullPoints {
  /// True when the solvers read every given point (the other fields are then empty): bodies of at
  /// most `kHillClimbingThreshold` points, and bodies none of whose points is proven redundant.
  bool every_point = true;
  /// Indices of the points read among the given ones, ascending.
  std::vector<int> indices;
  /// Their rows of `ConvexPolyhedron::centred_vertices()`, in that order.
  VertexMatrix centred;
  /// Their hull, with indices into `indices`.
  Hull hull;
};

/// The hull points of a point set from its hull: `centred` are the points less the centre of
/// their box (as `ConvexPolyhedron::centred_vertices()`), `hull` their hull (`compute_hull`).
/// A point is left out only when it repeats an earlier point exactly or is proven to lie in the
/// hull of the points kept (see hull_points.cpp); the result does not change when the points are
/// scaled by a power of two or translated exactly.
HullPoints find_hull_points(const VertexMatrix& centred, const Hull& hull);

}  // namespace swarmcollide
