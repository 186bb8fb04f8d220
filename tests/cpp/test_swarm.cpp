#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "paper_cases.hpp"
#include "swarmcollide/problem/certificate.hpp"
#include "swarmcollide/queries/collide.hpp"
#include "swarmcollide/solvers/swarm.hpp"

namespace swarmcollide {
namespace {

using testing::paper_a;
using testing::paper_b_colliding;
using testing::paper_b_separate;

DistanceOptions with(Method method, ConstraintHandling handling = ConstraintHandling::projection) {
  DistanceOptions options;
  options.method = method;
  options.swarm.constraint_handling = handling;
  return options;
}

// What every answer must satisfy, however good it is.
void expect_consistent(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                       const DistanceResult& r) {
  EXPECT_TRUE((r.weights_a.array() >= 0).all());
  EXPECT_TRUE((r.weights_b.array() >= 0).all());
  EXPECT_NEAR(r.weights_a.sum(), 1.0, 1e-14);
  EXPECT_NEAR(r.weights_b.sum(), 1.0, 1e-14);
  EXPECT_TRUE(r.point_a.isApprox(a.vertices().transpose() * r.weights_a, 1e-14));
  EXPECT_TRUE(r.point_b.isApprox(b.vertices().transpose() * r.weights_b, 1e-14));
  EXPECT_NEAR(r.distance, (r.point_b - r.point_a).norm(), 1e-15);
  EXPECT_LE(r.lower_bound, r.distance);
  EXPECT_GE(r.lower_bound, 0.0);
  EXPECT_EQ(r.history.size(), static_cast<std::size_t>(r.iterations) + 1);
  for (std::size_t i = 1; i < r.history.size(); ++i) EXPECT_LE(r.history[i], r.history[i - 1]);
  EXPECT_EQ(r.history.back(), r.distance);
}

class PaperCases : public ::testing::TestWithParam<Method> {};

TEST_P(PaperCases, CollisionIsFoundAndCertified) {
  const auto a = paper_a();
  const auto b = paper_b_colliding();
  const DistanceResult r = distance(a, b, with(GetParam()));
  expect_consistent(a, b, r);
  EXPECT_LE(r.distance, 1e-6);
  EXPECT_TRUE(r.colliding);
  EXPECT_TRUE(r.certified);
  EXPECT_EQ(r.method, method_name(GetParam()));
}

TEST_P(PaperCases, SeparationIsOneBetweenX2AndY1) {
  const auto a = paper_a();
  const auto b = paper_b_separate();
  const DistanceResult r = distance(a, b, with(GetParam()));
  expect_consistent(a, b, r);
  EXPECT_NEAR(r.distance, 1.0, 1e-4);
  EXPECT_NEAR(r.weights_a(1), 1.0, 1e-4);
  EXPECT_NEAR(r.weights_b(0), 1.0, 1e-4);
  EXPECT_FALSE(r.colliding);
  EXPECT_TRUE(r.certified);
  EXPECT_GT(r.lower_bound, 1.0 - 1e-6);
  EXPECT_EQ(r.status, SolverStatus::converged);
}

TEST_P(PaperCases, PaperRulesGiveValidBoundsEvenWhenNotConverged) {
  for (const auto& b : {paper_b_colliding(), paper_b_separate()}) {
    const DistanceResult r =
        distance(paper_a(), b, with(GetParam(), ConstraintHandling::feasibility));
    expect_consistent(paper_a(), b, r);
  }
}

TEST_P(PaperCases, ZeroToleranceRunsTheWholeBudget) {
  DistanceOptions options = with(GetParam());
  options.swarm.tolerance = 0;
  options.swarm.max_iterations = 50;
  const DistanceResult r = distance(paper_a(), paper_b_separate(), options);
  EXPECT_EQ(r.iterations, 50);
  EXPECT_EQ(r.evaluations, 40L * 51);
  EXPECT_EQ(r.status, SolverStatus::max_iterations);
}

TEST_P(PaperCases, SameSeedSameAnswerOtherSeedOtherPath) {
  DistanceOptions options = with(GetParam(), ConstraintHandling::feasibility);
  options.swarm.seed = 42;
  const DistanceResult first = distance(paper_a(), paper_b_separate(), options);
  const DistanceResult again = distance(paper_a(), paper_b_separate(), options);
  EXPECT_EQ(first.history, again.history);
  EXPECT_EQ(first.weights_a, again.weights_a);
  options.swarm.seed = 43;
  EXPECT_NE(distance(paper_a(), paper_b_separate(), options).history, first.history);
}

INSTANTIATE_TEST_SUITE_P(Swarm, PaperCases, ::testing::Values(Method::ipso, Method::pso),
                         [](const auto& info) { return method_name(info.param); });

TEST(RankAdaptiveCoefficients, FollowEquations8And9) {
  const ParticleCoefficients best = rank_adaptive_coefficients(1, 40, 0.4, 0.9);
  EXPECT_DOUBLE_EQ(best.w, 0.9);
  EXPECT_DOUBLE_EQ(best.c1, (0.9 + 1 + 2 * std::sqrt(0.9)) / 2);
  EXPECT_DOUBLE_EQ(best.c2, best.c1);
  const ParticleCoefficients worst = rank_adaptive_coefficients(40, 40, 0.4, 0.9);
  EXPECT_DOUBLE_EQ(worst.w, 0.4);
  EXPECT_DOUBLE_EQ(worst.c1, (0.4 + 1 + 2 * std::sqrt(0.4)) / 2);
  const ParticleCoefficients middle = rank_adaptive_coefficients(21, 41, 0.4, 0.9);
  EXPECT_DOUBLE_EQ(middle.w, 0.65);
  EXPECT_THROW(rank_adaptive_coefficients(0, 40, 0.4, 0.9), std::invalid_argument);
  EXPECT_THROW(rank_adaptive_coefficients(41, 40, 0.4, 0.9), std::invalid_argument);
}

TEST(LinearDecreasingInertia, FollowsEquation7) {
  EXPECT_DOUBLE_EQ(linear_decreasing_inertia(0, 200, 0.9, 0.4), 0.9);
  EXPECT_DOUBLE_EQ(linear_decreasing_inertia(100, 200, 0.9, 0.4), 0.65);
  EXPECT_DOUBLE_EQ(linear_decreasing_inertia(200, 200, 0.9, 0.4), 0.4);
}

TEST(SwarmOptions, InvalidValuesAreNamed) {
  const auto message_of = [](SwarmOptions options) {
    try {
      options.validate();
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  SwarmOptions options;
  EXPECT_EQ(message_of(options), "");
  options.swarm_size = 1;
  EXPECT_NE(message_of(options).find("swarm_size"), std::string::npos);
  options = {};
  options.w_min = 1.0;
  EXPECT_NE(message_of(options).find("w_min"), std::string::npos);
  options = {};
  options.tolerance = std::nan("");
  EXPECT_NE(message_of(options).find("tolerance"), std::string::npos);
  options = {};
  options.velocity_limit = 0;
  EXPECT_NE(message_of(options).find("velocity_limit"), std::string::npos);
  options = {};
  options.max_iterations = -1;
  EXPECT_NE(message_of(options).find("max_iterations"), std::string::npos);
}

TEST(Collision, AnUnprovenSwarmVerdictIsEscalatedToAnExactMethod) {
  // Apart by less than the tolerance: a swarm with no iterations can neither prove a separation
  // nor find the contact.
  VertexMatrix near(4, 3);
  near << 1, -1e-7, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0;
  const ConvexPolyhedron b(near);
  DistanceOptions options = with(Method::ipso, ConstraintHandling::feasibility);
  options.swarm.max_iterations = 0;
  const DistanceResult raw = collision(paper_a(), b, options, /*escalate=*/false);
  ASSERT_FALSE(raw.certified);
  EXPECT_EQ(raw.method, "ipso");
  EXPECT_TRUE(raw.escalated_from.empty());

  const DistanceResult decided = collision(paper_a(), b, options);
  EXPECT_EQ(decided.method, "fcl");
  EXPECT_EQ(decided.escalated_from, "ipso");
  EXPECT_TRUE(decided.certified);
  EXPECT_TRUE(decided.colliding);
  EXPECT_NEAR(decided.distance, 1e-7, 1e-15);
  EXPECT_TRUE(collide(paper_a(), b, options));
  EXPECT_FALSE(collide(paper_a(), b, options, /*escalate=*/false));
}

TEST(Collision, ACertifiedSwarmVerdictStands) {
  const DistanceResult r = collision(paper_a(), paper_b_colliding(), with(Method::pso));
  EXPECT_EQ(r.method, "pso");
  EXPECT_TRUE(r.escalated_from.empty());
  EXPECT_TRUE(r.colliding);
}

TEST(Swarm, DegenerateBodiesAreSolved) {
  VertexMatrix point(1, 3);
  point << 0, 0, 3;
  VertexMatrix segment(2, 3);
  segment << -1, 0, 0, 1, 0, 0;
  const DistanceResult r = distance(ConvexPolyhedron(point), ConvexPolyhedron(segment));
  EXPECT_NEAR(r.distance, 3.0, 1e-6);
  EXPECT_TRUE(r.certified);
}

}  // namespace
}  // namespace swarmcollide
