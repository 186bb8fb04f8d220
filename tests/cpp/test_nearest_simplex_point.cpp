// The closed-form nearest point of a simplex of up to four points (the projection in Wolfe's
// algorithm), against an enumeration of the simplex's faces solved by a rank-revealing
// decomposition: random, degenerate (duplicate, collinear, coplanar points) and far-scaled
// simplexes.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "solvers/nearest_simplex_point.hpp"
#include "solvers/wolfe_min_norm.hpp"

namespace swarmcollide::detail {
namespace {

using Simplex = std::array<OraclePoint, 4>;

// The norm of the nearest point of the hull of s[0..m-1]: the least norm of the affine
// minimisers (least squares by complete orthogonal decomposition, which takes degenerate faces)
// of the faces whose weights come out non-negative.
Scalar oracle_norm(const Simplex& s, int m) {
  Scalar best = std::numeric_limits<Scalar>::infinity();
  for (int subset = 1; subset < (1 << m); ++subset) {
    std::array<int, 4> members{};
    int size = 0;
    for (int k = 0; k < m; ++k) {
      if (subset & (1 << k)) members[size++] = k;
    }
    const Vector3 p0 = s[members[0]].p;
    Eigen::MatrixXd edges(3, size - 1);
    for (int k = 1; k < size; ++k) edges.col(k - 1) = s[members[k]].p - p0;
    Eigen::VectorXd alpha = Eigen::VectorXd::Zero(size - 1);
    if (size > 1) alpha = edges.completeOrthogonalDecomposition().solve(-p0);
    const Scalar first = 1 - alpha.sum();
    if (first < -1e-12 || (alpha.array() < -1e-12).any()) continue;
    const Vector3 x = size > 1 ? Vector3(p0 + edges * alpha) : p0;
    best = std::min(best, x.norm());
  }
  return best;
}

Simplex simplex_of(const std::array<Vector3, 4>& points) {
  Simplex s;
  for (int k = 0; k < 4; ++k) s[k] = {points[k], k, 10 + k};
  return s;
}

// The projection's answer is a face of the given simplex (its points in their order) with
// positive weights summing to one; returns the norm of their combination.
Scalar checked_norm(const Simplex& given, int m) {
  Simplex s;
  std::array<Scalar, 4> w{};
  int size = 0;
  nearest_simplex_point(given, m, s, w, size);
  EXPECT_GE(size, 1);
  EXPECT_LE(size, m);
  Scalar total = 0;
  int previous = -1;
  for (int k = 0; k < size; ++k) {
    EXPECT_GT(w[k], 0);
    total += w[k];
    EXPECT_GT(s[k].ia, previous);  // a subset, in order
    previous = s[k].ia;
    EXPECT_EQ(s[k].ib, 10 + s[k].ia);
    EXPECT_EQ(s[k].p, given[s[k].ia].p);
  }
  EXPECT_NEAR(total, 1, 1e-14);
  return combination(s, w, size).stableNorm();
}

TEST(NearestSimplexPoint, RandomSimplexesMatchTheFaceEnumeration) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  for (int trial = 0; trial < 4000; ++trial) {
    const int m = 1 + trial % 4;
    // Offsets put the origin inside, near and far from the simplex.
    const Vector3 offset = (trial % 3) * Vector3(unit(rng), unit(rng), unit(rng));
    std::array<Vector3, 4> points;
    for (Vector3& p : points) p = Vector3(unit(rng), unit(rng), unit(rng)) + offset;
    const Simplex s = simplex_of(points);
    SCOPED_TRACE(trial);
    EXPECT_NEAR(checked_norm(s, m), oracle_norm(s, m), 1e-12);
  }
}

TEST(NearestSimplexPoint, OriginInsideATetrahedronKeepsAllFourPoints) {
  const std::array<Vector3, 4> points = {Vector3(1, 0, -0.5), Vector3(-1, 0.2, -0.5),
                                         Vector3(0, -1, -0.4), Vector3(0.1, 0.3, 1)};
  Simplex s;
  std::array<Scalar, 4> w{};
  int m = 0;
  nearest_simplex_point(simplex_of(points), 4, s, w, m);
  EXPECT_EQ(m, 4);
  EXPECT_LT(combination(s, w, m).norm(), 1e-15);
}

// Duplicate, collinear and coplanar points have no finite barycentric coordinates: every face
// is tried, and the answer is still the nearest point.
TEST(NearestSimplexPoint, DegenerateSimplexesMatchTheFaceEnumeration) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  for (int trial = 0; trial < 3000; ++trial) {
    const Vector3 a(unit(rng), unit(rng), unit(rng));
    const Vector3 u(unit(rng), unit(rng), unit(rng));
    const Vector3 v(unit(rng), unit(rng), unit(rng));
    std::array<Vector3, 4> points;
    int m = 4;
    switch (trial % 5) {
      case 0:  // duplicates
        points = {a, a + u, a, a + u};
        m = 2 + trial % 3;
        break;
      case 1:  // collinear
        points = {a, a + u, a - 0.5 * u, a + 2.5 * u};
        m = 3 + trial % 2;
        break;
      case 2:  // coplanar
        points = {a, a + u, a + v, a + 0.3 * u - 0.7 * v};
        break;
      case 3:  // coplanar through the origin
        points = {a, u, -a - u, 0.5 * a - 2 * u};
        break;
      default:  // all the same point
        points = {a, a, a, a};
        m = 1 + trial % 4;
        break;
    }
    const Simplex s = simplex_of(points);
    SCOPED_TRACE(trial);
    EXPECT_NEAR(checked_norm(s, m), oracle_norm(s, m), 1e-12);
  }
}

// Squares of coordinates near 1e-300 or 1e300 underflow or overflow: the projection scales them
// first, so the nearest point is the unit simplex's nearest point, scaled.
TEST(NearestSimplexPoint, FarScalesGiveTheScaledNearestPoint) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  for (Scalar scale : {1e-300, 1e-150, 1e150, 1e300}) {
    for (int trial = 0; trial < 400; ++trial) {
      const int m = 1 + trial % 4;
      const Vector3 offset = (trial % 3) * Vector3(unit(rng), unit(rng), unit(rng));
      std::array<Vector3, 4> points;
      std::array<Vector3, 4> scaled;
      for (int k = 0; k < 4; ++k) {
        points[k] = Vector3(unit(rng), unit(rng), unit(rng)) + offset;
        scaled[k] = scale * points[k];
      }
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " trial " << trial);
      const Scalar unit_norm = oracle_norm(simplex_of(points), m);
      EXPECT_NEAR(checked_norm(simplex_of(scaled), m) / scale, unit_norm, 1e-12);
    }
  }
}

}  // namespace
}  // namespace swarmcollide::detail
