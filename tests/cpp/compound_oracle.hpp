// The compound queries' oracle: every part pair answered by the convex query.
#pragma once

#include <limits>

#include "swarmcollide/geometry/compound_body.hpp"
#include "swarmcollide/geometry/pose.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide::testing {

/// The smallest distance (or signed distance) over every pair of a part of `a` and a part of
/// `b`, as the convex query answers each; `each` sees every part pair's answer.
template <typename Each>
DistanceResult best_part_pair(const Query& query, const CompoundBody& a, const Pose& pose_a,
                              const CompoundBody& b, const Pose& pose_b, bool signed_distance,
                              const Each& each) {
  DistanceResult best;
  best.distance = std::numeric_limits<Scalar>::infinity();
  for (const ConvexPolyhedron& pa : a.parts()) {
    for (const ConvexPolyhedron& pb : b.parts()) {
      const DistanceResult r = signed_distance ? query.signed_distance(pa, pose_a, pb, pose_b)
                                               : query.distance(pa, pose_a, pb, pose_b);
      each(r);
      if (r.distance < best.distance) best = r;
    }
  }
  return best;
}

inline DistanceResult best_part_pair(const Query& query, const CompoundBody& a, const Pose& pose_a,
                                     const CompoundBody& b, const Pose& pose_b,
                                     bool signed_distance) {
  return best_part_pair(query, a, pose_a, b, pose_b, signed_distance, [](const DistanceResult&) {});
}

}  // namespace swarmcollide::testing
