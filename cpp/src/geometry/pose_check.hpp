// Pose validation for callers that know already whether the rotation is the identity; private
// to the library's sources.
#pragma once

#include <cstdint>
#include <cstring>

#include "swarmcollide/geometry/pose.hpp"

namespace swarmcollide::detail {

/// What validate_pose checks, for a pose whose rotation is the identity exactly when `turned` is
/// false (`turned == !pose.has_identity_rotation()`): framing a pair needs that test anyway, so it
/// is made once. False where validate_pose would throw.
bool valid_pose(const Pose& pose, bool turned);

/// True when `x` and `y` hold the same bits: the same object, or a copy of it. Validation (and
/// the identity test) reads nothing but those bits, so a pair whose bodies share a pose checks it
/// once. Word by word, the first differing one ends the test (most often the first), where a
/// rotation's check is some 115 instructions.
inline bool same_pose(const Pose& x, const Pose& y) {
  if (&x == &y) return true;
  const auto same = [](const Scalar* u, const Scalar* v, int count) {
    for (int k = 0; k < count; ++k) {
      std::uint64_t a;
      std::uint64_t b;
      std::memcpy(&a, u + k, sizeof a);
      std::memcpy(&b, v + k, sizeof b);
      if (a != b) return false;
    }
    return true;
  };
  return same(x.rotation.data(), y.rotation.data(), 9) &&
         same(x.translation.data(), y.translation.data(), 3);
}

}  // namespace swarmcollide::detail
