// A pool of worker threads kept between jobs (a scene's, or the batches' through kept_threads);
// private to the library's sources.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace swarmcollide::detail {

/// Threads that wait for work between jobs, so that a job of a few milliseconds (a scene's frame,
/// a batch) does not pay for starting them. `for_each_chunk` runs on the calling thread too.
class ThreadPool {
 public:
  /// `threads` threads in all, the caller included; fewer when the process cannot start them.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// Threads that share the work, the caller included.
  int size() const { return static_cast<int>(workers_.size()) + 1; }

  /// Calls `work(begin, end)` for consecutive chunks of [0, count) of at most `chunk` items, on
  /// every thread; returns when all are done. When calls throw, the others' chunks still run
  /// and the exception of the lowest chunk is rethrown.
  void for_each_chunk(std::size_t count, std::size_t chunk,
                      const std::function<void(std::size_t, std::size_t)>& work);

 private:
  void run_chunks();
  void worker_loop();

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  // The job in progress, read by the workers under `mutex_` when `generation_` changes.
  const std::function<void(std::size_t, std::size_t)>* work_ = nullptr;
  std::size_t count_ = 0;
  std::size_t chunk_ = 1;
  std::size_t next_ = 0;
  std::size_t busy_ = 0;
  std::size_t generation_ = 0;
  bool stopping_ = false;
  std::size_t failed_chunk_ = 0;
  std::exception_ptr failure_;
};

}  // namespace swarmcollide::detail
