// How fast two moving bodies can close the gap between them; private to the library's sources.
#pragma once

#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/motion/rigid_motion.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// A bound on `|x|` over every point x of the body's core in its own frame (the points' hull, or
/// the curved shape), rounded up. A rounded body's ball turns into itself, so the rounded body
/// moves no farther than its core: the rounding radius is not part of the reach.
Scalar motion_reach(const ConvexPolyhedron& body);
/// The largest reach of the parts.
Scalar motion_reach(const CompoundBody& body);

/// A bound on the distance of every point of the body's core (in its own frame) from the line
/// through its origin along `axis` (any length; the zero vector: `motion_reach`): a turn about
/// that axis moves a point by its angle times this distance at most, which is less than the
/// reach for every body not flat across the axis.
Scalar motion_reach_across(const ConvexPolyhedron& body, const Vector3& axis);
/// The largest of the parts'.
Scalar motion_reach_across(const CompoundBody& body, const Vector3& axis);

/// Bounds on how fast the distance between A moving by `motion_a` and B moving by `motion_b`
/// can shrink, per unit of time, for bodies whose points lie within `reach_a` and `reach_b` of
/// the axes their motions turn about (motion_reach_across; a screw's axis is its rotation's).
///
/// A point x of A is at R0 Q(t) x + T(t), Q(t) = exp(t [w]) a rotation. Over a time h it moves
/// by at most |T1 - T0| h from the translation and, since Q(t + h) - Q(t) = Q(t) (exp(h [w]) - I)
/// and a chord is shorter than its arc, by at most |R0| |w| h |x_perp| from the rotation, x_perp
/// the part of x across w (its distance from the axis), at most `reach_a`
/// (motion_reach_across of A about w). The distance is unchanged by a common translation, so only the relative translation
/// counts: it shrinks by at most `full * h`. Along a fixed unit direction n, the separation
/// `min_B n.y - max_A n.x` changes by the translation's component along n and by the rotation's
/// rate, n . R0 (w x Q x) = (R0^T n) . (w x Q x) = (Q x) . ((R0^T n) x w) <= |(R0^T n) x w|
/// |x_perp| (the vector (R0^T n) x w is across w, and Q, a turn about w, keeps the length of
/// the part of x across it), which vanishes for a turn about n: `forward_along(n)` bounds how fast it shrinks forwards in time,
/// `backward_along(n)` backwards.
///
/// A screw motion G(t) = G0 exp(t xi), xi = (w, v), moves a point x of the body at
/// R(t) (v + w x x), R(t) = R0 Q(t). Split v = v_par + v_perp along and across the unit axis k
/// of w. Q(t) turns about k, so R(t) v_par = R0 v_par is a constant world velocity, which
/// replaces T1 - T0 in the relative translation (a common one still cancels); the rest, R(t)
/// v_perp, turns with the body and is at most |R0| |v_perp| long. So the distance shrinks by
/// at most |s_a - s_b| + sum |R0| (|v_perp| + |w| reach) per unit time (s = R0 v_par). Along n,
/// with m = R0^T n: n . R(t) v_perp = (Q^T m) . v_perp <= |(Q^T m)_perp| |v_perp| = |m x k|
/// |v_perp| (Q^T keeps m's component along k, hence the length of the rest), and the rotation's
/// term is bounded as for a linear motion, |(Q^T m) x w| |x| = |m x w| |x|. Both vanish for a
/// screw about n itself, whose translation along n is then all of n . s.
///
/// Second order (`reaches_along`): the rate above takes the largest speed of any point across the
/// axis, yet at time t the rotation moves the body's points along n at (Q x) . u, u = m x w,
/// whose largest value over the core is its support value h(Q(t)^T u), often far below |u|
/// reach, and at a grazing pass near zero. That rate changes as the body turns: Q(s)^T u turns
/// about w at |w| (u is across w), by at most |w| |u| |s - t| over the time from t, and a support
/// value changes by at most the distance of the core from the axis times the change of a
/// direction across it. So over a time h from t the separation shrinks by at most a h + k h^2 / 2,
/// a the rate at t (the translation's component along n and the supports of both bodies;
/// negative where the bodies draw apart) and k the sum of |w| |u| reach over the bodies. A screw
/// adds its translation across the axis at t, (Q(t)^T m) . v_perp, to a, and |u| |v_perp|, how
/// fast that turning velocity can change along n, to k.
///
/// Near contact that rate is still the fastest point's, while the separation closes at the rate
/// of the points on the support planes: advancement then closes the gap by a constant fraction a
/// step (14 queries a touching turning motion against 3 a translating one, bench/motion.py). Point
/// by point (`depth_reaches`, polyhedra whose supports are scans): a point x of A that lies
/// `depth_x` below A's support plane along n at t, moving along n at `rate_x`, is at most
/// rate_x h + k_A h^2 / 2 - depth_x above that plane after a time h; so the separation shrinks by
/// at most G(h) = a' h + max_x (rate_x h - depth_x) + max_y (rate_y h - depth_y) + k h^2 / 2 (a'
/// the rates every point of a body shares: the translation, a screw's slide), a convex function
/// of h with G(0) = 0 whose slope at 0 is the support points' rate. G at one time h_c proves the
/// gap open until h_c apart / G(h_c) (the chord from 0 lies above a convex function), and h_c,
/// the root of the support points' second-order model, makes that the root of G itself wherever
/// no other point overtakes the support points before it: near contact the steps then close the
/// gap as fast as Newton's would.
class MotionBound {
 public:
  MotionBound(const RigidMotion& motion_a, Scalar reach_a, const RigidMotion& motion_b,
              Scalar reach_b);

  /// A bound on how fast the distance can shrink, forwards or backwards in time.
  Scalar full() const { return full_; }
  /// A bound on how fast the separation along unit `n` (from A towards B) can shrink going
  /// forwards in time, and going backwards.
  Scalar forward_along(const Vector3& n) const { return along(n, 1); }
  Scalar backward_along(const Vector3& n) const { return along(n, -1); }

  /// How long a gap `apart` along unit `n` (from A towards B) at time `t` lasts at least, going
  /// forwards and going backwards, where `a` and `b` are the convex bodies the motions move: the
  /// larger of the first-order reach (`apart` over forward_along or backward_along) and the
  /// second-order one (see above), rounded down; infinite where the gap cannot close.
  struct Reaches {
    Scalar forward;
    Scalar backward;
  };
  Reaches reaches_along(const ConvexPolyhedron& a, const ConvexPolyhedron& b, Scalar t,
                        const Vector3& n, Scalar apart) const;

 private:
  // How fast, at time t, the turn of `motion` (with a screw's translation across its axis, which
  // turns with the body) moves the body's core along unit `towards` going forwards and going
  // backwards in time (its support values along the turning direction and its opposite), and how
  // fast those rates can grow per unit of time from t; rounded up.
  // `reach` is the body's motion_reach_across about the motion's axis.
  // `shared_forward` and `shared_backward` are the parts of the rates every point of the core
  // shares (a screw's slide and the roundings); `turning` is Q(t)^T u, along which a point x of
  // the core moves along `towards` at x . turning, and `facing` is `towards` in the body's frame
  // at t, Q(t)^T m (both zero for a motion that does not turn).
  struct TurnRates {
    Scalar forward = 0;
    Scalar backward = 0;
    Scalar growth = 0;
    Scalar shared_forward = 0;
    Scalar shared_backward = 0;
    Vector3 turning = Vector3::Zero();
    Vector3 facing = Vector3::Zero();
  };
  static TurnRates turn_rates(const RigidMotion& motion, const ConvexPolyhedron& body,
                              Scalar reach, Scalar t, const Vector3& towards);
  // The times a gap `apart` lasts at least from the points' own rates and depths (see above),
  // forwards and backwards, where `shared_forward` and `shared_backward` are the rates that every
  // point of both bodies shares (the relative translation along n, the slides, the roundings)
  // and `growth` k; 0 where the bodies are not both polyhedra whose supports are scans, where
  // neither turns, or where they cannot be longer than the `known` reaches. Rounded down.
  Reaches depth_reaches(const ConvexPolyhedron& a, const TurnRates& turn_a,
                        const ConvexPolyhedron& b, const TurnRates& turn_b, Scalar shared_forward,
                        Scalar shared_backward, Scalar growth, Scalar apart,
                        const Reaches& known) const;
  // The first time at which a gap `apart` closing at `rate` (negative: opening), growing by
  // `growth` per unit of time, can be gone; rounded down.
  static Scalar second_order_reach(Scalar rate, Scalar growth, Scalar apart);
  Scalar along(const Vector3& n, Scalar sense) const;
  // The motion's constant world translation per unit time: T1 - T0 for a linear motion, R0
  // v_par for a screw; `across` is set to the screw's |v_perp| (0 for a linear motion).
  static Vector3 translation_along_axis(const RigidMotion& motion, Scalar& across);

  const RigidMotion* motion_a_;
  const RigidMotion* motion_b_;
  Scalar reach_a_;
  Scalar reach_b_;
  // The relative translation per unit time, A's less B's (for screw motions, of the parts along
  // their axes).
  Vector3 closing_;
  // Per body, the screw translation across its axis, |v_perp| (zero for linear motions).
  Scalar across_a_ = 0;
  Scalar across_b_ = 0;
  // The rounding of the directional rates' terms, absolute.
  Scalar slack_;
  Scalar full_;
};

}  // namespace swarmcollide::detail
