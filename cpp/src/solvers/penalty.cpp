#include "swarmcollide/solvers/penalty.hpp"

#include <LBFGS.h>
#include <LBFGSpp/LineSearchNocedalWright.h>

#include <limits>
#include <stdexcept>

#include "exact_internal.hpp"
#include "swarmcollide/problem/simplex.hpp"

namespace swarmcollide {

namespace {

using Matrix3X = Eigen::Matrix<Scalar, 3, Eigen::Dynamic>;

// The penalised objective in normalised coordinates, remembering the best point it has seen so
// that a failed line search loses nothing.
class PenalisedObjective {
 public:
  PenalisedObjective(Matrix3X x, Matrix3X y) : x_(std::move(x)), y_(std::move(y)) {}

  void set_weight(Scalar mu) {
    mu_ = mu;
    best_value_ = std::numeric_limits<Scalar>::infinity();
  }

  Scalar operator()(const VectorX& z, VectorX& gradient) {
    ++evaluations_;
    const Eigen::Index ka = x_.cols();
    const auto lambda = z.head(ka);
    const auto delta = z.tail(y_.cols());
    const Vector3 r = y_ * delta - x_ * lambda;
    const Scalar ea = lambda.sum() - 1;
    const Scalar eb = delta.sum() - 1;
    const VectorX below = z.cwiseMin(0);
    const VectorX above = (z.array() - 1).cwiseMax(0).matrix();
    const Scalar value =
        r.squaredNorm() + mu_ * (ea * ea + eb * eb + below.squaredNorm() + above.squaredNorm());
    gradient.resize(z.size());
    gradient.head(ka) = -2 * x_.transpose() * r;
    gradient.tail(y_.cols()) = 2 * y_.transpose() * r;
    gradient.head(ka).array() += 2 * mu_ * ea;
    gradient.tail(y_.cols()).array() += 2 * mu_ * eb;
    gradient += 2 * mu_ * (below + above);
    if (value < best_value_) {
      best_value_ = value;
      best_ = z;
    }
    return value;
  }

  const VectorX& best() const { return best_; }
  long evaluations() const { return evaluations_; }

 private:
  Matrix3X x_;
  Matrix3X y_;
  Scalar mu_ = 1;
  Scalar best_value_ = std::numeric_limits<Scalar>::infinity();
  VectorX best_;
  long evaluations_ = 0;
};

}  // namespace

DistanceResult solve_penalty(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                             const PenaltyOptions& options) {
  options.validate();
  const int ka = a.size();
  const int kb = b.size();
  const Aabb box = a.aabb();
  const Vector3 centre = (box.min + box.max) / 2;
  Scalar scale = exact_internal::pair_scale(a, b);
  if (!(scale > 0)) scale = 1;
  PenalisedObjective objective((a.vertices().rowwise() - centre.transpose()).transpose() / scale,
                               (b.vertices().rowwise() - centre.transpose()).transpose() / scale);

  VectorX z(ka + kb);
  z.head(ka).setConstant(Scalar(1) / ka);
  z.tail(kb).setConstant(Scalar(1) / kb);

  LBFGSpp::LBFGSParam<Scalar> param;
  param.max_iterations = options.inner_iterations;
  param.epsilon = 1e-12;
  param.epsilon_rel = 0;
  param.max_linesearch = 60;
  param.linesearch = LBFGSpp::LBFGS_LINESEARCH_BACKTRACKING_STRONG_WOLFE;
  LBFGSpp::LBFGSSolver<Scalar, LBFGSpp::LineSearchNocedalWright> solver(param);

  DistanceResult best;
  Scalar best_lower = 0;
  Vector3 best_direction = Vector3::Zero();
  int iterations = 0;
  Scalar mu = options.initial_weight;
  bool converged = false;
  for (int k = 0; k < options.outer_iterations && !converged; ++k, mu *= options.growth_factor) {
    objective.set_weight(mu);
    Scalar value = 0;
    try {
      iterations += solver.minimize(objective, z, value);
      z = objective.best();
    } catch (const std::exception&) {
      // LBFGSpp throws when a line search cannot progress (the subproblem is solved to
      // rounding); the best point evaluated stands, and its iterations go uncounted.
      z = objective.best();
    }
    DistanceResult current = exact_internal::result_from_weights(
        a, b, to_simplex(z.head(ka)), to_simplex(z.tail(kb)), "penalty", options.tolerance);
    if (current.lower_bound > best_lower) {
      best_lower = current.lower_bound;
      best_direction = current.direction;
    }
    if (best.history.empty() || current.distance < best.distance) {
      std::vector<Scalar> history = std::move(best.history);
      best = std::move(current);
      best.history = std::move(history);
    }
    best.history.push_back(best.distance);
    const Scalar tol = options.tolerance;
    converged = tol > 0 && (best.distance - best_lower <= tol || best.distance <= tol);
  }
  best.lower_bound = best_lower;
  best.direction = best_direction;
  best.colliding = best.distance <= options.tolerance;
  best.certified = best.colliding || best.lower_bound > options.tolerance;
  best.iterations = iterations;
  best.evaluations = objective.evaluations();
  best.status = converged ? SolverStatus::converged : SolverStatus::max_iterations;
  return best;
}

}  // namespace swarmcollide
