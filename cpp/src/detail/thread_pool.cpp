#include "thread_pool.hpp"

#include <pthread.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include "interruption.hpp"
#include "waking_pace.hpp"

namespace swarmcollide::detail {

namespace {

// Forks of this process and its ancestors since the first pool, counted in each child before
// fork returns there: a pool that counted fewer at its start was inherited from a parent.
std::atomic<std::size_t> forks{0};

void count_fork() { forks.fetch_add(1, std::memory_order_relaxed); }

std::size_t forks_so_far() {
  static std::once_flag registered;
  std::call_once(registered, [] { pthread_atfork(nullptr, nullptr, &count_fork); });
  return forks.load(std::memory_order_relaxed);
}

// How long a caller whose chunks are done spins for the workers' last ones before it sleeps.
constexpr std::chrono::microseconds kSpinBeforeSleeping{50};

// How often a caller waiting for the workers calls its interruption check (the bindings' calls
// Python's signal handlers at most every 20 ms).
constexpr std::chrono::milliseconds kInterruptionPollInterval{10};

}  // namespace

struct ThreadPool::Crew {
  explicit Crew(int threads);
  ~Crew();
  void for_each_chunk(std::size_t count, std::size_t chunk,
                      const std::function<void(std::size_t, std::size_t)>& work);
  void run_chunks();
  void worker_loop();

  std::vector<std::thread> workers;
  std::mutex mutex;
  std::condition_variable wake;
  std::condition_variable done;
  // The job in progress, read by the workers under `mutex` when `generation` changes.
  const std::function<void(std::size_t, std::size_t)>* work = nullptr;
  std::size_t count = 0;
  std::size_t chunk = 1;
  std::size_t next = 0;
  std::atomic<std::size_t> busy{0};  // changed under `mutex`; read without it while spinning
  std::size_t generation = 0;
  bool stopping = false;
  std::size_t failed_chunk = 0;
  std::exception_ptr failure;
  Crew* abandoned_before = nullptr;  // the crews forked children left behind, in a list
};

ThreadPool::Crew::Crew(int threads) {
  for (int t = 1; t < threads; ++t) {
    try {
      workers.emplace_back([this] { worker_loop(); });
    } catch (const std::system_error&) {
      break;  // the process cannot start more threads; those running share the work
    }
  }
}

ThreadPool::Crew::~Crew() {
  {
    const std::lock_guard<std::mutex> lock(mutex);
    stopping = true;
  }
  wake.notify_all();
  for (auto& worker : workers) worker.join();
}

// Takes chunks until none is left. The lock is held only to take a chunk: the chunks are large
// enough (dozens of pairs) that it is rarely contended.
void ThreadPool::Crew::run_chunks() {
  std::unique_lock<std::mutex> lock(mutex);
  // A worker that wakes late may find the job finished (and `work` reset): then no chunk is
  // left and it goes back to sleep.
  while (next < count) {
    const std::size_t begin = next;
    const std::size_t end = std::min(count, begin + chunk);
    const auto* job = work;
    next = end;
    lock.unlock();
    try {
      (*job)(begin, end);
    } catch (...) {
      lock.lock();
      if (!failure || begin < failed_chunk) {
        failure = std::current_exception();
        failed_chunk = begin;
      }
      continue;
    }
    lock.lock();
  }
}

void ThreadPool::Crew::worker_loop() {
  std::size_t seen = 0;
  std::unique_lock<std::mutex> lock(mutex);
  for (;;) {
    wake.wait(lock, [&] { return stopping || generation != seen; });
    if (stopping) return;
    seen = generation;
    ++busy;
    lock.unlock();
    run_chunks();
    lock.lock();
    if (--busy == 0) done.notify_all();
  }
}

void ThreadPool::Crew::for_each_chunk(std::size_t items, std::size_t chunk_size,
                                      const std::function<void(std::size_t, std::size_t)>& job) {
  if (items == 0) return;
  chunk_size = std::max<std::size_t>(chunk_size, 1);
  // Small jobs and single-threaded pools run inline: waking a worker costs microseconds.
  if (workers.empty() || items <= chunk_size) {
    job(0, items);
    return;
  }
  {
    const std::lock_guard<std::mutex> lock(mutex);
    work = &job;
    count = items;
    chunk = chunk_size;
    next = 0;
    failure = nullptr;
    failed_chunk = std::numeric_limits<std::size_t>::max();
    ++generation;
  }
  wake.notify_all();
  run_chunks();
  // Every chunk has been taken; wait for those still running on workers. Their last chunks are
  // short (the callers hand out smaller ones towards the end), and a caller asleep on `done` wakes
  // tens of microseconds after their notify on this project's VM: it spins a while first.
  const auto spin_until = std::chrono::steady_clock::now() + kSpinBeforeSleeping;
  while (busy.load(std::memory_order_acquire) != 0 &&
         std::chrono::steady_clock::now() < spin_until) {
  }
  std::unique_lock<std::mutex> lock(mutex);
  const auto finished = [&] { return busy == 0 && next >= count; };
  // While it waits, the caller keeps calling its thread's interruption check: a batch's rows on
  // the workers stop when it says so (SharedInterruption), which, once the caller's own rows were
  // done, nothing else would ask (a worker's last row of a large swarm budget ran on for hours
  // past Ctrl-C). What it answers changes nothing here: the workers' rows read it.
  const InterruptionHook hook = current_interruption_hook();
  if (hook.check == nullptr) {
    done.wait(lock, finished);
  } else {
    while (!done.wait_for(lock, kInterruptionPollInterval, finished)) {
      lock.unlock();
      hook.check(hook.context);
      lock.lock();
    }
  }
  work = nullptr;
  count = 0;
  next = 0;
  if (failure) std::rethrow_exception(failure);
}

ThreadPool::ThreadPool(int threads)
    : threads_(threads), forks_at_start_(forks_so_far()), crew_(std::make_unique<Crew>(threads)) {}

ThreadPool::~ThreadPool() {
  // In a forked child the parent's workers do not exist: joining them would wait forever.
  if (forks_so_far() != forks_at_start_) abandon_crew();
}

int ThreadPool::size() const { return static_cast<int>(crew_->workers.size()) + 1; }

void ThreadPool::abandon_crew() {
  static std::atomic<Crew*> abandoned{nullptr};
  Crew* const left = crew_.release();
  left->abandoned_before = abandoned.load(std::memory_order_relaxed);
  while (!abandoned.compare_exchange_weak(left->abandoned_before, left)) {
  }
}

ThreadPool::Crew& ThreadPool::crew() {
  const std::size_t now = forks_so_far();
  if (now != forks_at_start_) {
    abandon_crew();
    crew_ = std::make_unique<Crew>(threads_);
    forks_at_start_ = now;
  }
  return *crew_;
}

void ThreadPool::for_each_chunk(std::size_t count, std::size_t chunk,
                                const std::function<void(std::size_t, std::size_t)>& work) {
  crew().for_each_chunk(count, chunk, work);
}

void ThreadPool::for_each_chunk_paced(std::size_t count, std::size_t chunk,
                                      const std::function<void(std::size_t, std::size_t)>& work) {
  chunk = std::max<std::size_t>(chunk, 1);
  std::size_t done = 0;  // a whole number of chunks, so that the rest keep their boundaries
  std::exception_ptr failure;  // the first (lowest) chunk's that failed alone
  if (size() > 1) {
    const WakingPace pace(count);
    while (done < count && !pace.worth_waking(done)) {
      const std::size_t end = std::min(count, done + chunk);
      try {
        work(done, end);
      } catch (...) {
        if (!failure) failure = std::current_exception();
      }
      done = end;
    }
  }
  if (done < count) {
    try {
      for_each_chunk(count - done, chunk,
                     [&](std::size_t begin, std::size_t end) { work(done + begin, done + end); });
    } catch (...) {
      if (!failure) throw;
    }
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace swarmcollide::detail
