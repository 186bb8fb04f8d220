// A point core (a sphere's centre) against a cylinder, a cone or an ellipsoid, from the nearest
// point's closed form; private to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "answer.hpp"

namespace swarmcollide::detail {

/// True, with `answer` (default-constructed by the caller) the answer for `goal`, for a pair
/// whose one body is a single point (the core of a sphere) and whose other is a cylinder, a cone
/// or an ellipsoid in its own frame; false (`answer` then holds nothing to use) for any other
/// pair, a point on the surface, a point inside for goals other than the signed distance, or
/// bounds that leave the goal unmet: the caller's search then answers it. The answer is written
/// in the caller's place: returned in an optional and moved out of it, it was moved twice.
///
/// The closed form only chooses: the outward normal of the nearest surface point, and that point
/// as a combination of at most two of the shape's support points (rim points, the apex; an
/// ellipsoid's support point along the normal, found by Newton's method on the multiplier). The
/// bounds come from the certificate machinery as any search's: the upper one is the distance to
/// that combination (support points are points of the shape, so is their combination), the lower
/// one the separation along the normal, measured with the shape's support function (its support
/// error taken off by rounded.hpp). A point inside a cylinder or a cone is answered the same way,
/// the nearest surface point the nearer of the mantle and a cap (of the base and the slant), the
/// upper bound minus the depth that the shape's closed form proves (curved_depth.hpp); inside an
/// ellipsoid, or where that leaves the goal unmet, by the penetration solver.
bool point_against_curved(const FramedPair& pair, Goal goal, int max_iterations, Answer& answer);

/// True when `pair` may be one point against a curved body (cheap; point_against_curved decides).
inline bool point_and_curved(const FramedPair& pair) {
  return pair.a.curved() ? !pair.b.curved() && pair.b.size() == 1
                         : pair.b.curved() && pair.a.size() == 1;
}

}  // namespace swarmcollide::detail
