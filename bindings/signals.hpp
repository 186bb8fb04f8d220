// Ctrl-C in long queries: Python's signal handlers run while a query's solver iterates.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <optional>

#include "swarmcollide/interruption.hpp"

namespace swarmcollide::bindings {

namespace py = pybind11;

/// The error a Python signal handler raised during a query (KeyboardInterrupt for Ctrl-C): the
/// query was abandoned, so a fast path raises it rather than retrying the call on another path.
class SignalRaised : public py::error_already_set {
 public:
  explicit SignalRaised(const py::error_already_set& error) : py::error_already_set(error) {}
};

/// Runs `solve()` with the calling thread's interruption check running Python's signal handlers
/// (PyErr_CheckSignals, which runs them on the main thread only) at the solver's first check and
/// then at most every 20 ms, taking the GIL for it where `solve` released it. A solve stopped by
/// a handler's error throws SignalRaised with it. Called with the GIL held.
template <typename Solve>
auto interruptible(const Solve& solve);

namespace detail {

// The check installed by interruptible(), and the error that stopped the solve.
class SignalCheck {
 public:
  SignalCheck() noexcept : guard_(&SignalCheck::check, this) {}
  const std::optional<py::error_already_set>& error() const { return error_; }

 private:
  static bool check(void* self);

  std::int64_t next_ = 0;  // ms of a monotonic clock: the first check calls Python
  std::optional<py::error_already_set> error_;
  InterruptionGuard guard_;  // last: installed once the rest is ready, uninstalled first
};

}  // namespace detail

template <typename Solve>
auto interruptible(const Solve& solve) {
  detail::SignalCheck signals;
  try {
    return solve();
  } catch (const Interrupted&) {
    if (!signals.error()) throw;  // another check's (a guard installed by the caller)
    throw SignalRaised(*signals.error());
  }
}

}  // namespace swarmcollide::bindings
