// The one place where bounds become verdicts; private to the library's sources.
#pragma once

#include <algorithm>

#include "../geometry/framed_body.hpp"
#include "../solvers/answer.hpp"
#include "rounded.hpp"
#include "swarmcollide/queries/distance_result.hpp"

namespace swarmcollide::detail {

/// Whether a result carries the witnesses' weights over the given points: a batch reports no
/// weights, and spreading them over the given points is a good part of what finishing costs.
enum class Weights { given, none };

/// Every function here takes bounds on the cores of `pair` (what the solvers find) and reads
/// them as the rounded bodies' (rounded.hpp): the same for two polyhedra.
///
/// The result of `answer` to a query of `goal` asked of `requested`, in world units. Rounding
/// is accounted for: a bound proves a verdict only when it does so by more than
/// `kFrameRounding`. So `colliding` is proven by an intersection proof or by witnesses within
/// the tolerance, never by comparing a rounded distance with zero; and apart by a separation
/// above the tolerance. For distances and signed distances, `certified` also requires the bounds
/// to enclose the value to the tolerance (`goal_reached`).
/// With `Weights::none` the result's weights are left empty.
DistanceResult finish_result(const FramedPair& pair, Answer&& answer, Method requested, Goal goal,
                             Weights weights = Weights::given);

/// True when the bounds prove a verdict at the pair's tolerance (what `finish_result` calls
/// certified for a verdict): a separation above it, witnesses within it, or an intersection
/// proof, each beyond rounding.
bool verdict_proven(const FramedPair& pair, Scalar lower, Scalar upper, bool intersection_proven);
bool verdict_proven(const FramedPair& pair, const Answer& answer);
/// True when a separation `lower` alone proves the pair apart (verdict_proven's first case).
bool separation_proves_apart(const FramedPair& pair, Scalar lower);

/// True when the bounds enclose the value to within the pair's tolerance.
bool value_proven(const FramedPair& pair, Scalar lower, Scalar upper);
bool value_proven(const FramedPair& pair, const Answer& answer);

/// True when a pair proven at least `lower` apart (world units) while its size was `size`, whose
/// points have since moved by at most `moved` in all (both bodies together), is still proven
/// farther apart than `threshold` plus the tolerance: its distance is now at least
/// `lower - moved`, and its size (which sets the tolerance) at most `size + moved`. A scene
/// settles pairs that stay well apart so, from their cached bounds and the bodies' motion alone.
bool apart_after_motion(Scalar lower, Scalar size, Scalar moved, Scalar threshold,
                        Scalar relative_tolerance);

namespace verdict_detail {

// The tests below read bounds on the rounded bodies (rounded.hpp): the public functions, which
// the solvers call with bounds on the cores, shift theirs first; finish_result its answer.
// Inline: the solvers' stop tests ask them several times per query.

inline bool apart_proven(const FramedPair& pair, Scalar lower) {
  return lower - kFrameRounding > pair.tolerance;
}

inline bool close_proven(const FramedPair& pair, Scalar upper, bool intersection_proven) {
  // A pair of size zero is one point twice (every point of both bodies is the frame's centre,
  // exactly): the bodies share it, though no tolerance (zero times the size) can say so.
  return intersection_proven || upper + kFrameRounding <= pair.tolerance || pair.frame.size == 0;
}

inline bool proven_verdict(const FramedPair& pair, Scalar lower, Scalar upper,
                           bool intersection_proven) {
  return apart_proven(pair, lower) || close_proven(pair, upper, intersection_proven);
}

inline bool proven_value(const FramedPair& pair, Scalar lower, Scalar upper) {
  return upper - lower <= pair.tolerance + 2 * kFrameRounding;
}

inline bool reached(const FramedPair& pair, Goal goal, Scalar lower, Scalar upper,
                    bool intersection_proven) {
  switch (goal) {
    case Goal::verdict:
      return proven_verdict(pair, lower, upper, intersection_proven);
    case Goal::distance:
      // Contact makes the distance zero, but the answer is its upper bound, the witnesses'
      // distance: only witnesses within the tolerance settle it (an intersection proof does not
      // bring them together: FCL's weights on a tetrahedron of other points than its own left
      // them 0.02 apart, certified, on census case 49:8148).
      return proven_value(pair, std::max(lower, 0.0), upper) ||
             close_proven(pair, upper, false);
    case Goal::signed_distance:
      break;
  }
  return proven_value(pair, lower, upper);
}

}  // namespace verdict_detail

/// True when a solver working towards `goal` may stop: the verdict is proven (goal `verdict`), or
/// the value is (distances also when the witnesses are within the tolerance of each other).
inline bool goal_reached(const FramedPair& pair, Goal goal, Scalar lower, Scalar upper,
                         bool intersection_proven) {
  return verdict_detail::reached(pair, goal, rounded_lower(pair, lower),
                                 rounded_upper(pair, upper), intersection_proven);
}

/// True when no search can prove the verdict of a pair with bounds `lower` and `upper` (on the
/// cores, as goal_reached takes them), however long it runs. Read as the rounded bodies' (L and
/// U), they hold the distance d, as every later pair of bounds L' <= d <= U' will. Apart needs
/// L' - kFrameRounding > tolerance (rounded), which L' <= d <= U < (tolerance + kFrameRounding)
/// (1 - 4u) rules out; contact needs U' + kFrameRounding <= tolerance, which U' >= d >= L with
/// L + kFrameRounding > tolerance (1 + 4u) rules out, or an intersection proof, which L > 0
/// rules out. The factors cover the comparisons' own roundings (u = 2^-53).
inline bool verdict_out_of_reach(const FramedPair& pair, Scalar lower, Scalar upper) {
  const Scalar at_least = rounded_lower(pair, lower);
  const Scalar at_most = rounded_upper(pair, upper);
  return at_least > 0 && at_least + kFrameRounding > pair.tolerance * (1 + 4 * kRoundoff) &&
         at_most < (pair.tolerance + kFrameRounding) * (1 - 4 * kRoundoff);
}

/// goal_reached for bounds rounded already (rounded_bounds).
inline bool goal_reached(const FramedPair& pair, Goal goal, const RoundedBounds& bounds,
                         bool intersection_proven) {
  return verdict_detail::reached(pair, goal, bounds.lower, bounds.upper, intersection_proven);
}

}  // namespace swarmcollide::detail
