#include "swarmcollide/solvers/swarm.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../detail/interruption.hpp"
#include "minkowski.hpp"
#include "primal_swarm.hpp"
#include "swarm_kernels.hpp"
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

using detail::Answer;
using detail::FramedPair;
using detail::Goal;
using detail::InertiaStrategy;
using detail::kFrameRounding;
using detail::SwarmView;

// The per-particle arrays of a solve, one row each of the workspace's `per_particle` block.
enum PerParticle { kInertia, kPullOwn, kPullGlobal, kPerParticleArrays };

// Everything a solve writes besides its result. One per thread, kept between solves, so that a
// solve of the same size as the previous one allocates nothing but its result's arrays.
struct SwarmWorkspace {
  std::vector<double> swarm;
  std::vector<double> per_particle;
  std::vector<double> uniforms;
  std::vector<double> signed_vertices;
  std::vector<double> global_best;
  std::vector<std::int64_t> best_key;
  std::vector<std::int64_t> improved;
  std::vector<int> order;
  std::vector<detail::RankedParticle> ranked;
  // (8)-(9) depend only on the rank, so they are tabulated, and kept while the swarm size and
  // inertia bounds stay the same.
  std::vector<ParticleCoefficients> by_rank;
  Scalar by_rank_w_min = 0;
  Scalar by_rank_w_max = 0;
  VectorX lambda;
  VectorX delta;
  VectorX scratch;
  VertexMatrix points_a;
  VertexMatrix points_b;
};

// Rows are padded to whole groups of the generator's lanes, which also keeps them aligned.
int padded(int particles) {
  constexpr int lanes = detail::UniformLanes::kLanes;
  return (particles + lanes - 1) / lanes * lanes;
}

class SwarmSolver {
 public:
  SwarmSolver(const FramedPair& pair, const SwarmOptions& options, InertiaStrategy inertia,
              std::uint64_t seed, SwarmWorkspace& workspace)
      : pair_(pair),
        options_(options),
        inertia_(inertia),
        tolerance_(pair.tolerance),
        ka_(static_cast<int>(pair.a.given_size())),
        kb_(static_cast<int>(pair.b.given_size())),
        size_(options.swarm_size),
        stride_(padded(options.swarm_size)),
        work_(workspace),
        lanes_(seed) {
    const int rows = ka_ + kb_;
    const std::size_t block = static_cast<std::size_t>(rows) * stride_;
    // Every entry a solve reads is written first, so the buffers are only resized.
    work_.swarm.resize(4 * block);
    swarm_ = {rows,
              size_,
              stride_,
              work_.swarm.data(),
              work_.swarm.data() + block,
              work_.swarm.data() + 2 * block};
    next_position_ = work_.swarm.data() + 3 * block;
    // Padding columns start as particles but keep zero coefficients, so they stay put.
    work_.per_particle.assign(static_cast<std::size_t>(kPerParticleArrays) * stride_, 0.0);
    work_.global_best.resize(detail::kSplat * static_cast<std::size_t>(rows));
    work_.signed_vertices.resize(3 * detail::kSplat * static_cast<std::size_t>(rows));
    pair.a.given_points(work_.points_a);
    pair.b.given_points(work_.points_b);
    for (int r = 0; r < rows; ++r) {
      const bool on_a = r < ka_;
      const Vector3 vertex = on_a ? Vector3(-work_.points_a.row(r).transpose())
                                  : Vector3(work_.points_b.row(r - ka_).transpose());
      for (int c = 0; c < 3 * detail::kSplat; ++c) {
        work_.signed_vertices[3 * detail::kSplat * r + c] = vertex(c / detail::kSplat);
      }
    }
    work_.best_key.resize(stride_);
    work_.improved.resize(stride_);
    work_.order.resize(size_);
    std::iota(work_.order.begin(), work_.order.end(), 0);
    work_.ranked.resize(2 * (static_cast<std::size_t>(size_) + 1));
    if (inertia == InertiaStrategy::rank_adaptive) tabulate_coefficients();
    work_.lambda.resize(ka_);
    work_.delta.resize(kb_);
    fitness_ = {work_.signed_vertices.data(),
                options.constraint_handling == ConstraintHandling::feasibility,
                options.feasibility_tolerance};
  }

  Answer run(Goal goal) {
    goal_ = goal;
    result_.history.reserve(static_cast<std::size_t>(options_.max_iterations) + 1);
    initialise();
    detail::score_initial_positions(swarm_, ka_, fitness_, bests());
    find_global_best();
    record_best();
    int iteration = 0;
    const detail::InterruptionPoll stop_if_interrupted;
    while (iteration < options_.max_iterations && !precision_reached()) {
      stop_if_interrupted();
      assign_coefficients(iteration);
      const bool improved = advance();
      ++iteration;
      if (improved && find_global_best()) record_best();
      result_.history.push_back(result_.upper);
    }
    result_.iterations = iteration;
    result_.evaluations = static_cast<long>(size_) * (iteration + 1);
    result_.weights_a = ConvexWeights(std::move(best_lambda_));
    result_.weights_b = ConvexWeights(std::move(best_delta_));
    return std::move(result_);
  }

 private:
  void tabulate_coefficients() {
    if (static_cast<int>(work_.by_rank.size()) == size_ && work_.by_rank_w_min == options_.w_min &&
        work_.by_rank_w_max == options_.w_max) {
      return;
    }
    work_.by_rank.clear();
    for (int rank = 1; rank <= size_; ++rank) {
      work_.by_rank.push_back(
          rank_adaptive_coefficients(rank, size_, options_.w_min, options_.w_max));
    }
    work_.by_rank_w_min = options_.w_min;
    work_.by_rank_w_max = options_.w_max;
  }

  double* row(PerParticle array) { return work_.per_particle.data() + array * stride_; }
  double& weight(double* matrix, int r, int particle) { return matrix[r * stride_ + particle]; }

  // Step 1. Positions are uniform on the two simplexes, so every particle starts feasible;
  // velocities point to a second uniform point, so the first move stays on the constraint planes.
  void initialise() {
    const int cut_rows = 2 * (ka_ - 1 + kb_ - 1);
    work_.uniforms.resize(static_cast<std::size_t>(std::max(cut_rows, 2)) * stride_);
    work_.scratch.resize(std::max(ka_, kb_));
    detail::draw_uniforms(lanes_, work_.uniforms.data(), cut_rows * stride_);
    double* cuts = work_.uniforms.data();
    double* target = next_position_;
    for (double* points : {swarm_.position, target}) {
      for (const auto& [first_row, count] : {std::pair{0, ka_}, std::pair{ka_, kb_}}) {
        detail::uniform_simplex_points(count, stride_, stride_, cuts, points + first_row * stride_,
                                       work_.scratch.data());
        cuts += (count - 1) * stride_;
      }
    }
    for (int r = 0; r < swarm_.rows; ++r) {
      for (int j = 0; j < stride_; ++j) {
        weight(swarm_.velocity, r, j) = weight(target, r, j) - weight(swarm_.position, r, j);
      }
    }
  }

  detail::Bests bests() { return {work_.best_key.data(), work_.improved.data()}; }

  void assign_coefficients(int iteration) {
    double* inertia = row(kInertia);
    double* pull_own = row(kPullOwn);
    double* pull_global = row(kPullGlobal);
    if (inertia_ == InertiaStrategy::linear_decreasing) {
      const Scalar w = linear_decreasing_inertia(iteration, options_.max_iterations, options_.w_max,
                                                 options_.w_min);
      std::fill_n(inertia, size_, w);
      std::fill_n(pull_own, size_, options_.c1);
      std::fill_n(pull_global, size_, options_.c2);
    } else {
      int* order = work_.order.data();
      // Every particle is marked improved after the initial scoring, and after each generation
      // those whose personal best it changed: the order of the others still holds.
      detail::order_by_personal_best(size_, work_.best_key.data(), work_.improved.data(), order,
                                     work_.ranked.data());
      for (int rank = 0; rank < size_; ++rank) {
        const ParticleCoefficients& c = work_.by_rank[rank];
        inertia[order[rank]] = c.w;
        pull_own[order[rank]] = c.c1;
        pull_global[order[rank]] = c.c2;
      }
    }
    // The paper's feasibility rules need moves that keep the sums of (2): one pair r1, r2 per
    // particle. With projection the kernel draws them per weight.
    if (options_.constraint_handling == ConstraintHandling::feasibility) {
      double* uniforms = work_.uniforms.data();
      detail::draw_uniforms(lanes_, uniforms, 2 * stride_);
      for (int j = 0; j < size_; ++j) {
        pull_own[j] *= uniforms[j];
        pull_global[j] *= uniforms[stride_ + j];
      }
    }
  }

  // Step 2: updates (10)-(11) and Conditions 1-3, all particles against the global best of the
  // previous generation.
  bool advance() {
    for (int r = 0; r < swarm_.rows; ++r) {
      for (int c = 0; c < detail::kSplat; ++c) {
        work_.global_best[detail::kSplat * r + c] = weight(swarm_.personal_best, r, global_best_);
      }
    }
    const detail::Move move{row(kInertia),
                            row(kPullOwn),
                            row(kPullGlobal),
                            work_.global_best.data(),
                            options_.velocity_limit,
                            options_.constraint_handling == ConstraintHandling::projection,
                            &lanes_};
    const bool improved =
        detail::advance_particles(swarm_, ka_, move, fitness_, bests(), next_position_);
    std::swap(swarm_.position, next_position_);
    return improved;
  }

  // Whether the global best moved: to another particle, or with its own personal best. Only
  // then can the answer change.
  bool find_global_best() {
    const std::int64_t* key = work_.best_key.data();
    const int before = global_best_;
    for (int j = 0; j < size_; ++j) {
      if (key[j] < key[global_best_]) global_best_ = j;
    }
    return global_best_ != before || work_.improved[before] != 0;
  }

  // Turns the global best into an answer with exact guarantees: weights moved onto the simplexes
  // give an upper bound achieved by real points, and the direction between those points a lower
  // bound. The best of each is kept.
  void record_best() {
    VectorX& lambda = work_.lambda;
    VectorX& delta = work_.delta;
    for (int i = 0; i < ka_; ++i) lambda(i) = weight(swarm_.personal_best, i, global_best_);
    for (int i = 0; i < kb_; ++i) delta(i) = weight(swarm_.personal_best, ka_ + i, global_best_);
    to_simplex_in_place(lambda, work_.scratch);
    to_simplex_in_place(delta, work_.scratch);
    const Vector3 pa = work_.points_a.transpose() * lambda;
    const Vector3 pb = work_.points_b.transpose() * delta;
    const Scalar d = (pb - pa).norm();
    if (result_.history.empty() || d < result_.upper) {
      result_.upper = d;
      result_.point_a = pa;
      result_.point_b = pb;
      best_lambda_ = lambda;
      best_delta_ = delta;
    }
    if (result_.history.empty()) result_.history.push_back(result_.upper);
    if (d > 0) {
      const Vector3 n = (pb - pa) / d;
      const Scalar s = separation(pair_.a, pair_.b, n);
      if (s > result_.lower) {
        result_.lower = s;
        result_.direction = n;
      }
    }
  }

  // Step 3's precision test, made rigorous by the certificate; a tolerance of zero runs the
  // whole budget. A verdict is settled as soon as either bound proves it.
  bool precision_reached() const {
    const Scalar tol = tolerance_;
    if (!(tol > 0)) return false;
    if (goal_ == Goal::verdict && result_.lower - kFrameRounding > tol) return true;
    return result_.upper - result_.lower <= tol || result_.upper + kFrameRounding <= tol;
  }

  const FramedPair& pair_;
  const SwarmOptions& options_;
  const InertiaStrategy inertia_;
  const Scalar tolerance_;
  Goal goal_ = Goal::distance;
  const int ka_;
  const int kb_;
  const int size_;
  const int stride_;
  SwarmWorkspace& work_;
  detail::UniformLanes lanes_;
  SwarmView swarm_;
  // Moves are written here and then swapped in, so a move that breaks the velocity limit can be
  // redone from the old positions.
  double* next_position_;
  detail::Fitness fitness_;
  int global_best_ = 0;
  Answer result_;
  VectorX best_lambda_;
  VectorX best_delta_;
};

}  // namespace

const char* swarm_instruction_set() { return detail::kernel_isa_name(detail::kernel_isa()); }

namespace detail {

// A swarm's arrays hold swarm_size x (vertices of both bodies) entries, four times over.
constexpr double kMaxSwarmEntries = 1 << 26;

Answer solve_primal_swarm(const FramedPair& pair, const QueryOptions& options, Goal goal) {
  if (goal == Goal::signed_distance) {
    throw std::invalid_argument("the primal swarms measure no penetration depth");
  }
  const double entries =
      static_cast<double>(options.swarm.swarm_size) * (pair.a.given_size() + pair.b.given_size());
  if (entries > kMaxSwarmEntries) {
    throw std::invalid_argument(
        "swarm_size x (points of both bodies) must be at most 2^26 = 67,108,864 (the swarm's "
        "arrays would take over 2 GiB), got " +
        std::to_string(static_cast<long long>(entries)) + "; use fewer particles");
  }
  thread_local SwarmWorkspace workspace;
  const InertiaStrategy inertia = options.method == Method::pso ? InertiaStrategy::linear_decreasing
                                                                : InertiaStrategy::rank_adaptive;
  return SwarmSolver(pair, options.swarm, inertia, options.seed, workspace).run(goal);
}

}  // namespace detail

}  // namespace swarmcollide
