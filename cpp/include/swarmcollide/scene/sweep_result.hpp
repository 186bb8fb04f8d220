#pragma once

#include <cstdint>
#include <vector>

#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/motion/rigid_motion.hpp"
#include "swarmcollide/motion/time_of_impact.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// How `Scene::sweep` moves its bodies and brackets their first contacts; the distance queries
/// are the scene's (its method, tolerance and seed).
struct SweepOptions {
  /// How each listed body moves from its pose to the given one (see RigidMotion).
  MotionKind motion = MotionKind::linear;
  /// Largest width of a first contact's bracket, > 0 (as TimeOfImpactOptions).
  Scalar time_tolerance = kDefaultTimeTolerance;
  /// Distance queries at most per pair; past it the pair is reported uncertified.
  int max_iterations = kDefaultMotionIterations;
};

/// The pairs that touch during a `Scene::sweep`, one row per pair, in increasing order of (first
/// id, second id), the first id the smaller: row k is `time_of_impact` of bodies `pairs(k, 0)`
/// (A) and `pairs(k, 1)` (B) over the sweep's motions (see TimeOfImpactResult).
struct SweepResult {
  /// Ids of A and B.
  Eigen::Matrix<std::int64_t, Eigen::Dynamic, 2, Eigen::RowMajor> pairs;
  /// The pair is proven apart before `t_lower` and within the tolerance at `t_upper`.
  VectorX t_lower;
  VectorX t_upper;
  /// The poses at `t_upper`.
  std::vector<Pose> pose_a;
  std::vector<Pose> pose_b;
  /// The signed distance at `t_upper` (its upper bound), the witness points on A and on B and
  /// the unit contact normal from A to B there.
  VectorX distance;
  VertexMatrix point_a;
  VertexMatrix point_b;
  VertexMatrix normal;
  /// True where the bracket is proven (see TimeOfImpactResult); uncertified rows err on the
  /// side of contact.
  Eigen::Array<bool, Eigen::Dynamic, 1> certified;
  /// Distance queries each pair ran.
  Eigen::Array<int, Eigen::Dynamic, 1> iterations;

  Eigen::Index size() const { return pairs.rows(); }
};

}  // namespace swarmcollide
