#include "rounded.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swarmcollide::detail {

Scalar shifted_by_radii(const FramedPair& pair, Scalar core, Scalar outward) {
  using namespace rounding_detail;
  const Scalar radii = pair.radius_a + pair.radius_b;
  return shifted(pair, core, outward, radii, sum_error(pair.radius_a, pair.radius_b, radii) == 0);
}

void round_answer(const FramedPair& pair, Goal goal, Answer& answer) {
  if (!rounded(pair)) return;
  const Scalar radius_a = pair.radius_a;
  const Scalar radius_b = pair.radius_b;
  const bool signed_goal = goal == Goal::signed_distance;
  const RoundedBounds& kept = answer.rounded;
  if (kept.core_lower == answer.lower && kept.core_upper == answer.upper) {
    answer.lower = kept.lower;
    answer.upper = kept.upper;
  } else {
    answer.lower = rounded_lower(pair, answer.lower);
    answer.upper = rounded_upper(pair, answer.upper);
  }
  for (Scalar& h : answer.history) {
    h = rounded_upper(pair, h);
    if (!signed_goal) h = std::max(h, 0.0);
  }
  const Vector3 between = answer.point_b - answer.point_a;
  if (signed_goal || answer.upper >= 0) {
    // The contact normal, else the witnesses' direction; cores that share their witness (one
    // point twice, as two concentric spheres) have every direction for a normal. Their distance
    // only when it is asked for (its square root was some 15 instructions of a signed distance).
    Vector3 n = signed_goal ? answer.direction : Vector3::Zero();
    if (!(n.squaredNorm() > 0)) {
      const Scalar gap = between.norm();
      n = gap > 0 ? Vector3(between / gap) : Vector3::UnitZ();
    }
    answer.point_a += radius_a * n;
    answer.point_b -= radius_b * n;
    return;
  }
  if (!(radius_a + radius_b > 0)) return;
  // Cores closer than r_a + r_b: the rounded bodies overlap, and the point at r_a / (r_a + r_b)
  // along the witnesses' segment is within r_a of A's and r_b of B's.
  answer.point_a += (radius_a / (radius_a + radius_b)) * between;
  answer.point_b = answer.point_a;
  if (answer.upper + kFrameRounding < 0) answer.intersection_proven = true;
  answer.upper = 0;
}

}  // namespace swarmcollide::detail
