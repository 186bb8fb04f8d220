#include "motion_bound.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "../geometry/unit_direction.hpp"
#include "advancement_steps.hpp"

namespace swarmcollide::detail {

namespace {

constexpr Scalar kUnit = 0x1p-53;

// Regula falsi steps of depth_reaches after its chord.
constexpr int kDepthRefinements = 1;

// A polyhedron's points at a time t as lines in the time h from t (MotionBound, second order
// aside): point i is at most rate_i h - depth_i above the core's support plane along a direction,
// rate_i its speed along that direction at t and depth_i its depth below that plane at t. Kept
// for polyhedra whose supports are scans of their points, whose pass here costs what a support
// does.
class PointLines {
 public:
  static bool fits(const ConvexPolyhedron& body) {
    return !body.curved() && body.size() <= kHillClimbingThreshold;
  }

  // The body's points moving along the direction at x . turning going forwards in time (the
  // opposite going backwards), `facing` the direction in the body's frame. The depths are
  // compared on the centred points (rounded relative to the body's size) and rounded down. A
  // body that does not turn (`turning` zero) keeps no points: all of them move alike, and the
  // support points' line, rate 0 and depth 0, is the highest.
  PointLines(const ConvexPolyhedron& body, const Vector3& turning, const Vector3& facing)
      : count_(turning.isZero() ? 0 : body.size()) {
    const VertexMatrix& points = body.vertices();
    const VertexMatrix& centred = body.centred_vertices();
    Scalar top = -std::numeric_limits<Scalar>::infinity();
    for (int i = 0; i < count_; ++i) {
      rate_[i] = points.row(i).dot(turning);
      depth_[i] = centred.row(i).dot(facing);
      top = std::max(top, depth_[i]);
    }
    for (int i = 0; i < count_; ++i) depth_[i] = (top - depth_[i]) * (1 - 2 * kUnit);
  }

  // The largest rate of the points on the support plane (depth 0), G's slope at 0, going
  // forwards (`sense` 1) or backwards (-1).
  Scalar top_rate(Scalar sense) const {
    if (count_ == 0) return 0;
    Scalar top = -std::numeric_limits<Scalar>::infinity();
    for (int i = 0; i < count_; ++i) {
      if (depth_[i] == 0) top = std::max(top, sense * rate_[i]);
    }
    return top;
  }

  // max_i (sense rate_i h - depth_i); `size` is set to max_i (|rate_i| h + depth_i), which
  // bounds its rounding in roundoffs.
  Scalar at(Scalar h, Scalar sense, Scalar& size) const {
    Scalar highest = count_ == 0 ? 0 : -std::numeric_limits<Scalar>::infinity();
    size = 0;
    for (int i = 0; i < count_; ++i) {
      highest = std::max(highest, sense * rate_[i] * h - depth_[i]);
      size = std::max(size, std::abs(rate_[i]) * h + depth_[i]);
    }
    return highest;
  }

 private:
  std::array<Scalar, kHillClimbingThreshold> rate_;
  std::array<Scalar, kHillClimbingThreshold> depth_;
  int count_;
};

}  // namespace

Scalar motion_reach(const ConvexPolyhedron& body) {
  Scalar reach = 0;
  if (const SupportFunction* shape = body.curved()) {
    // The shape's points lie within its outer radius of its centre, which is the body's box
    // centre in its own frame.
    reach = body.bounds().centre.stableNorm() + shape->outer_radius();
  } else {
    reach = largest_row_length(body.vertices());
  }
  return reach * (1 + 8 * kUnit);
}

Scalar motion_reach(const CompoundBody& body) {
  Scalar reach = 0;
  for (const ConvexPolyhedron& part : body.parts()) reach = std::max(reach, motion_reach(part));
  return reach;
}

Scalar motion_reach_across(const ConvexPolyhedron& body, const Vector3& axis) {
  const Scalar length = axis.stableNorm();
  if (!(length > 0)) return motion_reach(body);
  const Vector3 unit = axis / length;
  Scalar across = 0;
  if (const SupportFunction* shape = body.curved()) {
    across = unit.cross(body.bounds().centre).stableNorm() + shape->outer_radius();
  } else {
    VertexMatrix crossed(body.vertices().rows(), 3);
    for (int i = 0; i < crossed.rows(); ++i) {
      crossed.row(i) = unit.cross(Vector3(body.vertices().row(i))).transpose();
    }
    across = largest_row_length(crossed);
  }
  // |unit x x| is within a few roundoffs of |x| (the unit vector's length included) of the
  // distance from the axis: 16 roundoffs of the reach cover them, as 8 cover the reach's own.
  return std::min(motion_reach(body), across * (1 + 8 * kUnit) + 16 * kUnit * motion_reach(body));
}

Scalar motion_reach_across(const CompoundBody& body, const Vector3& axis) {
  Scalar reach = 0;
  for (const ConvexPolyhedron& part : body.parts()) {
    reach = std::max(reach, motion_reach_across(part, axis));
  }
  return reach;
}

MotionBound::MotionBound(const RigidMotion& motion_a, Scalar reach_a, const RigidMotion& motion_b,
                         Scalar reach_b)
    : motion_a_(&motion_a), motion_b_(&motion_b), reach_a_(reach_a), reach_b_(reach_b) {
  const Vector3 shift_a = translation_along_axis(motion_a, across_a_);
  const Vector3 shift_b = translation_along_axis(motion_b, across_b_);
  closing_ = shift_a - shift_b;
  const Scalar turn_a = motion_a.angle() * motion_a.start_rotation_norm() * reach_a;
  const Scalar turn_b = motion_b.angle() * motion_b.start_rotation_norm() * reach_b;
  const Scalar across_a = across_a_ * motion_a.start_rotation_norm();
  const Scalar across_b = across_b_ * motion_b.start_rotation_norm();
  // Each difference above and each product is within a few roundoffs of its inputs; 16
  // roundoffs of their sizes (and of the angles' own rounding) cover them. A screw's split of v
  // is within a few roundoffs of |v|, which its share below covers.
  slack_ = 16 * kUnit *
           (shift_a.stableNorm() + shift_b.stableNorm() + turn_a + turn_b + 2 * across_a +
            2 * across_b);
  full_ = (closing_.stableNorm() + across_a + across_b + turn_a + turn_b) * (1 + 16 * kUnit) +
          slack_;
}

Vector3 MotionBound::translation_along_axis(const RigidMotion& motion, Scalar& across) {
  if (motion.kind() == MotionKind::linear) {
    across = 0;
    return motion.end().translation - motion.start().translation;
  }
  const Vector3& v = motion.twist_translation();
  if (motion.angle() == 0) {
    // No axis: the screw is a translation by R0 v.
    across = 0;
    return motion.start().rotation * v;
  }
  const Vector3 axis = motion.rotation_vector() / motion.angle();
  const Vector3 along = axis.dot(v) * axis;
  across = (v - along).stableNorm();
  return motion.start().rotation * along;
}

MotionBound::TurnRates MotionBound::turn_rates(const RigidMotion& motion,
                                               const ConvexPolyhedron& body, Scalar reach,
                                               Scalar t, const Vector3& towards) {
  TurnRates rates;
  if (motion.angle() == 0) return rates;
  // A point x of the core moves along `towards` at (Q(t) x) . u = x . (Q(t)^T u), u = m x w.
  const Vector3 m = motion.start().rotation.transpose() * towards;
  const Vector3 u = m.cross(motion.rotation_vector());
  const Matrix3 turn = motion.turn_at(t);
  const Vector3 turning = turn.transpose() * u;
  // The support point's height falls short of the support value by a few roundoffs of |x| |d|
  // (a curved shape's by its own bound), |x| at most the box centre's length plus the bounds'
  // radius; the computed direction is within some 300 roundoffs of |w| |R0| of the exact one
  // (turn_at's 40 per entry, the transposed products and the cross product), which moves the
  // support value by that times |x|.
  const Scalar size = body.bounds().centre.stableNorm() + body.bounds().radius;
  const Scalar shortfall = body.curved() ? body.curved()->support_error_roundoffs() + 16 : 16;
  const Scalar slack = kUnit * size *
                       (shortfall * turning.norm() +
                        512 * motion.start_rotation_norm() * motion.angle());
  const auto rate = [&](const Vector3& direction) {
    const Scalar height = direction.dot(body.support(direction));
    return height + 4 * kUnit * std::abs(height) + slack;
  };
  rates.forward = rate(turning);
  rates.backward = rate(-turning);
  rates.growth = motion.angle() * u.norm() * reach * (1 + 16 * kUnit);
  rates.shared_forward = rates.shared_backward = slack;
  rates.turning = turning;
  rates.facing = turn.transpose() * m;
  if (motion.kind() == MotionKind::screw) {
    // The screw's translation across its axis, R0 Q(t) v_perp, moves the whole body along
    // `towards` at (Q(t)^T m) . v_perp, which changes at most at |w x Q^T m| |v_perp| = |u|
    // |v_perp| (v_perp is across w); Q(t)^T m is within some 300 roundoffs of |R0| of the exact.
    const Vector3 axis = motion.rotation_vector() / motion.angle();
    const Vector3& v = motion.twist_translation();
    const Vector3 across = v - axis.dot(v) * axis;
    // A length: its squares vanish below 1e-162 (a screw of that size then lost its slide's
    // growth, and its time of impact was certified past the contact) and overflow above 1e154.
    const Scalar across_length = robust_length(across);
    const Scalar slide = (turn.transpose() * m).dot(across);
    const Scalar slide_slack =
        kUnit * across_length * (512 * motion.start_rotation_norm() + 4 * std::abs(slide));
    rates.forward += slide + slide_slack;
    rates.backward += slide_slack - slide;
    rates.shared_forward += slide + slide_slack;
    rates.shared_backward += slide_slack - slide;
    rates.growth += u.norm() * across_length * (1 + 16 * kUnit);
  }
  return rates;
}

Scalar MotionBound::second_order_reach(Scalar rate, Scalar growth, Scalar apart) {
  // The first time h with rate h + growth h^2 / 2 = apart, in the form without cancellation for
  // the sign of the rate; hypot keeps the squares of tiny or huge bodies' rates in range, and
  // where a term still leaves the double range there is no second-order reach.
  const Scalar root = std::hypot(rate, std::sqrt(2 * growth) * std::sqrt(apart));
  if (!std::isfinite(root)) return 0;
  Scalar reach = std::numeric_limits<Scalar>::infinity();
  if (rate > 0) {
    reach = apart / ((rate + root) / 2);
  } else if (growth > 0) {
    reach = root / growth - rate / growth;
  }
  return reach * (1 - 16 * kUnit);
}

MotionBound::Reaches MotionBound::reaches_along(const ConvexPolyhedron& a,
                                                const ConvexPolyhedron& b, Scalar t,
                                                const Vector3& n, Scalar apart) const {
  const TurnRates turn_a = turn_rates(*motion_a_, a, reach_a_, t, n);
  const TurnRates turn_b = turn_rates(*motion_b_, b, reach_b_, t, -n);
  const Scalar growth = (turn_a.growth + turn_b.growth) * (1 + 4 * kUnit);
  const auto shared = [&](Scalar sense, Scalar shared_a, Scalar shared_b) {
    const Scalar translation = sense * n.dot(closing_);
    return translation + shared_a + shared_b +
           16 * kUnit * (std::abs(translation) + std::abs(shared_a) + std::abs(shared_b)) + slack_;
  };
  const auto reach = [&](Scalar sense, Scalar rate_a, Scalar rate_b) {
    const Scalar translation = sense * n.dot(closing_);
    const Scalar rate =
        translation + rate_a + rate_b +
        16 * kUnit * (std::abs(translation) + std::abs(rate_a) + std::abs(rate_b)) + slack_;
    return std::max(reach_over(apart, along(n, sense)), second_order_reach(rate, growth, apart));
  };
  const Reaches known = {reach(1, turn_a.forward, turn_b.forward),
                         reach(-1, turn_a.backward, turn_b.backward)};
  const Reaches depth = depth_reaches(a, turn_a, b, turn_b,
                                      shared(1, turn_a.shared_forward, turn_b.shared_forward),
                                      shared(-1, turn_a.shared_backward, turn_b.shared_backward),
                                      growth, apart, known);
  return {std::max(known.forward, depth.forward), std::max(known.backward, depth.backward)};
}

MotionBound::Reaches MotionBound::depth_reaches(const ConvexPolyhedron& a, const TurnRates& turn_a,
                                                const ConvexPolyhedron& b, const TurnRates& turn_b,
                                                Scalar shared_forward, Scalar shared_backward,
                                                Scalar growth, Scalar apart,
                                                const Reaches& known) const {
  // Without a turn every point of a body moves alike: G is the second-order model already taken.
  if (!PointLines::fits(a) || !PointLines::fits(b) ||
      (turn_a.turning.isZero() && turn_b.turning.isZero())) {
    return {0, 0};
  }
  // The computed depths exceed the exact ones by at most the error of two heights each: the
  // facing direction is within some 300 roundoffs of |R0| of the exact one (as turn_rates'
  // directions are), and a height within a few roundoffs of the body's size. G is taken that much
  // higher at every time, 0 included.
  const auto depth_error = [](const RigidMotion& motion, const ConvexPolyhedron& body) {
    // An overflow to infinity only drops the bound (below).
    const Scalar size = robust_length(body.bounds().centre) + body.bounds().radius;
    return 2 * kUnit * size * (512 * motion.start_rotation_norm() + 16);
  };
  const Scalar offset = depth_error(*motion_a_, a) + depth_error(*motion_b_, b);
  if (!(offset < apart)) return {0, 0};
  const PointLines lines_a(a, turn_a.turning, turn_a.facing);
  const PointLines lines_b(b, turn_b.turning, turn_b.facing);
  const auto reach = [&](Scalar sense, Scalar shared, Scalar longest) -> Scalar {
    // The time to evaluate G at: where the support points' own second-order model closes the
    // gap (any time would be proven; this one is G's root while no other point overtakes them).
    const Scalar top_a = lines_a.top_rate(sense);
    const Scalar top_b = lines_b.top_rate(sense);
    const Scalar top = shared + top_a + top_b +
                       4 * kUnit * (std::abs(shared) + std::abs(top_a) + std::abs(top_b));
    const Scalar h = second_order_reach(top, growth, apart - offset);
    // G is proven no farther than h: not evaluated where the reach known already gets there.
    if (!(h > longest) || !std::isfinite(h)) return 0;
    // G at a time, rounded up: each term of the sum is within a few roundoffs of its size, the
    // sum within some of theirs.
    const auto closing = [&](Scalar at) {
      Scalar size_a = 0;
      Scalar size_b = 0;
      const Scalar turned = growth * at * at / 2;
      const Scalar closed = offset + shared * at + lines_a.at(at, sense, size_a) +
                            lines_b.at(at, sense, size_b) + turned;
      return closed + 16 * kUnit * (offset + std::abs(shared) * at + size_a + size_b + turned);
    };
    constexpr Scalar kDown = 1 - 16 * kUnit;
    const Scalar far = closing(h);
    if (far <= apart) return h * kDown;
    // The chord from (0, offset) to (h, far) lies above G: the gap is open until it reaches
    // apart.
    Scalar near = h * ((apart - offset) / (far - offset)) * kDown;
    for (int k = 0; k < kDepthRefinements; ++k) {
      // The chord from (near, G(near)) to (h, far) lies above G in between (regula falsi from
      // below, each step proven).
      const Scalar at_near = closing(near);
      if (!(at_near < apart)) break;
      const Scalar next = (near + (h - near) * ((apart - at_near) / (far - at_near))) * kDown;
      if (!(next > near)) break;
      near = next;
    }
    return near;
  };
  return {reach(1, shared_forward, known.forward), reach(-1, shared_backward, known.backward)};
}

Scalar MotionBound::along(const Vector3& n, Scalar sense) const {
  const Scalar translation = std::max<Scalar>(0, sense * n.dot(closing_));
  const auto turn = [&n](const RigidMotion& motion, Scalar reach, Scalar across) {
    if (motion.angle() == 0) return Scalar{0};
    const Vector3 local = motion.start().rotation.transpose() * n;
    const Scalar rotation = local.cross(motion.rotation_vector()).norm() * reach;
    if (across == 0) return rotation;
    return rotation + local.cross(motion.rotation_vector()).norm() / motion.angle() * across;
  };
  const Scalar rate = translation + turn(*motion_a_, reach_a_, across_a_) +
                      turn(*motion_b_, reach_b_, across_b_);
  return rate * (1 + 16 * kUnit) + slack_;
}

}  // namespace swarmcollide::detail
