#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"

namespace swarmcollide::testing {

/// Tetrahedron A of the paper's Section IV.
inline ConvexPolyhedron paper_a() {
  VertexMatrix v(4, 3);
  v << 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0;
  return ConvexPolyhedron(v);
}

/// Tetrahedron B of Section IV-A: touches A at (1, 0, 0); the distance is 0.
inline ConvexPolyhedron paper_b_colliding() {
  VertexMatrix v(4, 3);
  v << 1, 0, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0;
  return ConvexPolyhedron(v);
}

/// Tetrahedron B of Section IV-B: the distance to A is 1, from (1, 0, 0) to (1, -1, 0).
inline ConvexPolyhedron paper_b_separate() {
  VertexMatrix v(4, 3);
  v << 1, -1, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0;
  return ConvexPolyhedron(v);
}

}  // namespace swarmcollide::testing
