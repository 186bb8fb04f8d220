#pragma once

#include <string>
#include <vector>

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Why a solver stopped.
enum class SolverStatus {
  /// The precision test was met: the bounds are within the tolerance, or the bodies touch.
  converged,
  /// The iteration budget ran out first; the bounds are still valid, only further apart.
  max_iterations,
  /// An exact method answered.
  exact,
};

/// What every distance query returns, whatever the method.
///
/// `lower_bound <= true distance <= distance` always holds: `distance` is achieved by the witness
/// points, which are convex combinations of the bodies' points with the returned weights, and
/// `lower_bound` is the separation along `direction` (zero when no direction separates them).
struct DistanceResult {
  /// Upper bound on the distance: `|| point_b - point_a ||`.
  Scalar distance = 0;
  /// Lower bound on the distance, certified by `direction`.
  Scalar lower_bound = 0;
  /// Witness point on A: `sum_i weights_a_i x_i`.
  Vector3 point_a = Vector3::Zero();
  /// Witness point on B: `sum_j weights_b_j y_j`.
  Vector3 point_b = Vector3::Zero();
  /// lambda of model (2): nonnegative, summing to one.
  VectorX weights_a;
  /// delta of model (2): nonnegative, summing to one.
  VectorX weights_b;
  /// Unit direction whose separation gives `lower_bound` (zero if none separates).
  Vector3 direction = Vector3::Zero();
  /// Iterations run (0 for exact methods).
  int iterations = 0;
  /// Evaluations of the fitness (5)/(6).
  long evaluations = 0;
  /// Best distance after initialisation and after each iteration.
  std::vector<Scalar> history;
  /// True when `distance <= tolerance`.
  bool colliding = false;
  /// True when the bounds prove the verdict: `lower_bound > tolerance` (separate) or
  /// `distance <= tolerance` (colliding).
  bool certified = false;
  /// The method that produced the answer.
  std::string method;
  /// The method whose uncertified answer was handed to `method` by `collision()`; empty otherwise.
  std::string escalated_from;
  SolverStatus status = SolverStatus::max_iterations;
};

}  // namespace swarmcollide
