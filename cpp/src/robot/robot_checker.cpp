#include "swarmcollide/robot/robot_checker.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "../geometry/unit_direction.hpp"
#include "../queries/dispatch.hpp"
#include "box_screen.hpp"
#include "geometry_pairs.hpp"
#include "swarmcollide/queries/batch.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide {

namespace {

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

RobotChecker::RobotChecker(const RobotModel& model, std::vector<GeometryPair> pairs,
                           QueryOptions options, bool nearest, bool gradient)
    : model_(model),
      pairs_(std::move(pairs)),
      options_(std::move(options)),
      nearest_(nearest),
      gradient_(gradient) {
  if (gradient && !nearest) {
    throw std::invalid_argument("gradient needs the nearest pair: pass nearest=True with it");
  }
  validate_pairs(model_, pairs_);
  options_.validate();  // once, before any configuration
  detail::require_geometry_shapes(model_, pairs_, options_.method);
  // Here, before any configuration: the first configuration's pair query refused it, and a
  // batch's message named that configuration as if it were at fault.
  if (nearest_ && !(method_info(options_.method).capabilities & kSignedDistance)) {
    throw std::invalid_argument(
        std::string("method '") + method_name(options_.method) +
        "' answers verdicts, not the signed distances the nearest pair is found by: pass "
        "nearest=False for the verdict alone, or a method that answers them (" +
        detail::methods_with(kSignedDistance) + ")");
  }
  admitted_.resize(static_cast<std::size_t>(model_.dof()));
  if (gradient_) row_.gradient.setZero(model_.dof());
}

const RobotCheckRow& RobotChecker::admit_and_check(const Scalar* q, Eigen::Index count,
                                                   LimitMode mode) {
  admit_configuration(model_, q, count, mode, kSingleConfiguration, admitted_.data());
  return check(admitted_.data());
}

// The pairs in increasing order of the separation of their geometries' bounding balls (a proven
// lower bound on their signed distance: the bodies lie in the balls), answered until the next
// pair's balls are farther apart than the nearest pair found is, or than its contact threshold.
// The pairs skipped are then proven farther than the minimum and apart, so the answer is the one
// of answering every pair.
const RobotCheckRow& RobotChecker::check(const Scalar* q, std::size_t row) {
  link_poses(model_, q, links_);
  place_geometries();
  order_pairs();
  QueryOptions options = options_;
  options.seed = pair_seed(options_.seed, row);  // as signed_distance_many seeds row `row`
  const Query query(options);
  if (nearest_) {
    nearest_pair(query);
  } else {
    verdict(query);
  }
  return row_;
}

void RobotChecker::nearest_pair(const Query& query) {
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
  row_.colliding = colliding;
  row_.certified = certified;
  row_.min_distance = least;
  row_.lower_bound = lower;
  row_.pair = nearest;
  row_.point_a = row_.point_b = row_.normal = Vector3::Zero();
  if (gradient_) row_.gradient.setZero();
  if (nearest < 0) return;
  row_.point_a = best.point_a;
  row_.point_b = best.point_b;
  row_.normal = best.direction;
  if (!gradient_) return;
  const GeometryPair& pair = pairs_[static_cast<std::size_t>(nearest)];
  Scalar* out = row_.gradient.data();
  // d = normal . (point_b - point_a): B's witness moving along the normal adds, A's subtracts.
  add_jacobian(model_, links_, model_.geometries()[pair.b].link, best.point_b, best.direction, 1,
               out);
  add_jacobian(model_, links_, model_.geometries()[pair.a].link, best.point_a, best.direction, -1,
               out);
}

// The verdict alone: the pairs whose balls are not proven apart, nearest balls first, each
// answered by Query::collision (which stops at the first separating plane it proves) until one
// is proven in contact. The verdict is proven when that pair's is, or when no pair collides and
// every pair answered is certified.
void RobotChecker::verdict(const Query& query) {
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
  row_.colliding = colliding;
  row_.certified = certified;
  row_.pair = first;
  row_.min_distance = std::numeric_limits<Scalar>::quiet_NaN();
  row_.lower_bound = std::numeric_limits<Scalar>::quiet_NaN();
  row_.point_a = row_.point_b = row_.normal = Vector3::Zero();
}

// The separation of the pair's geometries' placed boxes (detail::box_separation).
Scalar RobotChecker::box_separation(const GeometryPair& pair) const {
  return detail::box_separation(model_.geometries()[pair.a].body.bounds().box, world_[pair.a],
                                model_.geometries()[pair.b].body.bounds().box, world_[pair.b]);
}

void RobotChecker::place_geometries() {
  const std::vector<Geometry>& geometries = model_.geometries();
  world_.resize(geometries.size());
  centres_.resize(geometries.size());
  for (std::size_t g = 0; g < geometries.size(); ++g) {
    const Geometry& geometry = geometries[g];
    world_[g] = geometry_pose(model_, links_, static_cast<int>(g));
    centres_[g] = world_[g].rotation * geometry.body.bounds().centre + world_[g].translation;
  }
}

void RobotChecker::order_pairs() {
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
    // Without overflow: the plain norm of centres 1.4e154 apart is infinite, a bound above
    // every pair's that could put this one after a nearer one.
    const Scalar apart = detail::robust_length(ca - cb);
    // Twice the threshold: a margin for the rounding of both.
    const Scalar contact = 2 * options_.tolerance * (apart + 2 * std::max(a.radius, b.radius));
    bounds_[p] = {apart - a.radius - b.radius - margin, contact, static_cast<int>(p)};
  }
  std::sort(bounds_.begin(), bounds_.end(), [](const BallBound& x, const BallBound& y) {
    return x.lower < y.lower || (x.lower == y.lower && x.pair < y.pair);
  });
}

}  // namespace swarmcollide
