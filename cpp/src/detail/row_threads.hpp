// Answering a batch's rows (a robot's configurations or motions, time_of_impact_many's motions) on
// threads, each answered whole by one thread; private to the library's sources.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>

#include "hardware_threads.hpp"
#include "kept_threads.hpp"
#include "waking_pace.hpp"
#include "swarmcollide/queries/batch.hpp"

namespace swarmcollide::detail {

/// Runs `answer(i)`, with `answer` each thread's own `make_answer()`, for every row i (a
/// configuration, or a motion) on `threads` threads (0: one per hardware thread) taking rows in
/// chunks, in increasing order, from one counter: when a row fails every one before it has been
/// taken, so the error rethrown is the lowest failing row's, prefixed "<label>[i]: ". Each row is
/// answered whole by one thread, so the answers do not depend on the threads. The calling thread
/// answers rows alone, one at a time, until the rows left are worth waking the others for
/// (WakingPace).
template <typename MakeAnswer>
void over_rows(std::size_t count, int threads, const MakeAnswer& make_answer,
               const char* label = "q") {
  if (threads < 0 || threads > kMaxThreads) {
    throw std::invalid_argument("threads must be in [0, " + std::to_string(kMaxThreads) +
                                "] (0: one per hardware thread), got " + std::to_string(threads));
  }
  const std::size_t wanted = threads > 0 ? static_cast<std::size_t>(threads)
                                         : detail::hardware_threads();
  const std::size_t workers = std::min(wanted, std::max<std::size_t>(count, 1));
  // Up to 8 rows a chunk, fewer towards the end, so that the threads finish together: a thread
  // woken late (WakingPace) took a chunk of 8 rows of tens of microseconds each near the end, and
  // the caller waited for it.
  const auto chunk_size = [count, workers](std::size_t taken) {
    const std::size_t left = taken < count ? count - taken : 0;
    return std::clamp<std::size_t>(left / (4 * workers), 1, 8);
  };
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;
  std::size_t failed_row = count;
  std::exception_ptr error;
  const WakingPace pace(count);
  const auto work = [&](bool alone) {
    auto answer = make_answer();
    for (std::size_t answered = 0;; ++answered) {
      if (alone && pace.worth_waking(answered)) return;
      const std::size_t chunk = alone ? 1 : chunk_size(next.load(std::memory_order_relaxed));
      const std::size_t start = next.fetch_add(chunk, std::memory_order_relaxed);
      if (start >= count || failed.load(std::memory_order_relaxed)) return;
      for (std::size_t i = start; i < std::min(count, start + chunk); ++i) {
        try {
          answer(i);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(mutex);
          if (i < failed_row) {
            failed_row = i;
            error = std::current_exception();
          }
          failed.store(true, std::memory_order_relaxed);
          return;
        }
      }
    }
  };
  if (workers > 1) work(true);
  if (next.load(std::memory_order_relaxed) < count && !failed.load(std::memory_order_relaxed)) {
    run_copies(workers, [&](std::size_t) { work(false); });
  }
  if (!error) return;
  try {
    std::rethrow_exception(error);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(label) + "[" + std::to_string(failed_row) + "]: " +
                                e.what());
  }
}

}  // namespace swarmcollide::detail
