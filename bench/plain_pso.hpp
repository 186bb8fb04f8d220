// The reference the swarm's kernels are timed against: the same method as swarmcollide's "ipso"
// with projection, written as a plain scalar loop over particles and weights.
#pragma once

#include <cstdint>

/// The method's parameters, with swarmcollide's defaults.
struct PlainPsoOptions {
  int swarm_size = 40;
  int max_iterations = 200;
  double w_min = 0.4;
  double w_max = 0.9;
  double velocity_limit = 0.02;
};

/// The distance found between the hulls of `a` (`ka` points, x y z each) and `b` (`kb` points)
/// after the whole budget: rank-adaptive coefficients (8)-(9), update (3) with r1 and r2 per
/// weight, components clamped to the velocity limit, each body's weights projected onto its
/// simplex after every move (sort-based), and Conditions 1-3 for the personal bests.
double plain_pso(const double* a, int ka, const double* b, int kb, const PlainPsoOptions& options,
                 std::uint64_t seed);
