#pragma once

#include <limits>
#include <vector>

#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/queries/options.hpp"
#include "swarmcollide/robot/kinematics.hpp"
#include "swarmcollide/robot/pair_filter.hpp"
#include "swarmcollide/robot/robot_model.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

class Query;

/// One configuration's answer of a check: a row of RobotCheck (robot_queries.hpp says what each
/// field holds).
struct RobotCheckRow {
  bool colliding = false;
  Scalar min_distance = std::numeric_limits<Scalar>::infinity();
  Scalar lower_bound = std::numeric_limits<Scalar>::infinity();
  bool certified = true;
  int pair = -1;
  Vector3 point_a = Vector3::Zero();
  Vector3 point_b = Vector3::Zero();
  Vector3 normal = Vector3::Zero();
  /// `d min_distance / dq` (dof values) when the checker was asked for it, else empty.
  VectorX gradient;
};

/// The check of one configuration at a time (robot_check's row, see robot_queries.hpp), with the
/// pairs and options validated once, when it is made, and its buffers kept from one
/// configuration to the next: a planner's validity check, called for every state it samples.
/// Holds `model` by reference (it must outlive the checker); not safe to share between threads
/// (each needs its own copy).
class RobotChecker {
 public:
  /// Throws std::invalid_argument as robot_check does: invalid options or pairs, a curved
  /// geometry `options.method` cannot answer, `gradient` without `nearest`.
  RobotChecker(const RobotModel& model, std::vector<GeometryPair> pairs, QueryOptions options,
               bool nearest, bool gradient);

  /// The answer at the admitted configuration `q` (dof values, see admit_configurations), its
  /// queries seeded for row `row` of a batch (pair_seed): valid until the next call.
  const RobotCheckRow& check(const Scalar* q, std::size_t row = 0);

  /// The same for `count` values at `q`, admitted first as `mode` says; throws as
  /// admit_configurations does (a wrong count, a value not finite or beyond the limits), naming
  /// the value q[j] and its joint (kSingleConfiguration).
  const RobotCheckRow& admit_and_check(const Scalar* q, Eigen::Index count, LimitMode mode);

  const std::vector<GeometryPair>& pairs() const { return pairs_; }
  const QueryOptions& options() const { return options_; }
  bool nearest() const { return nearest_; }
  bool gradient() const { return gradient_; }

 private:
  // A pair's lower bound from its geometries' bounding balls, a bound on its contact threshold
  // (the tolerance times the pair's size, which is at most the centres' distance plus twice the
  // larger radius), and its index.
  struct BallBound {
    Scalar lower;
    Scalar contact;
    int pair;
  };

  void nearest_pair(const Query& query);
  void verdict(const Query& query);
  Scalar box_separation(const GeometryPair& pair) const;
  void place_geometries();
  void order_pairs();

  const RobotModel& model_;
  std::vector<GeometryPair> pairs_;
  QueryOptions options_;
  bool nearest_;
  bool gradient_;
  RobotCheckRow row_;
  // Per configuration, reused from one to the next.
  std::vector<Scalar> admitted_;
  std::vector<Pose> links_;
  std::vector<Pose> world_;
  std::vector<Vector3> centres_;
  std::vector<BallBound> bounds_;
};

}  // namespace swarmcollide
