// Polling the calling thread's interruption check from a solver's loop; private to the library's
// sources.
#pragma once

#include <atomic>

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
/// check may read a clock (the bindings' does, in 5 ns).
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

/// The calling thread's check spread over the threads that share its work (a batch's rows): the
/// caller's check raises a flag when it says to stop, and every thread's check reads the flag,
/// so each thread stops at its next poll. Only the caller calls its own check (the bindings'
/// runs Python, which only the calling thread may). Without a check, the threads get none.
class SharedInterruption {
 public:
  /// Reads the calling thread's check.
  SharedInterruption() noexcept : caller_(current_interruption_hook()) {}

  /// A guard installing, for the thread it is made on, the check for the caller (`on_caller`)
  /// or for a thread helping it.
  InterruptionGuard install(bool on_caller) {
    if (caller_.check == nullptr) return InterruptionGuard(nullptr, nullptr);
    return InterruptionGuard(on_caller ? &check_caller : &check_helper, this);
  }

 private:
  static bool check_caller(void* self) {
    auto& shared = *static_cast<SharedInterruption*>(self);
    if (shared.stopped_.load(std::memory_order_relaxed)) return true;
    if (!shared.caller_.check(shared.caller_.context)) return false;
    shared.stopped_.store(true, std::memory_order_relaxed);
    return true;
  }
  static bool check_helper(void* self) {
    return static_cast<SharedInterruption*>(self)->stopped_.load(std::memory_order_relaxed);
  }

  InterruptionHook caller_;
  std::atomic<bool> stopped_{false};
};

}  // namespace swarmcollide::detail
