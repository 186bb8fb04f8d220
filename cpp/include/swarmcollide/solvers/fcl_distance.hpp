#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/solvers/distance_result.hpp"
#include "swarmcollide/solvers/exact_options.hpp"

namespace swarmcollide {

/// The GJK implementation FCL runs.
enum class FclGjk {
  /// `fcl::GST_LIBCCD`: libccd's GJK (distance) and EPA (signed distance). Method "fcl".
  libccd,
  /// `fcl::GST_INDEP`: FCL's own GJK. Method "fcl-indep".
  indep,
};

/// Distance by FCL 0.7 between `fcl::Convexd` shapes built from the bodies' Qhull hulls (shifted
/// so the pair is near the origin). FCL's answer is taken when it is positive and certified
/// optimal to rounding by the separation along its witness points; otherwise (FCL reports -1
/// without witnesses for touching and overlapping pairs, and GST_LIBCCD misses the optimum for
/// some flat, collinear and single-point hulls) the answer comes from `exact_nearest_points`.
/// Weights are those of the nearest points on the supporting features (see `exact_options.hpp`).
/// `method` is "fcl" or "fcl-indep"; `status` is `exact`.
DistanceResult fcl_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b, FclGjk gjk,
                            const ExactOptions& options = {});

/// Signed distance by FCL: `fcl_distance` when the bodies are apart; for colliding ones FCL's
/// signed distance with GST_LIBCCD (EPA) whatever `gjk` is, since GST_INDEP's signed distance
/// aborts on overlapping Convex pairs in Debian's libfcl. See `signed_distance`.
DistanceResult fcl_signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b, FclGjk gjk,
                                   const ExactOptions& options = {});

}  // namespace swarmcollide
