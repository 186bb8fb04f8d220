// The pool of a scene or of the kept batch threads: every item once, on the caller and the
// workers, and a pool inherited by a forked child works there and can be destroyed there (its
// workers do not exist in the child, so joining them would never return).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "detail/thread_pool.hpp"

namespace swarmcollide::testing {
namespace {

using detail::ThreadPool;

// Whether `pool` calls each of `count` items once, in chunks of `chunk`.
bool every_item_once(ThreadPool& pool, std::size_t count, std::size_t chunk) {
  std::vector<std::atomic<int>> runs(count);
  pool.for_each_chunk(count, chunk, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) runs[k].fetch_add(1);
  });
  for (const auto& run : runs) {
    if (run.load() != 1) return false;
  }
  return true;
}

TEST(ThreadPool, EveryItemOnceInChunks) {
  ThreadPool pool(2);
  for (const std::size_t count : {1, 7, 64, 1000}) {
    EXPECT_TRUE(every_item_once(pool, count, 3)) << count << " items";
  }
}

// The paced form (a scene's frames): every item once, chunks on their boundaries, the lowest
// failing chunk's error rethrown after every chunk ran, and a long job shared with the workers.
TEST(ThreadPool, ThePacedFormAnswersEveryItemOnceAndSharesALongJob) {
  ThreadPool pool(2);
  for (const std::size_t count : {1, 7, 64, 1000}) {
    std::vector<std::atomic<int>> runs(count);
    std::atomic<bool> aligned{true};
    pool.for_each_chunk_paced(count, 3, [&](std::size_t begin, std::size_t end) {
      if (begin % 3 != 0) aligned = false;
      for (std::size_t k = begin; k < end; ++k) runs[k].fetch_add(1);
    });
    for (std::size_t k = 0; k < count; ++k) EXPECT_EQ(runs[k].load(), 1) << k << " of " << count;
    EXPECT_TRUE(aligned) << count;
  }
  std::vector<std::atomic<int>> runs(600);
  try {
    pool.for_each_chunk_paced(runs.size(), 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        runs[k].fetch_add(1);
        if (k == 3 || k == 500) throw std::runtime_error("item " + std::to_string(k));
      }
    });
    ADD_FAILURE() << "no error rethrown";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "item 3");
  }
  for (const auto& run : runs) EXPECT_EQ(run.load(), 1);
  // Items of 100 us: the caller's pace says the rest is worth waking the worker for, which takes
  // some of them (within a few jobs: on a loaded machine it may start after the caller is done).
  std::mutex mutex;
  std::set<std::thread::id> threads;
  for (int attempt = 0; attempt < 50 && threads.size() < 2; ++attempt) {
    pool.for_each_chunk_paced(40, 1, [&](std::size_t, std::size_t) {
      std::this_thread::sleep_for(std::chrono::microseconds(100));
      const std::lock_guard<std::mutex> lock(mutex);
      threads.insert(std::this_thread::get_id());
    });
  }
  EXPECT_EQ(threads.size(), static_cast<std::size_t>(pool.size()));
}

// Runs `child_work` in a forked child with 10 s to finish: a hang becomes SIGALRM, a failure.
void expect_in_child(const std::function<bool()>& child_work) {
  const pid_t child = fork();
  ASSERT_NE(child, -1);
  if (child == 0) {
    alarm(10);
    _exit(child_work() ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the child was killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

// Whether every thread of `pool` has run a chunk of a job, after a few jobs at most: a job can
// finish on the caller alone while a worker is still starting.
bool every_thread_ran(ThreadPool& pool) {
  for (int attempt = 0; attempt < 200; ++attempt) {
    std::mutex mutex;
    std::set<std::thread::id> ran;
    pool.for_each_chunk(64, 1, [&](std::size_t, std::size_t) {
      std::this_thread::sleep_for(std::chrono::microseconds(50));
      const std::lock_guard<std::mutex> lock(mutex);
      ran.insert(std::this_thread::get_id());
    });
    if (static_cast<int>(ran.size()) == pool.size()) return true;
  }
  return false;
}

TEST(ThreadPool, AnInheritedPoolAnswersAndIsDestroyedInAForkedChild) {
  auto pool = std::make_unique<ThreadPool>(2);
  ASSERT_TRUE(every_item_once(*pool, 200, 4));
  // The workers have run before the fork, their start finished: a worker forked while still
  // starting (the caller alone can finish a job) held AddressSanitizer's allocator lock in 35
  // of 40 runs of the sanitizer build, and the child's own new worker then waited on it forever.
  ASSERT_TRUE(every_thread_ran(*pool));
  expect_in_child([&] {
    const bool right = every_item_once(*pool, 200, 4) && every_item_once(*pool, 50, 1);
    pool.reset();
    return right;
  });
  expect_in_child([&] {
    pool.reset();  // destroyed before any job in the child
    return true;
  });
  EXPECT_TRUE(every_item_once(*pool, 200, 4));  // the parent's pool is untouched
}

}  // namespace
}  // namespace swarmcollide::testing
