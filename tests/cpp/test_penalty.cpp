#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>

#include "contract.hpp"
#include "paper_cases.hpp"
#include "swarmcollide/queries/distance.hpp"
#include "swarmcollide/solvers/exact_nearest_points.hpp"
#include "swarmcollide/solvers/penalty.hpp"

namespace swarmcollide {
namespace {

using testing::paper_a;
using testing::paper_b_colliding;
using testing::paper_b_separate;

void expect_contract(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const DistanceResult& r,
                     Scalar tolerance) {
  testing::expect_contract(a, b, r);
  testing::expect_verdicts_from_bounds(r, tolerance);
  EXPECT_EQ(r.method, "penalty");
  EXPECT_GT(r.iterations, 0);
  EXPECT_GT(r.evaluations, 0);
  EXPECT_FALSE(r.history.empty());
}

TEST(Penalty, OptionsAreValidated) {
  const auto message = [](PenaltyOptions o) {
    try {
      o.validate();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message({}), "");
  PenaltyOptions o;
  o.initial_weight = 0;
  EXPECT_NE(message(o).find("initial_weight"), std::string::npos);
  o = {};
  o.growth_factor = 1;
  EXPECT_NE(message(o).find("growth_factor"), std::string::npos);
  o = {};
  o.outer_iterations = 0;
  EXPECT_NE(message(o).find("outer_iterations"), std::string::npos);
  o = {};
  o.inner_iterations = 0;
  EXPECT_NE(message(o).find("inner_iterations"), std::string::npos);
  o = {};
  o.tolerance = -1;
  EXPECT_NE(message(o).find("tolerance"), std::string::npos);
  EXPECT_THROW(solve_penalty(paper_a(), paper_b_separate(), o), std::invalid_argument);
}

TEST(Penalty, PaperSeparatePair) {
  DistanceOptions options;
  options.method = Method::penalty;
  const DistanceResult r = distance(paper_a(), paper_b_separate(), options);
  expect_contract(paper_a(), paper_b_separate(), r, options.penalty.tolerance);
  EXPECT_LE(r.lower_bound, 1 + 1e-12);
  EXPECT_GE(r.distance, 1 - 1e-12);
  EXPECT_NEAR(r.distance, 1, 1e-4);
  EXPECT_LE((r.point_a - Vector3(1, 0, 0)).norm(), 1e-2);
  EXPECT_FALSE(r.colliding);
}

TEST(Penalty, PaperTouchingPair) {
  const DistanceResult r = solve_penalty(paper_a(), paper_b_colliding());
  expect_contract(paper_a(), paper_b_colliding(), r, PenaltyOptions{}.tolerance);
  EXPECT_LE(r.distance, 1e-4);
}

TEST(Penalty, Deterministic) {
  const DistanceResult r1 = solve_penalty(paper_a(), paper_b_separate());
  const DistanceResult r2 = solve_penalty(paper_a(), paper_b_separate());
  EXPECT_EQ(r1.distance, r2.distance);
  EXPECT_EQ(r1.weights_a, r2.weights_a);
}

TEST(Penalty, BoundsBracketTheExactDistanceOnRandomPairs) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<Scalar> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    VertexMatrix va(8, 3);
    VertexMatrix vb(8, 3);
    for (int i = 0; i < 8; ++i) {
      va.row(i) << u(rng), u(rng), u(rng);
      vb.row(i) << 2.5 + u(rng), u(rng), u(rng);
    }
    const ConvexPolyhedron a(va);
    const ConvexPolyhedron b(vb);
    const Scalar exact = exact_nearest_points(a, b).distance;
    const DistanceResult r = solve_penalty(a, b);
    expect_contract(a, b, r, PenaltyOptions{}.tolerance);
    EXPECT_LE(r.lower_bound, exact + 1e-12);
    EXPECT_GE(r.distance, exact - 1e-12);
    EXPECT_NEAR(r.distance, exact, 1e-3);
  }
}

TEST(Penalty, HistoryIsNonIncreasing) {
  const DistanceResult r = solve_penalty(paper_a(), paper_b_separate());
  for (std::size_t k = 1; k < r.history.size(); ++k) EXPECT_LE(r.history[k], r.history[k - 1]);
  EXPECT_EQ(r.history.back(), r.distance);
}

}  // namespace
}  // namespace swarmcollide
