#include "swarmcollide/robot/robot_queries.hpp"

#include <limits>
#include <stdexcept>
#include <string>

#include "../detail/row_threads.hpp"
#include "geometry_pairs.hpp"
#include "swarmcollide/robot/robot_checker.hpp"

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
  detail::require_geometry_shapes(model, pairs, options.method);
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
    answers.push_back(detail::signed_distances_of(model, pair, options, settings, poses));
  }
  return answers;
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
                       const BatchSettings& settings, bool gradient, bool nearest) {
  // Validated here, in the calling thread: each thread's checker is a copy of this one.
  const RobotChecker checker(model, pairs, options, nearest, gradient);
  if (q.cols() != model.dof()) {
    throw std::invalid_argument("q must have " + std::to_string(model.dof()) +
                                " values per configuration, got " + std::to_string(q.cols()));
  }
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
  if (gradient) check.gradient.setZero(m, model.dof());
  // One checker per thread: its buffers are the thread's own; each writes only its rows.
  const auto write_row = [&q, &check](RobotChecker& own, std::size_t row) {
    const auto i = static_cast<Eigen::Index>(row);
    const RobotCheckRow& answer = own.check(q.row(i).data(), row);
    check.colliding(i) = answer.colliding;
    check.min_distance(i) = answer.min_distance;
    check.lower_bound(i) = answer.lower_bound;
    check.certified(i) = answer.certified;
    check.pair(i) = answer.pair;
    check.point_a.row(i) = answer.point_a.transpose();
    check.point_b.row(i) = answer.point_b.transpose();
    check.normal.row(i) = answer.normal.transpose();
    if (answer.gradient.size() > 0) check.gradient.row(i) = answer.gradient.transpose();
  };
  detail::over_rows(static_cast<std::size_t>(m), settings.threads, [&] {
    return [own = checker, &write_row](std::size_t row) mutable { write_row(own, row); };
  });
  return check;
}

}  // namespace swarmcollide
