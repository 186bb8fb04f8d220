#include "swarm_kernels.hpp"

#include <algorithm>
#include <cstring>
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

constexpr int kLanes = UniformLanes::kLanes;

// GCC's vector extensions: one value per particle of a block, compiled to whatever width each
// clone has, with every operation rounding as its scalar counterpart does.
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));
using Mask = std::int64_t __attribute__((vector_size(kLanes * sizeof(double))));

[[gnu::always_inline]] inline Lanes load(const double* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline Mask load_keys(const std::int64_t* p) {
  Mask v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store(double* p, Lanes v) { std::memcpy(p, &v, sizeof v); }
[[gnu::always_inline]] inline void store(std::int64_t* p, Mask v) { std::memcpy(p, &v, sizeof v); }
[[gnu::always_inline]] inline Lanes broadcast(double x) { return Lanes{} + x; }
inline double smaller(double a, double b) { return a < b ? a : b; }
inline double larger(double a, double b) { return a > b ? a : b; }
[[gnu::always_inline]] inline Lanes smaller(Lanes a, Lanes b) { return a < b ? a : b; }
[[gnu::always_inline]] inline Lanes larger(Lanes a, Lanes b) { return a > b ? a : b; }
[[gnu::always_inline]] inline bool any(Mask m) {
  std::int64_t set = 0;
  for (int l = 0; l < kLanes; ++l) set |= m[l];
  return set != 0;
}
static_assert(kLanes == 8, "lane_indices lists the lanes");
[[gnu::always_inline]] inline Mask lane_indices(int first) {
  return Mask{0, 1, 2, 3, 4, 5, 6, 7} + first;
}

// The score key of (5) or (6) for the block of particles starting at column j of `positions`.
[[gnu::always_inline]] inline Mask score_block(const double* positions, int rows, int stride,
                                               int rows_a, int j, const Fitness& fitness) {
  const double* vertex = fitness.signed_vertices;
  Lanes gx{}, gy{}, gz{}, sum_a{}, sum_b{};
  // They stay at 0 and 1 exactly when every weight lies in [0, 1].
  Lanes lowest{};
  Lanes highest = broadcast(1.0);
  for (int r = 0; r < rows; ++r) {
    const Lanes w = load(positions + r * stride + j);
    gx += vertex[3 * r] * w;
    gy += vertex[3 * r + 1] * w;
    gz += vertex[3 * r + 2] * w;
    if (r < rows_a) {
      sum_a += w;
    } else {
      sum_b += w;
    }
    if (fitness.check_bounds) {
      lowest = smaller(lowest, w);
      highest = larger(highest, w);
    }
  }
  const Lanes off_a = sum_a - 1.0;
  const Lanes off_b = sum_b - 1.0;
  const Lanes violation = off_a * off_a + off_b * off_b;
  const Mask ok = (lowest >= 0) & (highest <= 1) & (violation <= fitness.feasibility_tolerance);
  // The square of (5) orders particles as (5) does, without a square root.
  const Lanes squared_objective = gx * gx + gy * gy + gz * gz;
  const Mask value = reinterpret_cast<Mask>(ok ? squared_objective : violation);
  return ok ? value - kFeasibleKeyShift : value;
}

// The sort-based threshold: the largest (sum of the m biggest weights - 1) / m.
double sorted_threshold(double* weights, int count) {
  std::sort(weights, weights + count, [](double a, double b) { return a > b; });
  double sum = 0;
  double theta = -std::numeric_limits<double>::infinity();
  for (int m = 1; m <= count; ++m) {
    sum += weights[m - 1];
    theta = std::max(theta, (sum - 1.0) / m);
  }
  return theta;
}

// The threshold of the projection onto the simplex for K weights per particle, as the sort-based
// method has it: sorted by a network of compare-exchanges, all in registers.
template <int K>
[[gnu::always_inline]] inline Lanes network_threshold(const double* rows, int stride) {
  Lanes sorted[K];
  for (int i = 0; i < K; ++i) sorted[i] = load(rows + i * stride);
  for (int pass = 0; pass < K; ++pass) {
    for (int i = pass % 2; i + 1 < K; i += 2) {
      const Lanes high = larger(sorted[i], sorted[i + 1]);
      sorted[i + 1] = smaller(sorted[i], sorted[i + 1]);
      sorted[i] = high;
    }
  }
  Lanes sum{};
  Lanes theta = broadcast(-std::numeric_limits<double>::infinity());
  for (int m = 1; m <= K; ++m) {
    sum += sorted[m - 1];
    theta = larger(theta, (sum - 1.0) / static_cast<double>(m));
  }
  return theta;
}

// Projects the `count` rows of the block whose first weight is at `rows` onto the simplex, for
// the particles marked `off`, and adds the displacement to `velocities`.
[[gnu::always_inline]] inline void project_block(double* rows, double* velocities, int count,
                                                 int stride, Mask off, double* column) {
  if (!any(off)) return;
  Lanes theta{};
  switch (count) {
    case 1:
      theta = network_threshold<1>(rows, stride);
      break;
    case 2:
      theta = network_threshold<2>(rows, stride);
      break;
    case 3:
      theta = network_threshold<3>(rows, stride);
      break;
    case 4:
      theta = network_threshold<4>(rows, stride);
      break;
    case 5:
      theta = network_threshold<5>(rows, stride);
      break;
    case 6:
      theta = network_threshold<6>(rows, stride);
      break;
    case 7:
      theta = network_threshold<7>(rows, stride);
      break;
    case 8:
      theta = network_threshold<8>(rows, stride);
      break;
    default:
      for (int l = 0; l < kLanes; ++l) {
        if (!off[l]) continue;
        for (int i = 0; i < count; ++i) column[i] = rows[i * stride + l];
        theta[l] = sorted_threshold(column, count);
      }
  }
  for (int i = 0; i < count; ++i) {
    const Lanes x = load(rows + i * stride);
    const Lanes v = load(velocities + i * stride);
    const Lanes moved = off ? larger(x - theta, Lanes{}) : x;
    store(velocities + i * stride, v + (moved - x));
    store(rows + i * stride, moved);
  }
}

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
void score_initial_positions(const SwarmView& swarm, int rows_a, const Fitness& fitness,
                             const Bests& bests) {
  for (int j = 0; j < swarm.particles; j += kLanes) {
    store(bests.key + j, score_block(swarm.position, swarm.rows, swarm.stride, rows_a, j, fitness));
    store(bests.improved + j, ~Mask{});
  }
  std::copy_n(swarm.position, static_cast<std::size_t>(swarm.rows) * swarm.stride,
              swarm.personal_best);
}

SWARMCOLLIDE_CLONES
bool advance_particles(const SwarmView& swarm, int rows_a, const Move& move, const Fitness& fitness,
                       const Bests& bests, double* __restrict next, double* __restrict column) {
  const int stride = swarm.stride;
  const int rows = swarm.rows;
  const double limit = move.velocity_limit;
  Mask any_improved{};
  for (int j = 0; j < swarm.particles; j += kLanes) {
    const Lanes inertia = load(move.inertia + j);
    const Lanes pull_own = load(move.pull_own + j);
    const Lanes pull_global = load(move.pull_global + j);
    Lanes largest{};
    Lanes lowest_a{};
    Lanes lowest_b{};
    for (int r = 0; r < rows; ++r) {
      const Lanes x = load(swarm.position + r * stride + j);
      const Lanes v = load(swarm.velocity + r * stride + j);
      const Lanes own = load(swarm.personal_best + r * stride + j);
      const Lanes velocity =
          inertia * v + pull_own * (own - x) + pull_global * (move.global_best[r] - x);
      const Lanes moved = x + velocity;
      store(swarm.velocity + r * stride + j, velocity);
      store(next + r * stride + j, moved);
      largest = larger(largest, velocity < 0 ? -velocity : velocity);
      if (r < rows_a) {
        lowest_a = smaller(lowest_a, moved);
      } else {
        lowest_b = smaller(lowest_b, moved);
      }
    }
    // The limit binds in about one iteration in a hundred, so the block is redone only then.
    const Mask limited = largest > limit;
    if (any(limited)) {
      const Lanes scale = limited ? limit / largest : broadcast(1.0);
      lowest_a = Lanes{};
      lowest_b = Lanes{};
      for (int r = 0; r < rows; ++r) {
        const Lanes velocity = load(swarm.velocity + r * stride + j) * scale;
        const Lanes moved = load(swarm.position + r * stride + j) + velocity;
        store(swarm.velocity + r * stride + j, velocity);
        store(next + r * stride + j, moved);
        if (r < rows_a) {
          lowest_a = smaller(lowest_a, moved);
        } else {
          lowest_b = smaller(lowest_b, moved);
        }
      }
    }
    if (move.project) {
      // The move kept the sums, so only a negative weight takes a particle off its simplex.
      project_block(next + j, swarm.velocity + j, rows_a, stride, lowest_a < 0, column);
      project_block(next + rows_a * stride + j, swarm.velocity + rows_a * stride + j, rows - rows_a,
                    stride, lowest_b < 0, column);
    }
    const Mask key = score_block(next, rows, stride, rows_a, j, fitness);
    const Mask best_key = load_keys(bests.key + j);
    const Mask better = key < best_key;
    store(bests.key + j, better ? key : best_key);
    store(bests.improved + j, better);
    any_improved |= better;
    if (!any(better)) continue;
    for (int r = 0; r < rows; ++r) {
      double* own = swarm.personal_best + r * stride + j;
      store(own, better ? load(next + r * stride + j) : load(own));
    }
  }
  return any(any_improved);
}

SWARMCOLLIDE_CLONES
void rank_personal_bests(int particles, const std::int64_t* __restrict key,
                         std::int64_t* __restrict rank) {
  const int blocks_end = (particles + kLanes - 1) / kLanes * kLanes;
  // Particle j ranks behind every k with a smaller key and every k < j with an equal one. Keys
  // are below 2^63 - 2^52, so that is key_k < key_j + [k < j].
  for (int j = 0; j < blocks_end; j += kLanes) {
    const Mask own = load_keys(key + j);
    const Mask own_or_equal = own + 1;
    const Mask lane = lane_indices(j);
    const int block_end = j + kLanes < particles ? j + kLanes : particles;
    Mask ahead{};
    for (int k = 0; k < j; ++k) ahead -= key[k] < own_or_equal;
    for (int k = j; k < block_end; ++k) ahead -= key[k] < (lane > k ? own_or_equal : own);
    for (int k = block_end; k < particles; ++k) ahead -= key[k] < own;
    store(rank + j, ahead);
  }
}

}  // namespace swarmcollide::detail
