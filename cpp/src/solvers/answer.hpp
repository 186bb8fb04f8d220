// What a solver returns to the query layer; private to the library's sources.
#pragma once

#include <limits>
#include <optional>

#include "swarmcollide/problem/convex_weights.hpp"
#include "swarmcollide/queries/history.hpp"
#include "swarmcollide/queries/options.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// What a query asks of a solver.
enum class Goal {
  /// The distance, to within the tolerance.
  distance,
  /// Only whether the bodies are within the tolerance of each other: a solver may stop as soon
  /// as its bounds prove either answer.
  verdict,
  /// The signed distance (minus the penetration depth for overlapping bodies), to within the
  /// tolerance.
  signed_distance,
};

/// The rounded bodies' bounds `lower` and `upper` (queries/rounded.hpp's rounded_lower and
/// rounded_upper) of the bounds `core_lower` and `core_upper` on the cores. A closed form rounds
/// its bounds for its goal test and keeps them here, and round_answer takes them rather than
/// rounding the same bounds again (some 100 instructions of a ball's query). They are kept with
/// the core bounds they round, so an answer whose bounds are others (by default, NaN matches
/// none) is rounded anew.
struct RoundedBounds {
  Scalar core_lower = std::numeric_limits<Scalar>::quiet_NaN();
  Scalar core_upper = std::numeric_limits<Scalar>::quiet_NaN();
  Scalar lower = 0;
  Scalar upper = 0;
};

/// A solver's findings, in frame units (see FramedPair). Both bounds are always valid (up to
/// `kFrameRounding`): for a signed distance too, `upper` is proven (by a distance, or by an
/// enumeration of the candidate directions), never merely the best separation found. The solver
/// reports bounds and proofs only; `finish_result` (verdict.hpp) alone turns them into verdicts,
/// certificates and a status.
struct Answer {
  /// The lower bound of an answer that measured no separation.
  static constexpr Scalar kUnmeasured = -std::numeric_limits<Scalar>::infinity();
  /// The distance (signed distance) achieved by the witness points: an upper bound.
  Scalar upper = std::numeric_limits<Scalar>::infinity();
  /// A lower bound: the separation along `direction` (kUnmeasured until one is measured).
  Scalar lower = kUnmeasured;
  /// Witness points in the frame; `weights_a` and `weights_b` reproduce them from the points.
  Vector3 point_a = Vector3::Zero();
  Vector3 point_b = Vector3::Zero();
  ConvexWeights weights_a;
  ConvexWeights weights_b;
  /// Unit direction from A to B certifying `lower` (zero when none was found).
  Vector3 direction = Vector3::Zero();
  int iterations = 0;
  long evaluations = 0;
  /// Best upper bound after initialisation and after each iteration.
  History history;
  /// A proof that the bodies share a point: a simplex of their difference that encloses the
  /// origin by a margin above rounding, or exactly equal points.
  bool intersection_proven = false;
  /// False where the witnesses lie farther than the tolerance from `upper * direction` (an
  /// overlap the expanding polytope left so: PenetrationBounds::witnesses_along_normal): the
  /// bounds stay proven, the answer is not certified.
  bool witnesses_along_direction = true;
  /// Set when a method other than the requested one produced the answer.
  std::optional<Method> answered_by;
  /// `lower` and `upper` rounded already, where a closed form rounded them (see RoundedBounds).
  RoundedBounds rounded;
};

}  // namespace swarmcollide::detail
