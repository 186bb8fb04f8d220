// The number of hardware threads, read once; private to the library's sources.
#pragma once

#include <algorithm>
#include <thread>

namespace swarmcollide::detail {

/// The threads that "one per hardware thread" means, at least 1. Read once per process:
/// `std::thread::hardware_concurrency` opens and reads a file under /sys on every call (glibc
/// 2.36), 7.5 us, which every batch call with the default threads paid.
inline unsigned hardware_threads() {
  static const unsigned count = std::max(1u, std::thread::hardware_concurrency());
  return count;
}

}  // namespace swarmcollide::detail
