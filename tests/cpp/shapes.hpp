// Bodies the tests build: boxes, point sets, moved and scaled copies, seeded random hulls.
#pragma once

#include <Eigen/QR>
#include <algorithm>
#include <initializer_list>

#include "swarmcollide/detail/random.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"

namespace swarmcollide::testing {

/// The axis-aligned box with corners `lo` and `hi` (its 8 corners).
inline ConvexPolyhedron box(const Vector3& lo, const Vector3& hi) {
  VertexMatrix v(8, 3);
  for (int k = 0; k < 8; ++k) {
    v.row(k) << (k & 1 ? hi.x() : lo.x()), (k & 2 ? hi.y() : lo.y()), (k & 4 ? hi.z() : lo.z());
  }
  return ConvexPolyhedron(v);
}

/// The pose moving a body by `translation` after turning it by `rotation`.
inline Pose at(const Vector3& translation, const Matrix3& rotation = Matrix3::Identity()) {
  return {rotation, translation};
}

/// The pair's size as the queries measure it, less the frame's rounding to a ball: a bound from
/// below on the tolerance's scale, so `tolerance * size` bounds the error allowed.
inline Scalar size_of(const ConvexPolyhedron& a, const Pose& pose_a, const ConvexPolyhedron& b,
                      const Pose& pose_b) {
  const Vector3 ca = pose_a.rotation * a.bounds().centre + pose_a.translation;
  const Vector3 cb = pose_b.rotation * b.bounds().centre + pose_b.translation;
  return (cb - ca).norm() + 2 * std::max(a.bounds().radius, b.bounds().radius);
}

inline ConvexPolyhedron unit_cube() { return box(Vector3::Zero(), Vector3::Ones()); }

inline ConvexPolyhedron point_set(std::initializer_list<Vector3> list) {
  VertexMatrix v(static_cast<Eigen::Index>(list.size()), 3);
  Eigen::Index i = 0;
  for (const Vector3& p : list) v.row(i++) = p.transpose();
  return ConvexPolyhedron(v);
}

/// The body's points times `scale`, plus `offset`.
inline ConvexPolyhedron transformed(const ConvexPolyhedron& body, Scalar scale,
                                    const Vector3& offset) {
  VertexMatrix v = body.vertices() * scale;
  v.rowwise() += offset.transpose();
  return ConvexPolyhedron(v);
}

inline ConvexPolyhedron moved(const ConvexPolyhedron& body, const Vector3& offset) {
  return transformed(body, 1, offset);
}

/// Uniform numbers from the library's own generator: unlike the standard distributions, the same
/// on every standard library, so a seed names the same bodies everywhere.
class Random {
 public:
  explicit Random(std::uint64_t seed) : rng_(seed) {}
  /// Uniform in [lo, hi).
  Scalar uniform(Scalar lo = -1, Scalar hi = 1) { return lo + (hi - lo) * rng_.uniform(); }
  Vector3 vector(Scalar half_width = 1) {
    return Vector3(uniform(-half_width, half_width), uniform(-half_width, half_width),
                   uniform(-half_width, half_width));
  }
  /// A uniformly random unit vector (by rejection from the cube).
  Vector3 unit() {
    for (;;) {
      const Vector3 v = vector();
      const Scalar n = v.norm();
      if (n > 0.1 && n <= 1) return v / n;
    }
  }
  /// A uniformly random rotation (the QR factor of a random matrix, made proper).
  Matrix3 rotation() {
    Matrix3 m;
    for (int k = 0; k < 3; ++k) m.col(k) = vector();
    Matrix3 q = Eigen::HouseholderQR<Matrix3>(m).householderQ();
    if (q.determinant() < 0) q.col(0) = -q.col(0);
    return q;
  }
  /// `count` points uniform in the cube of half-width 1 around `centre`.
  ConvexPolyhedron body(int count, const Vector3& centre = Vector3::Zero()) {
    VertexMatrix v(count, 3);
    for (int i = 0; i < count; ++i) v.row(i) = (centre + vector()).transpose();
    return ConvexPolyhedron(v);
  }

 private:
  detail::Xoshiro256 rng_;
};

}  // namespace swarmcollide::testing
