#include "swarmcollide/queries/distance.hpp"

#include <stdexcept>

#include "swarmcollide/solvers/dual.hpp"
#include "swarmcollide/solvers/fcl_distance.hpp"
#include "swarmcollide/solvers/penalty.hpp"
#include "swarmcollide/solvers/swarm.hpp"

namespace swarmcollide {

std::string method_name(Method method) {
  switch (method) {
    case Method::ipso:
      return "ipso";
    case Method::pso:
      return "pso";
    case Method::penalty:
      return "penalty";
    case Method::fcl:
      return "fcl";
    case Method::fcl_indep:
      return "fcl-indep";
    case Method::libccd:
      return "libccd";
    case Method::dual:
      return "dual";
  }
  throw std::invalid_argument("unknown method");
}

Method method_from_name(const std::string& name) {
  for (Method m : {Method::ipso, Method::pso, Method::penalty, Method::fcl, Method::fcl_indep,
                   Method::libccd, Method::dual}) {
    if (method_name(m) == name) return m;
  }
  throw std::invalid_argument("unknown method '" + name +
                              "'; choose one of: 'ipso', 'pso', 'penalty', 'fcl', 'fcl-indep', "
                              "'libccd', 'dual'");
}

DistanceResult distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                        const DistanceOptions& options) {
  switch (options.method) {
    case Method::penalty:
      return solve_penalty(a, b, options.penalty);
    case Method::fcl:
      return fcl_distance(a, b, FclGjk::libccd, options.exact);
    case Method::fcl_indep:
      return fcl_distance(a, b, FclGjk::indep, options.exact);
    case Method::dual:
      return solve_dual(a, b, options.dual);
    case Method::libccd:
      throw std::invalid_argument(
          "method 'libccd' has no distance function (libccd only tests intersection and "
          "measures penetration); use method 'fcl' for an exact distance, or 'ipso'/'pso', or "
          "collide()/signed_distance() with 'libccd'");
    case Method::ipso:
    case Method::pso:
      break;
  }
  SwarmOptions swarm = options.swarm;
  swarm.inertia = options.method == Method::ipso ? InertiaStrategy::rank_adaptive
                                                 : InertiaStrategy::linear_decreasing;
  return solve_swarm(a, b, swarm);
}

}  // namespace swarmcollide
