// Threads kept for the process's batch calls; private to the library's sources.
#pragma once

#include <cstddef>
#include <functional>

namespace swarmcollide::detail {

/// Calls `work(k)` once for every k in [0, copies), the copies on different threads where they
/// can be (the caller runs one, and any copy no other thread has started by then), and returns
/// when every copy has returned, rethrowing the exception of the lowest k that threw. The other
/// threads are kept for the process's next call: starting and joining a thread costs 20-70 us on
/// a VM, the time of hundreds of rows of a small batch. A call made while another holds the kept
/// threads (from another thread of the program, or from inside `work`) starts threads of its
/// own, as does the first call in a forked child (the parent's threads do not exist there).
void run_copies(std::size_t copies, const std::function<void(std::size_t)>& work);

}  // namespace swarmcollide::detail
