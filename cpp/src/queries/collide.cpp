#include "swarmcollide/queries/collide.hpp"

#include "swarmcollide/queries/signed_distance.hpp"
#include "swarmcollide/solvers/fcl_distance.hpp"
#include "swarmcollide/solvers/libccd_penetration.hpp"

namespace swarmcollide {

Scalar collision_tolerance(const DistanceOptions& options) {
  switch (options.method) {
    case Method::ipso:
    case Method::pso:
      return options.swarm.tolerance;
    case Method::penalty:
      return options.penalty.tolerance;
    case Method::dual:
      // Zero means relative to the bodies' size, which this function does not see.
      if (options.dual.tolerance > 0) return options.dual.tolerance;
      break;
    case Method::fcl:
    case Method::fcl_indep:
    case Method::libccd:
      break;
  }
  return options.exact.tolerance;
}

DistanceResult collision(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                         const DistanceOptions& options, bool escalate) {
  DistanceResult result =
      options.method == Method::libccd ? signed_distance(a, b, options) : distance(a, b, options);
  if (result.certified || !escalate) return result;
  ExactOptions exact = options.exact;
  exact.tolerance = collision_tolerance(options);
  DistanceResult decided = fcl_distance(a, b, FclGjk::libccd, exact);
  decided.escalated_from = result.method;
  return decided;
}

bool collide(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const DistanceOptions& options,
             bool escalate) {
  // libccd's GJK intersection test answers without a penetration depth; its "no" is already
  // confirmed by an exact distance.
  if (options.method == Method::libccd) return libccd_intersect(a, b, options.exact);
  return collision(a, b, options, escalate).colliding;
}

}  // namespace swarmcollide
