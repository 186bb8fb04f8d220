#pragma once

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// An axis-aligned bounding box.
struct Aabb {
  Vector3 min;
  Vector3 max;
};

}  // namespace swarmcollide
