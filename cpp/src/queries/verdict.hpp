// The one place where bounds become verdicts; private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "../solvers/answer.hpp"
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

/// True when a solver working towards `goal` may stop: the verdict is proven (goal `verdict`), or
/// the value is (distances also when contact is proven: the distance is then within the
/// tolerance of zero).
bool goal_reached(const FramedPair& pair, Goal goal, Scalar lower, Scalar upper,
                  bool intersection_proven);

}  // namespace swarmcollide::detail
