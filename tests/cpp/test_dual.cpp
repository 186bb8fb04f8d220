#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "contract.hpp"
#include "hard_cases.hpp"
#include "paper_cases.hpp"
#include "swarmcollide/problem/certificate.hpp"
#include "swarmcollide/queries/collide.hpp"
#include "swarmcollide/queries/distance.hpp"
#include "swarmcollide/queries/signed_distance.hpp"
#include "swarmcollide/solvers/dual.hpp"
#include "swarmcollide/solvers/exact_nearest_points.hpp"
#include "swarmcollide/solvers/fcl_distance.hpp"

namespace swarmcollide {
namespace {

using testing::paper_a;
using testing::paper_b_colliding;
using testing::paper_b_separate;

using testing::size_of;

void expect_contract(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const DistanceResult& r,
                     Scalar eps = 1e-12) {
  testing::expect_contract(a, b, r, eps);
  EXPECT_EQ(r.method, "dual");
  EXPECT_GT(r.evaluations, 0);
  EXPECT_FALSE(r.history.empty());
  // Certified to 1e-9 of the bodies' size (the default tolerance).
  EXPECT_TRUE(r.certified);
  EXPECT_EQ(r.status, SolverStatus::converged);
  if (!r.colliding) EXPECT_LE(r.distance - r.lower_bound, 1e-9 * size_of(a, b));
}

// The hull vertices of `n` random points on the unit sphere, as a body.
VertexMatrix sphere_polytope(int n, std::mt19937_64& rng) {
  std::normal_distribution<Scalar> normal;
  VertexMatrix points(n, 3);
  for (int i = 0; i < n; ++i) {
    const Vector3 v(normal(rng), normal(rng), normal(rng));
    points.row(i) = v.normalized().transpose();
  }
  const ConvexPolyhedron body(points);
  const Hull& hull = body.hull();
  VertexMatrix vertices(static_cast<Eigen::Index>(hull.vertex_indices.size()), 3);
  for (std::size_t k = 0; k < hull.vertex_indices.size(); ++k) {
    vertices.row(k) = points.row(hull.vertex_indices[k]);
  }
  return vertices;
}

// B placed so that its exact distance to A is `gap` (apart) or so that it is pushed `-gap` past
// touching along the nearest-point direction (overlapping).
std::pair<ConvexPolyhedron, ConvexPolyhedron> random_pair(int n, Scalar gap, std::mt19937_64& rng) {
  std::normal_distribution<Scalar> normal;
  const VertexMatrix a = sphere_polytope(n, rng);
  const Vector3 u = Vector3(normal(rng), normal(rng), normal(rng)).normalized();
  const VertexMatrix b0 = sphere_polytope(n, rng).rowwise() + 3 * u.transpose();
  const DistanceResult r = exact_nearest_points(ConvexPolyhedron(a), ConvexPolyhedron(b0));
  const Vector3 along = (r.point_b - r.point_a).normalized();
  return {ConvexPolyhedron(a),
          ConvexPolyhedron(b0.rowwise() - ((r.distance - gap) * along).transpose())};
}

TEST(Dual, OptionsAreValidated) {
  const auto fails_naming = [](DualOptions o, const std::string& field) {
    try {
      solve_dual(paper_a(), paper_b_separate(), o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what()).find(field) != std::string::npos;
    }
    return false;
  };
  DualOptions o;
  o.swarm_size = 1;
  EXPECT_TRUE(fails_naming(o, "swarm_size"));
  o = {};
  o.max_iterations = -1;
  EXPECT_TRUE(fails_naming(o, "max_iterations"));
  o = {};
  o.w_min = -0.1;
  EXPECT_TRUE(fails_naming(o, "w_min"));
  o = {};
  o.w_max = 0.1;
  EXPECT_TRUE(fails_naming(o, "w_max"));
  o = {};
  o.tolerance = std::nan("");
  EXPECT_TRUE(fails_naming(o, "tolerance"));
  o = {};
  o.relative_tolerance = 0;
  EXPECT_TRUE(fails_naming(o, "relative_tolerance"));
  o = {};
  o.feature_tolerance = -1;
  EXPECT_TRUE(fails_naming(o, "feature_tolerance"));
  o = {};
  o.max_rounds = 0;
  EXPECT_TRUE(fails_naming(o, "max_rounds"));
}

TEST(Dual, MethodNameRoundTrips) {
  EXPECT_EQ(method_name(Method::dual), "dual");
  EXPECT_EQ(method_from_name("dual"), Method::dual);
}

TEST(Dual, PaperPairs) {
  DistanceOptions options;
  options.method = Method::dual;
  const DistanceResult apart = distance(paper_a(), paper_b_separate(), options);
  expect_contract(paper_a(), paper_b_separate(), apart);
  EXPECT_NEAR(apart.distance, 1, 1e-12);
  EXPECT_FALSE(apart.colliding);
  const DistanceResult touching = distance(paper_a(), paper_b_colliding(), options);
  expect_contract(paper_a(), paper_b_colliding(), touching);
  EXPECT_TRUE(touching.colliding);
  EXPECT_TRUE(collide(paper_a(), paper_b_colliding(), options));
  EXPECT_FALSE(collide(paper_a(), paper_b_separate(), options));
}

TEST(Dual, RandomPairsAreCertifiedAndAgreeWithTheExactReferences) {
  std::mt19937_64 rng(42);
  for (int n : {8, 64, 512, 4096}) {
    for (Scalar gap : {1.0, 1e-1, 1e-2, 1e-3, 1e-4, -1e-4, -1e-3, -1e-2, -1e-1}) {
      if (n == 4096 && std::abs(gap) != 1e-3) continue;  // a hull of 4096 points takes a while
      const auto [a, b] = random_pair(n, gap, rng);
      SCOPED_TRACE("n = " + std::to_string(n) + ", gap = " + std::to_string(gap));
      const DistanceResult r = solve_dual(a, b);
      expect_contract(a, b, r);
      const DistanceResult wolfe = exact_nearest_points(a, b);
      const DistanceResult fcl = fcl_distance(a, b, FclGjk::libccd);
      EXPECT_EQ(r.colliding, gap < 0);
      EXPECT_EQ(r.colliding, fcl.colliding);
      const Scalar size = size_of(a, b);
      EXPECT_NEAR(r.distance, wolfe.distance, 1e-9 * size);
      EXPECT_NEAR(r.distance, fcl.distance, 1e-9 * size);
    }
  }
}

TEST(Dual, SignedDistanceAgreesWithFclEpa) {
  std::mt19937_64 rng(7);
  for (int n : {8, 64, 512}) {
    for (Scalar gap : {1e-2, -1e-4, -1e-3, -1e-2, -1e-1}) {
      const auto [a, b] = random_pair(n, gap, rng);
      SCOPED_TRACE("n = " + std::to_string(n) + ", gap = " + std::to_string(gap));
      DistanceOptions options;
      options.method = Method::dual;
      const DistanceResult r = signed_distance(a, b, options);
      options.method = Method::fcl;
      const DistanceResult fcl = signed_distance(a, b, options);
      EXPECT_EQ(r.method, "dual");
      EXPECT_NEAR(r.distance, fcl.distance, 1e-6 * std::abs(fcl.distance));
      EXPECT_NEAR(separation(a, b, r.direction), r.lower_bound, 1e-12);
      EXPECT_LE(r.lower_bound, r.distance + 1e-12);
      EXPECT_LE((r.point_b - r.point_a - r.distance * r.direction).norm(), 1e-9);
      EXPECT_NEAR(r.weights_a.sum(), 1, 1e-12);
      EXPECT_NEAR(r.weights_b.sum(), 1, 1e-12);
      EXPECT_EQ(r.colliding, gap < 0);
    }
  }
}

TEST(Dual, SameSeedSameAnswer) {
  std::mt19937_64 rng(3);
  const auto [a, b] = random_pair(64, 1e-3, rng);
  DualOptions options;
  options.seed = 11;
  const DistanceResult first = solve_dual(a, b, options);
  const DistanceResult second = solve_dual(a, b, options);
  EXPECT_EQ(first.distance, second.distance);
  EXPECT_EQ(first.lower_bound, second.lower_bound);
  EXPECT_EQ(first.evaluations, second.evaluations);
  EXPECT_EQ(first.history, second.history);
}

TEST(Dual, AbsoluteToleranceIsHonoured) {
  DualOptions options;
  options.tolerance = 1e-3;
  const DistanceResult r = solve_dual(paper_a(), paper_b_separate(), options);
  EXPECT_LE(r.distance - r.lower_bound, 1e-3);
  EXPECT_TRUE(r.certified);
}

TEST(Dual, DegenerateBodies) {
  VertexMatrix point(1, 3);
  point << 0, 0, 3;
  VertexMatrix segment(2, 3);
  segment << -1, 0, 1, 1, 0, 1;
  VertexMatrix square(4, 3);
  square << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  const ConvexPolyhedron p(point), s(segment), q(square);
  for (const auto& [a, b, d] :
       {std::tuple{&p, &s, 2.0}, std::tuple{&s, &q, 1.0}, std::tuple{&q, &p, 3.0}}) {
    const DistanceResult r = solve_dual(*a, *b);
    expect_contract(*a, *b, r);
    EXPECT_NEAR(r.distance, d, 1e-12);
  }
}

TEST(Dual, HardCasesAreCertified) {
  for (const testing::HardCase& c : testing::hard_cases()) {
    SCOPED_TRACE(c.name);
    for (const bool swapped : {false, true}) {
      const ConvexPolyhedron& a = swapped ? c.b : c.a;
      const ConvexPolyhedron& b = swapped ? c.a : c.b;
      const DistanceResult r = solve_dual(a, b);
      // Rounding in the witness points grows with their coordinates.
      expect_contract(a, b, r, 1e-12 * (size_of(a, b) + r.point_a.norm()));
      EXPECT_NEAR(r.distance, c.distance, std::max(c.accuracy, 1e-9 * size_of(a, b)));
      EXPECT_EQ(r.colliding, c.distance <= 1e-9 * size_of(a, b));
    }
  }
}

TEST(HillClimbing, SupportMatchesTheScan) {
  std::mt19937_64 rng(5);
  std::normal_distribution<Scalar> normal;
  VertexMatrix points(500, 3);
  for (int i = 0; i < points.rows(); ++i) {
    points.row(i) << normal(rng), normal(rng), normal(rng);  // many interior points
  }
  const ConvexPolyhedron body(points);
  int start = -1;
  for (int k = 0; k < 200; ++k) {
    const Vector3 d(normal(rng), normal(rng), normal(rng));
    start = body.support_index(d, k % 3 == 0 ? -1 : start);
    EXPECT_DOUBLE_EQ(points.row(start).dot(d), (points * d).maxCoeff());
  }
  const Hull& hull = body.hull();
  ASSERT_EQ(hull.neighbour_offsets.size(), static_cast<std::size_t>(body.size()) + 1);
  for (int i = 0; i < body.size(); ++i) {
    for (int k = hull.neighbour_offsets[i]; k < hull.neighbour_offsets[i + 1]; ++k) {
      const int j = hull.neighbours[k];
      const auto begin = hull.neighbours.begin() + hull.neighbour_offsets[j];
      const auto end = hull.neighbours.begin() + hull.neighbour_offsets[j + 1];
      EXPECT_NE(std::find(begin, end, i), end);  // symmetric
    }
  }
}

}  // namespace
}  // namespace swarmcollide
