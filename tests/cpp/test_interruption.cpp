// The interruption check (swarmcollide/interruption.hpp): the long solves call it between their
// iterations and stop with Interrupted when it says so; it changes no answer, and nothing of an
// interrupted query stays behind.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "contract.hpp"
#include "detail/thread_pool.hpp"
#include "paper_cases.hpp"
#include "swarmcollide/interruption.hpp"
#include "swarmcollide/queries/batch.hpp"

namespace swarmcollide::testing {
namespace {

// Counts its calls and says to stop from the call numbered `stop_at` on (never when 0).
struct CountingCheck {
  long calls = 0;
  long stop_at = 0;
  static bool check(void* self) {
    auto& c = *static_cast<CountingCheck*>(self);
    ++c.calls;
    return c.stop_at > 0 && c.calls >= c.stop_at;
  }
};

QueryOptions with_method(Method method) {
  QueryOptions options;
  options.method = method;
  options.tolerance = 0;  // the whole budget: every iteration polls
  return options;
}

class LongSolves : public ::testing::TestWithParam<Method> {};

// A check that never stops is called, and the answer is bit for bit the one without it.
TEST_P(LongSolves, ACheckThatNeverStopsChangesNoAnswer) {
  const Query query(with_method(GetParam()));
  const DistanceResult plain = query.distance(paper_a(), paper_b_separate());
  CountingCheck counting;
  DistanceResult checked;
  {
    const InterruptionGuard guard(&CountingCheck::check, &counting);
    checked = query.distance(paper_a(), paper_b_separate());
  }
  EXPECT_GT(counting.calls, 0);
  expect_identical(plain, checked);
}

// A check that says to stop ends the solve with Interrupted; the next query, without a check,
// answers as a fresh one does (the thread's workspaces keep nothing of the interrupted one).
TEST_P(LongSolves, ACheckThatStopsThrowsInterrupted) {
  const Query query(with_method(GetParam()));
  const DistanceResult before = query.distance(paper_a(), paper_b_separate());
  CountingCheck stopping;
  stopping.stop_at = 3;
  {
    const InterruptionGuard guard(&CountingCheck::check, &stopping);
    EXPECT_THROW(query.distance(paper_a(), paper_b_separate()), Interrupted);
    EXPECT_THROW(query.collision(paper_a(), paper_b_separate(), true), Interrupted);
  }
  EXPECT_EQ(stopping.calls, 4);  // the stopping call of each query, and none after it
  expect_identical(before, query.distance(paper_a(), paper_b_separate()));
}

INSTANTIATE_TEST_SUITE_P(Methods, LongSolves,
                         ::testing::Values(Method::ipso, Method::pso, Method::penalty),
                         [](const auto& info) { return std::string(method_name(info.param)); });

// Budgets within the documented ranges that run for minutes (a million iterations of 20,000
// particles, a hundred subproblems of a million L-BFGS iterations) stop at the first check that
// says so.
TEST(Interruption, StopsLongBudgets) {
  QueryOptions ipso = with_method(Method::ipso);
  ipso.swarm.swarm_size = 20000;
  ipso.swarm.max_iterations = 1000000;
  QueryOptions penalty = with_method(Method::penalty);
  penalty.penalty.inner_iterations = 1000000;
  penalty.penalty.outer_iterations = 100;
  for (const QueryOptions& options : {ipso, penalty}) {
    CountingCheck stopping;
    stopping.stop_at = 2;
    const InterruptionGuard guard(&CountingCheck::check, &stopping);
    EXPECT_THROW(Query(options).distance(paper_a(), paper_b_separate()), Interrupted);
    EXPECT_EQ(stopping.calls, 2);
  }
}

// The exact method and the dual method's Wolfe search run no loop that takes seconds: no check.
TEST(Interruption, TheFastMethodsCallNoCheck) {
  for (Method method : {Method::dual, Method::exact}) {
    CountingCheck counting;
    const Query query(with_method(method));
    const DistanceResult plain = query.distance(paper_a(), paper_b_separate());
    const InterruptionGuard guard(&CountingCheck::check, &counting);
    expect_identical(plain, query.distance(paper_a(), paper_b_separate()));
    EXPECT_EQ(counting.calls, 0) << method_name(method);
  }
}

// Guards nest, each restoring the check before it; a thread sees only its own.
TEST(Interruption, GuardsNestAndStayOnTheirThread) {
  const Query query(with_method(Method::ipso));
  CountingCheck outer;
  const InterruptionGuard outer_guard(&CountingCheck::check, &outer);
  {
    CountingCheck inner;
    inner.stop_at = 1;
    const InterruptionGuard inner_guard(&CountingCheck::check, &inner);
    EXPECT_THROW(query.distance(paper_a(), paper_b_separate()), Interrupted);
    const InterruptionGuard none(nullptr, nullptr);
    EXPECT_NO_THROW(query.distance(paper_a(), paper_b_separate()));
    EXPECT_EQ(inner.calls, 1);
  }
  EXPECT_EQ(outer.calls, 0);
  std::thread([&] { query.distance(paper_a(), paper_b_separate()); }).join();
  EXPECT_EQ(outer.calls, 0);
  query.distance(paper_a(), paper_b_separate());
  EXPECT_GT(outer.calls, 0);
}

// A batch's rows check too: the caller's check alone is called, and when it says to stop, the
// other threads' rows stop at their next poll (each of these rows would run for minutes).
TEST(Interruption, ABatchStopsOnEveryThread) {
  const std::vector<ConvexPolyhedron> as(8, paper_a());
  const std::vector<ConvexPolyhedron> bs(8, paper_b_separate());
  QueryOptions ipso = with_method(Method::ipso);
  ipso.swarm.swarm_size = 20000;
  ipso.swarm.max_iterations = 1000000;
  CountingCheck stopping;
  stopping.stop_at = 3;
  const InterruptionGuard guard(&CountingCheck::check, &stopping);
  EXPECT_THROW(distance_many(as, bs, ipso, {2}), Interrupted);
  EXPECT_EQ(stopping.calls, 3);
}

// A check that never stops changes no row of a batch.
TEST(Interruption, ABatchAnswersAsWithoutACheck) {
  const std::vector<ConvexPolyhedron> as(40, paper_a());
  const std::vector<ConvexPolyhedron> bs(40, paper_b_separate());
  const QueryOptions ipso = with_method(Method::ipso);
  const BatchResult plain = distance_many(as, bs, ipso, {2});
  CountingCheck counting;
  const InterruptionGuard guard(&CountingCheck::check, &counting);
  const BatchResult checked = distance_many(as, bs, ipso, {2});
  EXPECT_GT(counting.calls, 0);
  EXPECT_EQ(plain.distance, checked.distance);
  EXPECT_EQ(plain.lower_bound, checked.lower_bound);
  EXPECT_EQ(plain.point_a, checked.point_a);
  EXPECT_EQ(plain.point_b, checked.point_b);
  EXPECT_TRUE((plain.iterations == checked.iterations).all());
}

// A pool's caller, its own chunks done, keeps calling its check while it waits for the workers':
// a worker's chunk that runs until the check is called ends (a batch's last row on a worker, of
// a swarm budget of hours, stops at Ctrl-C; before, nothing asked the check once the caller's
// rows were done).
TEST(Interruption, APoolsCallerKeepsCheckingWhileItWaits) {
  struct Raising {
    std::atomic<bool> called{false};
    static bool check(void* self) {
      static_cast<Raising*>(self)->called = true;
      return true;
    }
  };
  Raising raising;
  const InterruptionGuard guard(&Raising::check, &raising);
  detail::ThreadPool pool(2);
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<bool> worker_started{false};
  std::atomic<bool> worker_saw_check{false};
  pool.for_each_chunk(2, 1, [&](std::size_t, std::size_t) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    if (std::this_thread::get_id() == caller) {
      // The caller's chunk ends once a worker holds the other: the caller then waits.
      while (!worker_started && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::yield();
      }
      return;
    }
    worker_started = true;
    while (!raising.called && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::yield();
    }
    worker_saw_check = raising.called.load();
  });
  EXPECT_TRUE(worker_started);
  EXPECT_TRUE(worker_saw_check);
}

}  // namespace
}  // namespace swarmcollide::testing
