#include "support_cache.hpp"

#include <memory>
#include <vector>

namespace swarmcollide::detail {

namespace {

// The caches a thread has given back, for its next curved queries. A thread holds a few at a
// time (two per framed pair); more than kKept unused ones are freed.
constexpr std::size_t kKept = 16;

struct Pool {
  std::vector<std::unique_ptr<SupportCache>> unused;
  // False once the thread's pool is destroyed (at thread exit): a cache given back after that is
  // freed.
  bool alive = true;
  ~Pool() { alive = false; }
};

Pool& pool() {
  thread_local Pool p;
  return p;
}

}  // namespace

void SupportCache::reset(const SupportCache& start) {
  // The table copied (a vector keeps its capacity, so a grown table is not reallocated), and the
  // first rows; the rows stay at least half the table's size.
  slots_ = start.slots_;
  count_ = start.count_;
  if (points_.rows() < start.points_.rows()) points_.resize(start.points_.rows(), Eigen::NoChange);
  points_.topRows(count_) = start.points_.topRows(count_);
}

SharedSupportCache::SharedSupportCache(const SupportCache& start) {
  Pool& p = pool();
  if (p.alive && !p.unused.empty()) {
    cache_ = p.unused.back().release();
    p.unused.pop_back();
    cache_->reset(start);
  } else {
    cache_ = new SupportCache(start);
  }
  hold();
}

void SharedSupportCache::release(SupportCache* cache) {
  Pool& p = pool();
  if (p.alive && p.unused.size() < kKept) {
    p.unused.emplace_back(cache);
  } else {
    delete cache;
  }
}

}  // namespace swarmcollide::detail
