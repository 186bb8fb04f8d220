// Polling the calling thread's interruption check from a solver's loop; private to the library's
// sources.
#pragma once

#include "swarmcollide/interruption.hpp"

namespace swarmcollide::detail {

/// The calling thread's check and its context (both null without an InterruptionGuard).
struct InterruptionHook {
  InterruptionCheck check = nullptr;
  void* context = nullptr;
};

/// The calling thread's hook. A thread-local read (a call into the dynamic linker in a shared
/// library), so a solver reads it once, into an InterruptionPoll, not in its loop.
InterruptionHook current_interruption_hook() noexcept;

/// The calling thread's check as it was when the solve began: calling it costs one predictable
/// branch when there is none. Poll only in loops whose iterations take a microsecond or more: a
/// check may read a clock (the bindings' does, about 25 ns).
class InterruptionPoll {
 public:
  InterruptionPoll() noexcept : hook_(current_interruption_hook()) {}

  /// Throws Interrupted when the thread's check says to stop.
  void operator()() const {
    if (hook_.check != nullptr && hook_.check(hook_.context)) throw Interrupted();
  }

 private:
  InterruptionHook hook_;
};

}  // namespace swarmcollide::detail
