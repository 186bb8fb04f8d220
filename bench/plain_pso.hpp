// The reference the swarm's kernels are timed against: the same method as swarmcollide's "ipso"
// with projection, written as a plain scalar loop over particles and weights. Its other settings
// are the alternatives docs/method.md measured for the choices the paper leaves open.
#pragma once

#include <cstdint>

/// What a particle's velocity is after its move was projected onto the simplexes.
enum class VelocityAfterProjection {
  move_made,       ///< the projected position minus the old one (swarmcollide's choice)
  unprojected,     ///< the velocity of (10), as if nothing had been projected
  clipped_zeroed,  ///< that velocity with the components the projection set to 0 zeroed
};

/// The method's parameters and choices, with swarmcollide's defaults.
struct PlainPsoOptions {
  int swarm_size = 40;
  int max_iterations = 200;
  double w_min = 0.4;
  double w_max = 0.9;
  double velocity_limit = 0.02;
  /// r1 and r2 drawn per weight, as (3); otherwise one pair per particle, as (10) reads.
  bool factors_per_weight = true;
  /// A velocity over the limit scaled as a whole; otherwise each component clamped.
  bool scale_whole_velocity = false;
  VelocityAfterProjection after_projection = VelocityAfterProjection::move_made;
  /// The global best updated after every particle's move; otherwise after each generation.
  bool asynchronous = false;
};

/// The distance found between the hulls of `a` (`ka` points, x y z each) and `b` (`kb` points)
/// after the whole budget: rank-adaptive coefficients (8)-(9), update (3) (by default with r1 and
/// r2 per weight and components clamped to the velocity limit), each body's weights projected onto
/// its simplex after every move (sort-based), and Conditions 1-3 for the personal bests.
double plain_pso(const double* a, int ka, const double* b, int kb, const PlainPsoOptions& options,
                 std::uint64_t seed);
