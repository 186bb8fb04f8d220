#include "swarmcollide/solvers/swarm.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "swarmcollide/detail/random.hpp"
#include "swarmcollide/problem/certificate.hpp"
#include "swarmcollide/problem/simplex.hpp"

namespace swarmcollide {

ParticleCoefficients rank_adaptive_coefficients(int rank, int swarm_size, Scalar w_min,
                                                Scalar w_max) {
  if (swarm_size < 2 || rank < 1 || rank > swarm_size) {
    throw std::invalid_argument("rank must lie in [1, swarm_size] and swarm_size must be >= 2");
  }
  const Scalar w = w_min + (w_max - w_min) * static_cast<Scalar>(swarm_size - rank) /
                               static_cast<Scalar>(swarm_size - 1);
  const Scalar c = (w + 1 + 2 * std::sqrt(w)) / 2;
  return {w, c, c};
}

Scalar linear_decreasing_inertia(int iteration, int max_iterations, Scalar w_start, Scalar w_end) {
  if (max_iterations <= 0) return w_start;
  return (w_start - w_end) * static_cast<Scalar>(max_iterations - iteration) /
             static_cast<Scalar>(max_iterations) +
         w_end;
}

namespace {

using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
using Matrix3X = Eigen::Matrix<Scalar, 3, Eigen::Dynamic>;

// Fitness under the feasibility ordering of Conditions 1-3: feasible particles compare by the
// objective (5), infeasible ones by the violation (6), and any feasible one beats any infeasible.
struct Fitness {
  bool feasible = false;
  Scalar value = 0;
};

bool better(const Fitness& a, const Fitness& b) {
  if (a.feasible != b.feasible) return a.feasible;
  return a.value < b.value;
}

class SwarmSolver {
 public:
  SwarmSolver(const ConvexPolyhedron& a, const ConvexPolyhedron& b, const SwarmOptions& options)
      : a_(a),
        b_(b),
        options_(options),
        ka_(a.size()),
        kb_(b.size()),
        xa_(a.vertices().transpose()),
        yb_(b.vertices().transpose()),
        rng_(options.seed),
        position_(ka_ + kb_, options.swarm_size),
        velocity_(ka_ + kb_, options.swarm_size),
        fitness_(options.swarm_size),
        coefficients_(options.swarm_size) {}

  DistanceResult run() {
    initialise();
    personal_best_ = position_;
    personal_fitness_ = fitness_;
    update_global_best();
    record_best();
    int iteration = 0;
    while (iteration < options_.max_iterations && !precision_reached()) {
      assign_coefficients(iteration);
      move_particles();
      evaluate();
      update_personal_bests();
      update_global_best();
      ++iteration;
      record_best();
    }
    result_.iterations = iteration;
    result_.evaluations = static_cast<long>(options_.swarm_size) * (iteration + 1);
    result_.colliding = result_.distance <= options_.tolerance;
    result_.certified = result_.colliding || result_.lower_bound > options_.tolerance;
    result_.status = precision_reached() ? SolverStatus::converged : SolverStatus::max_iterations;
    return std::move(result_);
  }

 private:
  int dimension() const { return ka_ + kb_; }

  void fill_simplex(Eigen::Ref<VectorX> weights) {
    for (Eigen::Index i = 0; i < weights.size(); ++i) weights(i) = -std::log1p(-rng_.uniform());
    weights /= weights.sum();
  }

  // Step 1. Positions are uniform on the two simplexes, so every particle starts feasible;
  // velocities point to a second uniform point, so the first move stays on the constraint planes.
  void initialise() {
    VectorX target(dimension());
    for (int j = 0; j < options_.swarm_size; ++j) {
      fill_simplex(position_.col(j).head(ka_));
      fill_simplex(position_.col(j).tail(kb_));
      fill_simplex(target.head(ka_));
      fill_simplex(target.tail(kb_));
      velocity_.col(j) = target - position_.col(j);
    }
    evaluate();
  }

  void evaluate() {
    const Matrix3X gap = yb_ * position_.bottomRows(kb_) - xa_ * position_.topRows(ka_);
    for (int j = 0; j < options_.swarm_size; ++j) {
      const Scalar ea = position_.col(j).head(ka_).sum() - 1;
      const Scalar eb = position_.col(j).tail(kb_).sum() - 1;
      const Scalar violation = ea * ea + eb * eb;
      const auto column = position_.col(j).array();
      fitness_[j].feasible =
          violation <= options_.feasibility_tolerance && (column >= 0).all() && (column <= 1).all();
      fitness_[j].value = fitness_[j].feasible ? gap.col(j).norm() : violation;
    }
  }

  void assign_coefficients(int iteration) {
    const int n = options_.swarm_size;
    if (options_.inertia == InertiaStrategy::linear_decreasing) {
      const Scalar w = linear_decreasing_inertia(iteration, options_.max_iterations, options_.w_max,
                                                 options_.w_min);
      std::fill(coefficients_.begin(), coefficients_.end(),
                ParticleCoefficients{w, options_.c1, options_.c2});
      return;
    }
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int i, int j) {
      return better(personal_fitness_[i], personal_fitness_[j]);
    });
    for (int rank = 1; rank <= n; ++rank) {
      coefficients_[order[rank - 1]] =
          rank_adaptive_coefficients(rank, n, options_.w_min, options_.w_max);
    }
  }

  // Step 2: updates (10)-(11). r1 and r2 are one draw per particle, as (10) is written, so a move
  // is a combination of differences of feasible points and keeps the sums of (2) at one. The
  // velocity limit scales the whole vector for the same reason.
  void move_particles() {
    for (int j = 0; j < options_.swarm_size; ++j) {
      const ParticleCoefficients& c = coefficients_[j];
      const Scalar r1 = rng_.uniform();
      const Scalar r2 = rng_.uniform();
      auto x = position_.col(j);
      auto v = velocity_.col(j);
      v = c.w * v + c.c1 * r1 * (personal_best_.col(j) - x) +
          c.c2 * r2 * (personal_best_.col(global_best_) - x);
      const Scalar largest = v.cwiseAbs().maxCoeff();
      if (largest > options_.velocity_limit) v *= options_.velocity_limit / largest;
      const VectorX before = x;
      x += v;
      if (options_.constraint_handling == ConstraintHandling::projection) {
        x.head(ka_) = project_onto_simplex(x.head(ka_));
        x.tail(kb_) = project_onto_simplex(x.tail(kb_));
      }
      v = x - before;
    }
  }

  // Conditions 1-3 decide whether the new position replaces the particle's best.
  void update_personal_bests() {
    for (int j = 0; j < options_.swarm_size; ++j) {
      if (better(fitness_[j], personal_fitness_[j])) {
        personal_fitness_[j] = fitness_[j];
        personal_best_.col(j) = position_.col(j);
      }
    }
  }

  void update_global_best() {
    for (int j = 0; j < options_.swarm_size; ++j) {
      if (better(personal_fitness_[j], personal_fitness_[global_best_])) global_best_ = j;
    }
  }

  // Turns the global best into an answer with exact guarantees: weights moved onto the simplexes
  // give an upper bound achieved by real points, and the direction between those points a lower
  // bound. The best of each is kept.
  void record_best() {
    VectorX lambda = to_simplex(personal_best_.col(global_best_).head(ka_));
    VectorX delta = to_simplex(personal_best_.col(global_best_).tail(kb_));
    const Vector3 pa = xa_ * lambda;
    const Vector3 pb = yb_ * delta;
    const Scalar d = (pb - pa).norm();
    if (result_.history.empty() || d < result_.distance) {
      result_.distance = d;
      result_.point_a = pa;
      result_.point_b = pb;
      result_.weights_a = std::move(lambda);
      result_.weights_b = std::move(delta);
    }
    result_.history.push_back(result_.distance);
    if (d > 0) {
      const Scalar s = separation(a_, b_, pb - pa);
      if (s > result_.lower_bound) {
        result_.lower_bound = s;
        result_.direction = (pb - pa) / d;
      }
    }
  }

  // Step 3's precision test, made rigorous by the certificate.
  bool precision_reached() const {
    const Scalar tol = options_.tolerance;
    return tol > 0 && (result_.distance - result_.lower_bound <= tol || result_.distance <= tol);
  }

  const ConvexPolyhedron& a_;
  const ConvexPolyhedron& b_;
  const SwarmOptions& options_;
  const int ka_;
  const int kb_;
  const Matrix3X xa_;
  const Matrix3X yb_;
  detail::Xoshiro256 rng_;
  Matrix position_;
  Matrix velocity_;
  Matrix personal_best_;
  std::vector<Fitness> fitness_;
  std::vector<Fitness> personal_fitness_;
  std::vector<ParticleCoefficients> coefficients_;
  int global_best_ = 0;
  DistanceResult result_;
};

}  // namespace

DistanceResult solve_swarm(const ConvexPolyhedron& a, const ConvexPolyhedron& b,
                           const SwarmOptions& options) {
  options.validate();
  DistanceResult result = SwarmSolver(a, b, options).run();
  result.method = options.inertia == InertiaStrategy::rank_adaptive ? "ipso" : "pso";
  return result;
}

}  // namespace swarmcollide
