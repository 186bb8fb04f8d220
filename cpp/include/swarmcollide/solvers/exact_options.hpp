#pragma once

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Which libccd routine measures penetration depth.
enum class PenetrationAlgorithm {
  /// GJK followed by the expanding polytope algorithm (ccdGJKPenetration).
  epa,
  /// Minkowski portal refinement (ccdMPRPenetration).
  mpr,
};

/// Parameters of the exact reference methods ("fcl", "fcl-indep", "libccd").
struct ExactOptions {
  /// FCL's GJK stopping threshold (`fcl::DistanceRequest::distance_tolerance`).
  Scalar distance_tolerance = 1e-10;
  /// libccd's `epa_tolerance` and `mpr_tolerance` (its default 1e-4 gives depths only to ~1e-4;
  /// this one makes them agree with FCL's to ~1e-6 relative).
  Scalar penetration_tolerance = 1e-12;
  /// Iteration cap of libccd's routines and of the library's own nearest-point solver.
  int max_iterations = 1000;
  /// Absolute distance at or below which the bodies count as colliding (`colliding`,
  /// `certified`); rounding in the witness points is about 1e-16 times the coordinates.
  Scalar tolerance = 1e-9;
  /// Penetration routine of the "libccd" method.
  PenetrationAlgorithm penetration = PenetrationAlgorithm::epa;

  /// Throws std::invalid_argument naming the first invalid field.
  void validate() const;
};

}  // namespace swarmcollide
