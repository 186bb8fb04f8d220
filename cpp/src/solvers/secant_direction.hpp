// The secant model of a smooth support map, shared by the searches that ask along secant
// directions (secant_search.cpp, rolling_ball.cpp); private to the library's sources.
#pragma once

#include <array>
#include <cmath>

#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

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
inline bool secant_direction(const std::array<Sample, 3>& samples, int count, Scalar s, Vector3& m) {
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

}  // namespace swarmcollide::detail
