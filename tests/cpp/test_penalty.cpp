// method="penalty": the paper's baseline, an exterior quadratic penalty minimised by L-BFGS over
// a schedule of growing penalty weights.
#include <gtest/gtest.h>

#include "contract.hpp"
#include "paper_cases.hpp"

namespace swarmcollide::testing {
namespace {

QueryOptions penalty() {
  QueryOptions options;
  options.method = Method::penalty;
  return options;
}

// The history holds the best distance after each subproblem.
void expect_history(const DistanceResult& r) {
  ASSERT_FALSE(r.history.empty());
  for (std::size_t k = 1; k < r.history.size(); ++k) EXPECT_LE(r.history[k], r.history[k - 1]);
  EXPECT_EQ(r.history.back(), r.distance);
}

// With a tolerance of zero every subproblem of the schedule runs, each evaluating the penalty
// function (its L-BFGS iterations count only when its line search ended normally).
TEST(Penalty, ZeroToleranceRunsTheWholeSchedule) {
  for (int outer : {1, 3, 8}) {
    QueryOptions options = penalty();
    options.tolerance = 0;
    options.penalty.outer_iterations = outer;
    const DistanceResult r = Query(options).distance(paper_a(), paper_b_separate());
    EXPECT_EQ(r.history.size(), static_cast<std::size_t>(outer));
    EXPECT_GE(r.evaluations, outer);
    EXPECT_GE(r.evaluations, r.iterations);
    expect_history(r);
  }
}

// The schedule stops at the first subproblem whose answer is within the tolerance, before its
// end on the paper's separate pair: the growing penalty weight soon makes the raw minimiser's
// constraint violation negligible.
TEST(Penalty, StopsWhenTheAnswerIsWithinTheTolerance) {
  const DistanceResult r = Query(penalty()).distance(paper_a(), paper_b_separate());
  EXPECT_EQ(r.status, SolverStatus::converged);
  EXPECT_LT(r.history.size(), static_cast<std::size_t>(PenaltyOptions{}.outer_iterations));
  EXPECT_NEAR(r.distance, 1, 1e-9);
  expect_history(r);
  // A verdict needs only a bound that proves it: the first subproblem's separation does.
  const DistanceResult verdict = Query(penalty()).collision(paper_a(), paper_b_separate(), false);
  EXPECT_TRUE(verdict.certified);
  EXPECT_EQ(verdict.history.size(), 1u);
}

// The first penalty weight and its growth shape every subproblem.
TEST(Penalty, TheScheduleReachesTheSolver) {
  QueryOptions options = penalty();
  options.tolerance = 0;
  options.penalty.outer_iterations = 3;
  const DistanceResult standard = Query(options).distance(paper_a(), paper_b_separate());
  QueryOptions heavier = options;
  heavier.penalty.initial_weight = 100;
  EXPECT_NE(Query(heavier).distance(paper_a(), paper_b_separate()).history, standard.history);
  QueryOptions faster = options;
  faster.penalty.growth_factor = 1000;
  EXPECT_NE(Query(faster).distance(paper_a(), paper_b_separate()).history, standard.history);
  QueryOptions shorter = options;
  shorter.penalty.inner_iterations = 1;
  EXPECT_LE(Query(shorter).distance(paper_a(), paper_b_separate()).iterations, 3);
}

// No randomness: the seed changes nothing.
TEST(Penalty, IsDeterministic) {
  QueryOptions options = penalty();
  const DistanceResult first = Query(options).distance(paper_a(), paper_b_colliding());
  options.seed = 99;
  expect_identical(first, Query(options).distance(paper_a(), paper_b_colliding()));
}

}  // namespace
}  // namespace swarmcollide::testing
