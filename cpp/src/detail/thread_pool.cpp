#include "thread_pool.hpp"

#include <algorithm>
#include <limits>
#include <system_error>

namespace swarmcollide::detail {

ThreadPool::ThreadPool(int threads) {
  for (int t = 1; t < threads; ++t) {
    try {
      workers_.emplace_back([this] { worker_loop(); });
    } catch (const std::system_error&) {
      break;  // the process cannot start more threads; those running share the work
    }
  }
}

ThreadPool::~ThreadPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (auto& worker : workers_) worker.join();
}

// Takes chunks until none is left. The lock is held only to take a chunk: the chunks are large
// enough (dozens of pairs) that it is rarely contended.
void ThreadPool::run_chunks() {
  std::unique_lock<std::mutex> lock(mutex_);
  // A worker that wakes late may find the job finished (and `work_` reset): then no chunk is
  // left and it goes back to sleep.
  while (next_ < count_) {
    const std::size_t begin = next_;
    const std::size_t end = std::min(count_, begin + chunk_);
    const auto* work = work_;
    next_ = end;
    lock.unlock();
    try {
      (*work)(begin, end);
    } catch (...) {
      lock.lock();
      if (!failure_ || begin < failed_chunk_) {
        failure_ = std::current_exception();
        failed_chunk_ = begin;
      }
      continue;
    }
    lock.lock();
  }
}

void ThreadPool::worker_loop() {
  std::size_t seen = 0;
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
    if (stopping_) return;
    seen = generation_;
    ++busy_;
    lock.unlock();
    run_chunks();
    lock.lock();
    if (--busy_ == 0) done_.notify_all();
  }
}

void ThreadPool::for_each_chunk(std::size_t count, std::size_t chunk,
                                const std::function<void(std::size_t, std::size_t)>& work) {
  if (count == 0) return;
  chunk = std::max<std::size_t>(chunk, 1);
  // Small jobs and single-threaded pools run inline: waking a worker costs microseconds.
  if (workers_.empty() || count <= chunk) {
    work(0, count);
    return;
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    work_ = &work;
    count_ = count;
    chunk_ = chunk;
    next_ = 0;
    failure_ = nullptr;
    failed_chunk_ = std::numeric_limits<std::size_t>::max();
    ++generation_;
  }
  wake_.notify_all();
  run_chunks();
  std::unique_lock<std::mutex> lock(mutex_);
  // Every chunk has been taken; wait for those still running on workers.
  done_.wait(lock, [&] { return busy_ == 0 && next_ >= count_; });
  work_ = nullptr;
  count_ = 0;
  next_ = 0;
  if (failure_) std::rethrow_exception(failure_);
}

}  // namespace swarmcollide::detail
