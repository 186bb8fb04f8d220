#include "swarmcollide/robot/robot_queries.hpp"

#include <cmath>
#include <limits>

namespace swarmcollide {

namespace {

// Geometry g's poses in the table of geometry_poses (row-major transforms), one per
// configuration.
PoseArray poses_of(const std::vector<Scalar>& table, std::size_t geometries, std::size_t g,
                   std::size_t count) {
  const auto stride = static_cast<std::ptrdiff_t>(geometries) * 16;
  const Scalar* first = table.data() + static_cast<std::ptrdiff_t>(g) * 16;
  return PoseArray{first, first + 3, count, stride, 4, stride, 4};
}

// Every pair's signed distances over the configurations, one batch per pair.
std::vector<BatchResult> pair_answers(const RobotModel& model,
                                      const std::vector<GeometryPair>& pairs,
                                      const Configurations& q, const QueryOptions& options,
                                      const BatchSettings& settings) {
  validate_pairs(model, pairs);
  if (q.cols() != model.dof()) {
    throw std::invalid_argument("q must have " + std::to_string(model.dof()) +
                                " values per configuration, got " + std::to_string(q.cols()));
  }
  const std::size_t count = static_cast<std::size_t>(q.rows());
  // A batch without poses would answer one row at the identity.
  if (count == 0) return std::vector<BatchResult>(pairs.size());
  const std::size_t geometries = model.geometries().size();
  std::vector<Scalar> table(count * geometries * 16);
  geometry_poses(model, q, table.data());
  std::vector<BatchResult> answers;
  answers.reserve(pairs.size());
  for (const GeometryPair& pair : pairs) {
    BatchPoses poses;
    poses.array_a = poses_of(table, geometries, static_cast<std::size_t>(pair.a), count);
    poses.array_b = poses_of(table, geometries, static_cast<std::size_t>(pair.b), count);
    answers.push_back(signed_distance_many(model.geometries()[pair.a].body,
                                           model.geometries()[pair.b].body, options, settings,
                                           poses));
  }
  return answers;
}

// The velocity of `point` fixed to `link` per unit speed of each degree of freedom, added into
// `row` with `sign` along `normal`.
void add_jacobian(const RobotModel& model, const std::vector<Pose>& links, int link,
                  const Vector3& point, const Vector3& normal, Scalar sign, Scalar* row) {
  for (int l = link; l >= 0;) {
    const int j = model.parent_joint(l);
    if (j < 0) break;
    const Joint& joint = model.joints()[j];
    const int dof = model.driving_dof(j);
    if (dof >= 0) {
      // A mimic joint turns `multiplier` times as fast as the joint it mimics.
      const Scalar rate = joint.mimic < 0 ? 1 : joint.multiplier;
      // The child's frame is the joint frame after the motion: the axis and the turning point are
      // the child's.
      const Pose& frame = links[joint.child];
      const Vector3 axis = frame.rotation * joint.axis;
      const Vector3 velocity = joint.type == JointType::prismatic
                                   ? axis
                                   : Vector3(axis.cross(point - frame.translation));
      row[dof] += sign * rate * normal.dot(velocity);
    }
    l = joint.parent;
  }
}

}  // namespace

RobotDistances robot_distances(const RobotModel& model, const std::vector<GeometryPair>& pairs,
                               const Configurations& q, const QueryOptions& options,
                               const BatchSettings& settings) {
  const std::vector<BatchResult> answers = pair_answers(model, pairs, q, options, settings);
  const Eigen::Index m = q.rows();
  const auto count = static_cast<Eigen::Index>(pairs.size());
  RobotDistances result{RowTable<Scalar>(m, count), RowTable<Scalar>(m, count),
                        RowTable<bool>(m, count), RowTable<bool>(m, count)};
  for (Eigen::Index p = 0; p < count; ++p) {
    const BatchResult& answer = answers[static_cast<std::size_t>(p)];
    result.distance.col(p) = answer.distance.array();
    result.lower_bound.col(p) = answer.lower_bound.array();
    result.colliding.col(p) = answer.colliding;
    result.certified.col(p) = answer.certified;
  }
  return result;
}

RobotCheck robot_check(const RobotModel& model, const std::vector<GeometryPair>& pairs,
                       const Configurations& q, const QueryOptions& options,
                       const BatchSettings& settings, bool gradient) {
  const std::vector<BatchResult> answers = pair_answers(model, pairs, q, options, settings);
  const Eigen::Index m = q.rows();
  RobotCheck check;
  check.colliding.setConstant(m, false);
  check.min_distance.setConstant(m, std::numeric_limits<Scalar>::infinity());
  check.lower_bound.setConstant(m, std::numeric_limits<Scalar>::infinity());
  check.certified.setConstant(m, true);
  check.pair.setConstant(m, -1);
  check.point_a.setZero(m, 3);
  check.point_b.setZero(m, 3);
  check.normal.setZero(m, 3);
  for (std::size_t p = 0; p < answers.size(); ++p) {
    const BatchResult& answer = answers[p];
    for (Eigen::Index i = 0; i < m; ++i) {
      check.colliding(i) = check.colliding(i) || answer.colliding(i);
      check.certified(i) = check.certified(i) && answer.certified(i);
      check.lower_bound(i) = std::min(check.lower_bound(i), answer.lower_bound(i));
      // Strictly less: the lowest pair index wins a tie, whatever the order rows were answered in.
      if (answer.distance(i) < check.min_distance(i)) {
        check.min_distance(i) = answer.distance(i);
        check.pair(i) = static_cast<int>(p);
        check.point_a.row(i) = answer.point_a.row(i);
        check.point_b.row(i) = answer.point_b.row(i);
        check.normal.row(i) = answer.direction.row(i);
      }
    }
  }
  if (!gradient) return check;
  check.gradient.setZero(m, model.dof());
  std::vector<Pose> links;
  for (Eigen::Index i = 0; i < m; ++i) {
    if (check.pair(i) < 0) continue;
    link_poses(model, q.row(i).data(), links);
    const GeometryPair& pair = pairs[static_cast<std::size_t>(check.pair(i))];
    const Vector3 normal = check.normal.row(i).transpose();
    Scalar* row = check.gradient.row(i).data();
    // d = normal . (point_b - point_a): B's witness moving along the normal adds, A's subtracts.
    add_jacobian(model, links, model.geometries()[pair.b].link, check.point_b.row(i).transpose(),
                 normal, 1, row);
    add_jacobian(model, links, model.geometries()[pair.a].link, check.point_a.row(i).transpose(),
                 normal, -1, row);
  }
  return check;
}

}  // namespace swarmcollide
