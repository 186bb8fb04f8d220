#pragma once

#include <optional>

#include "swarmcollide/problem/convex_weights.hpp"
#include "swarmcollide/queries/history.hpp"
#include "swarmcollide/queries/options.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Why a query stopped.
enum class SolverStatus {
  /// The precision test was met: the bounds are within the tolerance of each other, or the
  /// bodies are proven to be within the tolerance of each other.
  converged,
  /// An iteration budget ran out first; the bounds are still valid, only further apart.
  max_iterations,
};

/// What every query returns, whatever the method, in the units of the input.
///
/// `lower_bound <= true value <= distance` always holds, up to rounding (about 1e-14 of the
/// pair's size): `distance` is achieved by the witness points, convex combinations of the bodies'
/// points with `weights_a` and `weights_b`, and `lower_bound` is the separation along
/// `direction`. For `distance` queries the true value is the distance and `lower_bound >= 0`;
/// for `signed_distance` it is the signed distance (minus the penetration depth when the bodies
/// overlap) and neither bound is clamped. For rounded bodies (ConvexPolyhedron::radius) the
/// values and bounds are the rounded bodies', the weights those of the cores' witnesses, and each
/// witness is its core's moved out by the radius along the normal (rounded.hpp).
struct DistanceResult {
  /// Upper bound on the distance (signed distance), achieved by the witness points.
  Scalar distance = 0;
  /// Lower bound on the distance (signed distance), certified by `direction`.
  Scalar lower_bound = 0;
  /// Witness point on A: the combination of A's points with `weights_a` (plus A's radius times
  /// the unit normal towards B, for a rounded body).
  Vector3 point_a = Vector3::Zero();
  /// Witness point on B: the combination of B's points with `weights_b` (less B's radius times
  /// the unit normal, for a rounded body).
  Vector3 point_b = Vector3::Zero();
  /// lambda of model (2): nonnegative, summing to one.
  ConvexWeights weights_a;
  /// delta of model (2): nonnegative, summing to one.
  ConvexWeights weights_b;
  /// Unit direction from A to B whose separation gives `lower_bound` (zero when none was found).
  /// For signed distances it is the contact normal, and `point_b - point_a = distance * direction`
  /// to within the bounds' gap, or the tolerance where a normal a gap's worth of angle off a long
  /// edge's facet tilts the witnesses apart.
  Vector3 direction = Vector3::Zero();
  /// Iterations run (of the method's main loop).
  int iterations = 0;
  /// Evaluations of the method's objective (the fitness (5)/(6), or support queries).
  long evaluations = 0;
  /// Best upper bound after initialisation and after each iteration (iterative methods only).
  History history;
  /// True when the bodies are within `tolerance` of each other (the query's tolerance times the
  /// pair's size): proven when `certified`; otherwise true unless a separation proves them apart
  /// (an unproven verdict errs on the side of contact).
  bool colliding = false;
  /// True when the answer is proven: the bounds (with their rounding) prove the verdict, and for
  /// distances and signed distances they also enclose the value to within the tolerance (a
  /// distance proven within the tolerance of zero by contact counts as enclosed). A verdict is
  /// proven by a separating direction (`lower_bound > tolerance`), by witness points within the
  /// tolerance, or by a simplex of the bodies' difference that encloses the origin.
  bool certified = false;
  /// The method that produced the answer.
  Method method = Method::dual;
  /// The method that was asked for, when another one answered: `collide` hands an unproven
  /// verdict to "exact", and "fcl" and "libccd" hand a case their library cannot answer safely
  /// (touching and overlapping pairs for FCL's distance, say) to "exact".
  std::optional<Method> escalated_from;
  SolverStatus status = SolverStatus::max_iterations;
};

}  // namespace swarmcollide
