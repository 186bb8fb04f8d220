#include "swarm_kernels.hpp"

#include <algorithm>
#include <limits>

#include "swarmcollide/detail/random.hpp"

// One clone per instruction set, picked when the library is loaded. This file is compiled with
// floating-point contraction off, so every clone rounds exactly like the baseline one and a seed
// gives the same answer on every x86-64 processor.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define SWARMCOLLIDE_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define SWARMCOLLIDE_CLONES
#endif

namespace swarmcollide::detail {

namespace {

inline double smaller(double a, double b) { return a < b ? a : b; }
inline double larger(double a, double b) { return a > b ? a : b; }

}  // namespace

UniformLanes::UniformLanes(std::uint64_t seed) {
  // splitmix64, as in Xoshiro256, spreads any seed over all 32 words.
  for (auto& word : state) {
    for (auto& lane : word) {
      seed += 0x9e3779b97f4a7c15ULL;
      lane = mix64(seed);
    }
  }
}

SWARMCOLLIDE_CLONES
void draw_uniforms(UniformLanes& lanes, double* __restrict out, int count) {
  constexpr int L = UniformLanes::kLanes;
  std::uint64_t* __restrict s0 = lanes.state[0];
  std::uint64_t* __restrict s1 = lanes.state[1];
  std::uint64_t* __restrict s2 = lanes.state[2];
  std::uint64_t* __restrict s3 = lanes.state[3];
  for (int block = 0; block < count; block += L) {
    double* __restrict draws = out + block;
    for (int l = 0; l < L; ++l) {
      const std::uint64_t sum = s0[l] + s3[l];
      const std::uint64_t result = ((sum << 23) | (sum >> 41)) + s0[l];
      const std::uint64_t t = s1[l] << 17;
      s2[l] ^= s0[l];
      s3[l] ^= s1[l];
      s1[l] ^= s2[l];
      s0[l] ^= s3[l];
      s2[l] ^= t;
      s3[l] = (s3[l] << 45) | (s3[l] >> 19);
      // The top 52 bits as the mantissa of a number in [1, 2): exact, and free of the
      // integer-to-double conversion that older vector units lack.
      draws[l] = __builtin_bit_cast(double, (result >> 12) | 0x3ff0000000000000ULL) - 1.0;
    }
  }
}

SWARMCOLLIDE_CLONES
void uniform_simplex_points(int count, int particles, int stride, double* __restrict uniforms,
                            double* __restrict out, double* __restrict column) {
  const int cuts = count - 1;
  // Odd-even transposition sorts every particle's column at once with branch-free min/max over
  // rows; its cuts^2 / 2 exchanges are cheaper than sorting column by column for few cuts.
  constexpr int kMaxCutsForNetwork = 16;
  if (cuts <= kMaxCutsForNetwork) {
    for (int pass = 0; pass < cuts; ++pass) {
      for (int i = pass % 2; i + 1 < cuts; i += 2) {
        double* __restrict low = uniforms + i * stride;
        double* __restrict high = uniforms + (i + 1) * stride;
        for (int j = 0; j < particles; ++j) {
          const double a = low[j];
          const double b = high[j];
          low[j] = smaller(a, b);
          high[j] = larger(a, b);
        }
      }
    }
  } else {
    for (int j = 0; j < particles; ++j) {
      for (int i = 0; i < cuts; ++i) column[i] = uniforms[i * stride + j];
      std::sort(column, column + cuts);
      for (int i = 0; i < cuts; ++i) uniforms[i * stride + j] = column[i];
    }
  }
  for (int j = 0; j < particles; ++j) out[j] = cuts > 0 ? uniforms[j] : 1.0;
  for (int i = 1; i < cuts; ++i) {
    const double* __restrict cut = uniforms + i * stride;
    const double* __restrict previous = uniforms + (i - 1) * stride;
    double* __restrict gap = out + i * stride;
    for (int j = 0; j < particles; ++j) gap[j] = cut[j] - previous[j];
  }
  if (cuts > 0) {
    const double* __restrict last = uniforms + (cuts - 1) * stride;
    double* __restrict gap = out + cuts * stride;
    for (int j = 0; j < particles; ++j) gap[j] = 1.0 - last[j];
  }
}

SWARMCOLLIDE_CLONES
void move_particles(const SwarmView& swarm, int rows_a, const double* __restrict inertia,
                    const double* __restrict pull_own, const double* __restrict pull_global,
                    const double* __restrict global_best, double limit, double* __restrict next,
                    double* __restrict largest, double* __restrict lowest_a,
                    double* __restrict lowest_b) {
  const int n = swarm.particles;
  for (int j = 0; j < n; ++j) largest[j] = 0;
  for (int j = 0; j < n; ++j) lowest_a[j] = 0;
  for (int j = 0; j < n; ++j) lowest_b[j] = 0;
  for (int r = 0; r < swarm.rows; ++r) {
    const double* __restrict x = swarm.position + r * swarm.stride;
    const double* __restrict own = swarm.personal_best + r * swarm.stride;
    double* __restrict v = swarm.velocity + r * swarm.stride;
    double* __restrict moved = next + r * swarm.stride;
    double* __restrict lowest = r < rows_a ? lowest_a : lowest_b;
    const double global = global_best[r];
    for (int j = 0; j < n; ++j) {
      const double velocity =
          inertia[j] * v[j] + pull_own[j] * (own[j] - x[j]) + pull_global[j] * (global - x[j]);
      v[j] = velocity;
      moved[j] = x[j] + velocity;
      largest[j] = larger(largest[j], velocity < 0 ? -velocity : velocity);
      lowest[j] = smaller(lowest[j], moved[j]);
    }
  }
  bool limited = false;
  for (int j = 0; j < n; ++j) limited |= largest[j] > limit;
  // The limit binds in about one iteration in a hundred, so the moves are redone only then.
  if (!limited) return;
  for (int j = 0; j < n; ++j) largest[j] = largest[j] > limit ? limit / largest[j] : 1.0;
  for (int j = 0; j < n; ++j) lowest_a[j] = 0;
  for (int j = 0; j < n; ++j) lowest_b[j] = 0;
  for (int r = 0; r < swarm.rows; ++r) {
    const double* __restrict x = swarm.position + r * swarm.stride;
    double* __restrict v = swarm.velocity + r * swarm.stride;
    double* __restrict moved = next + r * swarm.stride;
    double* __restrict lowest = r < rows_a ? lowest_a : lowest_b;
    for (int j = 0; j < n; ++j) {
      v[j] *= largest[j];
      moved[j] = x[j] + v[j];
      lowest[j] = smaller(lowest[j], moved[j]);
    }
  }
}

SWARMCOLLIDE_CLONES
void project_rows_onto_simplex(const SwarmView& swarm, int first_row, int count,
                               const double* __restrict lowest, double* __restrict theta,
                               double* __restrict sum, double* __restrict count_at_least) {
  const int n = swarm.particles;
  double* const rows = swarm.position + first_row * swarm.stride;
  for (int j = 0; j < n; ++j) theta[j] = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < count; ++i) {
    const double* __restrict pivot = rows + i * swarm.stride;
    for (int j = 0; j < n; ++j) sum[j] = 0;
    for (int j = 0; j < n; ++j) count_at_least[j] = 0;
    for (int l = 0; l < count; ++l) {
      const double* __restrict other = rows + l * swarm.stride;
      for (int j = 0; j < n; ++j) {
        const bool at_least = other[j] >= pivot[j];
        sum[j] += at_least ? other[j] : 0.0;
        count_at_least[j] += at_least ? 1.0 : 0.0;
      }
    }
    for (int j = 0; j < n; ++j) theta[j] = larger(theta[j], (sum[j] - 1.0) / count_at_least[j]);
  }
  for (int i = 0; i < count; ++i) {
    double* __restrict x = rows + i * swarm.stride;
    double* __restrict v = swarm.velocity + (first_row + i) * swarm.stride;
    for (int j = 0; j < n; ++j) {
      const double projected = larger(x[j] - theta[j], 0.0);
      const double moved = lowest[j] < 0 ? projected : x[j];
      v[j] += moved - x[j];
      x[j] = moved;
    }
  }
}

SWARMCOLLIDE_CLONES
void evaluate_fitness(const SwarmView& swarm, int rows_a, const double* __restrict signed_vertices,
                      bool check_bounds, double feasibility_tolerance,
                      const FitnessScratch& scratch, double* __restrict value,
                      double* __restrict feasible) {
  const int n = swarm.particles;
  double* __restrict gx = scratch.offset_x;
  double* __restrict gy = scratch.offset_y;
  double* __restrict gz = scratch.offset_z;
  double* __restrict lowest = scratch.lowest;
  double* __restrict highest = scratch.highest;
  double* __restrict sum_a = scratch.sum_a;
  double* __restrict sum_b = scratch.sum_b;
  // The first weight of each body starts the sums, which spares zeroing them.
  const double* __restrict first_a = swarm.position;
  const double* __restrict first_b = swarm.position + rows_a * swarm.stride;
  for (int j = 0; j < n; ++j) {
    gx[j] = signed_vertices[0] * first_a[j] + signed_vertices[3 * rows_a] * first_b[j];
    gy[j] = signed_vertices[1] * first_a[j] + signed_vertices[3 * rows_a + 1] * first_b[j];
    gz[j] = signed_vertices[2] * first_a[j] + signed_vertices[3 * rows_a + 2] * first_b[j];
    sum_a[j] = first_a[j];
    sum_b[j] = first_b[j];
    // They stay at 0 and 1 exactly when every weight lies in [0, 1].
    lowest[j] = check_bounds ? smaller(smaller(first_a[j], first_b[j]), 0.0) : 0.0;
    highest[j] = check_bounds ? larger(larger(first_a[j], first_b[j]), 1.0) : 1.0;
  }
  for (int r = 0; r < swarm.rows; ++r) {
    if (r == 0 || r == rows_a) continue;
    const double* __restrict w = swarm.position + r * swarm.stride;
    const double vx = signed_vertices[3 * r];
    const double vy = signed_vertices[3 * r + 1];
    const double vz = signed_vertices[3 * r + 2];
    double* __restrict total = r < rows_a ? sum_a : sum_b;
    for (int j = 0; j < n; ++j) {
      gx[j] += vx * w[j];
      gy[j] += vy * w[j];
      gz[j] += vz * w[j];
      total[j] += w[j];
    }
    if (check_bounds) {
      for (int j = 0; j < n; ++j) {
        lowest[j] = smaller(lowest[j], w[j]);
        highest[j] = larger(highest[j], w[j]);
      }
    }
  }
  for (int j = 0; j < n; ++j) {
    const double off_a = sum_a[j] - 1;
    const double off_b = sum_b[j] - 1;
    const double violation = off_a * off_a + off_b * off_b;
    const bool ok = lowest[j] >= 0 && highest[j] <= 1 && violation <= feasibility_tolerance;
    // The square of (5) orders particles as (5) does, without a square root.
    const double squared_objective = gx[j] * gx[j] + gy[j] * gy[j] + gz[j] * gz[j];
    value[j] = ok ? squared_objective : violation;
    feasible[j] = ok ? 1.0 : 0.0;
  }
}

SWARMCOLLIDE_CLONES
bool keep_personal_bests(const SwarmView& swarm, const double* __restrict value,
                         const double* __restrict feasible, double* __restrict best_value,
                         double* __restrict best_feasible, double* __restrict improved) {
  const int n = swarm.particles;
  double any = 0;
  for (int j = 0; j < n; ++j) {
    const bool better = (feasible[j] > best_feasible[j]) |
                        ((feasible[j] == best_feasible[j]) & (value[j] < best_value[j]));
    improved[j] = better ? 1.0 : 0.0;
    best_value[j] = better ? value[j] : best_value[j];
    best_feasible[j] = better ? feasible[j] : best_feasible[j];
    any = larger(any, improved[j]);
  }
  if (any == 0) return false;
  for (int r = 0; r < swarm.rows; ++r) {
    const double* __restrict x = swarm.position + r * swarm.stride;
    double* __restrict own = swarm.personal_best + r * swarm.stride;
    for (int j = 0; j < n; ++j) {
      const double kept = own[j];
      own[j] = improved[j] != 0 ? x[j] : kept;
    }
  }
  return true;
}

SWARMCOLLIDE_CLONES
void rank_personal_bests(int particles, const double* __restrict best_feasible,
                         const double* __restrict best_value, std::int64_t* __restrict key,
                         std::int64_t* __restrict rank) {
  // Nonnegative doubles order like their bit patterns. Feasible values are shifted below every
  // infeasible one, which is what Conditions 1-3 ask, and one integer comparison decides.
  constexpr std::int64_t kBelowInfeasible = 0x7ff0000000000001LL;
  for (int j = 0; j < particles; ++j) {
    const std::int64_t bits = __builtin_bit_cast(std::int64_t, best_value[j]);
    key[j] = best_feasible[j] != 0 ? bits - kBelowInfeasible : bits;
  }
  // A particle ranks behind every smaller key and behind equal keys of lower index; keys are
  // integers below 2^63 - 2^52, so "equal and lower index" is "less than key + 1".
  for (int j = 0; j < particles; ++j) {
    const std::int64_t own = key[j];
    std::int64_t ahead = 0;
    for (int k = 0; k < particles; ++k) {
      const std::int64_t threshold = k < j ? own + 1 : own;
      ahead += key[k] < threshold ? 1 : 0;
    }
    rank[j] = ahead;
  }
}

}  // namespace swarmcollide::detail
