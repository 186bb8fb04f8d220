// The certified penetration solver; private to the library's sources.
#pragma once

#include "swarmcollide/geometry/hull.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// Proven bounds on the signed distance `sd` of two convex hulls of point sets, with the best
/// direction found and witness points on it.
///
/// `sd` is the largest separation `s(n) = min_j n.y_j - max_i n.x_i` over unit directions `n`:
/// the distance for separated bodies, minus the penetration depth for overlapping ones.
struct PenetrationBounds {
  /// Proven `sd >= lower`: `s(normal)` minus its rounding margin (-infinity only if no direction
  /// was evaluated, which cannot happen for valid input).
  Scalar lower = 0;
  /// Proven `sd <= upper`; +infinity when nothing could be proven.
  Scalar upper = 0;
  /// Unit direction from A to B of the largest separation found: `s(normal)` is `lower` up to its
  /// rounding margin.
  Vector3 normal = Vector3::UnitX();
  /// `s(normal)` as computed (without the margin).
  Scalar separation = 0;
  /// Points of A's supporting feature along `normal` and of B's along `-normal` (each within
  /// `feature_slack` of the supporting plane) with `point_b - point_a` closest to
  /// `separation * normal`; equal to it up to rounding when `normal` is optimal.
  Vector3 point_a = Vector3::Zero();
  Vector3 point_b = Vector3::Zero();
  /// Convex weights over the rows of `a` and `b` that give `point_a` and `point_b`.
  VectorX weights_a;
  VectorX weights_b;
  /// `|point_b - point_a - separation * normal|`, as computed.
  Scalar witness_residual = 0;
  /// The slack within which the witnesses' supporting features were collected.
  Scalar feature_slack = 0;
  /// Iterations of the nearest-point and polytope-expansion loops, added up.
  int iterations = 0;
  /// True when `upper - lower <= tolerance`.
  bool proven = false;
};

/// Certified signed distance (mostly for overlapping bodies: minus the penetration depth) of the
/// convex hulls of the rows of `a` and `b`, whose hulls are `hull_a` and `hull_b`.
///
/// The pair should be in a normalised frame (coordinates of magnitude about 1 or less): the
/// rounding margins are absolute multiples of the unit roundoff times the largest coordinate.
/// `hint` is a good direction from A to B if one is known (zero otherwise); `tolerance` (absolute,
/// >= 0) is the requested gap `upper - lower`; `max_iterations` (>= 1) caps each iterative stage.
/// The solver uses the Minkowski difference `A - B`: Wolfe's nearest point, then an expanding
/// polytope whose closed, origin-enclosing surface is checked before it proves `upper`, and for
/// bodies with few edges (or when the polytope cannot prove the gap) the exhaustive candidate axes
/// (face normals and crossing Gauss-map arcs). Every loop is bounded; nothing aborts.
PenetrationBounds penetration(const VertexMatrix& a, const Hull& hull_a, const VertexMatrix& b,
                              const Hull& hull_b, const Vector3& hint, Scalar tolerance,
                              int max_iterations);

}  // namespace swarmcollide::detail
