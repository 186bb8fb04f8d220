#include "swarmcollide/motion/time_of_impact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "../detail/number_text.hpp"
#include "../detail/row_threads.hpp"
#include "../geometry/unit_direction.hpp"
#include "advancement_steps.hpp"
#include "motion_bound.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide {

namespace {

constexpr Scalar kUnit = 0x1p-53;

// A pose moved by `shift`.
Pose shifted(const Pose& pose, const Vector3& shift) {
  Pose moved = pose;
  moved.translation += shift;
  return moved;
}

// The motion with both ends' translations less `origin`: distances depend only on where the
// bodies are relative to each other, and A's start translation as the origin keeps the
// translations' rounding relative to the distances the motion spans, not to how far from the
// world's origin it happens.
RigidMotion relative_to(const RigidMotion& motion, const Vector3& origin) {
  RigidMotion moved = motion.shifted(-origin);
  if (!moved.start().translation.allFinite() || !moved.end().translation.allFinite()) {
    throw std::invalid_argument(
        "the motions' translations differ by more than the double range (about 1.8e308): "
        "express the poses in a frame nearer the bodies");
  }
  return moved;
}

// How far the motion's origin may get from its start: the chord for a linear motion, the
// path's length |R0| |v| for a screw (its origin moves at R(t) v).
Scalar origin_travel(const RigidMotion& motion) {
  if (motion.kind() == MotionKind::linear) {
    return (motion.end().translation - motion.start().translation).stableNorm();
  }
  return motion.start_rotation_norm() * motion.twist_translation().stableNorm() * (1 + 8 * kUnit);
}

// What a distance query at one time proves.
struct Sample {
  Scalar t;
  // Proven within the tolerance at t (contact).
  bool contact;
  // The times after t, and before it, over which the bodies are proven apart.
  Scalar forward;
  Scalar backward;
};

// Compound pairs with more part pairs than this step by the whole motion's speed alone (their
// other pairs are not measured at every sample).
constexpr std::size_t kMostPartPairs = 256;

// Conservative advancement on one pair: `Body` is ConvexPolyhedron or CompoundBody.
template <typename Body>
class Advancement {
 public:
  // A query's answer: a compound pair's names the parts that realise it.
  using Result = std::conditional_t<std::is_same<Body, CompoundBody>::value, CompoundResult,
                                    DistanceResult>;

  Advancement(const Body& a, const RigidMotion& motion_a, const Body& b,
              const RigidMotion& motion_b, const TimeOfImpactOptions& options)
      : a_(a),
        b_(b),
        origin_(motion_a.start().translation),
        motion_a_(relative_to(motion_a, origin_)),
        motion_b_(relative_to(motion_b, origin_)),
        reach_a_(detail::motion_reach(a)),
        reach_b_(detail::motion_reach(b)),
        bound_(motion_a_, detail::motion_reach_across(a, motion_a_.rotation_vector()), motion_b_,
               detail::motion_reach_across(b, motion_b_.rotation_vector())),
        options_(options),
        query_(precise(options.query)) {
    // The moved ends are rounded: the motions above are within a roundoff of their translations'
    // sizes of the given ones (the same shift at both ends, so at every time in between). A
    // screw's twist is computed again from the moved ends: its translation part v = V(w)^-1 p
    // changes by V(w)^-1 of p's rounding (|V(w)^-1| <= pi / 2 for angles up to pi), plus that
    // of computing it twice (a few roundoffs of |p| each), and the path by at most as much
    // (|V(t w) t| <= 1): 16 roundoffs cover it.
    const auto shift_error = [](const RigidMotion& m) {
      const Scalar roundoffs = m.kind() == MotionKind::screw ? 16 : 2;
      return roundoffs * kUnit *
             (m.start().translation.stableNorm() + m.end().translation.stableNorm());
    };
    // The largest size any pair query in this motion can see: where the bodies' box centres can
    // be from each other, plus the larger ball; the queries' own rounding is within
    // kFrameRounding (128 roundoffs) of their frame's unit, which is at most that size. Linear
    // motions' origins are farthest apart at an end (their distance is convex in time); screws'
    // are at most their paths' lengths farther apart than at the start.
    const Scalar ends_apart =
        motion_a_.kind() == MotionKind::linear && motion_b_.kind() == MotionKind::linear
            ? std::max((motion_a_.start().translation - motion_b_.start().translation).stableNorm(),
                       (motion_a_.end().translation - motion_b_.end().translation).stableNorm())
            : (motion_a_.start().translation - motion_b_.start().translation).stableNorm() +
                  origin_travel(motion_a_) + origin_travel(motion_b_);
    const Scalar centres = ends_apart +
        motion_a_.start_rotation_norm() * a.bounds().centre.stableNorm() +
        motion_b_.start_rotation_norm() * b.bounds().centre.stableNorm();
    const Scalar largest_size = centres + 2 * std::max(a.bounds().radius, b.bounds().radius);
    margin_ = (motion_a_.pose_error(reach_a_) + motion_b_.pose_error(reach_b_) +
               shift_error(motion_a_) + shift_error(motion_b_) + 256 * kUnit * largest_size) *
              (1 + 16 * kUnit);
    size_ = 2 * (a.bounds().radius + b.bounds().radius);
    contact_threshold_ = options.query.tolerance * size_;
  }

  TimeOfImpactResult run() {
    // The start is asked its signed distance, which is its distance when the bodies are apart: a
    // motion that starts in contact answers with that result, without asking it again (two
    // queries, the second's penetration depth aside, were a third of such a motion's cost).
    const Result start = measure(0, Goal::signed_distance);
    Sample low = sample(0, start, Goal::signed_distance);
    if (low.contact) return contact(0, 0, start);
    // Sampled times after `low`, nearest last: each one still to be reached.
    std::vector<Sample> ahead;
    const Scalar width = options_.time_tolerance;
    while (true) {
      if (!ahead.empty()) {
        const Sample& next = ahead.back();
        if (low.forward + next.backward >= next.t - low.t) {
          // Proven apart from both ends: every time between them is at most the one's forward
          // reach after it or the other's backward reach before it.
          low = next;
          ahead.pop_back();
          if (low.contact) return contact(low.t, low.t);
          continue;
        }
        if (next.contact && next.t - low.t <= width) return contact(low.t, next.t);
      } else if (low.forward > 1 - low.t) {
        return free();
      }
      if (iterations_ >= options_.max_iterations) {
        return unproven(low, ahead, MotionStatus::max_iterations);
      }
      const Scalar limit = ahead.empty() ? 1 : ahead.back().t;
      if (low.forward >= width) {
        // Advance: the bodies are apart over [low.t, low.t + forward).
        const Scalar t = detail::advanced(low.t, low.forward);
        if (t > low.t && t < limit) {
          const Sample reached = sample(t);
          if (reached.contact) return contact(t, t);
          low = reached;
          continue;
        }
      }
      if (ahead.empty()) {
        // Steps are below the time tolerance: look one tolerance ahead, rounded down so that a
        // contact there closes the bracket (rounded up, it was split once more).
        ahead.push_back(sample(std::min<Scalar>(1, within(low.t, width))));
        continue;
      }
      // Neither end proves the interval: split it.
      const Scalar middle = low.t + (limit - low.t) / 2;
      if (!(middle > low.t && middle < limit)) {
        return unproven(low, ahead, MotionStatus::unresolved);
      }
      ahead.push_back(sample(middle));
    }
  }

 private:
  // The queries ask for a quarter of the motion's tolerance: near contact (where the pair's
  // size is at most 1.5 `size_`) their bounds are then within 3/8 of the threshold of each
  // other, so a time not proven in contact is proven apart by 5/8 of it (less the margin), which
  // lets bisection prove every interval short enough (motions.md).
  static QueryOptions precise(QueryOptions options) {
    options.tolerance /= 4;
    return options;
  }

  // The query's answer at the poses, asked again of "dual" where "exact" or "fcl" (which goes on
  // to "exact" itself) left it unproven and it decides nothing (TimeOfImpactOptions::query):
  // neither proven in contact nor proven farther apart than the contact threshold. Farther, an
  // unproven value still steps as far as a proven one would; in between, the bisection needs
  // the value proven.
  template <typename Ask>
  auto answer(const Ask& ask) {
    auto result = ask(query_);
    if (options_.query.method != Method::dual && !result.certified &&
        !(result.distance + margin_ <= contact_threshold_) &&
        !(result.lower_bound - margin_ > contact_threshold_)) {
      // Made when first needed: most motions never ask it, and a Query checks its options.
      if (!second_query_) {
        QueryOptions dual = precise(options_.query);
        dual.method = Method::dual;
        second_query_.emplace(dual);
      }
      auto second = ask(*second_query_);
      if (second.certified) result = std::move(second);
    }
    return result;
  }

  // `t + width` rounded down to a time no more than `width` after t (t itself where none is).
  static Scalar within(Scalar t, Scalar width) {
    Scalar next = t + width;
    while (next > t && next - t > width) next = std::nextafter(next, t);
    return next > t ? next : t + width;
  }

  enum class Goal { distance, signed_distance };

  // The query's answer at time t.
  Result measure(Scalar t, Goal goal) {
    ++iterations_;
    const Pose pose_a = motion_a_.at(t);
    const Pose pose_b = motion_b_.at(t);
    if (goal == Goal::signed_distance) {
      return answer([&](const Query& q) { return q.signed_distance(a_, pose_a, b_, pose_b); });
    }
    return answer([&](const Query& q) { return q.distance(a_, pose_a, b_, pose_b); });
  }

  Sample sample(Scalar t) { return sample(t, measure(t, Goal::distance), Goal::distance); }

  // What `result`, the query's answer to `goal` at t, proves.
  Sample sample(Scalar t, const Result& result, Goal goal) {
    Sample s{t, result.distance + margin_ <= contact_threshold_, 0, 0};
    const Scalar apart = result.lower_bound - margin_;
    if (!s.contact && !(apart > 0) && goal == Goal::distance &&
        result.distance <= contact_threshold_) {
      // In contact, but its distance (0 for an overlap) is not proven within the threshold once
      // the margin is added: the margin grows with the motion's extent, and past some 1e5 times
      // the bodies' size it exceeds the threshold (unit cubes 1e5 from the origin moving a few
      // units were never certified in contact, however deep they overlapped). An overlap deeper
      // than the margin still proves contact: the signed distance measures it, as
      // Robot.check_motion's samples do.
      s.contact = measure(t, Goal::signed_distance).distance + margin_ <= contact_threshold_;
    }
    if (s.contact || !(apart > 0)) return s;
    s.forward = s.backward = detail::reach_over(apart, bound_.full());
    const Scalar length = result.direction.norm();
    if (length > 0.5) reach_along(t, result, result.direction / length, apart, s);
    return s;
  }

  // The lower bound of a convex pair is the separation along `direction`, so its reaches along it
  // hold. A compound body's is the least over its part pairs: only the pair that realises the
  // answer (`part_a`, `part_b`, whose own lower bound, at least the compound's, is its separation
  // along `direction`) keeps to it; every other pair is apart by at least the compound's bound
  // and by what other_pairs_apart measures, closing at no more than the whole motion's speed.
  // The union stays apart while every pair does. (Without it, a tetrahedron grazing a compound
  // body of an ellipsoid and a cone took 25,968 queries and 149 s; alone, the ellipsoid 16.)
  void reach_along(Scalar t, const Result& result, const Vector3& n, Scalar apart,
                   Sample& s) {
    detail::MotionBound::Reaches reaches{0, 0};
    if constexpr (std::is_same<Body, ConvexPolyhedron>::value) {
      reaches = bound_.reaches_along(a_, b_, t, n, apart);
    } else {
      const std::size_t pairs = a_.parts().size() * b_.parts().size();
      if (pairs > kMostPartPairs || result.part_a < 0 || result.part_b < 0) return;
      reaches = bound_.reaches_along(a_.parts()[static_cast<std::size_t>(result.part_a)],
                                     b_.parts()[static_cast<std::size_t>(result.part_b)], t, n,
                                     apart);
      const Scalar others = detail::reach_over(
          std::max(apart, other_pairs_apart(t, result.part_a, result.part_b, n, apart)),
          bound_.full());
      reaches.forward = std::min(reaches.forward, others);
      reaches.backward = std::min(reaches.backward, others);
    }
    s.forward = std::max(s.forward, reaches.forward);
    s.backward = std::max(s.backward, reaches.backward);
  }

  // A lower bound at t on the distance between every pair of parts but (`skip_a`, `skip_b`):
  // the best of their bounding balls' separation and their separations along `n` (the realising
  // pair's direction, which often separates its neighbours too) and along their centres'
  // difference, less the poses' rounding (the margin); where these prove no more than `floor`
  // (the compound's own bound), the pair's distance query's lower bound, counted as a query (a
  // box sliding past an ellipsoid part near a cylinder part whose ball its own overlaps took
  // 63,082 queries, stepping by the ellipsoid's gap).
  Scalar other_pairs_apart(Scalar t, int skip_a, int skip_b, const Vector3& n, Scalar floor) {
    const Pose pose_a = motion_a_.at(t);
    const Pose pose_b = motion_b_.at(t);
    Scalar least = std::numeric_limits<Scalar>::infinity();
    for (std::size_t i = 0; i < a_.parts().size(); ++i) {
      const ConvexPolyhedron& part_a = a_.parts()[i];
      const Vector3 centre_a = pose_a.rotation * part_a.bounds().centre + pose_a.translation;
      for (std::size_t j = 0; j < b_.parts().size(); ++j) {
        if (static_cast<int>(i) == skip_a && static_cast<int>(j) == skip_b) continue;
        const ConvexPolyhedron& part_b = b_.parts()[j];
        const Vector3 centre_b = pose_b.rotation * part_b.bounds().centre + pose_b.translation;
        const Vector3 between = centre_b - centre_a;
        // Without overflow (an infinite length would prove the parts apart).
        const Scalar length = detail::robust_length(between);
        const Scalar rounding = 16 * kUnit *
            (detail::robust_length(centre_a) + detail::robust_length(centre_b) +
             part_a.bounds().radius + part_b.bounds().radius);
        Scalar apart = length - part_a.bounds().radius - part_b.bounds().radius - rounding;
        apart = std::max(apart, separation(part_a, pose_a, part_b, pose_b, n));
        if (length > 0) {
          apart = std::max(apart, separation(part_a, pose_a, part_b, pose_b, between / length));
        }
        if (!(apart - margin_ > floor)) {
          ++iterations_;
          apart = std::max(apart, query_.distance(part_a, pose_a, part_b, pose_b).lower_bound);
        }
        least = std::min(least, apart - margin_);
      }
    }
    return least;
  }

  // How far B lies beyond A along the unit `n` at the poses (a lower bound on their distance
  // where positive): their support values, less a curved support's error and the rounding of
  // the placed heights.
  static Scalar separation(const ConvexPolyhedron& a, const Pose& pose_a,
                           const ConvexPolyhedron& b, const Pose& pose_b, const Vector3& n) {
    const Vector3 top = pose_a.rotation * a.support(pose_a.rotation.transpose() * n) +
                        pose_a.translation;
    const Vector3 bottom = pose_b.rotation * b.support(-(pose_b.rotation.transpose() * n)) +
                           pose_b.translation;
    const Scalar error = a.support_error_per_radius() * a.bounds().radius +
                         b.support_error_per_radius() * b.bounds().radius +
                         32 * kUnit * (detail::robust_length(top) + detail::robust_length(bottom) +
                                       a.radius() + b.radius());
    return n.dot(bottom) - n.dot(top) - a.radius() - b.radius() - error;
  }

  TimeOfImpactResult free() {
    TimeOfImpactResult r;
    r.touches = false;
    r.t_lower = r.t_upper = 1;
    r.pose_a = shifted(motion_a_.at(1), origin_);
    r.pose_b = shifted(motion_b_.at(1), origin_);
    r.distance = std::numeric_limits<Scalar>::quiet_NaN();
    r.certified = true;
    r.iterations = iterations_;
    r.status = MotionStatus::converged;
    return r;
  }

  TimeOfImpactResult contact(Scalar lower, Scalar upper) {
    return contact(lower, upper, signed_at(upper));
  }

  // The same, with `result` the signed distance at `upper`.
  TimeOfImpactResult contact(Scalar lower, Scalar upper, const DistanceResult& result) {
    TimeOfImpactResult r = touching(upper, result);
    r.t_lower = lower;
    r.certified = true;
    r.status = MotionStatus::converged;
    return r;
  }

  TimeOfImpactResult unproven(const Sample& low, const std::vector<Sample>& ahead,
                              MotionStatus status) {
    Scalar upper = 1;
    for (const Sample& s : ahead) {
      if (s.contact) upper = std::min(upper, s.t);
    }
    TimeOfImpactResult r = touching(upper, signed_at(upper));
    r.t_lower = low.t;
    r.certified = false;
    r.status = status;
    return r;
  }

  // The signed distance at t, which touching reports (not counted as an iteration).
  DistanceResult signed_at(Scalar t) {
    const Pose pose_a = motion_a_.at(t);
    const Pose pose_b = motion_b_.at(t);
    return answer([&](const Query& q) { return q.signed_distance(a_, pose_a, b_, pose_b); });
  }

  // The poses at `t`, with the witnesses and normal of `contact`, the signed distance there.
  TimeOfImpactResult touching(Scalar t, const DistanceResult& contact) {
    TimeOfImpactResult r;
    r.touches = true;
    r.t_upper = t;
    r.pose_a = shifted(motion_a_.at(t), origin_);
    r.pose_b = shifted(motion_b_.at(t), origin_);
    r.distance = contact.distance;
    r.point_a = contact.point_a + origin_;
    r.point_b = contact.point_b + origin_;
    r.normal = contact.direction;
    r.iterations = iterations_;
    return r;
  }

  const Body& a_;
  const Body& b_;
  Vector3 origin_;
  RigidMotion motion_a_;
  RigidMotion motion_b_;
  Scalar reach_a_;
  Scalar reach_b_;
  detail::MotionBound bound_;
  const TimeOfImpactOptions& options_;
  Query query_;
  // "dual" at the same tolerance, for times that "exact" leaves unproven near contact.
  std::optional<Query> second_query_;
  Scalar margin_ = 0;
  Scalar size_ = 0;
  Scalar contact_threshold_ = 0;
  int iterations_ = 0;
};

TimeOfImpactResult advance(const ConvexPolyhedron& a, const RigidMotion& motion_a,
                           const ConvexPolyhedron& b, const RigidMotion& motion_b,
                           const TimeOfImpactOptions& options) {
  return Advancement<ConvexPolyhedron>(a, motion_a, b, motion_b, options).run();
}

// Two compound bodies of one part each are those parts (placed in their bodies' frames), and
// answer as convex bodies: their queries' separating directions bound the motion, which a
// compound body's do not. So a pair of convex bodies in a batch that holds compound bodies (where
// every body is wrapped as one) answers as it does alone, whatever the other rows hold.
TimeOfImpactResult advance(const CompoundBody& a, const RigidMotion& motion_a,
                           const CompoundBody& b, const RigidMotion& motion_b,
                           const TimeOfImpactOptions& options) {
  if (a.size() == 1 && b.size() == 1) {
    return advance(a.parts().front(), motion_a, b.parts().front(), motion_b, options);
  }
  return Advancement<CompoundBody>(a, motion_a, b, motion_b, options).run();
}

template <typename Body>
TimeOfImpactResult solve(const Body& a, const RigidMotion& motion_a, const Body& b,
                         const RigidMotion& motion_b, const TimeOfImpactOptions& options) {
  options.validate();
  return advance(a, motion_a, b, motion_b, options);
}

template <typename Body>
std::vector<TimeOfImpactResult> solve_many(const BatchBodies<Body>& as,
                                           const std::vector<RigidMotion>& motions_a,
                                           const BatchBodies<Body>& bs,
                                           const std::vector<RigidMotion>& motions_b,
                                           const TimeOfImpactOptions& options, int threads) {
  options.validate();
  // The rows: the longest list other than one for all, or none when every such list is empty.
  std::size_t rows = 1;
  bool none = false;
  const auto count = [&rows, &none](std::size_t n, bool single) {
    if (!single && n == 0) none = true;
    if (!single && n != 1) rows = std::max(rows, n);
  };
  count(as.size(), as.single());
  count(bs.size(), bs.single());
  count(motions_a.size(), false);
  count(motions_b.size(), false);
  if (none && rows == 1) rows = 0;
  const auto check = [rows](std::size_t n, bool single, const char* name) {
    if (!single && n != 1 && n != rows) {
      throw std::invalid_argument(std::string(name) + " has " + std::to_string(n) +
                                  " entries where the other arguments have " +
                                  std::to_string(rows) + "; give one per row, or one for all");
    }
  };
  check(as.size(), as.single(), "As");
  check(bs.size(), bs.single(), "Bs");
  check(motions_a.size(), false, "motions_a");
  check(motions_b.size(), false, "motions_b");
  if (motions_a.empty() || motions_b.empty() || as.size() == 0 || bs.size() == 0) return {};
  const auto pick = [](std::size_t n, std::size_t row) { return n == 1 ? 0 : row; };
  std::vector<TimeOfImpactResult> results(rows);
  // Each motion answered whole by one thread (detail::over_rows: the caller alone until the rows
  // left are worth waking the others for; the lowest failing row's error, "motion[i]: ...").
  detail::over_rows(
      rows, threads,
      [&] {
        return [&](std::size_t row) {
          results[row] = advance(as[pick(as.size(), row)], motions_a[pick(motions_a.size(), row)],
                                 bs[pick(bs.size(), row)], motions_b[pick(motions_b.size(), row)],
                                 options);
        };
      },
      "motion");
  return results;
}

}  // namespace

void TimeOfImpactOptions::validate() const {
  query.validate();
  const unsigned needed = kDistance | kSignedDistance;
  if ((method_info(query.method).capabilities & needed) != needed) {
    throw std::invalid_argument(std::string("time_of_impact needs a method with distances and "
                                            "signed distances; method '") +
                                method_name(query.method) + "' has not both: use 'dual', "
                                "'exact' or 'fcl'");
  }
  if (!(query.tolerance > 0)) {
    throw std::invalid_argument(
        "tolerance must be positive for a motion: the poses between its ends are rounded, so "
        "contact can only be proven to within a tolerance (got 0)");
  }
  // A bracket within [0, 1] is never wider than the whole motion: a width above 1 would ask for
  // nothing and read as a mistaken unit (seconds, a percentage).
  if (!(time_tolerance > 0 && time_tolerance <= 1)) {
    throw std::invalid_argument("time_tolerance must be a positive fraction of the motion's "
                                "duration, at most 1 (got " + detail::number_text(time_tolerance) +
                                ")");
  }
  if (max_iterations < 1) {
    throw std::invalid_argument("max_iterations must be at least 1 (got " +
                                std::to_string(max_iterations) + ")");
  }
}

TimeOfImpactResult time_of_impact(const ConvexPolyhedron& a, const RigidMotion& motion_a,
                                  const ConvexPolyhedron& b, const RigidMotion& motion_b,
                                  const TimeOfImpactOptions& options) {
  return solve(a, motion_a, b, motion_b, options);
}

TimeOfImpactResult time_of_impact(const CompoundBody& a, const RigidMotion& motion_a,
                                  const CompoundBody& b, const RigidMotion& motion_b,
                                  const TimeOfImpactOptions& options) {
  return solve(a, motion_a, b, motion_b, options);
}

std::vector<TimeOfImpactResult> time_of_impact_many(const BatchBodies<ConvexPolyhedron>& as,
                                                    const std::vector<RigidMotion>& motions_a,
                                                    const BatchBodies<ConvexPolyhedron>& bs,
                                                    const std::vector<RigidMotion>& motions_b,
                                                    const TimeOfImpactOptions& options,
                                                    int threads) {
  return solve_many(as, motions_a, bs, motions_b, options, threads);
}

std::vector<TimeOfImpactResult> time_of_impact_many(const BatchBodies<CompoundBody>& as,
                                                    const std::vector<RigidMotion>& motions_a,
                                                    const BatchBodies<CompoundBody>& bs,
                                                    const std::vector<RigidMotion>& motions_b,
                                                    const TimeOfImpactOptions& options,
                                                    int threads) {
  return solve_many(as, motions_a, bs, motions_b, options, threads);
}

}  // namespace swarmcollide
