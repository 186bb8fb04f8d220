#pragma once

#include <cstddef>
#include <random>

#include "swarmcollide/geometry/convex_polyhedron.hpp"

// The hull's vertices of n points drawn uniformly on the unit sphere, moved by `shift` along x:
// the separated pairs of swarm_speed.cpp and swarm_targets.cpp.
inline swarmcollide::VertexMatrix sphere_polytope(int n, std::mt19937_64& rng, double shift) {
  std::normal_distribution<double> normal;
  swarmcollide::VertexMatrix points(n, 3);
  for (int i = 0; i < n; ++i) {
    const swarmcollide::Vector3 v(normal(rng), normal(rng), normal(rng));
    points.row(i) = v.normalized().transpose();
  }
  const swarmcollide::ConvexPolyhedron body(points);
  const auto& hull = body.hull().vertex_indices;
  swarmcollide::VertexMatrix vertices(hull.size(), 3);
  for (std::size_t k = 0; k < hull.size(); ++k) vertices.row(k) = points.row(hull[k]);
  vertices.col(0).array() += shift;
  return vertices;
}
