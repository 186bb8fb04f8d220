// A pool of worker threads kept between jobs (a scene's, or the batches' through kept_threads);
// private to the library's sources.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>

namespace swarmcollide::detail {

/// Threads that wait for work between jobs, so that a job of a few milliseconds (a scene's frame,
/// a batch) does not pay for starting them. `for_each_chunk` runs on the calling thread too.
///
/// A pool inherited by a forked child (a scene kept across `os.fork` or multiprocessing) has no
/// workers there, and its lock may have been held by one of them at the fork: the child leaves
/// them behind, never joined, and starts its own on its first job; destroying the pool there
/// returns at once.
class ThreadPool {
 public:
  /// `threads` threads in all, the caller included; fewer when the process cannot start them.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// Threads that share the work, the caller included.
  int size() const;

  /// Calls `work(begin, end)` for consecutive chunks of [0, count) of at most `chunk` items, on
  /// every thread; returns when all are done. When calls throw, the others' chunks still run
  /// and the exception of the lowest chunk is rethrown.
  void for_each_chunk(std::size_t count, std::size_t chunk,
                      const std::function<void(std::size_t, std::size_t)>& work);

  /// As for_each_chunk, but the calling thread answers the first chunks alone, in order, and
  /// wakes the other threads only once the chunks left are worth it (WakingPace): for jobs that
  /// are often short, such as a scene's frame, which were slower on two threads than on one.
  void for_each_chunk_paced(std::size_t count, std::size_t chunk,
                            const std::function<void(std::size_t, std::size_t)>& work);

 private:
  struct Crew;  // the workers and the job they share

  /// This process's crew: the one started here, or a new one in a forked child.
  Crew& crew();
  /// Leaves the crew of the parent behind (reachable, for leak checkers).
  void abandon_crew();

  int threads_;
  std::size_t forks_at_start_;  // the process's forks counted when `crew_` started
  std::unique_ptr<Crew> crew_;
};

}  // namespace swarmcollide::detail
