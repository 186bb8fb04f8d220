// The support points a curved body has answered in one query; private to the library's sources.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <utility>
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
  /// A cache of `initial`'s rows that adds no point (`add` hands a new one to its caller): a
  /// body's own, which its framings read until they find a new support point
  /// (SharedSupportCache::reading), then copy (SharedSupportCache's constructor). Sealed, it is
  /// only read, so every thread may read it.
  static SupportCache sealed(const VertexMatrix& initial) {
    SupportCache cache(initial);
    cache.sealed_ = true;
    cache.limit_ = cache.count_;  // every new point goes to add's test of the seal
    return cache;
  }
  /// Moved whole, sealed or not (into the body's derived data, ConvexPolyhedron::derived).
  SupportCache(SupportCache&& other) noexcept
      : points_(std::move(other.points_)),
        owned_(std::move(other.owned_)),
        slots_(other.slots_),
        mask_(other.mask_),
        limit_(other.limit_),
        count_(other.count_),
        sealed_(other.sealed_) {}
  /// A copy of `other`'s points and table (not of its users), not sealed.
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
  /// that adds none copies no table (a ball's closed form against a curved body takes no cache at
  /// all: SharedSupportCache::reading), and one that adds points copies it then (a cache that
  /// grew keeps its table's capacity but takes `start`'s table, so that it costs a copy, not a
  /// rehash). `start` must outlive this cache's use, as the body that holds it outlives the
  /// framed body that reads this cache.
  void reset(const SupportCache& start);

  /// The number of `point` (exact equality of coordinates, -0 = +0), added when it is new; a
  /// new point of a sealed cache is `sealed_add(p, slot)`'s (`p` the point with -0 as +0, `slot`
  /// as add_new takes it), and the cache is left as it was. The seal is tested where a new point
  /// meets a full or borrowed table, which add tests anyway: the points found and added cost no
  /// more.
  template <typename SealedAdd>
  int add(const Vector3& point, const SealedAdd& sealed_add) {
    const Vector3 p = point + Vector3::Zero();  // -0 + 0 = +0, so both zeros hash alike
    if (count_ == limit_) return add_at_limit(p, find(p), sealed_add);
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
  /// `add(p, sealed_add)` for a point without -0 coordinates (a sum with +0 already, as the
  /// curved searches' supports place it): the same number, without adding +0 again (the compiler
  /// keeps both additions, two instructions of every curved support call).
  template <typename SealedAdd>
  int add_without_negative_zeros(const Vector3& p, const SealedAdd& sealed_add) {
    const std::size_t slot = find(p);
    if (slots_[slot] >= 0) return slots_[slot];
    if (count_ == limit_) return add_at_limit(p, slot, sealed_add);
    return insert(p, slot);
  }
  /// The same for a cache that is not sealed.
  int add(const Vector3& point) {
    return add(point, [](const Vector3&, std::size_t) -> int {
      throw std::logic_error("a sealed SupportCache was asked to add a point");
    });
  }
  /// Adds `p` (with -0 as +0), not among the points, whose empty slot `find` gave: in this
  /// cache's table, or in the table of the sealed cache it was started from (a copy or a reset of
  /// it, whose table has the same slots) for the first point not among that one's.
  int add_new(const Vector3& p, std::size_t slot) {
    if (count_ == limit_) return add_growing(p, slot);
    return insert(p, slot);
  }
  /// True for a sealed cache (`sealed`).
  bool is_sealed() const { return sealed_; }
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
  // Adds `p`, new, at its empty slot in a table that is not full.
  int insert(const Vector3& p, std::size_t slot) {
    slots_[slot] = count_;
    points_.row(count_) = p.transpose();
    return count_++;
  }
  // The table is this cache's own storage: full at half its slots.
  void own_table() {
    slots_ = owned_.data();
    mask_ = owned_.size() - 1;
    limit_ = static_cast<int>(owned_.size() / 2);
  }
  // Adds the new point `p` (with -0 as +0), whose empty slot `find` gave, where `add` cannot
  // (count_ is limit_): to a borrowed table, which it copies into this cache's storage first (the
  // slot is the copy's), or to a full one, which it doubles (kept at most half full), rehashing
  // the points, and the rows when they are full (support_cache.cpp). There are always at least
  // half as many rows as slots (reset keeps a grown cache's rows but takes the start's smaller
  // table), so a full table comes first: below the limit, the row `count_` exists.
  int add_growing(const Vector3& p, std::size_t slot);
  // The number of `p` at `slot` (find's) where count_ is limit_: held, or new, then a sealed
  // cache's `sealed_add`'s and any other's add_growing's (out of line: inlined, the growth made
  // every support call save and restore the registers it uses, 3.7% of a cylinder pair's query).
  template <typename SealedAdd>
  int add_at_limit(const Vector3& p, std::size_t slot, const SealedAdd& sealed_add) {
    if (slots_[slot] >= 0) return slots_[slot];
    return sealed_ ? sealed_add(p, slot) : add_growing(p, slot);
  }

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
  // A body's own points, which no query adds to (sealed()).
  bool sealed_ = false;
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
  explicit SharedSupportCache(const SupportCache& start) : cache_(started_as(start)) {}
  /// A handle that reads the sealed cache `start` without holding a cache of its own (nor
  /// counting itself among `start`'s users): a body that finds no new support point (a ball's
  /// closed form against a cylinder) takes none from the pool. `start` must outlive it.
  static SharedSupportCache reading(const SupportCache& start) {
    SharedSupportCache handle;
    // Never written through: a sealed cache hands every new point to add's caller.
    handle.cache_ = const_cast<SupportCache*>(&start);
    return handle;
  }
  /// Holds, in place of the sealed cache this handle reads (reading), a cache of its own started
  /// as that one.
  void own() { cache_ = started_as(*cache_); }
  /// The number of unused caches in this thread's pool (for tests: what a query takes from it).
  static std::size_t pooled();
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
  // A sealed cache (reading) is a body's, which counts no users and is never given back.
  void hold() {
    if (cache_ != nullptr && !cache_->sealed_) {
      cache_->users_.fetch_add(1, std::memory_order_relaxed);
    }
  }
  void drop() {
    if (cache_ != nullptr && !cache_->sealed_ &&
        cache_->users_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
      release(cache_);
    }
    cache_ = nullptr;
  }
  // A cache of this thread's pool (or a new one) started as `start`, held once.
  static SupportCache* started_as(const SupportCache& start);
  // Gives an unused cache back to this thread's pool (or frees it).
  static void release(SupportCache* cache);

  SupportCache* cache_ = nullptr;
};

}  // namespace swarmcollide::detail
