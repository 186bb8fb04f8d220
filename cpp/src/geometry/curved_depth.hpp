// Depth proofs from the closed forms of curved shapes; private to the library's sources.
#pragma once

#include <limits>

#include "framed_body.hpp"
#include "normalise.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// A proven lower bound on the penetration depth of a framed pair's cores, and the direction
/// from A to B that the bound's nearest surface suggests.
struct ClosedFormDepth {
  /// In frame units; -infinity when no closed form applies.
  Scalar depth = -std::numeric_limits<Scalar>::infinity();
  /// Unit direction from A to B (zero when `depth` is -infinity).
  Vector3 normal = Vector3::Zero();
  /// A point of the curved body `depth` from the least deep point of the other, along its
  /// outward direction (the nearest surface point where the closed form is exact), in the frame:
  /// the witness on the curved body.
  Vector3 surface = Vector3::Zero();
  /// True when the curved body is A.
  bool curved_a = false;
};

/// The depth that a curved body's closed form (SupportFunction::depth_of) proves for a
/// polyhedron whose points (at most `kClosedFormPoints`) all lie inside it, either way round.
/// The points of a curved shape at depth at least `d` form a convex set, so it holds the
/// polyhedron B once it holds B's points, and then `h_A(n) >= h_B(n) + d` for every direction n:
/// the depth `min_n h_A(n) + h_B(-n)` is at least `d` plus B's width along n. The expanding
/// polytope cannot prove this where a whole circle of directions is deepest (a point on a
/// cylinder's or a cone's axis, at an ellipsoid's centre with two equal radii): its faces would
/// have to be tens of thousands.
ClosedFormDepth closed_form_depth(const FramedBody& a, const FramedBody& b);

/// A frame point, given as `from_offset`, its difference from `body`'s offset, in the body's own
/// frame (centred on its box, in the units of its points): where a closed form compares it with
/// the body's shape.
inline Vector3 in_own_frame(const FramedBody& body, const Vector3& from_offset) {
  return times_power_of_two(body.local_direction(from_offset), body.exponent());
}

/// How far the rotation R that places `body` is from orthogonal: 3 max |R^T R - I| (0 for a body
/// not turned) bounds how much turning back by R^T (in_own_frame) may be off, and how much R may
/// shrink a ball's radius. A valid pose's rotation is orthogonal to 1e-9.
inline Scalar rotation_skew(const FramedBody& body) {
  const Matrix3& r = body.rotation();
  return body.rotated() ? 3 * (r.transpose() * r - Matrix3::Identity()).cwiseAbs().maxCoeff() : 0;
}

/// A proven lower bound on the depth in `body` of a frame point within `farthest` of the body's
/// offset, from `framed`, a lower bound (its own rounding included) on the depth of its own-frame
/// coordinates (in_own_frame) in the body's shape, scaled to frame units; `skew` is
/// rotation_skew(body) and `shortfall` its scan_shortfall(). The placement's rounding is taken
/// off: the shortfall covers the frame's placing of the body's points, and as much again the turn
/// back; then the frame's own.
inline Scalar depth_in_frame(Scalar framed, Scalar skew, Scalar farthest, Scalar shortfall) {
  return framed * (1 - skew) - 2 * skew * farthest - 2 * shortfall - kFrameRounding;
}

/// The axis of a framed body in the frame: its rotation's last column.
inline Vector3 frame_axis(const FramedBody& body) {
  return body.rotated() ? Vector3(body.rotation().col(2)) : Vector3::UnitZ();
}

/// The most points a polyhedron may have for closed_form_depth to read them (points and
/// segments, the cores of spheres and capsules, boxes).
inline constexpr int kClosedFormPoints = 64;

}  // namespace swarmcollide::detail
