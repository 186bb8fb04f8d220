#pragma once

#include <cstddef>
#include <cstdint>

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// A body's name in a Scene: given by `Scene::add`, never reused.
using BodyId = std::uint32_t;

/// Pairs of bodies a Scene query found, one row per pair, in the units of the scene.
///
/// Pair k is the bodies `first(k)` (A) and `second(k)` (B); every vector points from A to B.
/// `lower_bound(k) <= distance between A and B <= distance(k)` (for contacts, the signed
/// distance: minus the penetration depth when the bodies overlap).
struct SceneResult {
  /// Ids of A and B, one pair per row.
  Eigen::Matrix<std::int64_t, Eigen::Dynamic, 2, Eigen::RowMajor> pairs;
  /// Upper bound on the distance, achieved by the witness points.
  VectorX distance;
  /// Lower bound on the distance, certified by `normal`.
  VectorX lower_bound;
  /// Witness points on A and on B.
  VertexMatrix point_a;
  VertexMatrix point_b;
  /// Unit direction from A to B that certifies `lower_bound`: a separating direction for
  /// bodies apart, the contact normal for contacts; zero rows where a pair's overlap was proven
  /// by a common point, which has no direction (`contacts` gives those their normals).
  VertexMatrix normal;
  /// True where the answer is proven: the pair's membership in the result (in contact, within
  /// the distance, among the nearest), and for distances and contacts the value to within the
  /// tolerance.
  Eigen::Array<bool, Eigen::Dynamic, 1> certified;

  Eigen::Index size() const { return pairs.rows(); }
};

/// The contacts of every pair of bodies in contact: a SceneResult whose `distance` is the
/// certified signed distance and `normal` the contact normal from A to B, with up to
/// `max_points` contact points per pair where the two supporting features meet.
struct ContactResult : SceneResult {
  /// Number of contact points of each pair (at least one).
  Eigen::Array<int, Eigen::Dynamic, 1> counts;
  /// Contact points of all pairs, pair by pair: pair k's are rows `offsets(k)` to `offsets(k) +
  /// counts(k) - 1`. A point lies halfway between the two supporting planes (on them both when
  /// the bodies just touch).
  VertexMatrix points;
  /// Row of each contact point's pair in `pairs`.
  Eigen::Array<std::int64_t, Eigen::Dynamic, 1> point_pair;
  /// Index of each pair's first contact point in `points`.
  Eigen::Array<std::int64_t, Eigen::Dynamic, 1> offsets;
};

/// What the last Scene query did.
struct SceneStats {
  /// Pairs that passed the filters whose boxes, padded for the query, overlap.
  std::size_t candidates = 0;
  /// Candidates found apart by the separation along the line between their centres, before any
  /// solver (those without a cached proof are tried so first).
  std::size_t screened = 0;
  /// Candidates found apart by a cached lower bound on their distance less how far the two
  /// bodies have moved since: no support evaluated.
  std::size_t warm_bounded = 0;
  /// Candidates settled by re-evaluating what an earlier query proved: rejected by a cached
  /// separating direction, or proven in contact by a cached simplex (or one that Wolfe's
  /// algorithm found from it in a step or two).
  std::size_t warm_rejected = 0;
  std::size_t warm_proven = 0;
  /// Candidates handed to the method's solver (the others were screened or settled warm).
  std::size_t solved = 0;
  /// Verdicts the method could not prove, handed to the exact method.
  std::size_t escalations = 0;
  /// Candidates whose answer (verdict, and value where one is reported) is proven.
  std::size_t certified = 0;
  /// Pairs with cached proofs after the query, and the bytes their storage takes: a 64-byte
  /// record for every pair whose broadphase boxes (padded boxes with margins for motion) overlap,
  /// and, for a pair in contact, the last expanding polytope's surface (at most 16 corners).
  /// `cache_bytes` is summed by Scene::stats() when it is read (the storage then), not by the
  /// query: the sum reads every pair's record.
  std::size_t cached_pairs = 0;
  std::size_t cache_bytes = 0;
};

}  // namespace swarmcollide
