// DistanceFinish::whole for two ellipsoids: Wolfe's steps along secant directions. In a file of its
// own, so that whole()'s search for every other pair compiles as it does alone (with both in one
// file, polytope queries took 1-3% more instructions, the secant code unused).
#include <cmath>

#include "../queries/verdict.hpp"
#include "distance_finish.hpp"
#include "inline_minkowski.hpp"
#include "secant_direction.hpp"
#include "whole_search.hpp"

namespace swarmcollide::detail {

namespace {

// Wolfe's oracle point for the corral's point `d` (DistanceFinish::whole_secant): the support
// along the secant direction when it is nearer than the corral along `d` (it then joins the
// corral, whose point moves nearer; Wolfe's own gap test, 1e-14 of the scale, cannot end the
// search on it), else the support along `d`; the separation along the secant direction is
// offered either way.
OraclePoint secant_support(const FramedPair& pair, const Vector3& d, Secant& secant, int& hint_a,
                           int& hint_b, BestBounds& bounds, long& evaluations) {
  const Scalar dd = d.squaredNorm();
  const Scalar norm = std::sqrt(dd);
  Vector3 m;
  if (secant.count >= 2 && secant_direction(secant.samples, secant.count, norm, m)) {
    ++evaluations;
    const OraclePoint q = inline_minkowski_support(pair, m, hint_a, hint_b);
    secant.remember(m, q.p);
    bounds.offer_lower(m, m.dot(q.p));
    if (d.dot(q.p) < dd - 1e-13 * norm) {
      secant.asked_secant = true;
      secant.asked = m;
      return q;
    }
  }
  ++evaluations;
  const OraclePoint q = inline_minkowski_support(pair, d, hint_a, hint_b);
  if (norm > 0) secant.remember(d / norm, q.p);
  return q;
}

}  // namespace

// The same search as whole()'s (its stop test, witnesses and bounds), its oracle points asked
// along secant directions first. On a smooth difference Wolfe's algorithm halves the angle to the
// optimal direction per step (the new support point lands between the corral's, a bisection:
// traces of ellipsoid pairs apart cut the gap 4x per step with segment corrals, 2x with
// triangles); the secant step converges superlinearly.
bool DistanceFinish::whole_secant(const Vector3& start, int& hint_a, int& hint_b,
                                  BestBounds& bounds, Goal goal, bool enclosure) {
  // Each oracle point is asked along the secant direction of the last three samples first
  // (secant_support).
  Secant samples;
  const auto oracle = [&](const Vector3& d) {
    samples.asked_secant = false;
    return secant_support(pair_, d, samples, hint_a, hint_b, bounds, evaluations_);
  };
  // An oracle point bounds the distance by its separation along the direction it was asked for:
  // the secant direction m (`m . q`), or the corral's point `x` (`(x/|x|) . q`).
  const auto measured = [&samples](const MinNormPoint& current, const OraclePoint& q,
                                   Scalar inverse_norm) {
    return samples.asked_secant
               ? Separation{samples.asked.dot(q.p), samples.asked}
               : Separation{current.x.dot(q.p) * inverse_norm, current.x * inverse_norm};
  };
  const OraclePoint* asked_here = nullptr;  // the first point is asked along `start`
  const auto search = [&]() SWARMCOLLIDE_FLATTEN {
    return whole_search(pair_, start, asked_here, hint_a, hint_b, bounds, goal, enclosure,
                        max_iterations_, evaluations_, oracle, measured, PlacedByBodies{pair_});
  };
  return search();
}

}  // namespace swarmcollide::detail
