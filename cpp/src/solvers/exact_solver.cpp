#include "exact_solver.hpp"

#include "minkowski.hpp"
#include "sat_penetration.hpp"
#include "witness.hpp"

namespace swarmcollide::detail {

namespace {

// The exhaustive separating-axis enumeration costs edges_a x edges_b separations; beyond this
// many pairs (64-point bodies have about 35,000) it would take seconds.
constexpr long kMaxEdgePairs = 250'000;

}  // namespace

Answer exact_distance(const FramedPair& pair, int max_iterations, const Vector3& start) {
  int hint_a = -1;
  int hint_b = -1;
  long evaluations = 0;
  const auto oracle = [&](const Vector3& d) {
    ++evaluations;
    return minkowski_support(pair.a, pair.b, d, hint_a, hint_b);
  };
  const Vector3 from = start.norm() > 0 ? start : Vector3(pair.b.offset() - pair.a.offset());
  const MinNormPoint nearest = wolfe_min_norm(oracle, from, 2, max_iterations);
  Answer answer = answer_from_corral(pair, nearest);
  answer.iterations = nearest.iterations;
  answer.evaluations = evaluations;
  return answer;
}

Answer exact_penetration(const FramedPair& pair, int, const Vector3& hint,
                         Scalar distance_upper) {
  return sat_penetration(pair, hint, distance_upper, kMaxEdgePairs);
}

Answer exact_signed_distance(const FramedPair& pair, int max_iterations, const Vector3& hint) {
  Answer apart = exact_distance(pair, max_iterations, hint);
  // A positive separation proves the bodies apart, and their distance is the signed distance.
  if (apart.lower > kFrameRounding) return apart;
  const Vector3 start = hint.norm() > 0 ? hint : apart.direction;
  Answer overlap = exact_penetration(pair, max_iterations, start, apart.upper);
  overlap.iterations = apart.iterations;
  overlap.evaluations += apart.evaluations;
  overlap.intersection_proven = apart.intersection_proven;
  return overlap;
}

Answer solve_exact(const FramedPair& pair, const QueryOptions& options, Goal goal) {
  if (goal == Goal::signed_distance) {
    return exact_signed_distance(pair, options.exact.max_iterations, Vector3::Zero());
  }
  return exact_distance(pair, options.exact.max_iterations, Vector3::Zero());
}

}  // namespace swarmcollide::detail
