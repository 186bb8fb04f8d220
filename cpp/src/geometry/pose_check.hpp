// Pose validation for callers that know already whether the rotation is the identity; private
// to the library's sources.
#pragma once

#include "swarmcollide/geometry/pose.hpp"

namespace swarmcollide::detail {

/// What validate_pose checks, for a pose whose rotation is the identity exactly when `turned` is
/// false (`turned == !pose.has_identity_rotation()`): framing a pair needs that test anyway, so it
/// is made once. False where validate_pose would throw.
bool valid_pose(const Pose& pose, bool turned);

}  // namespace swarmcollide::detail
