// Scene::sweep: the bodies' motions from their poses to new ones, with every pair's first contact
// bracketed by time_of_impact over a broadphase of swept boxes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "scene_impl.hpp"
#include "swarmcollide/motion/time_of_impact.hpp"
#include "swarmcollide/queries/batch.hpp"

namespace swarmcollide {

namespace {

using detail::SceneBody;

constexpr Scalar kEpsilon = std::numeric_limits<Scalar>::epsilon();

// The box of the segment from `from` to `from + step`, added to `box`.
void add_segment(Aabb& box, const Vector3& step) {
  box.min += step.cwiseMin(Vector3::Zero());
  box.max += step.cwiseMax(Vector3::Zero());
}

// A box that holds the body over its whole motion (the exact motion: time_of_impact's verdicts
// are about it, its sampled poses' rounding covered by its margins).
//
// Without a turn the body only translates, by T1 - T0 for a linear motion and by R0 v for a
// screw (the same to rounding), so each of its support values moves linearly in time: the union
// of its boxes at the ends holds it.
//
// With a turn, a point x of the body is c + y in its own frame, c the centre of its box and |y|
// at most its reach about c (plus its rounding radius), and in the start frame the motion puts
// it at o(t) + Q(t) c + Q(t) y, o(t) the origin's path and Q(t) the turn by t w about an axis k
// through the origin. Q(t) c keeps its component along k and turns the rest, of length rho, on
// an arc of angle |w| <= pi whose chord joins its ends: every point of such an arc projects
// inside the chord and lies within its sagitta rho (1 - cos(|w| / 2)) of it. The origin's path
// o(t) is the segment to p = R0^T (T1 - T0) for a linear motion; a screw's is p's component
// along k (a segment) plus its component across (an arc about the screw axis, of the same angle,
// whose chord is that component and whose radius is |p_perp| / (2 sin(|w| / 2)), so its sagitta
// is |p_perp| tan(|w| / 4) / 2). So the body lies within the Minkowski sum of these segments,
// widened by the sagittas and the reach: in the world, R0 of it plus T0, whose box is the sum of
// the segments' boxes, padded by |R0| times the sagittas plus the reach.
Aabb swept_box(const SceneBody& b, const RigidMotion& motion) {
  const Pose& start = motion.start();
  const Pose& end = motion.end();
  const Vector3& c = b.body.bounds().centre;
  const Scalar reach = b.reach + b.body.radius();
  const Vector3 shift = end.translation - start.translation;
  const Scalar magnitude = start.translation.stableNorm() + end.translation.stableNorm() +
                           motion.start_rotation_norm() * c.stableNorm() + reach;
  // Each coordinate above is a few products and sums of numbers below `magnitude`, and the
  // screw's twist is within a few roundoffs of |T1 - T0| (rigid_motion.cpp): 64 roundoffs of it.
  const Scalar rounding = 64 * kEpsilon * magnitude;
  Aabb box;
  if (motion.angle() == 0) {
    box = b.box;
    add_segment(box, shift);
  } else {
    const Vector3 axis = motion.rotation_vector() / motion.angle();
    const Scalar sagitta_ratio = 1 - std::cos(motion.angle() / 2);
    const Vector3 centre_across = c - axis.dot(c) * axis;
    Scalar sagittas = centre_across.stableNorm() * sagitta_ratio;
    const Vector3 centre_start = start.rotation * c + start.translation;
    const Vector3 centre_end = start.rotation * (Eigen::AngleAxis<Scalar>(motion.angle(), axis) * c);
    box.min = box.max = centre_start;
    add_segment(box, centre_end - start.rotation * c);
    if (motion.kind() == MotionKind::screw) {
      const Vector3 p = start.rotation.transpose() * shift;
      const Vector3 along = axis.dot(p) * axis;
      add_segment(box, start.rotation * along);
      add_segment(box, start.rotation * (p - along));
      sagittas += (p - along).stableNorm() * std::tan(motion.angle() / 4) / 2;
    } else {
      add_segment(box, shift);
    }
    const Scalar pad = motion.start_rotation_norm() * (sagittas + reach) * (1 + 1e-12);
    box = detail::padded(box, pad);
  }
  return detail::padded(box, rounding);
}

// The radius time_of_impact takes for the body's share of the contact threshold, or more: a
// convex body paired with a compound one is answered as a compound of one part, whose envelope
// is its hull (the same bounds), or for a curved shape its box, at most sqrt(3) times its
// bounding ball.
Scalar threshold_radius(const SceneBody& b) {
  const Scalar radius = b.body.bounds().radius;
  return !b.compound && b.body.curved() ? 2 * radius : radius;
}

// The body as a compound: its own, or one of the one convex body.
const CompoundBody& as_compound(const SceneBody& b, std::unique_ptr<CompoundBody>& made) {
  if (b.compound) return *b.compound;
  made = std::make_unique<CompoundBody>(b.body);
  return *made;
}

struct SweptPair {
  std::uint64_t key;
  const SceneBody* first;
  const SceneBody* second;
};

}  // namespace

SweepResult Scene::sweep(const std::vector<BodyId>& ids, const std::vector<Pose>& poses,
                         const SweepOptions& sweep_options) {
  Impl& s = *impl_;
  const std::lock_guard<std::mutex> lock(s.mutex);
  const std::vector<SceneBody*> targets = s.bodies_to_move(ids, poses);
  TimeOfImpactOptions options;
  options.query = s.options.query;
  options.time_tolerance = sweep_options.time_tolerance;
  options.max_iterations = sweep_options.max_iterations;
  try {
    options.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("sweep: ") + e.what());
  }
  // Every body's motion: the listed ones' to their new poses, the others' still.
  std::unordered_map<BodyId, std::size_t> moving;
  std::vector<RigidMotion> motions;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    moving.emplace(ids[i], i);
    const std::string name = "poses[" + std::to_string(i) + "]";
    motions.emplace_back(targets[i]->pose, poses[i], sweep_options.motion, name.c_str());
  }
  // The still bodies' boxes, and the broadphase's, brought up to date.
  s.fit_boxes(s.padded_for);
  const Scalar share = 2 * (s.options.query.tolerance + 1e-12);
  std::vector<Aabb> swept(targets.size());
  for (std::size_t i = 0; i < targets.size(); ++i) {
    swept[i] = detail::padded(swept_box(*targets[i], motions[i]),
                              share * threshold_radius(*targets[i]));
  }

  // Moving against moving: their swept boxes in a broadphase of their own.
  std::vector<SweptPair> pairs;
  {
    std::vector<std::unique_ptr<detail::BoxedObject>> objects;
    std::vector<detail::BoxedObject*> registered;
    for (std::size_t i = 0; i < targets.size(); ++i) {
      objects.push_back(
          std::make_unique<detail::BoxedObject>(targets[i], targets[i]->id, targets[i]->filter));
      objects.back()->set_box(swept[i]);
      registered.push_back(objects.back().get());
    }
    detail::FclBroadphase broadphase(s.options.broadphase);
    broadphase.insert(registered);
    std::vector<detail::ObjectPair> overlaps;
    broadphase.overlapping_pairs(overlaps);
    for (const auto& [x, y] : overlaps) {
      if (!s.table.pairable(*x, *y)) continue;
      const auto* a = static_cast<const SceneBody*>(x->owner());
      const auto* b = static_cast<const SceneBody*>(y->owner());
      if (b->id < a->id) std::swap(a, b);
      pairs.push_back({detail::pair_key(a->id, b->id), a, b});
    }
    broadphase.erase(registered);
  }
  // Moving against still: the scene's broadphase holds each still body's box padded by at least
  // 4 tol r (Impl::pad_of), more than its share of the threshold.
  std::vector<detail::ObjectPair> overlaps;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const SceneBody& mover = *targets[i];
    detail::BoxedObject probe(targets[i], mover.id, mover.filter);
    probe.set_box(swept[i]);
    overlaps.clear();
    s.broadphase.overlapping(&probe, overlaps);
    for (const auto& [self, other] : overlaps) {
      const auto* still = static_cast<const SceneBody*>(other->owner());
      if (moving.count(still->id) > 0 || !s.table.pairable(probe, *other)) continue;
      if (!detail::overlap(swept[i],
                           detail::padded(still->box, share * threshold_radius(*still)))) {
        continue;
      }
      const SceneBody* a = mover.id < still->id ? &mover : still;
      const SceneBody* b = mover.id < still->id ? still : &mover;
      pairs.push_back({detail::pair_key(a->id, b->id), a, b});
    }
  }
  std::sort(pairs.begin(), pairs.end(),
            [](const SweptPair& x, const SweptPair& y) { return x.key < y.key; });

  // Each candidate's time of impact, on the pool.
  const auto motion_of = [&](const SceneBody& b) {
    const auto at = moving.find(b.id);
    return at != moving.end() ? motions[at->second]
                              : RigidMotion(b.pose, b.pose, sweep_options.motion);
  };
  std::vector<TimeOfImpactResult> results(pairs.size());
  s.pool.for_each_chunk_paced(pairs.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const SweptPair& pair = pairs[k];
      TimeOfImpactOptions pair_options = options;
      pair_options.query.seed = pair_seed(s.options.query.seed, pair.key);
      const RigidMotion motion_a = motion_of(*pair.first);
      const RigidMotion motion_b = motion_of(*pair.second);
      try {
        if (!pair.first->compound && !pair.second->compound) {
          results[k] = time_of_impact(pair.first->body, motion_a, pair.second->body, motion_b,
                                      pair_options);
        } else {
          std::unique_ptr<CompoundBody> made_a;
          std::unique_ptr<CompoundBody> made_b;
          results[k] = time_of_impact(as_compound(*pair.first, made_a), motion_a,
                                      as_compound(*pair.second, made_b), motion_b, pair_options);
        }
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument("bodies " + std::to_string(pair.first->id) + " and " +
                                    std::to_string(pair.second->id) + ": " + error.what());
      }
    }
  });

  std::vector<std::size_t> touching;
  for (std::size_t k = 0; k < results.size(); ++k) {
    if (results[k].touches) touching.push_back(k);
  }
  const auto m = static_cast<Eigen::Index>(touching.size());
  SweepResult out;
  out.pairs.resize(m, 2);
  out.t_lower.resize(m);
  out.t_upper.resize(m);
  out.distance.resize(m);
  out.point_a.resize(m, 3);
  out.point_b.resize(m, 3);
  out.normal.resize(m, 3);
  out.certified.resize(m);
  out.iterations.resize(m);
  for (Eigen::Index row = 0; row < m; ++row) {
    const std::size_t k = touching[static_cast<std::size_t>(row)];
    const TimeOfImpactResult& r = results[k];
    out.pairs(row, 0) = pairs[k].first->id;
    out.pairs(row, 1) = pairs[k].second->id;
    out.t_lower(row) = r.t_lower;
    out.t_upper(row) = r.t_upper;
    out.pose_a.push_back(r.pose_a);
    out.pose_b.push_back(r.pose_b);
    out.distance(row) = r.distance;
    out.point_a.row(row) = r.point_a.transpose();
    out.point_b.row(row) = r.point_b.transpose();
    out.normal.row(row) = r.normal.transpose();
    out.certified(row) = r.certified;
    out.iterations(row) = r.iterations;
  }
  s.stats = SceneStats{};
  s.stats.candidates = pairs.size();
  s.stats.solved = pairs.size();
  for (const TimeOfImpactResult& r : results) s.stats.certified += r.certified;
  for (std::size_t i = 0; i < targets.size(); ++i) s.move_to(*targets[i], poses[i]);
  return out;
}

}  // namespace swarmcollide
