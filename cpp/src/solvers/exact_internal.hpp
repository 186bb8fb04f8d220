// Helpers shared by the exact methods; private to the library's sources.
#pragma once

#include <string>
#include <vector>

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/solvers/distance_result.hpp"
#include "swarmcollide/solvers/exact_options.hpp"

namespace swarmcollide::exact_internal {

/// A point of a polytope given by a support oracle, with the indices that produced it (the
/// vertex of A and the vertex of B for a Minkowski-difference point, -1 when unused).
struct OraclePoint {
  Vector3 p;
  int ia = -1;
  int ib = -1;
};

/// The minimum-norm point of a polytope as a convex combination of at most four oracle points.
struct MinNormPoint {
  std::vector<OraclePoint> corral;
  std::vector<Scalar> weights;
  Vector3 x = Vector3::Zero();
  int iterations = 0;
};

/// Wolfe's nearest-point algorithm (Wolfe 1976) on the polytope spanned by `oracle`, where
/// `oracle(d)` returns a point minimising `d . q`. `scale` bounds the norms of the points and
/// sets the stopping test: the gap `|x| - (x/|x|) . oracle(x)` at most 1e-14 `scale`, or no
/// further decrease in `|x|` (rounding), or `max_iterations`.
template <class Oracle>
MinNormPoint wolfe_min_norm(const Oracle& oracle, const Vector3& start, Scalar scale,
                            int max_iterations);

/// Barycentric weights, over the points listed in `candidates` of `body`, of the point of their
/// convex hull nearest to `target` (Wolfe's algorithm on the explicit set). Returns weights over
/// all points of the body.
VectorX weights_of_nearest(const ConvexPolyhedron& body, const std::vector<int>& candidates,
                           const Vector3& target);

/// Indices of the points of `body` within `slack` of the supporting plane with outward normal
/// `normal` (the supporting feature, padded by rounding).
std::vector<int> supporting_feature(const ConvexPolyhedron& body, const Vector3& normal,
                                    Scalar slack);

/// A length that bounds the coordinates' spread of the pair (sum of bounding-box diagonals plus
/// the distance between their centres); the stopping tests are relative to it.
Scalar pair_scale(const ConvexPolyhedron& a, const ConvexPolyhedron& b);

/// A distance-query result from weights: witness points, distance (computed relative to a point
/// of A so large offsets do not cost precision), lower bound (clamped at 0) with its direction,
/// verdicts and status `exact`.
DistanceResult result_from_weights(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                   VectorX weights_a, VectorX weights_b, const std::string& method,
                                   Scalar tolerance);

/// A result from witness points found by another library: the weights are those of the nearest
/// points on the supporting features along `point_b - point_a` (or `normal` when given), and the
/// reported points are the combinations those weights give.
DistanceResult result_from_witnesses(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                     const Vector3& point_a, const Vector3& point_b,
                                     const std::string& method, Scalar tolerance);

/// The library's own exact distance (Wolfe on the Minkowski difference B - A).
DistanceResult nearest_points(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                              const ExactOptions& options, const std::string& method);

/// True when `result` is optimal to within rounding: `distance - lower_bound` is at most
/// 1e-11 `pair_scale` (or the bodies touch).
bool is_certified_optimal(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                          const DistanceResult& result);

/// The unit normal (from A to B) of least overlap among the facet normals of the Minkowski
/// difference (face normals of either hull, cross products of an edge of each, plus the axes for
/// degenerate pairs): the exact penetration direction of overlapping polytopes. Costs
/// O((faces + edges_a * edges_b) * points); a fallback for when a library's depth is wrong.
Vector3 minimum_overlap_normal(const ConvexPolyhedron& a, const ConvexPolyhedron& b);

/// A signed result for overlapping bodies from a contact normal `normal` (pointing from A to B)
/// and a penetration depth: `lower_bound = separation(a, b, normal)` (minus the overlap along the
/// normal), `distance = lower_bound` after replacing the normal by `minimum_overlap_normal` when
/// the overlap along it exceeds `depth` by more than rounding, and witnesses on the supporting
/// features along `normal` (A) and `-normal` (B) that the overlap along the normal brings together.
DistanceResult penetration_result(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                  const Vector3& normal, Scalar depth, const std::string& method,
                                  Scalar tolerance);

// ---------------------------------------------------------------------------------------------

namespace wolfe_detail {

// Affine coordinates of the point of least norm in the affine hull of the corral.
inline std::vector<Scalar> affine_minimizer(const std::vector<OraclePoint>& s) {
  const int m = static_cast<int>(s.size());
  std::vector<Scalar> alpha(m, 1);
  if (m == 1) return alpha;
  Eigen::Matrix<Scalar, 3, Eigen::Dynamic> e(3, m - 1);
  for (int k = 1; k < m; ++k) e.col(k - 1) = s[k].p - s[0].p;
  const VectorX beta = e.colPivHouseholderQr().solve(-s[0].p);
  alpha[0] = 1 - beta.sum();
  for (int k = 1; k < m; ++k) alpha[k] = beta(k - 1);
  return alpha;
}

inline Vector3 combine(const std::vector<OraclePoint>& s, const std::vector<Scalar>& w) {
  Vector3 x = Vector3::Zero();
  for (std::size_t k = 0; k < s.size(); ++k) x += w[k] * s[k].p;
  return x;
}

}  // namespace wolfe_detail

template <class Oracle>
MinNormPoint wolfe_min_norm(const Oracle& oracle, const Vector3& start, Scalar scale,
                            int max_iterations) {
  using namespace wolfe_detail;
  MinNormPoint best;
  best.corral = {oracle(start)};
  best.weights = {1};
  best.x = best.corral[0].p;
  std::vector<OraclePoint> s = best.corral;
  std::vector<Scalar> w = best.weights;
  Vector3 x = best.x;
  const Scalar gap_tolerance = 1e-14 * scale;
  for (int iteration = 1; iteration <= max_iterations; ++iteration) {
    best.iterations = iteration;
    const Scalar xx = x.squaredNorm();
    if (xx == 0) break;
    const OraclePoint q = oracle(x);
    if (xx - x.dot(q.p) <= gap_tolerance * std::sqrt(xx)) break;
    bool known = false;
    for (const OraclePoint& c : s) known = known || (c.ia == q.ia && c.ib == q.ib);
    if (known || s.size() >= 4) break;  // rounding: the optimum is reached
    s.push_back(q);
    w.push_back(0);
    // Minor cycles: move towards the affine minimiser, dropping points whose weight would turn
    // negative; each cycle removes a point, so there are at most four.
    for (int minor = 0; minor < 5; ++minor) {
      const std::vector<Scalar> alpha = affine_minimizer(s);
      bool interior = true;
      for (Scalar a : alpha) interior = interior && a > 0;
      if (interior) {
        w = alpha;
        break;
      }
      Scalar theta = 1;
      std::size_t leaving = 0;
      for (std::size_t k = 0; k < s.size(); ++k) {
        if (alpha[k] <= 0) {
          const Scalar t = w[k] / (w[k] - alpha[k]);
          if (t < theta) {
            theta = t;
            leaving = k;
          }
        }
      }
      for (std::size_t k = 0; k < s.size(); ++k) w[k] = theta * alpha[k] + (1 - theta) * w[k];
      w[leaving] = 0;
      std::vector<OraclePoint> s_kept;
      std::vector<Scalar> w_kept;
      Scalar total = 0;
      for (std::size_t k = 0; k < s.size(); ++k) {
        if (w[k] > 0) {
          s_kept.push_back(s[k]);
          w_kept.push_back(w[k]);
          total += w[k];
        }
      }
      for (Scalar& v : w_kept) v /= total;
      s = std::move(s_kept);
      w = std::move(w_kept);
      if (s.size() == 1) break;
    }
    x = combine(s, w);
    if (!(x.squaredNorm() < best.x.squaredNorm())) break;  // no progress left above rounding
    best.corral = s;
    best.weights = w;
    best.x = x;
  }
  return best;
}

}  // namespace swarmcollide::exact_internal
