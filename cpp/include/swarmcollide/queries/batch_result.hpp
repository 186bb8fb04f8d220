#pragma once

#include <cstddef>
#include <memory>

#include "swarmcollide/types.hpp"

namespace swarmcollide {

namespace detail {
/// Frees (or keeps for reuse) the block of a BatchResult of `rows` rows.
struct FreeBatchBlock {
  std::size_t rows = 0;
  void operator()(void* block) const;
};
}  // namespace detail

/// The answers to many queries, one entry (or row) per pair, in the units of the input.
///
/// The arrays are views of one block of memory that the result owns: each array starts on a cache
/// line, and a block of 2 MiB or more lies on huge pages where the system offers them. A batch's
/// threads write chunks of rows that then share no cache line, and fault a large result's memory
/// in a few pages rather than in thousands (which cost a fifth of a cheap row's time, and more on
/// two threads). The last large block freed (up to 64 MiB) is kept for the next result of its
/// size, so that a batch repeated over poses writes into memory already mapped. Copies copy the
/// block; a moved-from result is empty.
class BatchResult {
 public:
  /// A column of values, one per row.
  template <typename T>
  using Column = Eigen::Map<Eigen::Array<T, Eigen::Dynamic, 1>>;

  /// An empty result.
  BatchResult() : BatchResult(0) {}
  /// A result of `rows` rows whose entries are not yet written.
  explicit BatchResult(std::size_t rows);
  BatchResult(const BatchResult& other);
  BatchResult& operator=(const BatchResult& other);
  BatchResult(BatchResult&& other) noexcept;
  BatchResult& operator=(BatchResult&& other) noexcept;
  ~BatchResult() = default;

  /// The number of rows.
  std::size_t rows() const { return rows_; }

  Eigen::Map<VectorX> distance{nullptr, 0};
  Eigen::Map<VectorX> lower_bound{nullptr, 0};
  Eigen::Map<VertexMatrix> point_a{nullptr, 0, 3};
  Eigen::Map<VertexMatrix> point_b{nullptr, 0, 3};
  /// Unit directions from A to B certifying the lower bounds (contact normals for signed
  /// distances); zero rows where none was found.
  Eigen::Map<VertexMatrix> direction{nullptr, 0, 3};
  Column<bool> colliding{nullptr, 0};
  Column<bool> certified{nullptr, 0};
  Column<int> iterations{nullptr, 0};
  /// True where another method than the one asked for answered (see
  /// DistanceResult::escalated_from).
  Column<bool> escalated{nullptr, 0};
  /// The parts of A and of B that realise each answer (see CompoundResult); 0 for convex bodies.
  Column<int> part_a{nullptr, 0};
  Column<int> part_b{nullptr, 0};

 private:
  // Points the arrays at `rows` rows of `block_`.
  void place(std::size_t rows);

  std::size_t rows_ = 0;
  std::unique_ptr<unsigned char, detail::FreeBatchBlock> block_;
};

}  // namespace swarmcollide
