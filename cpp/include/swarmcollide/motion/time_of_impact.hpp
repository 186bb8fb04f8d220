#pragma once

#include <vector>

#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/motion/rigid_motion.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/options.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Default width of a time-of-impact bracket, in units of the motion's duration.
inline constexpr Scalar kDefaultTimeTolerance = 1e-6;
/// Default cap on the distance queries one time of impact may run.
inline constexpr int kDefaultMotionIterations = 100000;

/// The queries' defaults with the exact method, which motions use: conservative advancement
/// needs a proven lower bound at each sampled time, not a certified value far from contact, and
/// where rounding leaves Wolfe's bounds a little further apart than the tolerance "dual" spends
/// its swarm rounds (thousands of times a query's cost) on closing a gap that no step needs;
/// near contact, where the bisection needs it, "dual" is asked too.
inline QueryOptions exact_queries() {
  QueryOptions options;
  options.method = Method::exact;
  return options;
}

/// How `time_of_impact` works: the distance queries' method and tolerance, the bracket's width
/// and the iteration cap.
struct TimeOfImpactOptions {
  /// The queries at each sampled time: `query.method` must answer distances and signed
  /// distances ("exact", the default, "dual", "fcl"). With "exact" or "fcl", a sampled time
  /// whose query leaves the value unproven (Wolfe's algorithm can stall on smooth surfaces, or
  /// by rounding near contact) and proves neither contact nor the bodies farther apart than the
  /// contact threshold is asked again of "dual", whose swarm proves those.
  /// `query.tolerance` (relative, > 0) is the contact
  /// threshold: the bodies touch when they are within `tolerance x size` of each other, where
  /// `size` is the sum of the two bodies' bounding-ball diameters (BodyBounds::radius), constant
  /// over the motion, and between 2/3 and 2 times the pair's size (the queries' measure) at any
  /// pose where they touch.
  QueryOptions query = exact_queries();
  /// Largest width of the bracket [t_lower, t_upper] of a first contact, in (0, 1].
  Scalar time_tolerance = kDefaultTimeTolerance;
  /// Distance queries at most; past it the answer is returned uncertified.
  int max_iterations = kDefaultMotionIterations;

  /// Throws std::invalid_argument naming the first invalid value.
  void validate() const;
};

/// Why `time_of_impact` stopped.
enum class MotionStatus {
  /// Proven: free over the whole motion, or a first contact bracketed within the time tolerance.
  converged,
  /// The iteration cap ran out first (grazing motions at a tolerance too small for them).
  max_iterations,
  /// Two sampled times came closer than double precision can split while neither a contact nor
  /// a free interval between them was proven: the queries left those times unproven, or the
  /// contact threshold (tolerance x size) is below the rounding of the poses, which grows with
  /// the motion's extent and its distance from the world's origin (past some 1e5 times the
  /// bodies' size), and the bodies graze without overlapping deeper than it (a deeper overlap
  /// proves contact).
  unresolved,
};

/// The answer of `time_of_impact`.
///
/// When `certified`: `touches` is false only when the bodies are proven not to overlap at any
/// time in [0, 1]; when true, no overlap happens before `t_lower` (the bodies are proven apart
/// on [0, t_lower)) and at `t_upper` they are proven within `tolerance x size` of each other,
/// with `t_upper - t_lower <= time_tolerance`. So a first contact lies in the bracket, and
/// bodies that come within the tolerance of each other may be reported touching or not.
/// When not certified, `t_lower` is still proven (no overlap before it) and `touches` is true
/// (an unproven answer errs on the side of contact); `t_upper` is the earliest time found in
/// contact, or 1 when none was.
struct TimeOfImpactResult {
  bool touches = false;
  /// The bodies do not overlap before this time (1 for a free motion).
  Scalar t_lower = 1;
  /// The bodies are within the tolerance of each other at this time (1 for a free motion).
  Scalar t_upper = 1;
  /// The poses at `t_upper` (the end poses for a free motion), as `RigidMotion::at` computes them.
  Pose pose_a;
  Pose pose_b;
  /// The signed distance at `t_upper` (a DistanceResult of `signed_distance`), when touching:
  /// its upper bound, witness points on A and B and unit contact normal from A to B (zero
  /// vectors and NaN for a free motion).
  Scalar distance = 0;
  Vector3 point_a = Vector3::Zero();
  Vector3 point_b = Vector3::Zero();
  Vector3 normal = Vector3::Zero();
  bool certified = false;
  /// Distance queries run (the signed distance at t_upper not counted).
  int iterations = 0;
  MotionStatus status = MotionStatus::max_iterations;
};

/// The first time of contact of A moving by `motion_a` and B moving by `motion_b` over the time
/// [0, 1], by conservative advancement on the queries' certified lower bounds (motion.md):
/// from a time proven at least L apart, no point of either body can close the gap faster than
/// the motions' speed bound v (translation plus angular speed times the body's reach across
/// its axis of rotation, or that speed along the separating direction), so the next L / v of
/// time is free.
/// Where steps fall below the time tolerance, the time ahead is bisected, each half proven free
/// from both ends or found in contact. Throws std::invalid_argument for invalid options, a
/// method that cannot answer a body, or bodies beyond the double range.
TimeOfImpactResult time_of_impact(const ConvexPolyhedron& a, const RigidMotion& motion_a,
                                  const ConvexPolyhedron& b, const RigidMotion& motion_b,
                                  const TimeOfImpactOptions& options = {});
/// The same between compound bodies: the contact of any part of A with any part of B. The
/// queries' separating directions do not bound a union, so steps use the full speed bound.
TimeOfImpactResult time_of_impact(const CompoundBody& a, const RigidMotion& motion_a,
                                  const CompoundBody& b, const RigidMotion& motion_b,
                                  const TimeOfImpactOptions& options = {});

/// `time_of_impact(as[i], motions_a[i], bs[i], motions_b[i])` for every row i, on `threads`
/// threads (0: one per hardware thread); the answers do not depend on the number of threads. A
/// single body or motion serves every row; empty lists (the others one for all) make no rows and
/// no answers. Throws std::invalid_argument for mismatched lengths.
std::vector<TimeOfImpactResult> time_of_impact_many(const BatchBodies<ConvexPolyhedron>& as,
                                                    const std::vector<RigidMotion>& motions_a,
                                                    const BatchBodies<ConvexPolyhedron>& bs,
                                                    const std::vector<RigidMotion>& motions_b,
                                                    const TimeOfImpactOptions& options = {},
                                                    int threads = 0);
std::vector<TimeOfImpactResult> time_of_impact_many(const BatchBodies<CompoundBody>& as,
                                                    const std::vector<RigidMotion>& motions_a,
                                                    const BatchBodies<CompoundBody>& bs,
                                                    const std::vector<RigidMotion>& motions_b,
                                                    const TimeOfImpactOptions& options = {},
                                                    int threads = 0);

}  // namespace swarmcollide
