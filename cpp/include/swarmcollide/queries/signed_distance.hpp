#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/queries/distance.hpp"
#include "swarmcollide/solvers/distance_result.hpp"

namespace swarmcollide {

/// Signed distance: the distance when the bodies are apart, minus the penetration depth (the
/// shortest translation of B that separates them) when they overlap.
///
/// For either sign, `point_b - point_a = distance * direction`: `direction` is the unit contact
/// normal pointing from A to B, `point_a` (`point_b`) lies on A's (B's) supporting feature along
/// `direction` (`-direction`), and the weights reproduce them. `lower_bound` is
/// `separation(a, b, direction)` and is not clamped: for overlapping bodies it is minus the
/// overlap along the normal, a lower bound on the signed distance; `distance` is never below it.
/// `colliding` is `distance <= tolerance`.
///
/// Methods "fcl" and "fcl-indep" use FCL (EPA through GST_LIBCCD for overlapping pairs, in both),
/// "libccd" uses libccd's penetration depth, "dual" the maximum separation over directions (see
/// `dual_signed_distance`). Throws std::invalid_argument for the swarm and
/// penalty methods, which do not measure penetration.
DistanceResult signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                               const DistanceOptions& options = {});

}  // namespace swarmcollide
