#include "distance_finish.hpp"

#include <algorithm>
#include <array>
#include <cmath>
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

// A direction from A to B and the point of B - A least along it (its supporting pair).
struct Sample {
  Vector3 m;
  Vector3 q;
};

// The secant direction of up to three samples (the oldest first): the support map of B - A,
// modelled as affine over the samples' affine hull (the points `sum l_i q_i` for the directions
// `sum l_i m_i`, `sum l_i = 1`), and the direction where the model's point lies along it
// (`p = s m`, the optimality of the nearest point): for a fixed `s`, the weights of the nearest
// point of the affine hull of `q_i - s m_i` to the origin, then `s = |p|` again, a few times.
// On a smooth difference Wolfe's algorithm halves the angle to the optimal direction per step
// (the new support point lands between the corral's, a bisection); this secant step converges
// superlinearly. False when the samples are degenerate.
bool secant_direction(const std::array<Sample, 3>& samples, int count, Scalar s, Vector3& m) {
  std::array<Scalar, 3> l{};
  for (int round = 0; round < 3; ++round) {
    std::array<Vector3, 3> r;
    for (int i = 0; i < count; ++i) r[i] = samples[i].q - s * samples[i].m;
    const Vector3 e1 = r[1] - r[0];
    const Scalar a = e1.squaredNorm();
    if (!(a > 0)) return false;
    if (count == 3) {
      const Vector3 e2 = r[2] - r[0];
      const Scalar b = e1.dot(e2);
      const Scalar c = e2.squaredNorm();
      const Scalar det = a * c - b * b;
      if (!(det > 1e-12 * a * c)) return false;
      const Scalar f1 = -r[0].dot(e1);
      const Scalar f2 = -r[0].dot(e2);
      l[1] = (c * f1 - b * f2) / det;
      l[2] = (a * f2 - b * f1) / det;
      l[0] = 1 - l[1] - l[2];
    } else {
      l[1] = -r[0].dot(e1) / a;
      l[0] = 1 - l[1];
    }
    Vector3 p = Vector3::Zero();
    for (int i = 0; i < count; ++i) p += l[i] * samples[i].q;
    s = p.norm();
  }
  Vector3 sum = Vector3::Zero();
  for (int i = 0; i < count; ++i) sum += l[i] * samples[i].m;
  const Scalar length = sum.norm();
  if (!(length > 0) || !std::isfinite(length)) return false;
  m = sum / length;
  return true;
}

// The samples of a search that asks along secant directions, and its last question.
struct Secant {
  std::array<Sample, 3> samples;
  int count = 0;
  /// The last oracle point is the support along `asked` (unit), a secant direction.
  bool asked_secant = false;
  Vector3 asked = Vector3::Zero();

  void remember(const Vector3& m, const Vector3& q) {
    if (count == 3) {
      samples[0] = samples[1];
      samples[1] = samples[2];
      --count;
    }
    samples[count++] = {m, q};
  }
};

// Wolfe's oracle point for the corral's point `d` on a pair that asks along secant directions
// (DistanceFinish::whole): the support along the secant direction when it is nearer than the
// corral along `d` (the corral's point then moves nearer), else the support along `d`; the
// separation along the secant direction is offered either way. Apart from the search's loop, so
// that the other pairs' oracle stays the support call alone.
[[gnu::noinline]] OraclePoint secant_support(const FramedPair& pair, const Vector3& d,
                                             Secant& secant, int& hint_a, int& hint_b,
                                             BestBounds& bounds, long& evaluations) {
  const Scalar dd = d.squaredNorm();
  const Scalar norm = std::sqrt(dd);
  Vector3 m;
  if (secant.count >= 2 && secant_direction(secant.samples, secant.count, norm, m)) {
    ++evaluations;
    const OraclePoint q = minkowski_support(pair.a, pair.b, m, hint_a, hint_b);
    secant.remember(m, q.p);
    bounds.offer_lower(m, m.dot(q.p));
    if (d.dot(q.p) < dd - 1e-13 * norm) {
      secant.asked_secant = true;
      secant.asked = m;
      return q;
    }
  }
  ++evaluations;
  const OraclePoint q = minkowski_support(pair.a, pair.b, d, hint_a, hint_b);
  if (norm > 0) secant.remember(d / norm, q.p);
  return q;
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
                           Goal goal, bool enclosure) {
  // The supports of large bodies climb from the previous ones, unless the direction turned by
  // more than about 25 degrees (as Wolfe's first steps do): the hull's climbing starts are then
  // nearer. Small bodies are scanned, whatever the hints.
  const bool climbs =
      pair_.a.size() > kHillClimbingThreshold || pair_.b.size() > kHillClimbingThreshold;
  Vector3 previous = start;
  const auto support = [&](const Vector3& d) {
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
  // Two ellipsoids (smooth, strictly convex: their support map is smooth) ask first along the
  // secant direction of the last three samples (secant_direction); its support point is Wolfe's
  // next one when it is nearer than the corral along the corral's point (so it joins the corral
  // and the corral's point moves nearer), else the support along the corral's point is asked as
  // usual. Either way the separation along the direction asked bounds the distance below. Other
  // pairs ask along the corral's point: a polytope's supports are finitely many points, where
  // Wolfe's algorithm ends in a few exact steps, and the edges and flat faces of cylinders, cones
  // and boxes make the support map far from affine (secant steps there cost more support calls
  // than they save: cylinder-cylinder apart 29,380 -> 43,068 instructions per query).
  const bool secant = pair_.a.curved() && pair_.b.curved() && smooth(pair_.a) && smooth(pair_.b);
  Secant samples;
  const auto oracle = [&](const Vector3& d) {
    samples.asked_secant = false;
    if (secant) return secant_support(pair_, d, samples, hint_a, hint_b, bounds, evaluations_);
    return support(d);
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
    const Scalar lower = q == nullptr ? bounds.lower()
                         : samples.asked_secant ? samples.asked.dot(q->p)
                                        : current.x.dot(q->p) * inverse_norm;
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
    if (q != nullptr) bounds.offer_lower(
        samples.asked_secant ? samples.asked : Vector3(current.x * inverse_norm), lower);
    offered = bounds.reached(pair_, goal);
    return offered;
  };
  // The first oracle point is the supporting pair along `start`, whose separation and distance
  // often settle a verdict at once.
  const MinNormPoint first = single_point(oracle(start));
  bounds.offer_lower(start, start.dot(first.x));
  bounds.offer_upper(vertex_witness(pair_, first.corral[0].ia, first.corral[0].ib));
  if (bounds.reached(pair_, goal)) return true;
  // In the frame every point lies in the unit ball, so 2 bounds every difference.
  const MinNormPoint nearest = wolfe_min_norm_from(oracle, first, 2, max_iterations_, stop);
  if (offered) return true;
  offer(nearest);
  return bounds.reached(pair_, goal);
}

}  // namespace swarmcollide::detail
