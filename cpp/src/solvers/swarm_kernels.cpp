#include "swarm_kernels.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>

#include "swarmcollide/detail/random.hpp"

// Each instruction set's kernels are the same source, swarm_kernels_body.inc, included in its own
// namespace under its own target. This file is compiled with floating-point contraction off, so
// every set rounds exactly like the baseline and a seed gives the same answer on every x86-64
// processor. Only GCC on x86-64 gets the wider sets; elsewhere the baseline is all there is.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define SWARMCOLLIDE_WIDER_KERNELS 1
#endif
#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace swarmcollide::detail {

#ifdef SWARMCOLLIDE_WIDER_KERNELS
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
namespace avx512 {
#define SWARMCOLLIDE_KERNEL_WIDTH 8
#include "swarm_kernels_body.inc"
#undef SWARMCOLLIDE_KERNEL_WIDTH
}  // namespace avx512
#pragma GCC pop_options

#pragma GCC push_options
#pragma GCC target("arch=x86-64-v3")
namespace avx2 {
#define SWARMCOLLIDE_KERNEL_WIDTH 4
#include "swarm_kernels_body.inc"
#undef SWARMCOLLIDE_KERNEL_WIDTH
}  // namespace avx2
#pragma GCC pop_options
#endif

namespace baseline {
// 128 bits: SSE2 on x86-64.
#define SWARMCOLLIDE_KERNEL_WIDTH 2
#include "swarm_kernels_body.inc"
#undef SWARMCOLLIDE_KERNEL_WIDTH
}  // namespace baseline

namespace {

struct Kernels {
  decltype(&baseline::draw_uniforms) draw_uniforms;
  decltype(&baseline::score_initial_positions) score_initial_positions;
  decltype(&baseline::advance_particles) advance_particles;
};

#define SWARMCOLLIDE_KERNELS(set) \
  Kernels { &set::draw_uniforms, &set::score_initial_positions, &set::advance_particles }
constexpr Kernels kBaseline = SWARMCOLLIDE_KERNELS(baseline);
#ifdef SWARMCOLLIDE_WIDER_KERNELS
constexpr Kernels kAvx2 = SWARMCOLLIDE_KERNELS(avx2);
constexpr Kernels kAvx512 = SWARMCOLLIDE_KERNELS(avx512);
#endif
#undef SWARMCOLLIDE_KERNELS

const Kernels& kernels_of(KernelIsa isa) {
#ifdef SWARMCOLLIDE_WIDER_KERNELS
  if (isa == KernelIsa::avx512) return kAvx512;
  if (isa == KernelIsa::avx2) return kAvx2;
#endif
  return kBaseline;
}

const Kernels& kernels() { return kernels_of(kernel_isa()); }

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

void draw_uniforms(UniformLanes& lanes, double* out, int count) {
  kernels().draw_uniforms(lanes, out, count);
}

void uniform_simplex_points(int count, int particles, int stride, double* __restrict uniforms,
                            double* __restrict out, double* __restrict column) {
  const int cuts = count - 1;
  // Odd-even transposition sorts every particle's column at once with branch-free min/max over
  // rows; its cuts^2 / 2 exchanges are cheaper than sorting column by column for few cuts. This
  // runs once per solve, so it is not worth a kernel per instruction set.
  constexpr int kMaxCutsForNetwork = 16;
  if (cuts <= kMaxCutsForNetwork) {
    for (int pass = 0; pass < cuts; ++pass) {
      for (int i = pass % 2; i + 1 < cuts; i += 2) {
        double* __restrict low = uniforms + i * stride;
        double* __restrict high = uniforms + (i + 1) * stride;
        for (int j = 0; j < particles; ++j) {
          const double a = low[j];
          const double b = high[j];
          low[j] = a < b ? a : b;
          high[j] = a < b ? b : a;
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

void score_initial_positions(const SwarmView& swarm, int rows_a, const Fitness& fitness,
                             const Bests& bests) {
  kernels().score_initial_positions(swarm, rows_a, fitness, bests);
}

bool advance_particles(const SwarmView& swarm, int rows_a, const Move& move, const Fitness& fitness,
                       const Bests& bests, double* next) {
  return kernels().advance_particles(swarm, rows_a, move, fitness, bests, next);
}

void order_by_personal_best(int particles, const std::int64_t* key, const std::int64_t* improved,
                            int* order, RankedParticle* scratch) {
  const auto before = [](const RankedParticle& a, const RankedParticle& b) {
    return a.key < b.key || (a.key == b.key && a.particle < b.particle);
  };
  // The particles are split without a branch, with their keys beside them, so that the sort and
  // the merge read no key through an index. Each list gets a last entry that no particle comes
  // after, so that the merge needs no bounds test; its branch mostly takes the next kept particle.
  RankedParticle* kept = scratch;
  RankedParticle* moved = scratch + particles + 1;
  int kept_count = 0;
  int moved_count = 0;
  for (int i = 0; i < particles; ++i) {
    const int p = order[i];
    const RankedParticle item{key[p], p};
    const bool marked = improved[p] != 0;
    kept[kept_count] = item;
    moved[moved_count] = item;
    kept_count += !marked;
    moved_count += marked;
  }
  // Few improve in a step once a swarm settles, and an insertion sort of them is the quickest;
  // in the first steps all may, which for 100,000 particles made the insertion sort's quadratic
  // time most of a second. `before` orders every pair (no two particles share an index), so
  // either sort gives the same order.
  constexpr int kInsertionSortLimit = 64;
  if (moved_count > kInsertionSortLimit) {
    std::sort(moved, moved + moved_count, before);
  } else {
    for (int i = 1; i < moved_count; ++i) {
      const RankedParticle item = moved[i];
      int k = i;
      for (; k > 0 && before(item, moved[k - 1]); --k) moved[k] = moved[k - 1];
      moved[k] = item;
    }
  }
  constexpr RankedParticle kLast{std::numeric_limits<std::int64_t>::max(),
                                 std::numeric_limits<int>::max()};
  kept[kept_count] = kLast;
  moved[moved_count] = kLast;
  int next_kept = 0;
  int next_moved = 0;
  for (int i = 0; i < particles; ++i) {
    const bool take_moved = before(moved[next_moved], kept[next_kept]);
    order[i] = take_moved ? moved[next_moved].particle : kept[next_kept].particle;
    next_moved += take_moved;
    next_kept += !take_moved;
  }
}

}  // namespace swarmcollide::detail
