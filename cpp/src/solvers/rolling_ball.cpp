#include "rolling_ball.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "../geometry/normalise.hpp"
#include "minkowski.hpp"
#include "secant_direction.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

namespace {

// A body's rolling ball in the frame: its support point along a direction moved `offset` against
// it (inward) is the centre of a ball of radius `radius` inside the body; both 0 when none rolls.
struct Rolling {
  Scalar offset = 0;
  Scalar radius = 0;
};

// Local points x are placed at P(x) = R 2^-e x + o. The shape's ball of radius r - e_l (e_l its
// support points' rounding, SupportFunction::rolling_radius) about p - r v/|v|, p the support
// point for the local direction v = fl(R^T d), maps into the frame to a set holding the ball of
// radius (r_f - e_f) sigma_min(R) about P(p) - r_f R v/|v| (r_f = 2^-e r, e_f = 2^-e e_l, both
// scaled exactly). The oracle's centre is vertex - r_f n, the vertex within 8u of P(p) (5.2u |q|
// + 1.8u of the reach, both at most 1: framed_body.cpp) and n = fl(d / |d|): the two centres
// differ by 8u + r_f |R v/|v| - n|. With s = 3 max |R^T R - I| (a bound on the 2-norm of R^T R -
// I, so sigma_min(R) >= 1 - s): R v = R R^T d + R (v - R^T d) is within (s + 6u) |d| of d, |v| is
// |d| to as much, so R v/|v| is within 2.1 (s + 6u) of d/|d|, which n is within 4u of: under
// 3s + 20u. The ball of radius (r_f - e_f)(1 - s) - r_f (3s + 20u) - 8u about the oracle's
// centre lies in the body; the last factor covers this expression's own rounding (the terms
// are at most 1 in the frame).
Rolling rolling_of(const FramedBody& body) {
  if (!body.curved()) return {};
  const SupportFunction& shape = *body.body().curved();
  const Scalar r = shape.rolling_radius();
  if (!(r > 0)) return {};
  Rolling rolling;
  rolling.offset = times_power_of_two(r, -body.exponent());
  // Below the normal range the scaling rounds, and such a ball proves nothing anyway.
  if (!(rolling.offset > 0x1p-900)) return {};
  const Scalar error = times_power_of_two(
      shape.support_error_roundoffs() * kRoundoff * shape.outer_radius() * (1 + 4 * kRoundoff),
      -body.exponent());
  const Matrix3& rotation = body.rotation();
  const Scalar skew =
      body.rotated()
          ? 3 * (rotation.transpose() * rotation - Matrix3::Identity()).cwiseAbs().maxCoeff() +
                16 * kRoundoff
          : 0;
  const Scalar radius = ((rolling.offset - error) * (1 - skew) -
                         rolling.offset * (3 * skew + 20 * kRoundoff) - 8 * kRoundoff) *
                        (1 - 8 * kRoundoff);
  if (!(radius > 0)) return {};
  rolling.radius = radius;
  return rolling;
}

// An oracle call: the supports' indices and the unit direction they were asked along.
struct Asked {
  int ia;
  int ib;
  Vector3 n;
};

std::vector<Asked>& asked_buffer() {
  thread_local std::vector<Asked> asked;
  return asked;
}

}  // namespace

bool rolls(const FramedBody& body) {
  return body.curved() && body.body().curved()->rolling_radius() > 0;
}

RollingBallDepth rolling_ball_depth(const FramedBody& a, const FramedBody& b,
                                    const Vector3& start, Scalar stop_gap, int max_iterations) {
  RollingBallDepth result;
  const Rolling roll_a = rolling_of(a);
  const Rolling roll_b = rolling_of(b);
  const Scalar offset = roll_a.offset + roll_b.offset;
  if (!(offset > 0) || !(start.squaredNorm() > 0)) return result;
  // B' - A''s support point along d is B - A's (b - a) moved by r_A + r_B along d / |d|: the
  // difference of the rolling balls' centres, b + r_B n and a - r_A n. Each oracle point is
  // numbered by its call (the same supports asked along two directions are two points here), and
  // the call's supports and direction kept for the witnesses.
  std::vector<Asked>& asked = asked_buffer();
  asked.clear();
  const auto ask = [&](const Vector3& d) {
    const Vector3 n = d / d.norm();
    int ia = -1;
    int ib = -1;
    const OraclePoint q = minkowski_support(a, b, d, ia, ib);
    const int k = static_cast<int>(asked.size());
    asked.push_back({ia, ib, n});
    return OraclePoint{q.p + offset * n, k, k};
  };
  // Bounds meet once the gap `|x| - m.q` of the corral's point x and its oracle point q, asked
  // along the unit m (x/|x| here; the secant search's below may ask along another), is within
  // the caller's, less what the radii lose to rounding: the separation along m is m.q - (r_A +
  // r_B), the depth at least r_A + r_B - |x| less the radii's rounding.
  const Scalar gap = stop_gap - (offset - roll_a.radius - roll_b.radius) - 256 * kRoundoff;
  const auto stop = [gap](const MinNormPoint& current, Scalar norm, const OraclePoint* q) {
    return q != nullptr && norm - current.x.dot(q->p) / norm <= gap;
  };
  // Where both bodies roll, both are smooth and so is B' - A''s support map: Wolfe's steps, which
  // halve the angle to the nearest point's direction (the gap falls 4x per step: 17 steps on
  // average on the overlapping ellipsoid pairs of callgrind_curved that it proves), are asked
  // along the secant direction of the last samples first (secant_search.cpp's model), which
  // converges superlinearly (9 steps); its point is taken when it is nearer than the corral
  // along d, else the point along d. Only the stop reads which one was taken (m is then the
  // secant direction): the proof below reads the corral's points, whatever direction each was
  // asked along. Pairs where one body rolls search as before, in an instance of their own.
  Secant samples;
  const auto secant_oracle = [&](const Vector3& d) {
    samples.asked_secant = false;
    const Scalar dd = d.squaredNorm();
    const Scalar norm = std::sqrt(dd);
    Vector3 m;
    if (samples.count >= 2 && secant_direction(samples.samples, samples.count, norm, m)) {
      const OraclePoint q = ask(m);
      samples.remember(m, q.p);
      if (d.dot(q.p) < dd - 1e-13 * norm) {
        samples.asked_secant = true;
        samples.asked = m;
        return q;
      }
    }
    const OraclePoint q = ask(d);
    if (norm > 0) samples.remember(d / norm, q.p);
    return q;
  };
  const auto secant_stop = [gap, &samples](const MinNormPoint& current, Scalar norm,
                                           const OraclePoint* q) {
    if (q == nullptr) return false;
    const Scalar along =
        samples.asked_secant ? samples.asked.dot(q->p) : current.x.dot(q->p) / norm;
    return norm - along <= gap;
  };
  // The oracle's points lie within r_A + r_B + 2 of the origin, at most 4 in the frame.
  const bool secant = roll_a.offset > 0 && roll_b.offset > 0;
  const MinNormPoint nearest =
      secant ? wolfe_min_norm(secant_oracle, start, 4, max_iterations, secant_stop)
             : wolfe_min_norm(ask, start, 4, max_iterations, stop);
  result.iterations = nearest.iterations;
  // A corral of four holds the origin: it lies deeper than the radii.
  if (nearest.size == MinNormPoint::kCapacity) return result;
  // The exact convex combination of the corral's points (weights normalised) is within 32u of
  // a difference of centres of balls inside the bodies (those centres' convex combinations are
  // centres of such balls too, the bodies being convex): each point's computation from the
  // supports, q + fl(r_A + r_B) n, rounds by at most 4.2u (|q| + r_A + r_B) <= 17u. The
  // computed combination is within 6u of the largest point of the exact one, and its norm
  // within 2.5u of itself; the margin doubles these, with the subtractions'.
  Scalar total = 0;
  for (int k = 0; k < nearest.size; ++k) total += nearest.weights[k];
  if (!(total > 0)) return result;
  std::array<Scalar, 4> w{};
  Vector3 x = Vector3::Zero();
  Scalar largest = 0;
  for (int k = 0; k < nearest.size; ++k) {
    w[k] = nearest.weights[k] / total;
    x += w[k] * nearest.corral[k].p;
    largest = std::max(largest, nearest.corral[k].p.norm());
  }
  const Scalar distance = x.norm();
  if (!(distance > 0)) return result;
  const Scalar depth = roll_a.radius + roll_b.radius - distance * (1 + 8 * kRoundoff) -
                       16 * kRoundoff * largest - 128 * kRoundoff;
  if (!(depth > 0)) return result;
  result.proven = true;
  result.depth_lower = depth;
  result.normal = x / distance;
  result.measured = samples.asked_secant ? samples.asked : result.normal;
  // The witnesses: the combinations of the centres, moved by the proven radii along the normal,
  // where the balls about them reach; a body without a ball has its supports' combination, the
  // same points' weights.
  Vector3 centre_a = Vector3::Zero();
  Vector3 centre_b = Vector3::Zero();
  for (int k = 0; k < nearest.size; ++k) {
    const Asked& call = asked[static_cast<std::size_t>(nearest.corral[k].ia)];
    centre_a += w[k] * (a.vertex(call.ia) - roll_a.offset * call.n);
    centre_b += w[k] * (b.vertex(call.ib) + roll_b.offset * call.n);
    result.index_a[k] = call.ia;
    result.index_b[k] = call.ib;
    result.weight_a[k] = w[k];
    result.weight_b[k] = w[k];
  }
  result.size_a = result.size_b = nearest.size;
  if (roll_a.offset > 0) {
    result.index_a[0] = a.add_point(centre_a + roll_a.radius * result.normal);
    result.weight_a[0] = 1;
    result.size_a = 1;
  }
  if (roll_b.offset > 0) {
    result.index_b[0] = b.add_point(centre_b - roll_b.radius * result.normal);
    result.weight_b[0] = 1;
    result.size_b = 1;
  }
  result.point_a = Vector3::Zero();
  result.point_b = Vector3::Zero();
  for (int k = 0; k < result.size_a; ++k) {
    result.point_a += result.weight_a[k] * a.vertex(result.index_a[k]);
  }
  for (int k = 0; k < result.size_b; ++k) {
    result.point_b += result.weight_b[k] * b.vertex(result.index_b[k]);
  }
  return result;
}

}  // namespace swarmcollide::detail
