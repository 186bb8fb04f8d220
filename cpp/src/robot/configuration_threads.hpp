// Answering configurations (or motions) on threads, each answered whole by one thread; private to
// the library's sources.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>

#include "../detail/hardware_threads.hpp"
#include "../detail/kept_threads.hpp"
#include "swarmcollide/queries/batch.hpp"

namespace swarmcollide::detail {

/// Runs `answer(i)`, with `answer` each thread's own `make_answer()`, for every row i (a
/// configuration, or a motion) on `threads` threads (0: one per hardware thread) taking rows in
/// chunks, in increasing order, from one counter: when a row fails every one before it has been
/// taken, so the error rethrown is the lowest failing row's, prefixed "<label>[i]: ". Each row is
/// answered whole by one thread, so the answers do not depend on the threads.
template <typename MakeAnswer>
void over_configurations(std::size_t count, int threads, const MakeAnswer& make_answer,
                         const char* label = "q") {
  if (threads < 0 || threads > kMaxThreads) {
    throw std::invalid_argument("threads must be in [0, " + std::to_string(kMaxThreads) +
                                "] (0: one per hardware thread), got " + std::to_string(threads));
  }
  const std::size_t wanted = threads > 0 ? static_cast<std::size_t>(threads)
                                         : detail::hardware_threads();
  const std::size_t workers = std::min(wanted, std::max<std::size_t>(count, 1));
  constexpr std::size_t kChunk = 8;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;
  std::size_t failed_row = count;
  std::exception_ptr error;
  const auto work = [&] {
    auto answer = make_answer();
    for (;;) {
      const std::size_t start = next.fetch_add(kChunk, std::memory_order_relaxed);
      if (start >= count || failed.load(std::memory_order_relaxed)) return;
      for (std::size_t i = start; i < std::min(count, start + kChunk); ++i) {
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
  run_copies(workers, [&](std::size_t) { work(); });
  if (!error) return;
  try {
    std::rethrow_exception(error);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(label) + "[" + std::to_string(failed_row) + "]: " +
                                e.what());
  }
}

}  // namespace swarmcollide::detail
