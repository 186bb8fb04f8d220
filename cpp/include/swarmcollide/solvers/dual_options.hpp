#pragma once

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Parameters of the dual swarm ("dual"): the paper's rank-adaptive swarm (8)-(11) over unit
/// directions, with an exact finish on the supporting features.
///
/// The swarm runs in rounds: a round seeds `swarm_size` particles in a disc of the tangent plane
/// around the best direction so far and runs up to `max_iterations` iterations; the exact finish
/// runs whenever the best direction reaches a new pair of support points, and at the end of the
/// round. Rounds repeat until the answer is certified to the query's tolerance or `max_rounds`
/// have run.
struct DualOptions {
  /// N_p, the number of particles of a round.
  int swarm_size = 12;
  /// Iteration budget of one round.
  int max_iterations = 30;
  /// Smallest and largest inertia weight of (8).
  Scalar w_min = 0.4;
  Scalar w_max = 0.9;
  /// Slack, relative to the pair's size, within which a point counts as lying on a supporting
  /// plane when the finish collects the supporting features. Larger finds the optimal features
  /// from a coarser direction, at the cost of larger (still small) exact subproblems.
  Scalar feature_tolerance = 1e-3;
  /// Largest number of rounds (the first plus re-seedings).
  int max_rounds = 20;
  /// Keep the best upper bound after each iteration (the answer's `history`). Batches, which
  /// report none, turn it off: it is what a warmed-up search would otherwise allocate per pair.
  bool record_history = true;
};

}  // namespace swarmcollide
