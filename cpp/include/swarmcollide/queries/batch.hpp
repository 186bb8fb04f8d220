#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/queries/batch_result.hpp"
#include "swarmcollide/queries/options.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Largest number of threads a batch may ask for.
inline constexpr int kMaxThreads = 1024;

/// How a batch runs.
struct BatchSettings {
  /// Worker threads, 0 for one per hardware thread, at most kMaxThreads. Threads that cannot be
  /// started are done without: the answers do not depend on the number of threads.
  int threads = 0;
  /// The global index of the first pair: pair i is seeded with `pair_seed(seed, first_index +
  /// i)` and named `first_index + i` in errors, so a batch split into parts gives the answers of
  /// the whole.
  std::uint64_t first_index = 0;
  /// `collide_many` only: hand unproven verdicts to the exact method.
  bool escalate = true;
};

/// The bodies on one side of a batch, read where they are (never copied): a body per row, or one
/// body for every row ("A against B at these m poses" is one body on each side and m poses).
template <typename Body>
class BatchBodies {
 public:
  /// Row i's body is `bodies[i]`.
  BatchBodies(const std::vector<Body>& bodies)  // NOLINT(google-explicit-constructor)
      : single_(false) {
    items_.reserve(bodies.size());
    for (const Body& body : bodies) items_.push_back(&body);
  }
  /// Row i's body is `*bodies[i]` (bodies held elsewhere, as a binding's arguments are).
  explicit BatchBodies(std::vector<const Body*> bodies)
      : items_(std::move(bodies)), single_(false) {}
  /// `body` in every row.
  BatchBodies(const Body& body)  // NOLINT(google-explicit-constructor)
      : items_{&body}, single_(true) {}

  /// True when one body serves every row.
  bool single() const { return single_; }
  /// The number of bodies given (1 for a single body).
  std::size_t size() const { return items_.size(); }
  /// The body of row `row`.
  const Body& operator[](std::size_t row) const { return *items_[single_ ? 0 : row]; }
  /// The bodies given, one pointer each (one for a single body): what a thread copies once, so
  /// that its rows read no memory beside what other threads write.
  const Body* const* data() const { return items_.data(); }

 private:
  std::vector<const Body*> items_;
  bool single_;
};

/// Poses read where they are (never copied), as a binding's arrays hold them: entry (r, c) of
/// pose i's rotation is `rotations[i * rotation_stride + r * rotation_row_stride + c]` and entry
/// r of its translation `translations[i * translation_stride + r * translation_row_stride]`
/// (strides in elements). So an (m, 4, 4) array of transforms is read with strides 16 and 4 for
/// both, a pair of (m, 3, 3) and (m, 3) arrays with strides 9 and 3, and 3 and 1.
struct PoseArray {
  const Scalar* rotations = nullptr;
  const Scalar* translations = nullptr;
  std::size_t count = 0;
  std::ptrdiff_t rotation_stride = 9;
  std::ptrdiff_t rotation_row_stride = 3;
  std::ptrdiff_t translation_stride = 3;
  std::ptrdiff_t translation_row_stride = 1;

  /// Pose i.
  Pose operator[](std::size_t i) const {
    Pose pose;
    const Scalar* rotation = rotations + static_cast<std::ptrdiff_t>(i) * rotation_stride;
    const Scalar* translation =
        translations + static_cast<std::ptrdiff_t>(i) * translation_stride;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) pose.rotation(r, c) = rotation[r * rotation_row_stride + c];
      pose.translation(r) = translation[r * translation_row_stride];
    }
    return pose;
  }
};

/// Where the bodies of a batch are: pair i's A at `a[i]` and B at `b[i]`, or read in place at
/// `array_a[i]` and `array_b[i]` when those hold poses (`count` > 0; then their lists must be
/// empty); a side without poses puts every body of its side at the identity.
struct BatchPoses {
  std::vector<Pose> a;
  std::vector<Pose> b;
  PoseArray array_a;
  PoseArray array_b;
};

/// The seed of the pair with global index `index` in a batch seeded with `seed`: independent of
/// the thread count and of how the batch is split.
std::uint64_t pair_seed(std::uint64_t seed, std::uint64_t index);

/// `count` bodies of `vertices` points each, stored one after another: body i's points are the
/// rows i * vertices to (i + 1) * vertices - 1 of a row-major (count * vertices, 3) array. `name`
/// is what errors call the sequence ("As[3]: ...").
struct VertexStack {
  const Scalar* points;
  std::size_t count;
  Eigen::Index vertices;
  const char* name;
};

/// `Query(options).distance(as[i], poses.a[i], bs[i], poses.b[i])` for every row i, spread
/// over threads, with row i seeded by `pair_seed(options.seed, first_index + i)`. The options are
/// validated once, before any row is answered, and each row's poses once, by the thread that
/// answers the row. The rows are as many as the sequences of bodies (which must agree), or with a
/// single body on both sides as the poses (one row without poses). Throws std::invalid_argument
/// if the sequences (or non-empty pose lists) differ in length or a setting is invalid, and
/// rethrows the error of the pair with the lowest index that failed (an invalid pose, named
/// "poses_b[N]", or the query's error, prefixed with "pair N: ").
BatchResult distance_many(const BatchBodies<ConvexPolyhedron>& as,
                          const BatchBodies<ConvexPolyhedron>& bs, const QueryOptions& options,
                          const BatchSettings& settings = {}, const BatchPoses& poses = {});
/// `Query(options).collision(as[i], poses.a[i], bs[i], poses.b[i], settings.escalate)` for
/// every row i, like distance_many, except that a row whose bodies' balls about their boxes'
/// centres settle it needs no solver: bounding balls proven apart (the lower bound is their
/// separation, the distance that of the bodies' first given points, its witnesses), or balls
/// inside the bodies that overlap (distance and lower bound 0, both witnesses a point common to
/// the balls). Nor does a row of bodies of at most kHillClimbingThreshold points that are proven
/// apart along the axis through those centres, or along the face normal of either body nearest
/// that axis (the lower bound is their separation along the axis, the witnesses their supporting
/// points, the distance theirs). Bodies built from vertex stacks are screened by their bounding
/// balls and the centres' axis only.
BatchResult collide_many(const BatchBodies<ConvexPolyhedron>& as,
                         const BatchBodies<ConvexPolyhedron>& bs, const QueryOptions& options,
                         const BatchSettings& settings = {}, const BatchPoses& poses = {});
/// `Query(options).signed_distance(as[i], poses.a[i], bs[i], poses.b[i])` for every row i, like
/// distance_many.
BatchResult signed_distance_many(const BatchBodies<ConvexPolyhedron>& as,
                                 const BatchBodies<ConvexPolyhedron>& bs,
                                 const QueryOptions& options, const BatchSettings& settings = {},
                                 const BatchPoses& poses = {});

/// The same over bodies built from vertex stacks. Each pair's bodies are built, answered and
/// freed on the thread that answers the pair, so building and freeing them is spread over the
/// threads too and no thread frees memory that another allocated. A body that cannot be built
/// throws std::invalid_argument naming it by its global index.
BatchResult distance_many(const VertexStack& as, const VertexStack& bs, const QueryOptions& options,
                          const BatchSettings& settings = {}, const BatchPoses& poses = {});
BatchResult collide_many(const VertexStack& as, const VertexStack& bs, const QueryOptions& options,
                         const BatchSettings& settings = {}, const BatchPoses& poses = {});
BatchResult signed_distance_many(const VertexStack& as, const VertexStack& bs,
                                 const QueryOptions& options, const BatchSettings& settings = {},
                                 const BatchPoses& poses = {});

/// The same between compound bodies (CompoundResult's answers, with the parts that realise them
/// in `part_a` and `part_b`); collide_many settles no row by balls beyond what the compound
/// search's own bounding volumes do.
BatchResult distance_many(const BatchBodies<CompoundBody>& as, const BatchBodies<CompoundBody>& bs,
                          const QueryOptions& options, const BatchSettings& settings = {},
                          const BatchPoses& poses = {});
BatchResult collide_many(const BatchBodies<CompoundBody>& as, const BatchBodies<CompoundBody>& bs,
                         const QueryOptions& options, const BatchSettings& settings = {},
                         const BatchPoses& poses = {});
BatchResult signed_distance_many(const BatchBodies<CompoundBody>& as,
                                 const BatchBodies<CompoundBody>& bs, const QueryOptions& options,
                                 const BatchSettings& settings = {}, const BatchPoses& poses = {});

}  // namespace swarmcollide
