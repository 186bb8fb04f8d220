#include "support_cache.hpp"

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

namespace swarmcollide::detail {

namespace {

// The caches a thread has given back, for its next curved queries. A thread holds a few at a
// time (two per framed pair); more than kKept unused ones are freed.
constexpr std::size_t kKept = 16;

struct Pool {
  std::vector<std::unique_ptr<SupportCache>> unused;
};

// The thread's pool while it lives, null before its first use and after its destruction at
// thread exit: a pointer has no destructor, so a cache given back by another thread-local's
// destructor after the pool's reads null here (and is freed) rather than a destroyed object.
thread_local Pool* current = nullptr;

struct PoolOwner {
  Pool pool;
  PoolOwner() { current = &pool; }
  ~PoolOwner() { current = nullptr; }
};

// The thread's pool, made on first use; null once it is destroyed.
Pool* pool() {
  thread_local bool made = false;
  if (!made) {
    made = true;
    thread_local PoolOwner owner;
  }
  return current;
}

}  // namespace

int SupportCache::add_growing(const Vector3& p, std::size_t slot) {
  if (slots_[slot] >= 0) return slots_[slot];
  if (slots_ != owned_.data()) {
    // The start's table, borrowed since the reset, copied (a vector keeps its capacity, so a grown
    // table is not reallocated; the start's is never full).
    const int* borrowed = slots_;
    owned_.resize(mask_ + 1);
    std::copy_n(borrowed, owned_.size(), owned_.data());
    own_table();
  } else {
    if (count_ == points_.rows()) points_.conservativeResize(2 * points_.rows(), Eigen::NoChange);
    owned_.assign(2 * owned_.size(), -1);
    own_table();
    for (int i = 0; i < count_; ++i) slots_[find(points_.row(i).transpose())] = i;
    slot = find(p);
  }
  slots_[slot] = count_;
  points_.row(count_) = p.transpose();
  return count_++;
}

void SupportCache::reset(const SupportCache& start) {
  // The first rows copied; the rows stay at least half the table's size.
  count_ = start.count_;
  if (points_.rows() < start.points_.rows()) points_.resize(start.points_.rows(), Eigen::NoChange);
  // Row-major: the first rows are the first 3 count_ coordinates, one memmove (Eigen's block
  // assignment went entry by entry).
  std::copy_n(start.points_.data(), 3 * static_cast<std::size_t>(count_), points_.data());
  // Never written through while borrowed: the first point added makes count_ reach limit_, and
  // add_growing copies the table before it writes.
  slots_ = start.slots_;
  mask_ = start.mask_;
  limit_ = count_;
}

SharedSupportCache::SharedSupportCache(const SupportCache& start) {
  Pool* p = pool();
  if (p && !p->unused.empty()) {
    cache_ = p->unused.back().release();
    p->unused.pop_back();
    cache_->reset(start);
  } else {
    cache_ = new SupportCache(start);
  }
  hold();
}

void SharedSupportCache::release(SupportCache* cache) {
  Pool* p = pool();
  if (p && p->unused.size() < kKept) {
    p->unused.emplace_back(cache);
  } else {
    delete cache;
  }
}

}  // namespace swarmcollide::detail
