#include "swarmcollide/robot/robot_queries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "../detail/row_threads.hpp"
#include "box_screen.hpp"
#include "geometry_pairs.hpp"
#include "swarmcollide/queries/query.hpp"

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

namespace {

// A pair's lower bound from its geometries' bounding balls, a bound on its contact threshold
// (the tolerance times the pair's size, which is at most the centres' distance plus twice the
// larger radius), and its index.
struct BallBound {
  Scalar lower;
  Scalar contact;
  int pair;
};

// One configuration of a check: the pairs in increasing order of the separation of their
// geometries' bounding balls (a proven lower bound on their signed distance: the bodies lie in
// the balls), answered until the next pair's balls are farther apart than the nearest pair found
// is, or than its contact threshold. The pairs skipped are then proven farther than the minimum
// and apart, so the answer is the one of answering every pair.
class ConfigurationCheck {
 public:
  ConfigurationCheck(const RobotModel& model, const std::vector<GeometryPair>& pairs,
                     const Configurations& q, const QueryOptions& options, bool nearest,
                     bool gradient, RobotCheck& check)
      : model_(model), pairs_(pairs), q_(q), options_(options), nearest_(nearest),
        gradient_(gradient), check_(check) {}

  void operator()(std::size_t row) {
    const auto i = static_cast<Eigen::Index>(row);
    link_poses(model_, q_.row(i).data(), links_);
    place_geometries();
    order_pairs();
    QueryOptions options = options_;
    options.seed = pair_seed(options_.seed, row);  // as signed_distance_many seeds row `row`
    const Query query(options);
    if (!nearest_) return verdict(query, i);
    bool colliding = false;
    bool certified = true;
    Scalar least = std::numeric_limits<Scalar>::infinity();
    Scalar lower = least;
    int nearest = -1;
    DistanceResult best;
    for (const BallBound& bound : bounds_) {
      // Once some pair is in contact, only the minimum can still change.
      if (bound.lower > least && (colliding || bound.lower > bound.contact)) continue;
      const GeometryPair& pair = pairs_[static_cast<std::size_t>(bound.pair)];
      // The boxes' separation, a tighter proven bound than the balls' for elongated links.
      const Scalar boxes = box_separation(pair);
      if (boxes > least && (colliding || boxes > bound.contact)) continue;
      DistanceResult result =
          detail::signed_distance_of(query, model_, pair, world_[pair.a], world_[pair.b]);
      colliding = colliding || result.colliding;
      certified = certified && result.certified;
      lower = std::min(lower, result.lower_bound);
      if (result.distance < least || (result.distance == least && bound.pair < nearest)) {
        least = result.distance;
        nearest = bound.pair;
        best = std::move(result);
      }
    }
    check_.colliding(i) = colliding;
    check_.certified(i) = certified;
    check_.min_distance(i) = least;
    check_.lower_bound(i) = lower;
    check_.pair(i) = nearest;
    if (nearest < 0) return;
    check_.point_a.row(i) = best.point_a.transpose();
    check_.point_b.row(i) = best.point_b.transpose();
    check_.normal.row(i) = best.direction.transpose();
    if (!gradient_) return;
    const GeometryPair& pair = pairs_[static_cast<std::size_t>(nearest)];
    Scalar* out = check_.gradient.row(i).data();
    // d = normal . (point_b - point_a): B's witness moving along the normal adds, A's subtracts.
    add_jacobian(model_, links_, model_.geometries()[pair.b].link, best.point_b, best.direction,
                 1, out);
    add_jacobian(model_, links_, model_.geometries()[pair.a].link, best.point_a, best.direction,
                 -1, out);
  }

 private:
  // The verdict alone: the pairs whose balls are not proven apart, nearest balls first, each
  // answered by Query::collision (which stops at the first separating plane it proves) until one
  // is proven in contact. The verdict is proven when that pair's is, or when no pair collides and
  // every pair answered is certified.
  void verdict(const Query& query, Eigen::Index i) {
    bool colliding = false;
    bool certified = true;
    int first = -1;
    for (const BallBound& bound : bounds_) {
      if (bound.lower > bound.contact) continue;  // proven apart by their balls
      const GeometryPair& pair = pairs_[static_cast<std::size_t>(bound.pair)];
      // Elongated links' balls overlap where their boxes do not: a few dozen products each.
      if (box_separation(pair) > bound.contact) continue;
      const DistanceResult result =
          detail::collision_of(query, model_, pair, world_[pair.a], world_[pair.b]);
      if (result.colliding && result.certified) {
        colliding = true;
        certified = true;
        first = bound.pair;
        break;
      }
      colliding = colliding || result.colliding;
      certified = certified && result.certified;
      if (result.colliding && first < 0) first = bound.pair;
    }
    check_.colliding(i) = colliding;
    check_.certified(i) = certified;
    check_.pair(i) = first;
    check_.min_distance(i) = std::numeric_limits<Scalar>::quiet_NaN();
    check_.lower_bound(i) = std::numeric_limits<Scalar>::quiet_NaN();
  }

  // The separation of the pair's geometries' placed boxes (detail::box_separation).
  Scalar box_separation(const GeometryPair& pair) const {
    return detail::box_separation(model_.geometries()[pair.a].body.bounds().box, world_[pair.a],
                                  model_.geometries()[pair.b].body.bounds().box, world_[pair.b]);
  }

  void place_geometries() {
    const std::vector<Geometry>& geometries = model_.geometries();
    world_.resize(geometries.size());
    centres_.resize(geometries.size());
    for (std::size_t g = 0; g < geometries.size(); ++g) {
      const Geometry& geometry = geometries[g];
      world_[g] = geometry_pose(model_, links_, static_cast<int>(g));
      centres_[g] = world_[g].rotation * geometry.body.bounds().centre + world_[g].translation;
    }
  }

  void order_pairs() {
    bounds_.resize(pairs_.size());
    for (std::size_t p = 0; p < pairs_.size(); ++p) {
      const GeometryPair& pair = pairs_[p];
      const BodyBounds& a = model_.geometries()[pair.a].body.bounds();
      const BodyBounds& b = model_.geometries()[pair.b].body.bounds();
      const Vector3& ca = centres_[pair.a];
      const Vector3& cb = centres_[pair.b];
      // Less a margin for the rounding of the placed centres and of this sum (a few units in the
      // last place of the magnitudes involved), so that the bound stays below the true separation.
      const Scalar margin =
          1e-12 * (ca.lpNorm<Eigen::Infinity>() + cb.lpNorm<Eigen::Infinity>() + a.radius +
                   b.radius);
      const Scalar apart = (ca - cb).norm();
      // Twice the threshold: a margin for the rounding of both.
      const Scalar contact = 2 * options_.tolerance * (apart + 2 * std::max(a.radius, b.radius));
      bounds_[p] = {apart - a.radius - b.radius - margin, contact, static_cast<int>(p)};
    }
    std::sort(bounds_.begin(), bounds_.end(), [](const BallBound& x, const BallBound& y) {
      return x.lower < y.lower || (x.lower == y.lower && x.pair < y.pair);
    });
  }

  const RobotModel& model_;
  const std::vector<GeometryPair>& pairs_;
  const Configurations& q_;
  const QueryOptions& options_;
  bool nearest_;
  bool gradient_;
  RobotCheck& check_;
  // Per configuration, reused from one to the next by the thread that owns this.
  std::vector<Pose> links_;
  std::vector<Pose> world_;
  std::vector<Vector3> centres_;
  std::vector<BallBound> bounds_;
};

}  // namespace

RobotCheck robot_check(const RobotModel& model, const std::vector<GeometryPair>& pairs,
                       const Configurations& q, const QueryOptions& options,
                       const BatchSettings& settings, bool gradient, bool nearest) {
  if (gradient && !nearest) {
    throw std::invalid_argument("gradient needs the nearest pair: pass nearest=True with it");
  }
  validate_pairs(model, pairs);
  if (q.cols() != model.dof()) {
    throw std::invalid_argument("q must have " + std::to_string(model.dof()) +
                                " values per configuration, got " + std::to_string(q.cols()));
  }
  const Query validated(options);  // the options are checked once, before any configuration
  detail::require_geometry_shapes(model, pairs, options.method);
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
  detail::over_rows(static_cast<std::size_t>(m), settings.threads, [&] {
    return ConfigurationCheck(model, pairs, q, validated.options(), nearest, gradient, check);
  });
  return check;
}

}  // namespace swarmcollide
