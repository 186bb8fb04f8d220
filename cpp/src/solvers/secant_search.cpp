// DistanceFinish::whole for two ellipsoids: Wolfe's steps along secant directions. In a file of its
// own, so that whole()'s search for every other pair compiles as it does alone (with both in one
// file, polytope queries took 1-3% more instructions, the secant code unused).
#include <algorithm>
#include <array>
#include <cmath>

#include "../queries/verdict.hpp"
#include "distance_finish.hpp"
#include "minkowski.hpp"
#include "whole_search.hpp"

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
  // An oracle point bounds the distance by its separation along the direction it was asked for:
  // the secant direction m (`m . q`), or the corral's point `x` (`(x/|x|) . q`).
  const auto measured = [&samples](const MinNormPoint& current, const OraclePoint& q,
                                   Scalar inverse_norm) {
    return samples.asked_secant
               ? Separation{samples.asked.dot(q.p), samples.asked}
               : Separation{current.x.dot(q.p) * inverse_norm, current.x * inverse_norm};
  };
  const OraclePoint* asked_here = nullptr;  // the first point is asked along `start`
  return whole_search(pair_, start, asked_here, hint_a, hint_b, bounds, goal, enclosure,
                      max_iterations_, evaluations_, oracle, measured);
}

}  // namespace swarmcollide::detail
