// Rounded bodies: what the solvers find on the cores, made the rounded bodies' answer; private
// to the library's sources.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "../geometry/framed_body.hpp"
#include "../solvers/answer.hpp"

namespace swarmcollide::detail {

/// True when either body of `pair` is rounded (ConvexPolyhedron::radius() > 0) or curved (whose
/// support points may fall short: FramedPair::support_error).
inline bool rounded(const FramedPair& pair) { return pair.adjusted; }

/// The double next below `x` (std::nextafter(x, -infinity)), from its bits where `x` is finite:
/// the stop tests of curved pairs take it at every step, where libm's call was most of their cost.
inline Scalar next_down(Scalar x) {
  constexpr Scalar kLargest = std::numeric_limits<Scalar>::max();
  if (!(std::abs(x) <= kLargest)) {
    return std::nextafter(x, -std::numeric_limits<Scalar>::infinity());
  }
  if (x == 0) return -std::numeric_limits<Scalar>::denorm_min();
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  // Sign and magnitude: a positive number's magnitude steps down, a negative one's up.
  if (x > 0) {
    --bits;
  } else {
    ++bits;
  }
  std::memcpy(&x, &bits, sizeof bits);
  return x;
}

/// A bound on the rounding of `core - (r_a + r_b)` computed in the frame: each radius is exact in
/// the frame (a power-of-two scaling) but for underflow, half the smallest subnormal each; their
/// sum rounds by u of itself, the difference by u of its size. Twice that, and two subnormals.
inline Scalar subtraction_rounding(const FramedPair& pair, Scalar core) {
  const Scalar radii = pair.radius_a + pair.radius_b;
  return 4 * kRoundoff * (std::abs(core) + radii) + 4 * std::numeric_limits<Scalar>::denorm_min();
}

/// `core - r_a - r_b` moved `outward` (-1 down, +1 up) by a bound on its rounding, for a rounded
/// pair: what rounded_lower (but for a curved pair's finite bound, which it lowers itself) and
/// rounded_upper return when a radius is not zero.
Scalar shifted_by_radii(const FramedPair& pair, Scalar core, Scalar outward);

/// A lower bound on the signed distance of the rounded bodies from `core_lower`, one on their
/// cores': for convex cores the rounded bodies' Minkowski difference is the cores' grown by a
/// ball of radius `r_a + r_b`, so the signed distance drops by exactly that. The subtraction's
/// rounding is bounded and taken off, so the bound stays proven. `core_lower` itself (to the
/// bit) for two polyhedra.
/// Inline, so that the solvers' stop tests (several per query) pay one comparison for two
/// polyhedra.
inline Scalar rounded_lower(const FramedPair& pair, Scalar core_lower) {
  if (!rounded(pair)) return core_lower;
  // A curved pair's also loses `pair.support_error`: its separations are measured at support
  // points that may fall that short of the support function. Here rather than in
  // shifted_by_radii: its stop tests come here at every step.
  if (pair.support_error > 0 && std::isfinite(core_lower)) {
    const Scalar value = core_lower - (pair.radius_a + pair.radius_b);
    return next_down(value - subtraction_rounding(pair, core_lower) - pair.support_error);
  }
  return shifted_by_radii(pair, core_lower, -1);
}
/// The same for an upper bound: `core_upper - r_a - r_b`, rounded up.
inline Scalar rounded_upper(const FramedPair& pair, Scalar core_upper) {
  if (!rounded(pair)) return core_upper;
  // Without radii, shifted_by_radii subtracts 0 exactly and returns the bound itself.
  if (pair.radius_a == 0 && pair.radius_b == 0) return core_upper;
  return shifted_by_radii(pair, core_upper, 1);
}

namespace rounding_detail {

// The rounding error of the sum `sum` computed as `a + b` (Knuth's TwoSum: exact).
inline Scalar sum_error(Scalar a, Scalar b, Scalar sum) {
  const Scalar b_part = sum - a;
  const Scalar a_part = sum - b_part;
  return (a - a_part) + (b - b_part);
}

// A radius that may have lost bits when it was scaled into the frame.
inline bool underflowed(Scalar radius) {
  return radius > 0 && radius < std::numeric_limits<Scalar>::min();
}

// shifted_by_radii with the radii's sum `radii` given, and whether it is exact (`exact_sum`, from
// sum_error). Moved by nothing when the sum and the difference are proven exact: sphere radii and
// distances such as 1.5 stay 1.5. Always inline: the searches' stop tests call shifted_by_radii
// at every step.
[[gnu::always_inline]] inline Scalar shifted(const FramedPair& pair, Scalar core, Scalar outward,
                                             Scalar radii, bool exact_sum) {
  const Scalar value = core - radii;
  if (!std::isfinite(core)) return value;
  const bool exact = exact_sum && sum_error(core, -radii, value) == 0 &&
                     !underflowed(pair.radius_a) && !underflowed(pair.radius_b);
  if (exact) return value;
  // std::nextafter's value from the bits (next_down, negated for a step up): its libm call was a
  // third of this function's cost, which a ball's distance pays twice or more.
  const Scalar moved = value + outward * subtraction_rounding(pair, core);
  return outward > 0 ? -next_down(-moved) : next_down(moved);
}

}  // namespace rounding_detail

/// rounded_lower of `core_lower` and rounded_upper of `core_upper`, with the bounds they round:
/// for a closed form, which tests its goal on them and keeps them in its answer (Answer::rounded).
/// The upper bound's shifted_by_radii is inline (the same value): its call was some 20 of a
/// ball-cylinder query's instructions.
inline RoundedBounds rounded_bounds(const FramedPair& pair, Scalar core_lower, Scalar core_upper) {
  Scalar upper = core_upper;
  if (rounded(pair) && (pair.radius_a != 0 || pair.radius_b != 0)) {
    const Scalar radii = pair.radius_a + pair.radius_b;
    upper = rounding_detail::shifted(
        pair, core_upper, 1, radii,
        rounding_detail::sum_error(pair.radius_a, pair.radius_b, radii) == 0);
  }
  return {core_lower, core_upper, rounded_lower(pair, core_lower), upper};
}

/// rounded_bounds for a pair without support error (`pair.support_error == 0`: no curved body),
/// the same values: both bounds shifted by the radii (shifted_by_radii, which moves neither
/// without radii), testing the radii once. For balls' and capsules' closed forms, inline there:
/// its call was some 15 of a ball-box query's instructions.
inline RoundedBounds shifted_bounds(const FramedPair& pair, Scalar core_lower, Scalar core_upper) {
  const Scalar radii = pair.radius_a + pair.radius_b;
  const bool exact_sum = rounding_detail::sum_error(pair.radius_a, pair.radius_b, radii) == 0;
  return {core_lower, core_upper, rounding_detail::shifted(pair, core_lower, -1, radii, exact_sum),
          rounding_detail::shifted(pair, core_upper, 1, radii, exact_sum)};
}

/// Turns `answer`, found on the cores of `pair` for `goal`, into the rounded bodies' answer, in
/// place: both bounds (and the history) by rounded_lower and rounded_upper; the witnesses moved
/// out to the surfaces, `point_a + r_a n` and `point_b - r_b n` along the unit normal n (the
/// contact normal of a signed distance, else the witnesses' own direction). For a distance or
/// a verdict whose cores are within `r_a + r_b` of each other, the rounded bodies overlap: the
/// distance is then 0, both witnesses the point that splits the cores' witnesses in the ratio of
/// the radii (within both rounded bodies), and the overlap counts as an intersection proof when
/// the bound shows it beyond rounding. The weights stay those of the cores' witnesses. Nothing
/// changes for two polyhedra. Bounds that `answer.rounded` holds rounded already are taken from
/// it.
void round_answer(const FramedPair& pair, Goal goal, Answer& answer);

}  // namespace swarmcollide::detail
