#pragma once

#include <exception>

namespace swarmcollide {

/// Thrown out of a query when its thread's interruption check (InterruptionGuard) asked it to
/// stop. The answer is lost; the bodies, the Query and the thread's state stay as they were, so
/// the next query answers as if this one had never started.
class Interrupted : public std::exception {
 public:
  /// "interrupted".
  const char* what() const noexcept override;
};

/// A check that the solves able to run for seconds (the swarms on model (2) and over directions,
/// the penalty method) call between their iterations, with the `context` it was installed
/// with; returning true stops the solve with Interrupted. It only reads: what it returns can
/// stop a solve but never changes an answer.
using InterruptionCheck = bool (*)(void* context);

/// Installs `check` as the calling thread's interruption check while it lives, and restores the
/// one before when it goes (guards nest). Only the installing thread calls it: the other threads
/// of its batches stop when it says so (they read a flag), those of scenes, robots and motions
/// run without a check. Without a guard, solves check nothing (one branch).
class InterruptionGuard {
 public:
  /// Installs `check` (null: none) with `context` for the calling thread.
  InterruptionGuard(InterruptionCheck check, void* context) noexcept;
  /// Restores the thread's previous check.
  ~InterruptionGuard();
  InterruptionGuard(const InterruptionGuard&) = delete;
  InterruptionGuard& operator=(const InterruptionGuard&) = delete;

 private:
  InterruptionCheck previous_check_;
  void* previous_context_;
};

}  // namespace swarmcollide
