#pragma once

#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/queries/compound_result.hpp"
#include "swarmcollide/queries/distance_result.hpp"
#include "swarmcollide/queries/options.hpp"

namespace swarmcollide {

/// A method with its parameters, validated once, that answers queries between pairs of bodies.
/// Every query computes in a frame centred on the pair and scaled to its size, so answers scale
/// with the unit of length and do not depend on where the pair is. Cheap to copy; safe to use
/// from many threads.
class Query {
 public:
  /// Throws std::invalid_argument for invalid options (see QueryOptions::validate).
  explicit Query(QueryOptions options = {});

  const QueryOptions& options() const { return options_; }

  /// Distance between A and B (model (2)): `distance` is an upper bound achieved by witness
  /// points, `lower_bound` a lower bound from a separating direction. Throws
  /// std::invalid_argument for a method without distances ("libccd") or for bodies too far apart
  /// for their distance to be representable.
  DistanceResult distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b) const;
  DistanceResult distance(const ConvexPolyhedron& a, const Pose& pose_a, const ConvexPolyhedron& b,
                          const Pose& pose_b) const;

  /// The result that decides whether A and B collide: the method's own when it is certified;
  /// otherwise, with `escalate`, that of the exact method at the same tolerance (which names the
  /// method it was escalated from). Methods without distances answer with their signed distance.
  DistanceResult collision(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                           bool escalate = true) const;
  DistanceResult collision(const ConvexPolyhedron& a, const Pose& pose_a, const ConvexPolyhedron& b,
                           const Pose& pose_b, bool escalate = true) const;

  /// `collision(...).colliding`, except that bodies whose outer balls
  /// (ConvexPolyhedron::outer_radius, about their boxes' centres) are proven farther apart than
  /// the tolerance are answered apart from the balls alone, before any frame is made or any
  /// solver runs, whatever the method (a far pair then costs about a tenth of a solved one; a near
  /// one a few percent more). That verdict is proven: `collision` gives the same one wherever its
  /// own is certified.
  bool collide(const ConvexPolyhedron& a, const ConvexPolyhedron& b, bool escalate = true) const;
  bool collide(const ConvexPolyhedron& a, const Pose& pose_a, const ConvexPolyhedron& b,
               const Pose& pose_b, bool escalate = true) const;

  /// Signed distance: the distance when the bodies are apart, minus the penetration depth (the
  /// shortest translation of B that separates them) when they overlap. `direction` is the unit
  /// contact normal from A to B and `point_b - point_a = distance * direction`, with `point_a`
  /// on A's supporting feature along `direction` and `point_b` on B's along `-direction`. Throws
  /// std::invalid_argument for methods that measure no penetration (the primal swarms, penalty).
  DistanceResult signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b) const;
  DistanceResult signed_distance(const ConvexPolyhedron& a, const Pose& pose_a,
                                 const ConvexPolyhedron& b, const Pose& pose_b) const;

  /// The same queries between compound bodies (a convex body is a compound body of one part):
  /// the answers of the nearest (for signed distances, the deepest) pair of parts, found by
  /// branch and bound over the two bodies' trees. A pair of tree nodes whose bounding volumes are
  /// proven farther apart than the best part-pair distance found so far (less the tolerance) is
  /// never opened, and a part pair is screened by the separation along its centres' line before
  /// any solver runs. The tolerance is relative to the size of the pair of whole bodies and
  /// applies to every part pair alike, so the answer is certified to it; `collision` stops at the
  /// first part pair proven in contact.
  CompoundResult distance(const CompoundBody& a, const CompoundBody& b) const;
  CompoundResult distance(const CompoundBody& a, const Pose& pose_a, const CompoundBody& b,
                          const Pose& pose_b) const;
  CompoundResult collision(const CompoundBody& a, const CompoundBody& b,
                           bool escalate = true) const;
  CompoundResult collision(const CompoundBody& a, const Pose& pose_a, const CompoundBody& b,
                           const Pose& pose_b, bool escalate = true) const;
  bool collide(const CompoundBody& a, const CompoundBody& b, bool escalate = true) const;
  bool collide(const CompoundBody& a, const Pose& pose_a, const CompoundBody& b, const Pose& pose_b,
               bool escalate = true) const;
  /// The smallest signed distance between a part of A and a part of B: minus the deepest
  /// part-pair penetration when parts overlap. That is not in general the penetration depth of
  /// the non-convex union (the shortest translation separating the unions can be longer).
  CompoundResult signed_distance(const CompoundBody& a, const CompoundBody& b) const;
  CompoundResult signed_distance(const CompoundBody& a, const Pose& pose_a, const CompoundBody& b,
                                 const Pose& pose_b) const;

 private:
  QueryOptions options_;
};

/// `Query(options).distance(a, b)`.
DistanceResult distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                        const QueryOptions& options = {});
/// `Query(options).collide(a, b)`.
bool collide(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
             const QueryOptions& options = {});
/// `Query(options).signed_distance(a, b)`.
DistanceResult signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                               const QueryOptions& options = {});

}  // namespace swarmcollide
