#include "signals.hpp"

#include <time.h>

#include <chrono>
#include <cstdint>

namespace swarmcollide::bindings::detail {

namespace {

// How long a solve runs between two calls to Python's signal handlers: Ctrl-C answers within
// this, and the calls (with the GIL to take, which another thread may hold for up to its switch
// interval, 5 ms) cost a solve nothing measurable.
constexpr std::int64_t kSignalInterval = 20;  // ms

// Milliseconds of a monotonic clock. Linux's coarse clock is read in 5 ns (the precise one in 25
// ns, 2% of a small swarm's iteration, which a batch of them paid) and ticks every 4 ms.
std::int64_t now_ms() {
#ifdef CLOCK_MONOTONIC_COARSE
  timespec now;
  clock_gettime(CLOCK_MONOTONIC_COARSE, &now);
  return static_cast<std::int64_t>(now.tv_sec) * 1000 + now.tv_nsec / 1000000;
#else
  using std::chrono::steady_clock;
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             steady_clock::now().time_since_epoch())
      .count();
#endif
}

}  // namespace

bool SignalCheck::check(void* self) {
  auto& signals = *static_cast<SignalCheck*>(self);
  const std::int64_t now = now_ms();
  if (now < signals.next_) return false;
  signals.next_ = now + kSignalInterval;
  const PyGILState_STATE gil = PyGILState_Ensure();
  const bool raised = PyErr_CheckSignals() != 0;
  if (raised) signals.error_.emplace();  // fetches the handler's error, clearing it
  PyGILState_Release(gil);
  return raised;
}

}  // namespace swarmcollide::bindings::detail
