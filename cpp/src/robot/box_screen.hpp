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

/// A box placed by a pose with what the face axes take from it alone (its centre and
/// half-widths, its Gram matrix R^T R and its columns' norms), made once for every pair it is
/// screened in: the same expressions as made per pair, so the same values. The cross axes'
/// cofactor columns are made by box_separation where the face axes are not enough (most of the
/// screens that place a box once for many pairs take its face axes alone).
struct PlacedBox {
  PlacedBox() = default;
  PlacedBox(const Aabb& box, const Pose& pose)
      : half((box.max - box.min) / 2),
        centre(pose.rotation * ((box.max + box.min) / 2) + pose.translation),
        rotation(pose.rotation),
        gram(pose.rotation.transpose() * pose.rotation) {
    for (int i = 0; i < 3; ++i) {
      column_norm1(i) = rotation.col(i).lpNorm<1>();
      column_norm(i) = rotation.col(i).norm();
      own_reach(i) = half.dot(gram.col(i).cwiseAbs());
    }
    centre_norm = centre.lpNorm<1>();
    half_sum = half.sum();
  }

  Vector3 half;
  Vector3 centre;
  Matrix3 rotation;
  Matrix3 gram;
  // The columns' 1-norms and lengths (the box axes').
  Vector3 column_norm1;
  Vector3 column_norm;
  // Per box axis, the box's half-width along it (face_separation's, made once for every pair the
  // box is screened in: bench/robot_motion_profile.py places a box once for some 3 pairs).
  Vector3 own_reach;
  Scalar centre_norm;
  Scalar half_sum;
};

// The cofactor columns R_{m+1} x R_{m+2} of a placed box (box_separation's X_m and Y_m).
inline Matrix3 cofactor_columns(const Matrix3& rotation) {
  Matrix3 cofactors;
  for (int m = 0; m < 3; ++m) {
    cofactors.col(m) = rotation.col((m + 1) % 3).cross(rotation.col((m + 2) % 3));
  }
  return cofactors;
}

// Offers one axis to `best`: the separation along it, of 1-norm `norm1` and length `length`,
// with `along` = between . axis and the two half-widths, less `slack` and the margin
// (box_separation's proof).
inline void offer_axis(Scalar& best, Scalar magnitude, Scalar norm1, Scalar length, Scalar along,
                       Scalar reach_a, Scalar reach_b, Scalar slack) {
  const Scalar gap = std::abs(along) - reach_a - reach_b - 1e-12 * magnitude * norm1 - slack;
  if (gap > 0 && length > 0) best = std::max(best, gap / length * (1 - 1e-12));
}

// The two boxes' centres' difference and the magnitude their margin is taken of.
inline Vector3 box_between(const PlacedBox& a, const PlacedBox& b) { return b.centre - a.centre; }
inline Scalar box_magnitude(const PlacedBox& a, const PlacedBox& b) {
  return a.centre_norm + b.centre_norm + a.half_sum + b.half_sum;
}

/// box_separation over the 3 + 3 box axes alone (-inf when none separates the boxes): a proven
/// lower bound as well (each axis' separation is one), at a third of the work of all 15.
inline Scalar face_separation(const PlacedBox& a, const PlacedBox& b) {
  const Vector3 between = box_between(a, b);
  const Scalar magnitude = box_magnitude(a, b);
  const Matrix3& ra = a.rotation;
  const Matrix3& rb = b.rotation;
  Scalar best = -std::numeric_limits<Scalar>::infinity();
  // Entry (k, i): column k of the first dotted with column i of the second.
  const Matrix3 across = ra.transpose() * rb;
  for (int i = 0; i < 3; ++i) {
    offer_axis(best, magnitude, a.column_norm1(i), a.column_norm(i), between.dot(ra.col(i)),
               a.own_reach(i), b.half.dot(across.row(i).transpose().cwiseAbs()), 0);
    offer_axis(best, magnitude, b.column_norm1(i), b.column_norm(i), between.dot(rb.col(i)),
               a.half.dot(across.col(i).cwiseAbs()), b.own_reach(i), 0);
  }
  return best;
}

/// A proven lower bound on the distance between the boxes `a` and `b`, given in their bodies' own
/// frames and placed by their poses (-inf when no axis separates them): the largest
/// separation of their projections, over the 3 + 3 box axes and their 9 cross products, divided
/// by the axis' length (the separating axis test). A placed box's projection on an axis L is exact
/// for any linear map (the rotation need not be orthonormal): centre (R^T L).c + L.t, half-width
/// sum_i h_i |R_i . L|. The margin, 1e-12 of the magnitudes involved, is far above the rounding
/// of these few products, sums and the division. When the 6 box axes' separation alone already
/// satisfies `enough`, it is returned without the 9 cross products (two thirds of the work): a
/// caller that asks only whether the boxes are that far apart gets the same answer.
///
/// The products R_i . L are each made once: for a box axis they are entries of R_a^T R_a,
/// R_b^T R_b and R_a^T R_b (the same products, summed in the same order, as R^T L). For a cross
/// axis L = A_i x B_j (A = R_a, B = R_b, indices mod 3) they are triple products, which hold for
/// any matrices: A_i . L = 0, A_{i+1} . L = -(A_i x A_{i+1}) . B_j, A_{i+2} . L = (A_{i+2} x A_i)
/// . B_j, and B_k . L = A_i . (B_j x B_k) likewise, so the cofactor columns X_m = A_{m+1} x
/// A_{m+2} and Y_m = B_{m+1} x B_{m+2} dotted with B's and A's columns give them all (18 dot
/// products for the 9 axes instead of 54). They are exact for the cross product L* = A_i x B_j
/// of the stored columns, while the test is made along the computed L, |L - L*|_1 <= 2.01u
/// |A_i|_1 |B_j|_1 away: with N_a, N_b bounding the columns' 1-norms, each A_k . L is within
/// 2.01u N_a^2 N_b of A_k . L* (the dropped A_i . L too), and the computed cofactor dot within
/// (2.01 + 3.02)u N_a^2 N_b of A_k . L*, so each half-width is within 7.1u (N_a^2 N_b |h_a|_1 +
/// N_a N_b^2 |h_b|_1) of the exact one along L, an error that does not shrink with |L| (near
/// parallel columns) as the margin above does. It is taken off the gap, with N^2 <= 3 |R|_F^2 (a
/// column's 1-norm is at most sqrt 3 its length): 7.1u 3 sqrt(3) = 8.2e-15 per F_a^2 F_b |h_a|_1
/// + F_a F_b^2 |h_b|_1, and 1e-13 of that is taken (the traces' and the sums' rounding are far
/// inside the factor 12).
template <typename Enough>
Scalar box_separation(const PlacedBox& a, const PlacedBox& b, const Enough& enough) {
  Scalar best = face_separation(a, b);
  if (enough(best)) return best;
  const Vector3& half_a = a.half;
  const Vector3& half_b = b.half;
  const Vector3 between = box_between(a, b);
  const Scalar magnitude = box_magnitude(a, b);
  const Matrix3& ra = a.rotation;
  const Matrix3& rb = b.rotation;
  // d(m, j) = X_m . B_j, e(m, i) = Y_m . A_i.
  const Matrix3 d = cofactor_columns(ra).transpose() * rb;
  const Matrix3 e = cofactor_columns(rb).transpose() * ra;
  const Scalar fa2 = a.gram.trace();
  const Scalar fb2 = b.gram.trace();
  const Scalar fa = std::sqrt(fa2);
  const Scalar fb = std::sqrt(fb2);
  const Scalar slack = 1e-13 * (fa2 * fb * a.half_sum + fa * fb2 * b.half_sum);
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    const int i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const int j2 = (j + 2) % 3;
      const Vector3 axis = ra.col(i).cross(rb.col(j));
      offer_axis(best, magnitude, axis.lpNorm<1>(), axis.norm(), between.dot(axis),
                 half_a(i1) * std::abs(d(i2, j)) + half_a(i2) * std::abs(d(i1, j)),
                 half_b(j1) * std::abs(e(j2, i)) + half_b(j2) * std::abs(e(j1, i)), slack);
    }
  }
  return best;
}

/// The same from the boxes and their poses.
template <typename Enough>
Scalar box_separation(const Aabb& a, const Pose& pose_a, const Aabb& b, const Pose& pose_b,
                      const Enough& enough) {
  return box_separation(PlacedBox(a, pose_a), PlacedBox(b, pose_b), enough);
}

/// The same over all 15 axes.
inline Scalar box_separation(const Aabb& a, const Pose& pose_a, const Aabb& b,
                             const Pose& pose_b) {
  return box_separation(a, pose_a, b, pose_b, [](Scalar) { return false; });
}

}  // namespace swarmcollide::detail
