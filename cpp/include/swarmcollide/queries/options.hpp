#pragma once

#include <cstdint>

#include "swarmcollide/solvers/dual_options.hpp"
#include "swarmcollide/solvers/exact_options.hpp"
#include "swarmcollide/solvers/penalty_options.hpp"
#include "swarmcollide/solvers/swarm_options.hpp"
#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// The solvers a query can use; `method_table()` (methods.hpp) says what each answers.
enum class Method {
  /// The paper's rank-adaptive swarm (8)-(11) over separating directions (the dual of (2)) with
  /// an exact finish: certified. The default.
  dual,
  /// The paper's improved PSO on model (2): rank-adaptive inertia and acceleration, (8)-(9).
  ipso,
  /// The standard PSO on model (2) with linearly decreasing inertia (7).
  pso,
  /// The paper's penalty-function baseline: exterior quadratic penalty minimised by L-BFGS.
  penalty,
  /// The library's own exact solvers: Wolfe's nearest-point algorithm and a certified
  /// penetration depth.
  exact,
  /// FCL's GJK (its own implementation), checked by the library's certificate.
  fcl,
  /// libccd's GJK intersection test and EPA penetration depth, checked by the certificate.
  libccd,
};

/// Default relative tolerance of every query: answers are certified to 1e-9 of the pair's size.
inline constexpr Scalar kDefaultTolerance = 1e-9;

/// Everything a query needs besides the bodies: the method, the one tolerance, the one seed and
/// the parameters of each solver (only the method's own are read).
///
/// `tolerance` is relative to the size of the pair (the diameter of a ball around both bodies),
/// so an answer does not depend on the unit of length. It is both the precision and the contact
/// threshold: a query stops once its bounds are within `tolerance * size` of each other, and two
/// bodies count as colliding when they are proven to be within `tolerance * size` of each other.
/// Zero is valid: the answer is then as exact as double precision can prove it.
struct QueryOptions {
  Method method = Method::dual;
  Scalar tolerance = kDefaultTolerance;
  /// Seeds the randomised methods; answers are reproducible for a given seed.
  std::uint64_t seed = 0;
  SwarmOptions swarm;
  PenaltyOptions penalty;
  DualOptions dual;
  ExactOptions exact;

  /// Throws std::invalid_argument naming the first invalid value of the method's parameters
  /// and the valid range (methods.hpp lists them).
  void validate() const;
};

}  // namespace swarmcollide
