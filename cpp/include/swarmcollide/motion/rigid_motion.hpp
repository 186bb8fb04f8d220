#pragma once

#include <string>
#include <vector>

#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// How a body moves between its start and end poses (see RigidMotion).
enum class MotionKind {
  /// The origin moves on the straight segment while the body turns about it: the default.
  linear,
  /// A screw motion: G(t) = G0 exp(t xi), xi the twist of G0^-1 G1, a constant rotation about a
  /// fixed axis with a constant translation along it.
  screw,
};

/// Every motion kind's name ("linear", "screw"), in the enum's order.
const std::vector<std::string>& motion_kind_names();
/// The kind called `name`; throws std::invalid_argument listing the valid names.
MotionKind motion_kind_from_name(const std::string& name);

/// A body's motion from a start pose (time 0) to an end pose (time 1).
///
/// `MotionKind::linear` (the default): the translation moves linearly, `T(t) = T0 + t (T1 - T0)`, and the rotation turns at a constant angular velocity
/// about a fixed axis, `R(t) = R0 exp(t [w])` with `w` the rotation vector of `R0^T R1` (angle
/// in [0, pi], the shorter way round). `w` is in the body's start frame (right of R0); in the
/// world the axis is `R0 w`, through the body's origin, whose path is the straight segment. So
/// a body's origin moves on a line while the body turns about it (not a screw motion).
///
/// `MotionKind::screw`: the pose, as a 4x4 transform, is G(t) = G0 exp(t xi), where the twist
/// xi = (w, v) is the logarithm of G0^-1 G1 (w as above, v its translation part, both in the
/// body's start frame): R(t) is the same as above and T(t) = T0 + R0 V(t w) t v, with V the
/// exponential's left Jacobian. A point x of the body moves at R(t) (v + w x x): the body turns
/// about a fixed axis (parallel to R0 w) while sliding along it, the motion of a screw.
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
  /// The same, of the given kind.
  RigidMotion(const Pose& start, const Pose& end, MotionKind kind, const char* name = "motion");

  /// The same motion with both ends' translations moved by `shift` (not validated: the caller
  /// checks that they stay finite). Its rotation is this one's, bit for bit, not computed again.
  RigidMotion shifted(const Vector3& shift) const;
  const Pose& start() const { return start_; }
  const Pose& end() const { return end_; }
  MotionKind kind() const { return kind_; }
  /// For a screw motion, v: the translation part of the twist (in the body's start frame, per
  /// unit time), so that a point x of the body moves at R(t) (v + w x x); zero for a linear one.
  const Vector3& twist_translation() const { return twist_translation_; }
  /// The rotation vector `w` (radians, in the body's start frame): R(t) = R0 exp(t [w]).
  const Vector3& rotation_vector() const { return rotation_vector_; }
  /// |w|, in [0, pi]: the angle turned from time 0 to 1.
  Scalar angle() const { return angle_; }
  /// The pose at time t in [0, 1], computed in double precision: RigidMotion's bounds
  /// (`pose_error`) say how far it may be from the exact one.
  Pose at(Scalar t) const;
  /// The turn from the start rotation at time t, exp(t [w]) (so `at(t).rotation` is R0 times
  /// it), computed in double precision: each of its entries is within about 40 roundoffs of the
  /// exact exponential's (see rigid_motion.cpp).
  Matrix3 turn_at(Scalar t) const;
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
  MotionKind kind_ = MotionKind::linear;
  Vector3 rotation_vector_;
  Scalar angle_;
  // The unit axis w / |w| (zero when the motion does not turn).
  Vector3 axis_;
  Vector3 twist_translation_ = Vector3::Zero();
  Scalar start_norm_;

  // v = V(w)^-1 R0^T (T1 - T0), the twist's translation part, for a screw motion.
  Vector3 screw_translation() const;
};

}  // namespace swarmcollide
