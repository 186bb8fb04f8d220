// What a batch row keeps of a convex pair's answer; private to the library's sources.
#pragma once

#include "dispatch.hpp"

namespace swarmcollide::detail {

/// The values of finish_result's result that a batch row keeps, in world units, computed as
/// finish_result computes them (it builds on them): a batch writes them into its row without
/// building a DistanceResult (weights, history, optional fields) for every row.
struct FinishedValues {
  Scalar distance = 0;
  Scalar lower_bound = 0;
  Vector3 point_a;
  Vector3 point_b;
  Vector3 direction;
  int iterations = 0;
  bool colliding = false;
  bool certified = false;
  /// The status is converged.
  bool settled = false;
};

/// finish_result's values of `answer` (whose bounds it reads as the rounded bodies', in place),
/// with its check: throws std::invalid_argument when the distance exceeds the double range.
FinishedValues finish_values(const FramedPair& pair, Answer& answer, Goal goal);

/// What a batch row keeps of answer_pair's answer (Weights::none): its values, and whether it
/// is escalated_from another method.
struct RowAnswer {
  FinishedValues values;
  bool escalated = false;
};

/// answer_pair for a batch row, with `solve` the solver of `options.method` (solver_for, looked
/// up once per batch) and no DistanceResult built; the caller has required the method's
/// capability and the pair's shapes (require_shapes).
RowAnswer answer_row(const QueryOptions& options, Solver solve, Goal goal, const FramedPair& pair,
                     bool escalate);

}  // namespace swarmcollide::detail
