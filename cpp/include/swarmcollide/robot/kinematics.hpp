#pragma once

#include <cstddef>
#include <vector>

#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/robot/robot_model.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Configurations one per row, `(m, dof)`, row-major so that NumPy arrays map onto them.
using Configurations = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// What to do with a joint value outside its limits.
enum class LimitMode {
  /// Throw std::invalid_argument naming the configuration and the joint.
  raise,
  /// Replace it with the nearest limit.
  clamp,
  /// Add the multiple of 2 pi that brings a revolute joint's angle within its limits (the same
  /// pose); throw when none does, or when the joint is prismatic.
  wrap,
};

/// The pose `outer * inner`: `inner` given in the frame that `outer` places.
Pose compose(const Pose& outer, const Pose& inner);

/// The configurations as the kinematics reads them: checked once (one value per degree of
/// freedom, every value finite) and brought within the joints' limits as `mode` says. Throws
/// std::invalid_argument for a wrong number of columns (naming the model's dof) or a NaN or
/// infinite value, naming the row and the joint ("q[3], joint 'elbow': ...").
Configurations admit_configurations(const RobotModel& model, const Configurations& q,
                                    LimitMode mode);

/// admit_configuration's `row` for a configuration given alone (`(dof,)`, not a table's row): its
/// messages then name the value's own index, "q[2], joint 'elbow'".
inline constexpr std::size_t kSingleConfiguration = static_cast<std::size_t>(-1);

/// One configuration, `count` values at `q`, admitted as admit_configurations admits row `row`
/// (the row its messages name; kSingleConfiguration: a configuration given alone), into
/// `admitted_q` (dof values; it may be `q`).
void admit_configuration(const RobotModel& model, const Scalar* q, Eigen::Index count,
                         LimitMode mode, std::size_t row, Scalar* admitted_q);

/// The world pose of every link at the configuration `q` (`dof` values, already admitted), into
/// `links` (one pose per link, in the model's order). The root is at the identity.
void link_poses(const RobotModel& model, const Scalar* q, std::vector<Pose>& links);

/// The world poses of the child links of `joints` alone at the configuration `q`, into `links`
/// (one pose per link, the roots at the identity; the others are left as they are): `joints`
/// is a part of the model's joint order that holds, with each joint, the joints above it (a
/// robot motion's pair needs only the chains of its two links).
void link_poses(const RobotModel& model, const Scalar* q, const std::vector<int>& joints,
                std::vector<Pose>& links);

/// Geometry `g`'s world pose with the links at `links` (link_poses): its link's pose times its
/// origin (an obstacle's origin).
Pose geometry_pose(const RobotModel& model, const std::vector<Pose>& links, int g);

/// Forward kinematics over admitted configurations: link l's homogeneous transform at row i is
/// written row-major at `transforms + (i * links + l) * 16`.
void forward_kinematics(const RobotModel& model, const Configurations& q, Scalar* transforms);

/// The world transform of every geometry (its link's pose times its origin; an obstacle's
/// origin) at admitted configurations: geometry g's at row i is written row-major at
/// `transforms + (i * geometries + g) * 16`.
void geometry_poses(const RobotModel& model, const Configurations& q, Scalar* transforms);

}  // namespace swarmcollide
