#pragma once

#include "swarmcollide/geometry/convex_polyhedron.hpp"
#include "swarmcollide/solvers/distance_result.hpp"
#include "swarmcollide/solvers/dual_options.hpp"

namespace swarmcollide {

/// Distance by the dual of model (2): the maximum over unit directions `n` of the separation
/// `s(n) = min_j n.y_j - max_i n.x_i` (see `separation`), a function of two parameters whatever
/// the vertex count, searched by the paper's rank-adaptive swarm (8)-(11) over an exponential
/// chart of the sphere. Support points come from `ConvexPolyhedron::support_index(d, start)`,
/// warm-started per particle.
///
/// Exact finish: the nearest points of the supporting features along the best direction (points
/// within the feature slack of each supporting plane), by Wolfe's algorithm as in
/// `exact_nearest_points`, give weights (an upper bound) and a direction (a new lower bound).
/// When no separating direction is found, a common point is sought by Wolfe's algorithm on the
/// Minkowski difference, started from the swarm's direction. A warmed-up solve allocates only the
/// result's arrays (its buffers are thread-local). Verdicts are certified: separate by a direction
/// with `s(n) > tolerance`, colliding by witness points within `tolerance` of each other. `method`
/// is "dual"; deterministic for a given seed. Throws std::invalid_argument for invalid options.
DistanceResult solve_dual(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                          const DualOptions& options = {});

/// Signed distance by the dual: `solve_dual` when the bodies are apart; for overlapping ones the
/// maximum of `s`, minus the penetration depth, found by further swarm rounds with a finish that
/// tries the facet normals of the Minkowski difference spanned by the supporting features (face
/// normals of either body and cross products of an edge of each). Fields as `signed_distance`.
DistanceResult dual_signed_distance(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                                    const DualOptions& options = {});

}  // namespace swarmcollide
