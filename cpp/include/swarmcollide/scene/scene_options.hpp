#pragma once

#include <cstdint>

#include "swarmcollide/queries/options.hpp"
#include "swarmcollide/scene/broadphase.hpp"

namespace swarmcollide {

/// Largest relative tolerance a Scene accepts: its broadphase pads each box by the contact
/// threshold, which is relative to the size of pairs it has not met yet, and that padding is
/// finite only for tolerances well below one.
inline constexpr Scalar kMaxSceneTolerance = 0.1;

/// Farthest from the origin, along any axis, that a Scene takes a body's points (and largest
/// distance `pairs_within` takes): FCL's trees compare boxes by their squared extents, which
/// overflow beyond 1.3e154 (a tree then dereferences a null node), and the searches of
/// `min_distance` and `nearest` pad boxes by up to twice the scene's extent. A body must lie
/// within half of it from its own origin, and a pose move it by at most half along each axis.
inline constexpr Scalar kMaxSceneCoordinate = 1e150;

/// How a Scene answers: the narrowphase's method, tolerance, seed and solver parameters (one
/// QueryOptions, as for a Query), the broadphase, the threads, and whether frames start from
/// what earlier frames proved.
struct SceneOptions {
  /// The method, tolerance and seed of every pair's query. Pair (i, j) is seeded with
  /// `pair_seed(query.seed, (i << 32) | j)` for ids i < j, so answers depend neither on the
  /// broadphase, nor on the threads, nor on the order in which pairs are met.
  QueryOptions query;
  Broadphase broadphase = Broadphase::dynamic_aabb_tree;
  /// Worker threads of the narrowphase, 0 for one per hardware thread, at most kMaxThreads.
  int threads = 0;
  /// Keep, for each candidate pair, what the last query proved about it (a separating direction
  /// or a simplex enclosing the origin) and try it first in the next one. Off, every answer is
  /// computed from scratch: the same scene gives the same answers whatever its history.
  bool warm_start = true;
  /// Hand a verdict the method cannot prove to the exact method (as `Query::collision` does).
  bool escalate = true;

  /// Throws std::invalid_argument naming the first invalid value: the query's (see
  /// QueryOptions::validate), a tolerance above kMaxSceneTolerance, or threads out of range.
  void validate() const;
};

/// Which pairs a body takes part in: bodies a and b are paired when `a.group & b.mask` and
/// `b.group & a.mask` are both nonzero (Bullet's convention). By default every body is in group
/// 1 and collides with every group.
struct BodyFilter {
  std::uint32_t group = 1;
  std::uint32_t mask = 0xFFFFFFFFu;

  bool pairs_with(const BodyFilter& other) const {
    return (group & other.mask) != 0 && (other.group & mask) != 0;
  }
};

}  // namespace swarmcollide
