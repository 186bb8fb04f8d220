// The primal swarms ("ipso", "pso"): the paper's coefficients (7)-(9), Step 3's stopping test,
// seeds, the constraint handlings, and collide's escalation of their unproven verdicts.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "contract.hpp"
#include "oracle.hpp"
#include "paper_cases.hpp"
#include "shapes.hpp"
#include "solvers/swarm_kernels.hpp"
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

// n points drawn on the unit sphere (all of them hull vertices), moved by `shift` along x.
VertexMatrix sphere_points(int n, std::mt19937_64& rng, double shift) {
  std::normal_distribution<double> normal;
  VertexMatrix points(n, 3);
  for (int i = 0; i < n; ++i) {
    const Vector3 v(normal(rng), normal(rng), normal(rng));
    points.row(i) = v.normalized().transpose();
  }
  points.col(0).array() += shift;
  return points;
}

TEST(Swarm, EveryInstructionSetGivesTheSameBitsForASeed) {
  // Body sizes around the sorting networks' limit of 16 weights and well above it; a swarm size
  // that is not a whole number of generator blocks; both constraint handlings and both inertias.
  struct Case {
    int ka, kb, swarm_size;
  };
  std::vector<std::pair<ConvexPolyhedron, ConvexPolyhedron>> pairs = {
      {paper_a(), paper_b_separate()}, {paper_a(), paper_b_colliding()}};
  std::mt19937_64 rng(41);
  for (const Case c : {Case{4, 7, 40}, Case{8, 8, 13}, Case{16, 17, 40}, Case{33, 64, 21}}) {
    pairs.emplace_back(ConvexPolyhedron(sphere_points(c.ka, rng, 0)),
                       ConvexPolyhedron(sphere_points(c.kb, rng, 2.01)));
  }
  const detail::KernelIsa chosen = detail::kernel_isa();
  std::vector<DistanceResult> first;
  for (detail::KernelIsa isa :
       {detail::KernelIsa::baseline, detail::KernelIsa::avx2, detail::KernelIsa::avx512}) {
    if (!detail::kernel_isa_available(isa)) {
      std::cout << "[          ] " << detail::kernel_isa_name(isa) << " cannot run here\n";
      continue;
    }
    detail::use_kernel_isa(isa);
    EXPECT_EQ(std::string(swarm_instruction_set()), detail::kernel_isa_name(isa));
    std::size_t solve = 0;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      for (Method method : {Method::ipso, Method::pso}) {
        for (auto handling : {ConstraintHandling::projection, ConstraintHandling::feasibility}) {
          QueryOptions options = swarm(method, handling);
          options.tolerance = p % 2 ? 0.0 : 1e-6;
          options.swarm.swarm_size = p == 3 ? 13 : (p == 5 ? 21 : 40);
          options.seed = 100 + p;
          const DistanceResult r = Query(options).distance(pairs[p].first, pairs[p].second);
          if (first.size() <= solve) {
            first.push_back(r);
          } else {
            const DistanceResult& e = first[solve];
            const std::string what = std::string(detail::kernel_isa_name(isa)) + ", pair " +
                                     std::to_string(p) + ", " + method_name(r.method);
            EXPECT_EQ(r.history, e.history) << what;
            EXPECT_EQ(r.weights_a.dense(), e.weights_a.dense()) << what;
            EXPECT_EQ(r.weights_b.dense(), e.weights_b.dense()) << what;
            EXPECT_EQ(r.lower_bound, e.lower_bound) << what;
            EXPECT_EQ(r.iterations, e.iterations) << what;
          }
          ++solve;
        }
      }
    }
  }
  detail::use_kernel_isa(chosen);
}

TEST(Swarm, ProjectedSwarmKeepsImprovingPastThePapersBudget) {
  // With one pair r1, r2 per particle, every projected move stayed in span{v, p - x, g - x} and
  // 400 iterations gave exactly the answer of 200. Drawn per weight, the swarm keeps searching.
  std::mt19937_64 rng(8);
  const ConvexPolyhedron a(sphere_points(64, rng, 0)), b(sphere_points(64, rng, 2.01));
  int improved = 0;
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    QueryOptions options = swarm(Method::ipso);
    options.tolerance = 0;
    options.swarm.max_iterations = 400;
    options.seed = seed;
    const DistanceResult r = Query(options).distance(a, b);
    improved += r.history[400] < r.history[200];
  }
  EXPECT_GE(improved, 4);
}

}  // namespace
}  // namespace swarmcollide::testing
