// The swarm's vectorised kernels against their plain definitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "solvers/swarm_kernels.hpp"
#include "swarmcollide/problem/simplex.hpp"

namespace swarmcollide {
namespace {

using detail::SwarmView;

constexpr int kLanes = detail::UniformLanes::kLanes;

// A swarm of `particles` columns over `rows` weights, padded to whole blocks as the solver does,
// with everything one generation of `advance_particles` reads and writes.
struct TestSwarm {
  TestSwarm(int rows, int particles)
      : rows(rows),
        stride((particles + kLanes - 1) / kLanes * kLanes),
        position(rows * stride),
        velocity(rows * stride),
        personal_best(rows * stride),
        next(rows * stride),
        column(rows),
        inertia(stride),
        pull_own(stride),
        pull_global(stride),
        global_best(rows),
        key(stride, std::numeric_limits<std::int64_t>::max()),
        improved(stride),
        signed_vertices(3 * rows),
        view{rows, particles, stride, position.data(), velocity.data(), personal_best.data()} {}
  double& at(std::vector<double>& m, int r, int j) { return m[r * stride + j]; }

  bool advance(int rows_a, double limit, bool project) {
    const detail::Move move{inertia.data(),     pull_own.data(), pull_global.data(),
                            global_best.data(), limit,           project};
    const detail::Fitness fitness{signed_vertices.data(), !project, 1e-12};
    return detail::advance_particles(view, rows_a, move, fitness, {key.data(), improved.data()},
                                     next.data(), column.data());
  }

  int rows;
  int stride;
  std::vector<double> position, velocity, personal_best, next, column;
  std::vector<double> inertia, pull_own, pull_global, global_best;
  std::vector<std::int64_t> key, improved;
  std::vector<double> signed_vertices;
  SwarmView view;
};

// The key of a feasible particle whose squared objective is `value`.
std::int64_t feasible_key(double value) {
  return __builtin_bit_cast(std::int64_t, value) - detail::kFeasibleKeyShift;
}

TEST(SwarmKernels, ProjectionMatchesTheSortBasedProjectionForNegativeParticlesOnly) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(-1, 2);
  // Up to the sorting networks' limit, and beyond it where std::sort takes over.
  for (int k = 1; k <= detail::kMaxRowsProjectedTogether + 4; ++k) {
    const int particles = 37;
    // A's k rows, then B's single weight of 1, which never needs projecting.
    TestSwarm s(k + 1, particles);
    for (int j = 0; j < particles; ++j) {
      // Some particles carry ties, which the threshold must handle; every third one has no
      // negative weight and is left alone.
      for (int r = 0; r < k; ++r) {
        const double w = j % 5 == 0 ? 0.75 : U(rng);
        s.at(s.position, r, j) = j % 3 == 0 ? std::abs(w) : w;
      }
      s.at(s.position, k, j) = 1.0;
    }
    // No inertia and no pulls: the move leaves every particle where it is.
    const std::vector<double> before = s.position;
    s.advance(k, 10.0, true);
    for (int j = 0; j < particles; ++j) {
      VectorX column(k);
      for (int r = 0; r < k; ++r) column(r) = before[r * s.stride + j];
      const VectorX expected = column.minCoeff() < 0 ? project_onto_simplex(column) : column;
      for (int r = 0; r < k; ++r) {
        EXPECT_NEAR(s.at(s.next, r, j), expected(r), 1e-15) << "k " << k << " particle " << j;
        EXPECT_NEAR(s.at(s.velocity, r, j), expected(r) - column(r), 1e-15);
      }
      EXPECT_EQ(s.at(s.next, k, j), 1.0);
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
  std::vector<std::int64_t> key(32), rank(32);
  for (int j = 0; j < particles; ++j) {
    const std::int64_t bits = __builtin_bit_cast(std::int64_t, value[j]);
    key[j] = feasible[j] != 0 ? feasible_key(value[j]) : bits;
  }
  detail::rank_personal_bests(particles, key.data(), rank.data());

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
  // Pulls of 0.5 and 1 move within the limit; 4 and 8 exceed it and are scaled.
  s.pull_own = {0.5, 1.0, 4.0, 8.0, 0, 0, 0, 0};
  const double limit = 1.0;
  s.advance(rows_a, limit, false);
  for (int j = 0; j < particles; ++j) {
    double biggest = 0, sum_a = 0, sum_b = 0;
    for (int r = 0; r < rows; ++r) {
      const double v = s.at(s.velocity, r, j);
      const double unlimited = s.pull_own[j] * (own[r] - weights[r]);
      biggest = std::max(biggest, std::abs(v));
      EXPECT_NEAR(v, unlimited * std::min(1.0, limit / (s.pull_own[j] * 0.8)), 1e-15);
      EXPECT_DOUBLE_EQ(s.at(s.next, r, j), weights[r] + v);
      (r < rows_a ? sum_a : sum_b) += s.at(s.next, r, j);
    }
    EXPECT_LE(biggest, limit + 1e-15);
    EXPECT_NEAR(sum_a, 1.0, 1e-15);
    EXPECT_NEAR(sum_b, 1.0, 1e-15);
  }
}

TEST(SwarmKernels, AParticleTakesItsNewPositionAsPersonalBestOnlyWhenItScoresBetter) {
  // A is the point (1, 0, 0) or the origin, B the point (3, 0, 0): a particle's offset is
  // 3 - lambda_0, its squared objective (3 - lambda_0)^2.
  const int rows_a = 2, rows = 3, particles = 3;
  TestSwarm s(rows, particles);
  s.signed_vertices = {-1, 0, 0, 0, 0, 0, 3, 0, 0};
  for (int j = 0; j < particles; ++j) {
    s.at(s.position, 0, j) = 0.5;
    s.at(s.position, 1, j) = 0.5;
    s.at(s.position, 2, j) = 1.0;
  }
  // Particle 0 had a better best, particle 1 a worse one, particle 2 an infeasible one.
  s.key = {feasible_key(2.0), feasible_key(9.0), __builtin_bit_cast(std::int64_t, 0.25)};
  s.key.resize(s.stride, std::numeric_limits<std::int64_t>::max());
  const std::vector<double> best_before = s.personal_best;
  EXPECT_TRUE(s.advance(rows_a, 10.0, true));
  const std::int64_t now = feasible_key(2.5 * 2.5);
  EXPECT_EQ(s.key[0], feasible_key(2.0));
  EXPECT_EQ(s.key[1], now);
  EXPECT_EQ(s.key[2], now);
  EXPECT_EQ(s.improved[0], 0);
  EXPECT_NE(s.improved[1], 0);
  EXPECT_NE(s.improved[2], 0);
  for (int r = 0; r < rows; ++r) {
    EXPECT_EQ(s.at(s.personal_best, r, 0), best_before[r * s.stride]);
    EXPECT_EQ(s.at(s.personal_best, r, 1), s.at(s.next, r, 1));
    EXPECT_EQ(s.at(s.personal_best, r, 2), s.at(s.next, r, 2));
  }
}

}  // namespace
}  // namespace swarmcollide
