#include "swarmcollide/queries/batch.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "swarmcollide/detail/random.hpp"
#include "swarmcollide/queries/collide.hpp"

namespace swarmcollide {

std::uint64_t pair_seed(std::uint64_t seed, std::size_t index) {
  return detail::mix64(seed ^ detail::mix64(static_cast<std::uint64_t>(index)));
}

namespace {

BatchResult sized(std::size_t count) {
  const auto n = static_cast<Eigen::Index>(count);
  BatchResult result;
  result.distance.resize(n);
  result.lower_bound.resize(n);
  result.point_a.resize(n, 3);
  result.point_b.resize(n, 3);
  result.colliding.resize(n);
  result.certified.resize(n);
  result.iterations.resize(n);
  result.escalated.resize(n);
  return result;
}

void store(BatchResult& batch, std::size_t index, const DistanceResult& r) {
  const auto i = static_cast<Eigen::Index>(index);
  batch.distance(i) = r.distance;
  batch.lower_bound(i) = r.lower_bound;
  batch.point_a.row(i) = r.point_a.transpose();
  batch.point_b.row(i) = r.point_b.transpose();
  batch.colliding(i) = r.colliding;
  batch.certified(i) = r.certified;
  batch.iterations(i) = r.iterations;
  batch.escalated(i) = !r.escalated_from.empty();
}

// Runs `query(i, options_i)` for every pair on a pool of threads that take pairs in chunks.
template <typename Query>
BatchResult run_batch(std::size_t count, std::size_t other_count, const DistanceOptions& options,
                      int threads, const Query& query) {
  if (count != other_count) {
    throw std::invalid_argument("as and bs must have the same length, got " +
                                std::to_string(count) + " and " + std::to_string(other_count));
  }
  if (threads < 0) throw std::invalid_argument("threads must be >= 0 (0: all hardware threads)");
  BatchResult batch = sized(count);
  const std::size_t workers = std::min<std::size_t>(
      threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency()),
      std::max<std::size_t>(count, 1));
  constexpr std::size_t kChunk = 64;
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto work = [&] {
    DistanceOptions pair_options = options;
    for (std::size_t start = next.fetch_add(kChunk); start < count;
         start = next.fetch_add(kChunk)) {
      const std::size_t end = std::min(count, start + kChunk);
      for (std::size_t i = start; i < end; ++i) {
        try {
          pair_options.swarm.seed = pair_seed(options.swarm.seed, i);
          pair_options.dual.seed = pair_seed(options.dual.seed, i);
          store(batch, i, query(i, pair_options));
        } catch (...) {
          const std::lock_guard<std::mutex> lock(failure_mutex);
          if (!failure) failure = std::current_exception();
          next.store(count);
          return;
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  if (failure) std::rethrow_exception(failure);
  return batch;
}

// Body i of a stack, built on the calling thread.
ConvexPolyhedron body(const VertexStack& stack, std::size_t i) {
  const Scalar* points = stack.points + i * static_cast<std::size_t>(stack.vertices) * 3;
  try {
    return ConvexPolyhedron(Eigen::Map<const VertexMatrix>(points, stack.vertices, 3));
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(std::string(stack.name) + "[" + std::to_string(i) +
                                "]: " + error.what());
  }
}

}  // namespace

BatchResult distance_many(const std::vector<ConvexPolyhedron>& as,
                          const std::vector<ConvexPolyhedron>& bs, const DistanceOptions& options,
                          int threads) {
  return run_batch(
      as.size(), bs.size(), options, threads,
      [&](std::size_t i, const DistanceOptions& o) { return distance(as[i], bs[i], o); });
}

BatchResult collide_many(const std::vector<ConvexPolyhedron>& as,
                         const std::vector<ConvexPolyhedron>& bs, const DistanceOptions& options,
                         bool escalate, int threads) {
  return run_batch(as.size(), bs.size(), options, threads,
                   [&](std::size_t i, const DistanceOptions& o) {
                     return collision(as[i], bs[i], o, escalate);
                   });
}

BatchResult distance_many(const VertexStack& as, const VertexStack& bs,
                          const DistanceOptions& options, int threads) {
  return run_batch(as.count, bs.count, options, threads,
                   [&](std::size_t i, const DistanceOptions& o) {
                     const ConvexPolyhedron a = body(as, i);
                     const ConvexPolyhedron b = body(bs, i);
                     return distance(a, b, o);
                   });
}

BatchResult collide_many(const VertexStack& as, const VertexStack& bs,
                         const DistanceOptions& options, bool escalate, int threads) {
  return run_batch(as.count, bs.count, options, threads,
                   [&](std::size_t i, const DistanceOptions& o) {
                     const ConvexPolyhedron a = body(as, i);
                     const ConvexPolyhedron b = body(bs, i);
                     return collision(a, b, o, escalate);
                   });
}

}  // namespace swarmcollide
