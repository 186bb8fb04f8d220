#include "swarmcollide/queries/batch.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "../detail/hardware_threads.hpp"
#include "../detail/interruption.hpp"
#include "../detail/kept_threads.hpp"
#include "../detail/waking_pace.hpp"
#include "../geometry/framed_body.hpp"
#include "../geometry/pose_check.hpp"
#include "ball_screen.hpp"
#include "dispatch.hpp"
#include "row_answer.hpp"
#include "swarmcollide/detail/random.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide {

std::uint64_t pair_seed(std::uint64_t seed, std::uint64_t index) {
  return detail::mix64(seed ^ detail::mix64(index));
}

namespace {

enum class Kind { distance, collide, signed_distance };

// The rows of a BatchResult's arrays, through pointers that each thread copies before its first
// row: a thread that read them through the BatchResult (on the calling thread's stack, beside the
// locals that thread writes for every row it answers) would pull that cache line back and forth
// on every row, which doubled the CPU time of the rows the ball screens settle on two threads.
class RowWriter {
 public:
  explicit RowWriter(BatchResult& batch)
      : distance_(batch.distance.data()),
        lower_bound_(batch.lower_bound.data()),
        point_a_(batch.point_a.data()),
        point_b_(batch.point_b.data()),
        direction_(batch.direction.data()),
        colliding_(batch.colliding.data()),
        certified_(batch.certified.data()),
        iterations_(batch.iterations.data()),
        escalated_(batch.escalated.data()),
        part_a_(batch.part_a.data()),
        part_b_(batch.part_b.data()) {}

  void write(std::size_t row, const CompoundResult& r) const {
    write(row, static_cast<const DistanceResult&>(r), r.part_a, r.part_b);
  }
  // A convex pair's answer by a solver.
  void write(std::size_t row, const detail::RowAnswer& r) const {
    const detail::FinishedValues& v = r.values;
    write(row, v.distance, v.lower_bound, v.point_a, v.point_b, v.direction, v.colliding,
          v.certified, v.iterations, r.escalated, 0, 0);
  }
  // A verdict proven without a solver: certified, no iterations.
  void write(std::size_t row, const detail::ScreenVerdict& v) const {
    write(row, v.distance, v.lower_bound, v.point_a, v.point_b, v.direction, v.colliding, true, 0,
          false, 0, 0);
  }

 private:
  void write(std::size_t row, const DistanceResult& r, int part_a, int part_b) const {
    write(row, r.distance, r.lower_bound, r.point_a, r.point_b, r.direction, r.colliding,
          r.certified, r.iterations, r.escalated_from.has_value(), part_a, part_b);
  }
  // Every field of the row: the result's arrays start uninitialised.
  void write(std::size_t row, Scalar distance, Scalar lower_bound, const Vector3& point_a,
             const Vector3& point_b, const Vector3& direction, bool colliding, bool certified,
             int iterations, bool escalated, int part_a, int part_b) const {
    distance_[row] = distance;
    lower_bound_[row] = lower_bound;
    // The (m, 3) arrays are row-major: row i's coordinates are 3i, 3i + 1 and 3i + 2.
    for (int k = 0; k < 3; ++k) {
      point_a_[3 * row + k] = point_a(k);
      point_b_[3 * row + k] = point_b(k);
      direction_[3 * row + k] = direction(k);
    }
    colliding_[row] = colliding;
    certified_[row] = certified;
    iterations_[row] = iterations;
    escalated_[row] = escalated;
    part_a_[row] = part_a;
    part_b_[row] = part_b;
  }

  Scalar* distance_;
  Scalar* lower_bound_;
  Scalar* point_a_;
  Scalar* point_b_;
  Scalar* direction_;
  bool* colliding_;
  bool* certified_;
  int* iterations_;
  bool* escalated_;
  int* part_a_;
  int* part_b_;
};

// The bodies of one side as a thread reads them, from its own copy of the pointers (see
// RowWriter).
template <typename Body>
class BodyRows {
 public:
  explicit BodyRows(const BatchBodies<Body>& bodies)
      : items_(bodies.data()), single_(bodies.single()) {}
  const Body& operator[](std::size_t row) const { return *items_[single_ ? 0 : row]; }

 private:
  const Body* const* items_;
  bool single_;
};

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
                                         : detail::hardware_threads();
  return std::min(wanted, std::max<std::size_t>(pairs, 1));
}

// The poses of one side of a batch: a list, an array read in place, or none (the identity). A
// small value that each thread copies before its first row (see RowWriter).
class SidePoses {
 public:
  SidePoses(const std::vector<Pose>& list, const PoseArray& array, const char* name)
      : list_(list.data()), listed_(list.size()), array_(array), name_(name) {
    if (listed_ > 0 && array.count > 0) {
      throw std::invalid_argument(std::string(name) +
                                  ": give the poses as a list or as an array, not both");
    }
  }

  std::size_t size() const { return array_.count > 0 ? array_.count : listed_; }
  bool empty() const { return size() == 0; }
  // The pose of row i.
  Pose at(std::size_t i) const {
    if (array_.count > 0) return array_[i];
    return listed_ == 0 ? Pose{} : list_[i];
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
  const Pose* list_;
  std::size_t listed_;
  PoseArray array_;
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

// The rows of a batch, split into one range of consecutive rows per thread, each range handed out
// in chunks in increasing order: a thread takes chunks from its own range (its home), then from
// the others'. The split is the same in every call of the same size, so that a thread writes the
// same rows of a result block that is reused (see BatchResult) call after call: when a shared
// counter handed every row to whichever thread came first, the rows changed threads between calls,
// and the cache lines of the result and of the poses moved from core to core with them. At times
// (this VM's two cores are not always placed alike) that cost a 2-thread call of rows the ball
// screens settle 14-18% more CPU time than a 1-thread call (collide_many, 20,000 rows, 8 or 260
// vertices), and 2 threads answered 1.6-1.7x as many rows as 1. A chunk is a share of the rows
// left in its range (guided self-scheduling): large while many rows are left, so that threads
// work far apart (on rows the ball screens settle, chunks of 64 rows interleaved between two
// threads cost 1.7x the CPU time of one thread, the threads writing into the same cache lines and
// pages), and small at the end, so that threads finish together when rows differ in cost. A range
// and a large chunk begin at a whole number of 64 rows, a cache line of every array of the result
// (see BatchResult).
class RowChunks {
 public:
  struct Chunk {
    std::size_t start = 0;
    std::size_t end = 0;
  };

  RowChunks(std::size_t count, std::size_t workers) : ranges_(workers) {
    for (std::size_t k = 0; k < workers; ++k) {
      ranges_[k].next.store(first_row(count, workers, k), std::memory_order_relaxed);
      ranges_[k].end = first_row(count, workers, k + 1);
    }
  }

  // The next chunk into `chunk`, from the range `home` first, then from the others in turn;
  // false when every row is taken or when those left come after a failed row.
  bool take(std::size_t home, Chunk& chunk) {
    for (std::size_t k = 0; k < ranges_.size(); ++k) {
      if (take_from(ranges_[(home + k) % ranges_.size()], chunk)) return true;
    }
    return false;
  }

  // The next chunk of at most `most` rows that ends at the latest where a cache line of rows
  // does, for a thread answering alone (see run_batch), from the first range not yet taken: the
  // chunks after it still begin cache lines.
  bool take_line(std::size_t most, Chunk& chunk) {
    const std::size_t failed = failed_.load(std::memory_order_relaxed);
    for (Range& range : ranges_) {
      const std::size_t start = range.next.load(std::memory_order_relaxed);
      if (start >= range.end) continue;
      if (start >= failed) return false;
      const std::size_t line_end = (start / kLine + 1) * kLine;
      chunk = {start, std::min({range.end, line_end, start + most})};
      range.next.store(chunk.end, std::memory_order_relaxed);
      return true;
    }
    return false;
  }

  // True when every row is taken, but for those after a failed row.
  bool finished() const {
    const std::size_t failed = failed_.load(std::memory_order_relaxed);
    for (const Range& range : ranges_) {
      if (range.next.load(std::memory_order_relaxed) < std::min(range.end, failed)) return false;
    }
    return true;
  }

  // Row `row` failed: no chunk that begins after it is taken any more. Those before it still
  // are, so that every row before the first failing one is answered whatever the threads.
  void failed_at(std::size_t row) {
    std::size_t failed = failed_.load(std::memory_order_relaxed);
    while (row < failed &&
           !failed_.compare_exchange_weak(failed, row, std::memory_order_relaxed)) {
    }
  }

 private:
  static constexpr std::size_t kLine = 64;  // rows: a cache line of the result's bools
  static constexpr std::size_t kSmallest = 8;
  static constexpr std::size_t kShares = 4;

  // A range's counter, written by its threads at every chunk: on a cache line of its own.
  struct alignas(64) Range {
    std::atomic<std::size_t> next{0};
    std::size_t end = 0;
  };

  // Where range k of `workers` begins: k / workers of the rows, rounded down to a cache line.
  static std::size_t first_row(std::size_t count, std::size_t workers, std::size_t k) {
    if (k >= workers) return count;
    return count / workers * k / kLine * kLine;
  }

  bool take_from(Range& range, Chunk& chunk) {
    std::size_t start = range.next.load(std::memory_order_relaxed);
    std::size_t end = 0;
    do {
      if (start >= range.end || start >= failed_.load(std::memory_order_relaxed)) return false;
      end = start + size(range.end - start);
    } while (!range.next.compare_exchange_weak(start, end, std::memory_order_relaxed));
    chunk = {start, end};
    return true;
  }

  static std::size_t size(std::size_t left) {
    const std::size_t share = left / kShares;
    const std::size_t rows = share >= kLine ? (share + kLine - 1) / kLine * kLine
                                            : std::max(share, kSmallest);
    return std::min(rows, left);
  }

  std::vector<Range> ranges_;
  // The lowest failed row (none: the largest size_t).
  std::atomic<std::size_t> failed_{std::numeric_limits<std::size_t>::max()};
};

// The poses of a thread's rows, read from their lists or arrays a few rows before the row is
// answered. A pose read from an array is stored into a Pose 8 bytes at a time, and the row's first
// 16-byte reads of it cannot be served from those stores while they are in flight: they wait for
// the stores to retire, at the pace of the whole pipeline. On 8-vertex rows that the ball screens
// settle that wait was a sixth of the time (0.118 against 0.098 us a row read 2, 4 or 8 rows
// ahead). A thread's own copy of the sides (see RowWriter).
class PosesAhead {
 public:
  PosesAhead(const SidePoses& a, const SidePoses& b)
      : a_(a), b_(b), posed_a_(!a.empty()), posed_b_(!b.empty()) {}

  // Starts on the rows [start, end).
  void start(std::size_t start, std::size_t end) {
    end_ = end;
    for (std::size_t row = start; row < std::min(end, start + kAhead); ++row) read(row);
  }
  // The poses of `row`, the first row started or done not yet done.
  const Pose& a(std::size_t row) const { return a_ahead_[row % kAhead]; }
  const Pose& b(std::size_t row) const { return b_ahead_[row % kAhead]; }
  // `row` is answered: its poses give way to those kAhead rows on.
  void done(std::size_t row) {
    if (row + kAhead < end_) read(row + kAhead);
  }

 private:
  static constexpr std::size_t kAhead = 4;

  // A side without poses keeps the identity its slots start with.
  void read(std::size_t row) {
    if (posed_a_) a_ahead_[row % kAhead] = a_.at(row);
    if (posed_b_) b_ahead_[row % kAhead] = b_.at(row);
  }

  SidePoses a_;
  SidePoses b_;
  bool posed_a_;
  bool posed_b_;
  std::size_t end_ = 0;
  Pose a_ahead_[kAhead];
  Pose b_ahead_[kAhead];
};

// The poses of a row, validated, with their rotations' identity tests (`turned`: not the
// identity).
struct RowPoses {
  const Pose& a;
  bool turned_a;
  const Pose& b;
  bool turned_b;
};

// The options of a row: the validated options shared by the rows, seeded for the row
// (pair_seed) only when a solver is to read them. A row that the screens settle reads no seed,
// and the seed's hash was a few percent of such a row's cost.
class RowOptions {
 public:
  RowOptions(QueryOptions& options, std::uint64_t seed, std::uint64_t index)
      : options_(options), seed_(seed), index_(index) {}
  /// The options for what reads no seed (the method, the tolerance): their seed is another
  /// row's.
  const QueryOptions& unseeded() const { return options_; }
  /// The options seeded for this row, for a solver.
  const QueryOptions& seeded() const {
    options_.seed = pair_seed(seed_, index_);
    return options_;
  }

 private:
  QueryOptions& options_;
  std::uint64_t seed_;
  std::uint64_t index_;
};

// The caller's first chunk, before its first estimate of the rows left (WakingPace): a few rows,
// so that a batch of costly rows (microseconds each) wakes the others after those, not after a
// cache line of rows.
constexpr std::size_t kFirstRows = 8;

// Runs `answer(i, options_i, poses_i)` (RowPoses), which writes row i of the batch, for every
// pair, where options_i are the validated options to be seeded for pair i (RowOptions) and
// `answer` is the thread's own `make_answer(RowWriter(batch))` (with the thread's state), on a
// pool of threads that take pairs in chunks (RowChunks), the calling thread from the first range
// and the others from the next ones. When a pair fails, the chunks that begin after it are no
// longer taken and those before it still are, so the error of the lowest failing index is found
// whatever the threads. Everything the rows share (the options, the method's capability, the
// pose counts) is checked here, once; each row's poses once, by the thread that answers it. A
// thread's rows read only its own copies of what they share (see RowWriter) and the chunks'
// counters.
template <typename MakeAnswer>
BatchResult run_batch(Kind kind, std::size_t count, const QueryOptions& options,
                      const BatchSettings& settings, const BatchPoses& poses,
                      const MakeAnswer& make_answer) {
  const SidePoses poses_a(poses.a, poses.array_a, "poses_a");
  const SidePoses poses_b(poses.b, poses.array_b, "poses_b");
  poses_a.check_count(count);
  poses_b.check_count(count);
  // Row i is the global row first_index + i, seeded and named by it: past 2**64 - 1 a row would
  // wrap to another row's seed and name.
  if (count > 0 && count - 1 > std::numeric_limits<std::uint64_t>::max() - settings.first_index) {
    throw std::invalid_argument(
        "first_index + the number of rows must be at most 2**64 (the rows are the global rows "
        "first_index, first_index + 1, ...), got first_index " +
        std::to_string(settings.first_index) + " and " + std::to_string(count) + " rows");
  }
  const std::size_t workers = worker_count(settings.threads, count);
  const Query validated(options);
  detail::require(options.method, asked(kind).capability, asked(kind).name);
  BatchResult batch(count);
  RowChunks chunks(count, workers);
  FirstFailure failure;
  // The calling thread's home is the first range, the other threads' the next ones in the order
  // they start.
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<std::size_t> homes{1};
  // A row stopped by the caller's check (Ctrl-C) stops every thread's rows at their next poll;
  // it fails as a row does, so no chunk after it is taken.
  detail::SharedInterruption interruption;
  // The caller's for the whole batch, as its rows install it: the pool's wait for the workers'
  // last rows keeps calling it (thread_pool.cpp).
  const InterruptionGuard caller_check = interruption.install(true);
  // `alone`: the calling thread answers rows up to a cache line at a time, before any other
  // thread is woken, until the rows are done or worth waking the others for (WakingPace).
  const detail::WakingPace pace(count);
  const auto work = [&](bool alone) {
    const bool on_caller = std::this_thread::get_id() == caller;
    const std::size_t home =
        on_caller ? 0 : homes.fetch_add(1, std::memory_order_relaxed) % workers;
    const InterruptionGuard stop_with_caller = interruption.install(on_caller);
    PosesAhead ahead(poses_a, poses_b);
    const bool posed_a = !poses_a.empty();
    const bool posed_b = !poses_b.empty();
    const std::uint64_t first_index = settings.first_index;
    const std::uint64_t seed = options.seed;
    QueryOptions pair_options = validated.options();
    pair_options.dual.record_history = false;  // a batch reports no history
    auto answer = make_answer(RowWriter(batch));
    std::size_t answered = 0;  // rows this thread has answered alone
    for (RowChunks::Chunk chunk;
         alone ? chunks.take_line(answered == 0 ? kFirstRows : count, chunk)
               : chunks.take(home, chunk);) {
      ahead.start(chunk.start, chunk.end);
      for (std::size_t i = chunk.start; i < chunk.end; ++i) {
        try {
          // Each pose is validated once, by the thread that answers its row (a check in one
          // thread before the rows would not be spread over the threads).
          const std::uint64_t index = first_index + i;
          // Their identity tests serve the validation and the framing alike; a side without
          // poses is the identity without one.
          const Pose& pose_a = ahead.a(i);
          const Pose& pose_b = ahead.b(i);
          const bool turned_a = posed_a && !pose_a.has_identity_rotation();
          if (posed_a && !detail::valid_pose(pose_a, turned_a)) {
            validate_pose(pose_a, "poses_a", index);
          }
          // A row whose bodies share a pose checks it once.
          const bool shared = posed_a && posed_b && detail::same_pose(pose_a, pose_b);
          const bool turned_b = shared ? turned_a : posed_b && !pose_b.has_identity_rotation();
          if (posed_b && !shared && !detail::valid_pose(pose_b, turned_b)) {
            validate_pose(pose_b, "poses_b", index);
          }
          answer(i, RowOptions(pair_options, seed, index), RowPoses{pose_a, turned_a, pose_b,
                                                                    turned_b});
          ahead.done(i);
        } catch (...) {
          failure.offer(i);
          chunks.failed_at(i);
          break;
        }
      }
      if (alone) {
        answered += chunk.end - chunk.start;
        if (pace.worth_waking(answered)) break;
      }
    }
  };
  if (workers > 1) work(true);
  // Each thread takes rows until none is left: a copy that starts late finds fewer or none.
  if (!chunks.finished()) detail::run_copies(workers, [&](std::size_t) { work(false); });
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

// Answers a convex pair under poses validated once for the batch into its row, as Query answers
// it; a collision that the screens settle (the bodies' balls, or an axis through their centres)
// needs neither a frame nor a solver. The last row's framed pair is kept for the next (KeptPair).
class ConvexRows {
 public:
  // `solve` is the solver of the batch's method (solver_for), looked up once.
  ConvexRows(Kind kind, const RowWriter& rows, bool escalate, bool with_inner,
             detail::Solver solve)
      : kind_(kind), rows_(rows), escalate_(escalate), solve_(solve), balls_a_(with_inner),
        balls_b_(with_inner) {}

  void answer(std::size_t row, const RowOptions& row_options, const ConvexPolyhedron& a,
              const ConvexPolyhedron& b, const RowPoses& poses) {
    const Pose& pose_a = poses.a;
    const Pose& pose_b = poses.b;
    const QueryOptions& options = row_options.unseeded();
    // Before the screens, which would settle a curved pair for a method that cannot answer it.
    detail::require_shapes(options.method, a, b);
    if (kind_ == Kind::collide) {
      const detail::BodyBalls& balls_a = balls_a_.of(a);
      const detail::BodyBalls& balls_b = balls_b_.of(b);
      const std::optional<detail::ScreenVerdict> settled =
          detail::collision_by_screens(a, pose_a, balls_a, b, pose_b, balls_b, options.tolerance);
      if (settled) return rows_.write(row, *settled);
    }
    rows_.write(row, detail::answer_row(row_options.seeded(), solve_, asked(kind_).goal,
                                        pair_.frame(a, pose_a, poses.turned_a, b, pose_b,
                                                    poses.turned_b, options.tolerance),
                                        escalate_));
  }

 private:
  Kind kind_;
  RowWriter rows_;
  bool escalate_;
  detail::Solver solve_;
  BallsCache balls_a_;
  BallsCache balls_b_;
  detail::KeptPair pair_;
};

BatchResult convex_batch(Kind kind, const BatchBodies<ConvexPolyhedron>& as,
                         const BatchBodies<ConvexPolyhedron>& bs, const QueryOptions& options,
                         const BatchSettings& settings, const BatchPoses& poses) {
  return run_batch(kind, row_count(as, bs, poses), options, settings, poses,
                   [&](const RowWriter& writer) {
                     // Each thread keeps the balls of the bodies it last met.
                     return [rows = ConvexRows(kind, writer, settings.escalate, true,
                                               detail::solver_for(options.method)),
                             a = BodyRows<ConvexPolyhedron>(as),
                             b = BodyRows<ConvexPolyhedron>(bs)](
                                std::size_t i, const RowOptions& pair_options,
                                const RowPoses& poses) mutable {
                       rows.answer(i, pair_options, a[i], b[i], poses);
                     };
                   });
}

BatchResult compound_batch(Kind kind, const BatchBodies<CompoundBody>& as,
                           const BatchBodies<CompoundBody>& bs, const QueryOptions& options,
                           const BatchSettings& settings, const BatchPoses& poses) {
  return run_batch(kind, row_count(as, bs, poses), options, settings, poses,
                   [&](const RowWriter& writer) {
                     // A row of one part each (a convex body, wrapped) is a convex batch's row:
                     // its answer does not depend on whether another row holds a compound body.
                     return [writer, goal = asked(kind).goal, escalate = settings.escalate,
                             convex = ConvexRows(kind, writer, settings.escalate, true,
                                                 detail::solver_for(options.method)),
                             a = BodyRows<CompoundBody>(as), b = BodyRows<CompoundBody>(bs)](
                                std::size_t i, const RowOptions& pair_options,
                                const RowPoses& poses) mutable {
                       const CompoundBody& body_a = a[i];
                       const CompoundBody& body_b = b[i];
                       if (body_a.size() == 1 && body_b.size() == 1) {
                         return convex.answer(i, pair_options, body_a.parts()[0],
                                              body_b.parts()[0], poses);
                       }
                       writer.write(i, detail::answer_compound(pair_options.seeded(), goal,
                                                               escalate, body_a, poses.a, body_b,
                                                               poses.b));
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
  return run_batch(kind, as.count, options, settings, poses, [&](const RowWriter& writer) {
    return [writer, kind, as, bs, first_index = settings.first_index,
            escalate = settings.escalate,
            solve = detail::solver_for(options.method)](
               std::size_t i, const RowOptions& pair_options, const RowPoses& poses) {
      const ConvexPolyhedron a = body(as, i, first_index);
      const ConvexPolyhedron b = body(bs, i, first_index);
      // Every row's bodies are new (and may reuse the last row's addresses): no ball or framed
      // pair is kept, and no hull is built for an inner ball.
      ConvexRows(kind, writer, escalate, false, solve)
          .answer(i, pair_options, a, b, poses);
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
