// What the coal benches share: the conversion of a body to coal's convex shape, and how they end.
#pragma once

#include <coal/shape/convex.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "swarmcollide/geometry/convex_polyhedron.hpp"

/// The body's hull as a coal::Convex with its triangles (so coal builds its vertex neighbours
/// and support warm starts), its points numbered as coal's users number a mesh's hull, built once.
inline std::shared_ptr<coal::Convex<coal::Triangle>> to_coal(
    const swarmcollide::ConvexPolyhedron& body) {
  const swarmcollide::Hull& hull = body.hull();
  std::vector<int> local(body.size(), -1);
  auto points = std::make_shared<std::vector<coal::Vec3s>>();
  for (int i : hull.vertex_indices) {
    local[i] = static_cast<int>(points->size());
    points->push_back(body.vertices().row(i).transpose());
  }
  auto triangles = std::make_shared<std::vector<coal::Triangle>>();
  for (Eigen::Index f = 0; f < hull.faces.rows(); ++f) {
    triangles->emplace_back(local[hull.faces(f, 0)], local[hull.faces(f, 1)],
                            local[hull.faces(f, 2)]);
  }
  auto shape = std::make_shared<coal::Convex<coal::Triangle>>(
      points, static_cast<unsigned>(points->size()), triangles,
      static_cast<unsigned>(triangles->size()));
  shape->computeLocalAABB();
  return shape;
}

/// Ends the process without running the libraries' static destructors. Two octomap versions are
/// loaded (Debian's, which FCL links, and coal's own), and their static objects share symbols:
/// exit would destroy one of them twice ("free(): double free detected", an abort).
[[noreturn]] inline void leave(int status) {
  std::fflush(stdout);
  std::fflush(stderr);
  std::_Exit(status);
}
