#include <gtest/gtest.h>

#include <stdexcept>

#include "paper_cases.hpp"
#include "swarmcollide/problem/certificate.hpp"
#include "swarmcollide/problem/convex_weights.hpp"
#include "swarmcollide/problem/distance_model.hpp"
#include "swarmcollide/problem/simplex.hpp"

namespace swarmcollide {
namespace {

using testing::paper_a;
using testing::paper_b_separate;

VectorX weights(std::initializer_list<Scalar> values) {
  VectorX w(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (Scalar v : values) w(i++) = v;
  return w;
}

TEST(DistanceModel, ObjectiveIsTheDistanceBetweenTheCombinations) {
  // lambda picks x2 = (1, 0, 0), delta picks y1 = (1, -1, 0): the paper's optimum of Table 2.
  EXPECT_DOUBLE_EQ(
      objective(paper_a(), paper_b_separate(), weights({0, 1, 0, 0}), weights({1, 0, 0, 0})), 1.0);
  EXPECT_DOUBLE_EQ(
      objective(paper_a(), paper_b_separate(), weights({0, 0, 0, 1}), weights({0, 0, 0, 1})), 2.0);
  EXPECT_THROW(objective(paper_a(), paper_b_separate(), weights({1}), weights({1, 0, 0, 0})),
               std::invalid_argument);
}

TEST(DistanceModel, ViolationAndFeasibility) {
  EXPECT_DOUBLE_EQ(constraint_violation(weights({0.5, 0.5}), weights({1, 0, 0})), 0.0);
  EXPECT_DOUBLE_EQ(constraint_violation(weights({0.5, 1.0}), weights({0, 0, 0})), 0.25 + 1.0);
  EXPECT_TRUE(is_feasible(weights({0.5, 0.5}), weights({1, 0}), 0));
  EXPECT_FALSE(is_feasible(weights({1.5, -0.5}), weights({1, 0}), 1));  // bounds, not (6)
  EXPECT_TRUE(is_feasible(weights({0.5, 0.5001}), weights({1, 0}), 1e-6));
  EXPECT_FALSE(is_feasible(weights({0.5, 0.5001}), weights({1, 0}), 1e-9));
}

TEST(Simplex, ProjectionLandsOnTheSimplexAndIsIdempotent) {
  const VectorX inside = weights({0.2, 0.3, 0.5});
  EXPECT_TRUE(project_onto_simplex(inside).isApprox(inside));
  const VectorX p = project_onto_simplex(weights({2, -1, 0.5}));
  EXPECT_NEAR(p.sum(), 1.0, 1e-15);
  EXPECT_TRUE((p.array() >= 0).all());
  EXPECT_TRUE(p.isApprox(weights({1, 0, 0})));
  EXPECT_TRUE(project_onto_simplex(weights({0.5, 0.5, 0.5})).isApprox(weights({1, 1, 1}) / 3));
}

TEST(Simplex, RescalingKeepsVertexWeightsExact) {
  EXPECT_EQ(to_simplex(weights({0, 2, 0})), weights({0, 1, 0}));
  const VectorX negative = to_simplex(weights({-0.1, 1.1, 0}));
  EXPECT_EQ(negative, weights({0, 1, 0}));
}

TEST(Certificate, SeparationIsTheGapBetweenSupportPlanes) {
  EXPECT_DOUBLE_EQ(separation(paper_a(), paper_b_separate(), Vector3(0, -1, 0)), 1.0);
  // Scaling the direction changes nothing; a direction that does not separate gives a negative.
  EXPECT_DOUBLE_EQ(separation(paper_a(), paper_b_separate(), Vector3(0, -7, 0)), 1.0);
  EXPECT_LT(separation(paper_a(), paper_b_separate(), Vector3(0, 1, 0)), 0.0);
  EXPECT_THROW(separation(paper_a(), paper_b_separate(), Vector3::Zero()), std::invalid_argument);
}

// Exact methods give at most four weights, kept sparse (an index may repeat); swarms give one
// per point. Both read the same.
TEST(ConvexWeights, SparseAndDenseReadAlike) {
  const ConvexWeights sparse(5, {3, 1, 3, 0}, {0.25, 0.5, 0.25, 0}, 3);
  EXPECT_EQ(sparse.count(), 5);
  EXPECT_EQ(sparse.dense(), weights({0, 0.5, 0, 0.5, 0}));
  VectorX visited = VectorX::Zero(5);
  sparse.for_each([&](int i, Scalar w) { visited(i) += w; });
  EXPECT_EQ(visited, sparse.dense());
  const ConvexWeights dense(weights({0.2, 0.8}));
  EXPECT_EQ(dense.count(), 2);
  EXPECT_EQ(dense.dense(), weights({0.2, 0.8}));
  int calls = 0;
  dense.for_each([&](int, Scalar) { ++calls; });
  EXPECT_EQ(calls, 2);
  EXPECT_EQ(ConvexWeights().dense().size(), 0);
}

}  // namespace
}  // namespace swarmcollide
