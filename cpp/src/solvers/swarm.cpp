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

// Structure of arrays: one row per weight, one column per particle, each row contiguous, so every
// step of the update is an element-wise loop over the particles that the compiler vectorises.
using SwarmMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Matrix3X = Eigen::Matrix<Scalar, 3, Eigen::Dynamic>;

// One row of (10) over the whole swarm, tracking each particle's largest velocity component. The
// pointers never alias; saying so lets the compiler vectorise.
void update_velocity_row(int count, const Scalar* __restrict w, const Scalar* __restrict c1r1,
                         const Scalar* __restrict c2r2, const Scalar* __restrict own, Scalar global,
                         const Scalar* __restrict x, Scalar* __restrict v,
                         Scalar* __restrict largest) {
  for (int j = 0; j < count; ++j) {
    const Scalar velocity = w[j] * v[j] + c1r1[j] * (own[j] - x[j]) + c2r2[j] * (global - x[j]);
    const Scalar magnitude = velocity < 0 ? -velocity : velocity;
    v[j] = velocity;
    largest[j] = magnitude > largest[j] ? magnitude : largest[j];
  }
}

// One row of (11) with each particle's velocity scale, tracking its smallest weight.
void move_row(int count, const Scalar* __restrict scale, Scalar* __restrict v, Scalar* __restrict x,
              Scalar* __restrict lowest) {
  for (int j = 0; j < count; ++j) {
    v[j] *= scale[j];
    x[j] += v[j];
    lowest[j] = x[j] < lowest[j] ? x[j] : lowest[j];
  }
}

// One weight's contribution to every particle's gap (5) and weight sum (6).
void accumulate_row(int count, const Scalar* __restrict w, Scalar vx, Scalar vy, Scalar vz,
                    Scalar* __restrict gx, Scalar* __restrict gy, Scalar* __restrict gz,
                    Scalar* __restrict sum) {
  for (int j = 0; j < count; ++j) {
    gx[j] += vx * w[j];
    gy[j] += vy * w[j];
    gz[j] += vz * w[j];
    sum[j] += w[j];
  }
}

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
        size_(options.swarm_size),
        xa_(a.vertices().transpose()),
        yb_(b.vertices().transpose()),
        rng_(options.seed),
        position_(ka_ + kb_, size_),
        velocity_(ka_ + kb_, size_),
        fitness_(size_),
        inertia_(size_),
        pull_own_(size_),
        pull_global_(size_),
        per_particle_(7, size_),
        column_(ka_ + kb_),
        lambda_(ka_),
        delta_(kb_),
        order_(size_) {
    std::iota(order_.begin(), order_.end(), 0);
    if (options.inertia == InertiaStrategy::rank_adaptive) {
      for (int rank = 1; rank <= size_; ++rank) {
        by_rank_.push_back(rank_adaptive_coefficients(rank, size_, options.w_min, options.w_max));
      }
    }
  }

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
      const bool improved = update_personal_bests();
      if (improved) update_global_best();
      ++iteration;
      if (improved) record_best();
      result_.history.push_back(result_.distance);
    }
    result_.iterations = iteration;
    result_.evaluations = static_cast<long>(size_) * (iteration + 1);
    result_.colliding = result_.distance <= options_.tolerance;
    result_.certified = result_.colliding || result_.lower_bound > options_.tolerance;
    result_.status = precision_reached() ? SolverStatus::converged : SolverStatus::max_iterations;
    return std::move(result_);
  }

 private:
  int dimension() const { return ka_ + kb_; }

  // A uniform point of the simplex: the gaps between k - 1 sorted uniform numbers in [0, 1].
  void fill_simplex(Eigen::Ref<VectorX> weights) {
    const Eigen::Index k = weights.size();
    for (Eigen::Index i = 0; i + 1 < k; ++i) {
      const Scalar value = rng_.uniform();
      Eigen::Index j = i;
      for (; j > 0 && weights(j - 1) > value; --j) weights(j) = weights(j - 1);
      weights(j) = value;
    }
    Scalar previous = 0;
    for (Eigen::Index i = 0; i + 1 < k; ++i) {
      const Scalar cut = weights(i);
      weights(i) = cut - previous;
      previous = cut;
    }
    weights(k - 1) = 1 - previous;
  }

  // Step 1. Positions are uniform on the two simplexes, so every particle starts feasible;
  // velocities point to a second uniform point, so the first move stays on the constraint planes.
  void initialise() {
    VectorX target(dimension());
    for (int j = 0; j < size_; ++j) {
      fill_simplex(column_.head(ka_));
      fill_simplex(column_.tail(kb_));
      fill_simplex(target.head(ka_));
      fill_simplex(target.tail(kb_));
      position_.col(j) = column_;
      velocity_.col(j) = target - column_;
    }
    result_.history.reserve(static_cast<std::size_t>(options_.max_iterations) + 1);
    evaluate();
  }

  // The fitness (5)/(6) of every particle, accumulated weight by weight over the whole swarm in
  // one fused loop per weight.
  void evaluate() {
    Scalar* gx = per_particle_.row(0).data();
    Scalar* gy = per_particle_.row(1).data();
    Scalar* gz = per_particle_.row(2).data();
    Scalar* sum_a = per_particle_.row(3).data();
    Scalar* sum_b = per_particle_.row(4).data();
    Scalar* lowest = per_particle_.row(5).data();
    Scalar* highest = per_particle_.row(6).data();
    per_particle_.topRows(5).setZero();
    // Starting at 0 and 1, these stay there exactly when every weight lies in [0, 1].
    per_particle_.row(5).setConstant(0);
    per_particle_.row(6).setConstant(1);
    const bool check_bounds = options_.constraint_handling == ConstraintHandling::feasibility;
    for (int i = 0; i < dimension(); ++i) {
      const Scalar* w = position_.row(i).data();
      const bool on_a = i < ka_;
      const Scalar sign = on_a ? -1 : 1;
      const Scalar* vertex = on_a ? xa_.col(i).data() : yb_.col(i - ka_).data();
      const Scalar vx = sign * vertex[0];
      const Scalar vy = sign * vertex[1];
      const Scalar vz = sign * vertex[2];
      accumulate_row(size_, w, vx, vy, vz, gx, gy, gz, on_a ? sum_a : sum_b);
      if (check_bounds) {
        for (int j = 0; j < size_; ++j) {
          lowest[j] = w[j] < lowest[j] ? w[j] : lowest[j];
          highest[j] = w[j] > highest[j] ? w[j] : highest[j];
        }
      }
    }
    for (int j = 0; j < size_; ++j) {
      const Scalar violation = (sum_a[j] - 1) * (sum_a[j] - 1) + (sum_b[j] - 1) * (sum_b[j] - 1);
      const bool feasible =
          lowest[j] >= 0 && highest[j] <= 1 && violation <= options_.feasibility_tolerance;
      fitness_[j] = {feasible, feasible ? std::sqrt(gx[j] * gx[j] + gy[j] * gy[j] + gz[j] * gz[j])
                                        : violation};
    }
  }

  void assign_coefficients(int iteration) {
    if (options_.inertia == InertiaStrategy::linear_decreasing) {
      inertia_.setConstant(linear_decreasing_inertia(iteration, options_.max_iterations,
                                                     options_.w_max, options_.w_min));
      pull_own_.setConstant(options_.c1);
      pull_global_.setConstant(options_.c2);
    } else {
      // The order changes little between iterations, so insertion sort keeps it in about N steps.
      for (int i = 1; i < size_; ++i) {
        const int particle = order_[i];
        int k = i;
        for (; k > 0 && better(personal_fitness_[particle], personal_fitness_[order_[k - 1]]);
             --k) {
          order_[k] = order_[k - 1];
        }
        order_[k] = particle;
      }
      for (int rank = 1; rank <= size_; ++rank) {
        const ParticleCoefficients& c = by_rank_[rank - 1];
        const int particle = order_[rank - 1];
        inertia_(particle) = c.w;
        pull_own_(particle) = c.c1;
        pull_global_(particle) = c.c2;
      }
    }
    for (int j = 0; j < size_; ++j) {
      pull_own_(j) *= rng_.uniform();
      pull_global_(j) *= rng_.uniform();
    }
  }

  // Step 2: updates (10)-(11). r1 and r2 are one draw per particle, as (10) is written, so a
  // move is a combination of differences of feasible points and keeps the sums of (2) at one. The
  // velocity limit scales the whole vector for the same reason.
  void move_particles() {
    const Scalar* w = inertia_.data();
    const Scalar* c1r1 = pull_own_.data();
    const Scalar* c2r2 = pull_global_.data();
    Scalar* largest = per_particle_.row(0).data();
    Scalar* lowest = per_particle_.row(1).data();
    per_particle_.topRows(2).setZero();
    for (int d = 0; d < dimension(); ++d) {
      const Scalar* x = position_.row(d).data();
      const Scalar* own = personal_best_.row(d).data();
      const Scalar global = personal_best_(d, global_best_);
      update_velocity_row(size_, w, c1r1, c2r2, own, global, x, velocity_.row(d).data(), largest);
    }
    const Scalar limit = options_.velocity_limit;
    for (int j = 0; j < size_; ++j) largest[j] = largest[j] > limit ? limit / largest[j] : 1;
    for (int d = 0; d < dimension(); ++d) {
      move_row(size_, largest, velocity_.row(d).data(), position_.row(d).data(), lowest);
    }
    if (options_.constraint_handling != ConstraintHandling::projection) return;
    // The move kept the sums, so only a negative weight takes a particle off the simplexes.
    for (int j = 0; j < size_; ++j) {
      if (lowest[j] >= 0) continue;
      column_ = position_.col(j);
      project_onto_simplex_in_place(column_.head(ka_), scratch_);
      project_onto_simplex_in_place(column_.tail(kb_), scratch_);
      velocity_.col(j) += column_ - position_.col(j);
      position_.col(j) = column_;
    }
  }

  // Conditions 1-3 decide whether the new position replaces the particle's best.
  bool update_personal_bests() {
    bool improved = false;
    for (int j = 0; j < size_; ++j) {
      if (better(fitness_[j], personal_fitness_[j])) {
        personal_fitness_[j] = fitness_[j];
        personal_best_.col(j) = position_.col(j);
        improved = true;
      }
    }
    return improved;
  }

  void update_global_best() {
    for (int j = 0; j < size_; ++j) {
      if (better(personal_fitness_[j], personal_fitness_[global_best_])) global_best_ = j;
    }
  }

  // Turns the global best into an answer with exact guarantees: weights moved onto the simplexes
  // give an upper bound achieved by real points, and the direction between those points a lower
  // bound. The best of each is kept.
  void record_best() {
    lambda_ = personal_best_.col(global_best_).head(ka_);
    delta_ = personal_best_.col(global_best_).tail(kb_);
    to_simplex_in_place(lambda_, scratch_);
    to_simplex_in_place(delta_, scratch_);
    const Vector3 pa = xa_ * lambda_;
    const Vector3 pb = yb_ * delta_;
    const Scalar d = (pb - pa).norm();
    if (result_.history.empty() || d < result_.distance) {
      result_.distance = d;
      result_.point_a = pa;
      result_.point_b = pb;
      result_.weights_a = lambda_;
      result_.weights_b = delta_;
    }
    if (result_.history.empty()) result_.history.push_back(result_.distance);
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
  const int size_;
  const Matrix3X xa_;
  const Matrix3X yb_;
  detail::Xoshiro256 rng_;
  SwarmMatrix position_;
  SwarmMatrix velocity_;
  SwarmMatrix personal_best_;
  std::vector<Fitness> fitness_;
  std::vector<Fitness> personal_fitness_;
  // Per-particle inertia and the acceleration terms c1 r1 and c2 r2 of (10).
  VectorX inertia_;
  VectorX pull_own_;
  VectorX pull_global_;
  // Per-particle accumulators of `evaluate` and `move_particles`.
  SwarmMatrix per_particle_;
  // One particle's weights, and buffers for moving weights onto the simplexes.
  VectorX column_;
  VectorX scratch_;
  VectorX lambda_;
  VectorX delta_;
  std::vector<int> order_;
  // (8)-(9) depend only on the rank, so they are computed once.
  std::vector<ParticleCoefficients> by_rank_;
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
