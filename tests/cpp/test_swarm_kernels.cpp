// The swarm's vectorised kernels against plain definitions, on every instruction set this
// processor runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "solvers/swarm_kernels.hpp"
#include "swarmcollide/problem/simplex.hpp"

namespace swarmcollide {
namespace {

using detail::KernelIsa;
using detail::SwarmView;

constexpr int kLanes = detail::UniformLanes::kLanes;

std::vector<KernelIsa> available_isas() {
  std::vector<KernelIsa> isas;
  for (KernelIsa isa : {KernelIsa::baseline, KernelIsa::avx2, KernelIsa::avx512}) {
    if (detail::kernel_isa_available(isa)) isas.push_back(isa);
  }
  return isas;
}

// Runs the kernels of one instruction set while it lives, then restores the previous choice.
class UsingIsa {
 public:
  explicit UsingIsa(KernelIsa isa) : previous_(detail::kernel_isa()) {
    detail::use_kernel_isa(isa);
  }
  ~UsingIsa() { detail::use_kernel_isa(previous_); }
  UsingIsa(const UsingIsa&) = delete;
  UsingIsa& operator=(const UsingIsa&) = delete;

 private:
  KernelIsa previous_;
};

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
        inertia(stride),
        pull_own(stride),
        pull_global(stride),
        global_best(detail::kSplat * rows),
        key(stride, std::numeric_limits<std::int64_t>::max()),
        improved(stride),
        signed_vertices(3 * detail::kSplat * rows),
        lanes(7),
        view{rows, particles, stride, position.data(), velocity.data(), personal_best.data()} {}
  double& at(std::vector<double>& m, int r, int j) { return m[r * stride + j]; }
  // The kernels read values shared by all particles as kSplat copies.
  void set_global_best(int r, double w) {
    for (int c = 0; c < detail::kSplat; ++c) global_best[detail::kSplat * r + c] = w;
  }
  void set_vertex(int r, double x, double y, double z) {
    const double coordinates[3] = {x, y, z};
    for (int c = 0; c < 3 * detail::kSplat; ++c) {
      signed_vertices[3 * detail::kSplat * r + c] = coordinates[c / detail::kSplat];
    }
  }

  bool advance(int rows_a, double limit, bool project) {
    const detail::Move move{
        inertia.data(), pull_own.data(), pull_global.data(), global_best.data(), limit,
        project,        &lanes};
    const detail::Fitness fitness{signed_vertices.data(), !project, 1e-12};
    return detail::advance_particles(view, rows_a, move, fitness, {key.data(), improved.data()},
                                     next.data());
  }

  int rows;
  int stride;
  std::vector<double> position, velocity, personal_best, next;
  std::vector<double> inertia, pull_own, pull_global, global_best;
  std::vector<std::int64_t> key, improved;
  std::vector<double> signed_vertices;
  detail::UniformLanes lanes;
  SwarmView view;
};

// The key of a feasible particle whose squared objective is `value`.
std::int64_t feasible_key(double value) {
  return __builtin_bit_cast(std::int64_t, value) - detail::kFeasibleKeyShift;
}

VectorX uniform_simplex_point(int k, std::mt19937_64& rng) {
  std::exponential_distribution<double> E;
  VectorX w(k);
  for (int i = 0; i < k; ++i) w(i) = E(rng);
  return w / w.sum();
}

TEST(SwarmKernels, ProjectionMatchesTheSortBasedProjectionForAnyNumberOfWeights) {
  // Sorting networks up to 16 weights, Michelot's passes above.
  std::vector<int> counts(20);
  std::iota(counts.begin(), counts.end(), 1);
  counts.insert(counts.end(), {24, 33, 64, 70});
  std::vector<std::vector<double>> first_isa;
  for (KernelIsa isa : available_isas()) {
    UsingIsa using_isa(isa);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> U(-1, 2);
    for (std::size_t c = 0; c < counts.size(); ++c) {
      const int k = counts[c];
      const int particles = 45;
      // A's k rows, then B's single weight of 1, which projects onto itself.
      TestSwarm s(k + 1, particles);
      for (int j = 0; j < particles; ++j) {
        // Ties (every fifth column), points already on the simplex (every seventh), and columns
        // whose weights all lie far below or above it.
        const VectorX inside = uniform_simplex_point(k, rng);
        for (int r = 0; r < k; ++r) {
          double w = U(rng);
          if (j % 5 == 0) w = r % 2 ? 0.75 : -0.25;
          if (j % 7 == 0) w = inside(r);
          if (j == 11) w -= 5;
          if (j == 13) w += 5;
          s.at(s.position, r, j) = w;
        }
        s.at(s.position, k, j) = 1.0;
      }
      // No inertia and no pulls: the move leaves every particle where it is, then projects it.
      const std::vector<double> before = s.position;
      s.advance(k, 1.0, true);
      for (int j = 0; j < particles; ++j) {
        VectorX column(k);
        for (int r = 0; r < k; ++r) column(r) = before[r * s.stride + j];
        const VectorX expected = project_onto_simplex(column);
        double total = 0;
        for (int r = 0; r < k; ++r) {
          EXPECT_NEAR(s.at(s.next, r, j), expected(r), 1e-14)
              << detail::kernel_isa_name(isa) << " k " << k << " particle " << j;
          EXPECT_GE(s.at(s.next, r, j), 0.0);
          EXPECT_EQ(s.at(s.velocity, r, j), s.at(s.next, r, j) - column(r));
          total += s.at(s.next, r, j);
        }
        EXPECT_NEAR(total, 1.0, 1e-14);
        EXPECT_EQ(s.at(s.next, k, j), 1.0);
      }
      if (first_isa.size() < counts.size()) {
        first_isa.push_back(s.next);
      } else {
        EXPECT_EQ(s.next, first_isa[c]) << detail::kernel_isa_name(isa) << " k " << k;
      }
    }
  }
}

// xoshiro256++ on one lane of the kernels' generators.
std::uint64_t step(detail::UniformLanes& lanes, int lane) {
  auto rotl = [](std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); };
  std::uint64_t* s[4] = {&lanes.state[0][lane], &lanes.state[1][lane], &lanes.state[2][lane],
                         &lanes.state[3][lane]};
  const std::uint64_t result = rotl(*s[0] + *s[3], 23) + *s[0];
  const std::uint64_t t = *s[1] << 17;
  *s[2] ^= *s[0];
  *s[3] ^= *s[1];
  *s[1] ^= *s[2];
  *s[0] ^= *s[3];
  *s[2] ^= t;
  *s[3] = rotl(*s[3], 45);
  return result;
}

TEST(SwarmKernels, ProjectedMoveDrawsBothRandomFactorsPerWeightAsEquation3Does) {
  // Bodies of 5 and 3 weights (sorting networks) and of 20 and 18 (Michelot's passes).
  for (const auto& [rows_a, rows_b] : {std::pair{5, 3}, std::pair{20, 18}}) {
    const int rows = rows_a + rows_b;
    const int particles = 13;
    for (KernelIsa isa : available_isas()) {
      UsingIsa using_isa(isa);
      std::mt19937_64 rng(17);
      std::uniform_real_distribution<double> U(0, 1);
      TestSwarm s(rows, particles);
      const auto fill = [&](std::vector<double>& m, int j) {
        const VectorX a = uniform_simplex_point(rows_a, rng);
        const VectorX b = uniform_simplex_point(rows_b, rng);
        for (int r = 0; r < rows; ++r) s.at(m, r, j) = r < rows_a ? a(r) : b(r - rows_a);
      };
      for (int j = 0; j < s.stride; ++j) {
        fill(s.position, j);
        fill(s.personal_best, j);
        for (int r = 0; r < rows; ++r) s.at(s.velocity, r, j) = 0.4 * U(rng) - 0.2;
        s.inertia[j] = U(rng);
        s.pull_own[j] = 2 * U(rng);
        s.pull_global[j] = 2 * U(rng);
      }
      const VectorX g_a = uniform_simplex_point(rows_a, rng);
      const VectorX g_b = uniform_simplex_point(rows_b, rng);
      for (int r = 0; r < rows; ++r) s.set_global_best(r, r < rows_a ? g_a(r) : g_b(r - rows_a));
      const TestSwarm before = s;
      const double limit = 0.05;
      s.advance(rows_a, limit, true);

      // Lane l serves particles j = l (mod 8), one draw per row, in column then row order.
      detail::UniformLanes lanes = before.lanes;
      for (int j = 0; j < particles; ++j) {
        VectorX moved(rows);
        for (int r = 0; r < rows; ++r) {
          const std::uint64_t bits = step(lanes, j % kLanes);
          const double r1 = static_cast<double>(bits >> 32) * 0x1.0p-32;
          const double r2 = static_cast<double>(bits & 0xffffffffULL) * 0x1.0p-32;
          const double x = before.position[r * s.stride + j];
          const double v = before.velocity[r * s.stride + j];
          const double p = before.personal_best[r * s.stride + j];
          const double velocity = s.inertia[j] * v + s.pull_own[j] * r1 * (p - x) +
                                  s.pull_global[j] * r2 * (s.global_best[detail::kSplat * r] - x);
          moved(r) = x + std::clamp(velocity, -limit, limit);
        }
        VectorX expected(rows);
        expected << project_onto_simplex(moved.head(rows_a)),
            project_onto_simplex(moved.tail(rows_b));
        for (int r = 0; r < rows; ++r) {
          const double x = before.position[r * s.stride + j];
          EXPECT_NEAR(s.at(s.next, r, j), expected(r), 1e-15)
              << detail::kernel_isa_name(isa) << " particle " << j << " row " << r;
          EXPECT_NEAR(s.at(s.velocity, r, j), expected(r) - x, 1e-15);
        }
      }
      // The padding columns drew their numbers too, so every lane is as far along.
      for (int j = particles; j < s.stride; ++j) {
        for (int r = 0; r < rows; ++r) step(lanes, j % kLanes);
      }
      for (int word = 0; word < 4; ++word) {
        for (int lane = 0; lane < kLanes; ++lane) {
          EXPECT_EQ(s.lanes.state[word][lane], lanes.state[word][lane]);
        }
      }
    }
  }
}

TEST(SwarmKernels, OrderIsByPersonalBestWithTiesToTheLowerIndexFromTheOrderAndTheMarkedParticles) {
  std::mt19937_64 rng(5);
  // More marked particles than the insertion sort takes (64) as well.
  for (const int particles : {29, 300}) {
    std::vector<double> feasible(particles), value(particles);
    for (int j = 0; j < particles; ++j) {
      feasible[j] = rng() % 3 ? 1.0 : 0.0;
      value[j] = static_cast<double>(rng() % 6) * 0.25;  // many exact ties
    }
    value[4] = 1e300;
    value[7] = 0.0;
    std::vector<int> order(particles);
    std::iota(order.begin(), order.end(), 0);
    // Every particle is marked at first, as after the initial scoring.
    std::vector<std::int64_t> improved(particles, 1);
    std::vector<detail::RankedParticle> scratch(2 * (particles + 1));
    // Generations: some particles' scores fall, as personal bests do, and are marked; the order is
    // kept. Once the order is shuffled, with every particle marked.
    for (int generation = 0; generation < 8; ++generation) {
      std::vector<std::int64_t> key(particles);
      for (int j = 0; j < particles; ++j) {
        key[j] =
            feasible[j] != 0 ? feasible_key(value[j]) : __builtin_bit_cast(std::int64_t, value[j]);
      }
      if (generation == 3) {
        std::shuffle(order.begin(), order.end(), rng);
        std::fill(improved.begin(), improved.end(), 1);
      }
      detail::order_by_personal_best(particles, key.data(), improved.data(), order.data(),
                                     scratch.data());

      std::vector<int> expected(particles);
      std::iota(expected.begin(), expected.end(), 0);
      std::stable_sort(expected.begin(), expected.end(), [&](int a, int b) {
        if (feasible[a] != feasible[b]) return feasible[a] > feasible[b];
        return value[a] < value[b];
      });
      EXPECT_EQ(order, expected) << "generation " << generation;
      // Next: a third of the particles fall; after generation 4 none changes; after generation 5
      // every particle falls but the best, which is marked and goes to the end (any change of a
      // marked particle is allowed).
      std::fill(improved.begin(), improved.end(), 0);
      for (int j = 0; j < particles; ++j) {
        if (generation == 4 || (generation != 5 && j % 3 != 0)) continue;
        improved[j] = 1;
        if (generation == 5 && j == order[0]) {
          feasible[j] = 0;
          value[j] = 1e308;
        } else if (feasible[j] == 0 && rng() % 2) {
          feasible[j] = 1;
        } else {
          value[j] *= 0.5;
        }
      }
    }

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
  std::vector<double> first;
  for (KernelIsa isa : available_isas()) {
    UsingIsa using_isa(isa);
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
    // Lane l's k-th number is element 8 k + l.
    detail::UniformLanes replay(11);
    for (int k = 0; k < 3; ++k) {
      for (int l = 0; l < kLanes; ++l) {
        const std::uint64_t bits = step(replay, l);
        EXPECT_EQ(u[kLanes * k + l], static_cast<double>(bits >> 12) * 0x1.0p-52);
      }
    }
    if (first.empty()) {
      first = u;
    } else {
      EXPECT_EQ(u, first) << detail::kernel_isa_name(isa);
    }
  }
}

TEST(SwarmKernels, ALiteralMoveOverTheLimitScalesTheWholeVelocityAndKeepsTheSums) {
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
  for (bool project : {true, false}) {
    TestSwarm s(rows, particles);
    s.set_vertex(0, -1, 0, 0);
    s.set_vertex(1, 0, 0, 0);
    s.set_vertex(2, 3, 0, 0);
    for (int j = 0; j < particles; ++j) {
      s.at(s.position, 0, j) = 0.5;
      s.at(s.position, 1, j) = 0.5;
      s.at(s.position, 2, j) = 1.0;
    }
    // Particle 0 had a better best, particle 1 a worse one, particle 2 an infeasible one.
    s.key = {feasible_key(2.0), feasible_key(9.0), __builtin_bit_cast(std::int64_t, 0.25)};
    s.key.resize(s.stride, std::numeric_limits<std::int64_t>::max());
    const std::vector<double> best_before = s.personal_best;
    EXPECT_TRUE(s.advance(rows_a, 10.0, project));
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
}

TEST(SwarmKernels, InstructionSetsAreNamedAndTheBaselineAlwaysRuns) {
  for (KernelIsa isa : {KernelIsa::baseline, KernelIsa::avx2, KernelIsa::avx512}) {
    EXPECT_EQ(detail::kernel_isa_from_name(detail::kernel_isa_name(isa)), isa);
  }
  EXPECT_FALSE(detail::kernel_isa_from_name("sse2").has_value());
  EXPECT_FALSE(detail::kernel_isa_from_name("").has_value());
  EXPECT_TRUE(detail::kernel_isa_available(KernelIsa::baseline));
  EXPECT_TRUE(detail::kernel_isa_available(detail::kernel_isa()));
  for (KernelIsa isa : {KernelIsa::avx2, KernelIsa::avx512}) {
    if (!detail::kernel_isa_available(isa)) {
      EXPECT_THROW(detail::use_kernel_isa(isa), std::invalid_argument);
    }
  }
}

}  // namespace
}  // namespace swarmcollide
