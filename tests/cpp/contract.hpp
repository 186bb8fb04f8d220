// The contract every query result keeps, whatever the method, checked against the oracle.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/framed_body.hpp"
#include "oracle.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide::testing {

enum class QueryKind { distance, collide, signed_distance };

inline const char* kind_name(QueryKind kind) {
  switch (kind) {
    case QueryKind::distance:
      return "distance";
    case QueryKind::collide:
      return "collide";
    case QueryKind::signed_distance:
      break;
  }
  return "signed_distance";
}

inline Capability capability_of(QueryKind kind) {
  switch (kind) {
    case QueryKind::distance:
      return kDistance;
    case QueryKind::collide:
      return kCollide;
    case QueryKind::signed_distance:
      break;
  }
  return kSignedDistance;
}

/// The result of `kind` for the pair; collide gives the result that decides it (`collision`).
inline DistanceResult ask(const Query& query, QueryKind kind, const ConvexPolyhedron& a,
                          const ConvexPolyhedron& b) {
  switch (kind) {
    case QueryKind::distance:
      return query.distance(a, b);
    case QueryKind::collide:
      return query.collision(a, b);
    case QueryKind::signed_distance:
      break;
  }
  return query.signed_distance(a, b);
}

/// A pair's scale as the library defines it, in world units.
struct PairScale {
  /// The diameter of the ball around both bodies that the query's frame is built on.
  Scalar size;
  /// The query's tolerance in world units: the relative tolerance times `size`.
  Scalar tolerance;
  /// Rounding of bounds, values and the oracle, relative to the size. The library keeps its
  /// bounds to 64 epsilons of the size (kFrameRounding); the oracle's projections onto the
  /// facets of the difference add a few more; 1e-12 covers both with room to spare.
  Scalar rounding;
  /// Rounding of world points: each coordinate is rounded to its own magnitude, however small
  /// the pair, so checks on points allow 16 epsilons of the largest coordinate besides.
  Scalar point_rounding;
};

inline PairScale scale_of(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                          Scalar relative_tolerance) {
  const detail::FramedPair pair = detail::frame_pair(a, Pose{}, b, Pose{}, relative_tolerance);
  const Scalar size = pair.frame.length_to_world(pair.frame.size);
  const Scalar magnitude =
      std::max(a.vertices().cwiseAbs().maxCoeff(), b.vertices().cwiseAbs().maxCoeff());
  return {size, pair.frame.length_to_world(pair.tolerance), 1e-12 * size,
          16 * std::numeric_limits<Scalar>::epsilon() * magnitude};
}

/// The result contract of a query of `kind` asked of `requested`, for the pair (a, b) whose
/// true answers are `truth`:
/// - the weights lie on the simplexes and reproduce the witness points;
/// - `distance` is the distance between the witnesses (for signed distances, `point_b - point_a =
///   distance * direction`, and the witnesses lie on the supporting features along `direction`);
/// - `lower_bound <= true value <= distance`, and `lower_bound` is the separation along
///   `direction` (when positive, for distances);
/// - a certified verdict is right, and a certified signed distance is within the tolerance;
/// - `status == converged` means the bounds are within the tolerance of each other;
/// - the method is the one asked for, or "exact" naming it in `escalated_from`;
/// - methods that are always certified are (given the iteration budgets they need).
/// `budget_capped` says the options cut an iteration budget below what a proof may need, which
/// releases the methods that are always certified from being so.
inline void expect_contract(const ConvexPolyhedron& a, const ConvexPolyhedron& b, QueryKind kind,
                            Method requested, const DistanceResult& r, const Reference& truth,
                            const PairScale& s, bool budget_capped = false) {
  const Scalar rounding = s.rounding;
  const Scalar points = s.rounding + s.point_rounding;
  // Weights on the simplexes that reproduce the witnesses.
  const VectorX wa = r.weights_a.dense();
  const VectorX wb = r.weights_b.dense();
  ASSERT_EQ(r.weights_a.count(), a.size());
  ASSERT_EQ(r.weights_b.count(), b.size());
  ASSERT_EQ(wa.size(), a.size());
  ASSERT_EQ(wb.size(), b.size());
  EXPECT_GE(wa.minCoeff(), 0);
  EXPECT_GE(wb.minCoeff(), 0);
  EXPECT_NEAR(wa.sum(), 1, 1e-12);
  EXPECT_NEAR(wb.sum(), 1, 1e-12);
  EXPECT_LE((a.vertices().transpose() * wa - r.point_a).norm(), points);
  EXPECT_LE((b.vertices().transpose() * wb - r.point_b).norm(), points);

  const Scalar norm = r.direction.norm();
  EXPECT_TRUE(norm == 0 || std::abs(norm - 1) <= 1e-12) << "|direction| = " << norm;
  const VertexMatrix d = differences(a, b);
  // Methods without distances answer collide with their signed distance, unless an exact
  // method took over; either way the true signed distance is at most the distance.
  const bool signed_query =
      kind == QueryKind::signed_distance ||
      (kind == QueryKind::collide && !(method_info(requested).capabilities & kDistance));
  if (kind == QueryKind::signed_distance) {
    EXPECT_LE((r.point_b - r.point_a - r.distance * r.direction).norm(),
              r.distance - r.lower_bound + points);
    if (norm > 0) {
      EXPECT_NEAR(separation_along(d, r.direction), r.lower_bound, rounding);
      // point_a on A's supporting plane along the normal, point_b on B's along its opposite.
      // Apart, the witnesses are the nearest points and the normal is the direction between
      // them, exact only to the gap: the witnesses' distances below the planes add up to
      // distance - lower_bound.
      const Scalar plane = r.distance - r.lower_bound + points;
      EXPECT_NEAR(r.direction.dot(r.point_a), (a.vertices() * r.direction).maxCoeff(), plane);
      EXPECT_NEAR(r.direction.dot(r.point_b), (b.vertices() * r.direction).minCoeff(), plane);
    }
    EXPECT_LE(r.lower_bound, truth.signed_distance + rounding);
    EXPECT_LE(truth.signed_distance, r.distance + rounding);
  } else {
    if (signed_query) {
      // A signed distance's witnesses are `lower_bound` apart along the normal.
      EXPECT_LE(std::abs((r.point_b - r.point_a).norm() - std::abs(r.distance)),
                r.distance - r.lower_bound + points);
    } else {
      EXPECT_NEAR(r.distance, (r.point_b - r.point_a).norm(), points);
      EXPECT_GE(r.lower_bound, 0);
    }
    if (r.lower_bound > 0) {
      EXPECT_NEAR(std::abs(norm - 1), 0, 1e-12);
      EXPECT_NEAR(separation_along(d, r.direction), r.lower_bound, rounding);
    }
    EXPECT_LE(r.lower_bound, truth.distance + rounding);
    EXPECT_LE(signed_query ? truth.signed_distance : truth.distance, r.distance + rounding);
  }

  // A certified verdict is right; at the threshold itself, rounding decides.
  if (r.certified) {
    if (r.colliding) {
      EXPECT_LE(truth.distance, s.tolerance + rounding) << "certified contact of bodies apart";
    } else {
      EXPECT_GT(truth.distance, s.tolerance - rounding)
          << "certified separation of bodies in contact";
    }
    if (kind == QueryKind::signed_distance) {
      EXPECT_NEAR(r.distance, truth.signed_distance, s.tolerance + rounding);
    }
  }
  if (r.status == SolverStatus::converged) {
    EXPECT_LE(r.distance - r.lower_bound, s.tolerance + 2 * rounding);
  }

  if (r.escalated_from) {
    EXPECT_EQ(*r.escalated_from, requested);
    EXPECT_EQ(r.method, Method::exact);
    EXPECT_NE(requested, Method::exact);
  } else {
    EXPECT_EQ(r.method, requested);
  }
  if (!budget_capped && (method_info(requested).always_certified || r.method == Method::exact)) {
    EXPECT_TRUE(r.certified);
  }
}

/// Two answers of the same query are the same, bit for bit.
inline void expect_identical(const DistanceResult& first, const DistanceResult& second) {
  EXPECT_EQ(first.distance, second.distance);
  EXPECT_EQ(first.lower_bound, second.lower_bound);
  EXPECT_EQ(first.point_a, second.point_a);
  EXPECT_EQ(first.point_b, second.point_b);
  EXPECT_EQ(first.weights_a.dense(), second.weights_a.dense());
  EXPECT_EQ(first.weights_b.dense(), second.weights_b.dense());
  EXPECT_EQ(first.direction, second.direction);
  EXPECT_EQ(first.iterations, second.iterations);
  EXPECT_EQ(first.evaluations, second.evaluations);
  EXPECT_EQ(first.history, second.history);
  EXPECT_EQ(first.colliding, second.colliding);
  EXPECT_EQ(first.certified, second.certified);
  EXPECT_EQ(first.method, second.method);
  EXPECT_EQ(first.escalated_from, second.escalated_from);
  EXPECT_EQ(first.status, second.status);
}

}  // namespace swarmcollide::testing
