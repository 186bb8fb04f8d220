// A random search of directions for a framed pair's largest separation near a given direction:
// every separation is a lower bound on the signed distance, so a proven upper bound may not lie
// below the best one found (a depth claimed too large would put it there). And the penetration
// solver's answer those searches check.
#pragma once

#include "geometry/framed_body.hpp"
#include "shapes.hpp"
#include "solvers/minkowski.hpp"
#include "solvers/penetration.hpp"
#include "swarmcollide/solvers/exact_options.hpp"

namespace swarmcollide::testing {

/// The best separation found from `start`: 40 directions at each spread from `widest`, halved
/// down to `narrowest`, around the best direction so far.
inline Scalar best_separation_near(const detail::FramedPair& pair, const Vector3& start,
                                   Scalar widest, Scalar narrowest, Random& rng) {
  Vector3 best = start;
  Scalar best_separation = detail::exact_separation(pair.a, pair.b, best);
  for (Scalar spread = widest; spread > narrowest; spread /= 2) {
    for (int k = 0; k < 40; ++k) {
      const Vector3 n = (best + spread * rng.unit()).normalized();
      const Scalar s = detail::exact_separation(pair.a, pair.b, n);
      if (s > best_separation) {
        best_separation = s;
        best = n;
      }
    }
  }
  return best_separation;
}

/// The penetration solver's bounds on a framed pair, from the direction between the bodies'
/// offsets, at the pair's tolerance and the exact method's iteration cap.
inline detail::PenetrationBounds solve_penetration(const detail::FramedPair& pair) {
  return detail::penetration(pair.a, pair.b, pair.b.offset() - pair.a.offset(), nullptr,
                             pair.tolerance, ExactOptions().max_iterations);
}

}  // namespace swarmcollide::testing
