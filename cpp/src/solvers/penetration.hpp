// The certified penetration solver; private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "expanding_polytope.hpp"
#include "swarmcollide/geometry/hull.hpp"
#include "swarmcollide/problem/convex_weights.hpp"
#include "swarmcollide/types.hpp"
#include "wolfe_min_norm.hpp"

namespace swarmcollide::detail {

/// Which argument proved `PenetrationBounds::upper`.
enum class PenetrationProof {
  /// None: `upper` is +infinity.
  none,
  /// A point `p` of `B - A` (Wolfe's nearest point): `sd <= |p|`.
  nearest_point,
  /// A verified polytope inside `A - B` around the origin: `sd <= -(its inner radius)`.
  polytope,
  /// The enumeration of every facet normal of `A - B` (the candidate axes).
  candidate_axes,
  /// A curved shape's closed form holding the other body's points (curved_depth.hpp).
  closed_form,
  /// Balls that roll inside curved bodies, around a nearest point (rolling_ball.hpp).
  rolling_ball,
  /// A cylinder's side, with the expanding polytope's faces (cylinder_side.hpp).
  cylinder_side,
  /// A cone's side, with the expanding polytope's faces (cone_side.hpp).
  cone_side,
};

/// Proven bounds on the signed distance `sd` of two convex hulls of point sets, with the best
/// direction found and witness points on it.
///
/// `sd` is the largest separation `s(n) = min_j n.y_j - max_i n.x_i` over unit directions `n`:
/// the distance for separated bodies, minus the penetration depth for overlapping ones.
struct PenetrationBounds {
  /// Proven `sd >= lower`: `separation` minus its rounding margin.
  Scalar lower = 0;
  /// Proven `sd <= upper`; +infinity when nothing could be proven.
  Scalar upper = 0;
  /// Unit direction from A to B of the largest separation found: `s(normal)` is `lower` up to its
  /// rounding margin.
  Vector3 normal = Vector3::UnitX();
  /// `s(normal)` computed by scanning every point (the margin not subtracted).
  Scalar separation = 0;
  /// The rounding margin: `lower = separation - margin`. It is `separation_margin` of the largest
  /// coordinate plus `scan_shortfall`.
  Scalar margin = 0;
  /// The part of `margin` that covers support points found by scanning in the bodies' own frames
  /// (FramedBody::scan_shortfall of both; zero for points given in the frame).
  Scalar scan_shortfall = 0;
  /// Points of A's supporting feature along `normal` and of B's along `-normal` (each within
  /// `feature_slack` of the supporting plane) with `point_b - point_a` closest to
  /// `separation * normal`; equal to it up to rounding when `normal` is optimal.
  Vector3 point_a = Vector3::Zero();
  Vector3 point_b = Vector3::Zero();
  /// Convex weights over the bodies' points that give `point_a` and `point_b` (at most four
  /// nonzero, held sparsely).
  ConvexWeights weights_a;
  ConvexWeights weights_b;
  /// `|point_b - point_a - separation * normal|`, as computed.
  Scalar witness_residual = 0;
  /// `witness_residual` is within the tolerance (or 4 margins): false where a curved pair's
  /// expansion stopped at the rounding's floor with its normal still too far off the optimal one
  /// for any witnesses along it (at tolerances near 1e-12), whose answer is then not certified.
  bool witnesses_along_normal = true;
  /// The slack within which the witnesses' supporting features were collected.
  Scalar feature_slack = 0;
  /// Iterations of the nearest-point and polytope-expansion loops, added up.
  int iterations = 0;
  /// Which argument gave `upper`.
  PenetrationProof proof = PenetrationProof::none;
  /// True when `upper - lower <= tolerance`.
  bool proven = false;
};

/// Certified signed distance (mostly for overlapping bodies: minus the penetration depth) of the
/// framed bodies `a` and `b`, whose points lie in the frame's unit ball (a FramedPair's bodies).
///
/// `hint` is a good direction from A to B if one is known (zero otherwise); `nearest`, when not
/// null, is the corral of Wolfe's algorithm on `B - A` run to its stopping tests (its nearest
/// point to the origin), whose tetrahedron, if it encloses the origin (an intersection proof),
/// starts the expanding polytope at once; `tolerance` (absolute, >= 0) is the requested gap
/// `upper - lower`; `max_iterations` (>= 1) caps each iterative stage.
/// The solver works on the Minkowski difference: Wolfe's nearest point of `B - A` to the origin
/// (unless `nearest` is given), then an expanding polytope in `A - B` whose closed,
/// origin-enclosing surface is verified before it proves `upper`, and when that leaves a gap
/// (touching, flat or degenerate differences) the exhaustive candidate axes (face normals and
/// crossing Gauss-map arcs), for pairs where they cost at most about 2^22 steps. Every loop is
/// bounded; nothing aborts. Separated bodies get valid bounds too (Wolfe's distance). Support
/// points are climbed or scanned in each body's own frame (no point is placed in the frame but
/// those read; a large body's scan is the branch and bound of its SupportTree, built once per
/// body), so the lower bound's margin includes both bodies' `scan_shortfall`. Once a thread's
/// buffers have grown (and the bodies' trees are built), nothing is allocated.
/// `surface`, when not null, is the surface of this pair's last expansion (KeptSurface, empty
/// when none): if it still encloses the origin at these poses the expansion starts from it
/// instead of a tetrahedron, and the surface this solve ends with replaces it (emptied when no
/// expansion ran, or its surface proved nothing).
PenetrationBounds penetration(const FramedBody& a, const FramedBody& b, const Vector3& hint,
                              const MinNormPoint* nearest, Scalar tolerance, int max_iterations,
                              KeptSurface* surface = nullptr);

/// The same for the convex hulls of the rows of `a` and `b` (points given in the frame), whose
/// hulls are `hull_a` and `hull_b`.
///
/// The pair should be in a normalised frame (coordinates of magnitude about 1 or less): the
/// rounding margins are absolute multiples of the unit roundoff times the largest coordinate. A
/// largest coordinate outside [1e-100, 1e100] (other than 0) gets infinite bounds, unproven.
/// Preconditions: finite points, `hull_a` and `hull_b` from `compute_hull` of them.
PenetrationBounds penetration(const VertexMatrix& a, const Hull& hull_a, const VertexMatrix& b,
                              const Hull& hull_b, const Vector3& hint, Scalar tolerance,
                              int max_iterations);

}  // namespace swarmcollide::detail
