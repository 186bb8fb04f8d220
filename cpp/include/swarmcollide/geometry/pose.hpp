#pragma once

#include <cstddef>

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// A rigid placement of a body: its points `x` (given in the body's own frame) are at
/// `rotation * x + translation` in the world.
struct Pose {
  Matrix3 rotation = Matrix3::Identity();
  Vector3 translation = Vector3::Zero();

  /// True when the rotation is exactly the identity (the common case, which skips the rotation).
  bool has_identity_rotation() const { return rotation == Matrix3::Identity(); }
};

/// Largest deviation of `rotation^T rotation` from the identity, and of its determinant from 1,
/// that a pose's rotation may have: a rotation built from rounded trigonometry is about 1e-16 off.
inline constexpr Scalar kRotationTolerance = 1e-9;

/// Throws std::invalid_argument, naming `name`, when the pose has a NaN or infinite entry or its
/// rotation is not a proper rotation within `kRotationTolerance`.
void validate_pose(const Pose& pose, const char* name);
/// The same for the pose `name[index]` of a sequence.
void validate_pose(const Pose& pose, const char* name, std::size_t index);

}  // namespace swarmcollide
