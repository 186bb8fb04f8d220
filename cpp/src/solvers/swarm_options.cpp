#include "swarmcollide/solvers/swarm_options.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace swarmcollide {

namespace {

// Messages are only built on failure, so that validating allocates nothing.
void require(bool condition, const char* message) {
  if (!condition) throw std::invalid_argument(message);
}

bool finite_nonnegative(Scalar x) { return std::isfinite(x) && x >= 0; }

}  // namespace

void SwarmOptions::validate() const {
  if (swarm_size < 2) {
    throw std::invalid_argument(
        "swarm_size must be at least 2 (the ranking (8) divides by N_p - 1), got " +
        std::to_string(swarm_size));
  }
  if (max_iterations < 0) {
    throw std::invalid_argument("max_iterations must be nonnegative, got " +
                                std::to_string(max_iterations));
  }
  require(finite_nonnegative(w_min), "w_min must be a finite number >= 0");
  require(finite_nonnegative(w_max), "w_max must be a finite number >= 0");
  require(w_min <= w_max, "w_min must not exceed w_max");
  require(finite_nonnegative(c1), "c1 must be a finite number >= 0");
  require(finite_nonnegative(c2), "c2 must be a finite number >= 0");
  require(std::isfinite(velocity_limit) && velocity_limit > 0,
          "velocity_limit must be a finite number > 0");
  require(finite_nonnegative(tolerance), "tolerance must be a finite number >= 0");
  require(finite_nonnegative(feasibility_tolerance),
          "feasibility_tolerance must be a finite number >= 0");
}

}  // namespace swarmcollide
