#include "swarmcollide/motion/rigid_motion.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace swarmcollide {

namespace {

// The unit roundoff of double precision.
constexpr Scalar kUnit = 0x1p-53;

// Rotation entries' rounding, in roundoffs, of `at(t)` against the exact R0 exp(t [w]) (w the
// stored rotation vector, taken as exact), as a bound on the spectral norm of the difference:
// - the axis k = w / |w| is unit to 3 roundoffs; phi = t |w| is within 3 roundoffs of t |w|
//   relative (|phi| <= pi), so its sine and cosine (glibc: within 1 ulp) are within 4 pi + 2
//   roundoffs of the exact ones;
// - each entry of I + sin(phi) K + (1 - cos(phi)) K^2 (K = [k]x, |k_i k_j| <= 1, 1 - cos = 2
//   sin^2(phi / 2)) is then within about 40 roundoffs of the exact exponential's, so the matrix
//   is within 3 * 40 = 120 in spectral norm (at most 3 times its largest entry);
// - the product with R0 (|R0| <= 1 + 1e-9) adds at most 3.01 * 3 roundoffs per entry times 3.
// 256 covers the sum with room to spare.
constexpr Scalar kRotationRoundoffs = 256;

// A bound on the spectral norm of r: the square root of the largest absolute row sum of r^T r
// (which bounds its largest eigenvalue), rounded up.
Scalar spectral_norm_bound(const Matrix3& r) {
  const Matrix3 gram = r.transpose() * r;
  Scalar largest = 0;
  for (int i = 0; i < 3; ++i) largest = std::fmax(largest, gram.row(i).cwiseAbs().sum());
  return std::sqrt(largest) * (1 + 16 * kUnit);
}

// validate_pose naming the pose `name` `which` ("pose_a start"); the name is built only for the
// message: a batch checks a motion per row.
void validate_end(const Pose& pose, const char* name, const char* which) {
  try {
    validate_pose(pose, which);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(name) + " " + e.what());
  }
}

}  // namespace

const std::vector<std::string>& motion_kind_names() {
  static const std::vector<std::string> names{"linear", "screw"};
  return names;
}

MotionKind motion_kind_from_name(const std::string& name) {
  if (name == "linear") return MotionKind::linear;
  if (name == "screw") return MotionKind::screw;
  throw std::invalid_argument("motion must be 'linear' or 'screw', got '" + name + "'");
}

RigidMotion::RigidMotion(const Pose& start, const Pose& end, const char* name)
    : RigidMotion(start, end, MotionKind::linear, name) {}

RigidMotion::RigidMotion(const Pose& start, const Pose& end, MotionKind kind, const char* name)
    : start_(start), end_(end), kind_(kind) {
  validate_end(start, name, "start");
  validate_end(end, name, "end");
  // R0^T R1 as a unit quaternion (Eigen's branch on the largest diagonal term is accurate near
  // half turns), taken with w >= 0 so that its angle is the shorter way round, in [0, pi].
  Eigen::Quaternion<Scalar> turn(Matrix3(start.rotation.transpose() * end.rotation));
  turn.normalize();
  if (turn.w() < 0) turn.coeffs() = -turn.coeffs();
  const Scalar sine_half = turn.vec().norm();
  angle_ = 2 * std::atan2(sine_half, turn.w());
  axis_ = sine_half > 0 ? Vector3(turn.vec() / sine_half) : Vector3::Zero();
  rotation_vector_ = axis_ * angle_;
  start_norm_ = spectral_norm_bound(start.rotation);
  if (kind_ == MotionKind::screw) twist_translation_ = screw_translation();
}

Vector3 RigidMotion::screw_translation() const {
  // v = V(w)^-1 p for p = R0^T (T1 - T0), with V(w)^-1 = I - [w]/2 + g K^2 (K = [k]x, k the
  // unit axis) and g = 1 - (angle / 2) cot(angle / 2), which is in [0, 1] for angles in
  // [0, pi] and computed to within a few roundoffs absolute (the subtraction from 1 loses
  // digits of g near 0, not of the product g K^2 p, whose size is at most |p|).
  const Vector3 p = start_.rotation.transpose() * (end_.translation - start_.translation);
  const Scalar half = angle_ / 2;
  const Scalar g = angle_ == 0 ? 0 : 1 - half / std::tan(half);
  return p - rotation_vector_.cross(p) / 2 + g * axis_.cross(axis_.cross(p));
}

RigidMotion RigidMotion::shifted(const Vector3& shift) const {
  // The turn depends on the rotations alone; a screw's translation part on the translations too.
  RigidMotion moved = *this;
  moved.start_.translation += shift;
  moved.end_.translation += shift;
  if (kind_ == MotionKind::screw) moved.twist_translation_ = moved.screw_translation();
  return moved;
}

Pose RigidMotion::at(Scalar t) const {
  Pose pose;
  const Scalar phi = t * angle_;
  if (kind_ == MotionKind::screw) {
    // T(t) = T0 + R0 V(phi k) t v, V(phi k) = I + a K + b K^2 with a = (1 - cos phi) / phi =
    // 2 sin^2(phi / 2) / phi and b = 1 - sin(phi) / phi, both in [0, 1) for phi in [0, pi].
    const Vector3 tv = t * twist_translation_;
    Vector3 y = tv;
    if (phi != 0) {
      const Scalar half_sine = std::sin(phi / 2);
      const Scalar a = 2 * half_sine * half_sine / phi;
      const Scalar b = 1 - std::sin(phi) / phi;
      const Vector3 across = axis_.cross(tv);
      y += a * across + b * axis_.cross(across);
    }
    pose.translation = start_.translation + start_.rotation * y;
  } else {
    pose.translation = start_.translation + t * (end_.translation - start_.translation);
  }
  pose.rotation = angle_ == 0 ? start_.rotation : Matrix3(start_.rotation * turn_at(t));
  return pose;
}

Matrix3 RigidMotion::turn_at(Scalar t) const {
  if (angle_ == 0) return Matrix3::Identity();
  const Scalar phi = t * angle_;
  const Scalar half_sine = std::sin(phi / 2);
  Matrix3 cross;
  cross << 0, -axis_(2), axis_(1), axis_(2), 0, -axis_(0), -axis_(1), axis_(0), 0;
  return Matrix3::Identity() + std::sin(phi) * cross +
         (2 * half_sine * half_sine) * (cross * cross);
}

Scalar RigidMotion::pose_error(Scalar reach) const {
  // The translation: T1 - T0, its product with t and the sum with T0 round each coordinate by at
  // most a roundoff of a number below |T0| + |T1|: 3 in all, 4 with the norms' own rounding.
  Scalar translation =
      4 * kUnit * (start_.translation.stableNorm() + end_.translation.stableNorm());
  if (kind_ == MotionKind::screw) {
    // y = t v + a K t v + b K^2 t v: t v within a roundoff of |v|, a and b within 8 roundoffs
    // absolute (a sine's ulp, a square, a division; b's subtraction from 1), each cross product
    // within 3 relative, so y is within 32 roundoffs of |v| (|y| <= |v|: V is a contraction);
    // R0 y adds 3 roundoffs of |R0| |y| per coordinate, and the sum with T0 one of |T0| + |R0 y|.
    translation += 64 * kUnit * start_norm_ * twist_translation_.stableNorm();
  }
  const Scalar rotation = angle_ == 0 ? 0 : kRotationRoundoffs * kUnit * start_norm_ * reach;
  return (translation + rotation) * (1 + 8 * kUnit);
}

}  // namespace swarmcollide
