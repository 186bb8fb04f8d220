// DistanceFinish's search from a corral a Wolfe walk left (overlap_first on curved pairs), in a
// file of its own, so that whole()'s search from a single point, which every polytope query runs,
// compiles as it does alone: one search taking either start, or whole()'s oracle shared as a
// function object or a template, cost polytope queries 1-4% more instructions. Its oracle and
// measure are therefore whole()'s, written again (curved pairs: no climbing).
#include "distance_finish.hpp"
#include "minkowski.hpp"
#include "whole_search.hpp"

namespace swarmcollide::detail {

bool DistanceFinish::walk_from_corral(const Vector3& start, const MinNormPoint& corral,
                                      int& hint_a, int& hint_b, BestBounds& bounds, Goal goal,
                                      bool enclosure) {
  // A curved body's supports are its support function's. A large polytope beside it climbs from
  // the hints without whole()'s reset after a turn, which only chooses where a climb starts: it
  // ends at the support from any start, within the margins whole()'s bounds already take.
  const auto oracle = [&](const Vector3& d) {
    ++evaluations_;
    return minkowski_support(pair_.a, pair_.b, d, hint_a, hint_b);
  };
  const auto measured = [](const MinNormPoint& current, const OraclePoint& q,
                           Scalar inverse_norm) {
    return Separation{current.x.dot(q.p) * inverse_norm, current.x * inverse_norm};
  };
  return whole_search(pair_, start, &corral, hint_a, hint_b, bounds, goal, enclosure,
                      max_iterations_, evaluations_, oracle, measured, PlacedByBodies{pair_});
}

}  // namespace swarmcollide::detail
