// Points and segments (the cores of spheres and capsules) against each other and a point against a
// box, from the nearest points' closed forms; private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "answer.hpp"

namespace swarmcollide::detail {

/// True, with `answer` (default-constructed by the caller) the answer for `goal`, for a pair of
/// polyhedra of one or two points each (a point or a segment: the core of a sphere or a capsule),
/// or of one point against a box (eight points, the corners of a box in the body's own frame),
/// whose cores are apart, or, for a signed distance, a point inside a box; false (`answer` then
/// holds nothing to use) for any other pair, cores that touch or otherwise overlap, or bounds that
/// leave the goal unmet: the caller's search then answers it.
///
/// The closed form only chooses: the nearest points of the cores (Ericson's clamped form for two
/// segments, a clamp to the box's extents in its own frame), as combinations of the cores' points,
/// and the normal between them. The bounds come from the certificate machinery as any search's:
/// the upper one is the distance between those two points of the cores, the lower one the
/// separation along the normal, the least height of B's points less the greatest of A's. A point
/// inside a box is as deep as its nearest face is near, `min_k h_k - |c_k|` in the box's own
/// frame, along that face's normal: the upper bound is minus that depth as the frame's rounding
/// leaves it proven (curved_depth.hpp's depth_in_frame, as the curved shapes' closed forms prove
/// theirs), the lower one the separation along the face's normal.
bool core_closed_form(const FramedPair& pair, Goal goal, Answer& answer);

/// True when `pair` may be answered by core_closed_form (cheap; core_closed_form decides).
inline bool small_cores(const FramedPair& pair) {
  if (pair.a.curved() || pair.b.curved()) return false;
  const int a = pair.a.size();
  const int b = pair.b.size();
  return (a <= 2 && b <= 2) || (a == 1 && b == 8) || (a == 8 && b == 1);
}

}  // namespace swarmcollide::detail
