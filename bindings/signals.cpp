#include "signals.hpp"

namespace swarmcollide::bindings::detail {

namespace {

// How long a solve runs between two calls to Python's signal handlers: Ctrl-C answers within
// this, and the calls (with the GIL to take, which another thread may hold for up to its switch
// interval, 5 ms) cost a solve nothing measurable.
constexpr std::chrono::milliseconds kSignalInterval{20};

}  // namespace

bool SignalCheck::check(void* self) {
  auto& signals = *static_cast<SignalCheck*>(self);
  const auto now = std::chrono::steady_clock::now();
  if (now < signals.next_) return false;
  signals.next_ = now + kSignalInterval;
  const PyGILState_STATE gil = PyGILState_Ensure();
  const bool raised = PyErr_CheckSignals() != 0;
  if (raised) signals.error_.emplace();  // fetches the handler's error, clearing it
  PyGILState_Release(gil);
  return raised;
}

}  // namespace swarmcollide::bindings::detail
