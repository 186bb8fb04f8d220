// An exact reference for the distance and the signed distance of small convex hulls, independent
// of the solvers: both are read off the Minkowski difference D = conv{y_j - x_i}, built point by
// point (every pair) and hulled by compute_hull, which test_geometry checks against a brute force.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/hull.hpp"

namespace swarmcollide::testing {

/// The points y_j - x_i of D, one per row. Differences of nearby coordinates are exact, so D is
/// as accurate for bodies far from the origin as near it.
inline VertexMatrix differences(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  VertexMatrix d(static_cast<Eigen::Index>(a.size()) * b.size(), 3);
  for (int i = 0; i < a.size(); ++i) {
    for (int j = 0; j < b.size(); ++j) {
      d.row(static_cast<Eigen::Index>(i) * b.size() + j) =
          b.vertices().row(j) - a.vertices().row(i);
    }
  }
  return d;
}

/// The separation along the unit direction `n`, min over D of `n . d`, computed on the
/// differences (see `differences`).
inline Scalar separation_along(const VertexMatrix& d, const Vector3& n) {
  return (d * n).minCoeff();
}

/// Distance from the origin to the segment [p, q].
inline Scalar origin_to_segment(const Vector3& p, const Vector3& q) {
  const Vector3 e = q - p;
  const Scalar length2 = e.squaredNorm();
  const Scalar t = length2 > 0 ? std::clamp(-p.dot(e) / length2, Scalar(0), Scalar(1)) : 0;
  return (p + t * e).norm();
}

/// Distance from the origin to the triangle (a, b, c), by its Voronoi regions (Ericson,
/// Real-Time Collision Detection, 5.1.5); in the face region, the distance to the plane.
inline Scalar origin_to_triangle(const Vector3& a, const Vector3& b, const Vector3& c) {
  const Vector3 ab = b - a;
  const Vector3 ac = c - a;
  const Scalar d1 = ab.dot(-a), d2 = ac.dot(-a);
  const Scalar d3 = ab.dot(-b), d4 = ac.dot(-b);
  const Scalar d5 = ab.dot(-c), d6 = ac.dot(-c);
  const Scalar va = d3 * d6 - d5 * d4;
  const Scalar vb = d5 * d2 - d1 * d6;
  const Scalar vc = d1 * d4 - d3 * d2;
  const bool outside_face = (d1 <= 0 && d2 <= 0) || (d3 >= 0 && d4 <= d3) ||
                            (d6 >= 0 && d5 <= d6) || (vc <= 0 && d1 >= 0 && d3 <= 0) ||
                            (vb <= 0 && d2 >= 0 && d6 <= 0) ||
                            (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0);
  const Vector3 normal = ab.cross(ac);
  if (outside_face || !(normal.norm() > 0)) {
    return std::min({origin_to_segment(a, b), origin_to_segment(b, c), origin_to_segment(a, c)});
  }
  return std::abs(a.dot(normal)) / normal.norm();
}

/// The true answers for a pair.
struct Reference {
  /// The distance between the hulls: that of the origin from D.
  Scalar distance;
  /// The distance when apart; minus the penetration depth when the hulls overlap. The depth is
  /// the smallest support value h_D(n) = max over D of n . d over the facet normals n of D (the
  /// origin's distance to the nearest facet plane); support values of all of D's points are
  /// used, so a point the hull dropped as within rounding of a facet cannot lower it. A D without
  /// interior (coplanar flat bodies, say) has no depth: the signed distance is the distance.
  Scalar signed_distance;
};

/// The answers for the difference points `d`, which lie in the unit ball.
inline Reference unit_reference(const VertexMatrix& d) {
  const Hull hull = compute_hull(d);
  const auto point = [&d](int i) -> Vector3 { return d.row(i).transpose(); };
  if (hull.dimension == 0) {
    const Scalar distance = point(hull.vertex_indices[0]).norm();
    return {distance, distance};
  }
  if (hull.dimension == 1) {
    const Scalar distance =
        origin_to_segment(point(hull.vertex_indices[0]), point(hull.vertex_indices[1]));
    return {distance, distance};
  }
  Scalar distance = std::numeric_limits<Scalar>::infinity();
  bool inside = hull.dimension == 3;
  Scalar depth = std::numeric_limits<Scalar>::infinity();
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    const Vector3 p = point(hull.faces(f, 0));
    const Vector3 q = point(hull.faces(f, 1));
    const Vector3 r = point(hull.faces(f, 2));
    distance = std::min(distance, origin_to_triangle(p, q, r));
    if (hull.dimension == 3) {
      const Vector3 normal = (q - p).cross(r - p).normalized();
      // The origin is behind every facet plane when it lies in D.
      inside = inside && normal.dot(p) >= 0;
      depth = std::min(depth, (d * normal).maxCoeff());
    }
  }
  if (inside) return {0, -depth};
  return {distance, distance};
}

/// The true answers for the pair (a, b).
inline Reference reference(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  // Scaled by a power of two (exactly) into the unit ball, so that the squares and cross
  // products below neither overflow nor underflow for bodies of any size.
  int exponent = 0;
  VertexMatrix d = differences(a, b);
  const Scalar largest = d.cwiseAbs().maxCoeff();
  if (largest > 0) std::frexp(largest, &exponent);
  d *= std::ldexp(1.0, -exponent);
  const Reference unit = unit_reference(d);
  return {std::ldexp(unit.distance, exponent), std::ldexp(unit.signed_distance, exponent)};
}

}  // namespace swarmcollide::testing
