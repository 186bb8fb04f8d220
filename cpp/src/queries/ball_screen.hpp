// Verdicts that the bodies' balls, or an axis through their centres, prove before any frame is set
// up or any solver runs; private to the library's sources.
#pragma once

#include <optional>
#include <vector>

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
