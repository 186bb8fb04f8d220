#include <LBFGS.h>
#include <LBFGSpp/LineSearchNocedalWright.h>

#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "../detail/interruption.hpp"
#include "penalty_method.hpp"
#include "swarmcollide/problem/simplex.hpp"
#include "witness.hpp"

namespace swarmcollide::detail {

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
    // One subproblem can take a million L-BFGS iterations, each a few evaluations of about 0.1
    // us at 8 points a body: every 64th asks whether to stop, so that a check reading a clock
    // costs the solve nothing measurable.
    if (evaluations_ % 64 == 0) stop_if_interrupted_();
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
  const InterruptionPoll stop_if_interrupted_;
};

}  // namespace

Answer solve_penalty(const FramedPair& pair, const QueryOptions& query, Goal goal) {
  if (goal == Goal::signed_distance) {
    throw std::invalid_argument("the penalty method measures no penetration depth");
  }
  const PenaltyOptions& options = query.penalty;
  const int ka = pair.a.given_size();
  const int kb = pair.b.given_size();
  VertexMatrix points_a;
  VertexMatrix points_b;
  pair.a.given_points(points_a);
  pair.b.given_points(points_b);
  // The frame's coordinates are of order one, so the weights mean the same for bodies of any
  // size and position.
  PenalisedObjective objective(points_a.transpose(), points_b.transpose());

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

  Answer best;
  History history;
  Scalar best_lower = -std::numeric_limits<Scalar>::infinity();
  Vector3 best_direction = Vector3::Zero();
  int iterations = 0;
  Scalar mu = options.initial_weight;
  const Scalar tol = pair.tolerance;
  bool settled = false;
  for (int k = 0; k < options.outer_iterations && !settled; ++k, mu *= options.growth_factor) {
    objective.set_weight(mu);
    Scalar value = 0;
    try {
      iterations += solver.minimize(objective, z, value);
      z = objective.best();
    } catch (const Interrupted&) {
      throw;
    } catch (const std::exception&) {
      // LBFGSpp throws when a line search cannot progress (the subproblem is solved to
      // rounding); the best point evaluated stands, and its iterations go uncounted.
      z = objective.best();
    }
    Answer current = answer_from_weights(pair, points_a, points_b, to_simplex(z.head(ka)),
                                         to_simplex(z.tail(kb)));
    if (current.lower > best_lower) {
      best_lower = current.lower;
      best_direction = current.direction;
    }
    if (history.empty() || current.upper < best.upper) best = std::move(current);
    history.push_back(best.upper);
    settled = tol > 0 && (best.upper - best_lower <= tol || best.upper + kFrameRounding <= tol ||
                          (goal == Goal::verdict && best_lower - kFrameRounding > tol));
  }
  best.lower = best_lower;
  best.direction = best_direction;
  best.iterations = iterations;
  best.evaluations = objective.evaluations();
  best.history = std::move(history);
  return best;
}

}  // namespace swarmcollide::detail
