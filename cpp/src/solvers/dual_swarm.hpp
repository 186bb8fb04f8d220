// The paper's swarm over separating directions (method "dual"); private to the library.
#pragma once

#include "../geometry/framed_body.hpp"
#include "answer.hpp"
#include "swarmcollide/queries/options.hpp"

namespace swarmcollide::detail {

/// Distance by the dual of model (2): the maximum over unit directions `n` of the separation
/// `s(n) = min_j n.y_j - max_i n.x_i`, a function of two parameters whatever the vertex count,
/// searched by the paper's rank-adaptive swarm (8)-(11) over an exponential chart of the sphere.
///
/// The search starts with Wolfe's algorithm on the whole Minkowski difference (GJK with Wolfe's
/// corrals) from the direction between the bodies' centres, its supports climbing the hulls of
/// large bodies from the previous ones: its corrals give weights (an upper bound) and its
/// directions separations (lower bounds), and it stops as soon as these settle the goal (for a
/// verdict, at the first separating direction or proven common point). That settles almost
/// every pair; the swarm runs only where it stops short (rounding, its iteration cap). Exact
/// finish of the swarm's directions: the nearest points of the supporting features along the
/// best direction (points within the feature slack of each supporting plane), by Wolfe's
/// algorithm, give weights and a direction (a new lower bound). For signed distances of
/// overlapping bodies the exact penetration solver proves the depth from the best direction.
/// A warmed-up distance solve allocates only its answer's arrays (its buffers are thread-local).
/// Deterministic for a given seed. A verdict whose witnesses prove contact carries no
/// intersection proof (see DualStart::enclosure).
Answer solve_dual(const FramedPair& pair, const QueryOptions& options, Goal goal);

/// Where a dual search starts: a unit direction from A to B (frame coordinates) and the support
/// points along it from which hill climbing starts (-1: none).
struct DualStart {
  Vector3 direction = Vector3::UnitX();
  int support_a = -1;
  int support_b = -1;
  /// Whether a verdict proven by a common point keeps the tetrahedron that encloses the origin
  /// (`intersection_proven`) where witnesses within the tolerance prove contact already: a scene
  /// caches it for the pair's next frame, a compound screen reads it. `solve_dual` without a
  /// start keeps none (the query layer's verdicts read only the bounds).
  bool enclosure = true;
};

/// `solve_dual` started from `start` (its direction and support points) instead of the direction
/// between the bodies' centres. A scene passes the direction that separated (or nearly
/// separated) the pair in the previous frame, or the centres' direction that it found not to
/// separate them: after a small motion Wolfe's algorithm from it usually settles the pair in a
/// few steps. Otherwise the search, its bounds and the verdicts made of them are `solve_dual`'s.
Answer solve_dual(const FramedPair& pair, const QueryOptions& options, Goal goal,
                  const DualStart& start);

}  // namespace swarmcollide::detail
