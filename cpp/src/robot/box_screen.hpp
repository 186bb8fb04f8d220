// A certified screen between two placed boxes (the separating axis test); private to the
// library's sources.
#pragma once

#include <cmath>

#include "swarmcollide/geometry/aabb.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// True when the boxes `a` and `b`, given in their bodies' own frames and placed by `pose_a` and
/// `pose_b`, are proven farther apart than `gap`: some axis among the 3 + 3 box axes and their 9
/// cross products separates their projections by more than `gap` times its length. A placed
/// box's projection on an axis L is exact for any linear map (the rotation need not be
/// orthonormal): centre (R^T L).c + L.t, half-width sum_i h_i |R_i . L|. The margin, 1e-12 of
/// the magnitudes involved, is far above the rounding of these few products and sums.
inline bool boxes_apart(const Aabb& a, const Pose& pose_a, const Aabb& b, const Pose& pose_b,
                        Scalar gap) {
  const Vector3 half_a = (a.max - a.min) / 2;
  const Vector3 half_b = (b.max - b.min) / 2;
  const Vector3 centre_a = pose_a.rotation * ((a.max + a.min) / 2) + pose_a.translation;
  const Vector3 centre_b = pose_b.rotation * ((b.max + b.min) / 2) + pose_b.translation;
  const Vector3 between = centre_b - centre_a;
  const Scalar magnitude = centre_a.lpNorm<1>() + centre_b.lpNorm<1>() + half_a.sum() +
                           half_b.sum() + gap;
  const Matrix3& ra = pose_a.rotation;
  const Matrix3& rb = pose_b.rotation;
  const auto separates = [&](const Vector3& axis) {
    const Scalar reach_a = half_a.dot((ra.transpose() * axis).cwiseAbs());
    const Scalar reach_b = half_b.dot((rb.transpose() * axis).cwiseAbs());
    const Scalar length = axis.lpNorm<1>();
    return std::abs(between.dot(axis)) - reach_a - reach_b >
           gap * axis.norm() + 1e-12 * magnitude * length;
  };
  for (int i = 0; i < 3; ++i) {
    if (separates(ra.col(i)) || separates(rb.col(i))) return true;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (separates(ra.col(i).cross(rb.col(j)))) return true;
    }
  }
  return false;
}

}  // namespace swarmcollide::detail
