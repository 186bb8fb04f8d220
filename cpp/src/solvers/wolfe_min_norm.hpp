// Wolfe's minimum-norm-point algorithm; private to the library's sources.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "nearest_simplex_point.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// A point of a polytope given by a support oracle, with the indices that produced it (the
/// vertex of A and the vertex of B for a Minkowski-difference point, -1 when unused).
struct OraclePoint {
  Vector3 p = Vector3::Zero();
  int ia = -1;
  int ib = -1;
};

/// The minimum-norm point of a polytope as a convex combination of at most four oracle points
/// (its corral), held in place: a solve allocates nothing.
struct MinNormPoint {
  static constexpr int kCapacity = 4;
  std::array<OraclePoint, kCapacity> corral;
  /// Positive and summing to one over the first `size` entries.
  std::array<Scalar, kCapacity> weights{};
  int size = 0;
  Vector3 x = Vector3::Zero();
  int iterations = 0;
};

/// Wolfe's nearest-point algorithm (Wolfe 1976) on the polytope spanned by `oracle`, where
/// `oracle(d)` returns an OraclePoint minimising `d . q`, from `start`: up to four oracle points
/// (first brought to the nearest point of their hull). Each new oracle point joins the corral,
/// and the nearest point of their hull, in closed form (`nearest_simplex_point`, as GJK projects
/// where Wolfe's minor cycles would step towards it), gives the next corral: the smallest face
/// holding it, with positive weights. `scale` bounds the norms of the points (within a small
/// factor; a scale up to 2^90 promises coordinates below 2^100) and sets the
/// stopping test: the gap `|x| - (x/|x|) . oracle(x)` at most 1e-14 `scale`, or no further
/// decrease in `|x|` (rounding), or `max_iterations`, or `stop(current, norm, q)` true for the
/// current corral, whose point has norm `norm` (nonzero), first with `q` null, then with its
/// new oracle point `q = oracle(current.x)` (whose `(x/|x|) . q` bounds the norm of every point
/// below): a caller with a coarser goal stops as soon as it is met, before the oracle call when
/// the corral alone meets it.
template <class Oracle, class Stop>
MinNormPoint wolfe_min_norm_from(const Oracle& oracle, const MinNormPoint& start, Scalar scale,
                                 int max_iterations, const Stop& stop) {
  // Two corrals, the current one and the next: the new oracle point is put after the current
  // one's points, and their nearest point written into the other, so that a step that makes no
  // progress leaves the current one as it was, and no step copies a corral.
  std::array<MinNormPoint, 2> corrals{start, start};
  int current = 0;
  const Scalar gap_tolerance = 1e-14 * scale;
  // Points of norm about `scale` (a few frame units for every caller) have coordinates far below
  // 2^100: the projection need not look for overflow (nearest_simplex_point).
  const bool bounded = scale <= 0x1p90;
  // A start of several points is first brought to the nearest point of its hull (where it may
  // already be, up to rounding).
  bool settle = start.size > 1;
  // |x|^2 of the current corral's point, which the projection gave with it.
  Scalar xx = start.x.squaredNorm();
  int iteration = 1;
  for (; iteration <= max_iterations; ++iteration) {
    MinNormPoint& now = corrals[current];
    MinNormPoint& next = corrals[1 - current];
    int m = now.size;
    if (!settle) {
      const Vector3& x = now.x;
      if (xx == 0) break;
      const Scalar norm = std::sqrt(xx);
      if (stop(now, norm, static_cast<const OraclePoint*>(nullptr))) break;
      // A corral of four holds its nearest point inside (the origin, up to rounding): no point can
      // join it, so no oracle point is asked for.
      if (m == MinNormPoint::kCapacity) break;
      const OraclePoint q = oracle(x);
      if (stop(now, norm, &q) || xx - x.dot(q.p) <= gap_tolerance * norm) break;
      bool known = false;
      for (int k = 0; k < m; ++k) {
        known = known || (now.corral[k].ia == q.ia && now.corral[k].ib == q.ib);
      }
      if (known) break;  // rounding: the optimum is reached
      now.corral[m] = q;
      ++m;
    }
    Scalar after;
    nearest_simplex_point(now.corral, m, next.corral, next.weights, next.size, bounded, next.x,
                          after);
    if (!(settle ? after <= xx : after < xx)) break;  // no progress left above rounding
    xx = after;
    settle = false;
    current = 1 - current;
  }
  MinNormPoint& best = corrals[current];
  best.iterations = std::min(iteration, max_iterations);
  return best;
}

/// The corral of the one oracle point `q`, whose nearest point it is: where Wolfe's algorithm
/// starts.
inline MinNormPoint single_point(const OraclePoint& q) {
  MinNormPoint point;
  point.corral[0] = q;
  point.weights[0] = 1;
  point.size = 1;
  point.x = q.p;
  return point;
}

/// The same, run to its own stopping tests.
template <class Oracle>
MinNormPoint wolfe_min_norm_from(const Oracle& oracle, const MinNormPoint& start, Scalar scale,
                                 int max_iterations) {
  return wolfe_min_norm_from(oracle, start, scale, max_iterations,
                             [](const MinNormPoint&, Scalar, const OraclePoint*) { return false; });
}

/// Wolfe's algorithm from the single oracle point along `start`, with `stop` as above.
template <class Oracle, class Stop>
MinNormPoint wolfe_min_norm(const Oracle& oracle, const Vector3& start, Scalar scale,
                            int max_iterations, const Stop& stop) {
  return wolfe_min_norm_from(oracle, single_point(oracle(start)), scale, max_iterations, stop);
}

/// Wolfe's algorithm from the single oracle point along `start`.
template <class Oracle>
MinNormPoint wolfe_min_norm(const Oracle& oracle, const Vector3& start, Scalar scale,
                            int max_iterations) {
  return wolfe_min_norm(oracle, start, scale, max_iterations,
                        [](const MinNormPoint&, Scalar, const OraclePoint*) { return false; });
}

}  // namespace swarmcollide::detail
