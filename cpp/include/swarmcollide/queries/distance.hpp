#pragma once

#include <string>

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/solvers/distance_result.hpp"
#include "swarmcollide/solvers/swarm_options.hpp"

namespace swarmcollide {

/// The solvers behind `distance` and `collide`.
enum class Method {
  /// The paper's improved PSO (rank-adaptive inertia, (8)-(9)).
  ipso,
  /// The standard PSO with linearly decreasing inertia (7).
  pso,
};

/// The name of a method as the Python API spells it ("ipso", "pso").
std::string method_name(Method method);
/// The method of a given name; throws std::invalid_argument listing the valid names.
Method method_from_name(const std::string& name);

/// Options of a distance query: the method and the parameters of its solver.
struct DistanceOptions {
  Method method = Method::ipso;
  /// Used by the swarm methods; `inertia` is set from `method`.
  SwarmOptions swarm;
};

/// Distance between two convex polyhedra, model (2).
DistanceResult distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                        const DistanceOptions& options = {});

/// True when the bodies are found to intersect (`distance(a, b).colliding`).
bool collide(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
             const DistanceOptions& options = {});

}  // namespace swarmcollide
