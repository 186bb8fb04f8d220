#include "swarmcollide/queries/batch.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <utility>

#include "../geometry/framed_body.hpp"
#include "ball_screen.hpp"
#include "dispatch.hpp"
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

void check_same_length(std::size_t count_a, std::size_t count_b) {
  if (count_a != count_b) {
    throw std::invalid_argument("As and Bs must have the same length, got " +
                                std::to_string(count_a) + " and " + std::to_string(count_b));
  }
}

// The rows of a batch: the length of the sequences of bodies, or with a single body on both
// sides that of the poses (one row without them).
template <typename Body>
std::size_t row_count(const BatchBodies<Body>& as, const BatchBodies<Body>& bs,
                      const BatchPoses& poses) {
  if (!as.single() && !bs.single()) check_same_length(as.size(), bs.size());
  if (!as.single()) return as.size();
  if (!bs.single()) return bs.size();
  if (!poses.a.empty()) return poses.a.size();
  if (!poses.b.empty()) return poses.b.size();
  return 1;
}

// What a batch's rows ask: the query's goal, and `require`'s capability and name for it.
struct Asked {
  detail::Goal goal;
  Capability capability;
  const char* name;
};

Asked asked(Kind kind) {
  switch (kind) {
    case Kind::distance:
      return {detail::Goal::distance, kDistance, "distance"};
    case Kind::collide:
      return {detail::Goal::verdict, kCollide, "collide"};
    case Kind::signed_distance:
      break;
  }
  return {detail::Goal::signed_distance, kSignedDistance, "signed_distance"};
}

// Runs `answer(i, options_i)` for every pair, where options_i are the validated options seeded
// for pair i and `answer` is the thread's own `make_answer()` (with the thread's state), on a
// pool of threads that take pairs in chunks, in increasing order: when a pair fails, every pair
// before it has been taken, so the error of the lowest failing index is found whatever the
// threads. Everything a row shares with the others (the options, the poses, the
// method's capability) is checked here, once.
template <typename MakeAnswer>
BatchResult run_batch(Kind kind, std::size_t count, const QueryOptions& options,
                      const BatchSettings& settings, const BatchPoses& poses,
                      const MakeAnswer& make_answer) {
  check_poses(poses.a, count, "poses_a", settings.first_index);
  check_poses(poses.b, count, "poses_b", settings.first_index);
  const std::size_t workers = worker_count(settings.threads, count);
  const Query validated(options);
  detail::require(options.method, asked(kind).capability, asked(kind).name);
  BatchResult batch = sized(count);
  // Chunks small enough to balance the threads when rows differ in cost, large enough that the
  // rows two threads write next to each other (their results' cache lines) are few.
  constexpr std::size_t kChunk = 64;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  FirstFailure failure;
  const auto work = [&] {
    QueryOptions pair_options = validated.options();
    auto answer = make_answer();
    for (std::size_t start = next.fetch_add(kChunk); start < count && !stop.load();
         start = next.fetch_add(kChunk)) {
      const std::size_t end = std::min(count, start + kChunk);
      for (std::size_t i = start; i < end; ++i) {
        try {
          pair_options.seed = pair_seed(options.seed, settings.first_index + i);
          store(batch, i, answer(i, pair_options));
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

// The ball radius of the body of each row, looked up again only when the body changes (a
// single body, or a sequence repeating one, costs one lookup per thread and run of rows).
class BallRadii {
 public:
  Scalar of(const ConvexPolyhedron& body) {
    if (&body != body_) {
      body_ = &body;
      radius_ = detail::ball_radius(body);
    }
    return radius_;
  }

 private:
  const ConvexPolyhedron* body_ = nullptr;
  Scalar radius_ = 0;
};

// A convex pair framed from poses validated once for the batch, answered as Query answers it;
// collisions whose bounding balls prove them apart are settled without a solver.
DistanceResult answer_convex(Kind kind, const QueryOptions& options, const ConvexPolyhedron& a,
                             const Pose& pose_a, const ConvexPolyhedron& b, const Pose& pose_b,
                             bool escalate, BallRadii& radii_a, BallRadii& radii_b) {
  const detail::FramedPair pair =
      detail::frame_validated_pair(a, pose_a, b, pose_b, options.tolerance);
  if (kind == Kind::collide) {
    std::optional<DistanceResult> settled =
        detail::collision_by_balls(pair, radii_a.of(a), radii_b.of(b), options.method);
    if (settled) return std::move(*settled);
  }
  return detail::answer_pair(options, asked(kind).goal, pair, escalate);
}

BatchResult convex_batch(Kind kind, const BatchBodies<ConvexPolyhedron>& as,
                         const BatchBodies<ConvexPolyhedron>& bs, const QueryOptions& options,
                         const BatchSettings& settings, const BatchPoses& poses) {
  return run_batch(kind, row_count(as, bs, poses), options, settings, poses, [&] {
    // Each thread keeps the radii of the bodies it last met.
    return [&, radii_a = BallRadii(), radii_b = BallRadii()](
               std::size_t i, const QueryOptions& pair_options) mutable {
      return answer_convex(kind, pair_options, as[i], pose_of(poses.a, i), bs[i],
                           pose_of(poses.b, i), settings.escalate, radii_a, radii_b);
    };
  });
}

BatchResult compound_batch(Kind kind, const BatchBodies<CompoundBody>& as,
                           const BatchBodies<CompoundBody>& bs, const QueryOptions& options,
                           const BatchSettings& settings, const BatchPoses& poses) {
  return run_batch(kind, row_count(as, bs, poses), options, settings, poses, [&] {
    return [&](std::size_t i, const QueryOptions& pair_options) {
      return detail::answer_compound(pair_options, asked(kind).goal, settings.escalate, as[i],
                                     pose_of(poses.a, i), bs[i], pose_of(poses.b, i));
    };
  });
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

BatchResult stack_batch(Kind kind, const VertexStack& as, const VertexStack& bs,
                        const QueryOptions& options, const BatchSettings& settings,
                        const BatchPoses& poses) {
  check_same_length(as.count, bs.count);
  return run_batch(kind, as.count, options, settings, poses, [&] {
    return [&](std::size_t i, const QueryOptions& pair_options) {
      const ConvexPolyhedron a = body(as, i, settings.first_index);
      const ConvexPolyhedron b = body(bs, i, settings.first_index);
      // Every row's bodies are new (and may reuse the last row's addresses): no radius is kept.
      BallRadii radius_a, radius_b;
      return answer_convex(kind, pair_options, a, pose_of(poses.a, i), b, pose_of(poses.b, i),
                           settings.escalate, radius_a, radius_b);
    };
  });
}

}  // namespace

BatchResult distance_many(const BatchBodies<ConvexPolyhedron>& as,
                          const BatchBodies<ConvexPolyhedron>& bs, const QueryOptions& options,
                          const BatchSettings& settings, const BatchPoses& poses) {
  return convex_batch(Kind::distance, as, bs, options, settings, poses);
}

BatchResult collide_many(const BatchBodies<ConvexPolyhedron>& as,
                         const BatchBodies<ConvexPolyhedron>& bs, const QueryOptions& options,
                         const BatchSettings& settings, const BatchPoses& poses) {
  return convex_batch(Kind::collide, as, bs, options, settings, poses);
}

BatchResult signed_distance_many(const BatchBodies<ConvexPolyhedron>& as,
                                 const BatchBodies<ConvexPolyhedron>& bs,
                                 const QueryOptions& options, const BatchSettings& settings,
                                 const BatchPoses& poses) {
  return convex_batch(Kind::signed_distance, as, bs, options, settings, poses);
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

BatchResult distance_many(const BatchBodies<CompoundBody>& as, const BatchBodies<CompoundBody>& bs,
                          const QueryOptions& options, const BatchSettings& settings,
                          const BatchPoses& poses) {
  return compound_batch(Kind::distance, as, bs, options, settings, poses);
}

BatchResult collide_many(const BatchBodies<CompoundBody>& as, const BatchBodies<CompoundBody>& bs,
                         const QueryOptions& options, const BatchSettings& settings,
                         const BatchPoses& poses) {
  return compound_batch(Kind::collide, as, bs, options, settings, poses);
}

BatchResult signed_distance_many(const BatchBodies<CompoundBody>& as,
                                 const BatchBodies<CompoundBody>& bs, const QueryOptions& options,
                                 const BatchSettings& settings, const BatchPoses& poses) {
  return compound_batch(Kind::signed_distance, as, bs, options, settings, poses);
}

}  // namespace swarmcollide
