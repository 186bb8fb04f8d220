#include "swarmcollide/queries/batch.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>

#include "swarmcollide/detail/random.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide {

std::uint64_t pair_seed(std::uint64_t seed, std::uint64_t index) {
  return detail::mix64(seed ^ detail::mix64(index));
}

namespace {

enum class Kind { distance, collide, signed_distance };

BatchResult sized(std::size_t count) {
  const auto n = static_cast<Eigen::Index>(count);
  BatchResult result;
  result.distance.resize(n);
  result.lower_bound.resize(n);
  result.point_a.resize(n, 3);
  result.point_b.resize(n, 3);
  result.direction.resize(n, 3);
  result.colliding.resize(n);
  result.certified.resize(n);
  result.iterations.resize(n);
  result.escalated.resize(n);
  result.part_a.setZero(n);
  result.part_b.setZero(n);
  return result;
}

void store(BatchResult& batch, std::size_t index, const DistanceResult& r) {
  const auto i = static_cast<Eigen::Index>(index);
  batch.distance(i) = r.distance;
  batch.lower_bound(i) = r.lower_bound;
  batch.point_a.row(i) = r.point_a.transpose();
  batch.point_b.row(i) = r.point_b.transpose();
  batch.direction.row(i) = r.direction.transpose();
  batch.colliding(i) = r.colliding;
  batch.certified(i) = r.certified;
  batch.iterations(i) = r.iterations;
  batch.escalated(i) = r.escalated_from.has_value();
}

void store(BatchResult& batch, std::size_t index, const CompoundResult& r) {
  store(batch, index, static_cast<const DistanceResult&>(r));
  batch.part_a(static_cast<Eigen::Index>(index)) = r.part_a;
  batch.part_b(static_cast<Eigen::Index>(index)) = r.part_b;
}

// The error of the pair with the lowest index, whatever thread met it.
class FirstFailure {
 public:
  void offer(std::size_t index) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (index < index_) {
      index_ = index;
      error_ = std::current_exception();
    }
  }
  bool any() const { return static_cast<bool>(error_); }
  void rethrow(std::uint64_t first_index) const {
    try {
      std::rethrow_exception(error_);
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      // Body errors already name their body ("As[3]: ...").
      if (message.rfind("As[", 0) == 0 || message.rfind("Bs[", 0) == 0) throw;
      throw std::invalid_argument("pair " + std::to_string(first_index + index_) + ": " + message);
    }
  }

 private:
  std::mutex mutex_;
  std::size_t index_ = std::numeric_limits<std::size_t>::max();
  std::exception_ptr error_;
};

std::size_t worker_count(int threads, std::size_t pairs) {
  if (threads < 0 || threads > kMaxThreads) {
    throw std::invalid_argument("threads must be in [0, " + std::to_string(kMaxThreads) +
                                "] (0: one per hardware thread), got " + std::to_string(threads));
  }
  const std::size_t wanted = threads > 0 ? static_cast<std::size_t>(threads)
                                         : std::max(1u, std::thread::hardware_concurrency());
  return std::min(wanted, std::max<std::size_t>(pairs, 1));
}

const Pose kIdentity{};

// Every pose valid, one per pair (or none).
void check_poses(const std::vector<Pose>& poses, std::size_t count, const char* name,
                 std::uint64_t first_index) {
  if (poses.empty()) return;
  if (poses.size() != count) {
    throw std::invalid_argument(std::string(name) + " must have one pose per pair, got " +
                                std::to_string(poses.size()) + " for " + std::to_string(count) +
                                " pairs");
  }
  for (std::size_t i = 0; i < count; ++i) {
    validate_pose(poses[i], name, first_index + i);
  }
}

const Pose& pose_of(const std::vector<Pose>& poses, std::size_t i) {
  return poses.empty() ? kIdentity : poses[i];
}

// Runs `answer(i, query_i)` for every pair on a pool of threads that take pairs in chunks, in
// increasing order: when a pair fails, every pair before it has been taken, so the error of the
// lowest failing index is found whatever the threads.
template <typename Answer>
BatchResult run_batch(std::size_t count, std::size_t other_count, const QueryOptions& options,
                      const BatchSettings& settings, const BatchPoses& poses,
                      const Answer& answer) {
  if (count != other_count) {
    throw std::invalid_argument("As and Bs must have the same length, got " +
                                std::to_string(count) + " and " + std::to_string(other_count));
  }
  check_poses(poses.a, count, "poses_a", settings.first_index);
  check_poses(poses.b, count, "poses_b", settings.first_index);
  const std::size_t workers = worker_count(settings.threads, count);
  const Query validated(options);
  BatchResult batch = sized(count);
  constexpr std::size_t kChunk = 64;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  FirstFailure failure;
  const auto work = [&] {
    QueryOptions pair_options = validated.options();
    for (std::size_t start = next.fetch_add(kChunk); start < count && !stop.load();
         start = next.fetch_add(kChunk)) {
      const std::size_t end = std::min(count, start + kChunk);
      for (std::size_t i = start; i < end; ++i) {
        try {
          pair_options.seed = pair_seed(options.seed, settings.first_index + i);
          store(batch, i, answer(i, Query(pair_options)));
        } catch (...) {
          failure.offer(i);
          stop.store(true);
          break;
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < workers; ++t) {
    try {
      pool.emplace_back(work);
    } catch (const std::system_error&) {
      break;  // the process cannot start more threads; the ones running share the work
    }
  }
  work();
  for (auto& thread : pool) thread.join();
  if (failure.any()) failure.rethrow(settings.first_index);
  return batch;
}

// DistanceResult for convex bodies, CompoundResult for compound ones.
template <typename Body>
auto ask(Kind kind, const Query& query, const Body& a, const Pose& pose_a, const Body& b,
         const Pose& pose_b, bool escalate) {
  switch (kind) {
    case Kind::distance:
      return query.distance(a, pose_a, b, pose_b);
    case Kind::collide:
      return query.collision(a, pose_a, b, pose_b, escalate);
    case Kind::signed_distance:
      break;
  }
  return query.signed_distance(a, pose_a, b, pose_b);
}

// Body i of a stack, built on the calling thread.
ConvexPolyhedron body(const VertexStack& stack, std::size_t i, std::uint64_t first_index) {
  const Scalar* points = stack.points + i * static_cast<std::size_t>(stack.vertices) * 3;
  try {
    return ConvexPolyhedron(Eigen::Map<const VertexMatrix>(points, stack.vertices, 3));
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(std::string(stack.name) + "[" + std::to_string(first_index + i) +
                                "]: " + error.what());
  }
}

template <typename Body>
BatchResult bodies_batch(Kind kind, const std::vector<Body>& as, const std::vector<Body>& bs,
                         const QueryOptions& options, const BatchSettings& settings,
                         const BatchPoses& poses) {
  return run_batch(as.size(), bs.size(), options, settings, poses,
                   [&](std::size_t i, const Query& query) {
                     return ask(kind, query, as[i], pose_of(poses.a, i), bs[i], pose_of(poses.b, i),
                                settings.escalate);
                   });
}

BatchResult stack_batch(Kind kind, const VertexStack& as, const VertexStack& bs,
                        const QueryOptions& options, const BatchSettings& settings,
                        const BatchPoses& poses) {
  return run_batch(
      as.count, bs.count, options, settings, poses, [&](std::size_t i, const Query& query) {
        const ConvexPolyhedron a = body(as, i, settings.first_index);
        const ConvexPolyhedron b = body(bs, i, settings.first_index);
        return ask(kind, query, a, pose_of(poses.a, i), b, pose_of(poses.b, i), settings.escalate);
      });
}

}  // namespace

BatchResult distance_many(const std::vector<ConvexPolyhedron>& as,
                          const std::vector<ConvexPolyhedron>& bs, const QueryOptions& options,
                          const BatchSettings& settings, const BatchPoses& poses) {
  return bodies_batch(Kind::distance, as, bs, options, settings, poses);
}

BatchResult collide_many(const std::vector<ConvexPolyhedron>& as,
                         const std::vector<ConvexPolyhedron>& bs, const QueryOptions& options,
                         const BatchSettings& settings, const BatchPoses& poses) {
  return bodies_batch(Kind::collide, as, bs, options, settings, poses);
}

BatchResult signed_distance_many(const std::vector<ConvexPolyhedron>& as,
                                 const std::vector<ConvexPolyhedron>& bs,
                                 const QueryOptions& options, const BatchSettings& settings,
                                 const BatchPoses& poses) {
  return bodies_batch(Kind::signed_distance, as, bs, options, settings, poses);
}

BatchResult distance_many(const VertexStack& as, const VertexStack& bs, const QueryOptions& options,
                          const BatchSettings& settings, const BatchPoses& poses) {
  return stack_batch(Kind::distance, as, bs, options, settings, poses);
}

BatchResult collide_many(const VertexStack& as, const VertexStack& bs, const QueryOptions& options,
                         const BatchSettings& settings, const BatchPoses& poses) {
  return stack_batch(Kind::collide, as, bs, options, settings, poses);
}

BatchResult signed_distance_many(const VertexStack& as, const VertexStack& bs,
                                 const QueryOptions& options, const BatchSettings& settings,
                                 const BatchPoses& poses) {
  return stack_batch(Kind::signed_distance, as, bs, options, settings, poses);
}

BatchResult distance_many(const std::vector<CompoundBody>& as, const std::vector<CompoundBody>& bs,
                          const QueryOptions& options, const BatchSettings& settings,
                          const BatchPoses& poses) {
  return bodies_batch(Kind::distance, as, bs, options, settings, poses);
}

BatchResult collide_many(const std::vector<CompoundBody>& as, const std::vector<CompoundBody>& bs,
                         const QueryOptions& options, const BatchSettings& settings,
                         const BatchPoses& poses) {
  return bodies_batch(Kind::collide, as, bs, options, settings, poses);
}

BatchResult signed_distance_many(const std::vector<CompoundBody>& as,
                                 const std::vector<CompoundBody>& bs, const QueryOptions& options,
                                 const BatchSettings& settings, const BatchPoses& poses) {
  return bodies_batch(Kind::signed_distance, as, bs, options, settings, poses);
}

}  // namespace swarmcollide
