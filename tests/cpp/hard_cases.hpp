#pragma once

#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include "paper_cases.hpp"
#include "swarmcollide/geometry/convex_polyhedron.hpp"

namespace swarmcollide::testing {

/// A pair with a known distance, of the kind on which distance solvers have been wrong.
struct HardCase {
  std::string name;
  ConvexPolyhedron a;
  ConvexPolyhedron b;
  Scalar distance;
  /// How close an exact solver gets in double precision.
  Scalar accuracy;
};

inline ConvexPolyhedron box(const Vector3& lo, const Vector3& hi) {
  VertexMatrix v(8, 3);
  for (int k = 0; k < 8; ++k) {
    v.row(k) << (k & 1 ? hi.x() : lo.x()), (k & 2 ? hi.y() : lo.y()), (k & 4 ? hi.z() : lo.z());
  }
  return ConvexPolyhedron(v);
}

inline ConvexPolyhedron moved(const ConvexPolyhedron& body, const Vector3& offset) {
  VertexMatrix v = body.vertices();
  v.rowwise() += offset.transpose();
  return ConvexPolyhedron(v);
}

inline ConvexPolyhedron point_set(std::initializer_list<Vector3> list) {
  VertexMatrix v(static_cast<Eigen::Index>(list.size()), 3);
  Eigen::Index i = 0;
  for (const Vector3& p : list) v.row(i++) = p.transpose();
  return ConvexPolyhedron(v);
}

/// Touching, nearly touching and parallel faces (whose nearest points are not unique, so the
/// nearest-point subproblems are flat), a size ratio of a million, coordinates a million from the
/// origin, repeated points, and flat, collinear and single-point bodies.
inline std::vector<HardCase> hard_cases() {
  const ConvexPolyhedron unit = box({0, 0, 0}, {1, 1, 1});
  const Vector3 far(1e6, -1e6, 1e6);
  VertexMatrix repeated(9, 3);
  repeated << 1, -1, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0, 1, -1, 0, 1, -1, 0, 2, -2, 0, 0.5, -1.5, 0.2,
      0, -2, 0;
  const ConvexPolyhedron segment = point_set({{-1, 0, 1}, {1, 0, 1}});
  const ConvexPolyhedron crossing_segment = point_set({{0, -1, 3}, {0, 1, 3}});
  const ConvexPolyhedron square = point_set({{-1, -1, 2}, {1, -1, 2}, {1, 1, 2}, {-1, 1, 2}});
  return {
      {"touching faces", unit, box({1, 0.2, 0.3}, {2, 1.2, 1.3}), 0, 1e-14},
      {"faces 1e-12 apart", unit, box({1 + 1e-12, 0.2, 0.3}, {2, 1.2, 1.3}), 1e-12, 1e-15},
      {"faces 1e-6 apart", unit, box({1 + 1e-6, 0.2, 0.3}, {2, 1.2, 1.3}), 1e-6, 1e-15},
      {"stacked cubes", unit, box({0.3, 0, 3}, {1.3, 1, 4}), 2, 1e-12},
      {"size ratio 1e6", box({0, 0, 0}, {1e6, 1e6, 1e6}),
       moved(paper_a(), Vector3(1e6 + 1, 3e5, 2e5)), 1, 1e-8},
      {"offset 1e6, apart", moved(paper_a(), far), moved(paper_b_separate(), far), 1, 1e-9},
      {"offset 1e6, touching", moved(paper_a(), far), moved(paper_b_colliding(), far), 0, 1e-9},
      {"repeated points", paper_a(), ConvexPolyhedron(repeated), 1, 1e-12},
      {"point to solid", paper_a(), point_set({{3, 3, 3}}), 8 / std::sqrt(3.0), 1e-12},
      {"skew segments", segment, crossing_segment, 2, 1e-12},
      {"square to segment", square, crossing_segment, 1, 1e-12},
      {"segment through a solid", paper_a(), point_set({{0.2, 0.2, -1}, {0.2, 0.2, 3}}), 0, 1e-12},
  };
}

}  // namespace swarmcollide::testing
