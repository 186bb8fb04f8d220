#pragma once

#include <vector>

#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/options.hpp"
#include "swarmcollide/robot/kinematics.hpp"
#include "swarmcollide/robot/pair_filter.hpp"
#include "swarmcollide/robot/robot_model.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// A `(rows, columns)` row-major matrix of values, one row per configuration.
template <typename T>
using RowTable = Eigen::Array<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The signed distance of every checked pair at every configuration, `(m, pairs)` each.
struct RobotDistances {
  /// Upper bounds on the signed distances, achieved by witness points.
  RowTable<Scalar> distance;
  /// Lower bounds on the signed distances.
  RowTable<Scalar> lower_bound;
  /// True where the pair is within the tolerance of contact.
  RowTable<bool> colliding;
  /// True where the pair's answer is certified (see DistanceResult::certified).
  RowTable<bool> certified;
};

/// Per configuration: whether any checked pair collides, and the nearest (or deepest) pair.
struct RobotCheck {
  /// True when some pair is within the tolerance of contact.
  Eigen::Array<bool, Eigen::Dynamic, 1> colliding;
  /// The least signed distance over the pairs (an upper bound, achieved by the witnesses); +inf
  /// when nothing is checked.
  VectorX min_distance;
  /// The least lower bound over the pairs answered (those skipped are proven farther):
  /// `lower_bound <= true minimum <= min_distance`.
  VectorX lower_bound;
  /// True when every pair answered is certified (those skipped are proven farther than the
  /// minimum by their balls), so the verdict and both bounds are proven.
  Eigen::Array<bool, Eigen::Dynamic, 1> certified;
  /// The index (into the pairs) of the pair realising `min_distance`, the lowest on ties; -1
  /// when nothing is checked.
  Eigen::VectorXi pair;
  /// The pair's witness points in the world, and the unit normal from its first geometry to its
  /// second (`point_b - point_a = min_distance * normal`).
  VertexMatrix point_a;
  VertexMatrix point_b;
  VertexMatrix normal;
  /// `d min_distance / dq`, `(m, dof)`, when asked: from the witness points and the link
  /// Jacobians, holding the witnesses fixed to their links. It is the derivative where the
  /// closest pair and its closest features are unique, and one of the one-sided derivatives
  /// where they are not.
  Configurations gradient;
};

/// The signed distance of every pair at every configuration (`q` admitted, see
/// admit_configurations): for each pair, `signed_distance_many` over the configurations, with the
/// geometries' world poses read in place from one table (no body is copied), so answers do not
/// depend on the number of threads. A compound geometry against a curved one is answered part by
/// part (the least over the parts; compound bodies take no curved parts). Throws
/// std::invalid_argument for invalid options, threads or pairs, or, naming the geometry, for a
/// pair with a curved geometry that `options.method` cannot answer.
RobotDistances robot_distances(const RobotModel& model, const std::vector<GeometryPair>& pairs,
                               const Configurations& q, const QueryOptions& options,
                               const BatchSettings& settings = {});

/// Per configuration, the nearest pair: the pairs in increasing order of the separation of their
/// geometries' bounding balls, each answered by `Query::signed_distance` (seeded for the
/// configuration as robot_distances seeds its rows), skipping the pairs whose balls are proven
/// farther apart than the nearest pair found and than their contact threshold (the tolerance
/// times the pair's size). The pairs skipped are proven farther than the minimum and apart, so
/// the answer is that of robot_distances' row reduced to its nearest pair (the lowest index on
/// ties), and `colliding`, `lower_bound` and `certified` cover every pair. Each configuration is
/// answered whole by one of `settings.threads` threads, so answers do not depend on them. With
/// `gradient`, also d min_distance / dq. Without `nearest`, the verdict alone (a planner's
/// check): the pairs whose balls are within their contact threshold, nearest balls first, each
/// answered by `Query::collision` until one is proven in contact; `pair` is that pair (or the first
/// found colliding unproven, or -1), `certified` says whether the verdict is proven, and
/// `min_distance` and `lower_bound` are NaN, the witnesses zero. Throws as robot_distances does,
/// and for `gradient` without `nearest`.
RobotCheck robot_check(const RobotModel& model, const std::vector<GeometryPair>& pairs,
                       const Configurations& q, const QueryOptions& options,
                       const BatchSettings& settings = {}, bool gradient = false,
                       bool nearest = true);

}  // namespace swarmcollide
