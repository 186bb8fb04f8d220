// When a batch's calling thread should wake the other threads; private to the library's sources.
#pragma once

#include <chrono>
#include <cstddef>

namespace swarmcollide::detail {

/// The pace of the rows a calling thread answers alone at the start of a batch, and whether the
/// rows left are worth waking its other threads for. Waking a thread that has slept a millisecond
/// or more costs the caller 5-25 us (the futex's interrupt to the other core, through the
/// hypervisor) and that thread starts 15-140 us later (this project's 2-core VM;
/// `swarmcollide-thread-scaling wake`, bench/README Session 41): the other threads are woken only
/// when the rows left would take the caller longer than kWorthWaking. Woken at once, they made
/// batches of a few hundred microseconds slower on 2 threads than on 1 (collide_many of 500-2,000
/// rows 0.67-0.88x, robot.check of 2-32 configurations 0.57-0.87x, between 2 ms of Python work).
class WakingPace {
 public:
  // Where the other thread starts 50-80 us late and the caller pays 10-25 us to wake it, rows
  // left of 100-150 us ended no sooner on two threads than on one (robot.check of 16
  // configurations, 160 us, 0.82x; of 64 verdicts, 180 us, 0.94x) and those of 250 us or more
  // sooner (collide_many of 2,000 overlapping rows 1.40x, robot.check of 64 configurations 1.3x).
  static constexpr double kWorthWaking = 200e-6;  // seconds

  /// A batch of `count` rows whose calling thread starts now.
  explicit WakingPace(std::size_t count)
      : count_(count), start_(std::chrono::steady_clock::now()) {}

  /// True when the rows left after the `answered` first ones, at the pace those took, would take
  /// longer than kWorthWaking; false before two rows (a call's first row, on cold caches, is
  /// often its slowest).
  bool worth_waking(std::size_t answered) const {
    if (answered < 2) return false;
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start_;
    return elapsed.count() * static_cast<double>(count_ - answered) >
           kWorthWaking * static_cast<double>(answered);
  }

 private:
  std::size_t count_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace swarmcollide::detail
