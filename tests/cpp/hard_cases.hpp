// Pairs of the kinds on which distance and penetration solvers have been wrong, with their
// answers worked out by hand.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "paper_cases.hpp"
#include "shapes.hpp"

namespace swarmcollide::testing {

struct HardCase {
  std::string name;
  ConvexPolyhedron a;
  ConvexPolyhedron b;
  /// The distance and the signed distance (minus the penetration depth when overlapping).
  Scalar distance;
  Scalar signed_distance;
  /// How close an exact computation in double precision gets to them.
  Scalar accuracy;
};

/// Touching, nearly touching (1e-16 to 1e-6 apart) and parallel faces (whose nearest points are
/// not unique, so nearest-point subproblems are flat), stacked cubes, deep and shallow overlaps,
/// size ratios of a million, coordinates a million from the origin, repeated points, and flat,
/// collinear and single-point bodies, touching and overlapping.
inline std::vector<HardCase> hard_cases() {
  const ConvexPolyhedron unit = unit_cube();
  const Vector3 far(1e6, -1e6, 1e6);
  VertexMatrix repeated(9, 3);
  repeated << 1, -1, 0, 2, -2, 0, 0, -2, 2, 0, -2, 0, 1, -1, 0, 1, -1, 0, 2, -2, 0, 0.5, -1.5, 0.2,
      0, -2, 0;
  const ConvexPolyhedron segment = point_set({{-1, 0, 1}, {1, 0, 1}});
  const ConvexPolyhedron crossing_segment = point_set({{0, -1, 3}, {0, 1, 3}});
  const ConvexPolyhedron square = point_set({{-1, -1, 2}, {1, -1, 2}, {1, 1, 2}, {-1, 1, 2}});
  const ConvexPolyhedron tetrahedron = point_set({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  // Gaps as the doubles they are: 1 + 1e-12 is not exact, its difference from 1 is.
  const Scalar gap_12 = (1 + 1e-12) - 1;
  const Scalar gap_6 = (1 + 1e-6) - 1;
  return {
      {"touching faces", unit, box({1, 0.2, 0.3}, {2, 1.2, 1.3}), 0, 0, 1e-15},
      {"faces 1e-16 apart", box({-1, 0, 0}, {0, 1, 1}), box({1e-16, 0.2, 0.3}, {1, 1.2, 1.3}),
       1e-16, 1e-16, 1e-18},
      {"faces 1e-12 apart", unit, box({1 + 1e-12, 0.2, 0.3}, {2, 1.2, 1.3}), gap_12, gap_12, 1e-15},
      {"faces 1e-6 apart", unit, box({1 + 1e-6, 0.2, 0.3}, {2, 1.2, 1.3}), gap_6, gap_6, 1e-15},
      {"stacked cubes, touching", unit, box({0.3, 0.2, 1}, {1.3, 1.2, 2}), 0, 0, 1e-15},
      {"stacked cubes, apart", unit, box({0.3, 0, 3}, {1.3, 1, 4}), 2, 2, 1e-15},
      {"edge on edge", unit, moved(unit, {1, 1, 0}), 0, 0, 1e-15},
      {"vertex on vertex", tetrahedron, transformed(tetrahedron, -1, Vector3::Zero()), 0, 0, 1e-15},
      {"cubes overlapping by half", unit, moved(unit, {0.5, 0.25, 0.1}), 0, -0.5, 1e-15},
      // Offsets that are not binary fractions: the rounded corners leave face diagonals of the
      // two cubes a rounding away from parallel.
      {"cubes overlapping by tenths", unit, moved(unit, {0.1, 0.1, 0.4}), 0, -0.6, 1e-15},
      {"shallow overlap", unit, box({0.8, 0.1, 0.05}, {1.8, 0.9, 0.95}), 0, -0.2, 1e-15},
      {"needle through a plate", box({-1, -1, -1e-3}, {1, 1, 1e-3}),
       box({-1e-3, -1e-3, -1}, {1e-3, 1e-3, 1}), 0, -1.001, 1e-15},
      {"size ratio 1e6", box({0, 0, 0}, {1e6, 1e6, 1e6}),
       moved(paper_a(), Vector3(1e6 + 1, 3e5, 2e5)), 1, 1, 1e-9},
      {"tiny cube beside a tetrahedron", paper_a(), box({1 + 1e-6, 0, 0}, {1 + 2e-6, 1e-6, 1e-6}),
       gap_6, gap_6, 1e-15},
      {"offset 1e6, apart", moved(paper_a(), far), moved(paper_b_separate(), far), 1, 1, 1e-9},
      {"offset 1e6, touching", moved(paper_a(), far), moved(paper_b_colliding(), far), 0, 0, 1e-9},
      {"repeated points", paper_a(), ConvexPolyhedron(repeated), 1, 1, 1e-15},
      {"point to solid", paper_a(), point_set({{3, 3, 3}}), 8 / std::sqrt(3.0), 8 / std::sqrt(3.0),
       1e-14},
      {"point inside a solid", paper_a(), point_set({{0.1, 0.1, 0.1}}), 0, -0.1, 1e-15},
      {"one point twice", point_set({{1, 2, 3}}), point_set({{1, 2, 3}}), 0, 0, 0},
      {"skew segments", segment, crossing_segment, 2, 2, 1e-15},
      {"crossing segments", point_set({{-1, 0, 0}, {1, 0, 0}}), point_set({{0, -1, 0}, {0, 1, 0}}),
       0, 0, 1e-15},
      {"square to segment", square, crossing_segment, 1, 1, 1e-15},
      {"segment through a solid", paper_a(), point_set({{0.2, 0.2, -1}, {0.2, 0.2, 3}}), 0, -0.2,
       1e-15},
      {"square beside a tetrahedron", point_set({{0, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 1}}),
       moved(tetrahedron, {0.2, 0.2, 0.3}), 0.2, 0.2, 1e-15},
      {"coplanar squares overlapping", point_set({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}),
       point_set({{0.5, 0.5, 0}, {1.5, 0.5, 0}, {1.5, 1.5, 0}, {0.5, 1.5, 0}}), 0, 0, 1e-15},
  };
}

}  // namespace swarmcollide::testing
