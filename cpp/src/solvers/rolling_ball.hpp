// A depth proof from the balls that roll inside curved bodies; private to the library's sources.
#pragma once

#include <array>

#include "../geometry/framed_body.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// What rolling_ball_depth proved: the depth of the origin in `B - A` is at least `depth_lower`
/// (so `sd <= -depth_lower`), and the witnesses, a point of A and a point of B (up to rounding)
/// with `point_b - point_a = -depth_lower * normal` up to rounding, each within the search's gap
/// of its body's supporting plane along the normal.
struct RollingBallDepth {
  bool proven = false;
  Scalar depth_lower = 0;
  /// Unit, from A to B.
  Vector3 normal = Vector3::UnitX();
  /// The unit direction along which the search's last oracle point was asked (the normal's
  /// own, or a secant direction's): its separation met the search's gap.
  Vector3 measured = Vector3::UnitX();
  Vector3 point_a = Vector3::Zero();
  Vector3 point_b = Vector3::Zero();
  /// The witnesses as weights over the bodies' points (a curved body's witness is added to its
  /// points: one index of weight 1), `size_a` and `size_b` of each.
  std::array<int, 4> index_a{};
  std::array<int, 4> index_b{};
  std::array<Scalar, 4> weight_a{};
  std::array<Scalar, 4> weight_b{};
  int size_a = 0;
  int size_b = 0;
  int iterations = 0;
};

/// True when a ball rolls inside the body (a curved shape with SupportFunction::rolling_radius).
bool rolls(const FramedBody& body);

/// A body whose shape lets a ball of radius r roll inside (SupportFunction::rolling_radius) is
/// `A = A' + ball(r)`, and so is `B - A = (B' - A') + ball(r_A + r_B)`: the origin lies as deep in
/// `B - A` as `r_A + r_B` less its distance from `B' - A'`, whose support points are those of
/// `B - A` moved by `r_A + r_B` along the direction asked. Wolfe's algorithm on `B' - A'` from
/// `start` (a direction from A to B) gives that distance to `stop_gap` as on any pair apart,
/// where the expanding polytope needs dozens of steps to close on a curved surface. Proves
/// nothing when no body rolls, or the origin is as deep in `B' - A'` too (a depth beyond r_A +
/// r_B).
RollingBallDepth rolling_ball_depth(const FramedBody& a, const FramedBody& b,
                                    const Vector3& start, Scalar stop_gap, int max_iterations);

}  // namespace swarmcollide::detail
