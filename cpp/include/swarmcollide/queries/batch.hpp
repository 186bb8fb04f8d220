#pragma once

#include <cstdint>
#include <vector>

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/queries/distance.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// The answers to many queries, one entry (or row) per pair.
struct BatchResult {
  VectorX distance;
  VectorX lower_bound;
  VertexMatrix point_a;
  VertexMatrix point_b;
  Eigen::Array<bool, Eigen::Dynamic, 1> colliding;
  Eigen::Array<bool, Eigen::Dynamic, 1> certified;
  Eigen::Array<int, Eigen::Dynamic, 1> iterations;
  /// True where `collide_many` handed an unproven verdict to the exact method.
  Eigen::Array<bool, Eigen::Dynamic, 1> escalated;
};

/// The seed of pair `index` in a batch seeded with `seed`: independent of the thread count.
std::uint64_t pair_seed(std::uint64_t seed, std::size_t index);

/// `distance(as[i], bs[i], options)` for every i, spread over `threads` threads (0: one per
/// hardware thread), with pair i seeded by `pair_seed(seed, i)` for each solver's seed. Throws
/// std::invalid_argument if the sequences differ in length; the first error of any pair is
/// rethrown after all threads stop.
BatchResult distance_many(const std::vector<ConvexPolyhedron>& as,
                          const std::vector<ConvexPolyhedron>& bs, const DistanceOptions& options,
                          int threads = 0);

/// `collision(as[i], bs[i], options, escalate)` for every i, like `distance_many`.
BatchResult collide_many(const std::vector<ConvexPolyhedron>& as,
                         const std::vector<ConvexPolyhedron>& bs, const DistanceOptions& options,
                         bool escalate = true, int threads = 0);

/// `count` bodies of `vertices` points each, stored one after another: body i's points are the
/// rows i * vertices to (i + 1) * vertices - 1 of a row-major (count * vertices, 3) array. `name`
/// is what errors call the sequence ("As[3]: ...").
struct VertexStack {
  const Scalar* points;
  std::size_t count;
  Eigen::Index vertices;
  const char* name;
};

/// `distance_many` over bodies built from vertex stacks. Each pair's bodies are built, answered
/// and freed on the thread that answers the pair, so building and freeing them is spread over
/// the threads too and no thread frees memory that another allocated. A body that cannot be
/// built throws std::invalid_argument naming it.
BatchResult distance_many(const VertexStack& as, const VertexStack& bs,
                          const DistanceOptions& options, int threads = 0);

/// `collide_many` over bodies built from vertex stacks, like the `distance_many` above.
BatchResult collide_many(const VertexStack& as, const VertexStack& bs,
                         const DistanceOptions& options, bool escalate = true, int threads = 0);

}  // namespace swarmcollide
