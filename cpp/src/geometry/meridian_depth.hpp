// The depth of two bodies of revolution about parallel axes, from their meridian sections;
// private to the library's sources.
#pragma once

#include "curved_depth.hpp"
#include "curved_supports.hpp"
#include "framed_body.hpp"

namespace swarmcollide::detail {

/// A proven lower bound on the penetration depth of a framed pair's cores where each is
/// symmetric about an axis of its own (a cylinder, a cone, an ellipsoid with two equal radii,
/// a capsule's core segment) or about every axis through its centre (a ball's core point, a
/// ball), the axes parallel as placed (to 2^-30 rad), and at least one body curved. B - A is then
/// a body of revolution about the line through the centres' difference, and the origin's depth in
/// it is a point's depth in its meridian section, a convex set of the plane: a polygon of that
/// section's support points bounds it, as the expanding polytope does in space, but with a few
/// dozen corners where the polytope would need a ring of them around the axis (coaxial bodies
/// are deepest along a whole circle of directions, which no polytope of support points closes
/// on). `depth` is -infinity where the pair is not such a pair or the bound is not positive; the
/// normal, the surface point and `curved_a` are closed_form_depth's.
ClosedFormDepth meridian_depth(const FramedBody& a, const FramedBody& b);

/// How far apart two axes may lie for meridian_depth (the chord between them as unit vectors):
/// each body is then turned onto the other's axis, which moves its points by at most the chord
/// times their distance from its centre, taken off the bound. Poses computed along a robot's
/// chain put coaxial links' axes some roundoffs apart.
inline constexpr Scalar kMostAxisTilt = 0x1p-30;

/// A cylinder or a cone: a body with an axis of its own, by its kind alone.
inline bool axial_kind(const FramedBody& body) {
  return body.curved_kind() == CurvedKind::cylinder || body.curved_kind() == CurvedKind::cone;
}

/// False where meridian_depth cannot apply, by the bodies' kinds (an ellipsoid of three radii,
/// a polyhedron of more than two points) and, where both kinds have axes, by the axes; false too
/// for a point in a cylinder or a cone, whose closed form (depth_of) is the point's exact depth.
/// A cheap test inline, so that the overlapping curved pairs turned anyhow skip the call (some
/// 60 instructions of each).
inline bool may_share_an_axis(const FramedBody& a, const FramedBody& b) {
  const auto may_revolve = [](const FramedBody& body) {
    if (body.curved_kind() == CurvedKind::ellipsoid) {
      const Vector3& radii = static_cast<const EllipsoidSupport&>(*body.body().curved()).radii();
      return radii.x() == radii.y();
    }
    return body.curved() ? axial_kind(body) : body.size() <= 2;
  };
  if (!may_revolve(a) || !may_revolve(b)) return false;
  const auto point = [](const FramedBody& body) { return !body.curved() && body.size() == 1; };
  if ((axial_kind(a) && point(b)) || (axial_kind(b) && point(a))) return false;
  return !axial_kind(a) || !axial_kind(b) ||
         frame_axis(a).cross(frame_axis(b)).squaredNorm() <= kMostAxisTilt * kMostAxisTilt;
}

}  // namespace swarmcollide::detail
