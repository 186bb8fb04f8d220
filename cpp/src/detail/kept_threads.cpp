#include "kept_threads.hpp"

#include <pthread.h>

#include <atomic>
#include <memory>
#include <mutex>

#include "thread_pool.hpp"

namespace swarmcollide::detail {

namespace {

// The kept threads and the lock their one user holds. Never freed: a forked child abandons its
// parent's (their threads do not exist in the child, and the lock may be held by one of them)
// and keeps them reachable in `abandoned`, for leak checkers.
struct Kept {
  std::mutex in_use;
  std::unique_ptr<ThreadPool> pool;
  Kept* abandoned_before = nullptr;
};

std::atomic<Kept*> kept{nullptr};
Kept* abandoned = nullptr;

// Runs in a forked child, on its only thread, before fork returns there.
void abandon_in_child() {
  Kept* const parents = kept.exchange(nullptr);
  if (parents == nullptr) return;
  parents->abandoned_before = abandoned;
  abandoned = parents;
}

Kept& kept_threads() {
  Kept* now = kept.load(std::memory_order_acquire);
  if (now != nullptr) return *now;
  static std::once_flag registered;
  std::call_once(registered, [] { pthread_atfork(nullptr, nullptr, &abandon_in_child); });
  auto* const fresh = new Kept;
  if (kept.compare_exchange_strong(now, fresh, std::memory_order_acq_rel)) return *fresh;
  delete fresh;  // another thread made them first
  return *now;
}

}  // namespace

void run_copies(std::size_t copies, const std::function<void(std::size_t)>& work) {
  if (copies == 0) return;
  if (copies == 1) return work(0);
  const auto each = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) work(k);
  };
  const int threads = static_cast<int>(copies);
  Kept& threads_kept = kept_threads();
  std::unique_lock<std::mutex> lock(threads_kept.in_use, std::try_to_lock);
  if (!lock.owns_lock()) {
    ThreadPool own(threads);
    return own.for_each_chunk(copies, 1, each);
  }
  // A pool larger than asked for runs the copies on some of its threads; the others wake and
  // find nothing to do.
  if (!threads_kept.pool || threads_kept.pool->size() < threads) {
    threads_kept.pool.reset();  // joins the old threads before the new ones start
    threads_kept.pool = std::make_unique<ThreadPool>(threads);
  }
  threads_kept.pool->for_each_chunk(copies, 1, each);
}

}  // namespace swarmcollide::detail
