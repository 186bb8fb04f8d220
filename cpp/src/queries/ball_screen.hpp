// Verdicts that the bodies' balls, or an axis through their centres, prove before any frame is set
// up or any solver runs; private to the library's sources.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "../geometry/normalise.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// Two balls about the centre of a body's box (`bounds().centre`), in the body's own units: every
/// point of the body lies within `outer` of the centre, and the ball of radius `inner` about it
/// lies inside the body (0 when none is proven).
struct BodyBalls {
  Scalar outer = 0;
  Scalar inner = 0;
  /// The unit outward normals of the hull's triangles in the body's frame, found with the inner
  /// ball (else null): the axes apart_across_faces tries.
  const std::vector<Vector3>* face_normals = nullptr;
  /// The same normals by coordinate, for scans two at a time (null with more than
  /// PointColumns::kCapacity of them): the nearest normal is the first of the largest inner
  /// products, each rounded as Vector3::dot rounds it, bit for bit.
  const PointColumns* normal_columns = nullptr;
  /// The body's ConvexPolyhedron::centred_columns, looked up with the balls: a row's screens scan
  /// the bodies up to six times, and a lookup out of line for each scan cost collide_many 48
  /// instructions per row (8 vertices, overlapping: swarmcollide-thread-scaling count).
  const PointColumns* columns = nullptr;
};

/// `body`'s balls, computed on first use and kept with its derived data. The inner ball and the
/// face normals need the hull, so they are found only `with_inner` (else 0 and none): a batch that
/// builds its bodies row by row screens by the outer balls and the centres' axis alone.
BodyBalls body_balls(const ConvexPolyhedron& body, bool with_inner);

/// A collision's answer settled by a screen, in world units.
struct ScreenVerdict {
  bool colliding = false;
  /// Apart: the distance between two points of the bodies (an upper bound: their first given
  /// points, or their supporting points along the axis), and the separation of the balls or of
  /// the bodies along `direction` (a lower bound), the unit vector between the centres or a placed
  /// face normal.
  /// Colliding: 0 and 0, both witnesses a point common to the inner balls, no direction.
  Scalar distance = 0;
  Scalar lower_bound = 0;
  Vector3 point_a = Vector3::Zero();
  Vector3 point_b = Vector3::Zero();
  Vector3 direction = Vector3::Zero();
};

/// The collision verdict of `a` and `b` under validated poses when their balls prove it beyond
/// rounding: apart when the outer balls are farther apart than the tolerance (relative to the
/// pair's size, as frame_pair measures it), colliding when the inner balls overlap. Nothing
/// otherwise, and nothing where the world coordinates leave the double range (the framed query
/// then answers, or names the problem).
std::optional<ScreenVerdict> collision_by_balls(const ConvexPolyhedron& a, const Pose& pose_a,
                                              const BodyBalls& balls_a, const ConvexPolyhedron& b,
                                              const Pose& pose_b, const BodyBalls& balls_b,
                                              Scalar relative_tolerance);

/// The smallest double above 0 that keeps full precision: the screens' margins add a multiple of
/// it for products that underflow.
inline constexpr Scalar kUnderflow = std::numeric_limits<Scalar>::min();

/// A validated rotation has |R^T R - I| <= kRotationTolerance entrywise, so it stretches or
/// shrinks a vector's length by less than 1.5 of those (Gershgorin on R^T R); 2 covers it.
inline constexpr Scalar kStretch = 2 * kRotationTolerance;

/// The tolerance in world units of a pair whose centres are `centres` apart: relative to the
/// pair's size, the diameter of a ball about both bodies as frame_pair measures it (a hair more,
/// for its rounding).
inline Scalar world_tolerance(const ConvexPolyhedron& a, const ConvexPolyhedron& b, Scalar centres,
                              Scalar relative_tolerance) {
  const Scalar size = centres + 2 * std::max(a.bounds().radius, b.bounds().radius);
  return relative_tolerance * size * (1 + 0x1p-40);
}

/// How far apart two outer balls of radii `outer_a` and `outer_b` are proven (`lower`) whose
/// centres are computed `centres` apart from box centres c and translations t (a rotation R
/// applied, `R c + t`) with `reach` = |c_a|_1 + |t_a|_1 + |c_b|_1 + |t_b|_1, and the bound on
/// the rounding taken off for it (`margin`: not finite, and `lower` not above any tolerance, where
/// the world coordinates leave the double range).
struct BallsGap {
  Scalar lower;
  Scalar margin;
};

inline BallsGap balls_gap(Scalar outer_a, Scalar outer_b, Scalar reach, Scalar centres) {
  const Scalar outer = (outer_a + outer_b) * (1 + kStretch);
  // Each centre's coordinates are rounded by at most 7 u of |c| + |t| (c the box centre), their
  // distance by another 5 u of itself, and the sums below by a few u of their terms: 16 u of it
  // all is more than twice that (the 1-norms bound the lengths and do not underflow; the last
  // term covers products that do).
  const Scalar margin = 16 * kRoundoff * (reach + centres + outer) + 16 * kUnderflow;
  return {centres - outer - margin, margin};
}

/// True when `a` and `b`, under validated poses whose identity tests are known (`turned_a` is
/// `!pose_a.has_identity_rotation()`, as framing needs them), are proven apart by their outer
/// balls (ConvexPolyhedron::outer_radius) as collision_by_balls proves it, without the balls'
/// witnesses or the inner balls, whose hull `collide` does not build. Inline: Query::collide asks
/// it of every pair before framing it, and the pairs it does not settle pay for it (out of line,
/// with the general centres and no first comparison, it was some 200 instructions of a 4-vertex
/// overlapping verdict, 5%; now about 100). The same centres (a rotation that is the identity
/// adds exact zeros), their distance from the plain norm where its squares are far from both ends
/// of the double range (as the screens' `length`), and collision_by_balls itself otherwise.
[[gnu::always_inline]] inline bool outer_balls_apart(const ConvexPolyhedron& a, const Pose& pose_a,
                                                     bool turned_a, const ConvexPolyhedron& b,
                                                     const Pose& pose_b, bool turned_b,
                                                     Scalar relative_tolerance) {
  const Vector3 centre_a = turned_a ? Vector3(pose_a.rotation * a.bounds().centre +
                                              pose_a.translation)
                                    : Vector3(a.bounds().centre + pose_a.translation);
  const Vector3 centre_b = turned_b ? Vector3(pose_b.rotation * b.bounds().centre +
                                              pose_b.translation)
                                    : Vector3(b.bounds().centre + pose_b.translation);
  const Scalar squares = (centre_b - centre_a).squaredNorm();
  // Most pairs a verdict is asked of have balls that meet: the plain comparison turns them away
  // before the margins are made (it rejects, the test below decides).
  const Scalar outer = a.outer_radius() + b.outer_radius();
  if (!(squares > outer * outer)) return false;
  if (!(squares > 0x1p-1000 && squares < 0x1p1000)) {
    return collision_by_balls(a, pose_a, body_balls(a, false), b, pose_b, body_balls(b, false),
                              relative_tolerance)
        .has_value();
  }
  const Scalar centres = std::sqrt(squares);
  const Scalar reach = a.bounds().centre.lpNorm<1>() + pose_a.translation.lpNorm<1>() +
                       b.bounds().centre.lpNorm<1>() + pose_b.translation.lpNorm<1>();
  return balls_gap(a.outer_radius(), b.outer_radius(), reach, centres).lower >
         world_tolerance(a, b, centres, relative_tolerance);
}

/// The bodies proven apart along the axis through their boxes' centres, for bodies of at most
/// kHillClimbingThreshold points (scanned whole, as the solvers scan them): the separation of
/// their supporting points along it, less a bound on its rounding, exceeds the tolerance as
/// collision_by_balls measures it. The bodies' outer balls (`balls_a`, `balls_b`) bound the
/// rounding. It settles most pairs whose balls overlap though the bodies do not: bodies near each
/// other face each other across that axis. Nothing otherwise, or for larger bodies, or where the
/// world coordinates leave the double range.
std::optional<ScreenVerdict> apart_along_centres(const ConvexPolyhedron& a, const Pose& pose_a,
                                                 const BodyBalls& balls_a,
                                                 const ConvexPolyhedron& b, const Pose& pose_b,
                                                 const BodyBalls& balls_b,
                                                 Scalar relative_tolerance);

/// The bodies proven apart along one of two face normals, for bodies of at most
/// kHillClimbingThreshold points whose balls carry face normals: A's normal nearest the direction
/// from A's centre to B's, then B's normal nearest the opposite direction, each placed in the world
/// and tested as apart_along_centres tests its axis (the same bound on the rounding holds for any
/// unit axis). Where the centres' axis fails, one of these proves most pairs that are apart
/// (separating axis theorem: a face normal or an edge pair separates two polytopes), each try
/// costing a fraction of a solver's answer. Nothing otherwise.
std::optional<ScreenVerdict> apart_across_faces(const ConvexPolyhedron& a, const Pose& pose_a,
                                                const BodyBalls& balls_a,
                                                const ConvexPolyhedron& b, const Pose& pose_b,
                                                const BodyBalls& balls_b,
                                                Scalar relative_tolerance);

/// collision_by_balls, then apart_along_centres, then apart_across_faces, placing the centres
/// once: what a batch row asks.
std::optional<ScreenVerdict> collision_by_screens(const ConvexPolyhedron& a, const Pose& pose_a,
                                                  const BodyBalls& balls_a,
                                                  const ConvexPolyhedron& b, const Pose& pose_b,
                                                  const BodyBalls& balls_b,
                                                  Scalar relative_tolerance);

}  // namespace swarmcollide::detail
