#include "swarmcollide/solvers/penalty_options.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace swarmcollide {

void PenaltyOptions::validate() const {
  if (!(std::isfinite(initial_weight) && initial_weight > 0)) {
    throw std::invalid_argument("initial_weight must be a finite number > 0");
  }
  if (!(std::isfinite(growth_factor) && growth_factor > 1)) {
    throw std::invalid_argument("growth_factor must be a finite number > 1");
  }
  if (outer_iterations < 1) {
    throw std::invalid_argument("outer_iterations must be at least 1, got " +
                                std::to_string(outer_iterations));
  }
  if (inner_iterations < 1) {
    throw std::invalid_argument("inner_iterations must be at least 1, got " +
                                std::to_string(inner_iterations));
  }
  if (!(std::isfinite(tolerance) && tolerance >= 0)) {
    throw std::invalid_argument("tolerance must be a finite number >= 0");
  }
}

}  // namespace swarmcollide
