// Pose validation for callers that know already whether the rotation is the identity; private
// to the library's sources.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "swarmcollide/geometry/pose.hpp"

namespace swarmcollide::detail {

/// |R^T R - I| (largest entry) and det R: how far a rotation is from a proper rotation.
struct RotationDeviation {
  Scalar orthogonality;
  Scalar determinant;
};

/// The deviation of `r`. Inline: every query checks a pose with it, and its call was a tenth of
/// the check.
[[gnu::always_inline]] inline RotationDeviation rotation_deviation(const Matrix3& r) {
  // R^T R - I is symmetric: its six distinct entries, the columns' dot products (written out:
  // every row of a batch checks its poses).
  const auto dot = [&r](int i, int j) {
    return r(0, i) * r(0, j) + r(1, i) * r(1, j) + r(2, i) * r(2, j);
  };
  const Scalar orthogonality =
      std::max({std::abs(dot(0, 0) - 1), std::abs(dot(1, 1) - 1), std::abs(dot(2, 2) - 1),
                std::abs(dot(0, 1)), std::abs(dot(0, 2)), std::abs(dot(1, 2))});
  return {orthogonality, r.determinant()};
}

/// True for a proper rotation within kRotationTolerance.
inline bool rigid(const RotationDeviation& d) {
  return d.orthogonality <= kRotationTolerance &&
         std::abs(d.determinant - 1) <= kRotationTolerance;
}

/// True when every entry of `v` is finite, in one test where allFinite makes three: x - x is 0
/// for a finite x and NaN otherwise, and a NaN stays in the sum.
inline bool finite_entries(const Vector3& v) {
  return (v.x() - v.x()) + (v.y() - v.y()) + (v.z() - v.z()) == 0;
}

/// True when the translation is finite.
inline bool finite_translation(const Pose& pose) { return finite_entries(pose.translation); }

/// What validate_pose checks, for a pose whose rotation is the identity exactly when `turned` is
/// false (`turned == !pose.has_identity_rotation()`): framing a pair needs that test anyway, so it
/// is made once. False where validate_pose would throw. The rotation's entries need no test of
/// their own: the identity is finite, and every entry is a factor of a product in the
/// determinant, so one that is infinite or NaN makes it infinite or NaN, which rigid() rejects.
/// Inline: framing a pair and a batch row each check a pose or two with it (its call and its
/// reloads of the rotation were some 10 instructions of every posed query).
inline bool valid_pose(const Pose& pose, bool turned) {
  return finite_translation(pose) && (!turned || rigid(rotation_deviation(pose.rotation)));
}

/// True when `x` and `y` hold the same bits: the same object, or a copy of it. Validation (and
/// the identity test) reads nothing but those bits, so a pair whose bodies share a pose checks it
/// once. Word by word, the first differing one ends the test (most often the first), where a
/// rotation's check is some 115 instructions.
inline bool same_pose(const Pose& x, const Pose& y) {
  if (&x == &y) return true;
  const auto same = [](const Scalar* u, const Scalar* v, int count) {
    for (int k = 0; k < count; ++k) {
      std::uint64_t a;
      std::uint64_t b;
      std::memcpy(&a, u + k, sizeof a);
      std::memcpy(&b, v + k, sizeof b);
      if (a != b) return false;
    }
    return true;
  };
  return same(x.rotation.data(), y.rotation.data(), 9) &&
         same(x.translation.data(), y.translation.data(), 3);
}

/// Whether each pose of a pair turns its body (`!has_identity_rotation()`), both validated first
/// (validate_pose's errors, named "pose_a" and "pose_b"); a pose B shares with A (both bodies in
/// one rigid frame) is A's, checked already. What framing a posed pair needs of its poses, made
/// once for the validation too.
struct PoseTurns {
  bool a;
  bool b;
};

inline PoseTurns validated_turns(const Pose& pose_a, const Pose& pose_b) {
  const bool turned_a = !pose_a.has_identity_rotation();
  if (!valid_pose(pose_a, turned_a)) validate_pose(pose_a, "pose_a");
  const bool shared = same_pose(pose_a, pose_b);
  const bool turned_b = shared ? turned_a : !pose_b.has_identity_rotation();
  if (!shared && !valid_pose(pose_b, turned_b)) validate_pose(pose_b, "pose_b");
  return {turned_a, turned_b};
}

}  // namespace swarmcollide::detail
