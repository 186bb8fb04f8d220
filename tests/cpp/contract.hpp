#pragma once

#include <gtest/gtest.h>

#include <algorithm>

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/problem/certificate.hpp"
#include "swarmcollide/solvers/distance_result.hpp"

namespace swarmcollide::testing {

/// The size of a pair: the larger of the two bounding-box diagonals.
inline Scalar size_of(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  const auto diagonal = [](const ConvexPolyhedron& x) {
    return (x.aabb().max - x.aabb().min).norm();
  };
  return std::max({diagonal(a), diagonal(b), Scalar(1e-300)});
}

/// What every distance result satisfies, whatever the method and however good it is, up to the
/// rounding `eps`: weights on the simplexes that reproduce the witness points, `distance` the
/// distance between them, and `lower_bound` in [0, distance], certified by `direction`.
inline void expect_contract(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                            const DistanceResult& r, Scalar eps = 1e-12) {
  ASSERT_EQ(r.weights_a.size(), a.size());
  ASSERT_EQ(r.weights_b.size(), b.size());
  EXPECT_GE(r.weights_a.minCoeff(), 0);
  EXPECT_GE(r.weights_b.minCoeff(), 0);
  EXPECT_NEAR(r.weights_a.sum(), 1, 1e-12);
  EXPECT_NEAR(r.weights_b.sum(), 1, 1e-12);
  EXPECT_LE((a.vertices().transpose() * r.weights_a - r.point_a).norm(), eps);
  EXPECT_LE((b.vertices().transpose() * r.weights_b - r.point_b).norm(), eps);
  EXPECT_NEAR(r.distance, (r.point_b - r.point_a).norm(), eps);
  EXPECT_GE(r.lower_bound, 0);
  EXPECT_LE(r.lower_bound, r.distance + eps);
  if (r.lower_bound > 0) EXPECT_NEAR(separation(a, b, r.direction), r.lower_bound, eps);
}

/// The verdicts follow from the bounds at `tolerance`.
inline void expect_verdicts_from_bounds(const DistanceResult& r, Scalar tolerance) {
  EXPECT_EQ(r.colliding, r.distance <= tolerance);
  EXPECT_EQ(r.certified, r.colliding || r.lower_bound > tolerance);
}

}  // namespace swarmcollide::testing
