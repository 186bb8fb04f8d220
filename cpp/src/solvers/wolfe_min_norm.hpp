// Wolfe's minimum-norm-point algorithm; private to the library's sources.
#pragma once

#include <array>
#include <cmath>

#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// A point of a polytope given by a support oracle, with the indices that produced it (the
/// vertex of A and the vertex of B for a Minkowski-difference point, -1 when unused).
struct OraclePoint {
  Vector3 p = Vector3::Zero();
  int ia = -1;
  int ib = -1;
};

/// The minimum-norm point of a polytope as a convex combination of at most four oracle points
/// (its corral), held in place: a solve allocates nothing.
struct MinNormPoint {
  static constexpr int kCapacity = 4;
  std::array<OraclePoint, kCapacity> corral;
  /// Positive and summing to one over the first `size` entries.
  std::array<Scalar, kCapacity> weights{};
  int size = 0;
  Vector3 x = Vector3::Zero();
  int iterations = 0;
};

namespace wolfe_detail {

// Affine coordinates `alpha` of the point of least norm in the affine hull of s[0], ..., s[m-1]
// (m <= 4), in closed form: the coordinates of the origin's projection onto the line, the plane
// or (for a tetrahedron) the space they span. The determinants come from cross products of the
// edges from s[0], which keeps them accurate for long thin simplexes. False when the points are
// affinely dependent to rounding: then the corral cannot improve.
inline bool affine_minimizer(const std::array<OraclePoint, 4>& s, int m,
                             std::array<Scalar, 4>& alpha) {
  alpha[0] = 1;
  if (m == 1) return true;
  const Vector3& p0 = s[0].p;
  const Vector3 e1 = s[1].p - p0;
  if (m == 2) {
    alpha[1] = -p0.dot(e1) / e1.squaredNorm();
  } else if (m == 3) {
    // The normal equations' determinant and Cramer numerators by Lagrange's identity.
    const Vector3 e2 = s[2].p - p0;
    const Vector3 n = e1.cross(e2);
    const Scalar nn = n.squaredNorm();
    alpha[1] = -n.dot(p0.cross(e2)) / nn;
    alpha[2] = -n.dot(e1.cross(p0)) / nn;
  } else {
    // Cramer's rule; its residual (the common point's distance from the origin) can be far above
    // rounding for a flat tetrahedron, so the solve is repeated once for the residual (iterative
    // refinement), which brings it to a pivoted QR's.
    const Vector3 e2 = s[2].p - p0;
    const Vector3 e3 = s[3].p - p0;
    const Vector3 e23 = e2.cross(e3);
    const Scalar volume = e1.dot(e23);
    Vector3 r = p0;
    alpha[1] = alpha[2] = alpha[3] = 0;
    for (int pass = 0; pass < 2; ++pass) {
      alpha[1] -= r.dot(e23) / volume;
      alpha[2] -= e1.dot(r.cross(e3)) / volume;
      alpha[3] -= e1.dot(e2.cross(r)) / volume;
      r = p0 + alpha[1] * e1 + alpha[2] * e2 + alpha[3] * e3;
    }
  }
  for (int k = 1; k < m; ++k) {
    if (!std::isfinite(alpha[k])) return false;
    alpha[0] -= alpha[k];
  }
  return true;
}

inline Vector3 combine(const std::array<OraclePoint, 4>& s, const std::array<Scalar, 4>& w, int m) {
  Vector3 x = Vector3::Zero();
  for (int k = 0; k < m; ++k) x += w[k] * s[k].p;
  return x;
}

// Wolfe's minor cycles: from the convex weights `w` on s[0], ..., s[m-1], towards the affine
// minimiser, dropping points whose weight would turn negative (each cycle removes one, so there
// are at most four), until the weights are the corral's minimiser. False when the points are
// affinely dependent to rounding.
inline bool minor_cycles(std::array<OraclePoint, 4>& s, std::array<Scalar, 4>& w, int& m) {
  std::array<Scalar, 4> alpha{};
  for (int minor = 0; minor < 5; ++minor) {
    if (!affine_minimizer(s, m, alpha)) return false;
    bool interior = true;
    for (int k = 0; k < m; ++k) interior = interior && alpha[k] > 0;
    if (interior) {
      w = alpha;
      return true;
    }
    Scalar theta = 1;
    int leaving = -1;
    for (int k = 0; k < m; ++k) {
      if (alpha[k] <= 0) {
        const Scalar t = w[k] / (w[k] - alpha[k]);  // NaN (skipped) when both are zero
        if (t < theta) {
          theta = t;
          leaving = k;
        }
      }
    }
    for (int k = 0; k < m; ++k) w[k] = theta * alpha[k] + (1 - theta) * w[k];
    if (leaving >= 0) w[leaving] = 0;
    int kept = 0;
    Scalar total = 0;
    for (int k = 0; k < m; ++k) {
      if (w[k] > 0) {
        s[kept] = s[k];
        w[kept] = w[k];
        total += w[k];
        ++kept;
      }
    }
    m = kept;
    for (int k = 0; k < m; ++k) w[k] /= total;
    if (m == 1) return true;
  }
  return true;
}

}  // namespace wolfe_detail

/// Wolfe's nearest-point algorithm (Wolfe 1976) on the polytope spanned by `oracle`, where
/// `oracle(d)` returns an OraclePoint minimising `d . q`, from `start`: up to four oracle points
/// with positive weights summing to one (the minor cycles first bring them to their corral's
/// nearest point). `scale` bounds the norms of the points and sets the stopping test: the gap
/// `|x| - (x/|x|) . oracle(x)` at most 1e-14 `scale`, or no further decrease in `|x|`
/// (rounding), or `max_iterations`, or `stop(current, q)` true for the current corral, first
/// with `q` null, then with its new oracle point `q = oracle(current.x)` (whose `(x/|x|) . q`
/// bounds the norm of every point below): a caller with a coarser goal stops as soon as it is
/// met, before the oracle call when the corral alone meets it.
template <class Oracle, class Stop>
MinNormPoint wolfe_min_norm_from(const Oracle& oracle, const MinNormPoint& start, Scalar scale,
                                 int max_iterations, const Stop& stop) {
  using namespace wolfe_detail;
  MinNormPoint best = start;
  std::array<OraclePoint, 4> s = best.corral;
  std::array<Scalar, 4> w = best.weights;
  int m = best.size;
  Vector3 x = best.x;
  const Scalar gap_tolerance = 1e-14 * scale;
  // A start of several points is first settled on its own corral.
  bool settle = m > 1;
  for (int iteration = 1; iteration <= max_iterations; ++iteration) {
    best.iterations = iteration;
    if (!settle) {
      const Scalar xx = x.squaredNorm();
      if (xx == 0 || stop(best, static_cast<const OraclePoint*>(nullptr))) break;
      const OraclePoint q = oracle(x);
      if (stop(best, &q) || xx - x.dot(q.p) <= gap_tolerance * std::sqrt(xx)) break;
      bool known = false;
      for (int k = 0; k < m; ++k) known = known || (s[k].ia == q.ia && s[k].ib == q.ib);
      if (known || m == MinNormPoint::kCapacity) break;  // rounding: the optimum is reached
      s[m] = q;
      w[m] = 0;
      ++m;
    }
    settle = false;
    // The new point lies in the corral's affine hull up to rounding.
    if (!minor_cycles(s, w, m)) break;
    x = combine(s, w, m);
    if (!(x.squaredNorm() < best.x.squaredNorm())) break;  // no progress left above rounding
    best.corral = s;
    best.weights = w;
    best.size = m;
    best.x = x;
  }
  return best;
}

/// The corral of the one oracle point `q`, whose nearest point it is: where Wolfe's algorithm
/// starts.
inline MinNormPoint single_point(const OraclePoint& q) {
  MinNormPoint point;
  point.corral[0] = q;
  point.weights[0] = 1;
  point.size = 1;
  point.x = q.p;
  return point;
}

/// The same, run to its own stopping tests.
template <class Oracle>
MinNormPoint wolfe_min_norm_from(const Oracle& oracle, const MinNormPoint& start, Scalar scale,
                                 int max_iterations) {
  return wolfe_min_norm_from(oracle, start, scale, max_iterations,
                             [](const MinNormPoint&, const OraclePoint*) { return false; });
}

/// Wolfe's algorithm from the single oracle point along `start`, with `stop` as above.
template <class Oracle, class Stop>
MinNormPoint wolfe_min_norm(const Oracle& oracle, const Vector3& start, Scalar scale,
                            int max_iterations, const Stop& stop) {
  return wolfe_min_norm_from(oracle, single_point(oracle(start)), scale, max_iterations, stop);
}

/// Wolfe's algorithm from the single oracle point along `start`.
template <class Oracle>
MinNormPoint wolfe_min_norm(const Oracle& oracle, const Vector3& start, Scalar scale,
                            int max_iterations) {
  return wolfe_min_norm(oracle, start, scale, max_iterations,
                        [](const MinNormPoint&, const OraclePoint*) { return false; });
}

}  // namespace swarmcollide::detail
