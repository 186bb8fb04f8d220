#include "swarmcollide/solvers/exact_options.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace swarmcollide {

void ExactOptions::validate() const {
  if (!(std::isfinite(distance_tolerance) && distance_tolerance > 0)) {
    throw std::invalid_argument("distance_tolerance must be a finite number > 0");
  }
  if (!(std::isfinite(penetration_tolerance) && penetration_tolerance > 0)) {
    throw std::invalid_argument("penetration_tolerance must be a finite number > 0");
  }
  if (max_iterations < 1) {
    throw std::invalid_argument("max_iterations must be at least 1, got " +
                                std::to_string(max_iterations));
  }
  if (!(std::isfinite(tolerance) && tolerance >= 0)) {
    throw std::invalid_argument("tolerance must be a finite number >= 0");
  }
}

}  // namespace swarmcollide
