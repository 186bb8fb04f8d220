#include "swarmcollide/queries/distance.hpp"

#include <stdexcept>

#include "swarmcollide/solvers/swarm.hpp"

namespace swarmcollide {

std::string method_name(Method method) {
  switch (method) {
    case Method::ipso:
      return "ipso";
    case Method::pso:
      return "pso";
  }
  throw std::invalid_argument("unknown method");
}

Method method_from_name(const std::string& name) {
  for (Method m : {Method::ipso, Method::pso}) {
    if (method_name(m) == name) return m;
  }
  throw std::invalid_argument("unknown method '" + name + "'; choose one of: 'ipso', 'pso'");
}

DistanceResult distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                        const DistanceOptions& options) {
  SwarmOptions swarm = options.swarm;
  swarm.inertia = options.method == Method::ipso ? InertiaStrategy::rank_adaptive
                                                 : InertiaStrategy::linear_decreasing;
  return solve_swarm(a, b, swarm);
}

bool collide(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
             const DistanceOptions& options) {
  return distance(a, b, options).colliding;
}

}  // namespace swarmcollide
