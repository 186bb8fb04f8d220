// Wolfe's search on the whole Minkowski difference with its bounds and stop test, shared by
// DistanceFinish::whole and its secant variant (secant_search.cpp); private to the library.
#pragma once

#include <algorithm>

#include "../detail/flatten.hpp"
#include "../queries/verdict.hpp"
#include "best_bounds.hpp"
#include "minkowski.hpp"
#include "witness.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

/// Directions closer than this cosine (about 25 degrees) are nearby: a search's climb for one
/// starts from the support of the other (coal's threshold too).
inline constexpr Scalar kNearbyCosine = 0.9;

/// A climbing search's step to direction `d` from `previous`: where the direction turned by more
/// than kNearbyCosine allows, the climbs start afresh (the hints dropped), as the hull's starts
/// are then nearer; `previous` becomes `d`.
[[gnu::always_inline]] inline void drop_hints_after_turn(const Vector3& d, Vector3& previous,
                                                         int& hint_a, int& hint_b) {
  const Scalar along = d.dot(previous);
  if (along < 0 ||
      along * along < kNearbyCosine * kNearbyCosine * d.squaredNorm() * previous.squaredNorm()) {
    hint_a = hint_b = -1;
  }
  previous = d;
}

/// Whether the point `p`, asked along another direction than the corral's point `x`, lies nearer
/// than the corral along x by more than the rounding of Wolfe's tests (1e-13 |x|, compared
/// squared; Wolfe's gap test stops at 2e-14 |x|): such a point joins the corral and x moves
/// nearer. `along` is x . p. The test of the searches that ask along momentum or Newton's steps.
[[gnu::always_inline]] inline bool nearer_than_corral(const Vector3& x, Scalar along) {
  const Scalar xx = x.squaredNorm();
  const Scalar nearer = xx - along;
  return nearer > 0 && nearer * nearer > 1e-26 * xx;
}

/// An oracle point's separation along the unit direction it bounds the distance by.
struct Separation {
  Scalar value;
  Vector3 direction;
};

/// The corral the search starts from: the oracle's point along `start`, asked here unless given
/// (`given`, from the same hints, counted as the call it replaces).
template <class Oracle>
MinNormPoint first_corral(const OraclePoint* given, const Vector3& start, const Oracle& oracle,
                          int& hint_a, int& hint_b, long& evaluations) {
  if (given != nullptr) {
    ++evaluations;
    hint_a = given->ia;
    hint_b = given->ib;
  }
  return single_point(given != nullptr ? *given : oracle(start));
}

/// A corral a Wolfe walk left (DistanceFinish::whole_from_corral): its last point is the oracle's
/// along `start`, asked already.
template <class Oracle>
MinNormPoint first_corral(const MinNormPoint* given, const Vector3&, const Oracle&, int& hint_a,
                          int& hint_b, long& evaluations) {
  const OraclePoint& newest = given->corral[given->size - 1];
  ++evaluations;
  hint_a = newest.ia;
  hint_b = newest.ib;
  return *given;
}

/// The witnesses of a corral, their points placed by the bodies: whole_search's `witnesses` for
/// an oracle that keeps no placed points.
struct PlacedByBodies {
  const FramedPair& pair;
  Witness operator()(const MinNormPoint& corral, bool enclose) const {
    return enclose ? witness_of(pair, corral) : contact_witness_of(pair, corral);
  }
};

/// Wolfe's algorithm on B - A from the oracle's point along the unit direction `start` (or
/// `first`: that point already asked from the same hints, or a corral whose last point it is),
/// offering its bounds to `bounds` and stopping as soon as they settle `goal`
/// (DistanceFinish::whole says what it offers). Each kind of start is its own instance, so that
/// the single point's compiles as it would alone.
/// `oracle(d)` is the support point of B - A for the corral's point `d`, its supports from and into
/// `hint_a`/`hint_b`; `along(current, q, inverse_norm)` is the Separation of the point `q` it
/// returned for the corral `current` (whose point's norm is 1 / inverse_norm). `evaluations`
/// counts the oracle calls made here (the oracle counts its own). `witnesses(corral, enclose)` is
/// the corral's witness_of where `enclose`, else its contact_witness_of (PlacedByBodies, or the
/// same from points the oracle kept).
template <class First, class Oracle, class Along, class Witnesses>
bool whole_search(const FramedPair& pair, const Vector3& start, const First* first_point,
                  int& hint_a, int& hint_b, BestBounds& bounds, Goal goal, bool enclosure,
                  int max_iterations, long& evaluations, const Oracle& oracle, const Along& along,
                  const Witnesses& witnesses) {
  // A corral's witnesses. A distance needs no intersection proof where they prove contact, nor
  // does a verdict asked without `enclosure` (a fifth of an overlapping verdict's cost): the
  // witnesses within the tolerance prove the same verdict. Rounded or curved pairs keep it: there
  // the witnesses' distance is not yet the rounded bodies' bound that close_proven reads.
  const bool keep = goal != Goal::distance && (enclosure || pair.adjusted);
  const auto witness = [&](const MinNormPoint& corral) { return witnesses(corral, keep); };
  // The bounds of a corral: its witnesses (an upper bound) and the separation along them (a lower
  // bound, its supports climbing from the hints).
  const auto offer = [&](const MinNormPoint& corral) {
    const Witness w = witness(corral);
    bounds.offer_upper(w);
    if (!(w.distance > 0)) return;
    const Vector3 n = (w.point_b - w.point_a) / w.distance;
    int ia = hint_a;
    int ib = hint_b;
    ++evaluations;
    bounds.offer_lower(n, separation(pair.a, pair.b, n, ia, ib));
  };
  // The corral bounds the distance above by `|x|`, and each iteration's oracle point below by its
  // separation along the direction it was asked for (`along`): once these meet the goal, the
  // bounds are proven, the upper one from the corral's witnesses, and the search stops if they
  // meet it too (rounding aside, they do).
  bool offered = false;
  const bool distance_without_radii =
      goal == Goal::distance && pair.radius_a == 0 && pair.radius_b == 0;
  const auto stop = [&](const MinNormPoint& current, Scalar norm, const OraclePoint* q) {
    // Every goal needs the bounds within the tolerance (and rounding) of each other, or a
    // separation above the tolerance: a cheap test first, as most iterations meet neither.
    const Scalar slack = pair.tolerance + 2 * kFrameRounding;
    const auto wide_of = [&](Scalar best_lower) {
      return norm - std::max(best_lower, Scalar(0)) > slack;
    };
    // A new point whose separation is at most zero (most steps of an overlapping search) leaves
    // that test to the bounds alone: where the separation is the larger, both are at most zero,
    // so the gap above the lower bound is |x| either way and neither lies above the tolerance.
    // Its sign, which the positive 1 / |x| does not change, is read first, and the division by
    // |x| is taken only where the separation's value is: taken at every corral's first test
    // (beside the scans), its latency held up their retirement (natively a tenth of a 4-point
    // overlapping distance's samples sat on it).
    if (q != nullptr && along(current, *q, Scalar(1)).value <= 0 && wide_of(bounds.lower()) &&
        !(bounds.lower() > pair.tolerance)) {
      return false;
    }
    const Scalar inverse_norm = q != nullptr ? 1 / norm : Scalar(0);
    const Scalar lower = q != nullptr ? along(current, *q, inverse_norm).value : bounds.lower();
    const Scalar best_lower = std::max(lower, bounds.lower());
    const bool wide = wide_of(best_lower);
    if (wide && !(best_lower > pair.tolerance)) return false;
    // A distance of bodies without radii needs the bounds within the tolerance, or contact: a
    // pair proven apart but not yet to the tolerance (most steps of a search apart) fails both
    // whatever the rounding of its lower bound (rounded_lower only lowers it).
    if (wide && distance_without_radii && !(norm + kFrameRounding <= pair.tolerance) &&
        pair.frame.size != 0) {
      return false;
    }
    if (!goal_reached(pair, goal, best_lower, norm, false)) return false;
    bounds.offer_upper(witness(current));
    if (q != nullptr) bounds.offer_lower(along(current, *q, inverse_norm).direction, lower);
    offered = bounds.reached(pair, goal);
    return offered;
  };
  // The first oracle point is the supporting pair along `start`, whose separation and distance
  // often settle a verdict at once.
  const MinNormPoint first =
      first_corral(first_point, start, oracle, hint_a, hint_b, evaluations);
  const OraclePoint& newest = first.corral[first.size - 1];  // the point along `start`
  bounds.offer_lower(start, start.dot(newest.p));
  // A verdict often settles there (apart along the start, or the pair's points within the
  // tolerance); a distance seldom does, and Wolfe's corrals, from this point, give its witnesses.
  // The pair's distance is |newest.p|, as vertex_witness computes it from the same points.
  if (goal != Goal::distance) {
    bounds.offer_upper_vertex(newest.ia, newest.ib, newest.p.norm());
    if (bounds.reached(pair, goal)) return true;
  }
  // In the frame every point lies in the unit ball, so 2 bounds every difference.
  const MinNormPoint nearest = wolfe_min_norm_from(oracle, first, 2, max_iterations, stop);
  if (offered) return true;
  offer(nearest);
  return bounds.reached(pair, goal);
}

}  // namespace swarmcollide::detail
