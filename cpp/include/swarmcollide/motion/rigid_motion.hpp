#pragma once

#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// A body's motion from a start pose (time 0) to an end pose (time 1): the translation moves
/// linearly, `T(t) = T0 + t (T1 - T0)`, and the rotation turns at a constant angular velocity
/// about a fixed axis, `R(t) = R0 exp(t [w])` with `w` the rotation vector of `R0^T R1` (angle
/// in [0, pi], the shorter way round). `w` is in the body's start frame (right of R0); in the
/// world the axis is `R0 w`, through the body's origin, whose path is the straight segment. So
/// a body's origin moves on a line while the body turns about it (not a screw motion).
///
/// Built from two poses, checked once: both must be rigid (validate_pose) and finite. `w` is
/// computed in double precision, so R(1) is the given end rotation to within a few roundoffs
/// (for rotations that are orthogonal to 1e-16; to within their own deviation otherwise).
class RigidMotion {
 public:
  /// The motion that stays at the identity.
  RigidMotion() : RigidMotion(Pose{}, Pose{}) {}
  /// Throws std::invalid_argument naming `name` ("pose_a", ...) and which end when a pose has a
  /// NaN or infinite entry or is not a rigid motion.
  RigidMotion(const Pose& start, const Pose& end, const char* name = "motion");

  const Pose& start() const { return start_; }
  const Pose& end() const { return end_; }
  /// The rotation vector `w` (radians, in the body's start frame): R(t) = R0 exp(t [w]).
  const Vector3& rotation_vector() const { return rotation_vector_; }
  /// |w|, in [0, pi]: the angle turned from time 0 to 1.
  Scalar angle() const { return angle_; }
  /// The pose at time t in [0, 1], computed in double precision: RigidMotion's bounds
  /// (`pose_error`) say how far it may be from the exact one.
  Pose at(Scalar t) const;
  /// A bound on the distance between where `at(t)` puts a point `x` of the body and where the
  /// exact motion puts it at t, for any t in [0, 1], for `|x| <= reach`: the rounding of the
  /// rotation's and the translation's evaluation (see rigid_motion.cpp).
  Scalar pose_error(Scalar reach) const;
  /// A bound on the spectral norm of R0 (1 for an exact rotation; up to 1 + 1e-9 for a rotation
  /// at the edge of validate_pose's tolerance), rounded up.
  Scalar start_rotation_norm() const { return start_norm_; }

 private:
  Pose start_;
  Pose end_;
  Vector3 rotation_vector_;
  Scalar angle_;
  // The unit axis w / |w| (zero when the motion does not turn).
  Vector3 axis_;
  Scalar start_norm_;
};

}  // namespace swarmcollide
