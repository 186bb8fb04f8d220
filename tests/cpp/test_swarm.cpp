// The primal swarms ("ipso", "pso"): the paper's coefficients (7)-(9), Step 3's stopping test,
// seeds, the constraint handlings, and collide's escalation of their unproven verdicts.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "contract.hpp"
#include "oracle.hpp"
#include "paper_cases.hpp"
#include "shapes.hpp"
#include "swarmcollide/solvers/swarm.hpp"

namespace swarmcollide::testing {
namespace {

QueryOptions swarm(Method method, ConstraintHandling handling = ConstraintHandling::projection) {
  QueryOptions options;
  options.method = method;
  options.swarm.constraint_handling = handling;
  return options;
}

// The history records the best upper bound after initialisation and after every iteration.
void expect_history(const DistanceResult& r) {
  ASSERT_EQ(r.history.size(), static_cast<std::size_t>(r.iterations) + 1);
  for (std::size_t i = 1; i < r.history.size(); ++i) EXPECT_LE(r.history[i], r.history[i - 1]);
  EXPECT_EQ(r.history.back(), r.distance);
}

TEST(RankAdaptiveCoefficients, FollowEquations8And9) {
  const ParticleCoefficients best = rank_adaptive_coefficients(1, 40, 0.4, 0.9);
  EXPECT_DOUBLE_EQ(best.w, 0.9);
  EXPECT_DOUBLE_EQ(best.c1, (0.9 + 1 + 2 * std::sqrt(0.9)) / 2);
  EXPECT_DOUBLE_EQ(best.c2, best.c1);
  const ParticleCoefficients worst = rank_adaptive_coefficients(40, 40, 0.4, 0.9);
  EXPECT_DOUBLE_EQ(worst.w, 0.4);
  EXPECT_DOUBLE_EQ(worst.c1, (0.4 + 1 + 2 * std::sqrt(0.4)) / 2);
  EXPECT_DOUBLE_EQ(rank_adaptive_coefficients(21, 41, 0.4, 0.9).w, 0.65);
  EXPECT_THROW(rank_adaptive_coefficients(0, 40, 0.4, 0.9), std::invalid_argument);
  EXPECT_THROW(rank_adaptive_coefficients(41, 40, 0.4, 0.9), std::invalid_argument);
}

TEST(LinearDecreasingInertia, FollowsEquation7) {
  EXPECT_DOUBLE_EQ(linear_decreasing_inertia(0, 200, 0.9, 0.4), 0.9);
  EXPECT_DOUBLE_EQ(linear_decreasing_inertia(100, 200, 0.9, 0.4), 0.65);
  EXPECT_DOUBLE_EQ(linear_decreasing_inertia(200, 200, 0.9, 0.4), 0.4);
}

class Swarm : public ::testing::TestWithParam<Method> {};

// Step 3's precision is the query's tolerance: zero runs the whole budget, with one evaluation
// per particle per generation (the initial one included), even once the bounds have met.
TEST_P(Swarm, ZeroToleranceRunsTheWholeBudget) {
  QueryOptions options = swarm(GetParam());
  options.tolerance = 0;
  options.swarm.max_iterations = 50;
  options.swarm.swarm_size = 24;
  const DistanceResult r = Query(options).distance(paper_a(), paper_b_separate());
  EXPECT_EQ(r.iterations, 50);
  EXPECT_EQ(r.evaluations, 24L * 51);
  expect_history(r);
}

// At the default tolerance the paper's pairs stop within a few generations, the separate pair at
// the paper's optimum x2 - y1 (Table 2); a verdict stops as soon as a bound proves it, which is
// never later than the distance.
TEST_P(Swarm, StopsOnceTheBoundsMeetTheTolerance) {
  const Query query(swarm(GetParam()));
  for (const ConvexPolyhedron& b : {paper_b_colliding(), paper_b_separate()}) {
    const DistanceResult r = query.distance(paper_a(), b);
    EXPECT_EQ(r.status, SolverStatus::converged);
    EXPECT_LT(r.iterations, QueryOptions{}.swarm.max_iterations);
    expect_history(r);
    EXPECT_LE(query.collision(paper_a(), b, /*escalate=*/false).iterations, r.iterations);
  }
  const DistanceResult apart = query.distance(paper_a(), paper_b_separate());
  EXPECT_NEAR(apart.weights_a.dense()(1), 1, 1e-9);
  EXPECT_NEAR(apart.weights_b.dense()(0), 1, 1e-9);
}

TEST_P(Swarm, TheSeedDecidesThePath) {
  for (ConstraintHandling handling :
       {ConstraintHandling::projection, ConstraintHandling::feasibility}) {
    QueryOptions options = swarm(GetParam(), handling);
    options.tolerance = 0;
    options.swarm.max_iterations = 30;
    Random rng(7);
    const ConvexPolyhedron b = rng.body(6, {2, 0, 0});
    options.seed = 42;
    const DistanceResult first = Query(options).distance(paper_a(), b);
    expect_identical(first, Query(options).distance(paper_a(), b));
    options.seed = 43;
    EXPECT_NE(Query(options).distance(paper_a(), b).history, first.history);
  }
}

// The paper's rules (Conditions 1-3) leave particles off the simplexes; the answer is still
// moved onto them, so the contract holds however far from converged.
TEST_P(Swarm, ThePapersRulesKeepTheContract) {
  Random rng(13);
  for (int budget : {0, 5, 200}) {
    QueryOptions options = swarm(GetParam(), ConstraintHandling::feasibility);
    options.swarm.max_iterations = budget;
    const Query query(options);
    for (const auto& [a, b] :
         {std::pair{paper_a(), paper_b_colliding()}, std::pair{paper_a(), paper_b_separate()},
          std::pair{rng.body(7), rng.body(5, {1.5, 0.5, 0})}}) {
      SCOPED_TRACE("budget " + std::to_string(budget));
      const DistanceResult r = query.distance(a, b);
      expect_contract(a, b, QueryKind::distance, GetParam(), r, reference(a, b),
                      scale_of(a, b, options.tolerance));
      expect_history(r);
    }
  }
}

// A swarm without iterations can neither prove that bodies 1e-10 apart are within the
// tolerance (3.5e-9 here) nor that they are not: collide hands the verdict to "exact", which
// names the swarm; without escalation the swarm's unproven guess is returned.
TEST_P(Swarm, CollideEscalatesAnUnprovenVerdict) {
  VertexMatrix near(4, 3);
  near << 1, -1e-10, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0;
  const ConvexPolyhedron b(near);
  QueryOptions options = swarm(GetParam());
  options.swarm.max_iterations = 0;
  const Query query(options);
  const DistanceResult own = query.collision(paper_a(), b, /*escalate=*/false);
  EXPECT_FALSE(own.certified);
  EXPECT_EQ(own.method, GetParam());
  EXPECT_FALSE(own.escalated_from.has_value());
  const DistanceResult decided = query.collision(paper_a(), b);
  EXPECT_EQ(decided.method, Method::exact);
  EXPECT_EQ(decided.escalated_from, GetParam());
  EXPECT_TRUE(decided.certified);
  EXPECT_TRUE(decided.colliding);
  EXPECT_TRUE(query.collide(paper_a(), b));
  EXPECT_EQ(query.collide(paper_a(), b, /*escalate=*/false), own.colliding);
}

TEST_P(Swarm, ASwarmTooLargeToHoldIsRefused) {
  Random rng(1);
  const ConvexPolyhedron a = rng.body(400);
  const ConvexPolyhedron b = rng.body(400, {3, 0, 0});
  QueryOptions options = swarm(GetParam());
  options.swarm.swarm_size = 100000;  // 8e7 weights, over the 2^26 limit
  try {
    Query(options).distance(a, b);
    ADD_FAILURE() << "a swarm of 8e7 weights was run";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("use fewer particles"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, Swarm, ::testing::Values(Method::ipso, Method::pso),
                         [](const auto& info) { return std::string(method_name(info.param)); });

// "pso" reads its own acceleration coefficients; "ipso" derives them from the rank (9).
TEST(Swarm, PsoReadsItsAccelerationCoefficients) {
  Random rng(9);
  const ConvexPolyhedron a = rng.body(7);
  const ConvexPolyhedron b = rng.body(6, {2, 0, 0});
  QueryOptions options = swarm(Method::pso);
  options.tolerance = 0;
  options.swarm.max_iterations = 10;
  const DistanceResult standard = Query(options).distance(a, b);
  options.swarm.c1 = 0.5;
  EXPECT_NE(Query(options).distance(a, b).history, standard.history);
  options.method = Method::ipso;
  const DistanceResult rank_adaptive = Query(options).distance(a, b);
  options.swarm.c1 = 2;
  expect_identical(Query(options).distance(a, b), rank_adaptive);
}

}  // namespace
}  // namespace swarmcollide::testing
