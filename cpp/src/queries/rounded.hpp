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

/// The double next below the positive finite `x` (std::nextafter(x, 0)).
inline Scalar next_towards_zero(Scalar x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  --bits;
  std::memcpy(&x, &bits, sizeof bits);
  return x;
}
/// The double next above the positive `x` below the largest (std::nextafter(x, infinity)).
inline Scalar next_away_from_zero(Scalar x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  ++bits;
  std::memcpy(&x, &bits, sizeof bits);
  return x;
}

/// `core - r_a - r_b` moved `outward` (-1 down, +1 up) by a bound on its rounding, for a rounded
/// pair: what rounded_lower and rounded_upper return when a radius is not zero. A lower bound
/// (outward -1) also loses `pair.support_error`: the separations of curved bodies are measured at
/// support points that may fall that short of the support function.
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
  // Two bodies without radii, one curved at least (curved-curved and curved-polyhedron pairs,
  // whose stop tests come here at every step): shifted_by_radii's arithmetic inline, its
  // subtraction of r_a + r_b = 0 left out (it is exact), and the next double down taken from the
  // bits instead of libm's nextafter. The same double, a fifth of the instructions.
  if (pair.radius_a == 0 && pair.radius_b == 0 && pair.support_error > 0) {
    constexpr Scalar kLargest = std::numeric_limits<Scalar>::max();
    const Scalar value = core_lower - (4 * kRoundoff * std::abs(core_lower) +
                                       4 * std::numeric_limits<Scalar>::denorm_min()) -
                         pair.support_error;
    if (value > 0 && value <= kLargest) return next_towards_zero(value);
    if (value < 0 && value > -kLargest) return -next_away_from_zero(-value);
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

/// Turns `answer`, found on the cores of `pair` for `goal`, into the rounded bodies' answer, in
/// place: both bounds (and the history) by rounded_lower and rounded_upper; the witnesses moved
/// out to the surfaces, `point_a + r_a n` and `point_b - r_b n` along the unit normal n (the
/// contact normal of a signed distance, else the witnesses' own direction). For a distance or
/// a verdict whose cores are within `r_a + r_b` of each other, the rounded bodies overlap: the
/// distance is then 0, both witnesses the point that splits the cores' witnesses in the ratio of
/// the radii (within both rounded bodies), and the overlap counts as an intersection proof when
/// the bound shows it beyond rounding. The weights stay those of the cores' witnesses. Nothing
/// changes for two polyhedra.
void round_answer(const FramedPair& pair, Goal goal, Answer& answer);

}  // namespace swarmcollide::detail
