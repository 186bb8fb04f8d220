#include "curved_depth.hpp"

#include <algorithm>

#include "curved_supports.hpp"
#include "normalise.hpp"

namespace swarmcollide::detail {

namespace {

// The depth `inner`'s points reach inside the curved body `curved`, with the outward direction of
// the least deep one, in the frame.
ClosedFormDepth points_inside(const FramedBody& curved, const FramedBody& inner) {
  ClosedFormDepth least;
  if (!curved.curved() || inner.curved() || inner.size() > kClosedFormPoints) return least;
  const SupportFunction& shape = *curved.body().curved();
  const Scalar skew = rotation_skew(curved);
  Scalar depth = std::numeric_limits<Scalar>::infinity();
  Vector3 outward = Vector3::Zero();
  Vector3 deepest_point = Vector3::Zero();
  Scalar farthest = 0;
  for (int i = 0; i < inner.size(); ++i) {
    const Vector3 from_offset = inner.vertex(i) - curved.offset();
    farthest = std::max(farthest, from_offset.norm());
    Vector3 away;
    const Scalar d = shape.depth_of(in_own_frame(curved, from_offset), away);
    if (d < depth) {
      depth = d;
      outward = curved.rotated() ? Vector3(curved.rotation() * away) : away;
      deepest_point = inner.vertex(i);
    }
    if (!(depth > 0)) return least;  // a point outside (or on) the shape: no proof
  }
  const Scalar framed = times_power_of_two(depth, -curved.exponent());
  if (!(framed > 0)) return least;
  least.depth = depth_in_frame(framed, skew, farthest, curved.scan_shortfall());
  least.normal = outward.normalized();
  // Inside the ball about the point that the bound proves the shape holds.
  least.surface = deepest_point + least.depth * least.normal;
  return least;
}

// The axis of a framed cylinder in the frame: its rotation's last column.
Vector3 frame_axis(const FramedBody& body) {
  return body.rotated() ? Vector3(body.rotation().col(2)) : Vector3::UnitZ();
}

// Two cylinders whose axes are parallel as placed (the same axis column up to its sign, as
// bodies turned by one rotation, or by none, have them): B - A is then a cylinder, of the radii's
// and the half-lengths' sums, about the line between their centres, and the origin's depth in it
// is the pair's. Where the origin lies on that line (coaxial cylinders) a whole circle of
// directions is deepest, which the expanding polytope cannot close on.
ClosedFormDepth parallel_cylinders(const FramedBody& a, const FramedBody& b) {
  ClosedFormDepth none;
  if (a.curved_kind() != CurvedKind::cylinder || b.curved_kind() != CurvedKind::cylinder) {
    return none;
  }
  const Vector3 axis = frame_axis(a);
  const Vector3 axis_b = frame_axis(b);
  if (!(axis == axis_b || axis == -axis_b)) return none;
  const auto& shape_a = static_cast<const CylinderSupport&>(*a.body().curved());
  const auto& shape_b = static_cast<const CylinderSupport&>(*b.body().curved());
  // In A's own frame (its units, its axis z): B's axis is z too, up to the rotations' skew.
  const CylinderSupport difference(shape_a.radius() + shape_b.radius(),
                                   shape_a.half_length() + shape_b.half_length());
  // The origin seen from the centre of B - A.
  const Vector3 from_centre = a.offset() - b.offset();
  Vector3 away;
  const Scalar depth = difference.depth_of(in_own_frame(a, from_centre), away);
  const Scalar framed = times_power_of_two(depth, -a.exponent());
  if (!(framed > 0)) return none;
  // Both placements round: each body's shortfall, and the larger skew over every length read.
  const Scalar skew = std::max(rotation_skew(a), rotation_skew(b));
  const Scalar farthest =
      from_centre.norm() +
      times_power_of_two(difference.radius() + difference.half_length(), -a.exponent());
  ClosedFormDepth least;
  least.depth = depth_in_frame(framed, skew, farthest, a.scan_shortfall() + b.scan_shortfall());
  if (!(least.depth > 0)) return none;
  // The origin leaves B - A along `away`, so B leaves A the other way.
  const Vector3 outward = a.rotated() ? Vector3(a.rotation() * away) : away;
  least.normal = -outward.normalized();
  // A's witness: its own support point along the normal, a point of A.
  least.surface = a.support(least.normal);
  least.curved_a = true;
  if (away.z() == 0) {
    // Across the axes the supporting features are the sides, segments between the rims, and
    // the witnesses lie at a height both share: both rims of each side among the support points
    // let the witnesses find it. (Along the normal alone, rounded a little off the normal to
    // the axes, each body's support was a rim of its own choosing: witnesses a height apart.)
    for (const Scalar tilt : {Scalar(-1e-3), Scalar(1e-3)}) {
      a.support(least.normal + tilt * axis);
      b.support(-least.normal + tilt * axis);
    }
  }
  return least;
}

}  // namespace

ClosedFormDepth closed_form_depth(const FramedBody& a, const FramedBody& b) {
  // B's points inside A: B leaves along A's outward direction; A's inside B: A leaves along B's,
  // so B moves the other way.
  ClosedFormDepth b_in_a = points_inside(a, b);
  b_in_a.curved_a = true;
  ClosedFormDepth a_in_b = points_inside(b, a);
  a_in_b.normal = -a_in_b.normal;
  const ClosedFormDepth& inside = b_in_a.depth >= a_in_b.depth ? b_in_a : a_in_b;
  ClosedFormDepth parallel = parallel_cylinders(a, b);
  return parallel.depth > inside.depth ? parallel : inside;
}

}  // namespace swarmcollide::detail
