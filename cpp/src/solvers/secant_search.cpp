// DistanceFinish::whole for two ellipsoids: Wolfe's steps along secant directions. In a file of its
// own, so that whole()'s search for every other pair compiles as it does alone (with both in one
// file, polytope queries took 1-3% more instructions, the secant code unused).
#include <algorithm>
#include <array>
#include <cmath>

#include "../queries/verdict.hpp"
#include "distance_finish.hpp"
#include "minkowski.hpp"

namespace swarmcollide::detail {

namespace {

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
  // `(x/|x|) . q` (its supports along `x` are those along `x/|x|`), or by `m . q` when it is the
  // support along the secant direction m: once these meet the goal, the
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
    const Scalar lower = q == nullptr             ? bounds.lower()
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
    if (q != nullptr) {
      bounds.offer_lower(samples.asked_secant ? samples.asked : Vector3(current.x * inverse_norm),
                         lower);
    }
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
