// The support scan of a small body's points held by coordinate (PointColumns), on the x86-64
// baseline inline and on wider instruction sets out of line; private to the library's sources.
#pragma once

#include <atomic>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "../detail/instruction_set.hpp"

namespace swarmcollide::detail {

/// Entries per column, and the multiple each column is padded to: the widest set's doubles in a
/// register.
constexpr int kColumnCapacity = 32;
constexpr int kColumnPadding = 8;

/// A scan: the first index in [0, count) maximising `(x_i d_x + y_i d_y) + z_i d_z`, each height
/// rounded as written (no contraction), over `columns`, the x of kColumnCapacity points, then their
/// y, then their z, each column padded to a multiple of kColumnPadding entries by repeating its last
/// point. Heights that are NaN are compared as scalars compare them (never higher). The direction
/// comes as its coordinates: the wider sets' file, like the swarm's kernels, stays free of Eigen
/// (see swarm_kernels.hpp).
using ColumnScan = int (*)(const double* columns, int count, double dx, double dy, double dz);

/// The scalar scan, from the first point: the answer wherever a height is NaN.
inline int first_highest_column(const double* columns, int count, double dx, double dy,
                                double dz) {
  const double* x = columns;
  const double* y = x + kColumnCapacity;
  const double* z = y + kColumnCapacity;
  int best = 0;
  double highest = x[0] * dx + y[0] * dy + z[0] * dz;
  for (int i = 1; i < count; ++i) {
    const double h = x[i] * dx + y[i] * dy + z[i] * dz;
    if (h > highest) {
      highest = h;
      best = i;
    }
  }
  return best;
}

/// The baseline's scan, two heights a step (SSE2), each lane rounded as the scalar sum is; the
/// highest is found as the first height equal to the greatest, which is the first maximiser when no
/// height is NaN (a NaN, from infinite products, takes the scalar comparisons on the same heights).
[[gnu::always_inline]] inline int scan_columns_baseline(const double* columns, int count,
                                                        double dx, double dy, double dz) {
#if defined(__SSE2__)
  const double* x = columns;
  const double* y = x + kColumnCapacity;
  const double* z = y + kColumnCapacity;
  alignas(16) double heights[kColumnCapacity];
  const __m128d along_x = _mm_set1_pd(dx);
  const __m128d along_y = _mm_set1_pd(dy);
  const __m128d along_z = _mm_set1_pd(dz);
  const auto height = [&](int i) {
    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_loadu_pd(x + i), along_x),
                                 _mm_mul_pd(_mm_loadu_pd(y + i), along_y)),
                      _mm_mul_pd(_mm_loadu_pd(z + i), along_z));
  };
  __m128d h = height(0);
  _mm_store_pd(heights, h);
  __m128d top = h;
  __m128d unordered = _mm_cmpunord_pd(h, h);
  for (int i = 2; i < count; i += 2) {
    h = height(i);
    _mm_store_pd(heights + i, h);
    top = _mm_max_pd(top, h);
    unordered = _mm_or_pd(unordered, _mm_cmpunord_pd(h, h));
  }
  if (_mm_movemask_pd(unordered) != 0) return first_highest_column(columns, count, dx, dy, dz);
  top = _mm_max_pd(top, _mm_unpackhi_pd(top, top));
  top = _mm_unpacklo_pd(top, top);
  // Every point's equality to the greatest, in one mask: a loop that stopped at the first pair
  // holding it left a branch that went the other way about half the time.
  std::uint32_t equal = 0;
  for (int i = 0; i < count; i += 2) {
    const int pair = _mm_movemask_pd(_mm_cmpeq_pd(_mm_load_pd(heights + i), top));
    equal |= static_cast<std::uint32_t>(pair) << i;
  }
  return __builtin_ctz(equal);
#else
  return first_highest_column(columns, count, dx, dy, dz);
#endif
}

/// The most points the scan of a few points holds in two SSE2 registers, inline on every set.
constexpr int kRegisterColumns = 4;
static_assert(kColumnPadding >= kRegisterColumns, "the few points' registers read padding");

/// The scan of up to kRegisterColumns points (`count` of them, the columns padded by their last
/// point), in two SSE2 registers and inline: the same heights lane by lane as every set's scan,
/// the same first maximiser. A wider set's scan is a call, around which the searches' oracles on
/// the smallest pairs kept their live doubles on the stack (no vector register survives a call).
[[gnu::always_inline]] inline int scan_few_columns(const double* columns, int count, double dx,
                                                   double dy, double dz) {
#if defined(__SSE2__)
  const double* x = columns;
  const double* y = x + kColumnCapacity;
  const double* z = y + kColumnCapacity;
  const __m128d along_x = _mm_set1_pd(dx);
  const __m128d along_y = _mm_set1_pd(dy);
  const __m128d along_z = _mm_set1_pd(dz);
  const auto height = [&](int i) {
    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_loadu_pd(x + i), along_x),
                                 _mm_mul_pd(_mm_loadu_pd(y + i), along_y)),
                      _mm_mul_pd(_mm_loadu_pd(z + i), along_z));
  };
  const __m128d low = height(0);
  const __m128d high = height(2);
  if (_mm_movemask_pd(_mm_cmpunord_pd(low, high)) != 0) {
    return first_highest_column(columns, count, dx, dy, dz);
  }
  __m128d top = _mm_max_pd(low, high);
  top = _mm_max_pd(top, _mm_shuffle_pd(top, top, 1));
  // The first of the four equal to the greatest, without a branch on which pair holds it (the
  // processor guessed it wrong about half the time, and a search's next direction waits on it).
  const int equal = _mm_movemask_pd(_mm_cmpeq_pd(low, top)) |
                    _mm_movemask_pd(_mm_cmpeq_pd(high, top)) << 2;
  return __builtin_ctz(static_cast<unsigned>(equal));
#else
  return first_highest_column(columns, count, dx, dy, dz);
#endif
}

/// The wider sets' scans (the baseline's where the build has none): four heights a step (AVX2),
/// eight (AVX-512), the same index bit for bit.
int scan_columns_avx2(const double* columns, int count, double dx, double dy, double dz);
int scan_columns_avx512(const double* columns, int count, double dx, double dy, double dz);

/// `isa`'s scan (tests compare them); the baseline's where this build or processor has no other.
ColumnScan column_scan_for(KernelIsa isa);

/// The set the scans run: kernel_isa()'s (SWARMCOLLIDE_ISA's, else the widest available), chosen
/// at the first scan, or the widest where SWARMCOLLIDE_ISA names none that runs (the swarm
/// reports that at its first solve; the scans give the same index on every set). -1 until chosen.
extern std::atomic<int> column_scan_set;
/// Chooses column_scan_set, then scans.
int choose_column_scan(const double* columns, int count, double dx, double dy, double dz);

/// The most points the AVX2 scan holds in two registers, which an AVX-512 host scans with it as
/// well: one AVX-512 register measured slower on the host this was written on (AMD EPYC;
/// swarmcollide-narrowphase-coal, 4 vertices overlapping: a distance 0.41 us with the AVX-512
/// scan, 0.40 us with its heights reduced in one register, 0.37-0.38 us with AVX2's).
constexpr int kFewColumns = 8;

/// The scan on the chosen set: the baseline's inline, a wider set's by a direct call (always
/// inline, for PointColumns::inline_scan; PointColumns::scan leaves its own inlining to the
/// compiler). An AVX-512 host scans up to kFewColumns points with AVX2's.
[[gnu::always_inline]] inline int scan_columns(const double* columns, int count, double dx,
                                               double dy, double dz) {
  switch (column_scan_set.load(std::memory_order_relaxed)) {
    case static_cast<int>(KernelIsa::avx512):
      if (count > kFewColumns) return scan_columns_avx512(columns, count, dx, dy, dz);
      [[fallthrough]];
    case static_cast<int>(KernelIsa::avx2):
      return scan_columns_avx2(columns, count, dx, dy, dz);
    case static_cast<int>(KernelIsa::baseline):
      return scan_columns_baseline(columns, count, dx, dy, dz);
    default:
      return choose_column_scan(columns, count, dx, dy, dz);
  }
}

}  // namespace swarmcollide::detail
