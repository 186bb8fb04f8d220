// The threads kept between batch calls: every copy runs once, on threads other than the caller
// where the machine allows, the lowest failing copy's error is the one rethrown, and a call made
// while they are held, or in a forked child, still runs every copy.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "detail/kept_threads.hpp"

namespace swarmcollide::testing {
namespace {

using detail::run_copies;

// Runs `copies` copies that each record their index, and returns how many times each ran.
std::vector<int> runs_of(std::size_t copies) {
  std::vector<std::atomic<int>> runs(copies);
  run_copies(copies, [&](std::size_t k) { runs[k].fetch_add(1); });
  std::vector<int> counted;
  for (const auto& run : runs) counted.push_back(run.load());
  return counted;
}

TEST(KeptThreads, EveryCopyRunsOnceWhateverTheCountBetweenCalls) {
  for (const std::size_t copies : {0, 1, 2, 5, 2, 3, 1, 8}) {
    EXPECT_EQ(runs_of(copies), std::vector<int>(copies, 1)) << copies << " copies";
  }
}

TEST(KeptThreads, CopiesRunOnOtherThreadsThanTheCaller) {
  // Each copy waits (up to 10 s) for the others to start: copies sharing one thread would each
  // wait in turn, copies on threads of their own meet.
  constexpr std::size_t kCopies = 3;
  std::atomic<std::size_t> started{0};
  std::mutex mutex;
  std::set<std::thread::id> seen;
  run_copies(kCopies, [&](std::size_t) {
    started.fetch_add(1);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (started.load() < kCopies && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::yield();
    }
    const std::lock_guard<std::mutex> lock(mutex);
    seen.insert(std::this_thread::get_id());
  });
  EXPECT_EQ(started.load(), kCopies);
  EXPECT_GE(seen.size(), 2u);  // at least one copy off the caller's thread
}

TEST(KeptThreads, TheLowestFailingCopysErrorIsRethrownAfterEveryCopyRan) {
  std::atomic<int> ran{0};
  try {
    run_copies(4, [&](std::size_t k) {
      ran.fetch_add(1);
      if (k == 1 || k == 3) throw std::invalid_argument("copy " + std::to_string(k));
    });
    FAIL() << "no error rethrown";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()), "copy 1");
  }
  EXPECT_EQ(ran.load(), 4);
  EXPECT_EQ(runs_of(4), std::vector<int>(4, 1));  // the kept threads still serve
}

TEST(KeptThreads, ACallFromInsideACopyRunsOnThreadsOfItsOwn) {
  std::atomic<int> inner{0};
  run_copies(2, [&](std::size_t) {
    run_copies(3, [&](std::size_t) { inner.fetch_add(1); });
  });
  EXPECT_EQ(inner.load(), 6);
}

TEST(KeptThreads, AForkedChildRunsEveryCopy) {
  EXPECT_EQ(runs_of(2), std::vector<int>(2, 1));  // the parent keeps threads before it forks
  const pid_t child = fork();
  ASSERT_NE(child, -1);
  if (child == 0) {
    // The parent's threads do not exist here: a call must neither wait for them nor skip copies.
    const bool right = runs_of(3) == std::vector<int>(3, 1) && runs_of(2) == std::vector<int>(2, 1);
    _exit(right ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace swarmcollide::testing
