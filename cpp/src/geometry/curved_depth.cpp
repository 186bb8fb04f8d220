#include "curved_depth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "meridian_depth.hpp"
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

}  // namespace

ClosedFormDepth closed_form_depth(const FramedBody& a, const FramedBody& b) {
  // Bodies of revolution on parallel axes first (a shaft in a bore, coaxial cones): their
  // meridian sections give the pair's depth to some 1e-14, where one body's points inside the
  // other's shape bound it only (below by their least depth, which is the pair's only where the
  // other body has no width along the deepest direction). Taken only where it proved more, the
  // points' bound won the ties, and with it the normal of its least deep point: a capsule's core
  // on a cylinder's axis, its end as near a cap as the side, went to the expanding polytope along
  // the cap's normal (1,002 iterations, 0.3 ms, where the sections settle it in microseconds).
  if (may_share_an_axis(a, b)) {
    ClosedFormDepth revolution = meridian_depth(a, b);
    if (revolution.depth > 0) return revolution;
  }
  // B's points inside A: B leaves along A's outward direction; A's inside B: A leaves along B's,
  // so B moves the other way.
  ClosedFormDepth b_in_a = points_inside(a, b);
  b_in_a.curved_a = true;
  ClosedFormDepth a_in_b = points_inside(b, a);
  a_in_b.normal = -a_in_b.normal;
  return b_in_a.depth >= a_in_b.depth ? b_in_a : a_in_b;
}

}  // namespace swarmcollide::detail
