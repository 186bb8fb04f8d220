#include "distance_finish.hpp"

#include <algorithm>
#include <vector>

#include "../queries/verdict.hpp"
#include "minkowski.hpp"

namespace swarmcollide::detail {

namespace {

// Exact subproblems the finish solves from one direction before the caller's search takes over
// again. From the first generation's best direction, 512-vertex pairs need up to 10; with fewer,
// a quarter of them wait a dozen swarm iterations for the next finish.
constexpr int kFinishSteps = 10;

// Directions closer than this cosine (about 25 degrees) are nearby: a climb for one starts from
// the support of the other (coal's threshold too).
constexpr Scalar kNearbyCosine = 0.9;

struct Buffers {
  std::vector<char> visited;  // all zero between uses
  std::vector<int> feature_a;
  std::vector<int> feature_b;
  std::vector<int> grown;
};

Buffers& buffers() {
  thread_local Buffers b;
  return b;
}

// Adds the points of `more` missing from `into`; returns whether any was.
bool merge(std::vector<int>& into, const std::vector<int>& more) {
  bool grew = false;
  for (int i : more) {
    if (std::find(into.begin(), into.end(), i) == into.end()) {
      into.push_back(i);
      grew = true;
    }
  }
  return grew;
}

// True for an ellipsoid (a curved body whose support map is smooth).
bool smooth(const FramedBody& body) {
  return body.curved() &&
         body.body().curved()->parameters().kind == CurvedShapeParameters::Kind::ellipsoid;
}

}  // namespace

DistanceFinish::DistanceFinish(const FramedPair& pair, Scalar slack, int max_iterations)
    : pair_(pair), slack_(slack), max_iterations_(max_iterations) {}

// Points of `body` within the slack of its supporting plane along `n` (its support point climbing
// from, and returned in, `hint`), highest first, into `found`.
void DistanceFinish::feature(const FramedBody& body, const Vector3& n, int& hint,
                             std::vector<int>& found) {
  hint = body.support_index(n, hint);
  supporting_feature(body, n, hint, slack_, buffers().visited, found);
  std::sort(found.begin(), found.end(),
            [&](int i, int j) { return body.height(i, n) > body.height(j, n); });
}

// The exact nearest points of the hulls of two features: Wolfe's algorithm on their Minkowski
// difference from `start`, with support points by scanning the features.
Witness DistanceFinish::nearest_between(const std::vector<int>& fa, const std::vector<int>& fb,
                                        const Vector3& start) {
  const auto oracle = [&](const Vector3& d) {
    ++evaluations_;
    return feature_support(pair_.a, fa, pair_.b, fb, d);
  };
  // In the frame every point lies in the unit ball, so 2 bounds every difference.
  return witness_of(pair_, wolfe_min_norm(oracle, start, 2, max_iterations_));
}

bool DistanceFinish::from(const Vector3& n, int& hint_a, int& hint_b, BestBounds& bounds,
                          Goal goal) {
  Buffers& buf = buffers();
  std::vector<int>& fa = buf.feature_a;
  std::vector<int>& fb = buf.feature_b;
  feature(pair_.a, n, hint_a, fa);
  feature(pair_.b, -n, hint_b, fb);
  // Each subproblem grows around the previous one's nearest points, so Wolfe starts there.
  Vector3 start = n;
  for (int step = 0; step < kFinishSteps; ++step) {
    const Witness sub = nearest_between(fa, fb, start);
    bounds.offer_upper(sub);
    if (bounds.reached(pair_, goal)) return true;
    if (!(sub.distance > 0)) return false;
    const Vector3 next = (sub.point_b - sub.point_a) / sub.distance;
    start = next;
    int ia = hint_a;
    int ib = hint_b;
    ++evaluations_;
    bounds.offer_lower(next, separation(pair_.a, pair_.b, next, ia, ib));
    if (bounds.reached(pair_, goal)) return true;
    feature(pair_.a, next, ia, buf.grown);
    const bool grew_a = merge(fa, buf.grown);
    feature(pair_.b, -next, ib, buf.grown);
    const bool grew_b = merge(fb, buf.grown);
    if (!grew_a && !grew_b) return false;  // rounding: nothing left to add
  }
  return false;
}

bool DistanceFinish::whole(const Vector3& start, int& hint_a, int& hint_b, BestBounds& bounds,
                           Goal goal, bool enclosure, const OraclePoint* first_point) {
  // Two ellipsoids (smooth, strictly convex) ask along secant directions (secant_search.cpp). The
  // edges and flat faces of cylinders, cones and boxes make the support map far from affine:
  // secant steps there cost more support calls than they save (cylinder-cylinder apart 29,380 ->
  // 43,068 instructions per query), and a polytope's Wolfe walk ends in a few exact steps.
  // Its first point is asked again there (`first_point` only saves a scan of a polytope).
  if (pair_.a.curved() && pair_.b.curved() && smooth(pair_.a) && smooth(pair_.b)) {
    return whole_secant(start, hint_a, hint_b, bounds, goal, enclosure);
  }
  // The supports of large bodies climb from the previous ones, unless the direction turned by
  // more than about 25 degrees (as Wolfe's first steps do): the hull's climbing starts are then
  // nearer. Small bodies are scanned, whatever the hints.
  const bool climbs =
      pair_.a.size() > kHillClimbingThreshold || pair_.b.size() > kHillClimbingThreshold;
  Vector3 previous = start;
  const auto oracle = [&](const Vector3& d) {
    ++evaluations_;
    if (climbs) {
      const Scalar along = d.dot(previous);
      if (along < 0 || along * along < kNearbyCosine * kNearbyCosine * d.squaredNorm() *
                                            previous.squaredNorm()) {
        hint_a = hint_b = -1;
      }
      previous = d;
    }
    return minkowski_support(pair_.a, pair_.b, d, hint_a, hint_b);
  };
  // A corral's witnesses. A distance needs no intersection proof where they prove contact, nor
  // does a verdict asked without `enclosure` (a fifth of an overlapping verdict's cost): the
  // witnesses within the tolerance prove the same verdict. Rounded or curved pairs keep it: there
  // the witnesses' distance is not yet the rounded bodies' bound that close_proven reads.
  const bool keep = goal != Goal::distance && (enclosure || pair_.adjusted);
  const auto witness = [&](const MinNormPoint& corral) {
    return keep ? witness_of(pair_, corral) : contact_witness_of(pair_, corral);
  };
  // The bounds of a corral: its witnesses (an upper bound) and the separation along them (a lower
  // bound, its supports climbing from the hints).
  const auto offer = [&](const MinNormPoint& corral) {
    const Witness w = witness(corral);
    bounds.offer_upper(w);
    if (!(w.distance > 0)) return;
    const Vector3 n = (w.point_b - w.point_a) / w.distance;
    int ia = hint_a;
    int ib = hint_b;
    ++evaluations_;
    bounds.offer_lower(n, separation(pair_.a, pair_.b, n, ia, ib));
  };
  // The corral bounds the distance above by `|x|`, and each iteration's oracle point below by
  // `(x/|x|) . q` (its supports along `x` are those along `x/|x|`): once these meet the goal, the
  // bounds are proven, the upper one from the corral's witnesses, and the search stops if they
  // meet it too (rounding aside, they do).
  bool offered = false;
  const bool distance_without_radii =
      goal == Goal::distance && pair_.radius_a == 0 && pair_.radius_b == 0;
  // 1 / |x| of the corral being tested, taken at its first test, before its oracle call: the
  // division then runs beside the support scans instead of after them.
  Scalar inverse_norm = 0;
  const auto stop = [&](const MinNormPoint& current, Scalar norm, const OraclePoint* q) {
    if (q == nullptr) inverse_norm = 1 / norm;
    const Scalar lower = q != nullptr ? current.x.dot(q->p) * inverse_norm : bounds.lower();
    const Scalar best_lower = std::max(lower, bounds.lower());
    // Every goal needs the bounds within the tolerance (and rounding) of each other, or a
    // separation above the tolerance: a cheap test first, as most iterations meet neither.
    const Scalar slack = pair_.tolerance + 2 * kFrameRounding;
    const bool wide = norm - std::max(best_lower, Scalar(0)) > slack;
    if (wide && !(best_lower > pair_.tolerance)) return false;
    // A distance of bodies without radii needs the bounds within the tolerance, or contact: a
    // pair proven apart but not yet to the tolerance (most steps of a search apart) fails both
    // whatever the rounding of its lower bound (rounded_lower only lowers it).
    if (wide && distance_without_radii && !(norm + kFrameRounding <= pair_.tolerance) &&
        pair_.frame.size != 0) {
      return false;
    }
    if (!goal_reached(pair_, goal, best_lower, norm, false)) return false;
    bounds.offer_upper(witness(current));
    if (q != nullptr) bounds.offer_lower(current.x * inverse_norm, lower);
    offered = bounds.reached(pair_, goal);
    return offered;
  };
  // The first oracle point is the supporting pair along `start`, whose separation and distance
  // often settle a verdict at once.
  if (first_point != nullptr) {
    ++evaluations_;
    hint_a = first_point->ia;
    hint_b = first_point->ib;
  }
  const MinNormPoint first = single_point(first_point != nullptr ? *first_point : oracle(start));
  bounds.offer_lower(start, start.dot(first.x));
  // A verdict often settles there (apart along the start, or the pair's points within the
  // tolerance); a distance seldom does, and Wolfe's corrals, from this point, give its witnesses.
  // The pair's distance is |first.x|, as vertex_witness computes it from the same points.
  if (goal != Goal::distance) {
    bounds.offer_upper_vertex(first.corral[0].ia, first.corral[0].ib, first.x.norm());
    if (bounds.reached(pair_, goal)) return true;
  }
  // In the frame every point lies in the unit ball, so 2 bounds every difference.
  const MinNormPoint nearest = wolfe_min_norm_from(oracle, first, 2, max_iterations_, stop);
  if (offered) return true;
  offer(nearest);
  return bounds.reached(pair_, goal);
}

}  // namespace swarmcollide::detail
