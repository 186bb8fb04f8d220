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
      // Body and pose errors already name their row ("As[3]: ...", "poses_b[3] is ...").
      for (const char* named : {"As[", "Bs[", "poses_a[", "poses_b["}) {
        if (message.rfind(named, 0) == 0) throw;
      }
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

// The poses of one side of a batch: a list, an array read in place, or none (the identity).
class SidePoses {
 public:
  SidePoses(const std::vector<Pose>& list, const PoseArray& array, const char* name)
      : list_(list), array_(array), name_(name) {
    if (!list.empty() && array.count > 0) {
      throw std::invalid_argument(std::string(name) +
                                  ": give the poses as a list or as an array, not both");
    }
  }

  std::size_t size() const { return array_.count > 0 ? array_.count : list_.size(); }
  bool empty() const { return size() == 0; }
  // The pose of row i.
  Pose at(std::size_t i) const {
    if (array_.count > 0) return array_[i];
    return list_.empty() ? Pose{} : list_[i];
  }

  // One pose per pair (or none).
  void check_count(std::size_t count) const {
    if (!empty() && size() != count) {
      throw std::invalid_argument(std::string(name_) + " must have one pose per pair, got " +
                                  std::to_string(size()) + " for " + std::to_string(count) +
                                  " pairs");
    }
  }

 private:
  const std::vector<Pose>& list_;
  const PoseArray& array_;
  const char* name_;
};

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
  const SidePoses a(poses.a, poses.array_a, "poses_a");
  const SidePoses b(poses.b, poses.array_b, "poses_b");
  if (!a.empty()) return a.size();
  if (!b.empty()) return b.size();
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

// Runs `answer(i, options_i, pose_a_i, pose_b_i)`, which writes row i of the batch, for every
// pair, where options_i are the validated options seeded for pair i and `answer` is the thread's
// own `make_answer(batch)` (with the thread's state), on a pool of threads that take pairs in
// chunks, in increasing order: when a pair fails, every pair before it has been taken, so the
// error of the lowest failing index is found whatever the threads. Everything the rows share
// (the options, the method's capability, the pose counts) is checked here, once; each row's poses
// once, by the thread that answers it.
template <typename MakeAnswer>
BatchResult run_batch(Kind kind, std::size_t count, const QueryOptions& options,
                      const BatchSettings& settings, const BatchPoses& poses,
                      const MakeAnswer& make_answer) {
  const SidePoses poses_a(poses.a, poses.array_a, "poses_a");
  const SidePoses poses_b(poses.b, poses.array_b, "poses_b");
  poses_a.check_count(count);
  poses_b.check_count(count);
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
    pair_options.dual.record_history = false;  // a batch reports no history
    auto answer = make_answer(batch);
    for (std::size_t start = next.fetch_add(kChunk); start < count && !stop.load();
         start = next.fetch_add(kChunk)) {
      const std::size_t end = std::min(count, start + kChunk);
      for (std::size_t i = start; i < end; ++i) {
        try {
          // Each pose is validated once, by the thread that answers its row (a check in one
          // thread before the rows would not be spread over the threads).
          const std::uint64_t index = settings.first_index + i;
          const Pose pose_a = poses_a.at(i);
          const Pose pose_b = poses_b.at(i);
          if (!poses_a.empty()) validate_pose(pose_a, "poses_a", index);
          if (!poses_b.empty()) validate_pose(pose_b, "poses_b", index);
          pair_options.seed = pair_seed(options.seed, index);
          answer(i, pair_options, pose_a, pose_b);
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

// The balls of the body of each row, looked up again only when the body changes (a single
// body, or a sequence repeating one, costs one lookup per thread and run of rows).
class BallsCache {
 public:
  explicit BallsCache(bool with_inner) : with_inner_(with_inner) {}
  const detail::BodyBalls& of(const ConvexPolyhedron& body) {
    if (&body != body_) {
      body_ = &body;
      balls_ = detail::body_balls(body, with_inner_);
    }
    return balls_;
  }

 private:
  bool with_inner_;
  const ConvexPolyhedron* body_ = nullptr;
  detail::BodyBalls balls_;
};

void store(BatchResult& batch, std::size_t index, const detail::BallVerdict& verdict) {
  const auto i = static_cast<Eigen::Index>(index);
  batch.distance(i) = verdict.distance;
  batch.lower_bound(i) = verdict.lower_bound;
  batch.point_a.row(i) = verdict.point_a.transpose();
  batch.point_b.row(i) = verdict.point_b.transpose();
  batch.direction.row(i) = verdict.direction.transpose();
  batch.colliding(i) = verdict.colliding;
  batch.certified(i) = true;
  batch.iterations(i) = 0;
  batch.escalated(i) = false;
}

// Answers a convex pair under poses validated once for the batch into its row, as Query answers
// it; a collision that the bodies' balls settle needs neither a frame nor a solver.
class ConvexRows {
 public:
  ConvexRows(Kind kind, BatchResult& batch, bool escalate, bool with_inner)
      : kind_(kind), batch_(batch), escalate_(escalate), balls_a_(with_inner),
        balls_b_(with_inner) {}

  void answer(std::size_t row, const QueryOptions& options, const ConvexPolyhedron& a,
              const Pose& pose_a, const ConvexPolyhedron& b, const Pose& pose_b) {
    if (kind_ == Kind::collide) {
      const std::optional<detail::BallVerdict> settled = detail::collision_by_balls(
          a, pose_a, balls_a_.of(a), b, pose_b, balls_b_.of(b), options.tolerance);
      if (settled) return store(batch_, row, *settled);
    }
    const detail::FramedPair pair =
        detail::frame_validated_pair(a, pose_a, b, pose_b, options.tolerance);
    store(batch_, row, detail::answer_pair(options, asked(kind_).goal, pair, escalate_));
  }

 private:
  Kind kind_;
  BatchResult& batch_;
  bool escalate_;
  BallsCache balls_a_;
  BallsCache balls_b_;
};

BatchResult convex_batch(Kind kind, const BatchBodies<ConvexPolyhedron>& as,
                         const BatchBodies<ConvexPolyhedron>& bs, const QueryOptions& options,
                         const BatchSettings& settings, const BatchPoses& poses) {
  return run_batch(kind, row_count(as, bs, poses), options, settings, poses,
                   [&](BatchResult& batch) {
                     // Each thread keeps the balls of the bodies it last met.
                     return [&, rows = ConvexRows(kind, batch, settings.escalate, true)](
                                std::size_t i, const QueryOptions& pair_options,
                                const Pose& pose_a, const Pose& pose_b) mutable {
                       rows.answer(i, pair_options, as[i], pose_a, bs[i], pose_b);
                     };
                   });
}

BatchResult compound_batch(Kind kind, const BatchBodies<CompoundBody>& as,
                           const BatchBodies<CompoundBody>& bs, const QueryOptions& options,
                           const BatchSettings& settings, const BatchPoses& poses) {
  return run_batch(kind, row_count(as, bs, poses), options, settings, poses,
                   [&](BatchResult& batch) {
                     return [&](std::size_t i, const QueryOptions& pair_options,
                                const Pose& pose_a, const Pose& pose_b) {
                       store(batch, i,
                             detail::answer_compound(pair_options, asked(kind).goal,
                                                     settings.escalate, as[i], pose_a, bs[i],
                                                     pose_b));
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
  return run_batch(kind, as.count, options, settings, poses, [&](BatchResult& batch) {
    return [&](std::size_t i, const QueryOptions& pair_options, const Pose& pose_a,
               const Pose& pose_b) {
      const ConvexPolyhedron a = body(as, i, settings.first_index);
      const ConvexPolyhedron b = body(bs, i, settings.first_index);
      // Every row's bodies are new (and may reuse the last row's addresses): no ball is kept, and
      // no hull is built for an inner ball.
      ConvexRows(kind, batch, settings.escalate, false)
          .answer(i, pair_options, a, pose_a, b, pose_b);
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
