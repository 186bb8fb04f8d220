// The closed-form nearest point of a simplex of up to four points (the projection in Wolfe's
// algorithm), against an enumeration of the simplex's faces solved by a rank-revealing
// decomposition: random, degenerate (duplicate, collinear, coplanar points) and far-scaled
// simplexes.
#include <gtest/gtest.h>

#include <algorithm>
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
// positive weights summing to one, and the point it hands back is their combination as Wolfe's
// algorithm forms it (combination(), the same operations: equal values) with its squared norm;
// returns the norm of that combination.
Scalar checked_norm(const Simplex& given, int m) {
  Simplex s;
  std::array<Scalar, 4> w{};
  int size = 0;
  Vector3 point;
  Scalar norm2 = 0;
  nearest_simplex_point(given, m, s, w, size, false, point, norm2);
  EXPECT_EQ(point, combination(s, w, size));
  EXPECT_EQ(norm2, point.squaredNorm());
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

// The origin exactly on a vertex, in an edge or in a face of a tetrahedron or triangle (points
// on the grid of eighths, so that the origin's place is exact): the nearest point is the origin,
// and the face answered is the smallest one that holds it, with its weights. A projection that
// dropped a point it needs, or kept one with a weight that rounding made zero, fails here.
TEST(NearestSimplexPoint, TheOriginOnAVertexEdgeOrFaceGivesThatFeature) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> eighths(-16, 16);
  const auto grid = [&]() -> Vector3 { return Vector3(eighths(rng), eighths(rng), eighths(rng)) / 8; };
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int m = 3 + trial % 2;
    const int feature = 1 + (trial / 2) % 3;  // points of the face through the origin
    std::array<Vector3, 4> points;
    for (Vector3& p : points) p = grid();
    // The origin at the centroid-like point with weights 1/2 (edge) or 1/4, 1/4, 1/2 (face) of
    // the feature's points: the feature's last point is placed to make it so, exactly.
    Vector3 partial = Vector3::Zero();
    const std::array<Scalar, 3> share = feature == 2   ? std::array<Scalar, 3>{0.5, 0.5, 0}
                                        : feature == 3 ? std::array<Scalar, 3>{0.25, 0.25, 0.5}
                                                       : std::array<Scalar, 3>{1, 0, 0};
    for (int k = 0; k + 1 < feature; ++k) partial += share[k] * points[k];
    points[feature - 1] = -partial / share[feature - 1];
    // Rotate the order so that the feature's points are anywhere among the simplex's.
    const int turn = (trial / 6) % m;
    std::rotate(points.begin(), points.begin() + turn, points.begin() + m);
    std::array<bool, 4> in_feature{};
    for (int j = 0; j < feature; ++j) in_feature[(j - turn + m) % m] = true;
    const Simplex given = simplex_of(points);
    // Draws the enumeration does not place exactly on the origin (its own rounding, or a
    // degenerate feature: the degenerate test's) are left out.
    if (oracle_norm(given, m) != 0) continue;
    Simplex s;
    std::array<Scalar, 4> w{};
    int size = 0;
    nearest_simplex_point(given, m, s, w, size);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << ", feature of " << feature);
    const Vector3 x = combination(s, w, size);
    EXPECT_LT(x.norm(), 1e-14);
    // The feature's points, and others only with weights of rounding (a coordinate of the
    // origin that is zero computes as a tiny one of either sign).
    for (int k = 0; k < size; ++k) {
      EXPECT_GT(w[k], 0);
      if (!in_feature[s[k].ia]) EXPECT_LT(w[k], 1e-14) << "point " << s[k].ia;
    }
    int held = 0;
    for (int k = 0; k < size; ++k) held += in_feature[s[k].ia];
    EXPECT_EQ(held, feature);
    ++checked;
  }
  EXPECT_GT(checked, 1500);
}

// Triangles and tetrahedra that are nearly flat (a point within a sine of 1e-5 to 1e-11 of the
// line or plane of the others: on both sides of the flatness threshold, kFlat = 1e-8) and the
// origin near them: the nearest point is the enumeration's, whichever path the projection takes.
TEST(NearestSimplexPoint, NearlyFlatSimplexesMatchTheFaceEnumeration) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  const auto random = [&]() -> Vector3 { return Vector3(unit(rng), unit(rng), unit(rng)); };
  for (int trial = 0; trial < 4000; ++trial) {
    const Scalar sine = std::pow(10.0, -5 - trial % 7);
    const Vector3 a = random();
    const Vector3 u = random();
    const Vector3 v = random();
    const Vector3 off = random().normalized();
    std::array<Vector3, 4> points;
    int m = 4;
    if (trial % 2 == 0) {  // a nearly collinear triangle, or a tetrahedron over one
      points = {a, a + u, a + 0.4 * u + sine * u.norm() * off, a + 0.7 * v};
      m = 3 + (trial / 2) % 2;
    } else {  // a nearly coplanar tetrahedron
      points = {a, a + u, a + v, a + 0.3 * u + 0.5 * v + sine * u.norm() * off};
    }
    // The origin near the simplex: shift it by the nearest point of its face (a, b, c) or so.
    const Vector3 shift = (points[0] + points[1] + points[2]) / 3 + 1e-3 * random();
    for (Vector3& p : points) p -= shift;
    const Simplex s = simplex_of(points);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << ", sine " << sine);
    EXPECT_NEAR(checked_norm(s, m), oracle_norm(s, m), 1e-12);
  }
}

// Tetrahedra the origin lies beyond an edge or a vertex of (two or three barycentric coordinates
// negative, the case where the projection tries the face opposite the most negative one first,
// then the others): the nearest point is the enumeration's.
TEST(NearestSimplexPoint, TetrahedraFacingTheOriginWithSeveralFacesMatchTheFaceEnumeration) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<Scalar> unit(-1, 1);
  const auto random = [&]() -> Vector3 { return Vector3(unit(rng), unit(rng), unit(rng)); };
  int several = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::array<Vector3, 4> points;
    for (Vector3& p : points) p = random();
    // The origin moved out beyond a vertex (1 point) or the middle of an edge (2 points).
    const int beyond = 1 + trial % 2;
    Vector3 feature = Vector3::Zero();
    for (int k = 0; k < beyond; ++k) feature += points[3 - k] / beyond;
    const Vector3 centre = (points[0] + points[1] + points[2] + points[3]) / 4;
    const Vector3 origin = feature + (0.1 + 2 * std::abs(unit(rng))) * (feature - centre);
    for (Vector3& p : points) p -= origin;
    Eigen::Matrix3d edges;
    for (int k = 0; k < 3; ++k) edges.col(k) = points[k + 1] - points[0];
    const Vector3 tail = edges.fullPivLu().solve(-points[0]);
    const int negative = (1 - tail.sum() < 0) + (tail.array() < 0).count();
    several += negative >= 2;
    const Simplex s = simplex_of(points);
    SCOPED_TRACE(trial);
    EXPECT_NEAR(checked_norm(s, 4), oracle_norm(s, 4), 1e-12);
  }
  EXPECT_GT(several, 1500);
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
