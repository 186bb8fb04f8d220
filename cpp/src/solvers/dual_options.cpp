#include "swarmcollide/solvers/dual_options.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace swarmcollide {

void DualOptions::validate() const {
  if (swarm_size < 2) {
    throw std::invalid_argument("swarm_size must be at least 2, got " + std::to_string(swarm_size));
  }
  if (max_iterations < 0) {
    throw std::invalid_argument("max_iterations must be >= 0, got " +
                                std::to_string(max_iterations));
  }
  if (!(std::isfinite(w_min) && w_min >= 0)) {
    throw std::invalid_argument("w_min must be a finite number >= 0");
  }
  if (!(std::isfinite(w_max) && w_max >= w_min)) {
    throw std::invalid_argument("w_max must be a finite number >= w_min");
  }
  if (!(std::isfinite(tolerance) && tolerance >= 0)) {
    throw std::invalid_argument("tolerance must be a finite number >= 0");
  }
  if (!(std::isfinite(relative_tolerance) && relative_tolerance > 0)) {
    throw std::invalid_argument("relative_tolerance must be a finite number > 0");
  }
  if (!(std::isfinite(feature_tolerance) && feature_tolerance >= 0)) {
    throw std::invalid_argument("feature_tolerance must be a finite number >= 0");
  }
  if (max_rounds < 1) {
    throw std::invalid_argument("max_rounds must be at least 1, got " + std::to_string(max_rounds));
  }
}

}  // namespace swarmcollide
