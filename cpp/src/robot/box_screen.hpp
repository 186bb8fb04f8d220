// A proven lower bound on the distance between two placed boxes (the separating axis test), the
// robot checks' screen after the bounding balls; private to the library's sources.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "swarmcollide/geometry/aabb.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// A proven lower bound on the distance between the boxes `a` and `b`, given in their bodies' own
/// frames and placed by `pose_a` and `pose_b` (-inf when no axis separates them): the largest
/// separation of their projections, over the 3 + 3 box axes and their 9 cross products, divided
/// by the axis' length (the separating axis test). A placed box's projection on an axis L is exact
/// for any linear map (the rotation need not be orthonormal): centre (R^T L).c + L.t, half-width
/// sum_i h_i |R_i . L|. The margin, 1e-12 of the magnitudes involved, is far above the rounding
/// of these few products, sums and the division. When the 6 box axes' separation alone already
/// satisfies `enough`, it is returned without the 9 cross products (two thirds of the work): a
/// caller that asks only whether the boxes are that far apart gets the same answer.
template <typename Enough>
Scalar box_separation(const Aabb& a, const Pose& pose_a, const Aabb& b, const Pose& pose_b,
                      const Enough& enough) {
  const Vector3 half_a = (a.max - a.min) / 2;
  const Vector3 half_b = (b.max - b.min) / 2;
  const Vector3 centre_a = pose_a.rotation * ((a.max + a.min) / 2) + pose_a.translation;
  const Vector3 centre_b = pose_b.rotation * ((b.max + b.min) / 2) + pose_b.translation;
  const Vector3 between = centre_b - centre_a;
  const Scalar magnitude =
      centre_a.lpNorm<1>() + centre_b.lpNorm<1>() + half_a.sum() + half_b.sum();
  const Matrix3& ra = pose_a.rotation;
  const Matrix3& rb = pose_b.rotation;
  Scalar best = -std::numeric_limits<Scalar>::infinity();
  const auto offer = [&](const Vector3& axis) {
    const Scalar reach_a = half_a.dot((ra.transpose() * axis).cwiseAbs());
    const Scalar reach_b = half_b.dot((rb.transpose() * axis).cwiseAbs());
    const Scalar gap = std::abs(between.dot(axis)) - reach_a - reach_b -
                       1e-12 * magnitude * axis.lpNorm<1>();
    const Scalar length = axis.norm();
    if (gap > 0 && length > 0) best = std::max(best, gap / length * (1 - 1e-12));
  };
  for (int i = 0; i < 3; ++i) {
    offer(ra.col(i));
    offer(rb.col(i));
  }
  if (enough(best)) return best;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) offer(ra.col(i).cross(rb.col(j)));
  }
  return best;
}

/// The same over all 15 axes.
inline Scalar box_separation(const Aabb& a, const Pose& pose_a, const Aabb& b,
                             const Pose& pose_b) {
  return box_separation(a, pose_a, b, pose_b, [](Scalar) { return false; });
}

}  // namespace swarmcollide::detail
