#include "swarmcollide/problem/distance_model.hpp"

#include <stdexcept>
#include <string>

namespace swarmcollide {

namespace {

void check_weights(const ConvexPolyhedron& body, const WeightsRef& weights, const char* name) {
  if (weights.size() != body.size()) {
    throw std::invalid_argument(std::string(name) + " has " + std::to_string(weights.size()) +
                                " weights but the body has " + std::to_string(body.size()) +
                                " points");
  }
}

}  // namespace

Scalar objective(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const WeightsRef& lambda,
                 const WeightsRef& delta) {
  check_weights(a, lambda, "lambda");
  check_weights(b, delta, "delta");
  return (b.vertices().transpose() * delta - a.vertices().transpose() * lambda).norm();
}

Scalar constraint_violation(const WeightsRef& lambda, const WeightsRef& delta) {
  const Scalar ea = lambda.sum() - 1;
  const Scalar eb = delta.sum() - 1;
  return ea * ea + eb * eb;
}

bool is_feasible(const WeightsRef& lambda, const WeightsRef& delta, Scalar tolerance) {
  const auto in_unit_interval = [](const WeightsRef& w) {
    return (w.array() >= 0).all() && (w.array() <= 1).all();
  };
  return in_unit_interval(lambda) && in_unit_interval(delta) &&
         constraint_violation(lambda, delta) <= tolerance;
}

}  // namespace swarmcollide
