// Nesterov's momentum for the directions of Wolfe's search on polytope pairs; private to the
// library's sources.
#pragma once

#include <cmath>

#include "whole_search.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

/// Where DistanceFinish::whole's search asks its oracle points: not along the corral's point x
/// but along Nesterov's momentum, coal's for polytopes (GJKVariant::NesterovAcceleration with its
/// normalised directions, after Montaut, Le Lidec, Petrik, Sivic and Carpentier, "Collision
/// Detection Accelerated: An Optimization Perspective", RSS 2022): the k-th direction after the
/// first is delta d/|d| + (1 - delta) y/|y|, d the last direction, y = delta x + (1 - delta) w,
/// w the last point kept and delta = (k + 2) / (k + 3). Wolfe's steps are Frank-Wolfe steps on
/// |x|^2; the momentum carries the search across the zigzag between faces that makes polytope
/// pairs near contact take 6 to 9 oracle points (coal's accelerated GJK from the box centres'
/// direction took 3 to 5 on the same pairs, narrowphase_coal.cpp).
///
/// Any direction's support point is a point of B - A, and its separation along that direction a
/// lower bound on the distance, so the bounds stay proven whatever was asked: `measured` gives
/// the separation along the direction the point was asked for. Wolfe's own tests read the new
/// point along x (its gap, a point already in the corral, progress): a point asked with momentum
/// is kept only where it lies nearer than the corral along x by more than those tests' rounding,
/// so that it joins the corral and x moves nearer; otherwise the point along x is asked as well,
/// and from then on every point, as coal turns the momentum off when it stops helping.
class NesterovDirection {
 public:
  /// A search from the unit direction `start` whose first point, asked along it, is `first`, or
  /// (null) the first it asks.
  NesterovDirection(const Vector3& start, const OraclePoint* first)
      : last_(first != nullptr ? first->p : Vector3::Zero()),
        asked_(start),
        steps_(first != nullptr ? 1 : 0),
        on_(first == nullptr || !mostly_along_start(start, *first)) {}

  /// Whether the search's first point `first`, asked along the unit direction `start`, lies
  /// mostly along it (|start . first| more than half its norm): the bodies are then far apart or
  /// deep in each other, where Wolfe's steps along x reach the answer in a few points and the
  /// momentum's turned directions made them more (narrowphase_coal.cpp's pairs apart by 1,
  /// 32 points: 4.0 -> 4.3 oracle calls a distance, 512 points 4.65 -> 5.1; overlapping by 0.2,
  /// 64 points: 4.1 -> 4.85); such pairs' searches run without it. Pairs near contact, whose
  /// first point lies across the start, keep it (512 points apart by 1e-2: 11.2 oracle calls a
  /// distance without momentum, 8.1 with).
  static bool mostly_along_start(const Vector3& start, const OraclePoint& first) {
    const Scalar along = start.dot(first.p);
    return 4 * along * along > first.p.squaredNorm();
  }

  /// The point `support` gives for the corral's point `x`: asked along direction(x), and along x
  /// as well where the momentum's point is not kept (which turns the momentum off).
  template <typename Support>
  __attribute__((always_inline)) OraclePoint ask(const Vector3& x, Support& support) {
    for (;;) {
      const OraclePoint q = support(direction(x));
      if (keep(x, q)) return q;
    }
  }

  /// The separation of the kept point `q` along the direction it was asked for, which the
  /// corral's point `x` of norm 1 / `inverse_x` gave.
  Separation measured(const MinNormPoint& current, const OraclePoint& q, Scalar inverse_x) const {
    if (extrapolated_) return Separation{asked_.dot(q.p) * inverse_norm_, asked_ * inverse_norm_};
    return Separation{current.x.dot(q.p) * inverse_x, current.x * inverse_x};
  }

 private:
  /// The direction to ask for the corral's point `x`: x itself once the momentum ended, else
  /// coal's for polytopes, normalised, the last direction's unit vector weighted by delta and the
  /// unit vector of y = delta x + (1 - delta) w by 1 - delta.
  const Vector3& direction(const Vector3& x) {
    extrapolated_ = false;
    if (!on_ || steps_ == 0) return x;
    const Scalar delta = Scalar(steps_ + 2) / Scalar(steps_ + 3);
    const Vector3 y = delta * x + (1 - delta) * last_;
    // The last direction's unit vector: the start is one; an extrapolated direction's inverse
    // norm was taken for its separation.
    const Scalar unit = steps_ == 1 ? Scalar(1) : inverse_norm_;
    asked_ = (delta * unit) * asked_ + ((1 - delta) / y.norm()) * y;
    inverse_norm_ = 1 / asked_.norm();
    // Degenerate directions (y or the sum zero) end the momentum.
    if (!std::isfinite(inverse_norm_) || !asked_.allFinite()) {
      on_ = false;
      return x;
    }
    extrapolated_ = true;
    return asked_;
  }

  /// Whether the point `q`, asked along direction(x), is kept: it is if it was asked along x,
  /// or lies nearer than the corral along x by more than 1e-13 |x| (see the class; Wolfe's gap
  /// test stops at 2e-14 |x|), compared squared. A point that is not turns the momentum off, and
  /// ask() asks again, along x.
  bool keep(const Vector3& x, const OraclePoint& q) {
    if (!on_) return true;
    if (!extrapolated_) {
      // The first point, asked along the start (x).
      steps_ = 1;
      last_ = q.p;
      on_ = !mostly_along_start(x, q);
      return true;
    }
    const Scalar along = x.dot(q.p);
    if (!nearer_than_corral(x, along)) {
      on_ = false;
      return false;
    }
    ++steps_;
    last_ = q.p;
    // A kept point short of the origin's plane across x (x . q > 0) ends the momentum: the search
    // is then near its end, where the momentum's directions, turned from x, would ask their
    // last point in vain (narrowphase_coal.cpp's pairs, 64 points apart by 1e-2: 7.05 oracle
    // calls a distance with the momentum on until a point is refused, 6.75 ending it here).
    if (along > 0) on_ = false;
    return true;
  }

  // The last point kept.
  Vector3 last_;
  // The last direction the momentum asked (at first the start), and the inverse of its norm.
  Vector3 asked_;
  Scalar inverse_norm_ = 0;
  // Points kept so far, the first included.
  int steps_;
  bool on_;
  bool extrapolated_ = false;
};

/// NesterovDirection's interface without momentum: every point asked along the corral's point x
/// and measured along it, for the pairs that ask none with momentum (distance_finish.cpp's
/// kMomentumSize), whose search then compiles as it did without momentum.
struct AlongCorral {
  template <typename Support>
  __attribute__((always_inline)) OraclePoint ask(const Vector3& x, Support& support) const {
    return support(x);
  }
  Separation measured(const MinNormPoint& current, const OraclePoint& q, Scalar inverse_x) const {
    return Separation{current.x.dot(q.p) * inverse_x, current.x * inverse_x};
  }
};

}  // namespace swarmcollide::detail
