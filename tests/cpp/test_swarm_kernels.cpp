// The swarm's vectorised kernels against their plain definitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "solvers/swarm_kernels.hpp"
#include "swarmcollide/problem/simplex.hpp"

namespace swarmcollide {
namespace {

using detail::SwarmView;

// A swarm of `particles` columns over `rows` weights, with a padded stride as the solver uses.
struct TestSwarm {
  TestSwarm(int rows, int particles)
      : stride(particles + 3),
        position(rows * stride),
        velocity(rows * stride),
        personal_best(rows * stride),
        view{rows, particles, stride, position.data(), velocity.data(), personal_best.data()} {}
  double& at(std::vector<double>& m, int r, int j) { return m[r * stride + j]; }
  int stride;
  std::vector<double> position, velocity, personal_best;
  SwarmView view;
};

TEST(SwarmKernels, ProjectionMatchesTheSortBasedProjectionForNegativeParticlesOnly) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(-1, 2);
  for (int k = 1; k <= detail::kMaxRowsProjectedTogether; ++k) {
    const int particles = 37;
    TestSwarm s(k, particles);
    std::vector<double> lowest(particles), theta(particles), sum(particles), count(particles);
    for (int j = 0; j < particles; ++j) {
      // Some particles carry ties, which the counting threshold must handle.
      for (int r = 0; r < k; ++r) s.at(s.position, r, j) = j % 5 == 0 ? 0.75 : U(rng);
      lowest[j] = j % 3 == 0 ? 0.0 : -1.0;
    }
    const std::vector<double> before = s.position;
    detail::project_rows_onto_simplex(s.view, 0, k, lowest.data(), theta.data(), sum.data(),
                                      count.data());
    for (int j = 0; j < particles; ++j) {
      VectorX column(k);
      for (int r = 0; r < k; ++r) column(r) = before[r * s.stride + j];
      const VectorX expected = lowest[j] < 0 ? project_onto_simplex(column) : column;
      for (int r = 0; r < k; ++r) {
        EXPECT_NEAR(s.at(s.position, r, j), expected(r), 1e-15) << "k " << k << " particle " << j;
        EXPECT_NEAR(s.at(s.velocity, r, j), expected(r) - column(r), 1e-15);
      }
    }
  }
}

TEST(SwarmKernels, RanksFollowConditions1To3WithTiesToTheLowerIndex) {
  std::mt19937_64 rng(5);
  const int particles = 29;
  std::vector<double> feasible(particles), value(particles);
  for (int j = 0; j < particles; ++j) {
    feasible[j] = rng() % 3 ? 1.0 : 0.0;
    value[j] = static_cast<double>(rng() % 6) * 0.25;  // many exact ties
  }
  value[4] = 1e300;
  value[7] = 0.0;
  std::vector<std::int64_t> key(particles), rank(particles);
  detail::rank_personal_bests(particles, feasible.data(), value.data(), key.data(), rank.data());

  std::vector<int> order(particles);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    if (feasible[a] != feasible[b]) return feasible[a] > feasible[b];
    return value[a] < value[b];
  });
  for (int position = 0; position < particles; ++position) {
    EXPECT_EQ(rank[order[position]], position) << "particle " << order[position];
  }
}

TEST(SwarmKernels, SimplexPointsAreTheGapsBetweenSortedUniforms) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> U(0, 1);
  // 1 weight (no cuts), a sorting network, and more cuts than the network takes.
  for (int count : {1, 4, 17, 40}) {
    const int particles = 13, stride = 16, cuts = count - 1;
    std::vector<double> uniforms(std::max(cuts, 1) * stride), out(count * stride), column(count);
    for (double& u : uniforms) u = U(rng);
    const std::vector<double> drawn = uniforms;
    detail::uniform_simplex_points(count, particles, stride, uniforms.data(), out.data(),
                                   column.data());
    for (int j = 0; j < particles; ++j) {
      std::vector<double> sorted(cuts);
      for (int i = 0; i < cuts; ++i) sorted[i] = drawn[i * stride + j];
      std::sort(sorted.begin(), sorted.end());
      sorted.push_back(1.0);
      double previous = 0, total = 0;
      for (int i = 0; i < count; ++i) {
        EXPECT_DOUBLE_EQ(out[i * stride + j], sorted[i] - previous) << "count " << count;
        EXPECT_GE(out[i * stride + j], 0.0);
        total += out[i * stride + j];
        previous = sorted[i];
      }
      EXPECT_NEAR(total, 1.0, 1e-14);
    }
  }
}

TEST(SwarmKernels, UniformsLieInTheUnitIntervalAndDependOnlyOnTheSeed) {
  detail::UniformLanes lanes(11), same(11), other(12);
  std::vector<double> u(8000), v(8000), w(8000);
  detail::draw_uniforms(lanes, u.data(), 8000);
  detail::draw_uniforms(same, v.data(), 8000);
  detail::draw_uniforms(other, w.data(), 8000);
  EXPECT_EQ(u, v);
  EXPECT_NE(u, w);
  EXPECT_GE(*std::min_element(u.begin(), u.end()), 0.0);
  EXPECT_LT(*std::max_element(u.begin(), u.end()), 1.0);
  EXPECT_NEAR(std::accumulate(u.begin(), u.end(), 0.0) / 8000, 0.5, 0.01);
}

TEST(SwarmKernels, AMoveOverTheLimitScalesTheWholeVelocityAndKeepsTheSums) {
  const int rows_a = 3, rows = 5, particles = 4;
  TestSwarm s(rows, particles);
  const std::vector<double> weights = {0.2, 0.3, 0.5, 0.6, 0.4};
  const std::vector<double> own = {1.0, 0.0, 0.0, 0.0, 1.0};
  for (int j = 0; j < particles; ++j) {
    for (int r = 0; r < rows; ++r) {
      s.at(s.position, r, j) = weights[r];
      s.at(s.personal_best, r, j) = own[r];
    }
  }
  const std::vector<double> inertia(particles, 0.0), pull_global(particles, 0.0);
  // Pulls of 0.5 and 1 move within the limit; 4 and 8 exceed it and are scaled.
  const std::vector<double> pull_own = {0.5, 1.0, 4.0, 8.0};
  const std::vector<double> global(rows, 0.0);
  std::vector<double> next(rows * s.stride), largest(particles), lowest_a(particles),
      lowest_b(particles);
  const double limit = 1.0;
  detail::move_particles(s.view, rows_a, inertia.data(), pull_own.data(), pull_global.data(),
                         global.data(), limit, next.data(), largest.data(), lowest_a.data(),
                         lowest_b.data());
  for (int j = 0; j < particles; ++j) {
    double biggest = 0, sum_a = 0, sum_b = 0, smallest_a = 0;
    for (int r = 0; r < rows; ++r) {
      const double v = s.at(s.velocity, r, j);
      const double unlimited = pull_own[j] * (own[r] - weights[r]);
      biggest = std::max(biggest, std::abs(v));
      EXPECT_NEAR(v, unlimited * std::min(1.0, limit / (pull_own[j] * 0.8)), 1e-15);
      EXPECT_DOUBLE_EQ(next[r * s.stride + j], weights[r] + v);
      (r < rows_a ? sum_a : sum_b) += next[r * s.stride + j];
      if (r < rows_a) smallest_a = std::min(smallest_a, next[r * s.stride + j]);
    }
    EXPECT_LE(biggest, limit + 1e-15);
    EXPECT_NEAR(sum_a, 1.0, 1e-15);
    EXPECT_NEAR(sum_b, 1.0, 1e-15);
    EXPECT_DOUBLE_EQ(lowest_a[j], smallest_a);
  }
}

}  // namespace
}  // namespace swarmcollide
