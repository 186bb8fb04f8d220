#pragma once

namespace swarmcollide {

/// Parameters of the exact methods ("exact", "fcl", "libccd").
struct ExactOptions {
  /// Iteration cap of every loop the method runs (GJK, Wolfe's algorithm, EPA); the answer
  /// stays bounded and says `max_iterations` when a cap is reached.
  int max_iterations = 1000;
};

}  // namespace swarmcollide
