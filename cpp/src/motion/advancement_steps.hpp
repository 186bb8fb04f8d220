// The time steps of conservative advancement, rounded so that a step never reaches past what
// its bound proves; shared by time_of_impact and the robot's motion check, private to the
// library's sources.
#pragma once

#include <cmath>
#include <limits>

#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// `t + span` rounded down, so that the time it names is no later than the exact sum.
inline Scalar advanced(Scalar t, Scalar span) {
  constexpr Scalar kUnit = 0x1p-53;
  Scalar next = t + span * (1 - 4 * kUnit);
  // Up to t + 3 span the difference with t is exact only when next <= 2 t (Sterbenz); larger
  // steps lose at most a roundoff of next <= t + span, which the 4 taken off above cover.
  if (next <= 2 * t) {
    while (next > t && next - t > span) next = std::nextafter(next, t);
  }
  return next;
}

/// The time a gap `apart` lasts at most `speed` of closing, rounded down: 0 for no gap, infinite
/// for no closing.
inline Scalar reach_over(Scalar apart, Scalar speed) {
  constexpr Scalar kUnit = 0x1p-53;
  if (!(apart > 0)) return 0;
  if (speed == 0) return std::numeric_limits<Scalar>::infinity();
  return apart / speed * (1 - 4 * kUnit);
}

}  // namespace swarmcollide::detail
