#include "swarmcollide/queries/batch_result.hpp"

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace swarmcollide {

namespace {

constexpr std::size_t kCacheLine = 64;
// The size of a huge page on x86-64 and on most ARM64 systems: a block this large or larger is
// aligned to it and offered to the kernel for huge pages.
constexpr std::size_t kHugePage = std::size_t{2} << 20;

std::size_t round_up(std::size_t bytes, std::size_t alignment) {
  return (bytes + alignment - 1) / alignment * alignment;
}

// Where each array of a result of `rows` rows starts in its block, each on a cache line; `end` is
// the block's size.
struct Layout {
  explicit Layout(std::size_t rows) {
    std::size_t at = 0;
    const auto next = [&at, rows](std::size_t per_row) {
      const std::size_t start = at;
      at = round_up(at + rows * per_row, kCacheLine);
      return start;
    };
    distance = next(sizeof(Scalar));
    lower_bound = next(sizeof(Scalar));
    point_a = next(3 * sizeof(Scalar));
    point_b = next(3 * sizeof(Scalar));
    direction = next(3 * sizeof(Scalar));
    iterations = next(sizeof(int));
    part_a = next(sizeof(int));
    part_b = next(sizeof(int));
    colliding = next(sizeof(bool));
    certified = next(sizeof(bool));
    escalated = next(sizeof(bool));
    end = at;
  }
  std::size_t distance, lower_bound, point_a, point_b, direction, iterations, part_a, part_b,
      colliding, certified, escalated, end;
};

// The size of the block of a result of `rows` rows, and its alignment.
struct BlockSize {
  explicit BlockSize(std::size_t rows) {
    const std::size_t bytes = Layout(rows).end;
    alignment = bytes >= kHugePage ? kHugePage : kCacheLine;
    size = round_up(bytes, alignment);
  }
  std::size_t size;
  std::size_t alignment;
};

// The largest block kept for reuse once its result is freed (a result of about 600,000 rows).
constexpr std::size_t kLargestKept = std::size_t{64} << 20;

// One freed large block, kept for the next result of the same size: a batch repeated over poses
// (a planner's loop, a bench) then writes into memory that is already mapped, instead of faulting
// and zeroing every page again (a tenth of a cheap row's time on one thread, more on two threads
// faulting the same huge pages). The kernel may still take its pages back (MADV_FREE) under
// memory pressure; the block's contents do not matter.
class KeptBlock {
 public:
  // The kept block when it has `size` bytes (then no longer kept), else null.
  void* take(std::size_t size) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (block_ == nullptr || size_ != size) return nullptr;
    return std::exchange(block_, nullptr);
  }
  // Keeps `block` of `size` bytes (freeing the one kept before), or frees it when it is not a
  // large block.
  void keep(void* block, std::size_t size) {
    if (size < kHugePage || size > kLargestKept) return std::free(block);
#if defined(__linux__) && defined(MADV_FREE)
    madvise(block, size, MADV_FREE);
#endif
    void* freed = nullptr;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      freed = std::exchange(block_, block);
      size_ = size;
    }
    std::free(freed);
  }

 private:
  std::mutex mutex_;
  void* block_ = nullptr;
  std::size_t size_ = 0;
};

// Never destroyed: a result may be freed after static destructors have run.
KeptBlock& kept_block() {
  static KeptBlock* const kept = new KeptBlock;
  return *kept;
}

// The block of a result of `rows` rows (null for none).
unsigned char* allocate(std::size_t rows) {
  const BlockSize block_size(rows);
  if (block_size.size == 0) return nullptr;
  if (void* kept = kept_block().take(block_size.size)) return static_cast<unsigned char*>(kept);
  void* block = std::aligned_alloc(block_size.alignment, block_size.size);
  if (block == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: where huge pages are off (or not offered on request), the block stays on small
  // pages and nothing else changes.
  if (block_size.alignment == kHugePage) madvise(block, block_size.size, MADV_HUGEPAGE);
#endif
  return static_cast<unsigned char*>(block);
}

template <typename Map>
void point(Map& map, void* data, Eigen::Index rows) {
  // Re-seating an Eigen::Map is done by constructing it again in place.
  new (&map) Map(static_cast<typename Map::Scalar*>(data), rows, Map::ColsAtCompileTime);
}

}  // namespace

void detail::FreeBatchBlock::operator()(void* block) const {
  kept_block().keep(block, BlockSize(rows).size);
}

BatchResult::BatchResult(std::size_t rows)
    : block_(allocate(rows), detail::FreeBatchBlock{rows}) {
  place(rows);
}

BatchResult::BatchResult(const BatchResult& other) : BatchResult(other.rows_) {
  if (rows_ > 0) std::memcpy(block_.get(), other.block_.get(), Layout(rows_).end);
}

BatchResult& BatchResult::operator=(const BatchResult& other) {
  if (this != &other) *this = BatchResult(other);
  return *this;
}

BatchResult::BatchResult(BatchResult&& other) noexcept { *this = std::move(other); }

BatchResult& BatchResult::operator=(BatchResult&& other) noexcept {
  if (this != &other) {
    block_ = std::move(other.block_);
    place(other.rows_);
    other.place(0);
  }
  return *this;
}

void BatchResult::place(std::size_t rows) {
  rows_ = rows;
  const Layout at(rows);
  unsigned char* base = block_.get();
  const auto n = static_cast<Eigen::Index>(rows);
  const auto in = [base, rows](std::size_t offset) -> void* {
    return rows > 0 ? base + offset : nullptr;
  };
  point(distance, in(at.distance), n);
  point(lower_bound, in(at.lower_bound), n);
  point(point_a, in(at.point_a), n);
  point(point_b, in(at.point_b), n);
  point(direction, in(at.direction), n);
  point(iterations, in(at.iterations), n);
  point(part_a, in(at.part_a), n);
  point(part_b, in(at.part_b), n);
  point(colliding, in(at.colliding), n);
  point(certified, in(at.certified), n);
  point(escalated, in(at.escalated), n);
}

}  // namespace swarmcollide
