// A brute-force signed distance for the penetration tests: the hull of all pairwise differences.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "swarmcollide/geometry/hull.hpp"

namespace swarmcollide::testing {

/// The point of the triangle (a, b, c) nearest to p (Ericson, Real-Time Collision Detection 5.1.5).
inline Vector3 nearest_on_triangle(const Vector3& p, const Vector3& a, const Vector3& b,
                                   const Vector3& c) {
  const Vector3 ab = b - a, ac = c - a, ap = p - a;
  const Scalar d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3 bp = p - b;
  const Scalar d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const Scalar vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vector3 cp = p - c;
  const Scalar d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const Scalar vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const Scalar va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const Scalar denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

/// The oracle's answer, and on which side of the true signed distance it errs.
struct OracleValue {
  Scalar value;
  /// True when `value <= sd` up to the dot products' rounding (origin inside a solid D: the
  /// support of D along any direction bounds the depth); false when `value >= sd` (origin outside
  /// D or D flat: the distance to triangles inside D bounds the distance from above).
  bool is_lower_bound;
};

/// Signed distance of the convex hulls of the rows of `a` and `b` from the hull of the
/// differences `D = {y_j - x_i}`: minus the smallest support of D along a facet normal when the
/// origin is inside D, otherwise the distance from the origin to D's triangles. Qhull's facets
/// and the flat hulls' projection make it accurate to about 1e-13 on nearly flat differences,
/// and always on the side `is_lower_bound` says.
inline OracleValue oracle(const VertexMatrix& a, const VertexMatrix& b) {
  VertexMatrix d(a.rows() * b.rows(), 3);
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    for (Eigen::Index j = 0; j < b.rows(); ++j) d.row(i * b.rows() + j) = b.row(j) - a.row(i);
  }
  const Hull hull = compute_hull(d);
  const auto row = [&](int i) -> Vector3 { return d.row(i).transpose(); };
  if (hull.dimension == 0) return {row(hull.vertex_indices[0]).norm(), false};
  if (hull.dimension == 1) {
    const Vector3 p = row(hull.vertex_indices[0]);
    const Vector3 q = row(hull.vertex_indices[1]);
    const Scalar t = std::clamp(-p.dot(q - p) / (q - p).squaredNorm(), Scalar(0), Scalar(1));
    return {(p + t * (q - p)).norm(), false};
  }
  Scalar nearest_offset = std::numeric_limits<Scalar>::infinity();
  Scalar distance = std::numeric_limits<Scalar>::infinity();
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    const Vector3 p = row(hull.faces(f, 0)), q = row(hull.faces(f, 1)), r = row(hull.faces(f, 2));
    distance = std::min(distance, nearest_on_triangle(Vector3::Zero(), p, q, r).norm());
    // The support of D along the facet's normal rather than the plane through its corners, so a
    // normal spoilt by a sliver triangle still gives a true separation.
    const Vector3 n = (q - p).cross(r - p).normalized();
    nearest_offset = std::min(nearest_offset, (d * n).maxCoeff());
  }
  if (hull.dimension == 3 && nearest_offset >= 0) return {-nearest_offset, true};
  return {distance, false};
}

inline Scalar oracle_signed_distance(const VertexMatrix& a, const VertexMatrix& b) {
  return oracle(a, b).value;
}

}  // namespace swarmcollide::testing
