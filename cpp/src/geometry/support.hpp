// Support points of a point set, the scan and the hill climb that ConvexPolyhedron and
// FramedBody share; private to the library's sources.
#pragma once

#include <cstddef>

#include "swarmcollide/geometry/hull.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// `d . x_i`, from the row-major storage: the inner product of every support loop.
inline Scalar point_height(const VertexMatrix& points, int i, const Vector3& d) {
  const Scalar* x = points.data() + 3 * static_cast<std::ptrdiff_t>(i);
  return x[0] * d.x() + x[1] * d.y() + x[2] * d.z();
}

/// The first index in [0, count) maximising `height(i)`.
template <class Height>
int first_highest(int count, const Height& height) {
  int best = 0;
  Scalar highest = height(0);
  for (int i = 1; i < count; ++i) {
    const Scalar h = height(i);
    if (h > highest) {
      highest = h;
      best = i;
    }
  }
  return best;
}

/// Index of a point maximising `d . x` (the first one on ties), by scanning every point: each
/// height is one rounded inner product, so the answer is the maximum to that rounding.
inline int scan_support(const VertexMatrix& points, const Vector3& d) {
  return first_highest(static_cast<int>(points.rows()),
                       [&](int i) { return point_height(points, i, d); });
}

/// Index of a point maximising `d . x`, by steepest ascent over `hull`'s edge graph, as FCL and
/// coal do, from `start`: a search passes the previous answer, which is best for a nearby
/// direction. Without one (a point with no neighbours, or out of range, is none), or after a
/// jump, the climb starts from the highest of the hull's `climb_starts` (coal keeps such a table
/// too), so it crosses at most the part of the hull within about 25 degrees of `d`.
/// On a convex polytope a vertex with no higher neighbour maximises a linear function;
/// with rounded heights the climb can stop short of the maximum, so its answers serve search and
/// upper bounds (any point of the body does), never a proven lower bound on their own. Every
/// step strictly raises the height, so the climb ends.
inline int climb_support(const VertexMatrix& points, const Hull& hull, const Vector3& d,
                         int start) {
  const int* offsets = hull.neighbour_offsets.data();
  const int* neighbours = hull.neighbours.data();
  int current = start;
  Scalar highest;
  if (start >= 0 && start < static_cast<int>(points.rows()) && offsets[start + 1] > offsets[start]) {
    highest = point_height(points, current, d);
  } else {
    current = hull.climb_starts.front();
    highest = point_height(points, current, d);
    for (int s : hull.climb_starts) {
      const Scalar h = point_height(points, s, d);
      if (h > highest) {
        highest = h;
        current = s;
      }
    }
  }
  for (;;) {
    int next = current;
    for (int e = offsets[current]; e < offsets[current + 1]; ++e) {
      const Scalar h = point_height(points, neighbours[e], d);
      if (h > highest) {
        highest = h;
        next = neighbours[e];
      }
    }
    if (next == current) return current;
    current = next;
  }
}

}  // namespace swarmcollide::detail
