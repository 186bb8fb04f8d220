#pragma once

#include <string>
#include <vector>

namespace swarmcollide {

/// The FCL broadphase manager a Scene collects its candidate pairs with. Every manager is given
/// the same boxes (tight, from the bodies' supports), so the choice changes speed, never answers.
enum class Broadphase {
  /// fcl::DynamicAABBTreeCollisionManager: a bounding-volume tree refitted as bodies move. The
  /// default.
  dynamic_aabb_tree,
  /// fcl::SaPCollisionManager: sweep and prune on all three axes.
  sap,
  /// fcl::SSaPCollisionManager: sweep and prune along the axis of largest spread.
  ssap,
  /// fcl::IntervalTreeCollisionManager: interval trees on the three axes.
  interval_tree,
  /// fcl::SpatialHashingCollisionManager: a uniform grid of cells the size of a typical body.
  spatial_hashing,
  /// fcl::NaiveCollisionManager: every pair's boxes compared; the reference the others are
  /// tested against.
  brute_force,
};

/// Every broadphase's name ("dynamic_aabb_tree", ...), in the enum's order.
const std::vector<std::string>& broadphase_names();

/// The name of `broadphase`.
const std::string& broadphase_name(Broadphase broadphase);

/// The broadphase called `name`; throws std::invalid_argument listing the valid names (and, for
/// "dynamic_aabb_tree_array", saying why it is no longer offered).
Broadphase broadphase_from_name(const std::string& name);

}  // namespace swarmcollide
