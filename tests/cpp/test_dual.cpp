// method="dual": the paper's swarm over separating directions, its rounds and its exact finish,
// on bodies too large for the oracle, against the exact method.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "contract.hpp"
#include "penetration_oracle.hpp"
#include "shapes.hpp"

namespace swarmcollide::testing {
namespace {

// The hull vertices of `n` random points on the unit sphere, around `centre`.
ConvexPolyhedron sphere_polytope(int n, Random& rng, const Vector3& centre = Vector3::Zero()) {
  VertexMatrix points(n, 3);
  for (int i = 0; i < n; ++i) points.row(i) = (centre + rng.unit()).transpose();
  const ConvexPolyhedron cloud(points);
  const Hull& hull = cloud.hull();
  VertexMatrix vertices(static_cast<Eigen::Index>(hull.vertex_indices.size()), 3);
  for (std::size_t k = 0; k < hull.vertex_indices.size(); ++k) {
    vertices.row(static_cast<Eigen::Index>(k)) = points.row(hull.vertex_indices[k]);
  }
  return ConvexPolyhedron(vertices);
}

QueryOptions with(Method method) {
  QueryOptions options;
  options.method = method;
  return options;
}

// B moved so that its exact distance to A is `gap` (apart), or pushed `-gap` past touching
// along the nearest-point direction (overlapping).
std::pair<ConvexPolyhedron, ConvexPolyhedron> placed_pair(int n, Scalar gap, Random& rng) {
  const ConvexPolyhedron a = sphere_polytope(n, rng);
  const ConvexPolyhedron b = sphere_polytope(n, rng, 3 * rng.unit());
  const DistanceResult r = Query(with(Method::exact)).distance(a, b);
  const Vector3 along = (r.point_b - r.point_a).normalized();
  return {a, moved(b, -(r.distance - gap) * along)};
}

// Large bodies: hill climbing, the flood over the hull's graph for the supporting features, and
// the finish that grows them; every answer certified and agreeing with the exact method.
TEST(Dual, LargeBodiesAreCertifiedAndAgreeWithTheExactMethod) {
  Random rng(42);
  const Query dual(with(Method::dual));
  const Query exact(with(Method::exact));
  for (int n : {64, 512, 4096}) {
    for (Scalar gap : {1.0, 1e-2, 1e-4, -1e-4, -1e-2}) {
      if (n == 4096 && std::abs(gap) != 1e-2) continue;  // a hull of 4096 points takes a while
      const auto [a, b] = placed_pair(n, gap, rng);
      SCOPED_TRACE("n = " + std::to_string(n) + ", gap = " + std::to_string(gap));
      const DistanceResult r = dual.distance(a, b);
      const DistanceResult reference = exact.distance(a, b);
      const PairScale s = scale_of(a, b, kDefaultTolerance);
      EXPECT_TRUE(r.certified);
      EXPECT_EQ(r.status, SolverStatus::converged);
      EXPECT_EQ(r.colliding, gap < 0);
      EXPECT_EQ(r.colliding, reference.colliding);
      EXPECT_NEAR(r.distance, reference.distance, s.tolerance + s.rounding);
      EXPECT_LE(r.lower_bound, reference.distance + s.rounding);
      EXPECT_EQ(dual.collide(a, b), gap < 0);
    }
  }
}

// The signed distance of bodies too large for the oracle agrees with the exact method's.
// Wolfe's algorithm on the whole difference settles the pair before any swarm round, and a
// verdict stops at the first proof: no more support evaluations than the exact method's solve
// (plus the start's), where the supporting-feature finish used to run first and cost more.
TEST(Dual, TheStartSettlesPairsWithoutTheSwarm) {
  Random rng(7);
  const Query dual(with(Method::dual));
  const Query exact(with(Method::exact));
  for (int n : {8, 64, 512}) {
    for (Scalar gap : {1e-2, -1e-2}) {
      const auto [a, b] = placed_pair(n, gap, rng);
      SCOPED_TRACE("n = " + std::to_string(n) + ", gap = " + std::to_string(gap));
      const DistanceResult distance = dual.distance(a, b);
      const DistanceResult verdict = dual.collision(a, b);
      EXPECT_TRUE(distance.certified);
      EXPECT_TRUE(verdict.certified);
      EXPECT_EQ(verdict.colliding, gap < 0);
      EXPECT_EQ(distance.iterations, 0);
      EXPECT_EQ(verdict.iterations, 0);
      const long reference = exact.distance(a, b).evaluations;
      EXPECT_LE(distance.evaluations, reference + 2);
      EXPECT_LE(verdict.evaluations, reference + 2);
    }
  }
}

// Nesterov's momentum (NesterovDirection) carries the search across the zigzag of Wolfe's steps
// between faces: on pairs near contact whose bodies have more than 8 points, the distances and
// verdicts ask fewer oracle points than the exact method's Wolfe steps along the corral's point
// (without the momentum the distances asked as many), each answer certified and the exact
// method's.
TEST(Dual, MomentumAsksFewerPointsNearContact) {
  Random rng(5);
  const Query dual(with(Method::dual));
  const Query exact(with(Method::exact));
  long distance_points = 0;
  long verdict_points = 0;
  long exact_points = 0;
  for (int n : {16, 64, 256}) {
    for (Scalar gap : {1e-2, -1e-2}) {
      for (int k = 0; k < 8; ++k) {
        const auto [a, b] = placed_pair(n, gap, rng);
        SCOPED_TRACE("n = " + std::to_string(n) + ", gap = " + std::to_string(gap));
        const DistanceResult distance = dual.distance(a, b);
        const DistanceResult verdict = dual.collision(a, b);
        const DistanceResult reference = exact.distance(a, b);
        const PairScale s = scale_of(a, b, kDefaultTolerance);
        EXPECT_TRUE(distance.certified);
        EXPECT_TRUE(verdict.certified);
        EXPECT_EQ(verdict.colliding, gap < 0);
        EXPECT_NEAR(distance.distance, reference.distance, s.tolerance + s.rounding);
        EXPECT_LE(distance.lower_bound, reference.distance + s.rounding);
        distance_points += distance.evaluations;
        verdict_points += verdict.evaluations;
        exact_points += reference.evaluations;
      }
    }
  }
  // With the momentum 249 and 199 against 327; without it 327 and 245.
  EXPECT_LT(10 * distance_points, 9 * exact_points);
  EXPECT_LT(10 * verdict_points, 7 * exact_points);
}

// A signed distance of a pair apart along the centres' direction starts the distance search from
// that direction's oracle point, asked before it (overlap_first): the search's witnesses read
// that point's vertices, which its own oracle did not place. Two tetrahedra apex to apex along
// the line through their box centres have that very point as their nearest points: its witness
// settles the search at once, with no second oracle call (a witness off the bodies would not).
TEST(Dual, ASignedDistanceApartAtTheStartHasItsFirstPointAsWitnesses) {
  VertexMatrix points_a(4, 3);
  points_a << 1, 0, 0, -1, 1, 0, -1, -1, 1, -1, -1, -1;
  VertexMatrix points_b = points_a;
  points_b.col(0) = (3 - points_a.col(0).array()).matrix();
  const ConvexPolyhedron a(points_a);
  const ConvexPolyhedron b(points_b);
  const Query dual(with(Method::dual));
  for (const DistanceResult& r : {dual.signed_distance(a, b), dual.distance(a, b)}) {
    EXPECT_TRUE(r.certified);
    EXPECT_EQ(r.evaluations, 1);
    EXPECT_NEAR(r.distance, 1, 1e-12);
    EXPECT_NEAR((r.point_a - Vector3(1, 0, 0)).norm(), 0, 1e-12);
    EXPECT_NEAR((r.point_b - Vector3(2, 0, 0)).norm(), 0, 1e-12);
    EXPECT_EQ(r.weights_a.dense(), VectorX::Unit(4, 0));
    EXPECT_EQ(r.weights_b.dense(), VectorX::Unit(4, 0));
  }
}

// Overlaps within the frame's rounding (|gap| below 1e-12) as well: Wolfe's corral of four may
// hold the origin only up to rounding, and the expanding polytope's depth proves nothing; the
// answer is still certified, the pair colliding (within the tolerance), and the exact method's.
// Those pairs draw from a generator of their own, whose pair touching at 8 vertices gave a lower
// bound a rounding above the distance before finish_values capped it.
TEST(Dual, SignedDistancesAgreeWithTheExactMethod) {
  Random rng(7);
  Random touching_rng(11);
  const Query dual(with(Method::dual));
  const Query exact(with(Method::exact));
  for (int n : {8, 64}) {
    for (Scalar gap : {1e-2, -1e-4, -1e-2, -1e-1, -1e-13, -1e-15, 0.0}) {
      const auto [a, b] = placed_pair(n, gap, std::abs(gap) < 1e-12 ? touching_rng : rng);
      SCOPED_TRACE("n = " + std::to_string(n) + ", gap = " + std::to_string(gap));
      const DistanceResult r = dual.signed_distance(a, b);
      const DistanceResult reference = exact.signed_distance(a, b);
      const PairScale s = scale_of(a, b, kDefaultTolerance);
      EXPECT_TRUE(r.certified);
      EXPECT_LE(r.lower_bound, r.distance);
      EXPECT_NEAR(r.distance, reference.distance, s.tolerance + s.rounding);
      if (std::abs(gap) < 1e-12) {
        EXPECT_TRUE(r.colliding);
        continue;
      }
      EXPECT_EQ(r.method, Method::dual);
      // Overlaps far beyond the tolerance are proven by the expanding polytope's depth alone
      // (their witnesses are the depth apart).
      EXPECT_EQ(r.colliding, gap < 0);
      EXPECT_LE((r.point_b - r.point_a - r.distance * r.direction).norm(),
                r.distance - r.lower_bound + s.rounding);
    }
  }
}

// The swarm runs in rounds of at most max_iterations generations each, at most max_rounds of
// them, and stops as soon as the answer is certified.
TEST(Dual, RoundsBoundTheIterations) {
  Random rng(3);
  const auto [a, b] = placed_pair(64, 1e-3, rng);
  for (int rounds : {1, 3}) {
    for (int iterations : {0, 5}) {
      QueryOptions options = with(Method::dual);
      options.dual.max_rounds = rounds;
      options.dual.max_iterations = iterations;
      options.tolerance = 0;  // never certified: every round runs
      const DistanceResult r = Query(options).distance(a, b);
      EXPECT_LE(r.iterations, rounds * iterations);
      EXPECT_EQ(r.history.size(), static_cast<std::size_t>(r.iterations) + 1);
      for (std::size_t k = 1; k < r.history.size(); ++k) {
        EXPECT_LE(r.history[k], r.history[k - 1]);
      }
    }
  }
  const DistanceResult quick = Query(with(Method::dual)).distance(a, b);
  EXPECT_TRUE(quick.certified);
  EXPECT_LT(quick.iterations, QueryOptions{}.dual.max_rounds * QueryOptions{}.dual.max_iterations);
}

// The finish's feature slack trades subproblem size for how early the optimal features are
// found; the answer is certified either way.
TEST(Dual, AnyFeatureToleranceGivesACertifiedAnswer) {
  Random rng(5);
  const auto [a, b] = placed_pair(64, 1e-3, rng);
  const Scalar exact = Query(with(Method::exact)).distance(a, b).distance;
  for (Scalar slack : {0.0, 1e-6, 1e-1}) {
    QueryOptions options = with(Method::dual);
    options.dual.feature_tolerance = slack;
    const DistanceResult r = Query(options).distance(a, b);
    EXPECT_TRUE(r.certified) << slack;
    EXPECT_NEAR(r.distance, exact, 1e-8) << slack;
  }
}

// A signed distance's witnesses lie along its normal, `point_b - point_a = distance * direction`,
// at any tolerance: apart, the normal must then be the witnesses' direction, not merely a
// direction whose separation is within the tolerance (a few degrees off at 1e-3).
TEST(Dual, SignedWitnessesLieAlongTheNormalAtAnyTolerance) {
  Random rng(10);
  for (Scalar tolerance : {1e-3, 1e-6}) {
    QueryOptions options = with(Method::dual);
    options.tolerance = tolerance;
    const Query query(options);
    for (int trial = 0; trial < 30; ++trial) {
      SCOPED_TRACE("tolerance " + std::to_string(tolerance) + ", trial " + std::to_string(trial));
      const ConvexPolyhedron a = rng.body(1 + trial % 8);
      const ConvexPolyhedron b = rng.body(1 + (trial * 3) % 8, {2.5, 0, 0});
      const DistanceResult r = query.signed_distance(a, b);
      const PairScale s = scale_of(a, b, tolerance);
      EXPECT_LE((r.point_b - r.point_a - r.distance * r.direction).norm(),
                r.distance - r.lower_bound + s.rounding + s.point_rounding);
    }
  }
}

// The signed distance's proven bounds hold the brute-force one (the oracle's hull of every
// difference of points) on overlapping, touching, flat and apart pairs, placed by rotations and
// translations, at scales 2^-997 and 2^996 (about 1e-300 and 1e300) as at 1: the intersection
// proof, the expanding polytope's verified surface, its witnesses from the last face (along the
// normal at the reported distance) and the scans that measure the normal. Scales are powers of
// two, so the oracle of the unscaled pair, scaled, is the truth.
TEST(Dual, SignedDistanceBoundsHoldTheBruteForceOneAtEveryScale) {
  Random rng(2611);
  struct Case {
    std::string name;
    ConvexPolyhedron a;
    ConvexPolyhedron b;
  };
  std::vector<Case> cases;
  for (int n : {4, 8, 24}) {
    for (Scalar offset : {0.1, 0.6, 1.2, 1.8, 2.6}) {
      const ConvexPolyhedron a = rng.body(n);
      cases.push_back({"clouds of " + std::to_string(n) + " at " + std::to_string(offset), a,
                       rng.body(n, offset * rng.unit())});
    }
  }
  const ConvexPolyhedron cube = unit_cube();
  cases.push_back({"stacked boxes touching", cube, box({0.3, 0.2, 1}, {1.3, 1.2, 2})});
  cases.push_back({"stacked boxes 1e-12 deep", cube, box({0.3, 0.2, 1 - 1e-12}, {1.3, 1.2, 2})});
  cases.push_back({"square across the cube", cube,
                   point_set({{-0.5, -0.5, 0.3}, {1.5, -0.5, 0.3}, {1.5, 1.5, 0.3},
                              {-0.5, 1.5, 0.3}})});
  cases.push_back({"needle through the cube", cube,
                   point_set({{0.4, 0.45, -1}, {0.45, 0.4, 2}})});
  const Query dual(with(Method::dual));
  for (const Case& c : cases) {
    for (int placed = 0; placed < 2; ++placed) {
      Pose pose_a;
      Pose pose_b;
      if (placed) {
        pose_a.rotation = rng.rotation();
        pose_b.rotation = pose_a.rotation;
        pose_a.translation = rng.vector();
        pose_b.translation = pose_a.translation;
      }
      // The world points the oracle reads: A and B under the same rigid motion keep their sd.
      const Scalar truth = oracle_signed_distance(c.a.vertices(), c.b.vertices());
      for (int exponent : {0, -997, 996}) {
        SCOPED_TRACE(c.name + (placed ? ", placed" : "") + ", scale 2^" +
                     std::to_string(exponent));
        const Scalar scale = std::ldexp(Scalar(1), exponent);
        const ConvexPolyhedron a = transformed(c.a, scale, Vector3::Zero());
        const ConvexPolyhedron b = transformed(c.b, scale, Vector3::Zero());
        Pose scaled_a = pose_a;
        Pose scaled_b = pose_b;
        scaled_a.translation *= scale;
        scaled_b.translation *= scale;
        const DistanceResult r = dual.signed_distance(a, scaled_a, b, scaled_b);
        const PairScale s = scale_of(a, b, kDefaultTolerance);
        EXPECT_LE(r.lower_bound, scale * truth + s.rounding);
        EXPECT_GE(r.distance, scale * truth - s.rounding);
        EXPECT_TRUE(r.certified) << "gap " << r.distance - r.lower_bound;
        EXPECT_LE(r.distance - r.lower_bound, s.tolerance + s.rounding);
        // Measured at unit scale, where the squares of the norm do not overflow.
        const Vector3 off = (r.point_b - r.point_a - r.distance * r.direction) / scale;
        EXPECT_LE(off.norm(), (r.distance - r.lower_bound + s.rounding + s.point_rounding) / scale);
        if (truth < -1e-9) EXPECT_TRUE(r.colliding);
        if (truth > 1e-9) EXPECT_FALSE(r.colliding);
      }
    }
  }
}

TEST(Dual, TheSameSeedGivesTheSameAnswer) {
  Random rng(11);
  const auto [a, b] = placed_pair(64, -1e-3, rng);
  QueryOptions options = with(Method::dual);
  options.seed = 11;
  const Query query(options);
  expect_identical(query.distance(a, b), query.distance(a, b));
  expect_identical(query.signed_distance(a, b), query.signed_distance(a, b));
}

}  // namespace
}  // namespace swarmcollide::testing
