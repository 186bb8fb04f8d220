// Rounded bodies: what the solvers find on the cores, made the rounded bodies' answer; private
// to the library's sources.
#pragma once

#include "../geometry/framed_body.hpp"
#include "../solvers/answer.hpp"

namespace swarmcollide::detail {

/// True when either body of `pair` is rounded (ConvexPolyhedron::radius() > 0) or curved (whose
/// support points may fall short: FramedPair::support_error).
inline bool rounded(const FramedPair& pair) { return pair.adjusted; }

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
  return rounded(pair) ? shifted_by_radii(pair, core_lower, -1) : core_lower;
}
/// The same for an upper bound: `core_upper - r_a - r_b`, rounded up.
inline Scalar rounded_upper(const FramedPair& pair, Scalar core_upper) {
  return rounded(pair) ? shifted_by_radii(pair, core_upper, 1) : core_upper;
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
