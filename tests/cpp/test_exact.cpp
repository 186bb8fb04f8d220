// The exact methods: "exact" (Wolfe's algorithm and the certified depth), "fcl" (FCL's GJK,
// checked) and "libccd" (libccd's GJK and EPA, checked), and what each hands to "exact".
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "contract.hpp"
#include "hard_cases.hpp"
#include "oracle.hpp"
#include "paper_cases.hpp"
#include "queries/verdict.hpp"
#include "shapes.hpp"
#include "solvers/exact_solver.hpp"

namespace swarmcollide::testing {
namespace {

Query query_of(Method method, int max_iterations = ExactOptions{}.max_iterations) {
  QueryOptions options;
  options.method = method;
  options.exact.max_iterations = max_iterations;
  options.dual.max_iterations = max_iterations;
  return Query(options);
}

// Wolfe's algorithm stops at a gap of 1e-14 of the pair's size whatever the query's tolerance,
// so its distances are exact to rounding: far better than the tolerance the contract asks for.
TEST(Exact, DistancesOfTheHardCasesAreExactToRounding) {
  const Query exact = query_of(Method::exact);
  for (const HardCase& c : hard_cases()) {
    SCOPED_TRACE(c.name);
    const PairScale s = scale_of(c.a, c.b, kDefaultTolerance);
    EXPECT_NEAR(exact.distance(c.a, c.b).distance, c.distance, c.accuracy + 1e-13 * s.size);
    EXPECT_NEAR(exact.distance(c.b, c.a).distance, c.distance, c.accuracy + 1e-13 * s.size);
  }
}

// Bodies of more than 32 points are searched by hill climbing over their hulls; the answers are
// those of the oracle, and so is the depth, whose enumeration of edge pairs is still complete
// for 64 points.
TEST(Exact, LargeBodiesMatchTheOracle) {
  Random rng(17);
  for (const Method m : {Method::exact, Method::fcl, Method::libccd}) {
    const Query query = query_of(m);
    for (int trial = 0; trial < 4; ++trial) {
      SCOPED_TRACE(std::string(method_name(m)) + ", trial " + std::to_string(trial));
      const ConvexPolyhedron a = rng.body(64);
      const ConvexPolyhedron b = rng.body(64, trial % 2 ? Vector3(2.3, 0.2, 0) : rng.vector());
      const Reference truth = reference(a, b);
      const PairScale s = scale_of(a, b, kDefaultTolerance);
      if (method_info(m).capabilities & kDistance) {
        const DistanceResult r = query.distance(a, b);
        expect_contract(a, b, QueryKind::distance, m, r, truth, s);
        EXPECT_NEAR(r.distance, truth.distance, s.tolerance + s.rounding);
      }
      const DistanceResult r = query.signed_distance(a, b);
      expect_contract(a, b, QueryKind::signed_distance, m, r, truth, s);
      EXPECT_NEAR(r.distance, truth.signed_distance, s.tolerance + s.rounding);
    }
  }
}

// A pair stepping along a path, each distance started from the last one's corral with its points'
// support indices read again at the new poses (the robot motion check's queries after a pair's
// first): any start leaves the bounds proven, as they come from the supports along the direction
// Wolfe's algorithm ends with. Every answer brackets the oracle's distance, certified, within
// the tolerance of the answer started afresh, on bodies scanned (8 points) and climbed (64).
TEST(Exact, AStartFromTheLastPosesCorralProvesTheDistance) {
  Random rng(29);
  for (const int points : {8, 64}) {
    const ConvexPolyhedron a = rng.body(points);
    const ConvexPolyhedron b = rng.body(points);
    const Matrix3 turn = Eigen::AngleAxis<Scalar>(0.05, rng.unit()).toRotationMatrix();
    Pose pose_b = at(Vector3(3.5, 0.3, -0.2), rng.rotation());
    detail::MinNormPoint corral;
    int warm = 0;
    for (int step = 0; step < 40; ++step) {
      SCOPED_TRACE(std::to_string(points) + " points, step " + std::to_string(step));
      // Towards A and about it, so the nearest features change along the path.
      pose_b.translation = turn * pose_b.translation * 0.99;
      pose_b.rotation = turn * pose_b.rotation;
      const detail::FramedPair framed =
          detail::frame_pair(a, Pose{}, b, pose_b, kDefaultTolerance);
      const DistanceResult fresh = detail::finish_result(
          framed, detail::exact_distance(framed, 100, Vector3::Zero()), Method::exact,
          detail::Goal::distance, detail::Weights::none);
      warm += corral.size > 0;
      detail::Answer answer = detail::exact_distance_again(framed, 100, corral);
      const DistanceResult r = detail::finish_result(framed, std::move(answer), Method::exact,
                                                     detail::Goal::distance,
                                                     detail::Weights::none);
      VertexMatrix placed = (b.vertices() * pose_b.rotation.transpose()).eval();
      placed.rowwise() += pose_b.translation.transpose();
      const Reference truth = reference(a, ConvexPolyhedron(placed));
      const PairScale s = scale_of(a, ConvexPolyhedron(placed), kDefaultTolerance);
      EXPECT_TRUE(r.certified);
      EXPECT_LE(r.lower_bound, truth.distance + s.rounding);
      EXPECT_GE(r.distance, truth.distance - s.rounding);
      EXPECT_NEAR(r.distance, fresh.distance, s.tolerance + s.rounding);
    }
    EXPECT_GT(warm, 30);
  }
}

// Two roofs ridge to ridge, a hair apart along parallel ridges: the nearest point of B - A lies
// inside a segment (the ridges' difference), whose normals span a cone as narrow as the roofs'
// slopes, and the direction of a nearest point 1e-15..1e-12 from the origin is off by far more
// than that (the rounding of points of norm 1 over its norm). The plane through the segment and
// the lowest point along its normal proves the signed distance to rounding; before it, these
// pairs went to the expanding polytope and the candidate axes (40 times a distance's cost) and
// came back with lower bounds as far as 6e-11 below the distance.
TEST(ExactMethods, ParallelRidgesAHairApartAreProvenToRoundingByTheirSegment) {
  Random rng(23);
  for (int trial = 0; trial < 40; ++trial) {
    const Scalar slope = std::pow(10.0, rng.uniform(-5, -1));
    VertexMatrix roof(10, 3);
    roof << 0, -1, 0, 0, 1, 0, 1, -1, -slope, 1, 1, -slope, -1, -1, -slope, -1, 1, -slope,
        1, -1, -1, 1, 1, -1, -1, -1, -1, -1, 1, -1;
    VertexMatrix upside_down = roof;
    upside_down.col(2) *= -1;
    const ConvexPolyhedron a(roof), b(upside_down);
    const Scalar gap = std::pow(10.0, rng.uniform(-15, -12));
    Pose pose_a;
    pose_a.rotation = rng.rotation();
    Pose pose_b = pose_a;
    pose_b.translation = pose_a.rotation * Vector3(0, rng.uniform(-0.5, 0.5), gap);
    const Scalar size = 2 * std::sqrt(3.0);  // at most: both lie in a ball of radius sqrt(3)
    for (const Method m : {Method::exact, Method::dual}) {
      SCOPED_TRACE(std::string(method_name(m)) + ", trial " + std::to_string(trial) +
                   ", slope " + std::to_string(slope) + ", gap " + std::to_string(gap));
      const DistanceResult r = query_of(m).signed_distance(a, pose_a, b, pose_b);
      ASSERT_TRUE(r.certified);
      EXPECT_NEAR(r.distance, gap, 1e-14 * size);
      // Both bounds to rounding: each is a separation or a distance measured in the frame.
      EXPECT_LE(std::abs(r.lower_bound - r.distance), 1e-14 * size);
    }
  }
}

// FCL's GJK answers separated pairs itself, and touching ones when its simplex encloses the origin
// (the paper's colliding pair); every penetration depth goes to "exact", which names it.
TEST(Fcl, HandsWhatItCannotProveToExact) {
  const Query fcl = query_of(Method::fcl);
  const DistanceResult apart = fcl.distance(paper_a(), paper_b_separate());
  EXPECT_EQ(apart.method, Method::fcl);
  EXPECT_FALSE(apart.escalated_from.has_value());
  EXPECT_TRUE(apart.certified);
  const DistanceResult touching = fcl.distance(paper_a(), paper_b_colliding());
  EXPECT_EQ(touching.method, Method::fcl);
  EXPECT_FALSE(touching.escalated_from.has_value());
  EXPECT_TRUE(touching.certified && touching.colliding);
  const DistanceResult depth =
      fcl.signed_distance(unit_cube(), moved(unit_cube(), {0.5, 0.25, 0.125}));
  EXPECT_EQ(depth.method, Method::exact);
  EXPECT_EQ(depth.escalated_from, Method::fcl);
  EXPECT_NEAR(depth.distance, -0.5, 1e-12);
}

// A distance whose witnesses come within the tolerance is proven to it by them alone: FCL's
// answer stands without the enclosure test or the separation's scans, its lower bound the zero
// every distance has, whether the cubes overlap, touch or lie apart by less than the tolerance.
TEST(Fcl, ADistanceWithinTheToleranceStandsOnItsWitnesses) {
  const Query fcl = query_of(Method::fcl);
  const ConvexPolyhedron a = unit_cube();
  for (const Scalar offset : {0.999, 1.0, 1.0 + 1e-9}) {
    SCOPED_TRACE(offset);
    const ConvexPolyhedron b = moved(unit_cube(), {offset, 0.25, 0.125});
    const PairScale s = scale_of(a, b, kDefaultTolerance);
    const DistanceResult r = fcl.distance(a, b);
    expect_contract(a, b, QueryKind::distance, Method::fcl, r, reference(a, b), s);
    EXPECT_EQ(r.method, Method::fcl);
    EXPECT_TRUE(r.certified && r.colliding);
    EXPECT_LE(r.distance, s.tolerance);
    EXPECT_EQ(r.lower_bound, 0);
  }
}

// At a zero tolerance no witnesses prove contact: a collision verdict on overlapping bodies stands
// on FCL's final simplex alone, a tetrahedron whose Minkowski points (placed only for this test)
// enclose the origin, with no escalation to "exact".
TEST(Fcl, ItsEnclosingSimplexProvesAnOverlap) {
  QueryOptions options;
  options.method = Method::fcl;
  options.tolerance = 0;
  const Query fcl(options);
  const ConvexPolyhedron a = unit_cube();
  const ConvexPolyhedron b = moved(unit_cube(), {0.5, 0.25, 0.125});
  const DistanceResult r = fcl.collision(a, b);
  expect_contract(a, b, QueryKind::collide, Method::fcl, r, reference(a, b), scale_of(a, b, 0));
  EXPECT_EQ(r.method, Method::fcl);
  EXPECT_FALSE(r.escalated_from.has_value());
  EXPECT_TRUE(r.certified && r.colliding);
}

// A verdict runs FCL's GJK at fcl::collide's own tolerance (1e-6 in the frame), far coarser than
// ours: on faces 1e-5 to 1e-8 apart (which that GJK may call touching below 1e-6), within our
// tolerance and overlapping, under random turns, the verdict is certified and the exact method's.
TEST(Fcl, AVerdictNearContactIsTheExactMethods) {
  Random rng(52);
  const Query fcl = query_of(Method::fcl);
  const Query exact = query_of(Method::exact);
  const ConvexPolyhedron cube = unit_cube();
  for (int trial = 0; trial < 20; ++trial) {
    const Matrix3 turn = rng.rotation();
    for (const Scalar gap : {1e-5, 1e-6, 1e-7, 1e-8, 1e-11, -1e-8, -1e-6}) {
      SCOPED_TRACE("trial " + std::to_string(trial) + ", gap " + std::to_string(gap));
      const Pose pose_a{turn, Vector3::Zero()};
      const Pose pose_b{turn, turn * Vector3(1 + gap, rng.uniform(-0.5, 0.5),
                                             rng.uniform(-0.5, 0.5))};
      const DistanceResult f = fcl.collision(cube, pose_a, cube, pose_b);
      const DistanceResult e = exact.collision(cube, pose_a, cube, pose_b);
      ASSERT_TRUE(f.certified);
      ASSERT_TRUE(e.certified);
      EXPECT_EQ(f.colliding, gap < 1e-9);
      EXPECT_EQ(e.colliding, gap < 1e-9);
      EXPECT_EQ(fcl.collide(cube, pose_a, cube, pose_b), gap < 1e-9);
    }
  }
}

// libccd's EPA depth stands when the certificate proves it.
TEST(Libccd, ItsDepthStandsWhenProven) {
  const DistanceResult r =
      query_of(Method::libccd).signed_distance(unit_cube(), moved(unit_cube(), {0.5, 0.25, 0.125}));
  EXPECT_EQ(r.method, Method::libccd);
  EXPECT_TRUE(r.certified);
  EXPECT_NEAR(r.distance, -0.5, 1e-12);
  EXPECT_NEAR((r.direction - Vector3::UnitX()).norm(), 0, 1e-12);
}

// However small the iteration cap, the bounds hold (the contract) and a deep overlap is never
// called apart: an unfinished search has found no separating direction.
TEST(ExactMethods, SmallIterationCapsNeverCallADeepOverlapApart) {
  const ConvexPolyhedron a = unit_cube();
  const ConvexPolyhedron b = moved(unit_cube(), {0.5, 0.25, 0.125});
  const Reference truth = reference(a, b);
  const PairScale s = scale_of(a, b, kDefaultTolerance);
  for (const Method m : {Method::exact, Method::fcl, Method::libccd, Method::dual}) {
    for (int cap : {1, 2, 3}) {
      SCOPED_TRACE(std::string(method_name(m)) + ", max_iterations " + std::to_string(cap));
      const Query query = query_of(m, cap);
      const DistanceResult r = query.collision(a, b);
      expect_contract(a, b, QueryKind::collide, m, r, truth, s, /*budget_capped=*/true);
      EXPECT_TRUE(r.colliding);
      EXPECT_TRUE(query.collide(a, b));
    }
  }
}

}  // namespace
}  // namespace swarmcollide::testing
