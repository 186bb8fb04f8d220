// The nearest points of two segments, in the plane or in space; private to the library's sources.
#pragma once

#include <algorithm>

#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// The parameters s and t of the nearest points p0 + s (p1 - p0) and q0 + t (q1 - q0) of two
/// segments, either of which may be a point (its ends equal): Ericson's clamped closed form
/// (Real-Time Collision Detection, 5.1.9), the lines' nearest points with t clamped to the second
/// segment and s chosen again for the clamped t. Where sin^2 of the angle between the segments is
/// at most `parallel` the segments are taken as parallel: s = 0, and the nearest point of the
/// second to that end (where they overlap, every point of the overlap is as near). A contact
/// polygon's edges (2-vectors) and the cores of capsules (3-vectors) share it. Always inline, as
/// each has one caller: out of line, a ball's query against a capsule took 30 instructions more.
template <class Point>
[[gnu::always_inline]] inline void nearest_on_segments(const Point& p0, const Point& p1,
                                                       const Point& q0, const Point& q1,
                                                       Scalar parallel, Scalar& s, Scalar& t) {
  const auto clamped = [](Scalar x) { return std::clamp(x, Scalar(0), Scalar(1)); };
  const Point d1 = p1 - p0;
  const Point d2 = q1 - q0;
  const Point r = p0 - q0;
  const Scalar a = d1.squaredNorm();
  const Scalar e = d2.squaredNorm();
  const Scalar f = d2.dot(r);
  s = 0;
  t = 0;
  if (!(a > 0)) {
    if (e > 0) t = clamped(f / e);
    return;
  }
  const Scalar c = d1.dot(r);
  if (!(e > 0)) {
    s = clamped(-c / a);
    return;
  }
  const Scalar b = d1.dot(d2);
  const Scalar denominator = a * e - b * b;
  if (denominator > parallel * a * e) s = clamped((b * f - c * e) / denominator);
  t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = clamped(-c / a);
  } else if (t > 1) {
    t = 1;
    s = clamped((b - c) / a);
  }
}

}  // namespace swarmcollide::detail
