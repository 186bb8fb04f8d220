// Helpers shared by the exact methods; private to the library's sources.
#pragma once

#include <string>
#include <vector>

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/solvers/distance_result.hpp"
#include "swarmcollide/solvers/exact_options.hpp"

namespace swarmcollide::exact_internal {

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

}  // namespace swarmcollide::exact_internal
