#include "verdict.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "rounded.hpp"
#include "row_answer.hpp"

namespace swarmcollide::detail {

using namespace verdict_detail;

bool verdict_proven(const FramedPair& pair, Scalar lower, Scalar upper, bool intersection_proven) {
  return proven_verdict(pair, rounded_lower(pair, lower), rounded_upper(pair, upper),
                        intersection_proven);
}

bool separation_proves_apart(const FramedPair& pair, Scalar lower) {
  return apart_proven(pair, rounded_lower(pair, lower));
}

bool verdict_proven(const FramedPair& pair, const Answer& answer) {
  return verdict_proven(pair, answer.lower, answer.upper, answer.intersection_proven);
}

bool value_proven(const FramedPair& pair, Scalar lower, Scalar upper) {
  return proven_value(pair, rounded_lower(pair, lower), rounded_upper(pair, upper));
}

bool value_proven(const FramedPair& pair, const Answer& answer) {
  return value_proven(pair, answer.lower, answer.upper);
}

bool apart_after_motion(Scalar lower, Scalar size, Scalar moved, Scalar threshold,
                        Scalar relative_tolerance) {
  const Scalar distance = lower - moved;
  const Scalar contact = threshold + relative_tolerance * (size + moved);
  // The rounding of the sums above, and of the world-unit bounds they came from.
  const Scalar margin = 1e-12 * (std::abs(lower) + moved + threshold + size);
  return distance - margin > contact;
}

namespace {

// finish_values, inlined into finish_result too: its call and the copy of its values out and into
// the result were 60 instructions of every query.
[[gnu::always_inline]] inline FinishedValues finished(const FramedPair& pair, Answer& answer,
                                                      Goal goal) {
  // From here on the answer is the rounded bodies' (the same for two polyhedra).
  if (rounded(pair)) round_answer(pair, goal, answer);
  // A distance is never negative, so zero bounds it below whatever the solver found; and in the
  // frame both bodies lie in the unit ball, so a translation by 2 separates them.
  answer.lower = std::max(answer.lower, goal == Goal::signed_distance ? -2.0 : 0.0);
  // Both bounds of a touching pair are roundings of zero, each computed its own way (a separation
  // along a direction, a distance between witnesses): the lower may come out a rounding above
  // the upper (2.2e-16 against 1.7e-16 on a pair touching at 8 vertices). Any number below a
  // lower bound is one too, so the lower bound is taken down to the upper: never above it.
  answer.lower = std::min(answer.lower, answer.upper);
  const bool apart = apart_proven(pair, answer.lower);
  const bool close = close_proven(pair, answer.upper, answer.intersection_proven);
  const bool exact = proven_value(pair, answer.lower, answer.upper);
  FinishedValues r;
  const Frame& frame = pair.frame;
  r.distance = frame.length_to_world(answer.upper);
  r.lower_bound = frame.length_to_world(answer.lower);
  if (!std::isfinite(r.distance) || !std::isfinite(r.lower_bound)) {
    throw std::invalid_argument(
        "the distance between the bodies exceeds the largest double (1.8e308) and cannot be "
        "represented; use a larger unit of length");
  }
  r.point_a = frame.point_to_world(answer.point_a);
  r.point_b = frame.point_to_world(answer.point_b);
  r.direction = answer.direction;
  r.iterations = answer.iterations;
  // Unproven, the verdict errs on the side of contact: bodies not shown apart may touch.
  r.colliding = !apart;
  // A distance or a signed distance is certified only when its bounds also enclose it to the
  // tolerance: a proven verdict alone leaves the value of a swarm stopped early unproven.
  r.certified = (apart || close) &&
                reached(pair, goal, answer.lower, answer.upper, answer.intersection_proven) &&
                answer.witnesses_along_direction;
  // For a signed distance, contact alone does not settle the depth.
  r.settled = exact || (close && goal != Goal::signed_distance);
  return r;
}

// `weights` over `body`'s points, as weights over its given points (none with Weights::none). A
// polyhedron whose points are all its given points (every small one) keeps them as they are,
// moved without given_weights' call and the copies of its argument and result (46 instructions of
// every 8-vertex query, callgrind_query.py); a curved body's, over this query's support points,
// are none (given_weights' answer, without its call). Inline: its call was 27 instructions a body.
[[gnu::always_inline]] inline ConvexWeights give_weights(const FramedBody& body,
                                                         ConvexWeights& weights, Weights kept) {
  if (kept == Weights::none || body.curved()) return ConvexWeights();
  if (body.given_size() == body.size()) return std::move(weights);
  return body.given_weights(std::move(weights));
}

}  // namespace

FinishedValues finish_values(const FramedPair& pair, Answer& answer, Goal goal) {
  return finished(pair, answer, goal);
}

DistanceResult finish_result(const FramedPair& pair, Answer&& answer, Method requested, Goal goal,
                             Weights weights) {
  const FinishedValues values = finished(pair, answer, goal);
  const Method method = answer.answered_by.value_or(requested);
  // Made in place from its members, in DistanceResult's order: a default result assigned field by
  // field stored most of them twice.
  DistanceResult r{values.distance,
                   values.lower_bound,
                   values.point_a,
                   values.point_b,
                   give_weights(pair.a, answer.weights_a, weights),
                   give_weights(pair.b, answer.weights_b, weights),
                   values.direction,
                   values.iterations,
                   answer.evaluations,
                   std::move(answer.history),
                   values.colliding,
                   values.certified,
                   method,
                   method != requested ? std::optional<Method>(requested) : std::nullopt,
                   values.settled ? SolverStatus::converged : SolverStatus::max_iterations};
  for (Scalar& h : r.history) h = pair.frame.length_to_world(h);
  return r;
}

}  // namespace swarmcollide::detail
