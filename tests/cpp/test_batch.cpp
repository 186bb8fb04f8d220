#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "paper_cases.hpp"
#include "swarmcollide/queries/batch.hpp"

namespace swarmcollide {
namespace {

std::vector<ConvexPolyhedron> random_bodies(std::mt19937_64& rng, int count, double offset) {
  std::normal_distribution<double> normal;
  std::vector<ConvexPolyhedron> bodies;
  for (int i = 0; i < count; ++i) {
    VertexMatrix v(6, 3);
    for (Eigen::Index k = 0; k < v.size(); ++k) v.data()[k] = normal(rng);
    v.col(0).array() += offset;
    bodies.emplace_back(v);
  }
  return bodies;
}

TEST(Batch, ResultsDoNotDependOnTheThreadCount) {
  std::mt19937_64 rng(3);
  const auto as = random_bodies(rng, 50, 0);
  const auto bs = random_bodies(rng, 50, 2);
  DistanceOptions options;
  options.swarm.max_iterations = 20;
  const BatchResult one = distance_many(as, bs, options, 1);
  const BatchResult three = distance_many(as, bs, options, 3);
  EXPECT_EQ(one.distance, three.distance);
  EXPECT_EQ(one.point_a, three.point_a);
  for (std::size_t i : {0u, 17u, 49u}) {
    DistanceOptions single = options;
    single.swarm.seed = pair_seed(options.swarm.seed, i);
    EXPECT_EQ(one.distance(static_cast<Eigen::Index>(i)), distance(as[i], bs[i], single).distance);
  }
}

TEST(Batch, PairSeedsDiffer) {
  EXPECT_NE(pair_seed(0, 0), pair_seed(0, 1));
  EXPECT_NE(pair_seed(0, 1), pair_seed(1, 0));
}

TEST(Batch, CollideManyMatchesTheExactVerdicts) {
  std::mt19937_64 rng(4);
  const auto as = random_bodies(rng, 30, 0);
  const auto bs = random_bodies(rng, 30, 1.5);
  DistanceOptions exact;
  exact.method = Method::fcl;
  const BatchResult swarm = collide_many(as, bs, DistanceOptions{}, true, 2);
  const BatchResult reference = distance_many(as, bs, exact, 2);
  for (Eigen::Index i = 0; i < 30; ++i) {
    if (std::abs(reference.distance(i) - 1e-6) > 1e-12) {
      EXPECT_EQ(swarm.colliding(i), reference.distance(i) <= 1e-6) << "pair " << i;
    }
  }
}

TEST(Batch, ErrorsAreRethrown) {
  const std::vector<ConvexPolyhedron> one{testing::paper_a()};
  const std::vector<ConvexPolyhedron> two{testing::paper_a(), testing::paper_a()};
  EXPECT_THROW(distance_many(one, two, {}), std::invalid_argument);
  DistanceOptions bad;
  bad.swarm.swarm_size = 0;
  EXPECT_THROW(distance_many(two, two, bad, 2), std::invalid_argument);
  EXPECT_THROW(distance_many(two, two, {}, -1), std::invalid_argument);
}

TEST(Batch, VertexStacksGiveTheAnswersOfTheBodiesTheyHold) {
  std::mt19937_64 rng(6);
  std::normal_distribution<double> normal;
  const int pairs = 40, vertices = 7;
  std::vector<double> points_a(pairs * vertices * 3), points_b(points_a.size());
  for (double& x : points_a) x = normal(rng);
  for (double& x : points_b) x = normal(rng) + 1.5;
  std::vector<ConvexPolyhedron> as, bs;
  for (int i = 0; i < pairs; ++i) {
    as.emplace_back(Eigen::Map<const VertexMatrix>(&points_a[i * vertices * 3], vertices, 3));
    bs.emplace_back(Eigen::Map<const VertexMatrix>(&points_b[i * vertices * 3], vertices, 3));
  }
  const VertexStack stack_a{points_a.data(), pairs, vertices, "as"};
  const VertexStack stack_b{points_b.data(), pairs, vertices, "bs"};
  DistanceOptions options;
  options.swarm.max_iterations = 20;
  const BatchResult from_bodies = distance_many(as, bs, options, 1);
  const BatchResult from_stacks = distance_many(stack_a, stack_b, options, 2);
  EXPECT_EQ(from_stacks.distance, from_bodies.distance);
  EXPECT_EQ(from_stacks.point_b, from_bodies.point_b);
  const BatchResult verdicts = collide_many(stack_a, stack_b, options, true, 2);
  EXPECT_TRUE((verdicts.colliding == collide_many(as, bs, options, true, 1).colliding).all());
}

TEST(Batch, AStackBodyThatCannotBeBuiltIsNamed) {
  // Two tetrahedra; the second of `broken` has a NaN coordinate.
  std::vector<double> points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  points.insert(points.end(), points.begin(), points.end());
  std::vector<double> broken = points;
  broken[4 * 3 + 5] = std::numeric_limits<double>::quiet_NaN();
  const VertexStack good{points.data(), 1, 4, "as"};
  const VertexStack bad{broken.data(), 2, 4, "bs"};
  const VertexStack two_good{points.data(), 2, 4, "as"};
  EXPECT_THROW(distance_many(good, bad, {}), std::invalid_argument);
  try {
    distance_many(two_good, bad, {}, 2);
    ADD_FAILURE() << "a NaN vertex was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("bs[1]: "), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace swarmcollide
