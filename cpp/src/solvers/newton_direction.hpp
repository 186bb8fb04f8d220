// Newton's steps on the separating direction for the Wolfe searches of curved pairs; private to
// the library's sources.
#pragma once

#include <cmath>

#include "../geometry/framed_curved_support.hpp"
#include "whole_search.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

/// Where a curved pair's Wolfe search asks its oracle points once the bodies' nearest points lie
/// on smooth parts of their surfaces (a rim, an ellipsoid, a vertex beside them): not along the
/// corral's point x but along Newton's step on the separation. The distance is the largest
/// separation phi(n) = min over B - A of n . p over unit n; its gradient at n is the support point
/// p(n), and its Hessian in the plane across n is -(K + phi P), K the derivative of p(n) (the
/// bodies' curvatures at their support points, FramedBody::add_support_curvature) and P the
/// projection across n. Newton's step t = (P K P + phi I)^-1 P p then turns n towards the optimum
/// quadratically, where Wolfe's corrals close a rim against a rim by a factor of about 4 a step.
/// It is solved as a 2 x 2 system on the unit vectors across n (K's quadratic form on them), in
/// place of session 42's 3 x 3 matrices and their Cholesky factor: cone-ellipsoid pairs, which
/// have no crease below, took 6% fewer instructions for it alone.
///
/// A cylinder's support point jumps from one rim to the other as the direction crosses the
/// normals to its axis, so where the nearest point lies on its mantle, phi has a crease there and
/// the support points' own gaps stay large. Once the directions asked have crossed the normals
/// (`Mantle`) and lie within about 6 degrees of them, the step is taken on the crease: from n
/// moved onto it, along the one direction e = axis x n that stays on it, where phi is smooth
/// (the rim's curvature, either rim's). Where both cylinders' mantles hold the nearest points,
/// the direction normal to both axes is the optimum itself. On a crease either rim's point is a
/// support point, and Wolfe's corral needs both: each direction is tilted towards x's rim by a
/// thousandth of the tolerance, so that the rim asked is the one x would rather have.
///
/// Any direction's support point is a point of B - A and its separation along the direction a
/// lower bound, so the bounds stay proven whatever is asked (`measured`). As NesterovDirection,
/// a point asked along Newton's direction is kept only where it lies nearer than the corral along
/// x by more than Wolfe's tests' rounding; otherwise the point along x is asked as well, and the
/// steps end for the search.
///
/// Pairs with an ellipsoid, and two cylinders, search this way (curved_search.cpp), measured with
/// `bench/callgrind_query.py --curved --pairs 100 --repeats 1`, instructions per signed distance
/// apart (session 43, before -> after the creases and the 2 x 2 system): cylinder-cylinder 16,157
/// -> 14,374, cylinder-ellipsoid 16,514 -> 15,153, cone-ellipsoid 16,977 -> 15,936,
/// ellipsoid-box 17,269 -> 17,014. A cylinder beside a cone or a box lost with the steps (a
/// C++ probe of 300 random pairs apart: cylinder-cone 18,290 -> 19,564, cylinder-box 14,877 ->
/// 16,096 instructions, evaluations 17.4 -> 15.7 and 14.8 -> 14.2): the cone's crease (apex
/// against rim) and the box's edges are not modelled, their nearest points seldom start the
/// steps, and the tests of every step cost more than the steps save. Session 42: a start at a
/// gap of 1e-2 or 1e-3 of the separation (kStart) gave cone-ellipsoid 15,724 and 16,868 where
/// 1e-1 gave 15,660 (20 pairs).
class NewtonDirection {
 public:
  explicit NewtonDirection(const FramedPair& pair)
      : pair_(pair),
        mantle_a_(pair.a),
        mantle_b_(pair.b),
        mantles_(pair.a.curved_kind() == CurvedKind::cylinder ||
                 pair.b.curved_kind() == CurvedKind::cylinder),
        tilt_(1e-3 * pair.tolerance) {}

  /// The point `support` gives for the corral's point `x`: asked along direction(x), and along x
  /// as well where Newton's point is not kept (which ends the steps).
  template <typename Support>
  __attribute__((always_inline)) OraclePoint ask(const Vector3& x, Support& support) {
    for (;;) {
      const Vector3& d = direction(x);
      const OraclePoint q = support(d);
      if (keep(x, q)) {
        last_ = d;
        last_point_ = q.p;
        return q;
      }
    }
  }

  /// The separation of the kept point `q` along the direction it was asked for: Newton's unit
  /// direction, or the corral's point `x` of norm 1 / `inverse_x`.
  Separation measured(const MinNormPoint& current, const OraclePoint& q, Scalar inverse_x) const {
    if (extrapolated_) return Separation{asked_.dot(q.p), asked_};
    return Separation{current.x.dot(q.p) * inverse_x, current.x * inverse_x};
  }

 private:
  // The direction to ask for the corral's point `x`: Newton's from the last direction asked and
  // its point where that point's own gap |p| - n . p is within kStart of its separation n . p
  // (the supports then lie on the smooth parts that the nearest points will), else x.
  const Vector3& direction(const Vector3& x) {
    extrapolated_ = false;
    if (!on_ || !asked_once_) {
      asked_once_ = true;
      return x;
    }
    const Scalar along = last_.dot(last_point_);
    if (!(along > 0)) return x;
    const Scalar squared_length = last_.squaredNorm();
    if (mantles_) {
      const bool on_a = mantle_a_.active(last_, squared_length);
      const bool on_b = mantle_b_.active(last_, squared_length);
      if (on_a && on_b) return across_mantles(x);
      if (on_a || on_b) {
        return along_mantle(last_ / std::sqrt(squared_length),
                            on_a ? mantle_a_.axis() : mantle_b_.axis(), x);
      }
    }
    const Scalar threshold = (1 + kStart) * along;
    if (!(last_point_.squaredNorm() * squared_length <= threshold * threshold)) return x;
    const Vector3 n = last_ / std::sqrt(squared_length);
    const Scalar phi = n.dot(last_point_);
    // In the plane across n, on the unit vectors u along the gradient P p and v = n x u, Newton's
    // step solves the 2 x 2 system (K + phi I) (a, b) = (|P p|, 0).
    const Vector3 gradient = last_point_ - phi * n;
    const Scalar slope = gradient.norm();
    if (!(slope > 0)) return x;
    const Vector3 u = gradient / slope;
    const Vector3 v = n.cross(u);
    Vector3 form = Vector3::Zero();
    if (!pair_.a.add_support_curvature(n, u, v, form) ||
        !pair_.b.add_support_curvature(-n, u, v, form)) {
      on_ = false;
      return x;
    }
    const Scalar uu = form(0) + phi;
    const Scalar vv = form(2) + phi;
    const Scalar determinant = uu * vv - form(1) * form(1);
    if (!(determinant > 0)) return x;
    const Vector3 step = (slope / determinant) * (vv * u - form(1) * v);
    const Vector3 turned = n + step;
    const Scalar length = turned.norm();
    const bool short_step = step.squaredNorm() < kLargestStep * kLargestStep;
    if (!(length > 0) || !std::isfinite(length) || !short_step) return x;
    asked_ = turned / length;
    extrapolated_ = true;
    return asked_;
  }

  // Both bodies' nearest points on their mantles: the direction is normal to both axes, fixed.
  const Vector3& across_mantles(const Vector3& x) {
    const Vector3 normal = mantle_a_.axis().cross(mantle_b_.axis());
    const Scalar length = normal.norm();
    if (!(length > 0x1p-20)) return along_mantle(last_.normalized(), mantle_a_.axis(), x);
    return ask_tilted(normal.dot(last_) < 0 ? Vector3(-normal / length) : Vector3(normal / length),
                      x);
  }

  // One body's nearest point on its mantle (axis `axis`): the direction lies normal to the axis,
  // where the separation is smooth along the great circle across it; Newton's step along that
  // circle, from n moved onto it.
  const Vector3& along_mantle(const Vector3& n, const Vector3& axis, const Vector3& x) {
    const Vector3 onto = n - n.dot(axis) * axis;
    const Scalar onto_length = onto.norm();
    if (!(onto_length > 0)) return x;
    const Vector3 m = onto / onto_length;
    const Vector3 e = axis.cross(m);
    Vector3 form = Vector3::Zero();
    if (!pair_.a.add_support_curvature(m, e, e, form) ||
        !pair_.b.add_support_curvature(-m, e, e, form)) {
      on_ = false;
      return x;
    }
    // The support point at n stands for the one at m: the mantle's rims differ only along the
    // axis, which m and e are normal to, and n lies on the mantle after the first step.
    const Scalar phi = m.dot(last_point_);
    const Scalar slope = e.dot(last_point_);
    const Scalar curvature = form(0) + phi;
    if (!(phi > 0) || !(slope * slope <= (2 + kStart) * kStart * phi * phi) ||
        !(curvature > 0)) {
      return x;
    }
    const Scalar step = slope / curvature;
    if (!(std::abs(step) < kLargestStep)) return x;
    return ask_tilted((m + step * e).normalized(), x);
  }

  // `direction`, tilted a hair towards x along each mantle's axis: on a mantle the support point
  // may lie on either rim, and the one x would rather have is asked (the rim below x along x).
  const Vector3& ask_tilted(const Vector3& direction, const Vector3& x) {
    Vector3 tilted = direction;
    if (mantle_a_.on()) tilted += std::copysign(tilt_, x.dot(mantle_a_.axis())) * mantle_a_.axis();
    if (mantle_b_.on()) tilted += std::copysign(tilt_, x.dot(mantle_b_.axis())) * mantle_b_.axis();
    const Scalar length = tilted.norm();
    if (!(length > 0) || !std::isfinite(length)) return x;
    asked_ = tilted / length;
    extrapolated_ = true;
    return asked_;
  }

  // Whether the point `q`, asked along direction(x), is kept (nearer_than_corral);
  // a point refused ends the steps, and ask() asks again along x.
  bool keep(const Vector3& x, const OraclePoint& q) {
    if (!extrapolated_ || nearer_than_corral(x, x.dot(q.p))) return true;
    on_ = false;
    return false;
  }

  // A support point's gap |p| - n . p within this of its separation n . p starts the steps;
  // steps longer than kLargestStep (about half a radian) are not asked.
  static constexpr Scalar kStart = 1e-1;
  static constexpr Scalar kLargestStep = 0.5;

  // A cylinder's mantle: its axis in the frame, and whether the search's directions have
  // crossed the directions normal to it (its support point moved from one rim to the other),
  // which puts the nearest point on the mantle.
  class Mantle {
   public:
    explicit Mantle(const FramedBody& body)
        : axis_(body.curved_kind() != CurvedKind::cylinder ? Vector3::Zero()
                : body.rotated()                          ? Vector3(body.rotation().col(2))
                                                          : Vector3::UnitZ()) {}
    // Whether the nearest point is taken on the mantle, from the last direction asked, d (of
    // squared length `squared_length`): the directions asked have crossed the normals to the
    // axis (between two asks, the body's support moved from one rim to the other), and d lies
    // within about 6 degrees of them. Called once for every direction asked after the first.
    bool active(const Vector3& d, Scalar squared_length) {
      const Scalar height = axis_.dot(d);
      if (height * previous_height_ < 0) crossed_ = true;
      previous_height_ = height;
      on_ = crossed_ && height * height < 0.01 * squared_length;
      return on_;
    }
    bool on() const { return on_; }
    const Vector3& axis() const { return axis_; }

   private:
    Vector3 axis_;
    Scalar previous_height_ = 0;
    bool crossed_ = false;
    bool on_ = false;
  };

  const FramedPair& pair_;
  Mantle mantle_a_;
  Mantle mantle_b_;
  // Whether either body is a cylinder (else the mantles are not tracked).
  bool mantles_;
  // How far a direction on a mantle is tilted towards x's rim: a thousandth of the tolerance,
  // which the separation loses at most twice over (the frame's points lie in the unit ball).
  Scalar tilt_;
  // The last direction asked and its point, from which the next step starts.
  Vector3 last_ = Vector3::Zero();
  Vector3 last_point_ = Vector3::Zero();
  // Newton's last direction (unit).
  Vector3 asked_ = Vector3::Zero();
  // Whether the first point (along the start) was asked, the steps are still on, and the point
  // just asked was asked along asked_.
  bool asked_once_ = false;
  bool on_ = true;
  bool extrapolated_ = false;
};

}  // namespace swarmcollide::detail
