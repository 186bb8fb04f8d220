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
/// bodies' curvatures at their support points, FramedBody::add_support_derivative) and P the
/// projection across n. Newton's step t = (P K P + phi I)^-1 P p then turns n towards the optimum
/// quadratically, where Wolfe's corrals close a rim against a rim by a factor of about 4 a step.
///
/// Any direction's support point is a point of B - A and its separation along the direction a
/// lower bound, so the bounds stay proven whatever is asked (`measured`). As NesterovDirection,
/// a point asked along Newton's direction is kept only where it lies nearer than the corral along
/// x by more than Wolfe's tests' rounding; otherwise the point along x is asked as well, and the
/// steps end for the search.
///
/// Only pairs with an ellipsoid search this way (curved_search.cpp), measured with
/// `bench/callgrind_query.py --curved --pairs 20 --repeats 1`, instructions per signed distance
/// apart: cone-ellipsoid 17,537 -> 15,660, cylinder-ellipsoid 20,726 -> 18,893, ellipsoid-box
/// 16,115 -> 16,019. Cylinders and cones among themselves lost (cylinder-cylinder 17,301 ->
/// 18,107, cone-cone 12,946 -> 13,975): their nearest points mostly lie on a mantle, whose
/// support point jumps between the two rims as the direction crosses the normal to the axis, so
/// a support point's own gap stays large there and the test and bookkeeping of every step cost
/// more than the few rim-against-rim pairs saved; skipping a step whose direction would switch
/// rims saved no more. A start at a gap of 1e-2 or 1e-3 of the separation (kStart) gave
/// cone-ellipsoid 15,724 and 16,868.
class NewtonDirection {
 public:
  explicit NewtonDirection(const FramedPair& pair) : pair_(pair) {}

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
    const Scalar threshold = (1 + kStart) * along;
    if (!(last_point_.squaredNorm() * last_.squaredNorm() <= threshold * threshold)) return x;
    const Vector3 n = last_.normalized();
    const Scalar phi = n.dot(last_point_);
    Matrix3 k = Matrix3::Zero();
    if (!pair_.a.add_support_derivative(n, k) || !pair_.b.add_support_derivative(-n, k)) {
      on_ = false;
      return x;
    }
    const Matrix3 across = Matrix3::Identity() - n * n.transpose();
    Matrix3 m = across * k * across;
    m.diagonal().array() += phi;
    const Vector3 step = m.llt().solve(last_point_ - phi * n);
    const Vector3 turned = n + step;
    const Scalar length = turned.norm();
    const bool short_step = step.squaredNorm() < kLargestStep * kLargestStep;
    if (!(length > 0) || !std::isfinite(length) || !short_step) return x;
    asked_ = turned / length;
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

  const FramedPair& pair_;
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
