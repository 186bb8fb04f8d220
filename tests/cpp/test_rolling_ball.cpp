// Depths proven by balls that roll inside curved bodies (SupportFunction::rolling_radius,
// solvers/rolling_ball.hpp): the ball an ellipsoid promises lies inside it (and a slightly larger
// one does not), and the penetration solver's bounds from it bracket the depth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/framed_body.hpp"
#include "separation_search.hpp"
#include "shapes.hpp"
#include "solvers/minkowski.hpp"
#include "solvers/penetration.hpp"
#include "swarmcollide/geometry/shapes.hpp"
#include "swarmcollide/solvers/exact_options.hpp"

namespace swarmcollide::testing {
namespace {

constexpr Scalar kU = 0x1p-53;

// The largest |y / radii|^2 over `count` points y on the sphere of radius `radius` about
// `centre`, and the points on its axes.
Scalar largest_on_sphere(const Vector3& radii, const Vector3& centre, Scalar radius, Random& rng,
                         int count) {
  Scalar largest = 0;
  const auto f = [&](const Vector3& w) {
    largest = std::max(largest, (centre + radius * w).cwiseQuotient(radii).squaredNorm());
  };
  for (int k = 0; k < 3; ++k) {
    f(Vector3::Unit(k));
    f(-Vector3::Unit(k));
  }
  for (int i = 0; i < count; ++i) f(rng.unit());
  return largest;
}

TEST(RollingBall, TheEllipsoidsBallLiesInsideItAndALargerOneDoesNot) {
  Random rng(37);
  for (const Vector3& radii : {Vector3(0.3, 0.8, 0.5), Vector3(1, 1, 1), Vector3(0.2, 1, 0.9),
                               Vector3(1e-3, 1, 0.5), Vector3(3e5, 2e5, 1e5)}) {
    SCOPED_TRACE(::testing::Message() << radii.transpose());
    const Ellipsoid ellipsoid(radii);
    const SupportFunction& shape = *ellipsoid.curved();
    const Scalar rho = shape.rolling_radius();
    EXPECT_NEAR(rho, radii.minCoeff() * radii.minCoeff() / radii.maxCoeff(), 1e-12 * rho);
    // The promise: the ball of radius rho less the support point's rounding about
    // support(d) - rho d/|d| lies in the ellipsoid (to the rounding of this check).
    const Scalar error = shape.support_error_roundoffs() * kU * shape.outer_radius();
    Scalar worst = 0;
    for (int trial = 0; trial < 300; ++trial) {
      const Vector3 d = rng.unit() * std::pow(10.0, rng.uniform(-3, 3));
      const Vector3 centre = shape.support(d) - rho * d.normalized();
      worst = std::max(worst, largest_on_sphere(radii, centre, rho - error, rng, 200));
    }
    EXPECT_LE(worst, 1 + 1e-14);
    // Tight: along the longest axis the surface is curved by 1 / rho across the shortest, and a
    // ball 1% larger, tangent there, pokes out (unless every radius of curvature is equal).
    if (radii.maxCoeff() > radii.minCoeff()) {
      Eigen::Index longest = 0;
      radii.maxCoeff(&longest);
      const Vector3 d = Vector3::Unit(longest);
      const Scalar larger = 1.01 * rho;
      const Vector3 centre = shape.support(d) - larger * d;
      EXPECT_GT(largest_on_sphere(radii, centre, larger, rng, 20000), 1 + 1e-11);
    }
  }
}

// A rolling balls' proof `r` of the pair: the best separation a search of directions around its
// normal finds is a lower bound on sd, so at most the proven upper bound (a ball claimed too large
// would put it below); the witnesses lie in the bodies (A's, the ellipsoid of `radii_a`, in the
// frame's placement of it) and `upper * normal` apart to the gap.
void expect_rolling_proof_brackets_the_depth(const detail::FramedPair& pair,
                                             const detail::PenetrationBounds& r,
                                             const Vector3& radii_a, Random& rng) {
  // (The computed separations may exceed the true ones by the support points' shortfall.)
  EXPECT_LE(best_separation_near(pair, r.normal, 0.1, 1e-7, rng), r.upper + 1e-13);
  EXPECT_LE((r.point_b - r.point_a - r.upper * r.normal).norm(), r.upper - r.lower + 1e-14);
  const Vector3 local_a = pair.a.rotation().transpose() * (r.point_a - pair.a.offset()) *
                          std::ldexp(1.0, pair.a.exponent());
  EXPECT_LE(local_a.cwiseQuotient(radii_a).norm(), 1 + 1e-12);
}

Vector3 random_radii(Random& rng) {
  return Vector3(rng.uniform(0.2, 1), rng.uniform(0.2, 1), rng.uniform(0.2, 1));
}

// `a` within 0.2 of the origin and `b` within 0.8, turned at random, framed to a tolerance of
// 1e-9.
detail::FramedPair random_poses(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                Random& rng) {
  const Pose pa = at(rng.vector(0.2), rng.rotation());
  const Pose pb = at(rng.vector(0.8), rng.rotation());
  return detail::frame_pair(a, pa, b, pb, 1e-9);
}

detail::PenetrationBounds solve(const detail::FramedPair& pair) {
  return detail::penetration(pair.a, pair.b, pair.b.offset() - pair.a.offset(), nullptr,
                             pair.tolerance, ExactOptions().max_iterations);
}

// Overlapping pairs with an ellipsoid, drawn as bench/curved_coal.py draws them: the shallow ones
// (most) are proven by the rolling balls, and their bounds bracket the depth that a dense search
// of directions finds (sd >= the separation along any direction); the witnesses lie in the bodies
// and along the normal.
TEST(RollingBall, ShallowOverlapsAreProvenAndBracketTheDepth) {
  Random rng(26);
  int rolled = 0;
  int pairs = 0;
  for (int trial = 0; trial < 400 && pairs < 120; ++trial) {
    const Vector3 radii_a = random_radii(rng);
    const Vector3 radii_b = random_radii(rng);
    const Ellipsoid a(radii_a);
    const Box box(radii_b);
    const Ellipsoid ellipsoid_b(radii_b);
    const Cylinder cylinder(radii_b.x(), radii_b.y());
    const ConvexPolyhedron& b =
        trial % 3 == 0 ? static_cast<const ConvexPolyhedron&>(ellipsoid_b)
                       : trial % 3 == 1 ? static_cast<const ConvexPolyhedron&>(box)
                                        : static_cast<const ConvexPolyhedron&>(cylinder);
    const detail::FramedPair pair = random_poses(a, b, rng);
    const detail::PenetrationBounds r = solve(pair);
    if (!(r.upper < 0)) continue;  // apart or touching
    ++pairs;
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " proof "
                                      << static_cast<int>(r.proof));
    EXPECT_TRUE(r.proven);
    EXPECT_LE(r.upper - r.lower, pair.tolerance);
    if (r.proof != detail::PenetrationProof::rolling_ball) continue;
    ++rolled;
    expect_rolling_proof_brackets_the_depth(pair, r, radii_a, rng);
  }
  EXPECT_GT(pairs, 60);
  // Many are the rolling balls' (the rest: deeper than the balls, or a box's points that the
  // ellipsoid's closed form proves inside it).
  EXPECT_GT(rolled, pairs / 4);
}

// Two ellipsoids both roll, and the search on the difference of their balls' centres asks along
// secant directions (rolling_ball.cpp): the proofs hold as the plain search's, and take few
// steps (on these pairs 8.9 on average; the plain search took 22.4).
TEST(RollingBall, TwoEllipsoidsSecantSearchProvesInFewSteps) {
  Random rng(29);
  long iterations = 0;
  int rolled = 0;
  for (int trial = 0; rolled < 40 && trial < 200; ++trial) {
    const Ellipsoid a(random_radii(rng));
    const Ellipsoid b(random_radii(rng));
    const detail::FramedPair pair = random_poses(a, b, rng);
    const detail::PenetrationBounds r = solve(pair);
    if (!(r.upper < 0) || r.proof != detail::PenetrationProof::rolling_ball) continue;
    ++rolled;
    SCOPED_TRACE(::testing::Message() << "trial " << trial);
    EXPECT_TRUE(r.proven);
    EXPECT_LE(r.upper - r.lower, pair.tolerance);
    expect_rolling_proof_brackets_the_depth(pair, r, a.radii(), rng);
    iterations += r.iterations;
  }
  EXPECT_GE(rolled, 20);
  EXPECT_LE(iterations, 12 * rolled) << iterations / static_cast<double>(rolled);
}

}  // namespace
}  // namespace swarmcollide::testing
