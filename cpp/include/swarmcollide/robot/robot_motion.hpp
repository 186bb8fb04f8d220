#pragma once

#include <vector>

#include "swarmcollide/motion/time_of_impact.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/robot/kinematics.hpp"
#include "swarmcollide/robot/pair_filter.hpp"
#include "swarmcollide/robot/robot_model.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Per motion q(t) = q0 + t (q1 - q0), t in [0, 1]: whether any checked pair touches during it,
/// and if so the first contact, bracketed. The fields mean what TimeOfImpactResult's mean, over
/// every pair of the robot at once.
///
/// When `certified`: `touches` is false only when no pair is in contact at any time of the
/// motion; when true, no pair is in contact before `t_lower`, and at `t_upper` the pair `pair`
/// is proven within `tolerance x size` of contact (size: the sum of its geometries' bounding-ball
/// diameters), with `t_upper - t_lower <= time_tolerance`. When not certified (the iteration cap
/// ran out, or a query stayed unproven), `t_lower` is still proven, `touches` is true, and
/// `t_upper` is the earliest time found in contact (1 when none was: `pair` is then the pair left
/// unproven).
struct RobotMotionCheck {
  Eigen::Array<bool, Eigen::Dynamic, 1> touches;
  /// No pair is in contact before this time (1 for a free motion).
  VectorX t_lower;
  /// The pair `pair` is within the tolerance of contact at this time (1 for a free motion).
  VectorX t_upper;
  /// The configuration at `t_upper`, `q0 + t_upper (q1 - q0)` as the motion computes it (`q1`
  /// for a free motion), `(m, dof)`.
  Configurations configuration;
  /// The index (into the pairs) of the pair in contact at `t_upper`, -1 for a free motion.
  Eigen::VectorXi pair;
  /// That pair's signed distance at `configuration` (upper bound), its witness points and unit
  /// normal from its first geometry to its second; NaN and zeros for a free motion.
  VectorX distance;
  VertexMatrix point_a;
  VertexMatrix point_b;
  VertexMatrix normal;
  Eigen::Array<bool, Eigen::Dynamic, 1> certified;
  /// Distance queries run (the bounding-ball and box screens, and the signed distance at
  /// `t_upper`, not counted).
  Eigen::VectorXi iterations;
  std::vector<MotionStatus> status;
};

/// The first contact of every motion from `q0` row i to `q1` row i (admitted, see
/// admit_configurations; a single row of either serves every motion) along the straight segment
/// in joint space, by conservative advancement per pair on certified lower bounds (as
/// time_of_impact, motions.md): each link's points move by at most sum_j |dq_j| r_j over the joints
/// j of its chain (Schwarzer, Saha and Latombe), r_j bounding the distance from joint j's axis to
/// the link's points (1 for a slide), so a pair proven L apart at t stays apart for L / v of the
/// time, v its links' bound less the joints both chains share. Pairs are taken in increasing
/// order of their first possible contact from their bounding boxes and balls at t = 0, each
/// advanced only up to the earliest contact found so far. Each motion is answered whole by one of
/// `settings.threads` threads, its queries seeded by options.query.seed, so answers depend
/// neither on the threads nor on the other rows (a row answers as the same motion alone).
/// `options.max_iterations` caps the queries per motion.
/// Throws std::invalid_argument for invalid options, pairs or threads, rows of q0 and q1 that
/// are neither equal in number nor one, a wrong number of values per row, or a curved geometry
/// that `options.query.method` cannot answer.
RobotMotionCheck robot_check_motion(const RobotModel& model, const std::vector<GeometryPair>& pairs,
                                    const Configurations& q0, const Configurations& q1,
                                    const TimeOfImpactOptions& options = {},
                                    const BatchSettings& settings = {});

}  // namespace swarmcollide
