#pragma once

#include <string>

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/solvers/distance_result.hpp"
#include "swarmcollide/solvers/dual_options.hpp"
#include "swarmcollide/solvers/exact_options.hpp"
#include "swarmcollide/solvers/penalty_options.hpp"
#include "swarmcollide/solvers/swarm_options.hpp"

namespace swarmcollide {

/// The solvers behind `distance` and `collide`.
enum class Method {
  /// The paper's improved PSO (rank-adaptive inertia, (8)-(9)).
  ipso,
  /// The standard PSO with linearly decreasing inertia (7).
  pso,
  /// The paper's penalty-function baseline: exterior quadratic penalty with L-BFGS.
  penalty,
  /// Exact reference: FCL's GJK through libccd (GST_LIBCCD), with an exact fallback.
  fcl,
  /// Exact reference: FCL's own GJK (GST_INDEP), with an exact fallback.
  fcl_indep,
  /// Exact reference for `collide` and `signed_distance` only: libccd has no distance function.
  libccd,
  /// The paper's improved PSO over separating directions (the dual of (2)) with an exact finish
  /// on the supporting features; certified to `DualOptions::tolerance`.
  dual,
};

/// The name of a method as the Python API spells it ("ipso", "pso", "penalty", "fcl",
/// "fcl-indep", "libccd", "dual").
std::string method_name(Method method);
/// The method of a given name; throws std::invalid_argument listing the valid names.
Method method_from_name(const std::string& name);

/// Options of a distance query: the method and the parameters of its solver.
struct DistanceOptions {
  Method method = Method::ipso;
  /// Used by the swarm methods; `inertia` is set from `method`.
  SwarmOptions swarm;
  /// Used by the penalty method.
  PenaltyOptions penalty;
  /// Used by the exact methods ("fcl", "fcl-indep", "libccd").
  ExactOptions exact;
  /// Used by the dual method.
  DualOptions dual;
};

/// Distance between two convex polyhedra, model (2). Throws std::invalid_argument for
/// `Method::libccd`, which has no distance function (use "fcl" or a swarm method).
DistanceResult distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                        const DistanceOptions& options = {});

}  // namespace swarmcollide
