// The support points a curved body has answered in one query; private to the library's sources.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstring>
#include <vector>

#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// A curved body's support points so far in a query (FramedBody::curved_support), numbered in
/// the order found, with a hash table from a point's coordinates to its number: searches ask for
/// the same point again and again as they converge, and it keeps its number. Rows are reserved
/// in blocks (a query asks for a few dozen points), so a new point costs no allocation, and
/// finding one costs a hash, not a scan of every point so far (the two were 30% of a curved
/// signed distance: a reallocation per point, a linear scan per query).
class SupportCache {
 public:
  /// Starts with `initial`'s rows (the body's own points, all on its surface).
  explicit SupportCache(const VertexMatrix& initial)
      : points_(capacity_for(initial.rows()), 3), owned_(2 * points_.rows(), -1) {
    own_table();
    for (Eigen::Index i = 0; i < initial.rows(); ++i) add(initial.row(i).transpose());
  }
  /// A copy of `other`'s points and table (not of its users).
  SupportCache(const SupportCache& other)
      : points_(other.points_),
        owned_(other.slots_, other.slots_ + other.mask_ + 1),
        count_(other.count_) {
    own_table();
  }
  SupportCache& operator=(const SupportCache&) = delete;
  /// Starts again as `start`, a cache holding a body's own points only, keeping this one's
  /// storage: the points are numbered as `start` numbers them, so a reused cache answers as a
  /// new one. Its points are copied, but its table is only read until a point is added: a query
  /// that adds none (a closed form, point_against_curved) copies no table, and one that adds
  /// points copies it then (a cache that grew keeps its table's capacity but takes `start`'s
  /// table, so that it costs a copy, not a rehash). `start` must outlive this cache's use, as
  /// the body that holds it outlives the framed body that reads this cache.
  void reset(const SupportCache& start);

  /// The number of `point` (exact equality of coordinates, -0 = +0), added when it is new.
  int add(const Vector3& point) {
    const Vector3 p = point + Vector3::Zero();  // -0 + 0 = +0, so both zeros hash alike
    if (count_ == limit_) return add_growing(p, find(p));
    // Below the limit the row `count_` exists, unused: the point is written there before the
    // search for it, which then needs only its coordinates' registers (a point found leaves the
    // row unused again). Kept until after the search, they went to the stack and back: the
    // expanding polytope's curved supports (FramedBody::curved_support) made the overlapping
    // curved rows 10-197 instructions longer (callgrind_curved). The searches' inline supports
    // (add_without_negative_zeros) search first: written ahead there, the cone rows apart took
    // up to 112 instructions more.
    points_.row(count_) = p.transpose();
    const std::size_t slot = find(p);
    if (slots_[slot] >= 0) return slots_[slot];
    slots_[slot] = count_;
    return count_++;
  }
  /// `add(p)` for a point without -0 coordinates (a sum with +0 already, as the curved searches'
  /// supports place it): the same number, without adding +0 again (the compiler keeps both
  /// additions, two instructions of every curved support call).
  int add_without_negative_zeros(const Vector3& p) {
    const std::size_t slot = find(p);
    if (slots_[slot] >= 0) return slots_[slot];
    // A full table grows out of line, and a borrowed one is copied there: inlined, the growth
    // made every call save and restore the registers it uses (a cylinder pair apart: 3.7% of its
    // query's instructions).
    if (count_ == limit_) return add_growing(p, slot);
    slots_[slot] = count_;
    points_.row(count_) = p.transpose();
    return count_++;
  }
  /// Number of points found (the first `count()` rows of `points()`).
  int count() const { return count_; }
  /// The points, one per row; rows from `count()` on are unused.
  const VertexMatrix& points() const { return points_; }

 private:
  static Eigen::Index capacity_for(Eigen::Index rows) {
    Eigen::Index capacity = 64;
    while (capacity < 2 * rows) capacity *= 2;
    return capacity;
  }
  static std::uint64_t bits(Scalar x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  }
  static std::uint64_t rotated(std::uint64_t b, int by) { return b << by | b >> (64 - by); }
  // The coordinates' bits turned apart (so that points with permuted coordinates differ), mixed
  // by one multiplication, whose upper half depends on every bit below it: a slot is its bits
  // from 32 up. Half the instructions of three multiplications chained, on every support call;
  // the numbering, in the order points are found, does not depend on the slots.
  static std::size_t hash(const Vector3& p) {
    const std::uint64_t h =
        (bits(p.x()) ^ rotated(bits(p.y()), 21) ^ rotated(bits(p.z()), 42)) * 0x9E3779B97F4A7C15ull;
    return static_cast<std::size_t>(h >> 32);
  }
  // The slot holding `p`, or the empty slot where it goes.
  std::size_t find(const Vector3& p) const {
    std::size_t slot = hash(p) & mask_;
    for (int i = slots_[slot]; i >= 0; i = slots_[slot]) {
      if (points_(i, 0) == p.x() && points_(i, 1) == p.y() && points_(i, 2) == p.z()) break;
      slot = (slot + 1) & mask_;
    }
    return slot;
  }
  // The table is this cache's own storage: full at half its slots.
  void own_table() {
    slots_ = owned_.data();
    mask_ = owned_.size() - 1;
    limit_ = static_cast<int>(owned_.size() / 2);
  }
  // Adds `p` (with -0 as +0), whose slot `find` gave, where `add` cannot (count_ is limit_): its
  // number if the slot holds it, else the new point added to a borrowed table, which it copies
  // into this cache's storage first (the slot is the copy's), or to a full one, which it doubles
  // (kept at most half full), rehashing the points, and the rows when they are full
  // (support_cache.cpp). There are always at least half as many rows as slots (reset keeps a
  // grown cache's rows but takes the start's smaller table), so a full table comes first: below
  // the limit, the row `count_` exists.
  int add_growing(const Vector3& p, std::size_t slot);

  VertexMatrix points_;
  // The table's storage, and the table itself: the storage, or after a reset the start's table,
  // read only (the first point added copies it: count_ is limit_ there). Its size less one (a
  // power of two) masks the hashes; add goes out of line when count_ reaches limit_ (half the
  // size, or the count at the reset while borrowed). Members rather than the vector's size: each
  // support call of a search reads them, where the size was a subtraction and a shift.
  std::vector<int> owned_;
  int* slots_ = nullptr;
  std::size_t mask_ = 0;
  int limit_ = 0;
  int count_ = 0;
  // The handles (SharedSupportCache) that share this cache.
  std::atomic<int> users_{0};
  friend class SharedSupportCache;
};

/// A SupportCache shared by the copies of a FramedBody (a copy of a framed pair sees the points
/// the original found, and adds to them), taken from a pool of the thread's and given back when
/// the last copy goes: a curved query then allocates nothing once its thread has answered one
/// (the allocations of a new cache were a fifth of a sphere-cylinder query).
class SharedSupportCache {
 public:
  SharedSupportCache() = default;
  /// A cache started as `start` (SupportCache::reset).
  explicit SharedSupportCache(const SupportCache& start);
  SharedSupportCache(const SharedSupportCache& other) : cache_(other.cache_) { hold(); }
  SharedSupportCache& operator=(const SharedSupportCache& other) {
    if (cache_ != other.cache_) {
      drop();
      cache_ = other.cache_;
      hold();
    }
    return *this;
  }
  SharedSupportCache(SharedSupportCache&& other) noexcept : cache_(other.cache_) {
    other.cache_ = nullptr;
  }
  SharedSupportCache& operator=(SharedSupportCache&& other) noexcept {
    if (this != &other) {
      drop();
      cache_ = other.cache_;
      other.cache_ = nullptr;
    }
    return *this;
  }
  ~SharedSupportCache() { drop(); }

  SupportCache& operator*() const { return *cache_; }
  SupportCache* operator->() const { return cache_; }

 private:
  void hold() {
    if (cache_ != nullptr) cache_->users_.fetch_add(1, std::memory_order_relaxed);
  }
  void drop() {
    if (cache_ != nullptr && cache_->users_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
      release(cache_);
    }
    cache_ = nullptr;
  }
  // Gives an unused cache back to this thread's pool (or frees it).
  static void release(SupportCache* cache);

  SupportCache* cache_ = nullptr;
};

}  // namespace swarmcollide::detail
